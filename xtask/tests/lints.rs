//! Lints are silenced only by expectation: `#[expect(lint, reason = "...")]`, which fails
//! the build once the lint no longer fires, instead of `#[allow]`, which outlives its
//! cause. The one exception is a test module shared by several test programs
//! (`tests/common/mod.rs`), where some programs use all of it and an expectation would
//! fail there; it says so in its reason.

use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, build output aside.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        if path.is_dir() {
            if name != "target" && !name.to_string_lossy().starts_with('.') {
                rust_files(&path, out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The attributes `#[allow(...)]` / `#![allow(...)]` and `#[expect(...)]` of `src`,
/// each with the line it starts on and its text up to the closing `)]`.
fn attributes<'a>(src: &'a str, name: &str) -> Vec<(usize, &'a str)> {
    let mut found = Vec::new();
    for opening in [format!("#[{name}("), format!("#![{name}(")] {
        let mut from = 0;
        while let Some(at) = src[from..].find(&opening) {
            let start = from + at;
            let end = src[start..].find(")]").map_or(src.len(), |e| start + e + 2);
            let line = src[..start].matches('\n').count() + 1;
            found.push((line, &src[start..end]));
            from = end;
        }
    }
    found
}

#[test]
fn lints_are_silenced_by_expectations_with_reasons() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in ["crates", "xtask", "tests"] {
        rust_files(&root.join(dir), &mut files);
    }
    assert!(files.len() > 50, "{} files", files.len());
    let mut wrong = Vec::new();
    for file in &files {
        let src = std::fs::read_to_string(file).expect("a readable source");
        let shown = file.strip_prefix(&root).unwrap_or(file).display();
        let shared = file.ends_with("tests/common/mod.rs");
        // This file names the attributes it looks for.
        if file.ends_with("xtask/tests/lints.rs") {
            continue;
        }
        for (line, text) in attributes(&src, "allow") {
            if !(shared && text.contains("reason = ")) {
                wrong.push(format!(
                    "{shown}:{line}: {text}: write #[expect(..., reason = \"...\")]"
                ));
            }
        }
        for (line, text) in attributes(&src, "expect") {
            if !text.contains("reason = ") {
                wrong.push(format!(
                    "{shown}:{line}: {text}: give the expectation its reason"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn the_scan_finds_allows_and_expectations_across_lines() {
    let src = "#[allow(dead_code)]\nfn a() {}\n#[expect(\n    clippy::x,\n    reason = \"r\"\n)]\nfn b() {}\n#![allow(unused)]\n";
    assert_eq!(
        attributes(src, "allow"),
        vec![(1, "#[allow(dead_code)]"), (8, "#![allow(unused)]")]
    );
    assert_eq!(attributes(src, "expect").len(), 1);
    assert_eq!(attributes(src, "expect")[0].0, 3);
}
