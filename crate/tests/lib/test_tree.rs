//! Every test file is compiled. The integration tests are modules of one binary each
//! (`crate/tests/engine.rs`, `wasm/tests/wasm/main.rs`), and cargo no longer finds a file in a
//! test folder by itself: a file without its `mod` line would never be built or run, silently.

#![allow(clippy::unwrap_used)] // reading the crate's own sources: a failure should stop the test

use std::collections::BTreeSet;
use std::fs;
use std::path::Path;

use crate::common::rust_files;

/// The `.rs` files under `dir` (relative, `/`-separated, without `.rs`), but those under the
/// folders named in `skip`.
fn files(dir: &Path, skip: &[&str]) -> BTreeSet<String> {
    let mut paths = Vec::new();
    rust_files(dir, &mut paths);
    paths
        .iter()
        .map(|p| {
            let rel = p.strip_prefix(dir).unwrap().with_extension("");
            let parts: Vec<_> = rel
                .components()
                .map(|c| c.as_os_str().to_str().unwrap())
                .collect();
            parts.join("/")
        })
        .filter(|f| !skip.iter().any(|s| f.starts_with(&format!("{s}/"))))
        .collect()
}

/// The module files a root declares: `mod a;` at the top level is `a` (or `a/mod`), `mod b;`
/// inside `mod a { … }` is `a/b`. Reads only what these roots hold: `mod` lines and one level of
/// inline modules.
fn declared(root: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut inside: Option<String> = None;
    for line in root.lines().map(str::trim) {
        if let Some(name) = line.strip_prefix("mod ").and_then(|l| l.strip_suffix(" {")) {
            inside = Some(name.to_string());
        } else if line == "}" {
            inside = None;
        } else if let Some(name) = line.strip_prefix("mod ").and_then(|l| l.strip_suffix(';')) {
            out.insert(match &inside {
                Some(parent) => format!("{parent}/{name}"),
                None => name.to_string(),
            });
        }
    }
    out
}

/// `a/mod` and `a` name the same module.
fn modules(files: BTreeSet<String>) -> BTreeSet<String> {
    files
        .into_iter()
        .map(|f| f.strip_suffix("/mod").map(str::to_string).unwrap_or(f))
        .collect()
}

#[test]
fn every_engine_test_file_is_a_module_of_the_engine_binary() {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    // The helpers' folders are declared as a whole (`mod common;`); their own files by them.
    let mut found = files(&tests, &["common", "probe_common", "data"]);
    found.remove("engine");
    let mut found = modules(found);
    found.insert("common".into());
    found.insert("probe_common".into());
    let root = fs::read_to_string(tests.join("engine.rs")).unwrap();
    assert_eq!(
        declared(&root),
        found,
        "crate/tests/engine.rs against the files under crate/tests"
    );
    assert!(found.contains("lib/test_tree"), "the walk found this file");
}

#[test]
fn every_binding_test_file_is_a_module_of_the_wasm_binary() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../wasm/tests/wasm");
    let mut found = files(&dir, &[]);
    found.remove("main");
    let root = fs::read_to_string(dir.join("main.rs")).unwrap();
    assert_eq!(
        declared(&root),
        modules(found),
        "wasm/tests/wasm/main.rs against its folder"
    );
    // Nothing else in wasm/tests: a file there would be a test binary of its own.
    let others: Vec<_> = fs::read_dir(dir.join(".."))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        others,
        ["wasm"],
        "wasm/tests holds only the folder of its one binary"
    );
}
