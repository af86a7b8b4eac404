//! Sensing less: predict the next description instead of measuring it (off by default).
//!
//! The paper charges every measurement and leaves a "task-dependent world model (e.g., a
//! reduced map)" built from the learned representation as future work. In a
//! deterministic world most of CLASSIFY's measurements after a move can be predicted from
//! the description the robot left and the action it took. Two levels, never mixed in a
//! report (the setting `predict_sensing`, [`PredictSensing`]):
//!
//! | level | what the agent knows | type |
//! |---|---|---|
//! | `off` | nothing: every next state is classified (the paper's procedure) | [`crate::Classify`] alone |
//! | `learned` | a model learned on the way: (description, action) -> next description | [`Predicting::learned`], [`TransitionModel`] |
//! | `motion` | the learned model, and how its moves shift its view (dead reckoning) | [`Predicting::motion`] |
//!
//! # The learned model
//!
//! [`TransitionModel`] counts, for each description and action, the next description
//! measured. A transition is *trusted* once it has been measured
//! [`Prediction::confirmations`] times in a row with the same answer and never with
//! another one. When the agent leaves a description by a trusted transition it does not
//! classify the next state: it takes the predicted description, uncharged. It still
//! re-checks (classifies, charged) with probability [`Prediction::recheck`], and always
//! after [`Prediction::max_skips`] unmeasured uses in a row. A re-check that disagrees
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
//! (without charging, never shown to the learner) in [`PredictionStats`];
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
//! the cells it sensed in the last [`Prediction::memory_moves`] moves, placed by dead
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
//! probability [`Prediction::verify`] (and after `max_skips` unmeasured uses).

use cslearn::{FeatureId, Sensor, Value};
use mdp::{
    Action, ActionId, Cell, Feature, FeatureSpace, GridWorld, Offset, Reading, StateId, World,
};
use qlearn::{QTable, RowId};
use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::classify::Classify;
use crate::error::Error;
use crate::perception::Perception;
use crate::representation::DescriptionId;
use crate::tree::StateTree;

/// Which knowledge lets the agent skip measurements (the run setting `predict_sensing`).
///
/// ```
/// use csql::PredictSensing;
/// assert_eq!(PredictSensing::default(), PredictSensing::Off);
/// assert_eq!(PredictSensing::Motion.name(), "motion");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PredictSensing {
    /// Classify every next state (the paper's procedure; the default).
    #[default]
    Off,
    /// A learned model of (description, action) -> next description.
    Learned,
    /// The learned model, and features carried over by dead reckoning.
    Motion,
}

impl PredictSensing {
    /// The three levels, in order.
    ///
    /// ```
    /// assert_eq!(csql::PredictSensing::ALL.len(), 3);
    /// ```
    pub const ALL: [PredictSensing; 3] = [
        PredictSensing::Off,
        PredictSensing::Learned,
        PredictSensing::Motion,
    ];

    /// The setting's value: `off`, `learned` or `motion`.
    ///
    /// ```
    /// assert_eq!(csql::PredictSensing::Learned.name(), "learned");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            PredictSensing::Off => "off",
            PredictSensing::Learned => "learned",
            PredictSensing::Motion => "motion",
        }
    }

    /// Whether this is `off` (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::PredictSensing::Off.is_off());
    /// ```
    pub fn is_off(&self) -> bool {
        *self == PredictSensing::Off
    }
}

impl std::fmt::Display for PredictSensing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for PredictSensing {
    type Err = Error;
    fn from_str(s: &str) -> Result<PredictSensing, Error> {
        PredictSensing::ALL
            .into_iter()
            .find(|l| l.name() == s)
            .ok_or_else(|| Error::InvalidSetting {
                value: format!("predict_sensing = {s}"),
                expected: "one of off, learned, motion",
            })
    }
}

/// The confidence rule, the re-check rates and the evaluation of navigation (the TOML
/// table `[prediction]`; every key optional). Used only when `predict_sensing` is not
/// `off`.
///
/// ```
/// let p = csql::Prediction::default();
/// assert_eq!((p.confirmations, p.max_skips, p.navigation_trials, p.memory_moves), (3, 16, 10, 1));
/// assert_eq!((p.recheck, p.verify), (0.05, 0.05));
/// assert!(p.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Prediction {
    /// Equal measurements in a row, and none different, before a transition is trusted
    /// (default 3).
    pub confirmations: u32,
    /// Probability of re-checking a trusted transition while learning (default 0.05).
    pub recheck: f64,
    /// Most unmeasured uses of one transition in a row: the bound on how long a wrong
    /// prediction can go unmeasured (default 16).
    pub max_skips: u32,
    /// Probability of verifying a trusted transition while navigating (default 0.05).
    pub verify: f64,
    /// Evaluation trials of navigation from each non-goal free state (default 10).
    pub navigation_trials: u32,
    /// At the motion level, for how many moves a sensed cell is remembered (default 1:
    /// what was sensed at the previous state).
    pub memory_moves: u32,
}

