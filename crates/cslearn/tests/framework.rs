//! Unit tests of the five functions, one section each, and of the learners built on them.

use cslearn::{
    AppendAll, AppendErrors, Attend, Attention, CheapestFirst, ClassId, Cost, Decision,
    Discriminate, Example, FeatureCosts, FeatureId, InfoCost, Ledger, Library, MissingRule,
    Nearest, ObservationAttending, Predict, Probe, RandomOrder, RankedAttending, RuleAttending,
    Select, Unanimous, Update, Value,
};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn ex(pairs: &[(u32, u32)], class: u32) -> Example {
    Example::from_pairs(
        pairs.iter().map(|&(f, v)| (FeatureId(f), Value(v))),
        ClassId(class),
    )
}

fn row(values: &[u32]) -> Vec<Option<Value>> {
    values.iter().map(|&v| Some(Value(v))).collect()
}

// ---- 1. Example attending -------------------------------------------------------------

fn library() -> Library {
    Library::from(vec![
        ex(&[(0, 1), (1, 1)], 0),
        ex(&[(0, 2)], 1),
        ex(&[(1, 1)], 1),
        ex(&[], 0),
    ])
}

#[test]
fn observation_attending_drops_examples_that_lack_or_disagree() {
    let lib = library();
    let mut a = Attention::new();
    ObservationAttending.start(&lib, &mut a);
    assert_eq!(a.attended(), &[0, 1, 2, 3]);
    ObservationAttending.attend(&lib, FeatureId(0), Some(Value(1)), &mut a);
    assert_eq!(a.attended(), &[0]);
}

#[test]
fn rule_attending_keeps_rules_that_lack_the_feature() {
    let lib = library();
    let mut a = Attention::new();
    RuleAttending.start(&lib, &mut a);
    RuleAttending.attend(&lib, FeatureId(0), Some(Value(1)), &mut a);
    assert_eq!(a.attended(), &[0, 2, 3]);
}

#[test]
fn a_missing_value_drops_nothing() {
    let lib = library();
    for attend in [
        &ObservationAttending as &dyn Attend,
        &RuleAttending,
        &RankedAttending { tolerance: 0 },
    ] {
        let mut a = Attention::new();
        attend.start(&lib, &mut a);
        attend.attend(&lib, FeatureId(0), None, &mut a);
        assert_eq!(a.attended(), &[0, 1, 2, 3]);
    }
}

#[test]
fn ranked_attending_counts_mismatches_and_keeps_those_within_tolerance() {
    let lib = library();
    let ranked = RankedAttending { tolerance: 1 };
    let mut a = Attention::new();
    ranked.start(&lib, &mut a);
    ranked.attend(&lib, FeatureId(0), Some(Value(2)), &mut a);
    assert_eq!(a.mismatches(), &[1, 0, 1, 1]);
    assert_eq!(a.attended(), &[0, 1, 2, 3]);
    ranked.attend(&lib, FeatureId(1), Some(Value(1)), &mut a);
    assert_eq!(a.mismatches(), &[1, 1, 1, 2]);
    assert_eq!(a.attended(), &[0, 1, 2]);
    // With tolerance 0 it attends exactly what observation attending attends.
    let (mut strict, mut observed) = (Attention::new(), Attention::new());
    RankedAttending { tolerance: 0 }.start(&lib, &mut strict);
    ObservationAttending.start(&lib, &mut observed);
    for (f, v) in [(1, 1), (0, 1)] {
        RankedAttending { tolerance: 0 }.attend(&lib, FeatureId(f), Some(Value(v)), &mut strict);
        ObservationAttending.attend(&lib, FeatureId(f), Some(Value(v)), &mut observed);
        assert_eq!(strict.attended(), observed.attended());
    }
}

#[test]
fn attention_remembers_the_last_non_empty_set() {
    let lib = library();
    let mut a = Attention::new();
    ObservationAttending.start(&lib, &mut a);
    ObservationAttending.attend(&lib, FeatureId(1), Some(Value(1)), &mut a);
    ObservationAttending.attend(&lib, FeatureId(0), Some(Value(3)), &mut a);
    assert!(a.attended().is_empty());
    assert_eq!(a.last_nonempty(), &[0, 2]);
}

// ---- 2. Feature selection -------------------------------------------------------------

