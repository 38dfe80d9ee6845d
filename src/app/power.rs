//! Redraw only when something changes (issue 17: a school computer without a GPU spent both its
//! cores drawing the same paused picture, main thread 100% and llvmpipe 2 x 87%). While the run
//! is paused, with no seek, step or edit to do, the window updates on input (and every half
//! second); playing, every frame. Measured with `ps` over 10 s paused: see docs/sandbox.md.
//!
//! bevy_egui 0.42 feeds egui a `ModifiersChanged` event every frame even when no key changed;
//! egui answers any event with an immediate repaint, so the window never waited. The repeated
//! event is dropped here before egui's pass.
//!
//! The page too (issue 33: a paused page in headless Chromium took 19 CPU-s per 10 s): winit's
//! web loop waits the same way, the browser's animation frames asked for only when needed.
//! `RIGIDLAB_CONTINUOUS` keeps every frame natively (Xvfb has no window manager to give the
//! window focus, and tests count frames).

use super::editor::EditorCommand;
use super::physics::PhysicsCommand;
use super::playback::Playback;
use super::run::Run;
use bevy::prelude::*;
use bevy::winit::{UpdateMode, WinitSettings};
use bevy_egui::{EguiInput, EguiInputSet, EguiPreUpdateSet};
use std::time::Duration;

pub struct PowerPlugin;

/// How often a paused window redraws with no input: every half second natively (the status
/// line's clock); 5 s in a page, where a frame drawn by SwiftShader on the CPU costs about
/// 0.17 CPU-s at 1280x800 (headless Chromium, 2026-11-26: 20 wake-ups in 10 s took 3.6 CPU-s).
const IDLE_WAKE: Duration = if cfg!(target_arch = "wasm32") {
    Duration::from_secs(5)
} else {
    Duration::from_millis(500)
};

/// Whether this window may wait for input at all (not asked for every frame).
pub fn enabled() -> bool {
    std::env::var_os("RIGIDLAB_CONTINUOUS").is_none()
}

impl Plugin for PowerPlugin {
    fn build(&self, app: &mut App) {
        if !enabled() {
            return;
        }
        app.add_systems(
            PreUpdate,
            drop_repeated_modifiers
                .after(EguiInputSet::WriteEguiEvents)
                .before(EguiPreUpdateSet::BeginPass),
        )
        .add_systems(Last, redraw_when_needed);
    }
}

/// True when the coming frames show something new without any input.
pub fn animating(phys: &Run, playback: &Playback) -> bool {
    !playback.paused || phys.seek.is_some() || playback.steps_requested > 0
}

fn drop_repeated_modifiers(
    mut inputs: Query<&mut EguiInput>,
    mut last: Local<Option<bevy_egui::egui::Modifiers>>,
) {
    for mut input in inputs.iter_mut() {
        input.0.events.retain(|e| match e {
            bevy_egui::egui::Event::ModifiersChanged(m) => {
                let changed = *last != Some(*m);
                *last = Some(*m);
                changed
            }
            _ => true,
        });
    }
}

fn redraw_when_needed(
    (phys, playback): (Res<Run>, Res<Playback>),
    edits: MessageReader<EditorCommand>,
    run_commands: MessageReader<PhysicsCommand>,
    settings: Option<ResMut<WinitSettings>>,
) {
    let Some(mut settings) = settings else {
        return;
    };
    // A command or an edit asked for this frame is applied in the next one: draw it.
    let want = if animating(&phys, &playback) || !edits.is_empty() || !run_commands.is_empty() {
        WinitSettings::game()
    } else {
        WinitSettings {
            focused_mode: UpdateMode::reactive(IDLE_WAKE),
            unfocused_mode: UpdateMode::reactive_low_power(IDLE_WAKE),
        }
    };
    if settings.focused_mode != want.focused_mode || settings.unfocused_mode != want.unfocused_mode
    {
        *settings = want;
    }
}
