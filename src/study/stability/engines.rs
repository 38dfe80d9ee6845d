//! The stability suite on an engine other than rapier (Box2D v3), through the runner's entry
//! (`runner::engine_for`, `sim::Drive`), judged by the same criteria (`criteria::Monitor`).
//!
//! What differs, and why: `Drive` offers no engine poses to test for overlap, so penetration is
//! read from the step's contacts in the snapshot (the deepest point's negative distance, as
//! Box2D's manifolds give it at the step's collide phase), where rapier's runs measure it on the
//! engine's poses (`Simulation::deepest_overlap`). Box2D runs in f32 and has no joint softness
//! setting here: `--f64` and `--joint-hz` are rapier's only and refused with another engine.

use super::cases::Spec;
use super::criteria::Monitor;
use super::{Args, Plan, RunResult, Settings};
use crate::level::{PhysicsEngine, Scene};
use crate::runner::{engine_for, RunError};
use crate::sim::Options;
use crate::snapshot::Snapshot;
use indicatif::ProgressBar;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The engines of `--engine`, each once, in the order given (rapier if none).
pub fn engine_list(given: &[PhysicsEngine]) -> Vec<PhysicsEngine> {
    let mut v: Vec<PhysicsEngine> = Vec::new();
    for e in given {
        if !v.contains(e) {
            v.push(*e);
        }
    }
    if v.is_empty() {
        v.push(PhysicsEngine::Rapier);
    }
    v
}

/// Every case on every engine of `--engine`, in the order given: (spec, level file, plan).
pub fn case_runs<'a>(
    engines: &[PhysicsEngine],
    chosen: &[&'a Spec],
    paths: &'a [PathBuf],
    plan: &Plan,
) -> Vec<(&'a Spec, &'a PathBuf, Plan)> {
    engine_list(engines)
        .into_iter()
        .flat_map(|engine| {
            chosen.iter().zip(paths).map(move |(s, p)| {
                (
                    *s,
                    p,
                    Plan {
                        engine,
                        ..plan.clone()
                    },
                )
            })
        })
        .collect()
}

/// Err when a rapier-only setting is asked of another engine.
pub fn check_overrides(args: &Args) -> Result<(), String> {
    let other = args.engine.iter().find(|e| !e.is_rapier());
    if let Some(e) = other {
        for (flag, on) in [
            ("--f64", args.double),
            ("--joint-hz", args.joint_hz.is_some()),
        ] {
            if on {
                return Err(format!(
                    "error: {flag} is a rapier setting; the {} engine runs in f32 without joint softness\n  help: leave {flag} out, or give --engine rapier",
                    e.name()
                ));
            }
        }
    }
    Ok(())
}

/// The deepest overlap among the snapshot's contact points, m (0 without contacts).
pub fn contact_overlap(s: &Snapshot) -> f64 {
    s.contacts
        .iter()
        .flat_map(|c| c.points.iter())
        .map(|p| -p.distance)
        .fold(0.0, f64::max)
}

/// Runs the scene (its world already set to the run's settings) on `engine` to its end,
/// feeding the monitor; Ok(the error that stopped it, if any), or Err(why the engine refuses it).
pub fn drive(
    scene: &Scene,
    engine: PhysicsEngine,
    monitor: &mut Monitor,
    progress: Option<&ProgressBar>,
) -> Result<Option<String>, String> {
    let opts = Options {
        engine: Some(engine),
        ..Options::default()
    };
    let mut sim = match engine_for(scene, &opts) {
        Ok(sim) => sim,
        Err(RunError::Level(e)) => {
            return Err(format!(
                "{}:{}:{}: {}",
                e.file.display(),
                e.line,
                e.col,
                e.message
            ))
        }
        Err(e) => return Err(e.to_string()),
    };
    let total = (scene.level.world.duration / scene.level.world.dt)
        .round()
        .max(1.0) as u64;
    let mut done = 0u64;
    let ran = sim.run_each(&mut |s: &Snapshot| {
        monitor.observe(s);
        monitor.observe_overlap(s.time, contact_overlap(s));
        if s.step > 0 {
            done += 1;
            if done.is_multiple_of(256) {
                if let Some(p) = progress {
                    p.inc(256);
                }
            }
        }
    });
    if let Some(p) = progress {
        p.inc(done % 256 + total.saturating_sub(done));
    }
    Ok(ran.err().map(|e| e.to_string()))
}

/// The result of a case the engine refused: not run, nothing measured.
pub fn refused_run(settings: &Settings, why: String) -> RunResult {
    RunResult {
        settings: settings.clone(),
        steps: 0,
        passed: false,
        wall_ms: 0.0,
        figures: BTreeMap::new(),
        criteria: Vec::new(),
        error: None,
        refused: Some(why),
    }
}
