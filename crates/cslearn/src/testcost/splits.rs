//! The split trie: every node a tree could have, grown lazily and shared by the trees
//! grown over the same objects.
//!
//! Which objects reach a node depends only on the tests on its path, and the statistics
//! of a test at a node (its gain, its threshold, its split information; for DTMC the
//! misclassification cost it saves) depend only on those objects. So a learner that grows
//! many trees on the same objects with different prices (ICET's search) computes each
//! node's statistics once: a tree is a walk down the trie, choosing at each node by the
//! prices of the moment. A single tree grown through the trie costs what growing it
//! directly costs.
//!
//! Four things keep a node cheap, which matters most to ACT's lookahead (thousands of
//! sampled trees per tree): a node holds only its objects (as positions among the root's
//! objects) and their weights; the order of a numeric feature's values at a node is not
//! kept but made when its statistics are first asked for, by sorting each object's rank
//! in the root's order or, for a node of more than a few dozen objects, by reading its
//! ranks off a set of them, a bit per root object (either way the order the root's sort
//! gives, ties included), or, where the feature has few distinct values for the node's
//! objects and none missing, not made at all: the objects are tallied per value and
//! class and the values walked in order (the same thresholds and counts); objects of
//! weight 1 are scanned over whole counts, with what every feature of the node shares
//! (its entropy, the terms of split information) computed once; and the statistics of
//! an exact list of objects and weights are remembered ([`Memo`]), so a node reached
//! again by another path, or made again after [`Splits::forget_since`], reads them
//! instead of computing them. Statistics depend only on the node's objects and weights,
//! in their order, so none of this changes a bit of what a tree reads
//! (`tests/pins/lookahead.txt` holds sixty trees to it).

use std::collections::BTreeMap;
use std::sync::Arc;

use super::criterion::Criterion;
use super::data::{Column, Frame, MISSING};
use super::prices::MisclassCosts;
use super::stop::Stop;

/// The statistics of the best split of one feature at a node.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stat {
    pub feature: usize,
    /// The threshold of a numeric feature.
    pub at: Option<f64>,
    /// The information gain (times the share of known values); for DTMC the expected
    /// misclassification cost the split saves, before any test price.
    pub gain: f64,
    /// C4.5's split information.
    pub split_info: f64,
    /// `2^gain - 1`, EG2's numerator.
    pub exp2_gain: f64,
}

/// The children of a node for one test.
#[derive(Clone, Debug)]
pub(crate) struct Children {
    pub feature: usize,
    pub at: Option<f64>,
    /// The cell of each branch, `None` for a branch no object reaches.
    pub cells: Vec<Option<u32>>,
    /// The share of the objects with a known value in each branch.
    pub shares: Vec<f64>,
    /// The held-out objects' weight per class in each branch (no entry without them).
    pub held_out: Vec<Vec<f64>>,
}

/// A node of the trie: the objects reaching it (with C4.5's weights), what it knows of
/// them, and the children made so far.
pub(crate) struct Cell {
    /// The objects reaching it, as positions among the root's objects.
    objects: Vec<u32>,
    weights: Vec<f64>,
    /// The sum of `weights`.
    total: f64,
    /// Whether every weight is 1 (no object has come with a missing value).
    unit: bool,
    /// The tests on the path to it, in order.
    pub path: Vec<usize>,
    /// Weight per class.
    pub class_weights: Vec<f64>,
    /// The held-out objects reaching the cell (scored, never learned from), with weights.
    held_rows: Vec<u32>,
    held_weights: Vec<f64>,
    /// The held-out objects' weight per class.
    pub held_classes: Vec<f64>,
    stats: Option<Arc<[Stat]>>,
    /// What identifies its objects and weights, once its statistics are computed
    /// ([`Splits::content`]).
    content: Option<Content>,
    children: Vec<Children>,
}

/// What identifies a cell's objects and weights: their hash, and the entry remembering
/// them (none when the memo was full), the same for every cell with the same objects
/// and weights.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Content {
    pub hash: u64,
    pub entry: Option<u32>,
}

/// The statistics computed so far, by the objects and weights they were computed for: a
/// set of objects met again (by another path, or after [`Splits::forget_since`]) reads
/// its statistics back. Exact: a hit compares the objects and weights themselves, not
/// only their hash. Bounded: past [`Memo::MAX_BYTES`] nothing more is remembered, which
/// costs time, never a different statistic.
#[derive(Default)]
struct Memo {
    /// Entries by the hash of their objects and weights.
    by_hash: BTreeMap<u64, Vec<usize>>,
    entries: Vec<Remembered>,
    bytes: usize,
}

/// One set of objects, their weights (as bits; none when every weight is 1) and its
/// statistics.
struct Remembered {
    objects: Box<[u32]>,
    weights: Option<Box<[u64]>>,
    stats: Arc<[Stat]>,
}

impl Memo {
    /// The most bytes of objects, weights and statistics remembered per trie (a fit may
    /// hold several: CVT's fourteen, one per fold and kind).
    const MAX_BYTES: usize = 64 << 20;

    fn hash(objects: &[u32], weights: &[f64]) -> u64 {
        // FNV-1a over whole words: enough spread for a hash map whose hits are checked.
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for &o in objects {
            h = (h ^ u64::from(o)).wrapping_mul(0x0100_0000_01b3);
        }
        for &w in weights {
            h = (h ^ w.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
        h ^ (h >> 29)
    }

    /// The entry and statistics remembered for `objects` with `weights` (all 1 where
    /// `unit`).
    fn get(
        &self,
        hash: u64,
        objects: &[u32],
        weights: &[f64],
        unit: bool,
    ) -> Option<(u32, Arc<[Stat]>)> {
        self.by_hash.get(&hash)?.iter().find_map(|&i| {
            let e = &self.entries[i];
            let same_weights = match &e.weights {
                None => unit,
                Some(bits) => {
                    !unit
                        && bits.len() == weights.len()
                        && bits.iter().zip(weights).all(|(a, b)| *a == b.to_bits())
                }
            };
            (same_weights && *e.objects == *objects).then(|| (i as u32, Arc::clone(&e.stats)))
        })
    }

    fn insert(
        &mut self,
        hash: u64,
        objects: &[u32],
        weights: &[f64],
        unit: bool,
        stats: &Arc<[Stat]>,
    ) -> Option<u32> {
        // The objects, the weights unless all are 1, the statistics, and about 96 bytes
        // of boxes, entry and map.
        let bytes = objects.len() * if unit { 4 } else { 12 }
            + stats.len() * std::mem::size_of::<Stat>()
            + 96;
        if self.bytes + bytes > Memo::MAX_BYTES {
            return None;
        }
        self.bytes += bytes;
        self.by_hash
            .entry(hash)
            .or_default()
            .push(self.entries.len());
        self.entries.push(Remembered {
            objects: objects.into(),
            weights: (!unit).then(|| weights.iter().map(|w| w.to_bits()).collect()),
            stats: Arc::clone(stats),
        });
        Some(self.entries.len() as u32 - 1)
    }
}

/// The trie over one set of objects, for one kind of statistics.
pub(crate) struct Splits<'a> {
    frame: &'a Frame,
    /// The root's objects: the frame's row of each position.
    rows: Vec<u32>,
    /// The class of each root position.
    class_of: Vec<u32>,
    /// For each feature, its values ranked (nothing for a nominal feature).
    ranked: Vec<Ranked>,
    memo: Memo,
    mc: &'a MisclassCosts,
    classes: usize,
    min_objects: f64,
    /// DTMC's statistics (costs) instead of information gain.
    cost_based: bool,
    /// C4.5's charge for choosing among thresholds.
    threshold_penalty: bool,
    cells: Vec<Cell>,
    scratch: Scratch,
    /// The cell of every children list made, in order, so that [`Splits::forget_since`]
    /// can drop the ones made after a [`Mark`].
    made: Vec<u32>,
    /// Once it is requested, no cell offers a test ([`Splits::watch`]).
    stop: Option<&'a Stop>,
    /// The most tally slots per object of a node ([`Splits::tallies`]): [`TALLY_SLOTS`]
    /// but in the tests that compare the ways (0: no use of the groups of equal values
    /// at all, as before they were).
    tally_slots: usize,
}

/// A point in a trie's growth ([`Splits::mark`]) to forget what grew after it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mark {
    cells: usize,
    made: usize,
}

