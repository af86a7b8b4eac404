//! The main loop of CS-QL (the paper's Figure 3), organised in trials.
//!
//! The loop is generic over how states become table rows ([`Perception`]) and over how a
//! decrease is handled ([`Strategy`]). CS-QL is the loop with [`crate::Classify`] and one
//! of the four strategies; the reference points of the paper's discussion are the same
//! loop with a fixed perception and a strategy that never refines.
//!
//! # One move
//!
//! 1. Select an action by Boltzmann on the current row (or uniformly, during the random
//!    moves of the random strategy).
//! 2. Step. If the goal is reached the target is the reward alone and the goal is never
//!    classified; otherwise classify the next state (charged) and bootstrap from its row,
//!    also when the move cap cuts the trial.
//! 3. Update Q and V of the current row (equation 2). If V decreased by more than the
//!    decrease threshold outside random moves, ask the strategy. A refinement adds the
//!    next cheapest missing feature to the current row's description, valued at the
//!    current state (charged); then the next state is classified again (charged), since
//!    the refined description may no longer match it.
//!
//! # Random draws, in order
//!
//! Per trial: one `random_range(0..n)` for the start state. Per move: one uniform `f64`
//! for Boltzmann selection, or one `random_range(0..4)` for a random move.

use mdp::{GridWorld, Mdp, StateId};
use qlearn::{QTable, RowId, Target};
use rand::{Rng, RngExt};
use serde::Serialize;

use crate::check::Verdict;
use crate::strategy::{Reaction, Strategy};

/// How states become rows of the Q table, and what that costs.
///
/// ```
/// use csql::{Identified, Perception};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let mut p = Identified::new(&world, vec![5.0; 9]);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let (row, cost) = p.classify(&world, mdp::StateId(0), &mut table);
/// assert_eq!((row.0, cost), (0, 5.0));
/// ```
pub trait Perception {
    /// The row of a non-terminal state, adding rows to `table` if the perception grows;
    /// returns the sensing cost charged.
    fn classify(&mut self, world: &GridWorld, s: StateId, table: &mut QTable) -> (RowId, f64);
    /// Make `row` more specific, using state `s` (which it describes) for the new value;
    /// returns the cost charged, or `None` if the row cannot be refined further.
    fn refine(&mut self, world: &GridWorld, row: RowId, s: StateId) -> Option<f64>;
    /// How many rows (descriptions) the perception has made so far.
    fn rows(&self) -> usize;
    /// The oracle's verdict on the perception and the table (free, never seen by the learner).
    fn verdict(
        &self,
        world: &GridWorld,
        oracle: &mdp::Oracle,
        table: &QTable,
        tolerance: f64,
    ) -> Verdict;
}

/// Every state identified by its own row, at a fixed price per classification (for
/// example the cost of sensing the whole world): plain Q-learning.
#[derive(Clone, Debug)]
pub struct Identified {
    rows: Vec<Option<RowId>>,
    cost: Vec<f64>,
}

impl Identified {
    /// A perception that charges `cost[s]` each time state `s` is classified.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let p = csql::Identified::new(&world, vec![1.0; 9]);
    /// ```
    pub fn new(world: &GridWorld, cost: Vec<f64>) -> Identified {
        Identified {
            rows: vec![None; world.num_states()],
            cost,
        }
    }
}

