//! `csrl classify --max-test-cost B --max-tests K` and `csrl predict` with the same flags:
//! every object held to a budget, run as a user runs them on the heart-disease data with
//! Turney's prices and groups.

mod common;

use common::{csrl, stderr};

use std::path::PathBuf;
use std::process::Output;

fn repo(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
        .to_string_lossy()
        .into_owned()
}

/// `classify` on the Cleveland heart data with Turney's prices and groups, plus `extra`.
fn on_heart(learner: &str, extra: &[&str]) -> Output {
    let (data, costs, groups) = (
        repo("data/heart-disease/cleveland.csv"),
        repo("data/uci/heart-disease/costs/heart-disease.expense"),
        repo("data/uci/heart-disease/costs/heart-disease.group"),
    );
    let mut args = vec![
        "classify",
        "--data",
        &data,
        "--costs",
        &costs,
        "--groups",
        &groups,
        "--target",
        "num",
        "--positive-if",
        ">0",
        "--cost-name",
        "thalch=thalach",
        "--learner",
        learner,
        "--folds",
        "5",
        "--mc",
        "2000",
    ];
    args.extend_from_slice(extra);
    csrl(&args)
}

fn heart_json(learner: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["--json"];
    args.extend_from_slice(extra);
    let out = on_heart(learner, &args);
    assert!(out.status.success(), "{learner}: {}", stderr(&out));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A run refused with exit code 1 whose message holds every part of `expected`.
fn refused(out: &Output, expected: &[&str]) {
    let message = stderr(out);
    assert_eq!(out.status.code(), Some(1), "{message}");
    for part in expected {
        assert!(message.contains(part), "`{part}` missing in: {message}");
    }
    assert!(!message.contains("panicked"), "{message}");
}

/// Every learner, held to a price or a count: no test object pays or buys past it (each
/// object's own cost checked, not only the report's word), the report says so and gives
/// the tests bought per object.
#[test]
fn no_object_passes_the_budget_and_the_report_says_so() {
    for learner in ["eg2", "c45", "dtmc", "act"] {
        let free = heart_json(learner, &[]);
        assert_eq!(free["max_test_cost"], serde_json::Value::Null);
        assert_eq!(free["objects_over_budget"], 0);
        let free_tests = free["tests_per_object"].as_f64().unwrap();
        let free_costs = free["predictions"].as_array().unwrap().iter();
        // The budgets below bind: without them some object pays more than 3.
        assert!(
            free_costs
                .clone()
                .any(|p| p["test_cost"].as_f64().unwrap() > 3.0),
            "{learner}"
        );
        assert!(free_tests > 1.0, "{learner}: {free_tests}");
        for (flags, price, count) in [
            (vec!["--max-test-cost", "3"], Some(3.0), None),
            (vec!["--max-tests", "1"], None, Some(1)),
            (
                vec!["--max-test-cost", "100", "--max-tests", "2"],
                Some(100.0),
                Some(2),
            ),
        ] {
            let v = heart_json(learner, &flags);
            assert_eq!(v["objects_over_budget"], 0, "{learner} {flags:?}");
            assert_eq!(v["max_test_cost"].as_f64(), price);
            assert_eq!(v["max_tests"].as_u64(), count.map(|k: u64| k));
            let tests = v["tests_per_object"].as_f64().unwrap();
            let predictions = v["predictions"].as_array().unwrap();
            assert_eq!(predictions.len(), 304);
            for p in predictions {
                let cost = p["test_cost"].as_f64().unwrap();
                assert!(price.is_none_or(|b| cost <= b), "{learner} {flags:?}: {p}");
            }
            if let Some(k) = count {
                assert!(tests <= k as f64, "{learner}: {tests}");
            }
        }
    }
}

/// A budget of nothing: no test is bought, every object is answered at the root.
#[test]
fn a_budget_of_nothing_buys_no_test() {
    let v = heart_json("eg2", &["--max-tests", "0"]);
    assert_eq!(v["tests_per_object"], 0.0);
    assert_eq!(v["test_cost_per_object"], 0.0);
    let text = String::from_utf8(on_heart("eg2", &["--max-test-cost", "0"]).stdout).unwrap();
    assert!(
        text.contains("budget      at most 0 in price per object: 0.00 tests bought per object, no object past the budget"),
        "{text}"
    );
}

/// Without the flags, the report is the one it always was, apart from the new keys.
#[test]
fn without_a_budget_nothing_changes() {
    let out = on_heart("eg2", &[]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(!text.contains("budget      "), "{text}");
    let big = heart_json("eg2", &["--max-test-cost", "100000"]);
    let free = heart_json("eg2", &[]);
    for key in [
        "test_cost_per_object",
        "errors",
        "tree_nodes",
        "predictions",
    ] {
        assert_eq!(big[key], free[key], "{key}");
    }
}

#[test]
fn bad_budgets_are_refused_naming_the_flag() {
    refused(
        &on_heart("eg2", &["--max-test-cost", "-1"]),
        &["--max-test-cost -1", "finite price, not negative"],
    );
    refused(
        &on_heart("eg2", &["--max-test-cost", "NaN"]),
        &["--max-test-cost NaN"],
    );
    let out = on_heart("eg2", &["--max-tests=-2"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--max-tests"), "{}", stderr(&out));
    // The incremental learners have no budget.
    let dir = tempfile::tempdir().unwrap();
    let costs = dir.path().join("c.csv");
    std::fs::write(&costs, "feature,cost\nage,1\n").unwrap();
    let (data, costs) = (
        repo("data/heart-disease/cleveland.csv"),
        costs.to_string_lossy(),
    );
    let out = csrl(&[
        "classify",
        "--data",
        &data,
        "--costs",
        &costs,
        "--target",
        "num",
        "--learner",
        "cs-id3",
        "--max-tests",
        "2",
    ]);
    refused(&out, &["--max-tests is read by the test-cost family only"]);
}

/// A saved tree predicts within a budget given at prediction time: no row pays past it,
/// a budget of nothing measures nothing, and no budget is the old prediction.
#[test]
fn predict_holds_every_row_to_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("eg2.json").to_string_lossy().into_owned();
    let out = on_heart("eg2", &["--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    let data = repo("data/heart-disease/cleveland.csv");
    let predict = |extra: &[&str]| {
        let mut args = vec![
            "predict",
            "--model",
            &model,
            "--data",
            &data,
            "--probabilities",
        ];
        args.extend_from_slice(extra);
        let out = csrl(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        String::from_utf8(out.stdout).unwrap()
    };
    let free = predict(&[]);
    let costs = |text: &str| -> Vec<(f64, usize)> {
        text.lines()
            .skip(1)
            .map(|l| {
                let cells: Vec<&str> = l.split(',').collect();
                let measured = cells[3].split(';').filter(|m| !m.is_empty()).count();
                (cells[2].parse().unwrap(), measured)
            })
            .collect()
    };
    // Some rows pay more than 3, or buy more than 2 tests, without a budget.
    assert!(costs(&free).iter().any(|&(c, _)| c > 3.0));
    assert!(costs(&free).iter().any(|&(_, k)| k > 2));
    let within = predict(&["--max-test-cost", "3"]);
    assert!(costs(&within).iter().all(|&(c, _)| c <= 3.0), "{within}");
    let two = predict(&["--max-tests", "2"]);
    assert!(costs(&two).iter().all(|&(_, k)| k <= 2), "{two}");
    assert!(
        costs(&predict(&["--max-tests", "0"]))
            .iter()
            .all(|&(c, k)| (c, k) == (0.0, 0))
    );
    assert_eq!(predict(&["--max-test-cost", "1e9"]), free);
    let out = csrl(&[
        "predict",
        "--model",
        &model,
        "--data",
        &data,
        "--max-test-cost",
        "-3",
    ]);
    refused(&out, &["--max-test-cost -3"]);
}

/// An incremental model has no budget to hold: the flag is refused, naming it.
#[test]
fn predict_refuses_a_budget_for_an_incremental_model() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("d.csv");
    std::fs::write(&data, "a,t\n0,n\n1,p\n0,n\n1,p\n").unwrap();
    let costs = dir.path().join("c.csv");
    std::fs::write(&costs, "feature,cost\na,3\n").unwrap();
    let model = dir.path().join("m.json");
    let (data, costs, model) = (
        data.to_string_lossy().into_owned(),
        costs.to_string_lossy().into_owned(),
        model.to_string_lossy().into_owned(),
    );
    let out = csrl(&[
        "classify", "--data", &data, "--costs", &costs, "--target", "t", "--save", &model,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = csrl(&[
        "predict",
        "--model",
        &model,
        "--data",
        &data,
        "--max-tests",
        "1",
    ]);
    refused(
        &out,
        &["--max-tests is read with a tree of the test-cost family"],
    );
}