/// C4.5's least branch size for a split of `known` weight among `classes` classes.
fn min_split(min_objects: f64, classes: usize, known: f64) -> f64 {
    (0.1 * known / classes as f64).clamp(min_objects, 25.0_f64.max(min_objects))
}

/// The whole numbers below which `x log2 x` is read from a table.
const TABLE: usize = 4096;

/// `i log2 i` for `i` below [`TABLE`] (0 at 0).
fn xlog2x_table() -> &'static [f64; TABLE] {
    static VALUES: std::sync::OnceLock<Box<[f64; TABLE]>> = std::sync::OnceLock::new();
    VALUES.get_or_init(|| {
        let mut table = Box::new([0.0; TABLE]);
        for (i, v) in table.iter_mut().enumerate().skip(1) {
            *v = i as f64 * (i as f64).log2();
        }
        table
    })
}

/// `x log2 x`, read from a table for the small whole numbers that unweighted objects
/// give (0 at 0).
fn xlog2x(x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x < TABLE as f64 {
        // `x as u32` truncates (0 < x < TABLE here): a whole number comes back unchanged.
        let i = x as u32;
        if f64::from(i) == x {
            return xlog2x_table()[i as usize % TABLE];
        }
    }
    x * x.log2()
}

/// `n log2 n` for a whole number `n`, as [`xlog2x`] gives it for `n as f64`.
fn nlog2n(table: &[f64; TABLE], n: u32) -> f64 {
    match table.get(n as usize) {
        Some(&v) => v,
        None => {
            let x = f64::from(n);
            x * x.log2()
        }
    }
}

/// `total * entropy(weights)`, as `total log2 total - sum w log2 w`, from the terms
/// `xlog2x(w)` of the weights (kept up to date as a threshold moves).
fn entropy_of_terms(terms: &[f64], total: f64) -> f64 {
    let mut h = xlog2x(total);
    for &t in terms {
        h -= t;
    }
    h.max(0.0)
}

pub(crate) fn entropy(weights: &[f64], total: f64) -> f64 {
    if total <= 0.0 {
        return 0.0;
    }
    let mut h = 0.0;
    for &w in weights {
        if w > 0.0 {
            let p = w / total;
            h -= p * p.log2();
        }
    }
    h
}

/// `-sum p log2 p` over the parts of a total.
fn split_information(parts: impl Iterator<Item = f64>, total: f64) -> f64 {
    let mut h = 0.0;
    for w in parts {
        if w > 0.0 {
            let p = w / total;
            h -= p * p.log2();
        }
    }
    h
}

/// Reusable buffers for scoring splits.
struct Scratch {
    /// Per value, per class (nominal features).
    branch: Vec<f64>,
    /// (value, class, weight) of the objects with a known value, for numeric features.
    sorted: Vec<(f64, u32, f64)>,
    /// (rank, position) of the objects with a known value, to sort.
    keys: Vec<u64>,
    /// The ranks of the objects with a known value, to sort (objects of weight 1).
    ranks: Vec<u32>,
    /// Per class, whole counts: known, then on the left (objects of weight 1); in a
    /// split, the objects of each branch with a known value.
    counts: Vec<u32>,
    /// Per root position, its position in the node whose statistics are computed, for a
    /// node of weighted objects that reads its orders off a set of ranks ([`NO_RANK`]
    /// elsewhere).
    slot: Vec<u32>,
    /// A set of ranks among the root's objects, a bit each (empty between uses).
    bits: Vec<u64>,
    /// Per class: known weight, missing weight, and five buffers of numeric scans.
    classes: Vec<f64>,
    /// Per value of a nominal feature, the weight of its branch.
    sizes: Vec<f64>,
    /// Per group and class of a numeric feature, the node's objects (zero between uses).
    tally: Vec<u32>,
    /// The entropy of a node of weight 1, once a feature has computed it.
    node_entropy: Option<f64>,
    /// For a node of weight 1, `p log2 p` of each share `w / total` of it (`w` whole) a
    /// split information has needed (NaN for the others; empty until one does).
    split_terms: Vec<f64>,
    /// Per object of a cell being split, its branch ([`NO_BRANCH`] where its value is
    /// missing).
    of: Vec<u32>,
}

impl Scratch {
    /// Empty buffers for statistics over `classes` classes.
    fn new(classes: usize) -> Scratch {
        Scratch {
            branch: Vec::new(),
            sorted: Vec::new(),
            keys: Vec::new(),
            ranks: Vec::new(),
            counts: Vec::new(),
            slot: Vec::new(),
            bits: Vec::new(),
            classes: vec![0.0; 7 * classes],
            sizes: Vec::new(),
            tally: Vec::new(),
            node_entropy: None,
            split_terms: Vec::new(),
            of: Vec::new(),
        }
    }
}

/// The best threshold of a numeric feature over objects of weight 1, the thresholds
/// offered in increasing order: each side's entropy from whole counts, read from the
/// table.
struct WholeScan {
    table: &'static [f64; TABLE],
    /// The objects with a known value.
    all: u32,
    known_total: f64,
    /// The least weight of a branch.
    min: f64,
    /// The thresholds compared.
    tested: usize,
    /// The best so far: its quality, threshold and weight on the left.
    best: Option<(f64, f64, f64)>,
}

