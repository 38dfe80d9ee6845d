//! The sandbox's egui panels, one file per panel: the level browser and the exercise with its
//! graded questions on the left; playback, overlays, tools, solver settings, energy and momentum
//! plots and the checks on the right; the status bar with the keyboard shortcuts at the bottom.
//!
//! This file lays the panels out (the [`PanelsPlugin`]'s one egui system, a function per step); the state they share
//! is [`UiState`] (state.rs) and the exercise's [`Exercise`]; each panel's file says what it
//! shows. Panels read the run and ask for changes to it with [`PhysicsCommand`]s, which this
//! system writes; they import from beside and below them, never from this file.

pub mod assignment_list;
pub mod challenge;
pub mod checks;
pub mod course;
pub mod egui_input;
mod exercise;
pub mod help;
pub mod hints;
mod level_browser;
mod level_entry;
pub mod measure;
pub mod number_field;
mod overlay_controls;
mod playback;
pub mod plots;
pub mod predict;
pub mod questions_editor;
mod scene_editor;
pub mod shortcuts;
mod solver;
pub mod state;
mod student_id;
mod tool_controls;
pub mod tour;
mod track_editor;

pub use course::Course;
pub use exercise::{grade, grade_message, measured_shown, Exercise, Grade, SHOWN_WHEN_RIGHT};
pub use level_browser::{utc_minute, version_line, Browser, Entry};
pub use playback::{energy_drift_note, finer_step, DRIFT_WARNING, FINER_STEP};
pub use predict::Predict;
pub use solver::study_error;
pub use state::UiState;

use super::advice::WindowAdvice;
use super::editor::{Editor, EditorCommand};
use super::frame_rate::FrameRate;
use super::overlays::Overlays;
use super::physics::{LiveChecks, PhysicsCommand};
use super::playback::Playback;
use super::prefs::{Prefs, PrefsFile};
use super::run::Run;
use super::tools::ToolState;
use super::ui::{legible, rich, Typing};
use super::unsaved::{Leaving, Unsaved};
use super::user_files::default_save_path;
use super::view::{palette, View, WorldCamera};
use crate::level::{BodyKind, Level, Scene};
use bevy::camera::visibility::RenderLayers;
use bevy::camera::CameraOutputMode;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy::render::render_resource::BlendState;
use bevy_egui::{
    egui, EguiContexts, EguiGlobalSettings, EguiPrimaryContextPass, PrimaryEguiContext,
};
use checks::checks;
use exercise::exercise;
use level_browser::level_browser;
use overlay_controls::overlay_controls;
use playback::playback;
use plots::plots;
use scene_editor::scene_editor;
use shortcuts::keys;
use solver::solver;
use std::path::PathBuf;
use tool_controls::tool_controls;

pub struct PanelsPlugin;

impl Plugin for PanelsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<UiState>()
            .init_resource::<Exercise>()
            .init_resource::<Course>()
            .init_resource::<egui_input::EguiInputQueue>()
            .init_resource::<Typing>()
            .init_resource::<Predict>()
            .add_systems(
                PreUpdate,
                egui_input::input_to_egui.in_set(bevy_egui::EguiInputSet::ReadBevyMessages),
            )
            .add_systems(
                Update,
                (
                    shortcuts::follow_presses
                        .before(keys)
                        .before(super::overlays::overlay_keys),
                    keys.before(super::physics::PhysicsStep),
                    predict::follow.before(super::physics::PhysicsStep),
                    super::view::pan_zoom,
                    super::overlays::overlay_keys,
                ),
            )
            .add_systems(
                EguiPrimaryContextPass,
                (panels, course::track_progress).chain(),
            );
        challenge::plugin(app);
    }
}

