//! The command line: `rigidlab [check|run|verify|grade|play|render|study]`.

use crate::level::{self, LevelError};
use crate::report::{self, CsvWriter, LevelReport, Report};
use crate::runner::{self, RunError};
use crate::sim::Options;
use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::HashMap;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

mod grade;
mod link;
mod verify;

#[derive(Parser, Debug)]
#[command(
    name = "rigidlab",
    version,
    about = "A 2D rigid-body sandbox that checks rapier2d against the engineering-dynamics textbook."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The window's level library (with no command, or before `play`): this folder; by
    /// default ./levels, else a levels folder beside the program, else the one compiled in.
    #[arg(long, value_name = "DIR")]
    pub levels: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run levels headless and check them (exit 0: all pass, 1: a check failed, 2: bad input).
    Check {
        /// Level files or folders (searched recursively for *.ron).
        #[arg(required = true)]
        paths: Vec<PathBuf>,
        /// Print the JSON report instead of the table.
        #[arg(long)]
        json: bool,
        /// Grade a student's answer to a question: --answer ID=VALUE, with or without a unit
        /// (v_D=523.4in/s, omega=62rad/s, T=79.7ft*lb/s), converted to the question's unit
        /// (repeatable).
        #[arg(long = "answer", value_parser = parse_answer)]
        answers: Vec<(String, String)>,
        /// Print each level's worked solution under its questions (the JSON's `solution`).
        #[arg(long)]
        solution: bool,
        /// Do not search finer settings for a failing level (by default the cheapest settings
        /// that pass, up to 32x the level's cost and 2 s of estimated runs, are reported under
        /// it as its advice).
        #[arg(long)]
        no_advice: bool,
        /// How much the advice may search a level, in the run budget's estimated seconds
        /// (docs/cli.md; default 2, about 2 s on an idle 2-core machine): an estimate, not wall
        /// time, so the advice is the same on a busy machine. A level whose own run takes
        /// seconds needs more to be searched through.
        #[arg(long, alias = "advice-seconds", value_name = "S", value_parser = parse_seconds, default_value_t = crate::study::advice::SEARCH_COST_S)]
        advice_cost: f64,
        /// A student id: a level with parameters runs this student's variant (the same numbers
        /// for the same id and level file everywhere; docs/levels.md#variants-from-a-student-id).
        #[arg(long, value_name = "ID")]
        student: Option<String>,
        #[command(flatten)]
        solver: SolverArgs,
    },
    /// Run every corner of a parameterized level's ranges and N random variants; report each
    /// that fails with its values and advice (exit 0: all pass, 1: one fails, 2: bad input).
    Verify {
        level: PathBuf,
        /// How many random variants to run besides the nominal one and the corners.
        #[arg(long, default_value_t = 20)]
        variants: usize,
        /// The random variants' seed: variant i is the one of student id `verify:SEED:i`.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Print JSON instead of the text report.
        #[arg(long)]
        json: bool,
        /// Do not search settings that pass for a failing variant.
        #[arg(long)]
        no_advice: bool,
        /// How much the advice may search each failing variant (as `check --advice-cost`).
        #[arg(long, value_name = "S", value_parser = parse_seconds, default_value_t = crate::study::advice::SEARCH_COST_S)]
        advice_cost: f64,
        #[command(flatten)]
        solver: SolverArgs,
    },
    /// Grade a class's answers (answers.csv: student,level,question,answer), each against the
    /// student's own variant; write grades.csv and a gradebook to import (exit 0: every row
    /// graded, 1: some rows bad, reported by line, the rest graded, 2: nothing written).
    Grade {
        /// A level file or a folder of levels (its *.ron files, sorted).
        assignment: PathBuf,
        /// The answers: a CSV file whose header names student, level, question and answer.
        answers: PathBuf,
        /// grades.csv to write, one row per answer; never over an existing file.
        #[arg(long)]
        out: PathBuf,
        /// The gradebook to write (a row per student, a column per level and the total);
        /// default: beside --out, NAME_gradebook.csv; never over an existing file.
        #[arg(long)]
        gradebook: Option<PathBuf>,
        /// Do not run each variant (by default each is run once, and a variant the engine
        /// fails is warned about; the grades do not depend on the run).
        #[arg(long)]
        no_run: bool,
    },
    /// Run one level and write its per-step snapshots.
    Run {
        level: PathBuf,
        /// A student id: run this student's variant of a level with parameters.
        #[arg(long, value_name = "ID")]
        student: Option<String>,
        /// Write bodies to FILE and joints/contacts/springs beside it (FILE_joints.csv, ...),
        /// each whole once the run is complete; none of them may be the level.
        #[arg(long)]
        csv: Option<PathBuf>,
        #[command(flatten)]
        solver: SolverArgs,
    },
    /// Open one level, or an assignment (its folder or its assignment.ron), in the sandbox
    /// window.
    Play { level: PathBuf },
    /// Print the web page's address that carries LEVEL whole (#level=...), to hand out; exit 2
    /// when the level does not load.
    Link {
        level: PathBuf,
        /// The page's address (where web/dist is served).
        #[arg(long, default_value = link::DEFAULT_BASE)]
        base: String,
    },
    /// Studies: what accuracy costs (`accuracy`), whether hard cases stay stable (`stability`).
    Study {
        #[command(subcommand)]
        study: crate::study::StudyCommand,
    },
    /// Draw a level at a time into a PNG through the real renderer.
    Render {
        level: PathBuf,
        /// Simulated time to draw, s.
        #[arg(long, default_value_t = 0.0)]
        time: f64,
        /// The image to write: PNG only (FILE.png), written whole.
        #[arg(long)]
        out: PathBuf,
        /// Draw even when stepping to --time is estimated past the time or memory budget
        /// (runner::budget), which otherwise refuses it.
        #[arg(long)]
        allow_long: bool,
    },
}

