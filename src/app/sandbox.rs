//! The sandbox put together: the native window ([`sandbox`]) and, shared with the web page,
//! the plugins over an app that has its window ([`add_sandbox`]).

use super::physics::PhysicsPlugin;
use super::scene::ScenePlugins;
use super::view::palette;
use super::{advice, editor, frame_cost, frame_rate, panels, power, prefs, render, tools, unsaved};
use crate::level::{Level, Scene};
use crate::sim::Options;
use bevy::prelude::*;
use std::path::PathBuf;

/// The scene the sandbox opens with when there is no level to show.
pub fn empty_scene() -> Scene {
    Scene {
        file: PathBuf::from("untitled.ron"),
        level: Level {
            title: "Empty scene".into(),
            source: Default::default(),
            statement: "No level loaded: pick one in the level browser, or build a scene with the Build panel.".into(),
            effects: vec![
                crate::level::Effect::Gravity,
                crate::level::Effect::Contacts,
            ],
            world: Default::default(),
            bodies: Vec::new(),
            joints: Vec::new(),
            springs: Vec::new(),
            torsion_springs: Vec::new(),
            couplings: Vec::new(),
            loads: Vec::new(),
            events: Vec::new(),
            checks: Vec::new(),
            questions: Vec::new(),
        },
    }
}

/// Opens the sandbox window: the level browser over `levels`, or `level` directly.
/// The level the window opens with when none is named (under the levels folder).
pub const FIRST_LEVEL: &str = "kinetics/physical_pendulum.ron";

pub fn sandbox(levels: PathBuf, level: Option<PathBuf>) -> Result<(), String> {
    render::vulkan_check()?;
    let browser = panels::Browser::scan(&levels);
    let scene = match &level {
        Some(p) => crate::level::load(p).map_err(|e| e.to_string())?,
        // The first exercise of the first-steps tour: a pendulum, if the library has it.
        None => crate::level::load(&levels.join(FIRST_LEVEL))
            .ok()
            .or_else(|| browser.first_loadable())
            .unwrap_or_else(empty_scene),
    };
    let mut app = App::new();
    // winit panics when it cannot reach the display (DISPLAY set to a dead X server, a Wayland-only
    // session: this build speaks X11): catch that and say what to do instead of a backtrace.
    let hook = std::panic::take_hook();
    let why = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
    let why_hook = why.clone();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| info.payload().downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        *why_hook.lock().unwrap() = msg;
    }));
    let opened = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        app.add_plugins(frame_cost::without_render_pipeline(DefaultPlugins.set(
            WindowPlugin {
                primary_window: Some(Window {
                    title: "rigidlab".into(),
                    resolution: (1440, 900).into(),
                    ..default()
                }),
                // app/unsaved.rs closes it, after asking when there are unsaved edits.
                close_when_requested: false,
                ..default()
            },
        )));
    }));
    std::panic::set_hook(hook);
    if opened.is_err() {
        let display = std::env::var("DISPLAY").unwrap_or_default();
        return Err(format!(
            "cannot open the sandbox window on DISPLAY={display:?} (this build needs an X11 server): {}\n\
             Run the exercises headless instead:  rigidlab check levels\n\
             or draw a level into a PNG:          rigidlab render LEVEL --time T --out FILE.png",
            why.lock().unwrap().lines().next().unwrap_or("no reason given")
        ));
    }
    add_sandbox(&mut app, scene, browser, true);
    frame_cost::choose_executor(&mut app);
    if std::env::var_os("RIGIDLAB_CONTINUOUS").is_some() {
        // Xvfb has no window manager: the window never gets focus and Bevy would throttle.
        app.insert_resource(bevy::winit::WinitSettings::continuous());
    }
    let exit = app.run();
    if exit.is_error() {
        return Err("the sandbox window closed with an error".into());
    }
    Ok(())
}

/// The sandbox over an app that has its window: egui, the physics of `scene`, the drawing, the
/// panels and tools, and the level browser. The native window and the web page share this.
pub fn add_sandbox(app: &mut App, scene: Scene, browser: panels::Browser, paused: bool) {
    app.add_plugins(bevy_egui::EguiPlugin::default());
    app.insert_resource(ClearColor(palette::BACKGROUND));
    app.add_plugins(PhysicsPlugin {
        scene,
        options: Options::default(),
        paused,
    });
    app.add_plugins(ScenePlugins { legend: false });
    app.insert_resource(browser);
    // A preferences file that is wrong is reported (stderr now, the status line at the first
    // frame) and moved aside, never fatal (prefs.rs).
    let (prefs, prefs_file) = prefs::Prefs::load();
    app.insert_resource(prefs).insert_resource(prefs_file);
    app.add_plugins((
        panels::PanelsPlugin,
        tools::ToolsPlugin,
        editor::EditorPlugin,
        frame_rate::FrameRatePlugin,
        power::PowerPlugin,
        unsaved::UnsavedPlugin,
        advice::AdvicePlugin,
    ));
    app.add_systems(Startup, panels::spawn_cameras);
}
