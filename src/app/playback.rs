//! What play, pause and reset mean, for the keys and the playback panel alike.
//!
//! A level is an exercise with an end (`world.duration`, where `rigidlab check` stops): playing
//! at the end starts the exercise over rather than running past it unnoticed, and Reset puts
//! back everything a run changed (the stop at the end, the impulse tool's last arrow). Stepping
//! back goes to the step before by replaying the run.

use super::physics::Physics;
use super::tools::ToolState;

/// Play or pause. At the level's end (when the run stops there), play starts over from t = 0;
/// to run past the end, untick "stop at the level's end" first.
pub fn toggle_play(phys: &mut Physics, tools: &mut ToolState) {
    if phys.paused && phys.stop_at_end && phys.at_end() {
        restart(phys, tools);
    }
    phys.paused = !phys.paused;
}

/// One step back, paused: the run is replayed from t = 0 to the step before (see
/// `Physics::seek_steps`).
pub fn step_back(phys: &mut Physics) {
    let step = phys.seek.unwrap_or(phys.snapshot().step);
    if step > 0 {
        phys.paused = true;
        phys.seek = Some(step - 1);
    }
}

/// Back to t = 0 as the level opened: the run, the stop at the level's end, the impulse tool's
/// arrow. Paused or playing stays as it was.
pub fn restart(phys: &mut Physics, tools: &mut ToolState) {
    phys.reset();
    phys.stop_at_end = true;
    tools.last_impulse = None;
}
