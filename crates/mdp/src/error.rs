//! The crate's errors.

use std::fmt;

use crate::geometry::Pos;

/// A 1-based line and column in a map file (or in a bare layout).
///
/// ```
/// let p = mdp::Position { line: 3, column: 7 };
/// assert_eq!(p.to_string(), "line 3, column 7");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Position {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

fn at_suffix(at: &Option<Position>) -> String {
    at.map(|p| format!(" at {p}")).unwrap_or_default()
}

/// Why a map could not be read or is not valid.
///
/// Every variant names its source (a file path or a map name) and, where there is one,
/// the position of the problem.
///
/// ```
/// let err = mdp::Map::from_layout("m", "..\n.").unwrap_err();
/// assert!(matches!(err, mdp::MapError::RaggedRow { .. }));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MapError {
    /// The name is neither a built-in map nor an existing file.
    #[error("no built-in map and no file named `{name}` (built-in maps: {builtins})")]
    UnknownMap {
        /// What was asked for.
        name: String,
        /// The built-in names, comma-separated.
        builtins: String,
    },
    /// The file could not be read.
    #[error("{source_name}: cannot read: {error}")]
    Io {
        /// The file.
        source_name: String,
        /// The operating system's message.
        error: String,
    },
    /// The path is a directory or another non-file.
    #[error("{source_name}: not a regular file")]
    NotAFile {
        /// The path.
        source_name: String,
    },
    /// The file is larger than any valid map file can be.
    #[error("{source_name}: file is {bytes} bytes, more than the {max} a map file may have")]
    FileTooLarge {
        /// The file.
        source_name: String,
        /// Its size.
        bytes: u64,
        /// The limit.
        max: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{source_name}: not UTF-8 text (first bad byte at {at})")]
    NotUtf8 {
        /// The file.
        source_name: String,
        /// Where the first invalid byte is.
        at: Position,
    },
    /// The file is not valid TOML, or has missing, unknown or mistyped keys.
    #[error("{source_name}{}: {message}", at_suffix(.at))]
    Toml {
        /// The file.
        source_name: String,
        /// Where the parser stopped, if it knows.
        at: Option<Position>,
        /// The parser's message (it names unknown or missing keys).
        message: String,
    },
    /// The `name` key is blank.
    #[error("{source_name}: `name` must not be empty")]
    EmptyName {
        /// The file.
        source_name: String,
    },
    /// The layout has no rows.
    #[error("{source_name}: the layout is empty")]
    EmptyLayout {
        /// The file or map name.
        source_name: String,
    },
    /// The layout is wider or taller than [`crate::MAX_SIDE`].
    #[error(
        "{source_name}: the layout is {width} wide and {height} high; at most {max} cells a side are allowed"
    )]
    TooLarge {
        /// The file or map name.
        source_name: String,
        /// The widest row.
        width: usize,
        /// The number of rows.
        height: usize,
        /// The limit.
        max: usize,
    },
    /// A row's width differs from the first row's.
    #[error(
        "{source_name} at {at}: layout row {row} has {found} cells, but the first row has {expected}"
    )]
    RaggedRow {
        /// The file or map name.
        source_name: String,
        /// Where the row ends (or goes past the first row's width).
        at: Position,
        /// The row, from 0 at the top.
        row: usize,
        /// The first row's width.
        expected: usize,
        /// This row's width.
        found: usize,
    },
    /// A layout character other than `#`, `.` or `G`.
    #[error(
        "{source_name} at {at}: unknown map character {found:?} (use `#` obstacle, `.` empty, `G` goal)"
    )]
    UnknownChar {
        /// The file or map name.
        source_name: String,
        /// Where the character is.
        at: Position,
        /// The character.
        found: char,
    },
    /// The layout has no `G`.
    #[error("{source_name}: the layout has no goal `G`")]
    NoGoal {
        /// The file or map name.
        source_name: String,
    },
    /// The layout has more than one `G`.
    #[error(
        "{source_name} at {at}: a second goal; the first is at {first} (a map has exactly one)"
    )]
    SecondGoal {
        /// The file or map name.
        source_name: String,
        /// Where the second goal is.
        at: Position,
        /// Where the first goal is.
        first: Position,
    },
    /// The layout has a goal but no empty cell for the robot to start on.
    #[error("{source_name}: the layout has no empty cell besides the goal")]
    NoStates {
        /// The file or map name.
        source_name: String,
    },
    /// A free cell from which the goal cannot be reached.
    #[error("{source_name} at {at}: the free cell at {cell} cannot reach the goal")]
    Unreachable {
        /// The file or map name.
        source_name: String,
        /// Where the cell is in the file.
        at: Position,
        /// The cell.
        cell: Pos,
    },
    /// A map spec that cannot be read (see [`crate::resolve`]).
    #[error("map `{spec}`: {reason}")]
    BadSpec {
        /// The spec.
        spec: String,
        /// What is wrong with it.
        reason: String,
    },
    /// Random map parameters out of range.
    #[error("invalid random map parameter `{name}`: {reason}")]
    InvalidRandomParameter {
        /// The parameter.
        name: &'static str,
        /// What is wrong with it.
        reason: String,
    },
}

/// Why an MDP could not be built.
///
/// ```
/// use mdp::{MdpError, NegativeRewards, TabularMdp};
/// let err = TabularMdp::new(1, 1, vec![0], vec![-1.0], vec![false], NegativeRewards::Refuse).unwrap_err();
/// assert!(matches!(err, MdpError::NegativeReward { .. }));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MdpError {
    /// A reward is negative and shifting was not asked for.
    #[error(
        "reward {reward} of state {state}, action {action} is negative; the theorems need rewards >= 0 (ask for a shift to add a constant)"
    )]
    NegativeReward {
        /// The state.
        state: usize,
        /// The action.
        action: usize,
        /// The reward.
        reward: f64,
    },
    /// A reward is NaN or infinite.
    #[error("reward of state {state}, action {action} is not finite ({reward})")]
    NonFiniteReward {
        /// The state.
        state: usize,
        /// The action.
        action: usize,
        /// The reward.
        reward: f64,
    },
    /// A table has the wrong length for the state and action counts.
    #[error("the {table} table has {found} entries; {expected} expected")]
    WrongLength {
        /// Which table.
        table: &'static str,
        /// Its length.
        found: usize,
        /// The expected length.
        expected: usize,
    },
    /// A transition leads to a state that does not exist.
    #[error(
        "state {state}, action {action} leads to state {next}, but there are only {states} states"
    )]
    NoSuchState {
        /// The state.
        state: usize,
        /// The action.
        action: usize,
        /// The target.
        next: usize,
        /// The number of states.
        states: usize,
    },
    /// No states or no actions.
    #[error("an MDP needs at least one state and one action")]
    Empty,
    /// A discount outside `[0, 1)`.
    #[error("discount gamma = {gamma} is outside [0, 1)")]
    InvalidDiscount {
        /// The value given.
        gamma: f64,
    },
    /// A probability (of a slip, or of a sensing error) outside `[0, 1]`.
    #[error("{name} = {value} is not a probability in [0, 1]")]
    InvalidProbability {
        /// Which probability.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A policy that does not give one valid action per state.
    #[error("the policy has {found} actions for {states} states, or an action >= {actions}")]
    BadPolicy {
        /// Its length.
        found: usize,
        /// The number of states.
        states: usize,
        /// The number of actions.
        actions: usize,
    },
}