impl Default for Prediction {
    fn default() -> Prediction {
        Prediction {
            confirmations: 3,
            recheck: 0.05,
            max_skips: 16,
            verify: 0.05,
            navigation_trials: 10,
            memory_moves: 1,
        }
    }
}

impl Prediction {
    /// Whether every value is the default (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::Prediction::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == Prediction::default()
    }

    /// Check the ranges: probabilities in [0, 1], at least one confirmation, skip,
    /// evaluation trial and remembered move.
    ///
    /// ```
    /// let p = csql::Prediction { recheck: 1.5, ..Default::default() };
    /// let err = p.validate().unwrap_err();
    /// assert!(matches!(err, csql::Error::InvalidSetting { .. }));
    /// assert!(err.to_string().contains("prediction.recheck"));
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |name: &'static str, value: String, expected: &'static str| {
            Err(Error::InvalidSetting {
                value: format!("{name} = {value}"),
                expected,
            })
        };
        for (name, p) in [
            ("prediction.recheck", self.recheck),
            ("prediction.verify", self.verify),
        ] {
            if !(0.0..=1.0).contains(&p) {
                return bad(name, p.to_string(), "a probability in [0, 1]");
            }
        }
        for (name, n) in [
            ("prediction.confirmations", self.confirmations),
            ("prediction.max_skips", self.max_skips),
            ("prediction.navigation_trials", self.navigation_trials),
            ("prediction.memory_moves", self.memory_moves),
        ] {
            if n == 0 {
                return bad(name, "0".to_string(), "at least 1");
            }
        }
        Ok(())
    }
}

/// What prediction did in a run (the JSON's `prediction`, present only when
/// `predict_sensing` is not `off`). The last two figures are the oracle's: it looks up
/// the true description of every state reached unmeasured, without charging.
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
}

/// What the model knows of one (description, action).
#[derive(Clone, Debug, Default)]
struct Entry {
    /// The last next description measured.
    next: Option<RowId>,
    /// Every next description measured, in the order first seen.
    successors: Vec<RowId>,
    /// Measurements in a row that gave `next`.
    agree: u32,
    /// Whether two measurements disagreed since the entry was last invalidated.
    conflicted: bool,
    /// Unmeasured uses since the last measurement.
    unmeasured: u32,
    /// Wrong unmeasured uses since the last measurement (the oracle's count).
    wrong: u32,
}

/// The learned transition model at the level of descriptions: (description, action) ->
/// next description, with the confidence rule of [`Prediction::confirmations`].
///
/// ```
/// use csql::TransitionModel;
/// use mdp::ActionId;
/// use qlearn::RowId;
/// let mut m = TransitionModel::new(4, 2);
/// let (d, e) = (RowId(0), RowId(1));
/// m.observe(d, ActionId(1), e);
/// assert_eq!(m.trusted(d, ActionId(1)), None); // one measurement is not enough
/// m.observe(d, ActionId(1), e);
/// assert_eq!(m.trusted(d, ActionId(1)), Some(e));
/// m.invalidate(e); // refining e invalidates what leads to it
/// assert_eq!(m.trusted(d, ActionId(1)), None);
/// ```
#[derive(Clone, Debug)]
pub struct TransitionModel {
    actions: usize,
    confirmations: u32,
    entries: Vec<Entry>,
}

impl TransitionModel {
    /// An empty model for `actions` actions that trusts a transition after
    /// `confirmations` equal measurements.
    ///
    /// ```
    /// let m = csql::TransitionModel::new(4, 3);
    /// assert_eq!(m.trusted(qlearn::RowId(7), mdp::ActionId(0)), None);
    /// ```
    pub fn new(actions: usize, confirmations: u32) -> TransitionModel {
        TransitionModel {
            actions,
            confirmations,
            entries: Vec::new(),
        }
    }

