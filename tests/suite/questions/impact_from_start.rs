//! An impact after a free flight from the level's start: the analysis starts from the start's
//! state carried in closed form, not from the engine's step before the touch (issue 41: "no
//! analysis value disagrees with a correct hand answer beyond its tolerance while claiming to
//! apply"; questions/free_flight.rs).
//!
//! Symplectic Euler keeps a falling body's velocity exact under constant gravity but leads its
//! position by g h t / 2 (h the substep, t the time flown), so the engine lands early and slow:
//! the fourth new user's n3_11 (a disc dropped 5.8 mm onto an incline) lands at 0.3316 for
//! 0.33657 m/s at its 1/240 s and 4 substeps, and the energy lost, read by the impact solution
//! from that state, was 2.95e-2 off the hand answer (tolerance 2e-2).

use crate::common;

use common::{parse, rel, run};
use rigidlab::sim::Options;

const G: f64 = 9.81;

fn opts(dt: f64, substeps: usize) -> Options {
    Options {
        dt: Some(dt),
        substeps: Some(substeps),
        ..Options::default()
    }
}

/// n3_11: a uniform disc (m = 2 kg, R = 0.2 m, mu = 0.6) released from rest with its rim 5 mm
/// above a 30 degree incline, measured along the normal; a plastic rough landing (e = 0).
/// The gap closes along the normal at v cos 30, so it falls d = 0.005 / cos 30 and lands at
/// v = sqrt(2 g d): v_n = v cos 30 into the face, v_t = v sin 30 down it. H about the contact
/// point is kept (MK 6/17, gravity not impulsive): m v_t R = 3/2 m R^2 w', so it rolls at
/// v' = 2/3 v_t (the friction impulse m v_t / 3 is 0.19 of mu m v_n: no slip). Lost:
/// 1/2 m v^2 - 3/4 m v'^2 = 0.0943968 J.
fn disc_onto_incline() -> (rigidlab::level::Scene, f64) {
    let (m, r) = (2.0f64, 0.2f64);
    let th = 30f64.to_radians();
    let d = 0.005 / th.cos();
    let v = (2.0 * G * d).sqrt();
    let v_after = 2.0 / 3.0 * v * th.sin();
    let lost = 0.5 * m * v * v - 0.75 * m * v_after * v_after;
    // G 0.205 m from the face along its normal, over the point (0, 0) of the face.
    let (gx, gy) = (-0.205 * th.sin(), 0.205 * th.cos());
    let scene = parse(&format!(
        r#"Level(title: "disc dropped onto an incline", effects: [gravity, contacts, friction],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 0.1),
        bodies: [
          (name: "incline", kind: fixed, shape: Box(width: 12.0, height: 1.0), angle: {th},
           position: ({px}, {py})),
          (name: "disc", shape: Circle(radius: {r}), mass: {m}, position: ({gx}, {gy}), friction: 0.6),
        ],
        questions: [
          (id: "lost", ask: "energy lost", unit: "J", expected: {lost}, tolerance: 2e-2,
           quantity: EnergyLost(body: "disc", other: "incline"), at: End, why: "test"),
        ])"#,
        px = 0.5 * th.sin(),
        py = -0.5 * th.cos(),
    ));
    (scene, lost)
}

#[test]
fn a_landing_after_a_drop_from_rest_is_analysed_from_the_start() {
    // The parabola from the start is exact: what remains is the impact solution's own reading
    // of the engine's contact (its normal and point, the touching root), 1.7e-6 measured at
    // 1/240 s on 2026-12-07. Allowed 1e-4 at every setting; before, 2.95e-2 at 1/240 s. (At
    // 1/60 s the disc approaches at 0.29 m/s, less than gravity closes in two steps, 0.33: no
    // impact solution, docs/levels.md.)
    let (scene, lost) = disc_onto_incline();
    for (dt, n) in [(1.0 / 240.0, 4), (1.0 / 120.0, 4), (1.0 / 240.0, 8)] {
        let r = run(&scene, &opts(dt, n));
        let q = &r.questions[0];
        let analysis = q.analysis.expect("an impact analysis");
        eprintln!(
            "dt {dt:.4}, {n} substeps: analysis {analysis}, engine {}, hand {lost}",
            q.engine
        );
        assert!(
            rel(analysis, lost) < 1e-4,
            "dt {dt:.4}, {n} substeps: the analysis read {analysis} J for {lost} J ({})",
            q.note
        );
    }
}

