//! `csrl classify`, run as a user runs it: on the shipped heart-disease data and on broken
//! files.

mod common;

use common::{csrl, stderr};

use std::path::PathBuf;
use std::process::Output;

fn heart(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/heart-disease")
        .join(name);
    path.to_string_lossy().into_owned()
}

/// Write `text` to a file of its own in a scratch directory for this test process.
fn scratch(name: &str, bytes: &[u8]) -> String {
    let dir = std::env::temp_dir().join(format!("csrl-classify-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.to_string_lossy().into_owned()
}

/// `csrl classify` on the shipped heart data with target `num`, plus `extra` arguments.
fn on_heart(extra: &[&str]) -> Output {
    let (data, costs) = (heart("cleveland.csv"), heart("costs.csv"));
    let mut args = vec![
        "classify", "--data", &data, "--costs", &costs, "--target", "num",
    ];
    args.extend_from_slice(extra);
    csrl(&args)
}

fn classify_heart(learner: &str, seed: &str) -> serde_json::Value {
    let out = on_heart(&[
        "--positive-if",
        ">0",
        "--learner",
        learner,
        "--seed",
        seed,
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn heart_json_has_the_documented_fields() {
    let v = classify_heart("cs-id3", "1");
    assert_eq!(v["objects"], 304);
    let errors = v["errors"].as_u64().unwrap();
    let accuracy = v["accuracy"].as_f64().unwrap();
    assert!((accuracy - (304 - errors) as f64 / 304.0).abs() < 1e-12);
    let total = v["total_cost"].as_f64().unwrap();
    let mean = v["mean_cost"].as_f64().unwrap();
    assert!((mean - total / 304.0).abs() < 1e-9);
    assert!((v["full_cost"].as_f64().unwrap() - 600.57).abs() < 1e-9);
}

#[test]
fn cs_id3_spends_far_less_than_cost_blind_id3_at_comparable_accuracy() {
    for seed in ["1", "2", "3"] {
        let cs = classify_heart("cs-id3", seed);
        let blind = classify_heart("id3", seed);
        let (cs_cost, blind_cost) = (
            cs["mean_cost"].as_f64().unwrap(),
            blind["mean_cost"].as_f64().unwrap(),
        );
        assert!(
            cs_cost * 5.0 < blind_cost,
            "seed {seed}: {cs_cost} vs {blind_cost}"
        );
        assert!(blind_cost * 2.0 < 600.57, "seed {seed}: {blind_cost}");
        let (a, b) = (
            cs["accuracy"].as_f64().unwrap(),
            blind["accuracy"].as_f64().unwrap(),
        );
        assert!((a - b).abs() < 0.1, "seed {seed}: accuracy {a} vs {b}");
        assert!(a > 0.55, "seed {seed}: accuracy {a}");
    }
}

#[test]
fn json_is_the_same_for_the_same_seed_and_changes_with_it() {
    for learner in ["cs-id3", "cs-ibl", "id3"] {
        assert_eq!(classify_heart(learner, "5"), classify_heart(learner, "5"));
    }
    assert_ne!(
        classify_heart("id3", "5")["total_cost"],
        classify_heart("id3", "6")["total_cost"]
    );
}

#[test]
fn text_output_names_every_figure() {
    let out = on_heart(&["--positive-if", "!=0", "--learner", "cs-ibl"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    for word in [
        "objects",
        "errors",
        "accuracy",
        "total cost",
        "mean cost",
        "full cost   600.57",
    ] {
        assert!(text.contains(word), "`{word}` missing in {text}");
    }
}

/// Run on broken input: it must fail with exit 1 (not a panic's 101) and say why.
fn fails_with(data: &str, costs: &str, extra: &[&str], expected: &[&str]) {
    let mut args = vec![
        "classify",
        "--data",
        data,
        "--costs",
        costs,
        "--learner",
        "cs-id3",
    ];
    if !extra.contains(&"--target") {
        args.extend(["--target", "t"]);
    }
    args.extend(extra);
    let out = csrl(&args);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
    let message = stderr(&out);
    for part in expected {
        assert!(message.contains(part), "`{part}` missing in: {message}");
    }
    assert!(!message.contains("panicked"), "{message}");
}

#[test]
fn broken_files_give_clear_errors() {
    let costs = scratch("costs.csv", b"feature,cost\na,1\nb,2\n");
    let good = scratch("good.csv", b"a,b,t\n1,x,0\n2,y,1\n");

    let ragged = scratch("ragged.csv", b"a,b,t\n1,x,0\n2,y\n");
    fails_with(
        &ragged,
        &costs,
        &[],
        &["ragged.csv", "line 3", "2 fields", "header has 3"],
    );

    let not_utf8 = scratch("latin1.csv", b"a,b,t\n1,caf\xe9,0\n");
    fails_with(
        &not_utf8,
        &costs,
        &[],
        &["latin1.csv", "line 2", "not UTF-8"],
    );

    let empty = scratch("empty.csv", b"");
    fails_with(&empty, &costs, &[], &["empty.csv", "empty"]);

    fails_with(
        &good,
        &costs,
        &["--target", "nope"],
        &["no target column `nope`", "a, b, t"],
    );

    let missing_cost = scratch("costs-missing.csv", b"feature,cost\na,1\n");
    fails_with(
        &good,
        &missing_cost,
        &[],
        &["costs-missing.csv", "no cost for column `b`"],
    );

    let negative = scratch("costs-negative.csv", b"feature,cost\na,1\nb,-2\n");
    fails_with(
        &good,
        &negative,
        &[],
        &["costs-negative.csv", "line 3", "`b`", "-2", "non-negative"],
    );

    let header = scratch("costs-header.csv", b"name,price\na,1\nb,2\n");
    fails_with(&good, &header, &[], &["feature,cost"]);

    fails_with(
        &good,
        &costs,
        &["--positive-if", ">x"],
        &["positive-if", "needs a number"],
    );

    let text_target = scratch("text-target.csv", b"a,b,t\n1,x,yes\n");
    fails_with(
        &text_target,
        &costs,
        &["--positive-if", ">0"],
        &["line 2", "`yes` is not a number"],
    );

    let no_such = scratch("dir-marker", b"");
    let missing = format!("{no_such}-does-not-exist.csv");
    fails_with(
        &missing,
        &costs,
        &[],
        &["does-not-exist.csv", "cannot read"],
    );
}

/// Without `--learner`, `classify` runs CS-ID3, and says so.
#[test]
fn the_learner_is_cs_id3_unless_another_is_named() {
    let out = on_heart(&["--positive-if", ">0", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let default: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(default["learner"], "cs-id3");
    assert_eq!(default, classify_heart("cs-id3", "1"));
    let help = csrl(&["classify", "--help"]);
    assert!(String::from_utf8_lossy(&help.stdout).contains("[default: cs-id3]"));
}

#[test]
fn an_unknown_learner_is_a_usage_error() {
    let out = csrl(&[
        "classify",
        "--data",
        "d.csv",
        "--costs",
        "c.csv",
        "--target",
        "t",
        "--learner",
        "c4.5",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("cs-id3"));
}

#[test]
fn held_out_evaluation_is_reported_beside_the_prequential_one() {
    let run = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec!["--positive-if", ">0", "--learner", "cs-id3", "--json"];
        args.extend_from_slice(extra);
        let out = on_heart(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let plain = run(&[]);
    assert_eq!(plain["evaluation"], "prequential");
    assert!(plain.get("held_out").is_none());
    let folds = run(&["--folds", "5"]);
    // The prequential pass is the same with or without a held-out evaluation.
    assert_eq!(folds["accuracy"], plain["accuracy"]);
    let h = &folds["held_out"];
    assert_eq!(h["scheme"], "5-fold");
    assert_eq!(h["test_objects"], plain["objects"]);
    let acc = h["accuracy"].as_f64().unwrap();
    assert!((0.5..=1.0).contains(&acc), "{acc}");
    // CS-ID3 classifies for a few units per object; the cost-blind tree for far more.
    let (cs, tree) = (
        h["mean_cost"].as_f64().unwrap(),
        h["cost_blind_tree_mean_cost"].as_f64().unwrap(),
    );
    assert!(cs * 10.0 < tree, "{cs} against {tree}");
    assert_eq!(run(&["--folds", "5"]), folds);
    let split = run(&["--holdout", "0.25"]);
    assert_eq!(split["held_out"]["test_objects"], 76);
    for bad in [["--holdout", "1.5"], ["--folds", "1"]] {
        let mut args = vec!["--learner", "cs-id3"];
        args.extend_from_slice(&bad);
        let out = on_heart(&args);
        assert_eq!(out.status.code(), Some(1), "{bad:?}");
        assert!(stderr(&out).contains(bad[0]), "{}", stderr(&out));
    }
}

#[test]
fn a_held_out_share_of_one_object_is_a_clear_error_not_a_panic() {
    let costs = scratch("costs-one.csv", b"feature,cost\na,1\n");
    let one = scratch("one-row.csv", b"a,t\n1,x\n");
    for share in ["0.5", "0.001", "0.999"] {
        fails_with(
            &one,
            &costs,
            &["--holdout", share],
            &["--holdout needs at least 2 objects", "found 1"],
        );
    }
}

#[test]
fn a_positive_if_rule_that_matches_no_value_is_refused_naming_the_values() {
    let costs = scratch("costs-sex.csv", b"feature,cost\na,1\n");
    let sex = scratch("sex.csv", b"a,t\n1,Male\n2,Female\n3,Male\n");
    for (rule, shown) in [("cow", "==cow"), ("male", "==male")] {
        fails_with(
            &sex,
            &costs,
            &["--positive-if", rule],
            &[
                "sex.csv",
                "matches no value",
                shown,
                "Female, Male",
                "2 values",
            ],
        );
    }
    let numbers = scratch("numbers.csv", b"a,t\n1,0\n2,1\n3,2\n");
    fails_with(
        &numbers,
        &costs,
        &["--positive-if", ">5"],
        &[
            "numbers.csv",
            "matches no value",
            ">5",
            "0, 1, 2",
            "3 values",
        ],
    );
    // Many values: a few are named, and the count says how many there are.
    let mut many = b"a,t\n".to_vec();
    for i in 0..50 {
        many.extend(format!("{i},v{i:02}\n").as_bytes());
    }
    let many = scratch("many.csv", &many);
    fails_with(
        &many,
        &costs,
        &["--positive-if", "cow"],
        &["v00, v01", "50 values"],
    );
    // A rule that matches some value still runs.
    let out = csrl(&[
        "classify",
        "--data",
        &sex,
        "--costs",
        &costs,
        "--target",
        "t",
        "--learner",
        "cs-id3",
        "--positive-if",
        "Male",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn costs_whose_totals_cannot_be_represented_are_refused_up_front() {
    let data = scratch("big-data.csv", b"a,b,t\n1,x,0\n2,y,1\n3,x,0\n4,y,1\n");
    let huge = scratch("costs-huge.csv", b"feature,cost\na,1e308\nb,1e308\n");
    fails_with(
        &data,
        &huge,
        &["--folds", "2"],
        &["costs-huge.csv", "cannot be represented", "4 objects"],
    );
    // Each price and their sum per object are finite, but not the total over the objects.
    let large = scratch("costs-large.csv", b"feature,cost\na,1e307\nb,1e307\n");
    fails_with(
        &data,
        &large,
        &[],
        &["costs-large.csv", "cannot be represented"],
    );
    // Large but representable prices still run, and every figure stays finite.
    let fine = scratch("costs-fine.csv", b"feature,cost\na,1e290\nb,1e290\n");
    let out = csrl(&[
        "classify",
        "--data",
        &data,
        "--costs",
        &fine,
        "--target",
        "t",
        "--learner",
        "cs-id3",
        "--folds",
        "2",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["total_cost", "mean_cost", "full_cost"] {
        assert!(v[key].as_f64().is_some_and(f64::is_finite), "{key}: {v}");
    }
    for key in ["mean_cost", "cost_blind_tree_mean_cost"] {
        assert!(
            v["held_out"][key].as_f64().is_some_and(f64::is_finite),
            "{key}: {v}"
        );
    }
}

/// `--dot FILE` writes CS-ID3's decision tree as Graphviz DOT, with the data's feature
/// and class names; other learners are refused.
#[test]
fn dot_writes_the_cs_id3_tree() {
    let dir = tempfile::tempdir().unwrap();
    let dot = dir.path().join("tree.dot");
    let dot = dot.to_str().unwrap();
    let out = on_heart(&["--learner", "cs-id3", "--dot", dot]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(dot).unwrap();
    assert!(text.starts_with("digraph"), "{text}");
    assert!(text.contains("cost"), "{text}");
    assert!(stderr(&out).contains("tree.dot"), "{}", stderr(&out));
    let out = on_heart(&["--learner", "id3", "--dot", dot]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("--learner cs-id3"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_saved_model_predicts_new_rows_by_column_name() {
    let model = scratch("model.json", b"");
    let out = on_heart(&[
        "--positive-if",
        ">0",
        "--learner",
        "cs-id3",
        "--save",
        &model,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&model).unwrap();
    assert!(
        text.starts_with("{\"format\":\"csrl-classifier\",\"version\":1,"),
        "{text}"
    );
    // Three rows, columns in another order, no target.
    let rows = scratch(
        "new.csv",
        b"sex,age,cp,trestbps,chol,fbs,restecg,thalch,exang,oldpeak,slope,ca,thal\n\
          Male,63,typical angina,145,233,TRUE,lv hypertrophy,150,FALSE,2.3,downsloping,0,fixed defect\n\
          Male,67,asymptomatic,160,286,FALSE,lv hypertrophy,108,TRUE,1.5,flat,3,normal\n\
          ,,,,,,,,,,,,\n",
    );
    let out = csrl(&["predict", "--model", &model, "--data", &rows]);
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout.clone()).unwrap();
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], "line,class,cost,measured");
    assert_eq!(lines.len(), 4, "{stdout}");
    assert!(
        lines[1].starts_with("2,") && lines[3].starts_with("4,"),
        "{stdout}"
    );
    // The same rows in the training file's column order classify the same.
    let heart_rows = scratch(
        "heart3.csv",
        &std::fs::read(heart("cleveland.csv")).unwrap()[..]
            .split(|&b| b == b'\n')
            .take(3)
            .collect::<Vec<_>>()
            .join(&b'\n'),
    );
    let again = csrl(&["predict", "--model", &model, "--data", &heart_rows]);
    let again = String::from_utf8(again.stdout).unwrap();
    let tail = |s: &str| {
        s.lines()
            .skip(1)
            .take(2)
            .map(|l| l.split_once(',').unwrap().1.to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(tail(&stdout), tail(&again));
    assert!(
        stderr(&out).contains("classified 3 rows"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn bad_models_and_unwritable_outputs_have_their_exit_codes() {
    let out = on_heart(&["--learner", "cs-id3", "--save", "/no/such/dir/m.json"]);
    assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
    assert!(stderr(&out).contains("cannot write /no/such/dir/m.json"));
    let bad = scratch(
        "bad-model.json",
        b"{\"format\": \"csrl-classifier\", \"version\": 7}",
    );
    let out = csrl(&[
        "predict",
        "--model",
        &bad,
        "--data",
        &heart("cleveland.csv"),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("version 7 is not supported"),
        "{}",
        stderr(&out)
    );
    let model = scratch("model2.json", b"");
    assert!(
        on_heart(&["--learner", "cs-ibl", "--save", &model])
            .status
            .success()
    );
    let out = csrl(&[
        "predict",
        "--model",
        &model,
        "--data",
        &heart("cleveland.csv"),
        "--out",
        "/no/such/dir/o.csv",
    ]);
    assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
}

#[test]
fn save_and_dot_may_not_name_one_file() {
    let same = scratch("same.out", b"");
    let out = on_heart(&["--learner", "cs-id3", "--save", &same, "--dot", &same]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--save and --dot name the same file"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn predict_writes_out_only_for_a_table_it_accepts() {
    let model = scratch("model-out.json", b"");
    assert!(
        on_heart(&["--learner", "cs-id3", "--save", &model])
            .status
            .success()
    );
    let out = scratch("classified.csv", b"kept\n");
    let bad = scratch("bad-rows.csv", b"age,sex\n1,Male\n");
    let refused = csrl(&["predict", "--model", &model, "--data", &bad, "--out", &out]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "kept\n");
    let data = heart("cleveland.csv");
    let ok = csrl(&["predict", "--model", &model, "--data", &data, "--out", &out]);
    assert!(ok.status.success(), "{}", stderr(&ok));
    assert!(ok.stdout.is_empty());
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("line,class,cost,measured\n2,"), "{text}");
    assert_eq!(text.lines().count(), 305);
}
