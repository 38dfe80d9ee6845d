//! The playback panel: time and progress, play/pause, single step, reset, fit the view, the
//! time scale, whether to stop at the level's end, and why a run is slowed or no longer the
//! exercise's.

use super::super::physics::PhysicsCommand;
use super::super::playback::{play_restarts, Playback};
use super::super::run::Run;
use super::super::time_text;
use super::super::ui::{fixed_height, fmt, rich};
use super::super::view::{palette, View};
use bevy_egui::egui;

/// Draws the panel; what it asks of the run goes to `out`. True when it asked for the run to
/// start over (Reset, or Play at the level's end).
pub(super) fn playback(
    ui: &mut egui::Ui,
    (phys, play): (&Run, &Playback),
    time_scale: &mut f64,
    view: &mut View,
    selected: Option<usize>,
    out: &mut Vec<PhysicsCommand>,
) -> bool {
    let (time, step) = (phys.snapshot().time, phys.snapshot().step);
    let duration = phys.sim.level.world.duration;
    ui.heading("Playback");
    // Where the timeline is going shares the time's line: a row of its own came and went above
    // the buttons, which moved under the pointer.
    let going = phys
        .seek
        .map(|target| {
            let t = target as f64 * phys.sim.dt();
            format!("   going to t = {} s…", time_text::clock(t, phys.sim.dt()))
        })
        .unwrap_or_default();
    let dt = phys.sim.dt();
    ui.label(format!(
        "t = {} s of {} s   (step {step}){going}",
        time_text::clock(time, dt),
        time_text::clock(duration, dt),
    ));
    timeline(ui, phys, out);
    let restarts = buttons(ui, (phys, play), view, out);
    ui.horizontal(|ui| {
        ui.label("time scale");
        ui.add(
            egui::Slider::new(time_scale, 1.0 / 64.0..=8.0)
                .logarithmic(true)
                .max_decimals(3),
        );
    });
    let mut stop_at_end = play.stop_at_end;
    if ui
        .checkbox(
            &mut stop_at_end,
            "stop at the level's end (where `rigidlab check` stops)",
        )
        .changed()
    {
        out.push(PhysicsCommand::StopAtEnd(stop_at_end));
    }
    follow(ui, phys, view, selected);
    run_notes(ui, phys, play, out);
    restarts
}

/// The run's blows and warnings in a box of fixed height (scrolled when they are more): they
/// come and go while the run plays (a blow struck, the physics falling behind real time) and
/// moved every control below them as they did.
fn run_notes(ui: &mut egui::Ui, phys: &Run, play: &Playback, out: &mut Vec<PhysicsCommand>) {
    let row = super::super::ui::row_height(ui);
    let height = (2.0 * row).max(drift_note_room(ui, phys));
    egui::ScrollArea::vertical()
        .id_salt("run notes")
        .max_height(height)
        .min_scrolled_height(height)
        .auto_shrink([true, true])
        .show(ui, |ui| {
            fixed_height(ui, height, |ui| {
                warnings(ui, phys, play, out);
                blows(ui, phys);
            })
        });
}

/// The timeline: drag to any time of the level; going back replays the run from t = 0
/// (deterministic, the user's pushes included), so every overlay, plot and check is the run's.
fn timeline(ui: &mut egui::Ui, phys: &Run, out: &mut Vec<PhysicsCommand>) {
    let step = phys.snapshot().step;
    let dt = phys.sim.dt();
    let total = phys.sim.total_steps().max(step);
    let mut at = phys.seek.unwrap_or(step) as f64 * dt;
    let end = total as f64 * dt;
    let r = ui.add(
        egui::Slider::new(&mut at, 0.0..=end)
            .show_value(false)
            .text("timeline"),
    );
    if r.changed() {
        out.push(PhysicsCommand::Seek((at / dt).round() as u64));
    }
}

/// Step back, play or pause, step, reset, fit. True when the run was asked to start over.
fn buttons(
    ui: &mut egui::Ui,
    (phys, play): (&Run, &Playback),
    view: &mut View,
    out: &mut Vec<PhysicsCommand>,
) -> bool {
    let step = phys.snapshot().step;
    let mut restarts = false;
    ui.horizontal(|ui| {
        if ui
            .add_enabled(step > 0, egui::Button::new("⏮"))
            .on_hover_text("one step back (Left arrow): the run replayed to the step before")
            .clicked()
        {
            out.push(PhysicsCommand::StepBack);
        }
        let label = if play.paused { "▶ Play" } else { "⏸ Pause" };
        if ui.button(label).clicked() {
            restarts |= play_restarts(phys, play);
            out.push(PhysicsCommand::TogglePlay);
        }
        if ui
            .button("⏭ Step")
            .on_hover_text("one physics step (dt)")
            .clicked()
        {
            out.push(PhysicsCommand::Step);
        }
        if ui
            .button("⟲ Reset")
            .on_hover_text("back to t = 0 as the level opened (R)")
            .clicked()
        {
            restarts = true;
            out.push(PhysicsCommand::Restart);
        }
        if ui
            .button("Fit")
            .on_hover_text("fit the view to the scene (Home)")
            .clicked()
        {
            view.fit = true;
            view.follow = None;
        }
    });
    restarts
}

