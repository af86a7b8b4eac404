//! What a run reports: the measures of the paper's Table 1 (one definition of its rows),
//! the learning curve, every state and description at the end, and the builder that
//! computes them from a finished run.

use std::fmt;

use mdp::World;
use qlearn::QTable;
use serde::Serialize;

use crate::judging::judge::Verdict;
use crate::judging::quality::QualityMethod;
use crate::judging::trials::{Judging, Learned, Scene};
use crate::observe::TracePoint;
use crate::perception::rows::Perception;
use crate::perception::view::Describes;
use crate::settings::learner::StrategyKind;
use crate::settings::values::RunSettings;

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

/// A state at the end of the run (row 0 is the top line of the map).
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1)).unwrap();
/// let s = r.states.iter().find(|s| (s.row, s.col) == (Some(0), Some(1))).unwrap();
/// assert_eq!((s.greedy_action.as_deref(), s.value), (Some("right"), Some(1.0)));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StateReport {
    /// The world's label of the state (worlds that are not grids; grids give row and
    /// column instead).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// Row (grids).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub row: Option<usize>,
    /// Column (grids).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub col: Option<usize>,
    /// The label of the state's description, if it has one.
    pub description: Option<u32>,
    /// The greedy action of that description (lowest action id among ties).
    pub greedy_action: Option<String>,
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
/// assert_eq!(f.cost, (f.dx.unwrap().abs() + f.dy.unwrap().abs()) as f64);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FeatureReport {
    /// The feature's name (worlds that are not grids; grids give its offset instead).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub feature: Option<String>,
    /// Offset to the right (grids).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dx: Option<i32>,
    /// Offset up (grids).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dy: Option<i32>,
    /// The reading required, by its name (on grids `empty`, `obstacle` or `goal`).
    pub value: String,
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
    /// CS-QL's strategy (its name in JSON; absent for a baseline, which has none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strategy: Option<StrategyKind>,
    /// The seed.
    pub seed: u64,
    /// Whether the oracle judged the run converged before the trial cap (never in a run
    /// judged by the policy quality).
    pub converged: bool,
    /// Trials run.
    pub trials: u32,
    /// Moves made, random moves included.
    pub moves: u64,
    /// Sensing cost charged in the whole run.
    pub total_cost: f64,
    /// The policy quality at the end of the run (specification 6.2), in every run: exact
    /// in a deterministic world with exact sensors (1 for an optimal policy). The same as
    /// `quality.policy_quality`.
    pub policy_quality: f64,
    /// Who decided when the run had learned: the oracle (`converged`) or the policy
    /// quality (`quality.trials_to_quality`).
    pub judged_by: Judging,
    /// The measures of Table 1.
    pub table1: Table1,
    /// Whether the final representation is consistent in the literal reading too (equal
    /// sets of optimal actions), if it is sufficient.
    pub consistent_literal: Option<bool>,
    /// Every non-goal free cell.
    pub states: Vec<StateReport>,
    /// Every description.
    pub descriptions: Vec<DescriptionReport>,
    /// The learning curve, one point per trial (empty when an [`crate::Observer`] asked
    /// for no trace: see [`crate::run_observed`]).
    pub trace: Vec<TracePoint>,
    /// The settings of the run.
    pub settings: RunSettings,
    /// Sensing cost per move of navigation after learning (see [`crate::navigate`]);
    /// present only when `predict_sensing` is not `off`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub navigation_cost_per_move: Option<f64>,
    /// The share of navigation's evaluation trials that reached the goal by an optimal
    /// path; present only when `predict_sensing` is not `off`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub navigation_success: Option<f64>,
    /// What prediction did while learning; present only when `predict_sensing` is not
    /// `off`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prediction: Option<crate::perception::sense_less::PredictionStats>,
    /// The policy quality and what it took (specification §6), in every run, whoever
    /// judged it: the measures every learner is compared on.
    pub quality: QualityReport,
    /// Why the run ended early, when it did for a reason of its own: its representation
    /// passed the setting `max_rows` (at most [`crate::MAX_ROWS`]). Absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<String>,
    /// Why the run ended without learning (neither converged nor at policy quality 0.95
    /// kept to its end), and the settings to try. Absent in a run that learned.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub not_learned: Option<crate::NotLearned>,
    /// Every trial scored by its costed return, when the settings price sensing
    /// (`[costly]`; specification 6.12). Absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub costly: Option<crate::CostedRun>,
    /// Why `costly` is absent although the settings price sensing: the run was stopped
    /// (Ctrl-C, SIGTERM, an observer's no) before its trials were played again to be
    /// scored, or it went beyond [`crate::MAX_EPISODES`] trials, more than a report lists.
    /// Absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub costly_missing: Option<String>,
}

