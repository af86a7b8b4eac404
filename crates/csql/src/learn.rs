//! Learning over trials: the agent runs trial after trial while the oracle judges it
//! from outside (the paper's verdicts, or the policy quality beyond the paper), until it
//! converges or the trial cap; the outcome is what the report is built from.

use mdp::{Oracle, World};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::judge::Judge;
use crate::main_loop::{Agent, LoopParams};
use crate::observe::{Flow, Observer, TracePoint};
use crate::perception::Perception;
use crate::quality::{QualityEstimate, policy_quality};
use crate::settings::RunSettings;
use crate::strategy::Strategy;
use crate::view::Sees;

/// A world a run learns in, with the oracle's truth about it: what the judge, the policy
/// quality and the report measure against. The learner never sees the oracles.
///
/// ```
/// let settings = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let setup = csql::Setup::new(&settings).unwrap();
/// let sensed = setup.sensed(&settings);
/// let scene = csql::Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
/// let report = csql::run_in(&scene, &settings, &mut csql::KeepTrace).unwrap();
/// assert!(report.converged);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a, W: ?Sized> {
    /// The world.
    pub world: &'a W,
    /// The oracle of the world's deterministic moves: the paper's verdicts (consistent,
    /// sufficient, converged) when the world is deterministic.
    pub oracle: &'a Oracle,
    /// The oracle of the true model (slip included): the policy quality.
    pub truth: &'a Oracle,
    /// The world's name, for the report.
    pub name: &'a str,
}

impl<'a, W: World + ?Sized> Scene<'a, W> {
    /// A world, its oracles and its name.
    ///
    /// ```
    /// let settings = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// let setup = csql::Setup::new(&settings).unwrap();
    /// let sensed = setup.sensed(&settings);
    /// let scene = csql::Scene::new(&sensed, &setup.oracle, setup.truth(), "tan3x3");
    /// assert_eq!(scene.name, "tan3x3");
    /// ```
    pub fn new(world: &'a W, oracle: &'a Oracle, truth: &'a Oracle, name: &'a str) -> Self {
        Scene {
            world,
            oracle,
            truth,
            name,
        }
    }
}

impl From<&RunSettings> for LoopParams {
    fn from(settings: &RunSettings) -> LoopParams {
        LoopParams {
            beta: settings.beta,
            gamma: settings.gamma,
            temperature: settings.temperature,
            max_moves: settings.max_moves.get(),
            decrease_threshold: settings.decrease_threshold.get(),
        }
    }
}

/// The outcome of a learning loop over trials, before reporting.
pub(crate) struct Learned {
    pub trace: Vec<TracePoint>,
    /// Trials run (the trace's length when it is kept).
    pub trials: u32,
    /// The last trial's point, kept or not.
    pub last: Option<TracePoint>,
    pub first_sufficient: Option<(u32, f64)>,
    pub first_converged: Option<(u32, f64)>,
    pub moves: u64,
    pub cost: f64,
    /// Beyond the paper only: the policy quality's evaluations.
    pub quality: Option<QualityTrack>,
    /// Whether the run ended because its representation passed `max_rows` rows.
    pub capped: bool,
}

/// The policy quality over a run beyond the paper (specification §6).
#[derive(Clone, Copy, Debug)]
pub(crate) struct QualityTrack {
    pub last: QualityEstimate,
    pub evaluations: u32,
    /// Trial and cost after which the quality was at least 0.95 at every evaluation since.
    pub reached: Option<(u32, f64)>,
    /// Consecutive evaluations at or above 0.95.
    pub streak: u32,
}

/// The quality a policy must reach (specification §6).
pub(crate) const QUALITY_GOAL: f64 = 0.95;

/// Run trials until the oracle says converged or the trial cap; the oracle judges the
/// agent at the end of every trial, through the perception's free view.
pub(crate) fn learn<W: World + ?Sized, P: Perception + Sees, S: Strategy>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    agent: &mut Agent<P, S>,
    observer: &mut dyn Observer,
) -> Learned {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    let mut judge = Judge::default();
    let world = scene.world;
    let mut out = Learned {
        trace: Vec::new(),
        trials: 0,
        last: None,
        first_sufficient: None,
        first_converged: None,
        moves: 0,
        cost: 0.0,
        quality: None,
        capped: false,
    };
    // The paper's verdicts assume a deterministic world; a world file may be stochastic
    // whatever the settings say.
    let beyond = settings.beyond_paper() || !crate::quality::is_deterministic(world);
    // The evaluation's own generator: the run's, 2^192 draws ahead.
    let mut eval_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    eval_rng.long_jump();
    for trial in 1..=settings.max_trials.get() {
        let start = world.sample_start(&mut rng);
        let rec = agent.run_trial(world, start, trial, &mut rng);
        out.moves += rec.moves as u64;
        out.cost += rec.cost;
        let verdict = if beyond {
            // The paper's verdicts assume a deterministic, fully sensable world; beyond
            // it, the policy quality judges (every `quality_every` trials).
            agent.take_journal();
            let every = settings.extensions.quality_every;
            if trial % every == 0 || trial == settings.max_trials.get() {
                let q = policy_quality(
                    world,
                    scene.truth,
                    &mut agent.perception,
                    &agent.table,
                    settings.world.sensor_noise,
                    &mut eval_rng,
                );
                let track = out.quality.get_or_insert(QualityTrack {
                    last: q,
                    evaluations: 0,
                    reached: None,
                    streak: 0,
                });
                track.last = q;
                track.evaluations += 1;
                if q.quality >= QUALITY_GOAL {
                    track.streak += 1;
                    track.reached.get_or_insert((trial, out.cost));
                } else {
                    track.streak = 0;
                    track.reached = None;
                }
            }
            crate::judge::Verdict::default()
        } else {
            judge.judge(world, scene.oracle, agent, settings.tolerance.get())
        };
        if verdict.sufficient && out.first_sufficient.is_none() {
            out.first_sufficient = Some((trial, out.cost));
        }
        if verdict.converged {
            out.first_converged = Some((trial, out.cost));
        }
        let point = TracePoint {
            trial,
            moves: rec.moves,
            cumulative_cost: out.cost,
            descriptions: agent.perception.rows(),
            decreases: rec.decreases,
            refinements: rec.refinements,
            sufficient: verdict.sufficient,
            converged: verdict.converged,
        };
        out.trials = trial;
        out.last = Some(point);
        if observer.keep_trace() {
            out.trace.push(point);
        }
        let flow = observer.trial(&point);
        let settled = out
            .quality
            .is_some_and(|q| q.streak >= settings.extensions.quality_patience);
        out.capped = agent.perception.rows() > settings.max_rows;
        if verdict.converged || settled || flow == Flow::Stop || out.capped {
            break;
        }
    }
    out
}
