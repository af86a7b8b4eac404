//! How CS-QL reacts when the utility of a description decreases.
//!
//! The paper's section "Integrating CS-learning with Q-learning" and its Table 1 compare
//! four reactions. Each is a small type implementing [`Strategy`]; the main loop only
//! asks the strategy what to do, so a new strategy is a new type, not a new branch in
//! the loop.

use crate::settings::learner::StrategyKind;

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

impl StrategyKind {
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
