//! CVT, the cost-validated tree: the growth and the stopping point chosen by the total
//! cost measured on objects the tree did not learn from.
//!
//! Classifying an object is a sequence of decisions: pay for one more test, or stop and
//! answer. A tree makes them; what makes it cheap is which tests it asks for and where it
//! stops. CVT grows several unpruned trees, one per grower of a small set ([`GROWERS`]:
//! EG2 at four weights of the price, from none to a double one, C4.5's gain ratio, DTMC's
//! cost reduction, and ACT's sampled lookahead, which finds tests that are useless alone
//! but tell the class together), and considers for each the cuts along its
//! cost-complexity path (Breiman et al. 1984, here with the tests' prices inside the
//! cost): at a price `alpha` per leaf, each subtree stays only where it lowers the
//! training objects' tests plus misclassification plus `alpha` per leaf; raising `alpha`
//! cuts the tree back leaf by leaf to its root. One more cut per grower is ACT's: the
//! pessimistic pruning by cost ([`Pruning::Costs`](super::Pruning)), which cuts small
//! leaves harder than large ones where one `alpha` cuts them alike. Stratified `k`-fold
//! cross-validation on the training objects measures each grower's tree at each cut by
//! what really matters, the total cost of classifying the held-out objects (their tests
//! at the real prices, after their path, plus the misclassification of the answers). The
//! grower and cut of least held-out cost give the final tree, grown on every training
//! object and cut the same way.
//!
//! Where the pessimistic estimates of C4.5, ACT and ICET guess how a subtree will do on
//! new objects, CVT measures it, and keeps the estimate only where the measurement says
//! it guesses well; where ICET scores each of its trees on one half of the objects, CVT
//! scores on every object once.

use super::act::{Act, ActParams, check_samples, sub_seed, threads_wanted};
use super::criterion::Criterion;
use super::data::Frame;
use super::evaluate::folds_of;
use super::prices::{MisclassCosts, TestPrices};
use super::splits::Splits;
use super::stop::Stop;
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
    /// The most threads one fit uses (1 by default; 0 for every core): the trees on all
    /// the objects and on each fold's training part grow at the same time, each from its
    /// own seed, so the tree chosen does not depend on the number of threads.
    #[serde(default = "one_thread")]
    pub threads: usize,
    /// The trees the lookahead grower samples under each branch of each candidate test
    /// (5 by default, ACT's own; at most [`ActParams::MAX_SAMPLES`]): fewer make CVT
    /// faster, as its time is mostly the lookahead's; 0 leaves the lookahead out of the
    /// growers, so that CVT chooses among the greedy growers and their cuts only. Other
    /// than 5, other trees.
    #[serde(
        default = "lookahead_samples",
        skip_serializing_if = "is_lookahead_samples"
    )]
    pub samples: usize,
}

fn one_thread() -> usize {
    1
}

/// The lookahead's samples by default: ACT's.
fn lookahead_samples() -> usize {
    ActParams::default().samples
}

