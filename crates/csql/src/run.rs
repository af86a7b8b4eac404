//! One CS-QL run from settings to the measures of the paper's Table 1.

use mdp::{Action, FeatureSpace, GridWorld, Manhattan, Map, Mdp, Oracle};
use qlearn::QTable;
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::Serialize;

use crate::classify::Classify;
use crate::error::Error;
use crate::learner::{LoopParams, Perception, TrialRecord, run_trial};
use crate::observe::{Flow, KeepTrace, Observer};
use crate::representation::{DescriptionId, Representation};
use crate::settings::RunSettings;
use crate::strategy::Strategy;
use crate::tree::StateTree;

/// The eight measures of the paper's Table 1 for one run. A figure the run did not reach
/// is `None` (null in JSON); rows 5 to 8 are measured after convergence only.
///
/// ```
/// let t = csql::Table1::default();
/// assert!(t.trials_to_converge.is_none());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Table1 {
    /// Row 1: sensing cost until the representation was first sufficient.
    pub cost_to_sufficient: Option<f64>,
    /// Row 2: trials until then.
    pub trials_to_sufficient: Option<u32>,
    /// Row 3: sensing cost until convergence (row 1 included).
    pub cost_to_converge: Option<f64>,
    /// Row 4: trials until convergence.
    pub trials_to_converge: Option<u32>,
    /// Row 5: descriptions after convergence.
    pub descriptions: Option<usize>,
    /// Row 6: mean features per description.
    pub mean_features: Option<f64>,
    /// Row 7: most features in one description.
    pub max_features: Option<usize>,
    /// Row 8: mean sensing cost per state of the cost-sensitive decision tree built from
    /// the final descriptions.
    pub tree_cost_per_state: Option<f64>,
    /// Row 8, plain form: mean over states of the summed cost of their description's
    /// features.
    pub description_cost_per_state: Option<f64>,
}

/// One line of the learning curve: the state of the run at the end of a trial.
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Eager, 1)).unwrap();
/// let last = r.trace.last().unwrap();
/// assert!(last.converged && last.cumulative_cost == r.total_cost);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TracePoint {
    /// The trial, from 1.
    pub trial: u32,
    /// Moves in this trial.
    pub moves: u32,
    /// Sensing cost charged so far in the run.
    pub cumulative_cost: f64,
    /// Descriptions at the end of the trial.
    pub descriptions: usize,
    /// Decreases seen in this trial.
    pub decreases: u32,
    /// Features added in this trial.
    pub refinements: u32,
    /// The representation is sufficient.
    pub sufficient: bool,
    /// The run has converged.
    pub converged: bool,
}

/// A state at the end of the run (row 0 is the top line of the map).
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1)).unwrap();
/// let s = r.states.iter().find(|s| (s.row, s.col) == (0, 1)).unwrap();
/// assert_eq!((s.greedy_action, s.value), (Some("right"), Some(1.0)));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StateReport {
    /// Row.
    pub row: usize,
    /// Column.
    pub col: usize,
    /// The label of the state's description, if it has one.
    pub description: Option<u32>,
    /// The greedy action of that description (lowest action id among ties).
    pub greedy_action: Option<&'static str>,
    /// V of that description.
    pub value: Option<f64>,
    /// The optimal utility (for comparison).
    pub v_star: f64,
}

/// One feature of a description.
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1)).unwrap();
/// let f = r.descriptions.iter().flat_map(|d| &d.features).next().unwrap();
/// assert_eq!(f.cost, (f.dx.abs() + f.dy.abs()) as f64);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FeatureReport {
    /// Offset to the right.
    pub dx: i32,
    /// Offset up.
    pub dy: i32,
    /// The condition required there: `empty`, `obstacle` or `goal`.
    pub value: &'static str,
    /// Its sensing cost.
    pub cost: f64,
}

/// A description at the end of the run.
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1)).unwrap();
/// assert!(r.descriptions.iter().enumerate().all(|(i, d)| d.label as usize == i));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DescriptionReport {
    /// Its unique label.
    pub label: u32,
    /// Its features, in the feature order.
    pub features: Vec<FeatureReport>,
}