/// Overrides of the level's solver settings.
#[derive(Args, Debug, Clone, Default)]
pub struct SolverArgs {
    /// Physics step, s.
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Substeps per step (rapier's num_solver_iterations).
    #[arg(long)]
    pub substeps: Option<usize>,
    /// Solver iterations per substep (rapier's num_internal_pgs_iterations and
    /// num_internal_stabilization_iterations: the biased and the unbiased sweeps).
    #[arg(long)]
    pub iterations: Option<usize>,
    /// Turn every effect stage on (colliders, CCD, sleeping, ...) to compare the cost.
    #[arg(long)]
    pub all_effects: bool,
    /// Cut each rapier call at the first time of impact, so an impact's normal and lever arms
    /// are those of the touching instant whatever the gap it approached from (the default for
    /// scenes of up to 64 moving bodies; this asks for it in larger ones).
    #[arg(long, conflicts_with = "no_impact_cuts")]
    pub impact_cuts: bool,
    /// Leave impacts to rapier's speculative contact (made within 2 cm and bounced up to a step
    /// before the bodies touch, with the normal of the approach): to measure the difference.
    #[arg(long)]
    pub no_impact_cuts: bool,
    /// Run even when the run is estimated past the time or memory budget (runner::budget:
    /// 600 s, 4096 MB), which otherwise refuses it.
    #[arg(long)]
    pub allow_long: bool,
    /// The engine's floating point: f32 (rapier2d) or f64 (rapier2d-f64); default: the
    /// level's world.precision.
    #[arg(long, value_parser = parse_precision)]
    pub precision: Option<level::Precision>,
    /// The physics engine: rapier or box2d (Box2D v3, docs/engines.md); default: the level's
    /// world.engine.
    #[arg(long, value_parser = parse_engine)]
    pub engine: Option<level::PhysicsEngine>,
}

fn parse_engine(s: &str) -> Result<level::PhysicsEngine, String> {
    match s {
        "rapier" => Ok(level::PhysicsEngine::Rapier),
        "box2d" => Ok(level::PhysicsEngine::Box2d),
        _ => Err(format!("\"{s}\": write rapier or box2d")),
    }
}

fn parse_precision(s: &str) -> Result<level::Precision, String> {
    match s {
        "f32" => Ok(level::Precision::F32),
        "f64" => Ok(level::Precision::F64),
        _ => Err(format!("\"{s}\": write f32 or f64")),
    }
}

impl SolverArgs {
    /// Refuses a run estimated past the time or memory budget, unless `--allow-long`.
    pub fn budget(&self, scene: &level::Scene, opts: &Options) -> Result<(), LevelError> {
        if self.allow_long {
            return Ok(());
        }
        runner::Estimate::of(&scene.level, opts, runner::Mode::Check, None)
            .within_budget(&scene.file)
    }

