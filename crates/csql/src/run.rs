//! One CS-QL run from settings to the measures of the paper's Table 1.

use mdp::{FeatureSpace, GridWorld, Manhattan, Map, Oracle, SensedGrid, SlipperyGrid, World};
use qlearn::QTable;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::classify::Classify;
use crate::detector::RunDetector;
use crate::error::Error;
use crate::judge::Judge;
use crate::learner::LearnerKind;
use crate::main_loop::{Agent, LoopParams};
use crate::memory::Remembering;
use crate::navigate::navigate;
use crate::observe::{Flow, KeepTrace, Observer};
use crate::perception::FullView;
use crate::perception::Perception;
use crate::predict::{PredictSensing, Predicting};
use crate::quality::{QualityEstimate, Sees, policy_quality};
use crate::report::Describes;
use crate::report::{RunReport, TracePoint, report};
use crate::representation::Representation;
use crate::settings::RunSettings;
use crate::strategy::{Never, Strategy};
use crate::utree::UTree;

/// A prepared world: map, grid world, feature space and oracle.
///
/// ```
/// let s = csql::RunSettings::tan1991("tan8x8", csql::StrategyKind::Lazy, 1);
/// let setup = csql::Setup::new(&s).unwrap();
/// assert_eq!(setup.world.states().len(), 50);
/// ```
#[derive(Clone, Debug)]
pub struct Setup {
    /// The map.
    pub map: Map,
    /// The grid world.
    pub world: GridWorld,
    /// The features and their costs.
    pub space: FeatureSpace,
    /// The oracle for the run's gamma.
    pub oracle: Oracle,
    /// The oracle of the true model when the world slips (value iteration), else `None`
    /// ([`Setup::oracle`] is then the truth).
    pub stochastic_oracle: Option<Oracle>,
}

impl Setup {
    /// Load the map of the settings and prepare everything the run needs.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// let setup = csql::Setup::new(&s).unwrap();
    /// assert_eq!(setup.space.len(), 80);
    /// ```
    pub fn new(settings: &RunSettings) -> Result<Setup, Error> {
        let map = settings.map.resolve()?;
        Setup::for_map(map, settings)
    }

    /// Prepare a given map.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("ignored", csql::StrategyKind::Lazy, 1);
    /// let map = mdp::Map::from_layout("strip", ".G.").unwrap();
    /// assert_eq!(csql::Setup::for_map(map, &s).unwrap().world.states().len(), 2);
    /// ```
    pub fn for_map(map: Map, settings: &RunSettings) -> Result<Setup, Error> {
        settings.validate()?;
        let world = GridWorld::new(&map);
        let mut space = FeatureSpace::new(&map, &Manhattan)?;
        if let Some(r) = settings.world.sensing_radius {
            space = space.within(f64::from(r));
        }
        let oracle = Oracle::for_grid(&world, settings.gamma.get())?;
        let slip = settings.world.slip;
        let stochastic_oracle = if slip.is_zero() {
            None
        } else {
            Some(Oracle::solve_stochastic(
                &SlipperyGrid::new(&world, slip),
                settings.gamma.get(),
            )?)
        };
        Ok(Setup {
            map,
            world,
            space,
            oracle,
            stochastic_oracle,
        })
    }

    /// The oracle of the true model: V* under the world's slip.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.world.slip = mdp::Slip::new(0.2).unwrap();
    /// let setup = csql::Setup::new(&s).unwrap();
    /// let here = setup.world.states()[0];
    /// assert!(setup.truth().v_star(here) < setup.oracle.v_star(here));
    /// ```
    pub fn truth(&self) -> &Oracle {
        self.stochastic_oracle.as_ref().unwrap_or(&self.oracle)
    }

    /// The grid as a [`World`]: its local sensing and the slip of `settings`.
    ///
    /// ```
    /// use mdp::Sensors;
    /// let settings = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// let setup = csql::Setup::new(&settings).unwrap();
    /// assert_eq!(setup.sensed(&settings).num_features(), setup.space.len());
    /// ```
    pub fn sensed(&self, settings: &RunSettings) -> SensedGrid<'_> {
        SensedGrid::new(&self.world, &self.space, settings.world.slip)
    }
}

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
        if verdict.converged || settled || flow == Flow::Stop {
            break;
        }
    }
    out
}

/// Run CS-QL with the given settings: load the map, learn, measure.
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let report = csql::run(&RunSettings::tan1991("tan3x3", StrategyKind::Resetting, 1)).unwrap();
/// assert!(report.converged);
/// assert_eq!(report.states.len(), 8);
/// ```
pub fn run(settings: &RunSettings) -> Result<RunReport, Error> {
    run_settings(settings, &mut KeepTrace)
}

