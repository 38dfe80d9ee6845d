//! The sandbox's headless app for the window tests (feature `app`): MinimalPlugins with one
//! FixedUpdate per `App::update`, the physics of a new scene (paused) and the editor; the editor
//! commands sent as the panels send them; keyboard messages as the window delivers them.

use bevy::app::ScheduleRunnerPlugin;
use bevy::input::keyboard::{Key, KeyboardInput};
use bevy::input::ButtonState;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_egui::egui;
use rigidlab::app::editor::{Editor, EditorCommand, EditorPlugin};
use rigidlab::app::overlays::Overlays;
use rigidlab::app::panels::{self, Browser, Course, Exercise, UiState};
use rigidlab::app::tools::ToolState;
use rigidlab::app::view::View;
use rigidlab::app::{LiveChecks, PhysicsCommand, PhysicsPlugin, Playback, Run};
use rigidlab::editor;
use rigidlab::level::Level;
use std::path::PathBuf;
use std::time::Duration;

/// The app before its first update (add plugins and resources, then `update`): a new scene
/// (`my-scene.ron`, a ground line), paused, with the editor.
pub fn editor_app_unstarted() -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene: editor::empty_scene(PathBuf::from("my-scene.ron")),
            options: Default::default(),
            paused: true,
        })
        .add_plugins(EditorPlugin);
    app
}

/// [`editor_app_unstarted`], started (its first update run).
pub fn editor_app() -> App {
    let mut app = editor_app_unstarted();
    app.update();
    app
}

/// Sends one editor command and runs a frame: the editor's note and whether it worked.
pub fn send(app: &mut App, c: EditorCommand) -> (String, bool) {
    app.world_mut().write_message(c);
    app.update();
    app.world()
        .resource::<Editor>()
        .note
        .clone()
        .expect("the editor answers every command")
}

pub fn phys(app: &App) -> &Run {
    app.world().resource::<Run>()
}

/// The scene's level on screen.
pub fn level(app: &App) -> &Level {
    &phys(app).scene.level
}

/// A key pressed or released, as the window reports it.
pub fn key(code: KeyCode, key: Key, down: bool) -> KeyboardInput {
    KeyboardInput {
        key_code: code,
        logical_key: key,
        state: if down {
            ButtonState::Pressed
        } else {
            ButtonState::Released
        },
        text: None,
        repeat: false,
        window: Entity::PLACEHOLDER,
    }
}

pub fn ctrl(down: bool) -> KeyboardInput {
    key(KeyCode::ControlLeft, Key::Control, down)
}

pub fn letter(code: KeyCode, c: &str, down: bool) -> KeyboardInput {
    key(code, Key::Character(c.into()), down)
}

/// Ctrl down, the key down and up, Ctrl up: all of it within one frame.
pub fn quick_chord(code: KeyCode, c: &str) -> Vec<KeyboardInput> {
    vec![
        ctrl(true),
        letter(code, c, true),
        letter(code, c, false),
        ctrl(false),
    ]
}

/// A text egui drew: its string, where, and the rectangle it was clipped to (a scroll area's
/// view, a panel's).
#[derive(Debug, Clone)]
pub struct Drawn {
    pub text: String,
    pub rect: egui::Rect,
    pub clip: egui::Rect,
}

/// Every text of a shape, nested ones too, clipped to `clip`.
fn texts_of(shape: &egui::Shape, clip: egui::Rect, out: &mut Vec<Drawn>) {
    match shape {
        egui::Shape::Text(t) => out.push(Drawn {
            text: t.galley.text().to_string(),
            rect: t.visual_bounding_rect(),
            clip,
        }),
        egui::Shape::Vec(v) => v.iter().for_each(|s| texts_of(s, clip, out)),
        _ => {}
    }
}

/// The screen the window tests draw at: a 1280x800 laptop's.
pub const SCREEN: egui::Vec2 = egui::vec2(1280.0, 800.0);

