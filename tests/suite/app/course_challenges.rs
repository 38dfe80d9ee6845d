//! Challenges in the course (issue 42; the student trial of 2026-12-07 found "challenges 0/0
//! solved"): the library's ten challenges are counted, a challenge met is solved, and its row
//! shows its launches and the stars the Challenge box gives (3 in one or two launches, 2 in
//! three or four, 1 after). The course is drawn into a bare egui context.

use bevy_egui::egui;
use rigidlab::app::panels::challenge::stars;
use rigidlab::app::panels::{course, Browser, Course};
use rigidlab::app::progress::{self, Status};
use rigidlab::app::Run;
use rigidlab::sim::Options;
use std::path::Path;

use crate::common::app::{all_text, frames};

/// The library's challenges, one file each (docs/student.md#playing-a-challenge).
const CHALLENGES: usize = 10;

/// The course drawn once (twice: egui settles sizes), every text drawn.
fn draw(browser: &Browser, phys: &Run, c: &mut Course) -> Vec<String> {
    // A tall screen: every row of the course drawn.
    let screen = egui::vec2(1280.0, 8000.0);
    let texts = frames(
        &egui::Context::default(),
        screen,
        vec![Vec::new(); 2],
        |ui| {
            course::course(ui, browser, phys, c, &mut None);
        },
    );
    all_text(&texts).into_iter().map(String::from).collect()
}

#[test]
fn challenges_count_in_the_course_and_a_met_one_is_solved() {
    let browser = Browser::scan(Path::new("levels"));
    let challenges: Vec<_> = browser
        .groups
        .get("challenges")
        .expect("the library has a challenges topic")
        .clone();
    assert_eq!(challenges.len(), CHALLENGES);
    let open = |file: &str| {
        Run::new(
            rigidlab::level::load(Path::new(file)).unwrap(),
            Options::default(),
        )
    };
    // A challenge on screen: its topic is unfolded, its rows drawn.
    let cup = open("levels/challenges/projectile_into_cup.ron");
    let phys = &cup;
    let mut c = Course::default();
    let (_, total_before) = course::solved_count(&browser, &c);
    let texts = draw(&browser, phys, &mut c);
    assert!(
        texts
            .iter()
            .any(|t| t == &format!("challenges   0/{CHALLENGES} solved")),
        "{:?}",
        texts
            .iter()
            .filter(|t| t.starts_with("challenges"))
            .collect::<Vec<_>>()
    );
    let rows: Vec<_> = c
        .rows
        .iter()
        .filter(|r| r.path.starts_with("levels/challenges"))
        .collect();
    assert_eq!(rows.len(), CHALLENGES, "the challenges' rows are drawn");
    for row in rows {
        assert!(!row.text.contains("no questions"), "{}", row.text);
    }

    // A challenge missed twice, then met at its third launch: solved, 3 launches, 2 stars.
    for met in [false, false, true] {
        let kept = course::record_launch(&mut c, &browser, &cup, met, if met { 0.0 } else { 0.05 });
        assert_eq!(
            kept, None,
            "a course without a store keeps it for the session"
        );
    }
    // A launch after it was met is play: the stars stay.
    course::record_launch(&mut c, &browser, &cup, false, 0.2);
    let key = course::level_key(&browser.root, &cup.scene.file, &cup.scene.level.title);
    assert_eq!(c.progress.status(&key), Status::Solved);
    assert_eq!(c.progress.get(&key).unwrap().attempts, 3);
    assert_eq!(progress::challenge_stars(&c.progress, &key), Some(stars(3)));
    assert_eq!(stars(3), 2);
    assert_eq!(course::challenge_record(&c, &browser, &cup), (3, Some(2)));
    let (solved, total) = course::solved_count(&browser, &c);
    assert_eq!((solved, total), (1, total_before.max(total)));
    draw(&browser, phys, &mut c);
    let row = c
        .rows
        .iter()
        .find(|r| r.path == cup.scene.file)
        .expect("the cup's row is drawn");
    assert_eq!(row.status, Status::Solved);
    assert!(row.text.contains("3× **"), "{}", row.text);
    let texts = draw(&browser, phys, &mut c);
    assert!(
        texts
            .iter()
            .any(|t| t == &format!("challenges   1/{CHALLENGES} solved")),
        "{:?}",
        texts
            .iter()
            .filter(|t| t.starts_with("challenges"))
            .collect::<Vec<_>>()
    );
}
