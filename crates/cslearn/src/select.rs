//! Feature selection (Figure 2, step 1(b)): the most cost-effective feature to measure
//! next, by I^2/C.

use crate::attend::{Attention, Semantics};
use crate::example::{Example, Library};
use crate::sensing::Ledger;
use crate::types::{ClassId, Cost, CostBlind, Costs, FeatureCosts, FeatureId, Value};

/// How the information gain of a feature treats the examples that lack it.
///
/// ```
/// use cslearn::{InfoCost, MissingRule};
/// let csid3 = InfoCost::new(MissingRule::OwnBranch);
/// let csql = InfoCost::new(MissingRule::C45);
/// assert_eq!(csid3.missing(), MissingRule::OwnBranch);
/// assert_eq!(csql.missing(), MissingRule::C45);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MissingRule {
    /// The examples lacking the feature form a branch of their own (specification §2, CS-ID3).
    OwnBranch,
    /// The gain is computed on the examples that have the feature only, then scaled by
    /// their share of all examples (Quinlan's C4.5 rule; specification §4, CS-QL's CLASSIFY).
    C45,
}

/// Feature selection by I^2/C, where I is the information gain of splitting the examples
/// by the feature's value (Quinlan 1986) and C the feature's cost: the paper's choice for
/// CS-ID3 (section "Cost-Sensitive Learning") and for CS-QL's CLASSIFY (Figure 3, step 2).
///
/// The candidates are the features that some of the given examples have, that are not
/// yet measured and that have a price. The winner has the highest I^2/C; scores that agree
/// to a relative 1e-9 are ties (so that rounding cannot decide them), and ties go to the
/// lower cost, then the lower [`FeatureId`]. When every gain is zero, the cheapest
/// candidate therefore wins. A free feature (cost 0) with positive gain scores infinitely
/// high; with zero gain it scores 0.
///
/// The selector keeps its working buffers between calls, so selecting allocates nothing
/// once the buffers have grown to the size of the problem.
///
/// ```
/// use cslearn::{ClassId, Cost, Example, FeatureId, InfoCost, MissingRule, Value};
/// let costs = [Cost::ONE, Cost::new(10.0).unwrap()];
/// // Feature 0 separates the classes perfectly, feature 1 not at all.
/// let examples = [
///     Example::from_pairs([(FeatureId(0), Value(0)), (FeatureId(1), Value(0))], ClassId(0)),
///     Example::from_pairs([(FeatureId(0), Value(1)), (FeatureId(1), Value(0))], ClassId(1)),
/// ];
/// let mut select = InfoCost::new(MissingRule::OwnBranch);
/// assert_eq!(select.select_from(&examples, |_| false, &costs[..]), Some(FeatureId(0)));
/// // Once feature 0 is measured, only feature 1 is left.
/// assert_eq!(select.select_from(&examples, |f| f == FeatureId(0), &costs[..]), Some(FeatureId(1)));
/// ```
#[derive(Clone, Debug)]
pub struct InfoCost {
    missing: MissingRule,
    require_split: Option<Semantics>,
    cost_blind: bool,
    triples: Vec<(FeatureId, Value, ClassId)>,
    example_classes: Vec<ClassId>,
    totals: Vec<(ClassId, u32)>,
    having: Vec<u32>,
    /// Counts by (value, class) of every candidate feature, one span per feature.
    runs: Vec<(Value, ClassId, u32)>,
    spans: Vec<(FeatureId, usize, usize)>,
}

/// `x log2 x`, with `0 log 0 = 0`: entropies are sums of these over counts.
pub(crate) fn xlogx(x: u32) -> f64 {
    if x == 0 {
        0.0
    } else {
        let x = f64::from(x);
        x * x.log2()
    }
}

