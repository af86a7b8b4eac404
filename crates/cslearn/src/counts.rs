//! Class counts of a node of the indexed learners' tree, kept so that a selection costs
//! time in proportion to the features, not to the classes.
//!
//! [`SplitCounts`](crate::SplitCounts) keeps its counts in sorted vectors and
//! [`InfoCost::select_from_counts`](crate::InfoCost::select_from_counts) scores a feature
//! by summing a term per (value, class) count and per class, in one fixed order: both cost
//! time in proportion to the classes, which is most of the work when the classes are as
//! many as the examples. [`NodeCounts`] keeps a node's counts as [`SplitCounts`] does
//! while the node has at most [`FEW_CLASSES`] classes (sorting and scoring every count is
//! cheap then); past that, in hash maps ([`Hashed`]), and beside them the
//! sums of `x log2 x` terms that the I^2/C score is made of, kept exactly (every term is a
//! multiple of 2^-52, so the sums are integers at that scale) and updated in time
//! independent of the classes as examples come and go.
//!
//! The selection must be the one the plain procedure makes, bit for bit, and the plain
//! procedure sums its terms in floating point, one after the other: an exact sum differs
//! from it in the last bits. So the exact sums only bound the plain procedure's score:
//! every rounding in the plain procedure's computation of a feature's gain (a sequence of
//! M additions and subtractions of non-negative terms whose total is A) is at most 2^-53
//! times the exact result of its operation, so the computed gain differs from the exact
//! one by at most A((1 + 2^-53)^M - 1), and the operations after it (a division by the
//! number of examples, `max(0)`, squaring, a division by the cost) are monotone. The
//! selection runs the rule of [`BestScore`](crate::BestScore) over these intervals; when
//! every comparison it makes has the same outcome over the whole intervals, that outcome
//! is the plain procedure's. When one does not (two scores closer than the bounds, or
//! near the relative 1e-9 of a tie), the node's counts are sorted and scored by the plain
//! procedure's own function. The selection is therefore the plain procedure's in every
//! case (`tests/indexed.rs` checks it against the plain learner, with many classes too).

use std::hash::{BuildHasherDefault, Hasher};

use crate::example::Example;
use crate::select::{Rules, SplitCounts, same_score, xlogx};
use crate::types::{ClassId, Cost, Costs, FeatureId, Value};

/// A fast, deterministic hasher for the small integer keys of the counts (the
/// multiplicative hash of rustc's `FxHasher`).
#[derive(Clone, Copy, Default)]
struct Fx(u64);

impl Fx {
    #[inline]
    fn mix(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for Fx {
    fn write(&mut self, bytes: &[u8]) {
        bytes.iter().for_each(|&b| self.mix(u64::from(b)));
    }

    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.mix(u64::from(i));
    }

    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.mix(i);
    }

    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
}

/// A hash map with the fixed hasher above: its iteration order is the same in every run
/// (no random state), and nothing here depends on it anyway (the exact fallback sorts,
/// the majority breaks ties by id), which is why the workspace's ban on `HashMap` (for
/// its random iteration order) does not apply.
#[expect(
    clippy::disallowed_types,
    reason = "a hash map with a fixed hasher: its iteration order never reaches a result (see above)"
)]
type FxMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<Fx>>;

/// 2^52: every `x log2 x` term is a multiple of 2^-52 (0 for x <= 1; at least 2, hence a
/// multiple of 2^-51, for x >= 2), so scaled by this it is an exact integer, below 2^90
/// for counts below 2^32; sums of up to 2^32 of them fit an `i128`.
const SCALE: f64 = 4_503_599_627_370_496.0;

/// `x log2 x` as the plain procedure computes it, scaled to an exact integer, for
/// every count seen so far.
#[derive(Clone, Debug, Default)]
pub(crate) struct Terms(Vec<i128>);

impl Terms {
    pub(crate) fn new() -> Terms {
        Terms(Vec::new())
    }

    #[inline]
    fn get(&mut self, x: u32) -> i128 {
        let i = x as usize;
        if i >= self.0.len() {
            let from = self.0.len();
            self.0.extend((from..=i.max(2 * from)).map(|k| {
                let scaled = xlogx(k as u32) * SCALE;
                debug_assert_eq!(scaled.fract(), 0.0, "x log2 x is a multiple of 2^-52");
                scaled as i128
            }));
        }
        self.0[i]
    }
}

