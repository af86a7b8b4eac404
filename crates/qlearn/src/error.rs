//! The crate's one error type.

use mdp::StateId;

/// Everything that can go wrong when building parameters, tables or learners.
///
/// Every variant carries the offending value, so a message read from a settings file
/// says what was wrong without the file at hand.
///
/// ```
/// use qlearn::{Error, Temperature};
/// let err = Temperature::new(0.0).unwrap_err();
/// assert_eq!(err, Error::Temperature { value: 0.0 });
/// assert!(err.to_string().contains("temperature"));
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The learning rate beta is not in `(0, 1]`.
    #[error("learning rate (beta) must be in (0, 1], got {value}")]
    LearningRate {
        /// The rejected value.
        value: f64,
    },
    /// The discount gamma is not in `[0, 1)`.
    #[error("discount (gamma) must be in [0, 1), got {value}")]
    Discount {
        /// The rejected value.
        value: f64,
    },
    /// The Boltzmann temperature T is not a finite number greater than 0.
    #[error("temperature (T) must be finite and greater than 0, got {value}")]
    Temperature {
        /// The rejected value.
        value: f64,
    },
    /// The exploration rate epsilon is not in `[0, 1]`.
    #[error("exploration rate (epsilon) must be in [0, 1], got {value}")]
    Epsilon {
        /// The rejected value.
        value: f64,
    },
    /// The move cap of a trial is 0 or does not fit in 32 bits.
    #[error("move cap (max_moves) must be in 1..=4294967295, got {value}")]
    MoveCap {
        /// The rejected value.
        value: u64,
    },
    /// A starting value for Q that is not a finite number.
    #[error("Q cannot start at {value}: a finite number is needed")]
    BadInitialValue {
        /// The value given.
        value: f64,
    },
    /// A table or an MDP with no actions: nothing could ever be selected.
    #[error("a Q table needs at least one action, got {actions}")]
    NoActions {
        /// The number of actions asked for.
        actions: usize,
    },
    /// An MDP whose number of states does not fit a 32-bit row id.
    #[error("an MDP with {states} states has more than a 32-bit row id can number")]
    TooManyStates {
        /// The number of states of the MDP.
        states: usize,
    },
    /// Every state of the MDP is terminal, so no trial can start.
    #[error("the MDP has no non-terminal state to start a trial from")]
    NoStartState,
    /// A fixed start state that the MDP does not have.
    #[error("start state {state} is not a state of an MDP with {states} states")]
    StartOutOfRange {
        /// The requested start state.
        state: StateId,
        /// The number of states of the MDP.
        states: usize,
    },
    /// A fixed start state that is terminal: its trial would end before the first move.
    #[error("start state {state} is terminal")]
    StartTerminal {
        /// The requested start state.
        state: StateId,
    },
}
