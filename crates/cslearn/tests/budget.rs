//! A hard budget per object: classifying within it never pays more than it allows (in
//! price or in tests), whatever values are missing; without a limit it is plain
//! classification to the bit; a budget of nothing answers from the root; the greedy
//! growers grow no path the budget cannot pay for. Companions show the budget checks
//! failing on what plain classification and unbudgeted growth do.

use std::path::Path;

use cslearn::testcost::{
    ActParams, Budget, Catalogue, Classification, Column, CostTree, CvtParams, FamilyParams, Frame,
    IcetParams, MISSING, Method, MisclassCosts, Split, TestPrices, fit, laplace,
};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// A random data set: 30 to 69 objects, 2 or 3 classes, 3 to 5 features (numeric or
/// nominal) that tell the class through noise, about one value in eight missing.
fn random_frame(seed: u64) -> (Frame, TestPrices) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let n = rng.random_range(30..70usize);
    let k = rng.random_range(2..4u32);
    let m = rng.random_range(3..6usize);
    let classes: Vec<u32> = (0..n).map(|i| (i as u32) % k).collect();
    let mut columns = Vec::new();
    for _ in 0..m {
        let noise = rng.random_range(0.0..0.8);
        let mut told = |c: u32| -> u32 {
            if rng.random_bool(noise) {
                rng.random_range(0..k)
            } else {
                c
            }
        };
        if m % 2 == 0 || columns.len() % 2 == 0 {
            let x: Vec<f64> = classes
                .iter()
                .map(|&c| f64::from(told(c)) + f64::from(c) * 0.1)
                .collect();
            let x = x
                .into_iter()
                .map(|v| if rng.random_bool(0.125) { f64::NAN } else { v })
                .collect();
            columns.push(Column::Numeric(x));
        } else {
            let codes: Vec<u32> = classes.iter().map(|&c| told(c)).collect();
            let codes = codes
                .into_iter()
                .map(|v| if rng.random_bool(0.125) { MISSING } else { v })
                .collect();
            let values = (0..k).map(|v| format!("v{v}")).collect();
            columns.push(Column::Nominal { values, codes });
        }
    }
    let names = (0..m).map(|f| format!("f{f}")).collect();
    let class_names = (0..k).map(|c| format!("c{c}")).collect();
    let frame = Frame::new(names, columns, classes, class_names).unwrap();
    let prices: Vec<f64> = (0..m).map(|_| rng.random_range(1.0..20.0)).collect();
    (frame, TestPrices::flat(&prices).unwrap())
}

/// Small searches, so that every learner runs in a debug build.
fn params() -> FamilyParams {
    FamilyParams {
        icet: IcetParams {
            population: 6,
            generations: 3,
            ..IcetParams::default()
        },
        act: ActParams::with_samples(2).unwrap(),
        cvt: CvtParams::with_folds(2).unwrap(),
        ..FamilyParams::default()
    }
}

/// Heart and hepatitis with Turney's prices (groups and discounts) and missing values.
fn turney(name: &str) -> (Frame, TestPrices) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
    let loaded = catalogue.load(name).unwrap();
    (loaded.frame, loaded.turney.unwrap())
}

/// The budgets every check runs through: by count, by price, both, and nothing at all.
fn budgets(prices: &TestPrices) -> Vec<Budget> {
    let mean = prices.total() / prices.len() as f64;
    let mut all = vec![Budget::new(Some(0.0), None).unwrap()];
    for k in 0..4 {
        all.push(Budget::new(None, Some(k)).unwrap());
    }
    for f in [0.5, 1.0, 1.7, 2.5, 4.0] {
        all.push(Budget::new(Some(mean * f), None).unwrap());
        all.push(Budget::new(Some(mean * f), Some(2)).unwrap());
    }
    all
}

/// Whether what `c` paid and bought is within `budget`.
fn within(c: &Classification, budget: &Budget) -> bool {
    budget.max_test_cost().is_none_or(|b| c.test_cost <= b)
        && budget.max_tests().is_none_or(|k| c.tests.len() <= k)
}

fn bits(c: &Classification) -> (u32, u64, Vec<usize>, Vec<u64>) {
    (
        c.class,
        c.test_cost.to_bits(),
        c.tests.clone(),
        c.probabilities.iter().map(|p| p.to_bits()).collect(),
    )
}

