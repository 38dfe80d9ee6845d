//! The help window (F1 or ?): every key, overlay, tool and what the colors mean.

use super::super::view::palette;
use super::rich;
use bevy_egui::egui;

/// Draws the help window while `open`; its close button clears `open`.
pub(super) fn help(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Help (F1 or ?)")
        .open(open)
        .collapsible(false)
        .resizable(true)
        .default_width(520.0)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
        .show(ctx, |ui| {
            egui::ScrollArea::vertical().max_height(560.0).show(ui, |ui| {
                ui.label(
                    "A level is an exercise: a scene, a question, its textbook answer and a tolerance. \
                     Read the statement on the left, play the scene, type your answer into a question's box \
                     and press Enter: it is graded with the level's own rule, and rigidlab's measured value \
                     shows once your answer is right.",
                );
                ui.add_space(6.0);
                ui.strong("Keys");
                egui::Grid::new("help-keys").striped(true).show(ui, |ui| {
                    for (k, what) in KEYS {
                        ui.monospace(*k);
                        ui.label(*what);
                        ui.end_row();
                    }
                });
                ui.add_space(6.0);
                ui.strong("Overlays (keys toggle them; click a body to draw its diagrams)");
                egui::Grid::new("help-overlays").striped(true).show(ui, |ui| {
                    for (k, what, color) in overlays() {
                        ui.monospace(k);
                        ui.label(rich(what, color));
                        ui.end_row();
                    }
                });
                ui.add_space(6.0);
                ui.strong("Mouse");
                ui.label(
                    "Wheel zooms about the cursor; right or middle drag pans. Tool 1 selects a body and a point \
                     on it (v_P, lines to the instantaneous center) and drags it on a spring; tool 2 strikes: \
                     click-drag on a body, the arrow is the impulse; tool 3 sets O, the point angular momentum \
                     H_O is taken about. The Measure panel reads the clicked point's position, v_P and a_P; \
                     its protractor is a drag from the vertex along one arm, then a click at the other arm's \
                     end; its ruler is a drag.",
                );
                ui.add_space(6.0);
                ui.strong("Building a scene (the Build panel)");
                ui.label(
                    "New scene starts from a ground line. Place puts a box, disc, bar (1 kg each), ground, wall \
                     or incline where you click; polygon takes a body's corners click by click (the first corner \
                     again or Enter closes it); join makes a pin, slider or weld where two bodies overlap (on one \
                     body alone, to a fixed point there); spring is a drag from a body to another body or the \
                     ground; torsion puts a coil on the clicked body, to the body under it or the ground. Select a \
                     body to edit its mass, size, position, angle, velocity, friction and restitution; paused at \
                     t = 0, drag it to move it. Each edit is checked like a level file (a refused one says why and \
                     changes nothing), declares the effects it needs, and restarts the run. Save writes a level \
                     that `rigidlab check` runs, into saved-levels/, which the level browser lists.",
                );
                ui.add_space(6.0);
                ui.strong("Headless");
                ui.label(
                    "Every level also runs without the window: `rigidlab check LEVEL --answer ID=VALUE` grades \
                     the same answers, and `rigidlab check levels` runs the whole library.",
                );
            });
        });
}

const KEYS: &[(&str, &str)] = &[
    ("Space", "play / pause (at the level's end: start over)"),
    ("S or Right", "one physics step"),
    (
        "Left",
        "one step back (the run is replayed to the step before; the timeline goes to any time)",
    ),
    ("R", "reset to t = 0 as the level opened"),
    ("− / =", "time scale ÷ 2 / × 2"),
    ("Home", "fit the view to the scene"),
    ("1 2 3", "tools: select and drag · impulse · set O"),
    ("Esc", "clear the selection"),
    (
        "Delete",
        "delete the selected body (with its joints and the questions about it)",
    ),
    ("Ctrl+Z", "undo an edit"),
    ("Ctrl+Y, Ctrl+Shift+Z", "redo"),
    (
        "F12",
        "screenshot into screenshots/LEVEL-TIMEs.png, never over an earlier one (downloaded in a web page)",
    ),
    ("F1 or ?", "this help"),
];

fn overlays() -> Vec<(&'static str, &'static str, bevy::color::Color)> {
    vec![
        (
            "V",
            "velocity of G and of the chosen point",
            palette::VELOCITY,
        ),
        ("A", "acceleration of G", palette::ACCEL),
        (
            "C",
            "instantaneous center of zero velocity",
            palette::CENTER,
        ),
        ("F", "free-body diagram: weight", palette::GRAVITY),
        ("", "contact normal force N", palette::NORMAL),
        ("", "friction F", palette::FRICTION),
        ("", "joint reaction R", palette::REACTION),
        ("", "applied loads", palette::LOAD),
        (
            "K",
            "kinetic diagram: m a_G and I_G alpha beside the body",
            palette::ACCEL,
        ),
        ("H", "angular momentum about O", palette::MOMENTUM),
        ("T", "trails of G", palette::TRAIL),
        ("L", "labels with magnitudes", palette::TEXT),
    ]
}
