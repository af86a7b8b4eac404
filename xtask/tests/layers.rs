//! No module of any crate of the workspace (every `crates/*`, and `xtask`) uses a module
//! that uses it back, directly or through others: one checker for every crate.
//!
//! Each file under a crate's `src/` is a node (`classify/cache.rs` is `classify::cache`);
//! a node
//! uses another when its code outside comments and `#[cfg(test)]` items names it by a
//! `crate::...`, `self::...` or `super::...` path, or names an item that the crate root
//! (`lib.rs`, `main.rs`) re-exports (`crate::Classify` uses `classify`). Declaring a child
//! module (`mod x;`) is
//! not a use. The layering this keeps is described in `docs/architecture.md`.
//!

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The source with line comments (doc comments included) and `#[cfg(test)]` items
/// removed.
fn strip(src: &str) -> String {
    let mut out = String::new();
    let mut lines = src.lines();
    while let Some(line) = lines.next() {
        if line.trim_start().starts_with("#[cfg(test)]") {
            // Skip the next item: up to its closing brace, or its semicolon.
            let mut depth = 0i32;
            let mut opened = false;
            for l in lines.by_ref() {
                let code = l.split("//").next().unwrap_or("");
                depth += code.matches('{').count() as i32 - code.matches('}').count() as i32;
                opened |= code.contains('{');
                if (opened && depth <= 0) || (!opened && code.trim_end().ends_with(';')) {
                    break;
                }
            }
            continue;
        }
        out.push_str(line.split("//").next().unwrap_or(""));
        out.push('\n');
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The paths that follow `prefix` (`crate::`, `self::`, `super::`), each as its
/// segments; a group `{a::B, c}` gives one path per item.
fn paths_after(code: &str, prefix: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(prefix) {
        let before = rest[..i].chars().next_back();
        rest = &rest[i + prefix.len()..];
        if before.is_some_and(|c| is_ident(c) || c == ':') {
            continue;
        }
        out.extend(parse_tree(rest));
    }
    out
}

/// The paths of a use tree at the start of `s`: `a::b::C` or `{a::B, c::{D, E}}`.
fn parse_tree(s: &str) -> Vec<Vec<String>> {
    let s = s.trim_start();
    if let Some(group) = s.strip_prefix('{') {
        let mut depth = 0;
        let mut items = Vec::new();
        let mut start = 0;
        for (i, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    items.push(&group[start..i]);
                    break;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    items.push(&group[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        return items
            .into_iter()
            .filter(|i| !i.trim().is_empty())
            .flat_map(parse_tree)
            .collect();
    }
    let mut segments = Vec::new();
    let mut rest = s;
    loop {
        let end = rest.find(|c: char| !is_ident(c)).unwrap_or(rest.len());
        if end == 0 {
            if rest.starts_with('{') {
                let inner = parse_tree(rest);
                if inner.is_empty() {
                    return vec![segments];
                }
                return inner
                    .into_iter()
                    .map(|tail| segments.iter().cloned().chain(tail).collect())
                    .collect();
            }
            break;
        }
        segments.push(rest[..end].to_string());
        match rest[end..].strip_prefix("::") {
            Some(r) => rest = r,
            None => break,
        }
    }
    vec![segments]
}

/// The module a path from the crate root names: the longest prefix that is a module,
/// or the module whose item the root re-exports.
fn resolve(
    segments: &[String],
    modules: &BTreeSet<String>,
    reexports: &BTreeMap<String, String>,
) -> Option<String> {
    (1..=segments.len())
        .rev()
        .map(|n| segments[..n].join("::"))
        .find(|m| modules.contains(m))
        .or_else(|| segments.first().and_then(|s| reexports.get(s).cloned()))
}

/// Every module file under `src` (the root file excluded) with its source.
fn sources(src: &Path, root: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("a readable source folder") {
            let path = entry.expect("a readable entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path.strip_prefix(src).expect("under src");
                let name = rel
                    .with_extension("")
                    .to_string_lossy()
                    .replace(['/', '\\'], "::");
                if name != root {
                    let text = std::fs::read_to_string(&path).expect("a readable file");
                    out.insert(name, text);
                }
            }
        }
    }
    out
}

/// The module graph of the crate whose root file is `src/<root>.rs`.
fn graph(src: &Path, root: &str) -> BTreeMap<String, BTreeSet<String>> {
    let files = sources(src, root);
    let modules: BTreeSet<String> = files.keys().cloned().collect();
    let root_src = std::fs::read_to_string(src.join(format!("{root}.rs"))).expect("a root");
    let mut reexports = BTreeMap::new();
    for path in paths_after(
        &strip(&root_src).replace("pub use ", "pub use crate::"),
        "crate::",
    ) {
        if let (Some(m), Some(item)) = (resolve(&path, &modules, &BTreeMap::new()), path.last()) {
            reexports.insert(item.clone(), m);
        }
    }
    let mut out = BTreeMap::new();
    for (name, text) in &files {
        let code = strip(text);
        let here: Vec<String> = name.split("::").map(String::from).collect();
        let mut uses = BTreeSet::new();
        let mut absolute = paths_after(&code, "crate::");
        for p in paths_after(&code, "self::") {
            absolute.push(here.iter().cloned().chain(p).collect());
        }
        for p in paths_after(&code, "super::") {
            absolute.push(here[..here.len() - 1].iter().cloned().chain(p).collect());
        }
        for p in absolute {
            if let Some(m) = resolve(&p, &modules, &reexports)
                && &m != name
            {
                uses.insert(m);
            }
        }
        out.insert(name.clone(), uses);
    }
    out
}

/// A cycle of the graph, if it has one, as the modules along it (the first repeated).
fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        done: &mut BTreeSet<String>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == node) {
            let mut c = path[i..].to_vec();
            c.push(node.to_string());
            return Some(c);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(c) = visit(next, graph, done, path) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| visit(n, graph, &mut done, &mut Vec::new()))
}

fn show(graph: &BTreeMap<String, BTreeSet<String>>) -> String {
    graph
        .iter()
        .map(|(m, uses)| {
            format!(
                "{m} -> {}\n",
                uses.iter().cloned().collect::<Vec<_>>().join(" ")
            )
        })
        .collect()
}

/// The first cycle among the modules of the crate whose sources are `src` (relative to
/// the workspace) and whose root file is `root`, shown with the graph; and how many
/// modules the crate has.
fn find_cycle(src: &str, root: &str) -> (usize, Option<String>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(src);
    let g = graph(&src, root);
    let found = cycle(&g).map(|c| {
        format!(
            "a cycle of modules in {}: {}\n\nthe graph:\n{}",
            src.display(),
            c.join(" -> "),
            show(&g)
        )
    });
    (g.len(), found)
}

/// Fails with the first cycle among the modules of the crate whose sources are `src`
/// (relative to the workspace) and whose root file is `root`.
fn assert_acyclic(src: &str, root: &str) {
    let (modules, found) = find_cycle(src, root);
    assert!(modules > 5, "no modules found in {src}");
    if let Some(c) = found {
        panic!("{c}");
    }
}

/// Every crate of the workspace: `xtask` and each folder of `crates/`, with the root
/// files its `src` has (`lib`, `main`; both when it has both).
fn every_crate() -> Vec<(String, &'static str)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out = vec![("xtask/src".to_string(), "main")];
    let mut names: Vec<String> = std::fs::read_dir(root.join("crates"))
        .expect("a readable crates folder")
        .map(|e| {
            e.expect("a readable entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    for name in names {
        for file in ["lib", "main"] {
            if root
                .join("crates")
                .join(&name)
                .join("src")
                .join(format!("{file}.rs"))
                .is_file()
            {
                out.push((format!("crates/{name}/src"), file));
            }
        }
    }
    out
}

#[test]
fn the_modules_of_xtask_use_each_other_without_cycles() {
    assert_acyclic("xtask/src", "main");
}

#[test]
fn the_modules_of_csql_use_each_other_without_cycles() {
    assert_acyclic("crates/csql/src", "lib");
}

/// Every crate, whatever its size: a new crate is checked without a line here.
#[test]
fn the_modules_of_every_crate_use_each_other_without_cycles() {
    let crates = every_crate();
    assert!(crates.len() >= 7, "{crates:?}");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut found = Vec::new();
    for (src, file) in &crates {
        let g = graph(&root.join(src), file);
        if let Some(c) = cycle(&g) {
            found.push(format!(
                "a cycle of modules in {src}: {}\n\nthe graph:\n{}",
                c.join(" -> "),
                show(&g)
            ));
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n\n"));
}

/// The checker sees uses through every kind of path, and finds a cycle when there is one.
#[test]
fn the_checker_finds_uses_and_cycles() {
    let code = strip(
        "use crate::{a::X, b::{Y, Z}};\nuse crate::c;\nfn f() { crate::d::g(); }\n\
         // crate::e in a comment\n#[cfg(test)]\nmod tests {\n    use crate::f;\n}\n",
    );
    let found: Vec<String> = paths_after(&code, "crate::")
        .into_iter()
        .map(|p| p.join("::"))
        .collect();
    assert_eq!(found, ["a::X", "b::Y", "b::Z", "c", "d::g"]);
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, to) in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")] {
        g.entry(from.into()).or_default().insert(to.into());
    }
    assert_eq!(cycle(&g).unwrap(), ["a", "b", "c", "a"]);
    g.get_mut("c").unwrap().remove("a");
    assert_eq!(cycle(&g), None);
}

/// The rows of the markdown table that follows `heading` in `doc`: each row's first
/// column's module (its first backticked name) and the backticked names of its last
/// column ("nothing" for none).
fn layer_table(doc: &str, heading: &str) -> Vec<(String, BTreeSet<String>)> {
    let start = doc
        .find(heading)
        .unwrap_or_else(|| panic!("no heading {heading:?} in the architecture"));
    let ticked = |cell: &str| -> Vec<String> {
        cell.split('`')
            .skip(1)
            .step_by(2)
            .map(String::from)
            .collect()
    };
    doc[start..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2)
        .map(|row| {
            let cells: Vec<&str> = row.trim_matches('|').split('|').collect();
            let module = ticked(cells[0])
                .into_iter()
                .next()
                .unwrap_or_else(|| panic!("a row of the layer table names no module: {row}"));
            let uses = ticked(cells[cells.len() - 1]).into_iter().collect();
            (module, uses)
        })
        .collect()
}

/// The layer table of `docs/architecture.md` is the code: one row per module of `csql`,
/// bottom up, each listing exactly the modules it uses, all of them in rows above it.
#[test]
fn the_layer_table_of_csql_is_the_code() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).expect("the doc");
    let table = layer_table(&doc, "#### Layers of `csql`");
    let g = graph(&root.join("crates/csql/src"), "lib");
    let mut problems = Vec::new();
    let mut above = BTreeSet::new();
    for (module, uses) in &table {
        match g.get(module) {
            None => problems.push(format!("`{module}` is in the table, not in the code")),
            Some(real) if real != uses => problems.push(format!(
                "`{module}` uses {} (the table says {})",
                show_set(real),
                show_set(uses)
            )),
            Some(_) => {}
        }
        let later: Vec<&String> = uses.iter().filter(|u| !above.contains(*u)).collect();
        if !later.is_empty() {
            problems.push(format!("`{module}` uses {later:?}, which are not above it"));
        }
        above.insert(module.clone());
    }
    for (module, uses) in &g {
        if !table.iter().any(|(m, _)| m == module) {
            problems.push(format!(
                "`{module}` is missing from the table; it uses {}",
                show_set(uses)
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "docs/architecture.md's layer table of csql differs from the code:\n{}",
        problems.join("\n")
    );
}

fn show_set(s: &BTreeSet<String>) -> String {
    if s.is_empty() {
        return "nothing".into();
    }
    s.iter()
        .map(|m| format!("`{m}`"))
        .collect::<Vec<_>>()
        .join(", ")
}
