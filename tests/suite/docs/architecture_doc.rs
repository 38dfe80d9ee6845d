//! ARCHITECTURE.md names every source file, and only files that exist.
//!
//! ARCHITECTURE.md gives one line to each `.rs` file under `src/`, named by its path relative
//! to `src/` (`sim/world.rs`; `src/sim/world.rs` is read the same way). These tests fail when a
//! file is added, moved or renamed under `src/` without its line, and when a line names a path
//! under `src/` that no longer exists. Paths under `tests/`, `benches/` and the other top-level
//! folders are not source files and are not checked here.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

/// Top-level folders whose `.rs` files are not under `src/`.
const OTHER_ROOTS: &[&str] = &[
    "tests", "benches", "examples", "web", "docs", "levels", "target",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir`, as a path relative to `base` with `/` between components.
fn rust_files(base: &Path, dir: &Path, out: &mut BTreeSet<String>) {
    let entries = fs::read_dir(dir).unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(base, &path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            let relative = path.strip_prefix(base).expect("a path under src/");
            let parts: Vec<String> = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            out.insert(parts.join("/"));
        }
    }
}

fn source_files() -> BTreeSet<String> {
    let src = root().join("src");
    let mut files = BTreeSet::new();
    rust_files(&src, &src, &mut files);
    assert!(
        !files.is_empty(),
        "no .rs file found under {}",
        src.display()
    );
    files
}

fn architecture_text() -> String {
    let path = root().join("ARCHITECTURE.md");
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

fn is_path_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/')
}

/// The `.rs` paths the text names under `src/`, relative to `src/`: every longest run of path
/// characters that ends in `.rs`, with a leading `src/` taken off, except runs that start in
/// another top-level folder (`tests/...`, `benches/...`) or go up (`../`).
fn named_source_paths(text: &str) -> BTreeSet<String> {
    let mut named = BTreeSet::new();
    for token in text.split(|c: char| !is_path_char(c)) {
        // A sentence may end right after a path: "... in sim/world.rs."
        let token = token.trim_end_matches('.');
        if !token.ends_with(".rs") || token.len() <= 3 {
            continue;
        }
        let token = token.strip_prefix("./").unwrap_or(token);
        if token.starts_with("../") || token.starts_with('/') {
            continue;
        }
        if let Some(inside) = token.strip_prefix("src/") {
            named.insert(inside.to_string());
            continue;
        }
        let first = token.split('/').next().unwrap_or("");
        if token.contains('/') && OTHER_ROOTS.contains(&first) {
            continue;
        }
        named.insert(token.to_string());
    }
    named
}

#[test]
fn every_source_file_is_named_in_architecture_md() {
    let named = named_source_paths(&architecture_text());
    let missing: Vec<String> = source_files()
        .into_iter()
        .filter(|f| !named.contains(f))
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md has no line for {} file(s) under src/ (name each by its path relative \
         to src/, e.g. sim/world.rs):\n  {}",
        missing.len(),
        missing.join("\n  ")
    );
}

#[test]
fn every_source_path_named_in_architecture_md_exists() {
    let files = source_files();
    let stale: Vec<String> = named_source_paths(&architecture_text())
        .into_iter()
        .filter(|p| !files.contains(p))
        .collect();
    assert!(
        stale.is_empty(),
        "ARCHITECTURE.md names {} path(s) that are not files under src/ (moved, renamed or \
         misspelt?):\n  {}",
        stale.len(),
        stale.join("\n  ")
    );
}

#[test]
fn the_path_reader_reads_whole_paths() {
    let named = named_source_paths(
        "`src/sim/world.rs`, sim/readings.rs. [x](src/lib.rs) tests/suite/runner/cli_io.rs benches/core.rs \
         ../shared/a.rs analysis::frame and main.rs",
    );
    let expected: BTreeSet<String> = ["sim/world.rs", "sim/readings.rs", "lib.rs", "main.rs"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(named, expected);
}
