//! Every built-in world learns from its defaults: CS-QL with every strategy, given only
//! the world's name, the strategy and a seed (as `csrl run --world NAME`, a settings file
//! naming the map and Python's `csrl.run` give them), reaches an optimal policy in every
//! deterministic built-in world. The defaults come from the world where it asks for its
//! own (`mdp::builtin_world_settings`), a key given always wins and is echoed, and a run
//! that ends without learning says why.
//!
//! One seed per strategy and world keeps this within the test suite's time (the resetting
//! strategy on Taxi, about 61000 trials, is its own test so that it runs beside the
//! others); `docs/worlds.md` has seeds 1 to 5, measured by
//! `cargo run --release -p csql --example world_defaults`.

use csql::{DetectorKind, RunReport, RunSettings, SettingsDraft, StrategyKind};

/// The settings of `world` with `strategy` and `seed`, every other key at its default.
fn defaults(world: &str, strategy: StrategyKind, seed: u64) -> RunSettings {
    SettingsDraft {
        map: Some(world.into()),
        strategy: Some(strategy),
        seed: Some(seed),
        ..SettingsDraft::default()
    }
    .build()
    .unwrap()
}

fn assert_learns(world: &str, strategy: StrategyKind) -> RunReport {
    let report = csql::run(&defaults(world, strategy, 1)).unwrap();
    assert!(
        report.converged && report.quality.policy_quality >= 0.95,
        "{world} {strategy} seed 1: converged {}, quality {} after {} trials; {:?}",
        report.converged,
        report.quality.policy_quality,
        report.trials,
        report.not_learned
    );
    assert!(report.not_learned.is_none(), "{:?}", report.not_learned);
    report
}

#[test]
fn frozenlake4x4_learns_from_its_defaults() {
    for strategy in StrategyKind::ALL {
        assert_learns("frozenlake4x4", strategy);
    }
}

#[test]
fn frozenlake8x8_learns_from_its_defaults() {
    for strategy in StrategyKind::ALL {
        let report = assert_learns("frozenlake8x8", strategy);
        if strategy == StrategyKind::Resetting {
            // Past the paper's cap: the world's own cap is what lets it learn.
            assert!(report.trials > 20_000, "{}", report.trials);
        }
    }
}

#[test]
fn cliffwalking_learns_from_its_defaults() {
    for strategy in StrategyKind::ALL {
        assert_learns("cliffwalking", strategy);
    }
}

#[test]
fn taxi_learns_from_its_defaults() {
    for strategy in [
        StrategyKind::Lazy,
        StrategyKind::Random,
        StrategyKind::Eager,
    ] {
        assert_learns("taxi", strategy);
    }
}

#[test]
fn taxi_learns_from_its_defaults_with_the_resetting_strategy() {
    let report = assert_learns("taxi", StrategyKind::Resetting);
    assert!(report.trials > 20_000, "{}", report.trials);
}

