//! A U-Tree-like learner (McCallum, 1995): the baseline from later work on the problem
//! CS-QL addresses, under CS-QL's sensing model and charges (the run setting
//! `learner = "u-tree"`).
//!
//! # The tree
//!
//! Internal nodes test a *distinction*: a feature of the feature space (measured and
//! charged its cost, through the same noisy sensors as CLASSIFY) or the previous action
//! (free: the agent remembers what it did; "none" at a trial's start). Each leaf is a row
//! of the Q table, which plain Q-learning updates (equation 2, the paper's parameters).
//! The tree starts as one leaf.
//!
//! # Splitting
//!
//! A leaf collects *instances*: for each visit, the action taken, the reward, the row
//! reached (or the goal), and the values of the leaf's *fringe*, its candidate
//! distinctions: the [`UTreeParams::fringe`] cheapest features its path does not test
//! (measured and charged at every visit while the leaf collects) and the previous action
//! (unless its path tests it). It keeps the last [`UTreeParams::window`] instances.
//! Every [`UTreeParams::test_every`] new instances it is tested: an instance's return is
//! `r + gamma V(next row)` with the table's current V (`r` at the goal), and for every
//! candidate, every action and every pair of the candidate's values seen at least
//! [`UTreeParams::min_group`] times with that action, a two-sample Kolmogorov-Smirnov
//! test compares the returns (asymptotic p-value). The leaf splits on the candidate with
//! the smallest p-value if that p-value is below [`UTreeParams::alpha`] divided by the
//! number of comparisons made (Bonferroni). The new leaves are one per value seen; the
//! most frequent value keeps the leaf's row and Q values, the others start new rows at
//! zero, with empty windows. A value first met later makes a new leaf then. A leaf that
//! was tested [`UTreeParams::patience`] times without a split stops collecting, and so
//! stops measuring its fringe.
//!
//! # Where this departs from McCallum's U-Tree
//!
//! * Q values are learned by Q-learning on the leaves, not by value iteration on a model
//!   estimated from the instances.
//! * The fringe holds the cheapest missing features and the previous action only, so
//!   that measuring it is not sensing the whole world; history distinctions go one step
//!   back.
//! * Returns are recomputed from the current table at each test, not stored.

use std::collections::VecDeque;

use mdp::{ActionId, Feature, Reading, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::perception::rows::Perception;
use crate::perception::sensor::SensorModel;
use crate::settings::learner::UTreeParams;

/// What a node tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Distinction {
    /// A feature's value (a [`Cell::code`]).
    Feature(Feature),
    /// The previous action (0 to 3), or 4 at a trial's start.
    PreviousAction,
}

/// The previous action's value at a trial's start.
const NO_ACTION: u32 = u32::MAX;

#[derive(Clone, Debug)]
enum Node {
    Leaf(RowId),
    Split {
        test: Distinction,
        children: Vec<(u32, usize)>,
    },
}

#[derive(Clone, Debug)]
struct Instance {
    /// The fringe's values, in the leaf's candidate order.
    values: Vec<u32>,
    action: ActionId,
    reward: f64,
    next: Option<RowId>,
}

#[derive(Clone, Debug)]
struct Leaf {
    /// Its node.
    node: usize,
    /// Candidate distinctions (features cheapest first, then the previous action).
    candidates: Vec<Distinction>,
    instances: VecDeque<Instance>,
    since_test: usize,
    tests: u32,
    open: bool,
}

/// An instance waiting for its update.
#[derive(Clone, Debug)]
struct Pending {
    row: RowId,
    values: Vec<u32>,
}

