//! The help names every tool and panel, natively and in the page (where it names no folder and
//! no command line); the tour's ticks stay once earned, and all seven can be earned in order.

use rigidlab::app::panels::help::{keys, sections};
use rigidlab::app::panels::tour::Tour;
use rigidlab::app::tools::ToolState;

fn text(web: bool) -> String {
    let mut t: String = keys(web)
        .iter()
        .map(|(k, w)| format!("{k} {w}\n"))
        .collect();
    for (title, body) in sections(web) {
        t.push_str(&format!("{title}\n{body}\n"));
    }
    t.to_lowercase()
}

#[test]
fn help_covers_every_tool_and_panel() {
    for web in [false, true] {
        let t = text(web);
        for what in [
            "plots",
            "csv",
            "stopwatch",
            "period",
            "motor",
            "solver panel",
            "ruler",
            "protractor",
            "place",
            "join",
            "spring",
            "torsion",
            "polygon",
            "curved track",
            "strike",
            "set o",
            "question",
            "compute it",
            "preview",
            "undo",
        ] {
            assert!(t.contains(what), "help (web: {web}) says nothing of {what}");
        }
    }
}

#[test]
fn the_pages_help_names_no_folder_and_no_command_line() {
    let t = text(true);
    for native in [
        "rigidlab check",
        "saved-levels/",
        "exports/",
        "screenshots/",
        "`",
    ] {
        assert!(!t.contains(native), "the page's help mentions {native}");
    }
    // The native help does say where files go.
    let n = text(false);
    assert!(n.contains("saved-levels/") && n.contains("rigidlab check"));
}

#[test]
fn tour_ticks_stay_once_earned_and_all_seven_come_in_order() {
    let names = [
        "play", "click", "diagrams", "back", "answer", "build", "help",
    ];
    let mut tour = Tour::default();
    // Step k done now (live state), as the student goes through the steps in order; opening a
    // new scene for step 6 ("build") drops the run, the selection and the answers, so the live
    // state of steps 1..5 is false again there.
    for k in 0..7 {
        let live: Vec<(&'static str, bool)> = names
            .iter()
            .enumerate()
            .map(|(i, n)| (*n, if k >= 5 { i == k } else { i <= k }))
            .collect();
        let shown = tour.tick(live);
        let done = shown.iter().filter(|(_, d)| *d).count();
        assert_eq!(done, k + 1, "after step {}: {shown:?}", k + 1);
    }
    // A level change later: nothing live, nothing lost.
    let shown = tour.tick(names.iter().map(|n| (*n, false)).collect());
    assert!(shown.iter().all(|(_, d)| *d), "{shown:?}");
}

#[test]
fn ruler_and_protractor_marks_go_with_the_level() {
    let mut t = ToolState {
        ruler: Some((glam::DVec2::ZERO, glam::DVec2::X)),
        protractor: Some(rigidlab::app::tools::Protractor {
            vertex: glam::DVec2::ZERO,
            arm1: glam::DVec2::X,
            arm2: Some(glam::DVec2::Y),
            dragging: false,
        }),
        ..ToolState::default()
    };
    t.forget_marks();
    assert!(t.ruler.is_none() && t.protractor.is_none());
}
