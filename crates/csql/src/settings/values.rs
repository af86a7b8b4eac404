//! Run settings: one struct of validated values, with the learner's own settings in the
//! learner ([`crate::LearnerSettings`]), and the paper's preset. The settings file's form, and
//! the one conversion from it, are [`crate::SettingsDraft`].
//!
//! Every field holds only valid values: numbers are newtypes whose constructors and
//! deserialisation share one check (as qlearn's parameters are), so a settings file with
//! `max_trials = 0` is refused when it is read. The map is either named (a built-in, a
//! file or a map spec, resolved when the run is set up) or given as a [`mdp::Map`] value.

use std::fmt;

use qlearn::{Discount, LearningRate, MoveCap, Temperature};
use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::perception::sense_less::level::{PredictSensing, PredictionParams};
use crate::settings::extensions::{Extensions, WorldExtras};
use crate::settings::learner::{
    CsQlSettings, LearnerKind, LearnerSettings, PAPER_RANDOM_MOVES, StrategyKind,
};

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

/// Everything a run depends on. A run is a pure function of these settings.
///
/// Build one with [`RunSettings::tan1991`] (the paper's values) and change fields, read
/// overrides from a TOML file with [`RunSettings::apply_toml`], or gather a file and
/// flags in a [`crate::SettingsDraft`] and build it. The learner holds the settings that
/// are only its own ([`LearnerSettings`]); how the run is judged is [`JudgeSettings`]. Every
/// field holds a valid value by its type, and [`RunSettings::validate`] checks what spans
/// several of them; a run checks them before it starts.
///
/// Serialised (a report's `settings`), it is the settings file's flat layout
/// ([`crate::SettingsDraft`]), with the defaults beyond the paper left out.
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 7);
/// assert_eq!((s.beta.get(), s.gamma.get(), s.temperature.get()), (1.0, 0.9, 0.4));
/// assert_eq!(s.max_moves.get(), 100);
/// assert_eq!(s.cs_ql().unwrap().random_moves, 20);
/// // A map of one's own is a value like any other.
/// let mine = mdp::Map::from_layout("mine", "..G\n.#.\n...").unwrap();
/// let report = csql::run(&RunSettings::tan1991(mine, StrategyKind::Lazy, 1)).unwrap();
/// assert!(report.converged && report.map == "mine");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RunSettings {
    /// The map: a name (built-in, file or spec) or a map value.
    pub map: MapSource,
    /// The learner, with its own settings: CS-QL (the paper's method) or a baseline.
    pub learner: LearnerSettings,
    /// Learning rate beta of equation 2.
    pub beta: LearningRate,
    /// Discount gamma of equation 2.
    pub gamma: Discount,
    /// Boltzmann temperature T.
    pub temperature: Temperature,
    /// Moves per trial before it is cut (the paper: 100).
    pub max_moves: MoveCap,
    /// Largest `|V(desc(s)) - V*(s)|` that counts as converged.
    pub tolerance: NonNegative,
    /// A decrease is a drop of V by more than this (0: any drop). The paper's remark on
    /// noisy utilities suggests a threshold; with the paper's settings none is needed.
    pub decrease_threshold: NonNegative,
    /// Trials after which an unconverged run stops and says so.
    pub max_trials: TrialCap,
    /// The seed of the run's one random generator.
    pub seed: u64,
    /// The world's departures from the paper (TOML table `[world]`).
    pub world: WorldExtras,
    /// How the run is judged (the TOML table `[judge]`).
    pub judge: JudgeSettings,
    /// The most rows the representation may reach before the run ends, saying so (at
    /// least 1, at most and by default [`MAX_ROWS`]).
    pub max_rows: usize,
    /// Sensing priced in reward units (the TOML table `[costly]`): when set, a report
    /// also scores every trial by its costed return (specification 6.10 and 6.12).
    /// AMRL-Q needs it; U-Tree and CS-QL with prediction or memory refuse it.
    pub costly: Option<CostlySettings>,
}

/// Sensing priced in reward units: the TOML table `[costly]` (`price`, and `rule`,
/// `with-move` by default).
///
/// ```
/// let c = csql::CostlySettings::new(0.025);
/// assert_eq!((c.price, c.rule), (0.025, mdp::SensingRule::WithMove));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostlySettings {
    /// Reward units per unit of sensing cost: a feature of cost `c` is priced `c *
    /// price` (the world's whole state, for AMRL-Q, the sum over its features).
    pub price: f64,
    /// When sensing is decided: with the move (the published rule) or after its outcome.
    pub rule: mdp::SensingRule,
}

impl CostlySettings {
    /// `price` reward units per unit of cost, sensing decided with the move.
    ///
    /// ```
    /// assert_eq!(csql::CostlySettings::new(1.0).price, 1.0);
    /// ```
    pub fn new(price: f64) -> CostlySettings {
        CostlySettings {
            price,
            rule: mdp::SensingRule::WithMove,
        }
    }
}

