//! The Bevy sandbox: a thin shell of plugins over the core (feature `app`).
//!
//! - [`physics`]: the core `Simulation` stepped in `FixedUpdate` at the level's dt, so the window
//!   computes the numbers `rigidlab check` computes;
//! - [`view`], [`draw`], [`geometry`]: camera, filled bodies, outlines, joints, springs, ground;
//! - [`overlays`]: the textbook's vectors and diagrams, from the snapshot ([`quantities`]);
//! - [`panels`] and [`tools`]: the egui panels and the mouse tools of the sandbox window;
//! - [`render`](mod@render): the same scene drawn into a PNG without a window.

pub mod advice;
pub mod blows;
pub mod draw;
pub mod editor;
pub mod frame_cost;
pub mod frame_rate;
pub mod geometry;
pub mod labels;
pub mod overlays;
pub mod panels;
pub mod physics;
pub mod playback;
pub mod power;
pub mod prefs;
pub mod quantities;
pub mod render;
pub mod scene_lines;
pub mod tools;
pub mod unsaved;
pub mod user_files;
pub mod view;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use physics::{LiveChecks, Physics, PhysicsPlugin, PhysicsStep};

use crate::level::{Level, Scene};
use crate::sim::Options;
use bevy::prelude::*;
use bevy_egui::{egui, EguiContexts, EguiPrimaryContextPass};
use draw::Drawing;
use overlays::{Overlays, Scales};
use std::path::{Path, PathBuf};
use view::{palette, Outlines, View};

/// Drawing of the running scene: meshes, lines, overlays, labels (no panels, no camera).
pub struct ScenePlugin {
    /// Paint the title/time/legend box (renders; the sandbox shows these in its panels).
    pub legend: bool,
}

/// The set of the scene drawing systems (after the physics step).
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct SceneDraw;

impl Plugin for ScenePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<View>()
            .init_resource::<Outlines>()
            .init_resource::<Drawing>()
            .init_resource::<Overlays>()
            .add_systems(
                Update,
                (
                    view::spawn_meshes,
                    view::sync_camera,
                    view::sync_meshes,
                    build_drawing,
                    draw::emit_gizmos,
                )
                    .chain()
                    .in_set(SceneDraw)
                    .after(PhysicsStep),
            )
            .add_systems(EguiPrimaryContextPass, paint_labels);
        if self.legend {
            app.add_systems(EguiPrimaryContextPass, paint_legend.after(paint_labels));
        }
    }
}

/// Body lines, overlays and scale bar of this frame.
pub fn build_drawing(
    phys: Res<Physics>,
    mut view: ResMut<View>,
    outlines: Res<Outlines>,
    ov: Res<Overlays>,
    tool: Option<Res<tools::ToolState>>,
    mut d: ResMut<Drawing>,
) {
    let s = phys.snapshot();
    if view.generation_speed != Some(phys.generation) {
        view.generation_speed = Some(phys.generation);
        view.max_speed = 0.0;
    }
    let fastest = s
        .bodies
        .iter()
        .map(|b| b.velocity.length())
        .fold(0.0, f64::max);
    if fastest.is_finite() && fastest > view.max_speed {
        view.max_speed = fastest;
    }
    d.clear(view.m_per_px);
    scene_lines::scene_lines(
        &phys.sim.level,
        &outlines.bodies,
        &outlines.index,
        s,
        view.m_per_px,
        &mut d,
    );
    if let Some(i) = ov.selected {
        scene_lines::highlight(&outlines.bodies, s, i, &mut d);
    }
    let mut scales = Scales::of(s, view.scene_size(), view.max_speed, view.m_per_px);
    scales.gain = ov.arrow_scale;
    let vp = view.viewport;
    let (a, b) = (
        view.to_world(Vec2::new(vp.min.x, vp.max.y)),
        view.to_world(Vec2::new(vp.max.x, vp.min.y)),
    );
    scales.visible = Some((a.min(b), a.max(b)));
    overlays::build(&ov, &phys, &outlines.bodies, &scales, &mut d);
    if let Some(tool) = tool {
        tools::preview(&tool, &phys, &scales, &mut d);
    }
    scene_lines::scale_bar(&view, &mut d);
}

pub(crate) fn color32(c: Color) -> egui::Color32 {
    let c = c.to_srgba();
    egui::Color32::from_rgba_unmultiplied(
        (c.red * 255.0).round() as u8,
        (c.green * 255.0).round() as u8,
        (c.blue * 255.0).round() as u8,
        (c.alpha * 255.0).round() as u8,
    )
}

