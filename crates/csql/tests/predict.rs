//! `predict_sensing`: off changes nothing; the learned and motion levels converge as
//! before, keep the bound on wrong predictions, and navigate by optimal paths.

mod common;

use common::StopAfter;

use csql::{PredictSensing, PredictionParams, RunReport, RunSettings, Setup, StrategyKind};

fn run(
    map: &str,
    strategy: StrategyKind,
    seed: u64,
    level: PredictSensing,
    p: PredictionParams,
) -> RunReport {
    let mut s = RunSettings::tan1991(map, strategy, seed);
    let q = s.cs_ql_mut().unwrap();
    q.predict_sensing = level;
    q.prediction = p;
    let setup = Setup::new(&s).unwrap();
    csql::run_on(&setup, &s).unwrap()
}

#[test]
fn off_adds_nothing_to_the_json() {
    let s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let report = csql::run(&s).unwrap();
    let json = serde_json::to_string(&report).unwrap();
    for key in [
        "predict_sensing",
        "\"prediction\"",
        "navigation_cost_per_move",
        "navigation_success",
    ] {
        assert!(!json.contains(key), "{key} in a default run's JSON");
    }
    assert_eq!(report.navigation_success, None);
}

#[test]
fn the_levels_are_read_from_toml_and_appear_in_the_json() {
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    s.apply_toml(
        "predict_sensing = \"learned\"\n[prediction]\nrecheck = 0.1\nmax_skips = 4",
        "t.toml",
    )
    .unwrap();
    let q = s.cs_ql().unwrap();
    assert_eq!(q.predict_sensing, PredictSensing::Learned);
    assert_eq!((q.prediction.recheck, q.prediction.max_skips), (0.1, 4));
    assert_eq!(
        q.prediction.confirmations,
        PredictionParams::default().confirmations
    );
    for bad in [
        "predict_sensing = \"always\"",
        "[prediction]\nrechek = 0.1",
        "[prediction]\nrecheck = 2.0",
    ] {
        assert!(s.clone().apply_toml(bad, "t.toml").is_err(), "{bad}");
    }
    let report = csql::run(&s).unwrap();
    let json: serde_json::Value = serde_json::to_value(&report).unwrap();
    assert_eq!(json["settings"]["predict_sensing"], "learned");
    assert_eq!(json["navigation_success"], 1.0);
    assert!(json["navigation_cost_per_move"].as_f64().unwrap() > 0.0);
    assert!(json["prediction"]["skipped"].as_u64().unwrap() > 0);
}

/// The guarantee: no transition is used more than `max_skips` times in a row without a
/// measurement, so no run of wrong predictions of one transition is longer. With a
/// small `max_skips` wrong predictions do happen on `tan8x8`, and the bound holds.
#[test]
fn wrong_predictions_are_caught_within_max_skips_uses() {
    for max_skips in [1, 3] {
        let p = PredictionParams {
            max_skips,
            recheck: 0.0,
            confirmations: 1,
            ..PredictionParams::default()
        };
        let mut wrong = 0;
        for seed in 1..=2 {
            let r = run(
                "tan8x8",
                StrategyKind::Lazy,
                seed,
                PredictSensing::Learned,
                p,
            );
            let stats = r.prediction.unwrap();
            assert!(r.converged, "seed {seed}");
            assert!(
                stats.longest_wrong_run <= max_skips,
                "{} wrong in a row with max_skips {max_skips}",
                stats.longest_wrong_run
            );
            assert!(stats.caught > 0 && stats.skipped > 0);
            wrong += stats.wrong;
        }
        assert!(wrong > 0, "the bound was never exercised");
    }
}

/// Both levels converge (so every description is consistent) with about one description
/// per state: on seed 1 the random strategy without prediction ends with 49 (two states
/// of equal utility and a shared best action share one) and with prediction with 50.
#[test]
fn the_learned_level_converges_to_the_same_kind_of_representation_for_less() {
    for strategy in [StrategyKind::Random, StrategyKind::Eager] {
        let off = run(
            "tan8x8",
            strategy,
            1,
            PredictSensing::Off,
            PredictionParams::default(),
        );
        let on = run(
            "tan8x8",
            strategy,
            1,
            PredictSensing::Learned,
            PredictionParams::default(),
        );
        assert!(on.converged && off.converged);
        for r in [&on, &off] {
            let d = r.table1.descriptions.unwrap();
            assert!((45..=50).contains(&d), "{strategy:?}: {d}");
        }
        let (c_on, c_off) = (
            on.table1.cost_to_converge.unwrap(),
            off.table1.cost_to_converge.unwrap(),
        );
        assert!(c_on < 0.8 * c_off, "{strategy:?}: {c_on} against {c_off}");
        assert_eq!(on.navigation_success, Some(1.0));
    }
}

