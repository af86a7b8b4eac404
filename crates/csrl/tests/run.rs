//! `csrl run`, as a user runs it.

mod common;

use common::{csrl, json, ok, stderr};

use std::process::{Command, Output};

#[test]
fn json_has_the_documented_fields() {
    let v = json(&[
        "run",
        "--map",
        "tan3x3",
        "--strategy",
        "lazy",
        "--seed",
        "3",
        "--json",
    ]);
    assert_eq!(v["map"], "tan3x3");
    assert_eq!(v["strategy"], "lazy");
    assert_eq!(v["seed"], 3);
    assert_eq!(v["converged"], true);
    assert!(v["trials"].as_u64().unwrap() >= 1);
    let t = &v["table1"];
    for key in [
        "cost_to_sufficient",
        "trials_to_sufficient",
        "cost_to_converge",
        "trials_to_converge",
        "descriptions",
        "mean_features",
        "max_features",
        "tree_cost_per_state",
        "description_cost_per_state",
    ] {
        assert!(t[key].is_number(), "{key}: {t}");
    }
    let states = v["states"].as_array().unwrap();
    assert_eq!(states.len(), 8);
    for s in states {
        assert!(["up", "down", "left", "right"].contains(&s["greedy_action"].as_str().unwrap()));
        assert!(
            s["row"].is_u64()
                && s["col"].is_u64()
                && s["description"].is_u64()
                && s["value"].is_f64()
        );
    }
    // The state left of the goal (row 0, col 1) goes right with V = 1.
    let left_of_goal = states
        .iter()
        .find(|s| s["row"] == 0 && s["col"] == 1)
        .unwrap();
    assert_eq!(left_of_goal["greedy_action"], "right");
    assert_eq!(left_of_goal["value"], 1.0);
    let descriptions = v["descriptions"].as_array().unwrap();
    assert_eq!(
        descriptions.len() as u64,
        t["descriptions"].as_u64().unwrap()
    );
    for d in descriptions {
        assert!(d["label"].is_u64());
        for f in d["features"].as_array().unwrap() {
            assert!(
                f["dx"].is_i64()
                    && f["dy"].is_i64()
                    && f["value"].is_string()
                    && f["cost"].is_f64()
            );
        }
    }
}

#[test]
fn the_same_command_gives_byte_identical_json() {
    let args = [
        "run",
        "--map",
        "tan8x8",
        "--strategy",
        "random",
        "--seed",
        "5",
        "--json",
    ];
    let a = csrl(&args);
    let b = csrl(&args);
    assert!(a.status.success());
    assert_eq!(a.stdout, b.stdout);
}

#[test]
fn an_unconverged_run_says_so_with_nulls() {
    let v = json(&["run", "--map", "tan8x8", "--max-trials", "2", "--json"]);
    assert_eq!(v["converged"], false);
    assert_eq!(v["trials"], 2);
    assert!(v["table1"]["cost_to_converge"].is_null());
    assert!(v["table1"]["tree_cost_per_state"].is_null());
    let text = csrl(&["run", "--map", "tan8x8", "--max-trials", "2"]);
    assert!(String::from_utf8_lossy(&text.stdout).contains("did NOT converge"));
}