/// Whether `samples` is the default, left out of a model file so that files written
/// before the setting existed are written the same.
fn is_lookahead_samples(samples: &usize) -> bool {
    *samples == lookahead_samples()
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
        Ok(CvtParams {
            folds,
            ..CvtParams::default()
        })
    }

    /// These settings using up to `threads` threads (0: every core).
    ///
    /// ```
    /// use cslearn::testcost::CvtParams;
    /// assert_eq!(CvtParams::default().with_threads(2).threads, 2);
    /// ```
    pub fn with_threads(self, threads: usize) -> CvtParams {
        CvtParams { threads, ..self }
    }

    /// These settings with the lookahead grower sampling `samples` trees under each
    /// branch (0: no lookahead grower), refused above [`ActParams::MAX_SAMPLES`].
    ///
    /// ```
    /// use cslearn::testcost::CvtParams;
    /// assert_eq!(CvtParams::default().samples, 5);
    /// assert_eq!(CvtParams::default().with_samples(1).unwrap().samples, 1);
    /// let e = CvtParams::default().with_samples(100_000).unwrap_err().to_string();
    /// assert!(e.contains("100000 samples for CVT's lookahead"), "{e}");
    /// ```
    pub fn with_samples(self, samples: usize) -> Result<CvtParams, Error> {
        check_samples(samples, || format!("{samples} samples for CVT's lookahead"))?;
        Ok(CvtParams { samples, ..self })
    }

    /// The growers of a fit: [`GROWERS`], the lookahead sampling [`CvtParams::samples`]
    /// trees under each branch, or left out where that is 0 (it is the last, so a
    /// grower's index in [`GROWERS`] stays its index here).
    fn growers(&self) -> Vec<Grower> {
        GROWERS
            .iter()
            .filter_map(|&(_, grower)| match grower {
                Grower::Lookahead { .. } if self.samples == 0 => None,
                Grower::Lookahead { .. } => Some(Grower::Lookahead {
                    samples: self.samples,
                }),
                greedy => Some(greedy),
            })
            .collect()
    }

    /// The threads a fit uses: `threads`, every core for 0, never more than `jobs`.
    fn threads_for(&self, jobs: usize) -> usize {
        threads_wanted(self.threads).clamp(1, jobs.max(1))
    }
}

impl Default for CvtParams {
    fn default() -> CvtParams {
        CvtParams {
            folds: 5,
            threads: 1,
            samples: lookahead_samples(),
        }
    }
}

/// How CVT grows one of its candidate trees.
///
/// ```
/// use cslearn::testcost::{Grower, GROWERS};
/// assert_eq!(GROWERS[6], ("act", Grower::Lookahead { samples: 5 }));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Grower {
    /// A greedy grower with this selection function, unpruned.
    Greedy(Criterion),
    /// ACT's sampled lookahead (stochastic EG2 at `w` = 1, this many trees sampled under
    /// each branch of each candidate test, a leaf where answering costs less), before
    /// ACT's pruning.
    Lookahead {
        /// Trees sampled under each branch.
        samples: usize,
    },
}

/// The growers CVT grows its candidate trees with, by name; the lookahead samples as many
/// trees as ACT does (with 2, on krk at mc 1000 and one price draw, CVT cost 2% more
/// for about half the time).
pub const GROWERS: [(&str, Grower); 7] = [
    ("eg2-w0", Grower::Greedy(Criterion::Eg2 { w: 0.0 })),
    ("eg2-w0.5", Grower::Greedy(Criterion::Eg2 { w: 0.5 })),
    ("eg2-w1", Grower::Greedy(Criterion::Eg2 { w: 1.0 })),
    ("eg2-w2", Grower::Greedy(Criterion::Eg2 { w: 2.0 })),
    ("c45", Grower::Greedy(Criterion::C45)),
    ("dtmc", Grower::Greedy(Criterion::Dtmc)),
    ("act", Grower::Lookahead { samples: 5 }),
];

impl Grower {
    /// The kind of split statistics the grower reads: growers of one kind on the same
    /// objects share one split trie (each cell's statistics computed once).
    fn kind(self) -> Criterion {
        match self {
            Grower::Greedy(Criterion::Eg2 { .. }) | Grower::Lookahead { .. } => {
                Criterion::Eg2 { w: 1.0 }
            }
            Grower::Greedy(criterion) => criterion,
        }
    }

    /// The unpruned tree this grower grows through `splits` (of its [`kind`](Grower::kind)),
    /// its samples drawn from `seed`.
    fn grow_in(
        self,
        splits: &mut Splits<'_>,
        prices: &TestPrices,
        mc: &MisclassCosts,
        selection: SelectionPrices,
        seed: u64,
    ) -> CostTree {
        match self {
            Grower::Greedy(criterion) => {
                let grow = GrowParams::new(criterion).selecting_at(selection);
                CostTree::grow_in(splits, prices, mc, &grow)
            }
            Grower::Lookahead { samples } => {
                let params = ActParams {
                    samples,
                    ..ActParams::default()
                };
                let act = Act {
                    prices,
                    mc,
                    params: &params,
                    w: 1.0,
                    selection,
                    seed,
                };
                act.grown_in(splits)
            }
        }
    }
}

