//! Run settings: one struct of validated values, the paper's preset, and a TOML file form.
//!
//! Every field holds only valid values: numbers are newtypes whose constructors and
//! deserialisation share one check (as qlearn's parameters are), so a settings file with
//! `max_trials = 0` is refused when it is read, and a [`RunSettings`] value can always be
//! run. The map is either named (a built-in, a file or a map spec, resolved when the run
//! is set up) or given as a [`mdp::Map`] value.

use std::fmt;
use std::io::Read;
use std::path::Path;

use qlearn::{Discount, LearningRate, MoveCap, Temperature};
use serde::{Deserialize, Serialize};

use crate::error::{Error, SettingsProblem};
use crate::extensions::{Extensions, WorldExtras};
use crate::learner::{LearnerKind, UTreeParams};
use crate::predict::level::{PredictSensing, Prediction};
use crate::strategy::StrategyKind;

/// The map of a run: a name (a built-in, a map file or a map spec such as
/// `random:8x8:0.2:7`, resolved by [`mdp::resolve`]) or a map value. Reports show its
/// name either way.
///
/// ```
/// use csql::MapSource;
/// let named = MapSource::from("tan3x3");
/// assert_eq!(named.name(), "tan3x3");
/// let mine = mdp::Map::from_layout("strip", ".G.").unwrap();
/// assert_eq!(MapSource::from(mine.clone()).resolve().unwrap(), mine);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MapSource {
    /// A built-in name, a file path or a map spec.
    Named(String),
    /// A map given as a value.
    Given(mdp::Map),
}

impl MapSource {
    /// The name reports show: the name given, or the map's own.
    ///
    /// ```
    /// let m = mdp::Map::from_layout("strip", ".G.").unwrap();
    /// assert_eq!(csql::MapSource::Given(m).name(), "strip");
    /// ```
    pub fn name(&self) -> &str {
        match self {
            MapSource::Named(name) => name,
            MapSource::Given(map) => map.name(),
        }
    }

    /// The map itself: loaded or generated for a name, cloned for a value.
    ///
    /// ```
    /// assert_eq!(csql::MapSource::from("tan3x3").resolve().unwrap().states().len(), 8);
    /// assert!(csql::MapSource::from("no-such-map").resolve().is_err());
    /// ```
    pub fn resolve(&self) -> Result<mdp::Map, mdp::MapError> {
        match self {
            MapSource::Named(name) => mdp::resolve(name),
            MapSource::Given(map) => Ok(map.clone()),
        }
    }
}

impl From<&str> for MapSource {
    fn from(name: &str) -> MapSource {
        MapSource::Named(name.to_string())
    }
}

impl From<&String> for MapSource {
    fn from(name: &String) -> MapSource {
        MapSource::Named(name.clone())
    }
}

impl From<String> for MapSource {
    fn from(name: String) -> MapSource {
        MapSource::Named(name)
    }
}

impl From<mdp::Map> for MapSource {
    fn from(map: mdp::Map) -> MapSource {
        MapSource::Given(map)
    }
}

impl fmt::Display for MapSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for MapSource {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for MapSource {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        String::deserialize(deserializer).map(MapSource::Named)
    }
}

/// A finite number at least 0: the convergence tolerance and the decrease threshold.
///
/// ```
/// use csql::NonNegative;
/// assert_eq!(NonNegative::new(1e-6).unwrap().get(), 1e-6);
/// assert!(NonNegative::new(-1.0).is_err());
/// assert!(NonNegative::new(f64::NAN).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct NonNegative(f64);

impl NonNegative {
    /// Zero.
    ///
    /// ```
    /// assert_eq!(csql::NonNegative::ZERO.get(), 0.0);
    /// ```
    pub const ZERO: NonNegative = NonNegative(0.0);

    /// The value, if it is finite and at least 0.
    ///
    /// ```
    /// assert!(csql::NonNegative::new(f64::INFINITY).is_err());
    /// ```
    pub fn new(value: f64) -> Result<NonNegative, Error> {
        if value.is_finite() && value >= 0.0 {
            Ok(NonNegative(value))
        } else {
            Err(Error::InvalidSetting {
                value: value.to_string(),
                expected: "a finite number >= 0",
            })
        }
    }