/// How a run is judged: one explicit choice, `judge_by_quality`, and the schedule of the
/// policy quality (the TOML table `[judge]`: `judge_by_quality`, `quality_every` and
/// `quality_patience`, each at its default when absent and then left out of a report's
/// JSON; specification §6.3). The learners played on costed episodes (`amrl-q`,
/// `belief`) are not judged and refuse the table.
///
/// By default a run in a deterministic world in the paper's setting is judged by the
/// oracle's convergence, and any other by the quality; `judge_by_quality = true` judges
/// every run by the quality ([`crate::Judging`]). The quality is measured in every run,
/// every `quality_every` trials.
///
/// ```
/// let j = csql::JudgeSettings::default();
/// assert_eq!((j.judge_by_quality, j.quality_every, j.quality_patience), (false, 10, 20));
/// let s = csql::SettingsDraft::from_toml("[judge]\nquality_every = 5", "f").unwrap();
/// assert_eq!(s.build().unwrap().judge.quality_every, 5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct JudgeSettings {
    /// Judge the run by the policy quality even in the paper's world (as every run beyond
    /// it is judged), so that runs in and beyond it are measured alike. Off by default:
    /// the paper's runs are judged by the oracle's convergence.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub judge_by_quality: bool,
    /// Trials between two evaluations of the policy quality (at least 1).
    #[serde(skip_serializing_if = "JudgeSettings::is_default_every")]
    pub quality_every: u32,
    /// Where the quality judges: the run ends once the quality has stayed at or above
    /// 0.95 for this many consecutive evaluations (at least 1; refused where the oracle
    /// judges).
    #[serde(skip_serializing_if = "JudgeSettings::is_default_patience")]
    pub quality_patience: u32,
}

impl JudgeSettings {
    fn is_default_every(n: &u32) -> bool {
        *n == JudgeSettings::default().quality_every
    }

    fn is_default_patience(n: &u32) -> bool {
        *n == JudgeSettings::default().quality_patience
    }
}

impl Default for JudgeSettings {
    fn default() -> JudgeSettings {
        JudgeSettings {
            judge_by_quality: false,
            quality_every: 10,
            quality_patience: 20,
        }
    }
}

/// The most bytes a settings file may have (64 KiB; the longest useful one is under 1 KiB).
///
/// ```
/// assert_eq!(csql::MAX_SETTINGS_BYTES, 65536);
/// ```
pub const MAX_SETTINGS_BYTES: u64 = 64 << 10;

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

/// The largest size the costed returns of a run may add up to, in reward units:
/// `[costly] price` times the world's summed feature costs, plus its largest reward in
/// size, times `max_moves` and `max_trials`, must not pass it, so that every sum of
/// costed returns a report prints is finite and true.
///
/// ```
/// let s = csql::SettingsDraft::from_toml("map = \"frozenlake4x4\"\nlearner = \"amrl-q\"\n[costly]\nprice = 1e308", "f").unwrap().build().unwrap();
/// let err = csql::Resolved::new(&s).unwrap_err().to_string();
/// assert!(err.contains("costly.price = 1e308"), "{err}");
/// assert_eq!(csql::MAX_COSTED_TOTAL, 1e300);
/// ```
pub const MAX_COSTED_TOTAL: f64 = 1e300;

impl RunSettings {
    /// The paper's settings (beta 1, gamma 0.9, T 0.4, 100 moves per trial, 20 random
    /// moves) for CS-QL with `strategy`, with a tolerance of 1e-6, no decrease threshold
    /// and a cap of 20000 trials.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Resetting, 1);
    /// assert_eq!(s.max_trials.get(), 20_000);
    /// ```
    pub fn tan1991(map: impl Into<MapSource>, strategy: StrategyKind, seed: u64) -> RunSettings {
        let q = qlearn::Params::tan1991();
        RunSettings {
            map: map.into(),
            learner: LearnerSettings::cs_ql(strategy),
            beta: q.learning_rate,
            gamma: q.discount,
            temperature: q.temperature,
            max_moves: q.max_moves,
            tolerance: NonNegative(1e-6),
            decrease_threshold: NonNegative::ZERO,
            max_trials: TrialCap(20_000),
            seed,
            world: WorldExtras::default(),
            judge: JudgeSettings::default(),
            max_rows: MAX_ROWS,
            costly: None,
        }
    }

    /// The same settings with another learner (at its defaults).
    ///
    /// ```
    /// use csql::{LearnerKind, RunSettings, StrategyKind};
    /// let s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1).with_learner(LearnerKind::UTree);
    /// assert_eq!(s.learner.kind(), LearnerKind::UTree);
    /// ```
    pub fn with_learner(mut self, kind: LearnerKind) -> RunSettings {
        self.learner = LearnerSettings::from(kind);
        self
    }

