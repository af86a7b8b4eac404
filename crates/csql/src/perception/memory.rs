//! Memory: the paper's remedy for states that no local feature tells apart (the run
//! setting `extensions.memory = K`, 0 by default).
//!
//! With a bounded sensing range, two states that call for different actions may look the
//! same from where they stand, and CS-QL refines their description until it has every
//! sensable feature, with nothing left to add. With memory `K`, a description whose
//! sensable features are exhausted is refined instead by what the agent did and saw in
//! its last steps: first the last step (the action taken to come here and the
//! description of the state it left), then the last two, up to `K`. Remembering costs
//! nothing: the agent knows what it did, and the previous description was already
//! measured. Each history a description meets becomes a row of its own; at a trial's
//! start there is no history, and the description's own row is used.
//!
//! The policy is then a function of the path, not of the state, so its quality is
//! estimated by Monte Carlo (specification §6).

use std::collections::{BTreeMap, VecDeque};

use mdp::{ActionId, Feature, Reading, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::Rng;

use crate::perception::classify::Classify;
use crate::perception::representation::DescriptionId;
use crate::perception::rows::Perception;
use crate::perception::view::Sees;

/// One step of history: the action taken and the description of the state it left.
type Step = (u8, u32);

/// CLASSIFY with a memory of the last `K` steps (see the module docs).
///
/// ```
/// use csql::{Classify, Perception, Remembering};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap().within(1.0);
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut p = Remembering::new(Classify::new(&sensed), 2);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let s = world.states()[0];
/// let (row, _) = p.classify(&sensed, s, &mut table);
/// // Four features within reach, then two steps of history, then nothing more.
/// let refinements = std::iter::from_fn(|| p.refine(&sensed, row, s)).count();
/// assert_eq!(refinements, 4 + 2);
/// ```
#[derive(Clone, Debug)]
pub struct Remembering {
    inner: Classify,
    limit: u32,
    /// Steps of history each description uses (indexed by description).
    depth: Vec<u32>,
    rows: BTreeMap<(u32, Vec<Step>), RowId>,
    /// The description of each row.
    description_of: Vec<u32>,
    /// The last steps, most recent first, and the description last given.
    history: VecDeque<Step>,
    current: u32,
    /// The same, as the quality evaluation sees it.
    seen_history: VecDeque<Step>,
    seen_current: u32,
}

impl Remembering {
    /// CLASSIFY with a memory of at most `limit` steps.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Remembering::new(csql::Classify::new(&sensed), 1);
    /// assert_eq!(csql::Perception::rows(&p), 0);
    /// ```
    pub fn new(inner: Classify, limit: u32) -> Remembering {
        Remembering {
            inner,
            limit,
            depth: Vec::new(),
            rows: BTreeMap::new(),
            description_of: Vec::new(),
            history: VecDeque::new(),
            current: 0,
            seen_history: VecDeque::new(),
            seen_current: 0,
        }
    }

    /// CLASSIFY underneath.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Remembering::new(csql::Classify::new(&sensed), 1);
    /// assert!(p.classify_ref().representation().is_empty());
    /// ```
    pub fn classify_ref(&self) -> &Classify {
        &self.inner
    }

    /// Give up CLASSIFY.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let p = csql::Remembering::new(csql::Classify::new(&sensed), 1);
    /// assert!(p.into_classify().representation().is_empty());
    /// ```
    pub fn into_classify(self) -> Classify {
        self.inner
    }

    /// Descriptions that use history.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(csql::Remembering::new(csql::Classify::new(&sensed), 1).remembering(), 0);
    /// ```
    pub fn remembering(&self) -> usize {
        self.depth.iter().filter(|&&d| d > 0).count()
    }

    /// The key of description `d` after `history`.
    fn key(&self, d: u32, history: &VecDeque<Step>) -> (u32, Vec<Step>) {
        let depth = self.depth.get(d as usize).copied().unwrap_or(0) as usize;
        (d, history.iter().take(depth).copied().collect())
    }

    /// The row of description `d` after the current history, made if new.
    fn row(&mut self, d: u32, table: &mut QTable) -> RowId {
        if self.depth.len() <= d as usize {
            self.depth.resize(d as usize + 1, 0);
        }
        let key = self.key(d, &self.history);
        if let Some(&row) = self.rows.get(&key) {
            return row;
        }
        let row = table.add_row();
        self.rows.insert(key, row);
        self.description_of.push(d);
        row
    }

    fn classify_here<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let (d, _) = self.inner.classify_quietly(world, s);
        self.current = d.0;
        (self.row(d.0, table), self.inner.last_cost())
    }
}

impl Perception for Remembering {
    fn classify<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.history.clear();
        self.classify_here(world, s, table)
    }

    fn classify_next<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        _from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
        _rng: &mut R,
    ) -> (RowId, f64) {
        self.history.push_front((a.0 as u8, self.current));
        self.history.truncate(self.limit as usize);
        self.classify_here(world, s, table)
    }

    fn classify_again<W: World + ?Sized>(
        &mut self,
        world: &W,
        _refined: RowId,
        _current: RowId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.classify_here(world, s, table)
    }

    fn refine<W: World + ?Sized>(&mut self, world: &W, row: RowId, s: StateId) -> Option<f64> {
        let d = self.description_of[row.index()];
        let depth = &mut self.depth[d as usize];
        if *depth == 0
            && let Some(cost) = self.inner.add_feature(world, DescriptionId(d), s)
        {
            return Some(cost);
        }
        (*depth < self.limit).then(|| {
            *depth += 1;
            0.0
        })
    }

    fn rows(&self) -> usize {
        self.rows.len()
    }

    /// The row of `s` with no history (as at a trial's start).
    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        let d = self.inner.lookup(world, s)?;
        self.rows.get(&(d.0, Vec::new())).copied()
    }
}

impl Sees for Remembering {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId> {
        let d = self.inner.lookup_noisy(world, s, noise, rng)?;
        self.seen_current = d.0;
        self.rows.get(&self.key(d.0, &self.seen_history)).copied()
    }
    fn memoryless(&self) -> bool {
        self.remembering() == 0
    }
    fn begin(&mut self) {
        self.seen_history.clear();
    }
    fn moved(&mut self, a: ActionId) {
        self.seen_history.push_front((a.0 as u8, self.seen_current));
        self.seen_history.truncate(self.limit as usize);
    }
}

impl crate::perception::view::Describes for Remembering {
    /// Each row with its description's features (its history is not a feature).
    fn described(&self) -> Vec<(RowId, Vec<(Feature, Reading)>)> {
        let rep = self.inner.representation();
        self.description_of
            .iter()
            .enumerate()
            .map(|(row, &d)| {
                (
                    RowId(row as u32),
                    rep.get(DescriptionId(d)).features().collect(),
                )
            })
            .collect()
    }
    fn cost_after_learning<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        self.inner.lookup_cost(world, s)
    }
}
