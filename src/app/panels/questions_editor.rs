//! The exercise's questions in the build panel: a teacher adds, rewrites and removes questions
//! (quantity, wording, instant, expected answer or "compute it", tolerance, unit), sees the
//! engine's and the analysis's values from a headless run before saving, and reads the
//! validator's refusal under the form. Every change goes to the editor as an [`EditorCommand`].

use super::super::editor::{preview_note, Editor, EditorCommand};
use super::super::ui::rich;
use super::super::view::palette;
use super::number_field::{number_field, Accepts};
use crate::editor::Edit;
use crate::level::{self, BodyKind, Level, Quantity, QuestionDef, When};
use crate::questions::QuestionResult;
use bevy_egui::egui;

/// What the question form holds while it is typed (egui keeps it between frames).
#[derive(Debug, Clone, PartialEq)]
pub struct QuestionForm {
    /// The question being rewritten (its index), or None for a new one.
    pub editing: Option<usize>,
    pub id: String,
    /// The question in words.
    pub ask: String,
    /// The quantity in the level file's words, `Speed("disc1")`.
    pub quantity: String,
    /// When it is read, in the level file's words: `End`, `Time(0.5)`, ...
    pub at: String,
    /// The expected answer as typed (ignored with `compute`).
    pub expected: String,
    /// Take the expected answer from the analysis layer's value.
    pub compute: bool,
    /// Relative tolerance on the engine's and the analysis's values.
    pub tolerance: String,
    /// Empty: the quantity's SI unit.
    pub unit: String,
    /// Why the tolerance is what it is.
    pub why: String,
}

impl Default for QuestionForm {
    fn default() -> Self {
        QuestionForm {
            editing: None,
            id: String::new(),
            ask: String::new(),
            quantity: String::new(),
            at: "End".into(),
            expected: String::new(),
            compute: false,
            tolerance: "0.01".into(),
            unit: String::new(),
            why: String::new(),
        }
    }
}

impl QuestionForm {
    /// The form filled from a question of the level, to rewrite it.
    pub fn from_question(index: usize, q: &QuestionDef) -> Self {
        QuestionForm {
            editing: Some(index),
            id: q.id.clone(),
            ask: q.ask.clone(),
            quantity: ron_text(&q.quantity),
            at: ron_text(&q.at),
            expected: format!("{}", q.expected),
            compute: false,
            tolerance: format!("{}", q.tolerance),
            unit: q.unit.clone(),
            why: q.why.clone(),
        }
    }

    /// The question the form describes, and whether its answer is to be computed; or what is
    /// wrong with a field (the validator judges the rest when the edit is applied).
    pub fn question(&self, level: &Level) -> Result<(QuestionDef, bool), String> {
        self.read(level, true)
    }

    /// The question to preview: as [`Self::question`], but the expected answer may still be
    /// blank (or not a number yet): the preview is where the teacher sees the engine's and the
    /// analysis's values before deciding it. Its placeholder answer is 1 and counts for nothing.
    pub fn preview(&self, level: &Level) -> Result<QuestionDef, String> {
        self.read(level, false).map(|(q, _)| q)
    }

    /// The expected answer the form stands for, given a preview's result: the analysis's value
    /// with "compute it", else the number typed (None while there is none).
    pub fn expected_for(&self, preview: &QuestionResult) -> Option<f64> {
        if self.compute {
            preview.analysis.filter(|a| a.is_finite())
        } else {
            self.expected
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
        }
    }

    fn read(&self, level: &Level, need_expected: bool) -> Result<(QuestionDef, bool), String> {
        let quantity: Quantity = level::ron_options()
            .from_str(self.quantity.trim())
            .map_err(|e| {
                format!(
                    "quantity: {} (write it as in a level file: Speed(\"disc1\"), RollingAcceleration(body: \"disc1\", ground: \"incline1\"))",
                    e.code
                )
            })?;
        let at: When = if self.at.trim().is_empty() {
            When::End
        } else {
            level::ron_options().from_str(self.at.trim()).map_err(|e| {
                format!(
                    "when: {} (End, Time(0.5), Max(0.0), Crossing(of: Distance(\"disc1\"), value: 1.0), ...)",
                    e.code
                )
            })?
        };
        let number = |what: &str, text: &str| -> Result<f64, String> {
            text.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{what}: \"{}\" is not a number", text.trim()))
        };
        let expected = if self.compute {
            // Replaced by the analysis's value when the edit is applied.
            1.0
        } else if need_expected {
            number("expected answer", &self.expected)?
        } else {
            number("expected answer", &self.expected).unwrap_or(1.0)
        };
        let tolerance = number("tolerance", &self.tolerance)?;
        let unit = if self.unit.trim().is_empty() {
            quantity.si_unit(level).to_string()
        } else {
            self.unit.trim().to_string()
        };
        let id = self.id.trim().to_string();
        if id.is_empty() {
            return Err("id: give the question a short name (speed_1s)".into());
        }
        Ok((
            QuestionDef {
                id,
                ask: self.ask.trim().to_string(),
                unit,
                expected,
                tolerance,
                student_tolerance: 0.01,
                quantity,
                at,
                why: self.why.trim().to_string(),
                mistakes: Vec::new(),
            },
            self.compute,
        ))
    }

    /// The command that adds or rewrites the question, or what is wrong with the form.
    pub fn command(&self, level: &Level) -> Result<EditorCommand, String> {
        let (q, compute) = self.question(level)?;
        Ok(EditorCommand::Ask {
            index: self.editing,
            question: Box::new(q),
            compute,
        })
    }
}