/// The split tries of one set of objects, one per kind of statistics.
type Tries<'a> = Vec<(Criterion, Splits<'a>)>;

/// The tree of each of `growers` on `rows`, in their order, growers of one kind
/// sharing a split trie; the lookahead's samples are drawn from `seed`. The tries are
/// `tries` (those of another call on the same objects, with their statistics), and stay
/// there but for DTMC's, whose statistics are priced at this call's `mc`. A trie made here
/// watches `stop`.
#[expect(
    clippy::too_many_arguments,
    reason = "the data, prices, costs, selection and seed, the growers, the tries and the stop"
)]
fn grow_all<'a>(
    frame: &'a Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &'a MisclassCosts,
    (selection, seed): (SelectionPrices, u64),
    growers: &[Grower],
    tries: &mut Tries<'a>,
    stop: &'a Stop,
) -> Vec<CostTree> {
    let ones = vec![1.0; rows.len()];
    let min_objects = GrowParams::new(Criterion::C45).min_objects;
    let trees = growers
        .iter()
        .map(|&grower| {
            let kind = grower.kind();
            let t = match tries.iter().position(|(k, _)| *k == kind) {
                Some(t) => t,
                None => {
                    let mut splits = Splits::new(frame, rows, &ones, mc, kind, min_objects);
                    splits.watch(stop);
                    tries.push((kind, splits));
                    tries.len() - 1
                }
            };
            grower.grow_in(&mut tries[t].1, prices, mc, selection, seed)
        })
        .collect();
    tries.retain(|(kind, _)| *kind != Criterion::Dtmc);
    trees
}

/// The split tries of CVT's trees on one set of training objects (and its folds), kept
/// from one misclassification cost to the next ([`fit_each`](super::fit_each)): every
/// statistic but DTMC's is the same at any cost, so a tree grown at a second cost reads
/// what the first computed, and is the tree it would have been.
#[derive(Default)]
pub(super) struct CvtTries<'a> {
    /// The tries on all the objects, then on each fold's training part.
    roots: Vec<Tries<'a>>,
}

