//! `csrl run` with sensing priced in reward units, and `--learner amrl-q`.

mod common;

use common::{config, csrl, json, lake, returns, stderr};

use rand::SeedableRng;

fn refused(args: &[&str]) -> String {
    let out = csrl(args);
    assert!(!out.status.success(), "{args:?} was not refused");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn amrl_q_in_csrl_run_is_csql_amrl_q() {
    let dir = tempfile::tempdir().unwrap();
    let plain = config(dir.path(), "amrl", "");
    let v = json(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "amrl-q",
        "--price",
        "0.025",
        "--episodes",
        "300",
        "--seed",
        "5",
        "--config",
        plain.to_str().unwrap(),
        "--json",
    ]);
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(5);
    let run = csql::amrl_q(
        &lake(),
        &csql::AmrlParams::default(),
        0.05,
        mdp::SensingRule::WithMove,
        300,
        100,
        &mut rng,
    );
    let returns = returns(&v);
    let expected: Vec<f64> = run.iter().map(csql::Episode::costed_return).collect();
    // JSON's decimal form read back is within a unit of the last place.
    assert_eq!(returns.len(), expected.len());
    for (got, want) in returns.iter().zip(&expected) {
        assert!((got - want).abs() < 1e-12, "{got} {want}");
    }
    assert_eq!(v["learner"], "amrl-q");
    assert_eq!(v["whole_state_price"], 0.05);
    let s = csql::CostlySummary::of(&run);
    assert_eq!(
        v["costly"]["summary"]["mean_all"].as_f64(),
        Some(s.mean_all)
    );
    // [amrl_q] tunes it, and the rule is a setting.
    let tuned = config(
        dir.path(),
        "tuned",
        "[amrl_q]\nepsilon = 0.3\n[costly]\nrule = \"after-outcome\"",
    );
    let v = json(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "amrl-q",
        "--price",
        "0.025",
        "--episodes",
        "50",
        "--config",
        tuned.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["settings"]["amrl_q"]["epsilon"], 0.3);
    assert_eq!(v["costly"]["rule"], "after-outcome");
    assert_eq!(v["costly"]["returns"].as_array().unwrap().len(), 50);
    let text = String::from_utf8(
        csrl(&[
            "run",
            "--world",
            "frozenlake4x4",
            "--learner",
            "amrl-q",
            "--price",
            "0.025",
            "--episodes",
            "50",
        ])
        .stdout,
    )
    .unwrap();
    assert!(
        text.contains("AMRL-Q on frozenlake4x4") && text.contains("Costed return"),
        "{text}"
    );
}

#[test]
fn costed_fields_only_when_priced_and_they_add_up() {
    let base = ["run", "--world", "frozenlake4x4", "--seed", "2", "--json"];
    for learner in ["cs-ql", "full-sensing"] {
        let mut args = base.to_vec();
        args.extend(["--learner", learner]);
        let plain = json(&args);
        assert!(plain.get("costly").is_none(), "{learner}");
        args.extend(["--price", "0.025", "--sensing-rule", "after-outcome"]);
        let priced = json(&args);
        let c = &priced["costly"];
        let returns = c["returns"].as_array().unwrap();
        assert_eq!(returns.len() as u64, priced["trials"].as_u64().unwrap());
        // Every trial that reaches the goal earns 1; the sensing is the run's cost, priced.
        let goals = c["summary"]["success"].as_f64().unwrap() * returns.len() as f64;
        let sum: f64 = returns.iter().map(|x| x.as_f64().unwrap()).sum();
        let cost = priced["total_cost"].as_f64().unwrap();
        assert!(
            (sum - (goals - 0.025 * cost)).abs() < 1e-6,
            "{learner}: {sum} {goals} {cost}"
        );
        // Nothing else changes.
        let mut without = priced.clone();
        without.as_object_mut().unwrap().remove("costly");
        without["settings"]
            .as_object_mut()
            .unwrap()
            .remove("costly");
        assert_eq!(without, plain, "{learner}");
    }
    let text =
        String::from_utf8(csrl(&["run", "--world", "frozenlake4x4", "--price", "0.025"]).stdout)
            .unwrap();
    assert!(text.contains("Costed return (sensing at 0.025"), "{text}");
}

