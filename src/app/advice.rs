//! Advice beside the checks: when a run in the window ends with a check or a question failed,
//! the cheapest finer settings at which the level passes (`study::advice`, what `rigidlab check`
//! prints), searched on a thread of its own so the frames go on. Natively only: a page has no
//! threads to spare, and the panel says to run `rigidlab check` there.

use super::physics::{LiveChecks, PhysicsCommand};
use super::run::Run;
use crate::level::Precision;
use crate::report::{Advice, AdvisedSettings, LevelReport};
use crate::study::advice::{self, SEARCH_COST_S};
use bevy::prelude::*;

/// Where the advice for the run on screen is.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum AdviceState {
    /// Nothing failed (or nothing ran to the end yet).
    #[default]
    None,
    /// Searching on its thread.
    Searching,
    Ready(Advice),
    /// Not searched here, and why (the page, the run pushed).
    NotHere(String),
}

/// The advice for the scene's last run to its end.
#[derive(Resource, Default)]
pub struct WindowAdvice {
    /// The run (`Run::generation`) it is for.
    generation: Option<u64>,
    pub state: AdviceState,
    #[cfg(not(target_arch = "wasm32"))]
    job: Option<std::sync::Mutex<std::sync::mpsc::Receiver<Advice>>>,
}

impl WindowAdvice {
    /// The panel's line, if there is one to show: in the window's words (the solver panel's
    /// step, substeps and precision), not the command line's flags.
    pub fn line(&self) -> Option<String> {
        match &self.state {
            AdviceState::None => None,
            AdviceState::Searching => Some(format!(
                "advice: searching finer settings (at most {SEARCH_COST_S:.0} s of estimated runs, the window goes on)…"
            )),
            AdviceState::Ready(Advice::Settings {
                settings: s,
                cost_ratio,
                ..
            }) => Some(format!(
                "advice: passes at dt {:.6} s ({:.0} Hz), {} substeps, {}: {cost_ratio}x the level's cost (estimated)",
                s.dt,
                1.0 / s.dt,
                s.substeps,
                match s.precision {
                    Precision::F32 => "f32",
                    Precision::F64 => "f64",
                },
            )),
            AdviceState::Ready(a) => Some(a.line()),
            AdviceState::NotHere(why) => Some(format!("advice: {why}")),
        }
    }

    /// The settings advised, when there are some to try.
    pub fn settings(&self) -> Option<AdvisedSettings> {
        match &self.state {
            AdviceState::Ready(Advice::Settings { settings, .. }) => Some(*settings),
            _ => None,
        }
    }
}

/// The run's settings with the advised ones in (the solver panel shows them; its "level's
/// settings" goes back): the scene runs again at them.
pub fn try_settings(run: &Run, s: &AdvisedSettings) -> PhysicsCommand {
    let mut options = run.options.clone();
    options.dt = Some(s.dt);
    options.substeps = Some(s.substeps);
    options.precision = Some(s.precision);
    PhysicsCommand::Settings(options)
}

/// The advice under the checks: its line, and a button that reruns at the settings it names
/// (asked in `out`).
pub fn panel(
    ui: &mut bevy_egui::egui::Ui,
    advice: &WindowAdvice,
    phys: &Run,
    out: &mut Vec<PhysicsCommand>,
) {
    let Some(line) = advice.line() else {
        return;
    };
    ui.label(super::ui::rich(line, super::view::palette::FRICTION).small());
    if let Some(s) = advice.settings() {
        if ui
            .small_button("run at these settings")
            .on_hover_text("the solver panel takes them; \"level's settings\" there goes back")
            .clicked()
        {
            out.push(try_settings(phys, &s));
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

fn advise_failed_run(phys: Res<Run>, live: NonSend<LiveChecks>, mut adv: ResMut<WindowAdvice>) {
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
    // The search bounds itself (`study::advice`: SEARCH_COST_S of estimated runs at most, no
    // candidate started whose estimate would pass it) and runs on a thread of its own: the
    // frames go on.
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
        // The window's run is the level's at these options: its verdicts are the report the
        // search starts from (a failure no setting can change is said without a search).
        let own = report;
        let spawned = std::thread::Builder::new()
            .name("rigidlab advice".into())
            .spawn(move || {
                let _ = tx.send(advice::advise(&scene, &options, Some(&own)));
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