    /// CS-QL's settings, if CS-QL is the learner.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(s.cs_ql().unwrap().strategy, csql::StrategyKind::Lazy);
    /// ```
    pub fn cs_ql(&self) -> Option<&CsQlSettings> {
        match &self.learner {
            LearnerSettings::CsQl(q) => Some(q),
            _ => None,
        }
    }

    /// CS-QL's settings to change, if CS-QL is the learner.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.cs_ql_mut().unwrap().extensions.reads = 3;
    /// assert!(s.validate().is_ok());
    /// ```
    pub fn cs_ql_mut(&mut self) -> Option<&mut CsQlSettings> {
        match &mut self.learner {
            LearnerSettings::CsQl(q) => Some(q),
            _ => None,
        }
    }

    /// CS-QL's extensions, or none (all off) for a baseline.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(s.extensions(), csql::Extensions::default());
    /// ```
    pub fn extensions(&self) -> Extensions {
        self.cs_ql().map(|q| q.extensions).unwrap_or_default()
    }

    /// Whether, and how, CS-QL predicts instead of sensing (`off` for a baseline).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(s.predict_sensing().is_off());
    /// ```
    pub fn predict_sensing(&self) -> PredictSensing {
        self.cs_ql().map(|q| q.predict_sensing).unwrap_or_default()
    }

    /// Whether the run leaves the paper's setting: a world with slip, slide, noise or a
    /// sensing range, or an extension of CS-QL on (other than the `action` detector,
    /// which works in the paper's world). Such a run ends by the policy quality
    /// (`docs/specification.md`, section 6); the paper's runs, whatever their learner,
    /// keep the paper's convergence ([`crate::Judging`]).
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(!s.beyond_paper());
    /// s = s.with_learner(csql::LearnerKind::FullSensing);
    /// assert!(!s.beyond_paper());
    /// s.world.slip = Some(mdp::Slip::new(0.1).unwrap());
    /// assert!(s.beyond_paper());
    /// ```
    pub fn beyond_paper(&self) -> bool {
        // The action detector only sees more of what the paper's rule sees, in the
        // paper's deterministic world: the oracle still judges.
        let mut extensions = self.extensions();
        if extensions.detector == crate::DetectorKind::Action {
            extensions.detector = crate::DetectorKind::default();
        }
        self.world.departs_from_the_paper() || extensions != Extensions::default()
    }

    /// Whether a run of these settings is judged by the policy quality: where it leaves
    /// the paper's setting ([`RunSettings::beyond_paper`]), where the world is not
    /// `deterministic`, or where `judge_by_quality` says so; by the oracle otherwise
    /// ([`crate::Judging::of`]).
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(!s.judged_by_quality(true) && s.judged_by_quality(false));
    /// s.judge.judge_by_quality = true;
    /// assert!(s.judged_by_quality(true));
    /// ```
    pub fn judged_by_quality(&self, deterministic: bool) -> bool {
        self.judge.judge_by_quality || self.beyond_paper() || !deterministic
    }