    pub fn options(&self) -> Result<Options, String> {
        if let Some(dt) = self.dt {
            if !(dt.is_finite() && dt > 0.0 && dt <= 0.1) {
                return Err(format!(
                    "error: --dt {dt}: the step must be greater than 0 and at most 0.1 s\n  help: e.g. --dt 0.004166 (1/240 s)"
                ));
            }
        }
        for (flag, n) in [
            ("--substeps", self.substeps),
            ("--iterations", self.iterations),
        ] {
            if n.is_some_and(|n| n == 0 || n > 1000) {
                return Err(format!(
                    "error: {flag} {}: out of range\n  help: give a number from 1 to 1000",
                    n.unwrap_or(0)
                ));
            }
        }
        Ok(Options {
            dt: self.dt,
            substeps: self.substeps,
            solver_iterations: self.iterations,
            all_effects: self.all_effects,
            substepping: None,
            precision: self.precision,
            engine: self.engine,
            spin_split: crate::sim::SpinSplit::Rule,
            impact_cuts: if self.impact_cuts {
                Some(true)
            } else if self.no_impact_cuts {
                Some(false)
            } else {
                None
            },
        })
    }
}

fn parse_answer(s: &str) -> Result<(String, String), String> {
    let (id, v) = s.split_once('=').ok_or("write --answer ID=VALUE")?;
    // The number is read now (a typo fails before any run); its unit once the question is known.
    crate::questions::units::answer_in(v, "1").or_else(|e| {
        if e.contains("does not start with a number") || e.contains("finite") {
            Err(e)
        } else {
            Ok(0.0)
        }
    })?;
    Ok((id.trim().to_string(), v.trim().to_string()))
}

/// The students' answers for one level, each converted to its question's unit.
fn answers_for(
    scene: &level::Scene,
    answers: &HashMap<String, String>,
) -> Result<HashMap<String, f64>, String> {
    let mut out = HashMap::new();
    for q in &scene.level.questions {
        if let Some(text) = answers.get(&q.id) {
            let v = crate::questions::units::answer_to(q, &scene.level, text).map_err(|e| {
                format!(
                    "error: --answer {}={text}: {e}\n  help: give the answer in {} or a unit of the same kind",
                    q.id, q.unit
                )
            })?;
            out.insert(q.id.clone(), v);
        }
    }
    Ok(out)
}

/// `--advice-cost`: a positive, finite number of (estimated) seconds.
fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!(
            "`{s}` is not a positive number of seconds (for example 2 or 30)"
        )),
    }
}

const BAD_INPUT: u8 = 2;

pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        None => sandbox(cli.levels),
        Some(Command::Check {
            paths,
            json,
            answers,
            solution,
            no_advice,
            advice_cost,
            student,
            solver,
        }) => check(
            &paths,
            (json, solution),
            answers,
            (!no_advice).then_some(advice_cost),
            &pick(student),
            &solver,
        ),
        Some(Command::Verify {
            level,
            variants,
            seed,
            json,
            no_advice,
            advice_cost,
            solver,
        }) => verify::verify(verify::VerifyArgs {
            level: &level,
            variants,
            seed,
            json,
            advice: (!no_advice).then_some(advice_cost),
            solver: &solver,
        }),
        Some(Command::Grade {
            assignment,
            answers,
            out,
            gradebook,
            no_run,
        }) => grade::grade(grade::GradeArgs {
            assignment: &assignment,
            answers: &answers,
            out: &out,
            gradebook: gradebook.as_deref(),
            no_run,
        }),
        Some(Command::Run {
            level,
            student,
            csv,
            solver,
        }) => run(&level, &pick(student), csv, &solver),
        Some(Command::Play { level }) => play(level, cli.levels),
        Some(Command::Link { level, base }) => link::link(&level, &base),
        Some(Command::Study { study }) => crate::study::main(study),
        Some(Command::Render {
            level,
            time,
            out,
            allow_long,
        }) => render(level, time, out, allow_long),
    }
}