/// The twin, started differently: a disc (m = 1 kg, r = 0.1 m) thrown up and across with spin,
/// G at 0.6 m over a smooth floor whose top is y = 0, at (1.5, 2.0) m/s and 4 rad/s; e = 0.5.
/// Smooth: only the normal velocity changes, v_n^2 = 2.0^2 + 2 g (0.6 - 0.1) at the touch,
/// reversed to e v_n. Lost (IM-14): 1/2 m v_n^2 (1 - e^2); the floor's impulse (IM-9):
/// m (1 + e) v_n. `blow` adds a downward impulse of 1 N s at 0.1 s: the flight from the start
/// then ends, and the analysis must start from the engine's state after the blow (v_n^2 from the
/// blow's state, v_b = 2.0 - 0.1 g - 1 at y_b = 0.6 + 0.2 - g 0.01 / 2).
fn thrown_disc(blow: bool) -> (rigidlab::level::Scene, f64, f64) {
    let (m, e) = (1.0f64, 0.5f64);
    let v_n2 = if blow {
        let (vb, yb) = (2.0 - 0.1 * G - 1.0, 0.6 + 0.2 - 0.5 * G * 0.01);
        vb * vb + 2.0 * G * (yb - 0.1)
    } else {
        2.0 * 2.0 + 2.0 * G * 0.5
    };
    let lost = 0.5 * m * v_n2 * (1.0 - e * e);
    let impulse = m * (1.0 + e) * v_n2.sqrt();
    let events = if blow {
        r#"events: [Impulse(name: "push", at: 0.1, body: "disc", impulse: (0.0, -1.0))],"#
    } else {
        ""
    };
    let scene = parse(&format!(
        r#"Level(title: "thrown disc", effects: [gravity, contacts, restitution],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 0.8),
        bodies: [
          (name: "floor", kind: fixed, shape: Box(width: 10.0, height: 0.2), position: (0.0, -0.1)),
          (name: "disc", shape: Circle(radius: 0.1), mass: {m}, restitution: {e},
           position: (0.0, 0.6), velocity: (1.5, 2.0), omega: 4.0),
        ],
        {events}
        questions: [
          (id: "lost", ask: "energy lost", unit: "J", expected: {lost}, tolerance: 2e-2,
           quantity: EnergyLost(body: "disc", other: "floor"), at: End, why: "test"),
          (id: "impulse", ask: "the floor's impulse", unit: "N*s", expected: {impulse}, tolerance: 2e-2,
           quantity: ContactImpulse(body: "disc", other: "floor"), at: ContactEnds(body: "disc", other: "floor"), why: "test"),
        ])"#
    ));
    (scene, lost, impulse)
}

#[test]
fn a_thrown_spinning_disc_is_analysed_from_the_start_and_a_blow_ends_the_flight() {
    // Without the blow the parabola is exact: allowed 1e-5 (measured 2026-12-07 below 1e-6).
    // With it the analysis carries the engine's state after the blow, whose position leads by
    // g h t / 2 (h = dt / 4, t about 0.5 s: 2.6 mm at a landing speed of 4.5 m/s, so v_n^2
    // about 2.5e-3 low; 3.6e-3 measured 2026-12-07): allowed 5e-3. Had the flight been kept past the blow, the analysis
    // would miss its 1 m/s and read v_n^2 14% off.
    for (blow, allowed) in [(false, 1e-5), (true, 5e-3)] {
        let (scene, lost, impulse) = thrown_disc(blow);
        let r = run(&scene, &Options::default());
        for (q, hand) in r.questions.iter().zip([lost, impulse]) {
            let analysis = q.analysis.expect("an impact analysis");
            eprintln!(
                "blow {blow}: {} analysis {analysis}, engine {}, hand {hand}",
                q.id, q.engine
            );
            assert!(
                rel(analysis, hand) < allowed,
                "blow {blow}: {} read {analysis} for {hand} ({})",
                q.id,
                q.note
            );
        }
    }
}
