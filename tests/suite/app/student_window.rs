//! What a student and a teacher meet first in the window (issue 42's first part), headless: the
//! window's size, the feedback's tolerance, the exercise above the level list, the keyboard
//! after typing in a box, controls that stay put, plot axes, legible small text, one reason per
//! preview, and saved versions told apart. The egui panels are drawn into a bare egui context
//! at the size of a 1280x800 screen (no GPU, no window).

use bevy::input::keyboard::Key;
use bevy::input::InputPlugin;
use bevy::prelude::*;
use bevy_egui::egui;
use rigidlab::app::editor::{preview_note, Editor};
use rigidlab::app::overlays::{overlay_keys, Overlays};
use rigidlab::app::panels::plots::nice_ticks;
use rigidlab::app::panels::{self, grade, grade_message, shortcuts, Browser, Exercise, UiState};
use rigidlab::app::tools::{Tool, ToolState};
use rigidlab::app::ui::{legible, Typing, SMALL_TEXT};
use rigidlab::app::view::View;
use rigidlab::app::{LiveChecks, PhysicsCommand, Playback, Run};
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::{Path, PathBuf};

use crate::common::app::{editor_app_unstarted, key};

/// One egui frame of `draw` on a screen of `size` logical pixels (run twice: egui settles sizes
/// it measured in its first pass).
fn frame(ctx: &egui::Context, size: (f32, f32), mut draw: impl FnMut(&mut egui::Ui)) {
    for _ in 0..2 {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(size.0, size.1),
            )),
            ..Default::default()
        };
        let _ = ctx.run_ui(input, &mut draw);
    }
}

fn load(file: &str) -> level::Scene {
    level::load(Path::new(file)).unwrap()
}

/// The window opens at a size a 1280x800 screen holds with a title bar (it opened at 1440x900,
/// cutting off the right panel and the status line), and, once the monitor is known, takes
/// what the screen has room for, up to 1440x900.
#[test]
fn the_window_fits_a_1280x800_screen() {
    let (w, h) = rigidlab::app::sandbox::OPENING_SIZE;
    // A title bar of 30 px at most and a taskbar of 30 px: 740 + 60 = 800.
    assert!(w <= 1280 && h + 60 <= 800, "{w}x{h}");
    let (w, h) = rigidlab::app::sandbox::fitted_size((1280.0, 800.0));
    assert!(w <= 1280.0 && h + 60.0 <= 800.0, "{w}x{h}");
    assert_eq!(
        rigidlab::app::sandbox::fitted_size((1920.0, 1080.0)),
        (1440.0, 900.0)
    );
    // Both side panels at their default widths (300 and 330) leave the scene most of the window.
    assert!(w - 630.0 >= 600.0, "{w}");
}

/// The simple pendulum's v_bottom question: the engine is judged within `tolerance` = 0.5 %,
/// the student within `student_tolerance`, 1 % by default. An answer 0.7 % off is right for the
/// student, and the message must print the 1.00 % that graded it (it printed 0.50 %: "correct:
/// off by 0.70% (tolerance 0.50%)", a contradiction on the student's screen).
#[test]
fn the_feedback_prints_the_tolerance_that_graded_the_answer() {
    let scene = load("levels/kinetics/simple_pendulum.ron");
    let q = &scene.level.questions[0];
    assert_eq!((q.tolerance, q.student_tolerance), (5e-3, 1e-2));
    // 0.7 % above the expected answer: between the two tolerances.
    let typed = format!("{:.4}", q.expected * 1.007);
    let (message, right) = grade_message(q, &grade(q, &typed));
    assert!(right, "{typed}: {message}");
    assert!(message.contains("(tolerance 1.00%)"), "{message}");
    // 1.5 % off fails, and says so against the same 1.00 %.
    let (message, right) = grade_message(q, &grade(q, &format!("{:.4}", q.expected * 1.015)));
    assert!(!right, "{message}");
    assert!(message.contains("(tolerance 1.00%)"), "{message}");
}

