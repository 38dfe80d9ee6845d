//! The levels graded by the linearized period (PL-14, levels/kinetics/linearized_*.ron): the
//! engine's measured period against the analysis at the level's settings, at 2x and 4x
//! substeps and at dt/2, and the analysis against the hand answer in each level's comment.
//!
//! What the engine measures is the period at the start's amplitude, which the linearized one
//! misses by the swing's nonlinearity; the analysis also gives that period
//! (`amplitude_period`, the energy integral along the excited mode's path). So each run is held
//! to the linearized period within the analysis's own `period_error` plus 3e-4 for the
//! integration (symplectic Euler's phase error, (omega h)^2 / 24 per substep h, is under 1e-5
//! for these levels at h <= 0.5 ms; zero crossings interpolated between steps add ~1e-5), and
//! the period at amplitude within 5e-4 (for one degree of freedom it is exact; on the cart the
//! mode's path stands in for the true motion).

use rigidlab::analysis::small_oscillations::Mechanism;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

struct Case {
    file: &'static str,
    body: &'static str,
    /// The hand answer in the level's comment, s.
    hand: f64,
}

const CASES: [Case; 3] = [
    Case {
        file: "levels/kinetics/linearized_pendulum_on_cart.ron",
        body: "bob",
        hand: 1.7387518583749657,
    },
    Case {
        file: "levels/kinetics/linearized_damped_torsion_pendulum.ron",
        body: "bar",
        hand: 1.052815551930376,
    },
    Case {
        file: "levels/kinetics/linearized_springs_at_an_angle.ron",
        body: "block",
        hand: 0.725519745693687,
    },
];

#[test]
fn engine_periods_agree_with_the_linearized_ones() {
    for c in &CASES {
        let scene = level::load(Path::new(c.file)).unwrap_or_else(|e| panic!("{e}"));
        let i = scene
            .level
            .bodies
            .iter()
            .position(|b| b.name == c.body)
            .unwrap();
        let osc = Mechanism::of_level(&scene.level, i)
            .and_then(|m| m.small_oscillations())
            .unwrap_or_else(|e| panic!("{}: {e}", c.file));
        let mode = osc.excited().unwrap();
        let linear = mode.damped_period.unwrap();
        // The analysis against the hand answer: 1e-6 (the module's finite differences, 1e-8).
        assert!(
            (linear / c.hand - 1.0).abs() < 1e-6,
            "{}: linearized {linear} against the hand answer {}",
            c.file,
            c.hand
        );
        // Undamped amplitude period, damped by the same ratio as the linear one.
        let at_amplitude = osc.amplitude_period.unwrap() * linear / mode.period;
        let world = &scene.level.world;
        let settings = [
            ("the level's settings", Options::default()),
            (
                "2x substeps",
                Options {
                    substeps: Some(2 * world.substeps),
                    ..Default::default()
                },
            ),
            (
                "4x substeps",
                Options {
                    substeps: Some(4 * world.substeps),
                    ..Default::default()
                },
            ),
            (
                "dt/2",
                Options {
                    dt: Some(world.dt / 2.0),
                    ..Default::default()
                },
            ),
        ];
        for (what, opts) in &settings {
            let report =
                rigidlab::runner::run_graded(&scene, opts, &Default::default(), |_| {}).unwrap();
            let q = &report.questions[0];
            assert_eq!(
                q.analysis,
                Some(linear),
                "{} at {what}: the question's analysis is the linearized period",
                c.file
            );
            let engine = q.engine;
            assert!(engine.is_finite(), "{} at {what}: no period", c.file);
            let off = (engine / linear - 1.0).abs();
            assert!(
                off <= osc.period_error + 3e-4,
                "{} at {what}: engine {engine} vs linearized {linear}: {off:.2e} > {:.2e}",
                c.file,
                osc.period_error + 3e-4
            );
            let off = (engine / at_amplitude - 1.0).abs();
            assert!(
                off <= 5e-4,
                "{} at {what}: engine {engine} vs at amplitude {at_amplitude}: {off:.2e}",
                c.file
            );
        }
    }
}
