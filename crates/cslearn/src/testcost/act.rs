//! ACT (Esmeir and Markovitch 2008): a split chosen by the cost of the trees sampled
//! under it.
//!
//! At each node ACT prices every candidate test by a lookahead: for each branch of the
//! test it grows `r` trees with a stochastic EG2 (each test drawn with probability in
//! proportion to its EG2 score) and keeps the cheapest; the candidate's cost is its own
//! price for every object reaching the node plus the cheapest sampled subtree of each
//! branch. The node splits on the cheapest candidate, or stays a leaf when answering
//! there is cheaper still. A tree, sampled or final, is valued at its expected total cost
//! on the training objects: the tests each object pays along its path, plus at each
//! leaf the misclassification cost of its objects with C4.5's pessimistic added errors
//! priced at the leaf's dearest error ([`Pruning::Costs`](super::Pruning)); a sampled
//! subtree is cut back wherever a leaf is cheaper, and the final tree is pruned the same
//! way. More samples give a better estimate for more time: ACT is anytime in `r`.

use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

use super::criterion::Criterion;
use super::data::Frame;
use super::prices::{MisclassCosts, TestPrices};
use super::splits::{Splits, Stat};
use super::tree::{
    CostTree, GrowParams, Scorer, SelectionPrices, deviation, estimated_cost, grow_nodes_by,
    is_pure, price_after,
};
use crate::Error;

/// ACT's settings.
///
/// ```
/// let p = cslearn::testcost::ActParams::default();
/// assert_eq!((p.samples, p.confidence), (5, 0.25));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ActParams {
    /// Trees sampled under each branch of each candidate test (`r`), 5 by default; more
    /// give a better estimate for more time, and 0 values each branch as a leaf (a
    /// one-step lookahead).
    pub samples: usize,
    /// The confidence of the pessimistic error estimate (C4.5's 0.25).
    pub confidence: f64,
}

impl ActParams {
    /// The most samples the front ends accept: each is a tree grown at every candidate
    /// test of every node.
    pub const MAX_SAMPLES: usize = 1000;

    /// ACT's defaults with `samples` trees per branch, refused above
    /// [`MAX_SAMPLES`](ActParams::MAX_SAMPLES).
    ///
    /// ```
    /// use cslearn::testcost::ActParams;
    /// assert_eq!(ActParams::with_samples(2).unwrap().samples, 2);
    /// let e = ActParams::with_samples(1001).unwrap_err().to_string();
    /// assert!(e.contains("1001") && e.contains("at most 1000"), "{e}");
    /// ```
    pub fn with_samples(samples: usize) -> Result<ActParams, Error> {
        if samples > ActParams::MAX_SAMPLES {
            return Err(Error::Invalid {
                what: format!("{samples} ACT samples"),
                reason: format!(
                    "at most {} trees per branch (each one is grown at every candidate test of every node)",
                    ActParams::MAX_SAMPLES
                ),
            });
        }
        Ok(ActParams {
            samples,
            ..ActParams::default()
        })
    }
}

impl Default for ActParams {
    fn default() -> ActParams {
        ActParams {
            samples: 5,
            confidence: 0.25,
        }
    }
}

/// What ACT grows a tree with, besides the objects: the prices, the misclassification
/// costs, its settings, EG2's `w` and the prices selection sees for its sampling, and the
/// seed of its samples.
#[derive(Clone, Copy)]
pub(super) struct Act<'a> {
    pub prices: &'a TestPrices,
    pub mc: &'a MisclassCosts,
    pub params: &'a ActParams,
    pub w: f64,
    pub selection: SelectionPrices,
    pub seed: u64,
}

impl<'b> Act<'b> {
    /// The split trie ACT grows through on the objects `rows` of `frame`: EG2's kind of
    /// statistics, which do not depend on the misclassification costs, and C4.5's least
    /// branch size.
    pub fn trie<'a>(&self, frame: &'a Frame, rows: &[usize]) -> Splits<'a>
    where
        'b: 'a,
    {
        let grow = GrowParams::new(Criterion::Eg2 { w: self.w });
        let ones = vec![1.0; rows.len()];
        Splits::new(
            frame,
            rows,
            &ones,
            self.mc,
            grow.criterion,
            grow.min_objects,
        )
    }

    /// ACT's tree through the split trie `splits`: [`grown_in`](Act::grown_in), then
    /// pruned by cost.
    pub fn tree_in(&self, splits: &mut Splits<'_>) -> CostTree {
        let mut tree = self.grown_in(splits);
        tree.prune_by_cost(self.params.confidence, self.prices);
        tree
    }

    /// ACT's tree before its pruning: each split chosen by the sampled lookahead, a leaf
    /// where answering costs less than every candidate's price plus sampled subtrees.
    #[cfg(test)]
    pub fn grown(&self, frame: &Frame, rows: &[usize]) -> CostTree {
        let mut splits = self.trie(frame, rows);
        self.grown_in(&mut splits)
    }

    /// [`grown`](Act::grown) through the split trie `splits` (made with EG2's kind of
    /// statistics and C4.5's least branch size), which other EG2 trees on the same
    /// objects may share.
    pub fn grown_in(&self, splits: &mut Splits<'_>) -> CostTree {
        let grow = GrowParams::new(Criterion::Eg2 { w: self.w }).selecting_at(self.selection);
        let sampler = Sampler {
            scorer: Scorer::new(self.prices, grow.criterion),
            prices: self.prices,
            mc: self.mc,
            selection: self.selection,
            confidence: self.params.confidence,
            coeff: deviation(self.params.confidence).powi(2),
            max_depth: grow.max_depth,
            samples: self.params.samples,
        };
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(self.seed);
        let nodes = grow_nodes_by(splits, self.mc, grow.max_depth, |splits, c| {
            sampler.choose(splits, c, &mut rng)
        });
        CostTree::from_nodes(nodes, self.mc)
    }
}

