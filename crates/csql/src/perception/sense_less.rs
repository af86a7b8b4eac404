//! Sensing less: predict the next description instead of measuring it (off by default).
//!
//! The paper charges every measurement and leaves a "task-dependent world model (e.g., a
//! reduced map)" built from the learned representation as future work. In a
//! deterministic world most of CLASSIFY's measurements after a move can be predicted from
//! the description the robot left and the action it took. The levels, never mixed in a
//! report (the setting `predict_sensing`, [`PredictSensing`]):
//!
//! | level | what the agent knows | type |
//! |---|---|---|
//! | `off` | nothing: every next state is classified (the paper's procedure) | [`crate::Classify`] alone |
//! | `learned` | a model learned on the way: (description, action) -> next description | [`Predicting::learned`], [`TransitionModel`] |
//! | `motion` | the learned model, and how its moves shift its view (dead reckoning) | [`Predicting::motion`] |
//! | `weighed` | the model's frequencies of next descriptions, weighed against a price in reward units (also in stochastic worlds) | [`Predicting::weighed`] |
//!
//! The weighed level is described in its own module (`sense_less/weighing.rs`, specification
//! 6.14): what follows describes the learned and motion levels, whose rules it shares
//! where it says so.
//!
//! # The learned model
//!
//! [`TransitionModel`] counts, for each description and action, the next description
//! measured. A transition is *trusted* once it has been measured
//! [`PredictionParams::confirmations`] times in a row with the same answer and never with
//! another one. When the agent leaves a description by a trusted transition it does not
//! classify the next state: it takes the predicted description, uncharged. It still
//! re-checks (classifies, charged) with probability [`PredictionParams::recheck`], and always
//! after [`PredictionParams::max_skips`] unmeasured uses in a row. A re-check that disagrees
//! marks the transition as not deterministic: it is never trusted again until one of its
//! two descriptions is refined.
//!
//! The model is kept as the representation changes. A new description takes states that
//! matched no description, so it invalidates nothing. A refinement of description `d`
//! moves some of `d`'s states out of it, so it invalidates the transitions that leave `d`
//! and those that lead to `d`, and no other.
//!
//! # The bound on wrong predictions
//!
//! No transition is ever used more than `max_skips` times in a row without a
//! measurement. So a wrong prediction of a transition is followed, within `max_skips`
//! uses of that transition, by a measured use, and the Q table receives at most
//! `max_skips` updates from one run of unmeasured uses (of which some may be wrong).
//! When that measurement disagrees with the model, the transition is distrusted for
//! good (until a refinement invalidates it). The oracle counts the wrong predictions
//! from outside the learner (without charging, never shown to it) in
//! [`PredictionStats`]: the run wraps the perception in a measuring wrapper
//! (`audit.rs`) that looks up the true description of every state reached unmeasured;
//! `longest_wrong_run <= max_skips` is the bound, checked in this module's tests and on
//! whole runs in `tests/predict.rs`. A measurement that agrees does not prove a
//! transition right for all its states: a description whose states lead to different
//! descriptions may be measured on one that agrees. Such a transition is measured again
//! at least every `max_skips` uses, and distrusted at the first disagreement.
//!
//! # The motion prior
//!
//! At the `motion` level the agent also knows that after a move that was not blocked a
//! cell sensed at offset `(dx, dy)` lies at `(dx - 1, dy)` (for a move right). It keeps
//! the cells it sensed in the last [`PredictionParams::memory_moves`] moves, placed by dead
//! reckoning from the start of the trial, and a measurement CLASSIFY asks for a cell it
//! remembers is free. It knows whether a move was blocked only when it remembers the cell
//! it moved towards; otherwise it forgets everything and starts over from where it is.
//! CLASSIFY chooses the same features either way, so the learned representation does not
//! change; only the charge does. This is prior knowledge the paper's agent does not
//! have, and the motion level is reported apart from the learned one.
//!
//! # Navigation after learning
//!
//! [`crate::navigate`]: the descriptions and the model form a reduced map; the agent
//! localises once (CLASSIFY, charged) and then follows its greedy policy on the graph,
//! measuring only where the model does not trust the transition, or to verify it with
//! probability [`PredictionParams::verify`] (and after `max_skips` unmeasured uses).

pub(crate) mod level;
pub(crate) mod model;
mod reckoning;
mod weighing;

