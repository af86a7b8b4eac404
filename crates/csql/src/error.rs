//! The crate's errors.

/// Why a run could not start.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// s.max_trials = 0;
/// assert!(matches!(s.validate(), Err(csql::Error::InvalidSetting { name: "max_trials", .. })));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A settings file could not be read or parsed, or has unknown keys or bad values.
    #[error("{source_name}: {message}")]
    Settings {
        /// The file.
        source_name: String,
        /// What is wrong (the parser names the key and the line).
        message: String,
    },
    /// A setting out of range.
    #[error("setting `{name}` = {value} is invalid: expected {expected}")]
    InvalidSetting {
        /// The setting.
        name: &'static str,
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
}
