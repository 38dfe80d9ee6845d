//! Every quantity a question can ask is asked somewhere with a known answer (issue 31).
//!
//! The quantities are the variants of `Quantity`, read from its source
//! (src/level/format/exercise.rs) as text, so a variant added there is seen here without
//! anyone updating a list. A variant is covered when some question with an `expected` answer
//! asks for it (`quantity: Variant`):
//! - in a level of the library (levels/, every folder: tests/suite/questions/library.rs runs the exercises,
//!   tests/suite/checks/settings_twins.rs every level at finer settings);
//! - in a level file under tests/ whose folder, or a folder above it, a test names (tests/newuser/
//!   with its topic folders and tests/hard_readings/ are run by
//!   tests/suite/questions/untuned_levels.rs);
//! - or in a level a test writes inline (RON text in a .rs file under tests/, the question's
//!   parentheses holding an `expected:`), or a `QuestionDef` it builds (`quantity:
//!   Quantity::Variant` beside an `expected:`).
//!
//! That the expected answers come from theory (a closed form or a derivation worked in the
//! level's comments) and not from the engine is the reviewers' part: this test only finds the
//! quantities nobody asks for. `cargo test --release --test suite -- questions::quantity_coverage:: --nocapture`
//! prints where each is asked.

use crate::common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The variant names of `pub enum Quantity`, in source order: the identifiers that open an item
/// at the enum's own brace depth (comments and attributes skipped).
fn quantity_variants() -> Vec<String> {
    let file = common::repo_path("src/level/format/exercise.rs");
    let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let start = text
        .find("pub enum Quantity {")
        .expect("src/level/format/exercise.rs declares `pub enum Quantity {`");
    let mut depth = 0i32;
    let mut names = Vec::new();
    for line in text[start..].lines() {
        let code = line.split("//").next().unwrap_or("").trim();
        if depth == 1 {
            let ident: String = code
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if ident.starts_with(|c: char| c.is_ascii_uppercase()) {
                names.push(ident);
            }
        }
        for c in code.chars() {
            match c {
                '{' | '(' | '[' => depth += 1,
                '}' | ')' | ']' => depth -= 1,
                _ => {}
            }
        }
        if depth == 0 && !names.is_empty() {
            break;
        }
    }
    names
}

/// The name of a quantity's variant, from its Debug form (`PointX { body: .. }` -> `PointX`).
fn variant_of(q: &rigidlab::level::Quantity) -> String {
    format!("{q:?}")
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect()
}

/// Where each variant is asked: variant -> places ("file: question id" or "file:line").
type Places = BTreeMap<String, Vec<String>>;

/// The questions of level files: the library's, and those under tests/ in a folder some test
/// file names (so that a test runs them). Files that do not load (a test's bad input) ask nothing.
fn level_questions(places: &mut Places, test_sources: &str) {
    let root = common::repo_path("");
    let mut files = common::ron_files("levels", &[]);
    for f in common::ron_files("tests", &[]) {
        let rel = f.strip_prefix(&root).unwrap_or(&f).to_path_buf();
        let folder = rel
            .parent()
            .unwrap_or(Path::new(""))
            .to_string_lossy()
            .to_string();
        let file = rel.to_string_lossy().to_string();
        // A folder a test names is walked with its subfolders (tests/newuser/ files its levels
        // in topic folders, and the tests that run them name tests/newuser).
        let ancestor_named = rel.ancestors().skip(2).any(|a| {
            let a = a.to_string_lossy();
            a.contains('/') && test_sources.contains(&format!("\"{a}\""))
        });
        if test_sources.contains(&format!("\"{folder}\""))
            || test_sources.contains(&format!("\"{folder}/"))
            || test_sources.contains(&file)
            || ancestor_named
        {
            files.push(f);
        } else {
            println!("not run by any test, not counted: {file}");
        }
    }
    for f in files {
        let rel = f.strip_prefix(&root).unwrap_or(&f).display().to_string();
        // A level that does not load would drop its questions from the coverage unseen.
        let scene =
            rigidlab::level::load(&f).unwrap_or_else(|e| panic!("{rel} does not load: {e}"));
        for q in &scene.level.questions {
            places
                .entry(variant_of(&q.quantity))
                .or_default()
                .push(format!("{rel}: {}", q.id));
        }
    }
}

