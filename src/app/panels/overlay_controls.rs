//! The overlays panel: which diagrams are drawn on the scene (velocity, acceleration,
//! instantaneous center, free-body and kinetic diagrams, H about O, trails, magnitudes), their
//! color key, and which body they are drawn for.

use super::super::overlays::Overlays;
use super::super::physics::Physics;
use super::super::quantities::ForceKind;
use super::super::view::palette;
use super::rich;
use crate::level::{Effect, Level};
use bevy::prelude::*;
use bevy_egui::egui;

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

/// Draws the panel.
pub(super) fn overlay_controls(ui: &mut egui::Ui, ov: &mut Overlays, phys: &Physics) {
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
    if ov.free_body {
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
    }
    ui.horizontal(|ui| {
        ui.label("arrow scale");
        ui.add(
            egui::Slider::new(&mut ov.arrow_scale, 0.25..=4.0)
                .logarithmic(true)
                .max_decimals(2),
        );
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