/// One feature at a node: how many examples have it, how many distinct values and (value,
/// class) pairs they have, and the exact sums of the terms its score is made of.
#[derive(Clone, Debug)]
struct FeatureCounts {
    feature: FeatureId,
    /// Examples having the feature.
    having: u32,
    /// Distinct values among them.
    values: u32,
    /// Distinct (value, class) pairs among them.
    runs: u32,
    /// Sum over values of g(examples with the value), g = x log2 x scaled by [`SCALE`].
    value_terms: i128,
    /// Sum over (value, class) of g(examples with the value and class).
    run_terms: i128,
    /// Sum over classes of g(examples of the class) - g(those lacking the feature), over
    /// the classes of which some example has the feature (the others give 0).
    lacking_gap: i128,
    /// Sum over classes of g(examples of the class having the feature).
    having_terms: i128,
}

impl FeatureCounts {
    fn new(feature: FeatureId) -> FeatureCounts {
        FeatureCounts {
            feature,
            having: 0,
            values: 0,
            runs: 0,
            value_terms: 0,
            run_terms: 0,
            lacking_gap: 0,
            having_terms: 0,
        }
    }
}

/// The class counts of a set of examples, overall and by each feature's values, with the
/// exact sums that bound I^2/C scores (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Hashed {
    len: u32,
    /// Examples by class.
    classes: FxMap<ClassId, u32>,
    /// The features some counted example has, ascending.
    features: Vec<FeatureCounts>,
    /// Examples by (feature, value).
    values: FxMap<(FeatureId, Value), u32>,
    /// Examples by (feature, value, class).
    runs: FxMap<(FeatureId, Value, ClassId), u32>,
    /// Examples having the feature, by (feature, class).
    having: FxMap<(FeatureId, ClassId), u32>,
    /// Sum over classes of g(examples of the class).
    class_terms: i128,
    /// The majority class, while known: kept as examples are added, forgotten when the
    /// majority class loses one.
    majority: Option<ClassId>,
}

/// How many classes a node's counts may have before they move from sorted vectors to hash
/// maps with exact sums: below it, sorting and scoring every count is cheaper than keeping
/// the sums.
const FEW_CLASSES: usize = 32;

/// The class counts of a node of the index: [`SplitCounts`] while the node has few
/// classes, [`Hashed`] (with exact sums, see the module docs) once it has had more.
#[derive(Clone, Debug)]
pub(crate) enum NodeCounts {
    Sorted(SplitCounts),
    Hashed(Box<Hashed>),
}

impl Default for NodeCounts {
    fn default() -> NodeCounts {
        NodeCounts::Sorted(SplitCounts::new())
    }
}

impl NodeCounts {
    /// Counts that keep exact sums from the start, whatever the number of classes (for
    /// tests of the bounds with few classes).
    #[cfg(test)]
    fn hashed() -> NodeCounts {
        NodeCounts::Hashed(Box::default())
    }

    /// The number of examples counted.
    pub(crate) fn len(&self) -> u32 {
        match self {
            NodeCounts::Sorted(c) => c.len(),
            NodeCounts::Hashed(c) => c.len(),
        }
    }

    /// The number of counted examples of `class`.
    pub(crate) fn class_total(&self, class: ClassId) -> u32 {
        match self {
            NodeCounts::Sorted(c) => {
                let totals = c.totals();
                totals
                    .binary_search_by_key(&class, |t| t.0)
                    .map_or(0, |k| totals[k].1)
            }
            NodeCounts::Hashed(c) => c.class_total(class),
        }
    }

    /// The one class of every counted example, if there is exactly one.
    pub(crate) fn only_class(&self) -> Option<ClassId> {
        match self {
            NodeCounts::Sorted(c) => match c.totals() {
                [(class, _)] => Some(*class),
                _ => None,
            },
            NodeCounts::Hashed(c) => c.only_class(),
        }
    }

    /// The number of counted examples whose `feature` is `value`.
    pub(crate) fn having(&self, feature: FeatureId, value: Value) -> u32 {
        match self {
            NodeCounts::Sorted(c) => c.having(feature, value),
            NodeCounts::Hashed(c) => c.having(feature, value),
        }
    }

