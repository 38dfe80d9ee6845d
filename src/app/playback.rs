//! What play, pause and reset mean, for the keys and the playback panel alike, and the
//! [`Playback`] they change (through `PhysicsCommand`s, applied in `physics.rs`).
//!
//! A level is an exercise with an end (`world.duration`, where `rigidlab check` stops): playing
//! at the end starts the exercise over rather than running past it unnoticed, and Reset puts
//! back everything a run changed (the stop at the end; the impulse tool's last arrow goes with
//! the run it struck, `tools.rs`). Stepping back goes to the step before by replaying the run.

use super::run::Run;
use bevy::prelude::*;

/// Whether and how the run plays: paused, single steps asked for, the stop at the level's end,
/// and the frame's budget for physics.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct Playback {
    pub paused: bool,
    /// Single steps requested while paused (run in `Update`).
    pub steps_requested: u32,
    /// Pause when the level's duration is reached (where `rigidlab check` stops).
    pub stop_at_end: bool,
    /// Wall time the physics may take per frame, ms: beyond it the remaining fixed steps of the
    /// frame are dropped (the scene runs slower than real time instead of freezing the window).
    pub frame_budget_ms: f64,
    /// Wall time the physics took this frame, ms.
    pub frame_ms: f64,
    /// Steps were dropped recently to keep the window responsive.
    pub behind: bool,
    /// Predict first (`panels/predict.rs`): the run is held at t = 0 until the student has
    /// answered; whatever would run it (play, step, seek, a push) is refused
    /// (`physics::refused_now`).
    pub answer_first: bool,
    /// How many asks the hold at t = 0 has refused so far (the panel says "answer first" when
    /// this grows).
    pub refused: u32,
}

impl Playback {
    pub fn new(paused: bool) -> Self {
        Playback {
            paused,
            steps_requested: 0,
            stop_at_end: true,
            frame_budget_ms: 30.0,
            frame_ms: 0.0,
            behind: false,
            answer_first: false,
            refused: 0,
        }
    }
}

/// Play or pause. At the level's end (when the run stops there), play starts over from t = 0;
/// to run past the end, untick "stop at the level's end" first.
pub fn toggle_play(run: &mut Run, playback: &mut Playback) {
    if play_restarts(run, playback) {
        restart(run, playback);
    }
    playback.paused = !playback.paused;
}

/// Play would start the run over: paused at the level's end, where the run stops.
pub fn play_restarts(run: &Run, playback: &Playback) -> bool {
    playback.paused && playback.stop_at_end && run.at_end()
}

/// One step back, paused: the run is replayed from t = 0 to the step before (see
/// `Run::seek_steps`).
pub fn step_back(run: &mut Run, playback: &mut Playback) {
    let step = run.seek.unwrap_or(run.snapshot().step);
    if step > 0 {
        playback.paused = true;
        run.seek = Some(step - 1);
    }
}

/// Back to t = 0 as the level opened: the run and the stop at the level's end. Paused or playing
/// stays as it was.
pub fn restart(run: &mut Run, playback: &mut Playback) {
    run.reset();
    playback.steps_requested = 0;
    playback.stop_at_end = true;
}