/// The left panel at a 1280x800 screen with the whole library listed: the open level's answer
/// box is on screen without scrolling (it sat below every level title, past the screen's
/// bottom), and a level opened from the list folds the list again.
#[test]
fn the_open_exercise_comes_before_the_level_list() {
    let mut browser = Browser::scan(Path::new("levels"));
    let titles: usize = browser.groups.values().map(Vec::len).sum();
    assert!(titles >= 30, "the library lists {titles} levels");
    let phys = Run::new(
        load("levels/kinetics/simple_pendulum.ron"),
        Options::default(),
    );
    let live = LiveChecks::new(&phys);
    let mut ex = Exercise::default();
    ex.start(phys.sim.level.questions.len());
    let ctx = egui::Context::default();
    let mut asked = None;
    frame(&ctx, (1280.0, 800.0), |ui| {
        egui::Panel::left("levels")
            .default_size(300.0)
            .show(ui, |ui| {
                asked = panels::left_column(
                    ui,
                    &mut browser,
                    (&phys, &live),
                    &mut ex,
                    &mut panels::Course::default(),
                );
            });
    });
    assert!(asked.is_none());
    let answer = ex.answer_boxes[0].expect("the first question's answer box was drawn");
    // The status line takes the bottom ~30 px of the window's 800.
    assert!(
        answer.max.y < 770.0,
        "the answer box is at {answer:?}, below the screen"
    );
}

/// After typing in a box that has lost the focus (Enter graded the answer, a button was
/// clicked), keys are still the box's: R does not reset the run, Space does not play it, L
/// and T do not toggle overlays (which the preferences saved). A click in the scene or Esc
/// gives the keys back to the shortcuts.
#[test]
fn keys_typed_after_a_text_box_lost_focus_are_not_shortcuts() {
    // The window's rule, frame by frame.
    let mut t = Typing::default();
    t.follow(true, false, false);
    assert!(t.active, "a focused text field has the keyboard");
    t.follow(false, false, false);
    assert!(t.active, "the focus lost, the keys stay off the shortcuts");
    t.follow(false, true, false);
    assert!(!t.active, "a click in the scene gives them back");
    t.follow(true, false, false);
    t.follow(false, false, true);
    assert!(!t.active, "Esc gives them back");

    // The shortcut systems, as the window runs them.
    let mut app = editor_app_unstarted();
    app.add_plugins(InputPlugin)
        .init_resource::<View>()
        .init_resource::<UiState>()
        .init_resource::<ToolState>()
        .init_resource::<Overlays>()
        .insert_resource(Typing { active: true })
        .add_message::<PhysicsCommand>()
        .add_systems(Update, (shortcuts::keys, overlay_keys));
    app.update();
    let before = app.world().resource::<Overlays>().clone();
    let press = |app: &mut App, code: KeyCode, k: Key| {
        app.world_mut().write_message(key(code, k.clone(), true));
        app.update();
        app.world_mut().write_message(key(code, k, false));
        app.update();
    };
    let tool_before = app.world().resource::<ToolState>().tool;
    // A typed answer "2 r" and a path "levels/t.ron": digits, letters, space.
    for (code, c) in [
        (KeyCode::Digit2, "2"),
        (KeyCode::KeyR, "r"),
        (KeyCode::KeyL, "l"),
        (KeyCode::KeyT, "t"),
        (KeyCode::KeyV, "v"),
    ] {
        press(&mut app, code, Key::Character(c.into()));
    }
    press(&mut app, KeyCode::Space, Key::Space);
    assert_eq!(
        *app.world().resource::<Overlays>(),
        before,
        "an overlay toggled"
    );
    assert_eq!(
        app.world().resource::<ToolState>().tool,
        tool_before,
        "2 chose a tool"
    );
    assert!(
        app.world().resource::<Playback>().paused,
        "Space played the run"
    );

    // A click in the scene later: the keys are shortcuts again.
    app.world_mut().resource_mut::<Typing>().active = false;
    press(&mut app, KeyCode::KeyL, Key::Character("l".into()));
    assert_ne!(
        app.world().resource::<Overlays>().labels,
        before.labels,
        "L toggles the labels once the keys are the shortcuts'"
    );
}