#[test]
fn a_world_default_is_a_default_a_setting_given_wins_and_the_report_echoes_both() {
    // Taxi's own defaults, echoed in the report's settings.
    let s = defaults("taxi", StrategyKind::Lazy, 1);
    assert_eq!(s.temperature.get(), 8.0);
    assert_eq!(s.max_trials.get(), 200_000);
    assert_eq!(s.extensions().detector, DetectorKind::Action);
    let echoed = serde_json::to_value(&s).unwrap();
    assert_eq!(echoed["temperature"], 8.0);
    assert_eq!(echoed["max_trials"], 200_000);
    assert_eq!(echoed["extensions"]["detector"], "action");
    assert_eq!(SettingsDraft::from(&s).build().unwrap(), s);
    // Keys given win, the paper's detector included, and are echoed so that the
    // settings build again to the same.
    let given = SettingsDraft::from_toml(
        "map = \"taxi\"\ntemperature = 0.4\nmax_trials = 30\n[extensions]\ndetector = \"decrease\"",
        "f",
    )
    .unwrap()
    .build()
    .unwrap();
    assert_eq!((given.temperature.get(), given.max_trials.get()), (0.4, 30));
    assert_eq!(given.extensions().detector, DetectorKind::Decrease);
    let echoed = serde_json::to_value(&given).unwrap();
    assert_eq!(echoed["extensions"]["detector"], "decrease");
    assert_eq!(SettingsDraft::from(&given).build().unwrap(), given);
    // Another key of [extensions] leaves the detector to the world.
    let reads = SettingsDraft::from_toml("map = \"cliffwalking\"\n[extensions]\nreads = 2", "f")
        .unwrap()
        .build()
        .unwrap();
    assert_eq!(reads.extensions().detector, DetectorKind::Action);
    // The action detector needs beta 1 and a deterministic world: elsewhere the world's
    // detector gives way to the paper's, and nothing is refused.
    for toml in [
        "map = \"cliffwalking\"\nbeta = 0.5",
        "map = \"cliffwalking\"\n[world]\nslip = 0.1",
    ] {
        let s = SettingsDraft::from_toml(toml, "f")
            .unwrap()
            .build()
            .unwrap();
        assert_eq!(s.extensions().detector, DetectorKind::Decrease, "{toml}");
        assert_eq!(s.temperature.get(), 40.0, "{toml}");
        assert_eq!(SettingsDraft::from(&s).build().unwrap(), s, "{toml}");
    }
    // The learners played on episodes keep the paper's number of episodes.
    let amrl = SettingsDraft::from_toml(
        "map = \"frozenlake8x8\"\nlearner = \"amrl-q\"\n[costly]\nprice = 0.01",
        "f",
    )
    .unwrap()
    .build()
    .unwrap();
    assert_eq!(amrl.max_trials.get(), 20_000);
    // The paper's preset is the paper's, whatever the map.
    let paper = RunSettings::tan1991("taxi", StrategyKind::Lazy, 1);
    assert_eq!(paper.temperature.get(), 0.4);
    assert_eq!(SettingsDraft::from(&paper).build().unwrap(), paper);
    // Grid maps and world files run at the paper's values.
    let map = defaults("tan8x8", StrategyKind::Lazy, 1);
    assert_eq!((map.temperature.get(), map.max_trials.get()), (0.4, 20_000));
}

#[test]
fn a_run_that_ends_without_learning_says_why_and_what_to_try() {
    // Taxi at the paper's settings: no utility ever falls, nothing is sensed.
    let mut paper = RunSettings::tan1991("taxi", StrategyKind::Lazy, 1);
    paper.max_trials = csql::TrialCap::new(40).unwrap();
    let report = csql::run(&paper).unwrap();
    let not = report
        .not_learned
        .clone()
        .expect("a run that did not learn says why");
    assert!(
        not.why.contains("trial cap, max_trials = 40"),
        "{}",
        not.why
    );
    assert!(not.why.contains("No utility ever decreased"), "{}", not.why);
    assert!(not.why.contains("floor of the returns"), "{}", not.why);
    assert!(not.why.contains("csrl world show taxi"), "{}", not.why);
    assert_eq!(
        not.to_try[..3],
        [
            "temperature = 8",
            "[extensions] detector = \"action\"",
            "max_trials = 200000"
        ]
    );
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["not_learned"]["try"][0], "temperature = 8");
    // Too few trials in the paper's world: only more trials to try.
    let mut short = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    short.max_trials = csql::TrialCap::new(5).unwrap();
    let not = csql::run(&short).unwrap().not_learned.unwrap();
    assert_eq!(not.to_try, ["max_trials = 50"], "{}", not.why);
    // The slippery lake: random moves, judged by the quality.
    let mut slippery = defaults("frozenlake4x4", StrategyKind::Lazy, 1);
    slippery.world.slip = Some(mdp::Slip::new(2.0 / 3.0).unwrap());
    slippery.max_trials = csql::TrialCap::new(20).unwrap();
    let not = csql::run(&slippery).unwrap().not_learned.unwrap();
    assert!(not.why.contains("random"), "{}", not.why);
    assert!(
        not.to_try.contains(&"beta = 0.02".to_string())
            && not
                .to_try
                .contains(&"[extensions] detector = \"statistical\"".to_string()),
        "{:?}",
        not.to_try
    );
}
