//! The exercise panel (left panel, under the browser): the level's source, statement and
//! effects, and its questions with an answer box each. A typed answer is graded with the
//! level's own rule; the value rigidlab measured is shown once the answer is right (or the
//! values are given away: predict first's results, the worked solution).

use super::super::physics::LiveChecks;
use super::super::run::Run;
use super::super::ui::{fixed_height, fmt, rich, text_height};
use super::super::view::palette;
use super::hints::{hints, HintState};
use bevy::prelude::Resource;
use bevy_egui::egui;

/// The student's side of the exercise: the answers typed and their grades, one per question
/// (emptied when the run starts over).
#[derive(Resource, Debug, Clone, Default)]
pub struct Exercise {
    /// Predict first (panels/predict.rs): a grade is held back until the motion has been seen,
    /// so an answer is not tried until it is right before the motion runs.
    pub hold_grades: bool,
    /// Predict first's results are shown (the run's values beside each prediction, right or
    /// wrong): the measured values show under the questions too.
    pub revealed: bool,
    pub answers: Vec<String>,
    /// A student's grade per question.
    pub grades: Vec<Option<Grade>>,
    /// Where each answer box was drawn last frame (egui points = CSS pixels in the page; the web
    /// page publishes them so a browser test can click into a box and type).
    pub answer_boxes: Vec<Option<egui::Rect>>,
    /// The worked solution was shown before every question was answered right: a solve now
    /// counts as "solved with help".
    pub help_used: bool,
    /// The hints shown and the solution's state (`hints.rs`).
    pub hints: HintState,
    /// The level the answers were typed for: its file and its statement (a student's own
    /// numbers are in the statement).
    pub typed_for: Option<(std::path::PathBuf, String)>,
}

impl Exercise {
    /// A run of a level with `n` questions starts: grades and boxes go, answers typed stay
    /// while the number of questions does.
    pub fn start(&mut self, n: usize) {
        if self.answers.len() != n {
            self.answers = vec![String::new(); n];
        }
        self.grades = vec![None; n];
        self.answer_boxes = vec![None; n];
    }

    /// [`Exercise::start`] of the level in `file` with `statement`: answers typed for another
    /// level, or for the same one with other numbers (another student's variant), go. Before
    /// 2026-12-07 they stayed while the number of questions did, so *Next level* from a pendulum
    /// to its parameterized copy showed the answers just typed, graded right without any work.
    pub fn start_level(&mut self, file: &std::path::Path, statement: &str, n: usize) {
        let key = (file.to_path_buf(), statement.to_string());
        if self.typed_for.as_ref() != Some(&key) {
            self.answers = vec![String::new(); n];
            self.typed_for = Some(key);
        }
        self.start(n);
    }
}

/// Draws the panel and grades the answers the student submits.
pub(super) fn exercise(ui: &mut egui::Ui, phys: &Run, live: &LiveChecks, st: &mut Exercise) {
    let level = &phys.sim.level;
    ui.heading(&level.title);
    if !level.source.book.is_empty() || !level.source.problem.is_empty() {
        ui.label(
            rich(
                format!("{} {}", level.source.book, level.source.problem),
                palette::OUTLINE,
            )
            .italics(),
        );
    }
    if !level.statement.is_empty() {
        ui.label(&level.statement);
    }
    let effects: Vec<&str> = level.effects.iter().map(|e| e.name()).collect();
    ui.label(rich(format!("effects: {}", effects.join(", ")), palette::OUTLINE).small());
    if level.questions.is_empty() {
        return;
    }
    ui.add_space(6.0);
    ui.strong("Questions");
    for (k, q) in level.questions.iter().enumerate() {
        ui.group(|ui| {
            ui.label(format!("{}. {}", k + 1, q.ask));
            ui.horizontal(|ui| {
                let edit = ui.add(
                    egui::TextEdit::singleline(&mut st.answers[k])
                        .desired_width(90.0)
                        .hint_text("your answer"),
                );
                ui.label(&q.unit);
                let submit = ui.button("Check").clicked()
                    || (edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)));
                st.answer_boxes[k] = Some(edit.rect);
                if submit {
                    st.grades[k] = Some(grade(q, &st.answers[k]));
                    let right = st.grades[k]
                        .as_ref()
                        .and_then(|g| g.as_ref().ok())
                        .map(|g| g.passed);
                    // A prediction's verdict waits for the motion (predict.rs): a hint now
                    // would tell the student it is wrong before they have seen the run.
                    if !st.hold_grades {
                        st.hints.graded(right, &st.grades);
                    }
                }
            });
            // The verdict's rows keep the height of the longest one this question can show,
            // from before the first Check: a verdict appearing moved every box below it, and a
            // click aimed at the next box missed it (the student trial of 2026-12-07).
            let room = verdict_height(ui, q);
            fixed_height(ui, room, |ui| verdict(ui, q, k, live, st));
        });
    }
    // The hints and the solution come after *Next level* ([`exercise_help`], `left_column`), so
    // that a hint appearing after a wrong answer moves neither that button nor Show solution.
}

/// The hints and the worked solution (under the *Next level* button: `hints.rs`).
pub(super) fn exercise_help(ui: &mut egui::Ui, phys: &Run, st: &mut Exercise) {
    hints(
        ui,
        &phys.sim.level,
        &phys.scene.file,
        &mut st.hints,
        &mut st.help_used,
    );
}

