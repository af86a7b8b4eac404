//! The test-cost family: each selection function against hand-computed choices, C4.5's
//! pruning by hand, group discounts, missing values, ICET's seed, the shipped data sets
//! and the refusals of bad cost files.

use std::path::Path;

use cslearn::testcost::{
    Catalogue, Column, CostTree, Criterion, FamilyParams, Frame, GrowParams, Method, MisclassCosts,
    SelectionPrices, Split, TestPrice, TestPrices, TurneyExtra, fit, fit_each, standard_cost,
};

/// Eight objects, four of each class. Feature `a` (price 10) tells the class exactly:
/// gain 1. Feature `b` (price 1) splits them 3:1 and 1:3: gain 1 - H(1/4) = 0.18872.
fn two_features() -> Frame {
    let a = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let b = vec![0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0];
    Frame::new(
        vec!["a".into(), "b".into()],
        vec![Column::Numeric(a), Column::Numeric(b)],
        vec![0, 0, 0, 0, 1, 1, 1, 1],
        vec!["no".into(), "yes".into()],
    )
    .unwrap()
}

fn root_test(criterion: Criterion, mc: f64) -> Option<usize> {
    let frame = two_features();
    let prices = TestPrices::flat(&[10.0, 1.0]).unwrap();
    let mc = MisclassCosts::uniform(2, mc).unwrap();
    let rows: Vec<usize> = (0..8).collect();
    let tree = CostTree::grow(&frame, &rows, &prices, &mc, &GrowParams::new(criterion));
    tree.node(0).split.as_ref().map(Split::feature)
}

#[test]
fn each_selection_function_picks_the_hand_computed_test() {
    let gain_b = 1.0 - (-(0.25f64 * 0.25f64.log2() + 0.75 * 0.75f64.log2()));
    assert!((gain_b - 0.188_72).abs() < 1e-5);
    // ID3 and C4.5: the larger gain (ratio): a (1 against 0.189).
    assert_eq!(root_test(Criterion::Id3, 100.0), Some(0));
    assert_eq!(root_test(Criterion::C45, 100.0), Some(0));
    // IDX, gain / price: a 1/10 = 0.1, b 0.189 / 1: b.
    assert_eq!(root_test(Criterion::Idx, 100.0), Some(1));
    // CS-ID3, gain^2 / price: a 0.1, b 0.0356: a.
    assert!(gain_b * gain_b < 0.1);
    assert_eq!(root_test(Criterion::CsId3, 100.0), Some(0));
    // EG2 (w = 1), (2^gain - 1) / (price + 1): a 1/11 = 0.0909, b 0.1397 / 2 = 0.0698: a;
    // with w = 0 the price does not count and the gain decides.
    assert!((gain_b.exp2() - 1.0) / 2.0 < 1.0 / 11.0);
    assert_eq!(root_test(Criterion::Eg2 { w: 1.0 }, 100.0), Some(0));
    // DTMC, reduction of expected total cost. mc = 10: as a leaf 4 * 10 = 40; a leaves 0
    // errors but costs 8 * 10 = 80 (reduction -40); b leaves 2 errors (20) for 8 * 1
    // (reduction 12): b. mc = 100: a 400 - 80 = 320, b 400 - 200 - 8 = 192: a.
    assert_eq!(root_test(Criterion::Dtmc, 10.0), Some(1));
    assert_eq!(root_test(Criterion::Dtmc, 100.0), Some(0));
    // mc = 1: no test pays for itself (a: 4 - 80, b: 4 - 2 - 8): a leaf.
    assert_eq!(root_test(Criterion::Dtmc, 1.0), None);
}

/// The root's feature, the feature tested in its upper branch and what object 6 pays, in
/// an unpruned IDX tree over twelve objects: `x` (price 1) is 0..=11, `y` (price 2) is 1
/// for x <= 3 and then tells the class exactly.
fn idx_test_above_the_root(selection: SelectionPrices) -> (usize, Option<usize>, f64) {
    let x: Vec<f64> = (0..12).map(f64::from).collect();
    // Classes by x: 0..=3 no; then no no yes no yes yes no yes.
    let class = vec![0, 0, 0, 0, 0, 0, 1, 0, 1, 1, 0, 1];
    let y: Vec<f64> = (0..12)
        .map(|i| if i < 4 { 1.0 } else { f64::from(class[i]) })
        .collect();
    let frame = Frame::new(
        vec!["x".into(), "y".into()],
        vec![Column::Numeric(x), Column::Numeric(y)],
        class.iter().map(|&c| c as u32).collect(),
        vec!["no".into(), "yes".into()],
    )
    .unwrap();
    let prices = TestPrices::flat(&[1.0, 2.0]).unwrap();
    let mc = MisclassCosts::uniform(2, 100.0).unwrap();
    let rows: Vec<usize> = (0..12).collect();
    let grow = GrowParams::new(Criterion::Idx).selecting_at(selection);
    let tree = CostTree::grow(&frame, &rows, &prices, &mc, &grow);
    let Some(Split::Threshold {
        feature, children, ..
    }) = tree.node(0).split.clone()
    else {
        panic!("the root should split on a threshold: {:?}", tree.node(0));
    };
    let below = tree
        .node(children[1] as usize)
        .split
        .as_ref()
        .map(Split::feature);
    // What object 6 (x = 6, class yes) pays on its way down.
    let paid = tree.classify(&frame, 6, &prices).test_cost;
    (feature, below, paid)
}

