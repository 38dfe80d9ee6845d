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
            hints: Vec::new(),
            solution: String::new(),
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
            challenge: None,
            checks: Vec::new(),
            questions: Vec::new(),
            predict_first: false,
        },
    }
}

/// The level the window opens with when none is named (under the levels folder).
pub const FIRST_LEVEL: &str = "kinetics/physical_pendulum.ron";

/// Opens the sandbox window: the level browser over the library (`levels`, the folder given;
/// else found as `app/library.rs` says), and `level` directly or the library's first level.
pub fn sandbox(levels: Option<PathBuf>, level: Option<PathBuf>) -> Result<(), String> {
    render::vulkan_check()?;
    let browser = library_browser(&super::library::here(levels.as_deref()));
    let scene = match &level {
        Some(p) => crate::level::load(p).map_err(|e| e.to_string())?,
        None => first_exercise(&browser),
    };
    open_window(scene, browser)
}

/// The level a student meets when none is named, in the window and the page alike: the
/// first-steps tour's pendulum ([`FIRST_LEVEL`]) if the library has it, else its first level
/// that loads, else the empty scene. (The page opened the library's first file, a challenge,
/// until 2026-12-07: a second student trial landed there on every visit.)
pub fn first_exercise(browser: &panels::Browser) -> Scene {
    browser
        .open_listed(&browser.root.join(FIRST_LEVEL))
        .and_then(Result::ok)
        .or_else(|| browser.first_loadable())
        .unwrap_or_else(empty_scene)
}

/// Opens the sandbox window on an assignment: its levels listed in order above the library
/// (found as [`sandbox`] finds it), the first that loads open (none loads: the empty scene,
/// each level's error listed).
pub fn sandbox_assignment(
    levels: Option<PathBuf>,
    assignment: panels::assignment_list::AssignmentList,
) -> Result<(), String> {
    render::vulkan_check()?;
    let mut browser = library_browser(&super::library::here(levels.as_deref()));
    let scene = assignment.first_loadable().unwrap_or_else(empty_scene);
    browser.assignment = Some(assignment);
    open_window(scene, browser)
}

/// The level browser over `library` (`app/library.rs`), its note for the status line in
/// `opened_from`: a folder scanned, or the compiled-in library with the saved levels.
pub fn library_browser(library: &super::library::Library) -> panels::Browser {
    let mut browser = match library.folder() {
        Some(dir) => panels::Browser::scan(&dir),
        None => {
            let mut b = panels::Browser::embedded(
                std::path::Path::new("levels"),
                super::library::library(),
            );
            b.list_saved();
            b
        }
    };
    browser.opened_from = library.note();
    browser
}

/// The window opened on `scene` with the level browser, run until it closes.
fn open_window(scene: Scene, browser: panels::Browser) -> Result<(), String> {
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
                    resolution: OPENING_SIZE.into(),
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
    app.add_systems(Update, fit_to_monitor);
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

/// The size the window opens at, in logical pixels, before the monitor is known: it fits a
/// 1280x800 screen with a title bar and a panel (it opened at 1440x900, which cut the right
/// panel and the status line off a 1280x800 laptop screen).
pub const OPENING_SIZE: (u32, u32) = (1240, 740);

/// The size the window takes once the monitor is known: as large as the panels like it
/// (1440x900) where the screen has room for it, else the screen less room for a title bar and
/// a taskbar (40 logical pixels across, 60 down), never below 640x480. `monitor` is the screen's
/// size in logical pixels.
pub fn fitted_size(monitor: (f32, f32)) -> (f32, f32) {
    let (w, h) = monitor;
    (
        (w - 40.0).clamp(640.0, 1440.0),
        (h - 60.0).clamp(480.0, 900.0),
    )
}

/// Fits the window to the monitor it opened on, once (winit reports the monitors after the
/// first frames): the window and every panel, the status line included, on the screen. The
/// scene is fitted again a few frames later, once the panels have laid out the new size.
fn fit_to_monitor(
    mut resized_at: Local<Option<u32>>,
    mut frames: Local<u32>,
    mut windows: Query<&mut Window, With<bevy::window::PrimaryWindow>>,
    monitors: Query<&bevy::window::Monitor, With<bevy::window::PrimaryMonitor>>,
    mut view: ResMut<super::view::View>,
) {
    *frames += 1;
    if let Some(at) = *resized_at {
        if *frames == at + 5 {
            view.fit = true;
        }
        return;
    }
    let (Ok(mut window), Ok(m)) = (windows.single_mut(), monitors.single()) else {
        return;
    };
    *resized_at = Some(*frames);
    let scale = m.scale_factor.max(0.5) as f32;
    let screen = (
        m.physical_width as f32 / scale,
        m.physical_height as f32 / scale,
    );
    let (w, h) = fitted_size(screen);
    window.resolution.set(w, h);
    window.position =
        bevy::window::WindowPosition::Centered(bevy::window::MonitorSelection::Primary);
}

/// The sandbox over an app that has its window: egui, the physics of `scene`, the drawing, the
/// panels and tools, and the level browser. The native window and the web page share this.
pub fn add_sandbox(app: &mut App, scene: Scene, browser: panels::Browser, paused: bool) {
    // A preferences file that is wrong is reported (stderr now, the status line at the first
    // frame) and moved aside, never fatal (prefs.rs). The student's id kept there opens the
    // first level with their numbers.
    let (prefs, prefs_file) = prefs::Prefs::load();
    let scene = super::student::resume(&prefs.student_id, scene);
    app.add_plugins(bevy_egui::EguiPlugin::default());
    app.insert_resource(ClearColor(palette::BACKGROUND));
    app.add_plugins(PhysicsPlugin {
        scene,
        options: Options::default(),
        paused,
    });
    app.add_plugins(ScenePlugins { legend: false });
    app.insert_resource(browser);
    app.insert_resource(prefs).insert_resource(prefs_file);
    // The course's progress, the same way: progress.ron beside prefs.ron, localStorage in the
    // page (progress_file.rs).
    app.insert_resource(panels::Course::load());
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