/// A level value written back in the level file's words.
fn ron_text<T: serde::Serialize>(x: &T) -> String {
    level::ron_options().to_string(x).unwrap_or_default()
}

/// Quantities of one body the picker offers (any other is typed as in a level file).
const PICKS: [&str; 8] = [
    "X",
    "Y",
    "Angle",
    "Vx",
    "Vy",
    "Speed",
    "Omega",
    "KineticEnergy",
];

/// Draws the questions: a line each (rewrite, remove), then the form.
pub(super) fn questions(
    ui: &mut egui::Ui,
    level: &Level,
    editor: &Editor,
    out: &mut Vec<EditorCommand>,
) {
    let id = egui::Id::new("question form");
    let mut form: QuestionForm = ui.data(|d| d.get_temp(id)).unwrap_or_default();
    let mut error: Option<String> = ui.data(|d| d.get_temp(id.with("error"))).flatten();
    ui.label(egui::RichText::new("questions").strong());
    level_step(ui, level, out);
    question_list(ui, level, &mut form, out);
    ui.label(
        rich(
            match form.editing {
                Some(i) => format!("rewriting question {}", i + 1),
                None => "a new question".into(),
            },
            palette::OUTLINE,
        )
        .small(),
    );
    form_fields(ui, level, &mut form);
    // The last add or rewrite: once the editor took it, the form starts a new question.
    let sent_id = id.with("sent");
    if ui.data(|d| d.get_temp::<bool>(sent_id)).unwrap_or(false) {
        ui.data_mut(|d| d.insert_temp(sent_id, false));
        if editor.note.as_ref().is_some_and(|(_, ok)| *ok) {
            form = QuestionForm {
                tolerance: form.tolerance.clone(),
                why: form.why.clone(),
                ..QuestionForm::default()
            };
        }
    }
    form_buttons(ui, level, (&mut form, &mut error), sent_id, out);
    let preview_text = editor.preview.as_ref().map(|(_, r)| match r {
        Ok(r) => preview_note(r),
        Err(e) => e.clone(),
    });
    form_note(ui, editor, error.as_ref(), preview_text.as_ref());
    if let (Some((q, r)), Some(text)) = (&editor.preview, preview_text) {
        preview(ui, level, &mut form, (q, r), &text);
    }
    ui.data_mut(|d| {
        d.insert_temp(id, form);
        d.insert_temp(id.with("error"), error);
    });
}

/// The level's own step: what the questions are read at, in the preview and in
/// `rigidlab check` (the solver panel changes only the window's run).
fn level_step(ui: &mut egui::Ui, level: &Level, out: &mut Vec<EditorCommand>) {
    ui.horizontal(|ui| {
        ui.label("the level's step dt, s");
        let (dt, substeps) = (level.world.dt, level.world.substeps);
        let at = Accepts::above(0.0, 1.0, "s");
        if let Some(dt) = number_field(ui, egui::Id::new("level dt"), dt, &at) {
            out.push(EditorCommand::Apply(Edit::SetStep { dt, substeps }));
        }
        ui.label("substeps");
        let n = Accepts::closed(1.0, 1000.0, "");
        if let Some(s) = number_field(ui, egui::Id::new("level substeps"), substeps as f64, &n) {
            out.push(EditorCommand::Apply(Edit::SetStep {
                dt,
                substeps: s.round() as usize,
            }));
        }
    });
}