#[test]
fn selection_prices_listed_charge_a_numeric_re_test_where_path_prices_do_not() {
    // At the root (8 no, 4 yes; H = 0.9183): x at 5.5 leaves 6 no | 2 no 4 yes, gain
    // 0.9183 - 6/12 H(1/3) = 0.4591, IDX 0.4591 / 1; y leaves 4 no | 4 no 4 yes, gain
    // 0.2516, IDX 0.2516 / 2: x, either way.
    // Above 5.5 (2 no, 4 yes): y tells the class, gain 0.9183, IDX 0.9183 / 2 = 0.4591; x
    // again at its best threshold, 6.5 (1 yes | 2 no 3 yes), gains 0.9183 - 5/6 H(2/5) =
    // 0.1092. After the path x is free, so IDX splits on it again.
    let (root, below, _) = idx_test_above_the_root(SelectionPrices::Path);
    assert_eq!((root, below), (0, Some(0)));
    // At its listed price x scores 0.1092 / 1 < 0.4591: y.
    let (root, below, paid) = idx_test_above_the_root(SelectionPrices::Listed);
    assert_eq!((root, below), (0, Some(1)));
    // The object still pays each test once: x, then y.
    assert_eq!(paid, 3.0);
}

#[test]
fn pessimistic_pruning_matches_a_hand_computed_tree() {
    // Ten objects: x < 5 are class a except one b at x = 2; x >= 5 are class b.
    // The full tree splits at 4.5, then the left side again around the odd object.
    let x: Vec<f64> = (0..10).map(f64::from).collect();
    let classes = vec![0, 0, 1, 0, 0, 1, 1, 1, 1, 1];
    let frame = Frame::new(
        vec!["x".into()],
        vec![Column::Numeric(x)],
        classes,
        vec!["a".into(), "b".into()],
    )
    .unwrap();
    let prices = TestPrices::flat(&[1.0]).unwrap();
    let mc = MisclassCosts::uniform(2, 1.0).unwrap();
    let rows: Vec<usize> = (0..10).collect();
    let mut params = GrowParams::new(Criterion::Id3);
    params.min_objects = 1.0;
    let full = CostTree::grow(&frame, &rows, &prices, &mc, &params);
    assert!(full.len() > 3, "the full tree isolates the odd object");
    // By hand, at confidence 0.25 (z = 0.6925, z^2 = 0.4796), estimated errors
    // N * U(E, N): the left node (5 objects, 1 error) as a leaf, with e = E + 0.5:
    // (1.5 + 0.2398 + sqrt(0.4796 * (1.5 * 0.7 + 0.1199))) / 5.4796 = 0.4542, so 2.271;
    // its subtree's three pure leaves of 2, 1 and 2 objects, N (1 - 0.25^(1/N)) each:
    // 1 + 0.75 + 1 = 2.75. As 2.271 <= 2.75 + 0.1, the left subtree becomes a leaf.
    // The root (10 objects, 4 errors) as a leaf: 5.587; its subtree: 2.271 + 1.211
    // (5 pure objects) = 3.482: the root's split stays.
    let leaf = |n: f64| n * (1.0 - 0.25f64.powf(1.0 / n));
    assert!((leaf(2.0) - 1.0).abs() < 1e-12 && (leaf(1.0) - 0.75).abs() < 1e-12);
    let pruned = CostTree::grow(&frame, &rows, &prices, &mc, &params.pruned(0.25));
    assert_eq!(pruned.len(), 3, "root split kept, the left subtree pruned");
    let Some(Split::Threshold { at, .. }) = &pruned.node(0).split else {
        panic!("the root keeps its threshold");
    };
    assert_eq!(*at, 4.5);
}

