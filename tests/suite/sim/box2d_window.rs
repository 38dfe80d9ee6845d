//! The window's simulation (`AnySimulation`) runs the engine the level or the options name
//! (issue 46): Box2D on its own thread (`sim::box2d::Threaded`, boxdd's world is `!Send`), step
//! for step the snapshots the runner's Box2D gives; a level Box2D refuses runs rapier with the
//! refusal kept for the window to show, never silently.

use crate::common;
use rigidlab::level::PhysicsEngine;
use rigidlab::sim::box2d::Simulation;
use rigidlab::sim::Options;
use rigidlab::simulation::AnySimulation;

fn on(engine: PhysicsEngine) -> Options {
    Options {
        engine: Some(engine),
        ..Options::default()
    }
}

/// The library's bar pendulum on Box2D through the window's simulation and directly: Box2D is
/// deterministic on one thread, so the two must agree exactly, every step (a copy sent over a
/// channel changes no bit).
#[test]
fn the_window_runs_box2d_on_its_thread_as_the_runner_does() {
    let scene = common::load("levels/kinetics/classic_physical_pendulum_small.ron");
    let opts = on(PhysicsEngine::Box2d);
    let mut window = AnySimulation::new(&scene, &opts);
    assert_eq!(window.engine(), PhysicsEngine::Box2d);
    assert!(window.refused.is_none());
    let mut direct = Simulation::new(&scene, &opts).expect("Box2D runs the level");
    assert_eq!(window.total_steps(), direct.total_steps());
    for _ in 0..500 {
        let a = window.step().expect("steps").clone();
        let b = direct.step().expect("steps");
        assert_eq!(&a, b, "step {}", b.step);
    }
    // A blow goes to the same thread and does there what it does to the runner's Box2D.
    let at = window.snapshot().bodies[1].com + glam::DVec2::new(0.0, -0.5);
    let j = glam::DVec2::new(1.0, 0.0);
    assert!(window.apply_impulse(1, at, j));
    assert!(direct.apply_impulse(1, at, j));
    for _ in 0..10 {
        let a = window.step().expect("steps").clone();
        assert_eq!(&a, direct.step().expect("steps"));
    }
    assert!(
        window.snapshot().bodies[1].omega.abs() > 1.0,
        "the blow turned the bar: omega {}",
        window.snapshot().bodies[1].omega
    );
}

/// A level with a spring asked for on Box2D: rapier runs it, and the refusal names the spring.
#[test]
fn a_level_box2d_refuses_runs_rapier_and_says_why() {
    let scene = common::load("levels/energy/classic_spring_block.ron");
    let sim = AnySimulation::new(&scene, &on(PhysicsEngine::Box2d));
    assert_eq!(sim.engine(), PhysicsEngine::Rapier);
    let why = sim.refused.as_deref().unwrap_or_default();
    assert!(why.contains("spring") && why.contains("box2d"), "{why}");
    let plain = AnySimulation::new(&scene, &Options::default());
    assert!(plain.refused.is_none());
}