/// Everything a run measured; `csrl run --json` prints it.
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Random, 2)).unwrap();
/// assert!(r.converged);
/// assert_eq!(r.trials as usize, r.trace.len());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunReport {
    /// The map's name.
    pub map: String,
    /// The strategy's name.
    pub strategy: &'static str,
    /// The seed.
    pub seed: u64,
    /// Whether the run converged before the trial cap.
    pub converged: bool,
    /// Trials run.
    pub trials: u32,
    /// Moves made, random moves included.
    pub moves: u64,
    /// Sensing cost charged in the whole run.
    pub total_cost: f64,
    /// The measures of Table 1.
    pub table1: Table1,
    /// Whether the final representation is consistent in the literal reading too (equal
    /// sets of optimal actions), if it is sufficient.
    pub consistent_literal: Option<bool>,
    /// Every non-goal free cell.
    pub states: Vec<StateReport>,
    /// Every description.
    pub descriptions: Vec<DescriptionReport>,
    /// The learning curve, one point per trial (empty when an [`Observer`] asked for no
    /// trace: see [`run_observed`]).
    pub trace: Vec<TracePoint>,
    /// The settings of the run.
    pub settings: RunSettings,
}

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
        settings.validate()?;
        let map = mdp::resolve(&settings.map)?;
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
        let world = GridWorld::new(&map);
        let space = FeatureSpace::new(&map, &Manhattan)?;
        let oracle = Oracle::for_grid(&world, settings.gamma.get())?;
        Ok(Setup {
            map,
            world,
            space,
            oracle,
        })
    }
}

