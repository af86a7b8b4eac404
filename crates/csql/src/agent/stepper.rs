//! CS-QL driven one move at a time, for environments without a published model.
//!
//! [`crate::Agent::run_trial`] owns a trial: it draws the start, samples the world's
//! moves and reads features of any state it names. A [`Stepper`] is the same main loop
//! (the same code: the trial is one state machine, which `run_trial` drives with a world)
//! with the world on the caller's side: [`Stepper::act`] asks the caller's sensor for the
//! features CLASSIFY decides to measure (each charged its price) and returns an action;
//! [`Stepper::update`] takes the move's reward, whether it terminated or was truncated,
//! and a sensor of the state reached.
//!
//! # Refining from the state left
//!
//! A refinement gives a description the next cheapest feature it lacks, valued at the
//! state the description was used for (specification 4.3): the state the move has just
//! left. With [`RefineFrom::StateLeft`] (the default, the paper's rule) the stepper asks
//! the sensor for that reading with [`Moment::Left`] during [`Stepper::update`]: a sensor
//! that reads features from an observation (the observation of each step kept until the
//! next update) answers it without a model. A sensor that can only read the present
//! takes [`RefineFrom::NextSensed`]: the feature is added the next time the description
//! is given to a state, valued there (specification 4.9).
//!
//! # Random draws
//!
//! The stepper draws from one generator seeded with the run's seed, in the main loop's
//! order: one draw per [`Stepper::act`] (Boltzmann selection, or a random move). A
//! simulator that draws a trial's start and each move's outcome from the same generator
//! ([`Stepper::rng`]) between those calls makes exactly the draws of `csql::run`, in the
//! same order, and so the same learning, bit for bit (`tests/stepper.rs`).

use std::cell::{Cell, RefCell};

use mdp::{ActionId, Feature, Reading, StateId, Step, World};
use qlearn::QTable;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::agent::main_loop::{Agent, Move, RefineFrom, Trial, TrialRecord};
use crate::agent::strategy::Strategy;
use crate::error::Error;
use crate::perception::classify::Classify;
use crate::perception::representation::Representation;
use crate::perception::rows::Perception;
use crate::perception::sense_less::level::PredictSensing;
use crate::settings::values::RunSettings;

/// Which state a sensor is asked about.
///
/// ```
/// assert_ne!(csql::Moment::Now, csql::Moment::Left);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Moment {
    /// The state the agent is in: in [`Stepper::act`], the state it acts in; in
    /// [`Stepper::update`], the state the move reached.
    Now,
    /// In [`Stepper::update`] only: the state the move left, for the feature a
    /// refinement adds ([`RefineFrom::StateLeft`]).
    Left,
}

/// The caller's sensors: what a feature reads in the state the agent is in, or in the
/// state its last move left.
///
/// Any `FnMut(Moment, Feature) -> Reading` is one.
///
/// ```
/// use csql::{Moment, Sense};
/// let mut s = |at: Moment, f: mdp::Feature| mdp::Reading(if at == Moment::Now { f.0 } else { 0 });
/// assert_eq!(s.read(Moment::Now, mdp::Feature(1)), mdp::Reading(1));
/// ```
pub trait Sense {
    /// What feature `f` (the caller's numbering) reads in the state `at` names: one of
    /// `0..readings` for the feature's number of readings.
    fn read(&mut self, at: Moment, f: Feature) -> Reading;
}

impl<F: FnMut(Moment, Feature) -> Reading> Sense for F {
    fn read(&mut self, at: Moment, f: Feature) -> Reading {
        self(at, f)
    }
}

/// A call of a [`Stepper`] that cannot be made.
///
/// ```
/// let e = csql::StepError::OutOfOrder { called: "update", expected: "act" };
/// assert_eq!(e.to_string(), "update called out of order: act comes next");
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StepError {
    /// `act` and `update` alternate, starting with `act`.
    #[error("{called} called out of order: {expected} comes next")]
    OutOfOrder {
        /// The method called.
        called: &'static str,
        /// The one expected.
        expected: &'static str,
    },
    /// A sensor read a value out of its feature's range.
    #[error("the sensor read {value} for feature {feature}, which reads 0 to {last}")]
    Reading {
        /// The feature (the caller's numbering).
        feature: u32,
        /// The value read.
        value: u32,
        /// Its largest reading.
        last: u32,
    },
    /// A reward that is not a finite number, or larger in size than [`mdp::MAX_REWARD`]
    /// (whose sums could overflow).
    #[error(
        "reward {0:e} is not a finite number of at most 1e200 in size (mdp::MAX_REWARD, so that the values learned from it stay finite)"
    )]
    Reward(f64),
    /// The stepper stopped at an earlier error (its learning may hold a reading that was
    /// never made) and takes no more calls.
    #[error("the agent stopped at an earlier error: {0}")]
    Stopped(String),
}

