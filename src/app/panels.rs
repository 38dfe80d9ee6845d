//! The sandbox's egui panels: level browser, statement and questions (graded), playback, overlays,
//! tools, solver settings with the measured step time, live energy and momentum plots, checks,
//! saving the scene as a level file.

use super::color32;
use super::overlays::Overlays;
use super::physics::{LiveChecks, Physics, SeriesPoint};
use super::tools::{Tool, ToolState};
use super::view::{palette, View, WorldCamera};
use crate::level::{self, BodyDef, BodyKind, Effect, Level, Scene, Shape};
use crate::snapshot::Snapshot;
use bevy::camera::visibility::RenderLayers;
use bevy::camera::CameraOutputMode;
use bevy::prelude::*;
use bevy::render::render_resource::BlendState;
use bevy::render::view::screenshot::{save_to_disk, Screenshot};
use bevy_egui::{
    egui, EguiContexts, EguiGlobalSettings, EguiPrimaryContextPass, PrimaryEguiContext,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One level file in the browser.
#[derive(Debug, Clone)]
pub struct Entry {
    pub path: PathBuf,
    pub title: String,
    pub statement: String,
    /// Why it does not load (shown instead of opening it).
    pub error: Option<String>,
}

/// The levels folder, grouped by topic (sub-folder).
#[derive(Resource, Debug, Clone, Default)]
pub struct Browser {
    pub root: PathBuf,
    pub groups: BTreeMap<String, Vec<Entry>>,
    pub error: Option<String>,
}

impl Browser {
    pub fn scan(root: &Path) -> Browser {
        let mut b = Browser {
            root: root.to_path_buf(),
            ..Default::default()
        };
        let files = match level::collect_files(&[root.to_path_buf()]) {
            Ok(f) => f,
            Err(e) => {
                b.error = Some(e.to_string());
                return b;
            }
        };
        for f in files {
            let group = f
                .parent()
                .and_then(|p| p.strip_prefix(root).ok())
                .map(|p| p.display().to_string())
                .filter(|s| !s.is_empty())
                .unwrap_or_else(|| "(top)".into());
            let entry = match level::load(&f) {
                Ok(s) => Entry {
                    path: f.clone(),
                    title: s.level.title,
                    statement: s.level.statement,
                    error: None,
                },
                Err(e) => Entry {
                    path: f.clone(),
                    title: f
                        .file_stem()
                        .map(|s| s.to_string_lossy().to_string())
                        .unwrap_or_default(),
                    statement: String::new(),
                    error: Some(e.to_string()),
                },
            };
            b.groups.entry(group).or_default().push(entry);
        }
        b
    }

    pub fn first_loadable(&self) -> Option<Scene> {
        self.groups
            .values()
            .flatten()
            .filter(|e| e.error.is_none())
            .find_map(|e| level::load(&e.path).ok())
    }
}

/// Panel state that is not the simulation's.
#[derive(Resource, Debug, Clone)]
pub struct UiState {
    pub answers: Vec<String>,
    /// A student's grade per question: (answer, relative error, passed).
    pub grades: Vec<Option<Result<(f64, f64, bool), String>>>,
    pub time_scale: f64,
    pub save_path: String,
    pub message: Option<(String, bool)>,
    pub generation: Option<u64>,
    pub spawned: usize,
}

impl Default for UiState {
    fn default() -> Self {
        UiState {
            answers: Vec::new(),
            grades: Vec::new(),
            time_scale: 1.0,
            save_path: String::new(),
            message: None,
            generation: None,
            spawned: 0,
        }
    }
}

pub struct PanelsPlugin;

impl Plugin for PanelsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<UiState>()
            .add_systems(
                Update,
                (keys, super::view::pan_zoom, super::overlays::overlay_keys),
            )
            .add_systems(EguiPrimaryContextPass, panels);
    }
}

/// The world camera and, over it, the egui camera (full window, draws only the UI).
pub fn spawn_cameras(mut commands: Commands, mut settings: ResMut<EguiGlobalSettings>) {
    settings.auto_create_primary_context = false;
    commands.spawn((Camera2d, WorldCamera, Msaa::Sample4));
    commands.spawn((
        PrimaryEguiContext,
        Camera2d,
        RenderLayers::none(),
        Camera {
            order: 1,
            output_mode: CameraOutputMode::Write {
                blend_state: Some(BlendState::ALPHA_BLENDING),
                clear_color: ClearColorConfig::None,
            },
            clear_color: ClearColorConfig::Custom(Color::NONE),
            ..default()
        },
    ));
}

