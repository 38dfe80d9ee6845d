//! Keys typed at once after a click into an answer box reach that box whole (issue 42, the
//! student trial of 2026-12-07: in the page at 3-10 fps a student clicked the box and typed
//! "7.104"; the box got ".104" and the answer was graded wrong by 98.5%).
//!
//! The mechanism (egui 0.36, `TextEdit::show`): a text box takes the frame's key events while it
//! is drawn, if it has the focus then, and asks for the focus only afterwards, when it sees the
//! press on it. At a low frame rate the press and the first keys come in one frame: those keys
//! went nowhere (or, with another box focused, to that box). The keys after a press in its
//! frame now wait for the next frame (`shortcuts::keys_to_egui`).
//!
//! Driven as the window drives it: the window's messages written as bevy_winit writes them
//! (each typed message, then the ordered `WindowEvent` batch) into the system that feeds egui's
//! keys, the pointer's events as bevy_egui makes them from the same batch, and the left column
//! of the small-swing pendulum (two questions) drawn into a bare egui context at 1280x800.

use bevy::input::keyboard::{Key, KeyboardFocusLost, KeyboardInput};
use bevy::input::mouse::MouseButtonInput;
use bevy::input::ButtonState;
use bevy::prelude::*;
use bevy::window::{RequestRedraw, WindowEvent};
use bevy_egui::input::EguiInputEvent;
use bevy_egui::{egui, PrimaryEguiContext};
use rigidlab::app::panels::{self, shortcuts, Browser, Course, Exercise};
use rigidlab::app::{LiveChecks, Run};
use rigidlab::sim::Options;

use crate::common;
use crate::common::app::key;

/// One thing the student does, as the window reports it.
#[derive(Clone)]
enum Act {
    /// A click (press and release) at a point.
    Click(egui::Pos2),
    /// A character typed (pressed and released).
    Type(char),
}

/// The system that gives egui the keys, alone in an app, with the window's messages.
fn key_app() -> App {
    let mut app = App::new();
    app.add_message::<KeyboardInput>()
        .add_message::<KeyboardFocusLost>()
        .add_message::<MouseButtonInput>()
        .add_message::<WindowEvent>()
        .add_message::<EguiInputEvent>()
        .add_message::<RequestRedraw>()
        .init_resource::<shortcuts::EguiKeys>()
        .add_systems(Update, shortcuts::keys_to_egui);
    app.world_mut().spawn(PrimaryEguiContext);
    app.update();
    app
}

fn code(c: char) -> KeyCode {
    match c {
        '.' => KeyCode::Period,
        '0' => KeyCode::Digit0,
        '1' => KeyCode::Digit1,
        '2' => KeyCode::Digit2,
        '4' => KeyCode::Digit4,
        '6' => KeyCode::Digit6,
        '7' => KeyCode::Digit7,
        '9' => KeyCode::Digit9,
        _ => panic!("no key for {c:?} in this test"),
    }
}

/// One frame of `acts`: the egui events the window gives the context, in order (the pointer's
/// first, as bevy_egui writes them before the keys), and whether a redraw was asked for.
fn frame(app: &mut App, acts: &[Act]) -> (Vec<egui::Event>, bool) {
    let window = Entity::PLACEHOLDER;
    let mut pointer = Vec::new();
    let mut batch = Vec::new();
    for a in acts {
        match a {
            Act::Click(at) => {
                pointer.push(egui::Event::PointerMoved(*at));
                for pressed in [true, false] {
                    pointer.push(egui::Event::PointerButton {
                        pos: *at,
                        button: egui::PointerButton::Primary,
                        pressed,
                        modifiers: Default::default(),
                    });
                    let m = MouseButtonInput {
                        button: MouseButton::Left,
                        state: if pressed {
                            ButtonState::Pressed
                        } else {
                            ButtonState::Released
                        },
                        window,
                    };
                    app.world_mut().write_message(m);
                    batch.push(WindowEvent::MouseButtonInput(m));
                }
            }
            Act::Type(c) => {
                for down in [true, false] {
                    let k = key(code(*c), Key::Character(c.to_string().into()), down);
                    app.world_mut().write_message(k.clone());
                    batch.push(WindowEvent::KeyboardInput(k));
                }
            }
        }
    }
    app.world_mut()
        .resource_mut::<Messages<WindowEvent>>()
        .write_batch(batch);
    app.update();
    let keys: Vec<egui::Event> = app
        .world()
        .resource::<Messages<EguiInputEvent>>()
        .iter_current_update_messages()
        .map(|m| m.event.clone())
        .collect();
    let redraw = app
        .world()
        .resource::<Messages<RequestRedraw>>()
        .iter_current_update_messages()
        .count()
        > 0;
    pointer.extend(keys);
    (pointer, redraw)
}

