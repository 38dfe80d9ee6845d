//! The normal force on a curve (issue 30, "Readings on curves"): `ContactForceFrom` with the
//! `Normal` component against a fixed `Arc` has the textbook's analysis from the state at the
//! instant, PN-2 along G's path (`analysis::curved_path`): N = m v^2 / rho + m g cos(theta)
//! inside a circle, N = m g cos(theta) - m v^2 / rho outside it, rho = R -+ r for a disc.
//!
//! Every expected value is derived below from energy (v^2 from the start's, RE-7) and PN-2 by
//! hand; the engine's reading and the analysis are each held to it.

use crate::common;

use common::{parse, run};
use rigidlab::questions::QuestionResult;
use rigidlab::sim::Options;

const G: f64 = 9.81;

fn questions(text: &str) -> Vec<QuestionResult> {
    run(&parse(text), &Options::default()).questions
}

fn question<'a>(qs: &'a [QuestionResult], id: &str) -> &'a QuestionResult {
    qs.iter()
        .find(|q| q.id == id)
        .unwrap_or_else(|| panic!("no {id}"))
}

/// Relative error of `x` against `expected`.
fn off(x: f64, expected: f64) -> f64 {
    (x - expected).abs() / expected.abs()
}

/// Prints a question's engine, analysis and hand values and their errors.
fn show(q: &QuestionResult) {
    println!(
        "{}: hand {:.6}, engine {:.6} ({:+.2e}), analysis {:?} ({:+.2e}) at t = {:.5}; {}",
        q.id,
        q.expected,
        q.engine,
        q.engine / q.expected - 1.0,
        q.analysis,
        q.analysis.map_or(f64::NAN, |a| a / q.expected - 1.0),
        q.time,
        q.note
    );
}

/// The analysis of question `id`, which must have one.
fn analysis(qs: &[QuestionResult], id: &str) -> f64 {
    let q = question(qs, id);
    q.analysis
        .unwrap_or_else(|| panic!("{id}: no analysis: {}", q.note))
}