    /// The number.
    ///
    /// ```
    /// assert_eq!(csql::NonNegative::new(0.5).unwrap().get(), 0.5);
    /// ```
    #[inline]
    pub fn get(self) -> f64 {
        self.0
    }
}

impl TryFrom<f64> for NonNegative {
    type Error = Error;
    fn try_from(value: f64) -> Result<Self, Error> {
        NonNegative::new(value)
    }
}

impl From<NonNegative> for f64 {
    fn from(x: NonNegative) -> f64 {
        x.0
    }
}

/// The number of trials after which an unconverged run stops: at least 1.
///
/// ```
/// use csql::TrialCap;
/// assert_eq!(TrialCap::new(500).unwrap().get(), 500);
/// assert!(TrialCap::new(0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(try_from = "u32", into = "u32")]
pub struct TrialCap(u32);

impl TrialCap {
    /// The cap, if it is at least 1.
    ///
    /// ```
    /// assert!(csql::TrialCap::new(1).is_ok());
    /// ```
    pub fn new(trials: u32) -> Result<TrialCap, Error> {
        if trials >= 1 {
            Ok(TrialCap(trials))
        } else {
            Err(Error::InvalidSetting {
                value: trials.to_string(),
                expected: "a number of trials of at least 1",
            })
        }
    }

    /// The number of trials.
    ///
    /// ```
    /// assert_eq!(csql::TrialCap::new(3).unwrap().get(), 3);
    /// ```
    #[inline]
    pub fn get(self) -> u32 {
        self.0
    }
}

impl TryFrom<u32> for TrialCap {
    type Error = Error;
    fn try_from(value: u32) -> Result<Self, Error> {
        TrialCap::new(value)
    }
}

/// Read from the command line: a whole number of at least 1.
///
/// ```
/// assert_eq!("40".parse::<csql::TrialCap>().unwrap().get(), 40);
/// assert!("0".parse::<csql::TrialCap>().is_err());
/// assert!("many".parse::<csql::TrialCap>().is_err());
/// ```
impl std::str::FromStr for TrialCap {
    type Err = Error;
    fn from_str(s: &str) -> Result<TrialCap, Error> {
        let n = s.trim().parse::<u32>().map_err(|_| Error::InvalidSetting {
            value: s.to_string(),
            expected: "a whole number of trials from 1 to 4294967295",
        })?;
        TrialCap::new(n)
    }
}

impl From<TrialCap> for u32 {
    fn from(x: TrialCap) -> u32 {
        x.0
    }
}

/// Everything a CS-QL run depends on. A run is a pure function of these settings.
///
/// Build one with [`RunSettings::tan1991`] (the paper's values) and change fields, or
/// read overrides from a TOML file with [`RunSettings::apply_toml`]. Every field holds a
/// valid value, so any `RunSettings` can be run.
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 7);
/// assert_eq!((s.beta.get(), s.gamma.get(), s.temperature.get()), (1.0, 0.9, 0.4));
/// assert_eq!((s.max_moves.get(), s.random_moves), (100, 20));
/// // A map of one's own is a value like any other.
/// let mine = mdp::Map::from_layout("mine", "..G\n.#.\n...").unwrap();
/// let report = csql::run(&RunSettings::tan1991(mine, StrategyKind::Lazy, 1)).unwrap();
/// assert!(report.converged && report.map == "mine");
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSettings {
    /// The map: a name (built-in, file or spec) or a map value.
    pub map: MapSource,
    /// How decreases are handled.
    pub strategy: StrategyKind,
    /// Learning rate beta of equation 2.
    pub beta: LearningRate,
    /// Discount gamma of equation 2.
    pub gamma: Discount,
    /// Boltzmann temperature T.
    pub temperature: Temperature,
    /// Moves per trial before it is cut (the paper: 100).
    pub max_moves: MoveCap,
    /// Random moves after each refinement, for the random strategy (the paper: 20).
    pub random_moves: u32,
    /// Largest `|V(desc(s)) - V*(s)|` that counts as converged.
    pub tolerance: NonNegative,
    /// A decrease is a drop of V by more than this (0: any drop). The paper's remark on
    /// noisy utilities suggests a threshold; with the paper's settings none is needed.
    pub decrease_threshold: NonNegative,
    /// Trials after which an unconverged run stops and says so.
    pub max_trials: TrialCap,
    /// The seed of the run's one random generator.
    pub seed: u64,
    /// Whether, and with what knowledge, the agent predicts instead of sensing (`off`,
    /// the paper's procedure, by default; see [`crate::Predicting`]). Absent from the
    /// JSON when `off`.
    #[serde(default, skip_serializing_if = "PredictSensing::is_off")]
    pub predict_sensing: PredictSensing,
    /// The confidence rule, re-check rates and navigation trials of prediction (the
    /// TOML table `[prediction]`). Absent from the JSON when every value is the default.
    #[serde(default, skip_serializing_if = "Prediction::is_default")]
    pub prediction: Prediction,
    /// The world's departures from the paper (TOML table `[world]`; omitted when off).
    #[serde(default, skip_serializing_if = "WorldExtras::is_default")]
    pub world: WorldExtras,
    /// CS-QL's remedies beyond the paper (TOML table `[extensions]`; omitted when off).
    #[serde(default, skip_serializing_if = "Extensions::is_default")]
    pub extensions: Extensions,
    /// The learner: CS-QL (the default, omitted from the JSON) or a baseline
    /// ([`LearnerKind`]).
    #[serde(default, skip_serializing_if = "LearnerKind::is_cs_ql")]
    pub learner: LearnerKind,
    /// The U-Tree learner's parameters (TOML table `[u_tree]`; omitted when default).
    #[serde(default, skip_serializing_if = "UTreeParams::is_default")]
    pub u_tree: UTreeParams,
    /// The most rows the representation may reach before the run ends, saying so (at
    /// least 1, at most and by default [`MAX_ROWS`]; omitted when default).
    #[serde(
        default = "default_max_rows",
        skip_serializing_if = "is_default_max_rows"
    )]
    pub max_rows: usize,
}

