//! The settings file's form, and the one conversion from it to [`RunSettings`].
//!
//! A settings file (and a report's `settings`) is flat: the learner's keys sit beside the
//! others (`strategy`, `predict_sensing`, the tables `[prediction]` and `[u_tree]`, the
//! CS-QL keys of `[extensions]`). A [`SettingsDraft`] holds what was given, from a file
//! and from flags over it; [`SettingsDraft::build`] gives each learner only its own
//! settings, fills what was not given with the paper's values, and checks everything
//! once, so that a key that means nothing for the learner chosen is refused with a
//! message that names both.

use std::io::Read;
use std::path::Path;

use qlearn::{Discount, LearningRate, MoveCap, Temperature};
use serde::{Deserialize, Serialize};

use crate::detector::{DetectorKind, RateParams};
use crate::error::{Error, SettingsProblem};
use crate::extensions::{Extensions, Matching, WorldExtras};
use crate::learner::{CsQlSettings, Learner, LearnerKind, PAPER_RANDOM_MOVES, UTreeParams};
use crate::predict::level::{PredictSensing, Prediction};
use crate::settings::{
    CostlySettings, JudgeSettings, MAX_ROWS, MAX_SETTINGS_BYTES, MapSource, NonNegative,
    RunSettings, TrialCap,
};
use crate::strategy::StrategyKind;

/// The map of a draft that names none (as `csrl run` has it).
pub const DEFAULT_MAP: &str = "tan8x8";

/// The settings as given: every key optional, in the settings file's flat layout.
///
/// Gather a file and flags over it ([`SettingsDraft::from_file`],
/// [`SettingsDraft::overlay`]), then [`SettingsDraft::build`] the run's settings. What
/// was not given takes the paper's value ([`RunSettings::tan1991`]); the map
/// [`DEFAULT_MAP`], CS-QL with the resetting strategy and seed 1 when those are not given
/// either, as `csrl run` has them.
///
/// ```
/// use csql::{LearnerKind, SettingsDraft, StrategyKind};
/// let mut draft = SettingsDraft::from_toml("strategy = \"lazy\"\n[extensions]\nreads = 3", "my.toml").unwrap();
/// draft.overlay(SettingsDraft { seed: Some(7), ..SettingsDraft::default() });
/// let s = draft.build().unwrap();
/// assert_eq!((s.learner.strategy(), s.seed), (Some(StrategyKind::Lazy), 7));
/// assert_eq!(s.cs_ql().unwrap().extensions.reads, 3);
/// // CS-QL's keys with a baseline mean nothing, and the message names both.
/// draft.learner = Some(LearnerKind::UTree);
/// let err = draft.build().unwrap_err().to_string();
/// assert!(err.contains("strategy = lazy") && err.contains("learner = u-tree"), "{err}");
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SettingsDraft {
    /// `map`: a built-in name, a file, a spec, or a world.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub map: Option<MapSource>,
    /// `strategy` (CS-QL only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strategy: Option<StrategyKind>,
    /// `beta`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta: Option<LearningRate>,
    /// `gamma`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<Discount>,
    /// `temperature`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub temperature: Option<Temperature>,
    /// `max_moves`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_moves: Option<MoveCap>,
    /// `random_moves` (CS-QL's random strategy only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub random_moves: Option<u32>,
    /// `tolerance`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<NonNegative>,
    /// `decrease_threshold`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub decrease_threshold: Option<NonNegative>,
    /// `max_trials`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_trials: Option<TrialCap>,
    /// `seed`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// `predict_sensing` (CS-QL only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub predict_sensing: Option<PredictSensing>,
    /// The table `[prediction]` (CS-QL, with `predict_sensing` other than `off`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prediction: Option<Prediction>,
    /// The table `[world]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub world: Option<WorldExtras>,
    /// The table `[extensions]`: CS-QL's extensions and how the run is judged.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<ExtensionsTable>,
    /// `learner`: `cs-ql` (when absent), `u-tree`, `full-sensing`, `amrl-q` or `belief`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub learner: Option<LearnerKind>,
    /// The table `[u_tree]` (U-Tree only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub u_tree: Option<UTreeParams>,
    /// `max_rows`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_rows: Option<usize>,
    /// The table `[amrl_q]` (AMRL-Q only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub amrl_q: Option<crate::AmrlParams>,
    /// The table `[costly]`: sensing priced in reward units.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub costly: Option<CostlyTable>,
    /// The table `[belief]` (sensing by belief only; its `price_scale` is `[costly]
    /// price`, not a key of the table).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub belief: Option<crate::BeliefParams>,
}

