//! How states become rows of the Q table: the learner's side of sensing.
//!
//! CS-QL's perception is [`crate::Classify`]; [`Identified`] gives every state its own
//! row, which makes the main loop plain Q-learning (the baseline and the paper's
//! full-sensing reference).

use mdp::{ActionId, Reading, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::Rng;

use crate::perception::view::{Describes, Sees};

/// How states become rows of the Q table, and what that costs.
///
/// The contract the oracle relies on to judge incrementally ([`crate::Judge`]): the row
/// of a state changes only when that row is refined, or when a state that had no row
/// gets one because rows were added. Rows are never removed. A perception that
/// restructures itself in other ways says so ([`Perception::keeps_rows`]) and is judged
/// from scratch at every trial instead.
///
/// ```
/// use csql::{Identified, Perception};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut p = Identified::new(&sensed, vec![5.0; 9]);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let (row, cost) = p.classify(&sensed, mdp::StateId(0), &mut table);
/// assert_eq!((row.0, cost), (0, 5.0));
/// ```
pub trait Perception {
    /// The row of a non-terminal state, adding rows to `table` if the perception grows;
    /// returns the sensing cost charged.
    fn classify<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64);
    /// The row of a non-terminal state `s` reached by action `a` from a state of row
    /// `from`: a perception that predicts may skip measurements here (see
    /// [`crate::Predicting`]). By default, [`Perception::classify`], drawing nothing from
    /// `rng`.
    ///
    /// ```
    /// use csql::{Identified, Perception};
    /// use rand::SeedableRng;
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut p = Identified::new(&sensed, vec![5.0; 9]);
    /// let mut table = qlearn::QTable::new(4).unwrap();
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let (from, _) = p.classify(&sensed, mdp::StateId(0), &mut table);
    /// let (row, cost) = p.classify_next(&sensed, from, mdp::ActionId(3), mdp::StateId(1), &mut table, &mut rng);
    /// assert_eq!((row.0, cost), (1, 5.0));
    /// ```
    fn classify_next<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
        rng: &mut R,
    ) -> (RowId, f64) {
        let _ = (from, a, rng);
        self.classify(world, s, table)
    }
    /// The row of state `s` after row `refined` was refined, when `s` was given row
    /// `current` just before: the paper classifies again (charged), the default.
    ///
    /// ```
    /// use csql::{Identified, Perception};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut p = Identified::new(&sensed, vec![5.0; 9]);
    /// let mut table = qlearn::QTable::new(4).unwrap();
    /// let (row, _) = p.classify(&sensed, mdp::StateId(0), &mut table);
    /// assert_eq!(p.classify_again(&sensed, row, row, mdp::StateId(0), &mut table), (row, 5.0));
    /// ```
    fn classify_again<W: World + ?Sized>(
        &mut self,
        world: &W,
        refined: RowId,
        current: RowId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let _ = (refined, current);
        self.classify(world, s, table)
    }
    /// The main loop updated `Q(row, a)` with reward `reward` and next row `next`
    /// (`None`: the goal). A perception that learns from returns ([`crate::UTree`])
    /// records it; by default nothing happens.
    fn updated(
        &mut self,
        row: RowId,
        a: ActionId,
        reward: f64,
        next: Option<RowId>,
        table: &mut QTable,
    ) {
        let _ = (row, a, reward, next, table);
    }
    /// Make `row` more specific, using state `s` (which it describes) for the new value;
    /// returns the cost charged, or `None` if the row cannot be refined further.
    fn refine<W: World + ?Sized>(&mut self, world: &W, row: RowId, s: StateId) -> Option<f64>;
    /// How many rows (descriptions) the perception has made so far.
    fn rows(&self) -> usize;
    /// The row state `s` belongs to now, found without charging and without adding a
    /// row (`None` if classifying it would add one). This is the view the oracle judges
    /// the perception through; the learner never uses it.
    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId>;
    /// Whether the main loop may learn from the move just observed: a perception that
    /// gave the state left (or, unless the move ended the trial, the state reached) a
    /// description it only guessed among several says false, and the move updates
    /// nothing (true by default).
    ///
    /// ```
    /// use csql::{Identified, Perception};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = Identified::new(&sensed, vec![1.0; 9]);
    /// assert!(p.learns_from_move(false));
    /// ```
    fn learns_from_move(&self, ended: bool) -> bool {
        let _ = ended;
        true
    }
    /// Whether the perception keeps the contract above (true by default). U-Tree, whose
    /// splits move states between rows without a refinement, says false.
    fn keeps_rows(&self) -> bool {
        true
    }
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
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Identified::new(&sensed, vec![1.0; 9]);
    /// ```
    pub fn new<W: World + ?Sized>(world: &W, cost: Vec<f64>) -> Identified {
        Identified {
            rows: vec![None; world.num_states()],
            cost,
        }
    }
}

