//! Run settings: one validated struct, the paper's preset, and a TOML file form.

use std::io::Read;
use std::path::Path;

use qlearn::{Discount, LearningRate, MoveCap, Temperature};
use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::extensions::{Extensions, WorldExtras};
use crate::strategy::StrategyKind;

/// Everything a CS-QL run depends on. A run is a pure function of these settings.
///
/// Build one with [`RunSettings::tan1991`] (the paper's values) and change fields, or
/// read overrides from a TOML file with [`RunSettings::apply_toml`].
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 7);
/// assert_eq!((s.beta.get(), s.gamma.get(), s.temperature.get()), (1.0, 0.9, 0.4));
/// assert_eq!((s.max_moves.get(), s.random_moves), (100, 20));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSettings {
    /// A built-in map name or a map file path.
    pub map: String,
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
    pub tolerance: f64,
    /// A decrease is a drop of V by more than this (0: any drop). The paper's remark on
    /// noisy utilities suggests a threshold; with the paper's settings none is needed.
    pub decrease_threshold: f64,
    /// Trials after which an unconverged run stops and says so.
    pub max_trials: u32,
    /// The seed of the run's one random generator.
    pub seed: u64,
    /// The world's departures from the paper (TOML table `[world]`; omitted when off).
    #[serde(default, skip_serializing_if = "WorldExtras::is_default")]
    pub world: WorldExtras,
    /// CS-QL's remedies beyond the paper (TOML table `[extensions]`; omitted when off).
    #[serde(default, skip_serializing_if = "Extensions::is_default")]
    pub extensions: Extensions,
}

/// The most bytes a settings file may have (64 KiB; the longest useful one is under 1 KiB).
///
/// ```
/// assert_eq!(csql::MAX_SETTINGS_BYTES, 65536);
/// ```
pub const MAX_SETTINGS_BYTES: u64 = 64 << 10;

/// The TOML file form: every key optional, each one overriding the preset.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SettingsFile {
    map: Option<String>,
    strategy: Option<StrategyKind>,
    beta: Option<LearningRate>,
    gamma: Option<Discount>,
    temperature: Option<Temperature>,
    max_moves: Option<MoveCap>,
    random_moves: Option<u32>,
    tolerance: Option<f64>,
    decrease_threshold: Option<f64>,
    max_trials: Option<u32>,
    seed: Option<u64>,
    world: Option<WorldExtras>,
    extensions: Option<Extensions>,
}

impl RunSettings {
    /// The paper's settings (beta 1, gamma 0.9, T 0.4, 100 moves per trial, 20 random
    /// moves) with a tolerance of 1e-6, no decrease threshold and a cap of 20000 trials.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Resetting, 1);
    /// assert_eq!(s.max_trials, 20_000);
    /// ```
    pub fn tan1991(map: &str, strategy: StrategyKind, seed: u64) -> RunSettings {
        let q = qlearn::Params::tan1991();
        RunSettings {
            map: map.to_string(),
            strategy,
            beta: q.learning_rate,
            gamma: q.discount,
            temperature: q.temperature,
            max_moves: q.max_moves,
            random_moves: 20,
            tolerance: 1e-6,
            decrease_threshold: 0.0,
            max_trials: 20_000,
            seed,
            world: WorldExtras::default(),
            extensions: Extensions::default(),
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
        let f: SettingsFile = toml::from_str(text).map_err(|e| Error::Settings {
            source_name: source.to_string(),
            message: e.to_string().trim().to_string(),
        })?;
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
            world,
            extensions
        );
        self.validate()
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
        let source = path.display().to_string();
        let fail = |message: String| Error::Settings {
            source_name: source.clone(),
            message,
        };
        let not_a_file = || fail("not a regular file".to_string());
        if !std::fs::metadata(path)
            .map_err(|e| fail(e.to_string()))?
            .is_file()
        {
            return Err(not_a_file());
        }
        let file = std::fs::File::open(path).map_err(|e| fail(e.to_string()))?;
        if !file.metadata().map_err(|e| fail(e.to_string()))?.is_file() {
            return Err(not_a_file());
        }
        let mut bytes = Vec::new();
        file.take(MAX_SETTINGS_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| fail(e.to_string()))?;
        if bytes.len() as u64 > MAX_SETTINGS_BYTES {
            return Err(fail(format!(
                "longer than the {MAX_SETTINGS_BYTES} bytes a settings file may have"
            )));
        }
        let text = String::from_utf8(bytes).map_err(|_| fail("not UTF-8 text".to_string()))?;
        self.apply_toml(&text, &source)
    }

    /// Whether the run leaves the paper's setting: a world with slip, noise or a sensing
    /// range, or an extension on. Such a run measures the policy quality (SPEC 6) and ends
    /// by it; the paper's runs keep the paper's convergence.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// assert!(!s.beyond_paper());
    /// s.world.slip = mdp::Slip::new(0.1).unwrap();
    /// assert!(s.beyond_paper());
    /// ```
    pub fn beyond_paper(&self) -> bool {
        !(self.world.is_default() && self.extensions.is_default())
    }

    /// Check the fields that have no type of their own.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.tolerance = -1.0;
    /// assert!(s.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |name: &'static str, value: String, expected: &'static str| {
            Err(Error::InvalidSetting {
                name,
                value,
                expected,
            })
        };
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return bad(
                "tolerance",
                self.tolerance.to_string(),
                "a finite number >= 0",
            );
        }
        if !(self.decrease_threshold.is_finite() && self.decrease_threshold >= 0.0) {
            return bad(
                "decrease_threshold",
                self.decrease_threshold.to_string(),
                "a finite number >= 0",
            );
        }
        if self.max_trials == 0 {
            return bad("max_trials", "0".to_string(), "at least 1");
        }
        if self.world.sensing_radius == Some(0) {
            return bad("world.sensing_radius", "0".to_string(), "at least 1");
        }
        self.extensions.validate()
    }
}