    /// The most frequent class, ties to the lowest id, as [`SplitCounts::majority`].
    pub(crate) fn majority(&mut self) -> Option<ClassId> {
        match self {
            NodeCounts::Sorted(c) => c.majority(),
            NodeCounts::Hashed(c) => c.majority(),
        }
    }

    /// Count `example` in.
    pub(crate) fn add(&mut self, example: &Example, terms: &mut Terms) {
        match self {
            NodeCounts::Sorted(c) => {
                c.add(example);
                if c.totals().len() > FEW_CLASSES {
                    *self = NodeCounts::Hashed(Box::new(Hashed::from_sorted(c, terms)));
                }
            }
            NodeCounts::Hashed(c) => c.add(example, terms),
        }
    }

    /// Count `example`, counted in before with the same pairs and class, out again.
    pub(crate) fn remove(&mut self, example: &Example, terms: &mut Terms) {
        match self {
            NodeCounts::Sorted(c) => c.remove(example),
            NodeCounts::Hashed(c) => c.remove(example, terms),
        }
    }

    /// [`InfoCost::select_from_counts`](crate::InfoCost::select_from_counts) on these
    /// counts, under `rules`: the same feature, bit for bit (see the module docs).
    /// `fallback` is scratch for the cases the bounds leave open.
    pub(crate) fn select<M, C>(
        &self,
        rules: Rules,
        is_measured: M,
        costs: &C,
        fallback: &mut Fallback,
    ) -> Option<FeatureId>
    where
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        match self {
            // `select_from_counts` itself.
            NodeCounts::Sorted(c) => rules.best(
                c.totals(),
                &mut fallback.having,
                c.features(),
                is_measured,
                costs,
            ),
            NodeCounts::Hashed(c) => c.select(rules, is_measured, costs, fallback),
        }
    }
}

/// Set `map[key]` to `count`, leaving no zero in the map.
fn set<K: std::hash::Hash + Eq>(map: &mut FxMap<K, u32>, key: K, count: u32) {
    if count == 0 {
        map.remove(&key);
    } else {
        map.insert(key, count);
    }
}

/// `g(t) - g(t - h)`: one class's share of a feature's `lacking_gap`.
#[inline]
fn gap(terms: &mut Terms, total: u32, having: u32) -> i128 {
    terms.get(total) - terms.get(total - having)
}

impl Hashed {
    /// The same counts as `sorted`, with their sums.
    fn from_sorted(sorted: &SplitCounts, terms: &mut Terms) -> Hashed {
        let mut hashed = Hashed {
            len: sorted.len(),
            ..Hashed::default()
        };
        for &(class, total) in sorted.totals() {
            hashed.classes.insert(class, total);
            hashed.class_terms += terms.get(total);
        }
        let mut by_class: Vec<(ClassId, u32)> = Vec::new();
        for (feature, runs) in sorted.features() {
            let mut counts = FeatureCounts::new(feature);
            by_class.clear();
            let mut i = 0;
            while i < runs.len() {
                let value = runs[i].0;
                let mut size = 0;
                while i < runs.len() && runs[i].0 == value {
                    let (_, class, n) = runs[i];
                    size += n;
                    counts.runs += 1;
                    counts.run_terms += terms.get(n);
                    hashed.runs.insert((feature, value, class), n);
                    by_class.push((class, n));
                    i += 1;
                }
                counts.values += 1;
                counts.value_terms += terms.get(size);
                counts.having += size;
                hashed.values.insert((feature, value), size);
            }
            by_class.sort_unstable();
            let mut k = 0;
            while k < by_class.len() {
                let class = by_class[k].0;
                let mut h = 0;
                while k < by_class.len() && by_class[k].0 == class {
                    h += by_class[k].1;
                    k += 1;
                }
                let total = sorted
                    .totals()
                    .binary_search_by_key(&class, |t| t.0)
                    .map_or(0, |j| sorted.totals()[j].1);
                counts.lacking_gap += gap(terms, total, h);
                counts.having_terms += terms.get(h);
                hashed.having.insert((feature, class), h);
            }
            hashed.features.push(counts);
        }
        hashed
    }

    /// The number of examples counted.
    fn len(&self) -> u32 {
        self.len
    }

    /// The number of counted examples of `class`.
    fn class_total(&self, class: ClassId) -> u32 {
        self.classes.get(&class).copied().unwrap_or(0)
    }