/// The variant `--student` asks for (the nominal one without it).
fn pick(student: Option<String>) -> level::params::Pick {
    student.map_or(level::params::Pick::Nominal, level::params::Pick::Student)
}

fn bad(e: impl std::fmt::Display) -> ExitCode {
    stderr!("{e}");
    ExitCode::from(BAD_INPUT)
}

fn check(
    paths: &[PathBuf],
    (json, solution): (bool, bool),
    answer_list: Vec<(String, String)>,
    advice: Option<f64>,
    pick: &level::params::Pick,
    solver: &SolverArgs,
) -> ExitCode {
    let opts = match solver.options() {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let answers = match unique_answers(answer_list) {
        Ok(a) => a,
        Err(e) => return bad(e),
    };
    let (files, bad_manifests) = match level::collect_levels(paths) {
        Ok(f) => f,
        Err(e) => return bad(e),
    };
    if files.is_empty() && bad_manifests.is_empty() {
        return bad("no level files (*.ron) found in the given paths");
    }
    // An assignment's manifest that does not read is bad input, reported as a row of its own.
    let mut bad_input = !bad_manifests.is_empty();
    let mut bad_answer = false;
    // Questions of levels not run because an answer to them could not be read.
    let mut asked_elsewhere: Vec<String> = Vec::new();
    let mut levels = Vec::new();
    // The variant each level ran (a level with parameters), for the JSON report.
    let mut variants = Vec::new();
    for e in &bad_manifests {
        stderr!("{e}");
        levels.push(failed(&e.file, &e.to_string()));
        variants.push(None);
    }
    for f in &files {
        let mut played = None;
        let mut picked = None;
        let run = load_played(f, pick, &answers, &mut bad_answer)
            .and_then(|(scene, control, variant)| {
                played = control;
                picked = variant;
                solver.budget(&scene, &opts).map(|()| scene)
            })
            .map_err(RunError::Level)
            .and_then(|scene| {
                let graded = match answers_for(&scene, &answers) {
                    Ok(a) => a,
                    Err(e) => {
                        // Not run: a report of a level whose answer could not be read must not
                        // say it passed (the table, the JSON and the exit code agree).
                        stderr!("{e}");
                        bad_answer = true;
                        asked_elsewhere.extend(scene.level.questions.iter().map(|q| q.id.clone()));
                        return Ok(failed(f, e.trim_start_matches("error: ")));
                    }
                };
                let bar = progress_bar(&scene, &opts);
                let r = runner::run_graded(&scene, &opts, &graded, |step| tick(&bar, step));
                if let Some(b) = bar {
                    b.finish_and_clear();
                }
                let r = r.map(|report| with_help(report, &scene.level, solution));
                let Some(cost_s) = advice else {
                    return r;
                };
                // A level the engine failed (or that stopped early): the cheapest settings
                // that pass, searched within a bound (study::advice).
                match r {
                    Ok(mut report) if crate::study::advice::engine_failed(&report) => {
                        report.advice = Some(crate::study::advice::advise_within(
                            &scene,
                            &opts,
                            Some(&report),
                            cost_s,
                        ));
                        report.other_engine =
                            Some(crate::study::other_engine::other_engine(&scene, &opts));
                        Ok(report)
                    }
                    Err(e @ RunError::Sim { .. }) => {
                        stderr!("{e}");
                        let mut report = failed(f, &e.to_string());
                        report.advice = Some(crate::study::advice::advise_within(
                            &scene, &opts, None, cost_s,
                        ));
                        report.engine = Some(runner::engine_of(&scene, &opts));
                        report.other_engine =
                            Some(crate::study::other_engine::other_engine(&scene, &opts));
                        Ok(report)
                    }
                    other => other,
                }
            });
        variants.push(picked);
        match run {
            Ok(mut r) => {
                if let (Some(c), Some((control, value, student))) = (r.challenge.as_mut(), &played)
                {
                    c.set_control(control, *value, *student);
                }
                if let Some((control, ..)) = &played {
                    asked_elsewhere.push(control.name.clone());
                }
                levels.push(r);
            }
            Err(RunError::Level(e)) => {
                stderr!("{e}");
                bad_input = true;
                levels.push(failed(f, &e.to_string()));
            }
            Err(e @ RunError::Sim { .. }) => {
                stderr!("{e}");
                levels.push(failed(f, &e.to_string()));
            }
        }
    }
    if names_unknown_questions(&answers, &levels, &asked_elsewhere) {
        bad_input = true;
    }
    let report = Report {
        passed: levels.iter().all(|l| l.passed),
        levels,
    };
    let code = if bad_input || bad_answer {
        ExitCode::from(BAD_INPUT)
    } else if report.passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    };
    let text = if json {
        json_with_variants(&report, &variants, pick)
    } else {
        report::table(&report)
    };
    report::print(&text, code)
}