/// The color key of the overlays that are on (force kinds only where the scene has them).
pub fn legend_entries(ov: &Overlays, level: &Level, window: usize) -> Vec<(String, Color)> {
    let mut v = Vec::new();
    let mut add = |on: bool, text: &str, c: Color| {
        if on {
            v.push((format!("— {text}"), c));
        }
    };
    add(ov.velocity, "velocity v_G", palette::VELOCITY);
    add(ov.acceleration, "acceleration a_G", palette::ACCEL);
    add(
        ov.instant_center,
        "instantaneous center IC",
        palette::CENTER,
    );
    if ov.free_body {
        let has = |e: Effect| level.effects.contains(&e);
        add(has(Effect::Gravity), "weight mg", palette::GRAVITY);
        add(has(Effect::Contacts), "contact normal N", palette::NORMAL);
        add(has(Effect::Friction), "friction F", palette::FRICTION);
        add(
            !level.joints.is_empty(),
            "joint reaction R",
            palette::REACTION,
        );
        add(!level.couplings.is_empty(), "coupling T", palette::COUPLING);
        add(!level.springs.is_empty(), "spring Fs", palette::SPRING);
        add(!level.loads.is_empty(), "load P", palette::LOAD);
    }
    add(ov.kinetic, "kinetic diagram m a_G, I_G α", palette::ACCEL);
    add(ov.momentum, "angular momentum H_O", palette::MOMENTUM);
    add(ov.trails, "trail of G", palette::TRAIL);
    if (ov.free_body || ov.kinetic) && window > 1 {
        v.push((
            format!("forces: mean over the last {window} steps (1/60 s)"),
            palette::TEXT,
        ));
    }
    v
}

#[allow(clippy::too_many_arguments)]
fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut phys: ResMut<Physics>,
    mut view: ResMut<View>,
    mut ui: ResMut<UiState>,
    mut tools: ResMut<ToolState>,
    mut ov: ResMut<Overlays>,
    mut commands: Commands,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
) {
    if egui_input.is_some_and(|e| e.wants_any_keyboard_input()) {
        return;
    }
    if keys.just_pressed(KeyCode::Space) {
        toggle_play(&mut phys);
    }
    if keys.just_pressed(KeyCode::KeyS) || keys.just_pressed(KeyCode::ArrowRight) {
        phys.paused = true;
        phys.steps_requested += 1;
    }
    if keys.just_pressed(KeyCode::KeyR) {
        phys.reset();
    }
    if keys.just_pressed(KeyCode::Home) {
        view.fit = true;
    }
    if keys.just_pressed(KeyCode::Minus) {
        ui.time_scale = (ui.time_scale / 2.0).max(1.0 / 64.0);
    }
    if keys.just_pressed(KeyCode::Equal) {
        ui.time_scale = (ui.time_scale * 2.0).min(8.0);
    }
    if keys.just_pressed(KeyCode::Digit1) {
        tools.tool = Tool::Select;
    }
    if keys.just_pressed(KeyCode::Digit2) {
        tools.tool = Tool::Impulse;
    }
    if keys.just_pressed(KeyCode::Digit3) {
        tools.tool = Tool::SetOrigin;
    }
    if keys.just_pressed(KeyCode::Escape) {
        ov.selected = None;
        ov.point = None;
    }
    if keys.just_pressed(KeyCode::F12) {
        let name = format!("rigidlab-{:.3}s.png", phys.snapshot().time);
        ui.message = Some((format!("screenshot saved to {name}"), true));
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(name));
    }
}

fn toggle_play(phys: &mut Physics) {
    if phys.paused && phys.at_end() && phys.stop_at_end {
        // Past the exercise's end: keep going as a free sandbox.
        phys.stop_at_end = false;
    }
    phys.paused = !phys.paused;
}

fn rich(text: impl Into<String>, c: Color) -> egui::RichText {
    egui::RichText::new(text.into()).color(color32(c))
}

