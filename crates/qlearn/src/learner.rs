//! Plain Q-learning in trials over any deterministic [`Mdp`], every state its own row.

use std::ops::ControlFlow;

use mdp::{Mdp, StateId};
use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::params::Params;
use crate::table::{QTable, RowId, Target};

/// Where a trial starts.
///
/// Read from a file it is `"uniform"` or `{ fixed = 12 }`.
///
/// ```
/// use qlearn::Start;
/// let s: Start = serde_json::from_str(r#"{"fixed": 3}"#).unwrap();
/// assert_eq!(s, Start::Fixed(mdp::StateId(3)));
/// assert_eq!(serde_json::from_str::<Start>(r#""uniform""#).unwrap(), Start::Uniform);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Start {
    /// A state drawn uniformly from the non-terminal states (the paper's "random empty
    /// state"), one draw per trial.
    Uniform,
    /// Always this state.
    Fixed(StateId),
}

/// How a trial ended.
///
/// ```
/// assert_ne!(qlearn::TrialEnd::Terminated, qlearn::TrialEnd::MoveCap);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum TrialEnd {
    /// A terminal state was reached; the last update used the reward alone.
    Terminated,
    /// The move cap was reached (or the MDP reported a truncation); the last update
    /// bootstrapped from the state reached.
    MoveCap,
    /// [`QLearner::run_steps`] ran out of steps in the middle of the trial; the last
    /// update bootstrapped, as for a move cap.
    StepBudget,
}

/// What one trial did.
///
/// ```
/// use rand::SeedableRng;
/// use qlearn::{Params, QLearner, Start, TrialEnd};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let mut learner = QLearner::new(&world, Params::tan1991(), Start::Uniform).unwrap();
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(0);
/// let trial = learner.trial(&mut rng);
/// assert!(trial.moves >= 1 && trial.moves <= 100);
/// assert_eq!(trial.end == TrialEnd::Terminated, trial.reward == 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Trial {
    /// The trial's number, from 0.
    pub index: u64,
    /// The state it started in.
    pub start: StateId,
    /// The moves made (each one selection, one step and one update).
    pub moves: u32,
    /// The sum of the rewards received (undiscounted).
    pub reward: f64,
    /// How many updates decreased `V` of their row (0 for consistent rows and
    /// non-negative rewards, by Theorem 1).
    pub decreases: u32,
    /// Why the trial ended.
    pub end: TrialEnd,
}

/// The outcome of [`QLearner::run`].
///
/// ```
/// let s = qlearn::RunSummary { trials: 3, moves: 40, stopped: true };
/// assert!(s.stopped);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Trials run in this call.
    pub trials: u64,
    /// Moves made in this call.
    pub moves: u64,
    /// Whether the callback asked to stop (rather than the trial limit being reached).
    pub stopped: bool,
}

/// Plain Q-learning (Figure 1) with Boltzmann selection over an [`Mdp`] in which every
/// state is identified: state `s` uses row `RowId(s.0)` of the table. This is the
/// baseline that CS-QL is compared against.
///
/// Each move of a trial selects an action by [`QTable::boltzmann`] in the current
/// state's row, steps the MDP, and applies [`QTable::update`] with [`Target::Terminal`]
/// if the step terminated and [`Target::Bootstrap`] otherwise, including the last move
/// of a trial cut off by the move cap.
///
/// Random draws, in order: one `rng.random_range(0..n)` at the start of a trial if the
/// start is [`Start::Uniform`] (over the `n` non-terminal states, in id order), then one
/// `rng.random::<f64>()` per move for the Boltzmann selection. Nothing else draws, so
/// the same seed gives the same run.
///
/// The learner is generic over the MDP (pass `&world` to borrow it), so the step call
/// is monomorphised and inlined.
///
/// ```
/// use std::ops::ControlFlow;
/// use rand::SeedableRng;
/// use qlearn::{Params, QLearner, Start};
///
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let oracle = mdp::Oracle::for_grid(&world, 0.9).unwrap();
/// let mut learner = QLearner::new(&world, Params::tan1991(), Start::Uniform).unwrap();
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7);
/// // Learn until every V is optimal, checking at the end of each trial.
/// let summary = learner.run(10_000, &mut rng, |_trial, table| {
///     let done = world.states().iter().all(|&s| {
///         (table.v(qlearn::RowId(s.0)) - oracle.v_star(s)).abs() < 1e-12
///     });
///     if done { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
/// });
/// assert!(summary.stopped);
/// ```
#[derive(Clone, Debug)]
pub struct QLearner<M> {
    mdp: M,
    params: Params,
    /// The states a trial may start in: one for a fixed start.
    starts: Vec<StateId>,
    uniform: bool,
    table: QTable,
    trials: u64,
    moves: u64,
}