    /// The one class of every counted example, if there is exactly one.
    fn only_class(&self) -> Option<ClassId> {
        if self.classes.len() == 1 {
            self.classes.keys().next().copied()
        } else {
            None
        }
    }

    /// The number of counted examples whose `feature` is `value`.
    fn having(&self, feature: FeatureId, value: Value) -> u32 {
        self.values.get(&(feature, value)).copied().unwrap_or(0)
    }

    /// The most frequent class, ties to the lowest id, as
    /// [`SplitCounts::majority`](crate::SplitCounts::majority).
    fn majority(&mut self) -> Option<ClassId> {
        if self.majority.is_none() {
            self.majority = self.count_majority();
        }
        self.majority
    }

    fn count_majority(&self) -> Option<ClassId> {
        self.classes
            .iter()
            .map(|(&class, &total)| (total, std::cmp::Reverse(class)))
            .max()
            .map(|(_, std::cmp::Reverse(class))| class)
    }

    /// Count `example` in.
    fn add(&mut self, example: &Example, terms: &mut Terms) {
        self.change(example, terms, true);
    }

    /// Count `example`, counted in before with the same pairs and class, out again.
    fn remove(&mut self, example: &Example, terms: &mut Terms) {
        self.change(example, terms, false);
    }

    fn change(&mut self, example: &Example, terms: &mut Terms, add: bool) {
        let class = example.class();
        let pairs = example.pairs();
        let step = |x: u32| if add { x + 1 } else { x - 1 };
        if add {
            self.len += 1;
        } else {
            debug_assert!(
                self.class_total(class) > 0,
                "removing an example not counted"
            );
            self.len -= 1;
        }
        for &(f, _) in pairs {
            if let Err(k) = self.features.binary_search_by_key(&f, |c| c.feature) {
                self.features.insert(k, FeatureCounts::new(f));
            }
        }
        let old_t = self.class_total(class);
        let new_t = step(old_t);
        if new_t == 0 {
            self.classes.remove(&class);
        } else {
            self.classes.insert(class, new_t);
        }
        self.class_terms += terms.get(new_t) - terms.get(old_t);
        self.majority = match self.majority {
            Some(m) if add && m != class => {
                let m_total = self.class_total(m);
                Some(
                    if (new_t, std::cmp::Reverse(class)) > (m_total, std::cmp::Reverse(m)) {
                        class
                    } else {
                        m
                    },
                )
            }
            Some(m) if add || m != class => Some(m),
            None if add && self.len == 1 => Some(class),
            _ => None,
        };
        // Every feature of which some example of the class has a value, and the
        // example's own: each one's `lacking_gap` term for the class changes with the
        // class's total (and, for the example's own features, with the count having it).
        let mut own = pairs.iter().peekable();
        for counts in &mut self.features {
            let feature = counts.feature;
            let pair = own.next_if(|p| p.0 == feature);
            let old_h = self.having.get(&(feature, class)).copied().unwrap_or(0);
            let Some(&(_, value)) = pair else {
                // Not the example's: its term changes with the class's total, unless no
                // example of the class has the feature (g(t) - g(t - 0) = 0 throughout).
                if old_h > 0 {
                    counts.lacking_gap += gap(terms, new_t, old_h) - gap(terms, old_t, old_h);
                }
                continue;
            };
            let new_h = step(old_h);
            counts.lacking_gap += gap(terms, new_t, new_h) - gap(terms, old_t, old_h);
            counts.having_terms += terms.get(new_h) - terms.get(old_h);
            set(&mut self.having, (feature, class), new_h);
            counts.having = step(counts.having);
            let old = self.values.get(&(feature, value)).copied().unwrap_or(0);
            let new = step(old);
            counts.value_terms += terms.get(new) - terms.get(old);
            counts.values = counts.values + u32::from(old == 0) - u32::from(new == 0);
            set(&mut self.values, (feature, value), new);
            let key = (feature, value, class);
            let old = self.runs.get(&key).copied().unwrap_or(0);
            let new = step(old);
            counts.run_terms += terms.get(new) - terms.get(old);
            counts.runs = counts.runs + u32::from(old == 0) - u32::from(new == 0);
            set(&mut self.runs, key, new);
        }
        debug_assert!(own.next().is_none());
        self.features.retain(|c| c.having > 0);
    }

