//! An assignment in the window's left column, headless: its title, due date and levels in the
//! manifest's order drawn above the library, a level that does not load listed with why (the
//! numbering kept), and the browser's rescan keeping the assignment.

use bevy_egui::egui;
use rigidlab::app::panels::assignment_list::AssignmentList;
use rigidlab::app::panels::{Browser, Exercise};
use rigidlab::app::{LiveChecks, Run};
use rigidlab::level::{self, assignment::Assignment};
use rigidlab::sim::Options;
use std::path::Path;

use crate::common::app::{all_text, left_column};

/// Every text the left column draws at a 1280x800 screen, in drawing order.
fn left_column_texts(browser: &mut Browser, phys: &Run) -> Vec<String> {
    let live = LiveChecks::new(phys);
    let mut ex = Exercise::default();
    ex.start(phys.sim.level.questions.len());
    let texts = left_column(
        &egui::Context::default(),
        browser,
        (phys, &live),
        &mut ex,
        Vec::new(),
    );
    all_text(&texts).into_iter().map(String::from).collect()
}

#[test]
fn the_assignment_is_listed_in_order_above_the_library() {
    let a = Assignment::load(Path::new("assignments/intro")).unwrap();
    let list = AssignmentList::read(&a);
    let titles: Vec<String> = a
        .levels
        .iter()
        .map(|p| level::load(p).unwrap().level.title)
        .collect();
    let mut browser = Browser::scan(Path::new("levels"));
    let phys = Run::new(list.first_loadable().unwrap(), Options::default());
    assert_eq!(phys.scene.file, a.levels[0], "the first level opens");
    browser.assignment = Some(list);
    let texts = left_column_texts(&mut browser, &phys);
    let at = |want: &str| {
        texts
            .iter()
            .position(|t| t.replace('\n', " ").contains(want))
            .unwrap_or_else(|| panic!("{want:?} not drawn in {texts:?}"))
    };
    let heading = at(&format!("Assignment: {}", a.title));
    let due = at("due 2026-12-14");
    let rows: Vec<usize> = titles
        .iter()
        .enumerate()
        .map(|(k, t)| at(&format!("{}. {t}", k + 1)))
        .collect();
    let library = at("Course:");
    assert!(heading < due && due < rows[0], "{texts:?}");
    assert!(rows.windows(2).all(|w| w[0] < w[1]), "in order: {rows:?}");
    assert!(rows[2] < library, "above the library: {texts:?}");
}

#[test]
fn a_level_that_does_not_load_keeps_its_number_and_says_why() {
    let dir = std::env::temp_dir().join(format!("rigidlab-alist-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy("levels/kinetics/simple_pendulum.ron", dir.join("a.ron")).unwrap();
    std::fs::write(dir.join("b.ron"), "Level(title: \"broken\", bodies: [").unwrap();
    std::fs::write(
        dir.join("assignment.ron"),
        "Assignment(title: \"t\", levels: [\"b.ron\", \"a.ron\"])",
    )
    .unwrap();
    let list = AssignmentList::read(&Assignment::load(&dir).unwrap());
    assert_eq!(list.entries.len(), 2);
    let why = list.entries[0].error.as_deref().expect("b.ron's error");
    assert!(why.contains("b.ron:1:"), "{why}");
    assert_eq!(list.errors().count(), 1);
    // The first level that loads opens: the second.
    assert_eq!(list.first_loadable().unwrap().file, dir.join("a.ron"));

    let mut browser = Browser::scan(Path::new("levels"));
    browser.assignment = Some(list);
    // The teacher fixes b.ron; a rescan reads it again and keeps the assignment.
    std::fs::copy("levels/kinetics/simple_pendulum.ron", dir.join("b.ron")).unwrap();
    browser.rescan();
    let kept = browser.assignment.as_ref().expect("kept over a rescan");
    assert!(kept.entries.iter().all(|e| e.error.is_none()));
    std::fs::remove_dir_all(dir).unwrap();
}
