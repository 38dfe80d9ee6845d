//! The overlays panel: which diagrams are drawn on the scene (velocity, acceleration,
//! instantaneous center, free-body and kinetic diagrams, H about O, trails, magnitudes), their
//! color key, and which body they are drawn for.

use super::super::overlays::{crowd, legend_entries, Overlays};
use super::super::quantities::ForceKind;
use super::super::run::Run;
use super::super::ui::{fixed_rows, rich};
use super::super::view::palette;
use bevy::prelude::*;
use bevy_egui::egui;

/// Draws the panel.
pub(super) fn overlay_controls(ui: &mut egui::Ui, ov: &mut Overlays, phys: &Run) {
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
        ui.checkbox(&mut ov.names, "names (N)");
        ui.end_row();
    });
    // Always there, greyed while the free-body diagram is off: a row that came with F (the key
    // too) moved the tools below it.
    ui.add_enabled_ui(ov.free_body, |ui| {
        ui.horizontal_wrapped(|ui| {
            ui.label("forces");
            for (kind, color) in [
                (ForceKind::Gravity, palette::GRAVITY),
                (ForceKind::ContactNormal, palette::NORMAL),
                (ForceKind::Friction, palette::FRICTION),
                (ForceKind::Joint, palette::REACTION),
                (ForceKind::Spring, palette::SPRING),
                (ForceKind::Load, palette::LOAD),
                (ForceKind::Coupling, palette::COUPLING),
            ] {
                let mut shown = !ov.hidden_forces.contains(&kind);
                if ui
                    .checkbox(&mut shown, rich(kind.symbol(), color))
                    .changed()
                {
                    ov.hidden_forces.retain(|k| *k != kind);
                    if !shown {
                        ov.hidden_forces.push(kind);
                    }
                }
            }
            ui.checkbox(&mut ov.components, "x, y components");
        });
    });
    ui.horizontal(|ui| {
        ui.label("arrow scale");
        ui.add(
            egui::Slider::new(&mut ov.arrow_scale, 0.25..=4.0)
                .logarithmic(true)
                .max_decimals(2),
        );
    });
    fixed_rows(ui, 2.0, |ui| {
        ui.horizontal_wrapped(|ui| {
            for (text, color) in legend_entries(ov, &phys.sim.level, phys.steps_averaged()) {
                ui.label(rich(text, color).small());
            }
        });
    });
    // The same height either way (the hint wraps in a narrow panel; the button row is taller
    // than a line of small text).
    let crowd = crowd(phys.snapshot());
    fixed_rows(ui, 2.0, |ui| match ov.selected {
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
            let hint = match crowd {
                Some(n) => format!(
                    "a crowd of {n}: click a body for its trail, arrows and diagrams (one at a time)"
                ),
                None => "click a body for its diagrams (all bodies when there are 4 or fewer)".into(),
            };
            ui.label(rich(hint, palette::OUTLINE).small());
        }
    });
    if let Some(n) = crowd {
        // In a crowd the trails and arrows are the selected body's (overlays::crowd); the
        // whole field is one click away, at its price.
        ui.checkbox(
            &mut ov.every_body,
            format!("trails and arrows on all {n} bodies (slow)"),
        );
    }
}
