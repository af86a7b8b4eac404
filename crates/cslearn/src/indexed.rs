//! CS-ID3 and ID3 over an index of the library: the same learner as [`cs_id3`] and
//! [`id3`], whose cost per object grows with the depth of what it learned instead of the
//! size of its library.
//!
//! The plain [`Learner`](crate::Learner) starts every object by attending the whole
//! library and counts the attended examples afresh at every selection, so each object
//! costs time in proportion to the library. But with observation attending, the examples
//! attended after measuring `f1 = v1, ..., fk = vk` (a missing value dropping nothing) are
//! a function of those measurements alone, and so is the next selection (the candidates
//! are the features not yet measured). The index is therefore a tree, built lazily along
//! the paths objects take: a node is such a sequence of measurements, and it keeps its
//! attended examples and their class counts (as [`SplitCounts`] keeps them while the node
//! has few classes, in hash maps past that), and remembers its decision until they change. Nodes catch up with the library
//! when a pass visits them (the root with the examples added since its last visit, a child
//! with those its parent gained since), so a new example costs a few look-ups per pair it
//! has, per node it reaches, instead of a recount. When
//! a node's selection changes, the children built for the old feature stay, untouched and
//! costing nothing, until a selection leads back to them. The one example that changes
//! after it was added (the learner refines the new example during its recheck) is taken
//! back out of the nodes visited since it was added.
//!
//! Selection is scored from the counts. A node of few classes scores them by
//! [`InfoCost::select_from_counts`], whose one scoring function [`InfoCost::select_from`]
//! shares. A node of many classes keeps, beside its counts, the sums of the `x log2 x`
//! terms that the I^2/C scores are made of, exactly (as integers at a scale of 2^-52),
//! updated in time independent of the number of classes; from them it bounds, for every
//! candidate, the score that function computes in floating point, and runs the selection's
//! rule over the bounds; where the bounds leave a comparison open, it sorts the node's
//! counts and scores them by that very function. A selection there costs time in
//! proportion to the features, not to the classes, and is the plain one bit for bit (the
//! argument is in `src/counts.rs`). Prediction, discrimination (the same [`Discriminate`]
//! parts, over the same conflicting examples) and updating are the plain procedure's. The learner therefore measures the same features in the same
//! order, predicts the same classes, charges the same costs and builds the same library as
//! [`cs_id3`] and [`id3`], bit for bit (`tests/indexed.rs` checks this object by object).

use rand::Rng;

use crate::attend::{Attention, ObservationAttending};
use crate::counts::{Fallback, NodeCounts, Terms};
use crate::discriminate::{CheapestFirst, Discriminate, RandomOrder};
use crate::example::{Example, Library};
use crate::learner::{Classified, Outcome, StreamReport};
use crate::predict::Votes;
use crate::select::{InfoCost, MissingRule};
use crate::sensing::{Ledger, Probe, Sensor};
use crate::types::{ClassId, Cost, CostBlind, FeatureCosts, FeatureId, Value};

#[cfg(doc)]
use crate::learner::{cs_id3, id3};
#[cfg(doc)]
use crate::select::SplitCounts;

/// CS-ID3 or ID3 (by its discrimination part `D` and whether selection is cost-blind)
/// over an index of the library: the same outcomes, charges and library as the plain
/// [`Learner`](crate::Learner) with [`ObservationAttending`], [`InfoCost`] (own-branch
/// rule), [`Unanimous`](crate::Unanimous), `D` and [`AppendAll`](crate::AppendAll), in
/// time per object that grows far slower than the library (see the module docs of
/// [`cslearn`](crate) for measured figures).
///
/// Build one with [`cs_id3_indexed`] or [`id3_indexed`].
///
/// ```
/// use cslearn::{ClassId, FeatureCosts, Value};
/// let costs = FeatureCosts::from_f64(&[1.0, 50.0]).unwrap();
/// let objects = [[Some(Value(0)), Some(Value(5))], [Some(Value(1)), Some(Value(6))]];
/// let mut fast = cslearn::cs_id3_indexed(costs.clone());
/// let mut plain = cslearn::cs_id3(costs);
/// for _ in 0..3 {
///     for (i, object) in objects.iter().enumerate() {
///         let class = ClassId(i as u32);
///         assert_eq!(fast.learn(&object[..], class), plain.learn(&object[..], class));
///         assert_eq!(fast.ledger(), plain.ledger());
///     }
/// }
/// assert_eq!(fast.library(), plain.library());
/// ```
#[derive(Clone, Debug)]
pub struct IndexedLearner<D> {
    costs: FeatureCosts,
    cost_blind: bool,
    library: Library,
    tree: Tree,
    select: InfoCost,
    discriminate: D,
    conflicting: Attention,
    ledger: Ledger,
    recheck: bool,
}

