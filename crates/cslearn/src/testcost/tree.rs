//! Growing, pruning and using a test-cost decision tree.
//!
//! One grower serves the whole family; what differs between learners is the score of a
//! split ([`Criterion`], the framework's selection function), whether growth stops when
//! no test pays for itself (DTMC), and whether the tree is pruned afterwards.

use super::budget::Budget;
use super::criterion::Criterion;
use super::data::{Column, Frame};
use super::prices::{MisclassCosts, TestPrices};
use super::splits::{Splits, Stat};
use crate::Error;

/// How a tree is grown.
///
/// ```
/// let params = cslearn::testcost::GrowParams::new(cslearn::testcost::Criterion::C45).pruned(0.25);
/// assert_eq!(params.confidence, Some(0.25));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GrowParams {
    /// The selection function.
    pub criterion: Criterion,
    /// C4.5's pessimistic pruning at this confidence, or no pruning.
    pub confidence: Option<f64>,
    /// The least weight of objects in each of two branches of a split (C4.5's `-m`, 2).
    pub min_objects: f64,
    /// The deepest a path may be (guards against runaway growth; 64 by default).
    pub max_depth: usize,
    /// The price the selection function sees for a test (what an object pays is always
    /// priced after its path).
    #[serde(default)]
    pub selection_prices: SelectionPrices,
    /// What pessimistic pruning weighs (when `confidence` is set).
    #[serde(default)]
    pub pruning: Pruning,
    /// The most an object may spend on the tests of its path: at a node, a test whose
    /// price after the node's path would take the path past the budget (in price, at the
    /// prices the tree is grown with, or in distinct tests) is not a candidate. Unlimited
    /// by default, which grows the same trees as before budgets existed.
    #[serde(default, skip_serializing_if = "Budget::is_unlimited")]
    pub budget: Budget,
}

/// What pessimistic pruning weighs a subtree against a leaf by.
///
/// ```
/// use cslearn::testcost::Pruning;
/// assert_eq!(Pruning::default(), Pruning::Errors);
/// assert_eq!(Pruning::parse("costs").unwrap().name(), "costs");
/// assert!(Pruning::parse("none").is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Pruning {
    /// C4.5's: the leaf's estimated errors against the subtree's plus 0.1. The default.
    #[default]
    Errors,
    /// Total cost: the leaf's estimated misclassification cost against the subtree's plus
    /// the price, after the node's path, of the node's test for every object that reaches
    /// it. A leaf's estimate is the misclassification cost of its training objects plus
    /// C4.5's added errors (at the confidence) priced at the leaf's dearest error; with a
    /// uniform `mc` that is `mc` times C4.5's estimate. A test that does not pay for
    /// itself is cut even where it removes errors.
    Costs,
}

impl Pruning {
    /// Every way, in order.
    pub const ALL: [Pruning; 2] = [Pruning::Errors, Pruning::Costs];

    /// The name the command line and the benchmark use (`errors`, `costs`).
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::Pruning::Errors.name(), "errors");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Pruning::Errors => "errors",
            Pruning::Costs => "costs",
        }
    }

    /// The way named `name`.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the accepted names.
    ///
    /// ```
    /// assert!(cslearn::testcost::Pruning::parse("errors").is_ok());
    /// ```
    pub fn parse(name: &str) -> Result<Pruning, Error> {
        Pruning::ALL
            .into_iter()
            .find(|p| p.name() == name)
            .ok_or_else(|| Error::Invalid {
                what: format!("pruning `{name}`"),
                reason: "expected `errors` or `costs`".into(),
            })
    }
}

/// The price a selection function scores a test at, at a node.
///
/// Either way, what an object pays is priced after its path (a test done once is free
/// further down, a group's later tests at their discount); this only changes which test
/// the tree prefers.
///
/// ```
/// use cslearn::testcost::SelectionPrices;
/// assert_eq!(SelectionPrices::default(), SelectionPrices::Path);
/// assert_eq!(SelectionPrices::parse("listed").unwrap(), SelectionPrices::Listed);
/// assert!(SelectionPrices::parse("free").is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SelectionPrices {
    /// After the node's path, as the object will pay: a test already on the path (a
    /// numeric feature split again at another threshold) is free, a test of a group
    /// already bought is at its discount. The default.
    #[default]
    Path,
    /// The test's listed full price whatever the path: a selection function written as
    /// a fixed function of gain and listed cost, as in the published implementations of
    /// the family that the test-cost benchmark compares with.
    Listed,
    /// The test's listed full price until the path has done it, nothing after: the
    /// listed prices, without charging twice a test the object pays once (a numeric
    /// feature split again). No group discount.
    ListedOnce,
}

impl SelectionPrices {
    /// Every way, in the order [`SelectionPrices::name`] lists them.
    pub const ALL: [SelectionPrices; 3] = [
        SelectionPrices::Path,
        SelectionPrices::Listed,
        SelectionPrices::ListedOnce,
    ];

    /// The name the command line and the benchmark use (`path`, `listed`, `listed-once`).
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::SelectionPrices::Listed.name(), "listed");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            SelectionPrices::Path => "path",
            SelectionPrices::Listed => "listed",
            SelectionPrices::ListedOnce => "listed-once",
        }
    }

    /// The price a selection function sees for `test` at a node whose path did the
    /// tests `done`.
    ///
    /// ```
    /// use cslearn::testcost::{SelectionPrices, TestPrices};
    /// let prices = TestPrices::flat(&[4.0, 9.0]).unwrap();
    /// assert_eq!(SelectionPrices::Path.price(&prices, 0, &[0]), 0.0);
    /// assert_eq!(SelectionPrices::Listed.price(&prices, 0, &[0]), 4.0);
    /// assert_eq!(SelectionPrices::ListedOnce.price(&prices, 0, &[0]), 0.0);
    /// assert_eq!(SelectionPrices::ListedOnce.price(&prices, 1, &[0]), 9.0);
    /// ```
    pub fn price(self, prices: &TestPrices, test: usize, done: &[usize]) -> f64 {
        match self {
            SelectionPrices::Path => price_after(prices, test, done),
            SelectionPrices::Listed => prices.test(test).full,
            SelectionPrices::ListedOnce if done.contains(&test) => 0.0,
            SelectionPrices::ListedOnce => prices.test(test).full,
        }
    }

    /// The way named `name`.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the accepted names.
    ///
    /// ```
    /// assert!(cslearn::testcost::SelectionPrices::parse("path").is_ok());
    /// ```
    pub fn parse(name: &str) -> Result<SelectionPrices, Error> {
        SelectionPrices::ALL
            .into_iter()
            .find(|p| p.name() == name)
            .ok_or_else(|| Error::Invalid {
                what: format!("selection prices `{name}`"),
                reason: "expected `path`, `listed` or `listed-once`".into(),
            })
    }
}

impl GrowParams {
    /// Unpruned growth with `criterion`, at least 2 objects in two branches.
    ///
    /// ```
    /// let p = cslearn::testcost::GrowParams::new(cslearn::testcost::Criterion::Id3);
    /// assert_eq!((p.confidence, p.min_objects), (None, 2.0));
    /// ```
    pub fn new(criterion: Criterion) -> GrowParams {
        GrowParams {
            criterion,
            confidence: None,
            min_objects: 2.0,
            max_depth: 64,
            selection_prices: SelectionPrices::Path,
            pruning: Pruning::Errors,
            budget: Budget::UNLIMITED,
        }
    }

    /// The same, pruned at `confidence`.
    ///
    /// ```
    /// let p = cslearn::testcost::GrowParams::new(cslearn::testcost::Criterion::Idx).pruned(0.1);
    /// assert_eq!(p.confidence, Some(0.1));
    /// ```
    pub fn pruned(mut self, confidence: f64) -> GrowParams {
        self.confidence = Some(confidence);
        self
    }

