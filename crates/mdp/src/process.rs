//! The deterministic MDP abstraction: dense state ids, a fixed action set, and a step
//! function that keeps termination and truncation apart.

use std::fmt;

/// A dense state id: states of an MDP are numbered `0..num_states()`.
///
/// ```
/// use mdp::StateId;
/// let s = StateId(3);
/// assert_eq!(s.index(), 3);
/// ```
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
pub struct StateId(pub u32);

impl StateId {
    /// The id as an index into dense per-state storage.
    ///
    /// ```
    /// assert_eq!(mdp::StateId(7).index(), 7);
    /// ```
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for StateId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "s{}", self.0)
    }
}

/// A dense action id: actions of an MDP are numbered `0..num_actions()`.
///
/// ```
/// use mdp::ActionId;
/// assert_eq!(ActionId(2).index(), 2);
/// ```
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
pub struct ActionId(pub u32);

impl ActionId {
    /// The id as an index into dense per-action storage.
    ///
    /// ```
    /// assert_eq!(mdp::ActionId(1).index(), 1);
    /// ```
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for ActionId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a{}", self.0)
    }
}

/// The outcome of one step.
///
/// `terminated` means the MDP reached a terminal state (the goal): the value of what
/// follows is zero and a learner must not bootstrap. `truncated` means the episode was
/// cut for a reason outside the MDP (a move cap): the next state still has a value and a
/// learner should bootstrap from it. An MDP's own [`Mdp::step`] never sets `truncated`;
/// trial loops that impose a move cap do.
///
/// ```
/// use mdp::{Step, StateId};
/// let s = Step { next: StateId(1), reward: 1.0, terminated: true, truncated: false };
/// assert!(s.done());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    /// The state reached.
    pub next: StateId,
    /// The reward received for the transition.
    pub reward: f64,
    /// The MDP reached a terminal state.
    pub terminated: bool,
    /// The episode was cut from outside (for example by a move cap).
    pub truncated: bool,
}

impl Step {
    /// Whether the episode ends after this step, for either reason.
    ///
    /// ```
    /// use mdp::{Step, StateId};
    /// let s = Step { next: StateId(0), reward: 0.0, terminated: false, truncated: true };
    /// assert!(s.done());
    /// ```
    #[inline]
    pub fn done(&self) -> bool {
        self.terminated || self.truncated
    }
}

/// A finite, deterministic Markov decision process.
///
/// States are dense ids `0..num_states()`, actions dense ids `0..num_actions()`, and the
/// same `(state, action)` always gives the same [`Step`]. Nothing here knows about grids,
/// so any finite deterministic system can implement it.
///
/// ```
/// use mdp::{ActionId, Mdp, StateId, Step};
///
/// /// A chain 0 -> 1 -> 2 where state 2 is terminal and entering it pays 1.
/// struct Chain;
/// impl Mdp for Chain {
///     fn num_states(&self) -> usize { 3 }
///     fn num_actions(&self) -> usize { 1 }
///     fn is_terminal(&self, s: StateId) -> bool { s.0 == 2 }
///     fn step(&self, s: StateId, _a: ActionId) -> Step {
///         let next = StateId((s.0 + 1).min(2));
///         let terminated = next.0 == 2;
///         Step { next, reward: if terminated { 1.0 } else { 0.0 }, terminated, truncated: false }
///     }
/// }
/// assert_eq!(Chain.step(StateId(1), ActionId(0)).reward, 1.0);
/// ```
pub trait Mdp {
    /// Number of states; ids are `0..num_states()`.
    fn num_states(&self) -> usize;
    /// Number of actions, the same in every state; ids are `0..num_actions()`.
    fn num_actions(&self) -> usize;
    /// Whether `s` is terminal (an episode that reaches it ends).
    fn is_terminal(&self, s: StateId) -> bool;
    /// Take action `a` in state `s`. Must be deterministic. Never sets `truncated`.
    fn step(&self, s: StateId, a: ActionId) -> Step;

    /// The non-terminal states, in id order: the default start distribution of a trial.
    ///
    /// ```
    /// use mdp::{builtin, GridWorld, Mdp};
    /// let w = GridWorld::new(&builtin("tan3x3").unwrap());
    /// assert_eq!(w.non_terminal_states().len(), 8);
    /// ```
    fn non_terminal_states(&self) -> Vec<StateId> {
        (0..self.num_states() as u32)
            .map(StateId)
            .filter(|&s| !self.is_terminal(s))
            .collect()
    }
}

impl<M: Mdp + ?Sized> Mdp for &M {
    fn num_states(&self) -> usize {
        (**self).num_states()
    }
    fn num_actions(&self) -> usize {
        (**self).num_actions()
    }
    fn is_terminal(&self, s: StateId) -> bool {
        (**self).is_terminal(s)
    }
    fn step(&self, s: StateId, a: ActionId) -> Step {
        (**self).step(s, a)
    }
}
