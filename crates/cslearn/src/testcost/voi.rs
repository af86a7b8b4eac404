//! VOI, the value-of-information tree: each test bought where its expected value, looking
//! a few tests ahead, exceeds its price.
//!
//! At a node, the objects reaching it stand for the objects a classification will send
//! there. Stopping costs the expected misclassification cost of the node's answer under
//! its class estimate; a test costs its price on the path plus, over its branches
//! (weighted as the training objects split), the value of going on from each branch,
//! found the same way `lookahead - 1` more tests ahead (a branch at the horizon stops).
//! The node buys the test of least expected total cost if that is less than stopping;
//! a pair of tests that pays while neither pays alone is therefore bought at a lookahead
//! of two. What stopping costs is estimated so that a branch of two objects of one class
//! does not look certain ([`VoiLeaf`]): by default C4.5's pessimistic error (the upper
//! limit of a confidence interval on the node's error rate), or an m-estimate of the
//! classes, which the tree then keeps as its nodes' weights.

use super::budget::Budget;
use super::criterion::Criterion;
use super::prices::{MisclassCosts, TestPrices};
use super::splits::{Splits, Stat};
use super::tree::{
    CostTree, GrowParams, NodeValue, SelectionPrices, TreeNode, deviation, estimated_cost,
    grow_nodes_valued, is_pure, path_spending, price_after,
};
use crate::Error;

/// VOI's settings.
///
/// ```
/// use cslearn::testcost::{VoiLeaf, VoiParams};
/// let p = VoiParams::default();
/// assert_eq!((p.lookahead, p.leaf), (None, VoiLeaf::Pessimistic { confidence: 0.25 }));
/// // Three tests ahead on heart's 13 features, two on Spambase's 57.
/// assert_eq!((p.lookahead_for(13), p.lookahead_for(57)), (3, 2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct VoiParams {
    /// How many tests ahead a test is valued (1: its branches stop; 2: each branch may
    /// buy one more test), at most [`MAX_LOOKAHEAD`](VoiParams::MAX_LOOKAHEAD); `None`
    /// (the default) by the data's width ([`lookahead_for`](VoiParams::lookahead_for)).
    pub lookahead: Option<usize>,
    /// How what stopping costs is estimated.
    pub leaf: VoiLeaf,
}

impl Default for VoiParams {
    fn default() -> Self {
        VoiParams {
            lookahead: None,
            leaf: VoiLeaf::Pessimistic { confidence: 0.25 },
        }
    }
}

/// How VOI estimates what stopping at a node costs, so that a node of few objects of one
/// class does not promise that the next object is of that class.
///
/// ```
/// use cslearn::testcost::VoiLeaf;
/// let leaf: VoiLeaf = serde_json::from_str(r#"{"m_estimate":{"m":2.0}}"#).unwrap();
/// assert_eq!(leaf, VoiLeaf::MEstimate { m: 2.0 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VoiLeaf {
    /// The cost of the node's errors under its answer, plus C4.5's added errors at
    /// `confidence` (ACT's estimate of a leaf) at the dearest error of that answer; the
    /// tree's nodes keep their training weights, as the family's do.
    Pessimistic {
        /// The confidence of the upper limit (C4.5's 0.25).
        confidence: f64,
    },
    /// The expected misclassification cost of the best answer under the m-estimate
    /// `(w_k + m p_k) / (W + m)` of each class (the node's class weights pulled towards
    /// the training objects' class shares `p`, Laplace-smoothed, by `m` objects' worth);
    /// the tree's nodes keep these pseudo-counts as their weights, so that its answers
    /// and probabilities are the estimates the tests were bought by.
    MEstimate {
        /// The weight of the class shares, in objects (0 takes the counts as they are).
        m: f64,
    },
}

impl VoiParams {
    /// The deepest lookahead accepted: the work per node grows as the number of features
    /// to this power.
    pub const MAX_LOOKAHEAD: usize = 3;

    /// The most features on which the default looks three tests ahead rather than two:
    /// a node then values at most 21³ = 9,261 sequences of three tests.
    pub const NARROW: usize = 21;

    /// How many tests ahead VOI values a test on data of `features` features: the
    /// lookahead set, or by default three where the features are at most
    /// [`NARROW`](VoiParams::NARROW) and two beyond (the work per node grows as the
    /// features to the lookahead's power: on Spambase's 57 a tree looking three ahead
    /// takes about 45 times as long as looking two).
    ///
    /// ```
    /// use cslearn::testcost::VoiParams;
    /// let p = VoiParams::default();
    /// assert_eq!((p.lookahead_for(21), p.lookahead_for(22)), (3, 2));
    /// let one = VoiParams { lookahead: Some(1), ..p };
    /// assert_eq!(one.lookahead_for(5), 1);
    /// ```
    pub fn lookahead_for(&self, features: usize) -> usize {
        self.lookahead
            .unwrap_or(if features <= VoiParams::NARROW { 3 } else { 2 })
    }