    /// The same, its selection function seeing `prices`.
    ///
    /// ```
    /// use cslearn::testcost::{Criterion, GrowParams, SelectionPrices};
    /// let p = GrowParams::new(Criterion::Idx).selecting_at(SelectionPrices::Listed);
    /// assert_eq!(p.selection_prices, SelectionPrices::Listed);
    /// ```
    pub fn selecting_at(mut self, prices: SelectionPrices) -> GrowParams {
        self.selection_prices = prices;
        self
    }

    /// The same, pruning by `pruning` (it takes effect with a confidence).
    ///
    /// ```
    /// use cslearn::testcost::{Criterion, GrowParams, Pruning};
    /// let p = GrowParams::new(Criterion::Eg2 { w: 1.0 }).pruned(0.25).pruning_by(Pruning::Costs);
    /// assert_eq!((p.confidence, p.pruning), (Some(0.25), Pruning::Costs));
    /// ```
    pub fn pruning_by(mut self, pruning: Pruning) -> GrowParams {
        self.pruning = pruning;
        self
    }

    /// The same, growing within `budget`: no path buys more than it allows.
    ///
    /// ```
    /// use cslearn::testcost::{Budget, Criterion, GrowParams};
    /// let b = Budget::new(None, Some(2)).unwrap();
    /// assert_eq!(GrowParams::new(Criterion::Idx).within(b).budget, b);
    /// ```
    pub fn within(mut self, budget: Budget) -> GrowParams {
        self.budget = budget;
        self
    }
}

/// The index of a node in a [`CostTree`].
pub type NodeIndex = u32;

/// The test at an inner node.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Split {
    /// One child per value of a nominal feature.
    Nominal {
        /// The feature.
        feature: usize,
        /// The child for each value code.
        children: Vec<NodeIndex>,
        /// The share of the node's objects with a known value that went to each child.
        shares: Vec<f64>,
    },
    /// Two children of a numeric feature: at most `at`, and above.
    Threshold {
        /// The feature.
        feature: usize,
        /// The threshold: between two values seen in training, at least the smaller and below
        /// the larger (their midpoint but where it would not separate them).
        at: f64,
        /// The child at or below the threshold, then the one above.
        children: [NodeIndex; 2],
        /// The share of objects with a known value in each.
        shares: [f64; 2],
    },
}

impl Split {
    /// The feature tested.
    ///
    /// ```
    /// let s = cslearn::testcost::Split::Threshold { feature: 3, at: 0.5, children: [1, 2], shares: [0.5, 0.5] };
    /// assert_eq!(s.feature(), 3);
    /// ```
    pub fn feature(&self) -> usize {
        match self {
            Split::Nominal { feature, .. } | Split::Threshold { feature, .. } => *feature,
        }
    }

    pub(super) fn children(&self) -> &[NodeIndex] {
        match self {
            Split::Nominal { children, .. } => children,
            Split::Threshold { children, .. } => children,
        }
    }

    fn shares(&self) -> &[f64] {
        match self {
            Split::Nominal { shares, .. } => shares,
            Split::Threshold { shares, .. } => shares,
        }
    }
}

/// A node: the weight of training objects of each class that reached it, its answer,
/// and its test if it has one.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TreeNode {
    /// Training weight per class.
    pub weights: Vec<f64>,
    /// The answer of least expected misclassification cost here.
    pub label: u32,
    /// The test, or `None` at a leaf.
    pub split: Option<Split>,
    /// What the node was worth to a learner that buys a test only where it expects the
    /// test to pay (VOI), where that learner valued it; `None` for the other learners
    /// (and left out of a model file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<NodeValue>,
}

/// What a node was worth when it was grown, per object reaching it: the expected total
/// cost (tests from here on and misclassification) of stopping there and answering, and
/// of buying the test it chose and going on as the learner looked ahead.
///
/// ```
/// let v = cslearn::testcost::NodeValue { stop: 30.0, test: Some(22.5) };
/// assert_eq!(v.gain(), Some(7.5));
/// assert_eq!(cslearn::testcost::NodeValue { stop: 4.0, test: None }.gain(), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NodeValue {
    /// The expected cost per object of stopping at the node.
    pub stop: f64,
    /// The expected cost per object of buying the node's test (its price included), or
    /// `None` where the node stops because no test was expected to pay.
    pub test: Option<f64>,
}

impl NodeValue {
    /// What buying the test was expected to save per object (`stop - test`), or `None`
    /// at a node that stops.
    pub fn gain(&self) -> Option<f64> {
        self.test.map(|t| self.stop - t)
    }
}

/// What classifying one object cost and answered.
///
/// ```
/// let c = cslearn::testcost::Classification {
///     class: 1, test_cost: 3.0, tests: vec![0], probabilities: vec![0.25, 0.75],
/// };
/// assert_eq!(c.tests.len(), 1);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Classification {
    /// The answer: the class of least expected misclassification cost, which is not
    /// always the most probable one (see [`probabilities`](Classification::probabilities)).
    pub class: u32,
    /// The tests paid for (discounts applied).
    pub test_cost: f64,
    /// The tests done, in the order they were done.
    pub tests: Vec<usize>,
    /// The probability of each class (indexed by class, summing to 1): the class weights
    /// of the node that answered, smoothed by Laplace's rule (one added to each class's
    /// weight, then normalised), so that a leaf of few training objects never claims
    /// certainty. Where a missing value sent the object down several branches, the
    /// weights are the mix [`class`](Classification::class) was chosen from: each leaf's
    /// class shares weighted by the share of the object that reached it, scaled to the
    /// training weight those leaves hold on average (so the smoothing is as strong as at
    /// a leaf of that weight), then smoothed the same way. Smoothing keeps the order of
    /// the classes, so under uniform misclassification costs `class` is a class of
    /// largest probability (up to ties).
    pub probabilities: Vec<f64>,
}

/// How one object was classified, test by test ([`CostTree::explain`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Explanation {
    /// The tests the object bought, in the order it bought them.
    pub steps: Vec<ExplainedTest>,
    /// The node the object stopped at and answered from, where it followed one path;
    /// `None` where a missing value sent it down several branches (it answered from the
    /// mix of the nodes they reached).
    pub stopped_at: Option<usize>,
    /// The classification: the answer, what the tests cost, and the probabilities when it
    /// stopped (the same as [`CostTree::classify_within`]'s).
    pub classification: Classification,
}

/// One test an object bought ([`Explanation::steps`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ExplainedTest {
    /// The feature tested.
    pub feature: usize,
    /// What the object paid for it, after the tests it bought before (group discounts).
    pub paid: f64,
    /// The node that asked for it, where the object followed one path to it; `None` for a
    /// test bought on one of several branches below a missing value.
    pub node: Option<usize>,
    /// The class probabilities at that node, before the test (Laplace's rule over its
    /// training weights, as a leaf there would answer).
    pub probabilities: Option<Vec<f64>>,
    /// What the learner expected the test to save per object at that node
    /// ([`NodeValue::gain`]): VOI's trees have it, the other learners' do not.
    pub expected_gain: Option<f64>,
}

/// Laplace's rule over class weights: `(w_c + 1) / (sum of w + k)` for `k` classes.
///
/// ```
/// let p = cslearn::testcost::laplace(&[3.0, 0.0]);
/// assert_eq!(p, vec![0.8, 0.2]);
/// assert_eq!(cslearn::testcost::laplace(&[0.0, 0.0, 0.0]), vec![1.0 / 3.0; 3]);
/// ```
pub fn laplace(weights: &[f64]) -> Vec<f64> {
    let total: f64 = weights.iter().map(|w| w + 1.0).sum();
    weights.iter().map(|w| (w + 1.0) / total).collect()
}

