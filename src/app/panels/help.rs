//! The help window (F1 or ?): every key, overlay, tool and what the colors mean.

use super::super::ui::rich;
use super::super::view::palette;
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
                ui.label(KEYBOARD_RULE);
                egui::Grid::new("help-keys").striped(true).show(ui, |ui| {
                    for (k, what) in keys(cfg!(target_arch = "wasm32")) {
                        ui.monospace(k);
                        ui.label(what);
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
                for (title, text) in sections(cfg!(target_arch = "wasm32")) {
                    ui.add_space(6.0);
                    ui.strong(title);
                    ui.label(text);
                }
            });
        });
}

/// The keys, the page's F12 without the folder.
pub fn keys(web: bool) -> Vec<(&'static str, &'static str)> {
    KEYS.iter()
        .map(|&(k, what)| match (k, web) {
            ("F12", true) => (k, "screenshot, downloaded as LEVEL-TIMEs.png"),
            _ => (k, what),
        })
        .collect()
}

/// The help's sections after the keys and overlays: every tool and panel. `web`: the page's
/// variant, which names no folder and no command line (a page has neither).
pub fn sections(web: bool) -> Vec<(&'static str, String)> {
    let save = if web {
        "Save downloads the level file; open it again with the page's file picker."
    } else {
        "Save writes a level that `rigidlab check` runs, into saved-levels/, which the level browser lists; a file already there is never replaced."
    };
    let csv = if web {
        "CSV downloads the plotted series as a file."
    } else {
        "CSV writes the plotted series into exports/ under a name of its own."
    };
    let mut out = vec![
        ("Mouse", "Wheel zooms about the cursor; right or middle drag pans. Tool 1 selects a body and a point \
          on it (v_P, lines to the instantaneous center) and drags it on a spring; tool 2 strikes: \
          click-drag on a body, the arrow is the impulse; tool 3 sets O, the point angular momentum \
          H_O is taken about.".to_string()),
        ("Measure panel", "The stopwatch starts and stops on the simulated clock (it reads sim time, not your \
          watch); the period timer reads the selected body's period from its omega's zero crossings; the clicked \
          point's position, v_P and a_P are read as the run goes. The ruler is a drag; the protractor is a \
          drag from the vertex along one arm, then a click at the other arm's end. Their marks are cleared \
          when another level opens.".to_string()),
        ("Plots", format!("The energies (kinetic, gravity, elastic, total) and H about O against time, and a \
          quantity of the selected body (position, speed, angle, omega, ...) against time or against \
          another of its quantities. {csv}")),
        ("Solver panel", "dt, substeps and iterations of the window's run (not of the level file), the time a \
          step takes, and the error as the accuracy study measures it: a finer step costs time and buys \
          accuracy. Theory against engine, below it, shows each check and question with its error; a \
          failed question shows the reading that failed (engine or analysis).".to_string()),
        ("Building a scene (the Build panel)", format!("New scene starts from a ground line. Place puts a box, \
          disc, bar (1 kg each), ground, wall, incline or arc (a half-circle bowl) where you click (a disc clicked into a fixed body \
          is set onto its surface; another shape overlapping one is placed with a warning); polygon takes a \
          body's corners click by click (the first corner again or Enter closes it); track takes a fixed \
          polyline track's points click by click (the last point again or Enter ends it), and curved \
          track adds an arc (center, radius, from and to angles, inside or outside) or a polyline from \
          typed x, y pairs, both editable in the inspector; join makes a pin, \
          slider or weld where two bodies overlap (on one body alone, to a fixed point there); spring is a \
          drag from a body to another body or the ground; torsion puts a coil on the clicked body, to the \
          body under it or the ground. Select a body to edit its mass, size, position, angle, velocity, \
          friction and restitution; paused at t = 0, drag it to move it. A body on a pin or slider has a \
          motor switch and its target rate. Each edit is checked like a level file (a refused one says why \
          and changes nothing), declares the effects it needs, and restarts the run. {save}")),
        ("Questions (the Build panel's exercise part)", "Add, edit or remove a question: its id, wording, \
          quantity (as in a level file, or picked for a body), when it is read, the expected answer or \
          'compute it' (the analysis layer's value from a run, where the quantity has a formula), the \
          tolerance and the unit. Preview runs the scene for the question and shows the engine's and the \
          analysis's values before you save. The level's own step (dt, substeps) is what the questions are \
          read at.".to_string()),
    ];
    if !web {
        out.push((
            "Headless",
            "Every level also runs without the window: `rigidlab check LEVEL --answer ID=VALUE` \
          grades the same answers, and `rigidlab check levels` runs the whole library."
                .to_string(),
        ));
    }
    out
}

/// Whose the keyboard is (the help says it above the keys; `ui::Typing` is the rule).
pub const KEYBOARD_RULE: &str = "These keys are shortcuts only while the keyboard is the \
     scene's, after a click in the scene. A click on a panel, into a box or on a window over the \
     scene gives the keys to the panels: what you type goes to the box, never to a shortcut \
     (an answer never plays or resets the run). Click the scene or press Esc to use the \
     shortcuts again; the status line says so meanwhile.";

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
        ("N", "names of bodies and joints", palette::TEXT),
    ]
}