/// Whether two I^2/C scores count as a tie: equal to a relative 1e-9, so that rounding
/// cannot decide between features that score the same in exact arithmetic.
pub(crate) fn same_score(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

impl InfoCost {
    /// A selector with the given missing-value rule, real costs and no split requirement.
    ///
    /// ```
    /// let s = cslearn::InfoCost::new(cslearn::MissingRule::C45);
    /// assert!(!s.is_cost_blind());
    /// ```
    pub fn new(missing: MissingRule) -> InfoCost {
        InfoCost {
            missing,
            require_split: None,
            cost_blind: false,
            triples: Vec::new(),
            example_classes: Vec::new(),
            totals: Vec::new(),
            having: Vec::new(),
            runs: Vec::new(),
            spans: Vec::new(),
        }
    }

    /// The same selector, but taking every cost as one when used as a [`Select`] part:
    /// plain ID3's gain criterion.
    ///
    /// ```
    /// let s = cslearn::InfoCost::new(cslearn::MissingRule::OwnBranch).cost_blind();
    /// assert!(s.is_cost_blind());
    /// ```
    pub fn cost_blind(mut self) -> InfoCost {
        self.cost_blind = true;
        self
    }

    /// The same selector, but only proposing features that split the examples into at
    /// least two groups under `semantics` (tree building needs this; lazy classification
    /// does not, since measuring can also show that the object is new).
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, InfoCost, MissingRule, Semantics, Value, Cost};
    /// let same = [
    ///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(1)),
    /// ];
    /// let costs = [Cost::ONE];
    /// let mut lazy = InfoCost::new(MissingRule::OwnBranch);
    /// assert_eq!(lazy.select_from(&same, |_| false, &costs[..]), Some(FeatureId(0)));
    /// let mut tree = InfoCost::new(MissingRule::OwnBranch).requiring_split(Semantics::Observation);
    /// assert_eq!(tree.select_from(&same, |_| false, &costs[..]), None);
    /// ```
    pub fn requiring_split(mut self, semantics: Semantics) -> InfoCost {
        self.require_split = Some(semantics);
        self
    }

    /// The missing-value rule.
    ///
    /// ```
    /// let s = cslearn::InfoCost::new(cslearn::MissingRule::C45);
    /// assert_eq!(s.missing(), cslearn::MissingRule::C45);
    /// ```
    pub fn missing(&self) -> MissingRule {
        self.missing
    }

    /// Whether the [`Select`] part ignores costs.
    ///
    /// ```
    /// assert!(!cslearn::InfoCost::new(cslearn::MissingRule::C45).is_cost_blind());
    /// ```
    pub fn is_cost_blind(&self) -> bool {
        self.cost_blind
    }

    /// The best feature to measure on an object, given the `examples` still relevant to
    /// it, which features are already measured, and the costs; `None` if no feature is a
    /// candidate. Selection itself never looks at [`is_cost_blind`](InfoCost::is_cost_blind):
    /// pass [`CostBlind`] costs for that.
    ///
    /// ```
    /// use cslearn::{ClassId, Cost, Example, FeatureId, InfoCost, MissingRule, Value};
    /// // Both features split perfectly; the cheaper one wins.
    /// let costs = [Cost::new(3.0).unwrap(), Cost::new(2.0).unwrap()];
    /// let examples = [
    ///     Example::from_pairs([(FeatureId(0), Value(0)), (FeatureId(1), Value(5))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1)), (FeatureId(1), Value(6))], ClassId(1)),
    /// ];
    /// let mut s = InfoCost::new(MissingRule::OwnBranch);
    /// assert_eq!(s.select_from(&examples, |_| false, &costs[..]), Some(FeatureId(1)));
    /// assert_eq!(s.select_from(&[], |_| false, &costs[..]), None);
    /// ```
    pub fn select_from<'a, I, M, C>(
        &mut self,
        examples: I,
        is_measured: M,
        costs: &C,
    ) -> Option<FeatureId>
    where
        I: IntoIterator<Item = &'a Example>,
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        self.triples.clear();
        self.example_classes.clear();
        for example in examples {
            let class = example.class();
            self.example_classes.push(class);
            for &(f, v) in example.pairs() {
                if costs.cost(f).is_some() && !is_measured(f) {
                    self.triples.push((f, v, class));
                }
            }
        }
        if self.triples.is_empty() {
            return None;
        }
        // Sorting groups each feature's entries, each value's within them and each
        // class's within those, so one scan turns them into the counts the gains need.
        self.triples.sort_unstable();
        self.example_classes.sort_unstable();
        self.totals.clear();
        for &c in &self.example_classes {
            match self.totals.last_mut() {
                Some((last, n)) if *last == c => *n += 1,
                _ => self.totals.push((c, 1)),
            }
        }
        self.runs.clear();
        self.spans.clear();
        for &(f, v, c) in &self.triples {
            let new_feature = self.spans.last().is_none_or(|span| span.0 != f);
            if new_feature {
                self.spans.push((f, self.runs.len(), self.runs.len()));
            }
            match self.runs.last_mut() {
                Some((lv, lc, n)) if !new_feature && (*lv, *lc) == (v, c) => *n += 1,
                _ => self.runs.push((v, c, 1)),
            }
            if let Some(span) = self.spans.last_mut() {
                span.2 = self.runs.len();
            }
        }
        let runs = &self.runs;
        let features = self.spans.iter().map(|&(f, a, b)| (f, &runs[a..b]));
        let rules = Rules {
            missing: self.missing,
            require_split: self.require_split,
        };
        rules.best(&self.totals, &mut self.having, features, is_measured, costs)
    }

    /// The scoring settings, for selectors that keep their own counts.
    pub(crate) fn rules(&self) -> Rules {
        Rules {
            missing: self.missing,
            require_split: self.require_split,
        }
    }

    /// [`select_from`](InfoCost::select_from) computed from the class counts of the
    /// examples instead of the examples themselves: the same feature, bit for bit, as
    /// `select_from` over the examples that `counts` counted, because both score through
    /// one function in the same order (features by ascending id, values by ascending
    /// value, classes by ascending id).
    ///
    /// Counts kept per node of a lazily built tree, and updated as examples come and go,
    /// let a learner select without looking at the examples again; the indexed learners
    /// ([`IndexedLearner`](crate::IndexedLearner)) do this.
    ///
    /// ```
    /// use cslearn::{ClassId, Cost, Example, FeatureId, InfoCost, MissingRule, SplitCounts, Value};
    /// let costs = [Cost::ONE, Cost::new(10.0).unwrap()];
    /// let examples = [
    ///     Example::from_pairs([(FeatureId(0), Value(0)), (FeatureId(1), Value(0))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1)), (FeatureId(1), Value(0))], ClassId(1)),
    /// ];
    /// let mut counts = SplitCounts::new();
    /// examples.iter().for_each(|e| counts.add(e));
    /// let mut select = InfoCost::new(MissingRule::OwnBranch);
    /// let by_counts = select.select_from_counts(&counts, |_| false, &costs[..]);
    /// assert_eq!(by_counts, Some(FeatureId(0)));
    /// assert_eq!(by_counts, select.select_from(&examples, |_| false, &costs[..]));
    /// ```
    pub fn select_from_counts<M, C>(
        &mut self,
        counts: &SplitCounts,
        is_measured: M,
        costs: &C,
    ) -> Option<FeatureId>
    where
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        let rules = Rules {
            missing: self.missing,
            require_split: self.require_split,
        };
        rules.best(
            counts.totals(),
            &mut self.having,
            counts.features(),
            is_measured,
            costs,
        )
    }
}