    fn index(&self, from: RowId, a: ActionId) -> usize {
        from.index() * self.actions + a.index()
    }

    fn entry(&self, from: RowId, a: ActionId) -> Option<&Entry> {
        self.entries.get(self.index(from, a))
    }

    fn entry_mut(&mut self, from: RowId, a: ActionId) -> &mut Entry {
        let i = self.index(from, a);
        if i >= self.entries.len() {
            self.entries.resize(i + 1, Entry::default());
        }
        &mut self.entries[i]
    }

    /// The predicted next description, if the transition is trusted.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(2));
    /// assert_eq!(m.trusted(d, a), Some(qlearn::RowId(2)));
    /// m.observe(d, a, qlearn::RowId(3)); // disagrees: distrusted for good
    /// m.observe(d, a, qlearn::RowId(3));
    /// assert_eq!(m.trusted(d, a), None);
    /// ```
    pub fn trusted(&self, from: RowId, a: ActionId) -> Option<RowId> {
        self.entry(from, a)
            .filter(|e| !e.conflicted && e.agree >= self.confirmations)
            .and_then(|e| e.next)
    }

    /// Record a measured transition; returns whether it agreed with what the model held
    /// (true for the first measurement).
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 2);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(3));
    /// assert!(m.observe(d, a, qlearn::RowId(1)));
    /// assert!(!m.observe(d, a, qlearn::RowId(2)));
    /// ```
    pub fn observe(&mut self, from: RowId, a: ActionId, to: RowId) -> bool {
        let e = self.entry_mut(from, a);
        e.unmeasured = 0;
        e.wrong = 0;
        if !e.successors.contains(&to) {
            e.successors.push(to);
        }
        match e.next {
            Some(n) if n == to => {
                e.agree = e.agree.saturating_add(1);
                true
            }
            Some(_) => {
                e.next = Some(to);
                e.agree = 1;
                e.conflicted = true;
                false
            }
            None => {
                e.next = Some(to);
                e.agree = 1;
                true
            }
        }
    }

    /// Never trust a transition again until it is invalidated (a prediction of it was
    /// found wrong).
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(1));
    /// m.distrust(d, a);
    /// assert_eq!(m.trusted(d, a), None);
    /// ```
    pub fn distrust(&mut self, from: RowId, a: ActionId) {
        let e = self.entry_mut(from, a);
        e.conflicted = true;
        e.unmeasured = 0;
        e.wrong = 0;
    }

    /// Every next description measured for a transition since it was last invalidated,
    /// in the order first seen: the edges of the reduced map.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(4));
    /// m.observe(d, a, qlearn::RowId(2));
    /// m.observe(d, a, qlearn::RowId(4));
    /// assert_eq!(m.successors(d, a), [qlearn::RowId(4), qlearn::RowId(2)]);
    /// ```
    pub fn successors(&self, from: RowId, a: ActionId) -> &[RowId] {
        self.entry(from, a).map_or(&[], |e| &e.successors)
    }

    /// Forget what a refinement of `row` may have made wrong: the transitions that leave
    /// it and those that lead to it.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let a = mdp::ActionId(0);
    /// m.observe(qlearn::RowId(0), a, qlearn::RowId(1));
    /// m.observe(qlearn::RowId(2), a, qlearn::RowId(3));
    /// m.invalidate(qlearn::RowId(0));
    /// assert_eq!(m.trusted(qlearn::RowId(0), a), None);
    /// assert_eq!(m.trusted(qlearn::RowId(2), a), Some(qlearn::RowId(3))); // untouched
    /// ```
    pub fn invalidate(&mut self, row: RowId) {
        let actions = self.actions;
        for (i, e) in self.entries.iter_mut().enumerate() {
            if i / actions == row.index() || e.next == Some(row) {
                *e = Entry::default();
            }
        }
    }

    /// How many transitions gave two different answers since they were last invalidated
    /// (the reduced map is deterministic everywhere else).
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// m.observe(qlearn::RowId(0), mdp::ActionId(0), qlearn::RowId(0));
    /// assert_eq!(m.conflicts(), 0);
    /// ```
    pub fn conflicts(&self) -> usize {
        self.entries.iter().filter(|e| e.conflicted).count()
    }
}

/// The cells sensed in the last few moves, placed by dead reckoning.
#[derive(Clone, Debug)]
struct Memory {
    /// Half the width and height of the area a trial can reach, offsets included.
    half: (i32, i32),
    offsets: Vec<Offset>,
    cells: Vec<Option<(Reading, u32)>>,
    /// The robot's position relative to where the memory was last anchored.
    pos: (i32, i32),
    /// Moves since the memory was anchored.
    now: u32,
    keep: u32,
}

