//! Readings that assume a rigid contact, against rapier's soft one (issue 41): a body resting or
//! rolling on a fixed floor settles into it by a depth d that grows with the step (about
//! 6.9e-5 m at 1/60 s and 4 substeps; `analysis::kinematics::contact_sag`). Gravity's work over
//! d is absorbed by the contact, and the floor's surface point lies d inside a ball's rim. The
//! readings must account for it: the kinetic energy's work-energy analysis takes gravity's work
//! along the rigid contact's path, and the slip speed is read at the point the solver's friction
//! holds (the ball's rim), where rolling means zero.

use crate::common;

use common::{parse, rel, run};
use rigidlab::questions::QuestionResult;
use rigidlab::sim::Options;

const G: f64 = 9.81;

/// A uniform disc (`m` kg, radius `r`) rolling without slip at `v` m/s to the right on a fixed
/// rough floor (mu = 0.5), omega = -v / r, with `questions` and the world's `dt` and substeps.
fn rolling_disc(
    m: f64,
    r: f64,
    v: f64,
    dt: f64,
    substeps: usize,
    questions: &str,
) -> Vec<QuestionResult> {
    let text = format!(
        r#"Level(title: "a disc rolls on a floor", effects: [gravity, contacts, friction],
        world: (dt: {dt}, substeps: {substeps}, duration: 1.6),
        bodies: [
            (name: "floor", kind: fixed, shape: Box(width: 40.0, height: 1.0), position: (10.0, -0.5), friction: 0.5),
            (name: "disc", shape: Circle(radius: {r}), mass: {m}, position: (0.0, {r}),
             velocity: ({v}, 0.0), omega: {w}, friction: 0.5),
        ],
        questions: [{questions}])"#,
        w = -v / r,
    );
    run(&parse(&text), &Options::default()).questions
}

/// T of a disc rolling on a level floor: 1/2 m v^2 + 1/2 (m r^2 / 2)(v / r)^2 = 3/4 m v^2
/// (6/9 with MP-3), and no force on it works (gravity and the normal force are normal to the
/// path, the contact point is at rest): T stays 3/4 m v^2 and the work-energy analysis (RE-7)
/// must say so at any configuration event, here the crossing x = 0.3 m. Before the fix the
/// analysis booked gravity's work over the settled depth, m g d: with d = 6.9e-5 m at 1/60 s,
/// 5.6e-3 of T at 0.4 m/s. The tolerance 1e-3 is the library's rule for analyses.
fn kinetic_energy_at_a_crossing(v: f64, dt: f64, substeps: usize) {
    let (m, r) = (2.0, 0.2);
    let t = 0.75 * m * v * v;
    let qs = rolling_disc(
        m,
        r,
        v,
        dt,
        substeps,
        &format!(
            r#"(id: "T", ask: "T at x = 0.3 m", unit: "J", expected: {t}, tolerance: 1e-3,
            quantity: KineticEnergy("disc"), at: Crossing(of: X("disc"), value: 0.3), why: "t")"#
        ),
    );
    let q = &qs[0];
    let a = q
        .analysis
        .unwrap_or_else(|| panic!("no analysis for a rolling disc: {q:?}"));
    eprintln!(
        "v {v}, dt {dt}: analysis {a}, engine {}, 3/4 m v^2 = {t}",
        q.engine
    );
    assert!(
        rel(a, t) <= 1e-3,
        "v {v}, dt {dt}, {substeps} substeps: analysis {a} against 3/4 m v^2 = {t} ({:.2e})",
        rel(a, t)
    );
    assert!(q.passed, "{q:?}");
}

#[test]
fn kinetic_energy_analysis_leaves_the_settled_depth_out() {
    kinetic_energy_at_a_crossing(0.4, 1.0 / 60.0, 4);
}

/// The twin: slower (0.25 m/s, where m g d is a larger share of T) at half the step and 8
/// substeps.
#[test]
fn kinetic_energy_analysis_leaves_the_settled_depth_out_at_dt_over_2() {
    kinetic_energy_at_a_crossing(0.25, 1.0 / 120.0, 8);
}

/// A disc rolling on a fixed floor: its contact point is at rest, so the slip speed is zero
/// (RK-8, v_G = -omega r). Before the fix the slip was taken at the floor's surface point, d
/// inside the rim, which moves at |omega| d: 6.9e-3 m/s at 103 rad/s, 4.1e-3 at 60 rad/s (1/60 s).
/// The tolerance, 1e-3 m/s absolute (the expected value is 0), is a quarter of that: what is
/// left is the solver's creep of the rolling contact (docs/known-gaps.md).
fn slip_while_rolling(r: f64, v: f64) {
    let qs = rolling_disc(
        1.0,
        r,
        v,
        1.0 / 60.0,
        4,
        r#"(id: "slip", ask: "slip at 0.5 s", unit: "m/s", expected: 0.0, tolerance: 1e-3,
            quantity: SlipSpeed(body: "disc", other: "floor"), at: Time(0.5), why: "t"),
           (id: "slip_floor", ask: "the floor's slip under it", unit: "m/s", expected: 0.0, tolerance: 1e-3,
            quantity: SlipSpeed(body: "floor", other: "disc"), at: Time(0.5), why: "t")"#,
    );
    for q in &qs {
        eprintln!("r {r}, v {v}: {} {} m/s", q.id, q.engine);
        assert!(q.engine.is_finite(), "{q:?}");
        assert!(
            q.passed,
            "r {r}, v {v} ({} rad/s): slip {} m/s",
            v / r,
            q.engine
        );
    }
}

#[test]
fn a_rolling_ball_reads_no_slip() {
    slip_while_rolling(0.1, 10.3);
}

/// The twin: a smaller disc, slower (0.05 m, 3 m/s: 60 rad/s).
#[test]
fn a_smaller_rolling_ball_reads_no_slip() {
    slip_while_rolling(0.05, 3.0);
}

/// The slip still reads a slide: a disc thrown without spin slides at v0 at first (the
/// correction moves the reading point by d along the normal, omega d at most).
#[test]
fn a_sliding_disc_still_reads_its_slip() {
    let v0 = 3.0;
    let text = format!(
        r#"Level(title: "a disc slides", effects: [gravity, contacts, friction],
        world: (dt: 0.016666666666666666, substeps: 4, duration: 0.2),
        bodies: [
            (name: "floor", kind: fixed, shape: Box(width: 40.0, height: 1.0), position: (10.0, -0.5), friction: 0.3),
            (name: "disc", shape: Circle(radius: 0.2), mass: 1.0, position: (0.0, 0.2),
             velocity: ({v0}, 0.0), friction: 0.3),
        ],
        questions: [(id: "slip", ask: "slip at 0.1 s", unit: "m/s", expected: {slip}, tolerance: 1e-2,
            quantity: SlipSpeed(body: "disc", other: "floor"), at: Time(0.1), why: "t")])"#,
        // The slip falls at 3 mu g (a disc, k_G^2 = r^2/2): v0 - 3 mu g t.
        slip = v0 - 3.0 * 0.3 * G * 0.1,
    );
    let q = run(&parse(&text), &Options::default()).questions.remove(0);
    assert!(q.passed, "{q:?}");
}