/// The U-Tree learner's perception (see the module docs): a tree of distinctions whose
/// leaves are rows of the Q table.
///
/// ```
/// use csql::{Perception, UTree, UTreeParams};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut tree = UTree::new(&sensed, UTreeParams::default(), 0.9);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let (row, cost) = tree.classify(&sensed, world.states()[0], &mut table);
/// // One leaf, whose fringe (the four cheapest features) is measured and charged.
/// assert_eq!((row.0, cost), (0, 4.0));
/// ```
#[derive(Clone, Debug)]
pub struct UTree {
    prices: Vec<f64>,
    params: UTreeParams,
    gamma: f64,
    /// What the learner's sensors make of the world's readings.
    sensor: SensorModel,
    nodes: Vec<Node>,
    /// Per node: what the path to it tests, with the values it requires.
    paths: Vec<Vec<(Distinction, u32)>>,
    /// Per row: its leaf.
    leaves: Vec<Leaf>,
    /// The previous action of the state being classified.
    previous: u32,
    /// The instance of the state classified last, and of the one before.
    current: Option<Pending>,
    last: Option<Pending>,
    /// The previous action as the quality evaluation sees it.
    seen_previous: u32,
    splits: u32,
}

impl UTree {
    /// An empty tree (one leaf, made at the first classification) over a feature space,
    /// with its parameters and the discount of the returns it compares.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let tree = csql::UTree::new(&sensed, csql::UTreeParams::default(), 0.9);
    /// assert_eq!(tree.splits(), 0);
    /// ```
    pub fn new<W: World + ?Sized>(world: &W, params: UTreeParams, gamma: f64) -> UTree {
        let features = (0..world.num_features() as u32).map(Feature);
        UTree {
            prices: features.map(|f| world.price(f)).collect(),
            params,
            gamma,
            sensor: SensorModel::exact(),
            nodes: Vec::new(),
            paths: Vec::new(),
            leaves: Vec::new(),
            previous: NO_ACTION,
            current: None,
            last: None,
            seen_previous: NO_ACTION,
            splits: 0,
        }
    }

    /// The same tree reading its features through noisy sensors, whose errors are drawn
    /// from `rng` (as [`crate::Classify::with_noise`]).
    ///
    /// ```
    /// use rand::SeedableRng;
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let noise = mdp::SensorNoise::new(0.1).unwrap();
    /// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let tree = csql::UTree::new(&sensed, csql::UTreeParams::default(), 0.9).with_noise(noise, rng);
    /// ```
    pub fn with_noise(mut self, noise: SensorNoise, rng: Xoshiro256PlusPlus) -> UTree {
        self.sensor = SensorModel::noisy(noise, rng);
        self
    }

    /// Splits made so far.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(csql::UTree::new(&sensed, Default::default(), 0.9).splits(), 0);
    /// ```
    pub fn splits(&self) -> u32 {
        self.splits
    }

    /// A new leaf with the given path; its row is added to `table`.
    fn new_leaf(&mut self, path: Vec<(Distinction, u32)>, table: &mut QTable) -> usize {
        let row = table.add_row();
        debug_assert_eq!(row.index(), self.leaves.len());
        self.leaves.push(Leaf {
            node: self.nodes.len(),
            candidates: self.fringe_of(&path),
            instances: VecDeque::new(),
            since_test: 0,
            tests: 0,
            open: true,
        });
        self.nodes.push(Node::Leaf(row));
        self.paths.push(path);
        self.nodes.len() - 1
    }

