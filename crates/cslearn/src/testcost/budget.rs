//! A hard budget per object: at most so many tests, or at most so much in price.
//!
//! The protocol of costly-feature classification holds every object to a budget (a user
//! who may spend at most 20 on a patient says so): a classification never buys a test
//! that would take the object past it, and stops where it is instead
//! ([`CostTree::classify_within`](super::CostTree::classify_within)); the greedy
//! growers refuse, at a node, the tests the node's path cannot afford
//! ([`GrowParams::budget`](super::GrowParams::budget)). Prices are counted as
//! classification charges them: after the tests already bought (a test done once is free,
//! a group's later tests at their discount).

use serde::{Deserialize, Serialize};

use crate::Error;

/// The most one object may spend on tests: a price, a number of distinct tests, both, or
/// neither (the default, [`Budget::UNLIMITED`]).
///
/// A test already bought is free and not counted again; a test of a group already opened
/// is priced at its discount. Both limits are inclusive: an object may spend exactly
/// `max_test_cost` and buy exactly `max_tests` tests.
///
/// ```
/// use cslearn::testcost::Budget;
/// let b = Budget::new(Some(20.0), Some(3)).unwrap();
/// assert_eq!((b.max_test_cost(), b.max_tests()), (Some(20.0), Some(3)));
/// // Having spent 15 on two tests, a third at 5 is allowed, a third at 6 is not.
/// assert!(b.allows(15.0, 2, 5.0, true));
/// assert!(!b.allows(15.0, 2, 6.0, true));
/// // A test already bought costs nothing and is not counted again.
/// assert!(b.allows(20.0, 3, 0.0, false));
/// assert!(Budget::default().is_unlimited());
/// assert!(Budget::new(Some(-1.0), None).unwrap_err().to_string().contains("max_test_cost"));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, try_from = "RawBudget")]
pub struct Budget {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    max_test_cost: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    max_tests: Option<usize>,
}

/// A budget as read, before it is checked.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBudget {
    #[serde(default)]
    max_test_cost: Option<f64>,
    #[serde(default)]
    max_tests: Option<usize>,
}

impl TryFrom<RawBudget> for Budget {
    type Error = Error;

    fn try_from(raw: RawBudget) -> Result<Budget, Error> {
        Budget::new(raw.max_test_cost, raw.max_tests)
    }
}

impl Budget {
    /// No limit: every test the tree asks for is bought.
    pub const UNLIMITED: Budget = Budget {
        max_test_cost: None,
        max_tests: None,
    };

    /// A budget of at most `max_test_cost` in price and at most `max_tests` distinct
    /// tests per object (`None`: no limit of that kind).
    ///
    /// # Errors
    /// [`Error::Invalid`] naming `max_test_cost` when it is negative, infinite or NaN.
    ///
    /// ```
    /// use cslearn::testcost::Budget;
    /// assert!(Budget::new(Some(0.0), Some(0)).is_ok());
    /// let err = Budget::new(Some(f64::NAN), None).unwrap_err().to_string();
    /// assert_eq!(err, "max_test_cost NaN: a budget must be a finite price, not negative");
    /// ```
    pub fn new(max_test_cost: Option<f64>, max_tests: Option<usize>) -> Result<Budget, Error> {
        if let Some(b) = max_test_cost
            && !(b.is_finite() && b >= 0.0)
        {
            return Err(Error::Invalid {
                what: format!("max_test_cost {b}"),
                reason: "a budget must be a finite price, not negative".into(),
            });
        }
        Ok(Budget {
            max_test_cost,
            max_tests,
        })
    }

    /// The most an object may pay for its tests, if limited.
    pub fn max_test_cost(&self) -> Option<f64> {
        self.max_test_cost
    }

    /// The most distinct tests an object may buy, if limited.
    pub fn max_tests(&self) -> Option<usize> {
        self.max_tests
    }

    /// Whether neither limit is set.
    ///
    /// ```
    /// assert!(cslearn::testcost::Budget::UNLIMITED.is_unlimited());
    /// ```
    pub fn is_unlimited(&self) -> bool {
        self.max_test_cost.is_none() && self.max_tests.is_none()
    }

    /// Whether an object that has spent `spent` on `bought` distinct tests may buy one
    /// more at `price` (its price after the tests bought); `new` is false for a test
    /// already bought, which is free and not counted again.
    ///
    /// ```
    /// let b = cslearn::testcost::Budget::new(None, Some(0)).unwrap();
    /// assert!(!b.allows(0.0, 0, 0.0, true));
    /// ```
    pub fn allows(&self, spent: f64, bought: usize, price: f64, new: bool) -> bool {
        if !new {
            return true;
        }
        let count = self.max_tests.is_none_or(|k| bought < k);
        let cost = self.max_test_cost.is_none_or(|b| spent + price <= b);
        count && cost
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_refuses_by_serde() {
        let b: Budget = serde_json::from_str(r#"{"max_test_cost": 2.5}"#).unwrap();
        assert_eq!(b, Budget::new(Some(2.5), None).unwrap());
        assert_eq!(serde_json::to_string(&Budget::UNLIMITED).unwrap(), "{}");
        let err = serde_json::from_str::<Budget>(r#"{"max_test_cost": -1.0}"#).unwrap_err();
        assert!(err.to_string().contains("max_test_cost -1"), "{err}");
        assert!(serde_json::from_str::<Budget>(r#"{"max_cost": 1.0}"#).is_err());
    }

    #[test]
    fn infinite_is_refused() {
        assert!(Budget::new(Some(f64::INFINITY), None).is_err());
    }
}
