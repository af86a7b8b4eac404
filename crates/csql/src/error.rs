//! The crate's errors.

/// Why a run could not start.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let err = s.apply_toml("max_trials = 0", "my.toml").unwrap_err();
/// assert!(matches!(err, csql::Error::Settings { .. }));
/// assert!(err.to_string().starts_with("my.toml: "));
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A settings file could not be read or parsed, or has unknown keys or bad values.
    #[error("{source_name}: {problem}")]
    Settings {
        /// The file (or the name given to the text).
        source_name: String,
        /// What is wrong with it (said in this error's message, not again as its source,
        /// so that a chain of errors prints it once).
        problem: SettingsProblem,
    },
    /// A setting out of range.
    #[error("invalid setting {value}: expected {expected}")]
    InvalidSetting {
        /// The value given.
        value: String,
        /// What is accepted.
        expected: &'static str,
    },
    /// The map could not be found or is invalid.
    #[error(transparent)]
    Map(#[from] mdp::MapError),
    /// The world could not be built (for example, a negative reward).
    #[error(transparent)]
    World(#[from] mdp::MdpError),
    /// The cost model gave a bad cost.
    #[error(transparent)]
    Cost(#[from] mdp::BadCost),
    /// A world file or a built-in world could not be read or built.
    #[error(transparent)]
    WorldFile(#[from] mdp::WorldError),
    /// Two settings (or a setting and the world) that mean nothing together.
    #[error("{first} and {second} cannot be used together: {why}")]
    Conflict {
        /// The first setting (or the world).
        first: String,
        /// The second setting.
        second: String,
        /// Why not.
        why: &'static str,
    },
    /// A run whose memory would exceed a documented bound, refused before it starts.
    #[error("{what} would keep {needed} values, over the limit of {limit}: {hint}")]
    TooLarge {
        /// What would be kept.
        what: String,
        /// How many values it would keep.
        needed: u64,
        /// The most allowed.
        limit: u64,
        /// What to do instead.
        hint: &'static str,
    },
    /// Sensing by belief could not plan in this world with these settings (for example,
    /// more features measured apart than a plan's menu takes).
    #[error("sensing by belief: {0}")]
    Plan(#[from] mdp::ReferenceError),
    /// A setting or a measure that only makes sense on a grid map, asked of another world.
    #[error("{what} needs a grid map; this world is not one")]
    GridOnly {
        /// What was asked.
        what: &'static str,
    },
}

/// What is wrong with a settings file.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let err = s.apply_file(std::path::Path::new("/")).unwrap_err();
/// assert!(matches!(err, csql::Error::Settings { problem: csql::SettingsProblem::NotAFile, .. }));
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SettingsProblem {
    /// It could not be read.
    #[error("cannot read it: {0}")]
    Read(std::io::Error),
    /// It is a directory, a device or a pipe.
    #[error("not a regular file")]
    NotAFile,
    /// It is longer than a settings file may be.
    #[error("longer than the {limit} bytes a settings file may have")]
    TooLarge {
        /// The limit in bytes.
        limit: u64,
    },
    /// It is not UTF-8 text.
    #[error("not UTF-8 text: {0}")]
    NotUtf8(std::string::FromUtf8Error),
    /// It is not valid settings TOML (the parser names the key, line and column).
    #[error("{}", .0.to_string().trim())]
    Parse(toml::de::Error),
    /// A table given as something else, or a key in the wrong table.
    #[error("{0}")]
    Layout(String),
}