/// Every learner's tree, on random data with missing values and on Turney's, classified
/// within each budget: no object pays more, or buys more tests, than it allows; the
/// probabilities sum to one; an unlimited budget is plain classification, to the bit.
#[test]
fn no_object_passes_its_budget() {
    let mut sets: Vec<(Frame, TestPrices)> = (0..6).map(random_frame).collect();
    sets.push(turney("heart"));
    sets.push(turney("hepatitis"));
    let mut checked = 0;
    for (s, (frame, prices)) in sets.iter().enumerate() {
        let mc = MisclassCosts::uniform(frame.class_count(), 200.0).unwrap();
        let rows: Vec<usize> = (0..frame.len()).collect();
        let methods: &[Method] = if s < 6 {
            &Method::ALL
        } else {
            &[Method::Eg2, Method::C45, Method::Dtmc, Method::Idx]
        };
        for &method in methods {
            let tree = fit(method, frame, &rows, prices, &mc, &params(), s as u64).tree;
            for &row in &rows {
                let plain = tree.classify(frame, row, prices);
                let free = tree.classify_within(frame, row, prices, &Budget::UNLIMITED);
                assert_eq!(bits(&plain), bits(&free), "{} row {row}", method.name());
                for budget in budgets(prices) {
                    let c = tree.classify_within(frame, row, prices, &budget);
                    assert!(
                        within(&c, &budget),
                        "{} set {s} row {row}: {c:?} past {budget:?}",
                        method.name()
                    );
                    let sum: f64 = c.probabilities.iter().sum();
                    assert!((sum - 1.0).abs() < 1e-9);
                    if within(&plain, &budget) {
                        // What plain classification could afford, it still gets.
                        assert_eq!(bits(&plain), bits(&c), "{} row {row}", method.name());
                    }
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 10_000, "{checked}");
}

/// The companion: plain classification does pass these budgets, so the check above can
/// fail.
#[test]
fn plain_classification_passes_the_budgets() {
    let (frame, prices) = turney("heart");
    let mc = MisclassCosts::uniform(2, 200.0).unwrap();
    let rows: Vec<usize> = (0..frame.len()).collect();
    let tree = fit(Method::Id3, &frame, &rows, &prices, &mc, &params(), 0).tree;
    let passed = budgets(&prices)
        .iter()
        .filter(|b| {
            rows.iter()
                .any(|&r| !within(&tree.classify(&frame, r, &prices), b))
        })
        .count();
    assert!(passed >= 8, "{passed}");
}

/// A budget of nothing (no price, or no test) answers from the root, paying nothing,
/// with the root's smoothed class weights.
#[test]
fn a_budget_of_nothing_answers_from_the_root() {
    for seed in 0..4 {
        let (frame, prices) = random_frame(seed);
        let mc = MisclassCosts::uniform(frame.class_count(), 200.0).unwrap();
        let rows: Vec<usize> = (0..frame.len()).collect();
        for method in [Method::Id3, Method::Eg2, Method::Act] {
            let tree = fit(method, &frame, &rows, &prices, &mc, &params(), seed).tree;
            let root = tree.node(0);
            assert!(root.split.is_some() || method == Method::Act);
            for budget in [Budget::new(Some(0.0), None), Budget::new(None, Some(0))] {
                let budget = budget.unwrap();
                for &row in &rows {
                    let c = tree.classify_within(&frame, row, &prices, &budget);
                    assert_eq!((c.class, c.test_cost, c.tests.len()), (root.label, 0.0, 0));
                    assert_eq!(c.probabilities, laplace(&root.weights));
                }
            }
        }
    }
}

/// What the most expensive root-to-leaf path of `tree` pays (prices after the path, as
/// classification charges them) and the most distinct tests on one path.
fn dearest_path(tree: &CostTree, prices: &TestPrices) -> (f64, usize) {
    let mut worst = (0.0f64, 0usize);
    let mut stack = vec![(0usize, Vec::<usize>::new(), 0.0)];
    while let Some((i, path, paid)) = stack.pop() {
        worst = (worst.0.max(paid), worst.1.max(path.len()));
        let children: Vec<u32> = match &tree.node(i).split {
            None => continue,
            Some(Split::Nominal { children, .. }) => children.clone(),
            Some(Split::Threshold { children, .. }) => children.to_vec(),
        };
        let feature = tree.node(i).split.as_ref().unwrap().feature();
        let (mut below, mut paid_below) = (path.clone(), paid);
        if !path.contains(&feature) {
            let group = prices.test(feature).group;
            let grouped = group.is_some() && path.iter().any(|&d| prices.test(d).group == group);
            paid_below += if grouped {
                prices.test(feature).discount
            } else {
                prices.test(feature).full
            };
            below.push(feature);
        }
        for c in children {
            stack.push((c as usize, below.clone(), paid_below));
        }
    }
    worst
}

/// The greedy learners grow within the budget: no path of their trees costs more, or
/// holds more distinct tests, than it allows (Turney's groups and discounts counted as
/// classification counts them), while without the budget some path does.
#[test]
fn greedy_trees_grow_within_the_budget() {
    let mut grown_past = 0;
    for name in ["heart", "hepatitis"] {
        let (frame, prices) = turney(name);
        let mc = MisclassCosts::uniform(2, 500.0).unwrap();
        let rows: Vec<usize> = (0..frame.len()).collect();
        for method in Method::ALL.into_iter().filter(|m| m.grows_within_budget()) {
            let free = fit(method, &frame, &rows, &prices, &mc, &params(), 0).tree;
            let (free_cost, free_tests) = dearest_path(&free, &prices);
            for budget in budgets(&prices) {
                let params = FamilyParams { budget, ..params() };
                let tree = fit(method, &frame, &rows, &prices, &mc, &params, 0).tree;
                let (cost, tests) = dearest_path(&tree, &prices);
                let name = method.name();
                assert!(
                    budget.max_test_cost().is_none_or(|b| cost <= b + 1e-9),
                    "{name}: a path of {cost} past {budget:?}"
                );
                assert!(
                    budget.max_tests().is_none_or(|k| tests <= k),
                    "{name}: a path of {tests} tests past {budget:?}"
                );
                let past = budget.max_test_cost().is_some_and(|b| free_cost > b)
                    || budget.max_tests().is_some_and(|k| free_tests > k);
                grown_past += usize::from(past);
            }
        }
    }
    assert!(grown_past > 50, "{grown_past}");
}

/// With no limit set, every learner's tree is the one it grows with the default
/// settings: the budget is a setting that changes nothing until it is used.
#[test]
fn an_unlimited_budget_changes_no_tree() {
    let (frame, prices) = random_frame(11);
    let mc = MisclassCosts::uniform(frame.class_count(), 200.0).unwrap();
    let rows: Vec<usize> = (0..frame.len()).collect();
    let explicit = FamilyParams {
        budget: Budget::new(None, None).unwrap(),
        ..params()
    };
    for method in Method::ALL {
        let a = fit(method, &frame, &rows, &prices, &mc, &params(), 4);
        let b = fit(method, &frame, &rows, &prices, &mc, &explicit, 4);
        assert_eq!(a, b, "{}", method.name());
    }
}