/// The running choice of the most cost-effective feature: the highest I^2/C, where a
/// free feature (cost 0) with positive gain scores infinitely high and with zero gain 0;
/// scores equal to a relative 1e-9 are ties (so that rounding cannot decide them), won by
/// the lower cost, then the lower id. The tie rule is not transitive: offer features in
/// ascending id, as every selector here does. The one rule behind [`InfoCost`] and any
/// selector that computes gains its own way (csql's cached CLASSIFY does).
///
/// ```
/// use cslearn::{BestScore, Cost, FeatureId};
/// let mut best = BestScore::new();
/// best.offer(FeatureId(0), 0.5, Cost::new(4.0).unwrap()); // 0.0625
/// best.offer(FeatureId(1), 0.5, Cost::new(2.0).unwrap()); // 0.125: better
/// best.offer(FeatureId(2), 0.5, Cost::new(2.0).unwrap()); // a tie, lost on the id
/// assert_eq!(best.best(), Some(FeatureId(1)));
/// assert_eq!(BestScore::new().best(), None);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct BestScore {
    best: Option<(f64, Cost, FeatureId)>,
}

impl BestScore {
    /// Nothing offered yet.
    ///
    /// ```
    /// assert_eq!(cslearn::BestScore::new().best(), None);
    /// ```
    pub fn new() -> BestScore {
        BestScore::default()
    }

