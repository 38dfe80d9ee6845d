//! `rigidlab study stability`: do hard cases stay numerically stable?
//!
//! Runs every stress level (levels/stress/*.ron) and judges it on criteria computed from the
//! snapshots alone (`criteria`): no NaN/inf, total energy never above the initial energy plus
//! the work put in plus a stated margin, penetration, joint separation, structures that hold,
//! bodies that stay inside a box, and a case-specific criterion (`cases`, keyed by file name).
//!
//! Each case runs at its *recorded* settings (the level's `world`, plus what the level format
//! cannot say yet: contact stiffness, precision, fast rotation; see `cases::Extra`) and, unless
//! `--quick` or `--long`, also at rapier's defaults (dt 1/60 s, 4 substeps, 1 iteration, f32,
//! 30 Hz contacts, no CCD, speed caps), so the table shows what the recorded settings buy.
//! Only the recorded runs decide the exit code; a criterion that fails by a known engine
//! limitation (`cases::Spec::gaps`) is reported with its figure and does not fail the case.
//! `--dt`, `--substeps`, ... try other settings in place of the recorded ones.
//!
//! Penetration is measured on the engine's poses (`Simulation::deepest_overlap`), not from the snapshot's
//! contact distances, which rapier leaves stale while it recycles a pair's contacts.

pub mod cases;
pub mod criteria;
mod engines;

use crate::clock::Instant;
use crate::level::{self, PhysicsEngine, Scene};
use crate::sim::{Engine, Options};
use criteria::{Criterion, Monitor, Outcome};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print the JSON report instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Run every case for 1e5 steps (recorded settings only; implies --allow-long).
    #[arg(long)]
    pub long: bool,
    /// Run even when a case is estimated past the time or memory budget (runner::budget).
    #[arg(long)]
    pub allow_long: bool,
    /// Recorded settings only: skip the comparison runs at rapier's defaults.
    #[arg(long)]
    pub quick: bool,
    /// Folder with the stress levels.
    #[arg(long, default_value = "levels/stress")]
    pub dir: PathBuf,
    /// Only these cases (level file names without `.ron`).
    pub cases: Vec<String>,
    /// Try another step instead of the recorded one, s (to look for cheaper settings).
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Try another number of substeps.
    #[arg(long)]
    pub substeps: Option<usize>,
    /// Try another number of solver iterations per substep.
    #[arg(long)]
    pub iterations: Option<usize>,
    /// Try f64 rapier.
    #[arg(long = "f64")]
    pub double: bool,
    /// Try rapier's allow_fast_rotation on every body.
    #[arg(long)]
    pub fast_rotation: bool,
    /// Try another contact stiffness: rapier's contact_softness natural frequency, Hz
    /// (default 30; contacts with fixed bodies get twice it, as rapier's defaults do).
    #[arg(long)]
    pub contact_hz: Option<f64>,
    /// Try soft joints: rapier's joint softness natural frequency, Hz (default 1e6, i.e. rigid).
    #[arg(long)]
    pub joint_hz: Option<f64>,
    /// The engines to run every case on, comma-separated: rapier (the default), box2d, or
    /// rapier,box2d; the same criteria judge both (Box2D runs in f32, without joint softness).
    #[arg(long, value_delimiter = ',', value_parser = crate::study::accuracy::parse_engine, default_value = "rapier")]
    pub engine: Vec<PhysicsEngine>,
}

/// Settings tried instead of the recorded ones (`--dt`, `--substeps`, ...).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    pub dt: Option<f64>,
    pub substeps: Option<usize>,
    pub iterations: Option<usize>,
    pub f64: bool,
    pub fast_rotation: bool,
    pub contact_hz: Option<f64>,
    pub joint_hz: Option<f64>,
}

