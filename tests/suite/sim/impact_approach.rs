//! Impacts that do not depend on how the bodies approach (issue 13).
//!
//! A contact's normal and lever arms must be the ones of the instant of impact, not of the moment
//! rapier first saw the pair within its prediction distance. Two textbook impacts are started
//! from gaps of 0.1 mm, 1 mm, 1 cm and 10 cm, and their post-impact velocities are held to their
//! closed-form impulse solutions within 0.1%:
//!
//! - a wheel (disc r = 0.5 m, m = 2 kg, I_G = m r^2 / 2) rolling at v = 2 m/s (omega = -v/r) into
//!   the corner C of a curb of height h = 0.2 m, plastic and without slip at C (no gravity, so
//!   nothing else acts): H_C is conserved,
//!   H_C = I_G w0 + (r_G/C x m v)_z = -1 - 1.2 = -2.2 N m s,  I_C = I_G + m r^2 = 0.75 kg m^2,
//!   w' = H_C / I_C = w0 (1 - 2h/(3r)) = -2.933333 rad/s,  v_G' = w' k x r_G/C = (0.88, 1.173333) m/s
//!   (r_G/C = (-0.4, 0.3) m at contact; friction needed |J_t/J_n| = 0.167 < mu = 1);
//! - two equal discs (1 kg, r = 0.1 m), A at 2 m/s along x striking B at rest with the line of
//!   centers at 30 degrees, frictionless, e = 0.8 (IM-9, IM-11): along n = (cos 30, sin 30),
//!   v_An' = v_An (1 - e)/2, v_Bn' = v_An (1 + e)/2, tangential parts unchanged:
//!   v_A' = (0.65, -0.7794229) m/s, v_B' = (1.35, 0.7794229) m/s.
//!
//! rapier alone solves an impact as a speculative contact made within its prediction distance
//! (2 cm), bouncing a new contact at the end of the call before the bodies touch, with the normal
//! and lever arms of that call's start: from 1 cm the oblique discs were 1.8% off at dt = 1/240
//! s, 0.32% at 1/960, 0.12% at 1/3840 (first order in dt). rigidlab now plans each rapier call
//! around the impacts in it (sim/impacts.rs, the default for scenes of up to 64 moving bodies):
//! the prediction distance is lowered below the gap of approaching pairs, the call is cut at the
//! first time of impact, and the contact is made in a short call (1/64 of the step) where
//! rapier's soft contact acts nearly rigidly. Measured, over every gap and dt below: oblique
//! 3.4e-7 to 5.9e-6; curb 1.2e-6 to 4.8e-5 except 4.9e-4 (10 cm at 1/240 s). The tests hold
//! every case within 0.1% (the issue's bound), and rapier's own speculative contact
//! (`impact_cuts: Some(false)`) outside it, so the cut is what the pass rests on.

use crate::common;

use rigidlab::level;
use rigidlab::sim::{Options, Simulation};
use std::path::Path;

/// Runs a level's text and returns the final velocities (v_G, omega) of the named bodies.
fn final_state(text: &str, names: &[&str]) -> Vec<(f64, f64, f64)> {
    let cuts = Options {
        impact_cuts: Some(true),
        ..Default::default()
    };
    final_state_with(text, names, &cuts)
}

fn final_state_with(text: &str, names: &[&str], opts: &Options) -> Vec<(f64, f64, f64)> {
    let scene = level::parse(Path::new("approach.ron"), text).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Simulation::new(&scene, opts);
    sim.run(|_| {}).unwrap();
    let s = sim.snapshot();
    names
        .iter()
        .map(|n| {
            let b = &s.bodies[s.body_index(n).unwrap()];
            (b.velocity.x, b.velocity.y, b.omega)
        })
        .collect()
}

fn rel(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / scale
}

const GAPS: [f64; 4] = [1e-4, 1e-3, 1e-2, 1e-1];
const DTS: [f64; 3] = [1.0 / 240.0, 1.0 / 960.0, 1.0 / 3840.0];

/// `errors[d * GAPS.len() + g]` for DTS[d], GAPS[g]: every case within 0.1% of the impulse
/// solution (the issue's bound; see the module doc for the measured sizes).
fn assert_within_bound(errors: &[f64]) {
    for (k, e) in errors.iter().enumerate() {
        let (d, g) = (k / GAPS.len(), k % GAPS.len());
        assert!(
            *e < 1e-3,
            "gap {} m at dt {} s: {e:.3e} off the impulse solution",
            GAPS[g],
            DTS[d]
        );
    }
}

