//! CLASSIFY's decision-tree cache, kept up to date as the representation changes.
//!
//! Which feature step 3 of CLASSIFY measures next depends only on the candidates still
//! attended and on the features already measured, so the whole procedure is a decision
//! tree over the representation. This cache grows that tree lazily and keeps, at every
//! node, what the decision there is computed from:
//!
//! * the candidates (descriptions consistent with the values measured on the way to the
//!   node, in ascending id order), and
//! * for every feature some candidate has and the path has not measured, how many
//!   candidates require each value: the counts the I^2/C score is a function of.
//!
//! When a description is added or refined, only the nodes where it is (or was) a
//! candidate change: their candidates and counts are updated in place and their decision
//! is marked stale. A stale decision is recomputed from the counts when a walk next
//! reaches the node; if it is unchanged the subtree below survives, otherwise the subtree
//! is dropped and regrown lazily. A node's candidates and counts depend on the values on
//! its path, not on their order, so when a node that measured `f` comes to measure `g`
//! while its children measured `g`, the grandchildren are kept under new children that
//! measure `f` ([`Cache::transpose`]): two near-equal features trading places, the
//! common change at large nodes, costs a few nodes instead of their subtrees. A decision
//! therefore costs a pass over the node's counts, never a pass over the library, and a
//! refinement costs work in proportion to the nodes that involve the refined description.
//!
//! The score is computed with the same floating-point operations, in the same order, as
//! [`cslearn::InfoCost::select_from`] with the C4.5 rule when every candidate is a class of
//! its own (as descriptions are), so the cached tree measures exactly the features the
//! plain procedure measures (`tests/classify.rs` checks it, feature for feature).

use cslearn::{Cost, FeatureId, Library, Value};
use mdp::{Feature, Reading};

use crate::perception::representation::DescriptionId;

/// What step 2 or 3 of CLASSIFY decides at one point of the procedure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Step {
    /// Return this description.
    Found(DescriptionId),
    /// Add the new description and return it.
    Create,
    /// Measure this feature next.
    Measure(Feature),
}

const NONE: u32 = u32::MAX;
/// What a walk down the tree reads at a node is one record of `Cache::table`, kept
/// apart from what the node's decision is computed from so that walks touch small,
/// dense records: the decision (`Step`, two words), whether it is stale (must be
/// recomputed from the node's candidates and counts before it is used), and for a node
/// that measures, its child for each reading (or `NONE`).
const STEP_TAG: usize = 0;
const STEP_ARG: usize = 1;
const STALE: usize = 2;
const CHILDREN: usize = 3;

fn encode(step: Step) -> [u32; 2] {
    match step {
        Step::Found(d) => [0, d.0],
        Step::Create => [1, 0],
        Step::Measure(f) => [2, f.0],
    }
}

fn decode(tag: u32, arg: u32) -> Step {
    match tag {
        0 => Step::Found(DescriptionId(arg)),
        2 => Step::Measure(Feature(arg)),
        _ => Step::Create,
    }
}

/// What a node's decision is computed from.
#[derive(Clone, Debug, Default)]
struct Node {
    /// Candidate descriptions, ascending.
    cands: Vec<u32>,
    /// Every feature some candidate has and the path has not measured, ascending.
    feats: Vec<u32>,
    /// For each of `feats` in turn, how many candidates require each reading: one block
    /// of the cache's arity per feature; no all-zero block.
    vals: Vec<u32>,
}

impl Node {
    fn has_cand(&self, d: u32) -> bool {
        self.cands.binary_search(&d).is_ok()
    }

    /// Add `delta` (+1 or -1) to the count of `value` for `feature`.
    fn count(&mut self, arity: usize, feature: u32, value: u32, delta: i32) {
        debug_assert!(
            (value as usize) < arity,
            "a reading beyond its feature's range"
        );
        match self.feats.binary_search(&feature) {
            Ok(i) => {
                let block = &mut self.vals[i * arity..(i + 1) * arity];
                let c = &mut block[value as usize];
                *c = c.wrapping_add_signed(delta);
                if block.iter().all(|&c| c == 0) {
                    self.feats.remove(i);
                    self.vals.drain(i * arity..(i + 1) * arity);
                }
            }
            Err(i) => {
                debug_assert_eq!(delta, 1, "a count below zero");
                self.feats.insert(i, feature);
                let at = i * arity;
                self.vals
                    .splice(at..at, (0..arity as u32).map(|v| u32::from(v == value)));
            }
        }
    }
}

