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
//!
//! Each sample's draws are seeded by what its nodes hold (their objects, the tests on
//! their path, their depth) and its number, not taken in turn from one generator: a
//! sampled subtree met again is the same one and is read back, and a candidate or a
//! sample can stop being valued once it is sure to lose, without moving any later draw.
//! The choice is the one valuing everything whole gives, to the bit.
//!
//! So the candidates of a node can be valued on several threads ([`ActParams::threads`]),
//! each thread in a split trie of its own over the same objects: which thread values
//! which candidate, and with what bound, changes how much is grown, never the choice.

use std::collections::BTreeMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

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
/// assert_eq!((p.samples, p.confidence, p.threads), (5, 0.25, 1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ActParams {
    /// Trees sampled under each branch of each candidate test (`r`), 5 by default; more
    /// give a better estimate for more time, and 0 values each branch as a leaf (a
    /// one-step lookahead).
    pub samples: usize,
    /// The confidence of the pessimistic error estimate (C4.5's 0.25).
    pub confidence: f64,
    /// The most threads one fit uses to value a node's candidates (1 by default; 0 for
    /// every core; never more than the features, a node's most candidates). The tree is
    /// the same on any number of threads.
    #[serde(default = "one_thread", skip_serializing_if = "is_one_thread")]
    pub threads: usize,
}

fn one_thread() -> usize {
    1
}

/// Whether `threads` is the default, left out of a model file so that files written
/// before the setting existed are written the same.
fn is_one_thread(threads: &usize) -> bool {
    *threads == 1
}

/// The threads a `threads` setting asks for (ACT's, CVT's): itself, or every core for 0.
pub(super) fn threads_wanted(threads: usize) -> usize {
    match threads {
        0 => std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
        n => n,
    }
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
        check_samples(samples, || format!("{samples} ACT samples"))?;
        Ok(ActParams {
            samples,
            ..ActParams::default()
        })
    }

    /// These settings using up to `threads` threads (0: every core).
    ///
    /// ```
    /// use cslearn::testcost::ActParams;
    /// assert_eq!(ActParams::default().with_threads(2).threads, 2);
    /// ```
    pub fn with_threads(self, threads: usize) -> ActParams {
        ActParams { threads, ..self }
    }
}

/// Refuses more than [`ActParams::MAX_SAMPLES`] trees sampled under each branch (ACT's,
/// or CVT's lookahead's), the samples named by `what`.
pub(super) fn check_samples(samples: usize, what: impl FnOnce() -> String) -> Result<(), Error> {
    if samples > ActParams::MAX_SAMPLES {
        return Err(Error::Invalid {
            what: what(),
            reason: format!(
                "at most {} trees per branch (each one is grown at every candidate test of every node)",
                ActParams::MAX_SAMPLES
            ),
        });
    }
    Ok(())
}