    /// [`InfoCost::select_from_counts`](crate::InfoCost::select_from_counts) on these
    /// counts, under `rules`: the same feature, bit for bit (see the module docs).
    /// `fallback` is scratch for the cases the bounds leave open.
    fn select<M, C>(
        &self,
        rules: Rules,
        is_measured: M,
        costs: &C,
        fallback: &mut Fallback,
    ) -> Option<FeatureId>
    where
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        match self.select_bounded(rules, &is_measured, costs) {
            Some(decided) => decided,
            None => {
                fallback.bounded_undecided += 1;
                self.select_exactly(rules, &is_measured, costs, fallback)
            }
        }
    }

    /// The selection from the exact sums: `Some(choice)` when the bounds decide every
    /// comparison, `None` when one is left open.
    fn select_bounded<M, C>(
        &self,
        rules: Rules,
        is_measured: &M,
        costs: &C,
    ) -> Option<Option<FeatureId>>
    where
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        let n = self.len;
        let classes = self.classes.len() as u64;
        let g = |x: u32| {
            let v = xlogx(x) * SCALE;
            v as i128
        };
        let mut best: Option<(Bounds, Cost, FeatureId)> = None;
        for counts in &self.features {
            let feature = counts.feature;
            if is_measured(feature) {
                continue;
            }
            let Some(cost) = costs.cost(feature) else {
                continue;
            };
            let values = counts.values;
            let split_ok = match rules.require_split {
                None => true,
                Some(crate::attend::Semantics::Observation) => {
                    values + u32::from(counts.having < n) >= 2
                }
                Some(crate::attend::Semantics::Rule) => !(counts.having == n && values == 1),
            };
            if !split_ok {
                continue;
            }
            let gain = if values == 1 && counts.having == n {
                // One value that every example has: the plain procedure computes the
                // same float twice and subtracts it, an exact 0.
                Bounds::exact(0.0)
            } else {
                let branches = counts.value_terms - counts.run_terms;
                let (exact, total) = match rules.missing {
                    crate::select::MissingRule::OwnBranch => {
                        let lacking_classes = self.class_terms - counts.lacking_gap;
                        let lacking = g(n - counts.having) - lacking_classes;
                        let base = g(n) - self.class_terms;
                        (
                            base - branches - lacking,
                            g(n) + self.class_terms
                                + counts.value_terms
                                + counts.run_terms
                                + g(n - counts.having)
                                + lacking_classes,
                        )
                    }
                    crate::select::MissingRule::C45 => {
                        let known = g(counts.having) - counts.having_terms;
                        (
                            known - branches,
                            g(counts.having)
                                + counts.having_terms
                                + counts.value_terms
                                + counts.run_terms,
                        )
                    }
                };
                // The plain procedure's additions and subtractions: a sum over every
                // class (twice with the own-branch rule), one per (value, class) count,
                // two per value, and a few more.
                let ops = 2 * classes + u64::from(counts.runs) + 2 * u64::from(values) + 8;
                Bounds::around(exact as f64 / SCALE, total as f64 / SCALE, ops)?.gain(n)
            };
            let score = gain.score(cost);
            let better = match best {
                None => true,
                Some((s, c, f)) => better(score, s, (cost, feature) < (c, f))?,
            };
            if better {
                best = Some((score, cost, feature));
            }
        }
        Some(best.map(|(_, _, f)| f))
    }

    /// The plain procedure's scoring, over these counts sorted as it sorts them.
    fn select_exactly<M, C>(
        &self,
        rules: Rules,
        is_measured: &M,
        costs: &C,
        fallback: &mut Fallback,
    ) -> Option<FeatureId>
    where
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        let Fallback {
            totals,
            having,
            runs,
            spans,
            sorted,
            ..
        } = fallback;
        totals.clear();
        totals.extend(self.classes.iter().map(|(&c, &k)| (c, k)));
        totals.sort_unstable();
        let candidate = |f: FeatureId| !is_measured(f) && costs.cost(f).is_some();
        sorted.clear();
        sorted.extend(
            self.runs
                .iter()
                .filter(|((f, _, _), _)| candidate(*f))
                .map(|(&(f, v, c), &k)| (f, v, c, k)),
        );
        sorted.sort_unstable();
        runs.clear();
        spans.clear();
        for &(f, v, c, k) in sorted.iter() {
            if spans
                .last()
                .is_none_or(|span: &(FeatureId, usize, usize)| span.0 != f)
            {
                spans.push((f, runs.len(), runs.len()));
            }
            runs.push((v, c, k));
            if let Some(span) = spans.last_mut() {
                span.2 = runs.len();
            }
        }
        let runs = &*runs;
        let features = spans.iter().map(|&(f, a, b)| (f, &runs[a..b]));
        rules.best(totals, having, features, is_measured, costs)
    }
}

