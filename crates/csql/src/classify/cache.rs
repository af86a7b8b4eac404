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
//! is dropped and regrown lazily. A decision therefore costs a pass over the node's
//! counts, never a pass over the library, and a refinement costs work in proportion to
//! the nodes that involve the refined description.
//!
//! The score is computed with the same floating-point operations, in the same order, as
//! [`cslearn::InfoCost::select_from`] with the C4.5 rule when every candidate is a class of
//! its own (as descriptions are), so the cached tree measures exactly the features the
//! plain procedure measures (`tests/classify.rs` checks it, feature for feature).

use cslearn::{Cost, FeatureId, Library};
use mdp::{Feature, Reading};

use crate::representation::DescriptionId;

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
/// Readings kept inline per node: a grid's three cell conditions fit; worlds with more
/// readings per feature spill the rest to the heap.
const INLINE: usize = 4;

/// One `u32` per reading code, `FILL` where nothing was written: the first [`INLINE`]
/// inline, the rest on the heap (a grid's readings never allocate). Iteration is in code
/// order, so sums over counts add in the same order whatever the storage.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Slots<const FILL: u32> {
    inline: [u32; INLINE],
    more: Vec<u32>,
}

impl<const FILL: u32> Slots<FILL> {
    const EMPTY: Self = Slots {
        inline: [FILL; INLINE],
        more: Vec::new(),
    };
    #[inline]
    fn get(&self, code: u32) -> u32 {
        let c = code as usize;
        if c < INLINE {
            self.inline[c]
        } else {
            self.more.get(c - INLINE).copied().unwrap_or(FILL)
        }
    }
    #[inline]
    fn slot(&mut self, code: u32) -> &mut u32 {
        let c = code as usize;
        if c < INLINE {
            &mut self.inline[c]
        } else {
            if self.more.len() <= c - INLINE {
                self.more.resize(c - INLINE + 1, FILL);
            }
            &mut self.more[c - INLINE]
        }
    }
    #[inline]
    fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        self.inline.iter().chain(self.more.iter()).copied()
    }
    /// The codes written, with their values, in code order.
    #[inline]
    fn written(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.iter()
            .enumerate()
            .filter(|&(_, v)| v != FILL)
            .map(|(c, v)| (c as u32, v))
    }
    #[inline]
    fn is_blank(&self) -> bool {
        self.iter().all(|v| v == FILL)
    }
}

impl<const FILL: u32> Default for Slots<FILL> {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// A node's children, one per reading measured there.
type Children = Slots<NONE>;
/// How many candidates require each reading of a feature.
type Counts = Slots<0>;

/// What a walk down the tree reads at a node, kept apart from what the node's decision
/// is computed from so that walks touch small, dense records.
#[derive(Clone, Debug)]
struct Link {
    step: Step,
    /// The decision must be recomputed from the node's candidates and counts before it
    /// is used.
    stale: bool,
    /// For `Measure`: the child for each reading, or `NONE`.
    children: Children,
}

impl Link {
    const FRESH: Link = Link {
        step: Step::Create,
        stale: true,
        children: Children::EMPTY,
    };
}

/// What a node's decision is computed from.
#[derive(Clone, Debug, Default)]
struct Node {
    /// Candidate descriptions, ascending.
    cands: Vec<u32>,
    /// (feature, candidates requiring each value) for every feature some candidate has
    /// and the path has not measured, ascending by feature; no all-zero entry.
    counts: Vec<(u32, Counts)>,
}

impl Node {
    fn has_cand(&self, d: u32) -> bool {
        self.cands.binary_search(&d).is_ok()
    }