    /// Walk the tree to a leaf through the learner's sensors (charged through `cost`);
    /// `table` is given when unseen values may add leaves, else a value with no branch
    /// gives `None`.
    fn walk<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        previous: u32,
        mut table: Option<&mut QTable>,
        cost: &mut f64,
    ) -> Option<RowId> {
        if self.nodes.is_empty() {
            let table = table.as_deref_mut()?;
            self.new_leaf(Vec::new(), table);
        }
        let mut at = 0;
        loop {
            let (prices, sensor) = (&self.prices[..], &mut self.sensor);
            let found = descend(&self.nodes, at, |d| {
                read(prices, world, s, d, previous, sensor, cost)
            });
            let (node, value) = match found {
                Ok(row) => return Some(row),
                Err(missing) => missing,
            };
            let table = table.as_deref_mut()?;
            let Node::Split { test, .. } = self.nodes[node] else {
                unreachable!("only a split node lacks a branch");
            };
            let mut path = self.paths[node].clone();
            path.push((test, value));
            let child = self.new_leaf(path, table);
            if let Node::Split { children, .. } = &mut self.nodes[node] {
                children.push((value, child));
            }
            at = child;
        }
    }

    /// Record the fringe of the leaf `row` at state `s`, if it collects.
    fn note<W: World + ?Sized>(&mut self, world: &W, s: StateId, row: RowId, cost: &mut f64) {
        let leaf = &self.leaves[row.index()];
        if !leaf.open {
            self.last = self.current.take();
            return;
        }
        let (prices, sensor, previous) = (&self.prices[..], &mut self.sensor, self.previous);
        let values = leaf
            .candidates
            .iter()
            .map(|&d| read(prices, world, s, d, previous, sensor, cost))
            .collect();
        self.last = self.current.replace(Pending { row, values });
    }

    /// Test leaf `row` and split it if a distinction makes a difference.
    fn test(&mut self, row: RowId, table: &mut QTable) {
        let gamma = self.gamma;
        let params = self.params;
        let leaf = &mut self.leaves[row.index()];
        leaf.since_test = 0;
        leaf.tests += 1;
        let returns: Vec<f64> = leaf
            .instances
            .iter()
            .map(|i| i.reward + i.next.map_or(0.0, |n| gamma * table.v(n)))
            .collect();
        let mut comparisons = 0usize;
        let mut best: Option<(f64, usize)> = None;
        for c in 0..leaf.candidates.len() {
            for a in 0..table.num_actions() as u32 {
                let mut groups: Vec<(u32, Vec<f64>)> = Vec::new();
                for (i, r) in leaf.instances.iter().zip(&returns) {
                    if i.action.0 != a {
                        continue;
                    }
                    let v = i.values[c];
                    match groups.iter_mut().find(|(g, _)| *g == v) {
                        Some((_, xs)) => xs.push(*r),
                        None => groups.push((v, vec![*r])),
                    }
                }
                groups.retain(|(_, xs)| xs.len() >= params.min_group);
                for i in 0..groups.len() {
                    for j in i + 1..groups.len() {
                        comparisons += 1;
                        let p = ks_p_value(&groups[i].1, &groups[j].1);
                        if best.is_none_or(|(bp, _)| p < bp) {
                            best = Some((p, c));
                        }
                    }
                }
            }
        }
        match best {
            Some((p, c)) if p < params.alpha / comparisons as f64 => self.split(row, c, table),
            _ => {
                if leaf.tests >= params.patience {
                    leaf.open = false;
                    leaf.instances.clear();
                }
            }
        }
    }

    /// Split leaf `row` on its candidate `c`.
    fn split(&mut self, row: RowId, c: usize, table: &mut QTable) {
        self.splits += 1;
        let leaf = &self.leaves[row.index()];
        let test = leaf.candidates[c];
        let node = leaf.node;
        let mut counts: Vec<(u32, usize)> = Vec::new();
        for i in &leaf.instances {
            match counts.iter_mut().find(|(v, _)| *v == i.values[c]) {
                Some((_, n)) => *n += 1,
                None => counts.push((i.values[c], 1)),
            }
        }
        // Most frequent first (ties: the smaller value); it keeps the row.
        counts.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        let path = self.paths[node].clone();
        let mut children = Vec::new();
        for (k, &(value, _)) in counts.iter().enumerate() {
            let mut p = path.clone();
            p.push((test, value));
            if k == 0 {
                // The leaf itself, one level down: same row, a new path and fringe.
                let candidates = self.fringe_of(&p);
                let child = self.nodes.len();
                self.nodes.push(Node::Leaf(row));
                self.paths.push(p);
                self.leaves[row.index()] = Leaf {
                    node: child,
                    candidates,
                    instances: VecDeque::new(),
                    since_test: 0,
                    tests: 0,
                    open: true,
                };
                children.push((value, child));
            } else {
                children.push((value, self.new_leaf(p, table)));
            }
        }
        self.nodes[node] = Node::Split { test, children };
        // Pending instances of the old leaf no longer fit its fringe.
        for p in [&mut self.current, &mut self.last] {
            if p.as_ref().is_some_and(|p| p.row == row) {
                *p = None;
            }
        }
    }

    fn fringe_of(&self, path: &[(Distinction, u32)]) -> Vec<Distinction> {
        let mut candidates: Vec<Distinction> = self
            .prices
            .iter()
            .enumerate()
            .map(|(f, _)| Feature(f as u32))
            .filter(|f| !path.iter().any(|(d, _)| *d == Distinction::Feature(*f)))
            .take(self.params.fringe)
            .map(Distinction::Feature)
            .collect();
        if !path.iter().any(|(d, _)| *d == Distinction::PreviousAction) {
            candidates.push(Distinction::PreviousAction);
        }
        candidates
    }

    /// The row of state `s` after the previous action `previous`, free and noiseless
    /// (`None` where classifying would add a leaf).
    fn peek<W: World + ?Sized>(&self, world: &W, s: StateId, previous: u32) -> Option<RowId> {
        if self.nodes.is_empty() {
            return None;
        }
        let (mut cost, mut exact) = (0.0, SensorModel::<Xoshiro256PlusPlus>::exact());
        descend(&self.nodes, 0, |d| {
            read(&self.prices, world, s, d, previous, &mut exact, &mut cost)
        })
        .ok()
    }
}

