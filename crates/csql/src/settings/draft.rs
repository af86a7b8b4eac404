//! The settings file's form, and the one conversion from it to [`RunSettings`].
//!
//! A settings file (and a report's `settings`) is flat: the learner's keys sit beside the
//! others (`strategy`, `predict_sensing`, the tables `[prediction]`, `[extensions]` and
//! `[u_tree]`, how a run is judged in `[judge]`). Which learner reads which key is one
//! table, [`SETTING_KEYS`]. A [`SettingsDraft`] holds what was given, from a file and from
//! flags over it; [`SettingsDraft::build`] refuses every key given that the learner chosen
//! does not read, naming the key and the learner, gives each learner only its own
//! settings, fills what was not given with the world's defaults (the paper's values, or
//! a built-in world's own: [`crate::WorldDefaults`]), and checks everything once.

use std::io::Read;
use std::path::Path;

use qlearn::{Discount, LearningRate, MoveCap, Temperature};
use serde::{Deserialize, Serialize};

use crate::error::{Error, SettingsProblem};
use crate::perception::classify::Matching;
use crate::perception::sense_less::level::{PredictSensing, PredictionParams};
use crate::settings::defaults::WorldDefaults;
use crate::settings::extensions::{DetectorKind, Extensions, RateParams, WorldExtras};
use crate::settings::learner::{
    CsQlSettings, LearnerKind, LearnerSettings, PAPER_RANDOM_MOVES, StrategyKind, UTreeParams,
};
use crate::settings::values::{
    CostlySettings, JudgeSettings, MAX_ROWS, MAX_SETTINGS_BYTES, MapSource, NonNegative,
    RunSettings, TrialCap,
};

/// The map of a draft that names none (as `csrl run` has it).
pub const DEFAULT_MAP: &str = "tan8x8";