/// The world camera and, over it, the egui camera (full window, draws only the UI).
pub fn spawn_cameras(
    mut commands: Commands,
    mut settings: ResMut<EguiGlobalSettings>,
    adapter: Option<Res<bevy::render::renderer::RenderAdapterInfo>>,
) {
    settings.auto_create_primary_context = false;
    // Keys, the cursor and the mouse buttons reach egui through egui_input::input_to_egui, in
    // the order they came and with a click a frame before the keys typed after it (bevy_egui's
    // own systems typed "a" for a Ctrl+A pressed within one frame, and lost the keys typed in
    // the frame of the click into a box).
    let input = &mut settings.input_system_settings;
    input.run_write_keyboard_input_messages_system = false;
    input.run_write_window_pointer_moved_messages = false;
    input.run_write_pointer_button_messages = false;
    let msaa = super::frame_cost::scene_samples(adapter.as_deref());
    commands.spawn((Camera2d, WorldCamera, msaa));
    commands.spawn((
        PrimaryEguiContext,
        Camera2d,
        // Cameras drawing into one window must agree on the sample count (wgpu refuses a pass
        // with a 4x color and a 1x depth attachment: the native window went blank when they did
        // not).
        msaa,
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

/// What the panels read and change: the run and the asks to it, and the window's state.
#[derive(SystemParam)]
struct PanelInput<'w, 's> {
    contexts: EguiContexts<'w, 's>,
    phys: Res<'w, Run>,
    play: Res<'w, Playback>,
    run_commands: MessageWriter<'w, PhysicsCommand>,
    live: NonSend<'w, LiveChecks>,
    exercise: ResMut<'w, Exercise>,
    predict: ResMut<'w, Predict>,
    view: ResMut<'w, View>,
    ov: ResMut<'w, Overlays>,
    tools: ResMut<'w, ToolState>,
    st: ResMut<'w, UiState>,
    browser: ResMut<'w, Browser>,
    time: ResMut<'w, Time<Virtual>>,
    rate: Option<Res<'w, FrameRate>>,
    typing: ResMut<'w, Typing>,
    files: FileInput<'w, 's>,
}

/// The editor, the preferences, the unsaved-work question and the advice the panels show.
#[derive(SystemParam)]
struct FileInput<'w, 's> {
    editor: ResMut<'w, Editor>,
    edits: MessageWriter<'w, EditorCommand>,
    prefs: Option<ResMut<'w, Prefs>>,
    prefs_file: Option<Res<'w, PrefsFile>>,
    unsaved: Option<ResMut<'w, Unsaved>>,
    course: ResMut<'w, Course>,
    commands: Commands<'w, 's>,
    advice: Option<Res<'w, WindowAdvice>>,
}

/// The egui system: lays out the side panels and the status bar, and leaves the rest of the
/// window to the scene; opens the level the browser asked for.
fn panels(mut p: PanelInput) -> Result {
    let ctx = p.contexts.ctx_mut()?.clone();
    follow_the_run(&ctx, &mut p);
    let mut root = egui::Ui::new(
        ctx.clone(),
        "rigidlab-root".into(),
        egui::UiBuilder::new()
            .layer_id(egui::LayerId::background())
            .max_rect(ctx.viewport_rect()),
    );
    let mut load = left_panel(&mut root, &mut p);
    // What the panels ask of the run, written in the order asked.
    for c in right_panel(&mut root, &mut p) {
        p.run_commands.write(c);
    }
    status_bar(&mut root, &mut p);
    // What is left is the scene's viewport.
    let free = root.available_rect_before_wrap();
    p.view.viewport = Rect::new(free.min.x, free.min.y, free.max.x, free.max.y);
    help_and_tour(&ctx, &mut p, free);
    let asked = challenge::window(
        &ctx,
        (&p.phys, &p.browser, &p.view, p.st.tour.open),
        (&p.live, &mut p.files.course, &mut p.st.message),
        free,
    );
    for c in asked {
        p.run_commands.write(c);
    }
    tidy_after_frame(&ctx, &mut p);
    if load.is_none() {
        load = p.st.pending_open.take();
    }
    if let Some(scene) = settle_leaving(&ctx, &mut p, load) {
        open_level(&mut p, scene);
    }
    Ok(())
}

/// The first frame's look and preferences, a new level's save name and answers, the time scale.
fn follow_the_run(ctx: &egui::Context, p: &mut PanelInput) {
    let st = &mut *p.st;
    let phys = &*p.phys;
    if st.generation.is_none() {
        // The textbook look: dark ink on paper, no text smaller than ui::SMALL_TEXT.
        ctx.set_visuals(egui::Visuals::light());
        ctx.all_styles_mut(legible);
        if let Some(prefs) = p.files.prefs.as_deref() {
            st.tour.open = !prefs.tour_done;
            st.time_scale = prefs.time_scale;
            p.ov.arrow_scale = prefs.arrow_scale;
            p.ov.labels = prefs.labels;
            p.ov.trails = prefs.trails;
            if prefs.predict_first {
                p.predict.switch = Some(true);
            }
        }
        // The tour's steps ticked in an earlier session (the page has no preferences file).
        tour::restore(&mut st.tour, &p.files.course.progress);
        if let Some(problem) = p
            .files
            .prefs_file
            .as_deref()
            .and_then(|f| f.problem.clone())
        {
            st.message = Some((problem, false));
        } else if !p.browser.opened_from.is_empty() {
            // Which library opened: started from another folder, it is not ./levels.
            st.message = Some((p.browser.opened_from.clone(), true));
        }
    }
    if st.save_for.as_ref() != Some(&phys.scene.file) {
        // A different level (opened, or a new scene): save it under its own name.
        st.save_for = Some(phys.scene.file.clone());
        st.save_path = default_save_path(&phys.scene);
    }
    if st.generation != Some(phys.generation) {
        st.generation = Some(phys.generation);
        p.exercise.start_level(
            &phys.scene.file,
            &phys.sim.level.statement,
            phys.sim.level.questions.len(),
        );
        st.edit_title = None;
        if st.save_path.is_empty() {
            st.save_path = default_save_path(&phys.scene);
        }
    }
    if (p.time.relative_speed_f64() - st.time_scale).abs() > 1e-12 {
        p.time.set_relative_speed_f64(st.time_scale);
    }
}

/// The left panel: the open exercise over the level browser. The level the browser asked for,
/// if any.
fn left_panel(root: &mut egui::Ui, p: &mut PanelInput) -> Option<Scene> {
    let mut load: Option<Scene> = None;
    egui::Panel::left("levels")
        .resizable(true)
        .default_size(300.0)
        .size_range(200.0..=520.0)
        .show(root, |ui| {
            let (phys, play) = (&*p.phys, &*p.play);
            let (pred, message) = (&mut *p.predict, &mut p.st.message);
            load = left_column_under(
                ui,
                |ui, ex| predict::predict(ui, (phys, play), ex, pred, message),
                &mut p.browser,
                (&p.phys, &p.live),
                &mut p.exercise,
                &mut p.files.course,
            );
        });
    load
}

/// The left panel of a level with questions, as the window draws it: predict first's part on
/// top, then [`left_column`], in one scroll area. The level asked for, if any.
pub fn left_panel_of(
    ui: &mut egui::Ui,
    (phys, play, live): (&Run, &Playback, &LiveChecks),
    (browser, ex, pred, progress): (&mut Browser, &mut Exercise, &mut Predict, &mut Course),
) -> Option<Scene> {
    let mut message = None;
    left_column_under(
        ui,
        |ui, ex| predict::predict(ui, (phys, play), ex, pred, &mut message),
        browser,
        (phys, live),
        ex,
        progress,
    )
}

/// The left panel's column: the open exercise first, its statement and questions where a
/// student looks first (they sat below the whole level list: 30 titles to scroll past), with
/// the *Next level* button under them, then the course (open: it sits below the exercise, which
/// it no longer pushes down). A level opened brings the column back to its top. The level the
/// browser or the course asked for, if any.
pub fn left_column(
    ui: &mut egui::Ui,
    browser: &mut Browser,
    (phys, live): (&Run, &LiveChecks),
    ex: &mut Exercise,
    progress: &mut Course,
) -> Option<Scene> {
    left_column_under(ui, |_, _| {}, browser, (phys, live), ex, progress)
}

/// [`left_column`] under `top` (predict first's switch and results), in the column's one scroll
/// area: the results had a scroll area of their own stacked over the column's, each with its
/// scroll bar (the student trial of 2026-12-07).
fn left_column_under(
    ui: &mut egui::Ui,
    top: impl FnOnce(&mut egui::Ui, &Exercise),
    browser: &mut Browser,
    (phys, live): (&Run, &LiveChecks),
    ex: &mut Exercise,
    progress: &mut Course,
) -> Option<Scene> {
    let mut load: Option<Scene> = None;
    let shown = egui::Id::new("left column: level shown");
    let new_level = ui.data(|d| d.get_temp::<PathBuf>(shown)) != Some(phys.scene.file.clone());
    ui.data_mut(|d| d.insert_temp(shown, phys.scene.file.clone()));
    let mut scroll = egui::ScrollArea::vertical().id_salt("left column");
    if new_level {
        scroll = scroll.vertical_scroll_offset(0.0);
    }
    scroll.show(ui, |ui| {
        top(ui, ex);
        exercise(ui, phys, live, ex);
        course::next_level(ui, (browser, phys, ex), progress, &mut load);
        exercise::exercise_help(ui, phys, ex);
        ui.separator();
        assignment_list::assignment_list(ui, browser.assignment.as_ref(), phys, &mut load);
        student_id::student_id(ui, browser, phys, &mut load);
        let (solved, total) = course::solved_count(browser, progress);
        let list = egui::CollapsingHeader::new(
            egui::RichText::new(format!("Course: {solved}/{total} solved")).heading(),
        )
        .id_salt("all levels")
        .default_open(true);
        list.show(ui, |ui| {
            level_browser(ui, browser);
            course::course(ui, browser, phys, progress, &mut load);
        });
    });
    load
}

/// The right panel, top to bottom: playback, overlays, tools, the Build panel, solver, measure,
/// plots, checks and advice. What its panels ask of the run, in the order asked.
fn right_panel(root: &mut egui::Ui, p: &mut PanelInput) -> Vec<PhysicsCommand> {
    let mut asked: Vec<PhysicsCommand> = Vec::new();
    egui::Panel::right("controls")
        .resizable(true)
        .default_size(330.0)
        .size_range(260.0..=520.0)
        .show(root, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                let edits = upper_controls(
                    ui,
                    (&p.phys, &p.play, &p.files.editor),
                    (&mut p.view, &mut p.ov, &mut p.tools, &mut p.st),
                    &mut asked,
                );
                send_edits(p, edits);
                ui.separator();
                solver(ui, &p.phys, &p.live, &mut asked);
                ui.separator();
                measure_and_plots(ui, p);
                ui.separator();
                checks(ui, &p.phys, &p.live);
                if let Some(a) = p.files.advice.as_deref() {
                    super::advice::panel(ui, a, &p.phys, &mut asked);
                }
            });
        });
    asked
}