impl Overrides {
    pub fn apply(&self, s: &Settings) -> Settings {
        Settings {
            dt: self.dt.unwrap_or(s.dt),
            substeps: self.substeps.unwrap_or(s.substeps),
            iterations: self.iterations.unwrap_or(s.iterations),
            f64: s.f64 || self.f64,
            fast_rotation: s.fast_rotation || self.fast_rotation,
            contact_hz: self.contact_hz.or(s.contact_hz),
            joint_hz: self.joint_hz.or(s.joint_hz),
            dropped: s.dropped.clone(),
            engine: s.engine,
        }
    }
}

/// The steps `--long` runs.
pub const LONG_STEPS: u64 = 100_000;

/// rapier's defaults (IntegrationParameters::default()).
pub const DEFAULT_DT: f64 = 1.0 / 60.0;
pub const DEFAULT_SUBSTEPS: usize = 4;
pub const DEFAULT_ITERATIONS: usize = 1;

/// The solver settings of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    pub dt: f64,
    pub substeps: usize,
    pub iterations: usize,
    /// f64 rapier (rapier2d-f64) instead of f32.
    pub f64: bool,
    /// rapier's `allow_fast_rotation` on every body (lifts the (pi/4)/dt angular speed cap).
    pub fast_rotation: bool,
    /// rapier's contact stiffness `contact_softness.natural_frequency`, Hz (None: rapier's 30 Hz;
    /// contacts with fixed bodies get twice it, as rapier's defaults do).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_hz: Option<f64>,
    /// rapier's joint softness natural frequency, Hz (None: rapier's 1e6 Hz, rigid joints).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint_hz: Option<f64>,
    /// Effects of the level dropped for this run (e.g. `ccd` in the defaults run).
    pub dropped: Vec<String>,
    /// The engine of the run (absent in the JSON: rapier).
    #[serde(default, skip_serializing_if = "PhysicsEngine::is_rapier")]
    pub engine: PhysicsEngine,
}

impl Settings {
    /// The recorded settings of a case: the level's world plus the spec's extras.
    pub fn recorded(scene: &Scene, spec: &cases::Spec) -> Self {
        let w = &scene.level.world;
        Settings {
            dt: w.dt,
            substeps: w.substeps,
            iterations: w.solver_iterations,
            f64: spec.recorded.f64,
            // The level declares these now (world.allow_fast_rotation, world.contact_hz).
            fast_rotation: w.allow_fast_rotation || spec.recorded.fast_rotation,
            contact_hz: w.contact_hz.or(spec.recorded.contact_hz),
            joint_hz: spec.recorded.joint_hz,
            dropped: Vec::new(),
            engine: PhysicsEngine::Rapier,
        }
    }

    /// rapier's defaults, with the level's non-default effects dropped.
    pub fn defaults(scene: &Scene, spec: &cases::Spec) -> Self {
        Settings {
            dt: DEFAULT_DT,
            substeps: DEFAULT_SUBSTEPS,
            iterations: DEFAULT_ITERATIONS,
            f64: false,
            fast_rotation: false,
            contact_hz: None,
            joint_hz: None,
            dropped: spec
                .not_default
                .iter()
                .filter(|e| scene.level.effects.contains(e))
                .map(|e| e.name().to_string())
                .collect(),
            engine: PhysicsEngine::Rapier,
        }
    }

    /// The same settings on `engine`.
    pub fn on(self, engine: PhysicsEngine) -> Self {
        Settings { engine, ..self }
    }

    pub fn is_default(&self) -> bool {
        (self.dt - DEFAULT_DT).abs() < 1e-12
            && self.substeps == DEFAULT_SUBSTEPS
            && self.iterations == DEFAULT_ITERATIONS
            && !self.f64
            && !self.fast_rotation
            && self.contact_hz.is_none()
            && self.joint_hz.is_none()
    }

