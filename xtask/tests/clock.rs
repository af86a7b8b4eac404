//! No test waits a fixed time or judges by the wall clock: a signal test sends its signal
//! when the program's ready line has come, a Python test waits for an event, and a result
//! is judged by what was computed, never by how long it took. Every test source is read
//! for the calls that would do either: each crate's and xtask's `tests/` folders, and the
//! Python package's tests.

use std::path::{Path, PathBuf};

/// The calls that sleep or read the clock, by language.
const RUST: &[&str] = &[
    "thread::sleep",
    "Instant::now",
    "SystemTime::now",
    ".elapsed()",
];
const PYTHON: &[&str] = &[
    "sleep(",
    "time.time(",
    "time.monotonic(",
    "perf_counter(",
    "process_time(",
    "datetime.now(",
];

/// `(line number, call)` of each line of `src` (a file of the language that `calls` are
/// of) that makes one of `calls`, comments left out.
fn clock_calls(src: &str, calls: &[&'static str], comment: &str) -> Vec<(usize, &'static str)> {
    src.lines()
        .enumerate()
        .flat_map(|(i, line)| {
            let code = line.split(comment).next().unwrap_or("");
            calls
                .iter()
                .filter(move |c| code.contains(**c))
                .map(move |c| (i + 1, *c))
        })
        .collect()
}

fn files(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, ext, out);
        } else if path.extension().is_some_and(|e| e == ext) {
            out.push(path);
        }
    }
}

#[test]
fn no_test_sleeps_or_reads_the_clock() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let mut rust = Vec::new();
    files(&root.join("xtask/tests"), "rs", &mut rust);
    let mut python = Vec::new();
    for krate in std::fs::read_dir(root.join("crates")).unwrap() {
        let tests = krate.unwrap().path().join("tests");
        files(&tests, "rs", &mut rust);
        files(&tests, "py", &mut python);
    }
    // This file names the calls it looks for.
    let this = Path::new(file!()).file_name().unwrap();
    rust.retain(|p| !(p.starts_with(root.join("xtask/tests")) && p.file_name() == Some(this)));
    assert!(
        rust.len() > 10 && !python.is_empty(),
        "too few test files found under {}",
        root.display()
    );
    let mut found = Vec::new();
    for (list, calls, comment) in [(&rust, RUST, "//"), (&python, PYTHON, "#")] {
        for path in list {
            let src = std::fs::read_to_string(path).unwrap();
            for (line, call) in clock_calls(&src, calls, comment) {
                found.push(format!("{}:{line}: {call}", path.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "tests that wait a fixed time or read the clock (wait for a ready line or an \
         event instead):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_search_finds_a_sleep_and_a_clock() {
    let rust = "let t = std::time::Instant::now();\n// thread::sleep in a comment\nstd::thread::sleep(d);\n";
    assert_eq!(
        clock_calls(rust, RUST, "//"),
        [(1, "Instant::now"), (3, "thread::sleep")]
    );
    let python = "import time\ntime.sleep(0.5)  # wait\nassert time.monotonic() - t < 5\n";
    assert_eq!(
        clock_calls(python, PYTHON, "#"),
        [(2, "sleep("), (3, "time.monotonic(")]
    );
}