/// A decision tree over a [`Frame`]'s features, grown to classify for little total cost.
///
/// ```
/// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
/// // Feature 0 decides the class and costs 50; feature 1 decides it too and costs 1.
/// let frame = Frame::new(vec!["dear".into(), "cheap".into()],
///     vec![Column::Numeric(vec![0.0, 0.0, 1.0, 1.0, 0.0, 1.0]),
///          Column::Numeric(vec![5.0, 5.0, 7.0, 7.0, 5.0, 7.0])],
///     vec![0, 0, 1, 1, 0, 1], vec!["no".into(), "yes".into()]).unwrap();
/// let prices = TestPrices::flat(&[50.0, 1.0]).unwrap();
/// let mc = MisclassCosts::uniform(2, 100.0).unwrap();
/// let rows: Vec<usize> = (0..6).collect();
/// let tree = CostTree::grow(&frame, &rows, &prices, &mc, &GrowParams::new(Criterion::Idx));
/// let answer = tree.classify(&frame, 2, &prices);
/// assert_eq!((answer.class, answer.test_cost), (1, 1.0));
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CostTree {
    nodes: Vec<TreeNode>,
    /// The misclassification costs the labels were chosen by.
    mc: MisclassCosts,
}

/// One feature as a tree read from outside (a model file, a pickle) may test it: its name,
/// for messages, and for a nominal feature the number of its values.
///
/// ```
/// let f = cslearn::testcost::FeatureShape { name: "colour", values: Some(3) };
/// assert_eq!(f.values, Some(3));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FeatureShape<'a> {
    /// The feature's name.
    pub name: &'a str,
    /// `Some(n)` for a nominal feature of `n` values, `None` for a numeric one.
    pub values: Option<usize>,
}

/// What is wrong with a tree read from outside ([`CostTree::check`]): where, and why.
///
/// ```
/// let f = cslearn::testcost::TreeFault { at: "tree node 2".into(), reason: "no children".into() };
/// assert_eq!(f.to_string(), "tree node 2: no children");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TreeFault {
    /// Where: the node, or the part of the tree.
    pub at: String,
    /// What is wrong there.
    pub reason: String,
}

impl std::fmt::Display for TreeFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.at, self.reason)
    }
}