/// A line per question: its quantity and answer, "edit" (into the form) and "remove".
fn question_list(
    ui: &mut egui::Ui,
    level: &Level,
    form: &mut QuestionForm,
    out: &mut Vec<EditorCommand>,
) {
    for (i, q) in level.questions.iter().enumerate() {
        ui.horizontal_wrapped(|ui| {
            // Six significant digits here (a computed answer carries all 17): the full value
            // on hover.
            ui.label(format!(
                "{}: {} = {} {}",
                q.id,
                q.quantity.variant_name(),
                short_number(q.expected),
                q.unit
            ))
            .on_hover_text(format!("{}\nexpected {} {}", q.ask, q.expected, q.unit));
            if ui.small_button("edit").clicked() {
                *form = QuestionForm::from_question(i, q);
            }
            if ui.small_button("remove").clicked() {
                out.push(EditorCommand::Apply(Edit::RemoveQuestion {
                    id: q.id.clone(),
                }));
            }
        });
    }
}

/// A text field as wide as the panel leaves (they ran past its edge, and a long refusal
/// widened it).
fn wide(ui: &egui::Ui) -> f32 {
    (ui.available_width() - 8.0).max(80.0)
}

/// The form's fields, a row each: id, question, quantity (typed or picked), when, expected,
/// tolerance, unit, why.
fn form_fields(ui: &mut egui::Ui, level: &Level, form: &mut QuestionForm) {
    egui::Grid::new("question form").num_columns(2).show(ui, |ui| {
        ui.label("id");
        ui.add(egui::TextEdit::singleline(&mut form.id).desired_width(wide(ui)));
        ui.end_row();
        ui.label("question");
        ui.add(
            egui::TextEdit::multiline(&mut form.ask)
                .desired_rows(2)
                .desired_width(wide(ui)),
        );
        ui.end_row();
        ui.label("quantity");
        ui.vertical(|ui| {
            ui.add(
                egui::TextEdit::singleline(&mut form.quantity)
                    .hint_text("Speed(\"disc1\")")
                    .desired_width(wide(ui)),
            );
            ui.horizontal_wrapped(|ui| quantity_pick(ui, level, form));
        });
        ui.end_row();
        ui.label("when");
        ui.add(
            egui::TextEdit::singleline(&mut form.at)
                .hint_text("End, Time(0.5)")
                .desired_width(wide(ui)),
        );
        ui.end_row();
        ui.label("expected");
        ui.horizontal(|ui| {
            ui.add_enabled(
                !form.compute,
                egui::TextEdit::singleline(&mut form.expected)
                    .hint_text("preview first")
                    .desired_width(90.0),
            );
            ui.checkbox(&mut form.compute, "compute it")
                .on_hover_text("the analysis layer's value from a run of this scene (where the quantity has a formula)");
        });
        ui.end_row();
        ui.label("tolerance");
        ui.add(egui::TextEdit::singleline(&mut form.tolerance).desired_width(60.0));
        ui.end_row();
        ui.label("unit");
        ui.add(
            egui::TextEdit::singleline(&mut form.unit)
                .hint_text("SI")
                .desired_width(60.0),
        )
        .on_hover_text("empty: the quantity's SI unit; or rpm, deg, ... where it converts");
        ui.end_row();
        ui.label("why this tolerance");
        ui.add(egui::TextEdit::singleline(&mut form.why).desired_width(wide(ui)));
        ui.end_row();
    });
}

/// The quantity picker: [`PICKS`] of each moving body, and its rolling acceleration on the
/// fixed body it may roll on.
fn quantity_pick(ui: &mut egui::Ui, level: &Level, form: &mut QuestionForm) {
    let bodies: Vec<&str> = level
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Dynamic)
        .map(|b| b.name.as_str())
        .collect();
    let ground = level
        .bodies
        .iter()
        .find(|b| b.kind == BodyKind::Fixed && b.name != "ground")
        .or_else(|| level.bodies.iter().find(|b| b.kind == BodyKind::Fixed))
        .map(|b| b.name.as_str());
    if !bodies.is_empty() {
        egui::ComboBox::from_id_salt("question pick")
            .selected_text("pick")
            .show_ui(ui, |ui| {
                for b in &bodies {
                    for p in PICKS {
                        if ui
                            .selectable_label(false, format!("{p}(\"{b}\")"))
                            .clicked()
                        {
                            form.quantity = format!("{p}(\"{b}\")");
                        }
                    }
                    if let Some(g) = ground {
                        let t = format!("RollingAcceleration(body: \"{b}\", ground: \"{g}\")");
                        if ui.selectable_label(false, &t).clicked() {
                            form.quantity = t;
                        }
                    }
                }
            });
    }
}