#[allow(clippy::too_many_arguments)]
fn panels(
    mut contexts: EguiContexts,
    mut phys: ResMut<Physics>,
    live: NonSend<LiveChecks>,
    mut view: ResMut<View>,
    mut ov: ResMut<Overlays>,
    mut tools: ResMut<ToolState>,
    mut ui_state: ResMut<UiState>,
    mut browser: ResMut<Browser>,
    mut time: ResMut<Time<Virtual>>,
    windows: Query<&Window>,
) -> Result {
    let ctx = contexts.ctx_mut()?.clone();
    let st = &mut *ui_state;
    if st.generation.is_none() {
        // The textbook look: dark ink on paper.
        ctx.set_visuals(egui::Visuals::light());
    }
    if st.generation != Some(phys.generation) {
        st.generation = Some(phys.generation);
        let n = phys.sim.level.questions.len();
        if st.answers.len() != n {
            st.answers = vec![String::new(); n];
        }
        st.grades = vec![None; n];
        if st.save_path.is_empty() {
            st.save_path = default_save_path(&phys.scene);
        }
    }
    if (time.relative_speed_f64() - st.time_scale).abs() > 1e-12 {
        time.set_relative_speed_f64(st.time_scale);
    }

    let mut root = egui::Ui::new(
        ctx.clone(),
        "rigidlab-root".into(),
        egui::UiBuilder::new()
            .layer_id(egui::LayerId::background())
            .max_rect(ctx.viewport_rect()),
    );

    let mut load: Option<Scene> = None;
    egui::Panel::left("levels")
        .resizable(true)
        .default_size(300.0)
        .size_range(200.0..=520.0)
        .show(&mut root, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                level_browser(ui, &mut browser, &phys, &mut load);
                ui.separator();
                exercise(ui, &phys, &live, st);
            });
        });

    egui::Panel::right("controls")
        .resizable(true)
        .default_size(330.0)
        .size_range(260.0..=520.0)
        .show(&mut root, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                playback(ui, &mut phys, st, &mut view);
                ui.separator();
                overlay_controls(ui, &mut ov, &phys);
                ui.separator();
                tool_controls(ui, &mut tools, &mut phys, &view, st);
                ui.separator();
                solver(ui, &mut phys, &live);
                ui.separator();
                plots(ui, &phys);
                ui.separator();
                checks(ui, &phys, &live);
            });
        });

    egui::Panel::bottom("status").show(&mut root, |ui| {
        ui.horizontal_wrapped(|ui| {
            if let Some((m, ok)) = &st.message {
                ui.label(rich(m.clone(), if *ok { palette::GRAVITY } else { palette::NORMAL }));
                ui.separator();
            }
            ui.label(
                "Space play/pause · S step · R reset · −/= time scale · wheel zoom · right-drag pan · Home fit · \
                 1 select/drag · 2 impulse · 3 set O · V A C F K H T L overlays · F12 screenshot",
            );
        });
    });

    // What is left is the scene's viewport.
    let free = root.available_rect_before_wrap();
    let _ = windows;
    view.viewport = Rect::new(free.min.x, free.min.y, free.max.x, free.max.y);

    if let Some(scene) = load {
        st.save_path = default_save_path(&scene);
        st.message = Some((format!("opened {}", scene.file.display()), true));
        ov.selected = None;
        ov.point = None;
        ov.origin = default_origin(&scene.level);
        tools.last_impulse = None;
        phys.options = Default::default();
        phys.stop_at_end = true;
        phys.paused = true;
        phys.load(scene);
    }
    Ok(())
}

/// O defaults to the first fixed pivot (a point body), else the world origin.
pub fn default_origin(level: &Level) -> glam::DVec2 {
    level
        .bodies
        .iter()
        .find(|b| b.kind == BodyKind::Fixed && b.shape.is_none())
        .map_or(glam::DVec2::ZERO, |b| {
            glam::DVec2::new(b.position.0, b.position.1)
        })
}

fn default_save_path(scene: &Scene) -> String {
    let stem = scene
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "scene".into());
    format!("{stem}-saved.ron")
}

fn level_browser(
    ui: &mut egui::Ui,
    browser: &mut Browser,
    phys: &Physics,
    load: &mut Option<Scene>,
) {
    ui.horizontal(|ui| {
        ui.heading("Levels");
        if ui
            .small_button("⟳")
            .on_hover_text("rescan the levels folder")
            .clicked()
        {
            *browser = Browser::scan(&browser.root.clone());
        }
    });
    if let Some(e) = &browser.error {
        ui.label(rich(e.clone(), palette::NORMAL));
    }
    if browser.groups.is_empty() && browser.error.is_none() {
        ui.label(format!("no *.ron levels under {}", browser.root.display()));
    }
    for (group, entries) in &browser.groups {
        egui::CollapsingHeader::new(group.as_str())
            .default_open(
                entries.iter().any(|e| e.path == phys.scene.file) || browser.groups.len() <= 6,
            )
            .show(ui, |ui| {
                for e in entries {
                    let current = e.path == phys.scene.file;
                    let text = if e.error.is_some() {
                        rich(format!("⚠ {}", e.title), palette::NORMAL)
                    } else {
                        egui::RichText::new(&e.title)
                    };
                    let r = ui.selectable_label(current, text);
                    let r = match &e.error {
                        Some(err) => r.on_hover_text(err),
                        None if !e.statement.is_empty() => r.on_hover_text(&e.statement),
                        None => r,
                    };
                    if r.clicked() && e.error.is_none() {
                        match level::load(&e.path) {
                            Ok(s) => *load = Some(s),
                            Err(err) => {
                                ui.label(rich(err.to_string(), palette::NORMAL));
                            }
                        }
                    }
                }
            });
    }
}

