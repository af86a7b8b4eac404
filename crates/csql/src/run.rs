//! One CS-QL run from settings to the measures of the paper's Table 1.

use mdp::World;
use qlearn::QTable;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::agent::main_loop::Agent;
use crate::agent::strategy::{Never, Strategy};
use crate::error::Error;
use crate::judging::audit::Audited;
use crate::judging::navigate::navigate;
use crate::judging::report::{RunReport, report};
use crate::judging::trials::{Scene, learn};
use crate::learners::costly::CostedReport;
use crate::learners::utree::UTree;
use crate::observe::{KeepTrace, Observer};
use crate::perception::classify::Classify;
use crate::perception::memory::Remembering;
use crate::perception::representation::Representation;
use crate::perception::rows::FullView;
use crate::perception::rows::Perception;
use crate::perception::sense_less::Predicting;
use crate::perception::sense_less::level::PredictSensing;
use crate::perception::view::{Describes, Sees};
use crate::perception::wraps::Wraps;
use crate::settings::learner::LearnerSettings;
use crate::settings::resolve::Resolved;
use crate::settings::setup::Setup;
use crate::settings::values::RunSettings;

/// What a run reports: trials judged against the oracle (CS-QL, U-Tree, full sensing),
/// or episodes scored by the costed return (AMRL-Q, sensing by belief). It is written as
/// the one report it holds (`csrl run --json` prints it).
///
/// ```
/// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let report = csql::run_resolved(&csql::Resolved::new(&s).unwrap(), &s, &mut csql::KeepTrace).unwrap();
/// let json = serde_json::to_value(&report).unwrap();
/// assert_eq!(json["converged"], true); // the trials' report itself, not wrapped
/// assert!(report.trials().is_some() && report.episodes().is_none());
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(untagged)]
pub enum Report {
    /// A run judged by trials.
    Trials(Box<RunReport>),
    /// A run played on episodes of the costed return.
    Episodes(Box<CostedReport>),
}

impl Report {
    /// The report of a run judged by trials, if this is one.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Eager, 2);
    /// let report = csql::run_resolved(&csql::Resolved::new(&s).unwrap(), &s, &mut csql::KeepTrace).unwrap();
    /// assert_eq!(report.trials().unwrap().seed, 2);
    /// ```
    pub fn trials(&self) -> Option<&RunReport> {
        match self {
            Report::Trials(r) => Some(r),
            Report::Episodes(_) => None,
        }
    }

    /// The report of a run played on costed episodes, if this is one.
    ///
    /// ```
    /// let s = csql::SettingsDraft::from_toml("map = \"frozenlake4x4\"\nlearner = \"amrl-q\"\nepisodes = 20\n[world]\nsensing = \"factors\"\n[costly]\nprice = 0.025", "f")
    ///     .unwrap()
    ///     .build()
    ///     .unwrap();
    /// let report = csql::run_resolved(&csql::Resolved::new(&s).unwrap(), &s, &mut csql::KeepTrace).unwrap();
    /// assert_eq!(report.episodes().unwrap().costly.returns.len(), 20);
    /// ```
    pub fn episodes(&self) -> Option<&CostedReport> {
        match self {
            Report::Episodes(r) => Some(r),
            Report::Trials(_) => None,
        }
    }
}