#[test]
fn a_group_discount_is_charged_once_per_group_and_object() {
    // The class is x AND y (each combination twice): the tree tests x, then y where x is
    // 1. x and y form one group (full 10, discount 2); z, alone at 5, tells nothing.
    let x = vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0];
    let y = vec![0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0];
    let z = vec![0.0; 8];
    let classes = vec![0, 0, 0, 1, 0, 0, 0, 1];
    let frame = Frame::new(
        vec!["x".into(), "y".into(), "z".into()],
        vec![Column::Numeric(x), Column::Numeric(y), Column::Numeric(z)],
        classes,
        vec!["no".into(), "yes".into()],
    )
    .unwrap();
    let grouped = |full, discount| TestPrice {
        full,
        discount,
        group: Some(0),
        delayed: false,
    };
    let prices = TestPrices::new(
        vec![
            grouped(10.0, 2.0),
            grouped(10.0, 2.0),
            TestPrice {
                full: 5.0,
                discount: 5.0,
                group: None,
                delayed: false,
            },
        ],
        vec!["blood".into()],
    )
    .unwrap();
    assert_eq!(prices.total(), 17.0);
    let mc = MisclassCosts::uniform(2, 1000.0).unwrap();
    let rows: Vec<usize> = (0..8).collect();
    let mut params = GrowParams::new(Criterion::Id3);
    params.min_objects = 1.0;
    let tree = CostTree::grow(&frame, &rows, &prices, &mc, &params);
    for r in 0..8 {
        let c = tree.classify(&frame, r, &prices);
        assert_eq!(c.class, frame.class(r));
        if frame.column(0).is_missing(r) {
            continue;
        }
        let Column::Numeric(x) = frame.column(0) else {
            unreachable!()
        };
        if x[r] == 1.0 {
            // x in full, then y at its discount: 12, not 20.
            assert_eq!((c.tests.clone(), c.test_cost), (vec![0, 1], 12.0));
        } else {
            assert_eq!((c.tests.clone(), c.test_cost), (vec![0], 10.0));
        }
    }
}

#[test]
fn a_missing_value_follows_every_branch_and_pays_their_tests() {
    // x decides the class; y splits the objects with x = 1 again (pure by then, so never).
    let x = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, f64::NAN];
    let frame = Frame::new(
        vec!["x".into()],
        vec![Column::Numeric(x)],
        vec![0, 0, 0, 1, 1, 1, 1],
        vec!["a".into(), "b".into()],
    )
    .unwrap();
    let prices = TestPrices::flat(&[4.0]).unwrap();
    let mc = MisclassCosts::from_rows(&[vec![0.0, 1.0], vec![50.0, 0.0]]).unwrap();
    let rows: Vec<usize> = (0..6).collect();
    let mut params = GrowParams::new(Criterion::Id3);
    params.min_objects = 1.0;
    let tree = CostTree::grow(&frame, &rows, &prices, &mc, &params);
    let c = tree.classify(&frame, 6, &prices);
    // It pays for x once, and is answered by the mix (half a, half b): answering a would
    // cost 0.5 * 50 for the b half, answering b 0.5 * 1: b.
    assert_eq!((c.test_cost, c.tests.clone()), (4.0, vec![0]));
    assert_eq!(c.class, 1);
}

/// ACT's choice by hand, on `two_features` with `a` at 30 and `b` at 1, samples of 5.
/// EG2 takes `b` (0.1398 / 2 = 0.070 against 1 / 31 = 0.032). ACT prices each candidate
/// by its price for the 8 objects plus the cheapest sampled subtree per branch, a leaf
/// costing its pessimistic errors (confidence 0.25) times `mc`:
/// - `a`: 30 * 8 + two pure leaves of 4 (1.172 added errors each) = 240 + 2.343 mc;
/// - `b`: 1 * 8 + two leaves of 4 with one error (2.189 each; `a` cannot split them,
///   a branch of 1 is below the least of 2) = 8 + 4.379 mc;
/// - a leaf at the root (4 errors of 8, 5.416) = 5.416 mc.
///
/// So ACT takes `a` when 2.036 mc > 232 (mc = 500: 1412 against 2198) and `b` below
/// (mc = 50: 357 against 227, the leaf 271).
#[test]
fn act_splits_where_the_sampled_subtrees_cost_least() {
    let frame = two_features();
    let prices = TestPrices::flat(&[30.0, 1.0]).unwrap();
    let rows: Vec<usize> = (0..8).collect();
    let root = |method: Method, mc: f64| {
        let mc = MisclassCosts::uniform(2, mc).unwrap();
        let fitted = fit(
            method,
            &frame,
            &rows,
            &prices,
            &mc,
            &FamilyParams::default(),
            3,
        );
        fitted.tree.node(0).split.as_ref().map(Split::feature)
    };
    assert_eq!(root(Method::Eg2, 500.0), Some(1));
    assert_eq!(root(Method::Act, 500.0), Some(0));
    assert_eq!(root(Method::Act, 50.0), Some(1));
    // Where errors are nearly free, no test pays for itself: 5.416 * 5 = 27.1 against
    // 8 + 21.9 for `b`.
    assert_eq!(root(Method::Act, 5.0), None);
}