impl WholeScan {
    /// The threshold between `value` and `next` (the greater), with `left` objects
    /// below it, `left_n` of each class, of `known_n` in all.
    #[inline]
    fn offer(&mut self, left: u32, known_n: &[u32], left_n: &[u32], value: f64, next: f64) {
        let left_total = f64::from(left);
        let right_total = self.known_total - left_total;
        if left_total < self.min || right_total < self.min {
            return;
        }
        self.tested += 1;
        let table = self.table;
        let mut h_left = nlog2n(table, left);
        let mut h_right = nlog2n(table, self.all - left);
        for (&kn, &ln) in known_n.iter().zip(left_n) {
            h_left -= nlog2n(table, ln);
            h_right -= nlog2n(table, kn - ln);
        }
        let quality = -(h_left.max(0.0) + h_right.max(0.0));
        if self.best.is_none_or(|(q, _, _)| quality > q) {
            self.best = Some((quality, threshold_between(value, next), left_total));
        }
    }
}

/// The mark of a position of a numeric feature's largest group in its tally slot.
const DOMINANT: u32 = 1 << 31;

/// The counters per class a numeric feature's largest group is tallied on.
const SINKS: usize = 8;

/// The most tally slots per object of a node for [`Splits::tallies`].
const TALLY_SLOTS: usize = 16;

/// The first index from `from` on where `tally` is not zero.
#[inline]
fn next_nonzero(tally: &[u32], from: usize) -> Option<usize> {
    // Eight at a time, where the whole eight can be read together.
    let mut i = from;
    while let Some(block) = tally.get(i..i + 8) {
        if block.iter().fold(0, |a, &t| a | t) != 0 {
            break;
        }
        i += 8;
    }
    tally.get(i..)?.iter().position(|&t| t != 0).map(|p| i + p)
}

/// The rank of a missing value.
const NO_RANK: u32 = u32::MAX;

/// The branch of a missing value.
const NO_BRANCH: u32 = u32::MAX;

/// Sets in `bits` (empty, or sized for `ranks` ranks) the rank of each of `objects` whose
/// value is known.
fn set_ranks(bits: &mut Vec<u64>, ranks: usize, objects: &[u32], rank: &[u32]) {
    bits.resize(ranks.div_ceil(64), 0);
    for &o in objects {
        let r = rank[o as usize];
        if r != NO_RANK {
            bits[(r >> 6) as usize] |= 1 << (r & 63);
        }
    }
}

/// Each rank set in `bits`, in increasing order, to `each`; `bits` is left empty.
fn take_ranks(bits: &mut [u64], mut each: impl FnMut(u32)) {
    for (i, word) in bits.iter_mut().enumerate() {
        let mut w = std::mem::take(word);
        while w != 0 {
            each(((i as u32) << 6) | w.trailing_zeros());
            w &= w - 1;
        }
    }
}

/// A numeric feature's values among the root's objects, in the order of the root's sort
/// (by value, ties by position): each position's rank ([`NO_RANK`] where the value is
/// missing), and the value and class of the object of each rank.
#[derive(Clone, Default)]
struct Ranked {
    rank: Vec<u32>,
    /// The position of each rank.
    object: Vec<u32>,
    value: Vec<f64>,
    class: Vec<u32>,
    /// Its values in groups of equal ones, where no root object misses it.
    groups: Option<Groups>,
}

/// A numeric feature's values among the root's objects (none missing) in groups of values
/// equal bit for bit, in the root's order: a node can tally its objects per group and
/// class instead of putting them in order ([`Splits::tallies`]).
#[derive(Clone)]
struct Groups {
    /// Each root position's tally slot: its group times the classes plus its class; in
    /// the largest group, [`DOMINANT`] plus its class.
    slot: Vec<u32>,
    /// The value of each group.
    value: Vec<f64>,
    /// The largest group (the first of the largest). Its objects are tallied apart, on
    /// [`SINKS`] counters per class in turn, so that their counts do not wait on each
    /// other.
    dominant: usize,
}

impl Groups {
    /// The groups of the root positions `known` (every one, in the root's order), of
    /// values `value` and classes `class` among `classes`; none where a slot would reach
    /// [`DOMINANT`].
    fn new(known: &[u32], value: &[f64], class: &[u32], classes: usize) -> Option<Groups> {
        if (known.len() + 1) * classes >= DOMINANT as usize {
            return None;
        }
        let mut group = vec![0; known.len()];
        let (mut values, mut sizes): (Vec<f64>, Vec<usize>) = (Vec::new(), Vec::new());
        for (&p, &v) in known.iter().zip(value) {
            match (values.last(), sizes.last_mut()) {
                (Some(last), Some(size)) if last.to_bits() == v.to_bits() => *size += 1,
                _ => {
                    values.push(v);
                    sizes.push(1);
                }
            }
            group[p as usize] = values.len() - 1;
        }
        let dominant = sizes
            .iter()
            .enumerate()
            .fold(
                (0, 0),
                |(d, n), (g, &s)| if s > n { (g, s) } else { (d, n) },
            )
            .0;
        let mut slot = vec![0; known.len()];
        for (&p, &c) in known.iter().zip(class) {
            let g = group[p as usize];
            slot[p as usize] = if g == dominant {
                DOMINANT | c
            } else {
                (g * classes) as u32 + c
            };
        }
        Some(Groups {
            slot,
            value: values,
            dominant,
        })
    }

    /// Whether every one of `objects` holds the largest group's value.
    fn all_dominant(&self, objects: &[u32]) -> bool {
        objects
            .iter()
            .all(|&o| self.slot[o as usize] & DOMINANT != 0)
    }

    /// `objects` tallied per group and class (`classes` of them) into `tally`, which is
    /// zero on entry and left zero past the groups' slots; the groups' slots returned.
    fn tally<'t>(&self, objects: &[u32], classes: usize, tally: &'t mut Vec<u32>) -> &'t mut [u32] {
        let slots = self.value.len() * classes;
        tally.resize(slots + SINKS * classes, 0);
        // Plain slices, so that the loop reads neither vector's length again.
        let (tally, slot) = (&mut tally[..], &self.slot[..]);
        for (i, &o) in objects.iter().enumerate() {
            let s = slot[o as usize];
            let sink = slots + (s & !DOMINANT) as usize * SINKS + i % SINKS;
            tally[std::hint::select_unpredictable(s & DOMINANT == 0, s as usize, sink)] += 1;
        }
        let d = self.dominant * classes;
        for c in 0..classes {
            let sinks = slots + c * SINKS..slots + (c + 1) * SINKS;
            tally[d + c] = tally[sinks.clone()].iter().sum();
            tally[sinks].fill(0);
        }
        &mut tally[..slots]
    }
}