use cslearn::{FeatureId, Sensor, Value};
use mdp::{
    Action, ActionId, Feature, FeatureSpace, GridWorld, Reading, SensorNoise, StateId, World,
};
use qlearn::{QTable, RowId};
use rand::{Rng, RngExt};
use serde::Serialize;

use self::level::{PredictSensing, PredictionParams};
use self::model::TransitionModel;
use self::reckoning::{Memory, charge};
use crate::perception::classify::Classify;
use crate::perception::representation::DescriptionId;
use crate::perception::rows::Perception;
use crate::perception::tree::StateTree;
use crate::perception::view::{Describes, Sees};

/// What prediction did in a run (the JSON's `prediction`, present only when
/// `predict_sensing` is not `off`). The last two figures are the oracle's, counted by the
/// run's measuring, outside the learner: it looks up the true description of every state
/// reached unmeasured, without charging ([`Predicting::stats`] leaves them 0).
///
/// ```
/// let s = csql::PredictionStats::default();
/// assert_eq!(s.skipped + s.rechecks, 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct PredictionStats {
    /// Classifications skipped (the next description predicted, uncharged).
    pub skipped: u64,
    /// Trusted transitions measured anyway (charged).
    pub rechecks: u64,
    /// Re-checks that found the model wrong (the transition is distrusted).
    pub caught: u64,
    /// Classifications skipped whose prediction was wrong (the oracle's count).
    pub wrong: u64,
    /// The most wrong predictions of one transition between two of its measurements
    /// (the guarantee: at most `max_skips`).
    pub longest_wrong_run: u32,
    /// States the weighed level resolved by measuring only what tells the likely
    /// descriptions apart (charged, and absent from the JSON when 0).
    #[serde(skip_serializing_if = "is_zero")]
    pub narrowed: u64,
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}

/// CLASSIFY with a learned transition model (and, at the motion level, a memory placed
/// by dead reckoning): the perception of a run whose `predict_sensing` is not `off`.
/// It changes what is charged and which states are measured, never how CLASSIFY chooses
/// its features.
///
/// ```
/// use csql::{Agent, Classify, LoopParams, Predicting, PredictionParams, RunSettings, Setup, StrategyKind};
/// use rand::SeedableRng;
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let world = setup.sensed(&settings);
/// let mut agent = Agent::new(
///     Predicting::learned(Classify::new(&world), &PredictionParams::default(), 4),
///     csql::Lazy::default(),
///     qlearn::QTable::new(4).unwrap(),
///     LoopParams::from(&settings),
/// );
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// for trial in 1..=50 {
///     let start = setup.world.states()[trial as usize % 8];
///     agent.run_trial(&world, start, trial, &mut rng);
/// }
/// assert!(agent.perception.stats().skipped > 0);
/// ```
#[derive(Clone, Debug)]
pub struct Predicting {
    inner: Classify,
    model: TransitionModel,
    memory: Option<Memory>,
    recheck: f64,
    max_skips: u32,
    /// Whether an untrusted transition with several known successors is resolved by
    /// measuring only what tells them apart (navigation) rather than by CLASSIFY.
    narrow: bool,
    /// The state before the current one, if its description was predicted unmeasured
    /// (a refinement of that description checks it first), and the current one.
    previous: Option<Unmeasured>,
    current: Option<Unmeasured>,
    /// Navigating: the decision tree over the final descriptions, which identifies a
    /// state's description without measuring every feature of it.
    tree: Option<StateTree>,
    scratch: Vec<(Feature, Reading)>,
    stats: PredictionStats,
    /// The weighed level: its price of sensing, in reward units per unit of cost.
    price: Option<f64>,
    /// The weighed level: what the agent knows of the state it is in.
    known: Known,
    /// The weighed level: moves since the last classification in full.
    blind: u32,
    /// The weighed level: whether the state before the current one was given the most
    /// likely of several descriptions (the current one's is `known`).
    left_guessed: bool,
    /// The weighed level: what was chosen with a move that ends an episode, before its
    /// outcome (costed episodes under the rule "with the move").
    chosen: Option<Choice>,
}