/// The features a [`Stepper`] senses: a price and a number of readings each.
#[derive(Clone, Debug)]
struct Features {
    /// In the stepper's order (ascending price, ties in the caller's order).
    prices: Vec<f64>,
    readings: Vec<u32>,
    /// The caller's number of each feature, in the stepper's order.
    theirs: Vec<u32>,
    num_actions: usize,
}

/// The caller's environment as a [`World`] the perception senses through: two state ids
/// take turns, the state the agent is in and the state its last move left; reading
/// either asks the caller's sensor. It is never sampled: the caller moves.
struct Live<'a, 's> {
    features: &'a Features,
    now: StateId,
    sense: RefCell<&'s mut dyn Sense>,
    /// The first reading out of range (clamped to 0 so that learning can go on to the
    /// end of the call, which then fails).
    bad: Cell<Option<(u32, u32, u32)>>,
}

impl mdp::Sensors for Live<'_, '_> {
    fn num_features(&self) -> usize {
        self.features.prices.len()
    }
    fn price(&self, f: Feature) -> f64 {
        self.features.prices[f.index()]
    }
    fn read(&self, s: StateId, f: Feature) -> Reading {
        let at = if s == self.now {
            Moment::Now
        } else {
            Moment::Left
        };
        let theirs = self.features.theirs[f.index()];
        let v = self.sense.borrow_mut().read(at, Feature(theirs));
        let n = self.features.readings[f.index()];
        if v.0 < n {
            v
        } else {
            if self.bad.get().is_none() {
                self.bad.set(Some((theirs, v.0, n - 1)));
            }
            Reading(0)
        }
    }
    fn readings(&self, f: Feature) -> u32 {
        self.features.readings[f.index()]
    }
    fn feature_name(&self, f: Feature) -> String {
        self.features.theirs[f.index()].to_string()
    }
    fn reading_name(&self, _f: Feature, v: Reading) -> String {
        v.0.to_string()
    }
}

impl mdp::StochasticMdp for Live<'_, '_> {
    fn num_states(&self) -> usize {
        2
    }
    fn num_actions(&self) -> usize {
        self.features.num_actions
    }
    fn is_terminal(&self, _s: StateId) -> bool {
        false
    }
    fn outcomes(&self, _s: StateId, _a: ActionId, out: &mut Vec<(f64, Step)>) {
        out.clear();
    }
    /// Never called: the caller moves. (A terminal step, should it be.)
    fn sample<R: rand::Rng + ?Sized>(&self, s: StateId, _a: ActionId, _rng: &mut R) -> Step {
        Step {
            next: s,
            reward: 0.0,
            terminated: true,
            truncated: false,
        }
    }
}

impl World for Live<'_, '_> {
    fn states(&self) -> Vec<StateId> {
        vec![StateId(0), StateId(1)]
    }
    fn start_distribution(&self) -> Vec<(f64, StateId)> {
        vec![(1.0, self.now)]
    }
    fn sample_start<R: rand::Rng + ?Sized>(&self, _rng: &mut R) -> StateId {
        self.now
    }
}

/// The caller's sensor as a world whose state `now` is the state the agent is in.
fn live<'a, 's>(features: &'a Features, now: StateId, sense: &'s mut dyn Sense) -> Live<'a, 's> {
    Live {
        features,
        now,
        sense: RefCell::new(sense),
        bad: Cell::new(None),
    }
}