impl CostTree {
    /// Check a tree read from outside (a model file, a pickle) against the features it
    /// may test and its number of classes: at least one node; a misclassification matrix
    /// of that many classes, every entry finite and not negative; at every node one
    /// finite, non-negative weight per class and a label among the classes; every test of
    /// a feature there is, of its kind (a threshold, finite, on a numeric feature; one
    /// child per value of a nominal one), with finite non-negative shares; and every child
    /// after its parent, so the nodes form a tree (no cycle) and every walk ends.
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 2.0, 3.0, 4.0])],
    ///     vec![0, 0, 1, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let tree = CostTree::grow(&frame, &[0, 1, 2, 3], &TestPrices::flat(&[1.0]).unwrap(),
    ///     &MisclassCosts::uniform(2, 100.0).unwrap(), &GrowParams::new(Criterion::Id3));
    /// let numeric = [FeatureShape { name: "x", values: None }];
    /// assert!(tree.check(&numeric, 2).is_ok());
    /// let nominal = [FeatureShape { name: "x", values: Some(2) }];
    /// assert!(tree.check(&nominal, 2).unwrap_err().reason.contains("a threshold on nominal feature `x`"));
    /// assert!(tree.check(&numeric, 3).is_err());
    /// ```
    pub fn check(&self, features: &[FeatureShape<'_>], classes: usize) -> Result<(), TreeFault> {
        let fault = |at: String, reason: String| TreeFault { at, reason };
        let mc = self
            .mc
            .clone()
            .checked()
            .map_err(|e| fault("key `tree.mc`".into(), e.to_string()))?;
        if mc.classes() != classes {
            return Err(fault(
                "key `tree.mc`".into(),
                format!("{} classes, but the model has {classes}", mc.classes()),
            ));
        }
        if self.is_empty() {
            return Err(fault("key `tree.nodes`".into(), "no nodes".into()));
        }
        let nodes = self.len();
        for i in 0..nodes {
            let node = self.node(i);
            let at = || format!("tree node {i}");
            if node.weights.len() != classes {
                return Err(fault(
                    at(),
                    format!(
                        "{} weights, but there are {classes} classes",
                        node.weights.len()
                    ),
                ));
            }
            if node.weights.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
                return Err(fault(
                    at(),
                    "a weight that is negative or not finite".into(),
                ));
            }
            if let Some(value) = &node.value
                && [Some(value.stop), value.test]
                    .into_iter()
                    .flatten()
                    .any(|v| !(v.is_finite() && v >= 0.0))
            {
                return Err(fault(
                    at(),
                    "a value (`stop` or `test`) that is negative or not finite".into(),
                ));
            }
            if node.label as usize >= classes {
                return Err(fault(
                    at(),
                    format!("label {}, but there are {classes} classes", node.label),
                ));
            }
            let Some(split) = &node.split else {
                continue;
            };
            let feature = split.feature();
            let Some(entry) = features.get(feature) else {
                return Err(fault(
                    at(),
                    format!(
                        "a test of feature {feature}, but there are {} features",
                        features.len()
                    ),
                ));
            };
            let (children, shares): (&[u32], &[f64]) = match split {
                Split::Nominal {
                    children, shares, ..
                } => {
                    let Some(values) = entry.values else {
                        return Err(fault(
                            at(),
                            format!("a nominal test of numeric feature `{}`", entry.name),
                        ));
                    };
                    if children.is_empty() || children.len() != shares.len() {
                        return Err(fault(
                            at(),
                            format!(
                                "{} children and {} shares: a nominal test needs one share per child, and a child",
                                children.len(),
                                shares.len()
                            ),
                        ));
                    }
                    if children.len() != values {
                        return Err(fault(
                            at(),
                            format!(
                                "{} children for the {values} values of nominal feature `{}`: a \
                             nominal test has one child per value",
                                children.len(),
                                entry.name
                            ),
                        ));
                    }
                    (children, shares)
                }
                Split::Threshold {
                    at: threshold,
                    children,
                    shares,
                    ..
                } => {
                    if entry.values.is_some() {
                        return Err(fault(
                            at(),
                            format!("a threshold on nominal feature `{}`", entry.name),
                        ));
                    }
                    if !threshold.is_finite() {
                        return Err(fault(at(), "a threshold that is not finite".into()));
                    }
                    (children, shares)
                }
            };
            if shares.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
                return Err(fault(at(), "a share that is negative or not finite".into()));
            }
            if let Some(&c) = children
                .iter()
                .find(|&&c| c as usize <= i || c as usize >= nodes)
            {
                return Err(fault(
                    at(),
                    format!("child {c}: a child comes after its parent, among the {nodes} nodes"),
                ));
            }
        }
        Ok(())
    }

    /// Grows a tree on the objects `rows` of `frame`, selecting tests with `prices` (the
    /// prices the learner believes: the real ones, or ICET's biased ones) and labelling
    /// nodes with `mc`, then prunes it if `params` says so.
    ///
    /// A node becomes a leaf when its objects are of one class, when no test leaves two
    /// branches with at least C4.5's least branch size (`min_objects`, or a tenth of the
    /// objects per class, at most 25), when no test has positive gain (for DTMC: when no
    /// test reduces the expected total cost), or at `max_depth`. Objects whose value of
    /// the tested feature is missing go down every branch with their weight split as the
    /// known values split (C4.5).
    ///
    /// ```
    /// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 2.0, 3.0, 4.0])],
    ///     vec![0, 0, 1, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[1.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let tree = CostTree::grow(&frame, &[0, 1, 2, 3], &prices, &mc, &GrowParams::new(Criterion::Id3));
    /// assert_eq!(tree.len(), 3);
    /// ```
    pub fn grow(
        frame: &Frame,
        rows: &[usize],
        prices: &TestPrices,
        mc: &MisclassCosts,
        params: &GrowParams,
    ) -> CostTree {
        let weights = vec![1.0; rows.len()];
        CostTree::grow_weighted(frame, rows, &weights, prices, mc, params)
    }

    /// [`grow`](CostTree::grow) with a weight per object.
    ///
    /// ```
    /// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 2.0])],
    ///     vec![0, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[1.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let tree = CostTree::grow_weighted(&frame, &[0, 1], &[3.0, 1.0], &prices, &mc,
    ///     &GrowParams::new(Criterion::Id3));
    /// assert_eq!(tree.node(0).label, 0);
    /// ```
    pub fn grow_weighted(
        frame: &Frame,
        rows: &[usize],
        weights: &[f64],
        prices: &TestPrices,
        mc: &MisclassCosts,
        params: &GrowParams,
    ) -> CostTree {
        let mut splits = Splits::new(
            frame,
            rows,
            weights,
            mc,
            params.criterion,
            params.min_objects,
        );
        CostTree::grow_in(&mut splits, prices, mc, params)
    }

    /// The tree of these nodes (parents before children), labelled by `mc`.
    pub(super) fn from_nodes(nodes: Vec<TreeNode>, mc: &MisclassCosts) -> CostTree {
        CostTree {
            nodes,
            mc: mc.clone(),
        }
    }

    /// Grows a tree by walking the split trie `splits` (made with the same objects, `mc`,
    /// criterion kind and `min_objects`), choosing each test by `prices` and `params`.
    pub(crate) fn grow_in(
        splits: &mut Splits<'_>,
        prices: &TestPrices,
        mc: &MisclassCosts,
        params: &GrowParams,
    ) -> CostTree {
        let nodes = grow_nodes(splits, prices, mc, params);
        let mut tree = CostTree {
            nodes,
            mc: mc.clone(),
        };
        if let Some(confidence) = params.confidence {
            match params.pruning {
                Pruning::Errors => tree.prune(confidence),
                Pruning::Costs => tree.prune_by_cost(confidence, prices),
            }
        }
        tree
    }

    /// The mean total cost, at `real` prices and `mc`, on the held-out objects of
    /// `splits` ([`Splits::hold_out`]) of the tree [`grow_in`](CostTree::grow_in) would
    /// grow: computed from the held-out weights each leaf receives, so without
    /// classifying the objects one by one. An object whose value is missing at a split
    /// is spread over the branches as in training and pays each path's tests in
    /// proportion (classifying it pays the union of the paths' tests once and answers for
    /// the mix); for objects without missing values the two agree exactly.
    pub(crate) fn held_out_cost(
        splits: &mut Splits<'_>,
        prices: &TestPrices,
        real: &TestPrices,
        mc: &MisclassCosts,
        params: &GrowParams,
    ) -> f64 {
        let walk = Walk {
            scorer: Scorer::new(prices, params.criterion),
            prices,
            real,
            mc,
            params,
            coeff: params.confidence.map_or(0.0, |c| deviation(c).powi(2)),
        };
        let mut path = Vec::new();
        let (_, cost) = walk.subtree(splits, 0, &mut path, 0.0);
        let n: f64 = splits.cell(0).held_classes.iter().sum();
        if n > 0.0 { cost / n } else { 0.0 }
    }

    /// C4.5's pessimistic pruning (subtree replacement): bottom up, a subtree becomes a
    /// leaf when the leaf's estimated errors (the upper limit of the binomial confidence
    /// interval at `confidence` on the errors seen) are at most the subtree's plus 0.1.
    /// Errors are counted against the majority class, as C4.5 does; labels stay those of
    /// least misclassification cost.
    ///
    /// ```
    /// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// // A split that separates one odd object out of nine is pruned away at 0.25.
    /// let x: Vec<f64> = (0..9).map(f64::from).collect();
    /// let classes = vec![0, 0, 0, 0, 0, 0, 0, 1, 0];
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(x)], classes,
    ///     vec!["a".into(), "b".into()]).unwrap();
    /// let (prices, mc) = (TestPrices::flat(&[1.0]).unwrap(), MisclassCosts::uniform(2, 1.0).unwrap());
    /// let rows: Vec<usize> = (0..9).collect();
    /// let mut params = GrowParams::new(Criterion::Id3);
    /// params.min_objects = 1.0;
    /// assert!(CostTree::grow(&frame, &rows, &prices, &mc, &params).len() > 1);
    /// assert_eq!(CostTree::grow(&frame, &rows, &prices, &mc, &params.pruned(0.25)).len(), 1);
    /// ```
    pub fn prune(&mut self, confidence: f64) {
        self.prune_in_place(confidence);
        self.compact();
    }

    /// Pessimistic pruning by total cost ([`Pruning::Costs`]): bottom up, a subtree
    /// becomes a leaf when the leaf's estimated misclassification cost is at most the
    /// subtree's plus what its test costs, at `prices` after the node's path, for the
    /// training weight that reaches it.
    ///
    /// ```
    /// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// // x tells the class of 20 objects exactly; an error costs 10.
    /// let x: Vec<f64> = (0..20).map(f64::from).collect();
    /// let classes = (0..20).map(|i| u32::from(i >= 10)).collect();
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(x)], classes,
    ///     vec!["a".into(), "b".into()]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let rows: Vec<usize> = (0..20).collect();
    /// let grown = |price: f64| {
    ///     let prices = TestPrices::flat(&[price]).unwrap();
    ///     let mut tree = CostTree::grow(&frame, &rows, &prices, &mc, &GrowParams::new(Criterion::Id3));
    ///     tree.prune_by_cost(0.25, &prices);
    ///     tree.len()
    /// };
    /// // As a leaf: (10 errors + 1.98 added) * 10 = 119.8. Split: two pure leaves of 10
    /// // with 1.29 added errors each (25.9) plus 20 tests: the test pays at a price of 1
    /// // (45.9), not at 10 (225.9).
    /// assert_eq!(grown(1.0), 3);
    /// assert_eq!(grown(10.0), 1);
    /// ```
    pub fn prune_by_cost(&mut self, confidence: f64, prices: &TestPrices) {
        let cut = self.cost_pruning_cut(confidence, prices);
        self.cut(&cut);
    }

    /// The nodes [`prune_by_cost`](CostTree::prune_by_cost) makes leaves (nodes below
    /// one of them may be marked too).
    pub(super) fn cost_pruning_cut(&self, confidence: f64, prices: &TestPrices) -> Vec<bool> {
        let coeff = deviation(confidence).powi(2);
        let n = self.nodes.len();
        let price_here = self.test_prices(prices);
        let mut estimate = vec![0.0; n];
        let mut cut = vec![false; n];
        for i in (0..n).rev() {
            let node = &self.nodes[i];
            let as_leaf = estimated_cost(&self.mc, &node.weights, confidence, coeff);
            match &node.split {
                None => estimate[i] = as_leaf,
                Some(split) => {
                    let total: f64 = node.weights.iter().sum();
                    let subtree: f64 = split
                        .children()
                        .iter()
                        .zip(split.shares())
                        .filter(|(_, s)| **s > 0.0)
                        .map(|(&c, _)| estimate[c as usize])
                        .sum::<f64>()
                        + price_here[i] * total;
                    if as_leaf <= subtree {
                        cut[i] = true;
                        estimate[i] = as_leaf;
                    } else {
                        estimate[i] = subtree;
                    }
                }
            }
        }
        cut
    }

    /// The price of each node's test at `prices` after the node's path (0 at a leaf).
    pub(super) fn test_prices(&self, prices: &TestPrices) -> Vec<f64> {
        let n = self.nodes.len();
        let mut price_here = vec![0.0; n];
        let mut paths: Vec<Vec<usize>> = vec![Vec::new(); n];
        // Parents come before children.
        for i in 0..n {
            let Some(split) = &self.nodes[i].split else {
                continue;
            };
            let feature = split.feature();
            let path = std::mem::take(&mut paths[i]);
            price_here[i] = price_after(prices, feature, &path);
            let mut below = path;
            if !below.contains(&feature) {
                below.push(feature);
            }
            for &c in split.children() {
                paths[c as usize].clone_from(&below);
            }
        }
        price_here
    }

    /// The misclassification costs the tree's labels were chosen by.
    pub(super) fn misclass_costs(&self) -> &MisclassCosts {
        &self.mc
    }

    /// Makes a leaf of every node marked in `cut` (one mark per node) and drops the
    /// nodes cut off.
    pub(super) fn cut(&mut self, cut: &[bool]) {
        for (node, &c) in self.nodes.iter_mut().zip(cut) {
            if c {
                node.split = None;
            }
        }
        self.compact();
    }

    /// The weight of the objects `rows` of `frame` that reaches each node, per class: an
    /// object whose value is missing at a split goes down every branch with its weight
    /// split as the training objects' known values split.
    pub(super) fn reach(&self, frame: &Frame, rows: &[usize]) -> Vec<Vec<f64>> {
        let classes = self.nodes[0].weights.len();
        let mut reached = vec![vec![0.0; classes]; self.nodes.len()];
        let mut stack = Vec::new();
        for &row in rows {
            let class = frame.class(row) as usize;
            stack.push((0usize, 1.0));
            while let Some((i, weight)) = stack.pop() {
                if let Some(w) = reached[i].get_mut(class) {
                    *w += weight;
                }
                let Some(split) = &self.nodes[i].split else {
                    continue;
                };
                if frame.column(split.feature()).is_missing(row) {
                    for (&c, &s) in split.children().iter().zip(split.shares()) {
                        if s > 0.0 {
                            stack.push((c as usize, weight * s));
                        }
                    }
                } else {
                    stack.push((self.child(split, frame, row) as usize, weight));
                }
            }
        }
        reached
    }

    /// [`prune`](CostTree::prune) without dropping the nodes cut off.
    fn prune_in_place(&mut self, confidence: f64) {
        let coeff = deviation(confidence).powi(2);
        let n = self.nodes.len();
        let mut estimate = vec![0.0; n];
        // Children always have larger indices than their parent.
        for i in (0..n).rev() {
            let node = &self.nodes[i];
            let total: f64 = node.weights.iter().sum();
            let majority = node.weights.iter().copied().fold(0.0, f64::max);
            let errors = total - majority;
            let as_leaf = errors + added_errors(total, errors, confidence, coeff);
            match &node.split {
                None => estimate[i] = as_leaf,
                Some(split) => {
                    // A branch no training object reached has no errors to estimate.
                    let subtree: f64 = split
                        .children()
                        .iter()
                        .zip(split.shares())
                        .filter(|(_, s)| **s > 0.0)
                        .map(|(&c, _)| estimate[c as usize])
                        .sum();
                    if as_leaf <= subtree + 0.1 {
                        self.nodes[i].split = None;
                        estimate[i] = as_leaf;
                    } else {
                        estimate[i] = subtree;
                    }
                }
            }
        }
    }

    /// Drops the nodes no longer reachable from the root, keeping parents before children.
    fn compact(&mut self) {
        let mut order = Vec::new();
        let mut stack = vec![0 as NodeIndex];
        while let Some(i) = stack.pop() {
            order.push(i);
            if let Some(split) = &self.nodes[i as usize].split {
                stack.extend(split.children().iter().rev());
            }
        }
        if order.len() == self.nodes.len() {
            return;
        }
        let mut new_index = vec![NodeIndex::MAX; self.nodes.len()];
        for (new, &old) in order.iter().enumerate() {
            new_index[old as usize] = new as NodeIndex;
        }
        let mut nodes: Vec<TreeNode> = order
            .iter()
            .map(|&i| self.nodes[i as usize].clone())
            .collect();
        for node in &mut nodes {
            match &mut node.split {
                Some(Split::Nominal { children, .. }) => {
                    children
                        .iter_mut()
                        .for_each(|c| *c = new_index[*c as usize]);
                }
                Some(Split::Threshold { children, .. }) => {
                    children
                        .iter_mut()
                        .for_each(|c| *c = new_index[*c as usize]);
                }
                None => {}
            }
        }
        self.nodes = nodes;
    }

    /// The labels of every node chosen again for other misclassification costs (the
    /// tree's shape stays).
    ///
    /// ```
    /// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 1.0, 1.0])],
    ///     vec![0, 0, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[1.0]).unwrap();
    /// let mut tree = CostTree::grow(&frame, &[0, 1, 2], &prices,
    ///     &MisclassCosts::uniform(2, 1.0).unwrap(), &GrowParams::new(Criterion::Id3));
    /// assert_eq!(tree.node(0).label, 0);
    /// tree.relabel(&MisclassCosts::from_rows(&[vec![0.0, 1.0], vec![10.0, 0.0]]).unwrap());
    /// assert_eq!(tree.node(0).label, 1);
    /// ```
    pub fn relabel(&mut self, mc: &MisclassCosts) {
        for node in &mut self.nodes {
            node.label = mc.best(&node.weights).0 as u32;
        }
        self.mc = mc.clone();
    }

    /// The number of nodes.
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// # let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0])], vec![0], vec!["a".into()]).unwrap();
    /// # let tree = CostTree::grow(&frame, &[0], &TestPrices::flat(&[1.0]).unwrap(),
    /// #     &MisclassCosts::uniform(1, 1.0).unwrap(), &GrowParams::new(Criterion::Id3));
    /// assert_eq!(tree.len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Never true: a tree has a root.
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// # let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0])], vec![0], vec!["a".into()]).unwrap();
    /// # let tree = CostTree::grow(&frame, &[0], &TestPrices::flat(&[1.0]).unwrap(),
    /// #     &MisclassCosts::uniform(1, 1.0).unwrap(), &GrowParams::new(Criterion::Id3));
    /// assert!(!tree.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Node `index` (0 is the root).
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// # let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0])], vec![0], vec!["a".into()]).unwrap();
    /// # let tree = CostTree::grow(&frame, &[0], &TestPrices::flat(&[1.0]).unwrap(),
    /// #     &MisclassCosts::uniform(1, 1.0).unwrap(), &GrowParams::new(Criterion::Id3));
    /// assert!(tree.node(0).split.is_none());
    /// ```
    pub fn node(&self, index: usize) -> &TreeNode {
        &self.nodes[index]
    }

    /// Classifies object `row` of `frame`, paying `prices` for each test on its way (a
    /// test already done is free; groups get their discount). An object whose value is
    /// missing goes down every branch, paying for the tests of all of them, and gets the
    /// answer of least expected cost over the leaves it reached, weighted as in training.
    /// The classification carries the probability of each class
    /// ([`Classification::probabilities`]), from the same leaves.
    ///
    /// ```
    /// use cslearn::testcost::{Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 2.0, 3.0, 4.0, f64::NAN])],
    ///     vec![0, 0, 1, 1, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[7.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let tree = CostTree::grow(&frame, &[0, 1, 2, 3], &prices, &mc, &GrowParams::new(Criterion::Id3));
    /// assert_eq!(tree.classify(&frame, 0, &prices).test_cost, 7.0);
    /// assert_eq!(tree.classify(&frame, 4, &prices).tests, vec![0]);
    /// // The leaf of objects 0 and 1 holds two of class a: (2 + 1) / (2 + 2).
    /// assert_eq!(tree.classify(&frame, 0, &prices).probabilities, vec![0.75, 0.25]);
    /// // A missing value: half of each leaf, as training split, two objects behind each.
    /// assert_eq!(tree.classify(&frame, 4, &prices).probabilities, vec![0.5, 0.5]);
    /// ```
    pub fn classify(&self, frame: &Frame, row: usize, prices: &TestPrices) -> Classification {
        self.classify_within(frame, row, prices, &Budget::UNLIMITED)
    }

    /// [`classify`](CostTree::classify) for an object held to `budget`: a test that would
    /// take the object past it is not bought, and the object answers from the node that
    /// asked for it, as if it were a leaf (its label, and its class weights smoothed as a
    /// leaf's for the probabilities). Without a limit the result is
    /// [`classify`](CostTree::classify)'s, to the bit.
    ///
    /// An object whose value is missing follows several branches with one purse: it buys
    /// tests in the order it meets them (depth first, branches in order, as `classify`
    /// walks them), each at its price after the tests bought so far on any branch, and a
    /// branch whose next test the purse cannot afford stops at that node, which joins the
    /// mix of answering nodes as a leaf would. What the object pays therefore never
    /// exceeds the budget, whatever it is missing.
    ///
    /// ```
    /// use cslearn::testcost::{Budget, Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 2.0, 3.0, 4.0, 5.0])],
    ///     vec![0, 0, 1, 1, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[7.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let tree = CostTree::grow(&frame, &[0, 1, 2, 3, 4], &prices, &mc, &GrowParams::new(Criterion::Id3));
    /// // Six is not enough for the test at 7: the root answers, with nothing paid.
    /// let poor = tree.classify_within(&frame, 0, &prices, &Budget::new(Some(6.0), None).unwrap());
    /// assert_eq!((poor.class, poor.test_cost, poor.tests.len()), (1, 0.0, 0));
    /// // The root holds two of a and three of b: (2 + 1) / (5 + 2) and (3 + 1) / (5 + 2).
    /// assert_eq!(poor.probabilities, vec![3.0 / 7.0, 4.0 / 7.0]);
    /// let rich = tree.classify_within(&frame, 0, &prices, &Budget::new(Some(7.0), None).unwrap());
    /// assert_eq!(rich, tree.classify(&frame, 0, &prices));
    /// ```
    pub fn classify_within(
        &self,
        frame: &Frame,
        row: usize,
        prices: &TestPrices,
        budget: &Budget,
    ) -> Classification {
        let mut tests: Vec<usize> = Vec::new();
        let mut spent = 0.0;
        // Whether the purse affords `feature` now, and its price if so.
        let afford = |feature: usize, tests: &[usize], spent: f64| -> Option<f64> {
            if tests.contains(&feature) {
                return Some(0.0);
            }
            let price = price_after(prices, feature, tests);
            budget
                .allows(spent, tests.len(), price, true)
                .then_some(price)
        };
        // The common case: no missing value on the path.
        let mut at = 0usize;
        loop {
            let node = &self.nodes[at];
            let answer = |tests, spent| Classification {
                class: node.label,
                test_cost: spent,
                tests,
                probabilities: laplace(&node.weights),
            };
            let Some(split) = &node.split else {
                return answer(tests, spent);
            };
            let feature = split.feature();
            let Some(price) = afford(feature, &tests, spent) else {
                return answer(tests, spent);
            };
            if frame.column(feature).is_missing(row) {
                break;
            }
            if !tests.contains(&feature) {
                spent += price;
                tests.push(feature);
            }
            at = self.child(split, frame, row) as usize;
        }
        // A missing value: explore every branch from here, weighted.
        let classes = self.nodes[0].weights.len();
        let mut mixed = vec![0.0; classes];
        // The training weight of the leaves reached, weighted as the object reached them.
        let mut held = 0.0;
        let mut stack = vec![(at, 1.0)];
        while let Some((i, weight)) = stack.pop() {
            let node = &self.nodes[i];
            let affordable = node
                .split
                .as_ref()
                .and_then(|split| Some((split, afford(split.feature(), &tests, spent)?)));
            match affordable {
                None => {
                    let total: f64 = node.weights.iter().sum();
                    if total > 0.0 {
                        for (m, w) in mixed.iter_mut().zip(&node.weights) {
                            *m += weight * w / total;
                        }
                        held += weight * total;
                    }
                }
                Some((split, price)) => {
                    let feature = split.feature();
                    if !tests.contains(&feature) {
                        spent += price;
                        tests.push(feature);
                    }
                    if frame.column(feature).is_missing(row) {
                        for (&c, &s) in split.children().iter().zip(split.shares()).rev() {
                            if s > 0.0 {
                                stack.push((c as usize, weight * s));
                            }
                        }
                    } else {
                        stack.push((self.child(split, frame, row) as usize, weight));
                    }
                }
            }
        }
        let scaled: Vec<f64> = mixed.iter().map(|m| m * held).collect();
        Classification {
            class: self.best_for(&mixed),
            test_cost: spent,
            tests,
            probabilities: laplace(&scaled),
        }
    }

    /// How object `row` is classified within `budget`, test by test: each test it buys, in
    /// order, with what it paid, the node that asked for it, the class probabilities there
    /// and what the learner expected the test to save ([`NodeValue::gain`], for VOI's
    /// trees), then where it stopped and what it answered. The classification is
    /// [`classify_within`](CostTree::classify_within)'s, to the bit.
    ///
    /// ```
    /// use cslearn::testcost::{Budget, Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![1.0, 2.0, 3.0, 4.0, f64::NAN])],
    ///     vec![0, 0, 1, 1, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[7.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let tree = CostTree::grow(&frame, &[0, 1, 2, 3], &prices, &mc, &GrowParams::new(Criterion::Id3));
    /// let why = tree.explain(&frame, 0, &prices, &Budget::UNLIMITED);
    /// assert_eq!((why.steps.len(), why.steps[0].feature, why.steps[0].paid), (1, 0, 7.0));
    /// // Asked at the root, which holds two objects of each class.
    /// assert_eq!((why.steps[0].node, why.steps[0].probabilities.clone()), (Some(0), Some(vec![0.5, 0.5])));
    /// assert_eq!(why.steps[0].expected_gain, None); // ID3 does not value its tests
    /// assert_eq!(why.classification, tree.classify(&frame, 0, &prices));
    /// assert!(why.stopped_at.is_some());
    /// // A missing value: the test is asked at the root, and the answer mixes both leaves.
    /// assert_eq!(tree.explain(&frame, 4, &prices, &Budget::UNLIMITED).stopped_at, None);
    /// ```
    pub fn explain(
        &self,
        frame: &Frame,
        row: usize,
        prices: &TestPrices,
        budget: &Budget,
    ) -> Explanation {
        let classification = self.classify_within(frame, row, prices, budget);
        let bought = &classification.tests;
        // The node that asked for each test bought on the object's one path.
        let mut asked: Vec<usize> = Vec::new();
        let mut at = 0usize;
        let stopped_at = loop {
            let node = &self.nodes[at];
            let Some(split) = &node.split else {
                break Some(at);
            };
            let feature = split.feature();
            if !bought[..asked.len()].contains(&feature) {
                if bought.get(asked.len()) != Some(&feature) {
                    // Not affordable: the object answers here.
                    break Some(at);
                }
                asked.push(at);
            }
            if frame.column(feature).is_missing(row) {
                break None;
            }
            at = self.child(split, frame, row) as usize;
        };
        let steps = bought
            .iter()
            .enumerate()
            .map(|(i, &feature)| {
                let node = asked.get(i).copied();
                ExplainedTest {
                    feature,
                    paid: price_after(prices, feature, &bought[..i]),
                    node,
                    probabilities: node.map(|n| laplace(&self.nodes[n].weights)),
                    expected_gain: node
                        .and_then(|n| self.nodes[n].value)
                        .and_then(|v| v.gain()),
                }
            })
            .collect();
        Explanation {
            steps,
            stopped_at,
            classification,
        }
    }

    /// The answer of least expected cost for a mix of leaves.
    fn best_for(&self, mixed: &[f64]) -> u32 {
        self.mc.best(mixed).0 as u32
    }

    fn child(&self, split: &Split, frame: &Frame, row: usize) -> NodeIndex {
        match (split, frame.column(split.feature())) {
            (Split::Nominal { children, .. }, Column::Nominal { codes, .. }) => {
                let code = codes[row] as usize;
                // A value never seen in training: the branch with most objects.
                children.get(code).copied().unwrap_or_else(|| {
                    let shares = split.shares();
                    let best = (0..shares.len())
                        .max_by(|&a, &b| shares[a].total_cmp(&shares[b]).then(b.cmp(&a)))
                        .unwrap_or(0);
                    children[best]
                })
            }
            (Split::Threshold { at, children, .. }, Column::Numeric(x)) => {
                children[usize::from(x[row] > *at)]
            }
            // A frame whose column kinds differ from training: the first branch.
            (s, _) => s.children()[0],
        }
    }
}