impl<'a> Splits<'a> {
    /// The trie over the objects `rows` (weighted) of `frame`, for trees grown with
    /// `criterion` and `min_objects`; `mc` labels nodes and, for DTMC, scores splits.
    pub fn new(
        frame: &'a Frame,
        rows: &[usize],
        weights: &[f64],
        mc: &'a MisclassCosts,
        criterion: Criterion,
        min_objects: f64,
    ) -> Splits<'a> {
        let rows: Vec<u32> = rows.iter().map(|&r| r as u32).collect();
        let class_of: Vec<u32> = rows.iter().map(|&r| frame.class(r as usize)).collect();
        let ranked = (0..frame.feature_count())
            .map(|f| match frame.column(f) {
                Column::Numeric(x) => {
                    let mut known: Vec<u32> = (0..rows.len() as u32)
                        .filter(|&p| !x[rows[p as usize] as usize].is_nan())
                        .collect();
                    // Stable: equal values keep the order of their positions.
                    known.sort_by(|&a, &b| {
                        x[rows[a as usize] as usize].total_cmp(&x[rows[b as usize] as usize])
                    });
                    let mut rank = vec![NO_RANK; rows.len()];
                    for (k, &p) in known.iter().enumerate() {
                        rank[p as usize] = k as u32;
                    }
                    let value: Vec<f64> = known
                        .iter()
                        .map(|&p| x[rows[p as usize] as usize])
                        .collect();
                    let class: Vec<u32> = known.iter().map(|&p| class_of[p as usize]).collect();
                    let groups = (known.len() == rows.len())
                        .then(|| Groups::new(&known, &value, &class, frame.class_count()))
                        .flatten();
                    Ranked {
                        rank,
                        object: known,
                        value,
                        class,
                        groups,
                    }
                }
                Column::Nominal { .. } => Ranked::default(),
            })
            .collect();
        let classes = frame.class_count();
        let mut splits = Splits {
            frame,
            rows,
            class_of,
            ranked,
            memo: Memo::default(),
            mc,
            classes,
            min_objects,
            cost_based: matches!(criterion, Criterion::Dtmc),
            threshold_penalty: matches!(criterion, Criterion::C45),
            cells: Vec::new(),
            made: Vec::new(),
            stop: None,
            scratch: Scratch::new(classes),
            tally_slots: TALLY_SLOTS,
        };
        let objects: Vec<u32> = (0..splits.rows.len() as u32).collect();
        let class_weights = splits.class_weights(&objects, weights);
        splits.cells.push(Cell {
            objects,
            weights: weights.to_vec(),
            total: weights.iter().sum(),
            unit: weights.iter().all(|&w| w == 1.0),
            path: Vec::new(),
            class_weights,
            held_rows: Vec::new(),
            held_weights: Vec::new(),
            held_classes: Vec::new(),
            stats: None,
            content: None,
            children: Vec::new(),
        });
        splits
    }

    /// A trie over the same root objects, of the same kind and watching the same stop,
    /// with nothing grown below its root and nothing remembered: one for another thread
    /// to value cells of this one in ([`adopt`](Splits::adopt)). Its statistics are this
    /// trie's, bit for bit (they depend on a cell's objects and weights alone).
    pub fn sibling(&self) -> Splits<'a> {
        let mut sibling = Splits {
            frame: self.frame,
            rows: self.rows.clone(),
            class_of: self.class_of.clone(),
            ranked: self.ranked.clone(),
            memo: Memo::default(),
            mc: self.mc,
            classes: self.classes,
            min_objects: self.min_objects,
            cost_based: self.cost_based,
            threshold_penalty: self.threshold_penalty,
            cells: Vec::new(),
            made: Vec::new(),
            stop: self.stop,
            scratch: Scratch::new(self.classes),
            tally_slots: self.tally_slots,
        };
        sibling.adopt(self, 0);
        sibling
    }

    /// The features a cell may be split on.
    pub fn feature_count(&self) -> usize {
        self.frame.feature_count()
    }

    /// Cell `c` of `other`, a trie over the same root objects (its
    /// [`sibling`](Splits::sibling)), made a cell of this one with the same objects,
    /// weights and path (not its held-out objects): the index of the new cell, which
    /// [`forget_since`](Splits::forget_since) a mark taken before drops.
    pub fn adopt(&mut self, other: &Splits<'_>, c: u32) -> u32 {
        let cell = &other.cells[c as usize];
        self.cells.push(Cell {
            objects: cell.objects.clone(),
            weights: cell.weights.clone(),
            total: cell.total,
            unit: cell.unit,
            path: cell.path.clone(),
            class_weights: cell.class_weights.clone(),
            ..Cell::placeholder()
        });
        self.cells.len() as u32 - 1
    }

    /// Also sends the objects `held_out` of the frame down every split made, to score
    /// trees on them without classifying them one by one
    /// ([`CostTree::held_out_cost`](super::CostTree)); call before any split is made.
    pub fn hold_out(&mut self, held_out: &[usize]) {
        let rows: Vec<u32> = held_out.iter().map(|&r| r as u32).collect();
        let weights = vec![1.0; rows.len()];
        let classes = self.row_class_weights(&rows, &weights);
        let root = &mut self.cells[0];
        root.held_rows = rows;
        root.held_weights = weights;
        root.held_classes = classes;
    }

    /// Offers no more tests once `stop` is requested: [`stats`](Splits::stats) answers
    /// none, so every walk down the trie ends where it stands.
    pub fn watch(&mut self, stop: &'a Stop) {
        self.stop = Some(stop);
    }

    /// Whether the stop it watches was requested.
    pub fn stopped(&self) -> bool {
        self.stop.is_some_and(Stop::is_requested)
    }

    /// Where the trie's growth stands now.
    pub fn mark(&self) -> Mark {
        Mark {
            cells: self.cells.len(),
            made: self.made.len(),
        }
    }

    /// Forget the cells and children lists made since `mark` (the statistics computed
    /// since for older cells stay): the trie is as it was then, as far as any walk can
    /// tell, and takes the memory it took then plus those statistics. Everything a walk
    /// reads is a function of the objects reaching a cell, so making a cell again gives
    /// it again.
    pub fn forget_since(&mut self, mark: Mark) {
        for &c in self.made[mark.made..].iter().rev() {
            self.cells[c as usize].children.pop();
        }
        self.made.truncate(mark.made);
        self.cells.truncate(mark.cells);
    }

    /// Whether the statistics are DTMC's.
    pub fn cost_based(&self) -> bool {
        self.cost_based
    }

    /// Cell `c`.
    pub fn cell(&self, c: u32) -> &Cell {
        &self.cells[c as usize]
    }

    /// Cell `c`, to change.
    pub fn cell_mut(&mut self, c: u32) -> &mut Cell {
        &mut self.cells[c as usize]
    }

    /// The weight of objects in cell `c`.
    pub fn total(&self, c: u32) -> f64 {
        self.cells[c as usize].total
    }

    /// The statistics of every feature that can split cell `c` (none once the stop it
    /// watches is requested).
    pub fn stats(&mut self, c: u32) -> &[Stat] {
        if self.stopped() {
            return &[];
        }
        if self.cells[c as usize].stats.is_some() {
        } else if self.cells[c as usize].total < 2.0 * self.min_objects - 1e-6 {
            // No test can leave the least branch size on two branches.
            self.cells[c as usize].stats = Some(Arc::from([]));
        } else {
            let cell = std::mem::replace(&mut self.cells[c as usize], Cell::placeholder());
            let hash = Memo::hash(&cell.objects, &cell.weights);
            let (entry, stats) = match self.memo.get(hash, &cell.objects, &cell.weights, cell.unit)
            {
                Some((entry, stats)) => (Some(entry), stats),
                None => {
                    #[cfg(feature = "work-counts")]
                    super::work::scored(cell.objects.len());
                    let rank_set = self.reads_rank_set(cell.objects.len());
                    // What the features of a node of weight 1 share, computed on first use.
                    self.scratch.node_entropy = None;
                    self.scratch.split_terms.clear();
                    // Where each object sits in the cell, for the weighted numeric scan
                    // (objects of weight 1 need no weights, DTMC's scan is weighted).
                    let slots = rank_set && (!cell.unit || self.cost_based);
                    if slots {
                        let slot = &mut self.scratch.slot;
                        slot.resize(self.rows.len(), NO_RANK);
                        for (p, &o) in cell.objects.iter().enumerate() {
                            slot[o as usize] = p as u32;
                        }
                    }
                    let stats: Arc<[Stat]> = (0..self.frame.feature_count())
                        .filter_map(|f| self.stat(f, &cell, rank_set))
                        .collect();
                    if slots {
                        for &o in &cell.objects {
                            self.scratch.slot[o as usize] = NO_RANK;
                        }
                    }
                    let entry =
                        self.memo
                            .insert(hash, &cell.objects, &cell.weights, cell.unit, &stats);
                    (entry, stats)
                }
            };
            self.cells[c as usize] = cell;
            self.cells[c as usize].stats = Some(stats);
            self.cells[c as usize].content = Some(Content { hash, entry });
        }
        self.cells[c as usize].stats.as_deref().unwrap_or(&[])
    }

    /// What identifies cell `c`'s objects and weights, once [`stats`](Splits::stats) has
    /// been asked for a cell large enough to split (none before, or for a smaller one).
    pub fn content(&self, c: u32) -> Option<Content> {
        self.cells[c as usize].content
    }

    /// Whether a node of `m` objects reads each numeric feature's order off a set of its
    /// ranks (a bit per root object: `m` bits set, then a pass over `n / 64` words) rather
    /// than sorting its own ranks (`m log2 m`): the same order either way.
    fn reads_rank_set(&self, m: usize) -> bool {
        m as f64 * (m as f64).log2() > (self.rows.len() / 64) as f64 + m as f64
    }

    /// Whether a node of `m` objects of weight 1 scores the numeric feature `ranked` by
    /// tallying its objects per group and class, then walking the groups
    /// (`groups * classes` slots), rather than by ordering its objects: where no value is
    /// missing and the slots are few for the objects. The same thresholds and counts
    /// either way.
    fn tallies(&self, groups: &Groups, m: usize) -> bool {
        groups.value.len() * self.classes <= self.tally_slots.saturating_mul(m)
    }

    /// The weight per class of the root positions `objects`.
    fn class_weights(&self, objects: &[u32], weights: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.classes];
        for (&o, &w) in objects.iter().zip(weights) {
            out[self.class_of[o as usize] as usize] += w;
        }
        out
    }

    /// The weight per class of the frame's `rows`.
    fn row_class_weights(&self, rows: &[u32], weights: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.classes];
        for (&r, &w) in rows.iter().zip(weights) {
            out[self.frame.class(r as usize) as usize] += w;
        }
        out
    }

    /// The best split of `feature` for the node's objects, or `None` if it has none
    /// (too few objects with a known value, a single value, no gain).
    fn stat(&mut self, feature: usize, cell: &Cell, rank_set: bool) -> Option<Stat> {
        let (objects, weights) = (&cell.objects[..], &cell.weights[..]);
        let rows = &self.rows[..];
        let node_weights = &cell.class_weights[..];
        let k = self.classes;
        let total = cell.total;
        let dtmc = self.cost_based;
        match self.frame.column(feature) {
            Column::Nominal { values, codes } => {
                let v = values.len();
                let branch = &mut self.scratch.branch;
                branch.clear();
                branch.resize(v * k, 0.0);
                let (known, rest) = self.scratch.classes.split_at_mut(k);
                known.fill(0.0);
                for (&o, &w) in objects.iter().zip(weights) {
                    let code = codes[rows[o as usize] as usize];
                    if code != MISSING {
                        let c = self.class_of[o as usize] as usize;
                        branch[code as usize * k + c] += w;
                        known[c] += w;
                    }
                }
                let known_total: f64 = known.iter().sum();
                if known_total <= 0.0 {
                    return None;
                }
                let sizes = &mut self.scratch.sizes;
                sizes.clear();
                sizes.extend((0..v).map(|b| branch[b * k..(b + 1) * k].iter().sum::<f64>()));
                let min = min_split(self.min_objects, self.classes, known_total);
                if sizes.iter().filter(|&&s| s >= min).count() < 2 {
                    return None;
                }
                let share = known_total / total;
                if dtmc {
                    let with_missing = &mut rest[..k];
                    let after: f64 = (0..v)
                        .map(|b| {
                            let part = &branch[b * k..(b + 1) * k];
                            for (m, (w, (n, kn))) in with_missing
                                .iter_mut()
                                .zip(part.iter().zip(node_weights.iter().zip(&*known)))
                            {
                                *m = w + (n - kn) * sizes[b] / known_total;
                            }
                            self.mc.best(with_missing).1
                        })
                        .sum();
                    let before = self.mc.best(node_weights).1;
                    return Some(Stat {
                        feature,
                        at: None,
                        gain: before - after,
                        split_info: 1.0,
                        exp2_gain: 0.0,
                    });
                }
                let after: f64 = (0..v)
                    .map(|b| sizes[b] * entropy(&branch[b * k..(b + 1) * k], sizes[b]))
                    .sum::<f64>()
                    / known_total;
                let gain = share * (entropy(known, known_total) - after);
                let split_info =
                    split_information(sizes.iter().copied().chain([total - known_total]), total);
                Some(Stat {
                    feature,
                    at: None,
                    gain,
                    split_info,
                    exp2_gain: gain.exp2() - 1.0,
                })
            }
            Column::Numeric(_) if cell.unit && !dtmc => {
                // Objects of weight 1: the same scan as below over whole counts, each
                // entropy term read from the table by count (the very values `xlog2x`
                // gives the weights, which are these counts, exactly).
                let ranked = &self.ranked[feature];
                // The feature's groups, unless the tests compare without them.
                let groups = ranked.groups.as_ref().filter(|_| self.tally_slots > 0);
                if groups.is_some_and(|g| g.all_dominant(objects)) {
                    // Every object holds the same value (the root's commonest): no
                    // threshold.
                    return None;
                }
                let tallied = groups.filter(|g| self.tallies(g, objects.len()));
                let keys = &mut self.scratch.ranks;
                keys.clear();
                if tallied.is_some() {
                    // No value missing: every object is known.
                } else if rank_set {
                    let bits = &mut self.scratch.bits;
                    set_ranks(bits, ranked.object.len(), objects, &ranked.rank);
                    take_ranks(bits, |r| keys.push(r));
                } else {
                    keys.extend(
                        objects
                            .iter()
                            .map(|&o| ranked.rank[o as usize])
                            .filter(|&r| r != NO_RANK),
                    );
                    keys.sort_unstable();
                }
                let all = if tallied.is_some() {
                    objects.len()
                } else {
                    keys.len()
                };
                if all < 2 {
                    return None;
                }
                let counts = &mut self.scratch.counts;
                counts.clear();
                counts.resize(2 * k, 0);
                let (known_n, left_n) = counts.split_at_mut(k);
                if all == objects.len() {
                    // Every object's value known: the node's own counts (whole weights).
                    for (n, &w) in known_n.iter_mut().zip(node_weights) {
                        *n = w as u32;
                    }
                } else {
                    for &r in keys.iter() {
                        known_n[ranked.class[r as usize] as usize] += 1;
                    }
                }
                let known = &mut self.scratch.classes[..k];
                for (w, &n) in known.iter_mut().zip(&*known_n) {
                    *w = f64::from(n);
                }
                let known_total: f64 = known.iter().sum();
                let base = if all == objects.len() {
                    // The node's own entropy, the same for every feature known throughout.
                    *self
                        .scratch
                        .node_entropy
                        .get_or_insert_with(|| entropy(known, known_total))
                } else {
                    entropy(known, known_total)
                };
                let mut scan = WholeScan {
                    table: xlog2x_table(),
                    all: all as u32,
                    known_total,
                    min: min_split(self.min_objects, self.classes, known_total),
                    tested: 0,
                    best: None,
                };
                if let Some(groups) = tallied {
                    // Each group's count per class, then the groups in the root's order:
                    // a threshold wherever the next group present has a greater value,
                    // with the counts the object by object scan has there.
                    let tally = groups.tally(objects, k, &mut self.scratch.tally);
                    let mut left = 0u32;
                    let mut value: Option<f64> = None;
                    let mut from = 0;
                    while let Some(s) = next_nonzero(tally, from) {
                        let g = s / k;
                        from = (g + 1) * k;
                        let group = &mut tally[g * k..from];
                        let n: u32 = group.iter().sum();
                        let next = groups.value[g];
                        if let Some(value) = value
                            && next > value
                        {
                            scan.offer(left, known_n, left_n, value, next);
                        }
                        for (l, t) in left_n.iter_mut().zip(group.iter_mut()) {
                            *l += std::mem::take(t);
                        }
                        left += n;
                        value = Some(next);
                        if left == scan.all {
                            // The groups after the last present are empty, as the tally
                            // is left between uses.
                            break;
                        }
                    }
                } else {
                    // The rank order's columns and the node's ranks as plain slices, read
                    // once (the loop writes only the counts).
                    let (class, values, keys) = (&ranked.class[..], &ranked.value[..], &keys[..]);
                    let mut next = values[keys[0] as usize];
                    for i in 0..keys.len() - 1 {
                        left_n[class[keys[i] as usize] as usize] += 1;
                        let value = next;
                        next = values[keys[i + 1] as usize];
                        if next <= value {
                            continue;
                        }
                        scan.offer(i as u32 + 1, known_n, left_n, value, next);
                    }
                }
                let (quality, at, left_total) = scan.best?;
                self.information_stat(
                    feature,
                    quality,
                    at,
                    [left_total, known_total, total],
                    base,
                    scan.tested,
                    true,
                )
            }
            Column::Numeric(_) => {
                // The objects with a known value in the order of the root's sort.
                let ranked = &self.ranked[feature];
                let keys = &mut self.scratch.keys;
                keys.clear();
                if rank_set {
                    let (bits, slot) = (&mut self.scratch.bits, &self.scratch.slot);
                    set_ranks(bits, ranked.object.len(), objects, &ranked.rank);
                    let object = &ranked.object[..];
                    take_ranks(bits, |r| {
                        let p = slot[object[r as usize] as usize];
                        keys.push((u64::from(r) << 32) | u64::from(p));
                    });
                } else {
                    for (p, &o) in objects.iter().enumerate() {
                        let r = ranked.rank[o as usize];
                        if r != NO_RANK {
                            keys.push((u64::from(r) << 32) | p as u64);
                        }
                    }
                    keys.sort_unstable();
                }
                let sorted = &mut self.scratch.sorted;
                sorted.clear();
                for &key in keys.iter() {
                    let r = (key >> 32) as usize;
                    let p = (key & u64::from(u32::MAX)) as usize;
                    sorted.push((ranked.value[r], ranked.class[r], weights[p]));
                }
                if sorted.len() < 2 {
                    return None;
                }
                let buffers = &mut self.scratch.classes[..7 * k];
                buffers.fill(0.0);
                let (known, rest) = buffers.split_at_mut(k);
                let (missing, rest) = rest.split_at_mut(k);
                for &(_, c, w) in sorted.iter() {
                    known[c as usize] += w;
                }
                let known_total: f64 = known.iter().sum();
                let min = min_split(self.min_objects, self.classes, known_total);
                let base = entropy(known, known_total);
                for (m, (n, kn)) in missing.iter_mut().zip(node_weights.iter().zip(&*known)) {
                    *m = n - kn;
                }
                let before_cost = if dtmc {
                    self.mc.best(node_weights).1
                } else {
                    0.0
                };
                let (left, rest) = rest.split_at_mut(k);
                let (right, rest) = rest.split_at_mut(k);
                let (mixed, rest) = rest.split_at_mut(k);
                // `xlog2x` of each class's weight on the left and on the right, kept as
                // objects move left: each side's weighted entropy from the same terms
                // in the same order, computed once per object instead of once per
                // threshold.
                let (left_terms, right_terms) = rest.split_at_mut(k);
                if !dtmc {
                    for j in 0..k {
                        right_terms[j] = xlog2x(known[j]);
                    }
                }
                let mut left_total = 0.0;
                let mut best: Option<(f64, f64, f64)> = None; // (value, at, left_total)
                let mut tested = 0usize;
                for i in 0..sorted.len() - 1 {
                    let (value, c, w) = sorted[i];
                    left[c as usize] += w;
                    left_total += w;
                    if !dtmc {
                        let c = c as usize;
                        left_terms[c] = xlog2x(left[c]);
                        right_terms[c] = xlog2x(known[c] - left[c]);
                    }
                    let next = sorted[i + 1].0;
                    if next <= value {
                        continue;
                    }
                    let right_total = known_total - left_total;
                    if left_total < min || right_total < min {
                        continue;
                    }
                    tested += 1;
                    let quality = if dtmc {
                        for j in 0..k {
                            right[j] = known[j] - left[j];
                        }
                        let share_left = left_total / known_total;
                        let mut cost = 0.0;
                        for (side, s) in [(&*left, share_left), (&*right, 1.0 - share_left)] {
                            for j in 0..k {
                                mixed[j] = side[j] + missing[j] * s;
                            }
                            cost += self.mc.best(mixed).1;
                        }
                        -cost
                    } else {
                        -(entropy_of_terms(left_terms, left_total)
                            + entropy_of_terms(right_terms, right_total))
                    };
                    if best.is_none_or(|(q, _, _)| quality > q) {
                        best = Some((quality, threshold_between(value, next), left_total));
                    }
                }
                let (quality, at, left_total) = best?;
                if dtmc {
                    return Some(Stat {
                        feature,
                        at: Some(at),
                        gain: before_cost + quality,
                        split_info: 1.0,
                        exp2_gain: 0.0,
                    });
                }
                self.information_stat(
                    feature,
                    quality,
                    at,
                    [left_total, known_total, total],
                    base,
                    tested,
                    false,
                )
            }
        }
    }

    /// A numeric test's statistics from its best threshold `at` of quality `quality`
    /// (minus the weighted entropy after the split): the weights left of it, with a
    /// known value and in all are `left_total`, `known_total` and `total`; `base` is the
    /// entropy of the known ones, `tested` the thresholds compared. `whole` where the
    /// objects are of weight 1 (the weights are whole numbers up to the node's count).
    #[expect(
        clippy::too_many_arguments,
        reason = "one numeric scan's outcome, in parts"
    )]
    fn information_stat(
        &mut self,
        feature: usize,
        quality: f64,
        at: f64,
        [left_total, known_total, total]: [f64; 3],
        base: f64,
        tested: usize,
        whole: bool,
    ) -> Option<Stat> {
        let right_total = known_total - left_total;
        let share = known_total / total;
        let mut gain = share * (base + quality / known_total);
        if self.threshold_penalty && tested > 1 {
            // C4.5 (release 8) charges the choice among thresholds.
            gain -= (tested as f64).log2() / total;
        }
        let parts = [left_total, right_total, total - known_total];
        let split_info = if whole {
            // The same terms, each computed once per node (the weights are whole, up to
            // the node's count).
            let terms = &mut self.scratch.split_terms;
            if terms.is_empty() {
                terms.resize(total as usize + 1, f64::NAN);
            }
            let mut h = 0.0;
            for w in parts {
                if w > 0.0 {
                    let t = &mut terms[w as usize];
                    if t.is_nan() {
                        let p = w / total;
                        *t = p * p.log2();
                    }
                    h -= *t;
                }
            }
            h
        } else {
            split_information(parts.into_iter(), total)
        };
        Some(Stat {
            feature,
            at: Some(at),
            gain,
            split_info,
            exp2_gain: gain.exp2() - 1.0,
        })
    }

    /// The children of cell `c` for `stat`'s test, made on first use: the objects with a
    /// known value go to their branch, the others to every branch with their weight split
    /// as the known ones split.
    pub fn children(&mut self, c: u32, stat: &Stat) -> &Children {
        let index = self.made_children(c, stat);
        &self.cells[c as usize].children[index]
    }

    /// The cell of branch `b` of cell `c`'s children list `list` (an index from
    /// [`made_children`](Splits::made_children)), `None` where no object goes.
    pub fn child(&self, c: u32, list: usize, b: usize) -> Option<u32> {
        self.cells[c as usize].children[list].cells[b]
    }

    /// The branches of cell `c`'s children list `list`.
    pub fn branches(&self, c: u32, list: usize) -> usize {
        self.cells[c as usize].children[list].cells.len()
    }

    /// The index among cell `c`'s children lists of `stat`'s, made on first use; it stays
    /// valid until [`forget_since`](Splits::forget_since) a mark taken before it was made.
    pub fn made_children(&mut self, c: u32, stat: &Stat) -> usize {
        let found = self.cells[c as usize]
            .children
            .iter()
            .position(|ch| ch.feature == stat.feature);
        match found {
            Some(i) => i,
            None => {
                #[cfg(feature = "work-counts")]
                super::work::split();
                let made = self.split(c, stat);
                self.cells[c as usize].children.push(made);
                self.made.push(c);
                self.cells[c as usize].children.len() - 1
            }
        }
    }

    fn split(&mut self, c: u32, stat: &Stat) -> Children {
        let frame = self.frame;
        let feature = stat.feature;
        let column = frame.column(feature);
        let branches = match column {
            Column::Nominal { values, .. } => values.len(),
            Column::Numeric(_) => 2,
        };
        let at = stat.at.unwrap_or(0.0);
        let branch_of = |r: u32| -> Option<usize> {
            match column {
                Column::Nominal { codes, .. } => {
                    let code = codes[r as usize];
                    (code != MISSING).then_some(code as usize)
                }
                Column::Numeric(x) => {
                    let v = x[r as usize];
                    (!v.is_nan()).then(|| usize::from(v > at))
                }
            }
        };
        let cell = &self.cells[c as usize];
        // Each object's branch ([`NO_BRANCH`] for a missing value), the known weight and
        // the count of each branch, and how many values are missing, first: every child's
        // vectors are then made at their size.
        let (of, counts) = (&mut self.scratch.of, &mut self.scratch.counts);
        of.clear();
        counts.clear();
        counts.resize(branches, 0);
        let mut known_by_branch = vec![0.0; branches];
        let mut unknown = 0usize;
        for (&o, &w) in cell.objects.iter().zip(&cell.weights) {
            match branch_of(self.rows[o as usize]) {
                Some(b) => {
                    known_by_branch[b] += w;
                    counts[b] += 1;
                    of.push(b as u32);
                }
                None => {
                    unknown += 1;
                    of.push(NO_BRANCH);
                }
            }
        }
        let known_total: f64 = known_by_branch.iter().sum();
        let shares: Vec<f64> = known_by_branch.iter().map(|k| k / known_total).collect();
        // Each child's objects, weights and weight per class, added in the child's order
        // (the known objects in the cell's order, then those with a missing value), so
        // the sums are the ones a pass over the child would make.
        let k = self.classes;
        let mut parts: Vec<(Vec<u32>, Vec<f64>, Vec<f64>)> = (0..branches)
            .map(|b| {
                let size = counts[b] as usize + if shares[b] > 0.0 { unknown } else { 0 };
                (
                    Vec::with_capacity(size),
                    Vec::with_capacity(size),
                    vec![0.0; k],
                )
            })
            .collect();
        for ((&o, &w), &b) in cell.objects.iter().zip(&cell.weights).zip(of.iter()) {
            if b != NO_BRANCH {
                let part = &mut parts[b as usize];
                part.0.push(o);
                part.1.push(w);
                part.2[self.class_of[o as usize] as usize] += w;
            }
        }
        if unknown > 0 {
            for ((&o, &w), &b) in cell.objects.iter().zip(&cell.weights).zip(of.iter()) {
                if b != NO_BRANCH {
                    continue;
                }
                let class = self.class_of[o as usize] as usize;
                for (part, &share) in parts.iter_mut().zip(&shares) {
                    if share > 0.0 {
                        let weight = w * share;
                        part.0.push(o);
                        part.1.push(weight);
                        part.2[class] += weight;
                    }
                }
            }
        }
        // The held-out objects follow the same rule, with the training shares. Without
        // them (every tree but ICET's search) there is nothing to send or count.
        let mut held: Vec<(Vec<u32>, Vec<f64>)> = Vec::new();
        let mut held_out: Vec<Vec<f64>> = Vec::new();
        if !cell.held_rows.is_empty() {
            held = vec![(Vec::new(), Vec::new()); branches];
            for (&r, &w) in cell.held_rows.iter().zip(&cell.held_weights) {
                match branch_of(r) {
                    Some(b) => {
                        held[b].0.push(r);
                        held[b].1.push(w);
                    }
                    None => {
                        for (b, part) in held.iter_mut().enumerate() {
                            if shares[b] > 0.0 {
                                part.0.push(r);
                                part.1.push(w * shares[b]);
                            }
                        }
                    }
                }
            }
            held_out = held
                .iter()
                .map(|(rows, weights)| self.row_class_weights(rows, weights))
                .collect();
        }
        // A child of a cell whose weights are all 1, with no value missing, has weights
        // of 1 too, and its total is its count.
        let whole = cell.unit && unknown == 0;
        let mut path = cell.path.clone();
        path.push(feature);
        let mut made = Vec::with_capacity(branches);
        let mut held = held.into_iter();
        for (b, (objects, weights, class_weights)) in parts.into_iter().enumerate() {
            let (held_rows, held_weights) = held.next().unwrap_or_default();
            if objects.is_empty() {
                made.push(None);
                continue;
            }
            let (total, unit) = if whole {
                (objects.len() as f64, true)
            } else {
                (weights.iter().sum(), weights.iter().all(|&w| w == 1.0))
            };
            self.cells.push(Cell {
                total,
                unit,
                objects,
                weights,
                path: path.clone(),
                class_weights,
                held_classes: held_out.get(b).cloned().unwrap_or_default(),
                held_rows,
                held_weights,
                stats: None,
                content: None,
                children: Vec::new(),
            });
            made.push(Some(self.cells.len() as u32 - 1));
        }
        Children {
            feature,
            at: stat.at,
            cells: made,
            shares,
            held_out,
        }
    }
}

