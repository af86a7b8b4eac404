//! The main loop of CS-QL (the paper's Figure 3), organised in trials.
//!
//! The loop is generic over how states become table rows ([`Perception`]) and over how a
//! decrease is handled ([`Strategy`]). CS-QL is the loop with [`crate::Classify`] and one
//! of the four strategies; the reference points of the paper's discussion are the same
//! loop with a fixed perception and a strategy that never refines.
//!
//! # The loop, step by step (the paper's Figure 3, MAIN LOOP)
//!
//! 1. A trial starts in a state `x`; classify it (charged).
//! 2. Select an action by Boltzmann on `x`'s row (or uniformly, during the random moves
//!    of the random strategy; the figure selects at steps 1 and 7, the code at the top of
//!    each move, which is the same sequence), act, and receive the reward.
//! 3. Classify the next state `y` (charged), unless it is the goal: the goal ends the
//!    trial and is never classified.
//! 4. and 5. Update `Q(x, a)` and `V(x)` by equation 2 (the target is the reward alone
//!    at the goal; the move cap does not change the target).
//! 6. If `V(x)` decreased by more than the decrease threshold outside random moves, the
//!    strategy decides: add the next cheapest feature `x`'s description lacks, valued at
//!    the state it was used for (charged), and reset Q and V (resetting), or not. The
//!    next state is then classified again (charged): the refined description may no
//!    longer match it.
//! 8. and 9. `x` becomes `y`, until the goal or the move cap.
//!
//! # Random draws, in order
//!
//! Per trial: one `random_range(0..n)` for the start state. Per move: one uniform `f64`
//! for Boltzmann selection, or one `random_range(0..4)` for a random move.

use mdp::{StateId, World};
use qlearn::{QTable, RowId, Target};
use rand::{Rng, RngExt};
use serde::Serialize;

use crate::detector::{Detector, RunDetector};
use crate::perception::Perception;
use crate::strategy::{Reaction, Strategy};

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

/// What happened in one trial (see [`Agent::run_trial`]).
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

/// The CS-QL agent: what it perceives with, how it reacts to a decrease, what it has
/// learned, and the loop's parameters. [`Agent::run_trial`] is the main loop of the
/// paper's Figure 3.
///
/// ```
/// use csql::{Agent, Classify, Lazy, LoopParams, RunSettings, Setup, StrategyKind};
/// use rand::SeedableRng;
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let world = setup.sensed(&settings);
/// let mut agent = Agent::new(
///     Classify::new(&world),
///     Lazy::default(),
///     qlearn::QTable::new(4).unwrap(),
///     LoopParams::from(&settings),
/// );
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let rec = agent.run_trial(&world, setup.world.states()[0], 1, &mut rng);
/// assert!(rec.moves >= 1 && rec.moves <= 100);
/// assert!(agent.perception.representation().len() >= 1);
/// ```
#[derive(Clone, Debug)]
pub struct Agent<P, S> {
    /// How states become rows (CS-QL: [`crate::Classify`]).
    pub perception: P,
    /// What a decrease of V does.
    pub strategy: S,
    /// Q and V of every row.
    pub table: QTable,
    /// Beta, gamma, T, the move cap and the decrease threshold.
    pub params: LoopParams,
    /// What changed since the oracle last looked (never read by the agent itself).
    journal: Journal,
    /// What the loop asks after every update: is the description inconsistent? (The
    /// paper's rule, any decrease, unless [`Agent::with_detector`] says otherwise.)
    detector: RunDetector,
}

/// What an agent changed since the oracle's judge last looked, so that the judge
/// re-examines only that: the rows whose Q values were updated, the rows refined (whose
/// states may now belong elsewhere), and whether the table was reset. Keeping it costs a
/// push per move; the agent never reads it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Journal {
    pub updated: Vec<RowId>,
    pub refined: Vec<RowId>,
    pub reset: bool,
}

impl<P, S> Agent<P, S> {
    /// An agent with a perception, a strategy, a table and the loop's parameters.
    ///
    /// ```
    /// use csql::{Agent, Identified, LoopParams, Never, RunSettings, StrategyKind};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let params = LoopParams::from(&RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1));
    /// let agent = Agent::new(Identified::new(&sensed, vec![0.0; 9]), Never, qlearn::QTable::new(4).unwrap(), params);
    /// assert_eq!(agent.table.rows(), 0);
    /// ```
    pub fn new(perception: P, strategy: S, table: QTable, params: LoopParams) -> Agent<P, S> {
        Agent {
            perception,
            strategy,
            table,
            params,
            journal: Journal::default(),
            detector: RunDetector::default(),
        }
    }

    /// The same agent with another detector of inconsistency.
    ///
    /// ```
    /// use csql::{Agent, DetectorKind, Identified, LoopParams, Never, RateParams, RunDetector, RunSettings, StrategyKind};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let params = LoopParams::from(&RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1));
    /// let agent = Agent::new(Identified::new(&sensed, vec![0.0; 9]), Never, qlearn::QTable::new(4).unwrap(), params)
    ///     .with_detector(RunDetector::new(DetectorKind::Statistical, RateParams::default()));
    /// ```
    pub fn with_detector(mut self, detector: RunDetector) -> Agent<P, S> {
        self.detector = detector;
        self
    }

