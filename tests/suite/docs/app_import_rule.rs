//! The import rule of a folder: inside `src/app` (the window) and `src/questions` (the questions),
//! imports run one way, down, and make no circle.
//!
//! In `src/questions` that is: `probe` -> `dispatch` (the dispatcher) -> the quantity families,
//! each with its own state -> the plain types they share (`meter`, `sample`, `level_facts`,
//! `contact_reading`, ...). A family that took a helper from another family, or a shared type
//! that named a family, would close a circle (issue 44: `meter.rs` held every family's state and
//! routed to the families, which imported it back, a circle of 14 files).
//!
//! Each file under the folder is a module (`panels/mod.rs` is `app::panels`, `panels/plots.rs` is
//! `app::panels::plots`). An *arrow* runs from a file to the module a path in its code names: a
//! `use` line (braces expanded) or a path written in the code that starts with `super::`,
//! `self::`, `crate::app::` (`crate::questions::`) or, in a `mod.rs`, a module that file declares; the path is followed
//! through modules for as long as its segments name modules, and the arrow ends at the last one
//! (`super::super::run::Run` from `panels/playback.rs` ends at `app/run.rs`). Only code counts:
//! comments and string literals are skipped.
//!
//! An arrow **runs back up** when it ends
//! - at an ancestor of the file: a module whose folder holds the file (`app/mod.rs` for every file
//!   of the window, `panels/mod.rs` for the panels), which is the case when the file names an
//!   item defined in that `mod.rs` (`super::UiState` from a panel, `super::empty_scene` from
//!   `web.rs`), or a name that `mod.rs` only re-exports: a `mod.rs` declares and assembles its
//!   children and sits above them;
//! - (src/app only) in `app::panels` from a file outside it other than the window's assembly (`app/mod.rs`,
//!   `sandbox.rs` and `web.rs`, which put the panels in the app): the panels are the top floor of
//!   the window, nothing below them may reach into them (`crate::app::panels::` from below).
//!
//! A **circle** is a set of files each reaching the others by arrows (a strongly connected set of
//! the arrow graph, self-references left out). The test lists every back-up arrow with its file
//! and line and every circle with the arrows inside it, and fails on any.
//!
//! A name shared by the window and its panels goes below both (`app/ui.rs` for the egui helpers,
//! `panels/state.rs` for the panels' state), never into the `mod.rs` above them.

use super::source_scan::{code_lines, rust_files};
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

/// The files allowed to reach into `app::panels` from outside it: they put the panels in the app.
const ASSEMBLY: &[&str] = &["src/app/mod.rs", "src/app/sandbox.rs", "src/app/web.rs"];

/// The module path of a file under `src/` (`app/panels/mod.rs` -> ["app", "panels"]).
fn module_of(rel: &str) -> Vec<String> {
    let rel = rel.trim_start_matches("src/").trim_end_matches(".rs");
    let mut m: Vec<String> = rel.split('/').map(str::to_string).collect();
    if m.last().is_some_and(|l| l == "mod") {
        m.pop();
    }
    m
}

fn is_ident(ch: char) -> bool {
    ch.is_alphanumeric() || ch == '_'
}

/// The paths of the `use` declarations in `code` (one string, comments and strings blanked), braces
/// expanded, each with the byte offset of its `use`.
fn use_paths(code: &str) -> Vec<(usize, Vec<String>)> {
    let b = code.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(k) = code[i..].find("use ") {
        let at = i + k;
        i = at + 4;
        let before_ok = at == 0 || !is_ident(b[at - 1] as char);
        if !before_ok {
            continue;
        }
        let Some(end) = code[i..].find(';') else {
            break;
        };
        // `name as alias`: the alias goes; then the spaces.
        let mut words = code[i..i + end].split_whitespace().peekable();
        let mut body = String::new();
        while let Some(w) = words.next() {
            if w == "as" {
                words.next();
            } else {
                body.push_str(w);
            }
        }
        for p in expand(&body) {
            out.push((at, p.split("::").map(str::to_string).collect()));
        }
        i += end;
    }
    out
}

/// `a::{b, c::{d, e}}` -> [a::b, a::c::d, a::c::e] (whitespace already removed).
fn expand(s: &str) -> Vec<String> {
    let s = s.trim_start_matches("::");
    let Some(open) = s.find('{') else {
        return vec![s.to_string()];
    };
    let prefix = &s[..open];
    let inner = &s[open + 1..s.rfind('}').unwrap_or(s.len())];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (k, ch) in inner.char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty())
        .flat_map(|p| expand(p).into_iter().map(move |q| format!("{prefix}{q}")))
        .collect()
}