/// The right panel's controls, top to bottom: playback, overlays, tools and the Build panel.
/// What playback asks of the run goes to `asked`; the Build panel's edits are returned. Rows
/// whose content comes and goes keep their height (`ui::fixed_rows`), so nothing here moves
/// under the pointer as the run plays, a body is selected or an edit is answered.
pub fn upper_controls(
    ui: &mut egui::Ui,
    (phys, play, editor): (&Run, &Playback, &Editor),
    (view, ov, tools, st): (&mut View, &mut Overlays, &mut ToolState, &mut UiState),
    asked: &mut Vec<PhysicsCommand>,
) -> Vec<EditorCommand> {
    let restarts = playback(
        ui,
        (phys, play),
        &mut st.time_scale,
        view,
        ov.selected,
        asked,
    );
    if restarts {
        // The impulse tool's arrow goes with the run it struck.
        tools.last_impulse = None;
    }
    ui.separator();
    overlay_controls(ui, ov, phys);
    ui.separator();
    tool_controls(ui, tools, phys, st);
    ui.separator();
    let mut out = Vec::new();
    scene_editor(ui, phys, editor, tools, ov.selected, st, &mut out);
    out
}

/// The Build panel's edits to the editor (a new scene over unsaved edits asks first).
fn send_edits(p: &mut PanelInput, out: Vec<EditorCommand>) {
    let phys = &*p.phys;
    let f = &mut p.files;
    for c in out {
        if c == EditorCommand::New {
            // Unsaved edits: ask first (app/unsaved.rs).
            if let Some(u) = f.unsaved.as_deref_mut() {
                if u.request(f.editor.unsaved(phys), Leaving::New).is_none() {
                    continue;
                }
            }
        }
        if matches!(c, EditorCommand::Apply(crate::editor::Edit::Delete { .. })) {
            p.ov.selected = None;
            p.ov.point = None;
        }
        f.edits.write(c);
    }
}

