//! Helpers shared by the integration tests (`use crate::common;` in a test module): finding and loading
//! levels, running them, summarising what failed, comparing numbers and calling the command
//! line. Each was copied between test files before; a test file uses the ones it needs.
#![allow(dead_code, unused_imports, unused_macros)]

#[cfg(feature = "app")]
pub mod app;
pub mod study;

use rigidlab::level::{self, Scene};
use rigidlab::report::LevelReport;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// `rel` (a path from the repository's root, like `levels/kinetics/simple_pendulum.ron`) as an
/// absolute path, so a test does not depend on the directory it is run from.
pub fn repo_path(rel: impl AsRef<Path>) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

/// Loads a level file (a path from the repository's root, or absolute), panicking with the
/// level's own error (file:line:col and how to fix it).
pub fn load(rel: impl AsRef<Path>) -> Scene {
    level::load(&repo_path(rel)).unwrap_or_else(|e| panic!("{e}"))
}

/// Parses level text written in a test (reported as `test.ron`), panicking with its error.
pub fn parse(text: &str) -> Scene {
    level::parse(Path::new("test.ron"), text).unwrap_or_else(|e| panic!("{e}"))
}

/// The `.ron` files under `dir` (a path from the repository's root, or absolute), sorted, in
/// every subfolder but those named in `skip` (`&["stress"]`: the exercises without the stress
/// scenes). A folder that does not exist has none.
pub fn ron_files(dir: impl AsRef<Path>, skip: &[&str]) -> Vec<PathBuf> {
    fn walk(dir: &Path, skip: &[&str], out: &mut Vec<PathBuf>) {
        let Ok(read) = std::fs::read_dir(dir) else {
            return;
        };
        let mut entries: Vec<PathBuf> = read.map(|e| e.unwrap().path()).collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                if !p.file_name().is_some_and(|n| skip.iter().any(|s| n == *s)) {
                    walk(&p, skip, out);
                }
            } else if p.extension().is_some_and(|x| x == "ron") {
                out.push(p);
            }
        }
    }
    let mut out = Vec::new();
    walk(&repo_path(dir), skip, &mut out);
    out
}

/// The `.ron` files under `dir` and its subfolders (tests/newuser/ files its levels by topic),
/// loaded, in path order.
pub fn levels_in(dir: impl AsRef<Path>) -> Vec<Scene> {
    ron_files(dir, &[])
        .iter()
        .map(|f| level::load(f).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

/// The index of the body named `name` in a level (its index in every snapshot's `bodies`).
pub fn body_index(level: &level::Level, name: &str) -> usize {
    level
        .bodies
        .iter()
        .position(|b| b.name == name)
        .unwrap_or_else(|| panic!("{}: no body named {name}", level.title))
}

/// Runs a scene headless with `opts` and no student answers: its report (checks, questions,
/// settings). Panics with the file's name if the run cannot start.
pub fn run(scene: &Scene, opts: &Options) -> LevelReport {
    runner::run_scene(scene, opts, &HashMap::new(), |_| {})
        .unwrap_or_else(|e| panic!("{}: {e}", scene.file.display()))
}

/// What failed in a report, one line per failed check or question with its numbers.
pub fn failures(r: &LevelReport) -> Vec<String> {
    let mut out = Vec::new();
    for c in r.checks.iter().filter(|c| !c.passed) {
        out.push(format!(
            "check {} {}: {:.3e} > {:.1e} ({})",
            c.kind, c.subject, c.max_rel_error, c.tolerance, c.note
        ));
    }
    for q in r.questions.iter().filter(|q| !q.passed) {
        out.push(format!(
            "question {}: expected {}, engine {} ({:.3e}), analysis {:?} ({:?}) > {:.1e} {}",
            q.id,
            q.expected,
            q.engine,
            q.rel_error,
            q.analysis,
            q.analysis_rel_error,
            q.tolerance,
            q.note
        ));
    }
    out
}

/// The normal contact force on body `i` over the step (the sum of its contacts' normal impulses,
/// each along its normal into `i`, over dt), N; zero at the initial snapshot (dt = 0).
pub fn normal_contact_force(s: &rigidlab::snapshot::Snapshot, i: usize) -> glam::DVec2 {
    contact_force_on(s, i, |c| {
        c.points.iter().map(|p| p.normal_impulse).sum::<f64>() * c.normal
    })
}

/// The friction force on body `i` over the step (its contacts' tangent impulses along the
/// normal turned +90 degrees, signed into `i` as the normal is, over dt), N; zero at dt = 0.
pub fn friction_contact_force(s: &rigidlab::snapshot::Snapshot, i: usize) -> glam::DVec2 {
    contact_force_on(s, i, |c| {
        let tangent = glam::DVec2::new(-c.normal.y, c.normal.x);
        c.points.iter().map(|p| p.tangent_impulse).sum::<f64>() * tangent
    })
}

/// The sum over body `i`'s contacts of `impulse(contact)` (as on body2), signed for `i`, over dt.
fn contact_force_on(
    s: &rigidlab::snapshot::Snapshot,
    i: usize,
    impulse: impl Fn(&rigidlab::snapshot::ContactState) -> glam::DVec2,
) -> glam::DVec2 {
    if s.dt <= 0.0 {
        return glam::DVec2::ZERO;
    }
    s.contacts
        .iter()
        .filter_map(|c| {
            let sign = if c.body2 == i {
                1.0
            } else if c.body1 == i {
                -1.0
            } else {
                return None;
            };
            Some(sign / s.dt * impulse(c))
        })
        .sum()
}

/// The largest of `values` (0 for none). Panics on a NaN or an infinity: `fold(0.0, f64::max)`
/// would drop a NaN (f64::max ignores it), and a test must not pass on a value it could not
/// measure.
pub fn worst(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |m, x| {
        assert!(x.is_finite(), "a value that could not be measured: {x}");
        m.max(x)
    })
}

/// |x - expected| / |expected|, or |x| when the expected answer is 0.
pub fn rel(x: f64, expected: f64) -> f64 {
    if expected == 0.0 {
        x.abs()
    } else {
        (x - expected).abs() / expected.abs()
    }
}

/// a and b agree to `tol` relative to b, or absolutely near 0: |a - b| <= tol (1 + |b|).
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

/// `assert_close!(a, b)` (to 1e-12) or `assert_close!(a, b, tol)`: [`close`], naming the
/// expression that was off.
macro_rules! assert_close {
    ($a:expr, $b:expr) => {
        $crate::common::assert_close!($a, $b, 1e-12)
    };
    ($a:expr, $b:expr, $tol:expr) => {{
        let (a, b) = ($a as f64, $b as f64);
        assert!(
            $crate::common::close(a, b, $tol),
            "{} = {a} but expected {b} (tol {})",
            stringify!($a),
            $tol
        );
    }};
}
pub(crate) use assert_close;

/// The `rigidlab` binary this test build made, run from the repository's root.
pub fn rigidlab() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rigidlab"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}