impl RunReport {
    /// Who learned, for titles: CS-QL's strategy, or the baseline.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Eager, 1);
    /// assert_eq!(csql::run(&s).unwrap().learned_by(), "eager strategy");
    /// s = s.with_learner(csql::LearnerKind::UTree);
    /// assert_eq!(csql::run(&s).unwrap().learned_by(), "U-Tree");
    /// ```
    pub fn learned_by(&self) -> String {
        match &self.settings.learner {
            crate::LearnerSettings::CsQl(q) => format!("{} strategy", q.strategy),
            crate::LearnerSettings::UTree(_) => "U-Tree".to_string(),
            crate::LearnerSettings::FullSensing => "full sensing".to_string(),
            crate::LearnerSettings::AmrlQ(_) => "AMRL-Q".to_string(),
            crate::LearnerSettings::Belief(_) => "sensing by belief".to_string(),
        }
    }
}

/// The policy quality of a run and what it took (specification §6), in every run.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let paper = csql::run(&s).unwrap();
/// assert_eq!(paper.judged_by, csql::Judging::Oracle);
/// assert_eq!(paper.quality.policy_quality, 1.0); // converged: optimal
/// assert!(paper.quality.trials_to_quality.unwrap() <= paper.trials);
/// s.world.slip = Some(mdp::Slip::new(0.1).unwrap());
/// let q = csql::run(&s).unwrap().quality;
/// assert_eq!(q.method, csql::QualityMethod::Exact);
/// assert!(q.policy_quality > 0.0 && q.policy_quality <= 1.0 + 1e-9);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QualityReport {
    /// The policy quality at the last evaluation (1.0 is optimal).
    pub policy_quality: f64,
    /// Exact policy evaluation, or a seeded Monte Carlo estimate under sensor noise.
    pub method: QualityMethod,
    /// The Monte Carlo standard error (0 when exact).
    pub standard_error: f64,
    /// Evaluations made (every `quality_every` trials, and at the run's last trial).
    pub evaluations: u32,
    /// Trials until the quality first reached 0.95 and stayed there (`None`: not reached).
    pub trials_to_quality: Option<u32>,
    /// Sensing cost charged until then.
    pub cost_to_quality: Option<f64>,
    /// Mean over states of what the learner's own classification of the state costs at
    /// the end, noise-free (CLASSIFY's walk for CS-QL, the tree's for U-Tree, every
    /// feature for full sensing); Table 1's rows 8 and 8' are the costs of a decision
    /// tree built after learning and of the descriptions' own features.
    pub learner_cost_per_state: f64,
    /// Descriptions at the end.
    pub descriptions: usize,
    /// Mean features per description at the end.
    pub mean_features: f64,
}

/// A figure of the paper's Table 1 as the paper prints it.
///
/// ```
/// use csql::{PaperValue, StrategyKind, Table1Row};
/// assert_eq!(Table1Row::Trials.paper(StrategyKind::Lazy), Some(PaperValue::Exact(127.0)));
/// assert_eq!(PaperValue::AtMost(9.0).to_string(), "≤ 9");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PaperValue {
    /// A number.
    Exact(f64),
    /// An upper bound (row 8).
    AtMost(f64),
}

impl PaperValue {
    /// The number (the bound, for an upper bound).
    ///
    /// ```
    /// assert_eq!(csql::PaperValue::AtMost(9.0).value(), 9.0);
    /// ```
    pub fn value(self) -> f64 {
        match self {
            PaperValue::Exact(x) | PaperValue::AtMost(x) => x,
        }
    }
}

impl fmt::Display for PaperValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PaperValue::Exact(x) => write!(f, "{x}"),
            PaperValue::AtMost(x) => write!(f, "≤ {x}"),
        }
    }
}

