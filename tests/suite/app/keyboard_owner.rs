//! Keys meant for a box never act as shortcuts (issue 42, the student trial of 2026-12-07): the
//! keyboard is the scene's only after a click in the scene, a press on a panel gives it to the
//! panels in the very frame of the press, and a question's box does not move when an answer
//! above it is checked (a click aimed at it missed, and the typed answer played and reset the
//! run). The shortcut systems run as the window runs them; the left column is drawn into a bare
//! egui context at a 1280x800 screen.

use bevy::input::keyboard::Key;
use bevy::input::mouse::MouseButtonInput;
use bevy::input::{ButtonState, InputPlugin};
use bevy::prelude::*;
use bevy_egui::egui;
use rigidlab::app::overlays::{overlay_keys, Overlays};
use rigidlab::app::panels::{self, shortcuts, Browser, Exercise, UiState};
use rigidlab::app::tools::{Tool, ToolState};
use rigidlab::app::ui::Typing;
use rigidlab::app::view::View;
use rigidlab::app::{LiveChecks, PhysicsCommand, Playback, Run};
use rigidlab::sim::Options;

use crate::common;
use crate::common::app::{click, editor_app_unstarted, key, left_column, Drawn};

/// The scene between the panels of a 1280x800 window (logical pixels).
fn scene() -> Rect {
    Rect::new(320.0, 30.0, 930.0, 710.0)
}

/// The window's shortcut systems on a paused run, with a window whose cursor is at `at`.
fn keyboard_app() -> (App, Entity) {
    let mut app = editor_app_unstarted();
    app.add_plugins(InputPlugin)
        .insert_resource(View {
            viewport: scene(),
            ..View::default()
        })
        .init_resource::<UiState>()
        .init_resource::<ToolState>()
        .init_resource::<Overlays>()
        .init_resource::<Typing>()
        .add_message::<PhysicsCommand>()
        .add_systems(
            Update,
            (
                shortcuts::follow_presses
                    .before(shortcuts::keys)
                    .before(overlay_keys),
                shortcuts::keys,
                overlay_keys,
            ),
        );
    let window = app.world_mut().spawn(Window::default()).id();
    app.update();
    (app, window)
}

/// A click at `at` and, in the same frame, the keys `typed`: at 3-6 fps in the page the click
/// into a box and the first key of the answer come in one frame.
fn click_and_type(app: &mut App, window: Entity, at: Vec2, typed: &[(KeyCode, Key)]) {
    app.world_mut()
        .get_mut::<Window>(window)
        .unwrap()
        .set_cursor_position(Some(at));
    let press = |state| MouseButtonInput {
        button: MouseButton::Left,
        state,
        window,
    };
    app.world_mut().write_message(press(ButtonState::Pressed));
    for (code, k) in typed {
        app.world_mut().write_message(key(*code, k.clone(), true));
    }
    app.update();
    app.world_mut().write_message(press(ButtonState::Released));
    for (code, k) in typed {
        app.world_mut().write_message(key(*code, k.clone(), false));
    }
    app.update();
}

fn typed(text: &str) -> Vec<(KeyCode, Key)> {
    text.chars()
        .map(|c| match c {
            '2' => (KeyCode::Digit2, Key::Character("2".into())),
            '1' => (KeyCode::Digit1, Key::Character("1".into())),
            'r' => (KeyCode::KeyR, Key::Character("r".into())),
            'l' => (KeyCode::KeyL, Key::Character("l".into())),
            ' ' => (KeyCode::Space, Key::Space),
            _ => panic!("no key for {c:?} in this test"),
        })
        .collect()
}

/// A click on the left panel (a box's old place, or the box itself in the click's frame) and
/// "2 r l " typed with it: no tool chosen, no reset, no play, no overlay. Before 2026-12-07 the
/// keyboard stayed the scene's until egui had focused a box, and "2" chose the impulse tool.
#[test]
fn a_press_on_a_panel_gives_the_keys_to_the_panels_in_its_frame() {
    let (mut app, window) = keyboard_app();
    let before = app.world().resource::<Overlays>().clone();
    let restarts = |app: &App| app.world().resource::<Run>().generation;
    let generation = restarts(&app);
    // On the left panel, where an answer box is.
    click_and_type(&mut app, window, Vec2::new(120.0, 400.0), &typed("2 r l "));
    assert!(
        app.world().resource::<Typing>().active,
        "the press on the panel did not give it the keyboard"
    );
    assert_eq!(
        app.world().resource::<ToolState>().tool,
        Tool::Select,
        "2 chose a tool"
    );
    assert!(
        app.world().resource::<Playback>().paused,
        "Space played the run"
    );
    assert_eq!(restarts(&app), generation, "R reset the run");
    assert_eq!(
        *app.world().resource::<Overlays>(),
        before,
        "L toggled the labels"
    );

    // A click in the scene: the keys are the shortcuts' again, from that frame on.
    click_and_type(&mut app, window, Vec2::new(600.0, 300.0), &typed("2"));
    assert!(!app.world().resource::<Typing>().active);
    assert_eq!(app.world().resource::<ToolState>().tool, Tool::Impulse);
    // A press off the window (None) or on the right panel is not the scene's.
    click_and_type(&mut app, window, Vec2::new(1100.0, 300.0), &typed("1"));
    assert_eq!(
        app.world().resource::<ToolState>().tool,
        Tool::Impulse,
        "1 chose a tool after a click on the right panel"
    );
}

