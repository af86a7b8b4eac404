//! AMRL-Q, the active-measurement baseline: its accounting, its two sensing rules, and
//! that it learns the deterministic lake.

mod common;

use common::StopAfter;

use csql::{AmrlParams, CostlySummary, Episode, Measuring, amrl_q};
use mdp::SensingRule;
use mdp::{SensingModel, WorldOptions};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn lake(slide: f64) -> mdp::FiniteWorld {
    let options = WorldOptions {
        slide: Some(slide),
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

/// Both learners on costed episodes ask their observer before every episode (sensing by
/// belief also while it builds a plan) and end where it says no, with the episodes played
/// so far, the same as those of a whole run; an episode longer than `STOP_CHECK_MOVES`
/// moves is cut there.
#[test]
fn learners_on_episodes_stop_when_their_observer_says_so() {
    let world = lake(0.5);
    for learner in [csql::LearnerKind::AmrlQ, csql::LearnerKind::Belief] {
        let mut s = csql::RunSettings::tan1991("frozenlake4x4", csql::StrategyKind::Lazy, 3)
            .with_learner(learner);
        s.costly = Some(csql::CostlySettings::new(0.025));
        s.max_trials = csql::TrialCap::new(40).unwrap();
        let mut counted = StopAfter { left: u32::MAX };
        let whole = csql::costed_report(&world, "lake", &s, &mut counted).unwrap();
        let asked = u32::MAX - counted.left;
        let left = match learner {
            // Asked before every episode only.
            csql::LearnerKind::AmrlQ => 7,
            // Asked while planning too: stopped halfway through its questions.
            _ => asked / 2,
        };
        let cut = csql::costed_report(&world, "lake", &s, &mut StopAfter { left }).unwrap();
        let n = cut.costly.summary.episodes;
        if learner == csql::LearnerKind::AmrlQ {
            assert_eq!((asked, n), (40, 7));
        }
        assert!(0 < n && n < 40, "{learner}: {n} episodes");
        assert_eq!(
            cut.costly.returns[..],
            whole.costly.returns[..n],
            "{learner}"
        );
    }
    // A room the agent can never leave: without the observer's no, the first episode
    // would last four billion moves; it is cut at the first check.
    let trap = mdp::FiniteWorld::from_json(
        r#"{"format": "csrl-world", "version": 1, "name": "trap", "states": 2,
            "actions": ["stay"], "start": [[1.0, 0]], "terminal": [1],
            "transitions": [[0, 0, [[1.0, 0, 0.0, false]]]],
            "features": [{"name": "where", "price": 1.0}], "readings": [[0], [1]]}"#,
    )
    .unwrap();
    let mut s = csql::RunSettings::tan1991("trap", csql::StrategyKind::Lazy, 3)
        .with_learner(csql::LearnerKind::AmrlQ);
    s.costly = Some(csql::CostlySettings::new(0.025));
    s.max_moves = qlearn::MoveCap::new(u64::from(u32::MAX)).unwrap();
    let cut = csql::costed_report(&trap, "trap", &s, &mut StopAfter { left: 1 }).unwrap();
    assert_eq!(cut.costly.summary.episodes, 1);
    assert_eq!(
        cut.costly.summary.steps_per_episode,
        f64::from(csql::STOP_CHECK_MOVES)
    );
}
