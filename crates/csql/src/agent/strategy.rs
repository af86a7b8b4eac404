//! How CS-QL reacts when the utility of a description decreases.
//!
//! The paper's section "Integrating CS-learning with Q-learning" and its Table 1 compare
//! four reactions. Each is a small type implementing [`Strategy`]; the main loop only
//! asks the strategy what to do, so a new strategy is a new type, not a new branch in
//! the loop.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// What the main loop does about one decrease.
///
/// ```
/// use csql::Reaction;
/// let r = Reaction::Refine { reset: true, random_moves: 0 };
/// assert!(matches!(r, Reaction::Refine { reset: true, .. }));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reaction {
    /// Leave the description as it is.
    Ignore,
    /// Add the next cheapest missing feature to the decreasing description.
    Refine {
        /// Then set every Q and V to 0.
        reset: bool,
        /// Then make this many uniformly random moves, during which decreases are ignored.
        random_moves: u32,
    },
}

/// A reaction to utility decreases. The loop calls [`Strategy::start_trial`] at the start
/// of every trial and [`Strategy::on_decrease`] at every decrease outside random moves.
///
/// ```
/// use csql::{Reaction, Strategy};
/// /// Refine only every other decrease.
/// struct EveryOther(bool);
/// impl Strategy for EveryOther {
///     fn start_trial(&mut self) {}
///     fn on_decrease(&mut self) -> Reaction {
///         self.0 = !self.0;
///         if self.0 { Reaction::Refine { reset: false, random_moves: 0 } } else { Reaction::Ignore }
///     }
/// }
/// let mut s = EveryOther(false);
/// assert_ne!(s.on_decrease(), s.on_decrease());
/// ```
pub trait Strategy {
    /// A trial begins.
    fn start_trial(&mut self);
    /// The V of the description just updated decreased: what now?
    fn on_decrease(&mut self) -> Reaction;
}

impl<S: Strategy + ?Sized> Strategy for Box<S> {
    fn start_trial(&mut self) {
        (**self).start_trial();
    }
    fn on_decrease(&mut self) -> Reaction {
        (**self).on_decrease()
    }
}

/// The paper's strategy: refine, then reset every Q and V to 0, so that no utility keeps
/// an overestimate that came from an inconsistent description (Theorem 2 applies again).
///
/// ```
/// use csql::{Resetting, Reaction, Strategy};
/// assert_eq!(Resetting.on_decrease(), Reaction::Refine { reset: true, random_moves: 0 });
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Resetting;

impl Strategy for Resetting {
    fn start_trial(&mut self) {}
    fn on_decrease(&mut self) -> Reaction {
        Reaction::Refine {
            reset: true,
            random_moves: 0,
        }
    }
}

/// Refine at the first decrease of a trial only; later decreases in the same trial are
/// ignored. No reset.
///
/// ```
/// use csql::{Lazy, Reaction, Strategy};
/// let mut s = Lazy::default();
/// s.start_trial();
/// assert!(matches!(s.on_decrease(), Reaction::Refine { .. }));
/// assert_eq!(s.on_decrease(), Reaction::Ignore);
/// s.start_trial();
/// assert!(matches!(s.on_decrease(), Reaction::Refine { .. }));
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Lazy {
    refined_this_trial: bool,
}

impl Strategy for Lazy {
    fn start_trial(&mut self) {
        self.refined_this_trial = false;
    }
    fn on_decrease(&mut self) -> Reaction {
        if std::mem::replace(&mut self.refined_this_trial, true) {
            Reaction::Ignore
        } else {
            Reaction::Refine {
                reset: false,
                random_moves: 0,
            }
        }
    }
}