/// Run the learner of `settings` in the world its `map` setting names (a grid map, a
/// built-in world or a world file), with an observer.
///
/// ```
/// let settings = csql::RunSettings::tan1991("frozenlake4x4", csql::StrategyKind::Lazy, 1);
/// let report = csql::run_settings(&settings, &mut csql::KeepTrace).unwrap();
/// assert!(report.converged);
/// assert_eq!(report.map, "frozenlake4x4");
/// ```
pub fn run_settings(
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<RunReport, Error> {
    match crate::resolve::Resolved::new(settings)? {
        crate::resolve::Resolved::Grid(setup) => Ok(run_observed(&setup, settings, observer)),
        crate::resolve::Resolved::Finite { world, oracle } => {
            let scene = Scene::new(&world, &oracle, &oracle, world.name());
            run_in(&scene, settings, observer)
        }
    }
}

/// Run CS-QL on a prepared world (the settings' map name is only reported).
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Eager, 3);
/// let setup = Setup::new(&settings).unwrap();
/// let a = csql::run_on(&setup, &settings);
/// let b = csql::run_on(&setup, &settings);
/// assert_eq!(a, b); // a pure function of the settings
/// ```
pub fn run_on(setup: &Setup, settings: &RunSettings) -> RunReport {
    run_with_representation(setup, settings).0
}

/// Run the learner of `settings` in any world: learn, measure against the scene's
/// oracles, report. Grid-only settings (the motion prior, sensor noise) are refused on a
/// world that is not a grid.
///
/// ```
/// let settings = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Random, 2);
/// let setup = csql::Setup::new(&settings).unwrap();
/// let sensed = setup.sensed(&settings);
/// let scene = csql::Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
/// let report = csql::run_in(&scene, &settings, &mut csql::KeepTrace).unwrap();
/// assert_eq!(report, csql::run_on(&setup, &settings));
/// ```
pub fn run_in<W: World + ?Sized>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<RunReport, Error> {
    settings.validate()?;
    if scene.world.grid().is_none() {
        if settings.predict_sensing == PredictSensing::Motion {
            return Err(Error::GridOnly {
                what: "predict_sensing = \"motion\" (dead reckoning on a grid)",
            });
        }
        if settings.world.sensing_radius.is_some() {
            return Err(Error::GridOnly {
                what: "[world] sensing_radius (offsets around a robot on a grid)",
            });
        }
    }
    let classify = Classify::new(scene.world);
    Ok(run_classify(scene, settings, classify, observer).0)
}

/// Run CS-QL on a prepared world and also return the final representation.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Random, 4);
/// let setup = Setup::new(&settings).unwrap();
/// let (report, rep) = csql::run_with_representation(&setup, &settings);
/// assert_eq!(report.descriptions.len(), rep.len());
/// ```
pub fn run_with_representation(
    setup: &Setup,
    settings: &RunSettings,
) -> (RunReport, Representation) {
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    run_classify(&scene, settings, Classify::new(&sensed), &mut KeepTrace)
}