#[test]
fn selection_trades_information_against_cost() {
    // Feature 0 separates the classes perfectly (gain 1) at cost 20: I^2/C = 0.05.
    // Feature 1 isolates one example of class 1 (gain 0.311) at cost 1: I^2/C = 0.097.
    let examples = [
        ex(&[(0, 0), (1, 0)], 0),
        ex(&[(0, 0), (1, 0)], 0),
        ex(&[(0, 1), (1, 0)], 1),
        ex(&[(0, 1), (1, 1)], 1),
    ];
    let costs = [Cost::new(20.0).unwrap(), Cost::new(1.0).unwrap()];
    let mut s = InfoCost::new(MissingRule::OwnBranch);
    assert_eq!(
        s.select_from(&examples, |_| false, &costs[..]),
        Some(FeatureId(1))
    );
    // At cost 3, feature 1 scores 0.032 and feature 0 wins.
    let costs = [Cost::new(20.0).unwrap(), Cost::new(3.0).unwrap()];
    assert_eq!(
        s.select_from(&examples, |_| false, &costs[..]),
        Some(FeatureId(0))
    );
    // Cost-blind selection (every cost one) takes the best gain whatever the prices.
    let costs = [Cost::new(20.0).unwrap(), Cost::new(1.0).unwrap()];
    let blind = cslearn::CostBlind(&costs[..]);
    assert_eq!(
        s.select_from(&examples, |_| false, &blind),
        Some(FeatureId(0))
    );
}

#[test]
fn the_missing_value_rules_differ_on_examples_lacking_the_feature() {
    // Feature 1: the two examples having it share a value but not a class; the two lacking
    // it share class 0. As a branch of their own they carry information (gain 0.31);
    // under C4.5's rule the feature has none, like feature 0, which every example has
    // with one value.
    let examples = [
        ex(&[(0, 0), (1, 0)], 0),
        ex(&[(0, 0), (1, 0)], 1),
        ex(&[(0, 0)], 0),
        ex(&[(0, 0)], 0),
    ];
    let costs = [Cost::ONE, Cost::ONE];
    let mut own = InfoCost::new(MissingRule::OwnBranch);
    let mut c45 = InfoCost::new(MissingRule::C45);
    assert_eq!(
        own.select_from(&examples, |_| false, &costs[..]),
        Some(FeatureId(1))
    );
    // Every gain zero: the tie goes to the cheapest, then the lowest id.
    assert_eq!(
        c45.select_from(&examples, |_| false, &costs[..]),
        Some(FeatureId(0))
    );
    let costs = [Cost::new(2.0).unwrap(), Cost::ONE];
    assert_eq!(
        c45.select_from(&examples, |_| false, &costs[..]),
        Some(FeatureId(1))
    );
}

#[test]
fn selection_skips_measured_and_unpriced_features_and_prefers_free_information() {
    let examples = [
        ex(&[(0, 0), (1, 0), (2, 0)], 0),
        ex(&[(0, 1), (1, 1), (2, 1)], 1),
    ];
    let costs = [Cost::ONE, Cost::ZERO]; // feature 2 has no price
    let mut s = InfoCost::new(MissingRule::OwnBranch);
    assert_eq!(
        s.select_from(&examples, |_| false, &costs[..]),
        Some(FeatureId(1))
    );
    assert_eq!(
        s.select_from(&examples, |f| f == FeatureId(1), &costs[..]),
        Some(FeatureId(0))
    );
    assert_eq!(s.select_from(&examples, |f| f.0 < 2, &costs[..]), None);
}

#[test]
fn the_select_part_uses_the_attended_examples_and_the_current_pass() {
    let lib = library();
    let costs = FeatureCosts::from_f64(&[1.0, 1.0]).unwrap();
    let mut a = Attention::new();
    ObservationAttending.start(&lib, &mut a);
    let mut ledger = Ledger::default();
    let mut s = InfoCost::new(MissingRule::OwnBranch);
    let first = s.select(&lib, &a, &ledger, &costs).unwrap();
    ledger.record(first, Some(Value(1)), Cost::ONE);
    let second = s.select(&lib, &a, &ledger, &costs).unwrap();
    assert_ne!(first, second);
    // A new pass may select the feature again; it will be replayed, not paid twice.
    ledger.start_pass();
    assert_eq!(s.select(&lib, &a, &ledger, &costs), Some(first));
}

// ---- 3. Class prediction --------------------------------------------------------------

#[test]
fn unanimous_prediction_follows_spec_2() {
    let lib = Library::from(vec![ex(&[], 1), ex(&[], 0), ex(&[], 1), ex(&[], 0)]);
    let mut p = Unanimous::default();
    let mut a = Attention::new();
    assert_eq!(p.predict(&Library::new(), &a, false), Decision::Abstain);
    a.attend_all(lib.len());
    assert_eq!(p.predict(&lib, &a, false), Decision::Measure);
    // A majority tie goes to the lowest class.
    assert_eq!(p.predict(&lib, &a, true), Decision::Predict(ClassId(0)));
    a.retain(|i| i != 1);
    assert_eq!(p.predict(&lib, &a, true), Decision::Predict(ClassId(1)));
    a.retain(|i| i != 3);
    assert_eq!(p.predict(&lib, &a, false), Decision::Predict(ClassId(1)));
    a.retain(|_| false);
    assert_eq!(p.predict(&lib, &a, false), Decision::Predict(ClassId(1)));
}

