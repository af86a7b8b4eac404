//! Learning over trials: the agent runs trial after trial while the oracle judges it
//! from outside (the paper's verdicts, or the policy quality beyond the paper), until it
//! converges or the trial cap; the outcome is what the report is built from.

use mdp::{Oracle, World};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::Serialize;

use crate::agent::main_loop::Agent;
use crate::agent::strategy::Strategy;
use crate::judging::judge::{Judge, Verdict, situations};
use crate::judging::quality::{QualityEstimate, QualityMeter};
use crate::observe::{Flow, Observer, TracePoint};
use crate::perception::rows::Perception;
use crate::perception::view::Sees;
use crate::settings::resolve::is_deterministic;
use crate::settings::values::RunSettings;

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

/// Who decides when a run has learned.
///
/// ```
/// assert_eq!(serde_json::to_string(&csql::Judging::Oracle).unwrap(), "\"oracle\"");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Judging {
    /// The oracle's verdicts (sufficient, converged) at the end of every trial, whatever
    /// the learner: the world is deterministic, the sensors exact, and nothing beyond the
    /// paper asks for the quality.
    Oracle,
    /// The policy quality (specification §6): a run has learned once the quality has
    /// stayed at or above 0.95 for `quality_patience` evaluations.
    Quality,
}

impl Judging {
    /// How a run of `settings` in `world` is judged: by the quality where the paper's
    /// verdicts do not apply (slip, slide, sensor noise, a sensing range, an extension,
    /// `judge_by_quality`, or a world file with stochastic moves), by the oracle otherwise.
    ///
    /// ```
    /// use csql::{Judging, LearnerKind, RunSettings, StrategyKind};
    /// let lake = mdp::builtin_world("frozenlake4x4", &Default::default()).unwrap();
    /// let mut s = RunSettings::tan1991("frozenlake4x4", StrategyKind::Lazy, 1);
    /// assert_eq!(Judging::of(&s, &lake), Judging::Oracle);
    /// s = s.with_learner(LearnerKind::UTree); // the baselines are judged as CS-QL is
    /// assert_eq!(Judging::of(&s, &lake), Judging::Oracle);
    /// s.judge.judge_by_quality = true;
    /// assert_eq!(Judging::of(&s, &lake), Judging::Quality);
    /// ```
    pub fn of<W: World + ?Sized>(settings: &RunSettings, world: &W) -> Judging {
        if settings.judged_by_quality(is_deterministic(world)) {
            Judging::Quality
        } else {
            Judging::Oracle
        }
    }
}

/// The outcome of a learning loop over trials, before reporting.
pub(crate) struct Learned {
    pub judging: Judging,
    pub trace: Vec<TracePoint>,
    /// Trials run (the trace's length when it is kept).
    pub trials: u32,
    /// The last trial's point, kept or not.
    pub last: Option<TracePoint>,
    pub first_sufficient: Option<(u32, f64)>,
    pub first_converged: Option<(u32, f64)>,
    pub moves: u64,
    pub cost: f64,
    /// The policy quality's evaluations (in every run).
    pub quality: QualityTrack,
    /// Whether the run ended because its representation passed `max_rows` rows.
    pub capped: bool,
    /// Whether its observer stopped it (Ctrl-C, SIGTERM, an observer's no).
    pub stopped: bool,
    /// Decreases detected over the whole run.
    pub decreases: u64,
}

/// The policy quality over a run (specification §6).
#[derive(Clone, Copy, Debug)]
pub(crate) struct QualityTrack {
    /// The last evaluation (`None` before the first).
    pub last: Option<QualityEstimate>,
    pub evaluations: u32,
    /// Trial and cost after which the quality was at least 0.95 at every evaluation since.
    pub reached: Option<(u32, f64)>,
    /// Consecutive evaluations at or above 0.95.
    pub streak: u32,
    /// The trial of the last evaluation (0 before the first).
    pub at: u32,
}

impl QualityTrack {
    /// Count an evaluation made after `trial`, with `cost` charged so far.
    fn add(&mut self, q: QualityEstimate, trial: u32, cost: f64) {
        self.last = Some(q);
        self.at = trial;
        self.evaluations += 1;
        if q.quality >= QUALITY_GOAL {
            self.streak += 1;
            self.reached.get_or_insert((trial, cost));
        } else {
            self.streak = 0;
            self.reached = None;
        }
    }
}

