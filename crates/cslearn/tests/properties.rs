//! Properties of the learners and trees on random small problems.

use std::collections::BTreeMap;

use cslearn::{
    ClassId, Cost, Costs, DecisionTree, Example, FeatureCosts, FeatureId, Library, Sensor,
    TreeOptions, Value,
};
use proptest::prelude::*;

/// A sensor that adds up the price of every measurement made through it, independently of
/// the learner's ledger.
struct Metered<'a> {
    row: &'a [Option<Value>],
    costs: &'a FeatureCosts,
    spent: f64,
    measured: Vec<FeatureId>,
}

impl Sensor for Metered<'_> {
    fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        self.spent += self.costs.cost(feature).map_or(0.0, Cost::get);
        self.measured.push(feature);
        self.row.get(feature.index()).copied().flatten()
    }
}

/// Dense objects with their classes.
type Objects = Vec<(Vec<Option<Value>>, ClassId)>;

/// Learn an object of the given class, then classify it again.
type LearnThenClassify<'a> = dyn FnMut(&[Option<Value>], ClassId) -> Option<ClassId> + 'a;

/// Distinct complete objects over `features` features with up to 3 values each, and a
/// class for each: noiseless and non-contradictory by construction.
fn problem() -> impl Strategy<Value = (Vec<f64>, Objects)> {
    (1_usize..6).prop_flat_map(|features| {
        let costs = prop::collection::vec(prop_oneof![Just(0.0), 0.5_f64..20.0], features);
        let objects =
            prop::collection::btree_map(prop::collection::vec(0_u32..3, features), 0_u32..3, 1..24);
        (costs, objects).prop_map(|(costs, objects): (Vec<f64>, BTreeMap<Vec<u32>, u32>)| {
            let objects = objects
                .into_iter()
                .map(|(row, class)| {
                    (
                        row.into_iter().map(|v| Some(Value(v))).collect(),
                        ClassId(class),
                    )
                })
                .collect();
            (costs, objects)
        })
    })
}

/// The case a random seed drew for incremental ID3 (every price 0, five features): its
/// recheck ended with a round that classified the object correctly but had just paid for
/// more of it, so the stored example changed after the check, and the next classification
/// took another path and answered class 1 for an object learned as class 0.
#[test]
fn a_recheck_that_changed_the_example_checks_again() {
    use rand::SeedableRng;
    let objects: [([u32; 5], u32); 15] = [
        ([0, 0, 0, 0, 1], 2),
        ([0, 0, 0, 0, 2], 0),
        ([0, 1, 0, 0, 0], 1),
        ([0, 1, 1, 0, 0], 0),
        ([0, 1, 2, 0, 1], 0),
        ([0, 2, 0, 0, 0], 0),
        ([0, 2, 0, 0, 1], 0),
        ([0, 2, 0, 1, 0], 2),
        ([1, 0, 0, 0, 1], 2),
        ([2, 0, 1, 0, 2], 0),
        ([2, 0, 1, 1, 0], 1),
        ([2, 0, 2, 0, 0], 1),
        ([2, 1, 0, 0, 0], 0),
        ([2, 1, 0, 0, 1], 0),
        ([2, 1, 1, 0, 0], 0),
    ];
    let picks = [
        547, 940, 993, 477, 683, 105, 2, 218, 885, 550, 273, 100, 796, 361, 621, 332, 417, 904,
        157, 850, 567, 706, 584, 262, 780, 224, 321, 540, 338, 656, 418, 812, 428, 983, 200, 981,
        474, 385, 761, 44, 800, 980, 292, 892, 349, 213, 475, 39, 14, 676,
    ];
    let costs = FeatureCosts::from_f64(&[0.0; 5]).unwrap();
    let rng = || rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(picks.len() as u64);
    let mut plain = cslearn::id3(costs.clone(), rng());
    let mut indexed = cslearn::id3_indexed(costs, rng());
    for (n, &pick) in picks.iter().enumerate() {
        let (row, class) = &objects[pick % objects.len()];
        let row: Vec<Option<Value>> = row.iter().map(|&v| Some(Value(v))).collect();
        let class = ClassId(*class);
        plain.learn(&row[..], class);
        indexed.learn(&row[..], class);
        assert_eq!(
            plain.classify(&row[..]).class,
            Some(class),
            "object {n}, plain"
        );
        assert_eq!(
            indexed.classify(&row[..]).class,
            Some(class),
            "object {n}, indexed"
        );
    }
}

fn stream_order(n: usize) -> impl Strategy<Value = Vec<usize>> {
    prop::collection::vec(0..n, 1..60)
}