/// A smooth puck (a disc, m = 0.1 kg, r = 0.05 m) slides inside a vertical ring of R = 0.5 m
/// centered at (0, 0.5): G rides a circle of rho = R - r = 0.45 m. It starts 30 degrees before
/// the bottom, theta0 = -30 deg, at v0 = 5 m/s along the path (counter-clockwise).
/// Energy, h the rise of G: v^2 = v0^2 - 2 g h, h = rho (cos(theta0) - cos(theta)):
///   bottom (theta = 0):  v^2 = 25 + 2 g rho (1 - cos 30 deg) = 26.182862 m^2/s^2,
///   side (theta = 90):   v^2 = v_bottom^2 - 2 g rho = 17.353862,
///   top (theta = 180):   v^2 = v_bottom^2 - 4 g rho = 8.524862 (> g rho = 4.4145: it stays on).
/// PN-2 inside: N = m v^2 / rho + m g cos(theta):
///   bottom 5.818414 + 0.981 = 6.799414 N, side 3.856414 N, top 1.894414 - 0.981 = 0.913414 N.
/// Frictionless, the whole contact force is N: `Magnitude` has the same analysis.
///
/// Three things are held apart:
/// - the engine's speed against energy: a fast rider on a concave faceted track loses energy
///   in proportion to dt (docs/known-gaps.md; 0.7% of v at the loop's top at this dt);
///   measured 4.9e-4, 3.3e-3, 9.2e-3 low at bottom, side, top: allowed 1e-3, 5e-3, 1.2e-2.
///   N_top = m (v^2 - g rho) / rho magnifies it: the analysis, from the engine's speed, reads
///   3.8% under the hand's 0.9134 N, and so does the engine;
/// - the analysis against PN-2 worked by hand with the engine's own speed at the same instant:
///   the same formula from the same state, the analysis averaged over the 0.01 s window
///   (trapezoid) where the hand takes the sample: N varies smoothly, so the mean over +-5 ms
///   differs by N'' w^2 / 24, below 1e-4 here; allowed 1e-3;
/// - the engine's N over the window against the analysis: the facets give N one vertex at a
///   time (2.3 vertices a step at 5 m/s), averaged over 48 steps; measured 1.2e-4 to 1.7e-4,
///   1.4e-3 to 5.9e-3, 3.4e-3 to 9.3e-4 at bottom, side and top in two builds of the engine
///   this day; allowed 1e-2 (docs/known-gaps.md: 4.1% over 48 steps at the loop's 6 m/s and
///   1.4 vertices a step).
#[test]
fn a_puck_sliding_inside_a_vertical_ring() {
    let (m, rho, v0, th0) = (0.1, 0.45, 5.0, -30f64.to_radians());
    let vb2 = v0 * v0 + 2.0 * G * rho * (1.0 - th0.cos());
    let v2 = [vb2, vb2 - 2.0 * G * rho, vb2 - 4.0 * G * rho];
    let cos = [1.0, 0.0, -1.0];
    let hand_n = |v2: f64, cos: f64| m * v2 / rho + m * G * cos;
    let (x0, y0) = (rho * th0.sin(), 0.5 - rho * th0.cos());
    let (vx, vy) = (v0 * th0.cos(), v0 * th0.sin());
    let at = [
        "Crossing(of: X(\"puck\"), value: 0.0)",
        "Crossing(of: Y(\"puck\"), value: 0.5)",
        "MaxOf(of: Y(\"puck\"))",
    ];
    let mut qs = String::new();
    for (k, name) in ["bottom", "side", "top"].iter().enumerate() {
        let (n, v) = (hand_n(v2[k], cos[k]), v2[k].sqrt());
        let w = at[k];
        qs += &format!(
            r#"(id: "N_{name}", ask: "N", unit: "N", expected: {n}, tolerance: 0.05, why: "t",
               quantity: ContactForceFrom(body: "puck", other: "ring", component: Normal, window: 0.01), at: {w}),
               (id: "F_{name}", ask: "F", unit: "N", expected: {n}, tolerance: 0.05, why: "t",
               quantity: ContactForceFrom(body: "puck", other: "ring", component: Magnitude, window: 0.01), at: {w}),
               (id: "v_{name}", ask: "v", unit: "m/s", expected: {v}, tolerance: 0.05, why: "t",
               quantity: Speed("puck"), at: {w}),
            "#
        );
    }
    let qs = questions(&format!(
        r#"Level(title: "puck in a ring", effects: [gravity, contacts],
        world: (dt: 0.00020833333333333335, substeps: 4, duration: 0.5),
        bodies: [
          (name: "ring", kind: fixed, shape: Arc(center: (0.0, 0.5), radius: 0.5, start: 0.0, end: 6.283185307179586, side: inside)),
          (name: "puck", shape: Circle(radius: 0.05), mass: 0.1, position: ({x0}, {y0}), velocity: ({vx}, {vy})),
        ],
        questions: [{qs}])"#
    ));
    for q in &qs {
        show(q);
    }
    for (k, (name, v_tol)) in [("bottom", 1e-3), ("side", 5e-3), ("top", 1.2e-2)]
        .into_iter()
        .enumerate()
    {
        let v = question(&qs, &format!("v_{name}")).engine;
        assert!(off(v, v2[k].sqrt()) < v_tol, "v_{name} = {v}");
        let n = analysis(&qs, &format!("N_{name}"));
        let from_engine_speed = hand_n(v * v, cos[k]);
        assert!(
            off(n, from_engine_speed) < 1e-3,
            "N_{name}: analysis {n}, by hand from the engine's speed {from_engine_speed}"
        );
        let engine = question(&qs, &format!("N_{name}")).engine;
        assert!(
            off(engine, n) < 1e-2,
            "N_{name}: engine {engine}, analysis {n}"
        );
        // Frictionless: the magnitude is N, with the same analysis (the window's mean force
        // vector's length, where `Normal` projects it on the sample's contact normal: they
        // differ by 1 - cos of the normal's facet-sized tilt, measured 2.7e-6).
        let f = question(&qs, &format!("F_{name}"));
        assert!(off(analysis(&qs, &format!("F_{name}")), n) < 1e-5);
        assert!(off(f.engine, engine) < 1e-5, "F_{name} {}", f.engine);
    }
}