fn exercise(ui: &mut egui::Ui, phys: &Physics, live: &LiveChecks, st: &mut UiState) {
    let level = &phys.sim.level;
    ui.heading(&level.title);
    if !level.source.book.is_empty() || !level.source.problem.is_empty() {
        ui.label(
            rich(
                format!("{} {}", level.source.book, level.source.problem),
                palette::OUTLINE,
            )
            .italics(),
        );
    }
    if !level.statement.is_empty() {
        ui.label(&level.statement);
    }
    let effects: Vec<&str> = level.effects.iter().map(|e| e.name()).collect();
    ui.label(rich(format!("effects: {}", effects.join(", ")), palette::OUTLINE).small());
    if level.questions.is_empty() {
        return;
    }
    ui.add_space(6.0);
    ui.strong("Questions");
    for (k, q) in level.questions.iter().enumerate() {
        ui.group(|ui| {
            ui.label(format!("{}. {}", k + 1, q.ask));
            ui.horizontal(|ui| {
                let edit = ui.add(
                    egui::TextEdit::singleline(&mut st.answers[k])
                        .desired_width(90.0)
                        .hint_text("your answer"),
                );
                ui.label(&q.unit);
                let submit = ui.button("Check").clicked()
                    || (edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)));
                if submit {
                    st.grades[k] = Some(grade(q, &st.answers[k]));
                }
            });
            match &st.grades[k] {
                Some(Ok((_, err, true))) => {
                    ui.label(rich(
                        format!(
                            "✔ correct: off by {:.2}% (tolerance {:.2}%)",
                            err * 100.0,
                            q.tolerance * 100.0
                        ),
                        palette::GRAVITY,
                    ));
                }
                Some(Ok((_, err, false))) => {
                    // |v - a| / |a| = 2 within tolerance: the magnitude is right, the sign is not.
                    let sign = if (err - 2.0).abs() <= q.tolerance {
                        "; the magnitude is right: check the sign"
                    } else {
                        ""
                    };
                    ui.label(rich(
                        format!(
                            "✘ not yet: off by {:.2}% (tolerance {:.2}%){sign}",
                            err * 100.0,
                            q.tolerance * 100.0
                        ),
                        palette::NORMAL,
                    ));
                }
                Some(Err(e)) => {
                    ui.label(rich(e.clone(), palette::NORMAL));
                }
                None => {}
            }
            if let Some(a) = live.answers.as_ref().and_then(|a| a.get(k)) {
                let show = st.grades[k]
                    .as_ref()
                    .is_some_and(|g| matches!(g, Ok((_, _, true))));
                if show {
                    ui.label(rich(
                        format!(
                            "textbook {} {} · rigidlab measured {} {} at t = {:.3} s",
                            fmt(a.expected),
                            q.unit,
                            fmt(a.engine),
                            q.unit,
                            a.time
                        ),
                        palette::OUTLINE,
                    ));
                } else {
                    ui.label(
                        rich(
                            format!("rigidlab measured this run; answer first to see it"),
                            palette::OUTLINE,
                        )
                        .small(),
                    );
                }
            }
        });
    }
}

fn fmt(x: f64) -> String {
    super::draw::si(x, "")
}

/// Grades a typed answer with the level's own rule (the core's [`crate::questions::grade_answer`]).
pub fn grade(q: &crate::level::QuestionDef, text: &str) -> Result<(f64, f64, bool), String> {
    let v: f64 = text
        .trim()
        .replace(',', ".")
        .parse()
        .map_err(|_| format!("`{}` is not a number", text.trim()))?;
    if !v.is_finite() {
        return Err("give a finite number".into());
    }
    let g = crate::questions::grade_answer(q, v);
    Ok((g.answer, g.rel_error, g.passed))
}

fn playback(ui: &mut egui::Ui, phys: &mut Physics, st: &mut UiState, view: &mut View) {
    let s = phys.snapshot();
    let duration = phys.sim.level.world.duration;
    ui.heading("Playback");
    ui.label(format!(
        "t = {:.3} s of {:.3} s   (step {})",
        s.time, duration, s.step
    ));
    ui.add(egui::ProgressBar::new((s.time / duration).clamp(0.0, 1.0) as f32).desired_height(6.0));
    ui.horizontal(|ui| {
        let label = if phys.paused { "▶ Play" } else { "⏸ Pause" };
        if ui.button(label).clicked() {
            toggle_play(phys);
        }
        if ui
            .button("⏭ Step")
            .on_hover_text("one physics step (dt)")
            .clicked()
        {
            phys.paused = true;
            phys.steps_requested += 1;
        }
        if ui.button("⟲ Reset").clicked() {
            phys.reset();
        }
        if ui
            .button("Fit")
            .on_hover_text("fit the view to the scene (Home)")
            .clicked()
        {
            view.fit = true;
        }
    });
    ui.horizontal(|ui| {
        ui.label("time scale");
        ui.add(
            egui::Slider::new(&mut st.time_scale, 1.0 / 64.0..=8.0)
                .logarithmic(true)
                .max_decimals(3),
        );
    });
    ui.checkbox(
        &mut phys.stop_at_end,
        "stop at the level's end (where `rigidlab check` stops)",
    );
    if let Some(e) = &phys.error {
        ui.label(rich(e.clone(), palette::NORMAL));
    }
    if phys.behind && !phys.paused {
        ui.label(rich(
            "The physics takes longer than real time here: it runs slowed down.",
            palette::FRICTION,
        ));
    }
    if phys.interfered {
        ui.label(rich(
            "You pushed the scene: this run is no longer the exercise's (Reset to start over).",
            palette::FRICTION,
        ));
    }
}