    /// Add `delta` (+1 or -1) to the count of `value` for `feature`.
    fn count(&mut self, feature: u32, value: u32, delta: i32) {
        match self.counts.binary_search_by_key(&feature, |e| e.0) {
            Ok(i) => {
                let c = self.counts[i].1.slot(value);
                *c = c.wrapping_add_signed(delta);
                if self.counts[i].1.is_blank() {
                    self.counts.remove(i);
                }
            }
            Err(i) => {
                debug_assert_eq!(delta, 1, "a count below zero");
                let mut c = Counts::EMPTY;
                *c.slot(value) = 1;
                self.counts.insert(i, (feature, c));
            }
        }
    }
}

/// Features measured on the way to a node, with their values.
type Path = Vec<(u32, u32)>;

fn on_path(path: &[(u32, u32)], feature: u32) -> Option<u32> {
    path.iter().find(|e| e.0 == feature).map(|e| e.1)
}

/// The cached decision tree of CLASSIFY (see the module docs).
#[derive(Clone, Debug, Default)]
pub(super) struct Cache {
    links: Vec<Link>,
    nodes: Vec<Node>,
    free: Vec<u32>,
    /// `x log2 x` for every count seen so far, computed as cslearn computes it.
    xlogx: Vec<f64>,
    /// Dense per-feature scratch for building a node's counts.
    scratch: Vec<Counts>,
    touched: Vec<u32>,
    marks: Vec<bool>,
    /// Traversal stack: (node, path length above it, edge into it).
    stack: Vec<(u32, usize, (u32, u32))>,
    path: Path,
}

impl Cache {
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
        loop {
            if self.links[at as usize].stale {
                self.refresh(at, costs);
            }
            match self.links[at as usize].step {
                Step::Found(d) => return Some(d),
                Step::Create => return None,
                Step::Measure(f) => {
                    let v = measure(f);
                    path.push((f, v));
                    let code = v.0;
                    let child = self.links[at as usize].children.get(code);
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
            let node = &mut self.nodes[at as usize];
            debug_assert!(node.cands.last().is_none_or(|&c| c < d.0));
            node.cands.push(d.0);
            for &(f, v) in pairs {
                if on_path(&self.path, f.0).is_none() {
                    node.count(f.0, v.0, 1);
                }
            }
            let link = &mut self.links[at as usize];
            link.stale = true;
            if let Step::Measure(g) = link.step {
                let wanted = pairs
                    .binary_search_by_key(&g.0, |p| p.0.0)
                    .ok()
                    .map(|i| pairs[i].1.0);
                for (code, child) in link.children.written() {
                    if wanted.is_none_or(|w| w == code) {
                        self.stack.push((child, self.path.len(), (g.0, code)));
                    }
                }
            }
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
            match on_path(&self.path, feature) {
                // Measured above with the value now required: nothing below changes.
                Some(w) if w == value => {}
                // Measured above with another value: `d` no longer belongs here.
                Some(_) => self.remove_below(at, library, d),
                None => {
                    self.nodes[at as usize].count(feature, value, 1);
                    let link = &mut self.links[at as usize];
                    link.stale = true;
                    if let Step::Measure(g) = link.step {
                        for (code, child) in link.children.written() {
                            self.stack.push((child, self.path.len(), (g.0, code)));
                        }
                    }
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
            let node = &mut self.nodes[at as usize];
            let Ok(i) = node.cands.binary_search(&d.0) else {
                continue;
            };
            node.cands.remove(i);
            for &(f, v) in pairs {
                if on_path(&self.path, f.0).is_none() {
                    node.count(f.0, v.0, -1);
                }
            }
            let link = &mut self.links[at as usize];
            link.stale = true;
            if let Step::Measure(g) = link.step {
                for (code, child) in link.children.written() {
                    stack.push((child, self.path.len(), (g.0, code)));
                }
            }
        }
        self.path.truncate(base);
    }

    /// Recompute a stale decision; drop the subtree if it changed.
    fn refresh(&mut self, at: u32, costs: &[Cost]) {
        let step = self.decide(at, costs);
        let link = &mut self.links[at as usize];
        link.stale = false;
        if link.step != step {
            link.step = step;
            let children = std::mem::replace(&mut link.children, Children::EMPTY);
            for (_, child) in children.written() {
                self.release(child);
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
        if node.counts.is_empty() {
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
        let xl = &self.xlogx;
        let mut best = cslearn::BestScore::new();
        for (feature, counts) in &node.counts {
            let feature = *feature;
            // Each class (candidate) occurs once, so every within-class term is zero:
            // the gain on the candidates having the feature, times their share, is
            // (g(having) - sum over values of g(count)) / n with g = x log2 x.
            let mut branches = 0.0;
            for c in counts.iter() {
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
        c.cands.extend(p.cands.iter().copied().filter(|&d| {
            examples[d as usize]
                .get(FeatureId(feature))
                .is_none_or(|v| v.0 == code)
        }));
        *self.links[parent as usize].children.slot(code) = child;
        self.fill_counts(child, library, path);
        child
    }

    /// Count, for a node whose candidates are set, the values of every unmeasured feature.
    fn fill_counts(&mut self, at: u32, library: &Library, path: &[(Feature, Reading)]) {
        let examples = library.examples();
        for &(f, _) in path {
            self.mark(f.0, true);
        }
        let node = &self.nodes[at as usize];
        for &d in &node.cands {
            for &(f, v) in examples[d as usize].pairs() {
                let f = f.0 as usize;
                if f >= self.scratch.len() {
                    self.scratch.resize(f + 1, Counts::EMPTY);
                }
                if self.marks.get(f).copied().unwrap_or(false) {
                    continue;
                }
                if self.scratch[f].is_blank() {
                    self.touched.push(f as u32);
                }
                *self.scratch[f].slot(v.0) += 1;
            }
        }
        self.touched.sort_unstable();
        let node = &mut self.nodes[at as usize];
        node.counts.clear();
        for &f in &self.touched {
            node.counts
                .push((f, std::mem::take(&mut self.scratch[f as usize])));
        }
        self.touched.clear();
        for &(f, _) in path {
            self.mark(f.0, false);
        }
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
                self.links.push(Link::FRESH);
                (self.nodes.len() - 1) as u32
            }
        }
    }

    /// Return a subtree's nodes to the free list.
    fn release(&mut self, top: u32) {
        let mut stack = vec![top];
        while let Some(at) = stack.pop() {
            let link = std::mem::replace(&mut self.links[at as usize], Link::FRESH);
            stack.extend(link.children.written().map(|(_, c)| c));
            let node = &mut self.nodes[at as usize];
            node.cands.clear();
            node.counts.clear();
            self.free.push(at);
        }
    }
}