/// The nodes of the tree grown through `splits` with these prices, before pruning.
fn grow_nodes(
    splits: &mut Splits<'_>,
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &GrowParams,
) -> Vec<TreeNode> {
    let scorer = Scorer::new(prices, params.criterion);
    grow_nodes_by(splits, mc, params.max_depth, |splits, c| {
        choose(splits, c, prices, params, &scorer)
    })
}

/// The nodes of the tree grown through `splits`, splitting each impure cell above
/// `max_depth` on the test `choose` picks for it (a leaf where it picks none); the nodes
/// grown so far once the stop `splits` watches is requested.
pub(super) fn grow_nodes_by(
    splits: &mut Splits<'_>,
    mc: &MisclassCosts,
    max_depth: usize,
    mut choose: impl FnMut(&mut Splits<'_>, u32) -> Option<Stat>,
) -> Vec<TreeNode> {
    grow_nodes_valued(splits, mc, max_depth, |splits, c| (choose(splits, c), None))
}

/// [`grow_nodes_by`] with `choose` also giving what it valued each node at, which the
/// node keeps ([`TreeNode::value`]).
pub(super) fn grow_nodes_valued(
    splits: &mut Splits<'_>,
    mc: &MisclassCosts,
    max_depth: usize,
    mut choose: impl FnMut(&mut Splits<'_>, u32) -> (Option<Stat>, Option<NodeValue>),
) -> Vec<TreeNode> {
    let root = splits.cell(0).class_weights.clone();
    let mut nodes = vec![TreeNode {
        label: mc.best(&root).0 as u32,
        weights: root,
        split: None,
        value: None,
    }];
    let mut stack: Vec<(NodeIndex, u32)> = vec![(0, 0)];
    while let Some((node, c)) = stack.pop() {
        if splits.stopped() {
            break;
        }
        let cell = splits.cell(c);
        if is_pure(&cell.class_weights) || cell.path.len() >= max_depth {
            continue;
        }
        let node_weights = cell.class_weights.clone();
        let (best, value) = choose(splits, c);
        nodes[node as usize].value = value;
        let Some(best) = best else {
            continue;
        };
        splits.children(c, &best);
        let splits = &*splits;
        let Some(children) = splits.cell(c).children_for(best.feature) else {
            continue;
        };
        let mut made = Vec::with_capacity(children.cells.len());
        for cell in &children.cells {
            let weights = match cell {
                Some(child) => splits.cell(*child).class_weights.clone(),
                None => node_weights.clone(),
            };
            let index = nodes.len() as NodeIndex;
            nodes.push(TreeNode {
                label: mc.best(&weights).0 as u32,
                weights,
                split: None,
                value: None,
            });
            made.push(index);
            if let Some(child) = cell {
                stack.push((index, *child));
            }
        }
        nodes[node as usize].split = Some(match children.at {
            Some(at) => Split::Threshold {
                feature: children.feature,
                at,
                children: [made[0], made[1]],
                shares: [children.shares[0], children.shares[1]],
            },
            None => Split::Nominal {
                feature: children.feature,
                children: made,
                shares: children.shares.clone(),
            },
        });
    }
    nodes
}

/// Whether weights per class hold a single class.
pub(super) fn is_pure(class_weights: &[f64]) -> bool {
    class_weights.iter().filter(|&&w| w > 1e-9).count() <= 1
}

/// What [`CostTree::held_out_cost`] walks with: the tree is never built, each subtree
/// reports its pessimistic error estimate and the held-out objects' total cost.
struct Walk<'a> {
    scorer: Scorer,
    prices: &'a TestPrices,
    real: &'a TestPrices,
    mc: &'a MisclassCosts,
    params: &'a GrowParams,
    coeff: f64,
}

impl Walk<'_> {
    /// A leaf with these training weights, reached by these held-out weights after
    /// paying `paid`: (its error estimate, the held-out total cost).
    fn leaf(&self, weights: &[f64], label_weights: &[f64], held: &[f64], paid: f64) -> (f64, f64) {
        let label = self.mc.best(label_weights).0;
        let reached: f64 = held.iter().sum();
        let wrong: f64 = held
            .iter()
            .enumerate()
            .map(|(c, w)| w * self.mc.cost(label, c))
            .sum();
        let estimate = match (self.params.confidence, self.params.pruning) {
            (Some(confidence), Pruning::Errors) => {
                let total: f64 = weights.iter().sum();
                let errors = total - weights.iter().copied().fold(0.0, f64::max);
                errors + added_errors(total, errors, confidence, self.coeff)
            }
            (Some(confidence), Pruning::Costs) => {
                estimated_cost(self.mc, weights, confidence, self.coeff)
            }
            (None, _) => 0.0,
        };
        (estimate, wrong + reached * paid)
    }

    /// The subtree grown from cell `c`, after the tests `path` that cost `paid`.
    fn subtree(
        &self,
        splits: &mut Splits<'_>,
        c: u32,
        path: &mut Vec<usize>,
        paid: f64,
    ) -> (f64, f64) {
        let as_leaf = {
            let cell = splits.cell(c);
            self.leaf(
                &cell.class_weights,
                &cell.class_weights,
                &cell.held_classes,
                paid,
            )
        };
        let cell = splits.cell(c);
        if is_pure(&cell.class_weights) || cell.path.len() >= self.params.max_depth {
            return as_leaf;
        }
        let Some(best) = choose(splits, c, self.prices, self.params, &self.scorer) else {
            return as_leaf;
        };
        let branches = splits.children(c, &best).cells.len();
        let feature = best.feature;
        let bought = !path.contains(&feature);
        let price = if bought {
            price_after(self.real, feature, path)
        } else {
            0.0
        };
        let paid_below = if bought { paid + price } else { paid };
        if bought {
            path.push(feature);
        }
        let (mut estimate, mut cost) = (0.0, 0.0);
        for b in 0..branches {
            let child = splits
                .cell(c)
                .children_for(feature)
                .and_then(|ch| ch.cells[b]);
            let (e, k) = match child {
                Some(child) => self.subtree(splits, child, path, paid_below),
                None => {
                    let cell = splits.cell(c);
                    let held = cell
                        .children_for(feature)
                        .and_then(|ch| ch.held_out.get(b))
                        .map_or(&[][..], Vec::as_slice);
                    // No training object: no errors to estimate, the parent's answer.
                    let (_, k) = self.leaf(&[], &cell.class_weights, held, paid_below);
                    (0.0, k)
                }
            };
            estimate += e;
            cost += k;
        }
        if bought {
            path.pop();
        }
        if self.params.confidence.is_none() {
            return (estimate, cost);
        }
        match self.params.pruning {
            Pruning::Errors if as_leaf.0 <= estimate + 0.1 => as_leaf,
            Pruning::Errors => (estimate, cost),
            Pruning::Costs => {
                let total: f64 = splits.cell(c).class_weights.iter().sum();
                let subtree = estimate + price * total;
                if as_leaf.0 <= subtree {
                    as_leaf
                } else {
                    (subtree, cost)
                }
            }
        }
    }
}

