//! What a question reports: its [`QuestionResult`], and grading a student's typed answer.
//!
//! Errors are relative to the expected answer (absolute when it is 0), and a NaN error (a value
//! that could not be read) counts as infinite, so it always fails. Grading a student is a pure
//! function of the question ([`grade_answer`]): the CLI's `--answer` and the window's answer
//! box use the same rule.

use super::sample::Reading;
use crate::level::QuestionDef;
use serde::{Deserialize, Serialize};

/// How a question's note starts when its quantity cannot be read in the scene at any setting
/// (a `ModePeriod` where the linearization refuses the scene): `study::advice` says so at once
/// instead of searching finer settings.
pub const CANNOT_BE_READ: &str = "cannot be read in this scene; no setting changes it";

/// One question's result (the JSON report's `questions[]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuestionResult {
    pub id: String,
    pub ask: String,
    pub unit: String,
    pub expected: f64,
    /// The answer computed by the analysis layer from the engine's state (textbook formula), if one applies.
    pub analysis: Option<f64>,
    /// The engine's own value.
    pub engine: f64,
    /// |engine - expected| / |expected| (absolute when expected is 0).
    pub rel_error: f64,
    /// |analysis - expected| / |expected| (absolute when expected is 0), when there is an analysis.
    #[serde(default)]
    pub analysis_rel_error: Option<f64>,
    /// Where the analysis value came from when it is not the quantity's textbook formula: the
    /// reference trajectory's label (`analysis::reference::LABEL`); empty otherwise.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub analysis_source: String,
    pub tolerance: f64,
    pub passed: bool,
    /// Time at which the value was read, s.
    pub time: f64,
    pub why: String,
    /// Why a value is missing (the event never happened, too few oscillations, ...).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub note: String,
    /// A student's answer and its grade, when given with `--answer ID=VALUE`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub student: Option<StudentGrade>,
}

/// A student's answer to a question and its grade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudentGrade {
    pub answer: f64,
    pub rel_error: f64,
    pub passed: bool,
    /// The message of the question's typical mistake a wrong answer matches (its `mistakes`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mistake: Option<String>,
}

/// |x - expected| / |expected| (|x| when expected is 0); a NaN error is infinite.
fn error_against(expected: f64, x: f64) -> f64 {
    let e = if expected == 0.0 {
        x.abs()
    } else {
        (x - expected).abs() / expected.abs()
    };
    if e.is_nan() {
        f64::INFINITY
    } else {
        e
    }
}

/// Grades a student's answer to the question: against the expected answer, to the question's
/// own student tolerance (default 1 %), not the engine's. A wrong answer within that tolerance
/// of one of the question's typical mistakes gets its message (the nearest, when two are).
pub fn grade_answer(def: &QuestionDef, answer: f64) -> StudentGrade {
    let rel_error = error_against(def.expected, answer);
    let passed = rel_error <= def.student_tolerance;
    let mistake = if passed {
        None
    } else {
        matching_mistake(def, answer)
    };
    StudentGrade {
        answer,
        rel_error,
        passed,
        mistake,
    }
}

/// The message of the mistake whose value the answer is nearest, among those it is within the
/// student tolerance of (the error relative to the mistake's value, as to the expected answer's).
fn matching_mistake(def: &QuestionDef, answer: f64) -> Option<String> {
    def.mistakes
        .iter()
        .map(|m| (error_against(m.value, answer), m))
        .filter(|(e, _)| *e <= def.student_tolerance)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, m)| m.message.clone())
}

impl QuestionResult {
    /// This result judged against another expected answer (its errors and verdict recomputed by
    /// the same rule): the window's question editor previews a question before its answer is
    /// typed, then shows whether the answer typed (or the analysis's) would pass.
    pub fn with_expected(&self, expected: f64) -> QuestionResult {
        let rel_error = error_against(expected, self.engine);
        let analysis_rel_error = self.analysis.map(|a| error_against(expected, a));
        QuestionResult {
            expected,
            rel_error,
            analysis_rel_error,
            passed: rel_error <= self.tolerance
                && analysis_rel_error.is_none_or(|a| a <= self.tolerance),
            ..self.clone()
        }
    }

    /// The result of a question whose quantity read `r` (with `note` saying why a value is
    /// missing), and the grade of the student's answer when there is one.
    pub(super) fn new(def: &QuestionDef, r: Reading, note: String, student: Option<f64>) -> Self {
        let expected = def.expected;
        let rel_error = error_against(expected, r.engine);
        let analysis_rel_error = r.analysis.map(|a| error_against(expected, a));
        // The engine and the textbook formula on the engine's state must both agree with the
        // expected answer: a right engine number for the wrong reason is not a pass.
        let passed =
            rel_error <= def.tolerance && analysis_rel_error.is_none_or(|a| a <= def.tolerance);
        // What never passes (docs/analysis-and-checks.md): a value that is not finite fails (its
        // error is infinite) and, unless the note already says why a value is missing, the note
        // says which, since the JSON shows it as null.
        let mut note = note;
        if note.is_empty() {
            let bad: Vec<String> = [("engine", Some(r.engine)), ("analysis", r.analysis)]
                .iter()
                .filter_map(|(what, v)| {
                    v.filter(|v| !v.is_finite())
                        .map(|v| format!("{what} = {v}"))
                })
                .collect();
            if !bad.is_empty() {
                note = format!(
                    "{}: not finite (null in the JSON), so the question fails",
                    bad.join(", ")
                );
            }
        }
        QuestionResult {
            id: def.id.clone(),
            ask: def.ask.clone(),
            unit: def.unit.clone(),
            expected,
            analysis: r.analysis,
            engine: r.engine,
            rel_error,
            analysis_rel_error,
            analysis_source: String::new(),
            tolerance: def.tolerance,
            passed,
            time: r.t,
            why: def.why.clone(),
            note,
            student: student.map(|a| grade_answer(def, a)),
        }
    }
}