/// CS-QL stepped from outside: the agent of [`crate::run`] (CLASSIFY, a strategy, the
/// same main loop and generator) for an environment the caller moves and senses.
///
/// [`Stepper::act`] and [`Stepper::update`] alternate: `act` classifies the state the
/// agent is in (at the start of a trial; later the state was classified when the move
/// reaching it was updated) and chooses an action; `update` learns from the move's
/// outcome. A trial ends when a move terminates (the goal, never classified) or is
/// truncated (the caller's move cap: the state reached is still classified and
/// bootstrapped from, as in `csql::run`); the next `act` starts another.
///
/// ```
/// use csql::{Moment, RunSettings, Stepper, StrategyKind};
/// use mdp::{Feature, Reading};
/// // A corridor of 4 cells, the goal right of the last; one feature: the position.
/// let settings = RunSettings::tan1991("corridor", StrategyKind::Lazy, 1);
/// let mut agent = Stepper::new(&[1.0], &[4], 2, &settings).unwrap();
/// for _ in 0..30 {
///     let mut pos = 0u32;
///     for moves in 1..=100 {
///         let a = agent.act(&mut |_: Moment, _: Feature| Reading(pos)).unwrap();
///         let next = if a.0 == 1 { pos + 1 } else { pos.saturating_sub(1) };
///         let goal = next == 4;
///         // The state reached, and the state left (for a refinement).
///         let mut sense = |at: Moment, _: Feature| Reading(if at == Moment::Now { next } else { pos });
///         agent.update(if goal { 1.0 } else { 0.0 }, goal, moves == 100, &mut sense).unwrap();
///         if goal { break; }
///         pos = next;
///     }
/// }
/// assert_eq!(agent.trials(), 30);
/// assert!(agent.cost() > 0.0);
/// // Position 3 has a description of its own, and has learned to go right.
/// let at3 = agent.descriptions().iter().position(|d| d == &[(0, 3)]).unwrap();
/// assert_eq!(agent.table().greedy(qlearn::RowId(at3 as u32)), mdp::ActionId(1));
/// ```
pub struct Stepper {
    agent: Agent<Classify, Box<dyn Strategy + Send + Sync>>,
    features: Features,
    rng: Xoshiro256PlusPlus,
    /// The trial in progress, if any.
    trial: Option<Trial>,
    /// The move chosen by `act`, until `update`.
    chosen: Option<Move>,
    /// Which of the two state ids names the state the agent is in.
    here: u32,
    trials: u32,
    moves: u64,
    /// The cost of the trials that ended, summed trial by trial as `csql::run` sums it.
    closed_cost: f64,
    /// The last trial ended.
    last: Option<TrialRecord>,
    stopped: Option<String>,
}

impl std::fmt::Debug for Stepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Stepper")
            .field("trials", &self.trials)
            .field("moves", &self.moves)
            .field("cost", &self.cost())
            .field("descriptions", &self.agent.perception.rows())
            .finish_non_exhaustive()
    }
}

