//! The fuzz campaign of docs/testing.md: mutated levels, preference files, command lines and
//! `--answer` values, counting panics, hangs, errors without a file:line:col and non-finite
//! passes (a check or question that passes with a NaN or an infinity among its values). Ignored
//! by `cargo test`: it runs for minutes. Its command (the counts go to docs/testing.md):
//!
//!   RIGIDLAB_FUZZ_SEED=1 RIGIDLAB_FUZZ_LEVELS=60000 RIGIDLAB_FUZZ_RUN_S=300 \
//!     cargo test --release --test suite -- runner::fuzz_campaign:: --ignored --nocapture
//!
//! In-process against the library for speed (the parser and validator, `runner::run_graded`
//! for the mutants that load and are estimated to run within 0.2 s, clap's parser of the real
//! `Cli`, `units::answer_in` and `grade_answer`, `Prefs::load`), plus a bounded number of runs
//! of the release binary itself with random flags, each killed after 20 s. The generator is a
//! seeded xorshift: a seed gives the same mutants.

use crate::common;

use clap::Parser;
use rigidlab::level::{self, LevelError};
use rigidlab::runner::{self, Estimate, Mode};
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
    fn chance(&mut self, p: f64) -> bool {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }
}

const WILD_NUMBERS: &[&str] = &[
    "NaN",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e400",
    "1e-320",
    "0",
    "-0.0",
    "-1",
    "1e20",
    "1e-20",
    "99999999999999999999999",
    "0x10",
    "1.",
    ".5",
    "+3",
    "1e9",
    "1e7",
    "4294967296",
    "18446744073709551616",
    "3",
    "1000",
    "1e-9",
    "0.5",
    "-5",
];

const WILD_TOKENS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    "\"",
    "//",
    "/*",
    "*/",
    "name",
    "bodies",
    "Circle",
    "fixed",
    "Some(",
    "None",
    "\u{0}",
    "é",
    "\\",
    "r#\"",
    "Time(",
    "End",
    "Max(",
    "joints: [],",
    "checks: [],",
    "questions: [],",
    "effects: [contacts],",
    "NaN",
    "(kind: impulse_momentum, body: \"x\", tolerance: 1e-3),",
];

fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        if text[i].is_ascii_digit()
            && (i == 0 || !(text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'_'))
        {
            let from = if i > 0 && text[i - 1] == b'-' {
                i - 1
            } else {
                i
            };
            let mut j = i;
            while j < text.len() && (text[j].is_ascii_alphanumeric() || b".-+".contains(&text[j])) {
                j += 1;
            }
            out.push((from, j));
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// One to five edits: a byte, a wild number, a token, a cut, or a line repeated.
fn mutate(rng: &mut Rng, bytes: &mut Vec<u8>, numbers_only: bool) {
    for _ in 0..1 + rng.below(5) {
        let op = if numbers_only { 1 } else { rng.below(6) };
        let len = bytes.len();
        let at = rng.below(len + 1);
        match op {
            0 => {
                let b = rng.next() as u8;
                match rng.below(3) {
                    0 if at < len => bytes[at] = b,
                    1 => bytes.insert(at, b),
                    _ if at < len => {
                        bytes.remove(at);
                    }
                    _ => {}
                }
            }
            1 | 5 => {
                let nums = numbers(bytes);
                if !nums.is_empty() {
                    let (s, t) = *rng.pick(&nums);
                    bytes.splice(s..t, rng.pick(WILD_NUMBERS).bytes());
                }
            }
            2 => {
                bytes.splice(at..at, rng.pick(WILD_TOKENS).bytes());
            }
            3 => {
                let j = (at + 1 + rng.below(40)).min(len);
                bytes.drain(at.min(j)..j);
            }
            _ => {
                // Repeat the line at `at` (a body, a joint or a question twice).
                let s = bytes[..at.min(len)]
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |p| p + 1);
                let e = bytes[at.min(len)..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(len, |p| at + p + 1);
                let line = bytes[s..e].to_vec();
                bytes.splice(e..e, line);
            }
        }
    }
}

#[derive(Default, Debug)]
struct Counts {
    cases: u64,
    panics: u64,
    hangs: u64,
    unlocated: u64,
    non_finite_passes: u64,
    loaded: u64,
    ran: u64,
    examples: Vec<String>,
}

impl Counts {
    fn note(&mut self, what: String) {
        if self.examples.len() < 40 {
            self.examples.push(what);
        }
    }
}

fn library() -> Vec<(PathBuf, Vec<u8>)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = [root.join("levels"), root.join("tests/newuser")];
    let mut out = Vec::new();
    for d in dirs.iter().filter(|d| d.is_dir()) {
        for f in level::collect_files(std::slice::from_ref(d)).unwrap_or_default() {
            if let Ok(b) = std::fs::read(&f) {
                if level::parse_bytes(&f, &b).is_ok() {
                    out.push((f, b));
                }
            }
        }
    }
    out
}

