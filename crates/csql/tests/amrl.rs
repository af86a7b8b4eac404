//! AMRL-Q, the active-measurement baseline: its accounting, its two sensing rules, and
//! that it learns the deterministic lake.

use csql::{AmrlParams, CostlySummary, Episode, Measuring, amrl_q};
use mdp::SensingRule;
use mdp::{SensingModel, WorldOptions};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn lake(slide: f64) -> mdp::FiniteWorld {
    let options = WorldOptions {
        slide,
        sensing: Some(SensingModel::Factors),
        ..WorldOptions::default()
    };
    mdp::builtin_world("frozenlake4x4", &options).unwrap()
}

fn run(world: &mdp::FiniteWorld, rule: SensingRule, seed: u64, episodes: u32) -> Vec<Episode> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    amrl_q(
        world,
        &AmrlParams::default(),
        0.05,
        rule,
        episodes,
        100,
        &mut rng,
    )
}

/// Every episode pays the price once per measurement, ends at the cap or on a terminal
/// move, and reaches the goal exactly when it earns FrozenLake's reward.
#[test]
fn episodes_are_accounted_for() {
    let world = lake(0.5);
    for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
        for e in run(&world, rule, 3, 400) {
            assert!(
                (e.sensing - 0.05 * f64::from(e.measurements)).abs() < 1e-9,
                "{e:?}"
            );
            assert!(e.measurements <= e.steps && e.steps <= 100, "{e:?}");
            assert_eq!(e.reached_goal, e.reward == 1.0, "{e:?}");
            assert!((e.costed_return() - (e.reward - e.sensing)).abs() < 1e-12);
        }
    }
}

/// Decided after the outcome, nothing is sensed on the move that ends an episode; decided
/// with the move, the last move of an episode is sometimes measured and paid.
#[test]
fn the_two_rules_differ_only_on_the_last_move() {
    let world = lake(0.5);
    let after = run(&world, SensingRule::AfterOutcome, 5, 600);
    let with = run(&world, SensingRule::WithMove, 5, 600);
    // An episode that ended on a terminal move before the cap: under the second rule at
    // most every move but the last was measured.
    let ended = |e: &&Episode| e.steps < 100;
    assert!(after.iter().filter(ended).all(|e| e.measurements < e.steps));
    assert!(
        with.iter().filter(ended).any(|e| e.measurements == e.steps),
        "a measured last move is paid under the published rule"
    );
}

/// On the deterministic lake the greedy last tenth of the episodes follows a shortest
/// path to the goal without measuring, in every seeded run: a costed return of 1.
#[test]
fn it_learns_the_deterministic_lake() {
    let world = lake(0.0);
    for seed in 1..=3 {
        let episodes = run(&world, SensingRule::WithMove, seed, 1000);
        let s = CostlySummary::of(&episodes);
        assert_eq!(s.mean_last10, 1.0, "seed {seed}: {s:?}");
        assert!(s.mean_all > 0.7 && s.mean_all < 1.0, "seed {seed}: {s:?}");
        let last = &episodes[900..];
        assert!(last.iter().all(|e| e.steps == 6 && e.measurements == 0));
    }
}

/// Measuring at every step: every move is measured and paid, and the greedy end follows a
/// shortest path, paying for each of its six moves.
#[test]
fn the_always_measuring_learner_pays_every_move() {
    let world = lake(0.0);
    let params = AmrlParams {
        measuring: Measuring::Always,
        ..AmrlParams::default()
    };
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
    let episodes = amrl_q(
        &world,
        &params,
        0.05,
        SensingRule::WithMove,
        1000,
        100,
        &mut rng,
    );
    assert!(episodes.iter().all(|e| e.measurements == e.steps));
    let s = CostlySummary::of(&episodes);
    assert!((s.mean_last10 - (1.0 - 6.0 * 0.05)).abs() < 1e-9, "{s:?}");
}
