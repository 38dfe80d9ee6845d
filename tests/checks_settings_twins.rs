//! Checks and questions hold for settings nobody tuned them for (issue 13).
//!
//! Every library level (the exercises and the stress scenes) is run at its own settings and at
//! four twins that only ask for more accuracy: 2x and 4x its substeps, dt/2 and dt/4. A check
//! or question that passes at the level's settings must pass at every twin, with one exception
//! the test states: a question whose engine value really moved away from the textbook answer
//! (its error against `expected` grew) may fail, and is printed with its numbers. A check has no
//! such excuse: its theory is recomputed from the twin's own state and settings, so a check
//! that fails only because the settings changed reads them wrong (as checks did when they read
//! the level's `world.substeps` while the engine ran an override).
//!
//! Also: the settings a run reports are the resolved ones (`--substeps 8` is what the checks,
//! the snapshot and the report see).

mod common;

use common::run;
use rayon::prelude::*;
use rigidlab::level::Scene;
use rigidlab::runner;
use rigidlab::sim::{Options, Simulation, Substepping};
use std::collections::HashMap;

/// Every level of the library, the stress scenes too.
fn library() -> Vec<Scene> {
    common::ron_files("levels", &[])
        .iter()
        .map(common::load)
        .collect()
}

/// The twins of a level: (name, overrides).
fn twins(scene: &Scene) -> Vec<(String, Options)> {
    let w = &scene.level.world;
    let mut v = Vec::new();
    for k in [2, 4] {
        v.push((
            format!("substeps x{k} ({})", w.substeps * k),
            Options {
                substeps: Some(w.substeps * k),
                ..Options::default()
            },
        ));
        v.push((
            format!("dt/{k}"),
            Options {
                dt: Some(w.dt / k as f64),
                ..Options::default()
            },
        ));
    }
    v
}

/// Pass-to-fail cases found by this test and not fixed yet, each with its numbers (open issues,
/// named in docs/known-gaps.md); the test fails on any other.
/// Open cases, each with its numbers (none now). The sliding block's G balance over a window
/// read 1.36e-4 against 1e-4 at 16 substeps and at dt/4: f32 rounding of v at every substep,
/// where the decrement mu g h is a few ulps of v and is rounded the same way step after step
/// (in f64 3e-15). `impulse_momentum` now discounts, window by window, what the engine's
/// precision may round away (2.8e-8 beyond it at 16 substeps).
const LISTED: &[(&str, &str)] = &[];

#[test]
fn more_accuracy_never_turns_a_pass_into_a_failure() {
    let scenes = library();
    // (level, twin, item, what happened)
    let outcomes: Vec<(String, String, String, String, bool)> = scenes
        .par_iter()
        .flat_map(|scene| {
            let base = run(scene, &Options::default());
            let mut out = Vec::new();
            for (name, opts) in twins(scene) {
                let twin = run(scene, &opts);
                let file = scene.file.display().to_string();
                for (b, t) in base.checks.iter().zip(&twin.checks) {
                    if b.passed && !t.passed {
                        out.push((
                            file.clone(),
                            name.clone(),
                            format!("check {} {}", b.kind, b.subject),
                            format!(
                                "max rel error {:.3e} -> {:.3e} (tolerance {:.1e}); {}",
                                b.max_rel_error, t.max_rel_error, b.tolerance, t.note
                            ),
                            false,
                        ));
                    }
                }
                for (b, t) in base.questions.iter().zip(&twin.questions) {
                    if b.passed && !t.passed {
                        // Excused only when the engine itself moved away from the answer.
                        let grew = t.rel_error > b.rel_error;
                        out.push((
                            file.clone(),
                            name.clone(),
                            format!("question {}", b.id),
                            format!(
                                "engine error {:.3e} -> {:.3e}, analysis {:?} -> {:?} (tolerance {:.1e}) {}",
                                b.rel_error,
                                t.rel_error,
                                b.analysis_rel_error,
                                t.analysis_rel_error,
                                b.tolerance,
                                t.note
                            ),
                            grew,
                        ));
                    }
                }
            }
            out
        })
        .collect();
    let mut unexplained = 0;
    for (file, twin, item, what, excused) in &outcomes {
        let listed = LISTED
            .iter()
            .any(|(f, i)| file.ends_with(f) && item.starts_with(i));
        println!(
            "{} {file} [{twin}] {item}: {what}",
            if *excused {
                "excused (engine error grew):"
            } else if listed {
                "listed (open, see LISTED):"
            } else {
                "REGRESSION:"
            }
        );
        unexplained += usize::from(!excused && !listed);
    }
    println!(
        "{} levels x 4 twins: {} pass->fail, {} with a grown engine error, {} listed as open",
        scenes.len(),
        outcomes.len(),
        outcomes.iter().filter(|o| o.4).count(),
        outcomes.len() - unexplained - outcomes.iter().filter(|o| o.4).count()
    );
    assert_eq!(
        unexplained, 0,
        "checks or questions that fail only because the settings changed (see above)"
    );
}

#[test]
fn the_checks_see_the_resolved_settings() {
    let scene = common::load("levels/kinetics/physical_pendulum.ron");
    assert_ne!(
        scene.level.world.substeps, 8,
        "the test needs an override that differs"
    );
    let opts = Options {
        substeps: Some(8),
        dt: Some(scene.level.world.dt / 2.0),
        ..Options::default()
    };
    let mut seen = Vec::new();
    let report = runner::run_scene(&scene, &opts, &HashMap::new(), |s| {
        seen.push((s.substeps, s.dt))
    })
    .unwrap();
    let settings = report
        .settings
        .as_ref()
        .expect("a run reports its settings");
    assert_eq!(settings.substeps, 8);
    assert_eq!(settings.dt, scene.level.world.dt / 2.0);
    // A pendulum's pin is a joint: its impulses are summed over the substeps.
    assert_eq!(settings.substepping, Substepping::Split);
    // Every snapshot, the initial one too, carries the substeps the engine ran.
    assert!(seen.iter().all(|&(n, _)| n == 8));
    assert!(seen[1..].iter().all(|&(_, dt)| dt == settings.dt));
    // The kinetic-energy check states the substeps it modelled: the override's.
    let ke = report
        .checks
        .iter()
        .find(|c| c.kind == "kinetic_energy_g")
        .expect("the level has a kinetic_energy_g check");
    assert!(ke.note.contains("S = 8 substeps"), "{}", ke.note);
    assert!(report.passed, "{report:#?}");
    // The simulation exposes the same record.
    let sim = Simulation::new(&scene, &opts);
    assert_eq!(sim.settings(), settings);
}