/// Scratch for [`NodeCounts::select`] when it falls back on the plain procedure's
/// scoring, and a count of how often it did.
#[derive(Clone, Debug, Default)]
pub(crate) struct Fallback {
    totals: Vec<(ClassId, u32)>,
    having: Vec<u32>,
    runs: Vec<(Value, ClassId, u32)>,
    spans: Vec<(FeatureId, usize, usize)>,
    sorted: Vec<(FeatureId, Value, ClassId, u32)>,
    /// Selections the bounds did not decide.
    pub(crate) bounded_undecided: u64,
}

/// Scores (or gains) that the plain procedure's value is known to lie between.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bounds {
    lo: f64,
    hi: f64,
}

/// The unit roundoff of `f64`: every rounding to nearest is within this relative error.
const UNIT: f64 = 1.0 / 9_007_199_254_740_992.0;

impl Bounds {
    fn exact(x: f64) -> Bounds {
        Bounds { lo: x, hi: x }
    }

    /// The weighted gain the plain procedure computes, from its exact value, the total
    /// of the (non-negative) terms it is made of and the number of operations: each
    /// rounding errs by at most [`UNIT`] times its operation's exact result, which is at
    /// most the total plus the errors so far, so all of them by at most
    /// `total ((1 + UNIT)^ops - 1)`, below `1.01 ops UNIT total` while `ops UNIT` is below
    /// 1/100. The bound here is twice that and more, which also covers the roundings of
    /// the exact values to `f64` and of this computation. `None` if `ops` is too large for
    /// the bound (never for counts that fit a `u32`).
    fn around(exact: f64, total: f64, ops: u64) -> Option<Bounds> {
        let ops = ops as f64;
        if ops * UNIT > 1e-3 {
            return None;
        }
        let err = 2.0 * (ops + 8.0) * UNIT * total + 4.0 * UNIT * exact.abs();
        Some(Bounds {
            lo: exact - err,
            hi: exact + err,
        })
    }

    /// The gain `max(weighted / n, 0)`, monotone in the weighted gain.
    fn gain(self, n: u32) -> Bounds {
        let n = f64::from(n);
        Bounds {
            lo: (self.lo / n).max(0.0),
            hi: (self.hi / n).max(0.0),
        }
    }

    /// The I^2/C score of [`BestScore::offer`](crate::BestScore::offer), monotone in the
    /// gain.
    fn score(self, cost: Cost) -> Bounds {
        let score = |gain: f64| {
            if cost.get() > 0.0 {
                gain * gain / cost.get()
            } else if gain > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        };
        Bounds {
            lo: score(self.lo),
            hi: score(self.hi),
        }
    }

    fn is_exact(self) -> bool {
        self.lo == self.hi
    }
}

/// Whether `same_score(a, b)` holds for every score in `a` and `b` (`Some(true)`), for
/// none (`Some(false)`), or is open. Scores are non-negative.
fn same(a: Bounds, b: Bounds) -> Option<bool> {
    if a.is_exact() && b.is_exact() {
        return Some(same_score(a.lo, b.lo));
    }
    if a.hi == f64::INFINITY || b.hi == f64::INFINITY {
        // An infinite score and a finite one count as a tie (`same_score` compares
        // infinite differences against an infinite tolerance).
        let finite = |x: Bounds| x.hi < f64::INFINITY;
        let infinite = |x: Bounds| x.lo == f64::INFINITY;
        return ((infinite(a) && finite(b)) || (finite(a) && infinite(b))).then_some(true);
    }
    // Far from the smallest normal numbers, where roundings are relative.
    const TINY: f64 = 1e-200;
    if a.lo < TINY || b.lo < TINY {
        return None;
    }
    let widest = (a.hi - b.lo).max(b.hi - a.lo);
    let closest = (a.lo - b.hi).max(b.lo - a.hi);
    if widest * (1.0 + 1e-6) <= 1e-9 * a.lo.max(b.lo) * (1.0 - 1e-6) {
        Some(true)
    } else if closest * (1.0 - 1e-6) > 1e-9 * a.hi.max(b.hi) * (1.0 + 1e-6) {
        Some(false)
    } else {
        None
    }
}