impl Perception for Identified {
    fn classify(&mut self, _world: &GridWorld, s: StateId, table: &mut QTable) -> (RowId, f64) {
        let row = *self.rows[s.index()].get_or_insert_with(|| table.add_row());
        (row, self.cost[s.index()])
    }
    fn refine(&mut self, _world: &GridWorld, _row: RowId, _s: StateId) -> Option<f64> {
        None
    }
    fn rows(&self) -> usize {
        self.rows.iter().flatten().count()
    }
    fn verdict(
        &self,
        world: &GridWorld,
        oracle: &mdp::Oracle,
        table: &QTable,
        tolerance: f64,
    ) -> Verdict {
        let rows: Vec<Option<RowId>> = world
            .states()
            .iter()
            .map(|s| self.rows[s.index()])
            .collect();
        Verdict::judge(world, oracle, table, &rows, tolerance)
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

/// The loop's parameters (a validated subset of [`crate::RunSettings`]).
///
/// ```
/// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// let p = csql::LoopParams::from(&s);
/// assert_eq!(p.max_moves, 100);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct LoopParams {
    /// Beta.
    pub beta: qlearn::LearningRate,
    /// Gamma.
    pub gamma: qlearn::Discount,
    /// T.
    pub temperature: qlearn::Temperature,
    /// Moves per trial.
    pub max_moves: u32,
    /// V must drop by more than this to count as a decrease.
    pub decrease_threshold: f64,
}

/// What happened in one trial (see [`run_trial`]).
///
/// ```
/// let t = csql::TrialRecord::default();
/// assert_eq!(t.moves, 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TrialRecord {
    /// The trial's number, from 1.
    pub trial: u32,
    /// Moves made (random moves included).
    pub moves: u32,
    /// Whether the goal was reached (otherwise the move cap cut the trial).
    pub reached_goal: bool,
    /// Sensing cost charged in this trial.
    pub cost: f64,
    /// Decreases of V seen (including ignored ones).
    pub decreases: u32,
    /// Features added to descriptions.
    pub refinements: u32,
    /// Resets of Q and V.
    pub resets: u32,
}

/// Run one trial from `start`: the loop of Figure 3 until the goal or the move cap.
///
/// ```
/// use csql::{Classify, Lazy, LoopParams, RunSettings, Setup, StrategyKind};
/// use rand::SeedableRng;
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let mut classify = Classify::new(&setup.space);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let start = setup.world.states()[0];
/// let rec = csql::run_trial(
///     &setup.world, &mut classify, &mut Lazy::default(), &mut table,
///     &LoopParams::from(&settings), start, 1, &mut rng,
/// );
/// assert!(rec.moves >= 1 && rec.moves <= 100);
/// assert!(classify.representation().len() >= 1);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn run_trial<P: Perception + ?Sized, S: Strategy + ?Sized, R: Rng + ?Sized>(
    world: &GridWorld,
    perception: &mut P,
    strategy: &mut S,
    table: &mut QTable,
    params: &LoopParams,
    start: StateId,
    trial: u32,
    rng: &mut R,
) -> TrialRecord {
    let mut rec = TrialRecord {
        trial,
        ..TrialRecord::default()
    };
    strategy.start_trial();
    let mut x = start;
    let (mut row_x, cost) = perception.classify(world, x, table);
    rec.cost += cost;
    let mut random_left = 0u32;
    while rec.moves < params.max_moves {
        let random_move = random_left > 0;
        let a = if random_move {
            random_left -= 1;
            mdp::ActionId(rng.random_range(0..world.num_actions() as u32))
        } else {
            table.boltzmann(row_x, params.temperature, rng)
        };
        let step = world.step(x, a);
        rec.moves += 1;
        let next = if step.terminated {
            None
        } else {
            let (row_y, cost) = perception.classify(world, step.next, table);
            rec.cost += cost;
            Some(row_y)
        };
        let target = next.map_or(Target::Terminal, Target::Bootstrap);
        let change = table.update(row_x, a, step.reward, target, params.beta, params.gamma);
        let mut row_y = next;
        if change.after < change.before - params.decrease_threshold {
            rec.decreases += 1;
            // Decreases during random moves are seen but never refine anything.
            if !random_move
                && let Reaction::Refine {
                    reset,
                    random_moves,
                } = strategy.on_decrease()
            {
                if let Some(cost) = perception.refine(world, row_x, x) {
                    rec.cost += cost;
                    rec.refinements += 1;
                }
                if reset {
                    table.reset();
                    rec.resets += 1;
                }
                random_left = random_moves;
                if !step.terminated {
                    // The refined description may no longer match the next state.
                    let (again, cost) = perception.classify(world, step.next, table);
                    rec.cost += cost;
                    row_y = Some(again);
                }
            }
        }
        match row_y {
            None => {
                rec.reached_goal = true;
                break;
            }
            Some(r) => {
                x = step.next;
                row_x = r;
            }
        }
    }
    rec
}