/// Dense per-feature counts where a node's counts are built: a block of the cache's arity
/// per feature, all zero but for the features in `touched`.
#[derive(Clone, Debug, Default)]
struct Tally {
    counts: Vec<u32>,
    /// Which features have a block in use.
    live: Vec<bool>,
    /// The features in use, in the order they were first counted.
    touched: Vec<u32>,
}

impl Tally {
    /// Put feature `f`'s block in use (blocks of `k` counts).
    fn open(&mut self, f: usize, k: usize) {
        if f >= self.live.len() {
            self.live.resize(f + 1, false);
            self.counts.resize((f + 1) * k, 0);
        }
        if !self.live[f] {
            self.live[f] = true;
            self.touched.push(f as u32);
        }
    }

    /// Count one more candidate requiring reading `v` of feature `f`.
    fn add_one(&mut self, f: usize, v: usize, k: usize) {
        debug_assert!(v < k, "a reading beyond its feature's range");
        self.open(f, k);
        self.counts[f * k + v] += 1;
    }

    /// Count the candidates of `block` (the counts of feature `f`'s readings).
    fn add_block(&mut self, f: usize, block: &[u32]) {
        let k = block.len();
        self.open(f, k);
        self.counts[f * k..(f + 1) * k].copy_from_slice(block);
    }

    /// Count one candidate fewer requiring reading `v` of feature `f`, if `f` is in use.
    fn take_one(&mut self, f: usize, v: usize, k: usize) {
        if self.live.get(f).copied().unwrap_or(false) {
            self.counts[f * k + v] -= 1;
        }
    }

    /// Move the counts to `node`, in feature order and without all-zero blocks, leaving
    /// every block clear.
    fn store(&mut self, node: &mut Node, k: usize) {
        self.touched.sort_unstable();
        node.feats.clear();
        node.vals.clear();
        for &f in &self.touched {
            let f = f as usize;
            let block = &mut self.counts[f * k..(f + 1) * k];
            if block.iter().any(|&c| c > 0) {
                node.feats.push(f as u32);
                node.vals.extend_from_slice(block);
                block.fill(0);
            }
            self.live[f] = false;
        }
        self.touched.clear();
    }
}

/// How much work the cache has done, counted in its tests only (in other builds this is
/// empty and counts nothing): elementary steps (a candidate scanned, a count changed, a
/// feature scored, a node walked through), and among them the counts changed by added
/// and refined descriptions.
#[derive(Clone, Copy, Debug, Default)]
struct Work {
    #[cfg(test)]
    steps: u64,
    #[cfg(test)]
    count_updates: u64,
}

impl Work {
    #[inline(always)]
    fn steps(&mut self, n: usize) {
        #[cfg(test)]
        {
            self.steps += n as u64;
        }
        let _ = n;
    }

    #[inline(always)]
    fn count_update(&mut self) {
        self.steps(1);
        #[cfg(test)]
        {
            self.count_updates += 1;
        }
    }
}

/// The reading a description (its `pairs`, by feature) requires of `feature`, if any.
#[inline]
fn reading(pairs: &[(FeatureId, Value)], feature: u32) -> Option<u32> {
    pairs
        .binary_search_by_key(&feature, |p| p.0.0)
        .ok()
        .map(|i| pairs[i].1.0)
}

/// Features measured on the way to a node, with their values, and for every feature the
/// value it has on the path, if any: a traversal asks that of each feature of a
/// description at each node, so it is read in one step, not by a search of the path.
#[derive(Clone, Debug, Default)]
struct Path {
    edges: Vec<(u32, u32)>,
    /// `value + 1` for a feature on the path, 0 for one that is not.
    value_of: Vec<u32>,
}

impl Path {
    fn len(&self) -> usize {
        self.edges.len()
    }

    fn push(&mut self, (feature, value): (u32, u32)) {
        let f = feature as usize;
        if f >= self.value_of.len() {
            self.value_of.resize(f + 1, 0);
        }
        debug_assert_eq!(self.value_of[f], 0, "a feature measured twice on a path");
        self.value_of[f] = value + 1;
        self.edges.push((feature, value));
    }

    fn truncate(&mut self, depth: usize) {
        while self.edges.len() > depth {
            if let Some((f, _)) = self.edges.pop() {
                self.value_of[f as usize] = 0;
            }
        }
    }