/// Paths written in the code (not in `use` lines): from `super::`, `self::`, `crate::ROOT::` (ROOT
/// the folder's module, `app`) or a child module of `mod.rs` files (`children`), each with its
/// byte offset.
fn code_paths(code: &str, root: &str, children: &BTreeSet<String>) -> Vec<(usize, Vec<String>)> {
    let c: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let boundary = i == 0 || !(is_ident(c[i - 1]) || c[i - 1] == ':');
        if boundary && is_ident(c[i]) {
            let mut segs = Vec::new();
            let mut k = i;
            loop {
                let s = k;
                while k < c.len() && is_ident(c[k]) {
                    k += 1;
                }
                segs.push(c[s..k].iter().collect::<String>());
                if k + 2 < c.len() && c[k] == ':' && c[k + 1] == ':' && is_ident(c[k + 2]) {
                    k += 2;
                } else {
                    break;
                }
            }
            let first = segs[0].as_str();
            let starts = matches!(first, "super" | "self")
                || (first == "crate" && segs.get(1).is_some_and(|s| s == root))
                || (segs.len() > 1 && children.contains(first));
            if starts && segs.len() > 1 {
                out.push((i, segs));
            }
            i = k.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// Where a path written in the module `from` ends: the module it names last (following its
/// segments while they name modules), or None for a path outside the folder's module `root`.
fn resolve(
    from: &[String],
    segs: &[String],
    root: &str,
    modules: &BTreeSet<Vec<String>>,
) -> Option<Vec<String>> {
    let mut cur: Vec<String>;
    let mut rest = segs;
    match segs.first()?.as_str() {
        "crate" => {
            if segs.get(1)? != root {
                return None;
            }
            cur = vec![root.into()];
            rest = &segs[2..];
        }
        "super" | "self" => {
            cur = from.to_vec();
            while let Some(s) = rest.first() {
                match s.as_str() {
                    "super" => {
                        cur.pop();
                    }
                    "self" => {}
                    _ => break,
                }
                rest = &rest[1..];
            }
        }
        first => {
            let mut child = from.to_vec();
            child.push(first.to_string());
            if !modules.contains(&child) {
                return None;
            }
            cur = child;
            rest = &segs[1..];
        }
    }
    for s in rest {
        if s == "self" {
            continue;
        }
        let mut next = cur.clone();
        next.push(s.clone());
        if modules.contains(&next) {
            cur = next;
        } else {
            break;
        }
    }
    cur.first().is_some_and(|f| f == root).then_some(cur)
}

/// One arrow: from a file to a module, where it is written.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Arrow {
    from: String,
    line: usize,
    to: Vec<String>,
    path: String,
}

/// The arrows of a folder's files (`files`: path relative to the repository, code), the folder
/// being the module `root` (`app`).
fn arrows(files: &[(String, String)], root: &str) -> Vec<Arrow> {
    let modules: BTreeSet<Vec<String>> = files.iter().map(|(p, _)| module_of(p)).collect();
    let mut out = Vec::new();
    for (rel, code) in files {
        let me = module_of(rel);
        let children: BTreeSet<String> = if rel.ends_with("mod.rs") {
            modules
                .iter()
                .filter(|m| m.len() == me.len() + 1 && m.starts_with(&me))
                .map(|m| m.last().unwrap().clone())
                .collect()
        } else {
            BTreeSet::new()
        };
        let line_of = |at: usize| code[..at].matches('\n').count() + 1;
        let mut found = use_paths(code);
        // A path in a `use` line is seen once, there; the rest of the code after.
        let uses: Vec<(usize, usize)> = found
            .iter()
            .map(|(at, _)| (*at, at + code[*at..].find(';').unwrap_or(0)))
            .collect();
        for (at, segs) in code_paths(code, root, &children) {
            if !uses.iter().any(|(a, b)| (*a..=*b).contains(&at)) {
                found.push((at, segs));
            }
        }
        for (at, segs) in found {
            if let Some(to) = resolve(&me, &segs, root, &modules) {
                if to != me {
                    out.push(Arrow {
                        from: rel.clone(),
                        line: line_of(at),
                        to,
                        path: segs.join("::"),
                    });
                }
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The arrows that run back up (see the file's doc), as `file:line: path (why)`.
fn back_up(arrows: &[Arrow]) -> Vec<String> {
    let mut bad = Vec::new();
    for a in arrows {
        let me = module_of(&a.from);
        if a.to.len() < me.len() && me.starts_with(&a.to) {
            bad.push(format!(
                "{}:{}: {} (names {}, a module above it: move the name below both)",
                a.from,
                a.line,
                a.path,
                a.to.join("::")
            ));
        } else if a.to.len() >= 2
            && a.to[0] == "app"
            && a.to[1] == "panels"
            && !(me.len() >= 2 && me[1] == "panels")
            && !ASSEMBLY.contains(&a.from.as_str())
        {
            bad.push(format!(
                "{}:{}: {} (reaches into the panels from below them)",
                a.from, a.line, a.path
            ));
        }
    }
    bad
}

/// The circles of the arrow graph between files (strongly connected sets of two files or more),
/// each with the arrows inside it.
fn circles(files: &[(String, String)], arrows: &[Arrow]) -> Vec<Vec<String>> {
    let file_of: BTreeMap<Vec<String>, String> = files
        .iter()
        .map(|(p, _)| (module_of(p), p.clone()))
        .collect();
    let names: Vec<&String> = files.iter().map(|(p, _)| p).collect();
    let index: BTreeMap<&String, usize> = names.iter().enumerate().map(|(i, p)| (*p, i)).collect();
    let mut next: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); names.len()];
    for a in arrows {
        if let (Some(&f), Some(t)) = (index.get(&a.from), file_of.get(&a.to)) {
            let t = index[t];
            if t != f {
                next[f].insert(t);
            }
        }
    }
    // Reachability by repeated search: a few dozen files.
    let reach = |s: usize| {
        let mut seen = BTreeSet::from([s]);
        let mut todo = vec![s];
        while let Some(u) = todo.pop() {
            for &v in &next[u] {
                if seen.insert(v) {
                    todo.push(v);
                }
            }
        }
        seen
    };
    let all: Vec<BTreeSet<usize>> = (0..names.len()).map(reach).collect();
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for s in 0..names.len() {
        if done.contains(&s) {
            continue;
        }
        let set: BTreeSet<usize> = all[s]
            .iter()
            .copied()
            .filter(|&t| all[t].contains(&s))
            .collect();
        done.extend(set.iter().copied());
        if set.len() > 1 {
            let mut lines: Vec<String> = set.iter().map(|&k| names[k].clone()).collect();
            lines.sort();
            for a in arrows {
                let inside = |p: &String| index.get(p).is_some_and(|k| set.contains(k));
                if inside(&a.from) && file_of.get(&a.to).is_some_and(inside) {
                    lines.push(format!("  {}:{} -> {}", a.from, a.line, a.path));
                }
            }
            out.push(lines);
        }
    }
    out
}

/// `code` without its inline modules (`mod tests { .. }`, the unit tests: their `super` is the
/// file itself), their lines kept blank.
fn without_inline_modules(code: &str) -> String {
    let c: Vec<char> = code.chars().collect();
    let mut out: Vec<char> = c.clone();
    let mut i = 0;
    while i + 4 < c.len() {
        let boundary = i == 0 || !is_ident(c[i - 1]);
        if boundary && c[i..].starts_with(&['m', 'o', 'd', ' ']) {
            let mut k = i + 4;
            while k < c.len() && (is_ident(c[k]) || c[k] == ' ') {
                k += 1;
            }
            if c.get(k) == Some(&'{') {
                let mut depth = 0;
                let start = i;
                while k < c.len() {
                    match c[k] {
                        '{' => depth += 1,
                        '}' => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                    k += 1;
                }
                for ch in out.iter_mut().take(k.min(c.len() - 1) + 1).skip(start) {
                    if *ch != '\n' {
                        *ch = ' ';
                    }
                }
                i = k;
            }
        }
        i += 1;
    }
    out.into_iter().collect()
}

/// The files of `folder` (`src/app`) as (path from the root, code without comments, strings and
/// inline modules).
fn folder_files(root: &Path, folder: &str) -> Vec<(String, String)> {
    rust_files(&root.join(folder))
        .into_iter()
        .map(|p| {
            let src = fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let rel = p
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            (rel, without_inline_modules(&code_lines(&src).join("\n")))
        })
        .collect()
}

#[test]
fn the_window_imports_run_down_and_make_no_circle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = folder_files(root, "src/app");
    assert!(
        files.len() > 20,
        "src/app not found under {}",
        root.display()
    );
    let arrows = arrows(&files, "app");
    // The scanner sees the window's arrows at all (the panels draw in the palette's colors).
    assert!(
        arrows
            .iter()
            .any(|a| a.from.starts_with("src/app/panels/") && a.to == ["app", "view"]),
        "no arrow found from a panel to app/view.rs: the scanner is broken"
    );
    let report = verdict(&files, &arrows);
    assert!(report.is_empty(), "src/app:\n{report}");
}

/// The back-up arrows and the circles of a folder's arrows, one line each (the circles with the
/// arrows inside them), empty when there are none.
fn verdict(files: &[(String, String)], arrows: &[Arrow]) -> String {
    let bad = back_up(arrows);
    let circles = circles(files, arrows);
    let mut report = String::new();
    for b in &bad {
        report.push_str(&format!("back up: {b}\n"));
    }
    for c in &circles {
        report.push_str(&format!(
            "circle of {} files:\n{}\n",
            c.iter().filter(|l| !l.starts_with(' ')).count(),
            c.join("\n")
        ));
    }
    if !report.is_empty() {
        report = format!(
            "{} arrows run back up and {} circles:\n{report}",
            bad.len(),
            circles.len()
        );
    }
    report
}

/// The questions' imports run dispatcher -> families -> shared plain types (issue 44): no
/// family's state in the dispatcher's file, no helper one family takes from another.
#[test]
fn the_questions_imports_run_down_and_make_no_circle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = folder_files(root, "src/questions");
    assert!(
        files.len() > 15,
        "src/questions not found under {}",
        root.display()
    );
    let arrows = arrows(&files, "questions");
    // The scanner sees the questions' arrows at all: the dispatcher routes to each family.
    for family in ["motion", "forces", "work_and_power", "periods", "impacts"] {
        assert!(
            arrows
                .iter()
                .any(|a| a.from == "src/questions/dispatch.rs" && a.to == ["questions", family]),
            "no arrow found from the dispatcher to {family}: the scanner is broken"
        );
    }
    let report = verdict(&files, &arrows);
    assert!(report.is_empty(), "src/questions:\n{report}");
}

/// The rule on a made-up window: each kind of back-up arrow and a circle is found, and the
/// arrows that run down are let through.
#[test]
fn the_rule_sees_each_kind_of_back_up_arrow_and_circles() {
    let file = |p: &str, code: &str| {
        let code = without_inline_modules(&code_lines(code).join("\n"));
        (p.to_string(), code)
    };
    let files = vec![
        file("src/app/mod.rs", "pub mod panels;\npub mod run;\npub mod ui;\npub mod tools;\npub mod web;\npub fn color() {}\nuse panels::PanelsPlugin;\n"),
        file("src/app/panels/mod.rs", "mod playback;\npub mod state;\npub struct UiState;\n"),
        // Down: a sibling's item, the run below, a helper written inline.
        file("src/app/panels/playback.rs", "use super::state::UiState;\nuse super::super::run::Run;\nfn f() { super::super::ui::rich(); } // super::UiState in a comment\n"),
        file("src/app/panels/state.rs", "use crate::app::ui::{self, rich as r};\nconst S: &str = \"super::UiState\";\n"),
        // Up: an item of panels/mod.rs, and of app/mod.rs inline.
        file("src/app/run.rs", "use std::fmt;\nfn g() { super::color(); }\n#[cfg(test)]\nmod tests {\n    use super::*;\n}\n"),
        file("src/app/ui.rs", "use super::{tools::Tool, run};\n"),
        // Into the panels from below, and a circle tools -> state -> ui -> tools.
        file("src/app/tools.rs", "use crate::app::panels::state::UiState;\nuse super::ui;\n"),
        file("src/app/web.rs", "use super::panels::{self, UiState};\n"),
    ];
    let mut files = files;
    files.push(file(
        "src/app/panels/bad.rs",
        "use super::{UiState, state};\n",
    ));
    let arrows = arrows(&files, "app");
    let bad = back_up(&arrows);
    let has = |s: &str| bad.iter().any(|b| b.starts_with(s));
    assert!(has("src/app/panels/bad.rs:1: super::UiState"), "{bad:#?}");
    assert!(has("src/app/run.rs:2: super::color"), "{bad:#?}");
    assert!(
        has("src/app/tools.rs:1: crate::app::panels::state::UiState"),
        "{bad:#?}"
    );
    assert!(!has("src/app/panels/playback.rs"), "{bad:#?}");
    assert!(!has("src/app/panels/state.rs"), "{bad:#?}");
    assert!(!has("src/app/web.rs"), "{bad:#?}");
    assert!(!has("src/app/mod.rs"), "{bad:#?}");
    assert_eq!(bad.len(), 3, "{bad:#?}");
    let circles = circles(&files, &arrows);
    assert_eq!(circles.len(), 1, "{circles:#?}");
    assert_eq!(
        circles[0][..3],
        [
            "src/app/panels/state.rs",
            "src/app/tools.rs",
            "src/app/ui.rs"
        ],
        "{circles:#?}"
    );
}