/// [`BestScore`](crate::BestScore)'s rule over bounds: whether a feature scoring `a`
/// replaces the best so far, scoring `b`, where `wins_tie` is whether it wins a tie
/// (lower cost, then lower id); `None` if the bounds leave it open.
fn better(a: Bounds, b: Bounds, wins_tie: bool) -> Option<bool> {
    let higher = if a.lo > b.hi {
        Some(true)
    } else if a.hi <= b.lo {
        Some(false)
    } else {
        None
    };
    match same(a, b) {
        Some(true) => Some(wins_tie),
        Some(false) => higher,
        None => higher.filter(|&h| h == wins_tie),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{InfoCost, MissingRule, Semantics, SplitCounts};
    use rand::{RngExt, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    #[test]
    fn the_term_of_one_is_zero() {
        assert_eq!(xlogx(1), 0.0);
        assert_eq!(xlogx(0), 0.0);
        assert_eq!(Terms::new().get(1), 0);
    }

    /// Random examples over `features` features, with up to `classes` classes, some
    /// cells missing.
    fn examples(
        rng: &mut Xoshiro256PlusPlus,
        count: usize,
        features: u32,
        values: u32,
        classes: u32,
    ) -> Vec<Example> {
        (0..count)
            .map(|_| {
                let mut pairs = Vec::new();
                for f in 0..features {
                    if rng.random_bool(0.8) {
                        pairs.push((FeatureId(f), Value(rng.random_range(0..values))));
                    }
                }
                Example::from_pairs(pairs, ClassId(rng.random_range(0..classes)))
            })
            .collect()
    }

    #[test]
    fn selection_is_the_plain_one_bit_for_bit() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(21);
        let mut fallback = Fallback::default();
        let mut terms = Terms::new();
        let mut checked = 0;
        let mut hashed_rounds = 0;
        for round in 0..300 {
            let features = rng.random_range(1..8);
            let values = rng.random_range(1..4);
            let classes = [2, 3, 10, 200][round % 4];
            let count = rng.random_range(1..300);
            let all = examples(&mut rng, count, features, values, classes);
            let costs: Vec<Cost> = (0..features)
                .map(|_| Cost::new(f64::from(rng.random_range(0..4))).unwrap())
                .collect();
            // Every other round with sums from the start, whatever the classes; else they
            // start from sorted vectors and switch past `FEW_CLASSES`.
            let mut counts = if round % 2 == 0 {
                NodeCounts::hashed()
            } else {
                NodeCounts::default()
            };
            let mut split = SplitCounts::new();
            all.iter().for_each(|e| {
                counts.add(e, &mut terms);
                split.add(e);
                assert_eq!(counts.majority(), split.majority());
            });
            if split.totals().len() > FEW_CLASSES {
                assert!(matches!(counts, NodeCounts::Hashed(_)));
            }
            // Take some out again.
            for e in all.iter().filter(|_| rng.random_bool(0.3)) {
                counts.remove(e, &mut terms);
                split.remove(e);
                assert_eq!(counts.majority(), split.majority());
            }
            if counts.len() == 0 {
                continue;
            }
            for missing in [MissingRule::OwnBranch, MissingRule::C45] {
                for require in [None, Some(Semantics::Observation), Some(Semantics::Rule)] {
                    let mut select = InfoCost::new(missing);
                    if let Some(s) = require {
                        select = select.requiring_split(s);
                    }
                    let measured = |f: FeatureId| f.0 == 0 && round % 3 == 0;
                    let plain = select.select_from_counts(&split, measured, &costs[..]);
                    let fast = counts.select(select.rules(), measured, &costs[..], &mut fallback);
                    assert_eq!(fast, plain, "round {round}");
                    checked += 1;
                }
            }
            assert_eq!(counts.majority(), split.majority());
            if let NodeCounts::Hashed(hashed) = &counts {
                assert_eq!(hashed.count_majority(), split.majority());
                hashed_rounds += 1;
            }
        }
        assert!(checked > 1000);
        assert!(hashed_rounds > 150, "{hashed_rounds}");
        // The bounds decide most selections.
        assert!(
            fallback.bounded_undecided * 2 < checked,
            "{}",
            fallback.bounded_undecided
        );
    }
}
