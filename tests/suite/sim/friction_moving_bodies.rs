//! Friction between two moving bodies (issue 29, item 6): a disc rolling on a plank that a
//! constant force pulls along a smooth floor, and, for contrast, a block that static friction
//! carries on a pulled plank.
//!
//! The disc used to creep on the plank: rapier 0.36 acts a contact's friction at the midpoint
//! of the two surfaces, p/2 inside the disc's rim when the bodies overlap by p, so the disc
//! rolled about a radius r - p/2 and its rim slipped at omega p/2 (6.4 mm/s after 1 s here at
//! 1/240 s, 0.33 mm = p/2 at every setting; the friction force 0.25% high). rigidlab now puts a
//! ball's solver point on its rim (src/sim/contact_points.rs); this file holds that.

use crate::common;

use rigidlab::level::{parse, Precision};
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

const G: f64 = 9.81;

/// The bodies start just touching and the soft contacts take up their load in the first steps
/// (at 1 substep the slip there reached 1.6e-4 m/s for a disc and 1.4e-4 for a block, with or
/// without the fix): the slip is judged after them.
const SETTLE: f64 = 0.05;

// The disc on the plank. A uniform disc (m = 1.5 kg, r = 0.15 m, I = m r^2 / 2) on a plank
// (M = 3 kg) lying on a smooth floor; P = 15 N pulls the plank; mu = 0.5 between disc and plank.
// Assume rolling without slip; friction F on the disc, forward (+x), at its contact point:
//   disc:  F = m a_d;  I alpha = F r  (the contact point is (0, -r) from G: k x (0,-r) F... the
//          moment of (F, 0) at (0, -r) is +r F, counter-clockwise, so alpha > 0);
//   no slip: the disc's contact point moves with the plank: a_d + alpha r = a_p
//          (velocity of the point (0, -r): v_G + omega k x (0, -r) = v_G + (omega r, 0));
//          alpha r = F r^2 / I = 2 F / m = 2 a_d, so a_p = 3 a_d;
//   plank: M a_p = P - F = P - m a_d  ->  a_d = P / (3 M + m) = 15 / 10.5 = 1.4285714 m/s^2,
//          a_p = 4.2857143 m/s^2, F = 2.1428571 N, alpha = 2 a_d / r = 19.047619 rad/s^2.
//   F / N = 2.1428571 / (1.5 x 9.81) = 0.146 < mu = 0.5: rolling holds.
const M_PLANK: f64 = 3.0;
const M_DISC: f64 = 1.5;
const R: f64 = 0.15;
const P: f64 = 15.0;

fn disc_on_plank(duration: f64) -> String {
    format!(
        r#"Level(title: "disc on a pulled plank", effects: [gravity, contacts, friction],
        world: (dt: 0.004166666666666667, substeps: 4, duration: {duration}),
        bodies: [
            (name: "floor", kind: fixed, shape: Box(width: 60.0, height: 1.0), position: (10.0, -0.5)),
            (name: "plank", shape: Box(width: 12.0, height: 0.1), mass: {M_PLANK}, position: (0.0, 0.05)),
            (name: "disc", shape: Circle(radius: {R}), mass: {M_DISC}, position: (5.0, 0.25), friction: 0.5),
        ],
        loads: [(name: "P", body: "plank", force: Constant(({P}, 0.0)))])"#
    )
}

// The block on the plank. A block (m = 1 kg, 0.2 m square) on a plank (M = 4 kg) on a smooth
// floor, P = 10 N on the plank, mu = 0.5. Together: a = P / (M + m) = 2 m/s^2; the block needs
// F = m a = 2 N of friction, less than mu m g = 4.905 N: static friction carries it, no slip.
fn block_on_plank() -> String {
    r#"Level(title: "block carried on a pulled plank", effects: [gravity, contacts, friction],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 1.0),
        bodies: [
            (name: "floor", kind: fixed, shape: Box(width: 60.0, height: 1.0), position: (10.0, -0.5)),
            (name: "plank", shape: Box(width: 4.0, height: 0.1), mass: 4.0, position: (0.0, 0.05)),
            (name: "block", shape: Box(width: 0.2, height: 0.2), mass: 1.0, position: (0.5, 0.2), friction: 0.5),
        ],
        loads: [(name: "P", body: "plank", force: Constant((10.0, 0.0)))])"#
        .to_string()
}

/// One sample per step: (t, slip of the top body's contact point on the plank, v_top, v_plank,
/// omega_top). The contact point is `below` under the top body's mass center (its rim, or the
/// middle of its bottom face), the plank's point velocity there includes its own (tiny) omega.
fn series(text: &str, opts: &Options, below: f64) -> Vec<(f64, f64, f64, f64, f64)> {
    let scene = parse(Path::new("plank.ron"), text).unwrap_or_else(|e| panic!("{e}"));
    let mut out = Vec::new();
    runner::run_scene(&scene, opts, &HashMap::new(), |s| {
        let (p, d) = (&s.bodies[1], &s.bodies[2]);
        let point = d.com - glam::DVec2::new(0.0, below);
        let rd = point - d.com;
        let rp = point - p.com;
        let v_top = d.velocity + glam::DVec2::new(-rd.y, rd.x) * d.omega;
        let v_plank = p.velocity + glam::DVec2::new(-rp.y, rp.x) * p.omega;
        out.push((
            s.time,
            (v_top - v_plank).x,
            d.velocity.x,
            p.velocity.x,
            d.omega,
        ));
    })
    .unwrap();
    out
}

