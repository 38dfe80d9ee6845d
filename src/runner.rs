//! One run loop: a level's checks and questions observe every snapshot of a run once.
//!
//! [`Observers`] owns a run's checks and questions; the CLI ([`run_scene`]), the window
//! (`app::physics::LiveChecks`), the accuracy study and the tests all feed it, so every consumer
//! grades a run the same way. [`run_scene`] drives a level headless from start to end.

use crate::checks::{CheckResult, CheckSet};
use crate::clock::Instant;
use crate::level::{self, Level, LevelError, Scene};
use crate::questions::{initial_in_f64, LevelFacts, QuestionProbe, QuestionResult};
use crate::report::LevelReport;
use crate::sim::{Options, SimError};
use crate::simulation::AnySimulation;
use crate::snapshot::Snapshot;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

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

/// The cost budget of one run, in body-iterations: [`Cost::total`] past this is refused unless
/// the user allows long runs (`--allow-long`). The library's costliest level at its own settings,
/// stress/joint_grid_30 (600 steps x 16 substeps x 1 iteration x 900 bodies = 8.6e6), checks in
/// 2.2 s on this machine (0.25 us per body-iteration; a level of a few bodies pays about 1 us,
/// its per-step overhead included); the budget is 115 times that, 4 to 15 minutes of stepping.
pub const COST_BUDGET: f64 = 1e9;

/// What a run will cost before it starts: steps x substeps x solver iterations x bodies
/// (f64, so that `--dt 1e-300` gives a number, not an overflow).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cost {
    pub steps: f64,
    pub substeps: usize,
    pub iterations: usize,
    pub bodies: usize,
}

impl Cost {
    /// The cost of running `level` with the command line's overrides.
    pub fn of(level: &Level, opts: &Options) -> Cost {
        let w = &level.world;
        Cost {
            // As Simulation::total_steps counts them.
            steps: (w.duration / opts.dt.unwrap_or(w.dt)).round().max(1.0),
            substeps: opts.substeps.unwrap_or(w.substeps),
            iterations: opts.solver_iterations.unwrap_or(w.solver_iterations),
            bodies: level.bodies.len().max(1),
        }
    }

    pub fn total(&self) -> f64 {
        self.steps * self.substeps as f64 * self.iterations as f64 * self.bodies as f64
    }

    /// Bad input (exit 2) when the run would cost more than [`COST_BUDGET`].
    pub fn within_budget(&self, file: &Path) -> Result<(), LevelError> {
        if self.total() <= COST_BUDGET {
            return Ok(());
        }
        Err(LevelError::new(
            file,
            (0, 0),
            format!(
                "this run would cost {:.2e} body-iterations ({:.3e} steps x {} substeps x {} iterations x {} bodies), past the budget of {COST_BUDGET:.0e}",
                self.total(),
                self.steps,
                self.substeps,
                self.iterations,
                self.bodies
            ),
            "pass --allow-long to run it anyway, or use a larger --dt, fewer --substeps or --iterations, or a shorter world.duration",
        ))
    }
}

/// Loads and runs a level file.
pub fn run_file(
    path: &Path,
    opts: &Options,
    answers: &HashMap<String, f64>,
) -> Result<LevelReport, RunError> {
    let scene = level::load(path)?;
    run_graded(&scene, opts, answers, |_| {})
}

/// The checks and questions of one run, fed every snapshot in order (the initial one first).
///
/// The questions share one copy of each snapshot (an `Arc`) and one copy of the level's facts:
/// a run's memory grows with its questions, not with questions x bodies (tests/cli_memory.rs: 1,000
/// questions on 1,000 bodies).
pub struct Observers {
    checks: CheckSet,
    questions: Vec<QuestionProbe>,
}

impl Observers {
    pub fn new(level: &Level) -> Self {
        let facts = Arc::new(LevelFacts::of(level));
        Observers {
            checks: CheckSet::new(level),
            questions: level
                .questions
                .iter()
                .map(|q| QuestionProbe::sharing(Arc::clone(&facts), q))
                .collect(),
        }
    }

    /// Whether a check or a question reads the snapshots' contacts (every question is taken to).
    pub fn reads_contacts(&self) -> bool {
        self.checks.reads_contacts() || !self.questions.is_empty()
    }

    pub fn observe(&mut self, s: &Snapshot) {
        self.checks.observe(s);
        // Questions read for good need no more snapshots: no copy once all are.
        if self.questions.iter().all(QuestionProbe::is_done) {
            return;
        }
        let shared = Arc::new(if s.is_initial() {
            initial_in_f64(s)
        } else {
            s.clone()
        });
        for q in self.questions.iter_mut() {
            q.observe_shared(&shared);
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

/// Runs a scene for its checks and questions alone, calling `progress` with each step's number:
/// the snapshots carry only what the level's readers read (no contacts where none reads them,
/// `sim::Simulation::set_contact_readings`). [`run_scene`] reads everything, for its `each`.
pub fn run_graded(
    scene: &Scene,
    opts: &Options,
    answers: &HashMap<String, f64>,
    mut progress: impl FnMut(u64),
) -> Result<LevelReport, RunError> {
    run_with(scene, opts, answers, true, |s| progress(s.step))
}

/// Runs a scene, calling `each` with every snapshot (initial state first).
pub fn run_scene(
    scene: &Scene,
    opts: &Options,
    answers: &HashMap<String, f64>,
    each: impl FnMut(&Snapshot),
) -> Result<LevelReport, RunError> {
    run_with(scene, opts, answers, false, each)
}

/// [`run_scene`]; `as_read`: the snapshots carry only what the observers read.
fn run_with(
    scene: &Scene,
    opts: &Options,
    answers: &HashMap<String, f64>,
    as_read: bool,
    mut each: impl FnMut(&Snapshot),
) -> Result<LevelReport, RunError> {
    let mut sim = AnySimulation::new(scene, opts);
    let mut observers = Observers::new(&sim.level);
    if as_read && !observers.reads_contacts() {
        sim.set_contact_readings(false);
    }
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
    // A student's wrong answer fails the level as a wrong engine value would: graders read the exit code.
    let passed = checks.iter().all(|c| c.passed)
        && questions
            .iter()
            .all(|q| q.passed && q.student.as_ref().is_none_or(|s| s.passed));
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
        advice: None,
    })
}