/// The `--answer ID=VALUE` pairs by question id; an id given twice is an error.
fn unique_answers(answer_list: Vec<(String, String)>) -> Result<HashMap<String, String>, String> {
    let mut answers = HashMap::new();
    for (id, v) in answer_list {
        if let Some(first) = answers.insert(id.clone(), v.clone()) {
            return Err(format!(
                "error: --answer {id} is given twice ({first} and {v})\n  help: give one answer per question"
            ));
        }
    }
    Ok(answers)
}

/// Whether an `--answer` names no question of the levels run (reported on stderr):
/// a student's answer to a question that is not there would otherwise be silently ignored.
fn names_unknown_questions(
    answers: &HashMap<String, String>,
    levels: &[LevelReport],
    asked_elsewhere: &[String],
) -> bool {
    let asked: Vec<&str> = levels
        .iter()
        .flat_map(|l| l.questions.iter().map(|q| q.id.as_str()))
        .chain(asked_elsewhere.iter().map(String::as_str))
        .collect();
    let mut unknown: Vec<&str> = answers
        .keys()
        .map(String::as_str)
        .filter(|id| !asked.contains(id))
        .collect();
    if !unknown.is_empty() {
        unknown.sort_unstable();
        stderr!(
            "error: --answer names no question in the levels run: {}\n  help: the questions are: {}",
            unknown.join(", "),
            if asked.is_empty() { "(none)".to_string() } else { asked.join(", ") }
        );
        return true;
    }
    false
}

/// A level's report with its first hint, when a student's answer to it was wrong, and its
/// worked solution, when asked for (`solution`).
fn with_help(mut report: LevelReport, level: &level::Level, solution: bool) -> LevelReport {
    let wrong = report
        .questions
        .iter()
        .any(|q| q.student.as_ref().is_some_and(|s| !s.passed));
    if wrong {
        report.hint = level.hints.first().cloned();
    }
    if solution && !level.solution.trim().is_empty() {
        report.solution = Some(level.solution.clone());
    }
    report
}

/// The JSON report with, in each level with parameters, the variant it ran: `"variant":
/// {"student", "values": [{"name", "value", "unit"}], "shown"}` (`student` absent for the nominal
/// variant), so a script grading a student's `--answer`s knows the numbers they were given.
fn json_with_variants(
    report: &Report,
    variants: &[Option<level::params::Variant>],
    pick: &level::params::Pick,
) -> String {
    let mut v = serde_json::to_value(report).expect("reports serialize");
    let student = match pick {
        level::params::Pick::Student(id) => Some(id.trim().to_string()),
        _ => None,
    };
    if let Some(levels) = v["levels"].as_array_mut() {
        for (l, variant) in levels.iter_mut().zip(variants) {
            let Some(variant) = variant else { continue };
            let values: Vec<serde_json::Value> = variant
                .values
                .iter()
                .map(|(name, value, unit)| {
                    serde_json::json!({"name": name, "value": value, "unit": unit})
                })
                .collect();
            let mut picked = serde_json::json!({"values": values, "shown": variant.shown});
            if let Some(id) = &student {
                picked["student"] = serde_json::Value::from(id.clone());
            }
            l["variant"] = picked;
        }
    }
    report::json(&v)
}

/// The control of a challenge as a run was made with it: the control, its value in its unit,
/// and whether that value is the student's (`--answer NAME=VALUE`) or the worked one.
type Played = (level::params::Control, f64, bool);