/// The quality a policy must reach (specification §6).
pub(crate) const QUALITY_GOAL: f64 = 0.95;

/// Run trials until the run has learned (the oracle says converged, or the quality has
/// stayed at its goal: [`Judging`]) or the trial cap. The oracle judges the agent at the
/// end of every trial through the perception's free view; the policy quality is
/// evaluated every `quality_every` trials and at the last one, in every run.
pub(crate) fn learn<W: World + ?Sized, P: Perception + Sees, S: Strategy>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    agent: &mut Agent<P, S>,
    observer: &mut dyn Observer,
) -> Learned {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    let mut judge = Judge::default();
    let world = scene.world;
    let judging = Judging::of(settings, world);
    let mut out = Learned {
        judging,
        trace: Vec::new(),
        trials: 0,
        last: None,
        first_sufficient: None,
        first_converged: None,
        moves: 0,
        cost: 0.0,
        quality: QualityTrack {
            last: None,
            evaluations: 0,
            reached: None,
            streak: 0,
            at: 0,
        },
        capped: false,
        stopped: false,
        decreases: 0,
    };
    // The evaluation's own generator: the run's, 2^192 draws ahead.
    let mut eval_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    eval_rng.long_jump();
    // Runs the oracle judges measure the quality as something new, at the speed of the
    // judge; runs judged by the quality keep the sweep their figures were made with.
    let mut meter = QualityMeter::new(
        scene.truth,
        settings.world.sensor_noise(),
        eval_rng,
        judging == Judging::Oracle,
    );
    let states = world.states().len() as u64;
    // Whether the oracle's judge can follow the perception incrementally (U-Tree's
    // splits move states between rows: it is judged whole at every trial).
    let incremental = agent.perception.keeps_rows();
    let mut moves_evaluated = 0u64;
    let tolerance = settings.tolerance.get();
    let cap = settings.max_trials.get();
    for trial in 1..=cap {
        let start = world.sample_start(&mut rng);
        let rec = agent.run_trial_observed(world, start, trial, &mut rng, observer);
        out.moves += rec.moves as u64;
        out.cost += rec.cost;
        out.decreases += u64::from(rec.decreases);
        let verdict = match judging {
            // The paper's verdicts assume a deterministic, fully sensable world.
            Judging::Quality => {
                agent.take_journal();
                Verdict::default()
            }
            Judging::Oracle if incremental => judge.judge(world, scene.oracle, agent, tolerance),
            Judging::Oracle => {
                agent.take_journal();
                let now = situations(world, &mut agent.perception);
                Verdict::of_situations(scene.oracle, &agent.table, &now, tolerance)
            }
        };
        if verdict.sufficient && out.first_sufficient.is_none() {
            out.first_sufficient = Some((trial, out.cost));
        }
        if verdict.converged {
            out.first_converged = Some((trial, out.cost));
        }
        // The quality: on its schedule, and at the last trial of a run the oracle ends.
        // Where the oracle judges, the quality is only measured, and an evaluation also
        // waits for as many moves as the world has states since the last, so that
        // measuring never costs much more than learning.
        let due = trial % settings.judge.quality_every == 0
            && (judging == Judging::Quality || out.moves >= moves_evaluated + states);
        if due || trial == cap || verdict.converged {
            moves_evaluated = out.moves;
            // The incremental judge has just looked up every state's row.
            let rows = (judging == Judging::Oracle && incremental).then(|| judge.rows());
            let q = meter.evaluate(world, &mut agent.perception, &agent.table, rows);
            out.quality.add(q, trial, out.cost);
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
        let settled =
            judging == Judging::Quality && out.quality.streak >= settings.judge.quality_patience;
        out.capped = agent.perception.rows() > settings.max_rows;
        out.stopped = flow == Flow::Stop;
        if verdict.converged || settled || out.stopped || out.capped {
            break;
        }
    }
    // A run stopped off the schedule (by its observer, or at `max_rows`) is evaluated
    // where it stopped, so that its quality is that of its final policy.
    if out.quality.at != out.trials {
        let q = meter.evaluate(world, &mut agent.perception, &agent.table, None);
        out.quality.add(q, out.trials, out.cost);
    }
    out
}