/// A uniform disc (m = 1 kg, r = 0.2 m, mu = 0.8) rolls without slipping inside a fixed ring of
/// R = 1 m (rho = 0.8 m), released from rest at theta0 = 60 degrees. Rolling (omega = v / r),
/// T = 3/4 m v^2, so energy gives v^2 = (4/3) g rho (cos(theta) - cos(theta0)). Friction at
/// the contact is tangent to the ring, at right angles to the radius through G, so PN-2 along
/// the radius is N = m v^2 / rho + m g cos(theta) as for a particle:
///   theta = 30 deg: v^2 = (4/3) g rho (cos 30 - 0.5) = 3.830140, N = 4.787675 + 8.495709
///   = 13.283384 N; bottom: v^2 = (2/3) g rho = 5.232, N = m g (1 + 2/3) = 16.35 N.
/// Rolling holds: the friction needed is largest at the start, tan(60 deg) / 3 = 0.577 < mu.
/// With friction the whole force is not N: `Magnitude` keeps Newton's analysis over the window.
/// Held apart as for the puck: the engine's speed against energy (measured -3.8e-4 and -4.6e-4
/// until 2026-11-26; since a spinning ball is stepped one substep a call, -7.8e-4 and -2.1e-3,
/// docs/known-gaps.md on concave faceted tracks: allowed 3e-3), the analysis against PN-2 by hand from the engine's speed (1e-3), and the
/// engine's N over 0.02 s (21 steps of 1/1050 s at 2.0 to 2.3 m/s, 2.1 to 2.5 vertices a step)
/// against the analysis: measured 3.0e-3 and 2.9e-4, allowed 7e-3.
#[test]
fn a_disc_rolling_inside_a_ring() {
    let (m, rho, th0) = (1.0, 0.8, 60f64.to_radians());
    let th = 30f64.to_radians();
    let v2 = |th: f64| 4.0 / 3.0 * G * rho * (th.cos() - th0.cos());
    let hand_n = |v2: f64, th: f64| m * v2 / rho + m * G * th.cos();
    let (x0, y0) = (rho * th0.sin(), -rho * th0.cos());
    let x30 = rho * th.sin();
    let (n30, n0) = (hand_n(v2(th), th), hand_n(v2(0.0), 0.0));
    let (v30, v0) = (v2(th).sqrt(), v2(0.0).sqrt());
    let qs = questions(&format!(
        r#"Level(title: "disc in a ring", effects: [gravity, contacts, friction],
        world: (dt: 0.0009523809523809524, substeps: 4, duration: 0.7),
        bodies: [
          (name: "ring", kind: fixed, shape: Arc(radius: 1.0, start: -1.5707963267948966, end: 4.71238898038469, side: inside)),
          (name: "disc", shape: Circle(radius: 0.2), mass: 1.0, friction: 0.8, position: ({x0}, {y0})),
        ],
        questions: [
          (id: "N_30", ask: "N", unit: "N", expected: {n30}, tolerance: 0.05, why: "t",
           quantity: ContactForceFrom(body: "disc", other: "ring", component: Normal, window: 0.02), at: Crossing(of: X("disc"), value: {x30})),
          (id: "v_30", ask: "v", unit: "m/s", expected: {v30}, tolerance: 0.05, why: "t",
           quantity: Speed("disc"), at: Crossing(of: X("disc"), value: {x30})),
          (id: "N_bottom", ask: "N", unit: "N", expected: {n0}, tolerance: 0.05, why: "t",
           quantity: ContactForceFrom(body: "disc", other: "ring", component: Normal, window: 0.02), at: Crossing(of: X("disc"), value: 0.0)),
          (id: "v_bottom", ask: "v", unit: "m/s", expected: {v0}, tolerance: 0.05, why: "t",
           quantity: Speed("disc"), at: Crossing(of: X("disc"), value: 0.0)),
          (id: "F_bottom", ask: "F", unit: "N", expected: {n0}, tolerance: 0.05, why: "t",
           quantity: ContactForceFrom(body: "disc", other: "ring", component: Magnitude, window: 0.02), at: Crossing(of: X("disc"), value: 0.0)),
        ])"#
    ));
    for q in &qs {
        show(q);
    }
    for (name, th) in [("30", th), ("bottom", 0.0)] {
        let v = question(&qs, &format!("v_{name}")).engine;
        assert!(off(v, v2(th).sqrt()) < 3e-3, "v_{name} = {v}");
        let n = analysis(&qs, &format!("N_{name}"));
        let from_engine_speed = hand_n(v * v, th);
        assert!(
            off(n, from_engine_speed) < 1e-3,
            "N_{name}: analysis {n}, by hand from the engine's speed {from_engine_speed}"
        );
        let engine = question(&qs, &format!("N_{name}")).engine;
        assert!(
            off(engine, n) < 7e-3,
            "N_{name}: engine {engine}, analysis {n}"
        );
    }
    // The whole force with friction is not N alone: Newton's analysis over the window (6/1),
    // m a_G - m g from the engine's momentum, which its contact impulses make (1e-5).
    let f = question(&qs, "F_bottom");
    assert!(f.analysis.is_some_and(|a| off(a, f.engine) < 1e-5), "{f:?}");
}