/// What the weighed level knows of the state it is in.
#[derive(Clone, Debug, PartialEq)]
enum Known {
    /// Classified in full: its description is measured.
    Measured,
    /// Given a description by the model (skipped, or told apart among the likely ones).
    Trusted,
    /// Given its most likely description; the belief over descriptions it may have.
    Spread(Vec<(RowId, f64)>),
    /// A refinement touched a description it may have: the next state is classified.
    Lost,
}

impl Known {
    /// Whether the state was given the most likely of several descriptions.
    fn guessed(&self) -> bool {
        matches!(self, Known::Spread(_) | Known::Lost)
    }
}

/// The weighed level's choice after a move, made before its outcome is seen.
#[derive(Clone, Debug, PartialEq)]
enum Choice {
    /// Classify in full (the paper's procedure).
    Classify,
    /// Measure nothing: take the most likely description, keep the belief.
    Skip(RowId, Vec<(RowId, f64)>),
    /// Measure only what tells the likely descriptions apart.
    Narrow(Vec<(RowId, f64)>),
}

/// A state sensed through the decision tree, keeping what was measured.
struct Recording<'a, W: ?Sized> {
    world: &'a W,
    state: StateId,
    measured: &'a mut Vec<(Feature, Reading)>,
}

impl<W: World + ?Sized> Sensor for Recording<'_, W> {
    fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        let f = Feature(feature.0);
        (f.index() < self.world.num_features()).then(|| {
            let reading = self.world.read(self.state, f);
            self.measured.push((f, reading));
            Value(reading.0)
        })
    }
}

/// A state given a description without measuring it, and the transition that predicted it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Unmeasured {
    /// The state reached.
    pub(crate) s: StateId,
    /// The description it was given.
    pub(crate) row: RowId,
    /// The description left.
    pub(crate) from: RowId,
    /// The action taken.
    pub(crate) a: ActionId,
}

impl Predicting {
    /// The learned level: CLASSIFY and a transition model.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert_eq!(p.level(), csql::PredictSensing::Learned);
    /// ```
    pub fn learned(classify: Classify, settings: &PredictionParams, actions: usize) -> Predicting {
        Predicting {
            inner: classify,
            model: TransitionModel::new(actions, settings.confirmations),
            memory: None,
            recheck: settings.recheck,
            max_skips: settings.max_skips,
            narrow: false,
            previous: None,
            current: None,
            tree: None,
            scratch: Vec::new(),
            stats: PredictionStats::default(),
            price: None,
            known: Known::Measured,
            blind: 0,
            left_guessed: false,
            chosen: None,
        }
    }

    /// The weighed level: CLASSIFY and a model of the frequencies of next descriptions,
    /// weighed against sensing at `price` reward units per unit of sensing cost (a run's
    /// `[costly] price`). At a price of 0 measuring is free, and the agent measures
    /// everything the paper's procedure measures.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::weighed(csql::Classify::new(&sensed), &Default::default(), 4, 0.01);
    /// assert_eq!(p.level(), csql::PredictSensing::Weighed);
    /// ```
    pub fn weighed(
        classify: Classify,
        settings: &PredictionParams,
        actions: usize,
        price: f64,
    ) -> Predicting {
        Predicting {
            price: Some(price),
            ..Predicting::learned(classify, settings, actions)
        }
    }

    /// The motion level: the learned level and a memory of the cells sensed in the last
    /// [`PredictionParams::memory_moves`] moves, placed by dead reckoning in `world`'s grid.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::motion(csql::Classify::new(&sensed), &Default::default(), &world, &space);
    /// assert_eq!(p.level(), csql::PredictSensing::Motion);
    /// ```
    pub fn motion(
        classify: Classify,
        settings: &PredictionParams,
        world: &GridWorld,
        space: &FeatureSpace,
    ) -> Predicting {
        Predicting {
            memory: Some(Memory::new(world, space, settings.memory_moves)),
            ..Predicting::learned(classify, settings, Action::ALL.len())
        }
    }

    /// Which level this is.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert_ne!(p.level(), csql::PredictSensing::Off);
    /// ```
    pub fn level(&self) -> PredictSensing {
        match (&self.memory, self.price) {
            (_, Some(_)) => PredictSensing::Weighed,
            (None, None) => PredictSensing::Learned,
            (Some(_), None) => PredictSensing::Motion,
        }
    }

