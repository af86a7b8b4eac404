//! `predict_sensing = "weighed"`: at a price of 0 it is the paper's run, move for move;
//! at a price it skips and narrows measurements, keeps the bound on wrong predictions and
//! still converges; it is refused without a price, and scored on costed episodes.

use csql::{
    CostlySettings, PredictSensing, PredictionParams, RunReport, RunSettings, StrategyKind,
};
use mdp::SensingRule;

fn settings(map: &str, strategy: StrategyKind, seed: u64, level: PredictSensing) -> RunSettings {
    let mut s = RunSettings::tan1991(map, strategy, seed);
    s.cs_ql_mut().unwrap().predict_sensing = level;
    s
}

fn priced(mut s: RunSettings, price: f64) -> RunSettings {
    s.costly = Some(CostlySettings::new(price));
    s
}

/// A report as JSON, without what only a predicting level reports.
fn learned_part(r: &RunReport) -> serde_json::Value {
    let mut v = serde_json::to_value(r).unwrap();
    let o = v.as_object_mut().unwrap();
    for key in [
        "prediction",
        "navigation_cost_per_move",
        "navigation_success",
        "settings",
    ] {
        o.remove(key);
    }
    v
}

/// Everything deterministic and nothing skipped (measuring is free at a price of 0):
/// every figure of the run, its trace and its costed episodes are the paper's.
#[test]
fn at_price_zero_the_belief_level_is_the_papers_run() {
    for map in ["tan3x3", "tan8x8"] {
        for strategy in StrategyKind::ALL {
            for seed in 1..=2 {
                let off = priced(settings(map, strategy, seed, PredictSensing::Off), 0.0);
                let belief = priced(settings(map, strategy, seed, PredictSensing::Weighed), 0.0);
                let (a, b) = (csql::run(&off).unwrap(), csql::run(&belief).unwrap());
                assert_eq!(
                    learned_part(&a),
                    learned_part(&b),
                    "{map} {strategy} {seed}"
                );
                assert!(a.costly.is_some());
                let p = b.prediction.unwrap();
                assert_eq!((p.skipped, p.narrowed, p.rechecks), (0, 0, 0));
            }
        }
    }
}

/// The same on a stochastic lake, for its costed episodes under both rules.
#[test]
fn at_price_zero_the_costed_episodes_are_cs_qls() {
    let options = mdp::WorldOptions {
        slide: Some(0.5),
        sensing: Some(mdp::SensingModel::Factors),
        ..Default::default()
    };
    let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
    for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
        let off = settings(
            "frozenlake4x4",
            StrategyKind::Resetting,
            3,
            PredictSensing::Off,
        );
        let mut belief = settings(
            "frozenlake4x4",
            StrategyKind::Resetting,
            3,
            PredictSensing::Weighed,
        );
        belief.costly = Some(CostlySettings { price: 0.0, rule });
        let a = csql::costed_episodes(&lake, &off, rule, 0.0, 300).unwrap();
        let b = csql::costed_episodes(&lake, &belief, rule, 0.0, 300).unwrap();
        assert_eq!(a, b, "{rule:?}");
    }
}

/// At a price the level skips most measurements of a deterministic map, never uses a
/// transition more than `max_skips` times in a row unmeasured, converges, and pays less
/// for sensing per move than the paper's procedure.
#[test]
fn at_a_price_it_senses_less_within_its_bound() {
    for (strategy, max_skips) in [(StrategyKind::Eager, 16), (StrategyKind::Lazy, 3)] {
        let off = csql::run(&settings("tan8x8", strategy, 2, PredictSensing::Off)).unwrap();
        let mut s = priced(
            settings("tan8x8", strategy, 2, PredictSensing::Weighed),
            0.01,
        );
        s.cs_ql_mut().unwrap().prediction = PredictionParams {
            max_skips,
            ..PredictionParams::default()
        };
        let r = csql::run(&s).unwrap();
        let p = r.prediction.unwrap();
        assert!(r.converged, "{strategy}");
        assert!(p.skipped > 100, "{strategy}: {p:?}");
        assert!(p.longest_wrong_run <= max_skips, "{strategy}: {p:?}");
        let per_move = |r: &RunReport| r.total_cost / r.moves as f64;
        assert!(
            per_move(&r) < 0.7 * per_move(&off),
            "{strategy}: {} against {}",
            per_move(&r),
            per_move(&off)
        );
        assert_eq!(r.navigation_success, Some(1.0));
    }
}

