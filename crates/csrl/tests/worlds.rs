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

/// The lake sensed by row and column with a third feature, `far`, reading 0 but where
/// `odd` says; written to `name` in the test's folder.
fn lake_with_far(name: &str, odd: &[(usize, u32)]) -> std::path::PathBuf {
    let mut spec = common::lake().to_spec();
    spec.features.push(mdp::FeatureSpec {
        name: "far".into(),
        price: 3.0,
        readings: vec![],
    });
    for (s, row) in spec.readings.iter_mut().enumerate() {
        row.push(odd.iter().find(|o| o.0 == s).map_or(0, |o| o.1));
    }
    let path = temp(name);
    std::fs::write(&path, mdp::FiniteWorld::new(spec).unwrap().to_json()).unwrap();
    path
}

/// `csrl run --json` on a world file under a 1 GB address-space limit, with the file's
/// path taken out of the report.
#[cfg(unix)]
fn run_in_1gb(world: &std::path::Path, strategy: &str) -> serde_json::Value {
    let out = std::process::Command::new("sh")
        .args([
            "-c",
            "ulimit -v 1000000 && exec \"$0\" run --world \"$1\" --strategy \"$2\" --json",
            env!("CARGO_BIN_EXE_csrl"),
            world.to_str().unwrap(),
            strategy,
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{world:?} {strategy}: {err}");
    let mut v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["settings"]["map"] = serde_json::Value::Null;
    v
}

/// A large reading costs memory only if it is sensed, and then as much as any other:
/// the run is the run of the same world with a small reading in its place.
#[cfg(unix)]
#[test]
fn a_large_reading_runs_in_little_memory_and_as_a_small_one() {
    // State 15 is the goal: terminal, never sensed. State 0 is the start.
    let small_goal = lake_with_far("small-goal.json", &[(15, 1)]);
    let large_goal = lake_with_far("large-goal.json", &[(15, 4_000_000_000)]);
    let small_start = lake_with_far("small-start.json", &[(0, 1)]);
    let large_start = lake_with_far("large-start.json", &[(0, 100_000_000)]);
    let mut sensed = 0;
    for strategy in ["resetting", "lazy", "random", "eager"] {
        let a = run_in_1gb(&small_goal, strategy);
        assert_eq!(a, run_in_1gb(&large_goal, strategy), "{strategy}");
        // A description of the start that requires `far` names the reading.
        let b = run_in_1gb(&small_start, strategy).to_string();
        let large = run_in_1gb(&large_start, strategy).to_string();
        sensed += usize::from(large.contains("\"value\":\"100000000\""));
        let large = large.replace("\"value\":\"100000000\"", "\"value\":\"1\"");
        assert_eq!(b, large, "{strategy}");
    }
    assert!(
        sensed > 0,
        "no run described the start by its large reading"
    );
    let shown = ok(&["world", "show", large_goal.to_str().unwrap()]);
    assert!(shown.contains("4000000001"), "{shown}");
}

/// A reading whose count of readings would not fit in 32 bits is refused by every
/// command that reads the file, naming the state and the feature.
#[test]
fn a_reading_beyond_the_largest_is_refused() {
    let file = lake_with_far("too-large.json", &[(15, 7)]);
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("[3,3,7]", "[3,3,4294967295]");
    std::fs::write(&file, text).unwrap();
    for command in ["check", "show"] {
        refused(
            &["world", command, file.to_str().unwrap()],
            &["state 15 reads 4294967295 on feature `far`", "4294967294"],
        );
    }
    refused(
        &["run", "--world", file.to_str().unwrap()],
        &["state 15 reads 4294967295"],
    );
}

/// Names from a world file reach the terminal with their control characters escaped:
/// `world show`, `world check`, a run's text report and an error.
#[test]
fn control_characters_in_names_are_escaped_for_the_terminal() {
    let mut spec = common::lake().to_spec();
    spec.name = "lake\u{1b}[2J\r".into();
    spec.actions[0] = "left\u{7}".into();
    spec.features[0].name = "row\u{1b}]0;title\u{7}".into();
    if let mdp::StatesSpec::Labels(labels) = &mut spec.states {
        labels[0] = "start\u{1b}[31m".into();
    }
    let file = temp("control.json");
    std::fs::write(
        &file,
        mdp::FiniteWorld::new(spec.clone()).unwrap().to_json(),
    )
    .unwrap();
    let path = file.to_str().unwrap();
    let clean = |text: &str| {
        assert!(
            !text.chars().any(|c| c.is_control() && c != '\n'),
            "{text:?}"
        );
    };
    let shown = ok(&["world", "show", path]);
    clean(&shown);
    assert!(shown.starts_with("lake\\u{1b}[2J\\r\n"), "{shown}");
    assert!(shown.contains("left\\u{7}") && shown.contains("row\\u{1b}]0;title\\u{7}"));
    clean(&ok(&["world", "check", path]));
    let run = ok(&["run", "--world", path, "--max-trials", "20"]);
    clean(&run);
    assert!(run.contains("lake\\u{1b}[2J\\r"), "{run}");
    // An error that names a feature of the file.
    spec.features[0].price = -1.5;
    std::fs::write(&file, serde_json::to_string(&spec).unwrap()).unwrap();
    let out = csrl(&["world", "check", path]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("row\\u{1b}]0;title\\u{7}`: price -1.5"),
        "{err}"
    );
    clean(&err);
}

#[test]
fn world_show_prints_the_settings_a_run_takes_from_the_world() {
    let text = ok(&["world", "show", "taxi"]);
    for part in [
        "temperature = 8",
        "[extensions] detector = \"action\"",
        "max_trials = 200000",
        "the world's own defaults",
        "rewards from -10 to 20",
    ] {
        assert!(text.contains(part), "{text:?} lacks {part:?}");
    }
    let taxi = json(&["world", "show", "taxi", "--json"]);
    let d = &taxi["run_defaults"];
    assert_eq!(
        (
            &d["temperature"],
            &d["detector"],
            &d["max_trials"],
            &d["from"]
        ),
        (
            &8.0.into(),
            &"action".into(),
            &200_000.into(),
            &"world".into()
        )
    );
    // A grid map runs at the paper's values.
    let map = json(&["world", "show", "tan3x3", "--json"]);
    assert_eq!(map["run_defaults"]["temperature"], 0.4);
    assert_eq!(map["run_defaults"]["from"], "paper");
    assert!(map["run_defaults"].get("why").is_none());
    // The list names them too.
    let list = ok(&["world", "list"]);
    assert!(
        list.contains("temperature 40, detector action, max_trials 20000"),
        "{list}"
    );
}

#[test]
fn a_run_from_a_world_s_defaults_learns_and_echoes_them() {
    let v = json(&[
        "run",
        "--world",
        "cliffwalking",
        "--strategy",
        "eager",
        "--json",
    ]);
    assert_eq!(v["converged"], true);
    assert_eq!(v["quality"]["policy_quality"], 1.0);
    assert_eq!(v["settings"]["temperature"], 40.0);
    assert_eq!(v["settings"]["extensions"]["detector"], "action");
    assert!(v.get("not_learned").is_none(), "{v}");
}

#[test]
fn a_run_that_ends_without_learning_says_why_and_what_to_try() {
    let cold = temp("cold.toml");
    std::fs::write(&cold, "temperature = 0.4\n").unwrap();
    let args = [
        "run",
        "--world",
        "taxi",
        "--strategy",
        "lazy",
        "--max-trials",
        "30",
        "--config",
        cold.to_str().unwrap(),
    ];
    let text = ok(&args);
    assert!(
        text.contains("Not learned: It reached its trial cap"),
        "{text}"
    );
    assert!(text.contains("No utility ever decreased"), "{text}");
    assert!(
        text.contains("Try (in a --config file): temperature = 8; max_trials = 200000"),
        "{text}"
    );
    let mut with_json = args.to_vec();
    with_json.push("--json");
    let v = json(&with_json);
    assert_eq!(v["not_learned"]["try"][0], "temperature = 8");
    assert!(
        v["not_learned"]["why"]
            .as_str()
            .unwrap()
            .contains("csrl world show taxi"),
        "{v}"
    );
}
