//! The window's frame rate, as the user sees it: the median frame time over the last two
//! seconds or so (120 frames), from Bevy's real-time clock. The status bar shows it, and the web
//! page publishes it, so anyone can tell what a school computer without a GPU draws.

use bevy::prelude::*;
use std::collections::VecDeque;

/// How many frames the median is taken over.
const WINDOW: usize = 120;

#[derive(Resource, Debug, Default, Clone)]
pub struct FrameRate {
    frame_ms: VecDeque<f64>,
    /// Frames drawn since the app started.
    pub frames: u64,
}

impl FrameRate {
    /// Records one frame that took `ms` milliseconds (0 and non-finite values are skipped: the
    /// first frame has no duration).
    pub fn record(&mut self, ms: f64) {
        self.frames += 1;
        if ms > 0.0 && ms.is_finite() {
            if self.frame_ms.len() == WINDOW {
                self.frame_ms.pop_front();
            }
            self.frame_ms.push_back(ms);
        }
    }

    /// The median frame time of the window, ms (None before the second frame).
    pub fn median_ms(&self) -> Option<f64> {
        let mut v: Vec<f64> = self.frame_ms.iter().copied().collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        Some(v[v.len() / 2])
    }

    /// Frames per second from the median frame time.
    pub fn fps(&self) -> Option<f64> {
        self.median_ms().map(|m| 1e3 / m)
    }
}

pub struct FrameRatePlugin;

impl Plugin for FrameRatePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<FrameRate>()
            .add_systems(First, count_frame);
    }
}

fn count_frame(
    time: Res<Time<Real>>,
    mut rate: ResMut<FrameRate>,
    mut exit: MessageWriter<AppExit>,
    phys: Option<Res<super::run::Run>>,
    playback: Option<Res<super::playback::Playback>>,
) {
    // Paused, a native window waits for input (app/power.rs): those waits are not frame times.
    let waiting = super::power::enabled()
        && phys
            .zip(playback)
            .is_some_and(|(p, b)| !super::power::animating(&p, &b));
    if waiting {
        rate.frames += 1;
    } else {
        rate.record(time.delta_secs_f64() * 1e3);
    }
    // RIGIDLAB_EXIT_AFTER_FRAMES=N closes the window after N frames (the window test's clean end).
    if let Some(n) = std::env::var("RIGIDLAB_EXIT_AFTER_FRAMES")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
    {
        if rate.frames >= n {
            exit.write(AppExit::Success);
        }
    }
    // RIGIDLAB_FPS_LOG=1 prints the rate every 120 frames: how the figures in docs/sandbox.md for a
    // software-rendered window were measured, and a way to check a school computer.
    if rate.frames.is_multiple_of(WINDOW as u64) && std::env::var_os("RIGIDLAB_FPS_LOG").is_some() {
        if let Some(ms) = rate.median_ms() {
            info!("frame rate: {:.1} fps (median frame {ms:.1} ms)", 1e3 / ms);
        }
    }
}
