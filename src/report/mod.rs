//! Stage 5: reports. The JSON contract, the terminal table and the per-step CSV.

use crate::checks::CheckResult;
use crate::files::Pending;
use crate::questions::{ChallengeResult, QuestionResult};
use crate::snapshot::Snapshot;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `rigidlab check --json`: `{"passed", "levels": [...]}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    pub passed: bool,
    pub levels: Vec<LevelReport>,
}

/// One level's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LevelReport {
    pub file: String,
    pub title: String,
    pub passed: bool,
    pub steps: u64,
    pub sim_time: f64,
    pub wall_ms: f64,
    pub effects: Vec<String>,
    /// The engine the run used (`--engine`, else the level's `world.engine`; None when the
    /// level could not be loaded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub engine: Option<crate::level::PhysicsEngine>,
    /// The settings the run used, resolved from the level and the command line (None when the
    /// level could not be loaded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settings: Option<crate::sim::Settings>,
    pub checks: Vec<CheckResult>,
    pub questions: Vec<QuestionResult>,
    /// A level with a challenge: its goal's verdict for the value run (docs/cli.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub challenge: Option<ChallengeResult>,
    /// Set when the run stopped early (explosion, non-finite state).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// For a level the engine failed: the cheapest settings that pass, or that none within the
    /// search's bound does (`study::advice`; `rigidlab check --no-advice` leaves it out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub advice: Option<Advice>,
    /// For a level the engine failed, with its advice: the same level on the other engine at
    /// the same settings (`study::advice::other_engine`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub other_engine: Option<OtherEngine>,
    /// The level's first hint, when a student's answer (`--answer`) to it was wrong.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hint: Option<String>,
    /// The level's worked solution, when `check --solution` asked for it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solution: Option<String>,
}

/// What a failing level's settings search found (`study::advice`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Advice {
    /// The cheapest settings tried at which every check and question passes.
    Settings {
        settings: AdvisedSettings,
        /// Estimated cost against the level's own run: steps x substeps, f64 at 1.25x f32.
        cost_ratio: f64,
        /// The advised run's wall time against the failing run's, measured in this check (None
        /// when the failing run stopped early): the table shows it, the JSON does not, so that
        /// the JSON's advice is the same on every machine (a busy machine changes wall times).
        #[serde(skip)]
        wall_ratio: Option<f64>,
    },
    /// No candidate up to `none_within` times the level's own cost passes; `why` says what
    /// that means. `within_estimated_seconds` is set when the search's bound, in the run
    /// budget's estimated seconds (`study::advice::SEARCH_COST_S`), ran out before the cost
    /// ratios did: the costlier candidates were not tried.
    NoneWithin {
        none_within: f64,
        why: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        within_estimated_seconds: Option<f64>,
        /// The published engine gaps (docs/known-gaps.md) the scene matches, when the search
        /// ended without a passing setting (`study::gaps`); `why` names them too.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        known_gaps: Vec<KnownGapRef>,
    },
}

/// A failing level run on the other engine (rapier for Box2D, Box2D for rapier) at the same
/// settings: whether it passes there, fails too, or is refused (the feature it lacks).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OtherEngine {
    /// The other engine.
    pub engine: crate::level::PhysicsEngine,
    pub verdict: OtherVerdict,
    /// What was found: the failing checks and questions, the refusal with its place in the
    /// file, why the run stopped, or that the engine is not in this build.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub why: String,
}

/// [`OtherEngine`]'s verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OtherVerdict {
    /// Every check and question passes on the other engine.
    Passes,
    /// It fails there too.
    Fails,
    /// The other engine refuses a feature of the level (before any run).
    Refused,
    /// The run stopped early (an explosion, a non-finite state).
    Stopped,
    /// The other engine is not in this build (the `box2d` feature, or the web page).
    NotBuilt,
}

impl OtherEngine {
    /// The table's line under a failing level, after its advice.
    pub fn line(&self) -> String {
        let e = self.engine.name();
        match self.verdict {
            OtherVerdict::Passes => format!(
                "advice: on {e} at the same settings this level passes: the failure is the \
                 engine's, not the level's (--engine {e})"
            ),
            OtherVerdict::Fails => format!(
                "advice: on {e} at the same settings it fails too: {}",
                self.why
            ),
            OtherVerdict::Refused => format!("advice: {e} refuses this level: {}", self.why),
            OtherVerdict::Stopped => format!(
                "advice: on {e} at the same settings the run stopped: {}",
                self.why
            ),
            OtherVerdict::NotBuilt => format!(
                "advice: {e} is not in this build, so it was not tried: {}",
                self.why
            ),
        }
    }
}

/// A published engine gap the advice names: its stable id, its heading in docs/known-gaps.md,
/// and whether a setting gets past it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KnownGapRef {
    pub id: String,
    pub heading: String,
    pub setting_gets_past: bool,
}

/// Solver settings the advice names (the level's solver iterations and effects unchanged).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AdvisedSettings {
    /// The physics step, s (`--dt`).
    pub dt: f64,
    /// Substeps per step (`--substeps`).
    pub substeps: usize,
    /// The engine's floating point (`--precision`).
    pub precision: crate::level::Precision,
}

impl Advice {
    /// The table's line under a failing level.
    pub fn line(&self) -> String {
        match self {
            Advice::Settings {
                settings: s,
                cost_ratio,
                wall_ratio,
            } => format!(
                "advice: passes with --dt {} --substeps {} --precision {} ({cost_ratio}x the level's cost, estimated{})",
                s.dt,
                s.substeps,
                match s.precision {
                    crate::level::Precision::F32 => "f32",
                    crate::level::Precision::F64 => "f64",
                },
                wall_ratio.map_or(String::new(), |w| format!("; {w:.1}x its wall time here"))
            ),
            Advice::NoneWithin { why, .. } => format!("advice: {why}"),
        }
    }
}

impl LevelReport {
    /// The report of a level that could not be loaded or run: failed, with why.
    pub fn failed(file: &std::path::Path, error: &str) -> LevelReport {
        LevelReport {
            file: file.display().to_string(),
            title: String::new(),
            passed: false,
            steps: 0,
            sim_time: 0.0,
            wall_ms: 0.0,
            effects: Vec::new(),
            engine: None,
            settings: None,
            checks: Vec::new(),
            questions: Vec::new(),
            challenge: None,
            error: Some(error.to_string()),
            advice: None,
            other_engine: None,
            hint: None,
            solution: None,
        }
    }
}

/// The terminal table: one line per level, then one per failing or noted check/question. Names
/// and other text from the level or the command line are escaped for the terminal
/// (`crate::terminal`): each field whole, newlines included, and the rest but its line breaks.
pub fn table(report: &Report) -> String {
    crate::terminal::text(&table_text(report)).into_owned()
}

/// The table's first line: the engine the levels ran on, or each engine with its number of
/// levels when they differ (`--engine`, else each level's `world.engine`); none when no level
/// ran.
fn engines_line(report: &Report) -> String {
    let mut counts: Vec<(crate::level::PhysicsEngine, usize)> = Vec::new();
    for e in report.levels.iter().filter_map(|l| l.engine) {
        match counts.iter_mut().find(|(k, _)| *k == e) {
            Some((_, n)) => *n += 1,
            None => counts.push((e, 1)),
        }
    }
    match counts.as_slice() {
        [] => String::new(),
        [(e, _)] => format!("engine: {}\n", e.name()),
        _ => {
            let each: Vec<String> = counts
                .iter()
                .map(|(e, n)| format!("{} ({n} level{})", e.name(), if *n == 1 { "" } else { "s" }))
                .collect();
            format!(
                "engines: {}; each level's row names its own\n",
                each.join(", ")
            )
        }
    }
}

fn table_text(report: &Report) -> String {
    use crate::terminal::field;
    let mut out = String::new();
    let w = report
        .levels
        .iter()
        .map(|l| l.file.len())
        .max()
        .unwrap_or(10)
        .clamp(10, 60);
    out += &engines_line(report);
    // Levels on different engines: each row names its own.
    let mixed = engines_line(report).starts_with("engines:");
    out += &format!(
        "{:<w$}  {:>6}  {:>7}  {:>8}  {:>6}  {:>9}  result\n",
        "level", "steps", "sim s", "wall ms", "checks", "questions"
    );
    for l in &report.levels {
        let cp = l.checks.iter().filter(|c| c.passed).count();
        let qp = l.questions.iter().filter(|q| q.passed).count();
        out += &format!(
            "{:<w$}  {:>6}  {:>7.3}  {:>8.1}  {:>6}  {:>9}  {}{}\n",
            field(&l.file),
            l.steps,
            l.sim_time,
            l.wall_ms,
            format!("{cp}/{}", l.checks.len()),
            format!("{qp}/{}", l.questions.len()),
            if l.passed { "pass" } else { "FAIL" },
            match l.engine {
                Some(e) if mixed => format!(" on {}", e.name()),
                _ => String::new(),
            }
        );
        if let Some(e) = &l.error {
            out += &format!("    error: {e}\n");
        }
        if let Some(a) = &l.advice {
            out += &format!("    {}\n", a.line());
        }
        if let Some(o) = &l.other_engine {
            out += &format!("    {}\n", o.line());
        }
        for c in &l.checks {
            out += &format!(
                "    {} check {:<28} {:<32} max rel err {:.2e} (tol {:.1e}){}\n",
                if c.passed { " " } else { "!" },
                c.kind,
                field(&c.subject),
                c.max_rel_error,
                c.tolerance,
                if c.note.is_empty() {
                    String::new()
                } else {
                    format!("  [{}]", c.note)
                }
            );
        }
        for q in &l.questions {
            out += &format!(
                "    {} question {:<14} expected {:>11.5} {:<6} engine {:>11.5}{} rel err {:.2e} (tol {:.1e})\n",
                if q.passed { " " } else { "!" },
                field(&q.id),
                q.expected,
                field(&q.unit),
                q.engine,
                q.analysis.map_or(String::new(), |a| format!("  analysis {a:>11.5}")),
                q.rel_error,
                q.tolerance
            );
            if !q.analysis_source.is_empty() && q.analysis.is_some() {
                out += &format!("      analysis from the {}\n", q.analysis_source);
            }
            if !q.note.is_empty() {
                out += &format!("      note: {}\n", q.note);
            }
            if let Some(s) = &q.student {
                out += &format!(
                    "      student answer {} -> {} (rel err {:.2e})\n",
                    s.answer,
                    if s.passed { "correct" } else { "wrong" },
                    s.rel_error
                );
                if let Some(m) = &s.mistake {
                    out += &format!("      typical mistake: {m}\n");
                }
            }
        }
        help_lines(&mut out, l);
        if let Some(c) = &l.challenge {
            out += &challenge_line(c);
        }
    }
    let n = report.levels.len();
    let p = report.levels.iter().filter(|l| l.passed).count();
    out += &format!("{p}/{n} levels passed\n");
    out
}

/// The level's hint and worked solution under its questions, one step per line, when the
/// report carries them.
fn help_lines(out: &mut String, l: &LevelReport) {
    if let Some(h) = &l.hint {
        *out += &format!("    hint 1: {}\n", h.trim());
    }
    if let Some(s) = &l.solution {
        *out += "    worked solution:\n";
        for line in s.lines().map(str::trim).filter(|l| !l.is_empty()) {
            *out += &format!("      {line}\n");
        }
    }
}

/// A challenge's lines in the table: the control's value and whose it is, the goal, the verdict.
fn challenge_line(c: &ChallengeResult) -> String {
    use crate::terminal::field;
    let unit = if c.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", field(&c.unit))
    };
    let mut out = format!(
        "    {} challenge {} = {}{unit} ({}; worked {}{unit}): {} -> {}\n",
        if c.success { " " } else { "!" },
        field(&c.control),
        c.value,
        if c.student { "student" } else { "worked value" },
        c.worked,
        field(&c.goal),
        c.verdict()
    );
    if !c.note.is_empty() {
        out += &format!("      note: {}\n", c.note);
    }
    out
}

/// Writes the per-step snapshots as CSV: bodies to `path`, and joints, contacts and springs
/// beside it (`<stem>_joints.csv`, `<stem>_contacts.csv`, `<stem>_springs.csv`) when the scene has them.
///
/// Each file is written to a temporary file beside it and renamed over its name only by
/// [`CsvWriter::finish`], once the run is complete: a run that fails leaves the files of an
/// earlier run as they were. A run's files go together: `finish` removes a sibling an earlier
/// run left that this run does not write (its scene has no contacts, say), so the folder never
/// mixes two runs.
pub struct CsvWriter {
    bodies: csv::Writer<Pending>,
    joints: Option<csv::Writer<Pending>>,
    contacts: Option<csv::Writer<Pending>>,
    springs: Option<csv::Writer<Pending>>,
    path: PathBuf,
}

/// The kinds of row written beside the bodies' CSV, in [`csv_files`]'s order after it.
const SIBLINGS: [&str; 3] = ["joints", "contacts", "springs"];

/// The header line of each of a run's CSV files, in [`csv_files`]'s order: bodies, joints,
/// contacts, springs. A file whose first line is its kind's header is one rigidlab wrote, and
/// the only kind of file a run replaces or removes ([`csv_ours`]).
const HEADERS: [&[&str]; 4] = [
    &[
        "step", "time", "body", "x", "y", "angle", "com_x", "com_y", "vx", "vy", "omega", "mass",
        "inertia",
    ],
    &[
        "step",
        "time",
        "joint",
        "anchor_x",
        "anchor_y",
        "impulse_x",
        "impulse_y",
        "angular_impulse",
        "motor_impulse",
        "limit_impulse",
        "force_x",
        "force_y",
        "coordinate",
    ],
    &[
        "step",
        "time",
        "body1",
        "body2",
        "point_x",
        "point_y",
        "normal_x",
        "normal_y",
        "distance",
        "normal_impulse",
        "tangent_impulse",
    ],
    &[
        "step",
        "time",
        "spring",
        "length",
        "extension",
        "tension",
        "energy",
    ],
];

/// Whether a run may write or remove `path`, the `kind`-th of [`csv_files`]: it does not exist,
/// or it is a device or FIFO the user named (written directly, nothing kept there), or a regular
/// file whose first line is that kind's header (a CSV an earlier run wrote). Anything else is
/// the user's and is refused with what it is: a file of other content (notes, a level, an
/// empty file), a link (replacing it would lose the link), a folder.
pub fn csv_ours(path: &Path, kind: usize) -> Result<(), String> {
    let meta = match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(format!("{}: {e}", path.display())),
        Ok(m) => m,
    };
    let followed = std::fs::metadata(path).ok();
    let special = |m: &std::fs::Metadata| !m.is_file() && !m.is_dir();
    if followed.as_ref().is_some_and(special) {
        return Ok(());
    }
    if meta.file_type().is_symlink() {
        return Err(format!(
            "{} is a link, which the run would replace",
            path.display()
        ));
    }
    if meta.is_dir() {
        return Err(format!("{} is a folder", path.display()));
    }
    let mut first = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| {
            use std::io::Read;
            f.take(4096).read_to_end(&mut first)
        })
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let first = first.split(|b| *b == b'\n').next().unwrap_or_default();
    let first = first.strip_suffix(b"\r").unwrap_or(first);
    if first == HEADERS[kind].join(",").as_bytes() {
        Ok(())
    } else {
        Err(format!(
            "{} exists and is not a CSV rigidlab wrote (its first line is not rigidlab's {} header)",
            path.display(),
            ["bodies", "joints", "contacts", "springs"][kind]
        ))
    }
}

fn sibling(path: &Path, suffix: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or("run".into(), |s| s.to_string_lossy().to_string());
    path.with_file_name(format!("{stem}_{suffix}.csv"))
}

/// Every file a run with `--csv path` may write: `path`, then its joints, contacts and springs
/// beside it.
pub fn csv_files(path: &Path) -> Vec<PathBuf> {
    std::iter::once(path.to_path_buf())
        .chain(SIBLINGS.iter().map(|s| sibling(path, s)))
        .collect()
}

impl CsvWriter {
    pub fn create(path: &Path) -> std::io::Result<Self> {
        let mut bodies = csv::Writer::from_writer(Pending::create(path)?);
        bodies.write_record(HEADERS[0])?;
        Ok(CsvWriter {
            bodies,
            joints: None,
            contacts: None,
            springs: None,
            path: path.to_path_buf(),
        })
    }

    fn side(
        slot: &mut Option<csv::Writer<Pending>>,
        path: PathBuf,
        header: &[&str],
    ) -> std::io::Result<()> {
        if slot.is_none() {
            let mut w = csv::Writer::from_writer(Pending::create(&path)?);
            w.write_record(header)?;
            *slot = Some(w);
        }
        Ok(())
    }

    pub fn write(&mut self, s: &Snapshot) -> std::io::Result<()> {
        let f = |x: f64| format!("{x:.9e}");
        for b in &s.bodies {
            self.bodies.write_record([
                s.step.to_string(),
                f(s.time),
                b.name.clone(),
                f(b.position.x),
                f(b.position.y),
                f(b.angle),
                f(b.com.x),
                f(b.com.y),
                f(b.velocity.x),
                f(b.velocity.y),
                f(b.omega),
                f(b.mass),
                f(b.inertia),
            ])?;
        }
        if !s.joints.is_empty() {
            Self::side(&mut self.joints, sibling(&self.path, "joints"), HEADERS[1])?;
            let w = self.joints.as_mut().expect("created above");
            for j in &s.joints {
                let force = if !s.is_initial() {
                    j.impulse_on_body2 / s.dt
                } else {
                    glam::DVec2::ZERO
                };
                w.write_record([
                    s.step.to_string(),
                    f(s.time),
                    j.name.clone(),
                    f(j.anchor.x),
                    f(j.anchor.y),
                    f(j.impulse_on_body2.x),
                    f(j.impulse_on_body2.y),
                    f(j.angular_impulse_on_body2),
                    f(j.motor_impulse),
                    f(j.limit_impulse),
                    f(force.x),
                    f(force.y),
                    f(j.coordinate),
                ])?;
            }
        }
        if !s.contacts.is_empty() {
            Self::side(
                &mut self.contacts,
                sibling(&self.path, "contacts"),
                HEADERS[2],
            )?;
            let w = self.contacts.as_mut().expect("created above");
            for c in &s.contacts {
                for p in &c.points {
                    w.write_record([
                        s.step.to_string(),
                        f(s.time),
                        s.bodies[c.body1].name.clone(),
                        s.bodies[c.body2].name.clone(),
                        f(p.point.x),
                        f(p.point.y),
                        f(c.normal.x),
                        f(c.normal.y),
                        f(p.distance),
                        f(p.normal_impulse),
                        f(p.tangent_impulse),
                    ])?;
                }
            }
        }
        if !s.springs.is_empty() {
            Self::side(
                &mut self.springs,
                sibling(&self.path, "springs"),
                HEADERS[3],
            )?;
            let w = self.springs.as_mut().expect("created above");
            for sp in &s.springs {
                w.write_record([
                    s.step.to_string(),
                    f(s.time),
                    sp.name.clone(),
                    f(sp.length),
                    f(sp.extension),
                    f(sp.tension),
                    f(sp.energy),
                ])?;
            }
        }
        Ok(())
    }

    /// Puts the run's files in place: each written file renamed over its name, and a sibling
    /// an earlier run left that this run did not write removed. Each name is checked again
    /// first ([`csv_ours`]: the command checked them before the run, but a file may have taken a
    /// name since): a file that is not rigidlab's is neither replaced nor removed, and the run's
    /// files are not put in place (an error that names it).
    pub fn finish(self) -> std::io::Result<()> {
        let done = |w: csv::Writer<Pending>| -> std::io::Result<Pending> {
            w.into_inner()
                .map_err(|e| std::io::Error::other(e.error().to_string()))
        };
        let mut all = vec![(self.path.clone(), Some(done(self.bodies)?))];
        for (suffix, w) in SIBLINGS
            .iter()
            .zip([self.joints, self.contacts, self.springs])
        {
            all.push((sibling(&self.path, suffix), w.map(done).transpose()?));
        }
        for (kind, (path, _)) in all.iter().enumerate() {
            csv_ours(path, kind).map_err(std::io::Error::other)?;
        }
        let mut all = all.into_iter();
        let (_, bodies) = all.next().expect("the bodies' file is first");
        for (path, w) in all {
            match w {
                Some(file) => file.commit()?,
                None => match std::fs::symlink_metadata(&path) {
                    Ok(m) if m.is_file() => std::fs::remove_file(&path)?,
                    _ => {}
                },
            }
        }
        bodies.expect("written").commit()
    }
}

/// A report as pretty JSON.
pub fn json<T: Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).expect("reports serialize") + "\n"
}

/// Exit code of a command whose reader closed the pipe (`rigidlab check levels | head`): what a
/// process killed by SIGPIPE reports in the shell (128 + 13), without a message.
pub const CLOSED_PIPE: u8 = 141;

/// Exit code of a command that could not write its output (a full disk, a closed file).
pub const CANNOT_WRITE: u8 = 2;

/// The one way commands print their output: writes `text` to stdout and flushes it, then ends with
/// `code`. A closed pipe ends quietly with [`CLOSED_PIPE`]; any other write or flush error (e.g.
/// `> /dev/full`) is reported on stderr and ends with [`CANNOT_WRITE`].
pub fn print(text: &str, code: ExitCode) -> ExitCode {
    match write_all_and_flush(&mut std::io::stdout().lock(), text) {
        Ok(()) => code,
        Err(e) => output_failed(&e),
    }
}

fn write_all_and_flush(out: &mut impl Write, text: &str) -> std::io::Result<()> {
    out.write_all(text.as_bytes())?;
    out.flush()
}

/// The exit code for output that could not be written (see [`print()`]).
pub fn output_failed(e: &std::io::Error) -> ExitCode {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        return ExitCode::from(CLOSED_PIPE);
    }
    // stderr may be gone too; there is nowhere left to say so.
    let _ = writeln!(
        std::io::stderr(),
        "error: cannot write the output: {e}\n  help: check that the disk is not full and the file or pipe is writable"
    );
    ExitCode::from(CANNOT_WRITE)
}
