//! Cross-validation and the benchmark's scores: total cost per object, and as a
//! percentage of Turney's standard cost.

use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

use super::data::Frame;
use super::family::shuffle;
use super::prices::{MisclassCosts, TestPrices};

/// Stratified folds: the objects of each class shuffled by `seed` and dealt in turn,
/// so every fold has each class in proportion. Returns the test objects of each fold.
///
/// ```
/// # use cslearn::testcost::{folds, Column, Frame};
/// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0; 10])],
///     vec![0, 0, 0, 0, 0, 1, 1, 1, 1, 1], vec!["a".into(), "b".into()]).unwrap();
/// let f = folds(&frame, 5, 7);
/// assert_eq!(f.len(), 5);
/// assert!(f.iter().all(|fold| fold.len() == 2));
/// ```
pub fn folds(frame: &Frame, k: usize, seed: u64) -> Vec<Vec<usize>> {
    let k = k.max(1);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); frame.class_count()];
    for r in 0..frame.len() {
        by_class[frame.class(r) as usize].push(r);
    }
    let mut out = vec![Vec::new(); k];
    let mut next = 0;
    for rows in &mut by_class {
        shuffle(rows, &mut rng);
        for &r in rows.iter() {
            out[next % k].push(r);
            next += 1;
        }
    }
    for fold in &mut out {
        fold.sort_unstable();
    }
    out
}

/// Random test prices as the benchmark draws them: each test's price uniform in
/// `[low, high]`, from a Xoshiro256++ generator seeded with `seed`, no groups.
///
/// ```
/// let p = cslearn::testcost::random_prices(3, 1.0, 100.0, 42);
/// assert_eq!(p.len(), 3);
/// assert!((0..3).all(|i| (1.0..=100.0).contains(&p.test(i).full)));
/// assert_eq!(p, cslearn::testcost::random_prices(3, 1.0, 100.0, 42));
/// ```
pub fn random_prices(tests: usize, low: f64, high: f64, seed: u64) -> TestPrices {
    let (low, high) = (low.max(0.0), high.max(low.max(0.0)));
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let prices: Vec<f64> = (0..tests).map(|_| rng.random_range(low..=high)).collect();
    TestPrices::flat_checked_by_caller(&prices)
}

/// Turney's standard cost of a data set under these prices and misclassification costs:
/// every test bought (discounts applied), then the answer of least risk given the class
/// shares of `frame`.
///
/// ```
/// # use cslearn::testcost::{standard_cost, Column, Frame, MisclassCosts, TestPrices};
/// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0; 4])],
///     vec![0, 0, 0, 1], vec!["a".into(), "b".into()]).unwrap();
/// let cost = standard_cost(&frame, &TestPrices::flat(&[10.0]).unwrap(),
///     &MisclassCosts::uniform(2, 100.0).unwrap());
/// assert_eq!(cost, 35.0);
/// ```
pub fn standard_cost(frame: &Frame, prices: &TestPrices, mc: &MisclassCosts) -> f64 {
    let n = frame.len() as f64;
    let shares: Vec<f64> = frame.class_totals().iter().map(|&c| c as f64 / n).collect();
    mc.standard_cost(&shares, prices)
}