#[test]
fn config_files_apply_and_bad_ones_are_refused() {
    let dir = std::env::temp_dir().join(format!("csrl-run-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("good.toml");
    std::fs::write(&good, "map = \"tan3x3\"\nstrategy = \"eager\"\nseed = 4\n").unwrap();
    let v = json(&["run", "--config", good.to_str().unwrap(), "--json"]);
    assert_eq!(
        (
            v["map"].as_str(),
            v["strategy"].as_str(),
            v["seed"].as_u64()
        ),
        (Some("tan3x3"), Some("eager"), Some(4))
    );
    // Flags override the file.
    let v = json(&[
        "run",
        "--config",
        good.to_str().unwrap(),
        "--seed",
        "6",
        "--json",
    ]);
    assert_eq!(v["seed"], 6);
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "temprature = 0.3\n").unwrap();
    let out = csrl(&["run", "--config", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml") && err.contains("temprature"),
        "{err}"
    );
}

#[test]
fn bad_arguments_are_clear_errors() {
    let out = csrl(&["run", "--map", "nowhere"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("nowhere"));
    let out = csrl(&["run", "--strategy", "greedy"]);
    assert_eq!(out.status.code(), Some(2));
    // A trial cap below 1 is refused while the arguments are read, as a usage error.
    let out = csrl(&["run", "--max-trials", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("at least 1"));
}

#[test]
fn svg_shows_the_policy() {
    let dir = std::env::temp_dir().join(format!("csrl-run-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("policy.svg");
    let out = csrl(&["run", "--map", "tan3x3", "--svg", path.to_str().unwrap()]);
    assert!(out.status.success());
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg"));
    assert_eq!(svg.matches("class=\"arrow\"").count(), 8); // one per state
    assert!(svg.contains("<title>"));
}

#[test]
fn a_reader_that_stops_early_is_no_error() {
    use std::process::Stdio;
    // The JSON of a resetting run is far larger than a pipe's buffer, so the program is
    // still writing when the reader goes away.
    let mut child = Command::new(env!("CARGO_BIN_EXE_csrl"))
        .args(["run", "--map", "tan8x8", "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The text output shows the learned policy (arrows on the map) and the descriptions
/// table after Table 1; the table's columns each have their own name.
#[test]
fn text_output_shows_the_policy_on_the_map_and_the_descriptions() {
    let out = csrl(&["run", "--map", "tan3x3"]);
    assert!(out.status.success());
    let text = stdout(&out);
    let policy = text.find("Learned policy").expect("a policy");
    assert!(text.find("# Descriptions").expect("descriptions") > policy);
    // The map with arrows: its first line is the wall, then rows with arrows.
    let map: Vec<&str> = text[policy..].lines().skip(1).take(5).collect();
    assert_eq!(map[0], "#####", "{text}");
    assert!(
        map[1..4].iter().any(|l| l.contains(['>', '<', '^', 'v'])),
        "{text}"
    );
    assert!(
        text.contains("| description | states (row, col) | features | cost | readings required |"),
        "{text}"
    );
}

/// In a world that is not a grid, the policy is a table of state -> action, and the
/// descriptions table names its states column for what it holds (labels).
#[test]
fn text_output_of_another_world_has_a_policy_table() {
    let out = csrl(&["run", "--world", "frozenlake4x4", "--max-trials", "50"]);
    assert!(out.status.success());
    let text = stdout(&out);
    assert!(
        text.contains("| state | greedy action | description |"),
        "{text}"
    );
    assert!(
        text.contains("| description | states | features | cost | readings required |"),
        "{text}"
    );
    assert!(!text.contains("(row, col)"), "{text}");
}

/// `--svg FILE` also writes the descriptions table its legend points to, as `FILE.md`,
/// and says so on stderr.
#[test]
fn svg_writes_the_descriptions_table_beside_it() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("policy.svg");
    let out = csrl(&["run", "--map", "tan3x3", "--svg", svg.to_str().unwrap()]);
    assert!(out.status.success());
    let table = std::fs::read_to_string(dir.path().join("policy.md")).expect("the table");
    assert!(table.starts_with("# Descriptions: tan3x3"), "{table}");
    assert!(stdout(&out).contains(&table));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("policy.md"), "{err}");
}

/// A run that senses less says what it skipped; its JSON holds the same counts; the
/// weighed level needs a price, and its old spelling `belief` is refused with a pointer.
#[test]
fn sensing_less_is_reported_in_the_text() {
    let args = [
        "run",
        "--map",
        "tan8x8",
        "--strategy",
        "eager",
        "--predict-sensing",
        "weighed",
        "--price",
        "0.01",
    ];
    let text = ok(&args);
    let v = json(&[&args[..], &["--json"]].concat());
    let skipped = v["prediction"]["skipped"].as_u64().unwrap();
    assert!(skipped > 0, "{v}");
    assert!(
        text.contains(&format!(
            "Sensing less (weighed): {skipped} classifications skipped"
        )),
        "{text}"
    );
    let plain = ok(&["run", "--map", "tan8x8", "--strategy", "eager"]);
    assert!(!plain.contains("Sensing less"), "{plain}");
    let out = csrl(&["run", "--map", "tan3x3", "--predict-sensing", "weighed"]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("[costly] price"), "{}", stderr(&out));
    let old = csrl(&["run", "--map", "tan3x3", "--predict-sensing", "belief"]);
    assert!(!old.status.success());
    assert!(
        stderr(&old).contains("predict_sensing = \"weighed\""),
        "{}",
        stderr(&old)
    );
}
