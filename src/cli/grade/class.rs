//! The class graded against the assignment: each answer against its student's own variant of
//! its level (the seeded pick `check --student ID` runs), each variant made, and run, once.

use super::answers::{BadRow, Layout, Row};
use crate::level::params::{Parameterized, Pick};
use crate::level::{self, Level, QuestionDef, Scene};
use crate::questions::{grade_answer, units};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// One level of the assignment.
pub struct Assigned {
    /// As answers.csv names it and the outputs show it: its path from the assignment's folder
    /// without `.ron` (`impact/central_impact_param`), or its file's stem for a lone file.
    pub name: String,
    pub path: PathBuf,
    /// Its parameters (None: every student gets the level as written).
    params: Option<Parameterized>,
    /// The level as written (its nominal variant): its questions, in order, for the outputs.
    pub nominal: Level,
}

impl Assigned {
    /// Loads a level of the assignment (every corner checked, as `check` does); the error is
    /// the level's own, located.
    pub fn load(name: String, path: &Path) -> Result<Assigned, String> {
        let loaded = level::load_variant(path, &Pick::Nominal).map_err(|e| e.to_string())?;
        let params = if loaded.variant.is_some() {
            let text = level::read_text(path).map_err(|e| e.to_string())?;
            Parameterized::read(path, &text).map_err(|e| e.to_string())?
        } else {
            None
        };
        Ok(Assigned {
            name,
            path: path.to_path_buf(),
            params,
            nominal: loaded.scene.level,
        })
    }

    /// The names answers.csv may give it: its name, with `.ron`, its file name and its stem.
    fn answers_to(&self, given: &str) -> bool {
        let given = given.trim_end_matches(".ron");
        given == self.name || Some(given) == self.stem().as_deref()
    }

    fn stem(&self) -> Option<String> {
        self.path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
    }
}

/// One student's variant of a level, made once.
pub struct Made {
    pub level: Level,
    /// Its values as the statement prints them ("m = 2.5 kg, theta = 30 deg"); empty for a
    /// level without parameters.
    pub shown: String,
    /// Whether the engine passed this variant's own checks and questions (None: not run).
    pub passed: Option<bool>,
}

/// One answer graded.
#[derive(Debug, Clone)]
pub struct Graded {
    pub line: u64,
    pub student: String,
    /// The index of its level in the assignment.
    pub level: usize,
    pub question: String,
    pub answer: String,
    /// The answer in the question's unit (None: unreadable).
    pub value: Option<f64>,
    pub expected: f64,
    pub unit: String,
    pub verdict: Verdict,
    /// |value - expected| / |expected| (absolute when expected is 0).
    pub rel_error: Option<f64>,
    pub variant: String,
    /// Whether the engine passed the variant's own checks and questions (None: not run).
    pub variant_passed: Option<bool>,
}

/// What an answer gets.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    Correct,
    Wrong,
    /// Wrong, at one of the question's typical mistakes: its message.
    Mistake(String),
    /// The answer is not a number, or its unit is of another kind than the question's.
    Unreadable,
}

impl Verdict {
    /// As grades.csv writes it: `correct`, `wrong`, `mistake:<message>`, `unreadable`.
    pub fn text(&self) -> String {
        match self {
            Verdict::Correct => "correct".into(),
            Verdict::Wrong => "wrong".into(),
            Verdict::Mistake(m) => format!("mistake:{m}"),
            Verdict::Unreadable => "unreadable".into(),
        }
    }
}

/// Runs a variant: whether the engine passed its checks and questions, or why it did not run.
pub type RunVariant<'a> = &'a dyn Fn(&Scene) -> Result<bool, String>;

/// The assignment's levels and the variants made so far.
pub struct Class<'a> {
    pub levels: Vec<Assigned>,
    /// Run each variant (its engine verdict in the outputs), or only make it.
    run: Option<RunVariant<'a>>,
    made: HashMap<(usize, Vec<u64>), Result<Rc<Made>, String>>,
    /// (student, level, question) -> the line of the first answer.
    seen: HashMap<(String, usize, String), u64>,
    /// Variants that failed to make or run, reported once each.
    pub warnings: Vec<String>,
}

impl<'a> Class<'a> {
    pub fn new(levels: Vec<Assigned>, run: Option<RunVariant<'a>>) -> Self {
        Class {
            levels,
            run,
            made: HashMap::new(),
            seen: HashMap::new(),
            warnings: Vec::new(),
        }
    }