    /// The value `feature` has on the path, if it is on it.
    #[inline]
    fn get(&self, feature: u32) -> Option<u32> {
        match self.value_of.get(feature as usize) {
            Some(&v) if v > 0 => Some(v - 1),
            _ => None,
        }
    }
}

/// The cached decision tree of CLASSIFY (see the module docs).
#[derive(Clone, Debug)]
pub(super) struct Cache {
    /// How many readings a feature may have (the largest over the world's features):
    /// the stride of `children` and of a node's counts.
    arity: usize,
    /// One record of `CHILDREN + arity` words per node (see [`STEP_TAG`]).
    table: Vec<u32>,
    nodes: Vec<Node>,
    free: Vec<u32>,
    /// `x log2 x` for every count seen so far, computed as cslearn computes it.
    xlogx: Vec<f64>,
    /// Where a node's counts are built.
    tally: Tally,
    marks: Vec<bool>,
    /// The candidates of a node that its new child leaves out.
    excluded: Vec<u32>,
    /// Traversal stack: (node, path length above it, edge into it).
    stack: Vec<(u32, usize, (u32, u32))>,
    path: Path,
    /// How many new children took over their grandchildren in [`Cache::transpose`].
    #[cfg(test)]
    transposed: usize,
    work: Work,
}

impl Cache {
    /// An empty cache for features with at most `arity` readings each (at least 1).
    pub(super) fn new(arity: u32) -> Cache {
        Cache {
            arity: arity.max(1) as usize,
            table: Vec::new(),
            nodes: Vec::new(),
            free: Vec::new(),
            xlogx: Vec::new(),
            tally: Tally::default(),
            marks: Vec::new(),
            excluded: Vec::new(),
            stack: Vec::new(),
            path: Path::default(),
            #[cfg(test)]
            transposed: 0,
            work: Work::default(),
        }
    }

    /// Where node `at`'s record starts in `table`.
    #[inline]
    fn rec(&self, at: u32) -> usize {
        at as usize * (CHILDREN + self.arity)
    }

    #[inline]
    fn step(&self, at: u32) -> Step {
        let r = self.rec(at);
        decode(self.table[r + STEP_TAG], self.table[r + STEP_ARG])
    }

    #[inline]
    fn set_step(&mut self, at: u32, step: Step) {
        let r = self.rec(at);
        let [tag, arg] = encode(step);
        self.table[r + STEP_TAG] = tag;
        self.table[r + STEP_ARG] = arg;
    }

    #[inline]
    fn set_stale(&mut self, at: u32, stale: bool) {
        let r = self.rec(at);
        self.table[r + STALE] = u32::from(stale);
    }

    /// The children of node `at`, one per reading.
    #[inline]
    fn children_of(&self, at: u32) -> &[u32] {
        let r = self.rec(at) + CHILDREN;
        &self.table[r..r + self.arity]
    }

    /// Mark node `at` stale and, if it measures, push its children with the edges into
    /// them (those whose reading passes `keep`) on `stack`.
    fn stale_and_push(
        &mut self,
        at: u32,
        depth: usize,
        keep: impl Fn(u32) -> bool,
        stack: &mut Vec<(u32, usize, (u32, u32))>,
    ) {
        self.set_stale(at, true);
        if let Step::Measure(g) = self.step(at) {
            for (code, &child) in self.children_of(at).iter().enumerate() {
                if child != NONE && keep(code as u32) {
                    stack.push((child, depth, (g.0, code as u32)));
                }
            }
        }
    }