/// A criterion's score, with EG2's price factor `(price + 1)^w` computed once per test
/// and price rather than at every node.
pub(super) struct Scorer {
    criterion: Criterion,
    /// Per test: its full and discount prices with their EG2 factors.
    eg2: Vec<[(f64, f64); 2]>,
}

impl Scorer {
    pub(super) fn new(prices: &TestPrices, criterion: Criterion) -> Scorer {
        let eg2 = match criterion {
            Criterion::Eg2 { w } => (0..prices.len())
                .map(|i| {
                    let t = prices.test(i);
                    [
                        (t.full, (t.full + 1.0).powf(w)),
                        (t.discount, (t.discount + 1.0).powf(w)),
                    ]
                })
                .collect(),
            _ => Vec::new(),
        };
        Scorer { criterion, eg2 }
    }

    pub(super) fn score(&self, stat: &Stat, price: f64) -> f64 {
        match self.criterion {
            Criterion::Eg2 { w } => {
                let factor = self.eg2[stat.feature]
                    .iter()
                    .find(|(p, _)| *p == price)
                    .map_or_else(|| (price + 1.0).powf(w), |(_, f)| *f);
                stat.exp2_gain / factor
            }
            c => c.score(stat.gain, stat.split_info, price),
        }
    }
}

/// The test to split cell `c` on with these prices, if any: the best score among the
/// tests with positive gain (for DTMC, a positive reduction of the expected total cost);
/// for C4.5 only among those whose gain is at least the average. Ties go to the higher
/// gain, then to the lower feature index.
fn choose(
    splits: &mut Splits<'_>,
    c: u32,
    prices: &TestPrices,
    params: &GrowParams,
    scorer: &Scorer,
) -> Option<Stat> {
    let criterion = params.criterion;
    let total = splits.total(c);
    let cost_based = splits.cost_based();
    let path = std::mem::take(&mut splits.cell_mut(c).path);
    // Whether the path can afford a test (always, without a budget). What the path has
    // paid is summed as classification sums it, test by test in the path's order.
    let budget = params.budget;
    let (paid, bought) = if budget.is_unlimited() {
        (0.0, 0)
    } else {
        path_spending(prices, &path)
    };
    let affords = |stat: &Stat| -> bool {
        budget.is_unlimited() || {
            let new = !path.contains(&stat.feature);
            let price = if new {
                price_after(prices, stat.feature, &path)
            } else {
                0.0
            };
            budget.allows(paid, bought, price, new)
        }
    };
    // (value, score) of a test: the gain (DTMC: the reduction of the expected total cost)
    // and the criterion's score at the test's price on this path.
    let judge = |stat: &Stat| -> (f64, f64) {
        let price = params.selection_prices.price(prices, stat.feature, &path);
        if cost_based {
            let reduction = stat.gain - price * total;
            (reduction, reduction)
        } else {
            (stat.gain, scorer.score(stat, price))
        }
    };
    let stats = splits.stats(c);
    let floor = if matches!(criterion, Criterion::C45) {
        let (sum, n) = stats
            .iter()
            .filter(|s| affords(s))
            .map(|s| judge(s).0)
            .filter(|&v| v > 1e-9)
            .fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
        if n > 0 { sum / n as f64 - 1e-12 } else { 0.0 }
    } else {
        f64::NEG_INFINITY
    };
    let mut best: Option<(Stat, f64, f64)> = None;
    for stat in stats {
        if !affords(stat) {
            continue;
        }
        let (value, score) = judge(stat);
        if value <= 1e-9 || value < floor || score <= 0.0 {
            continue;
        }
        let better = match &best {
            None => true,
            Some(b) => score > b.2 || (score == b.2 && value > b.1),
        };
        if better {
            best = Some((*stat, value, score));
        }
    }
    splits.cell_mut(c).path = path;
    best.map(|b| b.0)
}

