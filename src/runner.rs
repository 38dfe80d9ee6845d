//! Runs a level headless from start to end: simulation, checks and questions in one pass.

use crate::checks::questions::QuestionProbe;
use crate::checks::CheckSet;
use crate::level::{self, LevelError, Scene};
use crate::report::LevelReport;
use crate::sim::{Options, SimError, Simulation};
use crate::snapshot::Snapshot;
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

/// Why a level could not be run to the end.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// Bad input: exit code 2.
    #[error("{0}")]
    Level(#[from] LevelError),
    /// The scene exploded or became non-finite: reported as a failed level.
    #[error("{file}: the simulation stopped at {source}\n  help: a smaller dt, more substeps, or less extreme values usually fix this")]
    Sim { file: String, source: SimError },
}

/// Loads and runs a level file.
pub fn run_file(
    path: &Path,
    opts: &Options,
    answers: &HashMap<String, f64>,
) -> Result<LevelReport, RunError> {
    let scene = level::load(path)?;
    run_scene(&scene, opts, answers, |_| {})
}

/// Runs a scene, calling `each` with every snapshot (initial state first).
pub fn run_scene(
    scene: &Scene,
    opts: &Options,
    answers: &HashMap<String, f64>,
    mut each: impl FnMut(&Snapshot),
) -> Result<LevelReport, RunError> {
    let mut sim = Simulation::new(scene, opts);
    let level = &sim.level;
    let mut checks = CheckSet::new(level);
    let mut questions: Vec<QuestionProbe> = level
        .questions
        .iter()
        .map(|q| QuestionProbe::for_level(level, q))
        .collect();
    let start = Instant::now();
    let mut steps = 0;
    let result = sim.run(|s| {
        steps = s.step;
        checks.observe(s);
        for q in questions.iter_mut() {
            q.observe(s);
        }
        each(s);
    });
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    result.map_err(|source| RunError::Sim {
        file: scene.file.display().to_string(),
        source,
    })?;
    let checks = checks.finish();
    let questions: Vec<_> = questions
        .into_iter()
        .map(|q| {
            let answer = answers.get(q.id()).copied();
            q.finish(answer)
        })
        .collect();
    let passed = checks.iter().all(|c| c.passed) && questions.iter().all(|q| q.passed);
    Ok(LevelReport {
        file: scene.file.display().to_string(),
        title: sim.level.title.clone(),
        passed,
        steps,
        sim_time: sim.snapshot().time,
        wall_ms,
        effects: sim.effects.names(),
        checks,
        questions,
        error: None,
    })
}