    /// Offer a feature with its information gain and its cost.
    ///
    /// ```
    /// use cslearn::{BestScore, Cost, FeatureId};
    /// let mut best = BestScore::new();
    /// best.offer(FeatureId(3), 0.0, Cost::ONE);
    /// best.offer(FeatureId(4), 0.1, Cost::ZERO); // free and informative: infinite score
    /// assert_eq!(best.best(), Some(FeatureId(4)));
    /// ```
    #[inline]
    pub fn offer(&mut self, feature: FeatureId, gain: f64, cost: Cost) {
        let score = if cost.get() > 0.0 {
            gain * gain / cost.get()
        } else if gain > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        let better = match self.best {
            None => true,
            Some((s, c, f)) => {
                if same_score(score, s) {
                    (cost, feature) < (c, f)
                } else {
                    score > s
                }
            }
        };
        if better {
            self.best = Some((score, cost, feature));
        }
    }

    /// The winner so far.
    ///
    /// ```
    /// let mut best = cslearn::BestScore::new();
    /// best.offer(cslearn::FeatureId(7), 0.3, cslearn::Cost::ONE);
    /// assert_eq!(best.best(), Some(cslearn::FeatureId(7)));
    /// ```
    pub fn best(&self) -> Option<FeatureId> {
        self.best.map(|(_, _, f)| f)
    }
}

/// The two settings that decide how a split is scored and whether it counts.
#[derive(Clone, Copy)]
pub(crate) struct Rules {
    pub(crate) missing: MissingRule,
    pub(crate) require_split: Option<Semantics>,
}

impl Rules {
    /// The best feature by I^2/C among `features` (ascending id, each with its counts by
    /// ascending (value, class)), over examples whose class counts are `totals`
    /// (ascending class). The one scoring procedure behind both entry points, so that
    /// counting examples one way or the other cannot change a single bit of a score.
    pub(crate) fn best<'a, M, C>(
        self,
        totals: &[(ClassId, u32)],
        having: &mut Vec<u32>,
        features: impl Iterator<Item = (FeatureId, &'a [(Value, ClassId, u32)])>,
        is_measured: M,
        costs: &C,
    ) -> Option<FeatureId>
    where
        M: Fn(FeatureId) -> bool,
        C: Costs + ?Sized,
    {
        having.clear();
        having.resize(totals.len(), 0);
        let n: u32 = totals.iter().map(|&(_, k)| k).sum();
        let base = xlogx(n) - totals.iter().map(|&(_, k)| xlogx(k)).sum::<f64>();
        let mut best = BestScore::new();
        for (feature, runs) in features {
            if runs.is_empty() || is_measured(feature) {
                continue;
            }
            let Some(cost) = costs.cost(feature) else {
                continue;
            };
            let split = self.split(runs, totals, having, n, base);
            if !self.useful(&split, n) {
                continue;
            }
            // Offered in ascending id: the tie rule is not transitive.
            best.offer(feature, split.gain, cost);
        }
        best.best()
    }