/// What an object following `path` pays and how many distinct tests it buys: each
/// test at its price after the ones before it, summed in order as
/// [`CostTree::classify`] sums them (a test met again adds nothing).
pub(super) fn path_spending(prices: &TestPrices, path: &[usize]) -> (f64, usize) {
    let mut done: Vec<usize> = Vec::with_capacity(path.len());
    let mut spent = 0.0;
    for &test in path {
        if !done.contains(&test) {
            spent += price_after(prices, test, &done);
            done.push(test);
        }
    }
    (spent, done.len())
}

/// The price of `test` after the tests `done`: nothing if it was done, its discount if a
/// test of its group was, its full price otherwise ([`Basket`]'s rule, for a path).
pub(super) fn price_after(prices: &TestPrices, test: usize, done: &[usize]) -> f64 {
    prices.price_when(test, done.contains(&test), |g| {
        done.iter().any(|&d| prices.test(d).group == Some(g))
    })
}

/// The normal deviate for a one-sided confidence level, by C4.5's table and linear
/// interpolation.
pub(super) fn deviation(confidence: f64) -> f64 {
    const VAL: [f64; 9] = [0.0, 0.001, 0.005, 0.01, 0.05, 0.10, 0.20, 0.40, 1.00];
    const DEV: [f64; 9] = [4.0, 3.09, 2.58, 2.33, 1.65, 1.28, 0.84, 0.25, 0.00];
    let cf = confidence.clamp(0.0, 1.0);
    let mut i = 0;
    while i + 1 < VAL.len() && cf > VAL[i + 1] {
        i += 1;
    }
    let i = i.min(VAL.len() - 2);
    DEV[i] + (DEV[i + 1] - DEV[i]) * (cf - VAL[i]) / (VAL[i + 1] - VAL[i])
}