/// A level error must say what, how to fix it, and where (line and column inside the text).
fn located(e: &LevelError, bytes: &[u8]) -> bool {
    let lines = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
    !e.message.trim().is_empty()
        && !e.help.trim().is_empty()
        && e.line >= 1
        && e.col >= 1
        && e.line <= lines
}

/// The values a passing check or question shows; a non-finite one is a non-finite pass.
fn non_finite_pass(r: &rigidlab::report::LevelReport) -> Option<String> {
    for c in r.checks.iter().filter(|c| c.passed) {
        let v = [
            c.theory,
            c.engine,
            c.max_abs_error,
            c.max_rel_error,
            c.final_abs_error,
            c.final_rel_error,
            c.tolerance,
            c.scale,
        ];
        if v.iter().any(|x| !x.is_finite()) {
            return Some(format!("check {} {}: {v:?}", c.kind, c.subject));
        }
    }
    for q in r.questions.iter().filter(|q| q.passed) {
        let mut v = vec![q.expected, q.engine, q.rel_error, q.tolerance, q.time];
        v.extend(q.analysis);
        v.extend(q.analysis_rel_error);
        if v.iter().any(|x| !x.is_finite()) {
            return Some(format!("question {}: {v:?}", q.id));
        }
    }
    None
}

/// Runs a loaded mutant in a thread; a run past `limit` is a hang (its thread is left behind).
fn run_bounded(scene: level::Scene, limit: Duration) -> Result<Result<Option<String>, String>, ()> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let r = catch_unwind(AssertUnwindSafe(|| {
            match runner::run_graded(&scene, &Options::default(), &HashMap::new(), |_| {}) {
                Ok(report) => non_finite_pass(&report),
                Err(_) => None,
            }
        }));
        let _ = tx.send(r.map_err(|p| panic_text(&p)));
    });
    rx.recv_timeout(limit).map_err(|_| ())
}