    /// The gain of splitting on one feature whose counts by (value, class) are `runs`,
    /// with the number of distinct values and of examples having the feature.
    fn split(
        self,
        runs: &[(Value, ClassId, u32)],
        totals: &[(ClassId, u32)],
        having: &mut [u32],
        n: u32,
        base: f64,
    ) -> SplitStats {
        // Each term below is |S| * H(S) = g(|S|) - sum over classes of g(count), g = x log2 x;
        // the gain is (|S| H(S) - sum over branches |B| H(B)) / |S|.
        let mut values = 0;
        let mut branches = 0.0;
        let mut having_feature = 0;
        let mut i = 0;
        while i < runs.len() {
            let value = runs[i].0;
            let mut size = 0;
            let mut within = 0.0;
            while i < runs.len() && runs[i].0 == value {
                let (_, class, run) = runs[i];
                within += xlogx(run);
                size += run;
                if let Ok(k) = totals.binary_search_by_key(&class, |t| t.0) {
                    having[k] += run;
                }
                i += 1;
            }
            branches += xlogx(size) - within;
            values += 1;
            having_feature += size;
        }
        let weighted = match self.missing {
            MissingRule::OwnBranch => {
                let lacking = xlogx(n - having_feature)
                    - totals
                        .iter()
                        .zip(having.iter())
                        .map(|(&(_, total), &h)| xlogx(total - h))
                        .sum::<f64>();
                base - branches - lacking
            }
            MissingRule::C45 => {
                // Gain on the examples having the feature, times their share: the share's
                // numerator cancels the 1/|S_f| of the entropy, leaving one division by n.
                let known = xlogx(having_feature) - having.iter().map(|&h| xlogx(h)).sum::<f64>();
                known - branches
            }
        };
        having.iter_mut().for_each(|h| *h = 0);
        SplitStats {
            gain: (weighted / f64::from(n)).max(0.0),
            values,
            having: having_feature,
        }
    }

    fn useful(self, split: &SplitStats, n: u32) -> bool {
        match self.require_split {
            None => true,
            Some(Semantics::Observation) => split.values + u32::from(split.having < n) >= 2,
            Some(Semantics::Rule) => !(split.having == n && split.values == 1),
        }
    }
}

/// The class counts of a set of examples, overall and split by each feature's values:
/// everything I^2/C selection needs to know about the set
/// ([`InfoCost::select_from_counts`]).
///
/// Adding or removing one example costs a binary search per pair it has, whatever the size
/// of the set, so counts kept per node of a tree can follow a growing library instead of
/// recounting it. A feature no counted example has, and a (value, class) no counted
/// example has, take no room and are not listed.
///
/// ```
/// use cslearn::{ClassId, Example, FeatureId, SplitCounts, Value};
/// let mut counts = SplitCounts::new();
/// let a = Example::from_pairs([(FeatureId(2), Value(1))], ClassId(0));
/// let b = Example::from_pairs([(FeatureId(2), Value(1)), (FeatureId(0), Value(3))], ClassId(1));
/// counts.add(&a);
/// counts.add(&b);
/// assert_eq!(counts.len(), 2);
/// assert_eq!(counts.totals(), &[(ClassId(0), 1), (ClassId(1), 1)]);
/// assert_eq!(counts.feature(FeatureId(2)), &[(Value(1), ClassId(0), 1), (Value(1), ClassId(1), 1)]);
/// assert_eq!(counts.having(FeatureId(2), Value(1)), 2);
/// counts.remove(&b);
/// assert!(counts.feature(FeatureId(0)).is_empty());
/// assert_eq!(counts.features().count(), 1);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SplitCounts {
    len: u32,
    /// (class, examples of that class), ascending class.
    totals: Vec<(ClassId, u32)>,
    /// By feature index: (value, class, examples with that value and class), ascending.
    features: Vec<Vec<(Value, ClassId, u32)>>,
}

impl SplitCounts {
    /// Counts of no examples.
    ///
    /// ```
    /// assert!(cslearn::SplitCounts::new().is_empty());
    /// ```
    pub fn new() -> SplitCounts {
        SplitCounts::default()
    }

