//! CVT, the cost-validated tree: the growth and the stopping point chosen by the total
//! cost measured on objects the tree did not learn from.
//!
//! Classifying an object is a sequence of decisions: pay for one more test, or stop and
//! answer. A tree makes them; what makes it cheap is where it stops. CVT grows several
//! unpruned trees, one per selection function of a small set ([`GROWERS`]: EG2 at four
//! weights of the price, from none to a double one, C4.5's gain ratio and DTMC's cost
//! reduction), and follows each along its cost-complexity path (Breiman et al. 1984,
//! here with the tests' prices inside the cost): at a price `alpha` per leaf, each
//! subtree stays only where it lowers the training objects' tests plus misclassification
//! plus `alpha` per leaf; raising `alpha` cuts the tree back leaf by leaf to its root.
//! Stratified `k`-fold cross-validation on the training objects measures each grower's
//! tree at each point of its path by what really matters, the total cost of classifying
//! the held-out objects (their tests at the real prices, after their path, plus the
//! misclassification of the answers). The grower and `alpha` of least held-out cost give
//! the final tree, grown on every training object and cut back at that `alpha`.
//!
//! Where the pessimistic estimates of C4.5, ACT and ICET guess how a subtree will do on
//! new objects, CVT measures it; where ICET scores each of its trees on one half of the
//! objects, CVT scores on every object once.

use super::criterion::Criterion;
use super::data::Frame;
use super::evaluate::folds_of;
use super::prices::{MisclassCosts, TestPrices};
use super::tree::{CostTree, GrowParams, SelectionPrices};
use crate::Error;

/// CVT's settings.
///
/// ```
/// assert_eq!(cslearn::testcost::CvtParams::default().folds, 5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CvtParams {
    /// The folds of the cross-validation that chooses the grower and where to stop (5 by
    /// default; the front ends refuse fewer than 2, and the library takes fewer as 2).
    pub folds: usize,
}

impl CvtParams {
    /// CVT's defaults with `folds` folds, refused below 2.
    ///
    /// ```
    /// use cslearn::testcost::CvtParams;
    /// assert_eq!(CvtParams::with_folds(10).unwrap().folds, 10);
    /// let e = CvtParams::with_folds(1).unwrap_err().to_string();
    /// assert!(e.contains("1 folds") && e.contains("at least 2"), "{e}");
    /// ```
    pub fn with_folds(folds: usize) -> Result<CvtParams, Error> {
        if folds < 2 {
            return Err(Error::Invalid {
                what: format!("{folds} folds for CVT"),
                reason: "a cross-validation needs at least 2 folds".into(),
            });
        }
        Ok(CvtParams { folds })
    }
}

impl Default for CvtParams {
    fn default() -> CvtParams {
        CvtParams { folds: 5 }
    }
}

/// The selection functions CVT grows its candidate trees with, by name.
pub const GROWERS: [(&str, Criterion); 6] = [
    ("eg2-w0", Criterion::Eg2 { w: 0.0 }),
    ("eg2-w0.5", Criterion::Eg2 { w: 0.5 }),
    ("eg2-w1", Criterion::Eg2 { w: 1.0 }),
    ("eg2-w2", Criterion::Eg2 { w: 2.0 }),
    ("c45", Criterion::C45),
    ("dtmc", Criterion::Dtmc),
];

/// The most points of a cost-complexity path measured (evenly spaced along it when the
/// path is longer).
const MAX_POINTS: usize = 48;

/// What CVT chose.
///
/// ```
/// let c = cslearn::testcost::CvtChoice { grower: 2, alpha: 12.5, held_out_cost: 30.0 };
/// assert_eq!(c.grower_name(), "eg2-w1");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CvtChoice {
    /// The index of the grower in [`GROWERS`].
    pub grower: usize,
    /// The price per leaf the tree was cut back at.
    pub alpha: f64,
    /// The mean total cost per object measured on the held-out folds.
    pub held_out_cost: f64,
}

impl CvtChoice {
    /// The name of the grower chosen.
    pub fn grower_name(&self) -> &'static str {
        GROWERS.get(self.grower).map_or("?", |g| g.0)
    }
}

