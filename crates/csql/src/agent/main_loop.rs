//! The main loop of CS-QL (the paper's Figure 3), organised in trials.
//!
//! The loop is generic over how states become table rows ([`Perception`]) and over how a
//! decrease is handled ([`Strategy`]). CS-QL is the loop with [`crate::Classify`] and one
//! of the four strategies; the reference points of the paper's discussion are the same
//! loop with a fixed perception and a strategy that never refines. A run's agent is made
//! here from its settings, with its table started at [`value_floor`].
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
//! # A state machine
//!
//! A trial is a state machine: begin (step 1), choose (steps 1 and 7), observe a move's
//! outcome (steps 2 to 9). [`Agent::run_trial`] drives it with a world, sampling each
//! outcome between choosing and observing and marking the move that reaches the move cap
//! truncated; [`crate::Stepper`] lets a caller drive it with an environment of its own.
//!
//! # Random draws, in order
//!
//! Per trial: one `random_range(0..n)` for the start state (drawn by the caller of
//! `run_trial`). Per move: one uniform `f64` for Boltzmann selection, or one
//! `random_range(0..4)` for a random move, then whatever the world's sample draws (slip).

use mdp::{ActionId, StateId, World};
use qlearn::{QTable, RowId, Target};
use rand::{Rng, RngExt};
use serde::Serialize;

use crate::agent::detector::{Detector, RunDetector};
use crate::agent::strategy::{Reaction, Strategy};
use crate::observe::{KeepTrace, Observer, told_to_stop};
use crate::perception::rows::Perception;
use crate::settings::values::RunSettings;

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

impl From<&RunSettings> for LoopParams {
    fn from(settings: &RunSettings) -> LoopParams {
        LoopParams {
            beta: settings.beta,
            gamma: settings.gamma,
            temperature: settings.temperature,
            max_moves: settings.max_moves.get(),
            decrease_threshold: settings.decrease_threshold.get(),
        }
    }
}

/// The agent of a run: `perception`, `strategy` and `table` with the run's loop
/// parameters and CS-QL's detector (the paper's for a baseline).
pub(crate) fn agent_of<P, S>(
    perception: P,
    strategy: S,
    table: qlearn::QTable,
    settings: &RunSettings,
) -> Agent<P, S> {
    let extensions = settings.extensions();
    Agent::new(perception, strategy, table, LoopParams::from(settings))
        .with_detector(RunDetector::new(extensions.detector, extensions.rate))
}