#[test]
fn refused_combinations_name_both() {
    let err = refused(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "u-tree",
        "--price",
        "0.1",
    ]);
    assert!(
        err.contains("[costly] price") && err.contains("learner = u-tree"),
        "{err}"
    );
    let err = refused(&["run", "--world", "frozenlake4x4", "--learner", "amrl-q"]);
    assert!(
        err.contains("learner = amrl-q") && err.contains("--price"),
        "{err}"
    );
    let dir = tempfile::tempdir().unwrap();
    let tuned = config(dir.path(), "wrong", "[amrl_q]\nepsilon = 0.3");
    let err = refused(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--config",
        tuned.to_str().unwrap(),
    ]);
    assert!(
        err.contains("[amrl_q]") && err.contains("learner = cs-ql"),
        "{err}"
    );
    let err = refused(&["run", "--world", "frozenlake4x4", "--price=-1"]);
    assert!(err.contains("costly.price = -1"), "{err}");
    let err = refused(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--sensing-rule",
        "sideways",
    ]);
    assert!(err.contains("with-move or after-outcome"), "{err}");
    let err = refused(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "amrl-q",
        "--price",
        "0.1",
        "--svg",
        "x.svg",
    ]);
    assert!(
        err.contains("--svg") && err.contains("learner = amrl-q"),
        "{err}"
    );
    let err = refused(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--learner",
        "amrl-q",
        "--price",
        "0.1",
        "--episodes",
        "5",
        "--config",
        "/dev/null",
    ]);
    assert!(!err.contains("panicked"), "{err}");
}

/// Every episode of a learner on costed episodes is kept in its report: more than
/// `csql::MAX_EPISODES` are refused before anything runs (four billion aborted, asking
/// for 128 GB at once).
#[test]
fn too_many_episodes_are_refused_up_front() {
    for learner in ["amrl-q", "belief"] {
        let out = csrl(&[
            "run",
            "--world",
            "frozenlake4x4",
            "--learner",
            learner,
            "--price",
            "0.025",
            "--episodes",
            "4000000000",
        ]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{learner}: {err}");
        assert!(err.contains("at most 1000000 episodes"), "{learner}: {err}");
    }
}

/// Costed returns whose sums cannot be represented are refused before anything runs,
/// naming the price, the world and its costs and rewards: a price of 1e308 (its means
/// were printed as `null`), and a world file whose reward is 1e308.
#[test]
fn costed_returns_that_cannot_be_summed_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let world = dir.path().join("huge-reward.json");
    std::fs::write(
        &world,
        r#"{"format": "csrl-world", "version": 1, "name": "huge", "states": 2,
            "actions": ["go"], "start": [[1.0, 0]], "terminal": [1],
            "transitions": [[0, 0, [[1.0, 1, 1e308, true]]]],
            "features": [{"name": "where", "price": 1.0}], "readings": [[0], [1]]}"#,
    )
    .unwrap();
    let world = world.to_str().unwrap();
    for (args, named, bound) in [
        (
            vec![
                "--world",
                "frozenlake4x4",
                "--learner",
                "amrl-q",
                "--price",
                "1e308",
            ],
            "costly.price = 1e308 in frozenlake4x4",
            "at most 1e300",
        ),
        (
            vec![
                "--world",
                "frozenlake4x4",
                "--price",
                "1e308",
                "--max-trials",
                "5",
            ],
            "costly.price = 1e308",
            "at most 1e300",
        ),
        // A reward that large is refused with the world, before any price is applied.
        (
            vec!["--world", world, "--learner", "amrl-q", "--price", "0.1"],
            "reward 1e308",
            "mdp::MAX_REWARD",
        ),
    ] {
        let out = csrl(&[&["run"][..], &args].concat());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(named) && err.contains(bound),
            "{args:?}: {err}"
        );
    }
}
