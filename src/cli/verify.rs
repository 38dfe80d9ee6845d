//! `rigidlab verify LEVEL --variants N [--seed S] [--json]`: runs every corner of a
//! parameterized level's ranges and N random variants, and reports each that fails (a variant
//! that does not validate, or whose checks or questions fail) with its values and the advice a
//! failing level gets, so a teacher knows every variant is gradable before assigning it.

use super::{bad, SolverArgs};
use crate::level::params::{Parameterized, Pick, Variant};
use crate::level::{self, Scene};
use crate::report::{self, LevelReport, Report};
use crate::runner::{self, RunError};
use crate::sim::Options;
use serde::Serialize;
use std::collections::HashMap;
use std::path::Path;
use std::process::ExitCode;

/// The id of random variant `i` (1-based) of seed `seed`: its values are those a student of
/// this id gets (level::params::seed), so any variant verify reports can be handed out or
/// rerun with `check --student verify:S:i`.
pub fn random_id(seed: u64, i: usize) -> String {
    format!("verify:{seed}:{i}")
}

/// One variant's outcome.
#[derive(Debug, Serialize)]
pub struct Outcome {
    /// "nominal", "corner" or "random".
    pub kind: &'static str,
    /// The student id that gives this variant (random ones).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Each parameter's value in its unit.
    pub values: Vec<Value>,
    pub shown: String,
    pub passed: bool,
    /// Why it does not validate, or the run's error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The run's report (with its advice when it failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<LevelReport>,
}

/// One parameter's value in a variant.
#[derive(Debug, Serialize)]
pub struct Value {
    pub name: String,
    pub value: f64,
    pub unit: String,
}

/// The whole verification.
#[derive(Debug, Serialize)]
pub struct Verification {
    pub file: String,
    pub seed: u64,
    pub corners: usize,
    pub random: usize,
    pub passed: bool,
    pub failed: usize,
    pub variants: Vec<Outcome>,
}

pub struct VerifyArgs<'a> {
    pub level: &'a Path,
    pub variants: usize,
    pub seed: u64,
    pub json: bool,
    pub advice: Option<f64>,
    pub solver: &'a SolverArgs,
}

pub fn verify(a: VerifyArgs) -> ExitCode {
    let opts = match a.solver.options() {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let text = match level::read_text(a.level) {
        Ok(t) => t,
        Err(e) => return bad(e),
    };
    let p = match Parameterized::read(a.level, &text) {
        Ok(Some(p)) => p,
        Ok(None) => {
            return bad(format!(
                "{}: error: the level declares no parameters, so it has one variant\n  help: `rigidlab check` runs it; docs/teacher.md says how to parameterize a level",
                a.level.display()
            ))
        }
        Err(e) => return bad(e),
    };
    let mut picks: Vec<(&'static str, Option<String>, Vec<u64>)> =
        vec![("nominal", None, p.indices(&Pick::Nominal))];
    let corners = p.corners();
    picks.extend(corners.iter().map(|c| ("corner", None, c.clone())));
    for i in 1..=a.variants {
        let id = random_id(a.seed, i);
        let idx = p.indices(&Pick::Student(id.clone()));
        picks.push(("random", Some(id), idx));
    }
    let variants: Vec<Outcome> = picks
        .into_iter()
        .map(|(kind, id, idx)| one(&p, a.level, &opts, a.advice, a.solver, kind, id, &idx))
        .collect();
    let failed = variants.iter().filter(|v| !v.passed).count();
    let v = Verification {
        file: a.level.display().to_string(),
        seed: a.seed,
        corners: corners.len(),
        random: a.variants,
        passed: failed == 0,
        failed,
        variants,
    };
    let code = if v.passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    };
    let out = if a.json { report::json(&v) } else { table(&v) };
    report::print(&out, code)
}

/// Makes, runs and (when it fails) advises one variant.
#[allow(clippy::too_many_arguments)]
fn one(
    p: &Parameterized,
    path: &Path,
    opts: &Options,
    advice: Option<f64>,
    solver: &SolverArgs,
    kind: &'static str,
    id: Option<String>,
    idx: &[u64],
) -> Outcome {
    let Variant { values, shown } = p.variant(idx);
    let mut out = Outcome {
        kind,
        id,
        values: values
            .into_iter()
            .map(|(name, value, unit)| Value { name, value, unit })
            .collect(),
        shown,
        passed: false,
        error: None,
        report: None,
    };
    let scene = match p.make(path, idx) {
        Ok(made) => Scene {
            file: path.to_path_buf(),
            level: made.level,
        },
        Err(e) => {
            out.error = Some(e.to_string());
            return out;
        }
    };
    if let Err(e) = solver.budget(&scene, opts) {
        out.error = Some(e.to_string());
        return out;
    }
    let report = match runner::run_graded(&scene, opts, &HashMap::new(), |_| {}) {
        Ok(mut r) => {
            if let Some(cost) = advice.filter(|_| crate::study::advice::engine_failed(&r)) {
                r.advice = Some(crate::study::advice::advise_within(
                    &scene,
                    opts,
                    Some(&r),
                    cost,
                ));
            }
            r
        }
        Err(e @ RunError::Sim { .. }) => {
            let mut r = LevelReport::failed(path, &e.to_string());
            if let Some(cost) = advice {
                r.advice = Some(crate::study::advice::advise_within(
                    &scene, opts, None, cost,
                ));
            }
            r
        }
        Err(e) => {
            out.error = Some(e.to_string());
            return out;
        }
    };
    out.passed = report.passed;
    out.report = Some(report);
    out
}

/// The text report: a line per variant, and under each that fails why (its level's table, with
/// the advice) or its error.
fn table(v: &Verification) -> String {
    let mut s = format!(
        "verify {}: nominal, {} corners and {} random variants (seed {})\n",
        v.file, v.corners, v.random, v.seed
    );
    for o in &v.variants {
        let id = o.id.as_deref().map(|i| format!(" {i}")).unwrap_or_default();
        let mark = if o.passed { "ok  " } else { "FAIL" };
        s += &format!("  {mark} {}{id}: {}\n", o.kind, o.shown);
        if o.passed {
            continue;
        }
        if let Some(e) = &o.error {
            for line in e.lines() {
                s += &format!("         {line}\n");
            }
        }
        if let Some(r) = &o.report {
            let t = report::table(&Report {
                passed: r.passed,
                levels: vec![r.clone()],
            });
            for line in t.lines() {
                s += &format!("         {line}\n");
            }
        }
    }
    s += &format!(
        "{} variants, {} pass, {} fail\n",
        v.variants.len(),
        v.variants.len() - v.failed,
        v.failed
    );
    s
}