/// The Measure panel and the plots under it.
fn measure_and_plots(ui: &mut egui::Ui, p: &mut PanelInput) {
    let (phys, st, ov) = (&*p.phys, &mut *p.st, &*p.ov);
    measure::measure(
        ui,
        phys,
        &mut p.tools,
        &mut st.stopwatch,
        ov.selected,
        ov.point,
    );
    ui.separator();
    plots(ui, phys, ov.origin, &mut st.message);
    ui.add_space(4.0);
    plots::body_plot(
        ui,
        phys,
        ov.selected,
        (&mut st.body_plot, &mut st.body_plot_against),
        &mut st.message,
    );
}

/// The status bar: the last message, help, the frame rate and the keys.
fn status_bar(root: &mut egui::Ui, p: &mut PanelInput) {
    let rate = p.rate.as_deref().cloned().unwrap_or_default();
    let st = &mut *p.st;
    let typing_off_box = p.typing.active && !root.ctx().text_edit_focused();
    egui::Panel::bottom("status").show(root, |ui| {
        ui.horizontal_wrapped(|ui| {
            if typing_off_box {
                ui.label(rich(shortcuts::TYPING_NOTE, palette::FRICTION));
                ui.separator();
            }
            if let Some((m, ok)) = &st.message {
                ui.label(rich(m.clone(), if *ok { palette::GRAVITY } else { palette::NORMAL }));
                ui.separator();
            }
            if ui.small_button("? help").on_hover_text("F1 or ?").clicked() {
                st.help = !st.help;
            }
            if let Some(ms) = rate.median_ms() {
                ui.label(rich(format!("{:.0} fps ({ms:.0} ms a frame)", 1e3 / ms), palette::OUTLINE))
                    .on_hover_text("median over the last 120 frames");
                ui.separator();
            }
            ui.label(
                "Space play/pause · S step · Left back · R reset · −/= time scale · wheel zoom · right-drag pan · Home fit · \
                 1 select/drag · 2 impulse · 3 set O · V A C F K H T L N overlays · F12 screenshot · F1 help",
            );
        });
    });
}

