//! Action selection: Boltzmann draws follow the stated probabilities, and no
//! temperature or value range makes them NaN or panic.

use mdp::ActionId;
use proptest::prelude::*;
use qlearn::{Discount, LearningRate, QTable, RowId, Target, Temperature};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// A one-row table holding exactly `q`.
fn row_with(q: &[f64]) -> QTable {
    let mut t = QTable::with_rows(q.len(), 1).unwrap();
    let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.0).unwrap());
    for (a, &x) in q.iter().enumerate() {
        t.update(
            RowId(0),
            ActionId(a as u32),
            x,
            Target::Terminal,
            beta,
            gamma,
        );
    }
    assert_eq!(t.q_row(RowId(0)), q);
    t
}

#[test]
fn boltzmann_frequencies_match_the_probabilities() {
    let q = [0.0, 0.5, 0.2, 0.45];
    let mut table = row_with(&q);
    let t = Temperature::new(0.4).unwrap();
    // The paper's formula, computed directly (safe here: small Q over T).
    let e: Vec<f64> = q.iter().map(|x| (x / 0.4f64).exp()).collect();
    let p: Vec<f64> = e.iter().map(|x| x / e.iter().sum::<f64>()).collect();
    for (a, b) in p.iter().zip(table.boltzmann_probabilities(RowId(0), t)) {
        assert!((a - b).abs() < 1e-12);
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let n = 100_000;
    let mut counts = [0u32; 4];
    for _ in 0..n {
        counts[table.boltzmann(RowId(0), t, &mut rng).index()] += 1;
    }
    for (a, &c) in counts.iter().enumerate() {
        let freq = f64::from(c) / f64::from(n);
        // Five standard deviations of a binomial share.
        let sd = (p[a] * (1.0 - p[a]) / f64::from(n)).sqrt();
        assert!(
            (freq - p[a]).abs() < 5.0 * sd,
            "action {a}: {freq} vs {}",
            p[a]
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::Direct("proptest-regressions/selection.txt"),
        )),
        ..ProptestConfig::default()
    })]

    /// Q anywhere in [-1e6, 1e6], T anywhere in [1e-6, 1e6]: probabilities are finite,
    /// sum to 1, favour the greedy action, and draws stay in range.
    #[test]
    fn boltzmann_is_finite_for_extreme_values_and_temperatures(
        q in prop::collection::vec(-1e6..1e6f64, 1..6),
        log_t in -6.0..6.0f64,
        seed in any::<u64>(),
    ) {
        let mut table = row_with(&q);
        let t = Temperature::new(10f64.powf(log_t)).unwrap();
        let p = table.boltzmann_probabilities(RowId(0), t);
        prop_assert!(p.iter().all(|x| x.is_finite() && *x >= 0.0));
        prop_assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-9);
        let greedy = table.greedy(RowId(0)).index();
        prop_assert!(p.iter().all(|&x| x <= p[greedy]));
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        for _ in 0..32 {
            let a = table.boltzmann(RowId(0), t, &mut rng);
            prop_assert!(a.index() < q.len());
            prop_assert!(p[a.index()] > 0.0, "drew an action of probability 0");
        }
    }
}