/// The rule itself: a press outside the scene's viewport or over an egui window drawn over it
/// (the Challenge box, the tour) is the panels'; in the bare scene, the shortcuts'.
#[test]
fn a_press_is_the_scenes_only_in_the_bare_scene() {
    let mut t = Typing::default();
    t.press(true, Some(Vec2::new(100.0, 100.0)), scene(), false);
    assert!(t.active, "a press on the left panel");
    t.press(true, Some(Vec2::new(500.0, 300.0)), scene(), false);
    assert!(!t.active, "a press in the scene");
    t.press(true, Some(Vec2::new(500.0, 300.0)), scene(), true);
    assert!(t.active, "a press on a window over the scene");
    t.press(false, Some(Vec2::new(500.0, 300.0)), scene(), false);
    assert!(t.active, "no press, no change");
    t.press(true, None, scene(), false);
    assert!(t.active, "a press off the window");
    // The help says the rule where the keys are listed.
    assert!(panels::help::KEYBOARD_RULE.contains("click in the scene"));
}

/// A wrong answer to the first question of the small-swing physical pendulum (two questions, a
/// typical mistake with its message, hints and a worked solution, all in sight at 1280x800)
/// checked: the verdict appears under it, and
/// the second question's box, its Check button, *Show solution* and *Next level* stay where
/// they were (the box moved down by the verdict's rows, and the click aimed at it missed).
#[test]
fn checking_an_answer_moves_no_box_below_it() {
    let phys = Run::new(
        common::load("levels/kinetics/classic_physical_pendulum_small.ron"),
        Options::default(),
    );
    let live = LiveChecks::new(&phys);
    let q = &phys.sim.level.questions[0];
    assert!(
        !q.mistakes.is_empty(),
        "the test needs a question with mistakes"
    );
    let mut ex = Exercise::default();
    ex.start(phys.sim.level.questions.len());
    let ctx = egui::Context::default();
    let mut browser = Browser::default();
    let before_texts = left_column(&ctx, &mut browser, (&phys, &live), &mut ex, Vec::new());
    let boxes_before = ex.answer_boxes.clone();
    let place = |texts: &[Drawn], label: &str, nth: usize| {
        texts
            .iter()
            .filter(|d| d.text == label)
            .nth(nth)
            .map(|d| d.rect)
            .unwrap_or_else(|| panic!("no {label:?} #{nth} drawn"))
    };
    // The answer of the level's first typical mistake: its message, the longest verdict.
    ex.answers[0] = format!("{}", q.mistakes[0].value);
    let check = place(&before_texts, "Check", 0).center();
    left_column(
        &ctx,
        &mut browser,
        (&phys, &live),
        &mut ex,
        click(check, true),
    );
    let after_texts = left_column(
        &ctx,
        &mut browser,
        (&phys, &live),
        &mut ex,
        click(check, false),
    );
    let grade = ex.grades[0].clone().expect("the first answer was checked");
    let (message, right) = panels::grade_message(q, &grade);
    assert!(!right, "{message}");
    assert!(
        after_texts.iter().any(|d| d.text == message),
        "the verdict {message:?} is not drawn"
    );
    // Half a pixel: egui rounds positions to pixels.
    for (k, before) in boxes_before.iter().enumerate().skip(1) {
        let (a, b) = (before.unwrap(), ex.answer_boxes[k].unwrap());
        assert!(
            (a.min.y - b.min.y).abs() < 0.5,
            "box {} moved from {a:?} to {b:?}",
            k + 1
        );
        let (a, b) = (
            place(&before_texts, "Check", k),
            place(&after_texts, "Check", k),
        );
        assert!(
            (a.min.y - b.min.y).abs() < 0.5,
            "Check {} moved from {a:?} to {b:?}",
            k + 1
        );
    }
    let solution_before = place(&before_texts, "Show solution", 0);
    let solution_after = place(&after_texts, "Show solution", 0);
    assert!(
        (solution_before.min.y - solution_after.min.y).abs() < 0.5,
        "Show solution moved from {solution_before:?} to {solution_after:?} (a hint came above it)"
    );
}