/// CS-ID3 over an index of the library ([`cs_id3_indexed`]).
pub type IndexedCsId3 = IndexedLearner<CheapestFirst>;

/// Cost-blind ID3 over an index of the library ([`id3_indexed`]).
pub type IndexedId3<R> = IndexedLearner<RandomOrder<R>>;

/// CS-ID3 over the features priced by `costs`, indexed: the same results as
/// [`cs_id3`], faster on large libraries.
///
/// ```
/// let learner = cslearn::cs_id3_indexed(cslearn::FeatureCosts::from_f64(&[1.0]).unwrap());
/// assert!(learner.library().is_empty());
/// ```
pub fn cs_id3_indexed(costs: FeatureCosts) -> IndexedCsId3 {
    IndexedLearner::new(costs, false, CheapestFirst)
}

/// Cost-blind ID3 over the features priced by `costs`, drawing its discrimination orders
/// from `rng`, indexed: the same results as [`id3`] with the same generator.
///
/// ```
/// use rand::SeedableRng;
/// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let learner = cslearn::id3_indexed(cslearn::FeatureCosts::from_f64(&[1.0]).unwrap(), rng);
/// assert!(learner.library().is_empty());
/// ```
pub fn id3_indexed<R: Rng>(costs: FeatureCosts, rng: R) -> IndexedId3<R> {
    IndexedLearner::new(costs, true, RandomOrder::new(rng))
}

impl<D: Discriminate> IndexedLearner<D> {
    fn new(costs: FeatureCosts, cost_blind: bool, discriminate: D) -> Self {
        IndexedLearner {
            costs,
            cost_blind,
            library: Library::new(),
            tree: Tree::new(),
            select: InfoCost::new(MissingRule::OwnBranch),
            discriminate,
            conflicting: Attention::new(),
            ledger: Ledger::default(),
            recheck: true,
        }
    }

