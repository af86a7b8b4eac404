//! No module of any crate of the workspace (every `crates/*`, and `xtask`) uses a module
//! that uses it back, directly or through others: one checker for every crate. And the
//! same holds of its top-level modules, each folder with everything under it: no folder
//! (or file beside the folders) uses one that uses it back.
//!
//! Each file under a crate's `src/` is a node (`classify/cache.rs` is `classify::cache`,
//! `testcost/mod.rs` is `testcost`); a node
//! uses another when its code outside comments and `#[cfg(test)]` items names it by a
//! `crate::...`, `self::...` or `super::...` path, or names an item that the crate root
//! (`lib.rs`, `main.rs`) re-exports (`crate::Classify` uses `classify`). Declaring a child
//! module (`mod x;`) is
//! not a use. For the folders, each node is collapsed to its top-level ancestor
//! (`agent::trials` is `agent`) and a use between two of them is kept when they differ.
//! The layering this keeps is described in `docs/architecture.md`.
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
                // A folder's `mod.rs` is the folder's module.
                let name = name.strip_suffix("::mod").unwrap_or(&name).to_string();
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
    let root_src = std::fs::read_to_string(src.join(format!("{root}.rs"))).expect("a root");
    graph_of(&sources(src, root), &root_src)
}

/// The module graph of a crate whose modules are `files` (each module's source by its
/// path, the root excluded) and whose root file is `root_src`.
fn graph_of(
    files: &BTreeMap<String, String>,
    root_src: &str,
) -> BTreeMap<String, BTreeSet<String>> {
    let modules: BTreeSet<String> = files.keys().cloned().collect();
    let mut reexports = BTreeMap::new();
    for path in paths_after(
        &strip(root_src).replace("pub use ", "pub use crate::"),
        "crate::",
    ) {
        if let (Some(m), Some(item)) = (resolve(&path, &modules, &BTreeMap::new()), path.last()) {
            reexports.insert(item.clone(), m);
        }
    }
    let mut out = BTreeMap::new();
    for (name, text) in files {
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

/// A module's top-level ancestor: the folder it is in (`agent::trials` is `agent`), or
/// itself for a file beside the folders.
fn top(module: &str) -> &str {
    module.split("::").next().unwrap_or(module)
}

/// The graph of the top-level modules: every module collapsed to its top-level
/// ancestor, a use kept when the two differ.
fn folders(graph: &BTreeMap<String, BTreeSet<String>>) -> BTreeMap<String, BTreeSet<String>> {
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (module, uses) in graph {
        let from = top(module);
        let entry = out.entry(from.to_string()).or_default();
        entry.extend(
            uses.iter()
                .map(|u| top(u))
                .filter(|to| *to != from)
                .map(String::from),
        );
    }
    out
}

/// The first cycle among the folders of a crate whose module graph is `graph`, with
/// the uses of modules behind each of its steps (`agent -> judging: agent::trials ->
/// judging::judge`) and the graph of folders.
fn folder_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<String> {
    let g = folders(graph);
    let c = cycle(&g)?;
    let steps: String = c
        .windows(2)
        .map(|w| {
            let uses: Vec<String> = graph
                .iter()
                .filter(|(m, _)| top(m) == w[0])
                .flat_map(|(m, uses)| {
                    uses.iter()
                        .filter(|u| top(u) == w[1])
                        .map(move |u| format!("{m} -> {u}"))
                })
                .collect();
            format!("  {} -> {}: {}\n", w[0], w[1], uses.join(", "))
        })
        .collect();
    Some(format!(
        "{}\n\nthrough:\n{steps}\nthe graph of folders:\n{}",
        c.join(" -> "),
        show(&g)
    ))
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

/// Every crate, at the level of its folders: no folder (or file beside the folders)
/// uses another that uses it back, directly or through others.
#[test]
fn the_folders_of_every_crate_use_each_other_without_cycles() {
    let crates = every_crate();
    assert!(crates.len() >= 7, "{crates:?}");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let found: Vec<String> = crates
        .iter()
        .filter_map(|(src, file)| {
            folder_cycle(&graph(&root.join(src), file))
                .map(|c| format!("a cycle of folders in {src}: {c}"))
        })
        .collect();
    assert!(found.is_empty(), "{}", found.join("\n\n"));
}

/// A made-up crate, written under the target folder, whose files use each other without
/// a cycle while its folders do: `a::x` uses `b::y` and `b::z` uses `a::w`. The files
/// pass, the folders are refused with the uses behind the cycle. A folder's `mod.rs` is
/// the folder's module, whose `self::` paths are the folder's.
#[test]
fn a_cycle_of_folders_is_found_where_the_files_have_none() {
    let src = Path::new(env!("CARGO_TARGET_TMPDIR")).join("layers-made-up/src");
    // Left over from an earlier run, or absent.
    let _ = std::fs::remove_dir_all(&src);
    let files = [
        ("lib.rs", "mod a;\nmod b;\nmod c;\n"),
        ("a.rs", "pub mod w;\npub mod x;\n"),
        ("a/w.rs", "pub struct W;\n"),
        ("a/x.rs", "use crate::b::y::Y;\npub fn f(_: Y) {}\n"),
        ("b/mod.rs", "pub mod y;\npub mod z;\npub use self::y::Y;\n"),
        ("b/y.rs", "pub struct Y;\n"),
        ("b/z.rs", "pub fn g(_: crate::a::w::W) {}\n"),
        ("c.rs", "pub mod v;\npub struct C(pub super::a::w::W);\n"),
        ("c/v.rs", "use super::C;\n"),
    ];
    for (path, text) in files {
        let path = src.join(path);
        std::fs::create_dir_all(path.parent().expect("a folder")).expect("a writable folder");
        std::fs::write(&path, text).expect("a writable file");
    }
    let g = graph(&src, "lib");
    assert_eq!(
        show(&g),
        "a -> \na::w -> \na::x -> b::y\nb -> b::y\nb::y -> \nb::z -> a::w\nc -> a::w\nc::v -> c\n"
    );
    assert_eq!(cycle(&g), None);
    assert_eq!(show(&folders(&g)), "a -> b\nb -> a\nc -> a\n");
    let found = folder_cycle(&g).expect("the folders' cycle");
    assert!(found.starts_with("a -> b -> a"), "{found}");
    assert!(found.contains("a -> b: a::x -> b::y"), "{found}");
    assert!(found.contains("b -> a: b::z -> a::w"), "{found}");
    // Without `b::z`'s use of `a`, the folders are layers: a, then b and c.
    let mut layered = sources(&src, "lib");
    layered.insert("b::z".into(), "pub fn g() {}\n".into());
    let g = graph_of(&layered, files[0].1);
    assert_eq!(folder_cycle(&g), None, "{}", show(&folders(&g)));
    assert_eq!(show(&folders(&g)), "a -> b\nb -> \nc -> a\n");
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

/// How a table of `docs/architecture.md` (rows bottom up, each a module and the modules
/// it uses) differs from the graph `g`: a row's uses that are not exactly the code's,
/// uses not listed above the row, rows that are not modules and modules without a row.
fn table_problems(
    table: &[(String, BTreeSet<String>)],
    g: &BTreeMap<String, BTreeSet<String>>,
) -> Vec<String> {
    let mut problems = Vec::new();
    let mut above = BTreeSet::new();
    for (module, uses) in table {
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
    for (module, uses) in g {
        if !table.iter().any(|(m, _)| m == module) {
            problems.push(format!(
                "`{module}` is missing from the table; it uses {}",
                show_set(uses)
            ));
        }
    }
    problems
}

/// The module table of `docs/architecture.md` is the code: one row per module of `csql`,
/// bottom up, each listing exactly the modules it uses, all of them in rows above it.
#[test]
fn the_module_table_of_csql_is_the_code() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).expect("the doc");
    let table = layer_table(&doc, "#### Modules of `csql`");
    let g = graph(&root.join("crates/csql/src"), "lib");
    let problems = table_problems(&table, &g);
    assert!(
        problems.is_empty(),
        "docs/architecture.md's module table of csql differs from the code:\n{}",
        problems.join("\n")
    );
}

/// The layers of `csql` stated in `docs/architecture.md` are the code: one row per
/// top-level module (a folder with everything under it, or a file beside the folders),
/// bottom up, each listing exactly the layers it uses, all of them in rows above it.
#[test]
fn the_layers_of_csql_are_the_code() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).expect("the doc");
    let table = layer_table(&doc, "#### Layers of `csql`");
    assert!(table.len() >= 8, "{table:?}");
    let g = folders(&graph(&root.join("crates/csql/src"), "lib"));
    let problems = table_problems(&table, &g);
    assert!(
        problems.is_empty(),
        "docs/architecture.md's layers of csql differ from the code:\n{}",
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