/// The rows of Table 1: one definition of their numbers, labels, the paper's values and
/// where each comes from in a [`Table1`], shared by every program that prints the table.
///
/// ```
/// use csql::Table1Row;
/// assert_eq!(Table1Row::ALL.len(), 9);
/// assert_eq!(Table1Row::MaxFeatures.number(), "7");
/// let t = csql::Table1 { max_features: Some(12), ..Default::default() };
/// assert_eq!(Table1Row::MaxFeatures.of(&t), Some(12.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Table1Row {
    /// 1: sensing cost until the representation was first sufficient.
    CostToSufficient,
    /// 2: trials until then.
    TrialsToSufficient,
    /// 3: sensing cost until convergence.
    CostToConverge,
    /// 4: trials until convergence.
    Trials,
    /// 5: descriptions.
    Descriptions,
    /// 6: mean features per description.
    MeanFeatures,
    /// 7: most features in one description.
    MaxFeatures,
    /// 8: mean sensing cost per state through the decision tree.
    TreeCostPerState,
    /// 8': mean summed cost of each state's description (ours only).
    DescriptionCostPerState,
}

impl Table1Row {
    /// Every row, in the table's order.
    pub const ALL: [Table1Row; 9] = [
        Table1Row::CostToSufficient,
        Table1Row::TrialsToSufficient,
        Table1Row::CostToConverge,
        Table1Row::Trials,
        Table1Row::Descriptions,
        Table1Row::MeanFeatures,
        Table1Row::MaxFeatures,
        Table1Row::TreeCostPerState,
        Table1Row::DescriptionCostPerState,
    ];

    /// The row's number in the paper (`8'` for the plain form of row 8).
    ///
    /// ```
    /// assert_eq!(csql::Table1Row::DescriptionCostPerState.number(), "8'");
    /// ```
    pub fn number(self) -> &'static str {
        match self {
            Table1Row::CostToSufficient => "1",
            Table1Row::TrialsToSufficient => "2",
            Table1Row::CostToConverge => "3",
            Table1Row::Trials => "4",
            Table1Row::Descriptions => "5",
            Table1Row::MeanFeatures => "6",
            Table1Row::MaxFeatures => "7",
            Table1Row::TreeCostPerState => "8",
            Table1Row::DescriptionCostPerState => "8'",
        }
    }

    /// What the row measures.
    ///
    /// ```
    /// assert_eq!(csql::Table1Row::Descriptions.label(), "descriptions");
    /// ```
    pub fn label(self) -> &'static str {
        match self {
            Table1Row::CostToSufficient => "sensing cost to learn a representation",
            Table1Row::TrialsToSufficient => "trials to learn a representation",
            Table1Row::CostToConverge => "sensing cost to convergence",
            Table1Row::Trials => "trials to convergence",
            Table1Row::Descriptions => "descriptions",
            Table1Row::MeanFeatures => "mean features per description",
            Table1Row::MaxFeatures => "max features in a description",
            Table1Row::TreeCostPerState => "mean sensing cost per state (decision tree)",
            Table1Row::DescriptionCostPerState => {
                "mean sensing cost per state (description features)"
            }
        }
    }

    /// Decimal places to print the row's value with (mean over runs aside).
    ///
    /// ```
    /// assert_eq!(csql::Table1Row::MeanFeatures.decimals(), 2);
    /// ```
    pub fn decimals(self) -> usize {
        match self {
            Table1Row::MeanFeatures
            | Table1Row::TreeCostPerState
            | Table1Row::DescriptionCostPerState => 2,
            _ => 0,
        }
    }

    /// The paper's figure for a strategy (`None` for row 8', which the paper has not).
    ///
    /// ```
    /// use csql::{PaperValue, StrategyKind, Table1Row};
    /// assert_eq!(Table1Row::TreeCostPerState.paper(StrategyKind::Eager), Some(PaperValue::AtMost(16.0)));
    /// ```
    pub fn paper(self, strategy: StrategyKind) -> Option<PaperValue> {
        // Resetting, lazy, random, eager.
        let [resetting, lazy, random, eager] = match self {
            Table1Row::CostToSufficient => [467768.0, 62984.0, 37550.0, 27184.0],
            Table1Row::TrialsToSufficient => [851.0, 114.0, 58.0, 30.0],
            Table1Row::CostToConverge => [506313.0, 70562.0, 61051.0, 88585.0],
            Table1Row::Trials => [927.0, 127.0, 91.0, 86.0],
            Table1Row::Descriptions => [50.0, 50.0, 50.0, 50.0],
            Table1Row::MeanFeatures => [6.4, 6.9, 7.5, 10.2],
            Table1Row::MaxFeatures => [9.2, 10.6, 12.3, 16.8],
            Table1Row::TreeCostPerState => [9.0, 10.0, 11.0, 16.0],
            Table1Row::DescriptionCostPerState => return None,
        };
        let x = match strategy {
            StrategyKind::Resetting => resetting,
            StrategyKind::Lazy => lazy,
            StrategyKind::Random => random,
            StrategyKind::Eager => eager,
        };
        Some(if self == Table1Row::TreeCostPerState {
            PaperValue::AtMost(x)
        } else {
            PaperValue::Exact(x)
        })
    }

    /// The row's value in one run's measures (`None` if the run did not reach it).
    ///
    /// ```
    /// let t = csql::Table1 { trials_to_converge: Some(40), ..Default::default() };
    /// assert_eq!(csql::Table1Row::Trials.of(&t), Some(40.0));
    /// assert_eq!(csql::Table1Row::Descriptions.of(&t), None);
    /// ```
    pub fn of(self, t: &Table1) -> Option<f64> {
        match self {
            Table1Row::CostToSufficient => t.cost_to_sufficient,
            Table1Row::TrialsToSufficient => t.trials_to_sufficient.map(f64::from),
            Table1Row::CostToConverge => t.cost_to_converge,
            Table1Row::Trials => t.trials_to_converge.map(f64::from),
            Table1Row::Descriptions => t.descriptions.map(|n| n as f64),
            Table1Row::MeanFeatures => t.mean_features,
            Table1Row::MaxFeatures => t.max_features.map(|n| n as f64),
            Table1Row::TreeCostPerState => t.tree_cost_per_state,
            Table1Row::DescriptionCostPerState => t.description_cost_per_state,
        }
    }
}