    /// Walk the tree for one object: `measure` reads a feature of it (and is the only
    /// place where sensing happens), and `path` receives the features measured with their
    /// values, in order. Returns the description found, or `None` when CLASSIFY would
    /// create a new one.
    pub(super) fn walk(
        &mut self,
        library: &Library,
        costs: &[Cost],
        path: &mut Vec<(Feature, Reading)>,
        mut measure: impl FnMut(Feature) -> Reading,
    ) -> Option<DescriptionId> {
        if self.nodes.is_empty() {
            let root = self.alloc();
            debug_assert_eq!(root, 0);
            self.nodes[0].cands.extend(0..library.len() as u32);
            self.fill_counts(0, library, &[]);
        }
        path.clear();
        let mut at = 0u32;
        let width = CHILDREN + self.arity;
        loop {
            self.work.steps(1);
            let r = at as usize * width;
            if self.table[r + STALE] != 0 {
                self.refresh(at, costs, library, path);
            }
            let record = &self.table[r..r + width];
            match decode(record[STEP_TAG], record[STEP_ARG]) {
                Step::Found(d) => return Some(d),
                Step::Create => return None,
                Step::Measure(f) => {
                    let v = measure(f);
                    path.push((f, v));
                    let code = v.0;
                    debug_assert!(
                        (code as usize) < self.arity,
                        "a reading beyond its feature's range"
                    );
                    let child = record[CHILDREN + code as usize];
                    at = if child == NONE {
                        self.grow(at, f.0, code, library, path)
                    } else {
                        child
                    };
                }
            }
        }
    }

    /// Description `d` was just added to `library` (it has the highest id).
    pub(super) fn on_push(&mut self, library: &Library, d: DescriptionId) {
        if self.nodes.is_empty() {
            return;
        }
        let pairs = library.examples()[d.index()].pairs();
        self.stack.clear();
        self.stack.push((0, 0, (NONE, 0)));
        while let Some((at, depth, edge)) = self.stack.pop() {
            self.path.truncate(depth);
            if edge.0 != NONE {
                self.path.push(edge);
            }
            let arity = self.arity;
            let node = &mut self.nodes[at as usize];
            debug_assert!(node.cands.last().is_none_or(|&c| c < d.0));
            node.cands.push(d.0);
            for &(f, v) in pairs {
                if self.path.get(f.0).is_none() {
                    node.count(arity, f.0, v.0, 1);
                    self.work.count_update();
                }
            }
            let wanted = match self.step(at) {
                Step::Measure(g) => reading(pairs, g.0),
                _ => None,
            };
            let mut stack = std::mem::take(&mut self.stack);
            let depth = self.path.len();
            self.stale_and_push(
                at,
                depth,
                |code| wanted.is_none_or(|w| w == code),
                &mut stack,
            );
            self.stack = stack;
        }
    }

    /// Description `d` of `library` was just given `feature` = `value`.
    pub(super) fn on_refine(
        &mut self,
        library: &Library,
        d: DescriptionId,
        f: Feature,
        v: Reading,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let (feature, value) = (f.0, v.0);
        self.stack.clear();
        self.stack.push((0, 0, (NONE, 0)));
        while let Some((at, depth, edge)) = self.stack.pop() {
            self.path.truncate(depth);
            if edge.0 != NONE {
                self.path.push(edge);
            }
            if !self.nodes[at as usize].has_cand(d.0) {
                continue;
            }
            match self.path.get(feature) {
                // Measured above with the value now required: nothing below changes.
                Some(w) if w == value => {}
                // Measured above with another value: `d` no longer belongs here.
                Some(_) => self.remove_below(at, library, d),
                None => {
                    let arity = self.arity;
                    self.nodes[at as usize].count(arity, feature, value, 1);
                    self.work.count_update();
                    let mut stack = std::mem::take(&mut self.stack);
                    let depth = self.path.len();
                    self.stale_and_push(at, depth, |_| true, &mut stack);
                    self.stack = stack;
                }
            }
        }
    }

    /// Take `d` out of the subtree at `top` (whose path is `self.path`).
    fn remove_below(&mut self, top: u32, library: &Library, d: DescriptionId) {
        let pairs = library.examples()[d.index()].pairs();
        let base = self.path.len();
        let mut stack = vec![(top, base, (NONE, 0))];
        while let Some((at, depth, edge)) = stack.pop() {
            self.path.truncate(depth);
            if edge.0 != NONE {
                self.path.push(edge);
            }
            let arity = self.arity;
            let node = &mut self.nodes[at as usize];
            let Ok(i) = node.cands.binary_search(&d.0) else {
                continue;
            };
            node.cands.remove(i);
            for &(f, v) in pairs {
                if self.path.get(f.0).is_none() {
                    node.count(arity, f.0, v.0, -1);
                    self.work.count_update();
                }
            }
            let depth = self.path.len();
            self.stale_and_push(at, depth, |_| true, &mut stack);
        }
        self.path.truncate(base);
    }