impl Perception for Identified {
    fn classify<W: World + ?Sized>(
        &mut self,
        _world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let row = *self.rows[s.index()].get_or_insert_with(|| table.add_row());
        (row, self.cost[s.index()])
    }
    fn refine<W: World + ?Sized>(&mut self, _world: &W, _row: RowId, _s: StateId) -> Option<f64> {
        None
    }
    fn rows(&self) -> usize {
        self.rows.iter().flatten().count()
    }
    fn lookup<W: World + ?Sized>(&mut self, _world: &W, s: StateId) -> Option<RowId> {
        self.rows[s.index()]
    }
}

/// The most readings [`FullView`] may keep (about 1.6 GB); a run that would need more is
/// refused before it starts, with the estimate.
///
/// ```
/// assert_eq!(csql::FULL_VIEW_LIMIT, 100_000_000);
/// ```
pub const FULL_VIEW_LIMIT: u64 = 100_000_000;

/// Full sensing: every feature of the feature space whose cell lies in the bordered
/// world is measured at every classification and charged
/// ([`crate::whole_world_cost`]); states that look the same from where they stand share a
/// row. With an unbounded space every state has a row of its own (plain Q-learning on
/// the states, the paper's full-sensing reference); with a sensing radius, states whose
/// whole view within the radius is the same are aliased, as they are for any learner.
/// The run setting `learner = "full-sensing"`.
///
/// Under sensor noise the view is taken as read without error: with every feature
/// measured, a state's view is redundant enough to be recognised, so this baseline is
/// charged for noise but not confused by it (an optimistic baseline; see
/// `docs/specification.md` §6).
///
/// ```
/// use csql::{FullView, Perception};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut p = FullView::new(&sensed);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let s = world.states()[0];
/// let (row, cost) = p.classify(&sensed, s, &mut table);
/// assert_eq!((row.0, cost), (0, csql::whole_world_cost(&world, &space, s)));
/// // Within the four neighbours, the open middle of open8x8 looks the same everywhere.
/// let open = mdp::GridWorld::new(&mdp::builtin("open8x8").unwrap());
/// let space = mdp::FeatureSpace::new(open.map(), &mdp::Manhattan).unwrap().within(1.0);
/// let near = FullView::new(&mdp::SensedGrid::new(&open, &space, mdp::Slip::default()));
/// assert!(near.views() < open.states().len());
/// ```
#[derive(Clone, Debug)]
pub struct FullView {
    /// The view class of every state (`None` for the goal).
    class: Vec<Option<usize>>,
    /// The row of each view class, once it was seen.
    rows: Vec<Option<RowId>>,
    /// The whole view of each class: every feature in the bordered world and its value.
    views: Vec<Vec<(mdp::Feature, Reading)>>,
    /// What a classification of each state costs.
    cost: Vec<f64>,
}

impl FullView {
    /// Full sensing of a world through a feature space.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(csql::FullView::new(&sensed).views(), 8);
    /// ```
    pub fn new<W: World + ?Sized>(world: &W) -> FullView {
        let mut class = vec![None; world.num_states()];
        let mut views: Vec<Vec<(mdp::Feature, Reading)>> = Vec::new();
        let mut index = std::collections::BTreeMap::new();
        let mut cost = vec![0.0; world.num_states()];
        let every: Vec<mdp::Feature> = (0..world.num_features() as u32).map(mdp::Feature).collect();
        for s in world.states() {
            let features = full_features(world, s, &every);
            cost[s.index()] = features.iter().map(|&f| world.price(f)).sum();
            let view = features
                .into_iter()
                .map(|f| (f, world.read(s, f)))
                .collect::<Vec<_>>();
            let next = views.len();
            let c = *index.entry(view.clone()).or_insert(next);
            if c == next {
                views.push(view);
            }
            class[s.index()] = Some(c);
        }
        FullView {
            class,
            rows: vec![None; views.len()],
            views,
            cost,
        }
    }