impl Memory {
    fn new(world: &GridWorld, space: &FeatureSpace, keep: u32) -> Memory {
        // Displacements stay within the map and offsets within its bordered size.
        let half = (
            2 * world.map().width() as i32 + 2,
            2 * world.map().height() as i32 + 2,
        );
        let len = ((2 * half.0 + 1) * (2 * half.1 + 1)) as usize;
        Memory {
            half,
            offsets: space.features().map(|f| space.offset(f)).collect(),
            cells: vec![None; len],
            pos: (0, 0),
            now: 0,
            keep,
        }
    }

    fn clear(&mut self) {
        self.cells.fill(None);
        self.pos = (0, 0);
        self.now = 0;
    }

    fn index(&self, o: Offset) -> Option<usize> {
        let (x, y) = (self.pos.0 + o.dx, self.pos.1 + o.dy);
        if x.abs() > self.half.0 || y.abs() > self.half.1 {
            return None;
        }
        Some(((y + self.half.1) * (2 * self.half.0 + 1) + x + self.half.0) as usize)
    }

    /// The cell at offset `o` from the robot, if sensed recently enough.
    fn known(&self, o: Offset) -> Option<Reading> {
        let (cell, when) = self.cells[self.index(o)?]?;
        (self.now - when <= self.keep).then_some(cell)
    }

    fn record(&mut self, o: Offset, cell: Reading) {
        if let Some(i) = self.index(o) {
            self.cells[i] = Some((cell, self.now));
        }
    }

    /// Dead reckoning: the robot moved by `step` unless the cell there is an obstacle. If
    /// it does not remember that cell it cannot tell, and starts over.
    fn moved(&mut self, step: Offset) {
        let ahead = self.known(step);
        self.now += 1;
        match ahead {
            Some(r) if r == Reading::from(Cell::Obstacle) => {}
            Some(_) => self.pos = (self.pos.0 + step.dx, self.pos.1 + step.dy),
            None => self.clear(),
        }
    }
}

/// CLASSIFY with a learned transition model (and, at the motion level, a memory placed
/// by dead reckoning): the perception of a run whose `predict_sensing` is not `off`.
/// It changes what is charged and which states are measured, never how CLASSIFY chooses
/// its features.
///
/// ```
/// use csql::{Agent, Classify, LoopParams, Predicting, Prediction, RunSettings, Setup, StrategyKind};
/// use rand::SeedableRng;
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let world = setup.sensed(&settings);
/// let mut agent = Agent::new(
///     Predicting::learned(Classify::new(&world), &Prediction::default(), 4),
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
}

/// The charge of `measured` (`full` without a memory): what the memory holds is free,
/// and everything measured or carried is kept for the next state.
fn charge(
    memory: Option<&mut Memory>,
    prices: &[f64],
    measured: &[(Feature, Reading)],
    full: f64,
) -> f64 {
    let Some(memory) = memory else {
        return full;
    };
    let mut cost = 0.0;
    for &(f, cell) in measured {
        let o = memory.offsets[f.index()];
        match memory.known(o) {
            Some(remembered) => {
                debug_assert_eq!(remembered, cell, "dead reckoning placed a cell wrongly");
            }
            None => cost += prices[f.index()],
        }
        memory.record(o, cell);
    }
    cost
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
struct Unmeasured {
    s: StateId,
    row: RowId,
    from: RowId,
    a: ActionId,
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
    pub fn learned(classify: Classify, settings: &Prediction, actions: usize) -> Predicting {
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
        }
    }

    /// The motion level: the learned level and a memory of the cells sensed in the last
    /// [`Prediction::memory_moves`] moves, placed by dead reckoning in `world`'s grid.
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
        settings: &Prediction,
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
        match self.memory {
            None => PredictSensing::Learned,
            Some(_) => PredictSensing::Motion,
        }
    }

    /// What prediction has done so far.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Predicting::learned(csql::Classify::new(&sensed), &Default::default(), 4);
    /// assert_eq!(p.stats().skipped, 0);
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

    /// Count an unmeasured use of a transition, and whether the oracle finds it wrong.
    fn unmeasured<W: World + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        row: RowId,
    ) {
        self.current = Some(Unmeasured { s, row, from, a });
        let wrong = Perception::lookup(&mut self.inner, world, s) != Some(row);
        let entry = self.model.entry_mut(from, a);
        entry.unmeasured += 1;
        if wrong {
            entry.wrong += 1;
            let run = entry.wrong;
            self.stats.wrong += 1;
            self.stats.longest_wrong_run = self.stats.longest_wrong_run.max(run);
        }
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
        let due = self.model.entry_mut(from, a).unmeasured >= self.max_skips;
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
                    self.unmeasured(world, from, a, s, d.row());
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
        self.unmeasured(world, from, a, s, predicted);
        (predicted, 0.0)
    }

    /// A refinement of `refined` changes the description of no state outside it: the
    /// next state keeps its description unless that is the one refined.
    fn classify_again<W: World + ?Sized>(
        &mut self,
        world: &W,
        refined: RowId,
        current: RowId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        if current == refined {
            self.current = None;
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
        self.model.invalidate(row);
        Some(check + cost)
    }

    fn rows(&self) -> usize {
        self.inner.rows()
    }

    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        Perception::lookup(&mut self.inner, world, s)
    }
}

