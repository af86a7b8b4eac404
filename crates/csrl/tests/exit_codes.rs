//! One exit code per kind of ending, across commands; each message says a thing once;
//! SIGTERM stops a run as Ctrl-C does.

mod common;

use common::{csrl, stderr};

use std::process::{Command, Stdio};

/// A missing folder and a folder that is a file are both "cannot write": exit code 4,
/// for `run --svg` and `world export --out` alike.
#[test]
fn every_output_that_cannot_be_written_exits_4() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let missing = dir.path().join("no-such-folder").join("out");
    let under_file = file.join("out");
    for target in [&missing, &under_file] {
        let svg = target.with_extension("svg");
        let json = target.with_extension("json");
        let svg = svg.to_str().unwrap();
        let json = json.to_str().unwrap();
        for args in [
            vec!["run", "--map", "tan3x3", "--max-trials", "2", "--svg", svg],
            vec!["world", "export", "frozenlake4x4", "--out", json],
        ] {
            let out = csrl(&args);
            assert_eq!(out.status.code(), Some(4), "{args:?}: {}", stderr(&out));
            assert!(stderr(&out).contains("cannot write"), "{}", stderr(&out));
        }
    }
}

/// A bad input is 1 whatever the command; a usage error 2.
#[test]
fn a_bad_input_exits_1_and_a_usage_error_2() {
    for args in [
        vec!["run", "--map", "no-such-map"],
        vec!["map", "show", "no-such-map"],
        vec!["world", "show", "no-such-world"],
    ] {
        let out = csrl(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
    }
    assert_eq!(csrl(&["run", "--no-such-flag"]).status.code(), Some(2));
}

/// "not a regular file: not a regular file" was printed for a directory given as the
/// settings file: a cause already said is not said again.
#[test]
fn a_message_says_a_thing_once() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path().to_str().unwrap();
    for args in [
        vec!["run", "--config", dir],
        vec!["run", "--map", dir],
        vec!["world", "show", dir],
    ] {
        let out = csrl(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(
            err.matches("not a regular file").count(),
            1,
            "{args:?}: {err}"
        );
    }
}

/// Run `csrl` with `args`, send it SIGTERM once it is under way (time for the handler to
/// be installed and the run to start), and wait for it, for a minute at most.
#[cfg(unix)]
fn terminated(args: &[&std::ffi::OsStr]) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_csrl"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while child.try_wait().unwrap().is_none() {
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            panic!("SIGTERM did not stop {args:?} within a minute");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child.wait_with_output().unwrap()
}

/// SIGTERM, as Ctrl-C: the run stops, prints the report it reached, and exits 130.
#[cfg(unix)]
#[test]
fn sigterm_stops_a_run_with_its_report() {
    let args = [
        "run",
        "--map",
        "random:48x48:0.2:1",
        "--max-trials",
        "1000000",
    ];
    let out = terminated(&args.map(std::ffi::OsStr::new));
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted after"), "{err}");
    assert!(!out.stdout.is_empty(), "no report: {err}");
}

/// SIGTERM during the navigation after learning stops it too. Learning ends in three
/// trials; navigation, 10,000 trials from each state of a policy that has learned
/// nothing with a move cap of four billion, would run for days.
#[cfg(unix)]
#[test]
fn sigterm_stops_navigation_after_learning() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("long.toml");
    std::fs::write(
        &config,
        "max_moves = 4000000000\n[prediction]\nnavigation_trials = 10000\n",
    )
    .unwrap();
    let args = [
        "run",
        "--map",
        "tan8x8",
        "--strategy",
        "resetting",
        "--max-trials",
        "3",
        "--predict-sensing",
        "learned",
        "--json",
        "--config",
    ]
    .map(std::ffi::OsStr::new);
    let out = terminated(&[&args[..], &[config.as_os_str()]].concat());
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(130), "{err}");
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["trials"], 3, "{err}");
    assert!(report["navigation_success"].is_number(), "{report}");
}