/// CVT's tree on the objects `rows` of `frame`, with its choice; the folds are drawn from
/// `seed`.
pub(super) fn cvt_tree(
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &CvtParams,
    selection: SelectionPrices,
    seed: u64,
) -> (CostTree, CvtChoice) {
    // Each fold's training objects and held-out objects, the same for every grower.
    let parts: Vec<(Vec<usize>, Vec<usize>)> = folds_of(frame, rows, params.folds.max(2), seed)
        .into_iter()
        .filter_map(|out| {
            let mut held_out = vec![false; frame.len()];
            for &r in &out {
                held_out[r] = true;
            }
            let train: Vec<usize> = rows.iter().copied().filter(|&r| !held_out[r]).collect();
            (!train.is_empty() && !out.is_empty()).then_some((train, out))
        })
        .collect();
    // The first grower's first point until a cheaper one is measured.
    let mut choice = CvtChoice {
        grower: 0,
        alpha: 0.0,
        held_out_cost: f64::INFINITY,
    };
    let mut trees = Vec::with_capacity(GROWERS.len());
    for (g, &(_, criterion)) in GROWERS.iter().enumerate() {
        let grow = GrowParams::new(criterion).selecting_at(selection);
        let tree = CostTree::grow(frame, rows, prices, mc, &grow);
        let alphas = Costs::of(&tree, prices).path_points(&tree);
        let mut held = vec![0.0; alphas.len()];
        for (train, out) in &parts {
            let fold_tree = CostTree::grow(frame, train, prices, mc, &grow);
            let fold_costs = Costs::of(&fold_tree, prices);
            let reached = fold_tree.reach(frame, out);
            for (h, &alpha) in held.iter_mut().zip(&alphas) {
                *h += fold_costs.held_out(&fold_tree, &reached, alpha, mc);
            }
        }
        for (&alpha, &h) in alphas.iter().zip(&held) {
            let mean = h / rows.len().max(1) as f64;
            if mean < choice.held_out_cost {
                choice = CvtChoice {
                    grower: g,
                    alpha,
                    held_out_cost: mean,
                };
            }
        }
        trees.push(tree);
    }
    let mut tree = trees.swap_remove(choice.grower);
    let costs = Costs::of(&tree, prices);
    let cut = costs.cut_at(&tree, choice.alpha).1;
    tree.cut(&cut);
    (tree, choice)
}

/// A tree's training costs per node: what answering there costs its training objects,
/// and what its test costs them.
struct Costs {
    /// Misclassification cost of the node's training weights under its best answer.
    as_leaf: Vec<f64>,
    /// The price of the node's test after its path, times the node's training weight.
    test: Vec<f64>,
    /// The price of the node's test after its path, per object.
    price: Vec<f64>,
}

impl Costs {
    fn of(tree: &CostTree, prices: &TestPrices) -> Costs {
        let price = tree.test_prices(prices);
        let mc = tree.misclass_costs();
        let mut as_leaf = Vec::with_capacity(tree.len());
        let mut test = Vec::with_capacity(tree.len());
        for (i, &p) in price.iter().enumerate() {
            let w = &tree.node(i).weights;
            as_leaf.push(mc.best(w).1);
            test.push(p * w.iter().sum::<f64>());
        }
        Costs {
            as_leaf,
            test,
            price,
        }
    }

    /// The training cost plus `alpha` per leaf of the best cut of each subtree at
    /// `alpha`, and which nodes that cut makes leaves (leaves reached by no training
    /// object are free and count no `alpha`).
    fn cut_at(&self, tree: &CostTree, alpha: f64) -> (Vec<f64>, Vec<bool>) {
        let n = tree.len();
        let mut best = vec![0.0; n];
        let mut cut = vec![false; n];
        for i in (0..n).rev() {
            let node = tree.node(i);
            let leaf = if node.weights.iter().sum::<f64>() > 0.0 {
                self.as_leaf[i] + alpha
            } else {
                0.0
            };
            best[i] = match &node.split {
                None => leaf,
                Some(split) => {
                    let below: f64 = self.test[i]
                        + split
                            .children()
                            .iter()
                            .map(|&c| best[c as usize])
                            .sum::<f64>();
                    if leaf <= below {
                        cut[i] = true;
                        leaf
                    } else {
                        below
                    }
                }
            };
        }
        (best, cut)
    }