/// One run's Table 1 as text: a header and a row per measure, `not reached` where the
/// run did not get there, in columns as wide as their widest cell.
///
/// ```
/// let t = csql::Table1 { descriptions: Some(50), ..Default::default() };
/// let text = t.to_string();
/// assert!(text.lines().any(|l| l.starts_with("5 ") && l.ends_with(" 50")));
/// assert!(text.contains("not reached"));
/// // Every line has the same width.
/// let widths: Vec<usize> = text.lines().map(|l| l.chars().count()).collect();
/// assert!(widths.windows(2).all(|w| w[0] == w[1]));
/// ```
impl fmt::Display for Table1 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let rows: Vec<(String, String)> = Table1Row::ALL
            .iter()
            .map(|row| {
                let value = row.of(self).map_or_else(
                    || "not reached".to_string(),
                    |x| format!("{x:.*}", row.decimals()),
                );
                (format!("{} {}", row.number(), row.label()), value)
            })
            .collect();
        let head = ("Table 1 row", "value");
        let width = |s: &str| s.chars().count();
        let left = rows
            .iter()
            .map(|r| width(&r.0))
            .chain([width(head.0)])
            .max();
        let right = rows
            .iter()
            .map(|r| width(&r.1))
            .chain([width(head.1)])
            .max();
        let (left, right) = (left.unwrap_or(0), right.unwrap_or(0));
        writeln!(f, "{:<left$}  {:>right$}", head.0, head.1)?;
        for (name, value) in rows {
            writeln!(f, "{name:<left$}  {value:>right$}")?;
        }
        Ok(())
    }
}

pub(crate) fn report<
    W: World + ?Sized,
    P: Perception + Describes + crate::perception::view::Sees,
