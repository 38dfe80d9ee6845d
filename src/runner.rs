//! One run loop: a level's checks and questions observe every snapshot of a run once.
//!
//! [`Observers`] owns a run's checks and questions; the CLI ([`run_scene`]), the window
//! (`app::physics::LiveChecks`), the accuracy study and the tests all feed it, so every consumer
//! grades a run the same way. [`run_scene`] drives a level headless from start to end.

use crate::checks::questions::{QuestionProbe, QuestionResult};
use crate::checks::{CheckResult, CheckSet};
use crate::level::{self, Level, LevelError, Scene};
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

/// The checks and questions of one run, fed every snapshot in order (the initial one first).
pub struct Observers {
    checks: CheckSet,
    questions: Vec<QuestionProbe>,
}

impl Observers {
    pub fn new(level: &Level) -> Self {
        Observers {
            checks: CheckSet::new(level),
            questions: level
                .questions
                .iter()
                .map(|q| QuestionProbe::for_level(level, q))
                .collect(),
        }
    }

    pub fn observe(&mut self, s: &Snapshot) {
        self.checks.observe(s);
        for q in self.questions.iter_mut() {
            q.observe(s);
        }
    }

    /// The results, grading the students' answers given by question id.
    pub fn finish(self, answers: &HashMap<String, f64>) -> (Vec<CheckResult>, Vec<QuestionResult>) {
        let checks = self.checks.finish();
        let questions = self
            .questions
            .into_iter()
            .map(|q| {
                let answer = answers.get(q.id()).copied();
                q.finish(answer)
            })
            .collect();
        (checks, questions)
    }
}

/// Runs a scene, calling `each` with every snapshot (initial state first).
pub fn run_scene(
    scene: &Scene,
    opts: &Options,
    answers: &HashMap<String, f64>,
    mut each: impl FnMut(&Snapshot),
) -> Result<LevelReport, RunError> {
    let mut sim = Simulation::new(scene, opts);
    let mut observers = Observers::new(&sim.level);
    let start = Instant::now();
    let mut steps = 0;
    let result = sim.run(|s| {
        steps = s.step;
        observers.observe(s);
        each(s);
    });
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    result.map_err(|source| RunError::Sim {
        file: scene.file.display().to_string(),
        source,
    })?;
    let (checks, questions) = observers.finish(answers);
    let passed = checks.iter().all(|c| c.passed) && questions.iter().all(|q| q.passed);
    Ok(LevelReport {
        file: scene.file.display().to_string(),
        title: sim.level.title.clone(),
        passed,
        steps,
        sim_time: sim.snapshot().time,
        wall_ms,
        effects: sim.settings.effects.names(),
        settings: Some(sim.settings.clone()),
        checks,
        questions,
        error: None,
    })
}