#[test]
fn a_wheel_hitting_a_curb_converges_to_the_impulse_solution_from_any_gap() {
    // Contact when |G - C| = r: G = (-0.4, 0.5) with C = (0, 0.2).
    let mut errors = Vec::new();
    for dt in DTS {
        for gap in GAPS {
            let x0 = -0.4 - gap;
            // The wheel needs (gap + ~0.03 m) / 2 m/s to arrive, then flies clear of the corner.
            let text = format!(
                r#"Level(
  title: "wheel into a curb", effects: [contacts, friction],
  world: (dt: {dt}, substeps: 4, duration: {dur}),
  bodies: [
    (name: "curb", kind: fixed, shape: Box(width: 1.0, height: 1.2), position: (0.5, -0.4), friction: 1.0),
    (name: "wheel", shape: Circle(radius: 0.5), mass: 2.0, position: ({x0}, 0.5), velocity: (2.0, 0.0), omega: -4.0),
  ],
)"#,
                dur = gap / 2.0 + 0.1
            );
            let v = final_state(&text, &["wheel"])[0];
            let errs = [
                rel(v.2, -2.933333333, 2.933333333),
                rel(v.0, 0.88, 1.466667),
                rel(v.1, 1.173333333, 1.466667),
            ];
            let e = common::worst(errs);
            println!("curb, dt {dt:.2e} s, gap {gap:.0e} m: v' = ({:.6}, {:.6}) m/s, w' = {:.6} rad/s, worst rel error {e:.2e}", v.0, v.1, v.2);
            errors.push(e);
        }
    }
    assert_within_bound(&errors);
}

#[test]
fn an_oblique_impact_of_two_discs_converges_to_the_impulse_solution_from_any_gap() {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let mut errors = Vec::new();
    for dt in DTS {
        for gap in GAPS {
            // At contact A is at the origin and B at 0.2 (cos 30, sin 30).
            let text = format!(
                r#"Level(
  title: "oblique discs", effects: [contacts, restitution],
  world: (dt: {dt}, substeps: 4, duration: {dur}),
  bodies: [
    (name: "A", shape: Circle(radius: 0.1), mass: 1.0, position: ({xa}, 0.0), velocity: (2.0, 0.0), restitution: 0.8),
    (name: "B", shape: Circle(radius: 0.1), mass: 1.0, position: ({xb}, {yb}), restitution: 0.8),
  ],
)"#,
                dur = gap / 2.0 + 0.1,
                xa = -gap,
                xb = 0.2 * c,
                yb = 0.2 * s
            );
            let v = final_state(&text, &["A", "B"]);
            let errs = [
                rel(v[0].0, 0.65, 2.0),
                rel(v[0].1, -0.7794229, 2.0),
                rel(v[1].0, 1.35, 2.0),
                rel(v[1].1, 0.7794229, 2.0),
            ];
            let e = common::worst(errs);
            println!(
            "oblique, dt {dt:.2e} s, gap {gap:.0e} m: v_A' = ({:.6}, {:.6}), v_B' = ({:.6}, {:.6}) m/s, worst rel error {e:.2e}",
            v[0].0, v[0].1, v[1].0, v[1].1
        );
            errors.push(e);
        }
    }
    assert_within_bound(&errors);
}

/// Without the cuts (rapier's speculative contact, made 2 cm out), the oblique impact from 1 cm
/// at 1/240 s is off by more than 1% (measured 1.8%): the test above passes because of the cut.
#[test]
fn without_impact_cuts_rapier_solves_the_oblique_impact_from_its_approach() {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let text = format!(
        r#"Level(
  title: "oblique discs", effects: [contacts, restitution],
  world: (dt: {dt}, substeps: 4, duration: 0.105),
  bodies: [
    (name: "A", shape: Circle(radius: 0.1), mass: 1.0, position: (-0.01, 0.0), velocity: (2.0, 0.0), restitution: 0.8),
    (name: "B", shape: Circle(radius: 0.1), mass: 1.0, position: ({xb}, {yb}), restitution: 0.8),
  ],
)"#,
        dt = 1.0 / 240.0,
        xb = 0.2 * c,
        yb = 0.2 * s
    );
    let off = Options {
        impact_cuts: Some(false),
        ..Default::default()
    };
    let v = final_state_with(&text, &["A", "B"], &off);
    let e = rel(v[0].0, 0.65, 2.0).max(rel(v[1].1, 0.7794229, 2.0));
    println!("oblique without cuts, 1 cm at 1/240 s: {e:.2e}");
    assert!(e > 1e-2, "rapier alone: {e:.3e}");
}
