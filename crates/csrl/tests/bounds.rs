//! Finite but huge numbers never reach a report as `null` or `inf`: rewards and prices
//! whose sums over a run could overflow are refused up front, naming the bound, and
//! those within it give finite results.

mod common;

use common::{csrl, json, stderr};

/// A world of two states: `a` loops on itself with `reward`, `b` leads to the goal; one
/// feature at `price`.
fn world(dir: &std::path::Path, reward: f64, price: f64) -> std::path::PathBuf {
    let path = dir.join(format!("loop-{reward:e}-{price:e}.json"));
    let text = format!(
        r#"{{"format": "csrl-world", "version": 1, "name": "loop",
  "states": ["a", "b", "g"], "actions": ["stay", "go"], "start": [[1.0, 0]], "terminal": [2],
  "transitions": [
    [0, 0, [[1.0, 0, {reward:e}, false]]], [0, 1, [[1.0, 1, 0.0, false]]],
    [1, 0, [[1.0, 1, 0.0, false]]], [1, 1, [[1.0, 2, 1.0, true]]]],
  "features": [{{"name": "where", "price": {price:e}, "readings": ["a", "b", "g"]}}],
  "readings": [[0], [1], [2]]}}"#
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// Every number in a report, with where it is; `null` and non-numbers are skipped.
fn numbers(v: &serde_json::Value, at: &str, out: &mut Vec<(String, Option<f64>)>) {
    match v {
        serde_json::Value::Number(n) => out.push((at.to_string(), n.as_f64())),
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                numbers(x, &format!("{at}[{i}]"), out);
            }
        }
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                numbers(x, &format!("{at}.{k}"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn a_world_whose_sums_could_overflow_is_refused_by_check_and_run() {
    let dir = tempfile::tempdir().unwrap();
    for (reward, price, bound) in [
        (1e308, 1.0, "mdp::MAX_REWARD"),
        (-1e308, 1.0, "mdp::MAX_REWARD"),
        (0.0, 1e308, "mdp::MAX_PRICE"),
    ] {
        let path = world(dir.path(), reward, price);
        let path = path.to_str().unwrap();
        for args in [
            &["world", "check", path][..],
            &["run", "--world", path, "--max-trials", "5"][..],
        ] {
            let out = csrl(args);
            assert_eq!(out.status.code(), Some(1), "{args:?}");
            assert!(stderr(&out).contains(bound), "{args:?}: {}", stderr(&out));
        }
    }
}

#[test]
fn factor_costs_whose_sums_could_overflow_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let settings = dir.path().join("s.toml");
    std::fs::write(
        &settings,
        "[world]\nsensing = \"factors\"\nfactor_costs = [1.0, 1e308]\n",
    )
    .unwrap();
    let out = csrl(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--config",
        settings.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("mdp::MAX_PRICE"), "{}", stderr(&out));
}

#[test]
fn rewards_and_prices_at_the_bound_report_finite_numbers() {
    let dir = tempfile::tempdir().unwrap();
    for (reward, price) in [(1e200, 1.0), (-1e200, 1.0), (0.0, 1e200)] {
        let path = world(dir.path(), reward, price);
        let report = json(&[
            "run",
            "--json",
            "--world",
            path.to_str().unwrap(),
            "--seed",
            "1",
            "--max-trials",
            "50",
        ]);
        assert!(report["policy_quality"].is_number(), "{report}");
        assert!(report["total_cost"].is_number(), "{report}");
        let mut found = Vec::new();
        numbers(&report, "", &mut found);
        for (at, n) in found {
            assert!(n.is_some_and(f64::is_finite), "{at}: {n:?}");
        }
    }
}
