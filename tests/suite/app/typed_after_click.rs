//! Keys typed at once after a click into an answer box reach that box whole (issue 42, the
//! student trial of 2026-12-07: in the page at 3-10 fps a student clicked the box and typed
//! "7.104"; the box got ".104" and the answer was graded wrong by 98.5%).
//!
//! The mechanism (egui 0.36, `TextEdit::show`): a text box takes the frame's key events while it
//! is drawn, if it has the focus then, and asks for the focus only afterwards, when it sees the
//! press on it; egui moves the focus as it draws the box clicked. At a low frame rate the press
//! and the first keys come in one frame: those keys went nowhere (or, with another box focused,
//! to that box). Presses and keys now go to egui in frames of their own
//! (`panels::egui_input::route`).
//!
//! Driven as the window drives it: the window's messages written as bevy_winit writes them
//! (each typed message, then the ordered `WindowEvent` batch) into the system that feeds egui,
//! and the left column of the small-swing pendulum (two questions) drawn with what it sent into
//! a bare egui context at 1280x800.

use bevy::input::keyboard::{Key, KeyboardFocusLost, KeyboardInput};
use bevy::input::mouse::MouseButtonInput;
use bevy::input::ButtonState;
use bevy::prelude::*;
use bevy::window::CursorMoved;
use bevy::window::{RequestRedraw, WindowEvent};
use bevy_egui::input::EguiInputEvent;
use bevy_egui::{egui, PrimaryEguiContext};
use rigidlab::app::panels::{self, egui_input, Browser, Course, Exercise};
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

/// The system that gives egui the keys and the pointer, alone in an app, with the window's
/// messages.
fn key_app() -> App {
    let mut app = App::new();
    app.add_message::<KeyboardInput>()
        .add_message::<KeyboardFocusLost>()
        .add_message::<MouseButtonInput>()
        .add_message::<CursorMoved>()
        .add_message::<WindowEvent>()
        .add_message::<EguiInputEvent>()
        .add_message::<RequestRedraw>()
        .init_resource::<egui_input::EguiInputQueue>()
        .add_systems(Update, egui_input::input_to_egui);
    app.world_mut().spawn(PrimaryEguiContext);
    app.update();
    app
}

fn code(c: char) -> KeyCode {
    const DIGITS: [KeyCode; 10] = [
        KeyCode::Digit0,
        KeyCode::Digit1,
        KeyCode::Digit2,
        KeyCode::Digit3,
        KeyCode::Digit4,
        KeyCode::Digit5,
        KeyCode::Digit6,
        KeyCode::Digit7,
        KeyCode::Digit8,
        KeyCode::Digit9,
    ];
    match c {
        '.' => KeyCode::Period,
        d => DIGITS[d.to_digit(10).expect("a digit or a point") as usize],
    }
}

/// One frame of `acts`: the egui events the system sends the context, in order, and whether it
/// asked for a redraw.
fn frame(app: &mut App, acts: &[Act]) -> (Vec<egui::Event>, bool) {
    let window = Entity::PLACEHOLDER;
    let mut batch = Vec::new();
    for a in acts {
        match a {
            Act::Click(at) => {
                let moved = CursorMoved {
                    window,
                    position: Vec2::new(at.x, at.y),
                    delta: None,
                };
                app.world_mut().write_message(moved.clone());
                batch.push(WindowEvent::CursorMoved(moved));
                for state in [ButtonState::Pressed, ButtonState::Released] {
                    let m = MouseButtonInput {
                        button: MouseButton::Left,
                        state,
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
    let events: Vec<egui::Event> = app
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
    (events, redraw)
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

/// The small-swing pendulum's left column and the input system, a frame drawn.
struct Page {
    phys: Run,
    live: LiveChecks,
    ex: Exercise,
    ctx: egui::Context,
    app: App,
}

impl Page {
    fn new() -> Page {
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
        let mut page = Page {
            phys,
            live,
            ex,
            ctx: egui::Context::default(),
            app: key_app(),
        };
        page.play(&[]);
        page
    }

    /// One frame of `acts`; whether a redraw was asked for.
    fn play(&mut self, acts: &[Act]) -> bool {
        let (events, redraw) = frame(&mut self.app, acts);
        draw(&self.ctx, (&self.phys, &self.live), &mut self.ex, events);
        redraw
    }

    /// Frames with no input until nothing waits (at most 40).
    fn settle(&mut self) {
        for _ in 0..40 {
            if !self.play(&[]) {
                return;
            }
        }
        panic!("input still waiting after 40 frames");
    }

    fn click(&self, k: usize) -> Act {
        Act::Click(self.ex.answer_boxes[k].expect("a box drawn").center())
    }
}

#[test]
fn keys_typed_with_the_click_into_a_box_reach_it() {
    let mut p = Page::new();
    // The click into the first box and "7" in one frame, ".104" in the next.
    let redraw = p.play(&[p.click(0), Act::Type('7')]);
    p.play(&typed(".104"));
    p.settle();
    assert_eq!(p.ex.answers[0], "7.104", "the first box");
    assert!(
        redraw,
        "keys held for the next frame, and no redraw asked for it"
    );

    // With that box focused, a click into the second and its whole answer in one frame: all
    // of it goes to the second box, none to the first (it had the focus when it was drawn).
    let mut second = vec![p.click(1)];
    second.extend(typed("19.62"));
    p.play(&second);
    p.settle();
    assert_eq!(
        p.ex.answers[0], "7.104",
        "keys for the second box went to the first"
    );
    assert_eq!(p.ex.answers[1], "19.62", "the second box");
}

/// Both answers typed, each right after its click, within one frame (a fast student on a page
/// at 3 fps; the browser test's typing): before, neither box took the focus nor any key.
#[test]
fn two_clicks_and_their_answers_in_one_frame_each_reach_their_box() {
    let mut p = Page::new();
    let mut acts = vec![p.click(0)];
    acts.extend(typed("42"));
    acts.push(p.click(1));
    acts.extend(typed("8.25"));
    p.play(&acts);
    p.settle();
    assert_eq!(p.ex.answers, ["42", "8.25"]);
}

/// Keys typed just before a click, in its frame, stay the focused box's, also where the box
/// clicked is drawn above it (egui would move the focus to it before the lower box reads its
/// keys): the second box focused, "9" ends its answer, then the click into the first and "6".
#[test]
fn keys_typed_before_a_click_stay_the_focused_boxs() {
    let mut p = Page::new();
    let mut acts = vec![p.click(1)];
    acts.extend(typed("19.6"));
    p.play(&acts);
    p.settle();
    p.play(&[Act::Type('2'), p.click(0), Act::Type('6')]);
    p.settle();
    assert_eq!(p.ex.answers, ["6", "19.62"]);
}