/// The Build tools stay where they were while the run plays, a blow strikes, a body is
/// selected, the free-body diagram is turned on, a tool is chosen and an edit is answered: a row
/// that appeared above them moved them under the pointer (the "save this moment" button at
/// t > 0, the force filters with F, the editor's note, the blows).
#[test]
fn the_build_tools_do_not_move_as_the_run_plays() {
    let scene = load("levels/momentum/bar_struck_below_percussion.ron");
    let ctx = egui::Context::default();
    let place = |phys: &Run, ov: &mut Overlays, tools: &mut ToolState, editor: &Editor| {
        let (mut view, mut st, mut asked) = (View::default(), UiState::default(), Vec::new());
        let play = Playback::new(true);
        frame(&ctx, (1280.0, 800.0), |ui| {
            egui::Panel::right("controls")
                .default_size(330.0)
                .show(ui, |ui| {
                    panels::upper_controls(
                        ui,
                        (phys, &play, editor),
                        (&mut view, ov, tools, &mut st),
                        &mut asked,
                    );
                });
        });
        ["new scene", "place box", "join pin", "curved track"].map(|b| st.buttons[b])
    };
    let phys = Run::new(scene.clone(), Options::default());
    let start = place(
        &phys,
        &mut Overlays::default(),
        &mut ToolState::default(),
        &Editor::default(),
    );
    // Half a second in (the blow struck at 0.1 s), the bar selected, F on, the impulse tool,
    // and an edit answered.
    let mut phys = Run::new(scene, Options::default());
    for _ in 0..(0.5 / phys.sim.dt()).round() as usize {
        assert!(phys.advance());
    }
    assert!(!phys.blows.is_empty(), "the blow is listed by now");
    let mut ov = Overlays {
        selected: Some(1),
        free_body: true,
        ..Overlays::default()
    };
    let mut tools = ToolState {
        tool: Tool::Impulse,
        ..Default::default()
    };
    let mut editor = Editor::default();
    editor.note = Some(("mass of bar set to 2 kg".into(), true));
    let later = place(&phys, &mut ov, &mut tools, &editor);
    for (a, b) in start.iter().zip(&later) {
        // Half a pixel: egui rounds positions to pixels.
        assert!((a.min.y - b.min.y).abs() < 0.5, "moved from {a:?} to {b:?}");
    }
}

/// The plots' axes have ticks at round numbers: 1, 2 or 5 times a power of ten, inside the
/// range, at most as many as asked.
#[test]
fn plot_ticks_are_round_numbers_inside_the_range() {
    assert_eq!(nice_ticks(0.0, 3.84, 5), [0.0, 1.0, 2.0, 3.0]);
    assert_eq!(nice_ticks(-4.2, 4.2, 5), [-4.0, -2.0, 0.0, 2.0, 4.0]);
    assert_eq!(nice_ticks(0.0, 3.6, 6), [0.0, 1.0, 2.0, 3.0]);
    let t = nice_ticks(9.780, 9.831, 5);
    assert_eq!(t.len(), 3, "{t:?}");
    assert!(
        (t[0] - 9.78).abs() < 1e-12 && (t[2] - 9.82).abs() < 1e-12,
        "{t:?}"
    );
    assert!(nice_ticks(1.0, 1.0, 5).is_empty());
    assert!(nice_ticks(f64::NAN, 1.0, 5).is_empty());
}

/// The small text (editor notes, preview verdicts, hints) is drawn at 11.5 points at least, not
/// egui's 9.
#[test]
fn small_text_is_legible() {
    let ctx = egui::Context::default();
    let small = |ctx: &egui::Context| ctx.global_style().text_styles[&egui::TextStyle::Small].size;
    assert!(
        small(&ctx) < SMALL_TEXT,
        "egui's own small text is {}",
        small(&ctx)
    );
    ctx.all_styles_mut(legible);
    assert!(small(&ctx) >= 11.0, "{}", small(&ctx));
}