    /// The settings a front end's options ask for: the defaults where an option is not
    /// given, an m-estimate where `m` is given, checked ([`check`](VoiParams::check)). A
    /// confidence and an m together are refused: the leaf estimate is one or the other.
    ///
    /// ```
    /// use cslearn::testcost::{VoiLeaf, VoiParams};
    /// assert_eq!(VoiParams::from_options(None, None, None).unwrap(), VoiParams::default());
    /// let p = VoiParams::from_options(Some(3), None, Some(1.0)).unwrap();
    /// assert_eq!((p.lookahead, p.leaf), (Some(3), VoiLeaf::MEstimate { m: 1.0 }));
    /// assert!(VoiParams::from_options(None, Some(0.1), Some(1.0)).is_err());
    /// assert!(VoiParams::from_options(Some(9), None, None).is_err());
    /// ```
    pub fn from_options(
        lookahead: Option<usize>,
        confidence: Option<f64>,
        m: Option<f64>,
    ) -> Result<VoiParams, Error> {
        let default = VoiParams::default();
        let leaf = match (confidence, m) {
            (Some(confidence), Some(m)) => {
                return Err(Error::Invalid {
                    what: format!("VOI confidence {confidence} and m {m}"),
                    reason: "a leaf is estimated pessimistically (a confidence) or by an \
                             m-estimate (an m), not both"
                        .into(),
                });
            }
            (Some(confidence), None) => VoiLeaf::Pessimistic { confidence },
            (None, Some(m)) => VoiLeaf::MEstimate { m },
            (None, None) => default.leaf,
        };
        let params = VoiParams {
            lookahead: lookahead.or(default.lookahead),
            leaf,
        };
        params.check()?;
        Ok(params)
    }

    /// Whether these are the defaults (result files leave the defaults out).
    ///
    /// ```
    /// assert!(cslearn::testcost::VoiParams::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == VoiParams::default()
    }

    /// Refuse a lookahead outside 1 to [`MAX_LOOKAHEAD`](VoiParams::MAX_LOOKAHEAD), a
    /// confidence outside (0, 1) and an m that is negative or not finite.
    ///
    /// ```
    /// use cslearn::testcost::{VoiLeaf, VoiParams};
    /// assert!(VoiParams { lookahead: Some(0), ..VoiParams::default() }.check().is_err());
    /// let leaf = VoiLeaf::MEstimate { m: -1.0 };
    /// assert!(VoiParams { leaf, ..VoiParams::default() }.check().is_err());
    /// let leaf = VoiLeaf::Pessimistic { confidence: 1.0 };
    /// assert!(VoiParams { leaf, ..VoiParams::default() }.check().is_err());
    /// assert!(VoiParams::default().check().is_ok());
    /// ```
    pub fn check(&self) -> Result<(), Error> {
        if let Some(lookahead) = self.lookahead
            && !(1..=VoiParams::MAX_LOOKAHEAD).contains(&lookahead)
        {
            return Err(Error::Invalid {
                what: format!("VOI lookahead {lookahead}"),
                reason: format!(
                    "from 1 to {} tests ahead (the work per node grows as the number of features to this power)",
                    VoiParams::MAX_LOOKAHEAD
                ),
            });
        }
        match self.leaf {
            VoiLeaf::MEstimate { m } if !(m.is_finite() && m >= 0.0) => Err(Error::Invalid {
                what: format!("VOI m {m}"),
                reason: "the m-estimate's weight is a finite number of objects, 0 or more".into(),
            }),
            VoiLeaf::Pessimistic { confidence } if !(confidence > 0.0 && confidence < 1.0) => {
                Err(Error::Invalid {
                    what: format!("VOI confidence {confidence}"),
                    reason: "the pessimistic estimate's confidence is between 0 and 1, both \
                             excluded (C4.5's is 0.25)"
                        .into(),
                })
            }
            _ => Ok(()),
        }
    }
}

/// What VOI values nodes by.
struct Valuer<'p> {
    prices: &'p TestPrices,
    mc: &'p MisclassCosts,
    selection: SelectionPrices,
    budget: Budget,
    leaf: VoiLeaf,
    /// The class prior the m-estimates are pulled towards, times m (zeros for the
    /// pessimistic estimate).
    prior_m: Vec<f64>,
    /// C4.5's squared normal deviate at the pessimistic estimate's confidence.
    coeff: f64,
}