    /// Recompute a stale decision (node `at`'s path is `path`); if it changed, drop the
    /// subtree, but for what the new decision can keep (see [`Cache::transpose`]).
    fn refresh(
        &mut self,
        at: u32,
        costs: &[Cost],
        library: &Library,
        path: &mut Vec<(Feature, Reading)>,
    ) {
        let step = self.decide(at, costs);
        self.set_stale(at, false);
        let old = self.step(at);
        if old == step {
            return;
        }
        self.set_step(at, step);
        // Only a node that measures has children.
        let Step::Measure(f) = old else {
            return;
        };
        let r = self.rec(at) + CHILDREN;
        let children: Vec<u32> = self.table[r..r + self.arity].to_vec();
        self.table[r..r + self.arity].fill(NONE);
        self.transpose(at, f, &children, costs, library, path);
        for child in children {
            if child != NONE {
                self.release(child);
            }
        }
    }

    /// Node `at` measured `f`, and `children` were its children for `f`. If it now
    /// measures `g`: a node's candidates and counts depend only on the set of values on
    /// its path, not on their order, so where a child for `f` measured `g`, its children
    /// (path `f = a, g = b`) are what the children of a new child for `g = b` that
    /// measures `f` would be. Those new children are grown now and, where they measure
    /// `f`, take them over instead of regrowing them; whatever is taken over is unlinked
    /// from `children`.
    fn transpose(
        &mut self,
        at: u32,
        f: Feature,
        children: &[u32],
        costs: &[Cost],
        library: &Library,
        path: &mut Vec<(Feature, Reading)>,
    ) {
        let Step::Measure(g) = self.step(at) else {
            return;
        };
        let k = self.arity;
        // grand[a * k + b]: the child for `g = b` of the old child for `f = a`.
        let mut grand = vec![NONE; k * k];
        for (a, &child) in children.iter().enumerate() {
            if child != NONE && self.step(child) == Step::Measure(g) {
                let r = self.rec(child) + CHILDREN;
                grand[a * k..(a + 1) * k].copy_from_slice(&self.table[r..r + k]);
                self.table[r..r + k].fill(NONE);
            }
        }
        for b in 0..k {
            if (0..k).all(|a| grand[a * k + b] == NONE) {
                continue;
            }
            path.push((g, Reading(b as u32)));
            let new = self.grow(at, g.0, b as u32, library, path);
            self.refresh(new, costs, library, path);
            path.pop();
            let keep = self.step(new) == Step::Measure(f);
            #[cfg(test)]
            {
                self.transposed += usize::from(keep);
            }
            let r = self.rec(new) + CHILDREN;
            for a in 0..k {
                let old = grand[a * k + b];
                if keep {
                    self.table[r + a] = old;
                } else if old != NONE {
                    self.release(old);
                }
            }
        }
    }

    /// Steps 2 and 3 at a node: I^2/C over the counts, as cslearn's `InfoCost` with the
    /// C4.5 rule computes it when every candidate is its own class.
    fn decide(&mut self, at: u32, costs: &[Cost]) -> Step {
        let node = &self.nodes[at as usize];
        let Some(&first) = node.cands.first() else {
            return Step::Create;
        };
        if node.feats.is_empty() {
            // Every feature of every candidate is measured and matched; candidates are
            // pairwise disjoint, so there is one.
            return Step::Found(DescriptionId(first));
        }
        let n = node.cands.len();
        if self.xlogx.len() <= n {
            let from = self.xlogx.len();
            self.xlogx.extend((from..=n).map(|x| {
                if x == 0 {
                    0.0
                } else {
                    let x = x as f64;
                    x * x.log2()
                }
            }));
        }
        let node = &self.nodes[at as usize];
        self.work.steps(node.feats.len());
        let xl = &self.xlogx;
        let mut best = cslearn::BestScore::new();
        for (&feature, counts) in node.feats.iter().zip(node.vals.chunks_exact(self.arity)) {
            // Each class (candidate) occurs once, so every within-class term is zero:
            // the gain on the candidates having the feature, times their share, is
            // (g(having) - sum over values of g(count)) / n with g = x log2 x.
            let mut branches = 0.0;
            for &c in counts {
                if c > 0 {
                    branches += xl[c as usize];
                }
            }
            let having = counts.iter().sum::<u32>();
            let gain = ((xl[having as usize] - branches) / n as f64).max(0.0);
            best.offer(FeatureId(feature), gain, costs[feature as usize]);
        }
        let f = best
            .best()
            .expect("a node with counts has a candidate feature");
        Step::Measure(Feature(f.0))
    }

