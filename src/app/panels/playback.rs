//! The playback panel: time and progress, play/pause, single step, reset, fit the view, the
//! time scale, whether to stop at the level's end, and why a run is slowed or no longer the
//! exercise's.

use super::super::physics::Physics;
use super::super::playback::{restart, step_back, toggle_play};
use super::super::tools::ToolState;
use super::super::view::{palette, View};
use super::{fmt, rich, UiState};
use bevy_egui::egui;

/// Draws the panel.
pub(super) fn playback(
    ui: &mut egui::Ui,
    phys: &mut Physics,
    st: &mut UiState,
    view: &mut View,
    tools: &mut ToolState,
    selected: Option<usize>,
) {
    let (time, step) = (phys.snapshot().time, phys.snapshot().step);
    let duration = phys.sim.level.world.duration;
    ui.heading("Playback");
    ui.label(format!(
        "t = {:.3} s of {:.3} s   (step {})",
        time, duration, step
    ));
    // The timeline: drag to any time of the level; going back replays the run from t = 0
    // (deterministic, the user's pushes included), so every overlay, plot and check is the run's.
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
        phys.seek = Some((at / dt).round() as u64);
    }
    if let Some(target) = phys.seek {
        ui.label(
            rich(
                format!("going to t = {:.3} s…", target as f64 * dt),
                palette::OUTLINE,
            )
            .small(),
        );
    }
    ui.horizontal(|ui| {
        if ui
            .add_enabled(step > 0, egui::Button::new("⏮"))
            .on_hover_text("one step back (Left arrow): the run replayed to the step before")
            .clicked()
        {
            step_back(phys);
        }
        let label = if phys.paused { "▶ Play" } else { "⏸ Pause" };
        if ui.button(label).clicked() {
            toggle_play(phys, tools);
        }
        if ui
            .button("⏭ Step")
            .on_hover_text("one physics step (dt)")
            .clicked()
        {
            phys.paused = true;
            phys.steps_requested += 1;
        }
        if ui
            .button("⟲ Reset")
            .on_hover_text("back to t = 0 as the level opened (R)")
            .clicked()
        {
            restart(phys, tools);
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
    if view.follow.is_some_and(|i| Some(i) != selected) {
        view.follow = None;
    }
    if let Some(i) = selected {
        let name = phys
            .scene
            .level
            .bodies
            .get(i)
            .map_or("", |b| b.name.as_str());
        let mut follow = view.follow == Some(i);
        if ui
            .checkbox(&mut follow, format!("camera follows {name}"))
            .on_hover_text(
                "keeps its mass center at the center of the view (Home fits the scene again)",
            )
            .changed()
        {
            view.follow = follow.then_some(i);
        }
    }
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