impl Default for ActParams {
    fn default() -> ActParams {
        ActParams {
            samples: 5,
            confidence: 0.25,
            threads: 1,
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
        self.grown_by(splits, false)
    }

    /// [`grown`](Act::grown) with every candidate valued whole, in the order of its
    /// feature, and every sampled subtree grown whole and never read back: what the
    /// bounds and the remembered values of [`grown_in`](Act::grown_in) must not change.
    #[cfg(test)]
    fn grown_thorough(&self, frame: &Frame, rows: &[usize]) -> CostTree {
        let mut splits = self.trie(frame, rows);
        self.grown_by(&mut splits, true)
    }

    fn grown_by(&self, splits: &mut Splits<'_>, thorough: bool) -> CostTree {
        let grow = GrowParams::new(Criterion::Eg2 { w: self.w }).selecting_at(self.selection);
        let sampler = || Sampler {
            scorer: Scorer::new(self.prices, grow.criterion),
            prices: self.prices,
            mc: self.mc,
            selection: self.selection,
            confidence: self.params.confidence,
            coeff: deviation(self.params.confidence).powi(2),
            max_depth: grow.max_depth,
            samples: self.params.samples,
            seed: self.seed,
            values: Values::default(),
            candidates: Vec::new(),
            thorough,
        };
        let mut main = sampler();
        // No more threads than a node can have candidates (each holds a trie of its own).
        let threads = threads_wanted(self.params.threads).min(splits.feature_count());
        // Each thread values candidates in a trie and with remembered values of its own.
        let mut helpers: Vec<(Splits<'_>, Sampler<'_>)> = if threads > 1 && !thorough {
            (0..threads)
                .map(|_| (splits.sibling(), sampler()))
                .collect()
        } else {
            Vec::new()
        };
        let nodes = grow_nodes_by(splits, self.mc, grow.max_depth, |splits, c| {
            if helpers.is_empty() {
                main.choose(splits, c)
            } else {
                main.choose_on_threads(splits, c, &mut helpers)
            }
        });
        CostTree::from_nodes(nodes, self.mc)
    }
}

/// A seed of its own for the `k`-th of something grown from `seed` (SplitMix64's mix of
/// the two).
pub(super) fn sub_seed(seed: u64, k: u64) -> u64 {
    let mut z = seed
        ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(0x6A09_E667_F3BC_C909);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// What a sampled subtree is worth, as far as it was grown: its exact value, or (cut
/// short once it reached a cap) a value it is at least.
#[derive(Clone, Copy)]
enum Value {
    Exact(f64),
    AtLeast(f64),
}

impl Value {
    /// The value, exact or not.
    fn get(self) -> f64 {
        match self {
            Value::Exact(v) | Value::AtLeast(v) => v,
        }
    }
}

/// The sampled subtrees valued so far. Sample `s` from a cell is a function of what the
/// cell holds: its objects and weights (the split trie's memo entry), the set of tests
/// on its path (which sets every price below it), its depth, and `s`, which seed its
/// draws. So a subtree met again, under another candidate or at a later node, is read
/// back instead of grown again, exactly.
#[derive(Default)]
struct Values {
    /// Each set of path tests met, sorted, by its number.
    paths: BTreeMap<Box<[u32]>, u32>,
    /// By (memo entry, path set, depth, sample).
    values: BTreeMap<(u32, u32, u32, u32), Value>,
    /// The path being looked up.
    path: Vec<u32>,
}

impl Values {
    /// The most values remembered per tree (about 40 bytes each); past it, subtrees are
    /// grown again when met again, which costs time, never a different value.
    const MAX: usize = 1 << 20;
}

/// Where a sampled subtree grows from: its key among the [`Values`] (none when the
/// trie's memo was full) and the seed of its draws.
#[derive(Clone, Copy)]
struct Origin {
    key: Option<(u32, u32, u32)>,
    seed: u64,
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
    seed: u64,
    values: Values,
    /// One buffer for the candidates of every sampled node (each node is done with it
    /// before it goes down a branch).
    candidates: Vec<(Stat, f64)>,
    /// Value everything whole (the reference the bounds are tested against).
    thorough: bool,
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
    /// EG2 scores at the selection prices, into the buffer.
    fn candidates(&mut self, splits: &mut Splits<'_>, c: u32) {
        self.candidates.clear();
        let path = std::mem::take(&mut splits.cell_mut(c).path);
        let (selection, prices, scorer) = (self.selection, self.prices, &self.scorer);
        self.candidates.extend(
            splits
                .stats(c)
                .iter()
                .filter(|s| s.gain > 1e-9)
                .map(|s| {
                    let price = selection.price(prices, s.feature, &path);
                    (*s, scorer.score(s, price))
                })
                .filter(|(_, score)| *score > 0.0),
        );
        splits.cell_mut(c).path = path;
    }

    /// The test ACT splits cell `c` on: the candidate whose price plus cheapest sampled
    /// subtree per branch is least (ties: the lower feature index), if that is below the
    /// leaf's cost.
    ///
    /// The same choice, bit for bit, as valuing every candidate whole, for less: the
    /// candidates are valued first with one sample per branch (an estimate, to order
    /// them), then cheapest first, each only until it is sure not to be chosen, and each
    /// subtree grown only as far as it could still matter.
    fn choose(&mut self, splits: &mut Splits<'_>, c: u32) -> Option<Stat> {
        let leaf = self.leaf(splits, c);
        self.candidates(splits, c);
        let candidates = std::mem::take(&mut self.candidates);
        if self.thorough {
            let mut best: Option<(Stat, f64)> = None;
            for &(stat, _) in &candidates {
                let cost = self.value(splits, c, &stat, f64::INFINITY, false, self.samples);
                if best.is_none_or(|(_, b)| cost < b) {
                    best = Some((stat, cost));
                }
            }
            self.candidates = candidates;
            return best.filter(|(_, cost)| *cost < leaf).map(|(stat, _)| stat);
        }
        let mut order: Vec<(f64, usize)> = Vec::with_capacity(candidates.len());
        let mut guess = leaf;
        for (i, (stat, _)) in candidates.iter().enumerate() {
            let estimate = self.value(splits, c, stat, guess, false, self.samples.min(1));
            guess = guess.min(estimate);
            order.push((estimate, i));
        }
        order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // The leaf wins a tie with any candidate; a candidate one of a higher index.
        let mut best = leaf;
        let mut chosen: Option<usize> = None;
        for &(_, i) in &order {
            let lower = chosen.is_some_and(|j| i < j);
            let cost = self.value(splits, c, &candidates[i].0, best, lower, self.samples);
            if cost < best || (lower && cost == best) {
                best = cost;
                chosen = Some(i);
            }
        }
        let stat = chosen.map(|i| candidates[i].0);
        self.candidates = candidates;
        stat
    }

    /// [`choose`](Sampler::choose)'s choice, the candidates valued by `helpers` (a trie
    /// over the same objects and a sampler each), one thread per helper. Each thread
    /// takes the next candidate not yet taken and values it against the best found so
    /// far by any thread: the estimates (and so the order) may differ from one run to
    /// the next, the choice cannot, as every candidate that could be chosen is valued
    /// exactly and the least (ties: the lower index; the leaf wins a tie) is chosen.
    fn choose_on_threads(
        &mut self,
        splits: &mut Splits<'_>,
        c: u32,
        helpers: &mut [(Splits<'_>, Sampler<'_>)],
    ) -> Option<Stat> {
        let leaf = self.leaf(splits, c);
        self.candidates(splits, c);
        let candidates = std::mem::take(&mut self.candidates);
        let samples = self.samples;
        let shared: &Splits<'_> = splits;
        // The candidates' estimates, one sample a branch, the least so far their bound.
        let taken = AtomicUsize::new(0);
        let guess = Mutex::new(leaf);
        let estimates = Mutex::new(Vec::with_capacity(candidates.len()));
        on_threads(helpers, shared, c, |trie, sampler, cell| {
            loop {
                let i = taken.fetch_add(1, Ordering::Relaxed);
                let Some((stat, _)) = candidates.get(i) else {
                    break;
                };
                let bound = *lock(&guess);
                let estimate = sampler.value(trie, cell, stat, bound, false, samples.min(1));
                let mut least = lock(&guess);
                *least = least.min(estimate);
                drop(least);
                lock(&estimates).push((estimate, i));
            }
        });
        let mut order = estimates.into_inner().unwrap_or_else(|e| e.into_inner());
        order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // Cheapest estimate first, each against the best so far.
        let taken = AtomicUsize::new(0);
        let best = Mutex::new((leaf, None::<usize>));
        on_threads(helpers, shared, c, |trie, sampler, cell| {
            loop {
                let k = taken.fetch_add(1, Ordering::Relaxed);
                let Some(&(_, i)) = order.get(k) else {
                    break;
                };
                let (bound, chosen) = *lock(&best);
                let lower = chosen.is_some_and(|j| i < j);
                let cost = sampler.value(trie, cell, &candidates[i].0, bound, lower, samples);
                // A cost at or above the bound is one it is at least, and never chosen:
                // the best only falls, and changes at an equal cost only to a lower
                // index.
                let mut best = lock(&best);
                let lower = best.1.is_some_and(|j| i < j);
                if cost < best.0 || (lower && cost == best.0) {
                    *best = (cost, Some(i));
                }
            }
        });
        let (_, chosen) = best.into_inner().unwrap_or_else(|e| e.into_inner());
        let stat = chosen.map(|i| candidates[i].0);
        self.candidates = candidates;
        stat
    }

    /// `stat`'s price at cell `c` plus, for each branch, the cheapest of `samples`
    /// sampled subtrees: exact where it is below `best` (or equal to it, where `ties`),
    /// otherwise a value at least `best`.
    fn value(
        &mut self,
        splits: &mut Splits<'_>,
        c: u32,
        stat: &Stat,
        best: f64,
        ties: bool,
        samples: usize,
    ) -> f64 {
        let out = |cost: f64| cost > best || (cost >= best && !ties);
        let mut cost = self.test_price(splits, c, stat);
        let list = splits.made_children(c, stat);
        // The sampled trees are thrown away once valued: the trie keeps only the
        // candidates' children, so its memory follows the tree grown, not the samples.
        let mark = splits.mark();
        for b in 0..splits.branches(c, list) {
            if out(cost) {
                break;
            }
            let Some(child) = splits.child(c, list, b) else {
                continue;
            };
            cost += if samples == 0 {
                self.leaf(splits, child)
            } else {
                match self.cheapest(splits, child, cap_after(best, cost), samples) {
                    Value::Exact(v) => v,
                    // The candidate is sure to be out.
                    Value::AtLeast(v) if out(cost + v) => v,
                    Value::AtLeast(_) => self.cheapest(splits, child, f64::INFINITY, samples).get(),
                }
            };
        }
        splits.forget_since(mark);
        cost
    }

    /// The cheapest of the first `samples` subtrees sampled from cell `c` where it is below
    /// `cap`; otherwise a value it is at least.
    fn cheapest(&mut self, splits: &mut Splits<'_>, c: u32, cap: f64, samples: usize) -> Value {
        let mut least = cap;
        let mut found = false;
        for s in 0..samples as u32 {
            let v = match self.sample(splits, c, s, least) {
                Value::Exact(v) => v,
                Value::AtLeast(v) if v >= least => continue,
                Value::AtLeast(_) => self.sample(splits, c, s, f64::INFINITY).get(),
            };
            if v < least || (!found && v == least) {
                least = v;
                found = true;
            }
        }
        if found {
            Value::Exact(least)
        } else {
            Value::AtLeast(least)
        }
    }

    /// What `stat`'s test costs every object of cell `c`, priced after the cell's path.
    fn test_price(&self, splits: &Splits<'_>, c: u32, stat: &Stat) -> f64 {
        price_after(self.prices, stat.feature, &splits.cell(c).path) * splits.total(c)
    }

    /// Where sample `s` from cell `c` grows from (its statistics computed).
    fn origin(&mut self, splits: &Splits<'_>, c: u32, s: u32) -> Origin {
        let cell = splits.cell(c);
        let content = splits.content(c);
        let path = &mut self.values.path;
        path.clear();
        path.extend(cell.path.iter().map(|&f| f as u32));
        path.sort_unstable();
        path.dedup();
        let mut seed = sub_seed(self.seed, content.map_or(0, |k| k.hash));
        for &f in path.iter() {
            seed = sub_seed(seed, u64::from(f));
        }
        seed = sub_seed(seed, cell.path.len() as u64);
        seed = sub_seed(seed, u64::from(s));
        let key = content.and_then(|k| k.entry).map(|entry| {
            let next = self.values.paths.len() as u32;
            let id = match self.values.paths.get(&self.values.path[..]) {
                Some(&id) => id,
                None => {
                    self.values
                        .paths
                        .insert(self.values.path.clone().into_boxed_slice(), next);
                    next
                }
            };
            (entry, id, cell.path.len() as u32)
        });
        Origin { key, seed }
    }

    /// Sample `s` from cell `c`: the expected total cost of a tree grown from it by
    /// stochastic EG2 (its draws seeded by where it grows from and `s`), cut back
    /// wherever a leaf is cheaper; grown only until it is sure to be at least `cap`.
    fn sample(&mut self, splits: &mut Splits<'_>, c: u32, s: u32, cap: f64) -> Value {
        let leaf = self.leaf(splits, c);
        let cell = splits.cell(c);
        if is_pure(&cell.class_weights) || cell.path.len() >= self.max_depth {
            return Value::Exact(leaf);
        }
        self.candidates(splits, c);
        let sum: f64 = self.candidates.iter().map(|(_, score)| score).sum();
        if self.candidates.is_empty() || !(sum > 0.0 && sum.is_finite()) {
            return Value::Exact(leaf);
        }
        let origin = self.origin(splits, c, s);
        let key = origin
            .key
            .filter(|_| !self.thorough)
            .map(|(e, p, d)| (e, p, d, s));
        match key.and_then(|k| self.values.values.get(&k)) {
            Some(&Value::Exact(v)) => return Value::Exact(v),
            Some(&Value::AtLeast(v)) if v >= cap => return Value::AtLeast(v),
            _ => {}
        }
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(origin.seed);
        let mut draw = rng.random_range(0.0..sum);
        let drawn = self
            .candidates
            .iter()
            .position(|(_, score)| {
                draw -= score;
                draw < 0.0
            })
            .unwrap_or(self.candidates.len() - 1);
        let stat = self.candidates[drawn].0;
        let bound = cap.min(leaf);
        let mut cost = self.test_price(splits, c, &stat);
        let mut short = false;
        let list = splits.made_children(c, &stat);
        for b in 0..splits.branches(c, list) {
            if cost >= bound {
                short = true;
                break;
            }
            let Some(child) = splits.child(c, list, b) else {
                continue;
            };
            cost += match self.sample(splits, child, s, cap_after(bound, cost)) {
                Value::Exact(v) => v,
                Value::AtLeast(v) => {
                    short = true;
                    v
                }
            };
        }
        // Each part of `cost` is at most what the whole subtree would have paid there.
        let value = if cost >= leaf {
            // No cheaper than the leaf it is cut back to.
            Value::Exact(leaf)
        } else if short {
            Value::AtLeast(cost)
        } else {
            Value::Exact(cost)
        };
        if let Some(k) = key
            && self.values.values.len() < Values::MAX
        {
            self.values.values.insert(k, value);
        }
        value
    }
}

/// Runs `work` on one thread per helper (the first on this one), each with its trie, its
/// sampler and its own copy of cell `c` of `shared`, dropped once the work is done.
fn on_threads<'s, F>(
    helpers: &mut [(Splits<'s>, Sampler<'_>)],
    shared: &Splits<'_>,
    c: u32,
    work: F,
) where
    F: Fn(&mut Splits<'s>, &mut Sampler<'_>, u32) + Sync,
{
    let run = |(trie, sampler): &mut (Splits<'s>, Sampler<'_>)| {
        let mark = trie.mark();
        let cell = trie.adopt(shared, c);
        work(trie, sampler, cell);
        trie.forget_since(mark);
    };
    let Some((first, rest)) = helpers.split_first_mut() else {
        return;
    };
    std::thread::scope(|scope| {
        for helper in rest {
            scope.spawn(|| run(helper));
        }
        run(first);
    });
}

/// The value behind `mutex`, even if a thread panicked holding it (the panic is
/// raised again where the threads are joined).
fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|e| e.into_inner())
}

