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
//! of two. Class estimates are m-estimates: `(w_k + m p_k) / (W + m)`, the node's class
//! weights pulled towards the training objects' class shares `p` (Laplace-smoothed) by
//! `m` objects' worth, so that a branch of two objects never looks certain; the tree's
//! nodes keep these pseudo-counts as their weights, so its answers and probabilities
//! are the estimates the choices were made by.

use super::budget::Budget;
use super::criterion::Criterion;
use super::prices::{MisclassCosts, TestPrices};
use super::splits::{Splits, Stat};
use super::tree::{
    CostTree, GrowParams, SelectionPrices, TreeNode, grow_nodes_by, is_pure, path_spending,
    price_after,
};
use crate::Error;

/// VOI's settings.
///
/// ```
/// let p = cslearn::testcost::VoiParams::default();
/// assert_eq!((p.lookahead, p.m), (2, 2.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct VoiParams {
    /// How many tests ahead a test is valued (1: its branches stop; 2: each branch may
    /// buy one more test), 2 by default, at most [`MAX_LOOKAHEAD`](VoiParams::MAX_LOOKAHEAD).
    pub lookahead: usize,
    /// The m-estimate's weight of the class prior, in objects (2 by default; 0 takes the
    /// training weights as they are).
    pub m: f64,
}

impl Default for VoiParams {
    fn default() -> Self {
        VoiParams {
            lookahead: 2,
            m: 2.0,
        }
    }
}

impl VoiParams {
    /// The deepest lookahead accepted: the work per node grows as the number of features
    /// to this power.
    pub const MAX_LOOKAHEAD: usize = 3;

    /// Whether these are the defaults (result files leave the defaults out).
    ///
    /// ```
    /// assert!(cslearn::testcost::VoiParams::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == VoiParams::default()
    }

    /// Refuse a lookahead outside 1 to [`MAX_LOOKAHEAD`](VoiParams::MAX_LOOKAHEAD) and an m
    /// that is negative or not finite.
    ///
    /// ```
    /// use cslearn::testcost::VoiParams;
    /// assert!(VoiParams { lookahead: 0, m: 2.0 }.check().is_err());
    /// assert!(VoiParams { lookahead: 2, m: -1.0 }.check().is_err());
    /// assert!(VoiParams::default().check().is_ok());
    /// ```
    pub fn check(&self) -> Result<(), Error> {
        if !(1..=VoiParams::MAX_LOOKAHEAD).contains(&self.lookahead) {
            return Err(Error::Invalid {
                what: format!("VOI lookahead {}", self.lookahead),
                reason: format!(
                    "from 1 to {} tests ahead (the work per node grows as the number of features to this power)",
                    VoiParams::MAX_LOOKAHEAD
                ),
            });
        }
        if !(self.m.is_finite() && self.m >= 0.0) {
            return Err(Error::Invalid {
                what: format!("VOI m {}", self.m),
                reason: "the m-estimate's weight is a finite number of objects, 0 or more".into(),
            });
        }
        Ok(())
    }
}

/// What VOI values nodes by.
struct Valuer<'p> {
    prices: &'p TestPrices,
    mc: &'p MisclassCosts,
    selection: SelectionPrices,
    budget: Budget,
    /// The class prior the estimates are pulled towards, times m.
    prior_m: Vec<f64>,
    m: f64,
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
        let (_, cost) = self.mc.best(&self.pseudo(weights));
        // `best` sums the pseudo-counts' costs: per object, divide by their sum.
        total * cost / (total + self.m)
    }

    /// Whether the path's objects may still buy `stat`'s test.
    fn affords(&self, path: &[usize], stat: &Stat) -> bool {
        if self.budget.is_unlimited() {
            return true;
        }
        let (paid, bought) = path_spending(self.prices, path);
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
        let stats: Vec<Stat> = splits.stats(c).to_vec();
        let mut best = (stop, None);
        for stat in stats {
            if !self.affords(&path, &stat) {
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
    let prior_m: Vec<f64> = root
        .iter()
        .map(|w| params.m * (w + 1.0) / (total + classes))
        .collect();
    let valuer = Valuer {
        prices,
        mc,
        selection: grow.selection_prices,
        budget: grow.budget,
        prior_m,
        m: params.m,
    };
    let mut nodes = grow_nodes_by(splits, mc, grow.max_depth, |splits, c| {
        valuer.value(splits, c, params.lookahead).1
    });
    for node in &mut nodes {
        relabel(node, &valuer);
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
