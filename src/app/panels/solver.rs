//! The solver panel: the engine (rapier, or Box2D where it is built), dt, substeps and
//! iterations (changing them restarts the run), the measured
//! step time, the energy change since t = 0, and the error against the textbook answers as the
//! accuracy study measures it ([`study_error`]).

use super::super::physics::{LiveChecks, PhysicsCommand};
use super::super::run::Run;
use super::super::ui::rich;
use super::super::view::palette;
use bevy_egui::egui;

/// Draws the panel; a changed setting overrides the level's and restarts the run (asked in `out`).
pub(super) fn solver(
    ui: &mut egui::Ui,
    phys: &Run,
    live: &LiveChecks,
    out: &mut Vec<PhysicsCommand>,
) {
    ui.heading("Solver");
    engine_row(ui, phys, out);
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
        let mut options = phys.options.clone();
        options.dt = Some(new_dt);
        options.substeps = Some(substeps);
        options.solver_iterations = Some(iterations);
        out.push(PhysicsCommand::Settings(options));
    }
    match phys.step_times.median_ms() {
        // A web page's clock ticks in 0.1 ms steps (browsers coarsen `performance.now()`): a
        // faster step reads 0, which is no measurement.
        Some(0.0) => {
            ui.label("step time: under the clock's resolution (0.1 ms in a web page)");
        }
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
        out.push(PhysicsCommand::Settings(Default::default()));
    }
}

/// Whether Box2D is in this build (native, with the `box2d` feature): the page has rapier only.
const BOX2D_BUILT: bool = cfg!(all(feature = "box2d", not(target_arch = "wasm32")));

/// The engine the window runs, the one the level declares, and a choice between them where
/// Box2D is built (choosing restarts the run, as a changed step does). A level Box2D refuses
/// runs on rapier, and the panel says so with the refusal: never a silent swap.
fn engine_row(ui: &mut egui::Ui, phys: &Run, out: &mut Vec<PhysicsCommand>) {
    use crate::level::PhysicsEngine;
    let running = phys.sim.engine();
    let declared = phys.sim.level.world.engine;
    // Box2D asked for and refused: the choice stays on Box2D, the line below says what runs.
    let chosen = match phys.sim.refused {
        Some(_) => PhysicsEngine::Box2d,
        None => running,
    };
    ui.horizontal(|ui| {
        ui.label("engine");
        for (e, name) in [
            (PhysicsEngine::Rapier, "rapier"),
            (PhysicsEngine::Box2d, "Box2D"),
        ] {
            if e == PhysicsEngine::Box2d && !BOX2D_BUILT {
                continue;
            }
            if ui.selectable_label(chosen == e, name).clicked() && chosen != e {
                let mut options = phys.options.clone();
                options.engine = Some(e);
                out.push(PhysicsCommand::Settings(options));
            }
        }
        if declared != chosen {
            ui.label(format!("(the level declares {})", declared.name()));
        }
    });
    if let Some(why) = &phys.sim.refused {
        // Wrapped under the row (a long refusal in the row would widen the panel).
        ui.label(rich(
            format!("Box2D does not run this level: {why}. The window runs rapier."),
            palette::FRICTION,
        ));
    }
}

/// The accuracy study's error of the run so far (`study::accuracy::measure::RunGrade`, the one
/// definition): the worst error against the answers and closed forms, and the worst
/// error-to-tolerance ratio.
pub fn study_error(
    checks: &[crate::checks::CheckResult],
    answers: &[crate::questions::QuestionResult],
) -> (Option<f64>, Option<f64>) {
    let grade = crate::study::accuracy::measure::RunGrade::of(checks, answers);
    (grade.error(), grade.tolerance_ratio)
}
