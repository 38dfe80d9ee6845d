//! A number typed into the inspector: the text being typed is kept apart from the scene's value
//! and committed only on Enter or when the field loses focus; a value out of its range or not a
//! number is refused with a short message beside the field, and the scene keeps its value.
//!
//! egui's `DragValue` applied every keystroke as an edit (typing 45 into an angle applied 4
//! degrees first; the scene restarting under the field mangled 1.5 into "0.5.433013") and
//! clamped out-of-range values (-1 kg became 1e-6 kg). [`NumberField`] is the plain logic,
//! tested without a window; [`number_field`] draws it.

use bevy_egui::egui;

/// What a field accepts: its range (an open end where `min_open`), its unit for the messages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accepts {
    pub min: f64,
    pub max: f64,
    /// The minimum itself is refused (a mass, a size: more than 0).
    pub min_open: bool,
    pub unit: &'static str,
}

impl Accepts {
    pub const fn closed(min: f64, max: f64, unit: &'static str) -> Accepts {
        Accepts {
            min,
            max,
            min_open: false,
            unit,
        }
    }

    /// More than `min` (not equal), at most `max`.
    pub const fn above(min: f64, max: f64, unit: &'static str) -> Accepts {
        Accepts {
            min,
            max,
            min_open: true,
            unit,
        }
    }

    /// The value of `text`, or why it is refused (one short line).
    pub fn parse(&self, text: &str) -> Result<f64, String> {
        let t = text.trim();
        if t.is_empty() {
            return Err("type a number".into());
        }
        let x: f64 = t.parse().map_err(|_| format!("{t:?} is not a number"))?;
        if !x.is_finite() {
            return Err("type a finite number".into());
        }
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        if self.min_open && x <= self.min {
            return Err(format!("must be more than {}{unit}", show(self.min)));
        }
        if x < self.min {
            return Err(format!("must be at least {}{unit}", show(self.min)));
        }
        if x > self.max {
            return Err(format!("must be at most {}{unit}", show(self.max)));
        }
        Ok(x)
    }
}

/// A value as the field shows it: at most 6 decimals, trailing zeros dropped (45, 0.25, 1e-6 as
/// 0.000001).
pub fn show(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e9 || x.abs() < 1e-6) {
        return format!("{x:e}");
    }
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// One field's text buffer and what it decided.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NumberField {
    /// What the field shows: the scene's value, or what is being typed.
    pub text: String,
    /// The user is typing (the scene's value does not overwrite the text).
    pub editing: bool,
    /// Why the last commit was refused (shown beside the field until the next edit).
    pub refused: Option<String>,
}

impl NumberField {
    /// Shows the scene's `value` unless the user is typing or a refused text is still shown.
    pub fn sync(&mut self, value: f64) {
        if !self.editing && self.refused.is_none() {
            self.text = show(value);
        }
    }

    /// The text changed under the user's keys: nothing is applied yet.
    pub fn typed(&mut self, text: &str) {
        self.text = text.to_string();
        self.editing = true;
        self.refused = None;
    }

    /// Enter, or the focus left the field: the value to apply, if the text is one the field
    /// accepts and differs from `current`; a refused text stays with its reason.
    pub fn commit(&mut self, current: f64, accepts: &Accepts) -> Option<f64> {
        if !self.editing {
            return None;
        }
        self.editing = false;
        match accepts.parse(&self.text) {
            Ok(x) => {
                self.refused = None;
                self.text = show(x);
                // Unchanged to the shown precision: no edit (no step to undo).
                (show(x) != show(current)).then_some(x)
            }
            Err(why) => {
                self.refused = Some(why);
                None
            }
        }
    }

    /// Escape: the typing is dropped and the scene's value shown again.
    pub fn cancel(&mut self, current: f64) {
        self.editing = false;
        self.refused = None;
        self.text = show(current);
    }
}

/// The field drawn: a one-line text box (its buffer kept in egui's memory under `id`); returns
/// the value to apply when one is committed. A refusal shows in red under it.
pub fn number_field(
    ui: &mut egui::Ui,
    id: egui::Id,
    current: f64,
    accepts: &Accepts,
) -> Option<f64> {
    let mut f: NumberField = ui.data_mut(|d| d.get_temp(id)).unwrap_or_default();
    f.sync(current);
    let mut text = f.text.clone();
    let mut out = None;
    ui.vertical(|ui| {
        let r = ui.add(
            egui::TextEdit::singleline(&mut text)
                .id(id)
                .desired_width(62.0),
        );
        if r.changed() {
            f.typed(&text);
        }
        // The focus left the field however it went (Enter, a click elsewhere, the panels
        // dropping the text focus when the pointer goes back to the scene, which egui does not
        // report as a lost focus): commit what was typed, or drop it on Escape.
        let escape = ui.input(|i| i.key_pressed(egui::Key::Escape));
        if f.editing && (!r.has_focus() || escape) {
            if escape {
                f.cancel(current);
            } else {
                out = f.commit(current, accepts);
            }
        }
        if let Some(why) = &f.refused {
            ui.label(
                egui::RichText::new(why)
                    .small()
                    .color(egui::Color32::from_rgb(190, 30, 30)),
            )
            .on_hover_text("not applied; Escape shows the value again");
        }
    });
    ui.data_mut(|d| d.insert_temp(id, f));
    out
}