    /// Short human form: "defaults" or what differs from them.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if !self.engine.is_rapier() {
            parts.push(self.engine.name().to_string());
        }
        if (self.dt - DEFAULT_DT).abs() > 1e-12 {
            parts.push(format!("dt 1/{:.0}", 1.0 / self.dt));
        }
        if self.substeps != DEFAULT_SUBSTEPS {
            parts.push(format!("substeps {}", self.substeps));
        }
        if self.iterations != DEFAULT_ITERATIONS {
            parts.push(format!("iters {}", self.iterations));
        }
        if self.f64 {
            parts.push("f64".into());
        }
        if self.fast_rotation {
            parts.push("fast rotation".into());
        }
        if let Some(hz) = self.contact_hz {
            parts.push(format!("contacts {hz:.0} Hz"));
        }
        if let Some(hz) = self.joint_hz {
            parts.push(format!("joints {hz:.0} Hz"));
        }
        for d in &self.dropped {
            parts.push(format!("no {d}"));
        }
        if parts.is_empty() || parts == [self.engine.name()] {
            parts.push("defaults".into());
        }
        parts.join(", ")
    }
}

/// One run of one case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    pub settings: Settings,
    pub steps: u64,
    pub passed: bool,
    pub wall_ms: f64,
    /// Criterion and figure values by name (criteria first, then the extra figures).
    pub figures: BTreeMap<String, f64>,
    pub criteria: Vec<Criterion>,
    /// Set when the run stopped early (non-finite state, explosion guard).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Set when the engine refused the case (a feature it does not run, with its place in the
    /// level): not run, and not counted as a pass or a failure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refused: Option<String>,
}

impl RunResult {
    pub fn failed(&self) -> Vec<&Criterion> {
        self.criteria.iter().filter(|c| !c.passed).collect()
    }
    pub fn criterion(&self, name: &str) -> Option<&Criterion> {
        self.criteria.iter().find(|c| c.name == name)
    }
    pub fn figure(&self, name: &str) -> Option<f64> {
        self.figures.get(name).copied()
    }
}

/// One case: its recorded run, and the comparison at rapier's defaults.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseResult {
    pub name: String,
    /// The engine the case ran on (absent in the JSON: rapier).
    #[serde(default, skip_serializing_if = "PhysicsEngine::is_rapier")]
    pub engine: PhysicsEngine,
    pub about: String,
    pub steps: u64,
    pub passed: bool,
    pub figures: BTreeMap<String, f64>,
    pub recorded: RunResult,
    /// The same case at rapier's defaults (absent when the recorded settings are the defaults,
    /// or with --quick / --long).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub defaults: Option<RunResult>,
    /// Extra measurement runs (the disc at dt 1/60 with fast rotation).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub variants: Vec<RunResult>,
    /// Why the recorded settings differ from the defaults.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub settings_why: String,
}

/// The JSON report: `{"passed", "cases": [...]}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StabilityReport {
    pub passed: bool,
    pub cases: Vec<CaseResult>,
}