impl From<&RunSettings> for LoopParams {
    fn from(settings: &RunSettings) -> LoopParams {
        LoopParams {
            beta: settings.beta,
            gamma: settings.gamma,
            temperature: settings.temperature,
            max_moves: settings.max_moves.get(),
            decrease_threshold: settings.decrease_threshold,
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
}

/// Run trials until the oracle says converged or the trial cap; the oracle looks at the
/// end of every trial.
pub(crate) fn learn<P: Perception + ?Sized, S: Strategy + ?Sized>(
    setup: &Setup,
    settings: &RunSettings,
    perception: &mut P,
    strategy: &mut S,
    table: &mut QTable,
    observer: &mut dyn Observer,
) -> Learned {
    let params = LoopParams::from(settings);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    let starts = setup.world.states();
    let mut out = Learned {
        trace: Vec::new(),
        trials: 0,
        last: None,
        first_sufficient: None,
        first_converged: None,
        moves: 0,
        cost: 0.0,
    };
    for trial in 1..=settings.max_trials {
        let start = starts[rng.random_range(0..starts.len())];
        let rec: TrialRecord = run_trial(
            &setup.world,
            perception,
            strategy,
            table,
            &params,
            start,
            trial,
            &mut rng,
        );
        out.moves += rec.moves as u64;
        out.cost += rec.cost;
        let verdict = perception.verdict(&setup.world, &setup.oracle, table, settings.tolerance);
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
            descriptions: perception.rows(),
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
        if verdict.converged || flow == Flow::Stop {
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
    let setup = Setup::new(settings)?;
    Ok(run_on(&setup, settings))
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
    run_classify(setup, settings, Classify::new(&setup.space), &mut KeepTrace)
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
    run_classify(setup, settings, Classify::new(&setup.space), observer).0
}

/// Run CS-QL with a given CLASSIFY (for example with its cache off, or starting from a
/// representation).
///
/// ```
/// use csql::{Classify, RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let plain = Classify::new(&setup.space).with_cache(false);
/// assert_eq!(csql::run_on_with(&setup, &settings, plain), csql::run_on(&setup, &settings));
/// ```
pub fn run_on_with(setup: &Setup, settings: &RunSettings, classify: Classify) -> RunReport {
    run_classify(setup, settings, classify, &mut KeepTrace).0
}

fn run_classify(
    setup: &Setup,
    settings: &RunSettings,
    classify: Classify,
    observer: &mut dyn Observer,
) -> (RunReport, Representation) {
    let mut perception = classify;
    let mut strategy = settings.strategy.build(settings.random_moves);
    let mut table = QTable::new(setup.world.num_actions()).expect("grid worlds have four actions");
    let learned = learn(
        setup,
        settings,
        &mut perception,
        strategy.as_mut(),
        &mut table,
        observer,
    );
    let report = report(
        setup,
        settings,
        perception.representation(),
        &table,
        learned,
    );
    (report, perception.into_representation())
}

fn report(
    setup: &Setup,
    settings: &RunSettings,
    rep: &Representation,
    table: &QTable,
    learned: Learned,
) -> RunReport {
    let states = setup.world.states();
    let labels: Vec<Option<DescriptionId>> = states
        .iter()
        .map(|&s| rep.matching(&setup.world, &setup.space, s))
        .collect();
    let converged = learned.first_converged.is_some();
    let mut table1 = Table1 {
        cost_to_sufficient: learned.first_sufficient.map(|x| x.1),
        trials_to_sufficient: learned.first_sufficient.map(|x| x.0),
        cost_to_converge: learned.first_converged.map(|x| x.1),
        trials_to_converge: learned.first_converged.map(|x| x.0),
        ..Table1::default()
    };
    if converged {
        let n = rep.len();
        let counts: Vec<usize> = rep.iter().map(|(_, d)| d.len()).collect();
        table1.descriptions = Some(n);
        table1.mean_features = Some(counts.iter().sum::<usize>() as f64 / n as f64);
        table1.max_features = counts.iter().max().copied();
        let tree = StateTree::build(rep, &setup.space);
        let costs: Vec<f64> = states
            .iter()
            .map(|&s| tree.classify(&setup.world, &setup.space, s).1)
            .collect();
        table1.tree_cost_per_state = Some(costs.iter().sum::<f64>() / states.len() as f64);
        let plain: f64 = labels
            .iter()
            .map(|l| {
                rep.get(l.expect("converged: every state matches"))
                    .cost(&setup.space)
            })
            .sum();
        table1.description_cost_per_state = Some(plain / states.len() as f64);
    }
    let last = learned.last;
    let sufficient_now = last.is_some_and(|t| t.sufficient);
    let consistent_literal = sufficient_now.then(|| {
        let rows: Vec<_> = labels
            .iter()
            .map(|l| l.map(|d| qlearn::RowId(d.0)))
            .collect();
        crate::check::Verdict::judge(
            &setup.world,
            &setup.oracle,
            table,
            &rows,
            settings.tolerance,
        )
        .consistent_literal
    });
    RunReport {
        map: setup.map.name().to_string(),
        strategy: settings.strategy.name(),
        seed: settings.seed,
        converged,
        trials: learned.trials,
        moves: learned.moves,
        total_cost: learned.cost,
        table1,
        consistent_literal,
        states: states
            .iter()
            .zip(&labels)
            .map(|(&s, l)| {
                let p = setup.world.pos(s);
                let row = l.map(|d| qlearn::RowId(d.0));
                StateReport {
                    row: p.row,
                    col: p.col,
                    description: l.map(|d| d.0),
                    greedy_action: row.map(|r| {
                        Action::from_id(table.greedy(r))
                            .expect("grid action")
                            .name()
                    }),
                    value: row.map(|r| table.v(r)),
                    v_star: setup.oracle.v_star(s),
                }
            })
            .collect(),
        descriptions: rep
            .iter()
            .map(|(id, d)| DescriptionReport {
                label: id.0,
                features: d
                    .features()
                    .map(|(f, v)| {
                        let o = setup.space.offset(f);
                        FeatureReport {
                            dx: o.dx,
                            dy: o.dy,
                            value: v.name(),
                            cost: setup.space.cost(f),
                        }
                    })
                    .collect(),
            })
            .collect(),
        trace: learned.trace,
        settings: settings.clone(),
    }
}