/// The span of the innermost brackets ((), {} or []) around `at` in `text`, or None.
fn enclosing(text: &str, at: usize) -> Option<&str> {
    let b = text.as_bytes();
    let mut depth = 0;
    let mut open = None;
    for i in (0..at).rev() {
        match b[i] {
            b')' | b'}' | b']' => depth += 1,
            b'(' | b'{' | b'[' if depth == 0 => {
                open = Some(i);
                break;
            }
            b'(' | b'{' | b'[' => depth -= 1,
            _ => {}
        }
    }
    let open = open?;
    let mut depth = 0;
    for (i, &c) in b.iter().enumerate().skip(open) {
        match c {
            b'(' | b'{' | b'[' => depth += 1,
            b')' | b'}' | b']' => {
                depth -= 1;
                if depth == 0 {
                    return Some(&text[open..=i]);
                }
            }
            _ => {}
        }
    }
    None
}

/// The questions tests write inline: `quantity: Variant` (RON text) or `quantity:
/// Quantity::Variant` (a `QuestionDef` built in Rust) whose enclosing brackets hold an
/// `expected`.
fn inline_questions(places: &mut Places, sources: &[(PathBuf, String)]) {
    for (file, text) in sources {
        for (at, _) in text.match_indices("quantity:") {
            let rest = text[at + "quantity:".len()..].trim_start();
            let rest = rest.strip_prefix("Quantity::").unwrap_or(rest);
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.starts_with(|c: char| c.is_ascii_uppercase()) {
                continue;
            }
            if enclosing(text, at).is_some_and(|q| q.contains("expected")) {
                let line = text[..at].lines().count();
                places
                    .entry(name)
                    .or_default()
                    .push(format!("{}:{line}", file.display()));
            }
        }
    }
}

/// The test sources (every `.rs` file under tests/, the suite's modules in their stage
/// folders), this file left out: its own text names quantities without asking for them.
fn test_sources() -> Vec<(PathBuf, String)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    let root = common::repo_path("");
    let mut files = Vec::new();
    walk(&root.join("tests"), &mut files);
    // file!() is this file's path from the package's root (tests/suite/questions/...).
    let count = files.len();
    files.retain(|p| !p.ends_with(file!()));
    assert_eq!(files.len(), count - 1, "{} not found under tests/", file!());
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p.strip_prefix(&root).unwrap().to_path_buf(), text)
        })
        .collect()
}

#[test]
fn the_quantity_list_is_read_from_the_source() {
    let v = quantity_variants();
    // Spot checks of the reading: the first variant, a unit variant, struct variants, the last.
    assert_eq!(v.first().map(String::as_str), Some("X"), "{v:?}");
    for name in [
        "Time",
        "PointX",
        "JointReaction",
        "MotorTorque",
        "GroupMomentum",
    ] {
        assert!(v.iter().any(|n| n == name), "{name} not read: {v:?}");
    }
    // Field names of struct variants (`body`, `window`) are not variants.
    assert!(
        v.iter()
            .all(|n| n.starts_with(|c: char| c.is_ascii_uppercase())),
        "{v:?}"
    );
    let mut sorted = v.clone();
    sorted.sort();
    sorted.dedup();
    assert_eq!(sorted.len(), v.len(), "a variant read twice: {v:?}");
}

#[test]
fn every_quantity_is_asked_with_a_known_answer() {
    let variants = quantity_variants();
    let sources = test_sources();
    let all_sources: String = sources.iter().map(|(_, t)| t.as_str()).collect();
    let mut places = Places::new();
    level_questions(&mut places, &all_sources);
    // Every quantity a level asks is one the source declares: the reading above is complete.
    let unknown: Vec<&String> = places.keys().filter(|k| !variants.contains(k)).collect();
    assert!(
        unknown.is_empty(),
        "levels ask for {unknown:?}, which the reading of `enum Quantity` did not find: {variants:?}"
    );
    inline_questions(&mut places, &sources);
    let mut missing = Vec::new();
    for v in &variants {
        match places.get(v) {
            Some(p) => println!("{v:<24} {:>3} questions, e.g. {}", p.len(), p[0]),
            None => {
                println!("{v:<24} NOT ASKED");
                missing.push(v.as_str());
            }
        }
    }
    println!(
        "{} quantities, {} asked",
        variants.len(),
        variants.len() - missing.len()
    );
    assert!(
        missing.is_empty(),
        "no question with an expected answer asks for {missing:?}: add a library level (levels/<topic>/) \
         or a test whose answer is worked from theory (see docs/levels.md for what each reads)"
    );
}