/// Runs one case's scene at the given settings for `steps` steps (None: the level's duration).
pub fn run(
    scene: &Scene,
    spec: &cases::Spec,
    settings: &Settings,
    steps: Option<u64>,
    progress: Option<&ProgressBar>,
) -> RunResult {
    let mut scene = scene.clone();
    {
        let w = &mut scene.level.world;
        w.dt = settings.dt;
        w.substeps = settings.substeps;
        w.solver_iterations = settings.iterations;
        // The simulation applies these from the level, as `rigidlab check` does.
        w.allow_fast_rotation = settings.fast_rotation;
        w.contact_hz = settings.contact_hz;
        if let Some(n) = steps {
            w.duration = n as f64 * settings.dt;
        }
    }
    scene
        .level
        .effects
        .retain(|e| !settings.dropped.iter().any(|d| d == e.name()));
    let limits = (spec.limits)(&scene, settings);
    let special = (spec.special)(&scene, settings);
    let mut monitor = Monitor::new(&scene.level, limits, special);
    let opts = Options::default();
    let start = Instant::now();
    let error = if !settings.engine.is_rapier() {
        match engines::drive(&scene, settings.engine, &mut monitor, progress) {
            Ok(error) => error,
            Err(why) => return engines::refused_run(settings, why),
        }
    } else if settings.f64 {
        let mut sim = crate::sim64::Simulation::new(&scene, &opts);
        if let Some(hz) = settings.joint_hz {
            sim.set_joint_softness(hz);
        }
        drive(sim, |s| s.deepest_overlap(), &mut monitor, progress)
    } else {
        let mut sim = crate::sim::Simulation::new(&scene, &opts);
        if let Some(hz) = settings.joint_hz {
            sim.set_joint_softness(hz);
        }
        drive(sim, |s| s.deepest_overlap(), &mut monitor, progress)
    };
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut outcome: Outcome = monitor.finish(error.as_deref());
    for c in outcome.criteria.iter_mut() {
        if !c.passed {
            if let Some((_, why)) = spec.gaps.iter().find(|(name, _)| *name == c.name) {
                c.known_gap = Some(why.to_string());
            }
        }
    }
    let mut figures = BTreeMap::new();
    for c in &outcome.criteria {
        figures.insert(c.name.clone(), c.value);
    }
    figures.extend(outcome.figures.clone());
    RunResult {
        settings: settings.clone(),
        steps: monitor.steps(),
        passed: outcome.passed(),
        wall_ms,
        figures,
        criteria: outcome.criteria,
        error,
        refused: None,
    }
}

/// Steps a simulation to its end, feeding the monitor; returns the error that stopped it, if any.
fn drive<S: Engine>(
    mut sim: S,
    overlap: impl Fn(&S) -> f64,
    monitor: &mut Monitor,
    progress: Option<&ProgressBar>,
) -> Option<String> {
    let total = sim.total_steps();
    monitor.observe(sim.snapshot());
    monitor.observe_overlap(sim.snapshot().time, overlap(&sim));
    let mut done = 0u64;
    let mut error = None;
    for _ in 0..total {
        let time = match sim.step() {
            Ok(s) => {
                monitor.observe(s);
                s.time
            }
            Err(e) => {
                error = Some(e.to_string());
                break;
            }
        };
        monitor.observe_overlap(time, overlap(&sim));
        done += 1;
        if done.is_multiple_of(256) {
            if let Some(p) = progress {
                p.inc(256);
            }
        }
    }
    if let Some(p) = progress {
        p.inc(done % 256 + (total - done));
    }
    error
}

/// What to run.
#[derive(Debug, Clone, Default)]
pub struct Plan {
    /// Also run at rapier's defaults (and the extra measurement variants).
    pub compare: bool,
    /// Steps per run (None: each level's duration).
    pub steps: Option<u64>,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Settings to try instead of the recorded ones.
    pub overrides: Overrides,
    /// The engine every run of the case is made on.
    pub engine: PhysicsEngine,
}

/// Runs one case (by level file) according to the plan.
pub fn run_case(path: &Path, spec: &cases::Spec, plan: &Plan) -> Result<CaseResult, String> {
    run_case_with(path, spec, plan, None)
}

fn run_case_with(
    path: &Path,
    spec: &cases::Spec,
    plan: &Plan,
    bar: Option<&ProgressBar>,
) -> Result<CaseResult, String> {
    let scene = level::load(path).map_err(|e| e.to_string())?;
    let recorded_settings = plan
        .overrides
        .apply(&Settings::recorded(&scene, spec))
        .on(plan.engine);
    let recorded = run(&scene, spec, &recorded_settings, plan.steps, bar);
    let mut defaults = None;
    let mut variants = Vec::new();
    if plan.compare {
        let d = Settings::defaults(&scene, spec).on(plan.engine);
        if d != recorded_settings && recorded.refused.is_none() {
            defaults = Some(run(&scene, spec, &d, plan.steps, bar));
        }
        if spec.name == "spinning_disc" && recorded.refused.is_none() {
            // Lifting the cap at rapier's default step: only the linearized rotation remains.
            let v = Settings {
                fast_rotation: true,
                ..Settings::defaults(&scene, spec).on(plan.engine)
            };
            variants.push(run(&scene, spec, &v, plan.steps, bar));
        }
    }
    Ok(CaseResult {
        engine: plan.engine,
        name: spec.name.to_string(),
        about: spec.about.to_string(),
        steps: recorded.steps,
        passed: recorded.passed,
        figures: recorded.figures.clone(),
        recorded,
        defaults,
        variants,
        settings_why: spec.settings_why.to_string(),
    })
}