/// Where every run starts Q and V: `min(0, r*) / (1 - gamma)`, with `r*` the least, over
/// the states a trial may visit, of the best reward an action can surely get there (the
/// largest over actions of the smallest reward among the action's outcomes): the value of
/// earning the worst state's best reward forever. Rounded down until
/// `r* + gamma * floor >= floor` holds in floating point too. 0 in worlds without
/// negative rewards, and on every grid map (docs/specification.md, 1.11).
///
/// From there, in a deterministic world whose descriptions are homomorphic, V never
/// decreases: an action not yet tried keeps its row at the floor, and once the best one
/// of a state is tried its target `r + gamma V` is at least the floor. Actions that pay
/// the step penalty keep the floor exactly (`-1 + 0.9 * -10 = -10`), as untried ones do,
/// so Boltzmann selection still explores them evenly, as it does in the paper's world.
///
/// ```
/// let taxi = mdp::builtin_world("taxi", &Default::default()).unwrap();
/// let f = csql::value_floor(&taxi, 0.9);
/// assert!(f <= -10.0 && f > -10.0 - 1e-9); // -1 per step, forever
/// assert!(-1.0 + 0.9 * f >= f);
/// let lake = mdp::builtin_world("frozenlake4x4", &Default::default()).unwrap();
/// assert_eq!(csql::value_floor(&lake, 0.9), 0.0);
/// ```
pub fn value_floor<W: World + ?Sized>(world: &W, gamma: f64) -> f64 {
    let mut out = Vec::new();
    let r_star = world
        .states()
        .into_iter()
        .map(|s| {
            (0..world.num_actions() as u32)
                .map(|a| {
                    world.outcomes(s, ActionId(a), &mut out);
                    out.iter().map(|o| o.1.reward).fold(f64::INFINITY, f64::min)
                })
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .fold(0.0, f64::min);
    if r_star >= 0.0 {
        return 0.0;
    }
    let mut floor = r_star / (1.0 - gamma);
    // Rounding can leave `r* + gamma * floor` a unit in the last place below `floor`,
    // which would read as a decrease: step down until the floor holds in floating point
    // too (rounding is monotone, so every target of a state's best action then holds it).
    while r_star + gamma * floor < floor {
        floor = floor.next_down();
    }
    floor
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
    /// Where a refinement reads its new feature's value (the paper's rule by default).
    refine_from: RefineFrom,
    /// Rows waiting for their refinement ([`RefineFrom::NextSensed`] only).
    waiting: Vec<RowId>,
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
            refine_from: RefineFrom::StateLeft,
            waiting: Vec::new(),
        }
    }

    /// The same agent reading a refinement's new feature where `from` says (the paper's
    /// [`RefineFrom::StateLeft`] by default).
    ///
    /// ```
    /// use csql::{Agent, Identified, LoopParams, Never, RefineFrom, RunSettings, StrategyKind};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let params = LoopParams::from(&RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1));
    /// let agent = Agent::new(Identified::new(&sensed, vec![0.0; 9]), Never, qlearn::QTable::new(4).unwrap(), params)
    ///     .refining_from(RefineFrom::NextSensed);
    /// assert_eq!(agent.refine_from(), RefineFrom::NextSensed);
    /// ```
    pub fn refining_from(mut self, from: RefineFrom) -> Agent<P, S> {
        self.refine_from = from;
        self
    }

    /// Where a refinement reads its new feature's value.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let params = csql::LoopParams::from(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1));
    /// let agent = csql::Agent::new(csql::Identified::new(&sensed, vec![0.0; 9]), csql::Never, qlearn::QTable::new(4).unwrap(), params);
    /// assert_eq!(agent.refine_from(), csql::RefineFrom::StateLeft);
    /// ```
    pub fn refine_from(&self) -> RefineFrom {
        self.refine_from
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

    /// Empty the journal, keeping its room (for an agent no judge follows).
    pub(crate) fn clear_journal(&mut self) {
        self.journal.updated.clear();
        self.journal.refined.clear();
        self.journal.reset = false;
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

/// Where a refinement reads the value of the feature it adds to a description.
///
/// ```
/// assert_eq!(csql::RefineFrom::default(), csql::RefineFrom::StateLeft);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RefineFrom {
    /// The paper's rule: on the state the description was used for, which the agent has
    /// just left (a world with a model can still read it; so can a sensor that reads an
    /// observation kept from that step).
    #[default]
    StateLeft,
    /// For sensors that read only the present: the refinement is decided at once (the
    /// strategy's reset and random moves take effect at once) and the feature is added
    /// the next time a classification gives the description, valued at that state
    /// (charged), which then matches the refined description by construction; no
    /// classification is repeated. A description waiting for its feature waits once,
    /// however many decreases it shows meanwhile (specification 4.9).
    NextSensed,
}

/// A trial in progress: the main loop of the paper's Figure 3 as a state machine that the
/// caller drives one move at a time ([`Agent::run_trial`] drives it with a world; a
/// [`crate::Stepper`] with the caller's environment).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Trial {
    /// The state the agent is in, as the world it senses through names it.
    pub(crate) state: StateId,
    /// Its row.
    pub(crate) row: RowId,
    /// Random moves left (the random strategy).
    random_left: u32,
    /// What happened so far.
    pub(crate) rec: TrialRecord,
    /// Whether the trial has ended (at the goal, or cut by the caller).
    pub(crate) over: bool,
}

/// A move chosen by [`Agent::choose`], until its outcome is observed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Move {
    pub(crate) action: ActionId,
    /// A uniformly drawn move of the random strategy: its decreases refine nothing.
    random: bool,
}

impl Trial {
    /// x <- y (row `next`, `None` at the goal), and go on until the goal or the cap.
    fn move_on(&mut self, next: Option<RowId>, step: mdp::Step) {
        match next {
            None => {
                self.rec.reached_goal = true;
                self.over = true;
            }
            Some(r) => {
                self.state = step.next;
                self.row = r;
                self.over = step.truncated;
            }
        }
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
    /// drawn), or any finite world with priced features. The trial is the state machine a
    /// [`crate::Stepper`] exposes, driven by the world: choose, sample the world's outcome
    /// from the same generator, observe it, until the goal or the move cap.
    pub fn run_trial<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        start: StateId,
        trial: u32,
        rng: &mut R,
    ) -> TrialRecord {
        self.run_trial_observed(world, start, trial, rng, &mut KeepTrace)
    }