    /// The same learner with `library` as what it learned (its index starts afresh and
    /// catches up with the library as objects come).
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureCosts, FeatureId, Library, Value};
    /// let library: Library = [Example::from_pairs([(FeatureId(0), Value(1))], ClassId(2))].into_iter().collect();
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap()).with_library(library);
    /// assert_eq!(learner.classify(&[Some(Value(1))][..]).class, Some(ClassId(2)));
    /// ```
    pub fn with_library(mut self, library: Library) -> Self {
        self.library = library;
        self.tree = Tree::new();
        self
    }

    /// The library, taking the learner apart (no copy).
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// learner.learn(&[Some(Value(0))][..], ClassId(1));
    /// assert_eq!(learner.into_library().len(), 1);
    /// ```
    pub fn into_library(self) -> Library {
        self.library
    }

    /// Predict the class of the object behind `sensor`, as
    /// [`Learner::classify`](crate::Learner::classify) does.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// assert_eq!(learner.classify(&[Some(Value(0))][..]).class, None);
    /// learner.learn(&[Some(Value(0))][..], ClassId(4));
    /// assert_eq!(learner.classify(&[Some(Value(0))][..]).class, Some(ClassId(4)));
    /// ```
    pub fn classify<T: Sensor>(&mut self, sensor: T) -> Classified {
        let (class, _) = self.run(sensor, None);
        Classified {
            class,
            cost: self.ledger.cost(),
        }
    }

    /// [`classify`](IndexedLearner::classify), with the examples attended when it
    /// predicted counted by class (the last non-empty attended set when a measurement
    /// left none), as
    /// [`Learner::classify_with_votes`](crate::Learner::classify_with_votes) counts them.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// learner.learn(&[Some(Value(0))][..], ClassId(1));
    /// learner.learn(&[Some(Value(0))][..], ClassId(1));
    /// let (answer, votes) = learner.classify_with_votes(&[Some(Value(0))][..]);
    /// assert_eq!((answer.class, votes.total()), (Some(ClassId(1)), 2));
    /// ```
    pub fn classify_with_votes<T: Sensor>(&mut self, sensor: T) -> (Classified, Votes) {
        let (class, voters) = self.run(sensor, None);
        let votes = voters.map_or_else(Votes::default, |node| {
            let library = &self.library;
            Votes::of(
                self.tree.nodes[node]
                    .members
                    .iter()
                    .map(|&i| library[i as usize].class()),
            )
        });
        let classified = Classified {
            class,
            cost: self.ledger.cost(),
        };
        (classified, votes)
    }

    /// Learn from one object whose true class is `class`, as
    /// [`Learner::learn`](crate::Learner::learn) does.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, FeatureId, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0, 2.0]).unwrap());
    /// learner.learn(&[Some(Value(0)), Some(Value(0))][..], ClassId(0));
    /// let second = learner.learn(&[Some(Value(1)), Some(Value(0))][..], ClassId(1));
    /// assert_eq!(second.predicted, Some(ClassId(0)));
    /// assert_eq!(learner.library()[1].pairs(), &[(FeatureId(0), Value(1))]);
    /// ```
    pub fn learn<T: Sensor>(&mut self, sensor: T, class: ClassId) -> Outcome {
        let (predicted, _) = self.run(sensor, Some(class));
        Outcome {
            predicted,
            class,
            cost: self.ledger.cost(),
            measured: self.ledger.measured().len(),
        }
    }

    /// Learn from each (object, true class) in turn, as
    /// [`Learner::stream`](crate::Learner::stream) does.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// let rows = [[Some(Value(0))], [Some(Value(0))]];
    /// let report = learner.stream(rows.iter().map(|r| (&r[..], ClassId(0))));
    /// assert_eq!((report.objects, report.errors), (2, 1));
    /// ```
    pub fn stream<T: Sensor>(
        &mut self,
        objects: impl IntoIterator<Item = (T, ClassId)>,
    ) -> StreamReport {
        let full_cost = self.costs.total().get();
        crate::learner::stream_report(
            full_cost,
            objects.into_iter().map(|(o, c)| self.learn(o, c)),
        )
    }

    /// Turn the recheck after learning on or off (on by default), as
    /// [`Learner::recheck`](crate::Learner::recheck) does.
    ///
    /// ```
    /// let learner = cslearn::cs_id3_indexed(cslearn::FeatureCosts::new(Vec::new())).recheck(false);
    /// assert!(!learner.rechecks());
    /// ```
    pub fn recheck(mut self, on: bool) -> Self {
        self.recheck = on;
        self
    }

    /// Whether the learner checks, after learning an object, that it is now recognised.
    ///
    /// ```
    /// assert!(cslearn::cs_id3_indexed(cslearn::FeatureCosts::new(Vec::new())).rechecks());
    /// ```
    pub fn rechecks(&self) -> bool {
        self.recheck
    }

    /// The example library (read only: the index follows every change the learner makes).
    ///
    /// ```
    /// assert!(cslearn::cs_id3_indexed(cslearn::FeatureCosts::new(Vec::new())).library().is_empty());
    /// ```
    pub fn library(&self) -> &Library {
        &self.library
    }

    /// The price list charged.
    ///
    /// ```
    /// let learner = cslearn::cs_id3_indexed(cslearn::FeatureCosts::from_f64(&[3.0]).unwrap());
    /// assert_eq!(learner.costs().total().get(), 3.0);
    /// ```
    pub fn costs(&self) -> &FeatureCosts {
        &self.costs
    }

    /// Add a new feature (no closed world): from now on it can be measured and charged.
    ///
    /// ```
    /// let mut learner = cslearn::cs_id3_indexed(cslearn::FeatureCosts::new(Vec::new()));
    /// assert_eq!(learner.add_feature(cslearn::Cost::ONE), cslearn::FeatureId(0));
    /// ```
    pub fn add_feature(&mut self, cost: Cost) -> FeatureId {
        // Every remembered decision was taken under the old price list.
        self.tree.forget_decisions();
        self.costs.push(cost)
    }

    /// What was measured on the last object, and what it cost.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[2.0]).unwrap());
    /// learner.learn(&[Some(Value(0))][..], ClassId(0)); // nothing to measure against yet
    /// assert_eq!(learner.ledger().cost().get(), 0.0);
    /// learner.learn(&[Some(Value(1))][..], ClassId(1));
    /// assert_eq!(learner.ledger().cost().get(), 2.0);
    /// ```
    pub fn ledger(&self) -> &Ledger {
        &self.ledger
    }

    /// The number of nodes the index holds now (a measure of its memory).
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// assert_eq!(learner.index_nodes(), 1); // the root
    /// learner.learn(&[Some(Value(0))][..], ClassId(0));
    /// learner.learn(&[Some(Value(1))][..], ClassId(1));
    /// learner.learn(&[Some(Value(1))][..], ClassId(1));
    /// assert!(learner.index_nodes() > 1);
    /// ```
    pub fn index_nodes(&self) -> usize {
        self.tree.len()
    }

    /// How many times the index has looked at an example so far (an example counted into
    /// a node, or checked against a node's measurement): a measure of its work that does
    /// not depend on the machine. Per object it grows with the depth of what was learned
    /// and the examples a node gains, not with the size of the library.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// assert_eq!(learner.examples_visited(), 0);
    /// learner.learn(&[Some(Value(0))][..], ClassId(0));
    /// learner.learn(&[Some(Value(1))][..], ClassId(1)); // the root counts the first
    /// assert!(learner.examples_visited() >= 1);
    /// ```
    pub fn examples_visited(&self) -> u64 {
        self.tree.visited
    }

    /// The cycle for one object, step for step the plain learner's (`learner.rs`) with
    /// attending, selection and prediction answered by the tree.
    ///
    /// Returns the class predicted first and the node whose examples it went by.
    fn run<T: Sensor>(
        &mut self,
        sensor: T,
        label: Option<ClassId>,
    ) -> (Option<ClassId>, Option<NodeId>) {
        let IndexedLearner {
            costs,
            cost_blind,
            library,
            tree,
            select,
            discriminate,
            conflicting,
            ledger,
            recheck,
        } = self;
        ledger.clear();
        let mut probe = Probe::new(sensor, &*costs, ledger);
        let mut pass = Pass {
            tree,
            select,
            cost_blind: *cost_blind,
        };
        let (predicted, attended, voters) = pass.predict(library, &mut probe);
        let Some(label) = label else {
            return (predicted, voters);
        };
        let correct = predicted == Some(label);
        if !correct {
            pass.tree.discriminate(
                library,
                attended,
                label,
                conflicting,
                discriminate,
                &mut probe,
            );
        }
        // Step 4, as `AppendAll` does it: every example is kept.
        let index = library.push(probe.ledger().to_example(label));
        pass.tree.added();
        if *recheck {
            for _ in 0..=costs.len() {
                let paid = probe.ledger().measured().len();
                probe.ledger_mut().start_pass();
                let (again, attended, _) = pass.predict(library, &mut probe);
                if again != Some(label) {
                    pass.tree.discriminate(
                        library,
                        attended,
                        label,
                        conflicting,
                        discriminate,
                        &mut probe,
                    );
                }
                let refined = probe.ledger().to_example(label);
                if refined != library[index] {
                    pass.tree.refining(index, &library[index]);
                    if let Some(example) = library.get_mut(index) {
                        *example = refined;
                    }
                }
                // A round that paid for more has changed the example, and with it what the
                // library predicts: check again.
                if probe.ledger().measured().len() == paid {
                    break;
                }
            }
        }
        (predicted, voters)
    }
}