/// The spec for a level file name (without `.ron`).
pub fn spec(name: &str) -> Option<cases::Spec> {
    cases::all().into_iter().find(|s| s.name == name)
}

/// Steps a case's runs will take under the plan (for the progress bar).
fn planned_steps(path: &Path, spec: &cases::Spec, plan: &Plan) -> u64 {
    let Ok(scene) = level::load(path) else {
        return 0;
    };
    let w = &scene.level.world;
    let per = |dt: f64| {
        plan.steps
            .unwrap_or(((w.duration / dt).round().max(1.0)) as u64)
    };
    let mut n = per(plan.overrides.dt.unwrap_or(w.dt));
    if plan.compare {
        let d = Settings::defaults(&scene, spec);
        if d != Settings::recorded(&scene, spec) {
            n += per(DEFAULT_DT);
        }
        if spec.name == "spinning_disc" {
            n += per(DEFAULT_DT);
        }
    }
    n
}

/// The cases asked for, after the arguments are checked: the folder, the case names, the
/// step, the frequencies and the counts (each error says how to fix it; exit 2).
fn chosen_cases<'a>(args: &Args, specs: &'a [cases::Spec]) -> Result<Vec<&'a cases::Spec>, String> {
    if !args.dir.is_dir() {
        return Err(format!(
            "{}: no such folder\n  help: run from the repository root, or give --dir levels/stress",
            args.dir.display()
        ));
    }
    for c in &args.cases {
        if !specs.iter().any(|s| s.name == c) {
            let names: Vec<_> = specs.iter().map(|s| s.name).collect();
            return Err(format!(
                "unknown case \"{c}\"\n  help: use one of: {}",
                names.join(", ")
            ));
        }
    }
    let chosen: Vec<&'a cases::Spec> = specs
        .iter()
        .filter(|s| args.cases.is_empty() || args.cases.iter().any(|c| c == s.name))
        .collect();
    if let Some(dt) = args.dt {
        if !(dt.is_finite() && dt > 0.0 && dt <= 0.1) {
            return Err(format!("--dt {dt}: give a step between 0 and 0.1 s"));
        }
    }
    for hz in [args.contact_hz, args.joint_hz].into_iter().flatten() {
        if !(hz.is_finite() && hz > 0.0) {
            return Err(format!(
                "--contact-hz/--joint-hz {hz}: give a positive frequency in Hz"
            ));
        }
    }
    for (flag, n) in [
        ("--substeps", args.substeps),
        ("--iterations", args.iterations),
    ] {
        if n.is_some_and(|n| n == 0 || n > 1000) {
            return Err(format!("{flag}: give a number from 1 to 1000"));
        }
    }
    Ok(chosen)
}