/// What ACT values trees with.
struct Sampler<'a> {
    scorer: Scorer,
    prices: &'a TestPrices,
    mc: &'a MisclassCosts,
    selection: SelectionPrices,
    confidence: f64,
    coeff: f64,
    max_depth: usize,
    samples: usize,
}

impl Sampler<'_> {
    /// A leaf's pessimistic misclassification cost for cell `c`.
    fn leaf(&self, splits: &Splits<'_>, c: u32) -> f64 {
        estimated_cost(
            self.mc,
            &splits.cell(c).class_weights,
            self.confidence,
            self.coeff,
        )
    }

    /// The tests that can split cell `c` (a positive gain and EG2 score), with their
    /// EG2 scores at the selection prices, into `out` (emptied first).
    fn candidates(&self, splits: &mut Splits<'_>, c: u32, out: &mut Vec<(Stat, f64)>) {
        out.clear();
        let path = std::mem::take(&mut splits.cell_mut(c).path);
        out.extend(
            splits
                .stats(c)
                .iter()
                .filter(|s| s.gain > 1e-9)
                .map(|s| {
                    let price = self.selection.price(self.prices, s.feature, &path);
                    (*s, self.scorer.score(s, price))
                })
                .filter(|(_, score)| *score > 0.0),
        );
        splits.cell_mut(c).path = path;
    }

    /// The test ACT splits cell `c` on: the candidate whose price plus cheapest sampled
    /// subtree per branch is least, if that is below the leaf's cost.
    fn choose(
        &self,
        splits: &mut Splits<'_>,
        c: u32,
        rng: &mut Xoshiro256PlusPlus,
    ) -> Option<Stat> {
        let leaf = self.leaf(splits, c);
        let mut best: Option<(Stat, f64)> = None;
        let mut candidates = Vec::new();
        self.candidates(splits, c, &mut candidates);
        // One buffer for the candidates of every sampled node below (each node is done
        // with it before it goes down a branch).
        let mut below = Vec::new();
        for (stat, _) in candidates {
            let mut cost = self.test_price(splits, c, &stat);
            let list = splits.made_children(c, &stat);
            // The sampled trees are thrown away once valued: the trie keeps only the
            // candidates' children, so its memory follows the tree grown, not the samples.
            let mark = splits.mark();
            for b in 0..splits.branches(c, list) {
                let Some(child) = splits.child(c, list, b) else {
                    continue;
                };
                cost += if self.samples == 0 {
                    self.leaf(splits, child)
                } else {
                    (0..self.samples)
                        .map(|_| self.sample(splits, child, rng, &mut below))
                        .fold(f64::INFINITY, f64::min)
                };
            }
            splits.forget_since(mark);
            if best.is_none_or(|(_, b)| cost < b) {
                best = Some((stat, cost));
            }
        }
        best.filter(|(_, cost)| *cost < leaf).map(|(stat, _)| stat)
    }

    /// What `stat`'s test costs every object of cell `c`, priced after the cell's path.
    fn test_price(&self, splits: &Splits<'_>, c: u32, stat: &Stat) -> f64 {
        price_after(self.prices, stat.feature, &splits.cell(c).path) * splits.total(c)
    }

    /// The expected total cost of a tree grown from cell `c` by stochastic EG2, cut back
    /// wherever a leaf is cheaper.
    fn sample(
        &self,
        splits: &mut Splits<'_>,
        c: u32,
        rng: &mut Xoshiro256PlusPlus,
        candidates: &mut Vec<(Stat, f64)>,
    ) -> f64 {
        let leaf = self.leaf(splits, c);
        let cell = splits.cell(c);
        if is_pure(&cell.class_weights) || cell.path.len() >= self.max_depth {
            return leaf;
        }
        self.candidates(splits, c, candidates);
        let sum: f64 = candidates.iter().map(|(_, score)| score).sum();
        if candidates.is_empty() || !(sum > 0.0 && sum.is_finite()) {
            return leaf;
        }
        let mut draw = rng.random_range(0.0..sum);
        let drawn = candidates
            .iter()
            .position(|(_, score)| {
                draw -= score;
                draw < 0.0
            })
            .unwrap_or(candidates.len() - 1);
        let stat = candidates[drawn].0;
        let mut cost = self.test_price(splits, c, &stat);
        let list = splits.made_children(c, &stat);
        for b in 0..splits.branches(c, list) {
            let Some(child) = splits.child(c, list, b) else {
                continue;
            };
            if cost >= leaf {
                // The subtree is already dearer than the leaf it would be cut back to.
                return leaf;
            }
            cost += self.sample(splits, child, rng, candidates);
        }
        cost.min(leaf)
    }
}
