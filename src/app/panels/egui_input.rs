//! The keys and the pointer's moves and buttons to the window's egui context, in the order they
//! came, a frame at a time so that a text box clicked has the focus before the keys typed for it
//! (in place of bevy_egui's systems for them: `panels/mod.rs` turns those off).
//!
//! Why (issue 42, the student trial of 2026-12-07): egui's text box takes a frame's key events
//! while it is drawn, if it has the focus then, and asks for the focus only afterwards, when it
//! sees the press on it (egui 0.36, `TextEdit::show`); and egui moves the focus as it draws the
//! box clicked, before the boxes below it. In the page at 3-10 fps a click into a box and the
//! first keys typed came in one frame: those keys went nowhere ("7.104" became ".104", graded
//! wrong by 98.5%), or to the box focused before the click; two clicks and their answers in one
//! frame focused neither box. [`route`] keeps presses and keys in frames of their own.

use super::shortcuts::{egui_events, Held};
use bevy::input::keyboard::KeyboardInput;
use bevy::input::touch::TouchPhase;
use bevy::prelude::*;
use bevy::window::{RequestRedraw, WindowEvent};
use bevy_egui::input::{EguiContextPointerPosition, EguiInputEvent};
use bevy_egui::{egui, EguiZoomFactor, PrimaryEguiContext};

/// One of the window's messages egui gets from here, in the order they came.
#[derive(Debug, Clone, PartialEq)]
pub enum Input {
    Key(KeyboardInput),
    /// The window lost the keyboard: no modifier is held any more.
    FocusLost,
    /// The cursor, in the window's logical pixels.
    Moved(Vec2),
    /// A mouse button pressed (true) or released.
    Button(MouseButton, bool),
    /// A finger down (bevy_egui sends the touches; here it only marks a press).
    Touch,
}

impl Input {
    fn of(e: &WindowEvent) -> Option<Input> {
        Some(match e {
            WindowEvent::KeyboardInput(k) => Input::Key(k.clone()),
            WindowEvent::KeyboardFocusLost(_) => Input::FocusLost,
            WindowEvent::CursorMoved(m) => Input::Moved(m.position),
            WindowEvent::MouseButtonInput(b) => Input::Button(b.button, b.state.is_pressed()),
            WindowEvent::TouchInput(t) if t.phase == TouchPhase::Started => Input::Touch,
            _ => return None,
        })
    }
}

/// The modifiers as egui's keys have seen them, and what waits for the next frame.
#[derive(Resource, Debug, Default)]
pub struct EguiInputQueue {
    pub held: Held,
    pub waiting: Vec<Input>,
}

/// The messages that waited from the last frame (`waiting`) and this frame's (`frame`, as the
/// window delivered them), split into what egui gets this frame and what waits for the next: a
/// frame ends before a key that follows a press in it, and before a press that follows a key or
/// another press; the cursor's moves and the buttons' releases go along. So a click into a box
/// is a frame before the keys typed for it, and the keys typed before a click a frame before the
/// click, whatever the frame rate.
pub fn route<'a>(
    waiting: Vec<Input>,
    frame: impl IntoIterator<Item = &'a WindowEvent>,
) -> (Vec<Input>, Vec<Input>) {
    let incoming = waiting
        .into_iter()
        .chain(frame.into_iter().filter_map(Input::of));
    let (mut now, mut next) = (Vec::new(), Vec::new());
    let (mut typed, mut pressed) = (false, false);
    for m in incoming {
        let ends = match &m {
            Input::Key(_) => pressed,
            Input::Button(_, true) | Input::Touch => pressed || typed,
            _ => false,
        };
        if ends || !next.is_empty() {
            next.push(m);
            continue;
        }
        match &m {
            Input::Key(_) => typed = true,
            Input::Button(_, true) | Input::Touch => pressed = true,
            _ => {}
        }
        now.push(m);
    }
    (now, next)
}

/// egui's name of a mouse button (None: one egui does not know).
fn pointer_button(b: MouseButton) -> Option<egui::PointerButton> {
    Some(match b {
        MouseButton::Left => egui::PointerButton::Primary,
        MouseButton::Right => egui::PointerButton::Secondary,
        MouseButton::Middle => egui::PointerButton::Middle,
        MouseButton::Back => egui::PointerButton::Extra1,
        MouseButton::Forward => egui::PointerButton::Extra2,
        MouseButton::Other(_) => return None,
    })
}

/// This frame's share of the window's messages to the primary egui context ([`route`]): keys
/// with the modifiers held at each (a Ctrl+A within one frame selects, it does not type "a"),
/// the cursor (divided by egui's zoom, as bevy_egui does) and the buttons with the modifiers
/// held then. A frame with messages waiting asks for the next one at once (a paused page waits
/// for input).
pub fn input_to_egui(
    mut window: MessageReader<WindowEvent>,
    mut queue: ResMut<EguiInputQueue>,
    mut context: Query<
        (Entity, &EguiZoomFactor, &mut EguiContextPointerPosition),
        With<PrimaryEguiContext>,
    >,
    mut out: MessageWriter<EguiInputEvent>,
    mut redraw: MessageWriter<RequestRedraw>,
) {
    let waiting = std::mem::take(&mut queue.waiting);
    let (now, next) = route(waiting, window.read());
    let Ok((context, zoom, mut pointer)) = context.single_mut() else {
        return;
    };
    let mut send = |event| {
        out.write(EguiInputEvent { context, event });
    };
    for m in now {
        match m {
            Input::FocusLost => queue.held = Held::default(),
            Input::Key(e) => egui_events(&mut queue.held, &e)
                .into_iter()
                .for_each(&mut send),
            Input::Moved(at) => {
                let z = zoom.zoom_factor;
                pointer.position = egui::pos2(at.x / z, at.y / z);
                send(egui::Event::PointerMoved(pointer.position));
            }
            Input::Button(b, pressed) => {
                if let Some(button) = pointer_button(b) {
                    send(egui::Event::PointerButton {
                        pos: pointer.position,
                        button,
                        pressed,
                        modifiers: queue.held.egui(),
                    });
                }
            }
            Input::Touch => {}
        }
    }
    if !next.is_empty() {
        redraw.write(RequestRedraw);
    }
    queue.waiting = next;
}