/// On a slippery lake the likely descriptions after a move are several: the level
/// narrows among them, and senses less per episode than CS-QL at the same price.
#[test]
fn on_a_slippery_lake_it_narrows_and_senses_less() {
    let toml = "map = \"frozenlake4x4\"\nmax_trials = 600\nstrategy = \"resetting\"\n\
                predict_sensing = \"weighed\"\n[world]\nsensing = \"factors\"\nslide = 0.5\n\
                [costly]\nprice = 0.025";
    let belief = csql::SettingsDraft::from_toml(toml, "lake.toml")
        .unwrap()
        .build()
        .unwrap();
    let mut off = belief.clone();
    off.cs_ql_mut().unwrap().predict_sensing = PredictSensing::Off;
    let (a, b) = (csql::run(&off).unwrap(), csql::run(&belief).unwrap());
    let p = b.prediction.unwrap();
    assert!(p.narrowed > 0 && p.skipped > 0, "{p:?}");
    // The bound holds where outcomes are random too (the oracle's count).
    assert!(
        p.wrong > 0 && p.longest_wrong_run <= PredictionParams::default().max_skips,
        "{p:?}"
    );
    let (ca, cb) = (a.costly.unwrap().summary, b.costly.unwrap().summary);
    assert!(
        cb.sensing_per_episode < 0.6 * ca.sensing_per_episode,
        "{cb:?} against {ca:?}"
    );
}

/// With the move, a move that ends an episode is charged what the level chose to sense
/// with it; nothing else differs from the rule after the outcome.
#[test]
fn with_the_move_only_the_last_move_is_charged_more() {
    let options = mdp::WorldOptions {
        sensing: Some(mdp::SensingModel::Factors),
        ..Default::default()
    };
    let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
    let play = |rule| {
        let mut s = settings(
            "frozenlake4x4",
            StrategyKind::Resetting,
            5,
            PredictSensing::Weighed,
        );
        s.costly = Some(CostlySettings { price: 0.025, rule });
        csql::costed_episodes(&lake, &s, rule, 0.025, 400).unwrap()
    };
    let (with, after) = (play(SensingRule::WithMove), play(SensingRule::AfterOutcome));
    let mut more = 0;
    for (w, a) in with.iter().zip(&after) {
        assert_eq!((w.reward, w.steps), (a.reward, a.steps));
        assert!(w.sensing >= a.sensing - 1e-12);
        more += usize::from(w.sensing > a.sensing + 1e-12);
    }
    assert!(more > 0 && more < with.len(), "{more}");
}

#[test]
fn the_belief_level_needs_a_price_in_reward_units() {
    let s = settings("tan3x3", StrategyKind::Lazy, 1, PredictSensing::Weighed);
    let err = csql::run(&s).unwrap_err().to_string();
    assert!(err.contains("[costly] price"), "{err}");
    // Scored at one price, it must weigh sensing at that price.
    let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
    let s = priced(s, 0.05);
    let err = csql::costed_episodes(&lake, &s, SensingRule::WithMove, 0.025, 3)
        .unwrap_err()
        .to_string();
    assert!(err.contains("predict_sensing = belief"), "{err}");
    assert!(csql::costed_episodes(&lake, &s, SensingRule::WithMove, 0.05, 3).is_ok());
}

/// `[prediction] memory_moves` tunes the motion level only: elsewhere it is refused,
/// naming both settings.
#[test]
fn memory_moves_is_refused_away_from_the_motion_level() {
    for level in [PredictSensing::Learned, PredictSensing::Weighed] {
        let mut s = settings("tan3x3", StrategyKind::Lazy, 1, level);
        if level == PredictSensing::Weighed {
            s = priced(s, 0.01);
        }
        s.cs_ql_mut().unwrap().prediction.memory_moves = 5;
        let err = csql::run(&s).unwrap_err().to_string();
        assert!(err.contains("prediction.memory_moves = 5"), "{err}");
        assert!(err.contains(&format!("predict_sensing = {level}")), "{err}");
    }
}