/// The settings file's table `[costly]`: `price` (reward units per unit of sensing cost;
/// the table means nothing without it) and `rule` (`with-move`, the default, or
/// `after-outcome`).
///
/// ```
/// let d = csql::SettingsDraft::from_toml("[costly]\nprice = 0.025\nrule = \"after-outcome\"", "f").unwrap();
/// let c = d.build().unwrap().costly.unwrap();
/// assert_eq!((c.price, c.rule), (0.025, mdp::SensingRule::AfterOutcome));
/// let d = csql::SettingsDraft::from_toml("[costly]\nrule = \"after-outcome\"", "f").unwrap();
/// assert!(d.build().unwrap_err().to_string().contains("costly.price"));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CostlyTable {
    /// `price`: reward units per unit of sensing cost.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub price: Option<f64>,
    /// `rule`: when sensing is decided.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rule: Option<mdp::SensingRule>,
}

/// The settings file's table `[extensions]`: CS-QL's extensions ([`Extensions`]) and how
/// the run is judged ([`JudgeSettings`]), each key optional and at its default when
/// absent (and then left out of a report's JSON).
///
/// ```
/// let t = csql::ExtensionsTable::from_parts(csql::Extensions::default(), csql::JudgeSettings::default());
/// assert_eq!(t.split(), (csql::Extensions::default(), csql::JudgeSettings::default()));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExtensionsTable {
    /// `detector` ([`Extensions::detector`]).
    #[serde(skip_serializing_if = "is_default")]
    pub detector: DetectorKind,
    /// `rate` ([`Extensions::rate`]).
    #[serde(skip_serializing_if = "is_default")]
    pub rate: RateParams,
    /// `matching` ([`Extensions::matching`]).
    #[serde(skip_serializing_if = "is_default")]
    pub matching: Matching,
    /// `confirm_new` ([`Extensions::confirm_new`]).
    #[serde(skip_serializing_if = "is_one")]
    pub confirm_new: u32,
    /// `reads` ([`Extensions::reads`]).
    #[serde(skip_serializing_if = "is_one")]
    pub reads: u32,
    /// `memory` ([`Extensions::memory`]).
    #[serde(skip_serializing_if = "is_default")]
    pub memory: u32,
    /// `judge_by_quality` ([`JudgeSettings::judge_by_quality`]).
    #[serde(skip_serializing_if = "is_default")]
    pub judge_by_quality: bool,
    /// `quality_every` ([`JudgeSettings::quality_every`]).
    #[serde(skip_serializing_if = "is_default_every")]
    pub quality_every: u32,
    /// `quality_patience` ([`JudgeSettings::quality_patience`]).
    #[serde(skip_serializing_if = "is_default_patience")]
    pub quality_patience: u32,
}

fn is_default<T: Default + PartialEq>(x: &T) -> bool {
    *x == T::default()
}
fn is_one(x: &u32) -> bool {
    *x == 1
}
fn is_default_every(x: &u32) -> bool {
    *x == JudgeSettings::default().quality_every
}
fn is_default_patience(x: &u32) -> bool {
    *x == JudgeSettings::default().quality_patience
}

