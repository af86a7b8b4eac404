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

/// Run `csrl` with `args`, send it SIGTERM once it says it is under way (the ready line
/// it writes to stderr with `CSRL_READY_LINE` set, after its stop handler is installed),
/// and wait for it. No fixed wait: the signal goes when the program is ready for it, and
/// the runs given would go on for days without it, so their ending proves it honoured.
#[cfg(unix)]
fn terminated(args: &[&std::ffi::OsStr]) -> (std::process::ExitStatus, Vec<u8>, String) {
    use std::io::{BufRead, Read};
    let mut child = Command::new(env!("CARGO_BIN_EXE_csrl"))
        .args(args)
        .env("CSRL_READY_LINE", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read stdout on its own thread, so that a long report never blocks the program.
    let mut stdout = child.stdout.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut out = Vec::new();
        stdout.read_to_end(&mut out).unwrap();
        out
    });
    let mut stderr = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut err = String::new();
    loop {
        let mut line = String::new();
        if stderr.read_line(&mut line).unwrap() == 0 {
            let _ = child.kill();
            panic!("{args:?} ended before its ready line: {err}");
        }
        err.push_str(&line);
        if line.trim_end() == "csrl: under way (Ctrl-C or SIGTERM stops with the report)" {
            break;
        }
    }
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    stderr.read_to_string(&mut err).unwrap();
    let status = child.wait().unwrap();
    (status, reader.join().unwrap(), err)
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
    let (status, stdout, err) = terminated(&args.map(std::ffi::OsStr::new));
    assert_eq!(status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted after"), "{err}");
    assert!(!stdout.is_empty(), "no report: {err}");
}

/// A run priced by `[costly]` and stopped by SIGTERM says that its costed returns are
/// missing and why, in the text and in the JSON.
#[cfg(unix)]
#[test]
fn sigterm_on_a_priced_run_says_its_costed_returns_are_missing() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("priced.toml");
    std::fs::write(&config, "[costly]\nprice = 0.01\n").unwrap();
    for json in [false, true] {
        let mut args = vec![
            std::ffi::OsStr::new("run"),
            "--map".as_ref(),
            "random:48x48:0.2:1".as_ref(),
            "--max-trials".as_ref(),
            "1000000".as_ref(),
            "--config".as_ref(),
            config.as_os_str(),
        ];
        if json {
            args.push("--json".as_ref());
        }
        let (status, stdout, err) = terminated(&args);
        assert_eq!(status.code(), Some(130), "{err}");
        let text = String::from_utf8(stdout).unwrap();
        if json {
            let report: serde_json::Value = serde_json::from_str(&text).unwrap();
            assert!(report.get("costly").is_none(), "{report}");
            let why = report["costly_missing"].as_str().unwrap();
            assert!(why.contains("stopped (Ctrl-C or SIGTERM)"), "{why}");
        } else {
            assert!(
                text.contains("Costed returns missing: the run was stopped"),
                "{text}"
            );
        }
    }
}

/// SIGTERM during the navigation after learning stops it too. Learning ends after its
/// one trial (the ready line comes after it); navigation, 10,000 trials from each state
/// of a policy that has learned nothing with a move cap of four billion, would run for
/// days.
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
        "1",
        "--predict-sensing",
        "learned",
        "--json",
        "--config",
    ]
    .map(std::ffi::OsStr::new);
    let (status, stdout, err) = terminated(&[&args[..], &[config.as_os_str()]].concat());
    assert_eq!(status.code(), Some(130), "{err}");
    let report: serde_json::Value = serde_json::from_slice(&stdout).unwrap();
    assert_eq!(report["trials"], 1, "{err}");
    assert!(report["navigation_success"].is_number(), "{report}");
}