/// Heart with Turney's prices, mc 500, and every second object to learn from.
fn heart_at_mc_500() -> (Frame, TestPrices, MisclassCosts, Vec<usize>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
    let heart = catalogue.load("heart").unwrap();
    let rows: Vec<usize> = (0..heart.frame.len()).step_by(2).collect();
    let mc = MisclassCosts::uniform(2, 500.0).unwrap();
    (heart.frame, heart.turney.unwrap(), mc, rows)
}

/// ACT's samples flow from its seed: the same seed grows the same tree, and on a data
/// set with many candidate tests another seed grows another.
#[test]
fn act_is_reproducible_from_its_seed() {
    let (frame, prices, mc, rows) = heart_at_mc_500();
    let params = FamilyParams::default();
    let grown = |seed| fit(Method::Act, &frame, &rows, &prices, &mc, &params, seed).tree;
    assert_eq!(grown(7), grown(7));
    assert!((1..6).any(|seed| grown(seed) != grown(7)));
}

/// Every learner's trees at several costs at once are its trees at each cost alone (for
/// those whose tree does not depend on the costs, the tree at the first cost labelled at
/// each): on heart, with missing values and group discounts, every second object.
#[test]
fn fit_each_grows_what_fit_grows_at_each_cost() {
    let (frame, prices, _, rows) = heart_at_mc_500();
    let rows: Vec<usize> = rows.into_iter().step_by(2).collect();
    let mcs: Vec<MisclassCosts> = [50.0, 500.0, 5000.0]
        .map(|m| MisclassCosts::uniform(2, m).unwrap())
        .to_vec();
    let mut params = FamilyParams::default();
    params.icet.generations = 3;
    params.icet.population = 6;
    params.act.samples = 2;
    for method in Method::ALL {
        let each = fit_each(method, &frame, &rows, &prices, &mcs, &params, 11);
        assert_eq!(each.len(), mcs.len());
        for (fitted, mc) in each.iter().zip(&mcs) {
            let mut alone = if method.depends_on_mc() {
                fit(method, &frame, &rows, &prices, mc, &params, 11)
            } else {
                fit(method, &frame, &rows, &prices, &mcs[0], &params, 11)
            };
            alone.tree.relabel(mc);
            assert_eq!(fitted, &alone, "{} at {mc:?}", method.name());
        }
    }
    assert!(fit_each(Method::Act, &frame, &rows, &prices, &[], &params, 11).is_empty());
}

/// CVT's cross-validation grows its roots on several threads to the same tree and the
/// same choice as on one, whatever the number of threads (0: every core).
#[test]
fn cvt_grows_the_same_tree_on_any_number_of_threads() {
    let (frame, prices, mc, rows) = heart_at_mc_500();
    let mut params = FamilyParams::default();
    params.act.samples = 1;
    let grown = |threads| {
        let params = FamilyParams {
            cvt: params.cvt.with_threads(threads),
            ..params
        };
        fit(Method::Cvt, &frame, &rows, &prices, &mc, &params, 5)
    };
    let one = grown(1);
    for threads in [2, 3, 7, 0] {
        assert_eq!(grown(threads), one, "{threads} threads");
    }
}

#[test]
fn icet_is_reproducible_from_its_seed() {
    let (frame, prices, mc, rows) = heart_at_mc_500();
    let mut params = FamilyParams::default();
    params.icet.generations = 4;
    params.icet.population = 12;
    let one = fit(Method::Icet, &frame, &rows, &prices, &mc, &params, 7);
    let again = fit(Method::Icet, &frame, &rows, &prices, &mc, &params, 7);
    let other = fit(Method::Icet, &frame, &rows, &prices, &mc, &params, 8);
    assert_eq!(one.tree, again.tree);
    assert_eq!(one.genome, again.genome);
    assert_ne!(one.genome, other.genome);
    // The search starts from plain EG2, so its best is never worse on its own halves.
    let genome = one.genome.unwrap();
    assert!(genome.fitness.is_finite() && genome.fitness > 0.0);
}