    /// What prediction has done so far, as the learner knows it: `wrong` and
    /// `longest_wrong_run` are the oracle's and stay 0 here (a run counts them from
    /// outside, into its report's `prediction`).
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert_eq!(p.stats().skipped, 0);
    /// assert_eq!(p.stats().wrong, 0);
    /// ```
    pub fn stats(&self) -> PredictionStats {
        self.stats
    }

    /// The transition model (the reduced map's edges).
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert_eq!(p.model().conflicts(), 0);
    /// ```
    pub fn model(&self) -> &TransitionModel {
        &self.model
    }

    /// CLASSIFY underneath.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert!(p.classify_mut().representation().is_empty());
    /// ```
    pub fn classify_mut(&mut self) -> &mut Classify {
        &mut self.inner
    }

    /// Give up CLASSIFY.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert!(p.into_classify().representation().is_empty());
    /// ```
    pub fn into_classify(self) -> Classify {
        self.inner
    }

    /// Switch to navigation on the reduced map. States are classified through the
    /// decision tree over the current descriptions ([`StateTree`], the paper's Figure 5d):
    /// after learning the descriptions are trusted to cover the world, so the tree
    /// identifies a state's description without measuring every feature of it (CLASSIFY
    /// measures them all). Trusted transitions are verified with
    /// probability `verify` (and after `max_skips` unmeasured uses), and a transition
    /// that is not deterministic but whose successors are known is resolved by
    /// [`Classify::classify_among`] them, measuring only what tells them apart (itself
    /// a prediction, under the same verification rule: a verification classifies in
    /// full).
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// p.navigate_with(0.05);
    /// ```
    pub fn navigate_with(&mut self, verify: f64) {
        self.recheck = verify;
        self.narrow = true;
        self.tree = Some(StateTree::build(
            self.inner.representation(),
            self.inner.prices(),
        ));
    }

    /// Classify `s` (charged), less what the memory already holds at the motion level.
    fn measure<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        if let Some(tree) = &self.tree {
            self.scratch.clear();
            let out = tree.tree().classify(Recording {
                world,
                state: s,
                measured: &mut self.scratch,
            });
            if let Some(class) = out.class {
                let cost = charge(
                    self.memory.as_mut(),
                    self.inner.prices(),
                    &self.scratch,
                    out.cost.get(),
                );
                return (RowId(class.0), cost);
            }
        }
        let (row, full) = self.inner.classify(world, s, table);
        (row, self.charge(full))
    }

    /// The charge of the features CLASSIFY just measured (`full` without a memory),
    /// which the memory then holds.
    fn charge(&mut self, full: f64) -> f64 {
        charge(
            self.memory.as_mut(),
            self.inner.prices(),
            self.inner.last_measured(),
            full,
        )
    }

    /// Use a transition without measuring: `s` is given `row`, predicted from `from`
    /// by `a`. Whether the prediction was right is not the learner's to know: the run's
    /// measuring asks the oracle afterwards ([`Predicting::last_unmeasured`]).
    fn unmeasured(&mut self, from: RowId, a: ActionId, s: StateId, row: RowId) {
        self.current = Some(Unmeasured { s, row, from, a });
        self.model.used_unmeasured(from, a);
    }

    /// The unmeasured use of a transition that the last
    /// [`Perception::classify_next`] made, if it made one, with how many unmeasured uses
    /// of that transition in a row (this one included) since it was last measured,
    /// distrusted or invalidated. For the measuring side only: the learner never reads
    /// it.
    pub(crate) fn last_unmeasured(&self) -> Option<(Unmeasured, u32)> {
        let u = self.current?;
        Some((u, self.model.unmeasured_uses(u.from, u.a)))
    }
}