/// What the tree needs for one pass over an object.
struct Pass<'a> {
    tree: &'a mut Tree,
    select: &'a mut InfoCost,
    cost_blind: bool,
}

impl Pass<'_> {
    /// Figure 2, step 1, down the tree: the class predicted (`None` for an empty
    /// library), the node whose examples were attended at the moment of prediction
    /// (`None` when a measurement left none attended), and the node whose examples the
    /// prediction went by (that one, or the last non-empty attended set's).
    fn predict<T: Sensor>(
        &mut self,
        library: &Library,
        probe: &mut Probe<'_, T>,
    ) -> (Option<ClassId>, Option<NodeId>, Option<NodeId>) {
        if library.is_empty() {
            // Nothing attended and no earlier set: `Unanimous` abstains.
            return (None, None, None);
        }
        let mut node = self.tree.root(library);
        loop {
            let step = self.tree.step(node, self.select, probe, self.cost_blind);
            let feature = match step {
                Step::Predict(class) => return (class, Some(node), Some(node)),
                Step::Measure(feature) => feature,
            };
            let value = probe.measure(feature);
            if let Some(v) = value
                && self.tree.nodes[node].counts.having(feature, v) == 0
            {
                // Nothing is attended any more: the majority of the last non-empty
                // attended set, this node's.
                return (self.tree.nodes[node].counts.majority(), None, Some(node));
            }
            node = self.tree.child(node, feature, value, library);
        }
    }
}