/// The one declaration of the settings file's keys: each field of [`SettingsDraft`] is
/// a top-level key, with the learners that read it (`map: MapSource => EVERY;`), or a
/// table, with the learners that read each of its keys (`world: WorldExtras => { slip:
/// EVERY, .. };`). From it come the struct, [`SETTING_KEYS`] (the top level's keys, then
/// each table's, in the order declared), and the walks over the fields that
/// [`SettingsDraft::overlay`], [`SettingsDraft::build`] and the conversions use, so that a
/// key is added in one place. The fields' order is the order of a report's JSON.
macro_rules! settings_draft {
    (
        $(#[$attr:meta])*
        pub struct SettingsDraft {
            $(
                $(#[$field_doc:meta])*
                $field:ident: $ty:ty => $($read_by:ident)? $({ $($key:ident: $key_read_by:ident),* $(,)? })?;
            )*
        }
    ) => {
        $(#[$attr])*
        pub struct SettingsDraft {
            $(
                $(#[$field_doc])*
                #[serde(skip_serializing_if = "Option::is_none")]
                pub $field: Option<$ty>,
            )*
        }

        /// Every key of a settings file, where it is written, and which learners read it: the one
        /// definition that [`SettingsDraft::build`] refuses by (a key given that the learner does
        /// not read), that [`SettingsDraft::from_toml`] places keys by (a key in the wrong table
        /// says where it belongs), and that `csrl run --help` prints. A test holds it to the
        /// fields of the settings, to the learners' code, to `csrl run --help` and to the
        /// specification's list (6.9).
        ///
        /// AMRL-Q and sensing by belief play episodes of their own (`episodes` of at most
        /// `max_moves` moves): they read no key of Q-learning, convergence or judging, nor
        /// sensor noise (their worlds are read exactly).
        ///
        /// ```
        /// use csql::{LearnerKind, SETTING_KEYS};
        /// let read = |kind| SETTING_KEYS.iter().filter(|k| k.reads(kind)).count();
        /// assert!(read(LearnerKind::CsQl) > read(LearnerKind::FullSensing));
        /// assert!(SETTING_KEYS.iter().all(|k| !k.read_by.is_empty()));
        /// ```
        pub const SETTING_KEYS: &[SettingKey] = &[
            $($(top(stringify!($field), $read_by),)?)*
            $($($(inner(stringify!($field), stringify!($key), $key_read_by),)*)?)*
        ];

        impl SettingsDraft {
            /// Each field that `later` has replaces this draft's.
            fn take_given(&mut self, later: SettingsDraft) {
                $(if later.$field.is_some() {
                    self.$field = later.$field;
                })*
            }

            /// The top-level key `name` as given, with its value (`beta = 0.5`).
            fn top_given(&self, name: &str) -> Option<String> {
                match name {
                    // (Naming `$read_by` keeps this arm to the top-level keys.)
                    $($(stringify!($field) => {
                        let _: &[LearnerKind] = $read_by;
                        self.$field.as_ref().map(|v| format!("{name} = {}", v.shown()))
                    })?)*
                    _ => None,
                }
            }

            /// Table `table` as given: named with the keys that are not at their defaults.
            fn table_given(&self, table: &str) -> Option<String> {
                match table {
                    // (Naming `$key` keeps this arm to the tables.)
                    $($(stringify!($field) => {
                        $(let _ = stringify!($key);)*
                        self.$field.as_ref().map(|t| table_named(table, t))
                    })?)*
                    _ => None,
                }
            }

            /// Forget the top-level key or the whole table `name`.
            fn forget(&mut self, name: &str) {
                match name {
                    $(stringify!($field) => self.$field = None,)*
                    _ => {}
                }
            }
        }
    };
}

settings_draft! {
    /// The settings as given: every key optional, in the settings file's flat layout.
    ///
    /// Gather a file and flags over it ([`SettingsDraft::from_file`],
    /// [`SettingsDraft::overlay`]), then [`SettingsDraft::build`] the run's settings. What
    /// was not given takes the paper's value ([`RunSettings::tan1991`]), or where the map
    /// names a built-in world that asks for its own temperature, detector or trial cap, the
    /// world's ([`crate::WorldDefaults`]); the map [`DEFAULT_MAP`], CS-QL with the resetting
    /// strategy and seed 1 when those are not given either, as `csrl run` has them.
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
        map: MapSource => EVERY;
        /// `strategy` (CS-QL only).
        strategy: StrategyKind => CS_QL;
        /// `beta`.
        beta: LearningRate => TRIALS;
        /// `gamma`.
        gamma: Discount => TRIALS;
        /// `temperature`.
        temperature: Temperature => TRIALS;
        /// `max_moves`.
        max_moves: MoveCap => EVERY;
        /// `random_moves` (CS-QL's random strategy only).
        random_moves: u32 => CS_QL;
        /// `tolerance`.
        tolerance: NonNegative => TRIALS;
        /// `decrease_threshold`.
        decrease_threshold: NonNegative => TRIALS;
        /// `max_trials`: the cap on the trials of a learner judged over trials.
        max_trials: TrialCap => TRIALS;
        /// `episodes`: how many episodes a learner played on costed episodes plays
        /// (`amrl-q`, `belief`).
        episodes: TrialCap => EPISODES;
        /// `seed`.
        seed: u64 => EVERY;
        /// `predict_sensing` (CS-QL only).
        predict_sensing: PredictSensing => CS_QL;
        /// The table `[prediction]` (CS-QL, with `predict_sensing` other than `off`).
        prediction: PredictionParams => {
            confirmations: CS_QL,
            recheck: CS_QL,
            max_skips: CS_QL,
            verify: CS_QL,
            navigation_trials: CS_QL,
            memory_moves: CS_QL,
        };
        /// The table `[world]`.
        world: WorldExtras => {
            slip: EVERY,
            sensing_radius: EVERY,
            slide: EVERY,
            sensing: EVERY,
            factor_costs: EVERY,
            sensor_noise: TRIALS,
        };
        /// The table `[extensions]`: CS-QL's extensions (CS-QL only).
        extensions: ExtensionsTable => {
            detector: CS_QL,
            rate: CS_QL,
            matching: CS_QL,
            confirm_new: CS_QL,
            reads: CS_QL,
            memory: CS_QL,
        };
        /// The table `[judge]`: how the run is judged (the learners of [`crate::run`]).
        judge: JudgeSettings => {
            judge_by_quality: TRIALS,
            quality_every: TRIALS,
            quality_patience: TRIALS,
        };
        /// `learner`: `cs-ql` (when absent), `u-tree`, `full-sensing`, `amrl-q` or `belief`.
        learner: LearnerKind => EVERY;
        /// The table `[u_tree]` (U-Tree only).
        u_tree: UTreeParams => {
            fringe: U_TREE,
            alpha: U_TREE,
            window: U_TREE,
            test_every: U_TREE,
            min_group: U_TREE,
            patience: U_TREE,
        };
        /// `max_rows`.
        max_rows: usize => TRIALS;
        /// The table `[amrl_q]` (AMRL-Q only).
        amrl_q: crate::AmrlParams => {
            learning_rate: AMRL_Q,
            epsilon: AMRL_Q,
            discount: AMRL_Q,
            measure_bias: AMRL_Q,
            greedy_share: AMRL_Q,
            measuring: AMRL_Q,
        };
        /// The table `[costly]`: sensing priced in reward units.
        costly: CostlyTable => {
            price: PRICED,
            rule: PRICED,
        };
        /// The table `[belief]` (sensing by belief only; its `price_scale` is `[costly]
        /// price`, not a key of the table).
        belief: crate::BeliefParams => {
            max_uncertain: BELIEF,
            trust: BELIEF,
            prior: BELIEF,
            optimism: BELIEF,
            whole_state: BELIEF,
            max_beliefs: BELIEF,
            move_cost: BELIEF,
            blind_plans: BELIEF,
            shared_moves: BELIEF,
        };
    }
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

/// The settings file's table `[extensions]`: CS-QL's extensions ([`Extensions`]), each
/// key optional and at its default when absent (and then left out of a report's JSON).
/// How a run is judged is the table `[judge]` ([`JudgeSettings`]).
///
/// ```
/// let t = csql::ExtensionsTable::from(csql::Extensions::default());
/// assert_eq!(t.extensions(), csql::Extensions::default());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExtensionsTable {
    /// `detector` ([`Extensions::detector`]); when absent, the world's default
    /// ([`crate::WorldDefaults::detector_for`]: the paper's `decrease`, or a built-in
    /// world's own).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detector: Option<DetectorKind>,
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
}

fn is_default<T: Default + PartialEq>(x: &T) -> bool {
    *x == T::default()
}
fn is_one(x: &u32) -> bool {
    *x == 1
}

impl Default for ExtensionsTable {
    fn default() -> ExtensionsTable {
        ExtensionsTable::from(Extensions::default())
    }
}

/// The table of CS-QL's extensions.
///
/// ```
/// let e = csql::Extensions { reads: 3, ..Default::default() };
/// assert_eq!(csql::ExtensionsTable::from(e).reads, 3);
/// ```
impl From<Extensions> for ExtensionsTable {
    fn from(e: Extensions) -> ExtensionsTable {
        ExtensionsTable {
            detector: (e.detector != DetectorKind::default()).then_some(e.detector),
            rate: e.rate,
            matching: e.matching,
            confirm_new: e.confirm_new,
            reads: e.reads,
            memory: e.memory,
        }
    }
}

impl ExtensionsTable {
    /// CS-QL's extensions of the table, the paper's detector where none is given.
    ///
    /// ```
    /// assert_eq!(csql::ExtensionsTable::default().extensions(), csql::Extensions::default());
    /// ```
    pub fn extensions(&self) -> Extensions {
        self.extensions_with(DetectorKind::default())
    }

    /// CS-QL's extensions of the table, `detector` where the table gives none.
    ///
    /// ```
    /// use csql::{DetectorKind, ExtensionsTable};
    /// let none = ExtensionsTable::default();
    /// assert_eq!(none.extensions_with(DetectorKind::Action).detector, DetectorKind::Action);
    /// let given = ExtensionsTable { detector: Some(DetectorKind::Decrease), ..none };
    /// assert_eq!(given.extensions_with(DetectorKind::Action).detector, DetectorKind::Decrease);
    /// ```
    pub fn extensions_with(&self, detector: DetectorKind) -> Extensions {
        Extensions {
            detector: self.detector.unwrap_or(detector),
            rate: self.rate,
            matching: self.matching,
            confirm_new: self.confirm_new,
            reads: self.reads,
            memory: self.memory,
        }
    }
}

/// The keys a run reads and a step-driven agent ([`crate::Stepper`]) does not, as
/// `(table, key)` (`"*"`: every key of the table), refused by
/// [`SettingsDraft::build_for_stepper`]: the map, the trial and move caps, the tolerance
/// of the oracle's checks, a report's rows, the judging keys, the costed return and every
/// key of `[world]` (the agent senses the caller's world).
///
/// ```
/// assert!(csql::NOT_READ_BY_A_STEPPER.contains(&(None, "max_trials")));
/// assert!(csql::NOT_READ_BY_A_STEPPER.contains(&(Some("world"), "*")));
/// ```
pub const NOT_READ_BY_A_STEPPER: [(Option<&str>, &str); 8] = [
    (None, "map"),
    (None, "max_trials"),
    (None, "max_moves"),
    (None, "tolerance"),
    (None, "max_rows"),
    (Some("world"), "*"),
    (Some("judge"), "*"),
    (Some("costly"), "*"),
];

/// One key of a settings file: where it is written and which learners read it. The
/// settings' keys are [`SETTING_KEYS`].
///
/// ```
/// let beta = csql::setting_key(None, "beta").unwrap();
/// assert!(beta.reads(csql::LearnerKind::UTree) && !beta.reads(csql::LearnerKind::AmrlQ));
/// assert_eq!(csql::setting_key(Some("u_tree"), "fringe").unwrap().path(), "u_tree.fringe");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SettingKey {
    /// The table the key is written in (`[world]` is `Some("world")`), or `None` for the
    /// top level.
    pub table: Option<&'static str>,
    /// The key's name.
    pub name: &'static str,
    /// The learners that read it: given with any other, the key is refused
    /// ([`SettingsDraft::build`]).
    pub read_by: &'static [LearnerKind],
}

impl SettingKey {
    /// Whether learner `kind` reads the key.
    ///
    /// ```
    /// let strategy = csql::setting_key(None, "strategy").unwrap();
    /// assert!(strategy.reads(csql::LearnerKind::CsQl) && !strategy.reads(csql::LearnerKind::UTree));
    /// ```
    pub fn reads(&self, kind: LearnerKind) -> bool {
        self.read_by.contains(&kind)
    }

    /// The key as a report's JSON and the messages name it: `beta`, `world.slip`.
    ///
    /// ```
    /// assert_eq!(csql::setting_key(None, "seed").unwrap().path(), "seed");
    /// ```
    pub fn path(&self) -> String {
        match self.table {
            Some(table) => format!("{table}.{}", self.name),
            None => self.name.to_string(),
        }
    }
}

/// A value as a message names it: `beta = 0.5`, `[world] sensing = factors`.
trait Shown {
    fn shown(&self) -> String;
}

macro_rules! shown_as_displayed {
    ($($ty:ty),*) => {$(
        impl Shown for $ty {
            fn shown(&self) -> String {
                self.to_string()
            }
        }
    )*};
}
shown_as_displayed!(
    MapSource,
    StrategyKind,
    PredictSensing,
    LearnerKind,
    u32,
    u64,
    usize
);

macro_rules! shown_as_its_number {
    ($($ty:ty),*) => {$(
        impl Shown for $ty {
            fn shown(&self) -> String {
                self.get().to_string()
            }
        }
    )*};
}
shown_as_its_number!(
    LearningRate,
    Discount,
    Temperature,
    MoveCap,
    NonNegative,
    TrialCap
);

/// A key of a table as it reads back: a number as Rust writes it, a name without quotes.
impl Shown for toml::Value {
    fn shown(&self) -> String {
        match self {
            toml::Value::Float(x) => x.to_string(),
            toml::Value::String(s) => s.clone(),
            other => other.to_string(),
        }
    }
}

/// Every learner.
const EVERY: &[LearnerKind] = &[
    LearnerKind::CsQl,
    LearnerKind::UTree,
    LearnerKind::FullSensing,
    LearnerKind::AmrlQ,
    LearnerKind::Belief,
];
/// The learners of [`crate::run`], judged over trials of Q-learning.
const TRIALS: &[LearnerKind] = &[
    LearnerKind::CsQl,
    LearnerKind::UTree,
    LearnerKind::FullSensing,
];
/// The learners scored on sensing priced in reward units (U-Tree is not).
const PRICED: &[LearnerKind] = &[
    LearnerKind::CsQl,
    LearnerKind::FullSensing,
    LearnerKind::AmrlQ,
    LearnerKind::Belief,
];
/// The learners played on costed episodes, each a count of its own.
const EPISODES: &[LearnerKind] = &[LearnerKind::AmrlQ, LearnerKind::Belief];
const CS_QL: &[LearnerKind] = &[LearnerKind::CsQl];
const U_TREE: &[LearnerKind] = &[LearnerKind::UTree];
const AMRL_Q: &[LearnerKind] = &[LearnerKind::AmrlQ];
const BELIEF: &[LearnerKind] = &[LearnerKind::Belief];

const fn top(name: &'static str, read_by: &'static [LearnerKind]) -> SettingKey {
    SettingKey {
        table: None,
        name,
        read_by,
    }
}

const fn inner(
    table: &'static str,
    name: &'static str,
    read_by: &'static [LearnerKind],
) -> SettingKey {
    SettingKey {
        table: Some(table),
        name,
        read_by,
    }
}

/// The key `name` of `table` (`None`: the top level), if there is one.
///
/// ```
/// assert!(csql::setting_key(Some("world"), "slip").is_some());
/// assert!(csql::setting_key(None, "slip").is_none());
/// ```
pub fn setting_key(table: Option<&str>, name: &str) -> Option<&'static SettingKey> {
    SETTING_KEYS
        .iter()
        .find(|k| k.table == table && k.name == name)
}

/// The tables of a settings file, in the order of [`SETTING_KEYS`].
///
/// ```
/// let tables: Vec<_> = csql::setting_tables().collect();
/// assert_eq!(tables[0], "prediction");
/// assert!(tables.contains(&"judge") && tables.len() == 8);
/// ```
pub fn setting_tables() -> impl Iterator<Item = &'static str> {
    let mut seen: Vec<&'static str> = Vec::new();
    SETTING_KEYS.iter().filter_map(move |k| {
        let t = k.table?;
        (!seen.contains(&t)).then(|| {
            seen.push(t);
            t
        })
    })
}

