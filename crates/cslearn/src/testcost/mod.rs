//! The test-cost tree family: batch decision trees that pay for their tests and for
//! their errors, measured as their field measures them.
//!
//! A classification's **total cost** is the price of the tests it paid for plus the
//! misclassification cost of its answer ([`MisclassCosts`], a uniform `mc` or a full
//! matrix). Test prices ([`TestPrices`]) follow Turney's (1995) cost files: the first test
//! of a group ordered for an object is paid in full, later tests of the same group at
//! their discount price, and a test done once is free on the rest of the path
//! ([`Basket`]). Numeric features split at thresholds (binary, at the midpoint between
//! two values seen), nominal ones into one branch per value; an object whose value is
//! missing goes down every branch with its weight split as the known objects split (C4.5's
//! rule), in training and in classification, where it pays for the tests of every branch
//! it follows. Every node answers the class of least expected misclassification cost, not
//! the majority; beside the answer, a classification gives the probability of each class
//! ([`Classification::probabilities`]): the class weights of the node that answered (the
//! mix of the leaves reached, below a missing value), smoothed by Laplace's rule.
//!
//! # The family as instances of the five functions
//!
//! Tan's framework has five functions. For a batch tree they read: **attend** (which
//! training objects speak at a node: those reaching it, with C4.5's fractional weights),
//! **select** (which test to split on), **predict** (what a node answers), **discriminate**
//! (when to stop splitting and what to undo afterwards: the stopping rule and pruning)
//! and **update** (what is learned from the objects: one pass over them, or ICET's search
//! over the learner's own parameters). One grower ([`CostTree::grow`]) serves them all;
//! the table says which functions each learner changes from ID3's.
//!
//! | learner ([`Method`]) | attend | select ([`Criterion`]) | predict | discriminate | update |
//! |---|---|---|---|---|---|
//! | `id3-batch` | reaching objects | gain | least mc cost | stop at no gain | one pass |
//! | `c45` | same | **gain ratio** among tests of at least average gain, threshold penalty | same | **pessimistic pruning**, confidence 0.25 | one pass |
//! | `idx` (Norton 1989) | same | **gain / price** | same | pruning as C4.5 | one pass |
//! | `cs-id3-batch` (Tan 1991) | same | **gain² / price** | same | pruning as C4.5 | one pass |
//! | `eg2` (Núñez 1991) | same | **(2^gain − 1) / (price + 1)^w**, w = 1 | same | pruning as C4.5 | one pass |
//! | `dtmc` (Ling et al. 2004) | same | **reduction of expected total cost** | same | **stop when no test reduces it**, no pruning | one pass |
//! | `icet` (Turney 1995) | same | EG2 over **biased prices** | same | pruning at a **searched confidence** | **genetic search** of prices, w and confidence |
//! | `act` (Esmeir and Markovitch 2008) | same | **least cost of stochastic EG2 trees sampled** under each test | same | **stop when a leaf costs less**, pruning by cost | one pass |
//! | `cvt` (ours: the cost-validated tree) | same | **seven growers** (EG2 at four `w`, gain ratio, DTMC, ACT's lookahead) | same | **cut at a price per leaf or by pessimistic cost**, measured on held-out objects | **cross-validation** of grower and cut |
//! | `voi` (ours: the value-of-information tree) | same | **least expected total cost looking [`VoiParams::lookahead`] tests ahead** | **least mc cost under an m-estimate** of the classes | **stop when stopping costs least** within the lookahead, no pruning | one pass |
//!
//! The price a learner sees at a node is the test's price on that node's path: 0 for a
//! test already done (a numeric feature split again), the discount after another test of
//! its group. The incremental CS-ID3 and CS-IBL of the paper ([`cs_id3`](crate::cs_id3),
//! [`cs_ibl`](crate::cs_ibl)) are the same functions instantiated for objects that come
//! one at a time.
//!
//! # Example
//!
//! ```
//! use cslearn::testcost::{fit, folds, Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices};
//! // Two features that both tell the class: one costs 90, the other 2.
//! let n = 40;
//! let dear: Vec<f64> = (0..n).map(|i| f64::from(i % 2)).collect();
//! let cheap: Vec<f64> = (0..n).map(|i| f64::from(i % 2) * 10.0 + 3.0).collect();
//! let classes: Vec<u32> = (0..n).map(|i| (i % 2) as u32).collect();
//! let frame = Frame::new(vec!["dear".into(), "cheap".into()],
//!     vec![Column::Numeric(dear), Column::Numeric(cheap)], classes,
//!     vec!["no".into(), "yes".into()]).unwrap();
//! let prices = TestPrices::flat(&[90.0, 2.0]).unwrap();
//! let mc = MisclassCosts::uniform(2, 500.0).unwrap();
//! let test = &folds(&frame, 4, 1)[0];
//! let train: Vec<usize> = (0..frame.len()).filter(|r| !test.contains(r)).collect();
//! let c45 = fit(Method::C45, &frame, &train, &prices, &mc, &FamilyParams::default(), 1);
//! let eg2 = fit(Method::Eg2, &frame, &train, &prices, &mc, &FamilyParams::default(), 1);
//! // Cost-blind C4.5 takes the first of two equal tests; EG2 the cheap one.
//! assert_eq!(c45.tree.classify(&frame, test[0], &prices).test_cost, 90.0);
//! assert_eq!(eg2.tree.classify(&frame, test[0], &prices).test_cost, 2.0);
//! ```

mod act;
mod budget;
mod catalogue;
mod criterion;
mod cvt;
mod data;
mod evaluate;
mod family;
mod model;
mod prices;
mod splits;
mod stop;
mod tree;
mod voi;
#[cfg(feature = "work-counts")]
mod work;

pub use act::ActParams;
pub use budget::Budget;
pub use catalogue::{Catalogue, Loaded, Source};
pub use criterion::Criterion;
pub use cvt::{CvtChoice, CvtParams, GROWERS, Grower};
pub use data::{Column, Frame, FrameSpec, MISSING, read_rows};
pub use evaluate::{feature_gains, folds, gain_prices, random_prices, standard_cost};
pub use family::{
    FamilyParams, Fitted, IcetGenome, IcetParams, Method, fit, fit_each, fit_until, mean_total_cost,
};
pub use model::{SavedModel, TREE_MODEL_FORMAT, TREE_MODEL_VERSION, TreeModel};
pub use prices::{Basket, MisclassCosts, TestPrice, TestPrices, TurneyExtra};
pub use stop::Stop;
pub use tree::{
    Classification, CostTree, ExplainedTest, Explanation, FeatureShape, GrowParams, NodeIndex,
    NodeValue, Pruning, SelectionPrices, Split, TreeFault, TreeNode, laplace,
};
pub use voi::{VoiLeaf, VoiParams};
#[cfg(feature = "work-counts")]
pub use work::Work;