impl Default for ExtensionsTable {
    fn default() -> ExtensionsTable {
        ExtensionsTable::from_parts(Extensions::default(), JudgeSettings::default())
    }
}

/// The keys of CS-QL's extensions that are not at their defaults.
fn cs_ql_extension_keys(e: &Extensions) -> Vec<&'static str> {
    let d = Extensions::default();
    [
        ("detector", e.detector != d.detector),
        ("rate", e.rate != d.rate),
        ("matching", e.matching != d.matching),
        ("confirm_new", e.confirm_new != d.confirm_new),
        ("reads", e.reads != d.reads),
        ("memory", e.memory != d.memory),
    ]
    .into_iter()
    .filter_map(|(key, given)| given.then_some(key))
    .collect()
}

impl ExtensionsTable {
    /// The table of CS-QL's extensions and the judging.
    ///
    /// ```
    /// let mut j = csql::JudgeSettings::default();
    /// j.judge_by_quality = true;
    /// assert!(csql::ExtensionsTable::from_parts(csql::Extensions::default(), j).judge_by_quality);
    /// ```
    pub fn from_parts(e: Extensions, j: JudgeSettings) -> ExtensionsTable {
        ExtensionsTable {
            detector: e.detector,
            rate: e.rate,
            matching: e.matching,
            confirm_new: e.confirm_new,
            reads: e.reads,
            memory: e.memory,
            judge_by_quality: j.judge_by_quality,
            quality_every: j.quality_every,
            quality_patience: j.quality_patience,
        }
    }

    /// CS-QL's extensions and the judging, apart.
    ///
    /// ```
    /// let (e, _) = csql::ExtensionsTable::default().split();
    /// assert_eq!(e, csql::Extensions::default());
    /// ```
    pub fn split(&self) -> (Extensions, JudgeSettings) {
        (
            Extensions {
                detector: self.detector,
                rate: self.rate,
                matching: self.matching,
                confirm_new: self.confirm_new,
                reads: self.reads,
                memory: self.memory,
            },
            JudgeSettings {
                judge_by_quality: self.judge_by_quality,
                quality_every: self.quality_every,
                quality_patience: self.quality_patience,
            },
        )
    }
}

/// The tables of a settings file and the keys each takes: where a key given in the
/// wrong place belongs (a test checks every key here is read in its table).
const TABLES: &[(&str, &[&str])] = &[
    (
        "world",
        &[
            "slip",
            "sensor_noise",
            "sensing_radius",
            "slide",
            "sensing",
            "factor_costs",
        ],
    ),
    (
        "extensions",
        &[
            "detector",
            "rate",
            "matching",
            "confirm_new",
            "reads",
            "memory",
            "judge_by_quality",
            "quality_every",
            "quality_patience",
        ],
    ),
    (
        "prediction",
        &[
            "confirmations",
            "recheck",
            "max_skips",
            "verify",
            "navigation_trials",
            "memory_moves",
        ],
    ),
    (
        "u_tree",
        &[
            "fringe",
            "alpha",
            "window",
            "test_every",
            "min_group",
            "patience",
        ],
    ),
    (
        "amrl_q",
        &[
            "learning_rate",
            "epsilon",
            "discount",
            "measure_bias",
            "greedy_share",
            "measuring",
        ],
    ),
    ("costly", &["price", "rule"]),
    (
        "belief",
        &[
            "max_uncertain",
            "trust",
            "prior",
            "optimism",
            "whole_state",
            "max_beliefs",
            "move_cost",
        ],
    ),
];

/// The keys of the top level that are not tables.
const TOP: &[&str] = &[
    "map",
    "strategy",
    "beta",
    "gamma",
    "temperature",
    "max_moves",
    "random_moves",
    "tolerance",
    "decrease_threshold",
    "max_trials",
    "seed",
    "predict_sensing",
    "learner",
    "max_rows",
];