fn overlay_controls(ui: &mut egui::Ui, ov: &mut Overlays, phys: &Physics) {
    ui.heading("Overlays");
    egui::Grid::new("overlays").num_columns(2).show(ui, |ui| {
        ui.checkbox(&mut ov.velocity, "velocity (V)");
        ui.checkbox(&mut ov.acceleration, "acceleration (A)");
        ui.end_row();
        ui.checkbox(&mut ov.instant_center, "instant center (C)");
        ui.checkbox(&mut ov.free_body, "free-body diagram (F)");
        ui.end_row();
        ui.checkbox(&mut ov.kinetic, "kinetic diagram (K)");
        ui.checkbox(&mut ov.momentum, "H about O (H)");
        ui.end_row();
        ui.checkbox(&mut ov.trails, "trails (T)");
        ui.checkbox(&mut ov.labels, "magnitudes (L)");
        ui.end_row();
    });
    ui.horizontal_wrapped(|ui| {
        for (text, color) in legend_entries(ov, &phys.sim.level, phys.frame_window()) {
            ui.label(rich(text, color).small());
        }
    });
    match ov.selected {
        Some(i) => {
            ui.horizontal(|ui| {
                let name = phys
                    .snapshot()
                    .bodies
                    .get(i)
                    .map_or("?", |b| b.name.as_str());
                ui.label(format!("diagrams for \"{name}\""));
                if ui.small_button("all").on_hover_text("Esc").clicked() {
                    ov.selected = None;
                    ov.point = None;
                }
            });
        }
        None => {
            ui.label(
                rich(
                    "click a body for its diagrams (all bodies when there are 4 or fewer)",
                    palette::OUTLINE,
                )
                .small(),
            );
        }
    }
}

fn tool_controls(
    ui: &mut egui::Ui,
    tools: &mut ToolState,
    phys: &mut Physics,
    view: &View,
    st: &mut UiState,
) {
    ui.heading("Tools");
    ui.horizontal(|ui| {
        ui.selectable_value(&mut tools.tool, Tool::Select, "1 select / drag");
        ui.selectable_value(&mut tools.tool, Tool::Impulse, "2 impulse");
        ui.selectable_value(&mut tools.tool, Tool::SetOrigin, "3 set O");
    });
    let help = match tools.tool {
        Tool::Select => {
            "click a body to select it and a point on it (v_P, IC lines); drag it while playing"
        }
        Tool::Impulse => {
            "click-drag on a body: J = m × drag / 0.5 s at the clicked point, applied on release"
        }
        Tool::SetOrigin => "click: the point O for the angular momentum H_O",
    };
    ui.label(rich(help, palette::OUTLINE).small());
    ui.horizontal(|ui| {
        ui.label("spawn");
        for (name, what) in [
            ("box", Spawn::Box),
            ("disc", Spawn::Disc),
            ("bar", Spawn::Bar),
        ] {
            if ui.button(name).clicked() {
                let (scene, note) = spawn(&phys.scene, phys.snapshot(), what, view, st.spawned);
                st.spawned += 1;
                st.message = Some((note, true));
                let paused = phys.paused;
                // Keep the camera where the user put it: the new body appears in view.
                phys.load_keep_view(scene);
                phys.paused = paused;
            }
        }
    });
    ui.horizontal(|ui| {
        ui.label("save as");
        ui.add(egui::TextEdit::singleline(&mut st.save_path).desired_width(170.0));
        if ui
            .button("Save")
            .on_hover_text("the current state as a level file (checked by loading it back)")
            .clicked()
        {
            st.message = Some(match save(phys, Path::new(&st.save_path)) {
                Ok(m) => (m, true),
                Err(e) => (e, false),
            });
        }
    });
}

#[derive(Debug, Clone, Copy)]
enum Spawn {
    Box,
    Disc,
    Bar,
}