/// `draw` run by egui for one frame per entry of `inputs` (its events) at a `screen`-sized
/// screen: the texts of the last frame.
pub fn frames(
    ctx: &egui::Context,
    screen: egui::Vec2,
    inputs: Vec<Vec<egui::Event>>,
    mut draw: impl FnMut(&mut egui::Ui),
) -> Vec<Drawn> {
    let mut texts = Vec::new();
    for events in inputs {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, screen)),
            events,
            ..Default::default()
        };
        let out = ctx.run_ui(input, &mut draw);
        texts.clear();
        for s in &out.shapes {
            texts_of(&s.shape, s.clip_rect, &mut texts);
        }
    }
    texts
}

/// `draw` at 1280x800 for a frame with `events` and then one without (a click is seen on its
/// release, and a layout settles a frame late, as in the window): the texts of the last frame.
pub fn two_frames(
    ctx: &egui::Context,
    events: Vec<egui::Event>,
    draw: impl FnMut(&mut egui::Ui),
) -> Vec<Drawn> {
    frames(ctx, SCREEN, vec![events, Vec::new()], draw)
}

/// The left panel's column (`panels::left_column`: the exercise over the course) of `phys`, by
/// [`two_frames`] with `events`.
pub fn left_column(
    ctx: &egui::Context,
    browser: &mut Browser,
    (phys, live): (&Run, &LiveChecks),
    ex: &mut Exercise,
    events: Vec<egui::Event>,
) -> Vec<Drawn> {
    let mut course = Course::default();
    two_frames(ctx, events, |ui| {
        egui::Panel::left("levels")
            .default_size(300.0)
            .show(ui, |ui| {
                panels::left_column(ui, browser, (phys, live), ex, &mut course);
            });
    })
}

/// The right panel's upper controls (playback, overlays, tools, build) of `phys`, paused, by
/// [`two_frames`] with `events`: what they asked of the run, and the texts.
pub fn upper_controls(
    ctx: &egui::Context,
    phys: &Run,
    events: Vec<egui::Event>,
) -> (Vec<PhysicsCommand>, Vec<Drawn>) {
    let (mut view, mut ov, mut tools, mut st) = (
        View::default(),
        Overlays::default(),
        ToolState::default(),
        UiState::default(),
    );
    let (play, editor) = (Playback::new(true), Editor::default());
    let mut asked = Vec::new();
    let texts = two_frames(ctx, events, |ui| {
        egui::Panel::right("controls")
            .default_size(330.0)
            .show(ui, |ui| {
                panels::upper_controls(
                    ui,
                    (phys, &play, &editor),
                    (&mut view, &mut ov, &mut tools, &mut st),
                    &mut asked,
                );
            });
    });
    (asked, texts)
}

/// The first text drawn that is `text`, or a panic naming what was drawn.
pub fn drawn<'a>(texts: &'a [Drawn], text: &str) -> &'a Drawn {
    texts
        .iter()
        .find(|d| d.text == text)
        .unwrap_or_else(|| panic!("{text:?} is not drawn: {:?}", all_text(texts)))
}

/// The texts drawn, in order.
pub fn all_text(texts: &[Drawn]) -> Vec<&str> {
    texts.iter().map(|d| d.text.as_str()).collect()
}

/// A left click at `at`, pressed (the first frame's events) or released.
pub fn click(at: egui::Pos2, pressed: bool) -> Vec<egui::Event> {
    let button = egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    if pressed {
        vec![egui::Event::PointerMoved(at), button]
    } else {
        vec![button]
    }
}

/// A frame's drawing begun as the window's draw step begins it: cleared at `v`'s scale, then
/// the scene's own lines (bodies, joints, tracks) of `run` as it stands, from its `outlines`
/// (`view::body_outlines`, which the overlays read too).
pub fn scene_drawing(
    run: &Run,
    outlines: &[rigidlab::app::geometry::Outline],
    v: &View,
) -> rigidlab::app::draw::Drawing {
    let mut d = rigidlab::app::draw::Drawing::default();
    d.clear(v.m_per_px);
    rigidlab::app::scene_lines::scene_lines(
        &run.sim.level,
        outlines,
        &rigidlab::app::view::SceneIndex::of(&run.sim.level),
        run.snapshot(),
        v.m_per_px,
        &mut d,
    );
    d
}