/// The motion prior changes what is charged and nothing else: the same draws, the same
/// representation, the same trials; the dead reckoning is checked against the world at
/// every remembered cell (a debug assertion in the perception).
#[test]
fn motion_charges_less_for_the_same_run() {
    for memory_moves in [1, 100] {
        let p = PredictionParams {
            memory_moves,
            ..PredictionParams::default()
        };
        // The learned level keeps no memory: memory_moves is the motion level's alone.
        let learned = run(
            "tan8x8",
            StrategyKind::Random,
            2,
            PredictSensing::Learned,
            PredictionParams {
                memory_moves: 1,
                ..p
            },
        );
        let motion = run("tan8x8", StrategyKind::Random, 2, PredictSensing::Motion, p);
        assert_eq!(
            (
                learned.trials,
                learned.moves,
                &learned.descriptions,
                learned.prediction
            ),
            (
                motion.trials,
                motion.moves,
                &motion.descriptions,
                motion.prediction
            )
        );
        assert!(motion.total_cost < learned.total_cost);
        assert_eq!(motion.navigation_success, Some(1.0));
        assert!(motion.navigation_cost_per_move <= learned.navigation_cost_per_move);
    }
}

/// Navigation's narrowed classification: among candidates that hold a state's true
/// description, the features that tell them apart find it.
#[test]
fn classify_among_finds_the_true_description_among_candidates() {
    let settings = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    let setup = Setup::new(&settings).unwrap();
    let (report, rep) = csql::run_with_representation(&setup, &settings).unwrap();
    assert!(report.converged);
    let world = setup.sensed(&settings);
    let mut c = csql::Classify::with_representation(&world, rep.clone());
    let ids: Vec<csql::DescriptionId> = rep.iter().map(|(id, _)| id).collect();
    let cost = |c: &csql::Classify| -> f64 {
        c.last_measured()
            .iter()
            .map(|&(f, _)| setup.space.cost(f))
            .sum()
    };
    let (mut narrowed, mut full, mut calls) = (0.0, 0.0, 0.0);
    for s in setup.world.states() {
        let truth = c.lookup(&world, s).unwrap();
        c.classify_state(&world, s);
        let whole = cost(&c);
        for window in ids.chunks(3) {
            let mut candidates = window.to_vec();
            if !candidates.contains(&truth) {
                candidates.push(truth);
            }
            assert_eq!(c.classify_among(&world, s, &candidates), Some(truth));
            narrowed += cost(&c);
            full += whole;
            calls += 1.0;
        }
    }
    // Telling three or four descriptions apart costs far less than CLASSIFY's full check.
    assert!(
        narrowed < 0.5 * full,
        "{} against {} per call",
        narrowed / calls,
        full / calls
    );
}

/// Navigation asks its observer before every trial and within a long one, and ends
/// where it is told to: an untrained policy that never reaches the goal, with a move
/// cap that would take hours, ends at once.
#[test]
fn navigation_stops_when_its_observer_says_so() {
    use rand::SeedableRng;
    let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let setup = Setup::new(&settings).unwrap();
    let world = setup.sensed(&settings);
    let navigate = |observer: &mut StopAfter, max_moves: u32| {
        // Every greedy action is "up": from most states it walks into a wall forever.
        let mut p = csql::Identified::new(&world, vec![1.0; 9]);
        let mut table = qlearn::QTable::new(4).unwrap();
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
        csql::navigate(
            &world,
            &setup.oracle,
            &mut p,
            &mut table,
            csql::MAX_NAVIGATION_TRIALS,
            max_moves,
            &mut rng,
            observer,
        )
    };
    // Three trials, then a stop before the fourth.
    let n = navigate(&mut StopAfter { left: 3 }, 10);
    assert_eq!(n.trials, 3);
    // One question before the first trial, the next after 4,096 moves of it.
    let n = navigate(&mut StopAfter { left: 1 }, u32::MAX);
    assert_eq!((n.trials, n.moves), (1, u64::from(csql::STOP_CHECK_MOVES)));
}

#[test]
fn navigation_trials_have_an_upper_bound() {
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let toml = "predict_sensing = \"learned\"\n[prediction]\nnavigation_trials = 4294967295\n";
    let err = s.apply_toml(toml, "t.toml").unwrap_err().to_string();
    assert!(
        err.contains("prediction.navigation_trials") && err.contains("at most 10000"),
        "{err}"
    );
    let most = "predict_sensing = \"learned\"\n[prediction]\nnavigation_trials = 10000\n";
    s.apply_toml(most, "t.toml").unwrap();
}

/// A trial of learning asks the observer every `STOP_CHECK_MOVES` moves too: a no ends
/// the trial there, and the run after it.
#[test]
fn a_long_trial_of_learning_stops_when_its_observer_says_so() {
    let mut s = RunSettings::tan1991("random:48x48:0.2:1", StrategyKind::Lazy, 1);
    s.max_trials = csql::TrialCap::new(1).unwrap();
    s.max_moves = qlearn::MoveCap::new(1_000_000).unwrap();
    let setup = Setup::new(&s).unwrap();
    let whole = csql::run_on(&setup, &s).unwrap();
    let check = u64::from(csql::STOP_CHECK_MOVES);
    assert!(
        whole.moves > check,
        "the first trial is too short: {}",
        whole.moves
    );
    // One trial at most: the no cuts it, and the run ends with it.
    let stopped = csql::run_observed(&setup, &s, &mut StopAfter { left: 0 }).unwrap();
    assert_eq!((stopped.trials, stopped.moves), (1, check));
}