/// The current state as a level (t becomes 0): poses and velocities from the snapshot; events still
/// to come are shifted; checks and questions, which are about the exercise from its start, are
/// kept only at t = 0.
pub fn capture(level: &Level, s: &Snapshot) -> Level {
    let mut out = level.clone();
    if s.step == 0 {
        return out;
    }
    let t = s.time;
    for (def, b) in out.bodies.iter_mut().zip(&s.bodies) {
        def.position = (b.position.x, b.position.y);
        def.angle = b.angle;
        if def.kind == BodyKind::Dynamic {
            def.velocity = (b.velocity.x, b.velocity.y);
            def.omega = b.omega;
        }
    }
    // Impulses still to come keep their time from now; a weld on contact stays armed (bodies
    // already welded and touching weld again at once).
    out.events.retain(|e| match e {
        level::EventDef::Impulse { at, .. } => *at >= t,
        _ => true,
    });
    for e in out.events.iter_mut() {
        if let level::EventDef::Impulse { at, .. } = e {
            *at -= t;
        }
    }
    let remaining = out.world.duration - t;
    out.world.duration = if remaining >= 0.5 {
        remaining
    } else {
        out.world.duration
    };
    // Load tables continue from now: the value at t first, then the rows still to come.
    for l in out.loads.iter_mut() {
        if let Some(level::Profile::Table(rows)) = &mut l.force {
            let now = crate::sim::sample2(&level::Profile::Table(rows.clone()), t);
            let mut new = vec![(0.0, now)];
            new.extend(
                rows.iter()
                    .filter(|(ti, _)| *ti > t)
                    .map(|(ti, v)| (ti - t, *v)),
            );
            *rows = new;
        }
        if let Some(level::Profile::Table(rows)) = &mut l.torque {
            let now = crate::sim::sample1(&level::Profile::Table(rows.clone()), t);
            let mut new = vec![(0.0, now)];
            new.extend(
                rows.iter()
                    .filter(|(ti, _)| *ti > t)
                    .map(|(ti, v)| (ti - t, *v)),
            );
            *rows = new;
        }
    }
    out.checks.clear();
    out.questions.clear();
    out
}

fn spawn(scene: &Scene, s: &Snapshot, what: Spawn, view: &View, n: usize) -> (Scene, String) {
    let mut level = capture(&scene.level, s);
    let size = view.scene_size();
    let top = view.to_world(Vec2::new(
        view.viewport.center().x,
        view.viewport.min.y + 0.2 * view.viewport.height(),
    ));
    let (name, shape) = match what {
        Spawn::Box => (
            "box",
            Shape::Box {
                width: 0.12 * size,
                height: 0.08 * size,
            },
        ),
        Spawn::Disc => (
            "disc",
            Shape::Circle {
                radius: 0.05 * size,
            },
        ),
        Spawn::Bar => (
            "bar",
            Shape::Box {
                width: 0.35 * size,
                height: 0.03 * size,
            },
        ),
    };
    let mut name = format!("{name}{}", n + 1);
    while level.bodies.iter().any(|b| b.name == name) {
        name.push('_');
    }
    level.bodies.push(BodyDef {
        name: name.clone(),
        kind: BodyKind::Dynamic,
        shape: Some(shape),
        position: (top.x, top.y),
        angle: 0.0,
        velocity: (0.0, 0.0),
        omega: 0.0,
        mass: None,
        density: None,
        inertia: None,
        radius_of_gyration: None,
        lock_rotation: false,
        friction: None,
        restitution: None,
        linear_damping: None,
        angular_damping: None,
    });
    let mut note = format!("spawned {name}");
    for e in [Effect::Gravity, Effect::Contacts] {
        if !level.effects.contains(&e) {
            level.effects.push(e);
            note += &format!(" (turned on `{}`)", e.name());
        }
    }
    if s.step > 0 {
        note += "; the scene restarts from the current state (checks and questions apply from t = 0 only)";
    }
    (
        Scene {
            file: scene.file.clone(),
            level,
        },
        note,
    )
}