/// The most bytes a settings file may have (64 KiB; the longest useful one is under 1 KiB).
///
/// ```
/// assert_eq!(csql::MAX_SETTINGS_BYTES, 65536);
/// ```
pub const MAX_SETTINGS_BYTES: u64 = 64 << 10;

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

/// The most rows (descriptions, leaves, views or remembered histories) a run's
/// representation may reach, and the default of the setting `max_rows`: a run whose
/// descriptions keep multiplying (plain CS-QL under sensor noise makes a new one for
/// every misreading) ends at the trial where it passes `max_rows`, and its report says
/// so (`stopped`), so that memory stays bounded.
///
/// ```
/// assert_eq!(csql::MAX_ROWS, 100_000);
/// ```
pub const MAX_ROWS: usize = 100_000;

fn default_max_rows() -> usize {
    MAX_ROWS
}

fn is_default_max_rows(n: &usize) -> bool {
    *n == MAX_ROWS
}

/// The TOML file form: every key optional, each one overriding the preset.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SettingsFile {
    map: Option<MapSource>,
    strategy: Option<StrategyKind>,
    beta: Option<LearningRate>,
    gamma: Option<Discount>,
    temperature: Option<Temperature>,
    max_moves: Option<MoveCap>,
    random_moves: Option<u32>,
    tolerance: Option<NonNegative>,
    decrease_threshold: Option<NonNegative>,
    max_trials: Option<TrialCap>,
    seed: Option<u64>,
    predict_sensing: Option<PredictSensing>,
    prediction: Option<Prediction>,
    world: Option<WorldExtras>,
    extensions: Option<Extensions>,
    learner: Option<LearnerKind>,
    u_tree: Option<UTreeParams>,
    max_rows: Option<usize>,
}

impl RunSettings {
    /// The paper's settings (beta 1, gamma 0.9, T 0.4, 100 moves per trial, 20 random
    /// moves) with a tolerance of 1e-6, no decrease threshold and a cap of 20000 trials.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Resetting, 1);
    /// assert_eq!(s.max_trials.get(), 20_000);
    /// ```
    pub fn tan1991(map: impl Into<MapSource>, strategy: StrategyKind, seed: u64) -> RunSettings {
        let q = qlearn::Params::tan1991();
        RunSettings {
            map: map.into(),
            strategy,
            beta: q.learning_rate,
            gamma: q.discount,
            temperature: q.temperature,
            max_moves: q.max_moves,
            random_moves: 20,
            tolerance: NonNegative(1e-6),
            decrease_threshold: NonNegative::ZERO,
            max_trials: TrialCap(20_000),
            seed,
            predict_sensing: PredictSensing::Off,
            prediction: Prediction::default(),
            world: WorldExtras::default(),
            extensions: Extensions::default(),
            learner: LearnerKind::CsQl,
            u_tree: UTreeParams::default(),
            max_rows: MAX_ROWS,
        }
    }

