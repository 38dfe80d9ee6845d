//! Unsaved work is never lost without asking: opening another level, a new scene or closing the
//! window while the scene has edits not saved asks first (save, discard, cancel).
//!
//! [`Unsaved`] holds the question and decides; the panels draw it ([`dialog`]) and do what the
//! answer allows; [`close_requests`] turns the window's close button into a request (the native
//! window is opened with `close_when_requested: false`, so nothing else closes it).

use super::editor::Editor;
use super::run::Run;
use super::user_files::save_level_as;
use crate::level::Scene;
use bevy::prelude::*;
use bevy::window::WindowCloseRequested;
use bevy_egui::egui;
use std::path::Path;

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

    /// Settles the question with the answer clicked: Save writes the scene as `save_path` first
    /// (a file already there is kept: it goes under the next numbered name) and marks it saved.
    /// `Ok` holds the action to do now and the status line's note; a save that fails is `Err`
    /// with why, and the question stays open (nothing is lost, nothing left).
    pub fn settle(
        &mut self,
        answer: Answer,
        editor: &mut Editor,
        phys: &Run,
        save_path: &Path,
    ) -> Result<(Option<Leaving>, Option<String>), String> {
        self.asking.as_ref().ok_or("no question is open")?;
        let mut note = None;
        if answer == Answer::Save {
            let (used, m) = save_level_as(&phys.scene, save_path)?;
            editor.mark_saved(phys);
            editor.just_saved = Some(used);
            note = Some(m);
        }
        Ok((self.answer(answer), note))
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
    phys: Res<Run>,
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

/// Whether the question is open (a run condition: the scene's mouse tools and the keyboard
/// shortcuts wait while it is). The dialog is modal, but egui learns that the pointer is over it
/// only at the end of a frame: a click that moved onto the answer within one frame (a fast hand,
/// the page's 100 ms frames) also reached the build tool under it and placed a body there.
pub fn not_asking(unsaved: Option<Res<Unsaved>>) -> bool {
    unsaved.is_none_or(|u| u.asking.is_none())
}

/// The question, drawn over the window while it is asked (modal: the panels and the scene
/// behind it take no clicks); the answer clicked, if any (Escape is Cancel; a click beside the
/// question is nothing, so a stray click neither saves nor throws away).
pub fn dialog(ctx: &egui::Context, unsaved: &Unsaved, save_path: &str) -> Option<Answer> {
    let what = unsaved.asking.as_ref()?;
    let mut answer = None;
    egui::Modal::new(egui::Id::new("unsaved changes")).show(ctx, |ui| {
        ui.set_max_width(380.0);
        ui.heading("Unsaved changes");
        ui.label(format!(
            "The scene has edits that are not saved. Save them before {}?",
            what.what()
        ));
        ui.label(
            egui::RichText::new(format!("saved as {save_path} (a file there is kept)")).small(),
        );
        ui.add_space(4.0);
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
