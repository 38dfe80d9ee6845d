//! An assignment in the level browser: its title, its due date and its levels in the teacher's
//! order, above the library (`rigidlab play ASSIGNMENT`, or a page opened on one). A level that
//! does not load is listed with why, never skipped: the numbering stays the teacher's.

use super::super::run::Run;
use super::super::ui::rich;
use super::super::view::palette;
use super::level_entry::Entry;
use crate::level::assignment::Assignment;
use crate::level::{self, Scene};
use bevy_egui::egui;
use std::path::PathBuf;
use std::sync::Arc;

/// The assignment the browser lists, each level read once.
#[derive(Debug, Clone)]
pub struct AssignmentList {
    pub file: PathBuf,
    pub title: String,
    pub due: Option<String>,
    pub entries: Vec<Row>,
}

/// One level of the assignment: the level browser's [`Entry`] (its title and statement, or why
/// it does not load; its text where it was fetched). It was a near copy of it, with its own
/// `from_load` and `load` (the student trial's note of 2026-12-07).
pub type Row = Entry;

impl AssignmentList {
    /// The assignment's levels read from their files.
    pub fn read(a: &Assignment) -> AssignmentList {
        let entries = a
            .levels
            .iter()
            .map(|p| Row::from_load(p.clone(), level::load(p), None))
            .collect();
        AssignmentList::with(a, entries)
    }

    /// The assignment's levels from their texts, in its order (the web page fetched them): a
    /// level that could not be fetched is listed with `Err(why)`.
    pub fn from_texts(a: &Assignment, texts: Vec<Result<Arc<str>, String>>) -> AssignmentList {
        let entries = a
            .levels
            .iter()
            .zip(texts)
            .map(|(p, text)| match text {
                Ok(t) => Row::from_load(p.clone(), level::parse(p, &t), Some(t)),
                Err(why) => Row::from_load(
                    p.clone(),
                    Err(level::LevelError::new(p, (0, 0), why, "")),
                    None,
                ),
            })
            .collect();
        AssignmentList::with(a, entries)
    }

    fn with(a: &Assignment, entries: Vec<Row>) -> AssignmentList {
        AssignmentList {
            file: a.file.clone(),
            title: a.title.clone(),
            due: a.due.clone(),
            entries,
        }
    }

    /// The first level that loads, which the window opens with.
    pub fn first_loadable(&self) -> Option<Scene> {
        self.entries
            .iter()
            .filter(|e| e.error.is_none())
            .find_map(|e| e.load().ok())
    }

    /// Why each level that does not load does not, for the terminal (`play ASSIGNMENT`).
    pub fn errors(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().filter_map(|e| e.error.as_deref())
    }
}

impl AssignmentList {
    /// The assignment read again from its files (the browser's rescan: a teacher fixed a level
    /// or the manifest); as it was when it was fetched, or when its manifest no longer reads.
    pub fn reread(self) -> AssignmentList {
        if self.entries.iter().any(|e| e.source.is_some()) {
            return self;
        }
        match Assignment::load(&self.file) {
            Ok(fresh) => AssignmentList::read(&fresh),
            Err(_) => self,
        }
    }
}

/// Draws the assignment, when there is one, above the library: a clicked level that loads is put
/// in `load`.
pub(super) fn assignment_list(
    ui: &mut egui::Ui,
    assignment: Option<&AssignmentList>,
    phys: &Run,
    load: &mut Option<Scene>,
) {
    let Some(a) = assignment else {
        return;
    };
    ui.label(egui::RichText::new(format!("Assignment: {}", a.title)).strong())
        .on_hover_text(a.file.display().to_string());
    if let Some(due) = &a.due {
        ui.label(format!("due {due}"));
    }
    for (k, e) in a.entries.iter().enumerate() {
        let title = format!("{}. {}", k + 1, e.title);
        let text = if e.error.is_some() {
            rich(format!("⚠ {title}"), palette::NORMAL)
        } else {
            egui::RichText::new(title)
        };
        let r = ui.selectable_label(e.path == phys.scene.file, text);
        let r = match &e.error {
            Some(err) => r.on_hover_text(err),
            None if !e.statement.is_empty() => r.on_hover_text(&e.statement),
            None => r,
        };
        if r.clicked() && e.error.is_none() {
            match e.load() {
                Ok(s) => *load = Some(s),
                Err(err) => {
                    ui.label(rich(err.to_string(), palette::NORMAL));
                }
            }
        }
    }
    ui.separator();
}