#[test]
fn every_shipped_data_set_loads_with_its_documented_classes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
    let expected: &[(&str, usize, usize)] = &[
        ("breast-cancer", 286, 2),
        ("bupa", 345, 2),
        ("car", 1728, 4),
        ("flare", 1066, 2),
        ("glass", 214, 6),
        ("heart", 303, 2),
        ("hepatitis", 155, 2),
        ("iris", 150, 3),
        ("krk", 28056, 18),
        ("monks1", 124, 2),
        ("monks2", 169, 2),
        ("monks3", 122, 2),
        ("nursery", 12960, 5),
        ("pima", 768, 2),
        ("tae", 151, 3),
        ("thyroid", 7200, 3),
        ("tic-tac-toe", 958, 2),
        ("titanic", 2201, 2),
        ("spambase", 4601, 2),
        ("cube", 10000, 8),
    ];
    assert_eq!(catalogue.sources().len(), expected.len());
    for &(name, objects, classes) in expected {
        let loaded = catalogue.load(name).unwrap();
        assert_eq!(
            (loaded.frame.len(), loaded.frame.class_count()),
            (objects, classes),
            "{name}"
        );
    }
    let heart = catalogue.load("heart").unwrap();
    assert_eq!(heart.frame.class_totals(), vec![164, 139]);
    let thyroid = catalogue.load("thyroid").unwrap();
    let prices = thyroid.turney.unwrap();
    // 16 history tests at 1, the blood group (TSH, T3, TT4, T4U, FTI) with one draw.
    let fti = thyroid.frame.feature("FTI").unwrap();
    assert_eq!(prices.test(fti).group, Some(0));
    let pima = catalogue.load("pima").unwrap();
    assert!((pima.turney.unwrap().total() - (6.0 + 17.61 + 20.68)).abs() < 1e-9);
    // Turney's standard cost on heart at mc 500: all tests 323.97 + (139/303) * 500.
    let standard = standard_cost(
        &heart.frame,
        &heart.turney.unwrap(),
        &MisclassCosts::uniform(2, 500.0).unwrap(),
    );
    assert!((standard - (323.97 + 139.0 / 303.0 * 500.0)).abs() < 1e-9);
    // Spambase: the header line skipped, 57 numeric tests named as UCI names them, its
    // classes as UCI counts them; kept out of the benchmark, every test priced 1.
    let spambase = catalogue.load("spambase").unwrap();
    assert_eq!(spambase.frame.feature_count(), 57);
    assert_eq!(spambase.frame.class_totals(), vec![2788, 1813]);
    assert_eq!(spambase.frame.feature("capital_run_length_total"), Some(56));
    assert!(spambase.turney.is_none());
    let source = |name: &str| catalogue.sources().iter().find(|s| s.name == name).unwrap();
    assert!(!source("spambase").benchmark && source("spambase").unit_prices);
    assert!(!source("cube").benchmark && source("cube").unit_prices);
    assert!(source("heart").benchmark && !source("heart").unit_prices);
    let benchmark: Vec<&str> = catalogue.benchmark().map(|s| s.name.as_str()).collect();
    assert_eq!(benchmark.len(), expected.len() - 2);
    assert!(!benchmark.contains(&"spambase") && !benchmark.contains(&"cube"));
}

/// The manifest's `benchmark` and `unit_prices` keys: absent, a data set is the
/// benchmark's and has no unit prices; `benchmark = false` leaves it out of
/// [`Catalogue::benchmark`] but not out of [`Catalogue::sources`]; a misspelt key or a
/// value of the wrong kind is refused, naming the manifest and its line.
#[test]
fn the_benchmark_key_keeps_a_data_set_out_of_the_benchmark_only() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    let dir = tempfile::tempdir().unwrap();
    let iris = std::fs::read_to_string(root.join("iris/iris.data")).unwrap();
    std::fs::write(dir.path().join("iris.data"), iris).unwrap();
    let entry = |name: &str, extra: &str| {
        format!(
            "[[dataset]]\nname = \"{name}\"\nfiles = [\"iris.data\"]\n\
             columns = [\"a\", \"b\", \"c\", \"d\", \"class\"]\ntarget = \"class\"\n{extra}\n"
        )
    };
    let manifest = dir.path().join("datasets.toml");
    std::fs::write(
        &manifest,
        entry("one", "")
            + &entry("two", "benchmark = false\nunit_prices = true")
            + &entry("three", "benchmark = true"),
    )
    .unwrap();
    let catalogue = Catalogue::read(&manifest).unwrap();
    let names: Vec<&str> = catalogue.benchmark().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["one", "three"]);
    assert_eq!(catalogue.sources().len(), 3);
    let units: Vec<bool> = catalogue.sources().iter().map(|s| s.unit_prices).collect();
    assert_eq!(units, [false, true, false]);
    // A set left out of the benchmark still loads by name.
    assert_eq!(catalogue.load("two").unwrap().frame.len(), 150);
    for bad in ["benchmark = \"no\"", "unit_price = true"] {
        std::fs::write(&manifest, entry("one", bad)).unwrap();
        let err = Catalogue::read(&manifest).unwrap_err().to_string();
        assert!(
            err.contains("datasets.toml") && err.contains("line"),
            "{bad}: {err}"
        );
    }
}