/// The texts a question's verdict rows can show (`grade_message`'s and the measured line's),
/// as long as they can be: the height kept for them.
fn verdict_height(ui: &egui::Ui, q: &crate::level::QuestionDef) -> f32 {
    let worst = |g: crate::questions::StudentGrade| grade_message(q, &Ok(g)).0;
    let wrong = |mistake: Option<String>| crate::questions::StudentGrade {
        answer: -8.888e-88,
        rel_error: 9.99e5,
        passed: false,
        mistake,
    };
    let mut grades: Vec<String> = q
        .mistakes
        .iter()
        .map(|m| worst(wrong(Some(m.message.clone()))))
        .collect();
    grades.push(worst(wrong(None)));
    grades.push(
        grade_message(
            q,
            &Ok(crate::questions::StudentGrade {
                rel_error: 2.0,
                ..wrong(None)
            }),
        )
        .0,
    );
    // What an answer that cannot be read says (its text, as typed, aside).
    for typed in ["x", "1 x", "inf"] {
        if let Err(e) = grade(q, typed) {
            grades.push(e);
        }
    }
    grades.push("prediction taken: graded after the motion".into());
    let body = egui::TextStyle::Body;
    let grade_h = grades
        .iter()
        .map(|t| text_height(ui, t, body.clone()))
        .fold(0.0, f32::max);
    let n = fmt(-8.888e-88);
    let measured = format!(
        "textbook {n} {} · rigidlab measured {n} {} at t = 888.888 s",
        q.unit, q.unit
    );
    let measured_h = [NOT_YET_SEEN, SHOWN_WHEN_RIGHT]
        .iter()
        .map(|t| text_height(ui, t, egui::TextStyle::Small))
        .fold(text_height(ui, &measured, body), f32::max);
    grade_h + measured_h
}

/// Shown under a question not yet answered, where rigidlab has measured it.
const NOT_YET_SEEN: &str = "rigidlab measured this run; answer first to see it";

/// Shown under a question answered wrong: the measured value would give the answer away (the
/// hints and *Show solution* are the help, and the solution marks the level "solved with
/// help"). "answer first" showed here under an answer already given (the trial of 2026-12-07).
pub const SHOWN_WHEN_RIGHT: &str =
    "rigidlab's measured value shows once your answer is right, or with the solution";

/// Whether a question's measured value shows: its answer graded right, or the values already
/// given away (predict first's results, the worked solution shown).
pub fn measured_shown(st: &Exercise, k: usize) -> bool {
    let right = st.grades[k]
        .as_ref()
        .is_some_and(|g| g.as_ref().is_ok_and(|g| g.passed));
    (right && !st.hold_grades) || st.revealed || st.hints.solution_shown
}

/// A question's verdict: its grade, and rigidlab's measured value once [`measured_shown`].
fn verdict(
    ui: &mut egui::Ui,
    q: &crate::level::QuestionDef,
    k: usize,
    live: &LiveChecks,
    st: &Exercise,
) {
    if st.hold_grades && st.grades[k].as_ref().is_some_and(|g| g.is_ok()) {
        // Predict first (predict.rs): the grade comes with the results, after the motion.
        ui.label(rich(
            "prediction taken: graded after the motion",
            palette::VELOCITY,
        ));
    } else if let Some(g) = &st.grades[k] {
        let (text, right) = grade_message(q, g);
        let color = if right {
            palette::GRAVITY
        } else {
            palette::NORMAL
        };
        ui.label(rich(text, color));
    }
    if let Some(a) = live.answers.as_ref().and_then(|a| a.get(k)) {
        if measured_shown(st, k) {
            ui.label(rich(
                format!(
                    "textbook {} {} · rigidlab measured {} {} at t = {} s",
                    fmt(a.expected),
                    q.unit,
                    fmt(a.engine),
                    q.unit,
                    crate::app::time_text::instant(a.time)
                ),
                palette::OUTLINE,
            ));
        } else if st.grades[k].as_ref().is_some_and(|g| g.is_ok()) {
            ui.label(rich(SHOWN_WHEN_RIGHT, palette::OUTLINE).small());
        } else {
            ui.label(rich(NOT_YET_SEEN, palette::OUTLINE).small());
        }
    }
}

/// A typed answer's grade (answer, relative error, passed, the typical mistake it matches), or
/// why the answer could not be read.
pub type Grade = Result<crate::questions::StudentGrade, String>;

/// What the student reads after submitting an answer, and whether it was right. The tolerance
/// printed is the one that graded it, the question's `student_tolerance` (the level's
/// `tolerance` judges the engine in `rigidlab check`, not the student).
pub fn grade_message(q: &crate::level::QuestionDef, g: &Grade) -> (String, bool) {
    let tolerance = q.student_tolerance;
    match g {
        Ok(g) if g.passed => (
            format!(
                "✔ correct: off by {:.2}% (tolerance {:.2}%)",
                g.rel_error * 100.0,
                tolerance * 100.0
            ),
            true,
        ),
        Ok(g) => {
            let err = g.rel_error;
            // (No ✘: the window's fonts have no glyph for it, it drew as a box.)
            // The level's own typical mistake first (the grading found it); else |v - a| / |a|
            // = 2 within tolerance: the magnitude is right, the sign is not.
            let hint = match &g.mistake {
                Some(m) => format!(": {m}"),
                None if (err - 2.0).abs() <= tolerance => {
                    "; the magnitude is right: check the sign".to_string()
                }
                None => String::new(),
            };
            (
                format!(
                    "not yet: off by {:.2}% (tolerance {:.2}%){hint}",
                    err * 100.0,
                    tolerance * 100.0
                ),
                false,
            )
        }
        Err(e) => (e.clone(), false),
    }
}

/// Grades a typed answer with the level's own rule (the core's [`crate::questions::grade_answer`]),
/// after converting a unit typed with it (`523.4 in/s`) to the question's (`questions::units`).
pub fn grade(q: &crate::level::QuestionDef, text: &str) -> Grade {
    let v = crate::questions::units::answer_in(text, &q.unit)?;
    Ok(crate::questions::grade_answer(q, v))
}