    /// The child of `parent` (which measures `feature`) for `code`, built from the
    /// parent's candidates; `path` is the child's path.
    fn grow(
        &mut self,
        parent: u32,
        feature: u32,
        code: u32,
        library: &Library,
        path: &[(Feature, Reading)],
    ) -> u32 {
        let child = self.alloc();
        let examples = library.examples();
        let (p, c) = if parent < child {
            let (a, b) = self.nodes.split_at_mut(child as usize);
            (&a[parent as usize], &mut b[0])
        } else {
            let (a, b) = self.nodes.split_at_mut(parent as usize);
            (&b[0], &mut a[child as usize])
        };
        let excluded = &mut self.excluded;
        excluded.clear();
        for &d in &p.cands {
            match reading(examples[d as usize].pairs(), feature) {
                Some(v) if v != code => excluded.push(d),
                _ => c.cands.push(d),
            }
        }
        self.work.steps(self.nodes[parent as usize].cands.len());
        let r = self.rec(parent) + CHILDREN;
        self.table[r + code as usize] = child;
        if self.excluded.len() < self.nodes[child as usize].cands.len() {
            // Fewer candidates left out than kept: the parent's counts without those.
            self.counts_from_parent(parent, child, feature, library);
        } else {
            self.fill_counts(child, library, path);
        }
        child
    }

    /// The counts of `child`, the child of `parent` (which measures `feature`), as
    /// [`Cache::fill_counts`] would count them: the parent's, without `feature` and
    /// without the candidates in `self.excluded` (the parent's that the child left out).
    fn counts_from_parent(&mut self, parent: u32, child: u32, feature: u32, library: &Library) {
        let k = self.arity;
        let from = &self.nodes[parent as usize];
        self.work.steps(from.feats.len());
        for (&f, block) in from.feats.iter().zip(from.vals.chunks_exact(k)) {
            if f != feature {
                self.tally.add_block(f as usize, block);
            }
        }
        let examples = library.examples();
        for &d in &self.excluded {
            self.work.steps(examples[d as usize].pairs().len());
            for &(f, v) in examples[d as usize].pairs() {
                // Only the parent's features count: those measured on the way do not.
                self.tally.take_one(f.0 as usize, v.0 as usize, k);
            }
        }
        self.tally.store(&mut self.nodes[child as usize], k);
    }

    /// Count, for a node whose candidates are set, the values of every unmeasured feature.
    fn fill_counts(&mut self, at: u32, library: &Library, path: &[(Feature, Reading)]) {
        let examples = library.examples();
        for &(f, _) in path {
            self.mark(f.0, true);
        }
        let k = self.arity;
        for &d in &self.nodes[at as usize].cands {
            self.work.steps(examples[d as usize].pairs().len());
            for &(f, v) in examples[d as usize].pairs() {
                let f = f.0 as usize;
                if !self.marks.get(f).copied().unwrap_or(false) {
                    self.tally.add_one(f, v.0 as usize, k);
                }
            }
        }
        for &(f, _) in path {
            self.mark(f.0, false);
        }
        self.tally.store(&mut self.nodes[at as usize], k);
    }

    fn mark(&mut self, feature: u32, on: bool) {
        let f = feature as usize;
        if f >= self.marks.len() {
            self.marks.resize(f + 1, false);
        }
        self.marks[f] = on;
    }

    fn alloc(&mut self) -> u32 {
        match self.free.pop() {
            Some(i) => i,
            None => {
                self.nodes.push(Node::default());
                self.push_fresh();
                (self.nodes.len() - 1) as u32
            }
        }
    }

    /// A new record, as [`Cache::fresh`] leaves one.
    fn push_fresh(&mut self) {
        let [tag, arg] = encode(Step::Create);
        self.table.extend([tag, arg, 1]);
        self.table.extend(std::iter::repeat_n(NONE, self.arity));
    }

    /// Node `at`'s record as new: decision `Create`, stale, no children.
    fn fresh(&mut self, at: u32) {
        let r = self.rec(at);
        let [tag, arg] = encode(Step::Create);
        self.table[r + STEP_TAG] = tag;
        self.table[r + STEP_ARG] = arg;
        self.table[r + STALE] = 1;
        self.table[r + CHILDREN..r + CHILDREN + self.arity].fill(NONE);
    }