/// Tables are tables (`world = [0.3, 0.1]` would set fields by position), and a key in
/// the wrong place says where it belongs.
fn check_layout(layout: &toml::Table) -> Result<(), SettingsProblem> {
    for (key, value) in layout {
        if let Some((table, _)) = TABLES.iter().find(|(t, _)| t == key) {
            let Some(inner) = value.as_table() else {
                return Err(SettingsProblem::Layout(format!(
                    "`{key}` must be a table: write [{key}] and its settings by name, one per line"
                )));
            };
            for inner_key in inner.keys() {
                if TOP.contains(&inner_key.as_str()) {
                    return Err(SettingsProblem::Layout(format!(
                        "`{inner_key}` is a setting of the top level, not of [{table}]: write it before any table"
                    )));
                }
                if let Some((home, _)) = TABLES
                    .iter()
                    .find(|(t, keys)| t != table && keys.contains(&inner_key.as_str()))
                {
                    return Err(SettingsProblem::Layout(format!(
                        "`{inner_key}` is a setting of the [{home}] table, not of [{table}]"
                    )));
                }
            }
            if *table == "belief" && inner.contains_key("price_scale") {
                return Err(SettingsProblem::Layout(
                    "`price_scale` is not a setting of [belief]: sensing by belief prices a feature at its cost times [costly] price".to_string(),
                ));
            }
            if *table == "extensions"
                && let Some(rate) = inner.get("rate")
                && !rate.is_table()
            {
                return Err(SettingsProblem::Layout(
                    "`rate` in [extensions] must be a table: write [extensions.rate] and its settings by name".to_string(),
                ));
            }
        } else if !TOP.contains(&key.as_str())
            && let Some((home, _)) = TABLES.iter().find(|(_, keys)| keys.contains(&key.as_str()))
        {
            return Err(SettingsProblem::Layout(format!(
                "`{key}` is a setting of the [{home}] table: write it under [{home}]"
            )));
        }
    }
    Ok(())
}

impl SettingsDraft {
    /// The settings of TOML text (`source` names it in errors): unknown keys, keys in
    /// the wrong table, tables given as values and invalid values are refused, with the
    /// line and column where the reader has them.
    ///
    /// ```
    /// let d = csql::SettingsDraft::from_toml("temperature = 0.2", "my.toml").unwrap();
    /// assert_eq!(d.temperature.unwrap().get(), 0.2);
    /// assert!(csql::SettingsDraft::from_toml("temprature = 0.2", "my.toml").is_err());
    /// let err = csql::SettingsDraft::from_toml("[world]\nreads = 3", "my.toml").unwrap_err();
    /// assert!(err.to_string().contains("[extensions]"), "{err}");
    /// ```
    pub fn from_toml(text: &str, source: &str) -> Result<SettingsDraft, Error> {
        let fail = |problem: SettingsProblem| Error::Settings {
            source_name: source.to_string(),
            problem,
        };
        // The layout first (tables are tables, keys in their tables), with hints the
        // typed reading below cannot give; then the values, with line and column.
        let layout: toml::Table =
            toml::from_str(text).map_err(|e| fail(SettingsProblem::Parse(e)))?;
        check_layout(&layout).map_err(fail)?;
        toml::from_str(text).map_err(|e| fail(SettingsProblem::Parse(e)))
    }