/// The learners that read some key of `table`.
fn table_read_by(table: &str, kind: LearnerKind) -> bool {
    SETTING_KEYS
        .iter()
        .any(|k| k.table == Some(table) && k.reads(kind))
}

/// The keys of the settings, for `csrl run --help`: the top level's, then each table's,
/// each with the learners that read it where not every learner does.
///
/// ```
/// let help = csql::settings_keys_help();
/// assert!(help.contains("[u_tree]: fringe") && help.contains("(u-tree)"));
/// assert!(help.lines().next().unwrap().starts_with("top level: map"));
/// ```
pub fn settings_keys_help() -> String {
    let tables = std::iter::once(None).chain(setting_tables().map(Some));
    let mut lines = Vec::new();
    for table in tables {
        // The keys read by the same learners together, in the order first declared.
        let mut groups: Vec<(&[LearnerKind], Vec<&str>)> = Vec::new();
        for k in SETTING_KEYS.iter().filter(|k| k.table == table) {
            match groups.iter_mut().find(|(readers, _)| *readers == k.read_by) {
                Some((_, names)) => names.push(k.name),
                None => groups.push((k.read_by, vec![k.name])),
            }
        }
        let groups: Vec<String> = groups
            .into_iter()
            .map(|(readers, names)| {
                let names = names.join(", ");
                if readers == EVERY {
                    names
                } else {
                    let readers: Vec<&str> = readers.iter().map(|k| k.name()).collect();
                    format!("{names} ({})", readers.join(", "))
                }
            })
            .collect();
        let head = table.map_or("top level".to_string(), |t| format!("[{t}]"));
        lines.push(format!("{head}: {}", groups.join("; ")));
    }
    lines.join("\n")
}

