//! The selection functions of the test-cost family: how a test is scored at a node.
//!
//! Apart from the trees that use it, so that the split trie (which needs to know whether
//! a criterion scores by costs) and the grower both depend on it and not on each other.

/// How a test is scored at a node: the selection function of each learner.
///
/// `gain` is the information gain of the split on the objects whose value is known,
/// times their share (C4.5's rule for missing values); `price` the test's price on the
/// node's path (0 once bought, the discount after another test of its group).
///
/// ```
/// use cslearn::testcost::Criterion;
/// let (gain, price) = (0.5, 4.0);
/// assert_eq!(Criterion::Idx.score(gain, 1.0, price), 0.125);
/// assert_eq!(Criterion::CsId3.score(gain, 1.0, price), 0.0625);
/// let eg2 = Criterion::Eg2 { w: 1.0 }.score(gain, 1.0, price);
/// assert!((eg2 - (2f64.sqrt() - 1.0) / 5.0).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Criterion {
    /// Quinlan's ID3: the information gain.
    Id3,
    /// C4.5: the gain ratio, among the tests whose gain is at least the average.
    C45,
    /// Norton's IDX (1989): gain / price.
    Idx,
    /// Tan's CS-ID3 (1991): gain^2 / price.
    CsId3,
    /// Núñez's EG2 (1991): (2^gain - 1) / (price + 1)^w.
    Eg2 {
        /// How much the price counts (1: fully, 0: not at all).
        w: f64,
    },
    /// Ling, Yang, Wang and Zhang's DTMC (2004): the reduction of the expected total cost
    /// (tests plus misclassification) of the node's objects.
    Dtmc,
}

/// The smallest price a ratio divides by, so that a free test (bought already) scores
/// by its gain among free tests, above every priced one.
const FREE: f64 = 1e-6;

impl Criterion {
    /// The score of a test with this gain, split information and price (for DTMC the
    /// score is computed from costs, not from these: see [`CostTree::grow`](super::CostTree::grow)).
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::Criterion::C45.score(0.4, 0.8, 3.0), 0.5);
    /// ```
    pub fn score(self, gain: f64, split_info: f64, price: f64) -> f64 {
        let price_floor = price.max(FREE);
        match self {
            Criterion::Id3 | Criterion::Dtmc => gain,
            Criterion::C45 => {
                if split_info > 0.0 {
                    gain / split_info
                } else {
                    0.0
                }
            }
            Criterion::Idx => gain / price_floor,
            Criterion::CsId3 => gain * gain / price_floor,
            Criterion::Eg2 { w } => (gain.exp2() - 1.0) / (price + 1.0).powf(w),
        }
    }
}
