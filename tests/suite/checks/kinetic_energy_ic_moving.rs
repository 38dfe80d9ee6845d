//! `kinetic_energy_ic` with `other:` a body that moves (issue 34): the contact point of a body
//! rolling on a moving one is the center of the motion relative to it, not the world's
//! instantaneous center, so the check compares the kinetic energy of that relative motion.

use crate::common;

use common::{parse, rel, run};
use rigidlab::sim::Options;

/// A uniform disc (m = 2 kg, r = 0.2 m) set down at rest on a plank that moves at u = 1 m/s (a
/// kinematic body): relative to the plank it slides back at u, friction (mu = 0.5) rolls it
/// after u / (3 mu g) = 0.068 s, and it then rolls relative to the plank at 2/3 u (a disc's
/// slide to roll, with the plank's frame inertial). The relative kinetic energy is then
/// 3/4 m (2u/3)^2 = m u^2 / 3 = 0.6667 J, and 1/2 I_C (w - w_o)^2 about the contact point is
/// the same. The world's kinetic energy is not: 1/2 m (u/3)^2 + 1/2 I_G (2u / 3r)^2 = 0.3333 J.
#[test]
fn on_a_moving_plank_the_relative_motion_is_compared() {
    let text = r#"Level(title: "disc on a moving plank", effects: [gravity, contacts, friction],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 1.0),
        bodies: [
            (name: "plank", kind: kinematic, shape: Box(width: 20.0, height: 0.1), position: (8.0, -0.05),
             velocity: (1.0, 0.0), friction: 0.5),
            (name: "disc", shape: Circle(radius: 0.2), mass: 2.0, position: (0.0, 0.2), friction: 0.5),
        ],
        checks: [(kind: kinetic_energy_ic, body: "disc", other: "plank", tolerance: 2e-3, window: (0.2, 1.0),
            why: "rolling relative to the plank once the slide ends at 0.068 s")])"#;
    let report = run(&parse(text), &Options::default());
    let c = &report.checks[0];
    assert!(c.passed, "{c:?}");
    assert!(c.note.contains("moving body"), "{}", c.note);
    // The compared energy is the relative motion's, m u^2 / 3 (the world's would be m u^2 / 6,
    // 50% off). Measured 2026-11-27: 2.0e-6 (the engine's f32 velocities after the slide);
    // 2e-5 is a 10x margin, 100x under the check's own 2e-3.
    assert!(rel(c.theory, 2.0 / 3.0) < 2e-5, "{c:?}");
}
