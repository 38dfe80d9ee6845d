//! A failing level on the other engine: the first question a user asks of a failure is "would
//! another engine get it right?". rigidlab runs the level once more, on Box2D when rapier ran
//! it and on rapier when Box2D did, at the same settings, and the advice says whether it
//! passes there, fails too (with what fails), or is refused (the feature, located in the file).
//! A pass there says the failure is the engine's, not the level's; a refusal says what the
//! other engine lacks. Costs one run of the level (a refusal none); the run is graded on the
//! engine's values only (no student's answers).

use super::advice::engine_failed;
use crate::level::{PhysicsEngine, Scene};
use crate::report::{LevelReport, OtherEngine, OtherVerdict};
use crate::runner::{self, RunError};
use crate::sim::Options;
use std::collections::HashMap;

/// The engine that is not `e`.
pub fn other(e: PhysicsEngine) -> PhysicsEngine {
    match e {
        PhysicsEngine::Rapier => PhysicsEngine::Box2d,
        PhysicsEngine::Box2d => PhysicsEngine::Rapier,
    }
}

/// Whether Box2D is in this build (native, with the `box2d` feature).
const BOX2D_BUILT: bool = cfg!(all(feature = "box2d", not(target_arch = "wasm32")));

/// The level `scene`, which failed at the options `opts`, run on the other engine at the same
/// options (its step, substeps and precision overrides kept, the engine swapped).
pub fn other_engine(scene: &Scene, opts: &Options) -> OtherEngine {
    let engine = other(runner::engine_of(scene, opts));
    let said = |verdict, why: String| OtherEngine {
        engine,
        verdict,
        why,
    };
    if engine == PhysicsEngine::Box2d && !BOX2D_BUILT {
        return said(
            OtherVerdict::NotBuilt,
            "build with the `box2d` feature (the default natively) to compare".into(),
        );
    }
    let options = Options {
        engine: Some(engine),
        ..opts.clone()
    };
    match runner::run_graded(scene, &options, &HashMap::new(), |_| {}) {
        Ok(r) if !engine_failed(&r) => said(OtherVerdict::Passes, String::new()),
        Ok(r) => said(OtherVerdict::Fails, failures(&r)),
        // The refusal's first line: the file, line and column, and the feature it names.
        Err(RunError::Level(e)) => {
            let text = e.to_string();
            let first = text.lines().next().unwrap_or_default();
            said(OtherVerdict::Refused, first.replace(": error: ", ": "))
        }
        Err(RunError::Sim { source, .. }) => said(OtherVerdict::Stopped, source.to_string()),
    }
}

/// What fails in a report: its failing checks and questions with their errors and tolerances.
fn failures(r: &LevelReport) -> String {
    let checks = r.checks.iter().filter(|c| !c.passed).map(|c| {
        format!(
            "check {} on {} ({:.2e}, tolerance {:.1e})",
            c.kind, c.subject, c.max_rel_error, c.tolerance
        )
    });
    let questions = r.questions.iter().filter(|q| !q.passed).map(|q| {
        format!(
            "question `{}` ({:.2e}, tolerance {:.1e})",
            q.id, q.rel_error, q.tolerance
        )
    });
    let all: Vec<String> = checks.chain(questions).collect();
    match (&r.error, all.is_empty()) {
        (Some(e), _) => e.clone(),
        (None, true) => "no check or question named".into(),
        (None, false) => all.join("; "),
    }
}