type NodeId = usize;

const ROOT: NodeId = 0;

/// A node's decision, remembered until its examples change.
#[derive(Clone, Copy, Debug)]
enum Step {
    /// Stop and predict this class (unanimous, or the majority when nothing is left to
    /// measure; `None` only for no examples, which a visited node never has).
    Predict(Option<ClassId>),
    /// Measure this feature next.
    Measure(FeatureId),
}

/// One sequence of measurements from the root: the examples it attends (as far as it has
/// caught up with the library), their counts, and its children.
#[derive(Clone, Debug, Default)]
struct Node {
    /// Library indices of the attended examples, ascending.
    members: Vec<u32>,
    counts: NodeCounts,
    /// The examples below this library index have been looked at.
    synced: usize,
    /// ((measured feature, measured value), child), ascending; a `None` value is a
    /// missing one, which drops nothing. Children of every feature ever selected here are
    /// kept: a selection that changes back finds its subtree still there.
    children: Vec<((FeatureId, Option<Value>), NodeId)>,
    step: Option<Step>,
}

/// The lazily built tree over the library, with the root (every example) at [`ROOT`].
///
/// Nodes catch up with the library when a pass visits them, not when an example is
/// added: the root looks at the examples added since its last visit, a child at the ones
/// its parent gained since. A subtree no longer on any object's path (its parent selects
/// another feature now) so costs nothing until a selection leads back to it.
#[derive(Clone, Debug)]
struct Tree {
    nodes: Vec<Node>,
    /// The nodes visited since the last example was added: the only ones that can have
    /// counted it, and so the ones to correct when the learner refines it.
    touched: Vec<NodeId>,
    /// Examples looked at so far, one count per example per node that looked at it.
    visited: u64,
    /// `x log2 x` terms of the counts, shared by every node.
    terms: Terms,
    /// Scratch for selections the exact sums leave open.
    fallback: Fallback,
}

impl Tree {
    fn new() -> Tree {
        Tree {
            nodes: vec![Node::default()],
            touched: Vec::new(),
            visited: 0,
            terms: Terms::new(),
            fallback: Fallback::default(),
        }
    }

    fn len(&self) -> usize {
        self.nodes.len()
    }

    /// How many examples at `node` are of another class than `label`.
    fn conflicts(&self, node: NodeId, label: ClassId) -> u32 {
        let counts = &self.nodes[node].counts;
        counts.len() - counts.class_total(label)
    }

    /// Figure 2, step 3, from the examples attended at the moment of prediction, those of
    /// `node` (none for `None`): the conflicting ones are those of another class than
    /// `label`. Where the discrimination's order does not depend on the examples, the
    /// conflicting examples after each measurement are those of the child reached by it,
    /// so the walk down the index measures what filtering them would, without looking at
    /// them; otherwise they are filtered one by one.
    fn discriminate<D: Discriminate, T: Sensor>(
        &mut self,
        library: &Library,
        node: Option<NodeId>,
        label: ClassId,
        conflicting: &mut Attention,
        discriminate: &mut D,
        probe: &mut Probe<'_, T>,
    ) {
        let Some(mut node) = node else {
            // Nothing conflicts: nothing is measured, nothing is drawn.
            conflicting.attend_only(std::iter::empty());
            return discriminate.discriminate(library, &ObservationAttending, conflicting, probe);
        };
        if self.conflicts(node, label) == 0 {
            conflicting.attend_only(std::iter::empty());
            return discriminate.discriminate(library, &ObservationAttending, conflicting, probe);
        }
        let Some(order) = discriminate.order(probe.costs()) else {
            let members = &self.nodes[node].members;
            self.visited += members.len() as u64;
            conflicting.attend_only(
                members
                    .iter()
                    .map(|&i| i as usize)
                    .filter(|&i| library[i].class() != label),
            );
            return discriminate.discriminate(library, &ObservationAttending, conflicting, probe);
        };
        for &feature in order {
            if self.conflicts(node, label) == 0 {
                return;
            }
            if probe.ledger().consulted(feature) {
                continue;
            }
            let value = probe.measure(feature);
            node = self.child(node, feature, value, library);
        }
    }