/// The help window and the tour over the scene; the preferences saved when they changed.
fn help_and_tour(ctx: &egui::Context, p: &mut PanelInput, scene: egui::Rect) {
    let st = &mut *p.st;
    help::help(ctx, &mut st.help);
    let mut t = std::mem::take(&mut st.tour);
    let answered = p.exercise.grades.iter().any(|g| g.is_some());
    let finished = tour::tour(
        ctx,
        scene,
        &mut t,
        &p.phys,
        &p.ov,
        (answered, st.help),
        &p.files.editor,
    );
    st.tour = t;
    let course = &mut *p.files.course;
    if let Some(note) = tour::keep(
        &st.tour,
        finished,
        (&mut course.progress, &mut course.store),
    ) {
        st.message = Some((note, false));
    }
    if let Some(prefs) = p.files.prefs.as_deref_mut() {
        let now = Prefs {
            tour_done: prefs.tour_done || finished,
            arrow_scale: p.ov.arrow_scale,
            time_scale: st.time_scale,
            labels: p.ov.labels,
            trails: p.ov.trails,
            predict_first: p.predict.everywhere,
            student_id: super::student::id().unwrap_or_default(),
        };
        if now != *prefs {
            *prefs = now;
            let file = p.files.prefs_file.as_deref().cloned().unwrap_or_default();
            if let Err(e) = prefs.save(&file) {
                st.message = Some((format!("preferences not saved: {e}"), false));
            }
        }
    }
}

