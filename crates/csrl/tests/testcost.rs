//! `csrl classify --learner c45|idx|cs-id3-batch|eg2|dtmc|icet` and `csrl predict` on the
//! trees it saves, run as a user runs them: on the shipped heart-disease data with
//! Turney's prices, and on broken files.

mod common;

use common::{csrl, stderr};

use std::path::PathBuf;
use std::process::Output;

/// A path of the repository.
fn repo(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
        .to_string_lossy()
        .into_owned()
}

/// `classify` on the Cleveland heart data with Turney's prices and groups (the data
/// calls `thalach` `thalch`), two classes, plus `extra`.
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

fn f(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing: {v}"))
}

/// A scratch directory with a small data set: `a` numeric, `b` nominal, class `t`.
struct Scratch {
    dir: tempfile::TempDir,
}

impl Scratch {
    fn new() -> Scratch {
        let s = Scratch {
            dir: tempfile::tempdir().unwrap(),
        };
        let mut data = String::from("a,b,t\n");
        for i in 0..24 {
            let positive = i % 3 == 0;
            let b = if positive { "x" } else { "y" };
            let t = if positive { "p" } else { "n" };
            data.push_str(&format!("{},{b},{t}\n", i % 7));
        }
        s.file("data.csv", &data);
        s.file("prices.expense", "a: 10, 2\nb: 8, 3\n");
        s.file("prices.group", "G.\na: G.\nb: G.\n");
        s
    }

    fn file(&self, name: &str, text: &str) -> String {
        let path = self.dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_string_lossy().into_owned()
    }

    fn path(&self, name: &str) -> String {
        self.dir.path().join(name).to_string_lossy().into_owned()
    }

    /// `classify` on the scratch data with `learner` and `extra`.
    fn classify(&self, learner: &str, costs: &str, extra: &[&str]) -> Output {
        let (data, costs) = (self.path("data.csv"), self.path(costs));
        let mut args = vec![
            "classify",
            "--data",
            &data,
            "--costs",
            &costs,
            "--target",
            "t",
            "--learner",
            learner,
        ];
        args.extend_from_slice(extra);
        csrl(&args)
    }
}

/// A run refused with exit code 1 (not a panic's 101, not a usage error's 2) whose message
/// holds every part of `expected`.
fn refused(out: &Output, expected: &[&str]) {
    let message = stderr(out);
    assert_eq!(out.status.code(), Some(1), "{message}");
    for part in expected {
        assert!(message.contains(part), "`{part}` missing in: {message}");
    }
    assert!(!message.contains("panicked"), "{message}");
}

#[test]
fn every_family_learner_reports_what_its_tests_and_errors_cost() {
    let mut test_costs = Vec::new();
    for learner in ["c45", "idx", "cs-id3-batch", "eg2", "dtmc"] {
        let v = heart_json(learner, &[]);
        assert_eq!(v["learner"], learner);
        assert_eq!(v["evaluation"], "10-fold");
        assert_eq!(
            (v["objects"].as_u64(), v["test_objects"].as_u64()),
            (Some(304), Some(304))
        );
        assert_eq!(v["classes"], 2);
        assert_eq!(v["class_names"], serde_json::json!(["no", "yes"]));
        let (tests, mc, total) = (
            f(&v, "test_cost_per_object"),
            f(&v, "misclassification_cost_per_object"),
            f(&v, "total_cost_per_object"),
        );
        assert!((total - (tests + mc)).abs() < 1e-9, "{v}");
        let errors = v["errors"].as_u64().unwrap();
        assert!((f(&v, "error_rate") - errors as f64 / 304.0).abs() < 1e-12);
        // The default misclassification cost is the price of every test, discounts applied.
        assert_eq!(f(&v, "mc"), f(&v, "all_tests_cost"));
        assert!((f(&v, "all_tests_cost") - 323.97).abs() < 1e-9, "{v}");
        assert!((mc - errors as f64 * f(&v, "mc") / 304.0).abs() < 1e-9);
        assert!(f(&v, "error_rate") < 0.35, "{learner}: {v}");
        assert_eq!(v["splits"].as_array().unwrap().len(), 10);
        assert!(f(&v, "tree_nodes") >= 1.0);
        assert!(v["splits"][0].get("genome").is_none());
        assert!(total < f(&v, "standard_cost"), "{learner}: {v}");
        test_costs.push((learner, tests));
    }
    // Cost-blind C4.5 pays for far more tests than the cost-sensitive trees.
    let c45 = test_costs[0].1;
    for &(learner, cost) in &test_costs[1..] {
        assert!(cost * 5.0 < c45, "{learner}: {cost} against C4.5's {c45}");
    }
}

#[test]
fn selection_prices_are_a_family_setting_reported_with_the_results() {
    let path = heart_json("cs-id3-batch", &[]);
    assert_eq!(path["selection_prices"], "path");
    let listed = heart_json("cs-id3-batch", &["--selection-prices", "listed"]);
    assert_eq!(listed["selection_prices"], "listed");
    // A numeric test bought once is free further down the path; seen at its listed price
    // it is bought less often again, so the tree buys other, dearer tests.
    let (p, l) = (
        f(&path, "test_cost_per_object"),
        f(&listed, "test_cost_per_object"),
    );
    assert!(
        p != l,
        "path {p} and listed {l} should grow different trees"
    );
    assert_eq!(
        heart_json("cs-id3-batch", &["--selection-prices", "path"])["total_cost_per_object"],
        path["total_cost_per_object"]
    );
    refused(
        &on_heart("eg2", &["--selection-prices", "free"]),
        &[
            "--selection-prices",
            "`free`",
            "`path`, `listed` or `listed-once`",
        ],
    );
}