    /// Return a subtree's nodes to the free list.
    fn release(&mut self, top: u32) {
        let mut stack = vec![top];
        let k = self.arity;
        while let Some(at) = stack.pop() {
            let r = self.rec(at);
            let children = &mut self.table[r + CHILDREN..r + CHILDREN + k];
            stack.extend(children.iter().copied().filter(|&c| c != NONE));
            self.fresh(at);
            let node = &mut self.nodes[at as usize];
            node.cands.clear();
            node.feats.clear();
            node.vals.clear();
            self.free.push(at);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cslearn::{ClassId, Example};
    use rand::{RngExt, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    const FEATURES: u32 = 7;
    const ARITY: u32 = 3;

    /// Every node of `cache` against what it is computed from, made from scratch from its
    /// path: its candidates, its counts and, unless stale, its decision.
    fn check(cache: &Cache, library: &Library, costs: &[Cost]) {
        if cache.nodes.is_empty() {
            return;
        }
        let k = cache.arity;
        let mut stack = vec![(0u32, Vec::<(u32, u32)>::new())];
        while let Some((at, path)) = stack.pop() {
            let examples = library.examples();
            let cands: Vec<u32> = (0..library.len() as u32)
                .filter(|&d| {
                    let pairs = examples[d as usize].pairs();
                    path.iter()
                        .all(|&(f, v)| reading(pairs, f).is_none_or(|w| w == v))
                })
                .collect();
            let node = &cache.nodes[at as usize];
            assert_eq!(node.cands, cands, "candidates at {path:?}");
            let (mut feats, mut vals) = (Vec::new(), Vec::new());
            for f in (0..FEATURES).filter(|&f| path.iter().all(|e| e.0 != f)) {
                let mut block = vec![0; k];
                for &d in &cands {
                    if let Some(v) = reading(examples[d as usize].pairs(), f) {
                        block[v as usize] += 1;
                    }
                }
                if block.iter().any(|&c| c > 0) {
                    feats.push(f);
                    vals.extend(block);
                }
            }
            assert_eq!(
                (&node.feats, &node.vals),
                (&feats, &vals),
                "counts at {path:?}"
            );
            if cache.table[cache.rec(at) + STALE] == 0 {
                assert_eq!(
                    cache.step(at),
                    cache.clone().decide(at, costs),
                    "at {path:?}"
                );
            }
            if let Step::Measure(g) = cache.step(at) {
                for (code, &child) in cache.children_of(at).iter().enumerate() {
                    if child != NONE {
                        let mut below = path.clone();
                        below.push((g.0, code as u32));
                        stack.push((child, below));
                    }
                }
            }
        }
    }

    /// CLASSIFY's use of the cache on random objects (values of every feature): walk one,
    /// add what was measured when nothing is found, sometimes refine what was found
    /// with one more of the object's values, and now and then add a description of a few
    /// random values. After every step the whole tree is checked, and a cache built
    /// from scratch finds what the kept one finds. Returns how many transpositions kept
    /// grandchildren.
    fn exercise(seed: u64, steps: usize) -> usize {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let costs: Vec<Cost> = (0..FEATURES)
            .map(|_| Cost::new(f64::from(rng.random_range(1..4u32))).unwrap())
            .collect();
        let objects: Vec<Vec<u32>> = (0..24)
            .map(|_| (0..FEATURES).map(|_| rng.random_range(0..ARITY)).collect())
            .collect();
        let mut library = Library::new();
        let mut cache = Cache::new(ARITY);
        let mut path = Vec::new();
        for _ in 0..steps {
            let object = &objects[rng.random_range(0..objects.len())];
            let read = |f: Feature| Reading(object[f.0 as usize]);
            let found = cache.walk(&library, &costs, &mut path, read);
            let mut fresh = Cache::new(ARITY);
            let mut fresh_path = Vec::new();
            let again = fresh.walk(&library, &costs, &mut fresh_path, read);
            assert_eq!((found, &path), (again, &fresh_path));
            let pairs: Vec<(FeatureId, Value)> = match found {
                None => path
                    .iter()
                    .map(|&(f, v)| (FeatureId(f.0), Value(v.0)))
                    .collect(),
                Some(_) if rng.random_bool(0.2) => {
                    let f = rng.random_range(0..FEATURES);
                    vec![(FeatureId(f), Value(rng.random_range(0..ARITY)))]
                }
                Some(d) => {
                    let example = library.get_mut(d.index()).unwrap();
                    let missing = (0..FEATURES).find(|&f| example.get(FeatureId(f)).is_none());
                    if let Some(f) = missing.filter(|_| rng.random_bool(0.5)) {
                        let v = object[f as usize];
                        example.insert(FeatureId(f), Value(v));
                        cache.on_refine(&library, d, Feature(f), Reading(v));
                    }
                    check(&cache, &library, &costs);
                    continue;
                }
            };
            let id = library.len() as u32;
            let d = library.push(Example::from_pairs(pairs, ClassId(id)));
            cache.on_push(&library, DescriptionId(d as u32));
            check(&cache, &library, &costs);
        }
        cache.transposed
    }

    /// CLASSIFY's use of the cache as descriptions multiply: objects of 24 features, read
    /// with errors, make a new description for most misreadings, and a found description
    /// is refined with one more of its object's values half of the time (as eager CS-QL
    /// does). Returns, when the library reaches each of `sizes`, the descriptions, the
    /// cache's steps and its count updates so far.
    fn multiply(seed: u64, sizes: &[usize]) -> Vec<(usize, u64, u64)> {
        const WIDE: u32 = 24;
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let costs: Vec<Cost> = (0..WIDE)
            .map(|_| Cost::new(f64::from(rng.random_range(1..4u32))).unwrap())
            .collect();
        let objects: Vec<Vec<u32>> = (0..400)
            .map(|_| (0..WIDE).map(|_| rng.random_range(0..ARITY)).collect())
            .collect();
        let mut library = Library::new();
        let mut cache = Cache::new(ARITY);
        let mut path = Vec::new();
        let mut seen = Vec::new();
        while seen.len() < sizes.len() {
            let object = &objects[rng.random_range(0..objects.len())];
            let found = cache.walk(&library, &costs, &mut path, |f: Feature| {
                let v = object[f.0 as usize];
                Reading(if rng.random_bool(0.05) {
                    (v + 1) % ARITY
                } else {
                    v
                })
            });
            match found {
                None => {
                    let pairs = path.iter().map(|&(f, v)| (FeatureId(f.0), Value(v.0)));
                    let id = library.len() as u32;
                    let d =
                        library.push(Example::from_pairs(pairs.collect::<Vec<_>>(), ClassId(id)));
                    cache.on_push(&library, DescriptionId(d as u32));
                }
                Some(d) if rng.random_bool(0.5) => {
                    let example = library.get_mut(d.index()).unwrap();
                    if let Some(f) = (0..WIDE).find(|&f| example.get(FeatureId(f)).is_none()) {
                        let v = object[f as usize];
                        example.insert(FeatureId(f), Value(v));
                        cache.on_refine(&library, d, Feature(f), Reading(v));
                    }
                }
                Some(_) => {}
            }
            if library.len() == sizes[seen.len()] {
                let work = cache.work;
                seen.push((library.len(), work.steps, work.count_updates));
            }
        }
        seen
    }

    #[test]
    fn the_cache_work_per_description_follows_the_counts_it_keeps() {
        let seen = multiply(1, &[500, 1000, 2000, 4000]);
        let per_description = |&(d, steps, _): &(usize, u64, u64)| steps as f64 / d as f64;
        let per_update = |&(_, steps, updates): &(usize, u64, u64)| steps as f64 / updates as f64;
        let (first, last) = (&seen[0], &seen[seen.len() - 1]);
        // Eight times the descriptions: the cost of each grows far less than their number
        // (in proportion to it would be eight times); it grows as the counts each new
        // description changes (it lands in more nodes of a deeper tree), and per count
        // changed it stays the same.
        let grew = per_description(last) / per_description(first);
        assert!(
            grew < 4.0,
            "steps per description grew {grew:.2} times: {seen:?}"
        );
        for w in &seen {
            let drift = per_update(w) / per_update(first);
            assert!(
                (0.8..1.25).contains(&drift),
                "steps per count update moved {drift:.2} times: {seen:?}"
            );
        }
    }

    #[test]
    fn the_kept_tree_is_the_tree_built_from_scratch() {
        let transposed: usize = (0..16).map(|seed| exercise(seed, 300)).sum();
        // The cases include decisions that changed and kept their grandchildren.
        assert!(transposed > 0);
    }
}