impl Cell {
    /// The children made for a test of `feature`, if they were.
    pub fn children_for(&self, feature: usize) -> Option<&Children> {
        self.children.iter().find(|c| c.feature == feature)
    }

    fn placeholder() -> Cell {
        Cell {
            objects: Vec::new(),
            weights: Vec::new(),
            total: 0.0,
            unit: true,
            path: Vec::new(),
            class_weights: Vec::new(),
            held_rows: Vec::new(),
            held_weights: Vec::new(),
            held_classes: Vec::new(),
            stats: None,
            content: None,
            children: Vec::new(),
        }
    }
}

/// A threshold that separates `low` from `high` (`low < high`): an object goes right when
/// its value is above it, so it must be at least `low` and below `high`. Their midpoint
/// where it is one (always, but for extreme values); otherwise, where the sum overflows,
/// half of each; and where rounding lands on `high` (adjacent doubles), `low` itself.
pub(crate) fn threshold_between(low: f64, high: f64) -> f64 {
    let separates = |t: f64| low <= t && t < high;
    let mid = (low + high) / 2.0;
    if separates(mid) {
        return mid;
    }
    let halves = low / 2.0 + high / 2.0;
    if separates(halves) { halves } else { low }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// Every statistic of every cell down to depth three, each feature's split taken in
    /// turn, bit for bit.
    fn statistics(splits: &mut Splits<'_>) -> Vec<[u64; 5]> {
        let mut out = Vec::new();
        let mut cells = vec![(0u32, 0usize)];
        while let Some((c, depth)) = cells.pop() {
            let stats = splits.stats(c).to_vec();
            for s in &stats {
                out.push([
                    s.feature as u64,
                    s.at.map_or(u64::MAX, f64::to_bits),
                    s.gain.to_bits(),
                    s.split_info.to_bits(),
                    s.exp2_gain.to_bits(),
                ]);
                if depth < 3 {
                    let children = splits.children(c, s).cells.clone();
                    cells.extend(children.into_iter().flatten().map(|c| (c, depth + 1)));
                }
            }
        }
        out
    }

    /// A node's numeric statistics are the same whether its objects are tallied per group
    /// of equal values or put in order: few values and many (ties throughout, `-0.0`
    /// beside `0.0`), a sparse feature (nine objects in ten at 0, so that many nodes hold
    /// a single value), a feature with missing values, two, three and five classes, for
    /// EG2's statistics and C4.5's.
    #[test]
    fn tallied_and_ordered_scans_give_the_same_statistics() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let n = 300;
        for classes in [2u32, 3, 5] {
            let few = [-1.5, -0.0, 0.0, 0.25, 2.0];
            let columns = vec![
                Column::Numeric(
                    (0..n)
                        .map(|_| {
                            if rng.random_range(0..10) == 0 {
                                f64::from(rng.random_range(1..4u32))
                            } else {
                                0.0
                            }
                        })
                        .collect(),
                ),
                Column::Numeric(
                    (0..n)
                        .map(|_| few[rng.random_range(0..few.len())])
                        .collect(),
                ),
                Column::Numeric(
                    (0..n)
                        .map(|_| f64::from(rng.random_range(0..40u32)))
                        .collect(),
                ),
                Column::Numeric((0..n).map(|_| rng.random_range(-3.0..3.0)).collect()),
                Column::Numeric(
                    (0..n)
                        .map(|i| {
                            if i % 7 == 0 {
                                f64::NAN
                            } else {
                                f64::from(i as u32 % 9)
                            }
                        })
                        .collect(),
                ),
            ];
            // Classes that follow the second and third features in part, so that splits
            // gain.
            let (Column::Numeric(a), Column::Numeric(b)) = (&columns[1], &columns[2]) else {
                unreachable!()
            };
            let labels: Vec<u32> = (0..n)
                .map(|i| {
                    let noise = rng.random_range(0..classes);
                    if rng.random_range(0..3) == 0 {
                        noise
                    } else {
                        (u32::from(a[i] > 0.1) + u32::from(b[i] > 20.0)) % classes
                    }
                })
                .collect();
            let names = (0..columns.len()).map(|f| format!("x{f}")).collect();
            let class_names = (0..classes).map(|c| c.to_string()).collect();
            let frame = Frame::new(names, columns, labels, class_names).unwrap();
            let mc = MisclassCosts::uniform(classes as usize, 100.0).unwrap();
            let rows: Vec<usize> = (0..n).collect();
            let ones = vec![1.0; n];
            for criterion in [Criterion::Eg2 { w: 1.0 }, Criterion::C45] {
                let mut both = [0, usize::MAX].map(|tally_slots| {
                    let mut splits = Splits::new(&frame, &rows, &ones, &mc, criterion, 2.0);
                    splits.tally_slots = tally_slots;
                    statistics(&mut splits)
                });
                assert!(both[0].len() > 100, "{}", both[0].len());
                let [ordered, tallied] = &mut both;
                assert_eq!(ordered, tallied, "{classes} classes, {criterion:?}");
            }
        }
    }
}
