//! The exercise panel (left panel, under the browser): the level's source, statement and
//! effects, and its questions with an answer box each. A typed answer is graded with the
//! level's own rule; the value rigidlab measured is shown only once the answer is right.

use super::super::physics::LiveChecks;
use super::super::run::Run;
use super::super::ui::{fmt, rich};
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
                let show = st.grades[k]
                    .as_ref()
                    .is_some_and(|g| g.as_ref().is_ok_and(|g| g.passed));
                if show {
                    ui.label(rich(
                        format!(
                            "textbook {} {} · rigidlab measured {} {} at t = {:.3} s",
                            fmt(a.expected),
                            q.unit,
                            fmt(a.engine),
                            q.unit,
                            a.time
                        ),
                        palette::OUTLINE,
                    ));
                } else {
                    ui.label(
                        rich(
                            "rigidlab measured this run; answer first to see it",
                            palette::OUTLINE,
                        )
                        .small(),
                    );
                }
            }
        });
    }
    hints(
        ui,
        level,
        &phys.scene.file,
        &mut st.hints,
        &mut st.help_used,
    );
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
