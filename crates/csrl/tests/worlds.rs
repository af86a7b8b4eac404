//! `csrl world ...` and `csrl run --world`, as a user runs them.

mod common;

use common::{csrl, json, ok};

/// Fails with exit code 1 and an `error: ` line that contains every fragment.
fn refused(args: &[&str], fragments: &[&str]) {
    let out = csrl(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "csrl {args:?}: {err}");
    assert!(err.starts_with("error: "), "{err}");
    for f in fragments {
        assert!(err.contains(f), "csrl {args:?}: {err:?} lacks {f:?}");
    }
    assert!(!err.contains("panicked"), "{err}");
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("csrl-worlds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn the_built_in_worlds_are_listed_with_their_sizes() {
    let text = ok(&["world", "list"]);
    for name in ["frozenlake4x4", "frozenlake8x8", "taxi", "cliffwalking"] {
        assert!(text.contains(name), "{text}");
    }
    let all = json(&["world", "list", "--json"]);
    let taxi = all
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["name"] == "taxi")
        .unwrap();
    assert_eq!(taxi["states"], 500);
    assert_eq!(taxi["start_states"], 300);
    assert_eq!(taxi["actions"].as_array().unwrap().len(), 6);
    assert_eq!(taxi["features"].as_array().unwrap().len(), 4);
}

/// The proof that the core does not depend on grid code: the export of a map, run as a
/// world file, makes the same moves at the same costs, to the same Table 1, for every
/// strategy.
#[test]
fn a_map_exported_as_a_world_file_runs_exactly_as_the_map() {
    for map in ["tan3x3", "tan8x8"] {
        let file = temp(&format!("{map}.json"));
        ok(&["world", "export", map, "--out", file.to_str().unwrap()]);
        for strategy in ["resetting", "lazy", "random", "eager"] {
            let args = |how: &str, what: &str| {
                [
                    "run",
                    how,
                    what,
                    "--strategy",
                    strategy,
                    "--seed",
                    "2",
                    "--json",
                    "--trace",
                ]
                .map(String::from)
            };
            let a = json(&args("--map", map).each_ref().map(|s| s.as_str()));
            let b = json(
                &args("--world", file.to_str().unwrap())
                    .each_ref()
                    .map(|s| s.as_str()),
            );
            for key in [
                "table1",
                "trials",
                "moves",
                "total_cost",
                "trace",
                "converged",
            ] {
                assert_eq!(a[key], b[key], "{map} {strategy}: {key} differs");
            }
            assert!(a["converged"].as_bool().unwrap());
            // The same descriptions, named by the export's feature names.
            assert_eq!(
                a["descriptions"].as_array().unwrap().len(),
                b["descriptions"].as_array().unwrap().len()
            );
        }
    }
}

#[test]
fn an_export_reads_back_to_the_same_file() {
    let first = ok(&["world", "export", "frozenlake4x4"]);
    let file = temp("fl.json");
    std::fs::write(&file, &first).unwrap();
    assert_eq!(ok(&["world", "export", file.to_str().unwrap()]), first);
    let checked = ok(&[
        "world",
        "check",
        file.to_str().unwrap(),
        "--paper-assumptions",
    ]);
    assert!(checked.contains("valid world `frozenlake4x4`"), "{checked}");
}

#[test]
fn frozenlake_is_learned_with_either_sensing_model() {
    let local = json(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--strategy",
        "lazy",
        "--json",
    ]);
    assert!(local["converged"].as_bool().unwrap());
    assert_eq!(local["map"], "frozenlake4x4");
    // States are named by the world, features by name, actions by Gymnasium's names.
    let s = &local["states"][0];
    assert_eq!(s["label"], "(0,0)");
    assert!(s.get("row").is_none());
    assert!(["left", "down", "right", "up"].contains(&s["greedy_action"].as_str().unwrap()));
    let config = temp("factors.toml");
    std::fs::write(
        &config,
        "[world]\nsensing = \"factors\"\nfactor_costs = [2.0, 3.0]\n",
    )
    .unwrap();
    let factors = json(&[
        "run",
        "--world",
        "frozenlake4x4",
        "--config",
        config.to_str().unwrap(),
        "--strategy",
        "random",
        "--json",
    ]);
    assert!(factors["converged"].as_bool().unwrap());
    let prices: Vec<f64> = factors["descriptions"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|d| d["features"].as_array().unwrap())
        .map(|f| f["cost"].as_f64().unwrap())
        .collect();
    assert!(!prices.is_empty() && prices.iter().all(|&p| p == 2.0 || p == 3.0));
    let names: Vec<&str> = factors["descriptions"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|d| d["features"].as_array().unwrap())
        .map(|f| f["feature"].as_str().unwrap())
        .collect();
    assert!(
        names.iter().all(|n| *n == "row" || *n == "col"),
        "{names:?}"
    );
}

#[test]
fn settings_for_another_kind_of_world_are_refused_naming_both() {
    let config = temp("slide.toml");
    std::fs::write(&config, "[world]\nslide = 0.5\n").unwrap();
    refused(
        &[
            "run",
            "--map",
            "tan3x3",
            "--config",
            config.to_str().unwrap(),
        ],
        &["tan3x3", "slide"],
    );
    refused(
        &[
            "run",
            "--world",
            "taxi",
            "--svg",
            temp("t.svg").to_str().unwrap(),
        ],
        &["--svg", "grid"],
    );
    let local = temp("local.toml");
    std::fs::write(&local, "[world]\nsensing = \"local\"\n").unwrap();
    refused(
        &[
            "run",
            "--world",
            "taxi",
            "--config",
            local.to_str().unwrap(),
        ],
        &["local", "taxi"],
    );
}

#[test]
fn malformed_world_files_are_refused_with_where() {
    let file = temp("bad.json");
    std::fs::write(
        &file,
        r#"{"format": "csrl-world", "version": 1, "name": "coin",
  "states": 2, "actions": ["flip"], "start": [[1.0, 0]], "terminal": [1],
  "transitions": [[0, 0, [[0.5, 0, 0.0, false], [0.4, 1, 1.0, true]]]],
  "features": [], "readings": [[], []]}"#,
    )
    .unwrap();
    refused(
        &["world", "check", file.to_str().unwrap()],
        &["bad.json", "state 0, action 0", "sum to 0.9"],
    );
    refused(
        &["run", "--world", file.to_str().unwrap()],
        &["bad.json", "sum to 0.9"],
    );
    refused(
        &["world", "show", "no-such-world.json"],
        &["no-such-world.json"],
    );
}

/// Full sensing keeps every state's whole view: a world where that would not fit in
/// memory is refused before anything is built, with the estimate.
#[test]
fn full_sensing_of_a_huge_world_is_refused_up_front() {
    refused(
        &[
            "run",
            "--map",
            "random:256x256:0.2:1",
            "--learner",
            "full-sensing",
            "--max-trials",
            "2",
        ],
        &["full sensing", "over the limit", "6961158540"],
    );
}
