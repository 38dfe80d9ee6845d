//! Mutated library levels (random byte and token edits, truncation, NaN/inf/huge numbers) fed to
//! the level parser and validator: no input makes them panic, and every error says something
//! and where. Bounded to a few seconds in release.

use proptest::prelude::*;
use rigidlab::level::{self, LevelError};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Every library level's bytes, read once.
fn library() -> &'static [(PathBuf, Vec<u8>)] {
    static LEVELS: OnceLock<Vec<(PathBuf, Vec<u8>)>> = OnceLock::new();
    LEVELS.get_or_init(|| {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("levels");
        level::collect_files(&[dir])
            .unwrap()
            .into_iter()
            .map(|f| {
                let bytes = std::fs::read(&f).unwrap();
                (f, bytes)
            })
            .collect()
    })
}

/// Parses and validates; an error must carry a message, a fix and a position inside the text.
fn check(path: &Path, bytes: &[u8]) -> Result<(), TestCaseError> {
    if let Err(e) = level::parse_bytes(path, bytes) {
        well_formed(&e, bytes)?;
    }
    Ok(())
}

fn well_formed(e: &LevelError, bytes: &[u8]) -> Result<(), TestCaseError> {
    let shown = e.to_string();
    prop_assert!(!e.message.trim().is_empty(), "no message: {shown}");
    prop_assert!(!e.help.trim().is_empty(), "no help: {shown}");
    let lines = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
    prop_assert!(e.line <= lines, "line {} of {lines}: {shown}", e.line);
    prop_assert!((e.line == 0) == (e.col == 0), "half a position: {shown}");
    Ok(())
}

/// Numbers that levels must refuse or survive.
const WILD_NUMBERS: &[&str] = &[
    "NaN",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e400",
    "1e-320",
    "0",
    "-0.0",
    "-1",
    "1e20",
    "99999999999999999999999",
    "0x10",
    "1.",
    ".5",
    "+3",
];

/// Tokens that break structure or names.
const WILD_TOKENS: &[&str] = &[
    "(", ")", "[", "]", "{", ",", ":", "\"", "//", "/*", "name", "bodies", "Circle", "fixed",
    "Some(", "None", "\u{0}", "é", "\\", "r#\"",
];

/// Offsets of the numbers in the text (a digit run with its sign, point and exponent).
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let starts = text[i].is_ascii_digit()
            && (i == 0 || !(text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'_'));
        if starts {
            let from = if i > 0 && text[i - 1] == b'-' {
                i - 1
            } else {
                i
            };
            let mut j = i;
            while j < text.len() && (text[j].is_ascii_alphanumeric() || b".-+".contains(&text[j])) {
                j += 1;
            }
            out.push((from, j));
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

#[derive(Debug, Clone)]
enum Edit {
    /// Overwrite, insert or delete one byte at a fraction of the length.
    Byte(f64, u8, u8),
    /// Replace the n-th number (modulo their count) with a wild one.
    Number(usize, usize),
    /// Insert a wild token at a fraction of the length.
    Token(f64, usize),
    /// Delete a span (fraction, length).
    Cut(f64, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (0.0..1.0, 0u8..3, any::<u8>()).prop_map(|(at, op, b)| Edit::Byte(at, op, b)),
        (any::<usize>(), 0..WILD_NUMBERS.len()).prop_map(|(n, w)| Edit::Number(n, w)),
        (0.0..1.0, 0..WILD_TOKENS.len()).prop_map(|(at, t)| Edit::Token(at, t)),
        (0.0..1.0, 1usize..40).prop_map(|(at, n)| Edit::Cut(at, n)),
    ]
}

fn apply(bytes: &mut Vec<u8>, e: &Edit) {
    let at = |f: f64, len: usize| ((f * len as f64) as usize).min(len);
    match *e {
        Edit::Byte(f, op, b) => {
            let i = at(f, bytes.len());
            match op {
                0 if i < bytes.len() => bytes[i] = b,
                1 => bytes.insert(i, b),
                _ if i < bytes.len() => {
                    bytes.remove(i);
                }
                _ => {}
            }
        }
        Edit::Number(n, w) => {
            let nums = numbers(bytes);
            if !nums.is_empty() {
                let (s, t) = nums[n % nums.len()];
                bytes.splice(s..t, WILD_NUMBERS[w].bytes());
            }
        }
        Edit::Token(f, t) => {
            let i = at(f, bytes.len());
            bytes.splice(i..i, WILD_TOKENS[t].bytes());
        }
        Edit::Cut(f, n) => {
            let i = at(f, bytes.len());
            let j = (i + n).min(bytes.len());
            bytes.drain(i..j);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        // RIGIDLAB_FUZZ_CASES=340000 runs the three mutation properties 1e6 times in all.
        cases: std::env::var("RIGIDLAB_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(1500),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn edited_levels_never_panic(level in any::<prop::sample::Index>(),
                                 edits in prop::collection::vec(edit(), 1..6)) {
        let (path, bytes) = level.get(library());
        let mut bytes = bytes.clone();
        for e in &edits {
            apply(&mut bytes, e);
        }
        check(path, &bytes)?;
    }

    #[test]
    fn wild_numbers_never_panic(level in any::<prop::sample::Index>(),
                                picks in prop::collection::vec((any::<usize>(), 0..WILD_NUMBERS.len()), 1..4)) {
        // Numbers only: the structure stays valid, so the validator sees every value.
        let (path, bytes) = level.get(library());
        let mut bytes = bytes.clone();
        for (n, w) in picks {
            apply(&mut bytes, &Edit::Number(n, w));
        }
        check(path, &bytes)?;
    }

    #[test]
    fn truncated_levels_never_panic(level in any::<prop::sample::Index>(), keep in 0.0..1.0f64) {
        let (path, bytes) = level.get(library());
        let n = (keep * bytes.len() as f64) as usize;
        check(path, &bytes[..n])?;
    }
}

#[test]
fn the_library_itself_parses() {
    // The mutations start from valid levels (otherwise they test nothing past the first error).
    assert!(library().len() > 50);
    for (path, bytes) in library() {
        level::parse_bytes(path, bytes).unwrap_or_else(|e| panic!("{e}"));
    }
}