fn turney_dir(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    dir
}

fn read(dir: &tempfile::TempDir) -> Result<TestPrices, cslearn::Error> {
    let names: Vec<String> = ["age", "chol", "fbs"].map(String::from).to_vec();
    TestPrices::read_turney(&dir.path().join("t"), &names, &TurneyExtra::default())
}

#[test]
fn bad_cost_files_are_refused_naming_file_and_line() {
    let ok = turney_dir(&[
        (
            "t.expense",
            "age: 1.00, 1.00\nchol: 7.27, 5.17\nfbs: 5.20, 3.10\n",
        ),
        ("t.group", "A.\n\nchol: A.\nfbs: A.\n"),
    ]);
    let prices = read(&ok).unwrap();
    assert!((prices.total() - (1.0 + 5.17 + 3.10 + 2.10)).abs() < 1e-9);

    let unknown = turney_dir(&[("t.expense", "age: 1, 1\nchol: 7, 5\nfbs: 5, 3\nzap: 2, 2\n")]);
    let e = read(&unknown).unwrap_err().to_string();
    assert!(
        e.contains("t.expense: line 4") && e.contains("`zap` is not a column"),
        "{e}"
    );

    let negative = turney_dir(&[("t.expense", "age: 1, 1\nchol: -7, 5\nfbs: 5, 3\n")]);
    let e = read(&negative).unwrap_err().to_string();
    assert!(e.contains("line 2") && e.contains("`-7`"), "{e}");

    let nan = turney_dir(&[("t.expense", "age: 1, 1\nchol: 7, NaN\nfbs: 5, 3\n")]);
    let e = read(&nan).unwrap_err().to_string();
    assert!(e.contains("line 2") && e.contains("`NaN`"), "{e}");

    let no_discount = turney_dir(&[
        ("t.cost", "age: 1\nchol: 7.27\nfbs: 5.20\n"),
        ("t.group", "A.\nchol: A.\n"),
    ]);
    let e = read(&no_discount).unwrap_err().to_string();
    assert!(
        e.contains("t.group: line 2") && e.contains("no discount price"),
        "{e}"
    );

    let missing = turney_dir(&[("t.expense", "age: 1, 1\nchol: 7, 5\n")]);
    let e = read(&missing).unwrap_err().to_string();
    assert!(e.contains("no price for column `fbs`"), "{e}");

    let unknown_group = turney_dir(&[
        ("t.expense", "age: 1, 1\nchol: 7, 5\nfbs: 5, 3\n"),
        ("t.group", "A.\nchol: B.\n"),
    ]);
    let e = read(&unknown_group).unwrap_err().to_string();
    assert!(e.contains("line 2") && e.contains("group `B`"), "{e}");
}

#[test]
fn bad_misclassification_matrices_are_refused() {
    assert!(MisclassCosts::from_rows(&[vec![0.0, 1.0], vec![1.0]]).is_err());
    assert!(MisclassCosts::from_rows(&[vec![0.0, -1.0], vec![1.0, 0.0]]).is_err());
    assert!(MisclassCosts::from_rows(&[vec![0.0, f64::NAN], vec![1.0, 0.0]]).is_err());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mc.csv");
    let classes = vec!["no".to_string(), "yes".to_string()];
    std::fs::write(&path, "actual,no,yes\nno,0,10\nyes,100,0\n").unwrap();
    let mc = MisclassCosts::read_csv(&path, &classes).unwrap();
    assert_eq!((mc.cost(1, 0), mc.cost(0, 1)), (10.0, 100.0));
    std::fs::write(&path, "actual,no,yes\nno,0,10\n").unwrap();
    let e = MisclassCosts::read_csv(&path, &classes)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no row for class `yes`"), "{e}");
    std::fs::write(&path, "actual,no,yes\nno,0,-10\nyes,1,0\n").unwrap();
    let e = MisclassCosts::read_csv(&path, &classes)
        .unwrap_err()
        .to_string();
    assert!(e.contains("mc.csv: line 2"), "{e}");
    std::fs::write(&path, "actual,no,yes,maybe\nno,0,1,1\n").unwrap();
    let e = MisclassCosts::read_csv(&path, &classes)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 1") && e.contains("3 class columns"), "{e}");
}