    fn forget_decisions(&mut self) {
        self.nodes.iter_mut().for_each(|n| n.step = None);
    }

    /// A new example is in the library: no node has counted it yet.
    fn added(&mut self) {
        self.touched.clear();
    }

    /// Example `index`, the last one, is about to change from `example`: the nodes that
    /// counted it forget it, and count it again, changed, when next visited.
    fn refining(&mut self, index: usize, example: &Example) {
        for &n in &self.touched {
            let node = &mut self.nodes[n];
            if node.members.last().map(|&i| i as usize) == Some(index) {
                node.members.pop();
                node.counts.remove(example, &mut self.terms);
                node.step = None;
            }
            node.synced = node.synced.min(index);
        }
        self.touched.clear();
    }

    /// The root, caught up with the library.
    fn root(&mut self, library: &Library) -> NodeId {
        let root = &mut self.nodes[ROOT];
        if root.synced < library.len() {
            self.visited += (library.len() - root.synced) as u64;
            for i in root.synced..library.len() {
                // Counts are `u32`: the index holds fewer than 2^32 examples.
                root.members.push(i as u32);
                root.counts.add(&library[i], &mut self.terms);
            }
            root.synced = library.len();
            root.step = None;
        }
        self.touched.push(ROOT);
        ROOT
    }

    /// The decision at `node`, whose examples are not empty. Its candidates are the
    /// features not consulted in this pass, which are exactly those not on its path.
    fn step<T: Sensor>(
        &mut self,
        node: NodeId,
        select: &mut InfoCost,
        probe: &Probe<'_, T>,
        cost_blind: bool,
    ) -> Step {
        let fallback = &mut self.fallback;
        let node = &mut self.nodes[node];
        if let Some(step) = node.step {
            return step;
        }
        let counts = &mut node.counts;
        let step = if let Some(class) = counts.only_class() {
            Step::Predict(Some(class))
        } else {
            let ledger = probe.ledger();
            let measured = |f| ledger.consulted(f);
            let rules = select.rules();
            let chosen = if cost_blind {
                counts.select(rules, measured, &CostBlind(probe.costs()), fallback)
            } else {
                counts.select(rules, measured, probe.costs(), fallback)
            };
            chosen.map_or_else(|| Step::Predict(counts.majority()), Step::Measure)
        };
        node.step = Some(step);
        step
    }

    /// The child of `node` (caught up with the library) after measuring `feature` as
    /// `value`, created if new, and caught up with its parent.
    fn child(
        &mut self,
        node: NodeId,
        feature: FeatureId,
        value: Option<Value>,
        library: &Library,
    ) -> NodeId {
        let key = (feature, value);
        let id = match self.nodes[node]
            .children
            .binary_search_by_key(&key, |c| c.0)
        {
            Ok(k) => self.nodes[node].children[k].1,
            Err(k) => {
                self.nodes.push(Node::default());
                let id = self.nodes.len() - 1;
                self.nodes[node].children.insert(k, (key, id));
                id
            }
        };
        let mut child = std::mem::take(&mut self.nodes[id]);
        let parent = &self.nodes[node];
        let new = &parent.members[parent
            .members
            .partition_point(|&i| (i as usize) < child.synced)..];
        let before = child.members.len();
        self.visited += new.len() as u64;
        for &i in new {
            let example = &library[i as usize];
            if value.is_none() || example.get(feature) == value {
                child.members.push(i);
                child.counts.add(example, &mut self.terms);
            }
        }
        if child.members.len() > before {
            child.step = None;
        }
        child.synced = library.len();
        self.nodes[id] = child;
        self.touched.push(id);
        id
    }
}