    /// Check what spans several settings, or has no type of its own (every other field
    /// holds only valid values by its type). The message names both settings of a
    /// combination that means nothing.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(s.validate().is_ok());
    /// s.world.sensing_radius = Some(0);
    /// assert!(s.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let refuse =
            |value: String, expected: &'static str| Err(Error::InvalidSetting { value, expected });
        if self.world.sensing_radius == Some(0) {
            return refuse(
                "world.sensing_radius = 0".to_string(),
                "a sensing radius of at least 1",
            );
        }
        if self.judge.quality_every == 0 {
            return refuse("judge.quality_every = 0".into(), "at least 1");
        }
        if self.judge.quality_patience == 0 {
            return refuse("judge.quality_patience = 0".into(), "at least 1");
        }
        if !(1..=MAX_ROWS).contains(&self.max_rows) {
            return refuse(
                format!("max_rows = {}", self.max_rows),
                "max_rows from 1 to 100000 (csql::MAX_ROWS)",
            );
        }
        self.validate_costly()?;
        if self.learner.kind().on_episodes()
            && self.max_trials.get() > crate::settings::costed::MAX_EPISODES
        {
            return refuse(
                format!("episodes = {}", self.max_trials.get()),
                "at most 1000000 episodes (csql::MAX_EPISODES) for a learner on costed episodes: every episode is kept in the report",
            );
        }
        match &self.learner {
            LearnerSettings::CsQl(q) => self.validate_cs_ql(q),
            LearnerSettings::UTree(p) => p.validate(),
            LearnerSettings::FullSensing => Ok(()),
            LearnerSettings::AmrlQ(p) => p.validate(),
            LearnerSettings::Belief(p) => p.validate(),
        }
    }

    /// `[costly]`: a finite price of at least 0, for the learners that are scored on it.
    fn validate_costly(&self) -> Result<(), Error> {
        let Some(c) = self.costly else {
            let kind = self.learner.kind();
            if kind.on_episodes() {
                return Err(Error::Conflict {
                    first: format!("learner = {kind}"),
                    second: "no [costly] price".to_string(),
                    why: "the learner weighs measuring against reward: give [costly] price (reward units per unit of sensing cost; csrl run --price)",
                });
            }
            return Ok(());
        };
        if !(c.price.is_finite() && c.price >= 0.0) {
            return Err(Error::InvalidSetting {
                value: format!("costly.price = {}", c.price),
                expected: "a finite price of at least 0 reward units per unit of sensing cost",
            });
        }
        let conflict = |second: String| {
            Err(Error::Conflict {
                first: "[costly] price".to_string(),
                second,
                why: "costed episodes are scored for cs-ql (sensing every state it reaches, or by its belief), full-sensing, amrl-q and belief",
            })
        };
        match &self.learner {
            LearnerSettings::UTree(_) => conflict("learner = u-tree".to_string()),
            LearnerSettings::CsQl(q)
                if !(q.predict_sensing.is_off()
                    || q.predict_sensing == PredictSensing::Weighed) =>
            {
                conflict(format!("predict_sensing = {}", q.predict_sensing))
            }
            LearnerSettings::CsQl(q) if q.extensions.memory > 0 => {
                conflict(format!("[extensions] memory = {}", q.extensions.memory))
            }
            _ => Ok(()),
        }
    }

    fn validate_cs_ql(&self, q: &CsQlSettings) -> Result<(), Error> {
        let conflict = |first: String, second: String, why: &'static str| {
            Err(Error::Conflict { first, second, why })
        };
        q.prediction.validate()?;
        q.extensions.validate()?;
        let e = &q.extensions;
        if q.random_moves != PAPER_RANDOM_MOVES && q.strategy != StrategyKind::Random {
            return conflict(
                format!("random_moves = {}", q.random_moves),
                format!("strategy = {}", q.strategy),
                "random moves follow a refinement of the random strategy only",
            );
        }
        if e.rate != crate::RateParams::default() && e.detector != crate::DetectorKind::Statistical
        {
            return conflict(
                "extensions.rate".to_string(),
                format!("extensions.detector = {}", e.detector.name()),
                "the rate test is the statistical detector's parameters: give them with detector = \"statistical\"",
            );
        }
        if q.prediction != PredictionParams::default() && q.predict_sensing.is_off() {
            return conflict(
                "[prediction] settings".to_string(),
                "predict_sensing = off".to_string(),
                "[prediction] tunes predict_sensing = \"learned\", \"motion\" or \"weighed\"",
            );
        }
        if q.predict_sensing == PredictSensing::Weighed && self.costly.is_none() {
            return conflict(
                "predict_sensing = \"weighed\"".to_string(),
                "no [costly] price".to_string(),
                "the weighed level weighs the loss of acting on its belief against the price of measuring, in reward units: give [costly] price (csrl run --price)",
            );
        }
        if q.predict_sensing == PredictSensing::Motion
            && !(self.world.slip().is_zero()
                && self.world.slide().is_zero()
                && self.world.sensor_noise().is_zero())
        {
            return conflict(
                "predict_sensing = \"motion\"".to_string(),
                "[world] slip, slide or sensor_noise".to_string(),
                "dead reckoning (motion) needs deterministic moves and exact sensors: it places cells by the moves it believes it made",
            );
        }
        if e.detector == crate::DetectorKind::Action && self.beta.get() != 1.0 {
            return conflict(
                "extensions.detector = \"action\"".to_string(),
                format!("beta = {}", self.beta.get()),
                "the action detector needs beta = 1 (below 1, Q approaches a target from above and falls without proving anything)",
            );
        }
        if e.memory > 0 && !q.predict_sensing.is_off() {
            return conflict(
                format!("extensions.memory = {}", e.memory),
                format!("predict_sensing = {}", q.predict_sensing),
                "memory refines descriptions that CLASSIFY senses; give it with predict_sensing = off",
            );
        }
        let moves = q.prediction.memory_moves;
        if moves != PredictionParams::default().memory_moves
            && q.predict_sensing != PredictSensing::Motion
        {
            return conflict(
                format!("prediction.memory_moves = {moves}"),
                format!("predict_sensing = {}", q.predict_sensing),
                "memory_moves is how long the motion level remembers a sensed cell; give it with predict_sensing = \"motion\"",
            );
        }
        Ok(())
    }
}
