//! The stage boundaries of the data flow (src/lib.rs): `sim` (the rapier world) runs before
//! `analysis` and must not import it, and rapier's types stay in `sim`: no file outside src/sim
//! names rapier2d (or rapier2d-f64, parry2d, or the stage's `rapier` alias). Each offending line
//! is listed as file:line.
//!
//! Only code counts: comments and string and character literals are skipped (the docs and the
//! CLI's help name the engine). src/lib.rs's `sim64` module is src/sim compiled a second time
//! against rapier2d-f64 (`#[path = "sim"]`), so its lines count as src/sim's.

use super::source_scan::{code_lines, rust_files};
use std::fs;
use std::path::Path;

/// Whether `line` holds one of `words` as a whole identifier.
fn names(line: &str, words: &[&str]) -> Option<String> {
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut found = None;
    let mut start = None;
    for (k, ch) in line.char_indices().chain([(line.len(), ' ')]) {
        match (ident(ch), start) {
            (true, None) => start = Some(k),
            (false, Some(s)) => {
                if words.contains(&&line[s..k]) {
                    found = Some(line[s..k].to_string());
                }
                start = None;
            }
            _ => {}
        }
    }
    found
}

/// Line ranges (0-based, inclusive) of src/lib.rs's modules declared with `#[path = "sim"]`:
/// the sim stage compiled again (`sim64`).
fn sim_blocks(lines: &[String]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut k = 0;
    while k < lines.len() {
        let attr: String = lines[k].chars().filter(|c| !c.is_whitespace()).collect();
        // The attribute's string is blanked in the code: recognise it by its shape.
        if attr.starts_with("#[path=") && attr.ends_with(']') {
            let first = k;
            let mut depth = 0i32;
            let mut opened = false;
            while k < lines.len() {
                for ch in lines[k].chars() {
                    match ch {
                        '{' => {
                            depth += 1;
                            opened = true;
                        }
                        '}' => depth -= 1,
                        ';' if !opened && depth == 0 => opened = true,
                        _ => {}
                    }
                }
                if opened && depth == 0 {
                    break;
                }
                k += 1;
            }
            out.push((first, k));
        }
        k += 1;
    }
    out
}

#[test]
fn sim_does_not_import_analysis_and_rapier_stays_in_sim() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = root.join("src");
    let sim = src.join("sim");
    let mut offences = Vec::new();
    for file in rust_files(&src) {
        let text = fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let lines = code_lines(&text);
        let rel = file
            .strip_prefix(root)
            .unwrap_or(&file)
            .display()
            .to_string();
        let in_sim_dir = file.starts_with(&sim);
        // Only the `#[path = "sim"]` blocks of the crate root are the sim stage's.
        let raw: Vec<&str> = text.lines().collect();
        let blocks = if file == src.join("lib.rs") {
            sim_blocks(&lines)
                .into_iter()
                .filter(|&(a, _)| raw.get(a).is_some_and(|l| l.contains("\"sim\"")))
                .collect()
        } else {
            Vec::new()
        };
        for (k, line) in lines.iter().enumerate() {
            let in_sim = in_sim_dir || blocks.iter().any(|&(a, b)| (a..=b).contains(&k));
            let at = format!("{rel}:{}", k + 1);
            if in_sim {
                if let Some(w) = names(line, &["analysis"]) {
                    offences.push(format!(
                        "{at}: src/sim names `{w}` (sim runs before analysis and must not import it): {}",
                        raw.get(k).map_or("", |l| l.trim())
                    ));
                }
            } else if let Some(w) = names(line, &["rapier2d", "rapier2d_f64", "parry2d", "rapier"])
            {
                offences.push(format!(
                    "{at}: `{w}` outside src/sim (rapier's types stay in the sim stage): {}",
                    raw.get(k).map_or("", |l| l.trim())
                ));
            }
        }
    }
    assert!(
        offences.is_empty(),
        "stage boundaries crossed:\n{}",
        offences.join("\n")
    );
}

#[test]
fn the_scanner_sees_code_only() {
    let src = "use crate::analysis::x; // rapier2d\n\
               let s = \"rapier2d\"; let r = r#\"crate::analysis\"#;\n\
               /* rapier2d /* nested */ analysis */ let c = 'a'; fn f<'a>(x: &'a str) {}\n\
               let t = \"multi\n\
               line rapier2d\";\n\
               use rapier2d::prelude::*;";
    let lines = code_lines(src);
    assert_eq!(lines.len(), 6);
    assert_eq!(names(&lines[0], &["analysis"]).as_deref(), Some("analysis"));
    assert!(names(&lines[0], &["rapier2d"]).is_none());
    assert!(names(&lines[1], &["rapier2d", "analysis"]).is_none());
    assert!(names(&lines[2], &["rapier2d", "analysis"]).is_none());
    assert!(lines[2].contains("'a str"));
    assert!(names(&lines[4], &["rapier2d"]).is_none());
    assert_eq!(names(&lines[5], &["rapier2d"]).as_deref(), Some("rapier2d"));
    // A word that only contains a name is not the name.
    assert!(names("let analysis_sum = 0;", &["analysis"]).is_none());
    let lib = code_lines("pub mod sim;\n#[path = \"sim\"]\npub mod sim64 {\n    use rapier2d_f64 as rapier;\n}\npub mod app;");
    assert_eq!(sim_blocks(&lib), vec![(1, 4)]);
}
