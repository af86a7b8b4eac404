//! `csrl run --learner belief`: sensing by belief played on costed episodes, exactly as
//! `csql::belief_planning` plays it, its settings (`[belief]`, `[costly]`) checked and
//! echoed, and refused where they mean nothing.

mod common;

use common::{config, csrl, json, lake, ok, returns};

use std::path::Path;

use rand::SeedableRng;

/// The error of a refused run: exit code 1, one message, no panic.
fn refused(args: &[&str]) -> String {
    let out = csrl(args);
    assert_eq!(out.status.code(), Some(1), "{args:?} was not refused");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// [`refused`] in the lake.
fn lake_refused(extra: &[&str]) -> String {
    let mut args = vec!["run", "--world", "frozenlake4x4"];
    args.extend_from_slice(extra);
    refused(&args)
}

/// The report's returns are `belief_planning`'s for the same seed and settings, episode
/// for episode, under both rules, with the lake's defaults (shared moves, 48 tries, and 64
/// open-loop plans a step), with `[belief]` tuned and each pair apart, and with shared
/// moves and fewer plans.
#[test]
fn belief_in_csrl_run_is_csql_belief_planning() {
    let dir = tempfile::tempdir().unwrap();
    let tuned = csql::BeliefParams {
        max_uncertain: 5,
        trust: 3,
        prior: 2.0,
        optimism: 0.8,
        whole_state: false,
        max_beliefs: 3000,
        move_cost: 1e-5,
        blind_plans: Some(0),
        shared_moves: Some(0),
    };
    let lakes_own = csql::BeliefParams {
        shared_moves: Some(48),
        blind_plans: Some(64),
        ..csql::BeliefParams::default()
    };
    let shared = csql::BeliefParams {
        shared_moves: Some(48),
        blind_plans: Some(16),
        ..csql::BeliefParams::default()
    };
    let shared_table = "[belief]\nshared_moves = 48\nblind_plans = 16";
    let tuned_table = "[belief]\nmax_uncertain = 5\ntrust = 3\nprior = 2.0\noptimism = 0.8\nmax_beliefs = 3000\nmove_cost = 1e-5\nshared_moves = 0\nblind_plans = 0";
    for (name, table, params) in [
        ("default", "", lakes_own),
        ("tuned", tuned_table, tuned),
        ("shared", shared_table, shared),
    ] {
        for rule in [mdp::SensingRule::WithMove, mdp::SensingRule::AfterOutcome] {
            let path = config(dir.path(), name, table);
            let v = json(&[
                "run",
                "--world",
                "frozenlake4x4",
                "--learner",
                "belief",
                "--price",
                "0.025",
                "--sensing-rule",
                rule.name(),
                "--episodes",
                "150",
                "--seed",
                "4",
                "--config",
                path.to_str().unwrap(),
                "--json",
            ]);
            let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(4);
            let run =
                csql::belief_planning(&lake(), &params, 0.025, rule, 150, 100, &mut rng).unwrap();
            let expected: Vec<f64> = run.iter().map(csql::Episode::costed_return).collect();
            let got = returns(&v);
            assert_eq!(got.len(), expected.len(), "{name} {rule:?}");
            // JSON's decimal form read back is within a unit of the last place.
            for (g, w) in got.iter().zip(&expected) {
                assert!((g - w).abs() < 1e-12, "{name} {rule:?}: {g} {w}");
            }
            let s = csql::CostlySummary::of(&run);
            let summary = &v["costly"]["summary"];
            assert_eq!(summary["episodes"].as_u64(), Some(150));
            for (key, want) in [
                ("mean_all", s.mean_all),
                ("mean_last10", s.mean_last10),
                ("sensing_per_episode", s.sensing_per_episode),
                ("steps_per_episode", s.steps_per_episode),
                ("success", s.success),
            ] {
                let got = summary[key].as_f64().unwrap();
                assert!(
                    (got - want).abs() < 1e-12,
                    "{name} {rule:?} {key}: {got} {want}"
                );
            }
            assert_eq!(v["costly"]["rule"], rule.name());
        }
    }
}

/// The report's fields: the world, the learner, the seed, the prices, every episode's
/// costed return with their summary, and the settings echoed (`[belief]` where it departs
/// from the library's defaults, the lake's own shared moves and open-loop plans included;
/// the price is `[costly] price`, not a key of `[belief]`).
#[test]
fn the_report_has_the_fields_of_a_run_on_costed_episodes() {
    let dir = tempfile::tempdir().unwrap();
    let path = config(
        dir.path(),
        "fields",
        "learner = \"belief\"\n[belief]\ntrust = 2",
    );
    let text = ok(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--price",
        "0.5",
        "--episodes",
        "20",
        "--seed",
        "9",
        "--config",
        path.to_str().unwrap(),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    // These fields, in this order, and no other.
    let fields = [
        "map",
        "learner",
        "seed",
        "whole_state_price",
        "costly",
        "settings",
    ];
    assert_eq!(v.as_object().unwrap().len(), fields.len());
    let at: Vec<usize> = fields
        .iter()
        .map(|f| text.find(&format!("\"{f}\":")).unwrap())
        .collect();
    assert!(at.is_sorted() && at[0] == 1, "{text}");
    assert_eq!(v["map"], "frozenlake4x4");
    assert_eq!(v["learner"], "belief");
    assert_eq!(v["seed"], 9);
    // Row and column, each of cost 1, at 0.5 reward units each.
    assert_eq!(v["whole_state_price"], 1.0);
    assert_eq!(v["costly"]["price"], 0.5);
    assert_eq!(v["costly"]["rule"], "with-move");
    assert_eq!(returns(&v).len(), 20);
    let summary = v["costly"]["summary"].as_object().unwrap();
    for key in [
        "episodes",
        "mean_all",
        "mean_last10",
        "sensing_per_episode",
        "steps_per_episode",
        "success",
    ] {
        assert!(summary.contains_key(key), "{key}");
    }
    let s = &v["settings"];
    assert_eq!(s["learner"], "belief");
    assert_eq!(s["seed"], 9);
    assert_eq!(s["episodes"], 20);
    assert_eq!(s["costly"]["price"], 0.5);
    assert_eq!(
        s["belief"],
        serde_json::json!({"max_uncertain": 7, "trust": 2, "prior": 3.0, "optimism": 1.0, "whole_state": false, "max_beliefs": 5000, "move_cost": 1e-6, "blind_plans": 64, "shared_moves": 48})
    );
    assert!(s.get("strategy").is_none() && s.get("amrl_q").is_none());
    // With no [belief], the lake's own shared moves and open-loop plans are echoed, so
    // that the settings build again to the same.
    let plain = config(dir.path(), "plain", "");
    let v = json(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "belief",
        "--price",
        "0.5",
        "--episodes",
        "5",
        "--config",
        plain.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        v["settings"]["belief"],
        serde_json::json!({"max_uncertain": 7, "trust": 4, "prior": 3.0, "optimism": 1.0, "whole_state": false, "max_beliefs": 5000, "move_cost": 1e-6, "blind_plans": 64, "shared_moves": 48}),
        "{v}"
    );
    // The text report.
    let text = ok(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "belief",
        "--price",
        "0.025",
        "--episodes",
        "50",
        "--config",
        plain.to_str().unwrap(),
    ]);
    assert!(
        text.starts_with("Sensing by belief on frozenlake4x4, seed 1: 50 episodes")
            && text.contains(
                "Costed return (sensing at 0.025 reward units per unit of cost, with-move)"
            ),
        "{text}"
    );
}

/// The settings a report echoes, written as a settings file, are read back to the same
/// settings and the same report, byte for byte.
#[test]
fn a_settings_file_with_belief_is_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = config(
        dir.path(),
        "first",
        "learner = \"belief\"\nepisodes = 40\nseed = 3\n[belief]\nwhole_state = true\nmax_uncertain = 4\nprior = 1.5\n[costly]\nprice = 0.025\nrule = \"after-outcome\"",
    );
    let args = |p: &Path| {
        [
            "run",
            "--world",
            "frozenlake4x4",
            "--config",
            p.to_str().unwrap(),
            "--json",
        ]
        .map(str::to_string)
    };
    let first = ok(&args(&path).each_ref().map(String::as_str));
    let v: serde_json::Value = serde_json::from_str(&first).unwrap();
    assert_eq!(v["settings"]["belief"]["whole_state"], true);
    assert_eq!(v["settings"]["belief"]["max_uncertain"], 4);
    assert_eq!(v["settings"]["belief"]["prior"], 1.5);
    let settings: csql::RunSettings = serde_json::from_value(v["settings"].clone()).unwrap();
    match settings.learner {
        csql::LearnerSettings::Belief(p) => {
            assert!(p.whole_state && p.max_uncertain == 4 && p.prior == 1.5);
        }
        other => panic!("{other:?}"),
    }
    let echo = dir.path().join("echo.toml");
    std::fs::write(&echo, toml::to_string(&settings).unwrap()).unwrap();
    let again = ok(&args(&echo).each_ref().map(String::as_str));
    assert_eq!(again, first);
}

