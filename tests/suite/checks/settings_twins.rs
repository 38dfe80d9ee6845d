//! Checks and questions hold for settings nobody tuned them for (issue 13).
//!
//! Every library level (the exercises and the stress scenes) is run at its own settings and at
//! four twins that only ask for more accuracy: 2x and 4x its substeps, dt/2 and dt/4. A check
//! or question that passes at the level's settings must pass at every twin, unless it is named
//! in `LISTED` with the largest error measured over the twins and why (an engine limitation,
//! also published in docs/known-gaps.md). An unlisted pass-to-fail fails the test, so does a
//! listed one that grew past its measured size, and so does a listed one that no longer fails
//! (the list cannot go stale). A check's theory is recomputed from the twin's own state and
//! settings, so a check that fails only because the settings changed reads them wrong (as checks
//! did when they read the level's `world.substeps` while the engine ran an override).
//!
//! Every library check passes at its level's own settings (`every_library_check_passes_...`),
//! but those in `LISTED_AT_OWN_SETTINGS` (none now): `cargo test` states it, not only CI's
//! `rigidlab check levels`.
//!
//! Also: the settings a run reports are the resolved ones (`--substeps 8` is what the checks,
//! the snapshot and the report see).

use crate::common;

use common::run;
use rayon::prelude::*;
use rigidlab::level::Scene;
use rigidlab::runner;
use rigidlab::sim::{Options, Simulation, Substepping};
use std::collections::HashMap;

/// Every level of the library, the stress scenes too, but the 10,000-grain sand pile and the
/// 10,000-domino field: one run of the pile is 50 to 80 s of CPU here, of the field 18 s, so
/// their twins would add minutes to every suite run. CI's `check levels` runs them at their own
/// settings, and tests/suite/study/sand_pile.rs and domino_field.rs hold their stability
/// criteria (the whole field's ignored by default for its cost, two of its rows not).
fn library() -> Vec<Scene> {
    common::ron_files("levels", &[])
        .iter()
        .filter(|f| !f.ends_with("stress/sand_pile.ron") && !f.ends_with("stress/domino_field.ron"))
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

/// Pass-to-fail cases found by this test and not fixed yet: (level file, item as printed, the
/// largest error measured over the four twins on 2026-11-27 times the margin stated in `why`,
/// why). Each is an engine limitation named in docs/known-gaps.md. Matched exactly, by item.
///
/// History: the sliding block's G balance over a window read 1.36e-4 against 1e-4 at 16
/// substeps and at dt/4: f32 rounding of v at every substep, where the decrement mu g h is a few
/// ulps of v and is rounded the same way step after step (in f64 3e-15). `impulse_momentum` now
/// discounts, window by window, what the engine's precision may round away (2.8e-8 beyond it at
/// 16 substeps).
const LISTED: &[(&str, &str, f64, &str)] = &[
    // Its size is a bound, not a measurement: B's v (-6 m/s at 5 s) is rounded to f32 at every
    // substep, by at most ulp(6)/2 = 2^-22, the same way each time (a constant increment), so an
    // acceleration read over a step of n substeps is off by at most n 2^-22 / (n h) =
    // 2^-22 / h = 2.38e-7 x 960 = 2.29e-4 m/s^2 at h = 1/960 s (both failing twins), 1.91e-4 of
    // 1.2. Measured 1.678e-4 at 16 substeps and at dt/4; --precision f64 1.5e-13.
    (
        "levels/kinematics/ha_relative_motion_cars_fragment.ron",
        "question a_B",
        1.91e-4,
        "f32 rounding of v read as an acceleration (known-gaps: f32 velocity in a step's acceleration)",
    ),
    // (The ring's and the bowl's N_bottom, 1.8e-2 and 1.9e-2 at dt/4 on the facets, were
    // listed here until 2026-12-06: a disc on an `Arc` now touches its circle, and both pass at
    // every twin.)
    // f32 noise in a reaction read from two soft joints in a loop (known-gaps row): F read
    // 5.8e-4 off at the level's settings, 2.3e-3 at 8 substeps, 7.821e-3 at 16 (fails), 3.2e-3
    // at 32, 3.0e-3 at dt/2, 1.2e-3 at 0.1 ms; with --precision f64 1.5e-5 at 16 substeps.
    // 10% margin as above (8.6e-3).
    (
        "levels/kinetics/ha_collar_circular_guide_cylindrical.ron",
        "question F",
        8.6e-3,
        "f32 rounding of a joint reaction in a loop of two soft joints",
    ),
    // f32 rounding through a coupling's held tension (sim/coupling_tension.rs, 2026-12-07: each
    // call starts from the last call's tension, and the projection after it takes the
    // remainder): B's acceleration at dt/4 read 1.444e-3 off (1.016e-4 before the held
    // tension), the analysis from the same state 1.400e-3; at the level's settings 1.02e-4, at
    // dt/2 1.93e-4, at 16 substeps 8.65e-4; with --precision f64 2.9e-12 at dt/4. Larger than
    // the velocity rounding bound of the row above (1.0e-4 here), not traced. 10% margin.
    (
        "levels/kinetics/ha_three_block_dependent_motion.ron",
        "question a_B",
        1.6e-3,
        "f32 rounding through a coupling's held tension (known-gaps: f32 velocity in a step's acceleration)",
    ),
];

/// Checks that fail at their level's own settings: (level file, item as printed, why). None.
const LISTED_AT_OWN_SETTINGS: &[(&str, &str, &str)] = &[];

/// `item` of `file` in `list` (exact item, file by its ending).
fn listed<'a, T>(
    list: &'a [T],
    key: impl Fn(&T) -> (&str, &str),
    file: &str,
    item: &str,
) -> Option<&'a T> {
    list.iter().find(|e| {
        let (f, i) = key(e);
        file.ends_with(f) && item == i
    })
}