    /// Override fields from TOML text (`source` names it in errors); unknown keys and
    /// invalid values are refused.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.apply_toml("temperature = 0.2\nstrategy = \"eager\"", "my.toml").unwrap();
    /// assert_eq!(s.temperature.get(), 0.2);
    /// assert_eq!(s.strategy, csql::StrategyKind::Eager);
    /// assert!(s.apply_toml("temprature = 0.2", "my.toml").is_err());
    /// assert!(s.apply_toml("gamma = 1.0", "my.toml").is_err());
    /// ```
    pub fn apply_toml(&mut self, text: &str, source: &str) -> Result<(), Error> {
        self.merge_toml(text, source)?;
        self.validate()
    }

    /// Override fields from TOML text as [`RunSettings::apply_toml`] does, without the
    /// checks that span several settings ([`RunSettings::validate`]): for a caller that
    /// overrides more before it validates, such as a command line whose `--learner`
    /// makes the file's `[u_tree]` table mean something.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.merge_toml("[u_tree]\nfringe = 3", "my.toml").unwrap();
    /// assert!(s.validate().is_err()); // [u_tree] with cs-ql
    /// s.learner = csql::LearnerKind::UTree;
    /// assert!(s.validate().is_ok());
    /// assert!(s.merge_toml("temprature = 0.2", "my.toml").is_err());
    /// ```
    pub fn merge_toml(&mut self, text: &str, source: &str) -> Result<(), Error> {
        let fail = |problem: SettingsProblem| Error::Settings {
            source_name: source.to_string(),
            problem,
        };
        // The layout first (tables are tables, keys in their tables), with hints the
        // typed reading below cannot give; then the values, with line and column.
        let layout: toml::Table =
            toml::from_str(text).map_err(|e| fail(SettingsProblem::Parse(e)))?;
        check_layout(&layout).map_err(fail)?;
        let f: SettingsFile = toml::from_str(text).map_err(|e| fail(SettingsProblem::Parse(e)))?;
        let strategy_given = f.strategy.is_some();
        macro_rules! take {
            ($($field:ident),*) => { $( if let Some(v) = f.$field { self.$field = v; } )* };
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
            max_rows
        );
        if strategy_given && !self.learner.is_cs_ql() {
            return Err(Error::InvalidSetting {
                value: format!(
                    "strategy = {} with learner = {}",
                    self.strategy, self.learner
                ),
                expected: "a strategy only with learner = \"cs-ql\" (the baselines never refine by a strategy)",
            });
        }
        Ok(())
    }

    /// Override fields from a TOML file. Only a regular file of at most
    /// [`MAX_SETTINGS_BYTES`] is read: a directory, a device or a pipe is refused before it
    /// is opened, and reading stops at the limit whatever the file's metadata says.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(s.apply_file(std::path::Path::new("/no/such.toml")).is_err());
    /// ```
    pub fn apply_file(&mut self, path: &Path) -> Result<(), Error> {
        self.merge_file(path)?;
        self.validate()
    }

    /// Override fields from a TOML file as [`RunSettings::apply_file`] does, without the
    /// checks that span several settings (see [`RunSettings::merge_toml`]).
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(s.merge_file(std::path::Path::new("/no/such.toml")).is_err());
    /// ```
    pub fn merge_file(&mut self, path: &Path) -> Result<(), Error> {
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
        self.merge_toml(&text, &source)
    }

    /// Whether the run leaves the paper's setting: a world with slip, slide, noise or a
    /// sensing range, or an extension on (other than the `action` detector, which works
    /// in the paper's world). Such a run ends by the policy quality
    /// (`docs/specification.md`, section 6); the paper's runs, whatever their learner,
    /// keep the paper's convergence ([`crate::Judging`]).
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(!s.beyond_paper());
    /// s.learner = csql::LearnerKind::FullSensing;
    /// assert!(!s.beyond_paper());
    /// s.world.slip = mdp::Slip::new(0.1).unwrap();
    /// assert!(s.beyond_paper());
    /// ```
    pub fn beyond_paper(&self) -> bool {
        // The action detector only sees more of what the paper's rule sees, in the
        // paper's deterministic world: the oracle still judges.
        let mut extensions = self.extensions;
        if extensions.detector == crate::DetectorKind::Action {
            extensions.detector = crate::DetectorKind::default();
        }
        // The quality's schedule is how a run judged by quality is judged, not a reason
        // to judge it so.
        let defaults = Extensions::default();
        extensions.quality_every = defaults.quality_every;
        extensions.quality_patience = defaults.quality_patience;
        self.world.departs_from_the_paper() || !extensions.is_default()
    }

