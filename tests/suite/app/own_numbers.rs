//! A student's own numbers, the same wherever a level opens (issue 43) and never mixed with
//! another level's answers (the student trial of 2026-12-07): answers typed for one level go
//! when another level, or the same level with other numbers, opens; a challenge opened from its
//! text (the web page's compiled-in or fetched levels) is the one opened from its file (in the
//! page every challenge said "the level's file cannot be read" before).

use rigidlab::app::panels::Exercise;
use rigidlab::level::{self, params::Pick};
use std::path::Path;

#[test]
fn answers_typed_for_another_level_or_other_numbers_go() {
    let (a, b) = (Path::new("levels/x/a.ron"), Path::new("levels/x/b.ron"));
    let mut ex = Exercise::default();
    ex.start_level(a, "a 1 kg bob", 2);
    ex.answers = vec!["3.13".into(), "19.62".into()];
    // The same level started again (Reset, a step back): the answers stay.
    ex.start_level(a, "a 1 kg bob", 2);
    assert_eq!(ex.answers, ["3.13", "19.62"]);
    // Another level with as many questions (before: kept, and graded right at once).
    ex.start_level(b, "a 1 kg bob", 2);
    assert_eq!(ex.answers, ["", ""]);
    // The same level for another student: its numbers differ, so do its answers.
    ex.answers = vec!["3.13".into(), "19.62".into()];
    ex.start_level(b, "a 2 kg bob", 2);
    assert_eq!(ex.answers, ["", ""]);
}

#[test]
fn a_challenge_from_its_text_is_the_one_from_its_file() {
    let files = crate::common::ron_files(Path::new("levels/challenges"), &[]);
    assert!(files.len() >= 10, "the challenges: {files:?}");
    for f in files {
        let text = level::read_text(&f).unwrap();
        for pick in [Pick::Nominal, Pick::Student("alice".into())] {
            for value in [None, Some(1.0)] {
                let from_file = level::load_challenge(&f, &pick, value);
                let from_text = level::parse_challenge(&f, &text, &pick, value);
                match (from_file, from_text) {
                    (Ok(a), Ok(b)) => {
                        assert_eq!(a.scene.level, b.scene.level, "{}", f.display());
                        assert_eq!(
                            a.control.map(|c| c.1),
                            b.control.map(|c| c.1),
                            "{}",
                            f.display()
                        );
                    }
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                    (a, b) => panic!(
                        "{}: file {:?}, text {:?}",
                        f.display(),
                        a.is_ok(),
                        b.is_ok()
                    ),
                }
            }
        }
    }
}
