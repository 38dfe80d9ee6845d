//! The equation key, docs/equations.md, against the citations in src/: every textbook id a
//! `.rs` file under src/ cites must be an entry (a heading) of the key. Extra entries are allowed.
//!
//! The citation grammar (docs/equations.md, "How to read an id"):
//! - catalog ids `XX-n`: one of the catalog's two-letter prefixes (`PREFIXES`), a hyphen and a
//!   number, standing as a word of its own (`IM-9/IM-11` holds two, `UTF-8` and `PR-12` none).
//!   Whatever letters or digits run on after the hyphen belong to the id, so `RK-99`, `RK-011`
//!   or `RK-11x` are read as ids and fail unless the key has them.
//! - Meriam & Kraige chapter-6 equation numbers `6/n` and `6/na`: a `6` that no letter, digit,
//!   `.` or `/` precedes, a `/`, one or two digits and at most one lowercase letter, which no
//!   letter, digit, `_`, `/` or decimal part follows. So `2/3 g`, `1/60 s`, `16/9`, `6/255`,
//!   `6/2.5` and `6/1/2026` are not ids. A number right after `Art.`, `Fig.` (or `Arts.`,
//!   `Figs.`, `article`, `figure`, any case) names a section or a figure of the book, not an
//!   equation, and is not an id either.
//!
//! Std only; it reads the files, it does not build or link anything of the crate.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The catalog's topic prefixes (docs/equations.md has the table).
const PREFIXES: [&str; 12] = [
    "PK", "PN", "WE", "IM", "RK", "MP", "PL", "CP", "RE", "RM", "VW", "OT",
];

/// Words after which a `6/n` is a section or figure number, not an equation.
const NOT_EQUATION_AFTER: [&str; 8] = [
    "art.", "arts.", "article", "articles", "fig.", "figs.", "figure", "figures",
];

