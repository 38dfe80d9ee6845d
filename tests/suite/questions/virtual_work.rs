//! Virtual work gives a static mechanism's holding torque (issue 14; concepts.md VW-2, VW-6):
//! the slider-crank held by a servo against a gas force F on its piston, at any settings.
//! Expected: M = -F r sin(theta) [1 + r cos(theta) / sqrt(l^2 - r^2 sin^2 theta)] (ZH 4.3,
//! derived in the level's header), negative because the push turns the crank counter-clockwise.

use rigidlab::level::load;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

fn zh_torque(th: f64) -> f64 {
    let (r, l, f) = (0.1f64, 0.3f64, 50.0f64);
    -f * r * th.sin() * (1.0 + r * th.cos() / (l * l - (r * th.sin()).powi(2)).sqrt())
}

#[test]
fn the_servo_torque_and_its_virtual_work_analysis_match_zh_at_60_and_120_degrees() {
    let scene = load(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/levels/virtual-work/zh_slider_crank_static_servo.ron"
    )))
    .unwrap_or_else(|e| panic!("{e}"));
    for (substeps, dt) in [(4, 1e-3), (1, 1e-3), (8, 1e-3), (4, 5e-4)] {
        let opts = Options {
            substeps: Some(substeps),
            dt: Some(dt),
            ..Options::default()
        };
        let mut angles = [0.0; 2];
        let r = runner::run_scene(&scene, &opts, &HashMap::new(), |s| {
            for (k, name) in ["crank60", "crank120"].iter().enumerate() {
                angles[k] = s.bodies[s.body_index(name).unwrap()].angle;
            }
        })
        .unwrap();
        for ((q, theta), angle) in r.questions.iter().zip([60f64, 120.0]).zip(angles) {
            // Virtual work at the pose the servo holds the crank in. rapier's pins are soft and
            // part a little under the load, so the engine's geometry is not quite ZH's rigid
            // one at that crank angle: measured 1.8e-5 to 8e-5 at 4 and 8 substeps, 4.9e-4 at
            // 1 substep (engine 2.1e-4).
            let at_pose = zh_torque(angle);
            let pose_tol = if substeps == 1 { 1e-3 } else { 2e-4 };
            let analysis = q.analysis.expect("virtual work applies at rest");
            assert!(
                (analysis - at_pose).abs() < pose_tol * at_pose.abs(),
                "{substeps} substeps, dt {dt}: analysis {analysis} vs {at_pose} at {angle} rad"
            );
            assert!(
                (q.engine - at_pose).abs() < pose_tol * at_pose.abs(),
                "{substeps} substeps, dt {dt}: engine {} vs {at_pose} at {angle} rad",
                q.engine
            );
            // Against the exact angle, the servo's sag counts: within 1e-3 at the level's own
            // settings (issue 14's goal; measured 1.4e-4 and 2.4e-4); rapier's servo sags more
            // with longer substeps (2.2e-3 at 1 substep of 1 ms, 8e-5 to 2e-4 at 4 or 8).
            let exact = zh_torque(theta.to_radians());
            let tol = if substeps == 1 { 3e-3 } else { 1e-3 };
            assert!(
                (analysis - exact).abs() < tol * exact.abs(),
                "{substeps} substeps, dt {dt}: analysis {analysis} vs {exact} at {theta} deg"
            );
        }
        assert!(r.checks.iter().all(|c| c.passed), "{:?}", r.checks);
    }
}