impl Perception for UTree {
    fn classify<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.previous = NO_ACTION;
        let mut cost = 0.0;
        let row = self
            .walk(world, s, NO_ACTION, Some(table), &mut cost)
            .expect("a table is given");
        self.note(world, s, row, &mut cost);
        (row, cost)
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
        self.previous = a.0;
        let mut cost = 0.0;
        let row = self
            .walk(world, s, self.previous, Some(table), &mut cost)
            .expect("a table is given");
        self.note(world, s, row, &mut cost);
        (row, cost)
    }

    fn refine<W: World + ?Sized>(&mut self, _world: &W, _row: RowId, _s: StateId) -> Option<f64> {
        None
    }

    fn updated(
        &mut self,
        row: RowId,
        a: ActionId,
        reward: f64,
        next: Option<RowId>,
        table: &mut QTable,
    ) {
        let pending = if next.is_some() {
            self.last.take()
        } else {
            self.current.take()
        };
        let Some(p) = pending.filter(|p| p.row == row) else {
            return;
        };
        let window = self.params.window;
        let leaf = &mut self.leaves[row.index()];
        if !leaf.open {
            return;
        }
        if leaf.instances.len() == window {
            leaf.instances.pop_front();
        }
        leaf.instances.push_back(Instance {
            values: p.values,
            action: a,
            reward,
            next,
        });
        leaf.since_test += 1;
        if leaf.since_test >= self.params.test_every {
            self.test(row, table);
        }
    }

    fn rows(&self) -> usize {
        self.leaves.len()
    }

    /// A split moves the states of a leaf to its new children without a refinement.
    fn keeps_rows(&self) -> bool {
        false
    }

    /// The row of `s` at a trial's start (no previous action).
    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        self.peek(world, s, NO_ACTION)
    }
}

impl crate::perception::view::Sees for UTree {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId> {
        if self.nodes.is_empty() {
            return None;
        }
        // The evaluation's own noise and generator; the charge is not counted.
        let (previous, mut cost) = (self.seen_previous, 0.0);
        let mut sensor = SensorModel::noisy(noise, rng);
        descend(&self.nodes, 0, |d| {
            read(&self.prices, world, s, d, previous, &mut sensor, &mut cost)
        })
        .ok()
    }
    fn memoryless(&self) -> bool {
        !self.nodes.iter().any(|n| {
            matches!(
                n,
                Node::Split {
                    test: Distinction::PreviousAction,
                    ..
                }
            )
        })
    }
    fn begin(&mut self) {
        self.seen_previous = NO_ACTION;
    }
    fn moved(&mut self, a: ActionId) {
        self.seen_previous = a.0;
    }
}