/// Writes the current state as a level and reads it back: it must parse, validate, and be equal.
pub fn save(phys: &Physics, path: &Path) -> Result<String, String> {
    let level = capture(&phys.scene.level, phys.snapshot());
    let text = level::to_ron(&level);
    let back = level::parse(path, &text)
        .map_err(|e| format!("not saved: the level would not load back:\n{e}"))?;
    if back.level != level {
        return Err("not saved: the level read back differs from the scene".into());
    }
    std::fs::write(path, &text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(format!("saved {} (loads back identically)", path.display()))
}

fn solver(ui: &mut egui::Ui, phys: &mut Physics, live: &LiveChecks) {
    ui.heading("Solver");
    let dt = phys.sim.dt();
    let mut new_dt = dt;
    let mut substeps = phys.sim.substeps();
    let mut iterations = phys.sim.settings().solver_iterations;
    let mut changed = false;
    egui::Grid::new("solver").num_columns(3).show(ui, |ui| {
        ui.label("dt");
        ui.horizontal(|ui| {
            if ui.small_button("÷2").clicked() {
                new_dt = dt / 2.0;
                changed = true;
            }
            ui.label(format!("{:.5} s ({:.0} Hz)", dt, 1.0 / dt));
            if ui.small_button("×2").clicked() {
                new_dt = (dt * 2.0).min(0.1);
                changed = true;
            }
        });
        ui.end_row();
        ui.label("substeps");
        changed |= ui
            .add(egui::DragValue::new(&mut substeps).range(1..=200))
            .changed();
        ui.end_row();
        ui.label("iterations");
        changed |= ui
            .add(egui::DragValue::new(&mut iterations).range(1..=200))
            .changed();
        ui.end_row();
    });
    if changed {
        phys.options.dt = Some(new_dt);
        phys.options.substeps = Some(substeps);
        phys.options.solver_iterations = Some(iterations);
        phys.reset();
    }
    match phys.step_times.median_ms() {
        Some(ms) => {
            // The cost as `rigidlab study accuracy` reports it: wall µs per simulated second.
            ui.label(format!(
                "step time {:.3} ms (median of the last steps) = {:.0} µs per simulated s, {:.0}× real time",
                ms,
                ms * 1e3 / dt,
                dt * 1e3 / ms.max(1e-9)
            ));
        }
        None => {
            ui.label("step time: play to measure");
        }
    }
    // The current error: energy drift where energy should be conserved, else the checks' errors.
    if let (Some(first), Some(last)) = (phys.series.first(), phys.series.last()) {
        let e0 = first.total();
        let scale = first
            .kinetic
            .abs()
            .max(first.gravity.abs())
            .max(first.elastic.abs())
            .max(1e-12);
        ui.label(format!(
            "energy change since t = 0: {:+.3e} J ({:+.3}% of the largest energy term)",
            last.total() - e0,
            (last.total() - e0) / scale * 100.0
        ));
    }
    match (&live.checks, &live.answers) {
        (Some(checks), Some(answers)) => {
            let (error, ratio) = study_error(checks, answers);
            if let Some(e) = error {
                ui.label(format!(
                    "error against the textbook answers {e:.3e} (relative, as `rigidlab study accuracy` measures it)"
                ));
            }
            if let Some(r) = ratio {
                ui.label(format!(
                    "worst error / tolerance {r:.3} (checks and questions)"
                ));
            }
            if phys.interfered {
                ui.label(rich(
                    "(you pushed the scene: not the exercise's error)",
                    palette::FRICTION,
                ));
            }
        }
        _ if !phys.sim.level.checks.is_empty() || !phys.sim.level.questions.is_empty() => {
            ui.label(format!(
                "error against the textbook answers: at t = {:.3} s (the level's end)",
                phys.sim.level.world.duration
            ));
        }
        _ => {}
    }
    if phys.options != Default::default() && ui.small_button("level's settings").clicked() {
        phys.options = Default::default();
        phys.reset();
    }
}

/// The error the accuracy study plots for a level with exact answers (src/study/accuracy.rs,
/// `measure::full_run`): the worst relative error of the questions and of the closed-form
/// (constant-acceleration) checks; and the worst error-to-tolerance ratio of all checks and
/// questions.
pub fn study_error(
    checks: &[crate::checks::CheckResult],
    answers: &[crate::questions::QuestionResult],
) -> (Option<f64>, Option<f64>) {
    let closed_form = crate::checks::kind_name(crate::level::CheckKind::ConstantAcceleration);
    // As the study: kinds that observed nothing are not graded.
    let checks: Vec<_> = checks.iter().filter(|c| c.samples > 0).collect();
    let error = answers
        .iter()
        .map(|q| q.rel_error)
        .chain(
            checks
                .iter()
                .filter(|c| c.kind == closed_form)
                .map(|c| c.max_rel_error),
        )
        .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
    let ratio = |e: f64, tol: f64| {
        if tol > 0.0 {
            e / tol
        } else if e == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    };
    let worst = checks
        .iter()
        .map(|c| ratio(c.max_rel_error, c.tolerance))
        .chain(answers.iter().map(|q| ratio(q.rel_error, q.tolerance)))
        .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
    (error, worst)
}

fn plots(ui: &mut egui::Ui, phys: &Physics) {
    ui.heading("Energy and momentum");
    let series = &phys.series;
    if let Some(p) = series.last() {
        egui::Grid::new("energies").num_columns(2).show(ui, |ui| {
            ui.label(rich("kinetic T", palette::VELOCITY));
            ui.label(format!("{:.5} J", p.kinetic));
            ui.end_row();
            ui.label(rich("potential V (gravity + springs)", palette::GRAVITY));
            ui.label(format!("{:.5} J", p.gravity + p.elastic));
            ui.end_row();
            ui.label(rich("total E = T + V", palette::TEXT));
            ui.label(format!("{:.5} J", p.total()));
            ui.end_row();
            ui.label(rich("H about the world origin", palette::MOMENTUM));
            ui.label(format!("{:.5} N m s", p.h_o));
            ui.end_row();
        });
    }
    line_plot(
        ui,
        series,
        &[
            (&|p: &SeriesPoint| p.kinetic, palette::VELOCITY),
            (&|p: &SeriesPoint| p.gravity + p.elastic, palette::GRAVITY),
            (&|p: &SeriesPoint| p.total(), palette::TEXT),
        ],
        "J",
    );
    line_plot(
        ui,
        series,
        &[(&|p: &SeriesPoint| p.h_o, palette::MOMENTUM)],
        "N m s",
    );
}

type Pick<'a> = &'a dyn Fn(&SeriesPoint) -> f64;

/// A small line plot against time, with the value range and time range written on it.
fn line_plot(ui: &mut egui::Ui, series: &[SeriesPoint], lines: &[(Pick, Color)], unit: &str) {
    let width = ui.available_width().min(320.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 110.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_gray(250));
    painter.rect_stroke(
        rect,
        2.0,
        egui::Stroke::new(1.0, egui::Color32::from_gray(180)),
        egui::StrokeKind::Inside,
    );
    if series.len() < 2 {
        return;
    }
    let (t0, t1) = (
        series[0].t,
        series[series.len() - 1].t.max(series[0].t + 1e-9),
    );
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (f, _) in lines {
        for p in series {
            let v = f(p);
            if v.is_finite() {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    if !(lo <= hi) {
        return;
    }
    let pad = ((hi - lo) * 0.08).max(1e-9 * hi.abs().max(1.0));
    let (lo, hi) = (lo - pad, hi + pad);
    let inner = rect.shrink2(egui::vec2(4.0, 14.0));
    let map = |t: f64, v: f64| {
        egui::pos2(
            inner.min.x + ((t - t0) / (t1 - t0)) as f32 * inner.width(),
            inner.max.y - ((v - lo) / (hi - lo)) as f32 * inner.height(),
        )
    };
    if lo < 0.0 && hi > 0.0 {
        painter.line_segment(
            [map(t0, 0.0), map(t1, 0.0)],
            egui::Stroke::new(1.0, egui::Color32::from_gray(200)),
        );
    }
    let stride = (series.len() / (2 * width as usize).max(1)).max(1);
    for (f, c) in lines {
        let pts: Vec<egui::Pos2> = series
            .iter()
            .step_by(stride)
            .map(|p| map(p.t, f(p)))
            .collect();
        painter.add(egui::Shape::line(pts, egui::Stroke::new(1.5, color32(*c))));
    }
    let font = egui::FontId::proportional(10.0);
    let gray = egui::Color32::from_gray(90);
    painter.text(
        rect.left_top() + egui::vec2(3.0, 1.0),
        egui::Align2::LEFT_TOP,
        format!("{} {unit}", fmt(hi)),
        font.clone(),
        gray,
    );
    painter.text(
        rect.left_bottom() + egui::vec2(3.0, -1.0),
        egui::Align2::LEFT_BOTTOM,
        format!("{} {unit}", fmt(lo)),
        font.clone(),
        gray,
    );
    painter.text(
        rect.right_bottom() + egui::vec2(-3.0, -1.0),
        egui::Align2::RIGHT_BOTTOM,
        format!("t = {:.2} s", t1),
        font,
        gray,
    );
}

/// `text` cut to `n` characters with an ellipsis.
fn clip(text: &str, n: usize) -> String {
    if text.chars().count() <= n {
        return text.to_string();
    }
    let mut out: String = text.chars().take(n - 1).collect();
    out.push('…');
    out
}

fn checks(ui: &mut egui::Ui, phys: &Physics, live: &LiveChecks) {
    let level = &phys.sim.level;
    if level.checks.is_empty() && level.questions.is_empty() {
        return;
    }
    ui.heading("Theory against engine");
    match (&live.checks, &live.answers) {
        (Some(checks), Some(answers)) => {
            if phys.interfered {
                ui.label(rich(
                    "(you pushed the scene during this run)",
                    palette::FRICTION,
                ));
            }
            egui::Grid::new("checks")
                .num_columns(4)
                .striped(true)
                .show(ui, |ui| {
                    ui.strong("check");
                    ui.strong("max error");
                    ui.strong("tol.");
                    ui.strong("");
                    ui.end_row();
                    for c in checks {
                        // Clipped to a fixed length: a long subject would widen the panel over
                        // the scene (egui grows a side panel to its widest row).
                        ui.label(clip(&format!("{} {}", c.kind, c.subject), 18))
                            .on_hover_text(format!("{} {}\n{}", c.kind, c.subject, c.why));
                        ui.label(format!("{:.2e}", c.max_rel_error));
                        ui.label(format!("{:.1e}", c.tolerance));
                        ui.label(if c.passed {
                            rich("pass", palette::GRAVITY)
                        } else {
                            rich("FAIL", palette::NORMAL)
                        });
                        ui.end_row();
                    }
                    for q in answers {
                        ui.label(clip(&format!("question {}", q.id), 18))
                            .on_hover_text(format!("{}\n{}", q.ask, q.why));
                        ui.label(format!("{:.2e}", q.rel_error));
                        ui.label(format!("{:.1e}", q.tolerance));
                        ui.label(if q.passed {
                            rich("pass", palette::GRAVITY)
                        } else {
                            rich("FAIL", palette::NORMAL)
                        });
                        ui.end_row();
                    }
                });
        }
        _ => {
            ui.label(format!(
                "{} checks and {} questions are evaluated every step; results at t = {:.3} s (the level's end).",
                level.checks.len(),
                level.questions.len(),
                level.world.duration
            ));
        }
    }
}