/// A small smooth block (a disc, m = 1 kg, r = 0.05 m) over the top of a fixed cylinder of
/// R = 1 m (an `outside` arc over its upper half): G rides rho = R + r = 1.05 m, starting at the
/// top at v0 = 0.3 m/s. With theta from the top, energy gives v^2 = v0^2 + 2 g rho (1 -
/// cos(theta)), and PN-2 outside N = m g cos(theta) - m v^2 / rho
///   = m g (3 cos(theta) - 2) - m v0^2 / rho,
/// zero at cos(theta) = 2/3 + v0^2 / (3 g rho) = 0.669580 (from rest, 2/3): it leaves there,
/// G at y = rho cos(theta) = 0.703058 m.
///   theta = 30 deg: v^2 = 0.09 + 2 g rho (1 - cos 30) = 2.850174, N = 8.495709 - 2.714451
///   = 5.781258 N; theta = 45 deg (3 degrees before it leaves): N = m g (3 cos 45 - 2) -
///   0.085714 = 1.104140 N, v = 2.474650 m/s.
fn cylinder(opts: &Options) -> Vec<QuestionResult> {
    let (m, rho, v0) = (1.0, 1.05, 0.3);
    let n_at = |th: f64| m * G * (3.0 * th.cos() - 2.0) - m * v0 * v0 / rho;
    let cos_leave = 2.0 / 3.0 + v0 * v0 / (3.0 * G * rho);
    let (t30, t45) = (30f64.to_radians(), 45f64.to_radians());
    let v = |th: f64| (v0 * v0 + 2.0 * G * rho * (1.0 - th.cos())).sqrt();
    let text = format!(
        r#"Level(title: "block over a cylinder", effects: [gravity, contacts],
        world: (dt: 0.00020833333333333335, substeps: 4, duration: 1.0),
        bodies: [
          (name: "cylinder", kind: fixed, shape: Arc(radius: 1.0, start: 0.0, end: 3.141592653589793, side: outside)),
          (name: "block", shape: Circle(radius: 0.05), mass: 1.0, position: (0.0, 1.05), velocity: (0.3, 0.0)),
        ],
        questions: [
          (id: "N_30", ask: "N", unit: "N", expected: {n30}, tolerance: 0.05, why: "t",
           quantity: ContactForceFrom(body: "block", other: "cylinder", component: Normal, window: 0.01), at: Crossing(of: X("block"), value: {x30})),
          (id: "v_30", ask: "v", unit: "m/s", expected: {v30}, tolerance: 0.05, why: "t",
           quantity: Speed("block"), at: Crossing(of: X("block"), value: {x30})),
          (id: "N_45", ask: "N", unit: "N", expected: {n45}, tolerance: 0.05, why: "t",
           quantity: ContactForceFrom(body: "block", other: "cylinder", component: Normal, window: 0.01), at: Crossing(of: X("block"), value: {x45})),
          (id: "v_45", ask: "v", unit: "m/s", expected: {v45}, tolerance: 0.05, why: "t",
           quantity: Speed("block"), at: Crossing(of: X("block"), value: {x45})),
          (id: "y_leave", ask: "y", unit: "m", expected: {y_leave}, tolerance: 0.05, why: "t",
           quantity: Y("block"), at: ContactEnds(body: "block", other: "cylinder")),
        ])"#,
        n30 = n_at(t30),
        n45 = n_at(t45),
        v30 = v(t30),
        v45 = v(t45),
        x30 = rho * t30.sin(),
        x45 = rho * t45.sin(),
        y_leave = rho * cos_leave,
    );
    run(&parse(&text), opts).questions
}