fn egui_rect(r: Rect) -> egui::Rect {
    egui::Rect::from_min_max(egui::pos2(r.min.x, r.min.y), egui::pos2(r.max.x, r.max.y))
}

/// The labels of the drawing, in screen space, each on a light box so it reads over lines.
fn paint_labels(
    mut contexts: EguiContexts,
    d: Res<Drawing>,
    view: Res<View>,
    mut last: Local<Vec<(Vec2, Rect)>>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    let painter = ctx
        .layer_painter(egui::LayerId::new(
            egui::Order::Background,
            egui::Id::new("rigidlab-labels"),
        ))
        .with_clip_rect(egui_rect(view.viewport));
    let bg = color32(palette::BACKGROUND.with_alpha(0.8));
    let galleys: Vec<_> = d
        .labels
        .iter()
        .map(|l| {
            painter.layout_no_wrap(
                l.text.clone(),
                egui::FontId::proportional(l.size),
                color32(l.color),
            )
        })
        .collect();
    let wants: Vec<labels::Want> = d
        .labels
        .iter()
        .zip(&galleys)
        .map(|(l, g)| label_want(l, Vec2::new(g.size().x, g.size().y), &view))
        .collect();
    let rects = labels::place_keeping(&wants, &screen_bodies(&d, &view), view.viewport, &last);
    *last = wants
        .iter()
        .map(|w| w.home)
        .zip(rects.iter().copied())
        .collect();
    for ((l, galley), r) in d.labels.iter().zip(galleys).zip(rects) {
        painter.rect_filled(egui_rect(r).expand(1.5), 2.0, bg);
        painter.galley(egui::pos2(r.min.x, r.min.y), galley, color32(l.color));
    }
    Ok(())
}

/// Where a label wants to be: centered on its point (plus its offset), or pushed out along
/// `dir` until its box clears the point (labels at arrow tips).
pub fn label_want(l: &draw::Label, size: Vec2, view: &View) -> labels::Want {
    let push = 5.0 + 0.5 * (l.dir.x.abs() * size.x + l.dir.y.abs() * size.y);
    let p = view.to_screen(l.at) + l.offset + l.dir * push;
    labels::Want {
        home: p - 0.5 * size,
        size,
    }
}

/// The drawing's bodies in screen coordinates, for the label placer.
pub fn screen_bodies(d: &Drawing, view: &View) -> Vec<Vec<Vec2>> {
    d.bodies
        .iter()
        .map(|poly| poly.iter().map(|p| view.to_screen(*p)).collect())
        .collect()
}

/// Title, time and the color key (renders).
fn paint_legend(mut contexts: EguiContexts, phys: Res<Physics>, ov: Res<Overlays>) -> Result {
    let ctx = contexts.ctx_mut()?;
    egui::Area::new(egui::Id::new("rigidlab-legend"))
        .fixed_pos(egui::pos2(10.0, 8.0))
        .show(ctx, |ui| {
            egui::Frame::new()
                .fill(color32(palette::BACKGROUND.with_alpha(0.85)))
                .inner_margin(6.0)
                .show(ui, |ui| {
                    let s = phys.snapshot();
                    ui.label(
                        egui::RichText::new(&phys.sim.level.title)
                            .strong()
                            .color(color32(palette::TEXT)),
                    );
                    ui.label(
                        egui::RichText::new(format!(
                            "t = {:.3} s   dt = {:.4} s",
                            s.time,
                            phys.sim.dt()
                        ))
                        .color(color32(palette::TEXT)),
                    );
                    for (text, color) in
                        panels::legend_entries(&ov, &phys.sim.level, phys.frame_window())
                    {
                        ui.label(egui::RichText::new(text).color(color32(color)));
                    }
                });
        });
    Ok(())
}

/// The scene the sandbox opens with when there is no level to show.
pub(crate) fn empty_scene() -> Scene {
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
    app.add_plugins(ScenePlugin { legend: false });
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

/// Renders `scene` at simulated time `time` into a PNG at `out`.
///
/// The overlays are velocity, free-body diagram, trails and labels; `RIGIDLAB_OVERLAYS=vacfkhtl`
/// (letters as the sandbox keys) picks others.
pub fn render(scene: &Scene, time: f64, out: &Path) -> Result<(), String> {
    let mut opts = render::RenderOptions::default();
    if let Ok(letters) = std::env::var("RIGIDLAB_OVERLAYS") {
        opts.overlays = render::RenderOptions::overlays_from_letters(&letters)?;
    }
    render::render_frame(scene, time, Some(out), &opts).map(|_| ())
}
