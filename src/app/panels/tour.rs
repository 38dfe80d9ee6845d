//! The first-steps tour: a small window listing what to try first in the sandbox, each step
//! ticked when the user has done it (read from the window's own state, not from clicks on the
//! tour), until they finish or dismiss it; [`super::super::prefs::Prefs`] remembers that, and
//! the course's progress keeps the steps ticked and the finish ([`keep`], [`restore`]: natively
//! in `progress.ron`, in the page in localStorage), so a reload does not start the count again.

use super::super::editor::Editor;
use super::super::overlays::Overlays;
use super::super::progress::{Progress, TourRecord};
use super::super::progress_file::Store;
use super::super::run::Run;
use super::super::ui::rich;
use super::super::view::palette;
use bevy_egui::egui;

/// What the tour has seen that leaves no trace in the window's state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tour {
    pub open: bool,
    pub went_back: bool,
    pub saw_help: bool,
    /// The steps ticked so far: a step stays ticked once done (opening another level resets
    /// the run, the selection and the answers, not what the student has learnt).
    pub ticked: Vec<bool>,
}

impl Tour {
    /// The steps with what is done now added to what was done before.
    pub fn tick(&mut self, live: Vec<(&'static str, bool)>) -> Vec<(&'static str, bool)> {
        self.ticked.resize(live.len(), false);
        live.into_iter()
            .zip(self.ticked.iter_mut())
            .map(|((what, now), was)| {
                *was |= now;
                (what, *was)
            })
            .collect()
    }

    /// The ids of the steps ticked ([`STEP_IDS`]).
    pub fn ticked_ids(&self) -> Vec<String> {
        STEP_IDS
            .iter()
            .zip(&self.ticked)
            .filter(|(_, t)| **t)
            .map(|(id, _)| id.to_string())
            .collect()
    }

    /// Ticks the steps `ids` names (kept from an earlier session); an id this rigidlab does not
    /// know (a later one's step) ticks nothing.
    pub fn restore(&mut self, ids: &[String]) {
        self.ticked.resize(STEP_IDS.len(), false);
        for (step, t) in STEP_IDS.iter().zip(self.ticked.iter_mut()) {
            *t |= ids.iter().any(|id| id == step);
        }
    }
}

/// Each step's id, in the order of [`steps`]: what the course's progress keeps of the tour.
pub const STEP_IDS: [&str; 7] = [
    "play",
    "select",
    "diagrams",
    "step_back",
    "answer",
    "build",
    "help",
];

/// The tour as the course's progress kept it (at the window's first frame): its steps ticked
/// again, and closed where it was finished or hidden for good.
pub fn restore(tour: &mut Tour, progress: &Progress) {
    tour.restore(&progress.tour.ticked);
    if progress.tour.done {
        tour.open = false;
    }
}

/// Keeps in the course's progress, and its store, a step newly ticked or the tour `finished`
/// (nothing is written while nothing changed). A problem keeping it, for the status line.
pub fn keep(
    tour: &Tour,
    finished: bool,
    (progress, store): (&mut Progress, &mut Store),
) -> Option<String> {
    let now = TourRecord {
        ticked: tour.ticked_ids(),
        done: finished,
    };
    if !progress.tour.merge(&now) {
        return None;
    }
    match store.save(progress) {
        Ok(None) => None,
        Ok(Some(note)) | Err(note) => Some(note),
    }
}

/// The steps, and whether each is done.
pub fn steps(
    tour: &Tour,
    phys: &Run,
    ov: &Overlays,
    answered: bool,
    editor: &Editor,
) -> Vec<(&'static str, bool)> {
    vec![
        (
            "Press Space (or ▶ Play) to run the exercise",
            phys.snapshot().step > 0 || phys.seek.is_some(),
        ),
        (
            "Click a body: its velocity, and the velocity of the point you clicked",
            ov.selected.is_some(),
        ),
        (
            "Press F for its free-body diagram and K for the kinetic diagram beside it",
            ov.free_body && ov.kinetic,
        ),
        (
            "Drag the timeline back, or press Left to step back",
            tour.went_back,
        ),
        (
            "Type your answer into a question's box and press Enter",
            answered,
        ),
        (
            "Build: new scene, place a bar, and pin it with the join tool",
            editor.history.can_undo() && !phys.scene.level.joints.is_empty(),
        ),
        ("Press F1 for every key, overlay and tool", tour.saw_help),
    ]
}

/// The tour window's egui id (its area's, where egui keeps its rect: the Challenge box keeps
/// off it).
pub const TOUR_ID: &str = "first-steps";

/// Draws the tour while it is open; returns true when the user finished or dismissed it.
pub fn tour(
    ctx: &egui::Context,
    scene: egui::Rect,
    tour: &mut Tour,
    phys: &Run,
    ov: &Overlays,
    (answered, help): (bool, bool),
    editor: &Editor,
) -> bool {
    if phys.seeking_back() {
        tour.went_back = true;
    }
    if help {
        tour.saw_help = true;
    }
    if !tour.open {
        return false;
    }
    let live = steps(tour, phys, ov, answered, editor);
    let steps = tour.tick(live);
    let done = steps.iter().filter(|(_, d)| *d).count();
    let mut finished = false;
    egui::Window::new(format!("First steps ({done} of {})", steps.len()))
        .id(egui::Id::new(TOUR_ID))
        // In the scene's bottom right corner, inside the panels: anchored to the screen's
        // right edge it lay over the right panel's Play and overlay buttons once that panel
        // widened (seen at 1280x800, 2026-12-07), and a scene's bodies sit mostly above it.
        .pivot(egui::Align2::RIGHT_BOTTOM)
        .fixed_pos(scene.right_bottom() + egui::vec2(-8.0, -8.0))
        .default_open(!cfg!(target_arch = "wasm32"))
        .resizable(false)
        .show(ctx, |ui| {
            for (what, d) in &steps {
                let mark = if *d { "✔" } else { "○" };
                let color = if *d { palette::GRAVITY } else { palette::TEXT };
                ui.label(rich(format!("{mark} {what}"), color));
            }
            ui.horizontal(|ui| {
                let label = if done == steps.len() {
                    "done"
                } else {
                    "hide for good"
                };
                if ui.button(label).clicked() {
                    finished = true;
                }
                if ui
                    .button("later")
                    .on_hover_text("it comes back next time")
                    .clicked()
                {
                    tour.open = false;
                }
            });
        });
    if finished {
        tour.open = false;
    }
    finished
}
