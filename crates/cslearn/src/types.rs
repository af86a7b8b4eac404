//! Identifiers, costs and the feature order.
//!
//! Features, values and classes are plain numbers: the crate never needs their names,
//! and a caller can hand out new ones at any time (no closed world). Names, where there
//! are any, live with the caller (for a CSV file, in [`Dataset`](crate::Dataset)).

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, AddAssign};

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// A feature (an attribute that can be measured on an object).
///
/// ```
/// use cslearn::FeatureId;
/// assert!(FeatureId(2) < FeatureId(10));
/// assert_eq!(FeatureId(3).to_string(), "f3");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct FeatureId(pub u32);

/// A value of a feature. What the number means is up to the caller (for a CSV file, the
/// index of a category or of a numeric bin).
///
/// ```
/// use cslearn::Value;
/// assert_eq!(Value(1).to_string(), "1");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Value(pub u32);

/// A class label.
///
/// ```
/// use cslearn::ClassId;
/// assert_eq!(ClassId(1).to_string(), "class 1");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct ClassId(pub u32);

impl fmt::Display for FeatureId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "f{}", self.0)
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

impl fmt::Display for ClassId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "class {}", self.0)
    }
}

impl FeatureId {
    /// The id as an index into dense per-feature tables.
    ///
    /// ```
    /// assert_eq!(cslearn::FeatureId(7).index(), 7);
    /// ```
    pub const fn index(self) -> usize {
        self.0 as usize
    }
}

/// The price of measuring a feature: finite and non-negative, so costs can be summed and
/// totally ordered.
///
/// ```
/// use cslearn::Cost;
/// let c = Cost::new(1.5).unwrap() + Cost::new(2.0).unwrap();
/// assert_eq!(c.get(), 3.5);
/// assert!(Cost::new(-1.0).is_err());
/// assert!(Cost::new(f64::NAN).is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Cost(f64);

impl Cost {
    /// Nothing to pay.
    ///
    /// ```
    /// assert_eq!(cslearn::Cost::ZERO.get(), 0.0);
    /// ```
    pub const ZERO: Cost = Cost(0.0);

    /// One unit: the cost every feature has when costs are ignored.
    ///
    /// ```
    /// assert_eq!(cslearn::Cost::ONE.get(), 1.0);
    /// ```
    pub const ONE: Cost = Cost(1.0);

    /// A cost, if `value` is finite and not negative (`-0.0` becomes `0.0`).
    ///
    /// ```
    /// assert_eq!(cslearn::Cost::new(0.25).unwrap().get(), 0.25);
    /// assert!(cslearn::Cost::new(f64::INFINITY).is_err());
    /// ```
    pub fn new(value: f64) -> Result<Cost, Error> {
        if value.is_finite() && value >= 0.0 {
            // Adding 0.0 turns -0.0 into 0.0, so equal costs are bitwise equal.
            Ok(Cost(value + 0.0))
        } else {
            Err(Error::InvalidCost { value })
        }
    }

    /// The cost as a number.
    ///
    /// ```
    /// assert_eq!(cslearn::Cost::ONE.get(), 1.0);
    /// ```
    pub const fn get(self) -> f64 {
        self.0
    }
}

impl Eq for Cost {}

