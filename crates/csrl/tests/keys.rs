//! The keys of a settings file as `csrl run` takes them: its `--config` help lists every
//! key of the one table (`csql::SETTING_KEYS`) and none other, and a key the learner does
//! not read is refused from the file and from a flag alike.

mod common;

use common::{config, csrl, ok, stderr};

/// The lines of `csrl run --help` under `--config` that list the keys: `HEAD: GROUP;
/// GROUP`, where a group is `key, key (learner, learner)` or, read by every learner,
/// `key, key`.
fn config_help_keys() -> Vec<(Option<String>, String, Vec<String>)> {
    let help = ok(&["run", "--help"]);
    let at = help.find("--config <CONFIG>").expect("--config is listed");
    let mut keys = Vec::new();
    let lines = help[at..]
        .lines()
        .skip(2)
        .map(str::trim)
        .take_while(|l| !l.is_empty());
    for line in lines {
        let (head, groups) = line.split_once(": ").unwrap_or_else(|| panic!("{line:?}"));
        let table = match head {
            "top level" => None,
            t => Some(
                t.strip_prefix('[')
                    .and_then(|t| t.strip_suffix(']'))
                    .unwrap_or_else(|| panic!("{head:?}"))
                    .to_string(),
            ),
        };
        for group in groups.split("; ") {
            let (names, readers) = match group.strip_suffix(')') {
                Some(g) => {
                    let (names, readers) = g.split_once(" (").unwrap();
                    (names, readers.split(", ").map(str::to_string).collect())
                }
                None => (
                    group,
                    ["cs-ql", "u-tree", "full-sensing", "amrl-q", "belief"]
                        .map(str::to_string)
                        .to_vec(),
                ),
            };
            for name in names.split(", ") {
                keys.push((table.clone(), name.to_string(), readers.clone()));
            }
        }
    }
    keys
}

#[test]
fn the_config_help_lists_every_key_and_who_reads_it() {
    // The help groups the keys by their readers: the same keys, in another order.
    let mut listed = config_help_keys();
    let mut table: Vec<(Option<String>, String, Vec<String>)> = csql::SETTING_KEYS
        .iter()
        .map(|k| {
            (
                k.table.map(str::to_string),
                k.name.to_string(),
                k.read_by.iter().map(|l| l.to_string()).collect(),
            )
        })
        .collect();
    listed.sort();
    table.sort();
    assert_eq!(listed, table);
}

/// A key the learner does not read is refused from the file and from a flag, naming the
/// key and the learner.
#[test]
fn a_key_the_learner_does_not_read_is_refused_from_file_and_flag() {
    let dir = tempfile::tempdir().unwrap();
    let gamma = config(dir.path(), "gamma", "gamma = 0.9");
    let gamma = gamma.to_str().unwrap();
    let refused = |args: &[&str], named: &str| {
        let out = csrl(args);
        assert!(!out.status.success(), "{args:?} must be refused");
        assert!(stderr(&out).contains(named), "{args:?}: {}", stderr(&out));
    };
    let lake = ["run", "--world", "frozenlake4x4", "--max-trials", "5"];
    let episodes = ["run", "--world", "frozenlake4x4", "--episodes", "5"];
    refused(
        &[
            &episodes[..],
            &["--learner", "amrl-q", "--price", "0.1", "--config", gamma],
        ]
        .concat(),
        "gamma = 0.9 and learner = amrl-q",
    );
    refused(
        &[
            &lake[..],
            &["--learner", "u-tree", "--predict-sensing", "off"],
        ]
        .concat(),
        "predict_sensing = off and learner = u-tree",
    );
    refused(
        &[&lake[..], &["--learner", "u-tree", "--price", "0.1"]].concat(),
        "[costly] price and learner = u-tree",
    );
    let judged = config(dir.path(), "judged", "[judge]\nquality_every = 5");
    refused(
        &[
            &episodes[..],
            &["--learner", "belief", "--price", "0.1", "--config"],
            &[judged.to_str().unwrap()],
        ]
        .concat(),
        "[judge] quality_every and learner = belief",
    );
    // An old file with the judging keys under [extensions] is told where they went.
    let old = dir.path().join("old.toml");
    std::fs::write(&old, "[extensions]\njudge_by_quality = true\n").unwrap();
    refused(
        &["run", "--config", old.to_str().unwrap()],
        "moved from [extensions] to a table of its own: write it under [judge]",
    );
}