impl<M: Mdp> QLearner<M> {
    /// A learner with a zero table of one row per state.
    ///
    /// Fails if the MDP has no actions, has more states than 32-bit row ids can number,
    /// has no non-terminal state, or if a fixed start is out of range or terminal.
    ///
    /// ```
    /// use qlearn::{Error, Params, QLearner, Start};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let goal = world.goal();
    /// let err = QLearner::new(&world, Params::tan1991(), Start::Fixed(goal)).unwrap_err();
    /// assert_eq!(err, Error::StartTerminal { state: goal });
    /// ```
    pub fn new(mdp: M, params: Params, start: Start) -> Result<QLearner<M>, Error> {
        let states = mdp.num_states();
        if u32::try_from(states).is_err() {
            return Err(Error::TooManyStates { states });
        }
        let table = QTable::with_rows(mdp.num_actions(), states)?;
        let starts = match start {
            Start::Uniform => mdp.non_terminal_states(),
            Start::Fixed(s) if s.index() >= states => {
                return Err(Error::StartOutOfRange { state: s, states });
            }
            Start::Fixed(s) if mdp.is_terminal(s) => {
                return Err(Error::StartTerminal { state: s });
            }
            Start::Fixed(s) => vec![s],
        };
        if starts.is_empty() {
            return Err(Error::NoStartState);
        }
        Ok(QLearner {
            mdp,
            params,
            starts,
            uniform: start == Start::Uniform,
            table,
            trials: 0,
            moves: 0,
        })
    }

    /// Run one trial: from a start state until termination or the move cap.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// use qlearn::{Params, QLearner, Start};
    /// let world = mdp::GridWorld::new(&mdp::builtin("open8x8").unwrap());
    /// let mut learner = QLearner::new(&world, Params::tan1991(), Start::Uniform).unwrap();
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let first = learner.trial(&mut rng);
    /// assert_eq!((first.index, first.decreases), (0, 0));
    /// assert_eq!(learner.trial(&mut rng).index, 1);
    /// ```
    pub fn trial<R: Rng + ?Sized>(&mut self, rng: &mut R) -> Trial {
        self.trial_within(self.params.max_moves.get(), TrialEnd::MoveCap, rng)
    }

    /// Run trials until `on_trial`, called after each with the trial and the table,
    /// returns [`ControlFlow::Break`], or until `max_trials` trials have run.
    ///
    /// ```
    /// use std::ops::ControlFlow;
    /// use rand::SeedableRng;
    /// use qlearn::{Params, QLearner, Start};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let mut learner = QLearner::new(&world, Params::tan1991(), Start::Uniform).unwrap();
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let mut moves = 0;
    /// let s = learner.run(5, &mut rng, |t, _| { moves += u64::from(t.moves); ControlFlow::Continue(()) });
    /// assert_eq!((s.trials, s.moves, s.stopped), (5, moves, false));
    /// ```
    pub fn run<R, F>(&mut self, max_trials: u64, rng: &mut R, mut on_trial: F) -> RunSummary
    where
        R: Rng + ?Sized,
        F: FnMut(&Trial, &QTable) -> ControlFlow<()>,
    {
        let mut summary = RunSummary {
            trials: 0,
            moves: 0,
            stopped: false,
        };
        while summary.trials < max_trials {
            let trial = self.trial(rng);
            summary.trials += 1;
            summary.moves += u64::from(trial.moves);
            if on_trial(&trial, &self.table).is_break() {
                summary.stopped = true;
                break;
            }
        }
        summary
    }