#[test]
fn nearest_prediction_falls_back_to_the_fewest_mismatches() {
    let lib = Library::from(vec![ex(&[(0, 0)], 0), ex(&[(0, 1)], 1), ex(&[(0, 1)], 1)]);
    let ranked = RankedAttending { tolerance: 0 };
    let mut a = Attention::new();
    ranked.start(&lib, &mut a);
    let mut p = Nearest::default();
    assert_eq!(p.predict(&lib, &a, false), Decision::Measure);
    assert_eq!(p.predict(&lib, &a, true), Decision::Predict(ClassId(1)));
    ranked.attend(&lib, FeatureId(0), Some(Value(2)), &mut a);
    // Nothing within tolerance: every example has one mismatch; the majority is class 1.
    assert!(a.attended().is_empty());
    assert_eq!(p.predict(&lib, &a, false), Decision::Predict(ClassId(1)));
}

// ---- 4. Example discrimination --------------------------------------------------------

#[test]
fn cheapest_first_measures_in_cost_order_until_nothing_conflicts() {
    let lib = Library::from(vec![ex(&[(0, 0), (1, 0), (2, 0)], 0)]);
    let costs = FeatureCosts::from_f64(&[3.0, 1.0, 2.0]).unwrap();
    let object = row(&[1, 0, 0]); // differs only on the dearest feature
    let mut conflicting = Attention::new();
    ObservationAttending.start(&lib, &mut conflicting);
    let mut ledger = Ledger::default();
    let mut probe = Probe::new(&object[..], &costs, &mut ledger);
    CheapestFirst.discriminate(&lib, &ObservationAttending, &mut conflicting, &mut probe);
    let order: Vec<FeatureId> = ledger.measured().iter().map(|&(f, _)| f).collect();
    assert_eq!(order, vec![FeatureId(1), FeatureId(2), FeatureId(0)]);
    assert_eq!(ledger.cost().get(), 6.0);
    assert!(conflicting.attended().is_empty());
}

#[test]
fn discrimination_stops_when_no_feature_is_left() {
    let lib = Library::from(vec![ex(&[(0, 0)], 0)]);
    let costs = FeatureCosts::from_f64(&[1.0]).unwrap();
    let object = row(&[0]); // indistinguishable
    let mut conflicting = Attention::new();
    ObservationAttending.start(&lib, &mut conflicting);
    let mut ledger = Ledger::default();
    let mut probe = Probe::new(&object[..], &costs, &mut ledger);
    CheapestFirst.discriminate(&lib, &ObservationAttending, &mut conflicting, &mut probe);
    assert_eq!(ledger.measured().len(), 1);
    assert_eq!(conflicting.attended(), &[0]);
}

#[test]
fn random_order_is_seeded_and_value_stable() {
    let lib = Library::from(vec![ex(&(0..8).map(|f| (f, 0)).collect::<Vec<_>>(), 0)]);
    let costs = FeatureCosts::from_f64(&[1.0; 8]).unwrap();
    let object = row(&[1; 8]);
    let first_measured = |seed: u64| {
        let mut conflicting = Attention::new();
        ObservationAttending.start(&lib, &mut conflicting);
        let mut ledger = Ledger::default();
        let mut probe = Probe::new(&object[..], &costs, &mut ledger);
        RandomOrder::new(Xoshiro256PlusPlus::seed_from_u64(seed)).discriminate(
            &lib,
            &ObservationAttending,
            &mut conflicting,
            &mut probe,
        );
        assert_eq!(ledger.measured().len(), 1);
        ledger.measured()[0].0
    };
    assert_eq!(first_measured(1), first_measured(1));
    let firsts: Vec<u32> = (1..=6).map(|s| first_measured(s).0).collect();
    // Fixed for these seeds: a change of generator or shuffle shows here.
    assert_eq!(firsts, vec![4, 0, 0, 5, 2, 7]);
}

// ---- 5. Library updating --------------------------------------------------------------

#[test]
fn append_all_keeps_every_example_and_append_errors_only_mistakes() {
    let mut all = Library::new();
    let mut errors = Library::new();
    for (i, correct) in [true, false, true, false].into_iter().enumerate() {
        let e = ex(&[(0, i as u32)], 0);
        assert_eq!(AppendAll.update(&mut all, e.clone(), correct), Some(i));
        AppendErrors.update(&mut errors, e, correct);
    }
    assert_eq!(all.len(), 4);
    assert_eq!(
        errors
            .iter()
            .map(|e| e.get(FeatureId(0)))
            .collect::<Vec<_>>(),
        vec![Some(Value(1)), Some(Value(3))]
    );
}