    /// [`Agent::run_trial`], asking `observer` every [`crate::STOP_CHECK_MOVES`] moves whether
    /// to go on ([`Observer::keep_going`]); a no cuts the trial there, as the move cap
    /// would.
    pub(crate) fn run_trial_observed<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        start: StateId,
        trial: u32,
        rng: &mut R,
        observer: &mut dyn Observer,
    ) -> TrialRecord {
        let mut t = self.begin_trial(world, start, trial);
        while !t.over {
            let m = self.choose(&mut t, rng);
            let mut step = world.sample(t.state, m.action, rng);
            // The move cap, or a stop, cuts the trial; it does not change the target.
            let moves = t.rec.moves + 1;
            step.truncated |= moves >= self.params.max_moves || told_to_stop(observer, moves);
            self.observe(&mut t, world, m, step, rng);
        }
        t.rec
    }

    /// Start a trial in `start`: the paper's step 1, `descrip(x) <- CLASSIFY(x)`
    /// (charged).
    pub(crate) fn begin_trial<W: World + ?Sized>(
        &mut self,
        world: &W,
        start: StateId,
        trial: u32,
    ) -> Trial {
        self.strategy.start_trial();
        let mut rec = TrialRecord {
            trial,
            ..TrialRecord::default()
        };
        let (row, cost) = self.perception.classify(world, start, &mut self.table);
        rec.cost += cost;
        let mut t = Trial {
            state: start,
            row,
            random_left: 0,
            rec,
            over: self.params.max_moves == 0,
        };
        self.settle(world, &mut t.rec, row, start);
        t
    }

    /// Steps 1 and 7: `a <- select-action(descrip(x))`, Boltzmann on its Q values, or
    /// uniformly during the random moves that follow a random refinement (one draw from
    /// `rng` either way).
    pub(crate) fn choose<R: Rng + ?Sized>(&mut self, t: &mut Trial, rng: &mut R) -> Move {
        let random = t.random_left > 0;
        let action = if random {
            t.random_left -= 1;
            ActionId(rng.random_range(0..self.table.num_actions() as u32))
        } else {
            self.table.boltzmann(t.row, self.params.temperature, rng)
        };
        Move { action, random }
    }

    /// Steps 2 to 9 for the outcome `step` of move `m`: classify the state reached
    /// (unless the move terminated: the goal is never classified), update Q and V, let
    /// the strategy react to a decrease, and carry on from the state reached. The trial
    /// is over at the goal or when `step.truncated` (the move cap, or the caller's).
    pub(crate) fn observe<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        t: &mut Trial,
        world: &W,
        m: Move,
        step: mdp::Step,
        rng: &mut R,
    ) {
        let a = m.action;
        let (x, row_x) = (t.state, t.row);
        t.rec.moves += 1;
        // 3. descrip(y) <- CLASSIFY(y); the goal ends the trial unclassified.
        let next = if step.terminated {
            None
        } else {
            let (row_y, cost) =
                self.perception
                    .classify_next(world, row_x, a, step.next, &mut self.table, rng);
            t.rec.cost += cost;
            self.settle(world, &mut t.rec, row_y, step.next);
            Some(row_y)
        };
        let Agent {
            perception,
            strategy,
            table,
            params,
            journal,
            detector,
            refine_from,
            waiting,
        } = self;
        let rec = &mut t.rec;
        if !perception.learns_from_move(next.is_none()) {
            // A description only guessed: nothing to learn from this move.
            t.move_on(next, step);
            return;
        }
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
            && !m.random
            && let Reaction::Refine {
                reset,
                random_moves,
            } = strategy.on_decrease()
        {
            // Add the next cheapest feature x lacks, valued at the state x was used for
            // (charged); or, from a sensor of the present only, at the next state
            // given the description (which may be the state reached).
            let valued_at = match refine_from {
                RefineFrom::StateLeft => Some(x),
                RefineFrom::NextSensed if next == Some(row_x) => Some(step.next),
                RefineFrom::NextSensed => {
                    if !waiting.contains(&row_x) {
                        waiting.push(row_x);
                    }
                    None
                }
            };
            if let Some(s) = valued_at
                && let Some(cost) = perception.refine(world, row_x, s)
            {
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
            t.random_left = random_moves;
            if *refine_from == RefineFrom::StateLeft
                && let Some(current) = row_y
            {
                // The refined description may no longer match the next state.
                let (again, cost) =
                    perception.classify_again(world, row_x, current, step.next, table);
                rec.cost += cost;
                row_y = Some(again);
            }
        }
        // 8./9. x <- y, and go on until the goal.
        t.move_on(row_y, step);
    }

    /// A description waiting for its feature ([`RefineFrom::NextSensed`]) that state `s`
    /// was just given gets it now, valued at `s` (charged).
    fn settle<W: World + ?Sized>(
        &mut self,
        world: &W,
        rec: &mut TrialRecord,
        row: RowId,
        s: StateId,
    ) {
        if self.waiting.is_empty() {
            return;
        }
        if let Some(i) = self.waiting.iter().position(|&w| w == row) {
            self.waiting.swap_remove(i);
            if let Some(cost) = self.perception.refine(world, row, s) {
                rec.cost += cost;
                rec.refinements += 1;
                self.journal.refined.push(row);
                self.detector.refined(row);
            }
        }
    }
}
