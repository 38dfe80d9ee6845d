//! The window's "Your id" kept between runs (issue 42: the student typed it again every session,
//! and until then each level with parameters opened with the nominal numbers): kept in
//! prefs.ron, read back, and the first level opened with the student's own numbers; a prefs
//! file whose id is not one line of text is reported with its line and column and kept aside,
//! never replaced (the preferences' rule).

use rigidlab::app::prefs::{load_from, Prefs, PrefsFile};
use rigidlab::app::student;
use rigidlab::level::{self, params::Pick};
use std::fs;
use std::path::{Path, PathBuf};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-idkept-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_students_id_is_kept_in_prefs_and_read_back() {
    let dir = temp_dir("round-trip");
    let path = dir.join("prefs.ron");
    let prefs = Prefs {
        student_id: "ada-17".into(),
        ..Prefs::default()
    };
    let file = PrefsFile {
        path: Some(path.clone()),
        problem: None,
        can_save: true,
    };
    prefs.save(&file).unwrap();
    assert!(fs::read_to_string(&path).unwrap().contains("\"ada-17\""));
    let (read, found) = load_from(&path);
    assert_eq!(found.problem, None);
    assert_eq!(read.student_id, "ada-17");
    // No id: not written, so the file reads in a rigidlab from before the field too.
    Prefs::default().save(&file).unwrap();
    assert!(!fs::read_to_string(&path).unwrap().contains("student_id"));
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn an_id_that_is_not_one_line_is_reported_and_the_file_kept() {
    let dir = temp_dir("bad");
    let path = dir.join("prefs.ron");
    let text = "(\n    trails: false,\n    student_id: \"ada\\n17\",\n)\n";
    fs::write(&path, text).unwrap();
    let (read, found) = load_from(&path);
    assert_eq!(read, Prefs::default());
    let why = found.problem.expect("the problem is said");
    assert!(
        why.contains("prefs.ron:3:5") && why.contains("student_id"),
        "{why}"
    );
    assert!(!path.exists(), "the file is moved aside");
    let aside = dir.join("prefs.ron.bad");
    assert_eq!(fs::read_to_string(&aside).unwrap(), text, "{why}");
    let _ = fs::remove_dir_all(&dir);
}

/// The level the window opens with, for the kept id: the student's own variant (the numbers
/// `rigidlab check --student ada-17` runs), not the nominal one; a level without parameters as
/// it is.
#[test]
fn the_first_level_opens_with_the_kept_ids_numbers() {
    let file = Path::new("levels/kinetics/simple_pendulum_param.ron");
    let nominal = level::load(file).unwrap();
    let theirs = level::load_variant(file, &Pick::Student("ada-17".into()))
        .unwrap()
        .scene;
    assert_ne!(
        nominal.level.statement, theirs.level.statement,
        "the test needs a variant"
    );
    let opened = student::kept_variant("ada-17", nominal.clone());
    assert_eq!(opened.level.statement, theirs.level.statement);
    let plain = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    let opened = student::kept_variant("ada-17", plain.clone());
    assert_eq!(opened.level.statement, plain.level.statement);
}