    /// The settings of a TOML file. Only a regular file of at most
    /// [`MAX_SETTINGS_BYTES`] is read: a directory, a device or a pipe is refused before it
    /// is opened, and reading stops at the limit whatever the file's metadata says.
    ///
    /// ```
    /// assert!(csql::SettingsDraft::from_file(std::path::Path::new("/no/such.toml")).is_err());
    /// ```
    pub fn from_file(path: &Path) -> Result<SettingsDraft, Error> {
        let source = path.display().to_string();
        let fail = |problem: SettingsProblem| Error::Settings {
            source_name: source.clone(),
            problem,
        };
        if !std::fs::metadata(path)
            .map_err(|e| fail(SettingsProblem::Read(e)))?
            .is_file()
        {
            return Err(fail(SettingsProblem::NotAFile));
        }
        let file = std::fs::File::open(path).map_err(|e| fail(SettingsProblem::Read(e)))?;
        if !file
            .metadata()
            .map_err(|e| fail(SettingsProblem::Read(e)))?
            .is_file()
        {
            return Err(fail(SettingsProblem::NotAFile));
        }
        let mut bytes = Vec::new();
        file.take(MAX_SETTINGS_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| fail(SettingsProblem::Read(e)))?;
        if bytes.len() as u64 > MAX_SETTINGS_BYTES {
            return Err(fail(SettingsProblem::TooLarge {
                limit: MAX_SETTINGS_BYTES,
            }));
        }
        let text = String::from_utf8(bytes).map_err(|e| fail(SettingsProblem::NotUtf8(e)))?;
        SettingsDraft::from_toml(&text, &source)
    }

    /// Give `later` the last word: each key it has replaces this draft's (a table
    /// replaces the whole table).
    ///
    /// ```
    /// let mut d = csql::SettingsDraft::from_toml("seed = 3\nbeta = 0.5", "f").unwrap();
    /// d.overlay(csql::SettingsDraft { seed: Some(9), ..Default::default() });
    /// assert_eq!((d.seed, d.beta.unwrap().get()), (Some(9), 0.5));
    /// ```
    pub fn overlay(&mut self, later: SettingsDraft) {
        macro_rules! take {
            ($($field:ident),*) => { $( if later.$field.is_some() { self.$field = later.$field; } )* };
        }
        take!(
            map,
            strategy,
            beta,
            gamma,
            temperature,
            max_moves,
            random_moves,
            tolerance,
            decrease_threshold,
            max_trials,
            seed,
            predict_sensing,
            prediction,
            world,
            extensions,
            learner,
            u_tree,
            max_rows,
            amrl_q,
            costly,
            belief
        );
    }

    /// Forget the keys that belong to a learner (before another learner is chosen).
    fn forget_learner_keys(&mut self) {
        self.strategy = None;
        self.random_moves = None;
        self.predict_sensing = None;
        self.prediction = None;
        self.u_tree = None;
        self.amrl_q = None;
        self.belief = None;
        if let Some(table) = &mut self.extensions {
            let (_, judge) = table.split();
            *table = ExtensionsTable::from_parts(Extensions::default(), judge);
        }
    }

