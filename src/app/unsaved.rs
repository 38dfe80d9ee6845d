//! Unsaved work is never lost without asking: opening another level, a new scene or closing the
//! window while the scene has edits not saved asks first (save, discard, cancel).
//!
//! [`Unsaved`] holds the question and decides; the panels draw it ([`dialog`]) and do what the
//! answer allows; [`close_requests`] turns the window's close button into a request (the native
//! window is opened with `close_when_requested: false`, so nothing else closes it).

use super::editor::Editor;
use super::physics::Physics;
use crate::level::Scene;
use bevy::prelude::*;
use bevy::window::WindowCloseRequested;
use bevy_egui::egui;

/// What would throw the edits away.
#[derive(Debug, Clone, PartialEq)]
pub enum Leaving {
    /// Open another level (from the level browser or the web page's file picker).
    Open(Box<Scene>),
    /// A new scene.
    New,
    /// Close the window.
    Close(Entity),
}

impl Leaving {
    fn what(&self) -> &'static str {
        match self {
            Leaving::Open(_) => "opening another level",
            Leaving::New => "starting a new scene",
            Leaving::Close(_) => "closing the window",
        }
    }
}

/// The user's answer to the question.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answer {
    /// Save the scene (as the Build panel's "save as" names it), then go on.
    Save,
    /// Go on without saving.
    Discard,
    /// Stay.
    Cancel,
}

/// The question being asked, if any.
#[derive(Resource, Debug, Default)]
pub struct Unsaved {
    pub asking: Option<Leaving>,
}

impl Unsaved {
    /// `what` is asked for while the scene has unsaved edits (`unsaved`): the action to do at
    /// once, or `None` when the user is asked first (a question already open is kept).
    pub fn request(&mut self, unsaved: bool, what: Leaving) -> Option<Leaving> {
        if !unsaved {
            return Some(what);
        }
        if self.asking.is_none() {
            self.asking = Some(what);
        }
        None
    }

    /// The answer: the action to do now (after saving, where the answer is Save) or `None`.
    pub fn answer(&mut self, answer: Answer) -> Option<Leaving> {
        let what = self.asking.take()?;
        (answer != Answer::Cancel).then_some(what)
    }
}

/// Registers the question and the window's close requests.
pub struct UnsavedPlugin;

impl Plugin for UnsavedPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<Unsaved>()
            .add_message::<WindowCloseRequested>()
            .add_systems(Update, close_requests);
    }
}

/// The window's close button: closes at once when nothing is unsaved, else asks.
pub fn close_requests(
    mut requests: MessageReader<WindowCloseRequested>,
    editor: Res<Editor>,
    phys: Res<Physics>,
    mut unsaved: ResMut<Unsaved>,
    mut commands: Commands,
) {
    for r in requests.read() {
        if let Some(Leaving::Close(window)) =
            unsaved.request(editor.unsaved(&phys), Leaving::Close(r.window))
        {
            commands.entity(window).try_despawn();
        }
    }
}

/// The question, drawn over the window while it is asked; the answer clicked, if any (Escape
/// is Cancel).
pub fn dialog(ctx: &egui::Context, unsaved: &Unsaved, save_path: &str) -> Option<Answer> {
    let what = unsaved.asking.as_ref()?;
    let mut answer = None;
    egui::Window::new("Unsaved changes")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            ui.label(format!(
                "The scene has edits that are not saved. Save them before {}?",
                what.what()
            ));
            ui.label(
                egui::RichText::new(format!("saved as {save_path} (a file there is kept)")).small(),
            );
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    answer = Some(Answer::Save);
                }
                if ui.button("Discard").clicked() {
                    answer = Some(Answer::Discard);
                }
                if ui.button("Cancel").clicked() {
                    answer = Some(Answer::Cancel);
                }
            });
        });
    if ctx.input(|i| i.key_pressed(egui::Key::Escape)) {
        answer = Some(Answer::Cancel);
    }
    answer
}