#[test]
fn icet_pruned_by_costs_pays_for_fewer_tests_than_pruned_by_errors() {
    let errors = heart_json("icet", &["--holdout", "0.3", "--mc", "100"]);
    assert_eq!(errors["icet_pruning"], "errors");
    let costs = heart_json(
        "icet",
        &["--holdout", "0.3", "--mc", "100", "--icet-pruning", "costs"],
    );
    assert_eq!(costs["icet_pruning"], "costs");
    // At mc 100 an error costs less than a third of the tests: cut by cost, the tree
    // keeps only tests that pay for themselves.
    let (e, c) = (
        f(&errors, "test_cost_per_object"),
        f(&costs, "test_cost_per_object"),
    );
    assert!(c < e, "pruned by costs {c}, by errors {e}");
    refused(
        &on_heart("eg2", &["--icet-pruning", "costs"]),
        &["--icet-pruning", "--learner icet only"],
    );
    refused(
        &on_heart("icet", &["--icet-pruning", "leaves"]),
        &["--icet-pruning", "`leaves`", "`errors` or `costs`"],
    );
}

#[test]
fn act_samples_are_an_act_setting_reported_with_the_results() {
    let act = heart_json("act", &["--holdout", "0.3", "--mc", "500"]);
    assert_eq!(act["act_samples"], 5);
    let c45 = heart_json("c45", &["--holdout", "0.3", "--mc", "500"]);
    assert!(c45["act_samples"].is_null());
    // Turney's heart prices: ACT buys a few cheap tests where C4.5 buys most of them.
    let (a, c) = (
        f(&act, "test_cost_per_object"),
        f(&c45, "test_cost_per_object"),
    );
    assert!(a < c / 4.0, "ACT pays {a} for tests, C4.5 {c}");
    let one = heart_json("act", &["--holdout", "0.3", "--act-samples", "1"]);
    assert_eq!(one["act_samples"], 1);
    refused(
        &on_heart("eg2", &["--act-samples", "3"]),
        &["--act-samples", "--learner act only"],
    );
    refused(
        &on_heart("act", &["--act-samples", "1001"]),
        &["--act-samples", "1001 ACT samples", "at most 1000"],
    );
}

#[test]
fn cvt_reports_what_its_cross_validation_chose_and_its_folds_are_a_cvt_setting() {
    let v = heart_json("cvt", &["--holdout", "0.3", "--mc", "500"]);
    assert_eq!(v["cvt_folds"], 5);
    let choice = &v["splits"][0]["cvt"];
    let growers = [
        "eg2-w0", "eg2-w0.5", "eg2-w1", "eg2-w2", "c45", "dtmc", "act",
    ];
    assert!(
        growers.contains(&choice["grower"].as_str().unwrap_or("")),
        "{choice}"
    );
    // A price per leaf, or null where the pessimistic pruning was measured cheaper.
    assert!(
        choice["alpha"].is_null() || choice["alpha"].as_f64().is_some_and(|a| a >= 0.0),
        "{choice}"
    );
    assert!(
        choice["held_out_cost"].as_f64().is_some_and(|c| c > 0.0),
        "{choice}"
    );
    let c45 = heart_json("c45", &["--holdout", "0.3", "--mc", "500"]);
    assert!(c45["cvt_folds"].is_null() && c45["splits"][0]["cvt"].is_null());
    // Turney's heart prices: CVT buys a few cheap tests where C4.5 buys most of them.
    let (a, c) = (
        f(&v, "test_cost_per_object"),
        f(&c45, "test_cost_per_object"),
    );
    assert!(a < c / 4.0, "CVT pays {a} for tests, C4.5 {c}");
    let text = String::from_utf8(on_heart("cvt", &["--holdout", "0.3"]).stdout).unwrap();
    assert!(text.contains("cvt         held out: grown by "), "{text}");
    assert_eq!(
        heart_json("cvt", &["--holdout", "0.3", "--cvt-folds", "3"])["cvt_folds"],
        3
    );
    refused(
        &on_heart("eg2", &["--cvt-folds", "3"]),
        &["--cvt-folds", "--learner cvt only"],
    );
    refused(
        &on_heart("cvt", &["--cvt-folds", "1"]),
        &["--cvt-folds", "1 folds for CVT", "at least 2 folds"],
    );
}

/// `--cvt-samples`: the lookahead grower's samples, reported; 0 leaves it out, so that
/// the choice is a greedy grower's, measured at a held-out cost no lower than with the
/// lookahead among the growers (the greedy growers' trees and folds are the same).
#[test]
fn cvt_samples_set_its_lookahead_and_zero_leaves_it_out() {
    let mut held_out = Vec::new();
    for samples in ["5", "0"] {
        let v = heart_json(
            "cvt",
            &["--holdout", "0.3", "--mc", "1000", "--cvt-samples", samples],
        );
        assert_eq!(v["cvt_samples"].to_string(), samples);
        let choice = &v["splits"][0]["cvt"];
        if samples == "0" {
            assert_ne!(choice["grower"], "act", "{choice}");
        }
        held_out.push(choice["held_out_cost"].as_f64().unwrap());
    }
    assert!(held_out[1] >= held_out[0] - 1e-9, "{held_out:?}");
    assert_eq!(heart_json("cvt", &["--holdout", "0.3"])["cvt_samples"], 5);
    refused(
        &on_heart("eg2", &["--cvt-samples", "1"]),
        &["--cvt-samples", "--learner cvt only"],
    );
    refused(
        &on_heart("cvt", &["--cvt-samples", "1001"]),
        &[
            "--cvt-samples",
            "1001 samples for CVT's lookahead",
            "at most 1000",
        ],
    );
}

/// ACT and CVT on two threads, or on every core, write what they write on one, byte for
/// byte.
#[test]
fn act_and_cvt_on_several_threads_write_the_same_output() {
    for (learner, flag) in [("act", "--act-threads"), ("cvt", "--cvt-threads")] {
        let one = on_heart(learner, &["--folds", "3", "--json"]);
        assert!(
            one.status.success(),
            "{}",
            String::from_utf8_lossy(&one.stderr)
        );
        for threads in ["2", "0"] {
            let many = on_heart(learner, &["--folds", "3", "--json", flag, threads]);
            assert_eq!(many.stdout, one.stdout, "{flag} {threads}");
        }
        refused(
            &on_heart("eg2", &[flag, "2"]),
            &[flag, &format!("--learner {learner} only")],
        );
    }
}