/// A preview whose analysis is not applicable says so once: it also said "no analysis formula
/// for it" on the same line, a contradiction.
#[test]
fn a_preview_gives_one_reason_for_a_missing_analysis() {
    let result = |note: &str| -> rigidlab::questions::QuestionResult {
        serde_json::from_value(serde_json::json!({
            "id": "v", "ask": "speed", "unit": "m/s", "expected": 2.0, "analysis": null,
            "engine": 2.01, "rel_error": 0.005, "tolerance": 0.01, "passed": true, "time": 0.5,
            "why": "", "note": note,
        }))
        .unwrap()
    };
    let n = preview_note(&result(
        "analysis not applicable: the disc left the track; graded on the engine alone",
    ));
    assert!(!n.contains("no analysis formula"), "{n}");
    assert!(n.contains("analysis not applicable"), "{n}");
    let n = preview_note(&result(""));
    assert!(n.contains("no analysis formula"), "{n}");
}

/// Saved versions of one level are listed with their file name and the time they were written.
#[test]
fn saved_versions_show_their_file_and_date() {
    use std::time::{Duration, UNIX_EPOCH};
    let at = |s: u64| UNIX_EPOCH + Duration::from_secs(s);
    // 2026-12-07 00:10 UTC is 1796602200 s after the epoch; 2000-02-29 23:59 UTC 951868740 s
    // (both from Python's datetime, an independent calendar).
    assert_eq!(
        panels::utc_minute(at(1_796_602_200)).as_deref(),
        Some("2026-12-07 00:10 UTC")
    );
    assert_eq!(
        panels::utc_minute(at(951_868_740)).as_deref(),
        Some("2000-02-29 23:59 UTC")
    );
    let entry = |file: &str, s: u64| panels::Entry {
        path: PathBuf::from("saved-levels").join(file),
        title: "My scene".into(),
        statement: String::new(),
        error: None,
        questions: 0,
        challenge: false,
        source: None,
        modified: Some(at(s)),
    };
    let (a, b) = (
        panels::version_line(&entry("my-scene-saved.ron", 1_796_602_200)),
        panels::version_line(&entry("my-scene-saved-2.ron", 1_796_602_200 + 600)),
    );
    assert_eq!(a, "my-scene-saved.ron · 2026-12-07 00:10 UTC");
    assert_eq!(b, "my-scene-saved-2.ron · 2026-12-07 00:20 UTC");
}

/// The run says where the student looks when its energy drifts where the level conserves it:
/// the physical pendulum (gravity and a frictionless pin: T + V is constant, WE-14) at the
/// level's 120 Hz loses energy step by step to rapier's first-order integration (a known gap,
/// docs/known-gaps.md). Early in the run the drift is far below 5 % and nothing is said; by
/// 33 s it is past 5 % and the playback panel says how much and what to do (halve dt).
#[test]
fn an_energy_drift_is_said_where_the_student_looks() {
    let mut phys = Run::new(
        load("levels/kinetics/physical_pendulum.ron"),
        Options::default(),
    );
    let steps = |t: f64, phys: &Run| (t / phys.sim.dt()).round() as usize;
    for _ in 0..steps(0.5, &phys) {
        assert!(phys.advance());
    }
    assert_eq!(panels::energy_drift_note(&phys), None);
    for _ in steps(0.5, &phys)..steps(33.0, &phys) {
        assert!(phys.advance());
    }
    let (first, last) = (&phys.series[0], phys.series.last().unwrap());
    let drift = (last.total() - first.total()) / first.gravity.abs().max(first.kinetic.abs());
    println!(
        "energy drift after 33 s at the level's dt: {:+.1}%",
        drift * 100.0
    );
    let note = panels::energy_drift_note(&phys);
    if drift.abs() > panels::DRIFT_WARNING {
        let note = note.expect("a drift past 5 % is said");
        assert!(note.contains("halve dt"), "{note}");
        assert!(
            note.contains(&format!("{:.0}%", drift.abs() * 100.0)),
            "{note}"
        );
    } else {
        panic!(
            "the pendulum kept its energy within 5 % ({drift:+.3}): the test needs another scene"
        );
    }
    // A level with friction and contacts does not conserve energy: nothing to warn about.
    let rolling = Run::new(
        load("levels/kinetics/classic_rolling_disc.ron"),
        Options::default(),
    );
    assert_eq!(panels::energy_drift_note(&rolling), None);
}
