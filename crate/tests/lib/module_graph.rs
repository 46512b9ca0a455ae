//! The crate's module graph, read from its sources: the top-level modules (`chain`, `machine`,
//! `schema` …) and which names which through a `crate::` path outside comments. The graph must
//! have no cycle, and `schema` (the ground floor of inputs) names only `error`.
//!
//! A path is `crate::m…` or `crate::{m…, n…}`; a root re-export (`crate::Error`) or an exported
//! macro (`crate::inputs!`) counts as the module that defines it.

#![allow(clippy::unwrap_used)] // reading the crate's own sources: a failure should stop the test

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

use crate::common::rust_files;

type Graph = BTreeMap<String, BTreeSet<String>>;

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The top-level module a file belongs to (`None` for `lib.rs`).
fn module_of(file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src()).unwrap();
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    match first.strip_suffix(".rs") {
        Some("lib") => None,
        Some(m) => Some(m.to_string()),
        None => Some(first),
    }
}

/// The text without `//` comments (doc comments included) and `/* */` blocks.
fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |i| &r[i..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |i| &r[i + 2..]);
        } else {
            let c = rest.chars().next().unwrap();
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The first name of every `crate::` path in `code` (each item of a `crate::{…}` group).
fn crate_names(code: &str) -> Vec<String> {
    let mut names = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        if code[..i].chars().next_back().is_some_and(is_ident) {
            continue;
        }
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut item_start = true;
            for (j, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if item_start && is_ident(c) => {
                        let name: String =
                            group[j..].chars().take_while(|&c| is_ident(c)).collect();
                        names.push(name);
                        item_start = false;
                    }
                    _ => {}
                }
            }
        } else {
            names.push(rest.chars().take_while(|&c| is_ident(c)).collect());
        }
    }
    names
}

/// Root names that stand for a module: `pub use m::{A, B}` in `lib.rs` and exported macros.
fn aliases(files: &[(Option<String>, String)]) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for (module, code) in files {
        match module {
            None => {
                for line in code.lines() {
                    let Some(rest) = line.trim().strip_prefix("pub use ") else {
                        continue;
                    };
                    let Some((m, items)) = rest.trim_end_matches(';').split_once("::") else {
                        continue;
                    };
                    for item in items.trim_matches(|c| c == '{' || c == '}').split(',') {
                        out.insert(item.trim().to_string(), m.to_string());
                    }
                }
            }
            Some(m) => {
                for (i, _) in code.match_indices("#[macro_export]") {
                    let after = &code[i..];
                    if let Some(j) = after.find("macro_rules!") {
                        let name: String = after[j + "macro_rules!".len()..]
                            .trim_start()
                            .chars()
                            .take_while(|&c| is_ident(c))
                            .collect();
                        out.insert(name, m.clone());
                    }
                }
            }
        }
    }
    out
}

/// The graph of top-level modules: `m → n` when a file of `m` names `crate::n`.
fn module_graph() -> Graph {
    let mut paths = Vec::new();
    rust_files(&src(), &mut paths);
    let files: Vec<(Option<String>, String)> = paths
        .iter()
        .map(|p| {
            (
                module_of(p),
                strip_comments(&fs::read_to_string(p).unwrap()),
            )
        })
        .collect();
    let modules: BTreeSet<String> = files.iter().filter_map(|(m, _)| m.clone()).collect();
    let aliases = aliases(&files);
    let mut graph: Graph = modules
        .iter()
        .map(|m| (m.clone(), BTreeSet::new()))
        .collect();
    for (module, code) in &files {
        let Some(from) = module else { continue };
        for name in crate_names(code) {
            let to = aliases.get(&name).unwrap_or(&name);
            if modules.contains(to) && to != from {
                graph.get_mut(from).unwrap().insert(to.clone());
            }
        }
    }
    graph
}

/// A cycle of `graph` as a path `a → … → a`, if there is one.
fn find_cycle(graph: &Graph) -> Option<Vec<String>> {
    fn visit(
        graph: &Graph,
        node: &str,
        stack: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(at) = stack.iter().position(|n| n == node) {
            let mut cycle = stack[at..].to_vec();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if done.contains(node) {
            return None;
        }
        stack.push(node.to_string());
        for next in &graph[node] {
            if let Some(c) = visit(graph, next, stack, done) {
                return Some(c);
            }
        }
        stack.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| visit(graph, n, &mut Vec::new(), &mut done))
}

#[test]
fn the_reader_finds_known_edges() {
    // Guards against a graph that is acyclic only because the reader found nothing.
    let g = module_graph();
    for (from, to) in [
        ("chain", "rotary"),
        ("machine", "chain"),
        ("machine", "schema"),
        ("rotary", "schema"),
        ("cubic", "machine"),
        ("toolpath", "nonlinear"),
        ("schema", "error"),
    ] {
        assert!(g[from].contains(to), "{from} → {to} not found: {g:?}");
    }
}

#[test]
fn the_module_graph_has_no_cycle() {
    let g = module_graph();
    if let Some(cycle) = find_cycle(&g) {
        panic!("module cycle: {}", cycle.join(" → "));
    }
}

#[test]
fn schema_names_no_module_but_error() {
    let g = module_graph();
    let above: Vec<&String> = g["schema"].iter().filter(|m| *m != "error").collect();
    assert!(above.is_empty(), "schema names {above:?}");
    // Doc links too: the schema's text never names the machine.
    let mut files = Vec::new();
    rust_files(&src().join("schema"), &mut files);
    for f in files {
        let text = fs::read_to_string(&f).unwrap();
        assert!(
            !text.contains("crate::machine"),
            "{} names crate::machine",
            f.display()
        );
    }
}

#[test]
fn a_cycle_is_found() {
    let mut g = Graph::new();
    for (a, b) in [
        ("chain", "rotary"),
        ("rotary", "schema"),
        ("schema", "machine"),
    ] {
        g.entry(a.into()).or_default().insert(b.into());
        g.entry(b.into()).or_default();
    }
    assert_eq!(find_cycle(&g), None);
    g.get_mut("machine").unwrap().insert("chain".into());
    assert_eq!(
        find_cycle(&g).unwrap(),
        ["chain", "rotary", "schema", "machine", "chain"]
    );
    assert_eq!(
        crate_names("use crate::{chain::X, machine::{a, b}};\nuse crate::error::Result;"),
        ["chain", "machine", "error"]
    );
}