proptest! {
    // A fixed seed: the same cases on every run (the case another seed once drew, where the
    // recheck stopped too early, is `a_recheck_that_changed_the_example_checks_again`).
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(1),
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_learned_object_is_classified_correctly_when_it_comes_again(
        (costs, objects) in problem(),
        picks in stream_order(1000),
        which in 0_u8..3,
    ) {
        let costs = FeatureCosts::from_f64(&costs).unwrap();
        let learn_then_classify = |learner: &mut LearnThenClassify<'_>| {
            for &pick in &picks {
                let (row, class) = &objects[pick % objects.len()];
                prop_assert_eq!(learner(row, *class), Some(*class));
            }
            Ok(())
        };
        match which {
            0 => {
                let mut l = cslearn::cs_id3(costs);
                learn_then_classify(&mut |row, c| { l.learn(row, c); l.classify(row).class })?;
            }
            1 => {
                let mut l = cslearn::cs_ibl(costs, 1);
                learn_then_classify(&mut |row, c| { l.learn(row, c); l.classify(row).class })?;
            }
            _ => {
                use rand::SeedableRng;
                let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(picks.len() as u64);
                let mut l = cslearn::id3(costs, rng);
                learn_then_classify(&mut |row, c| { l.learn(row, c); l.classify(row).class })?;
            }
        }
    }

    #[test]
    fn charged_cost_is_the_sum_of_the_costs_of_the_features_measured(
        (costs, objects) in problem(),
        picks in stream_order(1000),
        which in 0_u8..3,
    ) {
        let costs = FeatureCosts::from_f64(&costs).unwrap();
        let run = |learn: &mut dyn FnMut(&mut Metered<'_>, ClassId) -> cslearn::Outcome| {
            for &pick in &picks {
                let (row, class) = &objects[pick % objects.len()];
                let mut sensor = Metered { row, costs: &costs, spent: 0.0, measured: Vec::new() };
                let outcome = learn(&mut sensor, *class);
                prop_assert!((outcome.cost.get() - sensor.spent).abs() <= 1e-9);
                prop_assert_eq!(outcome.measured, sensor.measured.len());
                // No feature is ever paid for twice on one object.
                let mut seen = sensor.measured.clone();
                seen.sort();
                seen.dedup();
                prop_assert_eq!(seen.len(), sensor.measured.len());
            }
            Ok(())
        };
        match which {
            0 => { let mut l = cslearn::cs_id3(costs.clone()); run(&mut |s, c| l.learn(s, c))?; }
            1 => { let mut l = cslearn::cs_ibl(costs.clone(), 1); run(&mut |s, c| l.learn(s, c))?; }
            _ => {
                use rand::SeedableRng;
                let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(picks.len() as u64);
                let mut l = cslearn::id3(costs.clone(), rng);
                run(&mut |s, c| l.learn(s, c))?;
            }
        }
    }

    #[test]
    fn an_observation_tree_classifies_every_training_example_to_its_class(
        costs in prop::collection::vec(0.0_f64..20.0, 1..6),
        raw in prop::collection::btree_map(
            prop::collection::btree_map(0_u32..6, 0_u32..3, 0..6),
            0_u32..3,
            1..30,
        ),
    ) {
        let costs = FeatureCosts::from_f64(&costs).unwrap();
        let n = costs.len() as u32;
        // Distinct feature sets with one class each: a non-contradictory library.
        let mut distinct: BTreeMap<Vec<(FeatureId, Value)>, ClassId> = BTreeMap::new();
        for (pairs, class) in raw {
            let pairs: Vec<_> = pairs
                .into_iter()
                .filter(|&(f, _)| f < n)
                .map(|(f, v)| (FeatureId(f), Value(v)))
                .collect();
            distinct.entry(pairs).or_insert(ClassId(class));
        }
        let library: Library = distinct
            .into_iter()
            .map(|(pairs, class)| Example::from_pairs(pairs, class))
            .collect();
        let tree = DecisionTree::build(&library, &costs, TreeOptions::observations());
        for example in &library {
            let result = tree.classify(example);
            prop_assert_eq!(result.class, Some(example.class()));
            // The charge is the sum of the prices along the path, at most everything once.
            prop_assert!(result.cost.get() <= costs.total().get() + 1e-9);
        }
    }

    #[test]
    fn a_rule_tree_classifies_each_object_matching_exactly_one_rule_to_it(
        costs in prop::collection::vec(0.5_f64..20.0, 1..5),
        candidates in prop::collection::vec(prop::collection::btree_map(0_u32..5, 0_u32..3, 0..5), 1..20),
    ) {
        let costs = FeatureCosts::from_f64(&costs).unwrap();
        let n = costs.len() as u32;
        let conflict = |a: &Example, b: &Example| {
            a.pairs().iter().any(|&(f, v)| b.get(f).is_some_and(|w| w != v))
        };
        let mut rules: Vec<Example> = Vec::new();
        for pairs in candidates {
            let rule = Example::from_pairs(
                pairs.into_iter().filter(|&(f, _)| f < n).map(|(f, v)| (FeatureId(f), Value(v))),
                ClassId(rules.len() as u32),
            );
            if rules.iter().all(|r| conflict(r, &rule)) {
                rules.push(rule);
            }
        }
        let library = Library::from(rules);
        let tree = DecisionTree::build(&library, &costs, TreeOptions::rules());
        for code in 0..3_u32.pow(n) {
            let row: Vec<Option<Value>> =
                (0..n).map(|f| Some(Value(code / 3_u32.pow(f) % 3))).collect();
            let matches = |r: &Example| r.pairs().iter().all(|&(f, v)| row[f.index()] == Some(v));
            let matching: Vec<&Example> = library.iter().filter(|r| matches(r)).collect();
            if let [only] = matching[..] {
                prop_assert_eq!(tree.classify(&row[..]).class, Some(only.class()));
            }
        }
    }
}