fn panic_text(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<String>()
        .cloned()
        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn levels_campaign(rng: &mut Rng, lib: &[(PathBuf, Vec<u8>)], n: u64, run_s: u64, c: &mut Counts) {
    let start = Instant::now();
    for i in 0..n {
        let (path, orig) = rng.pick(lib);
        let mut bytes = orig.clone();
        let numbers_only = rng.chance(0.5);
        if rng.chance(0.05) {
            bytes.truncate(rng.below(bytes.len() + 1));
        } else {
            mutate(rng, &mut bytes, numbers_only);
        }
        c.cases += 1;
        let t = Instant::now();
        let parsed = catch_unwind(AssertUnwindSafe(|| level::parse_bytes(path, &bytes)));
        if t.elapsed() > Duration::from_secs(2) {
            c.hangs += 1;
            c.note(format!(
                "slow parse {:?} of {}",
                t.elapsed(),
                path.display()
            ));
        }
        let scene = match parsed {
            Err(p) => {
                c.panics += 1;
                c.note(format!(
                    "parse panic {}: {}",
                    path.display(),
                    panic_text(&p)
                ));
                continue;
            }
            Ok(Err(e)) => {
                if !located(&e, &bytes) {
                    c.unlocated += 1;
                    c.note(format!("unlocated: {e}"));
                }
                continue;
            }
            Ok(Ok(s)) => s,
        };
        c.loaded += 1;
        // Warnings too (the CLI prints them): through a file, as the CLI reads it.
        let tmp = std::env::temp_dir().join(format!("rigidlab_fuzz_{}.ron", std::process::id()));
        let _ = std::fs::write(&tmp, &bytes);
        if let Err(p) = catch_unwind(AssertUnwindSafe(|| level::load_with_warnings(&tmp))) {
            c.panics += 1;
            c.note(format!(
                "warnings panic {}: {}",
                path.display(),
                panic_text(&p)
            ));
        }
        let e = Estimate::of(&scene.level, &Options::default(), Mode::Check, None);
        if start.elapsed() > Duration::from_secs(run_s) || e.seconds > 0.2 || i % 2 == 1 {
            continue;
        }
        c.ran += 1;
        let limit = Duration::from_secs_f64(5.0 + 50.0 * e.seconds);
        match run_bounded(scene, limit) {
            Err(()) => {
                c.hangs += 1;
                c.note(format!(
                    "run past {limit:?} (estimated {:.3} s): {}",
                    e.seconds,
                    path.display()
                ));
                let _ = std::fs::write(
                    std::env::temp_dir().join(format!("fuzz_hang_{i}.ron")),
                    &bytes,
                );
            }
            Ok(Err(p)) => {
                c.panics += 1;
                c.note(format!("run panic {}: {p}", path.display()));
                let _ = std::fs::write(
                    std::env::temp_dir().join(format!("fuzz_panic_{i}.ron")),
                    &bytes,
                );
            }
            Ok(Ok(Some(what))) => {
                c.non_finite_passes += 1;
                c.note(format!("non-finite pass {}: {what}", path.display()));
                let _ = std::fs::write(
                    std::env::temp_dir().join(format!("fuzz_nonfinite_{i}.ron")),
                    &bytes,
                );
            }
            Ok(Ok(None)) => {}
        }
    }
}

const FLAGS: &[&str] = &[
    "--dt",
    "--substeps",
    "--iterations",
    "--precision",
    "--all-effects",
    "--impact-cuts",
    "--no-impact-cuts",
    "--allow-long",
    "--json",
    "--no-advice",
    "--answer",
    "--csv",
    "--time",
    "--out",
    "--quick",
    "--long",
    "--f64",
    "--contact-hz",
    "--joint-hz",
    "--format",
    "--dir",
    "--",
    "-h",
    "--help",
    "--version",
    "=",
];

const VALUES: &[&str] = &[
    "0",
    "1",
    "-1",
    "1e-300",
    "1e-9",
    "0.1",
    "0.11",
    "NaN",
    "inf",
    "-inf",
    "1e308",
    "1000",
    "1001",
    "4294967297",
    "18446744073709551616",
    "f32",
    "f64",
    "f16",
    "",
    " ",
    "x",
    "1e12",
    "png",
    "svg",
    "/dev/null",
    "/dev/full",
    "levels",
    "spinning_disc",
    "height=5.095",
    "speed=9.81m/s",
    "q=1",
    "=",
    "é",
    "\u{0}",
];

const COMMANDS: &[&[&str]] = &[
    &["check", "levels/kinematics/free_fall.ron"],
    &["run", "levels/kinematics/free_fall.ron"],
    &["render", "levels/kinematics/free_fall.ron"],
    &["study", "stability"],
    &["study", "accuracy"],
    &["play", "levels/kinematics/free_fall.ron"],
    &["check"],
    &[],
];

fn random_args(rng: &mut Rng) -> Vec<String> {
    let mut args: Vec<String> = vec!["rigidlab".into()];
    args.extend(rng.pick(COMMANDS).iter().map(|s| s.to_string()));
    for _ in 0..rng.below(6) {
        let f = rng.pick(FLAGS).to_string();
        if rng.chance(0.2) {
            args.push(format!("{f}={}", rng.pick(VALUES)));
        } else {
            args.push(f);
            if rng.chance(0.7) {
                args.push(rng.pick(VALUES).to_string());
            }
        }
    }
    args
}

/// Command lines through clap's parser of the real `Cli`, then the solver options and the
/// budget of free_fall at those options.
fn flags_campaign(rng: &mut Rng, n: u64, c: &mut Counts) {
    let scene = common::load("levels/kinematics/free_fall.ron");
    for _ in 0..n {
        let args = random_args(rng);
        c.cases += 1;
        let r = catch_unwind(AssertUnwindSafe(|| {
            if let Ok(cli) = rigidlab::cli::Cli::try_parse_from(&args) {
                let solver = match cli.command {
                    Some(rigidlab::cli::Command::Check { solver, .. })
                    | Some(rigidlab::cli::Command::Run { solver, .. }) => solver,
                    _ => return,
                };
                if let Ok(opts) = solver.options() {
                    let _ = solver.budget(&scene, &opts);
                    let e = Estimate::of(&scene.level, &opts, Mode::Check, None);
                    assert!(e.seconds.is_finite() && e.megabytes.is_finite(), "{e:?}");
                }
            }
        }));
        if let Err(p) = r {
            c.panics += 1;
            c.note(format!("flags panic {args:?}: {}", panic_text(&p)));
        }
    }
}

const UNITS: &[&str] = &[
    "m", "m/s", "rad/s", "N", "N*m", "J", "W", "s", "rad", "deg", "Hz", "kg*m^2", "N*s", "1",
    "m/s^2", "rpm", "ft*lb/s", "in/s",
];
const ANSWER_PARTS: &[&str] = &[
    "1",
    "-2.5",
    "1e3",
    "1e400",
    "1e-400",
    "NaN",
    "inf",
    "-inf",
    "0x1",
    "1_000",
    ".",
    "",
    " ",
    "m",
    "m/s",
    "rad/s",
    "rpm",
    "in/s",
    "ft",
    "*",
    "/",
    "^",
    "^2",
    "^-1",
    "^999",
    "^1e9",
    "(",
    ")",
    "Hz",
    "rev/s",
    "deg",
    "°",
    "µ",
    "kg",
    "N",
    "s",
    "J",
    "W",
    "lb",
    "mi/h",
    "km/h",
    "%",
    "e",
    "E",
    "+",
    "-",
    "1/0",
    "2000rpm",
    "523.4in/s",
    "\u{0}",
];

/// `--answer` values through the unit conversion and the grading of every library question.
fn answers_campaign(rng: &mut Rng, lib: &[(PathBuf, Vec<u8>)], n: u64, c: &mut Counts) {
    let questions: Vec<level::QuestionDef> = lib
        .iter()
        .filter_map(|(p, b)| level::parse_bytes(p, b).ok())
        .flat_map(|s| s.level.questions)
        .collect();
    for _ in 0..n {
        let mut text = String::new();
        for _ in 0..1 + rng.below(4) {
            text += ANSWER_PARTS[rng.below(ANSWER_PARTS.len())];
        }
        let q = &questions[rng.below(questions.len())];
        let unit = if rng.chance(0.5) {
            q.unit.clone()
        } else {
            UNITS[rng.below(UNITS.len())].to_string()
        };
        c.cases += 1;
        let r = catch_unwind(AssertUnwindSafe(|| {
            let v = rigidlab::questions::units::answer_in(&text, &unit);
            if let Ok(v) = v {
                let g = rigidlab::questions::grade_answer(q, v);
                Some((v, g.passed))
            } else {
                None
            }
        }));
        match r {
            Err(p) => {
                c.panics += 1;
                c.note(format!(
                    "answer panic {text:?} in {unit}: {}",
                    panic_text(&p)
                ));
            }
            Ok(Some((v, passed))) if !v.is_finite() => {
                if passed {
                    c.non_finite_passes += 1;
                }
                c.note(format!(
                    "answer {text:?} in {unit} read as {v} (passed: {passed})"
                ));
            }
            _ => {}
        }
    }
}

/// Preference files through `Prefs::parse`, as `Prefs::load` reads them: no panic, every value
/// kept finite and positive, every refusal at `path:line:col`.
#[cfg(feature = "app")]
fn prefs_campaign(rng: &mut Rng, n: u64, c: &mut Counts) {
    let good = "(tour_done: true, arrow_scale: 1.5, time_scale: 0.25, labels: false, trails: true)";
    let path = Path::new("prefs.ron");
    for _ in 0..n {
        let mut bytes = good.as_bytes().to_vec();
        let numbers_only = rng.chance(0.5);
        mutate(rng, &mut bytes, numbers_only);
        let text = String::from_utf8_lossy(&bytes).into_owned();
        c.cases += 1;
        match catch_unwind(|| rigidlab::app::prefs::Prefs::parse(path, &text)) {
            Err(p) => {
                c.panics += 1;
                c.note(format!("prefs panic: {}", panic_text(&p)));
            }
            Ok(Ok(p)) => {
                if !(p.arrow_scale.is_finite()
                    && p.arrow_scale > 0.0
                    && p.time_scale.is_finite()
                    && p.time_scale > 0.0)
                {
                    c.non_finite_passes += 1;
                    c.note(format!("prefs kept {p:?} from {text:?}"));
                }
            }
            Ok(Err(e)) => {
                let at = e.strip_prefix("prefs.ron:").and_then(|r| {
                    let mut it = r.splitn(3, ':');
                    Some((
                        it.next()?.parse::<usize>().ok()?,
                        it.next()?.parse::<usize>().ok()?,
                    ))
                });
                if !at.is_some_and(|(l, c)| l >= 1 && c >= 1) {
                    c.unlocated += 1;
                    c.note(format!("prefs error not at line:col: {e}"));
                }
            }
        }
    }
}

#[cfg(not(feature = "app"))]
fn prefs_campaign(_: &mut Rng, _: u64, _: &mut Counts) {}

/// The release binary with random flags and mutated levels, each killed after 20 s: exit codes
/// 0, 1 or 2 only, no panic message, and bad input located at the file.
fn binary_campaign(rng: &mut Rng, lib: &[(PathBuf, Vec<u8>)], n: u64, c: &mut Counts) {
    let dir = std::env::temp_dir().join(format!("rigidlab_fuzz_bin_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for i in 0..n {
        let file = dir.join("mutant.ron");
        let (_, orig) = rng.pick(lib);
        let mut bytes = orig.clone();
        let numbers_only = rng.chance(0.7);
        mutate(rng, &mut bytes, numbers_only);
        std::fs::write(&file, &bytes).unwrap();
        let mut args = random_args(rng);
        args.remove(0);
        if let Some(p) = args.iter_mut().find(|a| a.ends_with("free_fall.ron")) {
            *p = file.display().to_string();
        }
        if args.first().is_some_and(|a| a == "play") || args.iter().any(|a| a.contains('\0')) {
            continue;
        }
        c.cases += 1;
        let mut child = common::rigidlab()
            .args(&args)
            .env("DISPLAY", "")
            .env("WAYLAND_DISPLAY", "")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // stderr read beside the wait, so a full pipe never blocks the child.
        let mut stderr = child.stderr.take().unwrap();
        let reader = std::thread::spawn(move || {
            let mut err = String::new();
            use std::io::Read;
            let _ = stderr.read_to_string(&mut err);
            err
        });
        let start = Instant::now();
        let status = loop {
            if let Some(s) = child.try_wait().unwrap() {
                break Some(s);
            }
            if start.elapsed() > Duration::from_secs(20) {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        let err = reader.join().unwrap_or_default();
        let Some(status) = status else {
            c.hangs += 1;
            c.note(format!("binary past 20 s: {args:?}"));
            let _ = std::fs::write(
                std::env::temp_dir().join(format!("fuzz_bin_hang_{i}.ron")),
                &bytes,
            );
            continue;
        };
        let code = status.code().unwrap_or(-1);
        if err.contains("panicked") || !(0..=2).contains(&code) {
            c.panics += 1;
            c.note(format!(
                "binary exit {code} {args:?}: {}",
                err.lines().take(3).collect::<Vec<_>>().join(" | ")
            ));
            let _ = std::fs::write(
                std::env::temp_dir().join(format!("fuzz_bin_panic_{i}.ron")),
                &bytes,
            );
        }
        // A bad level is reported at the file (file:line:col, or the file for what has no line).
        let f = file.display().to_string();
        let mentions_level = err
            .lines()
            .any(|l| l.contains(&format!("{f}:")) && l.contains("error"));
        if code == 2 && err.contains(&f) && !mentions_level {
            c.unlocated += 1;
            c.note(format!(
                "binary error not at the file {args:?}: {}",
                err.lines().next().unwrap_or("")
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore]
fn fuzz_campaign() {
    let seed = env("RIGIDLAB_FUZZ_SEED", 1);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed.wrapping_mul(0x2545_F491_4F6C_DD1D) | 1);
    let lib = library();
    let start = Instant::now();
    let mut report = Vec::new();
    let parts: [(&str, u64); 5] = [
        ("levels", env("RIGIDLAB_FUZZ_LEVELS", 60_000)),
        ("flags", env("RIGIDLAB_FUZZ_FLAGS", 20_000)),
        ("answers", env("RIGIDLAB_FUZZ_ANSWERS", 20_000)),
        ("prefs", env("RIGIDLAB_FUZZ_PREFS", 5_000)),
        ("binary", env("RIGIDLAB_FUZZ_BINARY", 1_000)),
    ];
    let mut total = Counts::default();
    for (name, n) in parts {
        let t = Instant::now();
        let mut c = Counts::default();
        match name {
            "levels" => levels_campaign(&mut rng, &lib, n, env("RIGIDLAB_FUZZ_RUN_S", 300), &mut c),
            "flags" => flags_campaign(&mut rng, n, &mut c),
            "answers" => answers_campaign(&mut rng, &lib, n, &mut c),
            "prefs" => prefs_campaign(&mut rng, n, &mut c),
            _ => binary_campaign(&mut rng, &lib, n, &mut c),
        }
        report.push(format!(
            "{name}: {} cases in {:.0} s (loaded {}, ran {}): {} panics, {} hangs, {} unlocated errors, {} non-finite passes",
            c.cases, t.elapsed().as_secs_f64(), c.loaded, c.ran, c.panics, c.hangs, c.unlocated, c.non_finite_passes
        ));
        for e in &c.examples {
            report.push(format!("  {name}: {e}"));
        }
        total.cases += c.cases;
        total.panics += c.panics;
        total.hangs += c.hangs;
        total.unlocated += c.unlocated;
        total.non_finite_passes += c.non_finite_passes;
    }
    println!(
        "fuzz campaign, seed {seed}, {} library levels, {:.0} s",
        lib.len(),
        start.elapsed().as_secs_f64()
    );
    for l in &report {
        println!("{l}");
    }
    println!(
        "TOTAL {} cases: {} panics, {} hangs, {} unlocated errors, {} non-finite passes",
        total.cases, total.panics, total.hangs, total.unlocated, total.non_finite_passes
    );
}
