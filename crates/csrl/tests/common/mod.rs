//! What the integration tests of `csrl` share: running the binary, reading what it
//! wrote, and the lake sensed by row and column that the costed runs play.

// Each test file is a crate of its own and uses some of these only.
#![allow(
    dead_code,
    reason = "shared by several test programs, each of which uses only some of it (an expectation would fail in those that use all)"
)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Run `csrl` with `args`, as a user runs it.
pub fn csrl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_csrl"))
        .args(args)
        .output()
        .expect("run csrl")
}

/// What a run wrote to stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// What a run that must succeed wrote to stdout (the test fails with its stderr if it
/// does not).
pub fn ok(args: &[&str]) -> String {
    let out = csrl(args);
    assert!(out.status.success(), "csrl {args:?}: {}", stderr(&out));
    String::from_utf8(out.stdout).unwrap()
}

/// The JSON a run that must succeed wrote to stdout.
pub fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(args)).unwrap()
}

/// A settings file `name.toml` in `dir` sensing the lake by row and column, with `extra`
/// before `[world]`.
pub fn config(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, format!("{extra}\n[world]\nsensing = \"factors\"\n")).unwrap();
    path
}

/// FrozenLake 4x4 sensed by row and column, as such a settings file makes it.
pub fn lake() -> mdp::FiniteWorld {
    let options = mdp::WorldOptions {
        sensing: Some(mdp::SensingModel::Factors),
        ..Default::default()
    };
    mdp::builtin_world("frozenlake4x4", &options).unwrap()
}

/// The costed return of each episode of a run's JSON report.
pub fn returns(v: &serde_json::Value) -> Vec<f64> {
    v["costly"]["returns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}
