//! The window's "Your id" field: a student types the id their teacher grades them by, and a
//! level with parameters opens with their own numbers (`app/student.rs`), the ones
//! `rigidlab grade` checks their answers against. The open level opens again with them.

use super::super::run::Run;
use super::super::student;
use super::level_browser::Browser;
use crate::level::Scene;
use bevy_egui::egui;

/// The field, one row: applied on Enter or when it loses focus; the open level, when the
/// browser lists it, opens again for the new id.
pub(super) fn student_id(
    ui: &mut egui::Ui,
    browser: &Browser,
    phys: &Run,
    load: &mut Option<Scene>,
) {
    let id = egui::Id::new("student id typed");
    let mut text: String = ui
        .data(|d| d.get_temp(id))
        .unwrap_or_else(|| student::id().unwrap_or_default());
    ui.horizontal(|ui| {
        ui.label("Your id:");
        let r = ui.add(
            egui::TextEdit::singleline(&mut text)
                .desired_width(120.0)
                .hint_text("for your own numbers"),
        );
        let r = r.on_hover_text(
            "the id your teacher grades you by: exercises with parameters give you your own numbers (the same as `rigidlab check --student ID`)",
        );
        let given = text.trim().to_string();
        let now = student::id().unwrap_or_default();
        if r.lost_focus() && given != now {
            student::set(Some(given));
            // Reopened only where the id changes the numbers: a level without parameters keeps
            // its run and the answers typed (the trial of 2026-12-07 lost a prediction here).
            if let Some(Ok(scene)) = browser.open_listed(&phys.scene.file) {
                if scene.level != phys.scene.level {
                    *load = Some(scene);
                }
            }
        }
    });
    ui.data_mut(|d| d.insert_temp(id, text));
}