    /// Grades one row: its grade (also for an unreadable answer), and why it is bad if it is.
    pub fn grade(&mut self, layout: &Layout, row: &Row) -> (Option<Graded>, Option<BadRow>) {
        let bad = |col: &str, message: String| BadRow {
            line: row.line,
            column: layout.column(col),
            message,
        };
        let Some(li) = self.level_of(&row.level) else {
            let names: Vec<&str> = self.levels.iter().map(|l| l.name.as_str()).collect();
            return (
                None,
                Some(bad(
                    "level",
                    format!(
                        "`{}` names no level of the assignment (its levels: {})",
                        row.level,
                        names.join(", ")
                    ),
                )),
            );
        };
        let made = match self.variant(li, &row.student) {
            Ok(m) => m,
            Err(e) => {
                return (
                    None,
                    Some(bad(
                        "student",
                        format!("student {}'s variant cannot be made: {e}", row.student),
                    )),
                )
            }
        };
        let Some(q) = made.level.questions.iter().find(|q| q.id == row.question) else {
            let ids: Vec<&str> = made.level.questions.iter().map(|q| q.id.as_str()).collect();
            return (
                None,
                Some(bad(
                    "question",
                    format!(
                        "`{}` is no question of {} (its questions: {})",
                        row.question,
                        self.levels[li].name,
                        ids.join(", ")
                    ),
                )),
            );
        };
        let key = (row.student.clone(), li, q.id.clone());
        if let Some(first) = self.seen.get(&key) {
            return (
                None,
                Some(bad(
                    "question",
                    format!(
                        "student {} answered {} of {} already, on line {first}: that first answer is graded, this one is not",
                        row.student, q.id, self.levels[li].name
                    ),
                )),
            );
        }
        self.seen.insert(key, row.line);
        let (g, b) = graded(row, li, q, &made);
        let b = b.map(|b| BadRow {
            column: layout.column("answer"),
            ..b
        });
        (g, b)
    }

    /// The index of the level answers.csv names: by its name, with or without `.ron`, or by its
    /// file's stem where no other level of the assignment has that stem.
    fn level_of(&self, given: &str) -> Option<usize> {
        let given = given.trim_end_matches(".ron");
        if let Some(i) = self.levels.iter().position(|l| l.name == given) {
            return Some(i);
        }
        let by_stem: Vec<usize> = (0..self.levels.len())
            .filter(|&i| self.levels[i].answers_to(given))
            .collect();
        (by_stem.len() == 1).then(|| by_stem[0])
    }

    /// A student's variant of level `li`, made (and run) the first time it is asked for.
    fn variant(&mut self, li: usize, student: &str) -> Result<Rc<Made>, String> {
        let idx = self.levels[li]
            .params
            .as_ref()
            .map(|p| p.indices(&Pick::Student(student.to_string())))
            .unwrap_or_default();
        let key = (li, idx);
        if let Some(m) = self.made.get(&key) {
            return m.clone();
        }
        let made = self.make(li, &key.1);
        if let Err(e) = &made {
            let path = self.levels[li].path.display().to_string();
            self.warnings.push(format!("{path}: {e}"));
        }
        self.made.insert(key, made.clone());
        made
    }

    fn make(&mut self, li: usize, idx: &[u64]) -> Result<Rc<Made>, String> {
        let a = &self.levels[li];
        let (level, shown) = match &a.params {
            Some(p) => {
                let m = p.make(&a.path, idx).map_err(|e| e.to_string())?;
                (m.level, m.variant.shown)
            }
            None => (a.nominal.clone(), String::new()),
        };
        let passed = match self.run {
            Some(run) => {
                let scene = Scene {
                    file: a.path.clone(),
                    level: level.clone(),
                };
                match run(&scene) {
                    Ok(passed) => Some(passed),
                    Err(e) => {
                        self.warnings
                            .push(format!("{}: [{shown}] not run: {e}", a.path.display()));
                        None
                    }
                }
            }
            None => None,
        };
        if passed == Some(false) {
            self.warnings.push(format!(
                "{}: the variant [{shown}] fails its own checks or questions: its answers are graded against its expected values all the same; `rigidlab verify` the level",
                a.path.display()
            ));
        }
        Ok(Rc::new(Made {
            level,
            shown,
            passed,
        }))
    }

    /// How many variants were made (each run once).
    pub fn variants_made(&self) -> usize {
        self.made.values().filter(|m| m.is_ok()).count()
    }
}

/// The grade of a row whose level, variant and question are known: the rule of
/// `check --answer` (`questions::grade_answer`), the answer read as `check` reads it.
fn graded(row: &Row, li: usize, q: &QuestionDef, made: &Made) -> (Option<Graded>, Option<BadRow>) {
    let mut g = Graded {
        line: row.line,
        student: row.student.clone(),
        level: li,
        question: q.id.clone(),
        answer: row.answer.clone(),
        value: None,
        expected: q.expected,
        unit: q.unit.clone(),
        verdict: Verdict::Unreadable,
        rel_error: None,
        variant: made.shown.clone(),
        variant_passed: made.passed,
    };
    match units::answer_to(q, &made.level, &row.answer) {
        Ok(v) => {
            let s = grade_answer(q, v);
            g.value = Some(v);
            g.rel_error = Some(s.rel_error);
            g.verdict = match (s.passed, s.mistake) {
                (true, _) => Verdict::Correct,
                (false, Some(m)) => Verdict::Mistake(m),
                (false, None) => Verdict::Wrong,
            };
            (Some(g), None)
        }
        Err(e) => (
            Some(g),
            Some(BadRow {
                line: row.line,
                column: None,
                message: format!("the answer `{}` cannot be read: {e} (give it in {} or a unit of the same kind); graded unreadable", row.answer, q.unit),
            }),
        ),
    }
}