/// Run the learner of `settings` in a resolved world: the one entry point for every
/// learner and every world. [`Resolved::new`] resolves the world the settings name (a
/// grid map, a built-in world, a world file) and [`Resolved::given`] a world built in
/// code; both check the settings against it. The learners judged by trials (CS-QL,
/// U-Tree, full sensing) learn and are measured against the world's oracle, with
/// `observer` called after every trial; the learners played on episodes (AMRL-Q and
/// sensing by belief) play `episodes` episodes scored by the costed return, `observer`
/// asked before every episode whether to go on.
///
/// The other `run_*` functions are forms of this one for CS-QL's own uses (a prepared
/// grid, a given CLASSIFY, the final representation); each refuses the learners played
/// on episodes rather than running another learner in their place.
///
/// # Errors
/// Settings refused by [`RunSettings::validate`] or by the world ([`Resolved::new`]
/// checks them when it resolves; they are checked again here), or a world sensing by
/// belief cannot plan in ([`Error::Plan`]).
///
/// ```
/// let s = csql::RunSettings::tan1991("frozenlake4x4", csql::StrategyKind::Lazy, 1);
/// let report = csql::run_resolved(&csql::Resolved::new(&s).unwrap(), &s, &mut csql::KeepTrace).unwrap();
/// assert_eq!(report.trials().unwrap().map, "frozenlake4x4");
/// ```
pub fn run_resolved(
    resolved: &Resolved,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<Report, Error> {
    if settings.learner.kind().on_episodes() {
        let report = crate::learners::costly::costed_report_in(resolved, settings, observer)?;
        return Ok(Report::Episodes(Box::new(report)));
    }
    let report = match resolved {
        Resolved::Grid(setup) => {
            settings.validate()?;
            crate::settings::resolve::check_with_world(settings, true, true)?;
            crate::settings::resolve::check_size(settings, &setup.sensed(settings))?;
            run_observed(setup, settings, observer)?
        }
        Resolved::Finite { world, oracle } => {
            let scene = Scene::new(world, oracle, oracle, world.name());
            run_in(&scene, settings, observer)?
        }
    };
    Ok(Report::Trials(Box::new(report)))
}

/// Run a learner judged by trials with the given settings, in the world they name: load
/// it, learn, measure. A thin form of [`run_resolved`]; the learners played on episodes
/// (AMRL-Q, sensing by belief) are refused: their report is a [`CostedReport`].
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let report = csql::run(&RunSettings::tan1991("tan3x3", StrategyKind::Resetting, 1)).unwrap();
/// assert!(report.converged);
/// assert_eq!(report.states.len(), 8);
/// ```
pub fn run(settings: &RunSettings) -> Result<RunReport, Error> {
    not_on_episodes(settings)?;
    match run_resolved(&Resolved::new(settings)?, settings, &mut KeepTrace)? {
        Report::Trials(report) => Ok(*report),
        Report::Episodes(_) => unreachable!("refused above"),
    }
}

/// AMRL-Q and sensing by belief are played on episodes of the costed return
/// ([`run_resolved`]), not in a run judged by trials.
fn not_on_episodes(settings: &RunSettings) -> Result<(), Error> {
    let kind = settings.learner.kind();
    if kind.on_episodes() {
        return Err(Error::Conflict {
            first: format!("learner = {kind}"),
            second: "a run judged by trials".to_string(),
            why: "the learner is played for a fixed number of episodes on the costed return (csql::run_resolved, or csrl run)",
        });
    }
    Ok(())
}

/// Run CS-QL on a prepared grid (the settings' map name is only reported). A form of
/// [`run_resolved`] that refuses the learners played on episodes.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Eager, 3);
/// let setup = Setup::new(&settings).unwrap();
/// let a = csql::run_on(&setup, &settings).unwrap();
/// let b = csql::run_on(&setup, &settings).unwrap();
/// assert_eq!(a, b); // a pure function of the settings
/// ```
pub fn run_on(setup: &Setup, settings: &RunSettings) -> Result<RunReport, Error> {
    Ok(run_with_representation(setup, settings)?.0)
}

/// Run the learner of `settings` in any world: learn, measure against the scene's
/// oracles, report. Grid-only settings (the motion prior, sensor noise) are refused on a
/// world that is not a grid, and so are the learners played on episodes.
///
/// ```
/// let settings = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Random, 2);
/// let setup = csql::Setup::new(&settings).unwrap();
/// let sensed = setup.sensed(&settings);
/// let scene = csql::Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
/// let report = csql::run_in(&scene, &settings, &mut csql::KeepTrace).unwrap();
/// assert_eq!(report, csql::run_on(&setup, &settings).unwrap());
/// ```
pub fn run_in<W: World + ?Sized>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<RunReport, Error> {
    settings.validate()?;
    not_on_episodes(settings)?;
    if scene.world.grid().is_none() {
        if settings.predict_sensing() == PredictSensing::Motion {
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
    crate::settings::resolve::check_with_world(
        settings,
        crate::settings::resolve::is_deterministic(scene.world),
        scene.world.grid().is_some(),
    )?;
    crate::settings::resolve::check_size(settings, scene.world)?;
    let classify = Classify::new(scene.world);
    Ok(run_classify(scene, settings, classify, observer)?.0)
}

/// Run CS-QL on a prepared grid and also return the final representation. A form of
/// [`run_resolved`] that refuses the learners played on episodes.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Random, 4);
/// let setup = Setup::new(&settings).unwrap();
/// let (report, rep) = csql::run_with_representation(&setup, &settings).unwrap();
/// assert_eq!(report.descriptions.len(), rep.len());
/// ```
pub fn run_with_representation(
    setup: &Setup,
    settings: &RunSettings,
) -> Result<(RunReport, Representation), Error> {
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    run_classify(&scene, settings, Classify::new(&sensed), &mut KeepTrace)
}

/// Run CS-QL on a prepared grid with an [`Observer`] called after every trial: for
/// progress, for streaming the trace instead of keeping it, or for stopping early (the
/// report then says what the run reached when it stopped, as at a trial cap). A form of
/// [`run_resolved`] that refuses the learners played on episodes.
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
/// let report = csql::run_observed(&setup, &settings, &mut count).unwrap();
/// assert!(report.trace.is_empty() && report.converged);
/// assert_eq!(count.0, report.trials);
/// ```
pub fn run_observed(
    setup: &Setup,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<RunReport, Error> {
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    Ok(run_classify(&scene, settings, Classify::new(&sensed), observer)?.0)
}

/// Run CS-QL on a prepared grid with a given CLASSIFY (for example with its cache off,
/// or starting from a representation). A form of [`run_resolved`] that refuses the
/// learners played on episodes.
///
/// ```
/// use csql::{Classify, RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let plain = Classify::new(&setup.sensed(&settings)).with_cache(false);
/// assert_eq!(
///     csql::run_on_with(&setup, &settings, plain).unwrap(),
///     csql::run_on(&setup, &settings).unwrap()
/// );
/// ```
pub fn run_on_with(
    setup: &Setup,
    settings: &RunSettings,
    classify: Classify,
) -> Result<RunReport, Error> {
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    Ok(run_classify(&scene, settings, classify, &mut KeepTrace)?.0)
}

fn run_classify<W: World + ?Sized>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    classify: Classify,
    observer: &mut dyn Observer,
) -> Result<(RunReport, Representation), Error> {
    not_on_episodes(settings)?;
    let (mut report, rep) = learn_classify(scene, settings, classify, observer);
    // With sensing priced (`[costly]`), the run's trials again, each scored by its
    // costed return: the same trials, as `costed_episodes` plays them from the same
    // generator. Every learner and setting it refuses was refused by
    // `RunSettings::validate` already.
    // A run stopped from outside is not played again (that would take as long as the
    // run did, after the stop): its report says why `costly` is missing, as it does for
    // a run of more trials than a report lists.
    if settings.costly.is_some() {
        if observer.keep_going() {
            match crate::learners::costly::costed_run(scene.world, settings, report.trials) {
                Ok(costly) => report.costly = costly,
                Err(e) => {
                    report.costly_missing = Some(format!(
                        "the {} trials were not scored by their costed return: {e}",
                        report.trials
                    ));
                }
            }
        } else {
            report.costly_missing = Some(format!(
                "the run was stopped (Ctrl-C or SIGTERM) before its {} trials were played \
                 again to be scored by their costed return; run it again with max_trials = {} \
                 to have them",
                report.trials, report.trials
            ));
        }
    }
    Ok((report, rep))
}

fn learn_classify<W: World + ?Sized>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    classify: Classify,
    observer: &mut dyn Observer,
) -> (RunReport, Representation) {
    // The sensors' own generator: the run's, 2^128 draws ahead (drawn from only under
    // sensor noise).
    let mut sensor_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    sensor_rng.jump();
    let extensions = settings.extensions();
    let classify = classify
        .with_noise(settings.world.sensor_noise(), sensor_rng)
        .with_extensions(&extensions);
    let (q, predicting) = match &settings.learner {
        // AMRL-Q and sensing by belief never come here: `run_classify` refuses them.
        LearnerSettings::FullSensing | LearnerSettings::AmrlQ(_) | LearnerSettings::Belief(_) => {
            let perception = FullView::new(scene.world);
            let (report, _) = learn_and_report(scene, settings, perception, Never, observer);
            return (report, classify.into_representation());
        }
        LearnerSettings::UTree(params) => {
            let mut utree_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
            utree_rng.jump();
            let perception = UTree::new(scene.world, *params, settings.gamma.get())
                .with_noise(settings.world.sensor_noise(), utree_rng);
            let (report, _) = learn_and_report(scene, settings, perception, Never, observer);
            return (report, classify.into_representation());
        }
        LearnerSettings::CsQl(q) => match q.predict_sensing {
            PredictSensing::Off if extensions.memory > 0 => {
                let perception = Remembering::new(classify, extensions.memory);
                let strategy = q.strategy.build(q.random_moves);
                let (report, perception) =
                    learn_and_report(scene, settings, perception, strategy, observer);
                return (report, perception.into_classify().into_representation());
            }
            PredictSensing::Off => {
                let strategy = q.strategy.build(q.random_moves);
                let (report, perception) =
                    learn_and_report(scene, settings, classify, strategy, observer);
                return (report, perception.into_representation());
            }
            PredictSensing::Learned => (
                q,
                Predicting::learned(classify, &q.prediction, scene.world.num_actions()),
            ),
            PredictSensing::Motion => (
                q,
                match scene.world.grid().zip(scene.world.local_space()) {
                    Some((grid, space)) => Predicting::motion(classify, &q.prediction, grid, space),
                    // Refused by run_in before anything runs.
                    None => Predicting::learned(classify, &q.prediction, scene.world.num_actions()),
                },
            ),
            PredictSensing::Weighed => (
                q,
                Predicting::weighed(
                    classify,
                    &q.prediction,
                    scene.world.num_actions(),
                    // Validated: the weighed level is given [costly] price.
                    settings.costly.map_or(0.0, |c| c.price),
                ),
            ),
        },
    };
    let strategy = q.strategy.build(q.random_moves);
    // The oracle counts wrong predictions from outside the learner.
    let mut agent = new_agent(scene.world, settings, Audited::new(predicting), strategy);
    let learned = learn(scene, settings, &mut agent, observer);
    let mut out = report(
        scene,
        settings,
        &mut agent.perception,
        &agent.table,
        learned,
    );
    out.prediction = Some(agent.perception.stats());
    agent
        .perception
        .inner_mut()
        .navigate_with(q.prediction.verify);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed ^ NAVIGATION_STREAM);
    let nav = navigate(
        scene.world,
        scene.oracle,
        &mut agent.perception,
        &mut agent.table,
        q.prediction.navigation_trials,
        settings.max_moves.get(),
        &mut rng,
        observer,
    );
    out.navigation_cost_per_move = Some(nav.cost_per_move());
    out.navigation_success = Some(nav.success());
    (
        out,
        agent
            .perception
            .into_inner()
            .into_classify()
            .into_representation(),
    )
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
    crate::agent::main_loop::agent_of(
        perception,
        strategy,
        QTable::new(world.num_actions())
            .and_then(|t| {
                t.starting_at(crate::agent::main_loop::value_floor(
                    world,
                    settings.gamma.get(),
                ))
            })
            .expect("a world has at least one action, and a finite floor of its returns"),
        settings,
    )
}