/// [`load_warned`], and for a level with a challenge the variant with its control set: to the
/// student's value when `--answer` names the control (converted to its unit; one that cannot be
/// read sets `bad_answer` and is an error), else to the worked value.
fn load_played(
    path: &std::path::Path,
    pick: &level::params::Pick,
    answers: &HashMap<String, String>,
    bad_answer: &mut bool,
) -> Result<(level::Scene, Option<Played>, Option<level::params::Variant>), LevelError> {
    let probe = level::load_variant(path, pick)?;
    let Some((control, _)) = probe.control else {
        return load_warned(path, pick).map(|(s, v)| (s, None, v));
    };
    let given = match answers.get(&control.name) {
        None => None,
        Some(text) => {
            let unit = if control.unit.is_empty() {
                "1"
            } else {
                control.unit.as_str()
            };
            let v = crate::questions::units::answer_in(text, unit).map_err(|e| {
                *bad_answer = true;
                LevelError::new(
                    path,
                    (0, 0),
                    format!("--answer {}={text}: {e}", control.name),
                    format!(
                        "give the control in {} or a unit of the same kind",
                        if control.unit.is_empty() {
                            "a plain number"
                        } else {
                            control.unit.as_str()
                        }
                    ),
                )
            })?;
            Some(v)
        }
    };
    let loaded = level::load_challenge(path, pick, given)?;
    for w in &loaded.warnings {
        stderr!("{w}");
    }
    if let (level::params::Pick::Student(id), Some(v)) = (pick, &loaded.variant) {
        stderr!("{}: student {}: {}", path.display(), id.trim(), v.shown);
    }
    let played = loaded.control.map(|(c, v)| (c, v, given.is_some()));
    Ok((loaded.scene, played, loaded.variant))
}

/// Loads a level (the picked variant of a level with parameters) and prints its warnings (legal
/// but probably not meant) to stderr, and a student's variant: its values and statement.
fn load_warned(
    path: &std::path::Path,
    pick: &level::params::Pick,
) -> Result<(level::Scene, Option<level::params::Variant>), LevelError> {
    let loaded = level::load_variant(path, pick)?;
    for w in loaded.warnings {
        stderr!("{w}");
    }
    if let (level::params::Pick::Student(id), Some(v)) = (pick, &loaded.variant) {
        stderr!(
            "{}: student {}: {}
  statement: {}",
            path.display(),
            id.trim(),
            v.shown,
            loaded.scene.level.statement
        );
    }
    Ok((loaded.scene, loaded.variant))
}

/// Runs estimated to take longer than this many seconds (runner::budget) show a progress bar.
const PROGRESS_FROM: f64 = 5.0;

