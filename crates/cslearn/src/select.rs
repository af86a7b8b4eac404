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
    /// The examples lacking the feature form a branch of their own (SPEC 2, CS-ID3).
    OwnBranch,
    /// The gain is computed on the examples that have the feature only, then scaled by
    /// their share of all examples (Quinlan's C4.5 rule; SPEC 4, CS-QL's CLASSIFY).
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
}

/// `x log2 x`, with `0 log 0 = 0`: entropies are sums of these over counts.
fn xlogx(x: u32) -> f64 {
    if x == 0 {
        0.0
    } else {
        let x = f64::from(x);
        x * x.log2()
    }
}

/// Whether two I^2/C scores count as a tie: equal to a relative 1e-9, so that rounding
/// cannot decide between features that score the same in exact arithmetic. (Not
/// transitive: compare candidates in a fixed order, as [`InfoCost`] does.)
///
/// ```
/// assert!(cslearn::same_score(1.0, 1.0 + 1e-12));
/// assert!(!cslearn::same_score(1.0, 1.001));
/// ```
pub fn same_score(a: f64, b: f64) -> bool {
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
        // class's within those, so one scan finds every count the gains need.
        self.triples.sort_unstable();
        self.example_classes.sort_unstable();
        self.totals.clear();
        for &c in &self.example_classes {
            match self.totals.last_mut() {
                Some((last, n)) if *last == c => *n += 1,
                _ => self.totals.push((c, 1)),
            }
        }
        self.having.clear();
        self.having.resize(self.totals.len(), 0);

        let n = self.example_classes.len() as u32;
        let base = xlogx(n) - self.totals.iter().map(|&(_, k)| xlogx(k)).sum::<f64>();
        let mut best: Option<(f64, Cost, FeatureId)> = None;
        let mut start = 0;
        while start < self.triples.len() {
            let feature = self.triples[start].0;
            let end = start
                + self.triples[start..]
                    .iter()
                    .take_while(|t| t.0 == feature)
                    .count();
            let split = self.split(start..end, n, base);
            start = end;
            if !self.useful(&split, n) {
                continue;
            }
            let gain = split.gain;
            let Some(cost) = costs.cost(feature) else {
                continue;
            };
            let score = if cost.get() > 0.0 {
                gain * gain / cost.get()
            } else if gain > 0.0 {
                f64::INFINITY
            } else {
                0.0
            };
            let better = match best {
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
                best = Some((score, cost, feature));
            }
        }
        best.map(|(_, _, f)| f)
    }

    /// The gain of splitting on the feature whose entries are `range` of the sorted
    /// triples, with the number of distinct values and of examples having the feature.
    fn split(&mut self, range: std::ops::Range<usize>, n: u32, base: f64) -> SplitStats {
        let triples = &self.triples[range];
        // Each term below is |S| * H(S) = g(|S|) - sum over classes of g(count), g = x log2 x;
        // the gain is (|S| H(S) - sum over branches |B| H(B)) / |S|.
        let mut values = 0;
        let mut branches = 0.0;
        let mut i = 0;
        while i < triples.len() {
            let value = triples[i].1;
            let mut size = 0;
            let mut within = 0.0;
            while i < triples.len() && triples[i].1 == value {
                let class = triples[i].2;
                let run = triples[i..]
                    .iter()
                    .take_while(|t| t.1 == value && t.2 == class)
                    .count();
                let run = run as u32;
                within += xlogx(run);
                size += run;
                if let Ok(k) = self.totals.binary_search_by_key(&class, |t| t.0) {
                    self.having[k] += run;
                }
                i += run as usize;
            }
            branches += xlogx(size) - within;
            values += 1;
        }
        let having = triples.len() as u32;
        let weighted = match self.missing {
            MissingRule::OwnBranch => {
                let lacking = xlogx(n - having)
                    - self
                        .totals
                        .iter()
                        .zip(&self.having)
                        .map(|(&(_, total), &h)| xlogx(total - h))
                        .sum::<f64>();
                base - branches - lacking
            }
            MissingRule::C45 => {
                // Gain on the examples having the feature, times their share: the share's
                // numerator cancels the 1/|S_f| of the entropy, leaving one division by n.
                let known = xlogx(having) - self.having.iter().map(|&h| xlogx(h)).sum::<f64>();
                known - branches
            }
        };
        self.having.iter_mut().for_each(|h| *h = 0);
        SplitStats {
            gain: (weighted / f64::from(n)).max(0.0),
            values,
            having,
        }
    }

    fn useful(&self, split: &SplitStats, n: u32) -> bool {
        match self.require_split {
            None => true,
            Some(Semantics::Observation) => split.values + u32::from(split.having < n) >= 2,
            Some(Semantics::Rule) => !(split.having == n && split.values == 1),
        }
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
