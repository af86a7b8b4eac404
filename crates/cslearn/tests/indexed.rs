//! The indexed learners against the plain procedure, object for object: the same
//! features measured in the same order, the same predictions, the same charges (bit for
//! bit) and the same library. And selection from counts against selection from examples.

use std::path::Path;

use cslearn::{
    ClassId, Cost, Dataset, DatasetOptions, Example, FeatureCosts, FeatureId, InfoCost,
    LearnerKind, MissingRule, Procedure, Semantics, SplitCounts, Value,
};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

type Row = Vec<Option<Value>>;

/// A random stream: `features` features of up to `values` values, some cells missing, a
/// class that mostly follows two features (so there is structure to learn) with some
/// noise (so there are contradictions), and prices drawn from a few values so that ties
/// between features are common.
fn stream(seed: u64, rows: usize, features: usize) -> (FeatureCosts, Vec<(Row, ClassId)>) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let values = rng.random_range(2..5u32);
    let classes = rng.random_range(2..4u32);
    let missing = [0.0, 0.05, 0.3][rng.random_range(0..3usize)];
    let noise = [0.0, 0.1][rng.random_range(0..2usize)];
    let prices = [0.0, 1.0, 1.0, 2.0, 3.0, 7.5];
    let costs: Vec<f64> = (0..features)
        .map(|_| prices[rng.random_range(0..prices.len())])
        .collect();
    let (a, b) = (rng.random_range(0..features), rng.random_range(0..features));
    let objects = (0..rows)
        .map(|_| {
            let full: Vec<u32> = (0..features).map(|_| rng.random_range(0..values)).collect();
            let mut class = (full[a] + 2 * full[b]) % classes;
            if rng.random_bool(noise) {
                class = rng.random_range(0..classes);
            }
            let row = full
                .iter()
                .map(|&v| (!rng.random_bool(missing)).then_some(Value(v)))
                .collect();
            (row, ClassId(class))
        })
        .collect();
    (FeatureCosts::from_f64(&costs).unwrap(), objects)
}

/// Learn (and every third object also classify first) through both learners, checking
/// every outcome and ledger, then the libraries.
fn check_cs_id3(costs: &FeatureCosts, objects: &[(Row, ClassId)], recheck: bool) {
    let mut plain = cslearn::cs_id3(costs.clone()).recheck(recheck);
    let mut fast = cslearn::cs_id3_indexed(costs.clone()).recheck(recheck);
    for (k, (row, class)) in objects.iter().enumerate() {
        if k % 3 == 0 {
            let a = plain.classify(&row[..]);
            let b = fast.classify(&row[..]);
            assert_eq!(a, b, "classify, object {k}");
            assert_eq!(plain.ledger(), fast.ledger(), "classify ledger, object {k}");
        }
        let a = plain.learn(&row[..], *class);
        let b = fast.learn(&row[..], *class);
        assert_eq!(a, b, "object {k}");
        assert_eq!(a.cost.get().to_bits(), b.cost.get().to_bits());
        assert_eq!(plain.ledger(), fast.ledger(), "ledger, object {k}");
    }
    assert_eq!(plain.library(), fast.library());
}

fn check_id3(costs: &FeatureCosts, objects: &[(Row, ClassId)], seed: u64) {
    let rng = || Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut plain = cslearn::id3(costs.clone(), rng());
    let mut fast = cslearn::id3_indexed(costs.clone(), rng());
    for (k, (row, class)) in objects.iter().enumerate() {
        assert_eq!(
            plain.learn(&row[..], *class),
            fast.learn(&row[..], *class),
            "{k}"
        );
        assert_eq!(plain.ledger(), fast.ledger(), "ledger, object {k}");
    }
    assert_eq!(plain.library(), fast.library());
}

#[test]
fn indexed_cs_id3_learns_exactly_as_the_plain_procedure() {
    for seed in 0..120 {
        let features = 1 + (seed as usize % 9);
        let (costs, objects) = stream(seed, 150, features);
        check_cs_id3(&costs, &objects, true);
        if seed % 4 == 0 {
            check_cs_id3(&costs, &objects, false);
        }
    }
}

#[test]
fn indexed_id3_learns_exactly_as_the_plain_procedure() {
    for seed in 0..60 {
        let (costs, objects) = stream(1000 + seed, 150, 2 + (seed as usize % 7));
        check_id3(&costs, &objects, seed);
    }
}

#[test]
fn indexed_cs_id3_agrees_on_a_larger_library() {
    // Enough objects for selections at the top of the tree to change while the library
    // grows, which drops and rebuilds subtrees.
    let (costs, objects) = stream(7, 600, 30);
    check_cs_id3(&costs, &objects, true);
}

/// A stream with many classes: each label a structured part (two features) times
/// `spread`, plus a uniform draw below `spread`, so that most classes have a few examples
/// and some have many; prices as in [`stream`], ties common.
fn stream_many_classes(
    seed: u64,
    rows: usize,
    features: usize,
    spread: u32,
) -> (FeatureCosts, Vec<(Row, ClassId)>) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let values = rng.random_range(2..5u32);
    let missing = [0.0, 0.05, 0.3][rng.random_range(0..3usize)];
    let prices = [0.0, 1.0, 1.0, 2.0, 3.0, 7.5];
    let costs: Vec<f64> = (0..features)
        .map(|_| prices[rng.random_range(0..prices.len())])
        .collect();
    let (a, b) = (rng.random_range(0..features), rng.random_range(0..features));
    let objects = (0..rows)
        .map(|_| {
            let full: Vec<u32> = (0..features).map(|_| rng.random_range(0..values)).collect();
            let class = (full[a] + values * full[b]) * spread + rng.random_range(0..spread);
            let row = full
                .iter()
                .map(|&v| (!rng.random_bool(missing)).then_some(Value(v)))
                .collect();
            (row, ClassId(class))
        })
        .collect();
    (FeatureCosts::from_f64(&costs).unwrap(), objects)
}