fn is_word(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// A catalog id starting at byte `i`: its text and the byte after it.
fn catalog_at(b: &[u8], i: usize) -> Option<(String, usize)> {
    if i > 0 && is_word(b[i - 1]) {
        return None;
    }
    if b.len() < i + 4 || b[i + 2] != b'-' || !b[i + 3].is_ascii_digit() {
        return None;
    }
    let prefix = std::str::from_utf8(&b[i..i + 2]).ok()?;
    if !PREFIXES.contains(&prefix) {
        return None;
    }
    let mut end = i + 3;
    while end < b.len() && is_word(b[end]) {
        end += 1;
    }
    Some((String::from_utf8(b[i..end].to_vec()).ok()?, end))
}

/// Whether the text before byte `i` ends with a word that makes a number a section or figure.
fn after_section_word(b: &[u8], i: usize) -> bool {
    let before = String::from_utf8_lossy(&b[..i]);
    let before = before.trim_end().to_ascii_lowercase();
    NOT_EQUATION_AFTER.iter().any(|w| {
        before.ends_with(w) && {
            let start = before.len() - w.len();
            start == 0 || !is_word(before.as_bytes()[start - 1])
        }
    })
}

/// An MK chapter-6 equation number starting at byte `i`: its text and the byte after it.
fn book_at(b: &[u8], i: usize) -> Option<(String, usize)> {
    if b[i] != b'6' || b.get(i + 1) != Some(&b'/') {
        return None;
    }
    if i > 0 && (is_word(b[i - 1]) || b[i - 1] == b'.' || b[i - 1] == b'/') {
        return None;
    }
    let mut end = i + 2;
    while end < b.len() && b[end].is_ascii_digit() && end < i + 4 {
        end += 1;
    }
    if end == i + 2 {
        return None;
    }
    if end < b.len() && b[end].is_ascii_lowercase() {
        end += 1;
    }
    match (b.get(end), b.get(end + 1)) {
        (Some(&c), _) if is_word(c) || c == b'/' => return None,
        (Some(&b'.'), Some(d)) if d.is_ascii_digit() => return None,
        _ => {}
    }
    if after_section_word(b, i) {
        return None;
    }
    Some((String::from_utf8(b[i..end].to_vec()).ok()?, end))
}

/// The ids one line cites, in order.
fn scan_line(line: &str) -> Vec<String> {
    let b = line.as_bytes();
    let mut ids = Vec::new();
    let mut i = 0;
    while i < b.len() {
        match catalog_at(b, i).or_else(|| book_at(b, i)) {
            Some((id, end)) => {
                ids.push(id);
                i = end;
            }
            None => i += 1,
        }
    }
    ids
}

/// One citation: where it is and what it cites.
struct Citation {
    file: String,
    line: usize,
    id: String,
}

fn scan_text(file: &str, text: &str) -> Vec<Citation> {
    text.lines()
        .enumerate()
        .flat_map(|(n, line)| {
            scan_line(line).into_iter().map(move |id| Citation {
                file: file.to_string(),
                line: n + 1,
                id,
            })
        })
        .collect()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every citation in the `.rs` files under src/, with paths relative to the crate root.
fn src_citations() -> Vec<Citation> {
    let root = root();
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    assert!(!files.is_empty(), "no .rs files under src/");
    files
        .iter()
        .flat_map(|p| {
            let text = fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let rel = p.strip_prefix(&root).unwrap_or(p).display().to_string();
            scan_text(&rel, &text)
        })
        .collect()
}

/// The key's entries: the ids that open a heading of docs/equations.md, with their lines.
fn key_entries(text: &str) -> BTreeMap<String, Vec<usize>> {
    let mut entries: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (n, line) in text.lines().enumerate() {
        let Some(heading) = line.strip_prefix('#') else {
            continue;
        };
        let first = heading
            .trim_start_matches('#')
            .split_whitespace()
            .next()
            .unwrap_or("");
        if scan_line(first) == [first] {
            entries.entry(first.to_string()).or_default().push(n + 1);
        }
    }
    entries
}

fn key() -> BTreeMap<String, Vec<usize>> {
    let path = root().join("docs/equations.md");
    let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    key_entries(&text)
}

/// The citations whose id the key lacks, as `file:line: id`.
fn missing(citations: &[Citation], key: &BTreeMap<String, Vec<usize>>) -> Vec<String> {
    citations
        .iter()
        .filter(|c| !key.contains_key(&c.id))
        .map(|c| format!("{}:{}: {}", c.file, c.line, c.id))
        .collect()
}

#[test]
fn every_id_cited_in_src_is_in_the_key() {
    let citations = src_citations();
    let key = key();
    let ids: BTreeSet<&str> = citations.iter().map(|c| c.id.as_str()).collect();
    eprintln!(
        "src/ cites {} distinct ids in {} citations; docs/equations.md has {} entries",
        ids.len(),
        citations.len(),
        key.len()
    );
    assert!(
        !citations.is_empty(),
        "no citations found under src/: is the scanner broken?"
    );
    let missing = missing(&citations, &key);
    assert!(
        missing.is_empty(),
        "{} citation(s) in src/ of ids that docs/equations.md has no entry for \
         (add the entry, or fix the citation):\n{}",
        missing.len(),
        missing.join("\n")
    );
    assert!(key.len() >= ids.len());
}

#[test]
fn the_key_has_one_entry_per_id() {
    let twice: Vec<String> = key()
        .into_iter()
        .filter(|(_, lines)| lines.len() > 1)
        .map(|(id, lines)| format!("{id} at lines {lines:?}"))
        .collect();
    assert!(
        twice.is_empty(),
        "docs/equations.md has ids with more than one entry: {twice:?}"
    );
}

#[test]
fn scanner_finds_ids() {
    assert_eq!(scan_line("    // RK-99"), ["RK-99"]);
    assert_eq!(
        scan_line("/// T = 1/2 I_C w^2 (6/10, RK-11); MK 6/11a; IM-9/IM-11, IM-15."),
        ["6/10", "RK-11", "6/11a", "IM-9", "IM-11", "IM-15"]
    );
    assert_eq!(
        scan_line("(MK eq. 6/1's moment), 6/9, 6/12 and 6/17"),
        ["6/1", "6/9", "6/12", "6/17"]
    );
    assert_eq!(scan_line("\"sum M_P (6/2) largest {:.2e}\""), ["6/2"]);
    // Malformed ids are read whole, so the key check reports them.
    assert_eq!(
        scan_line("RK-011, RK-11x and 6/99"),
        ["RK-011", "RK-11x", "6/99"]
    );
}

#[test]
fn scanner_skips_look_alikes() {
    let none: [&str; 0] = [];
    assert_eq!(
        scan_line("a = 2/3 g sin(theta), F = 1/3 m g sin(theta), I = 1/12 m l^2"),
        none
    );
    assert_eq!(
        scan_line("dt = 1/60 s, 1/960 s; 16/9; 0.6/2; x6/2; 6/255 per channel; 6/2.5"),
        none
    );
    assert_eq!(scan_line("on 2026-11-24, 6/1/2026 or 11/6/2026"), none);
    assert_eq!(scan_line("UTF-8, PR-12, XRK-1, rk-11, RK 11, RK-"), none);
    assert_eq!(
        scan_line("MK Art. 6/4, art. 6/10's impulse, Fig. 6/6b, Arts. 6/2"),
        none
    );
    assert_eq!(scan_line("chart. 6/4"), ["6/4"]);
}

#[test]
fn an_unknown_id_fails_the_check() {
    let key = key();
    let cited = scan_text(
        "src/x.rs",
        "fn f() {}\n// RK-99: not in the key; 2/3 g is not an id (6/1)\n",
    );
    assert_eq!(missing(&cited, &key), ["src/x.rs:2: RK-99"]);
}