#[test]
fn more_accuracy_never_turns_a_pass_into_a_failure() {
    let scenes = library();
    // (level, twin, item, what happened, error at the twin)
    let outcomes: Vec<(String, String, String, String, f64)> = scenes
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
                            t.max_rel_error,
                        ));
                    }
                }
                for (b, t) in base.questions.iter().zip(&twin.questions) {
                    if b.passed && !t.passed {
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
                            t.rel_error,
                        ));
                    }
                }
            }
            out
        })
        .collect();
    let mut bad = Vec::new();
    for (file, twin, item, what, err) in &outcomes {
        let entry = listed(LISTED, |e| (e.0, e.1), file, item);
        let verdict = match entry {
            // A NaN error is not within any size.
            Some(&(_, _, size, _)) if *err <= size => "listed (see LISTED):",
            Some(_) => "GREW PAST ITS LISTED SIZE:",
            None => "REGRESSION:",
        };
        println!("{verdict} {file} [{twin}] {item}: {what}");
        if !verdict.starts_with("listed") {
            bad.push(format!("{file} [{twin}] {item}"));
        }
    }
    for (f, i, size, _) in LISTED {
        if !outcomes.iter().any(|o| o.0.ends_with(f) && o.2 == *i) {
            println!("STALE: {f} {i} (listed at {size:.1e}) passes at every twin now");
            bad.push(format!("stale LISTED entry {f} {i}"));
        }
    }
    println!(
        "{} levels x 4 twins: {} pass->fail, {} listed",
        scenes.len(),
        outcomes.len(),
        LISTED.len()
    );
    assert!(
        bad.is_empty(),
        "pass-to-fail cases not listed, grown past their listed size, or stale: {bad:#?}"
    );
}

#[test]
fn every_library_check_passes_at_its_levels_own_settings() {
    let scenes = library();
    let failing: Vec<(String, String, String)> = scenes
        .par_iter()
        .flat_map(|scene| {
            let file = scene.file.display().to_string();
            let report = run(scene, &Options::default());
            report
                .checks
                .iter()
                .filter(|c| !c.passed)
                .map(|c| {
                    (
                        file.clone(),
                        format!("check {} {}", c.kind, c.subject),
                        format!(
                            "max rel error {:.3e} (tolerance {:.1e}, {} samples); {}",
                            c.max_rel_error, c.tolerance, c.samples, c.note
                        ),
                    )
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut bad = Vec::new();
    for (file, item, what) in &failing {
        let ok = listed(LISTED_AT_OWN_SETTINGS, |e| (e.0, e.1), file, item).is_some();
        println!(
            "{} {file} {item}: {what}",
            if ok { "listed:" } else { "FAILS:" }
        );
        if !ok {
            bad.push(format!("{file} {item}"));
        }
    }
    for (f, i, _) in LISTED_AT_OWN_SETTINGS {
        if !failing.iter().any(|o| o.0.ends_with(f) && o.1 == *i) {
            bad.push(format!("stale LISTED_AT_OWN_SETTINGS entry {f} {i}"));
        }
    }
    assert!(
        bad.is_empty(),
        "library checks failing at their level's own settings: {bad:#?}"
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
    // A pendulum's pin is a joint whose impulses a check reads: summed over the substeps, split
    // where a blow can fall (its first step), reconstructed from one call elsewhere
    // (sim/joint_sums.rs).
    assert!(settings.split_at_blows, "{settings:?}");
    assert_eq!(settings.substepping, Substepping::Mixed);
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
    // The simulation exposes the same record, which the report completes with how the run's
    // steps were called: one call a step as planned, some split (the first ones at least: a
    // blow could fall, or the impulses were not yet seen smooth; sim/joint_sums.rs).
    let sim = Simulation::new(&scene, &opts);
    assert!(
        settings.split_steps > 0 && settings.split_steps < report.steps,
        "{settings:?}"
    );
    assert_eq!(
        sim.settings(),
        &rigidlab::sim::Settings {
            split_steps: 0,
            substepping: Substepping::Internal,
            substepping_why: sim.settings().substepping_why.clone(),
            ..settings.clone()
        }
    );
}