    /// Count `example` in.
    ///
    /// ```
    /// let mut counts = cslearn::SplitCounts::new();
    /// counts.add(&cslearn::Example::new(cslearn::ClassId(4)));
    /// assert_eq!(counts.totals(), &[(cslearn::ClassId(4), 1)]);
    /// ```
    pub fn add(&mut self, example: &Example) {
        let class = example.class();
        self.len += 1;
        match self.totals.binary_search_by_key(&class, |t| t.0) {
            Ok(k) => self.totals[k].1 += 1,
            Err(k) => self.totals.insert(k, (class, 1)),
        }
        for &(f, v) in example.pairs() {
            if self.features.len() <= f.index() {
                self.features.resize_with(f.index() + 1, Vec::new);
            }
            let entries = &mut self.features[f.index()];
            match entries.binary_search_by_key(&(v, class), |e| (e.0, e.1)) {
                Ok(k) => entries[k].2 += 1,
                Err(k) => entries.insert(k, (v, class, 1)),
            }
        }
    }

    /// Count `example` out again. It must have been counted in (with the same pairs and
    /// class); counts of an example never added are left as they are.
    ///
    /// ```
    /// let mut counts = cslearn::SplitCounts::new();
    /// let e = cslearn::Example::new(cslearn::ClassId(4));
    /// counts.add(&e);
    /// counts.remove(&e);
    /// assert_eq!(counts, cslearn::SplitCounts::new());
    /// ```
    pub fn remove(&mut self, example: &Example) {
        let class = example.class();
        let Ok(k) = self.totals.binary_search_by_key(&class, |t| t.0) else {
            return;
        };
        self.len -= 1;
        self.totals[k].1 -= 1;
        if self.totals[k].1 == 0 {
            self.totals.remove(k);
        }
        for &(f, v) in example.pairs() {
            let Some(entries) = self.features.get_mut(f.index()) else {
                continue;
            };
            if let Ok(k) = entries.binary_search_by_key(&(v, class), |e| (e.0, e.1)) {
                entries[k].2 -= 1;
                if entries[k].2 == 0 {
                    entries.remove(k);
                }
            }
        }
        // Trailing empty features would make two equal sets compare unequal.
        while self.features.last().is_some_and(Vec::is_empty) {
            self.features.pop();
        }
    }

    /// Forget every count, keeping the buffers.
    ///
    /// ```
    /// let mut counts = cslearn::SplitCounts::new();
    /// counts.add(&cslearn::Example::new(cslearn::ClassId(0)));
    /// counts.clear();
    /// assert!(counts.is_empty());
    /// ```
    pub fn clear(&mut self) {
        self.len = 0;
        self.totals.clear();
        self.features.iter_mut().for_each(Vec::clear);
        self.features.clear();
    }

    /// The number of examples counted.
    ///
    /// ```
    /// assert_eq!(cslearn::SplitCounts::new().len(), 0);
    /// ```
    pub fn len(&self) -> u32 {
        self.len
    }

    /// Whether no example is counted.
    ///
    /// ```
    /// assert!(cslearn::SplitCounts::new().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// (class, number of examples of that class), by ascending class; classes with no
    /// example are left out.
    ///
    /// ```
    /// assert!(cslearn::SplitCounts::new().totals().is_empty());
    /// ```
    pub fn totals(&self) -> &[(ClassId, u32)] {
        &self.totals
    }

    /// (value, class, number of examples with that value and class) for `feature`, by
    /// ascending value, then class; empty if no counted example has the feature.
    ///
    /// ```
    /// assert!(cslearn::SplitCounts::new().feature(cslearn::FeatureId(3)).is_empty());
    /// ```
    pub fn feature(&self, feature: FeatureId) -> &[(Value, ClassId, u32)] {
        self.features
            .get(feature.index())
            .map_or(&[], Vec::as_slice)
    }