impl PartialOrd for Cost {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Cost {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

impl Add for Cost {
    type Output = Cost;
    fn add(self, rhs: Cost) -> Cost {
        // Saturate rather than reach infinity, so a sum is still a valid cost.
        Cost((self.0 + rhs.0).min(f64::MAX))
    }
}

impl AddAssign for Cost {
    fn add_assign(&mut self, rhs: Cost) {
        *self = *self + rhs;
    }
}

impl std::iter::Sum for Cost {
    fn sum<I: Iterator<Item = Cost>>(iter: I) -> Cost {
        iter.fold(Cost::ZERO, Add::add)
    }
}

impl fmt::Display for Cost {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

impl<'de> Deserialize<'de> for Cost {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Cost, D::Error> {
        let value = f64::deserialize(deserializer)?;
        Cost::new(value).map_err(serde::de::Error::custom)
    }
}

/// Where the price of each feature comes from.
///
/// `None` means the feature cannot be measured at all; selection never proposes it.
/// Implemented for [`FeatureCosts`], for slices of [`Cost`] indexed by [`FeatureId`],
/// and for [`CostBlind`].
///
/// ```
/// use cslearn::{Cost, Costs, FeatureId};
/// let table = [Cost::ONE, Cost::new(7.27).unwrap()];
/// assert_eq!(table[..].cost(FeatureId(1)), Some(Cost::new(7.27).unwrap()));
/// assert_eq!(table[..].cost(FeatureId(2)), None);
/// ```
pub trait Costs {
    /// The price of measuring `feature`, or `None` if it cannot be measured.
    fn cost(&self, feature: FeatureId) -> Option<Cost>;
}

impl Costs for [Cost] {
    fn cost(&self, feature: FeatureId) -> Option<Cost> {
        self.get(feature.index()).copied()
    }
}

impl<C: Costs + ?Sized> Costs for &C {
    fn cost(&self, feature: FeatureId) -> Option<Cost> {
        (**self).cost(feature)
    }
}

/// The costs of a wrapped table with every price replaced by [`Cost::ONE`]: what plain,
/// cost-blind ID3 sees. Features the table does not know stay unmeasurable.
///
/// ```
/// use cslearn::{Cost, CostBlind, Costs, FeatureCosts, FeatureId};
/// let costs = FeatureCosts::from_f64(&[1.0, 102.9]).unwrap();
/// assert_eq!(CostBlind(&costs).cost(FeatureId(1)), Some(Cost::ONE));
/// assert_eq!(CostBlind(&costs).cost(FeatureId(2)), None);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct CostBlind<C>(pub C);

impl<C: Costs> Costs for CostBlind<C> {
    fn cost(&self, feature: FeatureId) -> Option<Cost> {
        self.0.cost(feature).map(|_| Cost::ONE)
    }
}

/// A dense table of feature costs, with the feature order used for "the next cheapest
/// feature": ascending cost, ties by ascending [`FeatureId`].
///
/// Features are numbered `0..len()`. New features may be added at any time with
/// [`push`](FeatureCosts::push) (no closed world); the order is kept up to date.
///
/// ```
/// use cslearn::{FeatureCosts, FeatureId};
/// let mut costs = FeatureCosts::from_f64(&[5.0, 1.0, 5.0]).unwrap();
/// assert_eq!(costs.order(), &[FeatureId(1), FeatureId(0), FeatureId(2)]);
/// let f = costs.push(cslearn::Cost::ZERO);
/// assert_eq!(costs.order()[0], f);
/// assert_eq!(costs.total().get(), 11.0);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FeatureCosts {
    costs: Vec<Cost>,
    order: Vec<FeatureId>,
}

impl FeatureCosts {
    /// A table from one cost per feature, feature `i` at index `i`.
    ///
    /// ```
    /// use cslearn::{Cost, FeatureCosts};
    /// let costs = FeatureCosts::new(vec![Cost::ONE; 3]);
    /// assert_eq!(costs.len(), 3);
    /// ```
    pub fn new(costs: Vec<Cost>) -> FeatureCosts {
        let mut table = FeatureCosts {
            costs,
            order: Vec::new(),
        };
        table.reorder();
        table
    }

    /// A table from plain numbers, refusing any that is negative or not finite.
    ///
    /// ```
    /// assert!(cslearn::FeatureCosts::from_f64(&[1.0, -2.0]).is_err());
    /// ```
    pub fn from_f64(costs: &[f64]) -> Result<FeatureCosts, Error> {
        let costs = costs
            .iter()
            .map(|&c| Cost::new(c))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(FeatureCosts::new(costs))
    }

    /// Add a new feature with its cost and return its id.
    ///
    /// ```
    /// let mut costs = cslearn::FeatureCosts::new(Vec::new());
    /// assert_eq!(costs.push(cslearn::Cost::ONE), cslearn::FeatureId(0));
    /// ```
    pub fn push(&mut self, cost: Cost) -> FeatureId {
        let id = FeatureId(self.costs.len() as u32);
        self.costs.push(cost);
        self.reorder();
        id
    }

    fn reorder(&mut self) {
        self.order = (0..self.costs.len() as u32).map(FeatureId).collect();
        // A stable sort on cost keeps ascending ids among equal costs.
        self.order.sort_by_key(|f| self.costs[f.index()]);
    }

    /// The number of features.
    ///
    /// ```
    /// assert_eq!(cslearn::FeatureCosts::from_f64(&[1.0]).unwrap().len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        self.costs.len()
    }

    /// Whether there are no features.
    ///
    /// ```
    /// assert!(cslearn::FeatureCosts::new(Vec::new()).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.costs.is_empty()
    }

    /// Every feature, cheapest first, ties by ascending id.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::from_f64(&[2.0, 1.0]).unwrap();
    /// assert_eq!(costs.order()[0], cslearn::FeatureId(1));
    /// ```
    pub fn order(&self) -> &[FeatureId] {
        &self.order
    }

    /// The costs, indexed by feature.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::from_f64(&[2.0]).unwrap();
    /// assert_eq!(costs.as_slice()[0].get(), 2.0);
    /// ```
    pub fn as_slice(&self) -> &[Cost] {
        &self.costs
    }

    /// The cost of measuring every feature once.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::from_f64(&[2.0, 0.5]).unwrap();
    /// assert_eq!(costs.total().get(), 2.5);
    /// ```
    pub fn total(&self) -> Cost {
        self.costs.iter().copied().sum()
    }
}

impl Costs for FeatureCosts {
    fn cost(&self, feature: FeatureId) -> Option<Cost> {
        self.costs.cost(feature)
    }
}