/// Preview, add (or rewrite) and, while rewriting, a new question; a form the editor cannot
/// take leaves why in `error`.
fn form_buttons(
    ui: &mut egui::Ui,
    level: &Level,
    (form, error): (&mut QuestionForm, &mut Option<String>),
    sent_id: egui::Id,
    out: &mut Vec<EditorCommand>,
) {
    ui.horizontal(|ui| {
        if ui
            .button("preview")
            .on_hover_text(
                "run the scene for this question: the engine's and the analysis's values",
            )
            .clicked()
        {
            match form.preview(level) {
                Ok(q) => {
                    *error = None;
                    out.push(EditorCommand::Preview(Box::new(q)));
                }
                Err(e) => *error = Some(e),
            }
        }
        let verb = if form.editing.is_some() {
            "rewrite"
        } else {
            "add question"
        };
        if ui.button(verb).clicked() {
            match form.command(level) {
                Ok(c) => {
                    *error = None;
                    out.push(c);
                    ui.data_mut(|d| d.insert_temp(sent_id, true));
                }
                Err(e) => *error = Some(e),
            }
        }
        if form.editing.is_some() && ui.button("new").clicked() {
            *form = QuestionForm::default();
        }
    });
}

/// Under the form: what is wrong with it, or else the editor's answer to the last command (the
/// validator's refusal, in full here) unless it is the preview, shown below.
fn form_note(
    ui: &mut egui::Ui,
    editor: &Editor,
    error: Option<&String>,
    preview_text: Option<&String>,
) {
    if let Some(e) = error {
        ui.label(rich(e.clone(), palette::NORMAL));
    } else if let Some((note, ok)) = editor
        .note
        .as_ref()
        .filter(|(n, _)| Some(n) != preview_text)
    {
        ui.label(
            rich(
                note.clone(),
                if *ok {
                    palette::GRAVITY
                } else {
                    palette::NORMAL
                },
            )
            .small(),
        );
    }
}

/// The last preview (`text`): whether the form's expected answer passes against it, and its
/// analysis value to fill in.
fn preview(
    ui: &mut egui::Ui,
    level: &Level,
    form: &mut QuestionForm,
    (q, r): (&QuestionDef, &Result<QuestionResult, String>),
    text: &str,
) {
    // A preview of another question than the form's (its quantity or instant since
    // changed) is said to be one, and offers nothing to fill in.
    let current = form
        .preview(level)
        .is_ok_and(|f| f.quantity == q.quantity && f.at == q.at);
    let head = if current {
        "preview".to_string()
    } else {
        format!("earlier preview, of {}", q.id)
    };
    ui.label(rich(format!("{head}: {text}"), palette::OUTLINE).small());
    let (Ok(r), true) = (r, current) else {
        return;
    };
    match form.expected_for(r) {
        Some(e) => {
            let v = r.with_expected(e);
            ui.label(
                rich(
                    verdict(&v),
                    if v.passed {
                        palette::GRAVITY
                    } else {
                        palette::NORMAL
                    },
                )
                .small(),
            );
        }
        None if !form.compute => {
            ui.label(
                rich(
                    "type the expected answer (or tick \"compute it\") to see whether it passes",
                    palette::OUTLINE,
                )
                .small(),
            );
        }
        None => {}
    }
    if let (Some(a), false) = (r.analysis.filter(|a| a.is_finite()), form.compute) {
        if ui
            .small_button("use the analysis value")
            .on_hover_text(format!("{a}"))
            .clicked()
        {
            form.expected = format!("{a}");
        }
    }
}

/// A number in six significant digits, trailing zeros dropped (3.27887, 4.905, 1.5e-7).
pub fn short_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if !(1e-3..1e6).contains(&a) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Whether the previewed question passes with the expected answer the form stands for, and by
/// which reading it fails (both must agree with the answer, as in `rigidlab check`).
pub fn verdict(r: &QuestionResult) -> String {
    let analysis = match r.analysis_rel_error {
        Some(a) => format!(", analysis off {a:.2e}"),
        None => String::new(),
    };
    format!(
        "against {} {}: engine off {:.2e}{analysis} (tolerance {:.1e}): {}",
        short_number(r.expected),
        r.unit,
        r.rel_error,
        r.tolerance,
        if r.passed {
            "passes".to_string()
        } else if r.rel_error > r.tolerance {
            "FAILS on the engine's value".to_string()
        } else {
            "FAILS on the analysis's value".to_string()
        }
    )
}