    /// The number of counted examples whose `feature` is `value`.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, SplitCounts, Value};
    /// let mut counts = SplitCounts::new();
    /// counts.add(&Example::from_pairs([(FeatureId(0), Value(2))], ClassId(0)));
    /// assert_eq!(counts.having(FeatureId(0), Value(2)), 1);
    /// assert_eq!(counts.having(FeatureId(0), Value(1)), 0);
    /// ```
    pub fn having(&self, feature: FeatureId, value: Value) -> u32 {
        let entries = self.feature(feature);
        let start = entries.partition_point(|e| e.0 < value);
        entries[start..]
            .iter()
            .take_while(|e| e.0 == value)
            .map(|e| e.2)
            .sum()
    }

    /// Every feature some counted example has, by ascending id, with its counts as
    /// [`feature`](SplitCounts::feature) gives them.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, SplitCounts, Value};
    /// let mut counts = SplitCounts::new();
    /// counts.add(&Example::from_pairs([(FeatureId(5), Value(0))], ClassId(0)));
    /// let ids: Vec<FeatureId> = counts.features().map(|(f, _)| f).collect();
    /// assert_eq!(ids, [FeatureId(5)]);
    /// ```
    pub fn features(&self) -> impl Iterator<Item = (FeatureId, &[(Value, ClassId, u32)])> + '_ {
        self.features
            .iter()
            .enumerate()
            .filter(|(_, entries)| !entries.is_empty())
            .map(|(f, entries)| (FeatureId(f as u32), entries.as_slice()))
    }

    /// The most frequent class, ties to the lowest id (as CS-ID3's prediction takes it);
    /// `None` when nothing is counted.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, SplitCounts};
    /// let mut counts = SplitCounts::new();
    /// for c in [2, 1, 2, 1] {
    ///     counts.add(&Example::new(ClassId(c)));
    /// }
    /// assert_eq!(counts.majority(), Some(ClassId(1)));
    /// ```
    pub fn majority(&self) -> Option<ClassId> {
        let mut best: Option<(u32, ClassId)> = None;
        for &(class, n) in &self.totals {
            if best.is_none_or(|(m, _)| n > m) {
                best = Some((n, class));
            }
        }
        best.map(|(_, c)| c)
    }
}

struct SplitStats {
    gain: f64,
    values: u32,
    having: u32,
}

/// Feature selection, one of the five functions: the feature to measure next on the
/// object, or `None` when there is nothing worth measuring.
///
/// [`InfoCost`] is the implementation: I^2/C over the attended examples (CS-ID3, CS-IBL),
/// or I^2 alone when [`cost_blind`](InfoCost::cost_blind) (ID3).
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Example, FeatureCosts, FeatureId, InfoCost};
/// use cslearn::{Ledger, Library, MissingRule, ObservationAttending, Select, Value};
/// let lib = Library::from(vec![
///     Example::from_pairs([(FeatureId(1), Value(0))], ClassId(0)),
///     Example::from_pairs([(FeatureId(1), Value(1))], ClassId(1)),
/// ]);
/// let costs = FeatureCosts::from_f64(&[1.0, 5.0]).unwrap();
/// let mut attention = Attention::new();
/// ObservationAttending.start(&lib, &mut attention);
/// let mut select = InfoCost::new(MissingRule::OwnBranch);
/// let f = select.select(&lib, &attention, &Ledger::default(), &costs);
/// assert_eq!(f, Some(FeatureId(1))); // feature 0 is cheaper but no example has it
/// ```
pub trait Select {
    /// The feature to measure next, given the attended examples and the ledger of what
    /// was measured on the object (candidates are the features the current pass has not
    /// [consulted](Ledger::consulted)).
    fn select(
        &mut self,
        library: &Library,
        attention: &Attention,
        ledger: &Ledger,
        costs: &FeatureCosts,
    ) -> Option<FeatureId>;
}

impl Select for InfoCost {
    fn select(
        &mut self,
        library: &Library,
        attention: &Attention,
        ledger: &Ledger,
        costs: &FeatureCosts,
    ) -> Option<FeatureId> {
        let examples = attention.attended().iter().map(|&i| &library[i]);
        let measured = |f| ledger.consulted(f);
        if self.cost_blind {
            self.select_from(examples, measured, &CostBlind(costs))
        } else {
            self.select_from(examples, measured, costs)
        }
    }
}