/// The left column drawn once with `events`.
fn draw(
    ctx: &egui::Context,
    (phys, live): (&Run, &LiveChecks),
    ex: &mut Exercise,
    events: Vec<egui::Event>,
) {
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1280.0, 800.0),
        )),
        events,
        ..Default::default()
    };
    let mut browser = Browser::default();
    let _ = ctx.run_ui(input, |ui| {
        egui::Panel::left("levels")
            .default_size(300.0)
            .show(ui, |ui| {
                panels::left_column(ui, &mut browser, (phys, live), ex, &mut Course::default());
            });
    });
}

fn typed(text: &str) -> Vec<Act> {
    text.chars().map(Act::Type).collect()
}

#[test]
fn keys_typed_with_the_click_into_a_box_reach_it() {
    let phys = Run::new(
        common::load("levels/kinetics/classic_physical_pendulum_small.ron"),
        Options::default(),
    );
    assert_eq!(
        phys.sim.level.questions.len(),
        2,
        "the test needs two boxes"
    );
    let live = LiveChecks::new(&phys);
    let mut ex = Exercise::default();
    ex.start(2);
    let ctx = egui::Context::default();
    let mut app = key_app();
    let mut play = |ex: &mut Exercise, acts: &[Act]| -> bool {
        let (events, redraw) = frame(&mut app, acts);
        draw(&ctx, (&phys, &live), ex, events);
        redraw
    };
    play(&mut ex, &[]);
    let centre = |ex: &Exercise, k: usize| ex.answer_boxes[k].expect("a box drawn").center();

    // The click into the first box and "7" in one frame, ".104" in the next.
    let mut first = vec![Act::Click(centre(&ex, 0)), Act::Type('7')];
    let redraw = play(&mut ex, &first);
    play(&mut ex, &typed(".104"));
    play(&mut ex, &[]);
    assert_eq!(ex.answers[0], "7.104", "the first box");
    assert!(
        redraw,
        "keys held for the next frame, and no redraw asked for it"
    );

    // With that box focused, a click into the second and its whole answer in one frame: all
    // of it goes to the second box, none to the first (it had the focus when it was drawn).
    let mut second = vec![Act::Click(centre(&ex, 1))];
    second.extend(typed("19.62"));
    play(&mut ex, &second);
    play(&mut ex, &[]);
    assert_eq!(
        ex.answers[0], "7.104",
        "keys for the second box went to the first"
    );
    assert_eq!(ex.answers[1], "19.62", "the second box");

    // Keys typed before a click in the same frame stay the focused box's: with the first box
    // focused again, "9" ends its answer, then the click into the second box and "6" go there
    // (each inserted where the click put the cursor). (The other way, a key typed in the lower
    // box in the frame of a click into the higher one, is lost: egui moves the focus as it
    // draws the box clicked, before the lower box; `shortcuts::route_keys`.)
    play(&mut ex, &[Act::Click(centre(&ex, 0))]);
    play(
        &mut ex,
        &[Act::Type('9'), Act::Click(centre(&ex, 1)), Act::Type('6')],
    );
    play(&mut ex, &[]);
    let count = |s: &str, c: char| s.chars().filter(|x| *x == c).count();
    assert!(
        ex.answers[0].len() == 6 && count(&ex.answers[0], '9') == 1,
        "the key before the click: {:?}",
        ex.answers[0]
    );
    assert!(
        ex.answers[1].len() == 6 && count(&ex.answers[1], '6') == 2,
        "the key after the click: {:?}",
        ex.answers[1]
    );
}
