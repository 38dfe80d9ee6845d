//! Play, pause and reset as the keys and the playback panel do them (src/app/playback.rs).
#![cfg(feature = "app")]

use glam::DVec2;
use rigidlab::app::playback::{restart, toggle_play};
use rigidlab::app::tools::ToolState;
use rigidlab::app::Physics;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

fn pendulum_at_its_end() -> Physics {
    let scene = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    let mut phys = Physics::new(scene, Options::default(), false);
    while !phys.paused {
        assert!(phys.advance());
    }
    assert!(phys.at_end(), "the run paused before its end at t = {}", phys.snapshot().time);
    phys
}

/// The trap: Space at the end ran on past it and unticked "stop at the level's end".
#[test]
fn play_at_the_levels_end_starts_the_exercise_over() {
    let mut phys = pendulum_at_its_end();
    let mut tools = ToolState::default();
    toggle_play(&mut phys, &mut tools);
    assert!(!phys.paused, "play did not play");
    assert_eq!(phys.snapshot().step, 0, "play at the end did not start over");
    assert!(phys.stop_at_end, "the stop at the end was unticked");
}

/// Running past the end stays possible, but only when the user unticked the stop.
#[test]
fn play_at_the_end_runs_on_when_the_stop_is_off() {
    let mut phys = pendulum_at_its_end();
    let mut tools = ToolState::default();
    let step = phys.snapshot().step;
    phys.stop_at_end = false;
    toggle_play(&mut phys, &mut tools);
    assert!(!phys.paused);
    assert!(phys.advance());
    assert_eq!(phys.snapshot().step, step + 1);
}

/// Reset puts back everything a run changed: t = 0, the stop at the end, the impulse arrow.
#[test]
fn reset_restores_the_stop_and_clears_the_impulse_arrow() {
    let mut phys = pendulum_at_its_end();
    let mut tools = ToolState::default();
    tools.last_impulse = Some((DVec2::ZERO, DVec2::X, 0.3));
    phys.stop_at_end = false;
    restart(&mut phys, &mut tools);
    assert_eq!(phys.snapshot().step, 0);
    assert!(phys.stop_at_end);
    assert!(tools.last_impulse.is_none());
}
