//! The map commands, run as a user runs them.

mod common;

use common::{csrl, stderr};

use std::path::PathBuf;

fn scratch(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("csrl-maps-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn maps_lists_every_builtin() {
    let out = csrl(&["maps"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for name in mdp::builtin_names() {
        assert!(
            text.lines().any(|l| l.starts_with(name)),
            "{name} missing in {text}"
        );
    }
}

#[test]
fn show_json_has_the_documented_fields() {
    let out = csrl(&["map", "show", "tan8x8-maze", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["name"], "tan8x8-maze");
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(8), Some(8))
    );
    assert_eq!(v["states"], 50);
    assert_eq!(
        (v["goal"]["row"].as_u64(), v["goal"]["col"].as_u64()),
        (Some(2), Some(4))
    );
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 64);
    let goal = cells.iter().find(|c| c["kind"] == "goal").unwrap();
    assert_eq!(goal["distance"], 0);
    // Row 0 is the top line of the layout, col 0 its leftmost character.
    let first = &cells[0];
    assert_eq!(
        (
            first["row"].as_u64(),
            first["col"].as_u64(),
            first["kind"].as_str()
        ),
        (Some(0), Some(0), Some("empty"))
    );
    assert_eq!(cells[5]["kind"], "obstacle");
    assert!(cells[5]["distance"].is_null());
    let free = cells.iter().filter(|c| c["kind"] != "obstacle").count();
    assert_eq!(free, 51);
}

#[test]
fn show_text_prints_the_grid() {
    let out = csrl(&["map", "show", "tan3x3"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("#..G#\n#...#\n#...#"), "{text}");
}

#[test]
fn show_reads_a_file() {
    let path = scratch("file.toml", b"name = \"mine\"\nlayout = '''\nG.\n'''\n");
    let out = csrl(&["map", "show", path.to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["name"], "mine");
}

#[test]
fn check_accepts_a_valid_file() {
    let path = scratch(
        "ok.toml",
        mdp::builtin("tan8x8").unwrap().to_toml().as_bytes(),
    );
    let out = csrl(&["map", "check", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn check_refuses_broken_input_without_panicking() {
    let huge = vec![b'.'; (mdp::MAX_FILE_BYTES + 10) as usize];
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty.toml", vec![], "name"),
        ("binary.toml", vec![0, 159, 146, 150, 255, 0, 1], "UTF-8"),
        ("bad.toml", b"name = [\n".to_vec(), "line"),
        (
            "ragged.toml",
            b"name = \"r\"\nlayout = '''\n..G\n.\n'''\n".to_vec(),
            "line 4",
        ),
        (
            "nogoal.toml",
            b"name = \"n\"\nlayout = '''\n...\n'''\n".to_vec(),
            "no goal",
        ),
        (
            "unknown.toml",
            b"name = \"u\"\nlayout = '''\nG.?\n'''\n".to_vec(),
            "unknown map character",
        ),
        (
            "cut.toml",
            b"name = \"c\"\nlayout = '''\nG#.\n'''\n".to_vec(),
            "cannot reach",
        ),
        ("huge.toml", huge, "more than"),
    ];
    for (name, bytes, expect) in cases {
        let path = scratch(name, &bytes);
        let out = csrl(&["map", "check", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1), "{name}: {}", stderr(&out));
        let err = stderr(&out);
        assert!(err.contains(expect), "{name}: {err}");
        assert!(err.contains(name), "{name} not named: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
}

#[test]
fn missing_file_and_unknown_map_are_errors() {
    let out = csrl(&["map", "check", "/no/such/file.toml"]);
    assert_eq!(out.status.code(), Some(1));
    let out = csrl(&["map", "show", "no-such-map"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("tan8x8"),
        "lists the built-ins: {}",
        stderr(&out)
    );
}

#[test]
fn usage_errors_exit_2() {
    assert_eq!(csrl(&["map", "frobnicate"]).status.code(), Some(2));
}