#[test]
fn icet_reports_the_genome_its_search_found() {
    let v = heart_json("icet", &["--holdout", "0.3"]);
    assert_eq!(v["evaluation"], "holdout 0.3");
    assert_eq!(v["splits"].as_array().unwrap().len(), 1);
    // A share of each class: 30% of 165 "no" (49.5, rounded up) and of 139 "yes".
    assert_eq!(v["test_objects"], 50 + 42);
    let genome = &v["splits"][0]["genome"];
    assert_eq!(genome["prices"].as_object().unwrap().len(), 13, "{genome}");
    assert!(genome["prices"]["thalch"].as_f64().is_some(), "{genome}");
    for key in ["w", "confidence", "fitness"] {
        assert!(genome[key].as_f64().is_some_and(f64::is_finite), "{genome}");
    }
    let out = on_heart("icet", &["--holdout", "0.3"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("genome      held out: w "), "{text}");
}

#[test]
fn the_same_seed_gives_the_same_report() {
    let a = heart_json("eg2", &["--seed", "4", "--folds", "5"]);
    assert_eq!(a, heart_json("eg2", &["--seed", "4", "--folds", "5"]));
    assert_eq!(a["evaluation"], "5-fold");
    assert_ne!(
        a["splits"],
        heart_json("eg2", &["--seed", "5", "--folds", "5"])["splits"]
    );
}

#[test]
fn text_output_names_every_figure() {
    let out = on_heart("dtmc", &["--mc", "200"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    for part in [
        "learner     dtmc (seed 1)",
        "304 objects",
        "every test: 323.97",
        "mc          200 per wrong answer",
        "evaluation  10-fold: 304 test objects",
        "test cost ",
        "error rate ",
        "mc cost ",
        "total cost ",
        "of Turney's standard cost",
        "tree size ",
    ] {
        assert!(text.contains(part), "`{part}` missing in {text}");
    }
}

#[test]
fn the_feature_cost_csv_and_a_cost_matrix_serve_the_family_too() {
    let s = Scratch::new();
    s.file("costs.csv", "feature,cost\na,10\nb,8\n");
    s.file("mc.csv", "actual,n,p\nn,0,1\np,500,0\n");
    let out = s.classify("eg2", "costs.csv", &["--folds", "4", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // Without groups every test costs its full price; the default mc is their sum.
    assert_eq!(f(&v, "mc"), 18.0);
    let out = s.classify(
        "dtmc",
        "costs.csv",
        &["--mc-matrix", &s.path("mc.csv"), "--json"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["mc"].is_null());
    assert!(v["mc_matrix"].as_str().unwrap().ends_with("mc.csv"));
    // With groups, the second test of a group costs its discount: every test together is
    // b in full (8), then a at its discount (2).
    let out = s.classify(
        "idx",
        "prices.expense",
        &[
            "--groups",
            &s.path("prices.group"),
            "--folds",
            "3",
            "--json",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(f(&v, "all_tests_cost"), 10.0);
}

#[test]
fn a_saved_tree_predicts_new_rows_by_column_name() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("eg2.json").to_string_lossy().into_owned();
    let out = on_heart("eg2", &["--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("saved the model (eg2, "),
        "{}",
        stderr(&out)
    );
    let text = std::fs::read_to_string(&model).unwrap();
    assert!(
        text.starts_with("{\"format\":\"csrl-cost-tree\",\"version\":1,\"learner\":\"eg2\","),
        "{text}"
    );
    let data = repo("data/heart-disease/cleveland.csv");
    let out = csrl(&["predict", "--model", &model, "--data", &data]);
    assert!(out.status.success(), "{}", stderr(&out));
    let all = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = all.lines().collect();
    assert_eq!(lines[0], "line,class,cost,measured");
    assert_eq!(lines.len(), 305);
    assert!(lines[1].starts_with("2,"), "{all}");
    assert!(
        lines[1..]
            .iter()
            .all(|l| l.split(',').nth(1).is_some_and(|c| c == "no" || c == "yes")),
        "{all}"
    );
    // The first two rows again, columns in another order, no target; then a row of
    // missing cells and a category never seen.
    let rows = dir.path().join("new.csv");
    std::fs::write(
        &rows,
        "sex,age,cp,trestbps,chol,fbs,restecg,thalch,exang,oldpeak,slope,ca,thal\n\
         Male,63,typical angina,145,233,TRUE,lv hypertrophy,150,FALSE,2.3,downsloping,0,fixed defect\n\
         Male,67,asymptomatic,160,286,FALSE,lv hypertrophy,108,TRUE,1.5,flat,3,normal\n\
         ,,,,,,,,,,,,\n\
         Male,50,martian,,,,,,,,,,\n",
    )
    .unwrap();
    let rows = rows.to_string_lossy().into_owned();
    let out = csrl(&["predict", "--model", &model, "--data", &rows]);
    assert!(out.status.success(), "{}", stderr(&out));
    let new = String::from_utf8(out.stdout.clone()).unwrap();
    let tail = |l: &str| l.split_once(',').unwrap().1.to_string();
    let new_lines: Vec<&str> = new.lines().collect();
    assert_eq!(new_lines.len(), 5, "{new}");
    assert_eq!(tail(new_lines[1]), tail(lines[1]));
    assert_eq!(tail(new_lines[2]), tail(lines[2]));
    assert!(
        stderr(&out).contains("classified 4 rows") && stderr(&out).contains("(eg2, "),
        "{}",
        stderr(&out)
    );
}

#[test]
fn predict_refuses_broken_trees_naming_the_file() {
    let s = Scratch::new();
    let model = s.path("m.json");
    let out = s.classify("c45", "prices.expense", &["--folds", "3", "--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    let good = std::fs::read_to_string(&model).unwrap();
    let data = s.path("data.csv");
    let predict = |text: &str, data: &str| {
        let path = s.file("broken.json", text);
        csrl(&["predict", "--model", &path, "--data", data])
    };
    refused(
        &predict(&good.replace("\"version\":1", "\"version\":2"), &data),
        &["broken.json", "version 2 is not supported"],
    );
    refused(
        &predict(
            &good.replace("\"learner\":", "\"colour\":1,\"learner\":"),
            &data,
        ),
        &["broken.json", "unknown field `colour`"],
    );
    refused(
        &predict(&good.replace("\"nodes\":", "\"depth\":3,\"nodes\":"), &data),
        &[
            "broken.json",
            "key `tree.depth`",
            "not a key of a saved tree",
        ],
    );
    refused(
        &predict(
            &good.replace("\"format\":\"csrl-cost-tree\"", "\"format\":\"zip\""),
            &data,
        ),
        &["broken.json", "`zip` is not a model format"],
    );
    refused(
        &predict(
            &good.replace("\"learner\":\"c45\"", "\"learner\":\"c5\""),
            &data,
        ),
        &["broken.json", "key `learner`"],
    );
    refused(
        &predict(&good.replace("\"full\":10.0", "\"full\":-10.0"), &data),
        &["broken.json", "key `prices`", "-10"],
    );
    let few = s.file("few.csv", "b,t\nx,p\n");
    refused(
        &predict(&good, &few),
        &["few.csv", "no column `a`, which the model reads"],
    );
    let words = s.file("words.csv", "a,b\nten,x\n");
    refused(
        &predict(&good, &words),
        &["words.csv", "line 2", "`ten` in column `a` is not a number"],
    );
}

#[test]
fn a_tree_whose_child_does_not_follow_its_parent_is_refused() {
    let s = Scratch::new();
    let model = s.path("m.json");
    let out = s.classify(
        "dtmc",
        "prices.expense",
        &["--mc", "100", "--folds", "3", "--save", &model],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&model).unwrap()).unwrap();
    let nodes = v["tree"]["nodes"].as_array_mut().unwrap();
    let split = nodes
        .iter_mut()
        .find_map(|n| n["split"].as_object_mut())
        .expect("the scratch data is split");
    let (_, inner) = split.iter_mut().next().unwrap();
    inner["children"][0] = serde_json::json!(0);
    let broken = s.file("loop.json", &v.to_string());
    let out = csrl(&["predict", "--model", &broken, "--data", &s.path("data.csv")]);
    refused(&out, &["loop.json", "tree node", "child 0"]);
}

#[test]
fn broken_price_and_cost_files_are_refused_naming_file_and_line() {
    let s = Scratch::new();
    s.file("unknown.expense", "a: 10, 2\nbogus: 8, 3\nb: 1\n");
    refused(
        &s.classify("eg2", "unknown.expense", &[]),
        &[
            "unknown.expense",
            "line 2",
            "`bogus` is not a column of the data",
            "--cost-name",
        ],
    );
    s.file("nodiscount.expense", "a: 10, 2\nb: 8\n");
    let out = s.classify(
        "eg2",
        "nodiscount.expense",
        &["--groups", &s.path("prices.group")],
    );
    refused(
        &out,
        &[
            "prices.group",
            "line 3",
            "`b` is in group `G`",
            "no discount price",
        ],
    );
    s.file("negative.expense", "a: 10, 2\nb: -8, 3\n");
    refused(
        &s.classify("eg2", "negative.expense", &[]),
        &["negative.expense", "line 2", "`-8`", "non-negative"],
    );
    s.file("nan.cost", "a: NaN\nb: 3\n");
    refused(
        &s.classify("eg2", "nan.cost", &[]),
        &["nan.cost", "line 1", "`NaN`"],
    );
    s.file("short.expense", "a: 10, 2\n");
    refused(
        &s.classify("eg2", "short.expense", &[]),
        &["short.expense", "no price for column `b`"],
    );
    s.file("unknown.csv", "feature,cost\na,1\nbogus,2\nb,3\n");
    refused(
        &s.classify("c45", "unknown.csv", &[]),
        &[
            "unknown.csv",
            "line 3",
            "`bogus`",
            "not a column of the data",
        ],
    );
    s.file("nan.csv", "feature,cost\na,1\nb,NaN\n");
    refused(
        &s.classify("c45", "nan.csv", &[]),
        &["nan.csv", "line 3", "`NaN`"],
    );
    let (small, negative, unknown) = (
        s.file("mc-small.csv", "actual,n\nn,0\n"),
        s.file("mc-negative.csv", "actual,n,p\nn,0,1\np,-5,0\n"),
        s.file("mc-unknown.csv", "actual,n,q\nn,0,1\nq,5,0\n"),
    );
    refused(
        &s.classify("dtmc", "prices.expense", &["--mc-matrix", &small]),
        &["mc-small.csv", "line 1", "1 class columns", "2 classes"],
    );
    refused(
        &s.classify("dtmc", "prices.expense", &["--mc-matrix", &negative]),
        &["mc-negative.csv", "line 3", "`-5`"],
    );
    refused(
        &s.classify("dtmc", "prices.expense", &["--mc-matrix", &unknown]),
        &["mc-unknown.csv", "line 1", "`q` is not a class"],
    );
    refused(
        &s.classify("dtmc", "prices.expense", &["--mc", "-1"]),
        &["--mc -1", "not negative"],
    );
    refused(
        &s.classify("dtmc", "prices.expense", &["--mc", "NaN"]),
        &["--mc NaN"],
    );
}

#[test]
fn groups_need_discount_prices() {
    let s = Scratch::new();
    s.file("costs.csv", "feature,cost\na,10\nb,8\n");
    s.file("prices.cost", "a: 10\nb: 8\n");
    for costs in ["costs.csv", "prices.cost"] {
        refused(
            &s.classify("eg2", costs, &["--groups", &s.path("prices.group")]),
            &["--groups", "needs discount prices", costs],
        );
    }
}

#[test]
fn a_class_missing_from_a_training_part_is_refused() {
    let s = Scratch::new();
    let data = s.file("lonely.csv", "a,t\n1,n\n2,n\n3,n\n4,p\n5,n\n6,n\n");
    s.file("costs.csv", "feature,cost\na,1\n");
    let costs = s.path("costs.csv");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "classify",
            "--data",
            &data,
            "--costs",
            &costs,
            "--target",
            "t",
            "--learner",
            "eg2",
        ];
        args.extend_from_slice(extra);
        csrl(&args)
    };
    refused(
        &run(&["--folds", "3"]),
        &[
            "lonely.csv",
            "the training part of fold",
            "class `p`",
            "1 in the data",
        ],
    );
    // A rule that every object satisfies leaves the other class empty.
    let positive = s.file("positive.csv", "a,t\n1,1\n2,2\n3,3\n");
    let out = csrl(&[
        "classify",
        "--data",
        &positive,
        "--costs",
        &costs,
        "--target",
        "t",
        "--positive-if",
        ">0",
        "--learner",
        "eg2",
        "--holdout",
        "0.5",
    ]);
    refused(
        &out,
        &[
            "positive.csv",
            "the training part has no object of class `no` (0 in the data)",
        ],
    );
    refused(
        &run(&["--folds", "7"]),
        &["--folds must be between 2 and the number of objects (6), found 7"],
    );
}

#[test]
fn one_object_or_too_few_for_the_default_folds_are_refused_saying_what_to_give() {
    let s = Scratch::new();
    s.file("costs.csv", "feature,cost\na,1\n");
    let costs = s.path("costs.csv");
    let run = |data: &str, learner: &str, extra: &[&str]| {
        let mut args = vec![
            "classify",
            "--data",
            data,
            "--costs",
            &costs,
            "--target",
            "t",
            "--learner",
            learner,
        ];
        args.extend_from_slice(extra);
        csrl(&args)
    };
    let one = s.file("one.csv", "a,t\n1,n\n");
    for extra in [&[][..], &["--holdout", "0.5"], &["--folds", "2"]] {
        refused(
            &run(&one, "eg2", extra),
            &[
                "one.csv: one object",
                "cannot be both learned from and held out",
            ],
        );
    }
    // Seven objects, no --folds: the default ten folds would leave some empty.
    let seven = s.file("seven.csv", "a,t\n1,n\n2,n\n3,n\n4,p\n5,p\n6,p\n7,c\n");
    refused(
        &run(&seven, "eg2", &[]),
        &[
            "seven.csv: 7 objects, too few for the default 10-fold cross-validation",
            "give --folds K, 2 to 7, or --holdout F",
        ],
    );
    // Held out, the class of one object stays in training: it runs, and CVT, whose own
    // folds cannot all see it, says so.
    let out = run(&seven, "cvt", &["--holdout", "0.3", "--cvt-folds", "2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains(
            "warning: the training part has one object of class `c`: CVT's inner fold that \
             holds it out learns without the class"
        ),
        "{}",
        stderr(&out)
    );
    let out = run(&seven, "eg2", &["--holdout", "0.3"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

#[test]
fn flags_the_learner_does_not_read_are_refused() {
    let s = Scratch::new();
    s.file("costs.csv", "feature,cost\na,10\nb,8\n");
    let group = s.path("prices.group");
    for (learner, extra, expected) in [
        (
            "cs-id3",
            vec!["--mc", "5"],
            "--mc is read by the test-cost family only",
        ),
        (
            "id3",
            vec!["--groups", &group],
            "--groups is read by the test-cost family only",
        ),
        (
            "cs-ibl",
            vec!["--mc-matrix", &group],
            "--mc-matrix is read by the test-cost family only",
        ),
        (
            "cs-id3",
            vec!["--cost-name", "a=b"],
            "--cost-name is read by the test-cost family only",
        ),
        (
            "eg2",
            vec!["--tolerance", "2"],
            "--tolerance is read by --learner cs-ibl only",
        ),
        (
            "c45",
            vec!["--dot", "t.dot"],
            "--dot draws CS-ID3's decision tree",
        ),
    ] {
        let out = s.classify(learner, "costs.csv", &extra);
        refused(&out, &[expected, &format!("--learner {learner}")]);
    }
    refused(
        &s.classify("cs-id3", "prices.expense", &[]),
        &["prices.expense is in Turney's format", "--learner cs-id3"],
    );
    let both = s.classify(
        "eg2",
        "costs.csv",
        &["--mc", "5", "--mc-matrix", &s.path("costs.csv")],
    );
    assert_eq!(both.status.code(), Some(2), "{}", stderr(&both));
    refused(
        &s.classify("eg2", "costs.csv", &["--cost-name", "a"]),
        &["--cost-name a: give COLUMN=NAME"],
    );
    refused(
        &s.classify("eg2", "costs.csv", &["--cost-name", "z=a"]),
        &["`z` is not a feature column", "data.csv"],
    );
    refused(
        &s.classify("eg2", "costs.csv", &["--cost-name", "b=a"]),
        &["columns `a` and `b` would both be called `a`"],
    );
}

#[test]
fn save_never_overwrites_an_input() {
    let s = Scratch::new();
    let mc = s.file("mc.csv", "actual,n,p\nn,0,1\np,5,0\n");
    let inputs = [
        ("--data", s.path("data.csv")),
        ("--costs", s.path("prices.expense")),
        ("--groups", s.path("prices.group")),
        ("--mc-matrix", mc.clone()),
    ];
    for (flag, path) in &inputs {
        let before = std::fs::read(path).unwrap();
        let out = s.classify(
            "eg2",
            "prices.expense",
            &[
                "--groups",
                &s.path("prices.group"),
                "--mc-matrix",
                &mc,
                "--save",
                path,
            ],
        );
        refused(&out, &["--save", &format!("names the {flag} file")]);
        assert_eq!(std::fs::read(path).unwrap(), before);
    }
    // The incremental learners too.
    s.file("costs.csv", "feature,cost\na,10\nb,8\n");
    let data = s.path("data.csv");
    let before = std::fs::read(&data).unwrap();
    refused(
        &s.classify("cs-id3", "costs.csv", &["--save", &data]),
        &["--save", "names the --data file"],
    );
    assert_eq!(std::fs::read(&data).unwrap(), before);
    // Turney's `.delay` file, read from beside the prices without a flag, too.
    let delays = s.file("prices.delay", "a: immediate.\nb: delayed.\n");
    let before = std::fs::read(&delays).unwrap();
    refused(
        &s.classify("eg2", "prices.expense", &["--save", &delays]),
        &["--save", "names the `.delay` (read beside --costs) file"],
    );
    assert_eq!(std::fs::read(&delays).unwrap(), before);
}

#[test]
fn counts_beyond_what_the_data_allows_are_refused_before_anything_is_allocated() {
    // 10^10 folds once asked for 240 GB, u64::MAX overflowed a capacity.
    let s = Scratch::new();
    for folds in ["10000000000", "18446744073709551615", "25"] {
        refused(
            &s.classify("cvt", "prices.expense", &["--cvt-folds", folds]),
            &[
                "--learner cvt",
                &format!("{folds} folds for CVT"),
                "training objects",
            ],
        );
    }
    let out = s.classify("cvt", "prices.expense", &["--cvt-folds", "3"]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn a_target_with_more_classes_than_the_limit_is_refused_with_how_to_raise_it() {
    // A numeric column given as the target: once a 20 GB cost matrix.
    let s = Scratch::new();
    let mut data = String::from("a,b,t\n");
    for i in 0..1500 {
        data.push_str(&format!("{},x,{i}\n", i % 7));
    }
    s.file("data.csv", &data);
    refused(
        &s.classify("eg2", "prices.expense", &[]),
        &[
            "class column `t`",
            "1500 distinct values",
            "at most 1000",
            "--max-classes N",
        ],
    );
    // Raised, or binarised, it is read.
    let out = s.classify(
        "eg2",
        "prices.expense",
        &["--max-classes", "5", "--positive-if", ">700"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    refused(
        &s.classify("eg2", "prices.expense", &["--max-classes", "1499"]),
        &["1500 distinct values", "at most 1499"],
    );
}

#[test]
fn a_target_of_100000_values_with_the_limit_raised_is_refused_before_anything_is_learned() {
    // A numeric column given as the target, --max-classes raised to take it: its uniform
    // cost matrix, once 80 GB, is one number, and what cannot be learned is refused.
    let s = Scratch::new();
    let target = |modulus: usize| {
        let mut data = String::from("a,b,t\n");
        for i in 0..100_000 {
            data.push_str(&format!("{},x,{}\n", i % 7, i % modulus));
        }
        s.file("data.csv", &data);
    };
    // Every value once: no class can be learned and held out.
    target(100_000);
    refused(
        &s.classify("eg2", "prices.expense", &["--max-classes", "100000"]),
        &[
            "data.csv",
            "class `0` (1 in the data)",
            "a class of one object",
        ],
    );
    // Every value twice, one of each held out: a tree would keep a weight per class at
    // each of up to 50,000 nodes.
    target(50_000);
    refused(
        &s.classify(
            "eg2",
            "prices.expense",
            &["--max-classes", "100000", "--holdout", "0.5"],
        ),
        &[
            "--learner eg2",
            "50000 classes over 50000 training objects",
            "more than the 134217728 a fit may hold",
        ],
    );
}

#[test]
fn a_table_too_wide_for_the_lookahead_is_refused_naming_the_flag_that_raises_the_limit() {
    // 50 objects of 10,000 numeric columns: CVT once ran past three minutes (its
    // lookahead grower would take hours).
    let s = Scratch::new();
    let columns = 10_000;
    let mut data: String = (0..columns).map(|j| format!("x{j},")).collect();
    data.push_str("t\n");
    let mut prices = String::from("feature,cost\n");
    for j in 0..columns {
        prices.push_str(&format!("x{j},{}\n", 1 + j % 9));
    }
    for i in 0..50 {
        data.extend((0..columns).map(|j| format!("{},", (i * 7 + j * 13) % 101)));
        data.push_str(if i % 2 == 0 { "p\n" } else { "n\n" });
    }
    let (data, prices) = (s.file("wide.csv", &data), s.file("wide.costs.csv", &prices));
    let wide = |learner: &str, extra: &[&str]| {
        let mut args = vec![
            "classify",
            "--data",
            &data,
            "--costs",
            &prices,
            "--target",
            "t",
            "--learner",
            learner,
        ];
        args.extend_from_slice(extra);
        csrl(&args)
    };
    for (learner, what) in [
        ("cvt", "10000 features for CVT's lookahead grower"),
        ("act", "10000 features for ACT's lookahead"),
    ] {
        refused(
            &wide(learner, &[]),
            &[
                &format!("--learner {learner}"),
                what,
                "at most 1000",
                "--max-lookahead-features N raises the limit",
            ],
        );
    }
    // ACT without samples looks one step ahead, in time linear in the features.
    let out = wide("act", &["--act-samples", "0", "--holdout", "0.5"]);
    assert!(out.status.success(), "{}", stderr(&out));
    // The limit is the flag's, for ACT and CVT only.
    refused(
        &s.classify("cvt", "prices.expense", &["--max-lookahead-features", "1"]),
        &["2 features for CVT's lookahead grower: at most 1"],
    );
    let out = s.classify("cvt", "prices.expense", &["--max-lookahead-features", "2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    refused(
        &s.classify("eg2", "prices.expense", &["--max-lookahead-features", "2"]),
        &["--max-lookahead-features is read by --learner act and cvt only"],
    );
}

#[test]
fn predict_never_overwrites_its_model_or_its_data() {
    let s = Scratch::new();
    let model = s.path("model.json");
    let out = s.classify("eg2", "prices.expense", &["--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    let data = s.path("data.csv");
    for (flag, path) in [("--model", &model), ("--data", &data)] {
        let before = std::fs::read(path).unwrap();
        let out = csrl(&["predict", "--model", &model, "--data", &data, "--out", path]);
        refused(&out, &["--out", &format!("names the {flag} file")]);
        assert_eq!(std::fs::read(path).unwrap(), before, "{flag}");
    }
    // What is not a regular file (a FIFO would block for ever) is refused.
    #[cfg(unix)]
    {
        let fifo = s.path("fifo");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let out = csrl(&[
            "predict", "--model", &model, "--data", &data, "--out", &fifo,
        ]);
        refused(&out, &["--out", "is not a regular file"]);
    }
    // A name of its own is written.
    let out_path = s.path("out.csv");
    let out = csrl(&[
        "predict", "--model", &model, "--data", &data, "--out", &out_path,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        std::fs::read_to_string(&out_path)
            .unwrap()
            .starts_with("line,class")
    );
}

#[test]
fn turneys_delays_beside_the_prices_are_reported_never_priced() {
    let json = heart_json("dtmc", &["--mc", "500"]);
    let delayed: Vec<&str> = json["delayed_tests"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_str().unwrap())
        .collect();
    // heart-disease.delay: the first four tests are immediate, the other nine delayed.
    assert_eq!(
        delayed,
        [
            "chol", "fbs", "restecg", "thalch", "exang", "oldpeak", "slope", "ca", "thal"
        ]
    );
    let waiting = json["objects_waiting_for_a_delayed_test"].as_u64().unwrap();
    assert!(waiting <= json["test_objects"].as_u64().unwrap());
    let text = on_heart("dtmc", &["--mc", "500"]);
    assert!(String::from_utf8_lossy(&text.stdout).contains("waited for a delayed test"));
    // Delays are never priced: the same prices without their .delay file cost the same.
    let dir = tempfile::tempdir().unwrap();
    for ext in ["expense", "group"] {
        let from = repo(&format!("data/uci/heart-disease/costs/heart-disease.{ext}"));
        std::fs::copy(from, dir.path().join(format!("heart.{ext}"))).unwrap();
    }
    let (data, costs, groups) = (
        repo("data/heart-disease/cleveland.csv"),
        dir.path().join("heart.expense").display().to_string(),
        dir.path().join("heart.group").display().to_string(),
    );
    let out = csrl(&[
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
        "dtmc",
        "--mc",
        "500",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let plain: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(plain["delayed_tests"].as_array().unwrap().len(), 0);
    assert_eq!(
        f(&plain, "test_cost_per_object"),
        f(&json, "test_cost_per_object")
    );
    assert_eq!(
        f(&plain, "total_cost_per_object"),
        f(&json, "total_cost_per_object")
    );
}

/// The probabilities of a row: its class name's column to the value.
fn probabilities_of(v: &serde_json::Value) -> Vec<(String, f64)> {
    v.as_object()
        .unwrap_or_else(|| panic!("not an object: {v}"))
        .iter()
        .map(|(k, p)| (k.clone(), p.as_f64().unwrap()))
        .collect()
}

#[test]
fn classify_json_gives_every_test_object_its_class_probabilities() {
    // Three classes, a missing value in a tenth of the objects, so some go down several
    // branches.
    let dir = tempfile::tempdir().unwrap();
    let mut data = String::from("a,b,t\n");
    for i in 0..60 {
        let a = if i % 10 == 3 {
            "?".to_string()
        } else {
            (i % 7).to_string()
        };
        let t = ["lo", "mid", "hi"][(i % 7) % 3];
        data.push_str(&format!("{a},{},{t}\n", ["x", "y"][i % 2]));
    }
    let path = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    std::fs::write(path("d.csv"), data).unwrap();
    std::fs::write(path("c.csv"), "feature,cost\na,3\nb,1\n").unwrap();
    for learner in ["c45", "eg2", "dtmc"] {
        let (d, c) = (path("d.csv"), path("c.csv"));
        let args = [
            "classify",
            "--data",
            &d,
            "--costs",
            &c,
            "--target",
            "t",
            "--learner",
            learner,
            "--folds",
            "4",
            "--mc",
            "50",
            "--json",
        ];
        let v = common::json(&args);
        let objects = v["predictions"].as_array().expect("a predictions array");
        assert_eq!(objects.len(), 60, "{learner}: every object tested once");
        let mut errors = 0;
        for (i, o) in objects.iter().enumerate() {
            assert_eq!(o["object"].as_u64(), Some(i as u64), "{o}");
            let p = probabilities_of(&o["probabilities"]);
            let mut names: Vec<&str> = p.iter().map(|(n, _)| n.as_str()).collect();
            names.sort_unstable();
            assert_eq!(names, ["hi", "lo", "mid"], "{o}");
            let sum: f64 = p.iter().map(|(_, x)| x).sum();
            assert!((sum - 1.0).abs() < 1e-12, "{o}");
            assert!(p.iter().all(|(_, x)| *x > 0.0 && *x < 1.0), "{o}");
            // Uniform costs: the answer is a class of largest probability.
            let answer = o["class"].as_str().unwrap();
            let largest = p.iter().map(|(_, x)| *x).fold(0.0, f64::max);
            let mine = p.iter().find(|(n, _)| n == answer).unwrap().1;
            assert!(mine >= largest - 1e-9, "{learner}: {o}");
            errors += usize::from(o["actual"] != o["class"]);
        }
        assert_eq!(errors as u64, v["errors"].as_u64().unwrap(), "{learner}");
    }
}

#[test]
fn predict_writes_the_probabilities_a_saved_tree_gives() {
    let s = Scratch::new();
    let model = s.path("m.json");
    let out = s.classify("eg2", "prices.expense", &["--folds", "3", "--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = s.file("rows.csv", "a,b\n0,x\n1,y\n?,?\n5,z\n");
    let plain = common::ok(&["predict", "--model", &model, "--data", &rows]);
    let with = common::ok(&[
        "predict",
        "--model",
        &model,
        "--data",
        &rows,
        "--probabilities",
    ]);
    let lines: Vec<&str> = with.lines().collect();
    // The class names of the scratch data, in the model's order (as they first come).
    assert_eq!(lines[0], "line,class,cost,measured,p_p,p_n");
    assert_eq!(lines.len(), 5, "{with}");
    let mut unequal = 0;
    for (line, before) in lines[1..].iter().zip(plain.lines().skip(1)) {
        // The same row as without the flag, probabilities after it.
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells[..4].join(","), before);
        let p: Vec<f64> = cells[4..].iter().map(|c| c.parse().unwrap()).collect();
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{line}");
        // The default mc is uniform: the answer is the more probable class.
        let answer = if p[0] > p[1] { "p" } else { "n" };
        assert!(p[0] == p[1] || cells[1] == answer, "{line}");
        unequal += usize::from(p[0] != p[1]);
    }
    assert!(unequal > 0, "{with}");
}

#[test]
fn predict_writes_the_probabilities_of_an_incremental_model_too() {
    let s = Scratch::new();
    let model = s.path("m.json");
    s.file("costs.csv", "feature,cost\na,10\nb,8\n");
    let out = s.classify("cs-id3", "costs.csv", &["--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = s.file("rows.csv", "a,b\n0,x\n1,y\n");
    let with = common::ok(&[
        "predict",
        "--model",
        &model,
        "--data",
        &rows,
        "--probabilities",
    ]);
    let lines: Vec<&str> = with.lines().collect();
    // This model's classes are in sorted order.
    assert_eq!(lines[0], "line,class,cost,measured,p_n,p_p", "{with}");
    for line in &lines[1..] {
        let cells: Vec<&str> = line.split(',').collect();
        let p: Vec<f64> = cells[4..].iter().map(|c| c.parse().unwrap()).collect();
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{line}");
        // The majority of the examples it went by, ties to the first class.
        let answer = if p[0] >= p[1] { "n" } else { "p" };
        assert_eq!(cells[1], answer, "{line}");
    }
}

/// `predict --explain LINE` gives one row's account: each test bought, in order, with its
/// price, node and probabilities, and for VOI what it was expected to save; its tests
/// and answer are the table's for that row. A row that is not in the file, a classifier
/// of the incremental learners and an output file are refused.
#[test]
fn predict_explains_one_row_test_by_test() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("voi.json").to_string_lossy().into_owned();
    let out = on_heart("voi", &["--mc", "500", "--save", &model]);
    assert!(out.status.success(), "{}", stderr(&out));
    let data = repo("data/heart-disease/cleveland.csv");
    let table = csrl(&["predict", "--model", &model, "--data", &data]);
    assert!(table.status.success(), "{}", stderr(&table));
    let table = String::from_utf8(table.stdout).unwrap();
    for line in ["2", "3", "40"] {
        let out = csrl(&[
            "predict",
            "--model",
            &model,
            "--data",
            &data,
            "--explain",
            line,
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let text = String::from_utf8(out.stdout).unwrap();
        let row: Vec<&str> = table
            .lines()
            .find(|l| l.starts_with(&format!("{line},")))
            .unwrap()
            .split(',')
            .collect();
        let tests: Vec<&str> = row[3].split(';').filter(|t| !t.is_empty()).collect();
        let steps: Vec<&str> = text.lines().filter(|l| l.contains(". ")).collect();
        assert_eq!(steps.len(), tests.len(), "{text}");
        for (i, (step, test)) in steps.iter().zip(&tests).enumerate() {
            assert!(
                step.starts_with(&format!("{}. {test}: paid ", i + 1)),
                "{text}"
            );
            assert!(step.contains("expected to save"), "{text}");
        }
        assert!(
            text.contains(&format!("answer {} (tests {} in all)", row[1], row[2])),
            "{text}"
        );
    }
    let refused = csrl(&[
        "predict",
        "--model",
        &model,
        "--data",
        &data,
        "--explain",
        "999",
    ]);
    assert_eq!(refused.status.code(), Some(1));
    assert!(
        stderr(&refused)
            .contains("line 999: not a row of the table (its rows are on lines 2 to 305"),
        "{}",
        stderr(&refused)
    );
    let with_out = dir.path().join("x.csv").to_string_lossy().into_owned();
    let refused = csrl(&[
        "predict",
        "--model",
        &model,
        "--data",
        &data,
        "--explain",
        "2",
        "--out",
        &with_out,
    ]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("--explain prints one row's account"),
        "{}",
        stderr(&refused)
    );
    assert!(!std::path::Path::new(&with_out).exists());
    let classifier = dir.path().join("cs.json").to_string_lossy().into_owned();
    let costs = repo("data/heart-disease/costs.csv");
    let out = csrl(&[
        "classify",
        "--data",
        &data,
        "--costs",
        &costs,
        "--target",
        "num",
        "--positive-if",
        ">0",
        "--save",
        &classifier,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let refused = csrl(&[
        "predict",
        "--model",
        &classifier,
        "--data",
        &data,
        "--explain",
        "2",
    ]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("--explain is read with a tree"),
        "{}",
        stderr(&refused)
    );
}
