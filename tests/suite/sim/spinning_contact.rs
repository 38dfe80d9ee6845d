//! A round body spinning in contact keeps its normal force (issue 29, class 1).
//!
//! rapier follows a contact's separation within a call from anchors fixed in each body, so a
//! spinning ball's anchor turned away from the floor and the solver saw the floor fall away at
//! the rim's centripetal acceleration r w^2: a disc (m = 1 kg, r = 0.2 m) placed touching a
//! smooth floor and spun at 5 rad/s got 0.49 to 0.75 of m g dt in its first step (about
//! 1 - r w^2 / g = 0.49 at many substeps), at 20 rad/s none, and sank 3.3 mm at 1/60 s
//! (2026-11-26). rigidlab now hands rapier the normal speed that cancels the drift and calls it
//! one substep at a time where the drift's residual over a call would disturb the contact, and
//! in the first step, where no load is known yet (sim/contact_points.rs, `spin_calls`).
//!
//! Statics give the expected values: a disc at rest on a floor but for its spin needs m g dt of
//! normal impulse every step, and sinks only as far as rapier's soft contact lets a disc that
//! does not spin (its twin below).

use rigidlab::level::parse;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

const G: f64 = 9.81;

/// (first step's normal impulse / (m g dt), lowest center height - r) for spin `omega`; the
/// disc listed before the floor when `disc_first` (rapier then takes it as the pair's first
/// collider or second: both signs of the correction).
fn spin_kick(omega: f64, dt: f64, substeps: usize, disc_first: bool) -> (f64, f64) {
    let floor = r#"(name: "floor", kind: fixed, shape: Box(width: 10.0, height: 0.2), position: (0.0, -0.1)),"#;
    let disc = format!(
        r#"(name: "disc", shape: Circle(radius: 0.2), mass: 1.0, position: (0.0, 0.2), omega: {omega}),"#
    );
    let bodies = if disc_first {
        format!("{disc}\n{floor}")
    } else {
        format!("{floor}\n{disc}")
    };
    let text = format!(
        r#"Level(title: "spin kick", effects: [gravity, contacts],
        world: (dt: {dt}, substeps: {substeps}, duration: 0.25),
        bodies: [{bodies}])"#
    );
    let scene = parse(Path::new("spin.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
    let d = usize::from(!disc_first);
    let mut first = None;
    let mut lowest = f64::INFINITY;
    runner::run_scene(&scene, &Options::default(), &HashMap::new(), |s| {
        if s.step == 1 {
            let n: f64 = s
                .contacts
                .iter()
                .flat_map(|c| c.points.iter().map(|p| p.normal_impulse))
                .sum();
            first = Some(n / (G * s.dt));
        }
        // f64::min would drop a NaN height: it must be measured.
        let y = s.bodies[d].com.y - 0.2;
        assert!(y.is_finite(), "t = {}: height {y}", s.time);
        lowest = lowest.min(y);
    })
    .unwrap();
    (first.unwrap(), lowest)
}

#[test]
fn a_disc_spun_on_a_floor_gets_its_whole_normal_impulse_and_sinks_no_deeper() {
    for dt in [1.0 / 60.0, 1.0 / 240.0, 1.0 / 960.0] {
        for substeps in [1, 4, 16] {
            // The twin that does not spin: how far rapier's soft contact lets a disc sink
            // (6.9e-5 m at 1/60 s over 0.25 s, less at finer steps).
            // Its own first impulse is statics' m g dt except at 1/960 s with 16 substeps in one
            // call, where rapier's soft contact starts with 0.989 of it (2026-11-27; a spinning
            // disc is stepped one substep a call and gets the whole of it).
            let (n0, sag) = spin_kick(0.0, dt, substeps, false);
            if substeps < 16 || dt > 1.0 / 960.0 {
                assert!(
                    (n0 - 1.0).abs() < 1e-5,
                    "no spin, dt {dt}, {substeps}: {n0}"
                );
            }
            for omega in [-5.0, -20.0, 50.0] {
                for disc_first in [false, true] {
                    let (n, sink) = spin_kick(omega, dt, substeps, disc_first);
                    let at = format!(
                        "omega {omega}, dt {dt}, {substeps} substeps, disc first {disc_first}"
                    );
                    // The first step's impulse is statics' m g dt: f32's rounding of the
                    // impulse sum, 1e-5 of it, is the bound.
                    assert!((n - 1.0).abs() < 1e-5, "{at}: first impulse {n}");
                    // It sinks as the twin does, within 2 um (the soft contact's sag itself
                    // differs by that between one-substep calls and one call of several).
                    assert!(sink > sag - 2e-6, "{at}: sank {sink}, the twin {sag}");
                }
            }
        }
    }
}