    /// The run's settings: each learner with only its own keys, everything not given at
    /// the paper's value, and every combination checked once
    /// ([`RunSettings::validate`]). A key of one learner given with another is refused,
    /// naming both.
    ///
    /// ```
    /// let d = csql::SettingsDraft::from_toml("learner = \"u-tree\"\n[u_tree]\nfringe = 3", "f").unwrap();
    /// let s = d.build().unwrap();
    /// assert!(matches!(s.learner, csql::Learner::UTree(p) if p.fringe == 3));
    /// let d = csql::SettingsDraft::from_toml("[u_tree]\nfringe = 3", "f").unwrap();
    /// assert!(d.build().unwrap_err().to_string().contains("learner = cs-ql"));
    /// ```
    pub fn build(&self) -> Result<RunSettings, Error> {
        let kind = self.learner.unwrap_or_default();
        let (extensions, judge) = self.extensions.unwrap_or_default().split();
        let conflict = |first: String, why: &'static str| {
            Err(Error::Conflict {
                first,
                second: format!("learner = {kind}"),
                why,
            })
        };
        if kind != LearnerKind::UTree && self.u_tree.is_some_and(|p| !p.is_default()) {
            return conflict(
                "[u_tree] settings".to_string(),
                "[u_tree] tunes learner = \"u-tree\"",
            );
        }
        if kind != LearnerKind::AmrlQ && self.amrl_q.is_some_and(|p| !p.is_default()) {
            return conflict(
                "[amrl_q] settings".to_string(),
                "[amrl_q] tunes learner = \"amrl-q\"",
            );
        }
        if kind != LearnerKind::Belief && self.belief.is_some_and(|p| !p.is_default()) {
            return conflict(
                "[belief] settings".to_string(),
                "[belief] tunes learner = \"belief\"",
            );
        }
        let costly = match self.costly {
            None => None,
            Some(CostlyTable { price: None, .. }) => {
                return Err(Error::InvalidSetting {
                    value: "[costly] without costly.price".to_string(),
                    expected: "costly.price, reward units per unit of sensing cost",
                });
            }
            Some(CostlyTable {
                price: Some(price),
                rule,
            }) => Some(CostlySettings {
                price,
                rule: rule.unwrap_or(mdp::SensingRule::WithMove),
            }),
        };
        let learner = match kind {
            LearnerKind::CsQl => Learner::CsQl(CsQlSettings {
                strategy: self.strategy.unwrap_or(StrategyKind::Resetting),
                random_moves: self.random_moves.unwrap_or(PAPER_RANDOM_MOVES),
                predict_sensing: self.predict_sensing.unwrap_or_default(),
                prediction: self.prediction.unwrap_or_default(),
                extensions,
            }),
            LearnerKind::UTree
            | LearnerKind::FullSensing
            | LearnerKind::AmrlQ
            | LearnerKind::Belief => {
                let why =
                    "it is a setting of CS-QL, and the baselines have none of CS-QL's settings";
                if let Some(k) = self.strategy {
                    return conflict(format!("strategy = {k}"), why);
                }
                if let Some(n) = self.random_moves {
                    return conflict(format!("random_moves = {n}"), why);
                }
                if let Some(level) = self.predict_sensing.filter(|l| !l.is_off()) {
                    return conflict(format!("predict_sensing = {level}"), why);
                }
                if self.prediction.is_some_and(|p| !p.is_default()) {
                    return conflict("[prediction] settings".to_string(), why);
                }
                let given = cs_ql_extension_keys(&extensions);
                if !given.is_empty() {
                    return conflict(format!("[extensions] {}", given.join(", ")), why);
                }
                match kind {
                    LearnerKind::UTree => Learner::UTree(self.u_tree.unwrap_or_default()),
                    LearnerKind::AmrlQ => Learner::AmrlQ(self.amrl_q.unwrap_or_default()),
                    // Features priced at `[costly] price` (which the learner needs: refused
                    // without it below).
                    LearnerKind::Belief => Learner::Belief(crate::BeliefParams {
                        price_scale: costly.map_or(1.0, |c: CostlySettings| c.price),
                        ..self.belief.unwrap_or_default()
                    }),
                    _ => Learner::FullSensing,
                }
            }
        };
        let paper = RunSettings::tan1991(DEFAULT_MAP, StrategyKind::Resetting, 1);
        let settings = RunSettings {
            map: self.map.clone().unwrap_or(paper.map),
            learner,
            beta: self.beta.unwrap_or(paper.beta),
            gamma: self.gamma.unwrap_or(paper.gamma),
            temperature: self.temperature.unwrap_or(paper.temperature),
            max_moves: self.max_moves.unwrap_or(paper.max_moves),
            tolerance: self.tolerance.unwrap_or(paper.tolerance),
            decrease_threshold: self.decrease_threshold.unwrap_or(paper.decrease_threshold),
            max_trials: self.max_trials.unwrap_or(paper.max_trials),
            seed: self.seed.unwrap_or(paper.seed),
            world: self.world.clone().unwrap_or_default(),
            judge,
            max_rows: self.max_rows.unwrap_or(MAX_ROWS),
            costly,
        };
        settings.validate()?;
        Ok(settings)
    }
}

