//! Cross-validation and the benchmark's scores: total cost per object, and as a
//! percentage of Turney's standard cost.

use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

use super::criterion::Criterion;
use super::data::Frame;
use super::prices::{MisclassCosts, TestPrices};
use super::splits::Splits;
use super::tree::GrowParams;

/// Stratified folds: the objects of each class shuffled by `seed` and dealt in turn,
/// so every fold has each class in proportion. Returns the test objects of each fold:
/// `k` folds, or one per object where `k` is larger (no fold is left empty).
///
/// ```
/// # use cslearn::testcost::{folds, Column, Frame};
/// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0; 10])],
///     vec![0, 0, 0, 0, 0, 1, 1, 1, 1, 1], vec!["a".into(), "b".into()]).unwrap();
/// let f = folds(&frame, 5, 7);
/// assert_eq!(f.len(), 5);
/// assert!(f.iter().all(|fold| fold.len() == 2));
/// assert_eq!(folds(&frame, 1 << 40, 7).len(), 10);
/// ```
pub fn folds(frame: &Frame, k: usize, seed: u64) -> Vec<Vec<usize>> {
    let all: Vec<usize> = (0..frame.len()).collect();
    folds_of(frame, &all, k, seed)
}

/// [`folds`] of the objects `rows` only.
pub(super) fn folds_of(frame: &Frame, rows: &[usize], k: usize, seed: u64) -> Vec<Vec<usize>> {
    // Folds beyond the objects would stay empty: they are not made (the others are the
    // same), so a huge `k` allocates nothing.
    let k = k.clamp(1, rows.len().max(1));
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); frame.class_count()];
    for &r in rows {
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

/// Each feature's information gain on all of `frame`'s objects, as a tree's root would
/// score it (C4.5's rule for missing values; a numeric feature at its best threshold); 0
/// for a feature that cannot split them.
///
/// ```
/// # use cslearn::testcost::{feature_gains, Column, Frame};
/// let frame = Frame::new(vec!["tells".into(), "not".into()],
///     vec![Column::Numeric(vec![0.0, 0.0, 1.0, 1.0]), Column::Numeric(vec![0.0, 1.0, 0.0, 1.0])],
///     vec![0, 0, 1, 1], vec!["a".into(), "b".into()]).unwrap();
/// let gains = feature_gains(&frame);
/// assert!((gains[0] - 1.0).abs() < 1e-12 && gains[1].abs() < 1e-12);
/// ```
pub fn feature_gains(frame: &Frame) -> Vec<f64> {
    let rows: Vec<usize> = (0..frame.len()).collect();
    let weights = vec![1.0; rows.len()];
    let mc = MisclassCosts::uniform(frame.class_count(), 1.0)
        .unwrap_or_else(|_| unreachable!("a uniform cost of 1 is valid"));
    let mut params = GrowParams::new(Criterion::Id3);
    params.min_objects = 1.0;
    let mut splits = Splits::new(
        frame,
        &rows,
        &weights,
        &mc,
        Criterion::Id3,
        params.min_objects,
    );
    let mut gains = vec![0.0; frame.feature_count()];
    for stat in splits.stats(0) {
        gains[stat.feature] = stat.gain.max(0.0);
    }
    gains
}

/// Random prices that follow information gain: each test's price uniform in
/// `[low, low + (high - low) * g / g_max]`, with `g` its gain on the whole data set
/// ([`feature_gains`]) and `g_max` the largest; informative tests may be dear, tests that
/// tell nothing are cheap. With no gain anywhere, every price is `low`.
///
/// ```
/// # use cslearn::testcost::{gain_prices, Column, Frame};
/// let frame = Frame::new(vec!["tells".into(), "not".into()],
///     vec![Column::Numeric(vec![0.0, 0.0, 1.0, 1.0]), Column::Numeric(vec![0.0, 1.0, 0.0, 1.0])],
///     vec![0, 0, 1, 1], vec!["a".into(), "b".into()]).unwrap();
/// let prices = gain_prices(&frame, 1.0, 100.0, 3);
/// assert_eq!(prices.test(1).full, 1.0);
/// assert!((1.0..=100.0).contains(&prices.test(0).full));
/// ```
pub fn gain_prices(frame: &Frame, low: f64, high: f64, seed: u64) -> TestPrices {
    let (low, high) = (low.max(0.0), high.max(low.max(0.0)));
    let gains = feature_gains(frame);
    let top = gains.iter().copied().fold(0.0, f64::max);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let prices: Vec<f64> = gains
        .iter()
        .map(|&g| {
            let ceiling = if top > 0.0 {
                low + (high - low) * g / top
            } else {
                low
            };
            if ceiling > low {
                rng.random_range(low..=ceiling)
            } else {
                low
            }
        })
        .collect();
    TestPrices::flat_checked_by_caller(&prices)
}

/// Fisher-Yates with the crate's generator, so results do not depend on rand's own
/// shuffle changing between versions.
pub(crate) fn shuffle<T, R: rand::Rng>(items: &mut [T], rng: &mut R) {
    for i in (1..items.len()).rev() {
        let j = rng.random_range(0..=i);
        items.swap(i, j);
    }
}