impl Stepper {
    /// A stepper for features of prices `prices` reading `readings[i]` values each
    /// (`0..readings[i]`), in an environment of `num_actions` actions, learning as
    /// `settings` say: the strategy and its random moves, beta, gamma, T, the decrease
    /// threshold, the seed, and the CS-QL extensions that concern the learner (matching,
    /// `confirm_new`, `reads`, the detector). Settings that describe a world (the
    /// `[world]` table) or another learner (`learner`, `predict_sensing`, `memory`) are
    /// refused; those of a run (map, trial cap, tolerance) are not used. Q and V start at
    /// 0 ([`Stepper::starting_at`] for worlds of negative rewards).
    ///
    /// Features are numbered in the caller's order; the stepper takes them by ascending
    /// price (ties in the caller's order), the order of "the next cheapest feature".
    /// There are at most [`mdp::MAX_ACTIONS`] actions and [`mdp::MAX_FEATURES`] features,
    /// as in a world; a feature may read any `u32` (CLASSIFY's memory follows what it
    /// senses, see [`crate::CACHE_MAX_READINGS`]).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Eager, 1);
    /// assert!(csql::Stepper::new(&[2.0, 1.0], &[3, 2], 4, &s).is_ok());
    /// assert!(csql::Stepper::new(&[1.0], &[3, 2], 4, &s).is_err());
    /// assert!(csql::Stepper::new(&[1.0], &[3], 65, &s).is_err());
    /// assert!(csql::Stepper::new(&[1.0], &[u32::MAX], 4, &s).is_ok());
    /// ```
    pub fn new(
        prices: &[f64],
        readings: &[u32],
        num_actions: usize,
        settings: &RunSettings,
    ) -> Result<Stepper, Error> {
        let invalid =
            |value: String, expected: &'static str| Error::InvalidSetting { value, expected };
        // Sizes first, before anything is built: as many as a world may have.
        if num_actions > mdp::MAX_ACTIONS {
            return Err(invalid(
                format!("{num_actions} actions"),
                "at most 64 actions (mdp::MAX_ACTIONS, as in a world)",
            ));
        }
        if prices.len() > mdp::MAX_FEATURES || readings.len() > mdp::MAX_FEATURES {
            return Err(invalid(
                format!("{} features", prices.len().max(readings.len())),
                "at most 4096 features (mdp::MAX_FEATURES, as in a world)",
            ));
        }
        if prices.len() != readings.len() {
            return Err(invalid(
                format!("{} prices for {} features", prices.len(), readings.len()),
                "one price and one number of readings per feature",
            ));
        }
        if let Some(p) = prices
            .iter()
            .find(|p| !(p.is_finite() && (0.0..=mdp::MAX_PRICE).contains(*p)))
        {
            return Err(invalid(
                format!("price {p:e}"),
                "a finite price of at least 0 and at most 1e200 (mdp::MAX_PRICE, so that the total cost stays finite)",
            ));
        }
        if let Some(n) = readings.iter().find(|&&n| n == 0) {
            return Err(invalid(
                format!("{n} readings"),
                "at least one reading per feature",
            ));
        }
        // Every read of the settings is here.
        settings.validate()?;
        let refuse = |what: &str, why: &'static str| Error::Conflict {
            first: "a step-driven agent".to_string(),
            second: what.to_string(),
            why,
        };
        let Some(q) = settings.cs_ql() else {
            return Err(refuse("learner", "it is CS-QL"));
        };
        if q.predict_sensing != PredictSensing::Off || q.extensions.memory > 0 {
            return Err(refuse(
                "predict_sensing or memory",
                "it senses every state it classifies, without history",
            ));
        }
        if settings.world != crate::settings::extensions::WorldExtras::default() {
            return Err(refuse(
                "[world] settings",
                "they describe a world; the agent senses the caller's",
            ));
        }
        let mut order: Vec<usize> = (0..prices.len()).collect();
        order.sort_by(|&a, &b| prices[a].total_cmp(&prices[b]));
        let features = Features {
            prices: order.iter().map(|&i| prices[i]).collect(),
            readings: order.iter().map(|&i| readings[i]).collect(),
            theirs: order.iter().map(|&i| i as u32).collect(),
            num_actions,
        };
        let table = QTable::new(num_actions)
            .map_err(|_| invalid(format!("{num_actions} actions"), "at least one action"))?;
        let mut nothing = |_: Moment, _: Feature| Reading(0);
        let probe = live(&features, StateId(0), &mut nothing);
        let classify = Classify::new(&probe).with_extensions(&q.extensions);
        let agent = crate::agent::main_loop::agent_of(
            classify,
            q.strategy.build(q.random_moves),
            table,
            settings,
        );
        Ok(Stepper {
            agent,
            features,
            rng: Xoshiro256PlusPlus::seed_from_u64(settings.seed),
            trial: None,
            chosen: None,
            here: 0,
            trials: 0,
            moves: 0,
            closed_cost: 0.0,
            last: None,
            stopped: None,
        })
    }

    /// The same stepper with Q and V starting at `value` (as `csql::run` starts them at
    /// [`crate::value_floor`] of its world: 0 without negative rewards); before the
    /// first `act` only.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("taxi", csql::StrategyKind::Lazy, 1);
    /// let agent = csql::Stepper::new(&[1.0], &[5], 6, &s).unwrap().starting_at(-10.0).unwrap();
    /// assert!(csql::Stepper::new(&[1.0], &[5], 6, &s).unwrap().starting_at(f64::NAN).is_err());
    /// ```
    pub fn starting_at(mut self, value: f64) -> Result<Stepper, Error> {
        self.agent.table = QTable::new(self.features.num_actions)
            .and_then(|t| t.starting_at(value))
            .map_err(|_| Error::InvalidSetting {
                value: value.to_string(),
                expected: "a finite starting value of Q and V",
            })?;
        Ok(self)
    }

    /// The same stepper refining from where `from` says ([`RefineFrom::StateLeft`], the
    /// paper's rule, by default).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// let agent = csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().refining_from(csql::RefineFrom::NextSensed);
    /// assert_eq!(agent.refine_from(), csql::RefineFrom::NextSensed);
    /// ```
    pub fn refining_from(mut self, from: RefineFrom) -> Stepper {
        self.agent = self.agent.refining_from(from);
        self
    }

    /// Where refinements read their new feature.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().refine_from(), csql::RefineFrom::StateLeft);
    /// ```
    pub fn refine_from(&self) -> RefineFrom {
        self.agent.refine_from()
    }

    fn check(&self, called: &'static str, acting: bool) -> Result<(), StepError> {
        if let Some(why) = &self.stopped {
            return Err(StepError::Stopped(why.clone()));
        }
        match (acting, self.chosen.is_some()) {
            (true, true) => Err(StepError::OutOfOrder {
                called,
                expected: "update",
            }),
            (false, false) => Err(StepError::OutOfOrder {
                called,
                expected: "act",
            }),
            _ => Ok(()),
        }
    }

    /// The state the agent is in: classify it if a trial starts here (asking `sense` for
    /// what CLASSIFY measures, with [`Moment::Now`], each charged), and choose an action
    /// (one draw of the generator).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// let mut agent = csql::Stepper::new(&[1.0], &[2], 3, &s).unwrap();
    /// let a = agent.act(&mut |_: csql::Moment, _: mdp::Feature| mdp::Reading(1)).unwrap();
    /// assert!(a.0 < 3);
    /// // The first classification makes the empty description, measuring nothing.
    /// assert_eq!(agent.cost(), 0.0);
    /// // Acting twice without an update is refused.
    /// assert!(agent.act(&mut |_: csql::Moment, _: mdp::Feature| mdp::Reading(1)).is_err());
    /// ```
    pub fn act(&mut self, sense: &mut dyn Sense) -> Result<ActionId, StepError> {
        self.check("act", true)?;
        let mut t = match self.trial.take() {
            Some(t) => t,
            None => {
                self.trials += 1;
                let live = live(&self.features, StateId(self.here), sense);
                let t = self
                    .agent
                    .begin_trial(&live, StateId(self.here), self.trials);
                let bad = live.bad.get();
                self.fail_on(bad)?;
                t
            }
        };
        let m = self.agent.choose(&mut t, &mut self.rng);
        self.trial = Some(t);
        self.chosen = Some(m);
        Ok(m.action)
    }

    /// The outcome of the action `act` returned: its reward, whether it terminated (the
    /// state reached is not classified: the goal) and whether it was truncated (the trial
    /// ends after the state reached is classified and learned from). `sense` reads the
    /// state reached ([`Moment::Now`]) and, for a refinement under
    /// [`RefineFrom::StateLeft`], the state left ([`Moment::Left`]); it is asked only for
    /// what the agent measures, each read charged.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// let mut agent = csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap();
    /// let mut sense = |_: csql::Moment, _: mdp::Feature| mdp::Reading(0);
    /// assert!(agent.update(0.0, false, false, &mut sense).is_err()); // act comes first
    /// agent.act(&mut sense).unwrap();
    /// agent.update(1.0, true, false, &mut sense).unwrap();
    /// assert_eq!(agent.last_trial().unwrap().reached_goal, true);
    /// ```
    pub fn update(
        &mut self,
        reward: f64,
        terminated: bool,
        truncated: bool,
        sense: &mut dyn Sense,
    ) -> Result<(), StepError> {
        self.check("update", false)?;
        if !(reward.is_finite() && reward.abs() <= mdp::MAX_REWARD) {
            return Err(StepError::Reward(reward));
        }
        let (Some(mut t), Some(m)) = (self.trial.take(), self.chosen.take()) else {
            return Err(StepError::OutOfOrder {
                called: "update",
                expected: "act",
            });
        };
        let next = 1 - self.here;
        let step = Step {
            next: StateId(next),
            reward,
            terminated,
            truncated,
        };
        let live = live(&self.features, StateId(next), sense);
        self.agent.observe(&mut t, &live, m, step, &mut self.rng);
        let bad = live.bad.get();
        // Nobody judges a stepper: what the journal would tell a judge is dropped.
        self.agent.clear_journal();
        self.here = next;
        self.moves += 1;
        if t.over {
            self.closed_cost += t.rec.cost;
            self.last = Some(t.rec);
        } else {
            self.trial = Some(t);
        }
        self.fail_on(bad)
    }

    fn fail_on(&mut self, bad: Option<(u32, u32, u32)>) -> Result<(), StepError> {
        match bad {
            None => Ok(()),
            Some((feature, value, last)) => {
                let e = StepError::Reading {
                    feature,
                    value,
                    last,
                };
                self.stopped = Some(e.to_string());
                Err(e)
            }
        }
    }

    /// Stop the stepper: every later call fails with [`StepError::Stopped`] and `why`
    /// (for a driver whose sensor failed in a call: the learning then holds a reading
    /// that was never made).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// let mut agent = csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap();
    /// agent.stop("the sensor failed".into());
    /// let e = agent.act(&mut |_: csql::Moment, _: mdp::Feature| mdp::Reading(0)).unwrap_err();
    /// assert!(e.to_string().contains("the sensor failed"));
    /// ```
    pub fn stop(&mut self, why: String) {
        self.stopped.get_or_insert(why);
    }

    /// Whether an action awaits its [`Stepper::update`] (`act` was called last).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// let mut agent = csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap();
    /// assert!(!agent.acted());
    /// agent.act(&mut |_: csql::Moment, _: mdp::Feature| mdp::Reading(0)).unwrap();
    /// assert!(agent.acted());
    /// ```
    pub fn acted(&self) -> bool {
        self.chosen.is_some()
    }

    /// Why the stepper stopped, if it did ([`Stepper::stop`], or a reading out of range).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().stopped(), None);
    /// ```
    pub fn stopped(&self) -> Option<&str> {
        self.stopped.as_deref()
    }

    /// The generator the stepper draws from, for a simulator that draws its starts and
    /// outcomes from the same stream (as `csql::run` does).
    ///
    /// ```
    /// use rand::RngExt;
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// let mut agent = csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap();
    /// let _: u32 = agent.rng().random_range(0..10);
    /// ```
    pub fn rng(&mut self) -> &mut Xoshiro256PlusPlus {
        &mut self.rng
    }

    /// Trials started.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().trials(), 0);
    /// ```
    pub fn trials(&self) -> u32 {
        self.trials
    }

    /// Moves learned from.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().moves(), 0);
    /// ```
    pub fn moves(&self) -> u64 {
        self.moves
    }

    /// Sensing cost charged so far (the trials ended, summed as `csql::run` sums them,
    /// then the trial in progress).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().cost(), 0.0);
    /// ```
    pub fn cost(&self) -> f64 {
        match self.trial {
            Some(t) => self.closed_cost + t.rec.cost,
            None => self.closed_cost,
        }
    }

    /// What happened in the trial in progress so far (`None` between trials).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().current_trial().is_none());
    /// ```
    pub fn current_trial(&self) -> Option<TrialRecord> {
        self.trial.map(|t| t.rec)
    }

    /// What happened in the last trial that ended.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().last_trial().is_none());
    /// ```
    pub fn last_trial(&self) -> Option<TrialRecord> {
        self.last
    }

    /// The descriptions, in id order (a description's id is its row of the table): each
    /// a list of (feature, value), features in the caller's numbering, in the order they
    /// were added.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().descriptions().is_empty());
    /// ```
    pub fn descriptions(&self) -> Vec<Vec<(u32, u32)>> {
        self.representation()
            .iter()
            .map(|(_, d)| {
                d.features()
                    .map(|(f, v)| (self.features.theirs[f.index()], v.0))
                    .collect()
            })
            .collect()
    }

    /// The representation, in the stepper's feature order (ascending price: the caller's
    /// order when the prices are already ascending).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().representation().is_empty());
    /// ```
    pub fn representation(&self) -> &Representation {
        self.agent.perception.representation()
    }

    /// Q and V of every description (row `i` is description `i`).
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("any", csql::StrategyKind::Lazy, 1);
    /// assert_eq!(csql::Stepper::new(&[1.0], &[2], 2, &s).unwrap().table().rows(), 0);
    /// ```
    pub fn table(&self) -> &QTable {
        &self.agent.table
    }
}