impl Valuer<'_> {
    /// The class estimate's pseudo-counts for these weights.
    fn pseudo(&self, weights: &[f64]) -> Vec<f64> {
        weights
            .iter()
            .zip(&self.prior_m)
            .map(|(w, p)| w + p)
            .collect()
    }

    /// What stopping costs the objects of weight `total` with these class weights: their
    /// weight times the expected misclassification cost of the best answer.
    fn leaf(&self, weights: &[f64], total: f64) -> f64 {
        if total <= 0.0 {
            return 0.0;
        }
        match self.leaf {
            VoiLeaf::Pessimistic { confidence } => {
                estimated_cost(self.mc, weights, confidence, self.coeff)
            }
            VoiLeaf::MEstimate { m } => {
                let (_, cost) = self.mc.best(&self.pseudo(weights));
                // `best` sums the pseudo-counts' costs: per object, divide by their sum.
                total * cost / (total + m)
            }
        }
    }

    /// Whether the path's objects, which have spent `spent` (what they paid, the tests
    /// they bought; `None` without a budget), may still buy `stat`'s test.
    fn affords(&self, path: &[usize], spent: Option<(f64, usize)>, stat: &Stat) -> bool {
        let Some((paid, bought)) = spent else {
            return true;
        };
        let new = !path.contains(&stat.feature);
        let price = if new {
            price_after(self.prices, stat.feature, path)
        } else {
            0.0
        };
        self.budget.allows(paid, bought, price, new)
    }

    /// The least expected total cost (in weight times cost) of the objects of cell `c`
    /// looking `depth` tests ahead, and the test that reaches it (`None`: stopping).
    fn value(&self, splits: &mut Splits<'_>, c: u32, depth: usize) -> (f64, Option<Stat>) {
        let cell = splits.cell(c);
        let total = cell.class_weights.iter().sum::<f64>();
        let stop = self.leaf(&cell.class_weights, total);
        if depth == 0 || is_pure(&cell.class_weights) || splits.stopped() {
            return (stop, None);
        }
        let path = cell.path.clone();
        // What the path has spent, summed once for every test valued here.
        let spent = (!self.budget.is_unlimited()).then(|| path_spending(self.prices, &path));
        let stats: Vec<Stat> = splits.stats(c).to_vec();
        let mut best = (stop, None);
        for stat in stats {
            if !self.affords(&path, spent, &stat) {
                continue;
            }
            let price = self.selection.price(self.prices, stat.feature, &path);
            // The branches' cells live while they are valued: memory for one path of the
            // lookahead at a time, not for all of it.
            let mark = splits.mark();
            let list = splits.made_children(c, &stat);
            let mut cost = price * total;
            for b in 0..splits.branches(c, list) {
                if let Some(child) = splits.child(c, list, b) {
                    cost += self.value(splits, child, depth - 1).0;
                }
                if cost >= best.0 {
                    break;
                }
            }
            splits.forget_since(mark);
            // A test must save more than rounding: ties stop, or keep the earlier test.
            if cost < best.0 - 1e-9 * best.0.abs().max(1.0) {
                best = (cost, Some(stat));
            }
        }
        best
    }
}

/// VOI's tree on the objects of `splits` (a trie of DTMC's statistics).
pub(super) fn voi_tree_in(
    splits: &mut Splits<'_>,
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &VoiParams,
    grow: &GrowParams,
) -> CostTree {
    let root = splits.cell(0).class_weights.clone();
    let total: f64 = root.iter().sum();
    let classes = root.len().max(1) as f64;
    let (m, confidence) = match params.leaf {
        VoiLeaf::MEstimate { m } => (m, 0.25),
        VoiLeaf::Pessimistic { confidence } => (0.0, confidence),
    };
    let prior_m: Vec<f64> = root
        .iter()
        .map(|w| m * (w + 1.0) / (total + classes))
        .collect();
    let valuer = Valuer {
        prices,
        mc,
        selection: grow.selection_prices,
        budget: grow.budget,
        leaf: params.leaf,
        prior_m,
        coeff: deviation(confidence).powi(2),
    };
    let lookahead = params.lookahead_for(prices.len());
    let mut nodes = grow_nodes_valued(splits, mc, grow.max_depth, |splits, c| {
        let weights = &splits.cell(c).class_weights;
        let total: f64 = weights.iter().sum();
        let stop = valuer.leaf(weights, total);
        let (cost, stat) = valuer.value(splits, c, lookahead);
        let per_object = |v: f64| if total > 0.0 { v / total } else { 0.0 };
        let value = NodeValue {
            stop: per_object(stop),
            test: stat.map(|_| per_object(cost)),
        };
        (stat, Some(value))
    });
    if matches!(params.leaf, VoiLeaf::MEstimate { .. }) {
        for node in &mut nodes {
            relabel(node, &valuer);
        }
    }
    CostTree::from_nodes(nodes, mc)
}

/// A node's weights become its class estimate's pseudo-counts, and its answer the best
/// for them.
fn relabel(node: &mut TreeNode, valuer: &Valuer<'_>) {
    node.weights = valuer.pseudo(&node.weights);
    node.label = valuer.mc.best(&node.weights).0 as u32;
}

/// The trie VOI grows through.
pub(super) fn voi_trie<'a>(
    frame: &'a super::data::Frame,
    rows: &[usize],
    mc: &'a MisclassCosts,
    grow: &GrowParams,
) -> Splits<'a> {
    let ones = vec![1.0; rows.len()];
    Splits::new(frame, rows, &ones, mc, Criterion::Dtmc, grow.min_objects)
}
