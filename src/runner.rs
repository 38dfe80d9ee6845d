//! One run loop: a level's checks and questions observe every snapshot of a run once.
//!
//! [`Observers`] owns a run's checks and questions; the CLI ([`run_scene`]), the window
//! (`app::physics::LiveChecks`), the accuracy study and the tests all feed it, so every consumer
//! grades a run the same way. [`run_scene`] drives a level headless from start to end.

use crate::checks::{CheckResult, CheckSet};
use crate::clock::Instant;
use crate::level::PhysicsEngine;
use crate::level::{self, Level, LevelError, Scene};
use crate::questions::{
    initial_in_f64, ChallengeProbe, ChallengeResult, LevelFacts, QuestionProbe, QuestionResult,
};
use crate::report::LevelReport;
use crate::sim::{Drive, Options, SimError};
use crate::simulation::AnySimulation;
use crate::snapshot::Snapshot;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

pub mod budget;
pub use budget::{Estimate, Mode, Work, MEMORY_BUDGET_MB, TIME_BUDGET_S};

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
    run_graded(&scene, opts, answers, |_| {})
}

/// The checks and questions of one run, fed every snapshot in order (the initial one first).
///
/// The questions share one copy of each snapshot (an `Arc`) and one copy of the level's facts:
/// a run's memory grows with its questions, not with questions x bodies (tests/suite/runner/cli_memory.rs: 1,000
/// questions on 1,000 bodies).
pub struct Observers {
    checks: CheckSet,
    questions: Vec<QuestionProbe>,
    /// The level's challenge, judged on the same snapshots.
    challenge: Option<ChallengeProbe>,
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
            challenge: level
                .challenge
                .as_ref()
                .map(|c| ChallengeProbe::new(level, Arc::clone(&facts), c)),
        }
    }

    /// Whether a check or a question reads the snapshots' contacts (every question is taken to).
    pub fn reads_contacts(&self) -> bool {
        self.checks.reads_contacts() || !self.questions.is_empty() || self.challenge.is_some()
    }

    pub fn observe(&mut self, s: &Snapshot) {
        self.checks.observe(s);
        // Questions read for good need no more snapshots: no copy once all are.
        if self.questions.iter().all(QuestionProbe::is_done)
            && self.challenge.as_ref().is_none_or(ChallengeProbe::is_done)
        {
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
        if let Some(c) = self.challenge.as_mut() {
            c.observe_shared(&shared);
        }
    }

    /// The results, grading the students' answers given by question id.
    pub fn finish(self, answers: &HashMap<String, f64>) -> (Vec<CheckResult>, Vec<QuestionResult>) {
        let (checks, questions, _) = self.finish_all(answers);
        (checks, questions)
    }

    /// [`Observers::finish`], with the challenge's verdict (None without a challenge).
    pub fn finish_all(
        self,
        answers: &HashMap<String, f64>,
    ) -> (
        Vec<CheckResult>,
        Vec<QuestionResult>,
        Option<ChallengeResult>,
    ) {
        let challenge = self.challenge.map(ChallengeProbe::finish);
        let checks = self.checks.finish();
        let questions = self
            .questions
            .into_iter()
            .map(|q| {
                let answer = answers.get(q.id()).copied();
                q.finish(answer)
            })
            .collect();
        (checks, questions, challenge)
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
    let mut sim = engine_for(scene, opts)?;
    let mut observers = Observers::new(sim.level());
    if as_read && !observers.reads_contacts() {
        sim.set_contact_readings(false);
    }
    let start = Instant::now();
    let mut steps = 0;
    let result = sim.run_each(&mut |s| {
        steps = s.step;
        observers.observe(s);
        each(s);
    });
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    result.map_err(|source| RunError::Sim {
        file: scene.file.display().to_string(),
        source,
    })?;
    let (checks, questions, challenge) = observers.finish_all(answers);
    // A student's wrong answer fails the level as a wrong engine value would: graders read the
    // exit code. So does a challenge's missed goal, the worked value's or the student's.
    let passed = checks.iter().all(|c| c.passed)
        && questions
            .iter()
            .all(|q| q.passed && q.student.as_ref().is_none_or(|s| s.passed))
        && challenge.as_ref().is_none_or(|c| c.success);
    Ok(LevelReport {
        file: scene.file.display().to_string(),
        title: sim.level().title.clone(),
        passed,
        steps,
        sim_time: sim.snapshot().time,
        wall_ms,
        effects: sim.settings().effects.names(),
        engine: Some(engine_of(scene, opts)),
        settings: Some(sim.settings_as_run()),
        checks,
        questions,
        challenge,
        error: None,
        advice: None,
        other_engine: None,
        hint: None,
        solution: None,
    })
}

/// The engine a run of `scene` at `opts` uses: `--engine`, else the level's `world.engine`.
pub fn engine_of(scene: &Scene, opts: &Options) -> PhysicsEngine {
    opts.engine.unwrap_or(scene.level.world.engine)
}

/// The engine seam's dispatch: the engine `--engine` names, else the level's `world.engine`.
/// rapier runs every level; Box2D refuses, with the level item, what it does not run
/// (`sim::box2d::support`), and a build without the `box2d` feature refuses it whole.
pub fn engine_for(scene: &Scene, opts: &Options) -> Result<Box<dyn Drive>, RunError> {
    match engine_of(scene, opts) {
        PhysicsEngine::Rapier => Ok(Box::new(AnySimulation::new(scene, opts))),
        PhysicsEngine::Box2d => box2d_engine(scene, opts),
    }
}

#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
fn box2d_engine(scene: &Scene, opts: &Options) -> Result<Box<dyn Drive>, RunError> {
    Ok(Box::new(crate::sim::box2d::Simulation::new(scene, opts)?))
}

#[cfg(not(all(feature = "box2d", not(target_arch = "wasm32"))))]
fn box2d_engine(scene: &Scene, _opts: &Options) -> Result<Box<dyn Drive>, RunError> {
    let text = level::read_text(&scene.file).ok();
    Err(RunError::Level(
        crate::sim::box2d::not_built().locate(&scene.file, text.as_deref()),
    ))
}
