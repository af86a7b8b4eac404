//! Navigation after learning: follow the learned policy on the reduced map (specification §6,
//! "Navigation after learning").
//!
//! From every non-goal free state, a fixed number of evaluation trials with learning off:
//! the agent localises (CLASSIFY, charged), then takes the greedy action of its
//! description (ties: the lowest action id) and finds the next description through its
//! perception: with [`crate::Predicting`] by the learned model wherever it trusts the
//! transition, measuring elsewhere and to verify. A trial succeeds when it reaches the
//! goal in the optimal number of moves. Q is never updated; the model may still learn
//! from what is measured.

use mdp::{Oracle, World};
use qlearn::QTable;
use rand::Rng;
use serde::Serialize;

use crate::observe::{Observer, told_to_stop};
use crate::perception::rows::Perception;

/// What navigation measured.
///
/// ```
/// let n = csql::Navigation::default();
/// assert_eq!(n.trials, 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Navigation {
    /// Evaluation trials run.
    pub trials: u64,
    /// Moves made in all of them.
    pub moves: u64,
    /// Sensing cost charged in all of them (localisation included).
    pub cost: f64,
    /// Trials that reached the goal in the optimal number of moves.
    pub optimal: u64,
}

impl Navigation {
    /// Sensing cost per move (0 when no move was made).
    ///
    /// ```
    /// let n = csql::Navigation { trials: 1, moves: 4, cost: 6.0, optimal: 1 };
    /// assert_eq!(n.cost_per_move(), 1.5);
    /// ```
    pub fn cost_per_move(&self) -> f64 {
        if self.moves == 0 {
            0.0
        } else {
            self.cost / self.moves as f64
        }
    }

    /// The share of trials that reached the goal by an optimal path.
    ///
    /// ```
    /// let n = csql::Navigation { trials: 4, moves: 9, cost: 6.0, optimal: 3 };
    /// assert_eq!(n.success(), 0.75);
    /// ```
    pub fn success(&self) -> f64 {
        if self.trials == 0 {
            0.0
        } else {
            self.optimal as f64 / self.trials as f64
        }
    }
}

/// Run `trials` evaluation trials from every non-goal free state of `world`, each cut
/// after `max_moves` moves, following the greedy policy of `table` through `perception`.
/// `observer` is asked before every trial, and every [`crate::STOP_CHECK_MOVES`] moves
/// within one, whether to go on ([`Observer::keep_going`]); when it says no, navigation
/// ends there and the result counts the trials made (`trials`, with the one cut short).
///
/// ```
/// use csql::{Identified, RunSettings, Setup, StrategyKind};
/// use rand::SeedableRng;
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// // An untrained table: every greedy action is "up", so few trials succeed.
/// let world = setup.sensed(&settings);
/// let mut p = Identified::new(&world, vec![1.0; 9]);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let mut observer = csql::KeepTrace;
/// let n = csql::navigate(&world, &setup.oracle, &mut p, &mut table, 2, 10, &mut rng, &mut observer);
/// assert_eq!(n.trials, 16);
/// // One unit per classification: localising, then each state reached but the goal.
/// assert!(n.cost_per_move() > 1.0 && n.cost <= (n.trials + n.moves) as f64);
/// ```
#[expect(
    clippy::too_many_arguments,
    reason = "one argument per part of a navigation: the world, its oracle, the perception, the policy and its settings"
)]
pub fn navigate<W: World + ?Sized, P: Perception, R: Rng + ?Sized>(
    world: &W,
    oracle: &Oracle,
    perception: &mut P,
    table: &mut QTable,
    trials: u32,
    max_moves: u32,
    rng: &mut R,
    observer: &mut dyn Observer,
) -> Navigation {
    let mut out = Navigation::default();
    for start in world.states() {
        for _ in 0..trials {
            if !observer.keep_going() {
                return out;
            }
            out.trials += 1;
            let (mut row, cost) = perception.classify(world, start, table);
            out.cost += cost;
            let mut s = start;
            let mut moves = 0u32;
            let mut all_optimal = true;
            let mut stopped = false;
            while moves < max_moves {
                if told_to_stop(observer, moves) {
                    stopped = true;
                    break;
                }
                let a = table.greedy(row);
                all_optimal &= oracle.is_optimal(s, a);
                let step = world.sample(s, a, rng);
                moves += 1;
                if step.terminated {
                    // On a grid, a shortest path; elsewhere, optimal actions all the way.
                    let optimal = match oracle.distance(start) {
                        Some(d) => d == moves,
                        None => all_optimal,
                    };
                    if optimal {
                        out.optimal += 1;
                    }
                    break;
                }
                let (next, cost) = perception.classify_next(world, row, a, step.next, table, rng);
                out.cost += cost;
                row = next;
                s = step.next;
            }
            out.moves += u64::from(moves);
            if stopped {
                return out;
            }
        }
    }
    out
}