#[test]
fn with_zero_test_prices_the_cost_learners_grow_the_information_tree() {
    // With every price 0, IDX and CS-ID3 rank tests by gain as ID3 does.
    let frame = two_features();
    let prices = TestPrices::flat(&[0.0, 0.0]).unwrap();
    let mc = MisclassCosts::uniform(2, 1.0).unwrap();
    let rows: Vec<usize> = (0..8).collect();
    for criterion in [Criterion::Idx, Criterion::CsId3, Criterion::Eg2 { w: 1.0 }] {
        let tree = CostTree::grow(&frame, &rows, &prices, &mc, &GrowParams::new(criterion));
        assert_eq!(
            tree.node(0).split.as_ref().map(Split::feature),
            Some(0),
            "{criterion:?}"
        );
    }
}

/// 40 objects: `x` (price `price`) tells the class exactly; `noise` (price 1) is a
/// hashed number (SplitMix64's high bits) that tells nothing.
fn signal_and_noise(price: f64) -> (Frame, TestPrices, Vec<usize>) {
    let x: Vec<f64> = (0..40).map(|i| f64::from(i % 2)).collect();
    let noise: Vec<f64> = (0..40u64)
        .map(|i| {
            let mut z = i.wrapping_add(1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 40) as f64
        })
        .collect();
    let frame = Frame::new(
        vec!["x".into(), "noise".into()],
        vec![Column::Numeric(x), Column::Numeric(noise)],
        (0..40).map(|i| i % 2).collect(),
        vec!["even".into(), "odd".into()],
    )
    .unwrap();
    (
        frame,
        TestPrices::flat(&[price, 1.0]).unwrap(),
        (0..40).collect(),
    )
}

/// CVT pays for a test only where the held-out objects say it pays: `x` removes 20
/// errors for 40 tests, so at mc 10 (200 against 40 times its price) it is kept at a
/// price of 2 and cut at a price of 6 (240); a tree on the worthless `noise` is cut back
/// to its root, whatever its training fit.
#[test]
fn cvt_keeps_a_test_where_it_pays_on_held_out_objects() {
    let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    let params = FamilyParams::default();
    let fitted = |price: f64| {
        let (frame, prices, rows) = signal_and_noise(price);
        fit(Method::Cvt, &frame, &rows, &prices, &mc, &params, 1)
    };
    let cheap = fitted(2.0);
    assert_eq!(
        cheap.tree.node(0).split.as_ref().map(Split::feature),
        Some(0)
    );
    assert_eq!(cheap.tree.len(), 3);
    let choice = cheap.cvt.unwrap();
    assert!((choice.held_out_cost - 2.0).abs() < 1e-9, "{choice:?}");
    let dear = fitted(6.0);
    assert_eq!(dear.tree.len(), 1);

    // Only noise to learn from (`x` priced out of reach): a tree fits the noise on its
    // training objects...
    let (frame, _, rows) = signal_and_noise(2.0);
    let noise_only = TestPrices::flat(&[1e9, 0.0]).unwrap();
    let eg2 = GrowParams::new(Criterion::Eg2 { w: 1.0 });
    let grown = CostTree::grow(&frame, &rows, &noise_only, &mc, &eg2);
    assert!(grown.len() > 5, "the noise tree has {} nodes", grown.len());
    // ...and CVT cuts it back, as the held-out objects say it should.
    let cvt = fit(Method::Cvt, &frame, &rows, &noise_only, &mc, &params, 1);
    assert!(
        cvt.tree.len() <= 3,
        "{} nodes, {:?}",
        cvt.tree.len(),
        cvt.cvt
    );
}

/// CVT's folds flow from its seed: the same seed grows the same tree with the same
/// choice, and other seeds measure other held-out costs.
#[test]
fn cvt_is_reproducible_from_its_seed() {
    let (frame, prices, mc, rows) = heart_at_mc_500();
    let params = FamilyParams::default();
    let grown = |seed| fit(Method::Cvt, &frame, &rows, &prices, &mc, &params, seed);
    let (one, again) = (grown(7), grown(7));
    assert_eq!(one.tree, again.tree);
    assert_eq!(one.cvt, again.cvt);
    assert!((1..6).any(|seed| grown(seed).cvt != one.cvt));
}

