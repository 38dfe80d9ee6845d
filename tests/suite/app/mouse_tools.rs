//! The mouse tools through their systems (`ToolsPlugin`): a window whose cursor the test moves,
//! the left button pressed and released as the window would, over the headless sandbox of a new
//! scene. Each tool's effect is its definition's: the place tool adds the body at the click, a
//! drag with select while paused at t = 0 moves the body by the drag, a drag with the impulse
//! tool gives J = m d / AIM_TIME, the ruler measures from the press to the release.

use crate::common::app::editor_app_unstarted;
use bevy::prelude::*;
use glam::DVec2;
use rigidlab::app::draw::Drawing;
use rigidlab::app::editor::Placeable;
use rigidlab::app::overlays::{Overlays, Scales};
use rigidlab::app::tools::{Tool, ToolState, ToolsPlugin, AIM_TIME};
use rigidlab::app::view::{self, Outlines, View};
use rigidlab::app::Run;

// Tolerance 1e-9 m: points go to the window's f32 pixels and back (whole pixels here, each
// world point a whole number of 0.01 m pixels), so they come back within a few 1e-16 m; the
// edits and the impulse are computed from them exactly otherwise.

/// The sandbox with the tools and a 800x600 window; the view is the default one (world origin
/// at the viewport's center, 0.01 m a pixel), which nothing here moves.
fn tools_app() -> App {
    let mut app = editor_app_unstarted();
    app.add_plugins(ToolsPlugin)
        .init_resource::<View>()
        .init_resource::<Outlines>()
        .init_resource::<Overlays>()
        .init_resource::<Scales>()
        .init_resource::<Drawing>()
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>();
    app.world_mut().spawn(Window {
        resolution: (800, 600).into(),
        ..default()
    });
    app.update();
    app
}

/// One frame with the cursor over world point `at` and the left button pressed (`Some(true)`),
/// released (`Some(false)`) or left as it is; the outlines follow the level as the window's do.
fn frame(app: &mut App, at: DVec2, button: Option<bool>) {
    let screen = app.world().resource::<View>().to_screen(at);
    let mut windows = app.world_mut().query::<&mut Window>();
    windows
        .single_mut(app.world_mut())
        .unwrap()
        .set_cursor_position(Some(screen));
    let level = app.world().resource::<Run>().sim.level.clone();
    app.world_mut().resource_mut::<Outlines>().bodies = view::body_outlines(&level);
    let mut buttons = app.world_mut().resource_mut::<ButtonInput<MouseButton>>();
    match button {
        Some(true) => buttons.press(MouseButton::Left),
        Some(false) => buttons.release(MouseButton::Left),
        None => {}
    }
    app.update();
    app.world_mut()
        .resource_mut::<ButtonInput<MouseButton>>()
        .clear();
}

/// A drag from `from` to `to` (press, move, release), then a frame for what it asked.
fn drag(app: &mut App, from: DVec2, to: DVec2) {
    frame(app, from, Some(true));
    frame(app, to, None);
    frame(app, to, Some(false));
    frame(app, to, None);
}

fn use_tool(app: &mut App, tool: Tool) {
    app.world_mut().resource_mut::<ToolState>().tool = tool;
}

/// The position of the body placed last, and its index.
fn last_body(app: &App) -> (usize, DVec2) {
    let bodies = &app.world().resource::<Run>().scene.level.bodies;
    let b = bodies.last().unwrap();
    (bodies.len() - 1, DVec2::new(b.position.0, b.position.1))
}

#[test]
fn each_mouse_tool_does_what_it_says_through_its_system() {
    let mut app = tools_app();
    // Place: a click at (0, 1) m adds a disc there (1 m is a round point at any scene size).
    use_tool(&mut app, Tool::Place(Placeable::Disc));
    let before = app.world().resource::<Run>().scene.level.bodies.len();
    frame(&mut app, DVec2::new(0.0, 1.0), Some(true));
    frame(&mut app, DVec2::new(0.0, 1.0), Some(false));
    frame(&mut app, DVec2::new(0.0, 1.0), None);
    let (disc, at) = last_body(&app);
    assert_eq!(disc, before, "the place tool added no body");
    assert!(at.distance(DVec2::new(0.0, 1.0)) < 1e-9, "placed at {at}");

    // Select: a click on the disc selects it; paused at t = 0 a drag moves it by the drag
    // (0.3, 0.2) m, 30 and 20 px: exact in the view's 0.01 m a pixel.
    use_tool(&mut app, Tool::Select);
    drag(&mut app, DVec2::new(0.0, 1.0), DVec2::new(0.3, 1.2));
    assert_eq!(app.world().resource::<Overlays>().selected, Some(disc));
    let (_, moved) = last_body(&app);
    assert!(
        moved.distance(DVec2::new(0.3, 1.2)) < 1e-9,
        "the select drag left the disc at {moved}"
    );

    // Impulse: a drag of d = 0.5 m to the right from the disc's center strikes it with
    // J = m d / AIM_TIME (the tool's definition) at the center.
    use_tool(&mut app, Tool::Impulse);
    drag(&mut app, moved, moved + DVec2::new(0.5, 0.0));
    let m = app.world().resource::<Run>().snapshot().bodies[disc].mass;
    let (p, j, _) = app
        .world()
        .resource::<ToolState>()
        .last_impulse
        .expect("the impulse tool struck nothing");
    let expected = DVec2::new(m * 0.5 / AIM_TIME, 0.0);
    assert!(p.distance(moved) < 1e-9, "struck at {p}");
    assert!(j.distance(expected) < 1e-9, "J = {j}, expected {expected}");

    // Ruler: from the press to the release, 0.5 m (a 3-4-5 triangle).
    use_tool(&mut app, Tool::Ruler);
    drag(&mut app, DVec2::new(-2.0, -1.0), DVec2::new(-1.7, -0.6));
    let (a, b) = app.world().resource::<ToolState>().ruler.unwrap();
    assert!((a.distance(b) - 0.5).abs() < 1e-9, "ruler {a} to {b}");
}

/// One frame with Enter pressed (not into a text field).
fn press_enter(app: &mut App) {
    app.world_mut()
        .resource_mut::<ButtonInput<KeyCode>>()
        .press(KeyCode::Enter);
    app.update();
    let mut keys = app.world_mut().resource_mut::<ButtonInput<KeyCode>>();
    keys.release(KeyCode::Enter);
    keys.clear();
}

#[test]
fn enter_under_the_track_tool_makes_a_track_not_a_body() {
    // Before: the polygon tool's Enter ran for either tool, so three track points and Enter
    // made a polygon body (found when the tools became one system each, 2026-12-06).
    let mut app = tools_app();
    use_tool(&mut app, Tool::Track);
    let level = |app: &App| app.world().resource::<Run>().scene.level.clone();
    let before = level(&app);
    for p in [(-2.0, 0.0), (0.0, -1.0), (2.0, 0.0)] {
        let at = DVec2::new(p.0, p.1);
        frame(&mut app, at, Some(true));
        frame(&mut app, at, Some(false));
    }
    press_enter(&mut app);
    app.update();
    let after = level(&app);
    assert_eq!(
        after.bodies.len(),
        before.bodies.len() + 1,
        "one track body added"
    );
    let track = after.bodies.last().unwrap();
    assert!(
        !matches!(track.shape, Some(rigidlab::level::Shape::Polygon { .. })),
        "Enter under the track tool made a polygon: {:?}",
        track.shape
    );
}