/// Run CS-QL on a prepared world with an [`Observer`] called after every trial: for
/// progress, for streaming the trace instead of keeping it, or for stopping early (the
/// report then says what the run reached when it stopped, as at a trial cap).
///
/// ```
/// use csql::{Flow, Observer, RunSettings, Setup, StrategyKind, TracePoint};
/// struct Count(u32);
/// impl Observer for Count {
///     fn keep_trace(&self) -> bool { false }
///     fn trial(&mut self, _: &TracePoint) -> Flow { self.0 += 1; Flow::Continue }
/// }
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Eager, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let mut count = Count(0);
/// let report = csql::run_observed(&setup, &settings, &mut count);
/// assert!(report.trace.is_empty() && report.converged);
/// assert_eq!(count.0, report.trials);
/// ```
pub fn run_observed(
    setup: &Setup,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> RunReport {
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    run_classify(&scene, settings, Classify::new(&sensed), observer).0
}

/// Run CS-QL with a given CLASSIFY (for example with its cache off, or starting from a
/// representation).
///
/// ```
/// use csql::{Classify, RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let plain = Classify::new(&setup.sensed(&settings)).with_cache(false);
/// assert_eq!(csql::run_on_with(&setup, &settings, plain), csql::run_on(&setup, &settings));
/// ```
pub fn run_on_with(setup: &Setup, settings: &RunSettings, classify: Classify) -> RunReport {
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    run_classify(&scene, settings, classify, &mut KeepTrace).0
}

fn run_classify<W: World + ?Sized>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    classify: Classify,
    observer: &mut dyn Observer,
) -> (RunReport, Representation) {
    // The sensors' own generator: the run's, 2^128 draws ahead (drawn from only under
    // sensor noise).
    let mut sensor_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    sensor_rng.jump();
    let classify = classify
        .with_noise(settings.world.sensor_noise, sensor_rng)
        .with_matching(settings.extensions.matching)
        .with_confirmation(settings.extensions.confirm_new)
        .with_reads(settings.extensions.reads);
    let learner = settings.learner;
    let predicting = match (learner, settings.predict_sensing) {
        (LearnerKind::FullSensing, _) => {
            let perception = FullView::new(scene.world);
            let (report, _) = learn_and_report(scene, settings, perception, Never, observer);
            return (report, classify.into_representation());
        }
        (LearnerKind::UTree, _) => {
            let mut utree_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
            utree_rng.jump();
            let perception = UTree::new(scene.world, settings.u_tree, settings.gamma.get())
                .with_noise(settings.world.sensor_noise, utree_rng);
            let (report, _) = learn_and_report(scene, settings, perception, Never, observer);
            return (report, classify.into_representation());
        }
        (LearnerKind::CsQl, PredictSensing::Off) if settings.extensions.memory > 0 => {
            let perception = Remembering::new(classify, settings.extensions.memory);
            let strategy = settings.strategy.build(settings.random_moves);
            let (report, perception) =
                learn_and_report(scene, settings, perception, strategy, observer);
            return (report, perception.into_classify().into_representation());
        }
        (LearnerKind::CsQl, PredictSensing::Off) => {
            let strategy = settings.strategy.build(settings.random_moves);
            let (report, perception) =
                learn_and_report(scene, settings, classify, strategy, observer);
            return (report, perception.into_representation());
        }
        (LearnerKind::CsQl, PredictSensing::Learned) => {
            Predicting::learned(classify, &settings.prediction, scene.world.num_actions())
        }
        (LearnerKind::CsQl, PredictSensing::Motion) => {
            match scene.world.grid().zip(scene.world.local_space()) {
                Some((grid, space)) => {
                    Predicting::motion(classify, &settings.prediction, grid, space)
                }
                // Refused by run_in before anything runs.
                None => {
                    Predicting::learned(classify, &settings.prediction, scene.world.num_actions())
                }
            }
        }
    };
    let strategy = settings.strategy.build(settings.random_moves);
    let mut agent = new_agent(scene.world, settings, predicting, strategy);
    let learned = learn(scene, settings, &mut agent, observer);
    let mut out = report(
        scene,
        settings,
        &mut agent.perception,
        &agent.table,
        learned,
    );
    out.prediction = Some(agent.perception.stats());
    agent.perception.navigate_with(settings.prediction.verify);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed ^ NAVIGATION_STREAM);
    let nav = navigate(
        scene.world,
        scene.oracle,
        &mut agent.perception,
        &mut agent.table,
        settings.prediction.navigation_trials,
        settings.max_moves.get(),
        &mut rng,
    );
    out.navigation_cost_per_move = Some(nav.cost_per_move());
    out.navigation_success = Some(nav.success());
    (out, agent.perception.into_classify().into_representation())
}

/// Navigation's generator is seeded with the run's seed exclusive-or this constant, so
/// that its draws are not those of learning (the digits of pi's fraction, as a name).
const NAVIGATION_STREAM: u64 = 0x243F_6A88_85A3_08D3;

/// Learn with a perception and a strategy, and report.
fn learn_and_report<W: World + ?Sized, P: Perception + Sees + Describes, S: Strategy>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    perception: P,
    strategy: S,
    observer: &mut dyn Observer,
) -> (RunReport, P) {
    let mut agent = new_agent(scene.world, settings, perception, strategy);
    let learned = learn(scene, settings, &mut agent, observer);
    let report = report(
        scene,
        settings,
        &mut agent.perception,
        &agent.table,
        learned,
    );
    (report, agent.perception)
}

fn new_agent<W: World + ?Sized, P, S>(
    world: &W,
    settings: &RunSettings,
    perception: P,
    strategy: S,
) -> Agent<P, S> {
    Agent::new(
        perception,
        strategy,
        QTable::new(world.num_actions())
            .and_then(|t| t.starting_at(crate::quality::value_floor(world, settings.gamma.get())))
            .expect("a world has at least one action, and a finite floor of its returns"),
        LoopParams::from(settings),
    )
    .with_detector(RunDetector::new(
        settings.extensions.detector,
        settings.extensions.rate,
    ))
}