/// With every test free, CVT's choice is by errors alone, and so is VOI's valuation: over
/// 10 folds of three shipped data sets neither is less accurate than C4.5 beyond noise
/// (VOI with its defaults, three tests ahead on these narrow data sets; looking two ahead
/// it is not, on tic-tac-toe, where the class is three marks in a row: 116 objects wrong
/// for VOI alone against 64 for C4.5). Noise is judged on the objects one learner gets right and the other wrong
/// (McNemar): the learner's extra errors there stay within two standard deviations,
/// `2 sqrt(b + c)`.
#[test]
fn with_free_tests_cvt_and_voi_are_as_accurate_as_c45_within_noise() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
    for name in ["heart", "breast-cancer", "tic-tac-toe"] {
        let frame = catalogue.load(name).unwrap().frame;
        let prices = TestPrices::flat(&vec![0.0; frame.feature_count()]).unwrap();
        let mc = MisclassCosts::uniform(frame.class_count(), 1.0).unwrap();
        let wrong = |method: Method, params: &FamilyParams| {
            let mut wrong = vec![false; frame.len()];
            for (k, test) in cslearn::testcost::folds(&frame, 10, 1).iter().enumerate() {
                let train: Vec<usize> = (0..frame.len()).filter(|r| !test.contains(r)).collect();
                let tree = fit(method, &frame, &train, &prices, &mc, params, k as u64).tree;
                for &r in test {
                    wrong[r] = tree.classify(&frame, r, &prices).class != frame.class(r);
                }
            }
            wrong
        };
        let c45 = wrong(Method::C45, &FamilyParams::default());
        for (method, params) in [
            (Method::Cvt, FamilyParams::default()),
            (Method::Voi, FamilyParams::default()),
        ] {
            let other = wrong(method, &params);
            let only_other = other.iter().zip(&c45).filter(|(v, c)| **v && !**c).count() as f64;
            let only_c45 = other.iter().zip(&c45).filter(|(v, c)| !**v && **c).count() as f64;
            assert!(
                only_other - only_c45 <= 2.0 * (only_other + only_c45).sqrt(),
                "{name}: {} alone errs on {only_other} objects, C4.5 alone on {only_c45}",
                method.name()
            );
        }
    }
}

/// Objects whose class is whether two tests agree (monks1's `a1 == a2`), beside two
/// tests of noise: three values each, drawn by a fixed linear congruential generator.
fn agreeing_pair(n: usize, seed: u64) -> Frame {
    let mut state = seed;
    let mut draw = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) % 3) as u32
    };
    let cells: Vec<[u32; 4]> = (0..n).map(|_| [draw(), draw(), draw(), draw()]).collect();
    let values: Vec<String> = ["a", "b", "c"].iter().map(|v| v.to_string()).collect();
    let columns = (0..4)
        .map(|f| Column::Nominal {
            values: values.clone(),
            codes: cells.iter().map(|c| c[f]).collect(),
        })
        .collect();
    Frame::new(
        ["first", "second", "noise", "more noise"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        columns,
        cells.iter().map(|c| u32::from(c[0] == c[1])).collect(),
        vec!["differ".into(), "agree".into()],
    )
    .unwrap()
}

/// Where the class is whether two tests agree, neither test tells anything alone and
/// the greedy growers do not ask for the pair; CVT's cross-validation takes ACT's
/// lookahead, which does, and answers new objects almost without error.
#[test]
fn cvt_takes_the_lookahead_where_only_a_pair_of_tests_tells_the_class() {
    let frame = agreeing_pair(400, 11);
    let prices = TestPrices::flat(&[1.0; 4]).unwrap();
    let mc = MisclassCosts::uniform(2, 100.0).unwrap();
    let (train, test): (Vec<usize>, Vec<usize>) = (0..frame.len()).partition(|r| r % 2 == 0);
    let params = FamilyParams::default();
    let error_rate = |method: Method| {
        let fitted = fit(method, &frame, &train, &prices, &mc, &params, 3);
        let wrong = test
            .iter()
            .filter(|&&r| fitted.tree.classify(&frame, r, &prices).class != frame.class(r))
            .count();
        (wrong as f64 / test.len() as f64, fitted.cvt)
    };
    let (cvt, choice) = error_rate(Method::Cvt);
    let choice = choice.unwrap();
    assert_eq!(choice.grower_name(), "act", "{choice:?}");
    assert!(cvt < 0.05, "CVT errs on {cvt} of new objects");
    let (eg2, _) = error_rate(Method::Eg2);
    assert!(eg2 > cvt + 0.05, "EG2 errs on {eg2}, CVT on {cvt}");
}