impl Perception for Predicting {
    /// Localise: classify with no knowledge of where the robot came from (the memory is
    /// anchored afresh).
    fn classify<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        if let Some(memory) = &mut self.memory {
            memory.clear();
        }
        (self.previous, self.current) = (None, None);
        self.restart_belief();
        self.measure(world, s, table)
    }

    fn classify_next<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
        rng: &mut R,
    ) -> (RowId, f64) {
        if self.price.is_some() {
            return self.next_by_belief(world, from, a, s, table, rng);
        }
        if let (Some(memory), Some(action)) = (&mut self.memory, Action::from_id(a)) {
            memory.moved(action.offset());
        }
        self.previous = self.current.take();
        let predicted = self.model.trusted(from, a);
        let several = self.narrow && self.model.successors(from, a).len() >= 2;
        if predicted.is_none() && !several {
            let (row, cost) = self.measure(world, s, table);
            self.model.observe(from, a, row);
            return (row, cost);
        }
        // One draw per use of a trusted (or, navigating, narrowed) transition.
        let draw: f64 = rng.random();
        let due = self.model.unmeasured_uses(from, a) >= self.max_skips;
        let verify = due || draw < self.recheck;
        let Some(predicted) = predicted else {
            let mut partial = 0.0;
            if !verify {
                let candidates: Vec<DescriptionId> = self
                    .model
                    .successors(from, a)
                    .iter()
                    .map(|&r| DescriptionId(r.0))
                    .collect();
                let found = self.inner.classify_among(world, s, &candidates);
                let full = self.inner.last_cost();
                partial = self.charge(full);
                if let Some(d) = found {
                    self.unmeasured(from, a, s, d.row());
                    return (d.row(), partial);
                }
            }
            let (row, cost) = self.measure(world, s, table);
            self.model.observe(from, a, row);
            return (row, partial + cost);
        };
        if verify {
            self.stats.rechecks += 1;
            let (row, cost) = self.measure(world, s, table);
            if !self.model.observe(from, a, row) {
                self.stats.caught += 1;
            }
            return (row, cost);
        }
        self.stats.skipped += 1;
        self.unmeasured(from, a, s, predicted);
        (predicted, 0.0)
    }

    /// A refinement of `refined` changes the description of no state outside it: the
    /// next state keeps its description unless that is the one refined. (At the belief
    /// level with a price of 0, measuring is free: the state is classified again, as
    /// the paper does.)
    fn classify_again<W: World + ?Sized>(
        &mut self,
        world: &W,
        refined: RowId,
        current: RowId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let free = self.price.is_some_and(|p| p <= 0.0);
        if current == refined || free {
            self.current = None;
            if self.price.is_some() {
                self.known = Known::Measured;
                self.blind = 0;
            }
            self.measure(world, s, table)
        } else {
            (current, 0.0)
        }
    }

    /// Refine `row` at `s`; if `s` was given `row` by an unmeasured prediction, first
    /// check that `s` matches it (charged). A state that does not match is a wrong
    /// prediction caught: the transition is distrusted, nothing is refined, and the check
    /// is the cost returned.
    fn refine<W: World + ?Sized>(&mut self, world: &W, row: RowId, s: StateId) -> Option<f64> {
        let mut check = 0.0;
        if let Some(u) = self.previous.take().filter(|u| u.s == s && u.row == row) {
            let matches = self.inner.matches(world, s, DescriptionId(row.0));
            let full = self.inner.last_cost();
            // Measured around the state left behind: the memory, placed around the
            // current one, neither discounts nor keeps it.
            check = full;
            self.stats.rechecks += 1;
            if !matches {
                self.stats.caught += 1;
                self.model.distrust(u.from, u.a);
                return Some(check);
            }
        }
        let cost = self.inner.refine(world, row, s)?;
        if self.price.is_some() {
            self.refined_belief(row);
        } else {
            self.model.invalidate(row);
        }
        Some(check + cost)
    }

    fn rows(&self) -> usize {
        self.inner.rows()
    }

    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        Perception::lookup(&mut self.inner, world, s)
    }

    /// The weighed level learns nothing from a move from or (unless it ended the trial)
    /// to a state given the most likely of several descriptions.
    fn learns_from_move(&self, ended: bool) -> bool {
        !(self.known.guessed() || (!ended && self.left_guessed))
    }
}

/// A report reads CLASSIFY underneath: prediction changes what is charged while
/// learning, not the descriptions or what they cost after it.
impl Describes for Predicting {
    fn described(&self) -> Vec<(RowId, Vec<(mdp::Feature, Reading)>)> {
        self.inner.described()
    }
    fn cost_after_learning<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        self.inner.cost_after_learning(world, s)
    }
    fn table1_costs<W: World + ?Sized>(&mut self, world: &W) -> (f64, f64) {
        self.inner.table1_costs(world)
    }
}

impl Sees for Predicting {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId> {
        self.classify_mut().sees(world, s, noise, rng)
    }
}