/// A leaf's pessimistic misclassification cost ([`Pruning::Costs`]): the cost of its
/// training weights under its label, plus C4.5's added errors at the dearest error of
/// that label.
pub(super) fn estimated_cost(
    mc: &MisclassCosts,
    weights: &[f64],
    confidence: f64,
    coeff: f64,
) -> f64 {
    let total: f64 = weights.iter().sum();
    if total <= 0.0 {
        return 0.0;
    }
    let label = mc.best(weights).0;
    let seen: f64 = weights
        .iter()
        .enumerate()
        .map(|(c, w)| w * mc.cost(label, c))
        .sum();
    let errors = total - weights[label];
    let dearest = (0..weights.len())
        .map(|c| mc.cost(label, c))
        .fold(0.0, f64::max);
    seen + added_errors(total, errors, confidence, coeff) * dearest
}

/// C4.5's `AddErrs`: the extra errors to add to `errors` among `n` objects for the upper
/// limit of the confidence interval.
fn added_errors(n: f64, errors: f64, confidence: f64, coeff: f64) -> f64 {
    if n <= 0.0 {
        return 0.0;
    }
    if errors < 1e-6 {
        n * (1.0 - (confidence.ln() / n).exp())
    } else if errors < 0.9999 {
        let v = n * (1.0 - (confidence.ln() / n).exp());
        v + errors * (added_errors(n, 1.0, confidence, coeff) - v)
    } else if errors + 0.5 >= n {
        0.67 * (n - errors)
    } else {
        let e = errors + 0.5;
        let pr =
            (e + coeff / 2.0 + (coeff * (e * (1.0 - e / n) + coeff / 4.0)).sqrt()) / (n + coeff);
        n * pr - errors
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deviation_matches_c45_at_its_default() {
        // Between 0.20 (0.84) and 0.40 (0.25): 0.84 - 0.59 / 4.
        assert!((deviation(0.25) - 0.6925).abs() < 1e-12);
        assert_eq!(deviation(0.05), 1.65);
    }

    #[test]
    fn added_errors_by_hand() {
        let coeff = deviation(0.25).powi(2);
        // No errors among 6: 6 * (1 - 0.25^(1/6)) = 1.3636...
        let none = added_errors(6.0, 0.0, 0.25, coeff);
        assert!((none - 6.0 * (1.0 - 0.25f64.powf(1.0 / 6.0))).abs() < 1e-12);
        // One error among 6 by the normal approximation of C4.5.
        let e: f64 = 1.5;
        let pr = (e + coeff / 2.0 + (coeff * (e * (1.0 - e / 6.0) + coeff / 4.0)).sqrt())
            / (6.0 + coeff);
        assert!((added_errors(6.0, 1.0, 0.25, coeff) - (6.0 * pr - 1.0)).abs() < 1e-12);
    }
}