    /// How many readings full sensing of `world` keeps to tell its states' views apart
    /// (each state's whole view, twice: once as a view, once as its index key), for the
    /// bound [`FULL_VIEW_LIMIT`] that runs check before building one.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan, SensedGrid, Slip};
    /// let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = SensedGrid::new(&world, &space, Slip::default());
    /// // 50 states, each seeing the 99 other cells of the bordered 10 x 10 world.
    /// assert_eq!(csql::FullView::readings_needed(&sensed), 2 * 50 * 99);
    /// ```
    pub fn readings_needed<W: World + ?Sized>(world: &W) -> u64 {
        let every = world.num_features() as u64;
        let per_state = match world.grid() {
            // The cells of the bordered world other than the robot's, within its range.
            Some(grid) => {
                let m = grid.map();
                ((m.width() as u64 + 2) * (m.height() as u64 + 2) - 1).min(every)
            }
            None => every,
        };
        2 * world.states().len() as u64 * per_state
    }

    /// What full sensing reads in state `s` of `world`, any state (a terminal one
    /// included): the price of every feature of its view.
    pub(crate) fn cost_of<W: World + ?Sized>(world: &W, s: StateId) -> f64 {
        let every: Vec<mdp::Feature> = (0..world.num_features() as u32).map(mdp::Feature).collect();
        full_features(world, s, &every)
            .iter()
            .map(|&f| world.price(f))
            .sum()
    }

    /// How many different views the world's states show.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(csql::FullView::new(&sensed).views(), 50);
    /// ```
    pub fn views(&self) -> usize {
        self.views.len()
    }

    fn class_of(&self, s: StateId) -> usize {
        self.class[s.index()].expect("the goal is never classified")
    }
}

/// The features of state `s`'s whole view: on a grid, every cell of the bordered world
/// (the paper's reference); elsewhere, every feature (`every`).
fn full_features<W: World + ?Sized>(
    world: &W,
    s: StateId,
    every: &[mdp::Feature],
) -> Vec<mdp::Feature> {
    match world.grid().zip(world.local_space()) {
        Some((grid, space)) => {
            crate::perception::grid::bordered_features(grid, space, s, 1).collect()
        }
        None => every.to_vec(),
    }
}

impl Perception for FullView {
    fn classify<W: World + ?Sized>(
        &mut self,
        _world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let c = self.class_of(s);
        let row = *self.rows[c].get_or_insert_with(|| table.add_row());
        (row, self.cost[s.index()])
    }
    fn refine<W: World + ?Sized>(&mut self, _world: &W, _row: RowId, _s: StateId) -> Option<f64> {
        None
    }
    fn rows(&self) -> usize {
        self.rows.iter().flatten().count()
    }
    fn lookup<W: World + ?Sized>(&mut self, _world: &W, s: StateId) -> Option<RowId> {
        self.class[s.index()].and_then(|c| self.rows[c])
    }
}

impl Describes for FullView {
    fn described(&self) -> Vec<(RowId, Vec<(mdp::Feature, Reading)>)> {
        let mut out: Vec<_> = self
            .rows
            .iter()
            .zip(&self.views)
            .filter_map(|(r, v)| r.map(|r| (r, v.clone())))
            .collect();
        out.sort_by_key(|(r, _)| *r);
        out
    }
    fn cost_after_learning<W: World + ?Sized>(&mut self, _world: &W, s: StateId) -> f64 {
        self.cost[s.index()]
    }
}

impl Sees for FullView {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        _noise: SensorNoise,
        _rng: &mut R,
    ) -> Option<RowId> {
        Perception::lookup(self, world, s)
    }
}

impl Sees for Identified {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        _noise: SensorNoise,
        _rng: &mut R,
    ) -> Option<RowId> {
        Perception::lookup(self, world, s)
    }
}