    /// Run trials until exactly `steps` moves have been made; the last trial is cut off
    /// where the budget ends ([`TrialEnd::StepBudget`]). Returns the number of trials
    /// started. This is the throughput loop of the benchmark.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// use qlearn::{Params, QLearner, Start};
    /// let world = mdp::GridWorld::new(&mdp::builtin("open8x8").unwrap());
    /// let mut learner = QLearner::new(&world, Params::tan1991(), Start::Uniform).unwrap();
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// learner.run_steps(1000, &mut rng);
    /// assert_eq!(learner.moves(), 1000);
    /// ```
    pub fn run_steps<R: Rng + ?Sized>(&mut self, steps: u64, rng: &mut R) -> u64 {
        let mut left = steps;
        let mut trials = 0;
        let cap = self.params.max_moves.get();
        while left > 0 {
            let (limit, end) = match u32::try_from(left) {
                Ok(l) if l < cap => (l, TrialEnd::StepBudget),
                _ => (cap, TrialEnd::MoveCap),
            };
            left -= u64::from(self.trial_within(limit, end, rng).moves);
            trials += 1;
        }
        trials
    }

    /// One trial of at most `limit` moves; `cut` says why it ends if it hits the limit.
    #[inline]
    fn trial_within<R: Rng + ?Sized>(&mut self, limit: u32, cut: TrialEnd, rng: &mut R) -> Trial {
        let start = if self.uniform {
            self.starts[rng.random_range(0..self.starts.len())]
        } else {
            self.starts[0]
        };
        let Params {
            learning_rate: beta,
            discount: gamma,
            temperature,
            ..
        } = self.params;
        let mut trial = Trial {
            index: self.trials,
            start,
            moves: 0,
            reward: 0.0,
            decreases: 0,
            end: cut,
        };
        let mut s = start;
        loop {
            let row = RowId(s.0);
            let a = self.table.boltzmann(row, temperature, rng);
            let step = self.mdp.step(s, a);
            let target = if step.terminated {
                Target::Terminal
            } else {
                Target::Bootstrap(RowId(step.next.0))
            };
            let change = self.table.update(row, a, step.reward, target, beta, gamma);
            trial.moves += 1;
            trial.reward += step.reward;
            trial.decreases += u32::from(change.decreased());
            if step.terminated {
                trial.end = TrialEnd::Terminated;
                break;
            }
            if step.truncated {
                trial.end = TrialEnd::MoveCap;
                break;
            }
            if trial.moves >= limit {
                break;
            }
            s = step.next;
        }
        self.trials += 1;
        self.moves += u64::from(trial.moves);
        trial
    }

    /// The table: row `RowId(s.0)` belongs to state `s`.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.table().rows(), 9);
    /// ```
    pub fn table(&self) -> &QTable {
        &self.table
    }

    /// The table, to be kept after learning.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.into_table().num_actions(), 4);
    /// ```
    pub fn into_table(self) -> QTable {
        self.table
    }

    /// The row of a state (the identity: every state is identified).
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.row(mdp::StateId(4)), qlearn::RowId(4));
    /// ```
    #[inline]
    pub fn row(&self, s: StateId) -> RowId {
        RowId(s.0)
    }

    /// The MDP.
    ///
    /// ```
    /// use mdp::Mdp;
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.mdp().num_states(), 9);
    /// ```
    pub fn mdp(&self) -> &M {
        &self.mdp
    }

    /// The parameters.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.params().max_moves.get(), 100);
    /// ```
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Trials run so far.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.trials(), 0);
    /// ```
    pub fn trials(&self) -> u64 {
        self.trials
    }

    /// Moves made so far, over all trials.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let l = qlearn::QLearner::new(&world, qlearn::Params::tan1991(), qlearn::Start::Uniform).unwrap();
    /// assert_eq!(l.moves(), 0);
    /// ```
    pub fn moves(&self) -> u64 {
        self.moves
    }
}
