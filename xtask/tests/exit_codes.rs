//! `cargo xtask` exit codes, the same kinds as `csrl`'s: 1 a bad input, 2 a usage error, 4
//! an output that cannot be written.

use std::process::{Command, Output};

fn xtask(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .output()
        .expect("run xtask")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn each_kind_of_failure_has_its_exit_code() {
    let dir = tempfile::tempdir().unwrap();
    // A regular file where a folder should be: the output folder cannot be made.
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let under = file.join("out");
    let under = under.to_str().unwrap();
    for args in [
        &["sweep", "--maps", "tan3x3", "--runs", "1", "--out", under][..],
        &[
            "robustness",
            "--maps",
            "tan3x3",
            "--runs",
            "1",
            "--out",
            under,
        ][..],
    ] {
        let out = xtask(args);
        assert_eq!(out.status.code(), Some(4), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains("cannot write"), "{}", stderr(&out));
    }
    // A bad input is 1 and a usage error 2.
    let out = xtask(&["sweep", "--maps", "nosuchmap", "--out", under]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let out = xtask(&[
        "sweep", "--maps", "tan3x3", "--runs", "many", "--out", under,
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let missing = dir.path().join("missing.svg");
    let out = xtask(&["png", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
}