/// Refine at every decrease, then make `moves` uniformly random moves that update the
/// utilities of nearby descriptions without refining them. No reset.
///
/// ```
/// use csql::{RandomMoves, Reaction, Strategy};
/// let mut s = RandomMoves { moves: 20 };
/// assert_eq!(s.on_decrease(), Reaction::Refine { reset: false, random_moves: 20 });
/// ```
#[derive(Clone, Copy, Debug)]
pub struct RandomMoves {
    /// Random moves after each refinement (the paper: 20).
    pub moves: u32,
}

impl Strategy for RandomMoves {
    fn start_trial(&mut self) {}
    fn on_decrease(&mut self) -> Reaction {
        Reaction::Refine {
            reset: false,
            random_moves: self.moves,
        }
    }
}

/// Refine at every decrease. No reset.
///
/// ```
/// use csql::{Eager, Reaction, Strategy};
/// assert_eq!(Eager.on_decrease(), Reaction::Refine { reset: false, random_moves: 0 });
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Eager;

impl Strategy for Eager {
    fn start_trial(&mut self) {}
    fn on_decrease(&mut self) -> Reaction {
        Reaction::Refine {
            reset: false,
            random_moves: 0,
        }
    }
}

/// The four strategies of the paper by name, as read from settings and the command line.
///
/// ```
/// use csql::StrategyKind;
/// let k: StrategyKind = "lazy".parse().unwrap();
/// assert_eq!(k, StrategyKind::Lazy);
/// assert_eq!(k.to_string(), "lazy");
/// assert!("greedy".parse::<StrategyKind>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StrategyKind {
    /// [`Resetting`].
    Resetting,
    /// [`Lazy`].
    Lazy,
    /// [`RandomMoves`].
    Random,
    /// [`Eager`].
    Eager,
}

impl StrategyKind {
    /// All four, in the paper's column order.
    ///
    /// ```
    /// assert_eq!(csql::StrategyKind::ALL.len(), 4);
    /// ```
    pub const ALL: [StrategyKind; 4] = [
        StrategyKind::Resetting,
        StrategyKind::Lazy,
        StrategyKind::Random,
        StrategyKind::Eager,
    ];

    /// The name used in settings, on the command line and in reports.
    ///
    /// ```
    /// assert_eq!(csql::StrategyKind::Random.name(), "random");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            StrategyKind::Resetting => "resetting",
            StrategyKind::Lazy => "lazy",
            StrategyKind::Random => "random",
            StrategyKind::Eager => "eager",
        }
    }

    /// The strategy itself; `random_moves` is used by [`StrategyKind::Random`] only.
    ///
    /// ```
    /// use csql::{Reaction, StrategyKind};
    /// let mut s = StrategyKind::Random.build(5);
    /// assert_eq!(s.on_decrease(), Reaction::Refine { reset: false, random_moves: 5 });
    /// ```
    pub fn build(self, random_moves: u32) -> Box<dyn Strategy + Send + Sync> {
        match self {
            StrategyKind::Resetting => Box::new(Resetting),
            StrategyKind::Lazy => Box::new(Lazy::default()),
            StrategyKind::Random => Box::new(RandomMoves {
                moves: random_moves,
            }),
            StrategyKind::Eager => Box::new(Eager),
        }
    }
}

impl fmt::Display for StrategyKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A strategy name that is not one of the four.
///
/// ```
/// let err = "x".parse::<csql::StrategyKind>().unwrap_err();
/// assert!(err.to_string().contains("resetting"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown strategy `{0}` (expected resetting, lazy, random or eager)")]
pub struct UnknownStrategy(pub String);

impl FromStr for StrategyKind {
    type Err = UnknownStrategy;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        StrategyKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownStrategy(s.to_string()))
    }
}

/// A strategy that never refines: for learning on a fixed perception.
///
/// ```
/// use csql::{Never, Reaction, Strategy};
/// assert_eq!(Never.on_decrease(), Reaction::Ignore);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Never;

impl Strategy for Never {
    fn start_trial(&mut self) {}
    fn on_decrease(&mut self) -> Reaction {
        Reaction::Ignore
    }
}
