//! The "theory against engine" panel: every check and question of the level with its worst
//! error, tolerance and verdict, as `rigidlab check` reports them at the level's end.

use super::super::physics::LiveChecks;
use super::super::run::Run;
use super::super::ui::rich;
use super::super::view::palette;
use crate::questions::QuestionResult;
use bevy_egui::egui;

/// `text` cut to `n` characters with an ellipsis.
fn clip(text: &str, n: usize) -> String {
    if text.chars().count() <= n {
        return text.to_string();
    }
    let mut out: String = text.chars().take(n - 1).collect();
    out.push('…');
    out
}

/// The error a question's line shows, and whose reading it is: the engine's, unless the engine
/// is within tolerance and the analysis's value is not (a question fails on either, so a FAIL
/// beside an error within tolerance would read as a contradiction).
pub fn shown_error(q: &QuestionResult) -> (&'static str, f64) {
    match q.analysis_rel_error {
        Some(a) if q.rel_error <= q.tolerance && (a > q.tolerance || a.is_nan()) => ("analysis", a),
        _ => ("engine", q.rel_error),
    }
}

/// Draws the panel: the live results once the run reached the level's end, else what will be shown.
pub(super) fn checks(ui: &mut egui::Ui, phys: &Run, live: &LiveChecks) {
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
                        let (whose, err) = shown_error(q);
                        let r = ui.label(if whose == "engine" {
                            format!("{err:.2e}")
                        } else {
                            format!("{err:.2e} ({whose})")
                        });
                        r.on_hover_text(format!(
                            "engine {:.2e}{}",
                            q.rel_error,
                            q.analysis_rel_error
                                .map(|a| format!(", analysis {a:.2e}"))
                                .unwrap_or_default()
                        ));
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