// ---- The learners ---------------------------------------------------------------------

#[test]
fn cs_id3_runs_the_cycle_of_figure_2() {
    let costs = FeatureCosts::from_f64(&[1.0, 5.0]).unwrap();
    let mut l = cslearn::cs_id3(costs);
    // An empty library predicts nothing and stores an example with no features.
    let o = l.learn(&row(&[0, 0])[..], ClassId(0));
    assert_eq!((o.predicted, o.measured), (None, 0));
    assert!(l.library()[0].is_empty());
    // Predicted 0 for free, wrong: discrimination measures the cheapest feature, which
    // drops the featureless example.
    let o = l.learn(&row(&[1, 0])[..], ClassId(1));
    assert_eq!((o.predicted, o.cost.get()), (Some(ClassId(0)), 1.0));
    assert_eq!(l.library()[1].pairs(), &[(FeatureId(0), Value(1))]);
    // Now feature 0 is measured to choose between the two.
    let o = l.learn(&row(&[1, 1])[..], ClassId(1));
    assert_eq!((o.predicted, o.cost.get()), (Some(ClassId(1)), 1.0));
}

#[test]
fn id3_charges_real_costs_while_ignoring_them() {
    let costs = FeatureCosts::from_f64(&[100.0, 1.0]).unwrap();
    let rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let mut l = cslearn::id3(costs, rng);
    // Feature 0 carries slightly more information; cost-blind selection takes it.
    let rows = [([0, 0], 0), ([0, 0], 0), ([1, 0], 1), ([1, 1], 1)];
    for _ in 0..3 {
        for (r, c) in rows {
            l.learn(&row(&r)[..], ClassId(c));
        }
    }
    let c = l.classify(&row(&[1, 1])[..]);
    assert_eq!(c.class, Some(ClassId(1)));
    assert!(c.cost.get() >= 100.0);
}

#[test]
fn cs_ibl_tolerates_one_wrong_value_where_cs_id3_does_not() {
    // Four complete instances, each pair differing in at least three features.
    let instances = [
        ([0, 0, 0, 0, 0, 0], 0),
        ([1, 1, 1, 0, 0, 0], 1),
        ([0, 0, 0, 1, 1, 1], 2),
        ([1, 1, 1, 1, 1, 1], 3),
    ];
    let costs = FeatureCosts::from_f64(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).unwrap();
    let seed = |library: &mut Library| {
        for (values, class) in instances {
            let pairs: Vec<(u32, u32)> = values
                .iter()
                .enumerate()
                .map(|(f, &v)| (f as u32, v))
                .collect();
            library.push(ex(&pairs, class));
        }
    };
    let mut ibl = cslearn::cs_ibl(costs.clone(), 1);
    seed(ibl.library_mut());
    let mut id3 = cslearn::cs_id3(costs);
    seed(id3.library_mut());
    // Instance 0 with its cheapest feature misread.
    let noisy = row(&[1, 0, 0, 0, 0, 0]);
    assert_eq!(ibl.classify(&noisy[..]).class, Some(ClassId(0)));
    assert_eq!(id3.classify(&noisy[..]).class, Some(ClassId(1)));
    // Any single wrong value, anywhere: CS-IBL still finds the instance's class.
    for (values, class) in instances {
        for wrong in 0..6 {
            let mut object = row(&values);
            object[wrong] = Some(Value(1 - values[wrong]));
            assert_eq!(
                ibl.classify(&object[..]).class,
                Some(ClassId(class)),
                "{values:?}, feature {wrong}"
            );
        }
    }
}

#[test]
fn new_features_can_appear_at_any_time() {
    let mut l = cslearn::cs_id3(FeatureCosts::from_f64(&[1.0]).unwrap());
    for _ in 0..2 {
        l.learn(&row(&[0, 0])[..], ClassId(0));
        l.learn(&row(&[0, 1])[..], ClassId(1));
    }
    // Feature 1 is unknown: the two classes cannot be told apart yet.
    assert!(l.classify(&row(&[0, 1])[..]).cost.get() <= 1.0);
    let f = l.add_feature(Cost::new(2.0).unwrap());
    assert_eq!(f, FeatureId(1));
    for _ in 0..2 {
        l.learn(&row(&[0, 0])[..], ClassId(0));
        l.learn(&row(&[0, 1])[..], ClassId(1));
    }
    assert_eq!(l.classify(&row(&[0, 1])[..]).class, Some(ClassId(1)));
    assert_eq!(l.classify(&row(&[0, 0])[..]).class, Some(ClassId(0)));
}
