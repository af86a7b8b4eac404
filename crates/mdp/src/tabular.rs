//! An explicit finite deterministic MDP given by tables.

use crate::error::MdpError;
use crate::process::{ActionId, Mdp, StateId, Step};

/// What to do with negative rewards, which break the paper's Theorems 1 and 2.
///
/// ```
/// use mdp::NegativeRewards;
/// assert_ne!(NegativeRewards::Refuse, NegativeRewards::Shift);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NegativeRewards {
    /// Refuse an MDP with a negative reward (the default).
    #[default]
    Refuse,
    /// Add one constant to every reward so that the most negative becomes 0 (the paper's
    /// remark that Q-learning then behaves the same).
    Shift,
}

/// A deterministic MDP stored as dense tables: `next[s * A + a]`, `reward[s * A + a]` and
/// `terminal[s]`. Stepping from a terminal state stays there with reward 0.
///
/// ```
/// use mdp::{ActionId, Mdp, NegativeRewards, StateId, TabularMdp};
/// // Two states, one action: 0 -> 1 (terminal) with reward 1.
/// let m = TabularMdp::new(2, 1, vec![1, 1], vec![1.0, 0.0], vec![false, true], NegativeRewards::Refuse).unwrap();
/// let step = m.step(StateId(0), ActionId(0));
/// assert_eq!((step.next, step.reward, step.terminated), (StateId(1), 1.0, true));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TabularMdp {
    actions: usize,
    next: Vec<StateId>,
    reward: Vec<f64>,
    terminal: Vec<bool>,
    shift: f64,
}

impl TabularMdp {
    /// Build from tables, validating lengths, targets and rewards.
    ///
    /// ```
    /// use mdp::{NegativeRewards, TabularMdp};
    /// let m = TabularMdp::new(1, 2, vec![0, 0], vec![-2.0, 1.0], vec![false], NegativeRewards::Shift).unwrap();
    /// assert_eq!(m.shift(), 2.0);
    /// ```
    pub fn new(
        states: usize,
        actions: usize,
        next: Vec<u32>,
        reward: Vec<f64>,
        terminal: Vec<bool>,
        negative: NegativeRewards,
    ) -> Result<TabularMdp, MdpError> {
        if states == 0 || actions == 0 {
            return Err(MdpError::Empty);
        }
        let n = states * actions;
        for (table, found, expected) in [
            ("next", next.len(), n),
            ("reward", reward.len(), n),
            ("terminal", terminal.len(), states),
        ] {
            if found != expected {
                return Err(MdpError::WrongLength {
                    table,
                    found,
                    expected,
                });
            }
        }
        let mut min: f64 = 0.0;
        for (i, (&t, &r)) in next.iter().zip(&reward).enumerate() {
            let (state, action) = (i / actions, i % actions);
            if t as usize >= states {
                return Err(MdpError::NoSuchState {
                    state,
                    action,
                    next: t as usize,
                    states,
                });
            }
            if !r.is_finite() {
                return Err(MdpError::NonFiniteReward {
                    state,
                    action,
                    reward: r,
                });
            }
            if r < 0.0 && negative == NegativeRewards::Refuse {
                return Err(MdpError::NegativeReward {
                    state,
                    action,
                    reward: r,
                });
            }
            min = min.min(r);
        }
        let shift = -min;
        Ok(TabularMdp {
            actions,
            next: next.into_iter().map(StateId).collect(),
            reward: reward.into_iter().map(|r| r + shift).collect(),
            terminal,
            shift,
        })
    }

    /// The constant added to every reward (0 unless negative rewards were shifted).
    ///
    /// ```
    /// use mdp::{NegativeRewards, TabularMdp};
    /// let m = TabularMdp::new(1, 1, vec![0], vec![0.5], vec![false], NegativeRewards::Shift).unwrap();
    /// assert_eq!(m.shift(), 0.0);
    /// ```
    pub fn shift(&self) -> f64 {
        self.shift
    }
}

impl Mdp for TabularMdp {
    fn num_states(&self) -> usize {
        self.terminal.len()
    }
    fn num_actions(&self) -> usize {
        self.actions
    }
    fn is_terminal(&self, s: StateId) -> bool {
        self.terminal[s.index()]
    }
    #[inline]
    fn step(&self, s: StateId, a: ActionId) -> Step {
        if self.terminal[s.index()] {
            return Step {
                next: s,
                reward: 0.0,
                terminated: true,
                truncated: false,
            };
        }
        let i = s.index() * self.actions + a.index();
        let next = self.next[i];
        Step {
            next,
            reward: self.reward[i],
            terminated: self.terminal[next.index()],
            truncated: false,
        }
    }
}