/// After the panels: a selection an undo took away, egui's keyboard focus, the body the run
/// tracks, a just-saved level in the browser.
fn tidy_after_frame(ctx: &egui::Context, p: &mut PanelInput) {
    let phys = &*p.phys;
    if p.ov
        .selected
        .is_some_and(|i| i >= phys.scene.level.bodies.len())
    {
        // An undo took the selected body away.
        p.ov.selected = None;
        p.ov.point = None;
    }
    // A clicked button keeps egui's keyboard focus, and egui then reports that it wants the
    // keyboard: every shortcut went dead after any click in a panel (and Space pressed the
    // focused button too). Once the pointer is back over the scene, only a text being typed
    // keeps the focus (a number field clicked for typing takes it a frame before its text
    // edit shows, while the pointer is still on it).
    if !ctx.text_edit_focused() && !ctx.is_pointer_over_egui() {
        ctx.memory_mut(|m| m.stop_text_input());
    }
    // The keyboard stays the text field's after it loses the focus, and is the panels' after a
    // press on one (a click that missed a box), until a click in the scene or Esc (ui::Typing):
    // the shortcuts read this next frame.
    let pressed = ctx.input(|i| i.pointer.any_pressed());
    if pressed && ctx.is_pointer_over_egui() {
        p.typing.active = true;
    }
    let scene_click = pressed && !ctx.is_pointer_over_egui();
    let escape = ctx.input(|i| i.key_pressed(egui::Key::Escape));
    p.typing
        .follow(ctx.text_edit_focused(), scene_click, escape);
    if phys.tracked != p.ov.selected {
        p.run_commands.write(PhysicsCommand::Track(p.ov.selected));
    }
    if p.files.editor.just_saved.take().is_some() {
        // A level saved into the folder the browser lists shows there at once. The save field
        // keeps the name asked for: saving again keeps both files (the next numbered name).
        if !p.browser.embedded {
            p.browser.rescan();
        }
    }
}

/// A level asked for (`load`) over unsaved edits waits for the user's answer; the answer
/// settled (save, discard, cancel, and then open, start a new scene or close the window). The
/// level to open now, if any.
fn settle_leaving(ctx: &egui::Context, p: &mut PanelInput, load: Option<Scene>) -> Option<Scene> {
    let (phys, st, f) = (&*p.phys, &mut *p.st, &mut p.files);
    let mut load = load;
    if let (Some(scene), Some(u)) = (load.take(), f.unsaved.as_deref_mut()) {
        // Unsaved edits: ask before another level replaces them.
        if let Some(Leaving::Open(s)) =
            u.request(f.editor.unsaved(phys), Leaving::Open(Box::new(scene)))
        {
            load = Some(*s);
        }
    }
    let answer = f
        .unsaved
        .as_deref()
        .and_then(|u| super::unsaved::dialog(ctx, u, &st.save_path));
    if let (Some(answer), Some(u)) = (answer, f.unsaved.as_deref_mut()) {
        match u.settle(answer, &mut f.editor, phys, &PathBuf::from(&st.save_path)) {
            Ok((go, note)) => {
                if let Some(m) = note {
                    st.message = Some((m, true));
                }
                match go {
                    Some(Leaving::Open(s)) => load = Some(*s),
                    Some(Leaving::New) => {
                        f.edits.write(EditorCommand::New);
                    }
                    Some(Leaving::Close(window)) => {
                        f.commands.entity(window).try_despawn();
                    }
                    None => {}
                }
            }
            // Not saved: the question stays, with why in the status line.
            Err(e) => st.message = Some((e, false)),
        }
    }
    if f.editor.just_saved.take().is_some() && !p.browser.embedded {
        // Saved from the question: the browser lists it at once.
        p.browser.rescan();
    }
    load
}

/// Opens `scene`: its save name, the status line, the selection and O, and the run asked.
fn open_level(p: &mut PanelInput, scene: Scene) {
    p.st.save_path = default_save_path(&scene);
    p.st.message = Some((format!("opened {}", scene.file.display()), true));
    p.ov.selected = None;
    p.ov.point = None;
    // The crowd's every-body overlays are slow by choice for one scene, not for the next.
    p.ov.every_body = false;
    p.ov.origin = default_origin(&scene.level);
    p.tools.last_impulse = None;
    p.run_commands.write(PhysicsCommand::Open(Box::new(scene)));
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