    /// The points of the tree's cost-complexity path to measure: the geometric means of
    /// consecutive breakpoints (Breiman et al.), from 0 (the training cost's own best
    /// cut) to twice the last breakpoint (the root alone), at most [`MAX_POINTS`] of
    /// them.
    fn path_points(&self, tree: &CostTree) -> Vec<f64> {
        let breaks = self.breakpoints(tree);
        let mut points = vec![0.0];
        for pair in breaks.windows(2) {
            points.push((pair[0] * pair[1]).sqrt());
        }
        // Twice the last breakpoint: the root alone.
        if let Some(&last) = breaks.last() {
            points.push(2.0 * last);
        }
        if points.len() > MAX_POINTS {
            let last = points.len() - 1;
            points = (0..MAX_POINTS)
                .map(|i| points[i * last / (MAX_POINTS - 1)])
                .collect();
        }
        points.dedup();
        points
    }

    /// The values of `alpha` at which the best cut changes (weakest-link cutting), all
    /// positive, increasing.
    fn breakpoints(&self, tree: &CostTree) -> Vec<f64> {
        let n = tree.len();
        // Whether each inner node still tests (is not cut yet).
        let (_, at_zero) = self.cut_at(tree, 0.0);
        let mut tests: Vec<bool> = (0..n)
            .map(|i| tree.node(i).split.is_some() && !at_zero[i])
            .collect();
        let counted: Vec<bool> = (0..n)
            .map(|i| tree.node(i).weights.iter().sum::<f64>() > 0.0)
            .collect();
        let mut breaks = Vec::new();
        let mut in_tree = vec![false; n];
        let mut sub = vec![0.0; n];
        let mut leaves = vec![0usize; n];
        let mut g = vec![f64::INFINITY; n];
        loop {
            // Which nodes the cut tree still holds (parents come before children).
            in_tree[0] = true;
            for i in 0..n {
                if let Some(split) = &tree.node(i).split {
                    for &c in split.children() {
                        in_tree[c as usize] = in_tree[i] && tests[i];
                    }
                }
            }
            // Each testing node's subtree: its training cost, its leaves, and the price
            // per leaf at which cutting it pays.
            let mut weakest = f64::INFINITY;
            for i in (0..n).rev() {
                g[i] = f64::INFINITY;
                match &tree.node(i).split {
                    Some(split) if tests[i] => {
                        let children = split.children().iter().map(|&c| c as usize);
                        sub[i] = self.test[i] + children.clone().map(|c| sub[c]).sum::<f64>();
                        leaves[i] = children.map(|c| leaves[c]).sum();
                        if in_tree[i] && leaves[i] > 1 {
                            g[i] = (self.as_leaf[i] - sub[i]) / (leaves[i] - 1) as f64;
                            weakest = weakest.min(g[i]);
                        }
                    }
                    _ => {
                        sub[i] = if counted[i] { self.as_leaf[i] } else { 0.0 };
                        leaves[i] = usize::from(counted[i]);
                    }
                }
            }
            if !weakest.is_finite() {
                break;
            }
            breaks.push(weakest.max(0.0));
            let tie = weakest + 1e-9 * weakest.abs().max(1.0);
            for i in 0..n {
                if g[i] <= tie {
                    tests[i] = false;
                }
            }
        }
        breaks
    }

    /// The total cost of the held-out objects that `reached` each node of the tree (one
    /// weight per class per node) when the tree is cut at `alpha` by its training costs.
    fn held_out(
        &self,
        tree: &CostTree,
        reached: &[Vec<f64>],
        alpha: f64,
        mc: &MisclassCosts,
    ) -> f64 {
        let (_, cut) = self.cut_at(tree, alpha);
        let mut total = 0.0;
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let node = tree.node(i);
            match &node.split {
                Some(split) if !cut[i] => {
                    total += self.price[i] * reached[i].iter().sum::<f64>();
                    stack.extend(split.children().iter().map(|&c| c as usize));
                }
                _ => {
                    total += reached[i]
                        .iter()
                        .enumerate()
                        .map(|(c, w)| w * mc.cost(node.label as usize, c))
                        .sum::<f64>();
                }
            }
        }
        total
    }
}
