//! Play, pause and reset as the keys and the playback panel do them (src/app/playback.rs).

use crate::common;

use glam::DVec2;
use rigidlab::app::physics::play_step;
use rigidlab::app::playback::{restart, toggle_play, Playback};
use rigidlab::app::Run;
use rigidlab::sim::Options;

/// The pendulum played until its playback paused (at the level's end, where it stops).
fn pendulum_at_its_end() -> (Run, Playback) {
    let scene = common::load("levels/kinetics/simple_pendulum.ron");
    let mut phys = Run::new(scene, Options::default());
    let mut play = Playback::new(false);
    while !play.paused {
        assert!(play_step(&mut phys, &mut play));
    }
    assert!(
        phys.at_end(),
        "the run paused before its end at t = {}",
        phys.snapshot().time
    );
    (phys, play)
}

/// The trap: Space at the end ran on past it and unticked "stop at the level's end".
#[test]
fn play_at_the_levels_end_starts_the_exercise_over() {
    let (mut phys, mut play) = pendulum_at_its_end();
    toggle_play(&mut phys, &mut play);
    assert!(!play.paused, "play did not play");
    assert_eq!(
        phys.snapshot().step,
        0,
        "play at the end did not start over"
    );
    assert!(play.stop_at_end, "the stop at the end was unticked");
}

/// Running past the end stays possible, but only when the user unticked the stop.
#[test]
fn play_at_the_end_runs_on_when_the_stop_is_off() {
    let (mut phys, mut play) = pendulum_at_its_end();
    let step = phys.snapshot().step;
    play.stop_at_end = false;
    toggle_play(&mut phys, &mut play);
    assert!(!play.paused);
    assert!(play_step(&mut phys, &mut play));
    assert_eq!(phys.snapshot().step, step + 1);
}

/// Reset puts back everything a run changed: t = 0, the stop at the end (the impulse arrow is
/// the tools', cleared where Reset is asked for: the playback panel and the R key).
#[test]
fn reset_restores_the_stop() {
    let (mut phys, mut play) = pendulum_at_its_end();
    play.stop_at_end = false;
    restart(&mut phys, &mut play);
    assert_eq!(phys.snapshot().step, 0);
    assert!(play.stop_at_end);
}

/// Step back and the timeline: going back replays the run from t = 0 with the user's pushes at
/// their steps, so the state reached is the run's own, bit for bit (rapier is deterministic), and
/// the live checks see every step again.
#[test]
fn a_seek_back_reaches_the_runs_own_state_with_the_users_push_replayed() {
    let scene = common::load("levels/kinetics/physical_pendulum.ron");
    let mut phys = Run::new(scene, Options::default());
    let bar = common::body_index(&phys.scene.level, "bar");
    let mut kept = None;
    for step in 0..120u64 {
        if step == 40 {
            let at = phys.snapshot().bodies[bar].com;
            assert!(phys.apply_impulse(bar, at, DVec2::new(0.8, 0.0)));
        }
        if step == 70 {
            kept = Some(phys.snapshot().clone());
        }
        assert!(phys.advance());
    }
    let kept = kept.unwrap();
    phys.seek = Some(70);
    let mut observed = 0;
    let mut done = false;
    while !done {
        done = phys.seek_steps(f64::INFINITY, |_| observed += 1);
    }
    let s = phys.snapshot();
    assert_eq!(s.step, 70);
    assert!(phys.interfered, "the push is still part of this run");
    for (a, b) in s.bodies.iter().zip(&kept.bodies) {
        assert_eq!(
            (a.com, a.angle, a.velocity, a.omega),
            (b.com, b.angle, b.velocity, b.omega)
        );
    }
    // The initial state and each of the 70 steps.
    assert_eq!(observed, 71);
    assert_eq!(phys.series.last().unwrap().t, s.time);

    // Back before the push: the push is dropped once the run goes on from there.
    phys.seek = Some(20);
    while !phys.seek_steps(f64::INFINITY, |_| {}) {}
    assert!(phys.interventions.is_empty() && !phys.interfered);
}

/// A budget-limited seek goes on next frame from where it stopped and ends at the same state.
#[test]
fn a_seek_within_a_frames_budget_resumes_next_frame() {
    let scene = common::load("levels/kinetics/physical_pendulum.ron");
    let mut phys = Run::new(scene.clone(), Options::default());
    for _ in 0..200 {
        assert!(phys.advance());
    }
    let want = phys.snapshot().bodies.clone();
    for _ in 0..10 {
        assert!(phys.advance());
    }
    phys.seek = Some(200);
    let mut frames = 0;
    while !phys.seek_steps(0.0, |_| {}) {
        frames += 1;
        assert!(frames < 1000);
    }
    assert!(frames > 1, "a zero budget should take one step a frame");
    for (a, b) in phys.snapshot().bodies.iter().zip(&want) {
        assert_eq!((a.com, a.omega), (b.com, b.omega));
    }
}