>(
    scene: &Scene<'_, W>,
    settings: &RunSettings,
    perception: &mut P,
    table: &QTable,
    learned: Learned,
) -> RunReport {
    let world = scene.world;
    let states = world.states();
    let rows: Vec<Option<qlearn::RowId>> = states
        .iter()
        .map(|&s| perception.lookup(world, s))
        .collect();
    let described = perception.described();
    let converged = learned.first_converged.is_some();
    let reached = learned.quality.reached;
    let mut table1 = Table1 {
        cost_to_sufficient: learned.first_sufficient.map(|x| x.1),
        trials_to_sufficient: learned.first_sufficient.map(|x| x.0),
        cost_to_converge: learned.first_converged.map(|x| x.1),
        trials_to_converge: learned.first_converged.map(|x| x.0),
        ..Table1::default()
    };
    let n = described.len().max(1);
    let counts: Vec<usize> = described.iter().map(|(_, d)| d.len()).collect();
    let mean_features = counts.iter().sum::<usize>() as f64 / n as f64;
    if converged || reached.is_some() {
        table1.descriptions = Some(n);
        table1.mean_features = Some(mean_features);
        table1.max_features = counts.iter().max().copied();
        let (tree_cost, description_cost) = perception.table1_costs(world);
        table1.tree_cost_per_state = Some(tree_cost);
        table1.description_cost_per_state = Some(description_cost);
    }
    let learner_cost_per_state = states
        .iter()
        .map(|&s| perception.cost_after_learning(world, s))
        .sum::<f64>()
        / states.len() as f64;
    let track = learned.quality;
    let last_quality = track
        .last
        .expect("learning evaluates the quality at its last trial");
    let quality = QualityReport {
        policy_quality: last_quality.quality,
        method: last_quality.method,
        standard_error: last_quality.standard_error,
        evaluations: track.evaluations,
        trials_to_quality: track.reached.map(|r| r.0),
        cost_to_quality: track.reached.map(|r| r.1),
        learner_cost_per_state,
        descriptions: described.len(),
        mean_features,
    };
    let ending = crate::judging::diagnosis::Ending {
        judging: learned.judging,
        converged,
        kept_quality: reached.is_some(),
        quality: quality.policy_quality,
        trials: learned.trials,
        capped: learned.capped,
        stopped: learned.stopped,
        decreases: learned.decreases,
        descriptions: described.len(),
    };
    let not_learned = crate::judging::diagnosis::diagnose(world, settings, &ending);
    let last = learned.last;
    let sufficient_now = last.is_some_and(|t| t.sufficient);
    let consistent_literal = sufficient_now.then(|| {
        Verdict::judge(world, scene.oracle, table, &rows, settings.tolerance.get())
            .consistent_literal
    });
    RunReport {
        map: scene.name.to_string(),
        strategy: settings.learner.strategy(),
        seed: settings.seed,
        converged,
        trials: learned.trials,
        moves: learned.moves,
        total_cost: learned.cost,
        policy_quality: quality.policy_quality,
        judged_by: learned.judging,
        table1,
        consistent_literal,
        states: states
            .iter()
            .zip(&rows)
            .map(|(&s, &row)| {
                let p = world.grid().map(|g| g.pos(s));
                StateReport {
                    label: p.is_none().then(|| world.state_label(s)),
                    row: p.map(|p| p.row),
                    col: p.map(|p| p.col),
                    description: row.map(|r| r.0),
                    greedy_action: row.map(|r| world.action_name(table.greedy(r))),
                    value: row.map(|r| table.v(r)),
                    v_star: scene.oracle.v_star(s),
                }
            })
            .collect(),
        descriptions: described
            .iter()
            .map(|(row, d)| DescriptionReport {
                label: row.0,
                features: d
                    .iter()
                    .map(|&(f, v)| {
                        let o = world.local_space().map(|space| space.offset(f));
                        FeatureReport {
                            feature: o.is_none().then(|| world.feature_name(f)),
                            dx: o.map(|o| o.dx),
                            dy: o.map(|o| o.dy),
                            value: world.reading_name(f, v),
                            cost: world.price(f),
                        }
                    })
                    .collect(),
            })
            .collect(),
        trace: learned.trace,
        settings: settings.clone(),
        navigation_cost_per_move: None,
        navigation_success: None,
        prediction: None,
        quality,
        stopped: learned.capped.then(|| {
            format!(
                "the representation passed max_rows = {} rows at trial {}",
                settings.max_rows, learned.trials
            )
        }),
        not_learned,
        costly: None,
        costly_missing: None,
    }
}
