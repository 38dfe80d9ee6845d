//! Advice beside the checks: when a run in the window ends with a check or a question failed,
//! the cheapest finer settings at which the level passes (`study::advice`, what `rigidlab check`
//! prints), searched on a thread of its own so the frames go on. Natively only: a page has no
//! threads to spare, and the panel says to run `rigidlab check` there.

use super::physics::{LiveChecks, Physics};
use crate::report::{Advice, LevelReport};
use crate::runner::{Estimate, Mode};
use crate::study::advice::{self, SEARCH_BUDGET};
use bevy::prelude::*;

/// The longest search the window starts, s: the level's own run estimated by
/// `runner::budget`, times the search's bound ([`SEARCH_BUDGET`] runs' worth).
pub const WINDOW_SEARCH_S: f64 = 120.0;

/// Where the advice for the run on screen is.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum AdviceState {
    /// Nothing failed (or nothing ran to the end yet).
    #[default]
    None,
    /// Searching on its thread.
    Searching,
    Ready(Advice),
    /// Not searched here, and why (too long for the window, the page, the run pushed).
    NotHere(String),
}

/// The advice for the scene's last run to its end.
#[derive(Resource, Default)]
pub struct WindowAdvice {
    /// The run (`Physics::generation`) it is for.
    generation: Option<u64>,
    pub state: AdviceState,
    #[cfg(not(target_arch = "wasm32"))]
    job: Option<std::sync::Mutex<std::sync::mpsc::Receiver<Advice>>>,
}

impl WindowAdvice {
    /// The panel's line, if there is one to show.
    pub fn line(&self) -> Option<String> {
        match &self.state {
            AdviceState::None => None,
            AdviceState::Searching => Some("advice: searching finer settings…".into()),
            AdviceState::Ready(a) => Some(a.line()),
            AdviceState::NotHere(why) => Some(format!("advice: {why}")),
        }
    }
}

pub struct AdvicePlugin;

impl Plugin for AdvicePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<WindowAdvice>()
            .add_systems(Update, advise_failed_run);
    }
}

fn advise_failed_run(phys: Res<Physics>, live: NonSend<LiveChecks>, mut adv: ResMut<WindowAdvice>) {
    #[cfg(not(target_arch = "wasm32"))]
    if let Some(rx) = &adv.job {
        let got = match rx.lock() {
            Ok(rx) => rx.try_recv(),
            Err(_) => Err(std::sync::mpsc::TryRecvError::Disconnected),
        };
        match got {
            Ok(a) => {
                adv.state = AdviceState::Ready(a);
                adv.job = None;
            }
            Err(std::sync::mpsc::TryRecvError::Empty) => {}
            Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                adv.state = AdviceState::NotHere("the search stopped".into());
                adv.job = None;
            }
        }
    }
    if adv.generation.is_some_and(|g| g != phys.generation) {
        // Another run (an edit, a reset, another level): its own advice, if it fails.
        *adv = WindowAdvice::default();
    }
    let (Some(checks), Some(answers)) = (&live.checks, &live.answers) else {
        return;
    };
    if adv.generation == Some(phys.generation) {
        return;
    }
    adv.generation = Some(phys.generation);
    let report = LevelReport {
        checks: checks.clone(),
        questions: answers.clone(),
        error: None,
        ..LevelReport::failed(&phys.scene.file, "")
    };
    if !advice::engine_failed(&report) {
        return;
    }
    if phys.interfered {
        adv.state = AdviceState::NotHere(
            "not searched: you pushed the scene during this run (reset and play it untouched)"
                .into(),
        );
        return;
    }
    let estimate = Estimate::of(&phys.scene.level, &phys.options, Mode::Check, None);
    if estimate.seconds * SEARCH_BUDGET > WINDOW_SEARCH_S {
        adv.state = AdviceState::NotHere(format!(
            "not searched in the window (up to {:.0} s of runs): `rigidlab check` prints it",
            estimate.seconds * SEARCH_BUDGET
        ));
        return;
    }
    #[cfg(target_arch = "wasm32")]
    {
        adv.state = AdviceState::NotHere(
            "the page does not search for settings; `rigidlab check` on the level file prints them"
                .into(),
        );
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let (tx, rx) = std::sync::mpsc::channel();
        let (scene, options) = (phys.scene.clone(), phys.options.clone());
        let spawned = std::thread::Builder::new()
            .name("rigidlab advice".into())
            .spawn(move || {
                let _ = tx.send(advice::advise(&scene, &options, 0.0));
            });
        adv.state = match spawned {
            Ok(_) => {
                adv.job = Some(std::sync::Mutex::new(rx));
                AdviceState::Searching
            }
            Err(e) => AdviceState::NotHere(format!("could not start the search: {e}")),
        };
    }
}