#[test]
fn refused_settings_name_both_or_say_what_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    // No price.
    let err = lake_refused(&["--learner", "belief"]);
    assert!(
        err.contains("learner = belief") && err.contains("--price"),
        "{err}"
    );
    // [belief] with another learner, and another learner's settings with belief.
    let tuned = config(dir.path(), "tuned", "[belief]\ntrust = 2");
    for learner in ["cs-ql", "amrl-q", "full-sensing"] {
        let err = lake_refused(&[
            "--learner",
            learner,
            "--price",
            "0.1",
            "--config",
            tuned.to_str().unwrap(),
        ]);
        assert!(
            err.contains("[belief]") && err.contains(&format!("learner = {learner}")),
            "{err}"
        );
    }
    let amrl = config(dir.path(), "amrl", "[amrl_q]\nepsilon = 0.3");
    let err = lake_refused(&[
        "--learner",
        "belief",
        "--price",
        "0.1",
        "--config",
        amrl.to_str().unwrap(),
    ]);
    assert!(
        err.contains("[amrl_q]") && err.contains("learner = belief"),
        "{err}"
    );
    let err = lake_refused(&[
        "--learner",
        "belief",
        "--price",
        "0.1",
        "--strategy",
        "lazy",
    ]);
    assert!(
        err.contains("strategy = lazy") && err.contains("learner = belief"),
        "{err}"
    );
    // Bad values, each named with what is accepted.
    for (table, says) in [
        ("trust = 0", "belief.trust = 0"),
        ("prior = 0.0", "belief.prior = 0"),
        ("prior = -1.0", "belief.prior = -1"),
        ("optimism = nan", "belief.optimism = NaN"),
        ("move_cost = -1.0", "belief.move_cost = -1"),
        ("move_cost = inf", "belief.move_cost = inf"),
        ("max_beliefs = 0", "belief.max_beliefs = 0"),
        ("max_beliefs = 1000001", "belief.max_beliefs = 1000001"),
        ("max_uncertain = 65", "belief.max_uncertain = 65"),
        ("max_uncertain = -1", "max_uncertain"),
        ("whole_state = 1", "whole_state"),
        ("price_scale = 2.0", "[costly] price"),
        ("trsut = 2", "trsut"),
    ] {
        let path = config(dir.path(), "bad", &format!("[belief]\n{table}"));
        let err = lake_refused(&[
            "--learner",
            "belief",
            "--price",
            "0.1",
            "--config",
            path.to_str().unwrap(),
        ]);
        assert!(err.contains(says), "{table}: {err}");
    }
    // A key of [belief] in another table says where it belongs.
    let misplaced = config(dir.path(), "misplaced", "[costly]\ntrust = 2");
    let err = lake_refused(&[
        "--learner",
        "belief",
        "--price",
        "0.1",
        "--config",
        misplaced.to_str().unwrap(),
    ]);
    assert!(err.contains("[belief]"), "{err}");
    // Flags that mean nothing for a learner on episodes.
    for flag in [
        &["--svg", "x.svg"][..],
        &["--trace"],
        &["--require-convergence"],
    ] {
        let err = lake_refused(&[&["--learner", "belief", "--price", "0.1"], flag].concat());
        assert!(
            err.contains(flag[0]) && err.contains("learner = belief"),
            "{err}"
        );
    }
    // A world of more features than a plan's menu measures apart: a clear error, and the
    // remedy.
    let err = refused(&[
        "run",
        "--learner",
        "belief",
        "--price",
        "0.1",
        "--episodes",
        "3",
    ]);
    assert!(
        err.contains("sensing by belief") && err.contains("whole state"),
        "{err}"
    );
}

/// The remedy works: on the paper's grid, the whole state measured at once.
#[test]
fn the_whole_state_on_a_grid_map() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("whole.toml");
    std::fs::write(
        &path,
        "learner = \"belief\"\n[belief]\nwhole_state = true\n",
    )
    .unwrap();
    let v = json(&[
        "run",
        "--world",
        "tan3x3",
        "--price",
        "0.01",
        "--episodes",
        "30",
        "--config",
        path.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["map"], "tan3x3");
    assert_eq!(returns(&v).len(), 30);
    assert!(v["whole_state_price"].as_f64().unwrap() > 0.0);
}