/// Every key of the settings, as a report's JSON has them: the learner's own keys, and
/// the settings beyond the paper only where they are not at their defaults.
///
/// ```
/// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let d = csql::SettingsDraft::from(&s);
/// assert_eq!(d.build().unwrap(), s);
/// assert!(d.extensions.is_none() && d.learner.is_none());
/// ```
impl From<&RunSettings> for SettingsDraft {
    fn from(s: &RunSettings) -> SettingsDraft {
        let q = s.cs_ql();
        let table = ExtensionsTable::from_parts(s.extensions(), s.judge);
        SettingsDraft {
            map: Some(s.map.clone()),
            strategy: q.map(|q| q.strategy),
            beta: Some(s.beta),
            gamma: Some(s.gamma),
            temperature: Some(s.temperature),
            max_moves: Some(s.max_moves),
            random_moves: q.map(|q| q.random_moves),
            tolerance: Some(s.tolerance),
            decrease_threshold: Some(s.decrease_threshold),
            max_trials: Some(s.max_trials),
            seed: Some(s.seed),
            predict_sensing: q.map(|q| q.predict_sensing).filter(|l| !l.is_off()),
            prediction: q.map(|q| q.prediction).filter(|p| !p.is_default()),
            world: Some(s.world.clone()).filter(|w| !w.is_default()),
            extensions: Some(table).filter(|t| *t != ExtensionsTable::default()),
            learner: Some(s.learner.kind()).filter(|k| !k.is_cs_ql()),
            u_tree: match s.learner {
                Learner::UTree(p) if !p.is_default() => Some(p),
                _ => None,
            },
            max_rows: Some(s.max_rows).filter(|n| *n != MAX_ROWS),
            amrl_q: match s.learner {
                Learner::AmrlQ(p) if !p.is_default() => Some(p),
                _ => None,
            },
            costly: s.costly.map(|c| CostlyTable {
                price: Some(c.price),
                rule: Some(c.rule),
            }),
            belief: match s.learner {
                Learner::Belief(p) if !p.is_default() => Some(p),
                _ => None,
            },
        }
    }
}

impl Serialize for RunSettings {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        SettingsDraft::from(self).serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for RunSettings {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        SettingsDraft::deserialize(deserializer)?
            .build()
            .map_err(serde::de::Error::custom)
    }
}

impl RunSettings {
    /// Override settings from TOML text (`source` names it in errors), and check the
    /// result. A file that chooses another learner starts that learner from its
    /// defaults; unknown keys, invalid values and keys that mean nothing for the learner
    /// are refused.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.apply_toml("temperature = 0.2\nstrategy = \"eager\"", "my.toml").unwrap();
    /// assert_eq!(s.temperature.get(), 0.2);
    /// assert_eq!(s.learner.strategy(), Some(csql::StrategyKind::Eager));
    /// assert!(s.apply_toml("temprature = 0.2", "my.toml").is_err());
    /// assert!(s.apply_toml("gamma = 1.0", "my.toml").is_err());
    /// s.apply_toml("learner = \"u-tree\"", "my.toml").unwrap();
    /// assert_eq!(s.learner.strategy(), None);
    /// ```
    pub fn apply_toml(&mut self, text: &str, source: &str) -> Result<(), Error> {
        self.apply(SettingsDraft::from_toml(text, source)?)
    }

    /// Override settings from a TOML file as [`RunSettings::apply_toml`] does (read as
    /// [`SettingsDraft::from_file`] reads it).
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(s.apply_file(std::path::Path::new("/no/such.toml")).is_err());
    /// ```
    pub fn apply_file(&mut self, path: &Path) -> Result<(), Error> {
        self.apply(SettingsDraft::from_file(path)?)
    }

    fn apply(&mut self, file: SettingsDraft) -> Result<(), Error> {
        let mut draft = SettingsDraft::from(&*self);
        if file.learner.is_some_and(|k| k != self.learner.kind()) {
            draft.forget_learner_keys();
        }
        draft.overlay(file);
        *self = draft.build()?;
        Ok(())
    }
}