/// The budget `check` and `run` apply, to the settings each case will run at (skipped with
/// `--allow-long` or `--long`).
fn check_budgets(
    args: &Args,
    chosen: &[&cases::Spec],
    paths: &[PathBuf],
    plan: &Plan,
) -> Result<(), String> {
    if !(args.allow_long || args.long) {
        for (s, p) in chosen.iter().zip(paths) {
            let Ok(scene) = level::load(p) else {
                continue; // reported when the case runs
            };
            let set = plan.overrides.apply(&Settings::recorded(&scene, s));
            let opts = crate::sim::Options {
                dt: Some(set.dt),
                substeps: Some(set.substeps),
                solver_iterations: Some(set.iterations),
                precision: set.f64.then_some(level::Precision::F64),
                ..Default::default()
            };
            let estimate =
                crate::runner::Estimate::of(&scene.level, &opts, crate::runner::Mode::Check, None);
            estimate.within_budget(p).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}

/// Runs every (case, engine) with one progress bar: the results, a failed case's error
/// printed and listed in its place, and whether any input was bad.
fn run_cases(
    runs: &[(&cases::Spec, &PathBuf, Plan)],
    plan: &Plan,
    args: &Args,
) -> (Vec<CaseResult>, bool) {
    let total: u64 = runs
        .iter()
        .map(|(s, p, plan)| planned_steps(p, s, plan))
        .sum();
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps  {elapsed} (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    if !plan.progress || args.json && !args.long {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let results: Vec<Result<CaseResult, String>> = runs
        .par_iter()
        .map(|(s, p, plan)| run_case_with(p, s, plan, Some(&bar)))
        .collect();
    bar.finish_and_clear();
    let mut bad_input = false;
    let mut cases_out = Vec::new();
    for (r, (s, _, _)) in results.into_iter().zip(runs) {
        match r {
            Ok(c) => cases_out.push(c),
            Err(e) => {
                stderr!("{e}");
                bad_input = true;
                cases_out.push(missing(s, &e));
            }
        }
    }
    (cases_out, bad_input)
}

pub fn main(args: Args) -> ExitCode {
    let specs = cases::all();
    let chosen = match chosen_cases(&args, &specs) {
        Ok(chosen) => chosen,
        Err(e) => {
            stderr!("{e}");
            return ExitCode::from(2);
        }
    };
    let plan = Plan {
        compare: !(args.quick || args.long),
        steps: args.long.then_some(LONG_STEPS),
        progress: true,
        overrides: Overrides {
            dt: args.dt,
            substeps: args.substeps,
            iterations: args.iterations,
            f64: args.double,
            fast_rotation: args.fast_rotation,
            contact_hz: args.contact_hz,
            joint_hz: args.joint_hz,
        },
        engine: PhysicsEngine::Rapier,
    };
    if let Err(e) = engines::check_overrides(&args) {
        stderr!("{e}");
        return ExitCode::from(2);
    }
    let paths: Vec<PathBuf> = chosen
        .iter()
        .map(|s| args.dir.join(format!("{}.ron", s.name)))
        .collect();
    if let Err(e) = check_budgets(&args, &chosen, &paths, &plan) {
        stderr!("{e}");
        return ExitCode::from(2);
    }
    // Level files without a spec are reported, not silently skipped.
    let mut unjudged = Vec::new();
    if let Ok(files) = level::collect_files(std::slice::from_ref(&args.dir)) {
        for f in files {
            let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or("");
            if !specs.iter().any(|s| s.name == stem) {
                unjudged.push(f.display().to_string());
            }
        }
    }
    let runs = engines::case_runs(&args.engine, &chosen, &paths, &plan);
    let (cases_out, bad_input) = run_cases(&runs, &plan, &args);
    let report = StabilityReport {
        // A case an engine refuses is listed, not judged.
        passed: cases_out
            .iter()
            .all(|c| c.passed || c.recorded.refused.is_some()),
        cases: cases_out,
    };
    for u in &unjudged {
        stderr!("note: {u} has no criteria in src/study/stability/cases.rs and was not run");
    }
    let code = if bad_input {
        ExitCode::from(2)
    } else if report.passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    };
    let text = if args.json {
        crate::report::json(&report)
    } else {
        table(&report)
    };
    crate::report::print(&text, code)
}

fn missing(spec: &cases::Spec, error: &str) -> CaseResult {
    let run = RunResult {
        settings: Settings {
            dt: 0.0,
            substeps: 0,
            iterations: 0,
            f64: false,
            fast_rotation: false,
            contact_hz: None,
            joint_hz: None,
            dropped: Vec::new(),
            engine: PhysicsEngine::Rapier,
        },
        steps: 0,
        passed: false,
        wall_ms: 0.0,
        figures: BTreeMap::new(),
        criteria: Vec::new(),
        error: Some(error.to_string()),
        refused: None,
    };
    CaseResult {
        engine: PhysicsEngine::Rapier,
        name: spec.name.to_string(),
        about: spec.about.to_string(),
        steps: 0,
        passed: false,
        figures: BTreeMap::new(),
        recorded: run,
        defaults: None,
        variants: Vec::new(),
        settings_why: String::new(),
    }
}

/// A number in a short fixed width.
fn short(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        format!("{x}")
    } else if (1e-2..1e4).contains(&x.abs()) {
        format!("{x:.3}")
    } else {
        format!("{x:.2e}")
    }
}

fn criteria_line(r: &RunResult) -> String {
    r.criteria
        .iter()
        .filter(|c| c.name != "finite" || !c.passed)
        .map(|c| {
            let op = match c.sense {
                criteria::Sense::Max => "<=",
                criteria::Sense::Min => ">=",
            };
            format!(
                "{}{} {} {} {}",
                match (c.passed, c.known_gap.is_some()) {
                    (true, _) => "",
                    (false, true) => "~",
                    (false, false) => "!",
                },
                c.name,
                short(c.value),
                op,
                short(c.limit)
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn verdict(r: &RunResult) -> String {
    let gaps = r
        .criteria
        .iter()
        .any(|c| !c.passed && c.known_gap.is_some());
    if r.passed {
        if gaps { "pass*" } else { "pass" }.into()
    } else {
        let failed: Vec<_> = r
            .failed()
            .iter()
            .filter(|c| c.known_gap.is_none())
            .map(|c| c.name.clone())
            .collect();
        format!("FAIL ({})", failed.join(", "))
    }
}

/// The terminal table: a line per case, then its criteria (value, comparison, limit).
pub fn table(report: &StabilityReport) -> String {
    let mut out = String::new();
    let w = report
        .cases
        .iter()
        .map(|c| c.recorded.settings.describe().len())
        .max()
        .unwrap_or(0)
        .max(17);
    out += &format!(
        "{:<18} {:<w$} {:>7} {:>9}  {:<8} {}\n",
        "case", "recorded settings", "steps", "wall ms", "result", "at rapier defaults"
    );
    for c in &report.cases {
        let r = &c.recorded;
        if let Some(why) = &r.refused {
            out += &format!("{:<18} {:<w$} refused: {why}\n", c.name, c.engine.name());
            continue;
        }
        let d = match &c.defaults {
            Some(d) => verdict(d),
            None if r.settings.is_default() => "(same)".into(),
            None => "(not run)".into(),
        };
        out += &format!(
            "{:<18} {:<w$} {:>7} {:>9.1}  {:<8} {}\n",
            c.name,
            r.settings.describe(),
            c.steps,
            r.wall_ms,
            if r.passed { verdict(r) } else { "FAIL".into() },
            d
        );
        if let Some(e) = &r.error {
            out += &format!("    error: {e}\n");
        }
        out += &format!("    {}\n", criteria_line(r));
        if let Some(d) = &c.defaults {
            if let Some(e) = &d.error {
                out += &format!("    at defaults: error: {e}\n");
            }
            out += &format!("    at defaults: {}\n", criteria_line(d));
        }
        for v in &c.variants {
            out += &format!(
                "    {}: {} -- {}\n",
                v.settings.describe(),
                verdict(v),
                criteria_line(v)
            );
        }
    }
    let passed = report.cases.iter().filter(|c| c.passed).count();
    let refused = report
        .cases
        .iter()
        .filter(|c| c.recorded.refused.is_some())
        .count();
    out += &format!(
        "{passed}/{} cases passed at their recorded settings{} \
         (!: criterion failed; ~ and pass*: a known engine gap, reported, see --json)\n",
        report.cases.len() - refused,
        if refused > 0 {
            format!(", {refused} refused by their engine")
        } else {
            String::new()
        }
    );
    out
}