/// Every grower's trees on each root's objects (root `k` from seed `sub_seed(seed, k)`,
/// through `tries[k]`), in the order of the roots, grown on up to `threads` threads: the
/// roots are dealt to the threads in turn, and each tree depends only on its root.
#[expect(
    clippy::too_many_arguments,
    reason = "grow_all's own arguments, per root"
)]
fn grow_roots<'a>(
    frame: &'a Frame,
    roots: &[&[usize]],
    prices: &TestPrices,
    mc: &'a MisclassCosts,
    (selection, seed): (SelectionPrices, u64),
    tries: &mut [Tries<'a>],
    (growers, threads): (&[Grower], usize),
    stop: &'a Stop,
) -> Vec<Vec<CostTree>> {
    let grow = |k: usize, tries: &mut Tries<'a>| {
        grow_all(
            frame,
            roots[k],
            prices,
            mc,
            (selection, sub_seed(seed, k as u64)),
            growers,
            tries,
            stop,
        )
    };
    if threads <= 1 {
        return tries
            .iter_mut()
            .enumerate()
            .map(|(k, t)| grow(k, t))
            .collect();
    }
    let mut dealt: Vec<Vec<(usize, &mut Tries<'a>)>> = (0..threads).map(|_| Vec::new()).collect();
    for (k, t) in tries.iter_mut().enumerate() {
        dealt[k % threads].push((k, t));
    }
    let mut trees: Vec<(usize, Vec<CostTree>)> = std::thread::scope(|scope| {
        let handles: Vec<_> = dealt
            .into_iter()
            .map(|share| {
                let grow = &grow;
                scope.spawn(move || {
                    share
                        .into_iter()
                        .map(|(k, t)| (k, grow(k, t)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    trees.sort_by_key(|(k, _)| *k);
    trees.into_iter().map(|(_, t)| t).collect()
}

/// The most points of a cost-complexity path measured (evenly spaced along it when the
/// path is longer).
const MAX_POINTS: usize = 48;

/// What CVT chose.
///
/// ```
/// let c = cslearn::testcost::CvtChoice { grower: 2, alpha: Some(12.5), held_out_cost: 30.0 };
/// assert_eq!(c.grower_name(), "eg2-w1");
/// assert_eq!(c.cut_text(), "cut back at 12.5000 per leaf");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CvtChoice {
    /// The index of the grower in [`GROWERS`].
    pub grower: usize,
    /// The price per leaf the tree was cut back at, or `None` where it was pruned by ACT's
    /// pessimistic estimate of its cost instead.
    pub alpha: Option<f64>,
    /// The mean total cost per object measured on the held-out folds.
    pub held_out_cost: f64,
}

impl CvtChoice {
    /// The name of the grower chosen.
    pub fn grower_name(&self) -> &'static str {
        GROWERS.get(self.grower).map_or("?", |g| g.0)
    }

    /// How the tree was cut, in words.
    ///
    /// ```
    /// let c = cslearn::testcost::CvtChoice { grower: 6, alpha: None, held_out_cost: 30.0 };
    /// assert_eq!(c.cut_text(), "pruned by its pessimistic cost");
    /// ```
    pub fn cut_text(&self) -> String {
        match self.alpha {
            Some(alpha) => format!("cut back at {alpha:.4} per leaf"),
            None => "pruned by its pessimistic cost".into(),
        }
    }
}

/// The confidence of the pessimistic pruning CVT measures beside the cost-complexity
/// path (ACT's and C4.5's 0.25).
const CONFIDENCE: f64 = 0.25;

/// CVT's tree on the objects `rows` of `frame`, with its choice; the folds are drawn from
/// `seed`. It grows through `tries`, those of CVT's trees on the same objects, folds and
/// prices at other costs (empty for a first tree), which watch `stop`.
#[expect(
    clippy::too_many_arguments,
    reason = "the data, prices, costs, settings and seed, the tries and the stop"
)]
pub(super) fn cvt_tree_in<'a>(
    frame: &'a Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &'a MisclassCosts,
    params: &CvtParams,
    selection: SelectionPrices,
    seed: u64,
    tries: &mut CvtTries<'a>,
    stop: &'a Stop,
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
    // Every grower's trees on all the objects (root 0) and on each fold's training part
    // (root k), each root from its own seed, on up to `threads` threads.
    tries.roots.resize_with(parts.len() + 1, Vec::new);
    let roots: Vec<&[usize]> = std::iter::once(rows)
        .chain(parts.iter().map(|(train, _)| &train[..]))
        .collect();
    let threads = params.threads_for(roots.len());
    let mut grown = grow_roots(
        frame,
        &roots,
        prices,
        mc,
        (selection, seed),
        &mut tries.roots[..roots.len()],
        (&params.growers(), threads),
        stop,
    )
    .into_iter();
    // Per grower: its tree on every object, its path's points, and the held-out total
    // cost at each point and then (last) under the pessimistic pruning.
    let mut measured: Vec<(CostTree, Vec<f64>, Vec<f64>)> = grown
        .next()
        .unwrap_or_default()
        .into_iter()
        .map(|tree| {
            let alphas = Costs::of(&tree, prices).path_points(&tree);
            let held = vec![0.0; alphas.len() + 1];
            (tree, alphas, held)
        })
        .collect();
    for ((_, out), fold_trees) in parts.iter().zip(grown) {
        for ((_, alphas, held), fold_tree) in measured.iter_mut().zip(&fold_trees) {
            let costs = Costs::of(fold_tree, prices);
            let reached = fold_tree.reach(frame, out);
            let on_path = costs.cut_points(fold_tree, alphas);
            let pruned: Vec<usize> = fold_tree
                .cost_pruning_cut(CONFIDENCE, prices)
                .into_iter()
                .map(|cut| usize::from(!cut))
                .collect();
            let path_costs = costs.held_out(fold_tree, &reached, &on_path, alphas.len(), mc);
            let pruned_cost = costs.held_out(fold_tree, &reached, &pruned, 1, mc)[0];
            for (h, c) in held.iter_mut().zip(path_costs.iter().chain([&pruned_cost])) {
                *h += c;
            }
        }
    }
    // The cheapest grower and cut; equal costs (up to rounding) go to the earlier grower
    // and the smaller alpha.
    let n = rows.len().max(1) as f64;
    let mut best = (0, 0, f64::INFINITY);
    for (g, (_, _, held)) in measured.iter().enumerate() {
        for (p, &total) in held.iter().enumerate() {
            let mean = total / n;
            if mean < best.2 - 1e-9 * best.2.min(1e12) {
                best = (g, p, mean);
            }
        }
    }
    let (g, p, held_out_cost) = best;
    let (mut tree, alphas, _) = measured.swap_remove(g);
    let alpha = alphas.get(p).copied();
    let cut = match alpha {
        Some(alpha) => Costs::of(&tree, prices).cut_at(&tree, alpha).1,
        None => tree.cost_pruning_cut(CONFIDENCE, prices),
    };
    tree.cut(&cut);
    let choice = CvtChoice {
        grower: g,
        alpha,
        held_out_cost,
    };
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

    /// For each node, the first of the increasing `alphas` at whose best cut it is a
    /// leaf (`alphas.len()` if at none): one bottom-up pass for every point at once, the
    /// same sums as [`cut_at`](Costs::cut_at) at each. The cut is monotone: a node cut at
    /// one `alpha` is cut at every larger one, since its subtree's cost grows at least as
    /// fast with `alpha` as its leaf's.
    fn cut_points(&self, tree: &CostTree, alphas: &[f64]) -> Vec<usize> {
        let (n, points) = (tree.len(), alphas.len());
        let mut best = vec![0.0; n * points];
        let mut first = vec![points; n];
        let mut below = vec![0.0; points];
        for i in (0..n).rev() {
            let node = tree.node(i);
            let counted = node.weights.iter().sum::<f64>() > 0.0;
            let leaf = |alpha: f64| {
                if counted {
                    self.as_leaf[i] + alpha
                } else {
                    0.0
                }
            };
            match &node.split {
                None => {
                    for (b, &alpha) in best[i * points..(i + 1) * points].iter_mut().zip(alphas) {
                        *b = leaf(alpha);
                    }
                    first[i] = 0;
                }
                Some(split) => {
                    below.iter_mut().for_each(|b| *b = 0.0);
                    for &c in split.children() {
                        let c = c as usize;
                        for (b, x) in below.iter_mut().zip(&best[c * points..(c + 1) * points]) {
                            *b += x;
                        }
                    }
                    let row = &mut best[i * points..(i + 1) * points];
                    for (p, (&alpha, b)) in alphas.iter().zip(&below).enumerate() {
                        let (leaf, below) = (leaf(alpha), self.test[i] + b);
                        if leaf <= below {
                            row[p] = leaf;
                            first[i] = first[i].min(p);
                        } else {
                            row[p] = below;
                        }
                    }
                }
            }
        }
        first
    }

    /// The total cost of the held-out objects that `reached` each node of the tree (one
    /// weight per class per node) when the tree is cut at each of `points` cuts, a node
    /// being a leaf from cut `cut_from[node]` on ([`cut_points`](Costs::cut_points)).
    /// One walk for every cut: a node is in the tree up to the first cut where an
    /// ancestor is a leaf.
    fn held_out(
        &self,
        tree: &CostTree,
        reached: &[Vec<f64>],
        cut_from: &[usize],
        points: usize,
        mc: &MisclassCosts,
    ) -> Vec<f64> {
        // The change of the total at each cut, summed up at the end.
        let mut change = vec![0.0; points + 1];
        // (node, the tests paid on its path, the cut from which it is cut off)
        let mut stack = vec![(0usize, 0.0, points)];
        while let Some((i, paid, until)) = stack.pop() {
            let node = tree.node(i);
            let from = match &node.split {
                Some(split) => {
                    let from = cut_from[i].min(until);
                    if from > 0 {
                        let paid = paid + self.price[i];
                        stack.extend(split.children().iter().map(|&c| (c as usize, paid, from)));
                    }
                    from
                }
                None => 0,
            };
            if from < until {
                let total: f64 = reached[i]
                    .iter()
                    .enumerate()
                    .map(|(c, w)| w * (paid + mc.cost(node.label as usize, c)))
                    .sum();
                change[from] += total;
                change[until] -= total;
            }
        }
        let mut sum = 0.0;
        change[..points]
            .iter()
            .map(|d| {
                sum += d;
                sum
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testcost::Catalogue;
    use crate::testcost::act::Act;

    /// Heart with Turney's prices (it has missing values), every other object.
    fn heart() -> (Frame, TestPrices, MisclassCosts, Vec<usize>, Vec<usize>) {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
        let heart = Catalogue::read(&root.join("datasets.toml"))
            .unwrap()
            .load("heart")
            .unwrap();
        let (train, out): (Vec<usize>, Vec<usize>) =
            (0..heart.frame.len()).partition(|r| r % 3 != 0);
        let mc = MisclassCosts::uniform(2, 500.0).unwrap();
        (heart.frame, heart.turney.unwrap(), mc, train, out)
    }

    /// The held-out objects' total cost with the tree cut at `alpha`, walked node by
    /// node: each inner node's price for the weight reaching it, each leaf's errors.
    fn walked(
        costs: &Costs,
        tree: &CostTree,
        reached: &[Vec<f64>],
        cut: &[bool],
        mc: &MisclassCosts,
    ) -> f64 {
        let mut total = 0.0;
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let node = tree.node(i);
            match &node.split {
                Some(split) if !cut[i] => {
                    total += costs.price[i] * reached[i].iter().sum::<f64>();
                    stack.extend(split.children().iter().map(|&c| c as usize));
                }
                _ => {
                    for (c, w) in reached[i].iter().enumerate() {
                        total += w * mc.cost(node.label as usize, c);
                    }
                }
            }
        }
        total
    }

    /// One bottom-up pass and one walk measure every point of the path as cutting the
    /// tree at each point and walking it does, and the cuts are nested.
    #[test]
    fn one_walk_measures_every_point_as_a_cut_and_a_walk_at_each() {
        let (frame, prices, mc, train, out) = heart();
        for criterion in [Criterion::Eg2 { w: 0.0 }, Criterion::Dtmc] {
            let tree = CostTree::grow(&frame, &train, &prices, &mc, &GrowParams::new(criterion));
            let costs = Costs::of(&tree, &prices);
            let alphas = costs.path_points(&tree);
            assert!(alphas.len() > 3, "{alphas:?}");
            let reached = tree.reach(&frame, &out);
            let from = costs.cut_points(&tree, &alphas);
            let measured = costs.held_out(&tree, &reached, &from, alphas.len(), &mc);
            for (p, &alpha) in alphas.iter().enumerate() {
                let cut = costs.cut_at(&tree, alpha).1;
                let inner = |i: usize| tree.node(i).split.is_some();
                for i in (0..tree.len()).filter(|&i| inner(i)) {
                    assert_eq!(cut[i], from[i] <= p, "node {i} at alpha {alpha}");
                }
                let expected = walked(&costs, &tree, &reached, &cut, &mc);
                assert!(
                    (measured[p] - expected).abs() <= 1e-9 * expected.max(1.0),
                    "alpha {alpha}: {} against {expected}",
                    measured[p]
                );
            }
            // The pessimistic pruning, measured as one cut.
            let pruned = tree.cost_pruning_cut(CONFIDENCE, &prices);
            let from: Vec<usize> = pruned.iter().map(|&c| usize::from(!c)).collect();
            let once = costs.held_out(&tree, &reached, &from, 1, &mc)[0];
            let expected = walked(&costs, &tree, &reached, &pruned, &mc);
            assert!((once - expected).abs() <= 1e-9 * expected.max(1.0));
        }
    }

    /// Growers sharing a split trie grow the trees each grows alone, the lookahead
    /// included.
    /// Without the lookahead grower CVT chooses among the greedy ones alone, whose trees
    /// and held-out costs do not depend on the lookahead's samples: its held-out cost is
    /// at least the full set's, and the same tree wherever the full set chose a greedy
    /// grower. With one sample the lookahead is another grower, its tree another tree.
    #[test]
    fn fewer_lookahead_samples_change_the_lookahead_alone() {
        let (frame, prices, _, train, _) = heart();
        let selection = SelectionPrices::Listed;
        let (mut chosen_greedy, mut chosen_lookahead) = (0, 0);
        for mc in [100.0, 500.0, 1000.0, 5000.0] {
            let mc = MisclassCosts::uniform(2, mc).unwrap();
            let fit = |samples: usize| {
                let params = CvtParams::default().with_samples(samples).unwrap();
                let (tree, choice) = cvt_tree_in(
                    &frame,
                    &train,
                    &prices,
                    &mc,
                    &params,
                    selection,
                    3,
                    &mut CvtTries::default(),
                    &Stop::default(),
                );
                (tree, choice)
            };
            let (full, full_choice) = fit(5);
            let (greedy, greedy_choice) = fit(0);
            assert!(greedy_choice.grower < 6, "{greedy_choice:?}");
            assert!(
                greedy_choice.held_out_cost >= full_choice.held_out_cost - 1e-9,
                "{greedy_choice:?} {full_choice:?}"
            );
            if full_choice.grower < 6 {
                chosen_greedy += 1;
                assert_eq!((&greedy, greedy_choice), (&full, full_choice));
            } else {
                chosen_lookahead += 1;
                assert!(greedy_choice.held_out_cost > full_choice.held_out_cost);
            }
            let (_, one) = fit(1);
            assert!(one.held_out_cost <= greedy_choice.held_out_cost + 1e-9);
        }
        assert!(chosen_greedy + chosen_lookahead == 4);
        // The samples reach the lookahead grower, and only it.
        let mc = MisclassCosts::uniform(2, 500.0).unwrap();
        let grow = |samples: usize| {
            let growers = CvtParams::default()
                .with_samples(samples)
                .unwrap()
                .growers();
            grow_all(
                &frame,
                &train,
                &prices,
                &mc,
                (selection, 3),
                &growers,
                &mut Vec::new(),
                &Stop::default(),
            )
        };
        let (five, one, none) = (grow(5), grow(1), grow(0));
        assert_eq!((five.len(), one.len(), none.len()), (7, 7, 6));
        assert_eq!(five[..6], none[..]);
        assert_eq!(one[..6], none[..]);
        assert_ne!(five[6], one[6]);
    }

    #[test]
    fn growers_sharing_a_trie_grow_what_each_grows_alone() {
        let (frame, prices, mc, train, _) = heart();
        let selection = SelectionPrices::Listed;
        let trees = grow_all(
            &frame,
            &train,
            &prices,
            &mc,
            (selection, 7),
            &CvtParams::default().growers(),
            &mut Vec::new(),
            &Stop::default(),
        );
        for (tree, &(name, grower)) in trees.iter().zip(&GROWERS) {
            let alone = match grower {
                Grower::Greedy(criterion) => {
                    let grow = GrowParams::new(criterion).selecting_at(selection);
                    CostTree::grow(&frame, &train, &prices, &mc, &grow)
                }
                Grower::Lookahead { samples } => {
                    let params = ActParams {
                        samples,
                        ..ActParams::default()
                    };
                    let act = Act {
                        prices: &prices,
                        mc: &mc,
                        params: &params,
                        w: 1.0,
                        selection,
                        seed: 7,
                    };
                    act.grown(&frame, &train)
                }
            };
            assert_eq!(*tree, alone, "{name}");
        }
    }
}