/// A report reads CLASSIFY underneath: prediction changes what is charged while
/// learning, not the descriptions or what they cost after it.
impl crate::report::Describes for Predicting {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disagreement_distrusts_until_invalidated() {
        let mut m = TransitionModel::new(4, 2);
        let (d, a) = (RowId(3), ActionId(2));
        for _ in 0..5 {
            m.observe(d, a, RowId(1));
        }
        assert_eq!(m.trusted(d, a), Some(RowId(1)));
        m.observe(d, a, RowId(2));
        for _ in 0..5 {
            m.observe(d, a, RowId(2));
        }
        assert_eq!(m.trusted(d, a), None);
        assert_eq!(m.conflicts(), 1);
        m.invalidate(RowId(2));
        assert_eq!(m.conflicts(), 0);
        m.observe(d, a, RowId(2));
        m.observe(d, a, RowId(2));
        assert_eq!(m.trusted(d, a), Some(RowId(2)));
    }

    #[test]
    fn invalidation_touches_only_the_refined_row() {
        let mut m = TransitionModel::new(4, 1);
        for from in 0..5u32 {
            for a in 0..4u32 {
                m.observe(RowId(from), ActionId(a), RowId((from + a) % 5));
            }
        }
        m.invalidate(RowId(2));
        for from in 0..5u32 {
            for a in 0..4u32 {
                let to = (from + a) % 5;
                let kept = from != 2 && to != 2;
                assert_eq!(
                    m.trusted(RowId(from), ActionId(a)).is_some(),
                    kept,
                    "{from} {a}"
                );
            }
        }
    }

    #[test]
    fn dead_reckoning_moves_unless_blocked_and_forgets_when_unsure() {
        let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
        let space = FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
        let mut m = Memory::new(&world, &space, 1);
        m.record(Offset::new(1, 0), Reading::from(Cell::Empty));
        m.record(Offset::new(2, 0), Reading::from(Cell::Obstacle));
        m.record(Offset::new(0, 1), Reading::from(Cell::Obstacle));
        m.moved(Offset::new(1, 0));
        assert_eq!(
            m.known(Offset::new(1, 0)),
            Some(Reading::from(Cell::Obstacle))
        );
        assert_eq!(
            m.known(Offset::new(-1, 1)),
            Some(Reading::from(Cell::Obstacle))
        );
        m.moved(Offset::new(1, 0)); // blocked: stays
        assert_eq!(m.pos, (1, 0));
        // Sensed two moves ago: forgotten with a memory of one move.
        assert_eq!(m.known(Offset::new(1, 0)), None);
        m.moved(Offset::new(0, -1)); // unknown: starts over
        assert_eq!((m.pos, m.known(Offset::new(-1, 1))), ((0, 0), None));
    }

    #[test]
    fn settings_are_checked() {
        for bad in [
            Prediction {
                verify: -0.1,
                ..Default::default()
            },
            Prediction {
                max_skips: 0,
                ..Default::default()
            },
            Prediction {
                confirmations: 0,
                ..Default::default()
            },
        ] {
            assert!(bad.validate().is_err());
        }
        assert_eq!(
            "motion".parse::<PredictSensing>().unwrap(),
            PredictSensing::Motion
        );
        assert!("on".parse::<PredictSensing>().is_err());
    }
}