    /// Hand over the journal and start a new one.
    pub(crate) fn take_journal(&mut self) -> Journal {
        let fresh = Journal {
            updated: Vec::with_capacity(self.journal.updated.capacity()),
            ..Journal::default()
        };
        std::mem::replace(&mut self.journal, fresh)
    }
}

impl<P: Perception, S: Strategy> Agent<P, S> {
    /// Run one trial from `start` until the goal or the move cap (the paper's Figure 3,
    /// with trials; the numbers in the comments are the figure's steps).
    ///
    /// ```
    /// use csql::{Agent, Identified, LoopParams, Never, RunSettings, StrategyKind};
    /// use rand::SeedableRng;
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    /// let mut agent = Agent::new(
    ///     Identified::new(&sensed, vec![1.0; 9]),
    ///     Never,
    ///     qlearn::QTable::new(4).unwrap(),
    ///     LoopParams::from(&settings),
    /// );
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
    /// let rec = agent.run_trial(&sensed, world.states()[2], 1, &mut rng);
    /// // Every classification costs 1 here: the start and each move but the last.
    /// assert_eq!(rec.cost, rec.moves as f64 - if rec.reached_goal { 1.0 } else { 0.0 } + 1.0);
    /// ```
    ///
    /// The world is any [`World`]: a grid map sensed around the robot
    /// ([`mdp::SensedGrid`], whose slippery moves draw from `rng`; without slip nothing is
    /// drawn), or any finite world with priced features.
    pub fn run_trial<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        start: StateId,
        trial: u32,
        rng: &mut R,
    ) -> TrialRecord {
        let Agent {
            perception,
            strategy,
            table,
            params,
            journal,
            detector,
        } = self;
        let mut rec = TrialRecord {
            trial,
            ..TrialRecord::default()
        };
        strategy.start_trial();
        // 1. x <- the start state, descrip(x) <- CLASSIFY(x).
        let mut x = start;
        let (mut row_x, cost) = perception.classify(world, x, table);
        rec.cost += cost;
        let mut random_left = 0u32;
        while rec.moves < params.max_moves {
            // 1./7. a <- select-action(descrip(x)): Boltzmann on its Q values, or
            //    uniformly during the random moves that follow a random refinement.
            let random_move = random_left > 0;
            let a = if random_move {
                random_left -= 1;
                mdp::ActionId(rng.random_range(0..world.num_actions() as u32))
            } else {
                table.boltzmann(row_x, params.temperature, rng)
            };
            // 2. y <- next-state(x, a), r <- reward.
            // 3. descrip(y) <- CLASSIFY(y); the goal ends the trial unclassified.
            let step = world.sample(x, a, rng);
            rec.moves += 1;
            let next = if step.terminated {
                None
            } else {
                let (row_y, cost) =
                    perception.classify_next(world, row_x, a, step.next, table, rng);
                rec.cost += cost;
                Some(row_y)
            };
            // 4./5. Equation 2 for Q(descrip(x), a), then V(descrip(x)).
            let target = next.map_or(Target::Terminal, Target::Bootstrap);
            let q_before = table.q(row_x, a);
            let change = table.update(row_x, a, step.reward, target, params.beta, params.gamma);
            detector.action_updated(
                row_x,
                a,
                table.q(row_x, a) < q_before - params.decrease_threshold,
            );
            journal.updated.push(row_x);
            perception.updated(row_x, a, step.reward, next, table);
            let mut row_y = next;
            // 6. If V(descrip(x)) decreased, descrip(x) is inconsistent (Theorem 2; the
            //    detector may ask for more evidence): the strategy decides. Decreases
            //    during random moves never refine anything.
            let dropped = change.after < change.before - params.decrease_threshold;
            rec.decreases += u32::from(dropped);
            if detector.inconsistent(row_x, change, dropped)
                && !random_move
                && let Reaction::Refine {
                    reset,
                    random_moves,
                } = strategy.on_decrease()
            {
                // Add the next cheapest feature x lacks, valued at the state x was
                // used for (charged).
                if let Some(cost) = perception.refine(world, row_x, x) {
                    rec.cost += cost;
                    rec.refinements += 1;
                    journal.refined.push(row_x);
                    detector.refined(row_x);
                }
                if reset {
                    table.reset();
                    detector.reset();
                    rec.resets += 1;
                    journal.reset = true;
                }
                random_left = random_moves;
                if let Some(current) = row_y {
                    // The refined description may no longer match the next state.
                    let (again, cost) =
                        perception.classify_again(world, row_x, current, step.next, table);
                    rec.cost += cost;
                    row_y = Some(again);
                }
            }

            // 8./9. x <- y, and go on until the goal.
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
}