#[test]
fn indexed_learners_agree_with_hundreds_of_classes() {
    for seed in 0..8 {
        // From a few examples per class to about one.
        let spread = [40, 100, 200, 1000][seed as usize % 4];
        let features = 3 + (seed as usize % 8);
        let (costs, objects) = stream_many_classes(3000 + seed, 300, features, spread);
        let classes: std::collections::BTreeSet<ClassId> = objects.iter().map(|o| o.1).collect();
        assert!(classes.len() >= 100, "{} classes", classes.len());
        check_cs_id3(&costs, &objects, seed % 3 != 0);
        check_id3(&costs, &objects, seed);
    }
    // Uniform labels over a thousand classes, thirty features.
    let (costs, objects) = stream_many_classes(77, 600, 30, 1000);
    check_cs_id3(&costs, &objects, true);
}

#[test]
fn indexed_learners_agree_on_the_heart_data() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/heart-disease");
    let options = DatasetOptions::new("num").positive_if(">0");
    let data = Dataset::load(&dir.join("cleveland.csv"), &dir.join("costs.csv"), &options).unwrap();
    for seed in 1..=10 {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let objects: Vec<(Row, ClassId)> = data
            .shuffled(&mut rng)
            .iter()
            .map(|&i| (data.object(i).to_vec(), data.labels()[i]))
            .collect();
        check_cs_id3(data.costs(), &objects, true);
        check_id3(data.costs(), &objects, seed);
        for kind in [LearnerKind::CsId3, LearnerKind::Id3] {
            let plain = cslearn::stream_dataset_with(&data, kind, seed, Procedure::Plain);
            let fast = cslearn::stream_dataset(&data, kind, seed);
            assert_eq!(plain, fast);
            assert_eq!(plain.total_cost.to_bits(), fast.total_cost.to_bits());
        }
    }
}

#[test]
fn the_comparison_can_fail() {
    // The same stream with one object's class changed must be told apart: the check above
    // compares something that depends on every object.
    let (costs, objects) = stream(3, 100, 5);
    let mut changed = objects.clone();
    changed[50].1 = ClassId(changed[50].1.0 + 1);
    let mut plain = cslearn::cs_id3(costs.clone());
    let mut fast = cslearn::cs_id3_indexed(costs);
    plain.stream(objects.iter().map(|(r, c)| (&r[..], *c)));
    fast.stream(changed.iter().map(|(r, c)| (&r[..], *c)));
    assert_ne!(plain.library(), fast.library());
}

fn example() -> impl Strategy<Value = Example> {
    (proptest::collection::vec((0..6u32, 0..3u32), 0..6), 0..3u32).prop_map(|(pairs, class)| {
        Example::from_pairs(
            pairs.into_iter().map(|(f, v)| (FeatureId(f), Value(v))),
            ClassId(class),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn selection_from_counts_is_selection_from_examples(
        examples in proptest::collection::vec(example(), 0..25),
        measured in proptest::collection::vec(any::<bool>(), 6),
        prices in proptest::collection::vec(prop_oneof![Just(0.0), Just(1.0), Just(2.0), 0.5..4.0f64], 5),
        c45 in any::<bool>(),
        split in 0..3u8,
        removed in 0..5usize,
    ) {
        // Feature 5 has no price: it must never be chosen by either path.
        let costs: Vec<Cost> = prices.iter().map(|&p| Cost::new(p).unwrap()).collect();
        let missing = if c45 { MissingRule::C45 } else { MissingRule::OwnBranch };
        let make = || {
            let s = InfoCost::new(missing);
            match split {
                0 => s,
                1 => s.requiring_split(Semantics::Observation),
                _ => s.requiring_split(Semantics::Rule),
            }
        };
        let is_measured = |f: FeatureId| measured[f.index()];
        let mut counts = SplitCounts::new();
        // Count some examples in and out again, to check that removing leaves the
        // counts as if they had never been added.
        for e in examples.iter().chain(examples.iter().take(removed)) {
            counts.add(e);
        }
        for e in examples.iter().take(removed) {
            counts.remove(e);
        }
        let by_examples = make().select_from(&examples, is_measured, &costs[..]);
        let by_counts = make().select_from_counts(&counts, is_measured, &costs[..]);
        prop_assert_eq!(by_examples, by_counts);
        prop_assert_eq!(counts.len() as usize, examples.len());
    }
}

/// Few features, many rows, classes the features cannot tell apart: every prediction is
/// wrong at a node holding a share of the whole library. The index's work per object
/// (examples looked at, a count that does not depend on the machine) must not grow with
/// the library as discrimination filtering those conflicting examples made it do
/// (per-object work ~ rows^1 there; the bound here is rows^0.5).
#[test]
fn indexed_work_per_object_grows_slower_than_the_square_root_of_the_rows() {
    let per_object = |rows: usize| {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let costs = FeatureCosts::from_f64(&[1.0, 2.0, 3.0]).unwrap();
        let mut learner = cslearn::cs_id3_indexed(costs);
        for _ in 0..rows {
            let row: Row = (0..3)
                .map(|_| Some(Value(rng.random_range(0..4))))
                .collect();
            learner.learn(&row[..], ClassId(rng.random_range(0..10)));
        }
        learner.examples_visited() as f64 / rows as f64
    };
    let (small, large) = (per_object(4_000), per_object(64_000));
    // 16 times the rows: at most 4 times the work per object.
    assert!(
        large / small <= 4.0,
        "work per object {small:.1} at 4,000 rows, {large:.1} at 64,000"
    );
}