/// A progress bar with the steps and the estimated time for a long run, drawn only when stderr is
/// a terminal: a pipe or a CI log stays silent.
fn progress_bar(scene: &level::Scene, opts: &Options) -> Option<ProgressBar> {
    let estimate = runner::Estimate::of(&scene.level, opts, runner::Mode::Check, None);
    if estimate.seconds < PROGRESS_FROM || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::with_draw_target(
        Some(estimate.work.steps as u64),
        ProgressDrawTarget::stderr(),
    );
    bar.set_style(
        ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} steps  {elapsed} (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(scene.file.display().to_string());
    Some(bar)
}

fn tick(bar: &Option<ProgressBar>, step: u64) {
    if let Some(b) = bar {
        b.set_position(step);
    }
}

fn failed(file: &std::path::Path, error: &str) -> LevelReport {
    LevelReport::failed(file, error)
}

fn run(
    path: &std::path::Path,
    pick: &level::params::Pick,
    csv: Option<PathBuf>,
    solver: &SolverArgs,
) -> ExitCode {
    let opts = match solver.options() {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let scene =
        match load_warned(path, pick).and_then(|(s, _)| solver.budget(&s, &opts).map(|()| s)) {
            Ok(s) => s,
            Err(e) => return bad(e),
        };
    if let Some(out) = csv.as_deref() {
        if let Err(e) = csv_out(path, out) {
            return bad(e);
        }
    }
    let mut writer = match csv.as_deref().map(CsvWriter::create).transpose() {
        Ok(w) => w,
        Err(e) => return bad(format!("cannot write the CSV file: {e}")),
    };
    let mut io_error = None;
    let bar = progress_bar(&scene, &opts);
    let result = runner::run_scene(&scene, &opts, &HashMap::new(), |s| {
        tick(&bar, s.step);
        if let Some(w) = writer.as_mut() {
            if let Err(e) = w.write(s) {
                io_error.get_or_insert(e);
            }
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(w) = writer {
        if let Err(e) = w.finish() {
            io_error.get_or_insert(e);
        }
    }
    if let Some(e) = io_error {
        return bad(format!("cannot write the CSV file: {e}"));
    }
    match result {
        Ok(r) => {
            let code = if r.passed {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            };
            report::print(
                &report::table(&Report {
                    passed: r.passed,
                    levels: vec![r],
                }),
                code,
            )
        }
        Err(RunError::Level(e)) => bad(e),
        Err(e) => {
            stderr!("{e}");
            ExitCode::from(1)
        }
    }
}

/// `run --csv FILE`: none of the files the run writes (FILE and its joints, contacts and springs
/// beside it) may be the level it runs, by canonical path or inode, or a folder. Checked before
/// the run, so a refused `--csv` touches nothing.
fn csv_out(level: &std::path::Path, out: &std::path::Path) -> Result<(), String> {
    for f in report::csv_files(out) {
        if crate::files::same_file(level, &f) {
            return Err(format!(
                "error: --csv {}: the run would write {}, the level file it runs\n  help: give another file for the CSV",
                out.display(),
                f.display()
            ));
        }
    }
    if out.is_dir() {
        return Err(format!(
            "error: --csv {} is a folder\n  help: give a file name, e.g. {}",
            out.display(),
            out.join("run.csv").display()
        ));
    }
    // Only a CSV an earlier run wrote is replaced or removed (its first line is rigidlab's
    // header); a user's file under one of the names is refused before the run.
    for (kind, f) in report::csv_files(out).iter().enumerate() {
        if let Err(why) = report::csv_ours(f, kind) {
            return Err(format!(
                "error: --csv {}: {why}; the run would replace or remove it\n  help: give another name for the CSV, or move or delete {} yourself if you no longer need it",
                out.display(),
                f.display()
            ));
        }
    }
    Ok(())
}

/// Where a window cannot open, say so and point to the headless commands.
pub fn no_display_message() -> String {
    "rigidlab: no display found (DISPLAY/WAYLAND_DISPLAY are not set), so the sandbox window cannot open.\n\
     Run the exercises headless instead:\n    cargo run --release -- check levels\n\
     or open a virtual display first:  Xvfb :99 & DISPLAY=:99 cargo run --release"
        .to_string()
}

/// `--levels DIR`: a folder, or what is wrong with it (exit 2).
fn levels_folder(dir: Option<&std::path::Path>) -> Result<(), String> {
    match dir {
        Some(d) if !d.is_dir() => Err(format!(
            "error: --levels {}: no such folder (give the folder that holds the level library)",
            d.display()
        )),
        _ => Ok(()),
    }
}

fn has_display() -> bool {
    std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| !d.is_empty())
}

#[cfg(feature = "app")]
fn sandbox(levels: Option<PathBuf>) -> ExitCode {
    if let Err(e) = levels_folder(levels.as_deref()) {
        return bad(e);
    }
    if !has_display() {
        stderr!("{}", no_display_message());
        return ExitCode::from(BAD_INPUT);
    }
    match crate::app::sandbox(levels, None) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => bad(e),
    }
}

#[cfg(feature = "app")]
fn play(level: PathBuf, levels: Option<PathBuf>) -> ExitCode {
    if let Err(e) = levels_folder(levels.as_deref()) {
        return bad(e);
    }
    if level::assignment::is_assignment(&level) {
        return play_assignment(&level, levels);
    }
    if let Err(e) = level::load(&level) {
        return bad(e);
    }
    if !has_display() {
        stderr!("{}", no_display_message());
        return ExitCode::from(BAD_INPUT);
    }
    match crate::app::sandbox(levels, Some(level)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => bad(e),
    }
}

/// `play ASSIGNMENT`: the assignment must read (exit 2 otherwise); a level of it that does not
/// load is said on stderr and listed in the window with why.
#[cfg(feature = "app")]
fn play_assignment(path: &std::path::Path, levels: Option<PathBuf>) -> ExitCode {
    let a = match level::assignment::Assignment::load(path) {
        Ok(a) => a,
        Err(e) => return bad(e),
    };
    let list = crate::app::panels::assignment_list::AssignmentList::read(&a);
    for e in list.errors() {
        stderr!("warning: a level of the assignment does not load:\n{e}");
    }
    if !has_display() {
        stderr!("{}", no_display_message());
        return ExitCode::from(BAD_INPUT);
    }
    match crate::app::sandbox_assignment(levels, list) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => bad(e),
    }
}

/// `render --time`: a finite time >= 0 whose steps (the window steps at the level's dt) are
/// estimated within the run budget, unless `--allow-long`.
fn render_budget(scene: &level::Scene, time: f64, allow_long: bool) -> Result<(), String> {
    if !(time.is_finite() && time >= 0.0) {
        return Err("error: --time must be a finite time >= 0 s".into());
    }
    if allow_long {
        return Ok(());
    }
    let steps = (time / scene.level.world.dt).round();
    runner::Estimate::of(
        &scene.level,
        &Options::default(),
        runner::Mode::Render,
        Some(steps),
    )
    .within_budget(&scene.file)
    .map_err(|e| e.to_string())
}

/// `render --out`: the renderer writes PNG only, never over the level it draws, and over an
/// existing file only when it is an image rigidlab drew (its mark, `crate::files::Mark`). Checked
/// before anything is read or written, so a refused `--out` leaves any file there as it was.
fn render_out(level: &std::path::Path, out: &std::path::Path) -> Result<(), String> {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if ext.as_deref() != Some("png") {
        return Err(format!(
            "error: --out {}: rigidlab render writes PNG images only\n  help: give a file name ending in .png",
            out.display()
        ));
    }
    if crate::files::same_file(level, out) {
        return Err(format!(
            "error: --out {} is the level file being drawn\n  help: give another file for the image",
            out.display()
        ));
    }
    crate::files::replaceable(out, crate::files::Mark::Png).map_err(|e| format!("error: --out {e}"))
}

#[cfg(feature = "app")]
fn render(level: PathBuf, time: f64, out: PathBuf, allow_long: bool) -> ExitCode {
    let scene = match render_scene(&level, time, &out, allow_long) {
        Ok(s) => s,
        Err(code) => return code,
    };
    match crate::app::render(&scene, time, &out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => bad(e),
    }
}

#[cfg(not(feature = "app"))]
fn no_app() -> ExitCode {
    let _ = has_display;
    bad("this rigidlab was built without the sandbox (the `app` feature). Headless: rigidlab check levels")
}

#[cfg(not(feature = "app"))]
fn sandbox(levels: Option<PathBuf>) -> ExitCode {
    if let Err(e) = levels_folder(levels.as_deref()) {
        return bad(e);
    }
    no_app()
}

#[cfg(not(feature = "app"))]
fn play(level: PathBuf, levels: Option<PathBuf>) -> ExitCode {
    // Bad input is bad input, with or without the window.
    if let Err(e) = levels_folder(levels.as_deref()) {
        return bad(e);
    }
    if level::assignment::is_assignment(&level) {
        if let Err(e) = level::assignment::Assignment::load(&level) {
            return bad(e);
        }
    }
    no_app()
}

#[cfg(not(feature = "app"))]
fn render(level: PathBuf, time: f64, out: PathBuf, allow_long: bool) -> ExitCode {
    match render_scene(&level, time, &out, allow_long) {
        Ok(_) => no_app(),
        Err(code) => code,
    }
}

/// What `render` checks before drawing, with or without the sandbox: the output (a PNG that is
/// not the level), the level, and the run's budget up to `time`.
fn render_scene(
    level: &std::path::Path,
    time: f64,
    out: &std::path::Path,
    allow_long: bool,
) -> Result<level::Scene, ExitCode> {
    render_out(level, out).map_err(bad)?;
    let scene = level::load(level).map_err(bad)?;
    render_budget(&scene, time, allow_long).map_err(bad)?;
    Ok(scene)
}
