//! An analysis that does not apply to a question says so, and the question is graded on the
//! engine alone (issue 14): at `ContactEnds`, the impact solution is the state just after an
//! impact, so it is used only when the contact was one.

use rigidlab::level::parse;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

const G: f64 = 9.81;

/// A ball (r = 0.1 m) dropped from rest onto a smooth 30-degree slope (a segment from the
/// origin down to the right, 1.5 m long) lands with e = 0, slides down and leaves the slope's
/// end. Geometry along the slope: t = (cos 30, -sin 30), n = (sin 30, cos 30); the ball falls at
/// x0 = 0.2 m and touches when G . n = r. The plastic, smooth impact keeps v_t = v sin 30; the
/// slide to the end adds 2 g (L - s_touch) sin 30 to v^2 (no friction, no loss).
#[test]
fn the_end_of_a_lasting_contact_is_not_graded_against_an_impact_solution() {
    let (r, x0, y0, len) = (0.1f64, 0.2f64, 0.6f64, 1.5f64);
    let (s30, c30) = (0.5f64, 3f64.sqrt() / 2.0);
    let y_touch = (r - x0 * s30) / c30;
    let v_touch = (2.0 * G * (y0 - y_touch)).sqrt();
    let s_touch = x0 * c30 - y_touch * s30;
    let v_release = ((v_touch * s30).powi(2) + 2.0 * G * (len - s_touch) * s30).sqrt();
    let text = format!(
        r#"Level(title: "slide off", effects: [gravity, contacts],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 1.5),
        bodies: [
            (name: "slope", kind: fixed, shape: Segment(a: (0.0, 0.0), b: ({bx}, {by}))),
            (name: "ball", shape: Circle(radius: {r}), mass: 1.0, position: ({x0}, {y0})),
        ],
        questions: [(id: "v", ask: "speed leaving the slope", unit: "m/s", expected: {v_release}, tolerance: 2e-2,
            quantity: Speed("ball"), at: ContactEnds(body: "ball", other: "slope"),
            why: "the plastic landing from a distance (rapier acts the step before touching)")],
        )"#,
        bx = len * c30,
        by = -len * s30,
    );
    let scene = parse(Path::new("slide.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
    let report = runner::run_scene(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
    let q = &report.questions[0];
    // The ball did approach the slope (an impact solution exists for the landing), but the
    // contact then lasted about 0.4 s while gravity worked: its end is no post-impact state.
    // Before, the analysis was that impact solution: the landing's v_t, 1.71 m/s against the
    // 3.99 m/s the ball leaves with (engine 4.03).
    assert_eq!(q.analysis, None, "{q:?}");
    assert!(q.note.contains("not impulsive"), "{}", q.note);
    assert!(q.passed, "{q:?}");
}