impl crate::perception::view::Describes for UTree {
    /// The features of each leaf's path (its previous-action tests are not features).
    fn described(&self) -> Vec<(RowId, Vec<(Feature, Reading)>)> {
        self.leaves
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let features = self.paths[l.node]
                    .iter()
                    .filter_map(|&(d, v)| match d {
                        Distinction::Feature(f) => Some((f, Reading(v))),
                        Distinction::PreviousAction => None,
                    })
                    .collect();
                (RowId(i as u32), features)
            })
            .collect()
    }

    /// The features on the path of `s` at a trial's start (the fringe is no longer
    /// measured once learning is over).
    fn cost_after_learning<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        let mut cost = 0.0;
        if !self.nodes.is_empty() {
            // A value with no branch ends the walk where it was read.
            let mut exact = SensorModel::<Xoshiro256PlusPlus>::exact();
            let _ = descend(&self.nodes, 0, |d| {
                read(&self.prices, world, s, d, NO_ACTION, &mut exact, &mut cost)
            });
        }
        cost
    }
}

/// Descend from `node` to a leaf, reading each tested distinction with `read`: the
/// leaf's row, or the split node and the value read there that has no branch.
fn descend(
    nodes: &[Node],
    mut node: usize,
    mut read: impl FnMut(Distinction) -> u32,
) -> Result<RowId, (usize, u32)> {
    loop {
        match &nodes[node] {
            Node::Leaf(row) => return Ok(*row),
            Node::Split { test, children } => {
                let value = read(*test);
                node = children
                    .iter()
                    .find(|(v, _)| *v == value)
                    .ok_or((node, value))?
                    .1;
            }
        }
    }
}

/// Read a distinction at state `s`: the previous action, or a feature's value through
/// `sensor`, its cost added to `cost`.
fn read<W: World + ?Sized, G: Rng>(
    prices: &[f64],
    world: &W,
    s: StateId,
    d: Distinction,
    previous: u32,
    sensor: &mut SensorModel<G>,
    cost: &mut f64,
) -> u32 {
    match d {
        Distinction::PreviousAction => previous,
        Distinction::Feature(f) => {
            *cost += prices[f.index()] * f64::from(sensor.reads());
            sensor.read(world, s, f).0
        }
    }
}

/// The asymptotic p-value of the two-sample Kolmogorov-Smirnov test of `a` against `b`:
/// `Q(sqrt(n) D)` with `n = |a||b| / (|a| + |b|)`, `D` the largest gap between the two
/// empirical distribution functions and `Q(x) = 2 sum_k (-1)^(k-1) exp(-2 k^2 x^2)`.
///
/// ```
/// // Identical samples: no evidence of a difference.
/// assert_eq!(csql::ks_p_value(&[1.0, 2.0, 3.0], &[1.0, 2.0, 3.0]), 1.0);
/// // Thirty values apart from thirty others: a difference beyond doubt.
/// let a = vec![0.0; 30];
/// let b = vec![1.0; 30];
/// assert!(csql::ks_p_value(&a, &b) < 1e-6);
/// ```
pub fn ks_p_value(a: &[f64], b: &[f64]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return 1.0;
    }
    let mut x = a.to_vec();
    let mut y = b.to_vec();
    x.sort_by(f64::total_cmp);
    y.sort_by(f64::total_cmp);
    let (n, m) = (x.len(), y.len());
    let (mut i, mut j, mut d) = (0, 0, 0.0f64);
    while i < n && j < m {
        let v = x[i].min(y[j]);
        while i < n && x[i] <= v {
            i += 1;
        }
        while j < m && y[j] <= v {
            j += 1;
        }
        d = d.max((i as f64 / n as f64 - j as f64 / m as f64).abs());
    }
    let en = ((n * m) as f64 / (n + m) as f64).sqrt();
    let lambda = (en + 0.12 + 0.11 / en) * d;
    if lambda < 1e-3 {
        return 1.0;
    }
    let mut sum = 0.0;
    let mut sign = 1.0;
    for k in 1..=100 {
        let term = (-2.0 * (k * k) as f64 * lambda * lambda).exp();
        sum += sign * term;
        if term < 1e-12 {
            break;
        }
        sign = -sign;
    }
    (2.0 * sum).clamp(0.0, 1.0)
}