/// Table `table` named with its keys that are not at their defaults: `[u_tree] fringe`,
/// or `[u_tree]` when all are.
fn table_named<T: Serialize + Default>(table: &str, value: &T) -> String {
    let keys = match (
        toml::Table::try_from(value),
        toml::Table::try_from(T::default()),
    ) {
        (Ok(given), Ok(default)) => given
            .iter()
            .filter(|(k, v)| default.get(k.as_str()) != Some(*v))
            .map(|(k, _)| k.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        _ => String::new(),
    };
    if keys.is_empty() {
        format!("[{table}]")
    } else {
        format!("[{table}] {keys}")
    }
}

/// Tables are tables (`world = [0.3, 0.1]` would set fields by position), and a key in
/// the wrong place says where it belongs.
fn check_layout(layout: &toml::Table) -> Result<(), SettingsProblem> {
    let is_top = |key: &str| setting_key(None, key).is_some();
    let home_of = |key: &str, not: Option<&str>| {
        SETTING_KEYS
            .iter()
            .find(|k| k.table.is_some() && k.table != not && k.name == key)
            .and_then(|k| k.table)
    };
    for (key, value) in layout {
        if let Some(table) = setting_tables().find(|t| t == key) {
            let Some(inner) = value.as_table() else {
                return Err(SettingsProblem::Layout(format!(
                    "`{key}` must be a table: write [{key}] and its settings by name, one per line"
                )));
            };
            for inner_key in inner.keys() {
                if is_top(inner_key) {
                    return Err(SettingsProblem::Layout(format!(
                        "`{inner_key}` is a setting of the top level, not of [{table}]: write it before any table"
                    )));
                }
                if let Some(home) = home_of(inner_key, Some(table)) {
                    if table == "extensions" && home == "judge" {
                        return Err(SettingsProblem::Layout(format!(
                            "`{inner_key}` moved from [extensions] to a table of its own: write it under [judge]"
                        )));
                    }
                    return Err(SettingsProblem::Layout(format!(
                        "`{inner_key}` is a setting of the [{home}] table, not of [{table}]"
                    )));
                }
            }
            if table == "belief" && inner.contains_key("price_scale") {
                return Err(SettingsProblem::Layout(
                    "`price_scale` is not a setting of [belief]: sensing by belief prices a feature at its cost times [costly] price".to_string(),
                ));
            }
            if table == "extensions"
                && let Some(rate) = inner.get("rate")
                && !rate.is_table()
            {
                return Err(SettingsProblem::Layout(
                    "`rate` in [extensions] must be a table: write [extensions.rate] and its settings by name".to_string(),
                ));
            }
        } else if !is_top(key)
            && let Some(home) = home_of(key, None)
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
        self.take_given(later);
    }

    /// The first key given that learner `kind` does not read ([`SETTING_KEYS`]), as a
    /// message names it: the key and its value at the top level, a table given at all
    /// when the learner reads none of it (even empty, or at its defaults), a key of
    /// `[world]` given (at any value, its default included).
    fn unread_given(&self, kind: LearnerKind) -> Option<String> {
        SETTING_KEYS
            .iter()
            .filter(|k| !k.reads(kind))
            .find_map(|k| self.given(k, kind))
    }

    /// Key `k` as given, named with its value (see [`SettingsDraft::unread_given`]).
    fn given(&self, k: &SettingKey, kind: LearnerKind) -> Option<String> {
        match k.table {
            None => self.top_given(k.name),
            // A key of [world] is given or not, whatever its value (its absent keys
            // are at their defaults): named with its value.
            Some("world") if table_read_by("world", kind) => {
                let value = toml::Table::try_from(self.world.as_ref()?).ok()?;
                let value = value.get(k.name)?;
                Some(format!("[world] {} = {}", k.name, value.shown()))
            }
            Some(table) => self.table_given(table),
        }
    }

    /// Forget every key that learner `kind` does not read (before it is chosen in place
    /// of another, or when settings are written out).
    fn forget_unread(&mut self, kind: LearnerKind) {
        for k in SETTING_KEYS.iter().filter(|k| !k.reads(kind)) {
            match k.table {
                // [world] is read key by key: its other keys stay.
                Some("world") if table_read_by("world", kind) => {
                    let kept = self.world.as_ref().and_then(|w| {
                        let mut keys = toml::Table::try_from(w).ok()?;
                        keys.remove(k.name);
                        keys.try_into::<WorldExtras>().ok()
                    });
                    self.world = kept.filter(|w| !w.is_default());
                }
                Some(table) => self.forget(table),
                None => self.forget(k.name),
            }
        }
    }

    /// The settings of a step-driven agent ([`crate::Stepper`]): [`SettingsDraft::build`],
    /// after refusing, by key, what a run reads and a stepper does not
    /// ([`NOT_READ_BY_A_STEPPER`]): the caller's loop decides the world, the trials, the
    /// moves and when the agent has learned.
    ///
    /// ```
    /// let d = csql::SettingsDraft::from_toml("temperature = 0.2\nseed = 4", "f").unwrap();
    /// assert_eq!(d.build_for_stepper().unwrap().seed, 4);
    /// let d = csql::SettingsDraft::from_toml("max_trials = 50", "f").unwrap();
    /// let err = d.build_for_stepper().unwrap_err().to_string();
    /// assert!(err.starts_with("max_trials = 50 and a step-driven agent"), "{err}");
    /// ```
    pub fn build_for_stepper(&self) -> Result<RunSettings, Error> {
        let unread = SETTING_KEYS.iter().filter(|k| {
            NOT_READ_BY_A_STEPPER
                .iter()
                .any(|&(table, name)| k.table == table && (name == "*" || k.name == name))
        });
        for k in unread {
            if let Some(first) = self.given(k, LearnerKind::CsQl) {
                return Err(Error::Conflict {
                    first,
                    second: "a step-driven agent (csql::Stepper, csrl.CsQlAgent)".to_string(),
                    why: "the agent does not read it: the caller's loop decides the world, the trials and moves, and when the agent has learned",
                });
            }
        }
        self.build()
    }

    /// The run's settings: each learner with only its own keys, everything not given at
    /// the world's default (the paper's value, or a built-in world's own temperature,
    /// detector and trial cap for the learners judged over trials:
    /// [`crate::WorldDefaults`]), and every combination checked once
    /// ([`RunSettings::validate`]). A key that the learner chosen does not read
    /// ([`SETTING_KEYS`]) is refused, naming the key and the learner; so is a table of
    /// another learner given at all, even empty or at its defaults.
    ///
    /// ```
    /// // Taxi's rewards run from -10 to 20: the world's temperature, detector and trial
    /// // cap where none is given; a key given always wins.
    /// let d = csql::SettingsDraft::from_toml("map = \"taxi\"\ntemperature = 5", "f").unwrap();
    /// let s = d.build().unwrap();
    /// assert_eq!((s.temperature.get(), s.max_trials.get()), (5.0, 200_000));
    /// assert_eq!(s.extensions().detector, csql::DetectorKind::Action);
    /// let d = csql::SettingsDraft::from_toml("learner = \"u-tree\"\n[u_tree]\nfringe = 3", "f").unwrap();
    /// let s = d.build().unwrap();
    /// assert!(matches!(s.learner, csql::LearnerSettings::UTree(p) if p.fringe == 3));
    /// let d = csql::SettingsDraft::from_toml("[u_tree]\nfringe = 3", "f").unwrap();
    /// assert!(d.build().unwrap_err().to_string().contains("learner = cs-ql"));
    /// let d = csql::SettingsDraft::from_toml("learner = \"amrl-q\"\ngamma = 0.9\n[costly]\nprice = 1", "f").unwrap();
    /// let err = d.build().unwrap_err().to_string();
    /// assert!(err.starts_with("gamma = 0.9 and learner = amrl-q cannot be used together"), "{err}");
    /// ```
    pub fn build(&self) -> Result<RunSettings, Error> {
        let kind = self.learner.unwrap_or_default();
        // Trials and episodes are counted apart: each count is refused with a pointer
        // to the other where the learner reads the other.
        let count = if kind.on_episodes() {
            self.max_trials.map(|n| {
                (
                    format!("max_trials = {}", n.get()),
                    "a learner played on costed episodes plays a count of episodes, not trials \
                     judged by the oracle: write episodes (csrl run --episodes)",
                )
            })
        } else {
            self.episodes.map(|n| {
                (
                    format!("episodes = {}", n.get()),
                    "this learner is judged over trials until it has learned: its cap is \
                     max_trials (csrl run --max-trials); episodes counts the episodes of amrl-q \
                     and belief",
                )
            })
        };
        if let Some((first, why)) = count {
            return Err(Error::Conflict {
                first,
                second: format!("learner = {kind}"),
                why,
            });
        }
        if let Some(first) = self.unread_given(kind) {
            return Err(Error::Conflict {
                first,
                second: format!("learner = {kind}"),
                why: "the learner does not read it (csrl run --help lists the keys each learner reads)",
            });
        }
        // What the world defaults to where a key is not given: the paper's values, or a
        // built-in world's own (`WorldDefaults`), for the learners judged over trials.
        let paper = RunSettings::tan1991(DEFAULT_MAP, StrategyKind::Resetting, 1);
        let defaults = match &self.map {
            Some(map) if !kind.on_episodes() => WorldDefaults::of_source(map),
            _ => WorldDefaults::paper(),
        };
        let beta = self.beta.unwrap_or(paper.beta);
        let world = self.world.clone().unwrap_or_default();
        let extensions = self
            .extensions
            .unwrap_or_default()
            .extensions_with(defaults.detector_for(beta.get(), &world));
        let judge = self.judge.unwrap_or_default();
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
        // Within CS-QL, two keys are read only with another: given without it (even at
        // their defaults) they would be ignored.
        let strategy = self.strategy.unwrap_or(StrategyKind::Resetting);
        if let Some(n) = self.random_moves
            && strategy != StrategyKind::Random
        {
            return Err(Error::Conflict {
                first: format!("random_moves = {n}"),
                second: format!("strategy = {strategy}"),
                why: "random moves follow a refinement of the random strategy only",
            });
        }
        let level = self.predict_sensing.unwrap_or_default();
        if let Some(p) = &self.prediction
            && level.is_off()
        {
            return Err(Error::Conflict {
                first: table_named("prediction", p),
                second: "predict_sensing = off".to_string(),
                why: "[prediction] tunes predict_sensing = \"learned\", \"motion\" or \"weighed\"",
            });
        }
        let learner = match kind {
            LearnerKind::CsQl => LearnerSettings::CsQl(CsQlSettings {
                strategy: self.strategy.unwrap_or(StrategyKind::Resetting),
                random_moves: self.random_moves.unwrap_or(PAPER_RANDOM_MOVES),
                predict_sensing: self.predict_sensing.unwrap_or_default(),
                prediction: self.prediction.unwrap_or_default(),
                extensions,
            }),
            LearnerKind::UTree => LearnerSettings::UTree(self.u_tree.unwrap_or_default()),
            LearnerKind::FullSensing => LearnerSettings::FullSensing,
            LearnerKind::AmrlQ => LearnerSettings::AmrlQ(self.amrl_q.unwrap_or_default()),
            // Its features are priced at `[costly] price` (which the learner needs:
            // refused without it by `validate`).
            // What `[belief]` leaves to the world is the world's (a lake's shared moves).
            LearnerKind::Belief => LearnerSettings::Belief(
                self.map
                    .as_ref()
                    .map_or_else(WorldDefaults::paper, WorldDefaults::of_source)
                    .belief_for(
                        self.belief.unwrap_or_default(),
                        &world,
                        self.max_moves.unwrap_or(paper.max_moves).get(),
                    ),
            ),
        };
        let settings = RunSettings {
            map: self.map.clone().unwrap_or(paper.map),
            learner,
            beta,
            gamma: self.gamma.unwrap_or(paper.gamma),
            temperature: self.temperature.unwrap_or(defaults.temperature),
            max_moves: self.max_moves.unwrap_or(paper.max_moves),
            tolerance: self.tolerance.unwrap_or(paper.tolerance),
            decrease_threshold: self.decrease_threshold.unwrap_or(paper.decrease_threshold),
            max_trials: if kind.on_episodes() {
                self.episodes
            } else {
                self.max_trials
            }
            .unwrap_or(defaults.max_trials),
            seed: self.seed.unwrap_or(paper.seed),
            world,
            judge,
            max_rows: self.max_rows.unwrap_or(MAX_ROWS),
            costly,
        };
        settings.validate()?;
        Ok(settings)
    }
}

/// Every key of the settings that the learner reads ([`SETTING_KEYS`]), as a report's
/// JSON has them: the learner's own keys, the keys it shares with others, and the
/// settings beyond the paper only where they are not at their defaults. Built again
/// ([`SettingsDraft::build`]), they give the same settings.
///
/// ```
/// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let d = csql::SettingsDraft::from(&s);
/// assert_eq!(d.build().unwrap(), s);
/// assert!(d.extensions.is_none() && d.learner.is_none() && d.judge.is_none());
/// // AMRL-Q reads no key of Q-learning: its settings leave them out.
/// let mut a = s.with_learner(csql::LearnerKind::AmrlQ);
/// a.costly = Some(csql::CostlySettings::new(0.5));
/// let d = csql::SettingsDraft::from(&a);
/// assert!(d.beta.is_none() && d.gamma.is_none() && d.seed == Some(1));
/// assert_eq!(d.build().unwrap(), a);
/// ```
impl From<&RunSettings> for SettingsDraft {
    fn from(s: &RunSettings) -> SettingsDraft {
        let q = s.cs_ql();
        let kind = s.learner.kind();
        let world_detector = WorldDefaults::of_source(&s.map).detector_for(s.beta.get(), &s.world);
        let mut draft = SettingsDraft {
            map: Some(s.map.clone()),
            strategy: q.map(|q| q.strategy),
            beta: Some(s.beta),
            gamma: Some(s.gamma),
            temperature: Some(s.temperature),
            max_moves: Some(s.max_moves),
            random_moves: q
                .filter(|q| q.strategy == StrategyKind::Random)
                .map(|q| q.random_moves),
            tolerance: Some(s.tolerance),
            decrease_threshold: Some(s.decrease_threshold),
            max_trials: (!kind.on_episodes()).then_some(s.max_trials),
            episodes: kind.on_episodes().then_some(s.max_trials),
            seed: Some(s.seed),
            predict_sensing: q.map(|q| q.predict_sensing).filter(|l| !l.is_off()),
            prediction: q.map(|q| q.prediction).filter(|p| !p.is_default()),
            world: Some(s.world.clone()).filter(|w| !w.is_default()),
            extensions: q
                .map(|q| {
                    let mut table = ExtensionsTable::from(q.extensions);
                    // The paper's detector is written out where the world would default
                    // to another, so that the settings build again to the same.
                    if q.extensions.detector != world_detector {
                        table.detector = Some(q.extensions.detector);
                    }
                    table
                })
                .filter(|t| *t != ExtensionsTable::default()),
            judge: Some(s.judge).filter(|j| *j != JudgeSettings::default()),
            learner: Some(kind).filter(|k| !k.is_cs_ql()),
            u_tree: match s.learner {
                LearnerSettings::UTree(p) if !p.is_default() => Some(p),
                _ => None,
            },
            max_rows: Some(s.max_rows).filter(|n| *n != MAX_ROWS),
            amrl_q: match s.learner {
                LearnerSettings::AmrlQ(p) if !p.is_default() => Some(p),
                _ => None,
            },
            costly: s.costly.map(|c| CostlyTable {
                price: Some(c.price),
                rule: Some(c.rule),
            }),
            belief: match s.learner {
                LearnerSettings::Belief(p) if !p.is_default() => Some(p),
                _ => None,
            },
        };
        draft.forget_unread(kind);
        draft
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
        if let Some(kind) = file.learner.filter(|k| *k != self.learner.kind()) {
            draft.forget_unread(kind);
        }
        // Another strategy, chosen over the random one at the paper's random moves,
        // leaves them (other random moves are refused with it, as they mean nothing).
        if file.strategy.is_some()
            && file.random_moves.is_none()
            && draft.random_moves == Some(PAPER_RANDOM_MOVES)
        {
            draft.random_moves = None;
        }
        draft.overlay(file);
        *self = draft.build()?;
        Ok(())
    }
}