/// The block over the cylinder at the level's settings, 16 substeps and dt/2. On the convex
/// side nothing takes energy: the engine's speed is within 3e-4 of energy's (allowed 1e-3).
/// The analysis against PN-2 by hand from the engine's speed: 1e-3 of m g (N at 45 degrees is
/// a difference of two near-equal terms, 1.1 N of m g = 9.81 N). The engine's N over 0.01 s at
/// 30 degrees (0.6 vertices a step) against the analysis: measured 2.4e-4 to 1.6e-3; allowed
/// 3e-3. Near the leaving point the engine's N comes in bursts as it fades (0.01 s at 45
/// degrees: from -39% to +19% of N over the three settings and two builds of the engine this
/// day, up to 4.3% of m g), and it leaves between 1.1% low and 2.4% high in y:
/// docs/known-gaps.md, allowed 3% there and nothing asked of the engine's N at 45 degrees.
#[test]
fn a_block_over_the_top_of_a_cylinder() {
    let (m, rho) = (1.0, 1.05);
    let hand_n = |v: f64, th: f64| m * G * th.cos() - m * v * v / rho;
    let dt = 0.00020833333333333335;
    for (dt, substeps) in [(None, None), (None, Some(16)), (Some(dt / 2.0), None)] {
        let qs = cylinder(&Options {
            dt,
            substeps,
            ..Options::default()
        });
        println!("dt {dt:?}, substeps {substeps:?}");
        for q in &qs {
            show(q);
        }
        for (name, th) in [("30", 30f64.to_radians()), ("45", 45f64.to_radians())] {
            let v = question(&qs, &format!("v_{name}"));
            assert!(off(v.engine, v.expected) < 1e-3, "{v:?}");
            let n = analysis(&qs, &format!("N_{name}"));
            let from_engine_speed = hand_n(v.engine, th);
            assert!(
                (n - from_engine_speed).abs() < 1e-3 * m * G,
                "N_{name}: analysis {n}, by hand from the engine's speed {from_engine_speed}"
            );
        }
        let n30 = question(&qs, "N_30");
        assert!(off(n30.engine, analysis(&qs, "N_30")) < 3e-3, "{n30:?}");
        let y = question(&qs, "y_leave");
        assert!(off(y.engine, y.expected) < 3e-2, "{y:?}");
    }
}
