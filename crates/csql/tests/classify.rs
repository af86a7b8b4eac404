//! The cached CLASSIFY charges exactly what the plain procedure of Figure 3 charges,
//! feature for feature, on representations grown by real learning.

use csql::{Classify, Perception, RunSettings, Setup, StrategyKind};
use mdp::{FeatureSpace, GridWorld, Manhattan, RandomMap, SensedGrid, Slip};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Grow a representation with random classifications and refinements, checking at every
/// step that the cached and plain procedures measure the same features in the same order.
fn check_same_charges(world: &GridWorld, ops: &[(usize, bool)]) {
    let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    let world = &SensedGrid::new(world, &space, Slip::default());
    let states = world.world().states();
    let mut cached = Classify::new(world);
    let mut plain = Classify::new(world).with_cache(false);
    for &(i, refine) in ops {
        let s = states[i % states.len()];
        let a = cached.classify_state(world, s);
        let b = plain.classify_state(world, s);
        assert_eq!(a, b, "state {s}");
        if refine {
            assert_eq!(
                cached.add_feature(world, a.description, s),
                plain.add_feature(world, b.description, s)
            );
        }
        // Every state, without changing anything: a fresh copy of each classifier.
        for &t in &states {
            let (mut c, mut p) = (cached.clone(), plain.clone());
            assert_eq!(
                c.classify_state(world, t),
                p.classify_state(world, t),
                "probe {t}"
            );
        }
    }
    assert_eq!(cached.representation().len(), plain.representation().len());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn cached_and_plain_classify_charge_the_same(
        seed: u64,
        ops in proptest::collection::vec((0usize..64, proptest::bool::weighted(0.4)), 1..60),
    ) {
        let map = RandomMap { width: 5, height: 4, obstacle_density: 0.25 }
            .generate("r", &mut Xoshiro256PlusPlus::seed_from_u64(seed))
            .unwrap();
        check_same_charges(&GridWorld::new(&map), &ops);
    }
}

#[test]
fn cached_and_plain_runs_are_identical_on_tan8x8() {
    // A whole run with each: same trace, same costs, same representation.
    let settings = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 11);
    let setup = Setup::new(&settings).unwrap();
    let fast = csql::run_on(&setup, &settings).unwrap();
    let slow = csql::run_on_with(
        &setup,
        &settings,
        Classify::new(&setup.sensed(&settings)).with_cache(false),
    )
    .unwrap();
    assert_eq!(fast, slow);
}

#[test]
fn the_first_call_creates_the_empty_description_and_refining_splits() {
    let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    let sensed = SensedGrid::new(&world, &space, Slip::default());
    let mut c = Classify::new(&sensed);
    let mut table = qlearn::QTable::new(4).unwrap();
    let top_left = world.state_at(mdp::Pos::new(0, 0)).unwrap();
    let below = world.state_at(mdp::Pos::new(1, 0)).unwrap();
    let (d0, cost) = c.classify(&sensed, top_left, &mut table);
    assert_eq!((d0.0, cost, table.rows()), (0, 0.0, 1));
    // Refining adds "up" (the cheapest feature) valued at the top-left state: a wall.
    assert_eq!(c.refine(&sensed, d0, top_left), Some(1.0));
    // The state below has no wall above: "up" is measured and a new description made.
    let (d1, cost) = c.classify(&sensed, below, &mut table);
    assert_eq!((d1.0, cost, table.rows()), (1, 1.0, 2));
    let r = c.representation();
    assert_eq!(
        r.get(csql::DescriptionId(1)).value(mdp::Feature(0)),
        Some(mdp::Reading::from(mdp::Cell::Empty))
    );
    // And the top-left state still finds its own description, paying for "up" once.
    let (again, cost) = c.classify(&sensed, top_left, &mut table);
    assert_eq!((again, cost), (d0, 1.0));
}

/// The free views (the oracle's exact walk, its cost and the noisy walk of an evaluation)
/// find and charge with the cache off what they find and charge with it on, drawing the
/// same errors.
#[test]
fn the_free_views_are_the_same_with_the_cache_off() {
    let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    let sensed = SensedGrid::new(&world, &space, Slip::default());
    let mut cached = Classify::new(&sensed);
    let mut plain = Classify::new(&sensed).with_cache(false);
    let states = world.states();
    let noise = mdp::SensorNoise::new(0.2).unwrap();
    for (i, &s) in states.iter().cycle().take(400).enumerate() {
        let a = cached.classify_state(&sensed, s);
        assert_eq!(a, plain.classify_state(&sensed, s));
        if i % 3 == 0 {
            cached.add_feature(&sensed, a.description, s);
            plain.add_feature(&sensed, a.description, s);
        }
        let t = states[(i * 7) % states.len()];
        assert_eq!(
            cached.lookup_cost(&sensed, t),
            plain.lookup_cost(&sensed, t)
        );
        let mut r1 = Xoshiro256PlusPlus::seed_from_u64(i as u64);
        let mut r2 = r1.clone();
        assert_eq!(
            cached.lookup_noisy(&sensed, t, noise, &mut r1),
            plain.lookup_noisy(&sensed, t, noise, &mut r2)
        );
        assert_eq!(r1, r2);
    }
}