    /// Check the settings beyond the paper that have no type of their own (every other
    /// field holds only valid values by its type).
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(s.validate().is_ok());
    /// s.world.sensing_radius = Some(0);
    /// assert!(s.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        if self.world.sensing_radius == Some(0) {
            return Err(Error::InvalidSetting {
                value: "world.sensing_radius = 0".to_string(),
                expected: "a sensing radius of at least 1",
            });
        }
        self.prediction.validate()?;
        self.extensions.validate()?;
        self.u_tree.validate()?;
        let refuse =
            |value: String, expected: &'static str| Err(Error::InvalidSetting { value, expected });
        if !self.learner.is_cs_ql() && !self.predict_sensing.is_off() {
            return refuse(
                format!(
                    "predict_sensing = {} with learner = {}",
                    self.predict_sensing, self.learner
                ),
                "predict_sensing = off with a learner other than cs-ql",
            );
        }
        if !(1..=MAX_ROWS).contains(&self.max_rows) {
            return refuse(
                format!("max_rows = {}", self.max_rows),
                "max_rows from 1 to 100000 (csql::MAX_ROWS)",
            );
        }
        if self.extensions.rate != crate::RateParams::default()
            && self.extensions.detector != crate::DetectorKind::Statistical
        {
            return refuse(
                format!(
                    "extensions.rate with extensions.detector = \"{}\"",
                    match self.extensions.detector {
                        crate::DetectorKind::Decrease => "decrease",
                        crate::DetectorKind::Statistical => "statistical",
                        crate::DetectorKind::Action => "action",
                    }
                ),
                "extensions.rate only with detector = \"statistical\" (the rate test is its parameters)",
            );
        }
        if !self.u_tree.is_default() && self.learner != LearnerKind::UTree {
            return refuse(
                format!("[u_tree] settings with learner = {}", self.learner),
                "[u_tree] only with learner = \"u-tree\"",
            );
        }
        if !self.prediction.is_default() && self.predict_sensing.is_off() {
            return refuse(
                "[prediction] settings with predict_sensing = off".to_string(),
                "[prediction] only with predict_sensing = \"learned\" or \"motion\"",
            );
        }
        if self.predict_sensing == PredictSensing::Motion
            && !(self.world.slip.is_zero()
                && self.world.slide.is_zero()
                && self.world.sensor_noise.is_zero())
        {
            return refuse(
                "predict_sensing = \"motion\" with [world] slip, slide or sensor_noise".to_string(),
                "dead reckoning (motion) only with deterministic moves and exact sensors: it places cells by the moves it believes it made",
            );
        }
        if self.extensions.detector == crate::DetectorKind::Action && self.beta.get() != 1.0 {
            return refuse(
                format!(
                    "extensions.detector = \"action\" with beta = {}",
                    self.beta.get()
                ),
                "beta = 1 with detector = \"action\" (below 1, Q approaches a target from above and falls without proving anything)",
            );
        }
        let e = &self.extensions;
        let cs_ql_only = e.detector != crate::DetectorKind::default()
            || e.matching != crate::Matching::Exact
            || e.confirm_new != 1
            || e.reads != 1
            || e.memory > 0;
        if !self.learner.is_cs_ql() && cs_ql_only {
            return refuse(
                format!("an extension of CS-QL with learner = {}", self.learner),
                "detector, matching, confirm_new, reads and memory at their defaults with a learner other than cs-ql",
            );
        }
        if self.extensions.memory > 0 && !(self.learner.is_cs_ql() && self.predict_sensing.is_off())
        {
            return refuse(
                format!(
                    "extensions.memory = {} with learner = {} and predict_sensing = {}",
                    self.extensions.memory, self.learner, self.predict_sensing
                ),
                "memory with learner = cs-ql and predict_sensing = off only",
            );
        }
        Ok(())
    }
}