/// The cap for what is left once `cost` of `bound` is spent: a subtree at least this is
/// sure to take `cost` to `bound` or past it, the sums' rounding included.
fn cap_after(bound: f64, cost: f64) -> f64 {
    bound - cost + bound.abs() * 1e-12
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testcost::Catalogue;

    /// The bounds (candidates valued cheapest first, each until it is out; subtrees
    /// grown until they are sure to be too dear) and the values read back choose what
    /// valuing everything whole chooses, bit for bit: nominal and numeric features,
    /// missing values, group discounts, two to six classes, every selection prices, at
    /// cheap and dear errors, with no sample (each branch a leaf), one, three and five;
    /// and so do the candidates valued on two or three threads.
    #[test]
    fn bounds_and_remembered_values_choose_what_valuing_everything_whole_chooses() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
        let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
        let mut compared = 0;
        for name in ["heart", "hepatitis", "glass", "monks1", "tae", "iris"] {
            let loaded = catalogue.load(name).unwrap();
            let frame = &loaded.frame;
            let rows: Vec<usize> = (0..frame.len()).step_by(2).collect();
            let random = crate::testcost::random_prices(frame.feature_count(), 1.0, 100.0, 3);
            let mut all_prices = vec![random];
            all_prices.extend(loaded.turney.clone());
            for prices in &all_prices {
                for mc in [50.0, 500.0, 5000.0] {
                    let mc = MisclassCosts::uniform(frame.class_count(), mc).unwrap();
                    for (selection, samples) in [
                        (SelectionPrices::Listed, 5),
                        (SelectionPrices::Path, 1),
                        (SelectionPrices::ListedOnce, 3),
                        (SelectionPrices::Path, 0),
                    ] {
                        let params = ActParams::with_samples(samples).unwrap();
                        let act = Act {
                            prices,
                            mc: &mc,
                            params: &params,
                            w: 1.0,
                            selection,
                            seed: 11,
                        };
                        let fast = act.grown(frame, &rows);
                        let whole = act.grown_thorough(frame, &rows);
                        assert_eq!(fast, whole, "{name} {selection:?} {samples}");
                        // The candidates valued on two or three threads: the same tree.
                        let threads = 2 + compared % 2;
                        let threaded = params.with_threads(threads);
                        let on_threads = Act {
                            params: &threaded,
                            ..act
                        }
                        .grown(frame, &rows);
                        assert_eq!(
                            on_threads, whole,
                            "{name} {selection:?} {samples} {threads}"
                        );
                        compared += usize::from(fast.len() > 1);
                    }
                }
            }
        }
        // Most of the comparisons are of trees that split.
        assert!(compared > 40, "{compared}");
    }

    /// Far more threads than features asked for: as many threads as features, the same
    /// tree.
    #[test]
    fn threads_beyond_the_features_grow_the_same_tree() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
        let loaded = Catalogue::read(&root.join("datasets.toml"))
            .unwrap()
            .load("iris")
            .unwrap();
        let frame = &loaded.frame;
        let rows: Vec<usize> = (0..frame.len()).collect();
        let prices = crate::testcost::random_prices(frame.feature_count(), 1.0, 100.0, 3);
        let mc = MisclassCosts::uniform(frame.class_count(), 500.0).unwrap();
        let one = ActParams::default();
        let many = one.with_threads(100_000);
        let grow = |params: &ActParams| {
            Act {
                prices: &prices,
                mc: &mc,
                params,
                w: 1.0,
                selection: SelectionPrices::Listed,
                seed: 5,
            }
            .grown(frame, &rows)
        };
        let tree = grow(&one);
        assert!(tree.len() > 1);
        assert_eq!(grow(&many), tree);
    }
}