/// "Camera follows" the selected body (a follow of another body ends).
fn follow(ui: &mut egui::Ui, phys: &Run, view: &mut View, selected: Option<usize>) {
    if view.follow.is_some_and(|i| Some(i) != selected) {
        view.follow = None;
    }
    // Always there (greyed without a selection), so selecting a body moves nothing below it.
    let name = selected
        .and_then(|i| phys.scene.level.bodies.get(i))
        .map_or("the selected body", |b| b.name.as_str());
    let mut follow = selected.is_some() && view.follow == selected;
    if ui
        .add_enabled(
            selected.is_some(),
            egui::Checkbox::new(&mut follow, format!("camera follows {name}")),
        )
        .on_hover_text(
            "keeps its mass center at the center of the view (Home fits the scene again)",
        )
        .changed()
    {
        view.follow = if follow { selected } else { None };
    }
}

/// The blows of the run: each one's impulse and the joints' impulsive reactions.
fn blows(ui: &mut egui::Ui, phys: &Run) {
    for b in &phys.blows {
        ui.label(rich(
            format!(
                "{} (step ending t = {:.3} s): P = {} N s ({}, {}) on {}",
                b.name,
                b.time,
                fmt(b.impulse.length()),
                fmt(b.impulse.x),
                fmt(b.impulse.y),
                phys.snapshot()
                    .bodies
                    .get(b.body)
                    .map(|x| x.name.as_str())
                    .unwrap_or("?")
            ),
            palette::TOOL,
        ));
        for j in &b.joints {
            let imp = j.impulsive();
            let steady = match j.steady {
                Some(s) => format!(" + steady {} N s", fmt(s.length())),
                None => " (first step: steady part unknown)".into(),
            };
            ui.label(rich(
                format!(
                    "   joint {}: impulsive {} N s ({}, {}){steady}",
                    j.joint,
                    fmt(imp.length()),
                    fmt(imp.x),
                    fmt(imp.y)
                ),
                palette::REACTION,
            ));
        }
    }
}

/// The energy drift above which the run says so where the student looks (5 % of the largest
/// energy term): a 60 Hz pendulum lost 36 % in 33 s with only a line in the solver panel to
/// say so.
pub const DRIFT_WARNING: f64 = 0.05;

/// Where the level conserves energy (no contact, friction, damping, motor, load or event:
/// `study::accuracy::metrics::conserved`), the drift of T + V since t = 0 as a fraction of the
/// largest energy term at t = 0, with what to do about it, once it is above [`DRIFT_WARNING`].
pub fn energy_drift_note(phys: &Run) -> Option<String> {
    if !crate::study::accuracy::metrics::conserved(&phys.sim.level).energy {
        return None;
    }
    let (first, last) = (phys.series.first()?, phys.series.last()?);
    let scale = first
        .kinetic
        .abs()
        .max(first.gravity.abs())
        .max(first.elastic.abs());
    let drift = (last.total() - first.total()) / scale;
    (drift.is_finite() && drift.abs() > DRIFT_WARNING).then(|| drift_note(drift))
}

/// The warning's text for a drift of `drift` (a fraction, negative for a loss).
fn drift_note(drift: f64) -> String {
    format!(
        "Energy should stay the same here, but this run has {} {:.0}% of it since t = 0: \
         the engine's time step is too coarse, not the physics. {FINER_STEP} to halve dt \
         and watch the loss shrink.",
        if drift < 0.0 { "lost" } else { "gained" },
        drift.abs() * 100.0
    )
}

/// The height the run notes keep where the drift warning can come (the level conserves
/// energy): its button's row and the warning wrapped whole, at its longest ("gained 100%").
/// The box was two rows, and the warning was cut after its first line (the student trial of
/// 2026-12-07, on the first level). Elsewhere nothing: the box keeps its two rows.
fn drift_note_room(ui: &egui::Ui, phys: &Run) -> f32 {
    if !crate::study::accuracy::metrics::conserved(&phys.sim.level).energy {
        return 0.0;
    }
    // Wrapped narrower than the box (its scroll bar's room), so never taller than it shows.
    let width = ui.available_width() - 2.0 * ui.spacing().scroll.bar_width;
    let galley = egui::WidgetText::from(drift_note(1.0)).into_galley(
        ui,
        Some(egui::TextWrapMode::Wrap),
        width,
        egui::TextStyle::Body,
    );
    super::super::ui::row_height(ui) + galley.size().y + 2.0 * ui.spacing().item_spacing.y
}

/// The button beside the energy-drift warning. The warning said "halve dt in Solver", a panel
/// the student of the trial (2026-12-07) did not find: the button does it where the warning is.
pub const FINER_STEP: &str = "Run again with a finer step";

/// The settings [`FINER_STEP`] runs with: the run's own, dt halved (the Solver panel's ÷2).
pub fn finer_step(phys: &Run) -> crate::sim::Options {
    let mut options = phys.options.clone();
    options.dt = Some(phys.sim.dt() / 2.0);
    options.substeps = Some(phys.sim.substeps());
    options.solver_iterations = Some(phys.sim.settings().solver_iterations);
    options
}

/// Why the run waits (predict first), stopped, runs slowed, or is no longer the exercise's, or
/// its energy drifted.
fn warnings(ui: &mut egui::Ui, phys: &Run, play: &Playback, out: &mut Vec<PhysicsCommand>) {
    // First in the box, so that its button is in sight without scrolling.
    if let Some(note) = energy_drift_note(phys) {
        if ui
            .button(FINER_STEP)
            .on_hover_text("dt halved (as Solver's ÷2): the run starts again from t = 0")
            .clicked()
        {
            out.push(PhysicsCommand::Settings(finer_step(phys)));
        }
        ui.label(rich(note, palette::NORMAL));
    }
    if play.answer_first {
        ui.label(rich(
            "Predict first: the motion waits at t = 0 for your answers (left).",
            palette::VELOCITY,
        ));
    }
    if let Some(e) = &phys.error {
        ui.label(rich(e.clone(), palette::NORMAL));
    }
    if play.behind && !play.paused {
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