fn opts(dt: f64, substeps: usize, iterations: usize, precision: Precision) -> Options {
    Options {
        dt: Some(dt),
        substeps: Some(substeps),
        solver_iterations: Some(iterations),
        precision: Some(precision),
        ..Options::default()
    }
}

#[test]
fn a_disc_rolls_on_a_pulled_plank_without_creeping() {
    let a_d = P / (3.0 * M_PLANK + M_DISC);
    let a_p = 3.0 * a_d;
    let alpha = 2.0 * a_d / R;
    let text = disc_on_plank(1.0);
    for precision in [Precision::F32, Precision::F64] {
        for (dt, sub, it) in [
            (1.0 / 240.0, 4, 1),
            (1.0 / 240.0, 1, 1),
            (1.0 / 240.0, 16, 1),
            (1.0 / 240.0, 4, 8),
            (1.0 / 960.0, 4, 1),
        ] {
            let s = series(&text, &opts(dt, sub, it, precision), R);
            let worst = s.iter().filter(|x| x.0 > SETTLE).map(|x| x.1.abs());
            let worst = common::worst(worst);
            // Before the fix the rim crept 4.3e-3 to 6.4e-3 m/s by 1 s at these settings (the
            // creep grows with omega: omega p/2). Now a few 1e-6 m/s, except at 1 substep,
            // where the contact's settling leaves a transient that peaks at 1.3e-4 m/s (f64) at
            // 0.075 s and decays below 2e-5 by 0.5 s. 2e-4 m/s: 20x below the old creep.
            assert!(
                worst < 2e-4,
                "{precision:?} dt {dt} sub {sub} it {it}: slip up to {worst:.3e} m/s"
            );
            let (t, _, vd, vp, w) = *s.last().unwrap();
            // The velocities at 1 s against a t, alpha t. The friction force, 0.25% high with
            // the short rolling radius, moved v_d by 1.6e-3; now 3e-5 (the contact's settling
            // in its first steps). 3e-4 relative: 5x below the old error, 10x above the new.
            for (what, got, want) in [
                ("v_disc", vd, a_d * t),
                ("v_plank", vp, a_p * t),
                ("omega", w, alpha * t),
            ] {
                assert!(
                    ((got - want) / want).abs() < 3e-4,
                    "{precision:?} dt {dt} sub {sub} it {it}: {what} {got} for {want}"
                );
            }
        }
    }
}

#[test]
fn a_block_is_carried_by_static_friction_on_a_pulled_plank() {
    // a = P / (M + m) = 2 m/s^2 for both; the block's bottom face is 0.1 m below its center.
    let a = 10.0 / 5.0;
    assert!(1.0 * a < 0.5 * 1.0 * G, "static friction suffices");
    for precision in [Precision::F32, Precision::F64] {
        for (dt, sub) in [(1.0 / 240.0, 4), (1.0 / 240.0, 1), (1.0 / 960.0, 16)] {
            let s = series(&block_on_plank(), &opts(dt, sub, 1, precision), 0.1);
            let worst = s.iter().filter(|x| x.0 > SETTLE).map(|x| x.1.abs());
            let worst = common::worst(worst);
            // No rim, no creep: the disc's 2e-4 m/s (measured below 1e-4: the 1-substep
            // settling transient again).
            assert!(
                worst < 2e-4,
                "{precision:?} dt {dt} sub {sub}: slip {worst:.3e}"
            );
            let (t, _, vb, vp, _) = *s.last().unwrap();
            for (what, got) in [("v_block", vb), ("v_plank", vp)] {
                assert!(
                    ((got - a * t) / (a * t)).abs() < 3e-4,
                    "{precision:?} dt {dt} sub {sub}: {what} {got} for {}",
                    a * t
                );
            }
        }
    }
}

/// The slip against the disc's turn per step, f32 and f64. Until 2026-11-26 the rim slipped
/// 4e-3 to 4e-2 m/s once the disc turned more than about 0.1 rad a step (the rim point rapier's
/// rows ride turned away from the plank within the step); since sim/contact_points.rs follows
/// a spinning ball's contact, below 1.5e-5 m/s up to 0.64 rad a step (1/60 s, 4 substeps).
/// Printed, not asserted: run with --ignored.
#[test]
#[ignore]
fn measure_slip_against_turn_per_step() {
    let text = disc_on_plank(2.0);
    for precision in [Precision::F32, Precision::F64] {
        for (dt, sub, it) in [
            (1.0 / 60.0, 4, 1),
            (1.0 / 120.0, 4, 1),
            (1.0 / 240.0, 4, 1),
            (1.0 / 240.0, 1, 1),
            (1.0 / 240.0, 16, 1),
            (1.0 / 480.0, 4, 1),
            (1.0 / 960.0, 4, 1),
        ] {
            let s = series(&text, &opts(dt, sub, it, precision), R);
            let mut line = format!("{precision:?} dt 1/{:.0} sub {sub}:", 1.0 / dt);
            for t in [0.5, 1.0, 1.5, 2.0] {
                let x = s.iter().find(|x| x.0 >= t - 1e-9).unwrap();
                line += &format!(" t {t} (w dt {:.3}) slip {:+.2e} |", x.4 * dt, x.1);
            }
            println!("{line}");
        }
    }
}
