//! What split substeps cost against rapier's internal ones (issue 13: pay for reading every
//! substep's joint impulse only where a level has joints). A timing, not a test of a target:
//! run with `cargo test --release --test suite -- sim::substepping_cost:: --ignored --nocapture`; it prints
//! per-step medians of interleaved rounds and their ratio, and asserts nothing.

use rigidlab::sim::{Options, Simulation, Substepping};
use std::path::Path;

fn per_step_seconds(level: &str, substepping: Substepping, steps: usize) -> f64 {
    let scene = rigidlab::level::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(level)).unwrap();
    let opts = Options {
        substepping: Some(substepping),
        ..Options::default()
    };
    let mut sim = Simulation::new(&scene, &opts);
    let t = std::time::Instant::now();
    for _ in 0..steps {
        if sim.step().is_err() {
            break;
        }
    }
    t.elapsed().as_secs_f64() / steps as f64
}

#[test]
#[ignore = "timing: run with --ignored --nocapture; prints medians and their ratio, asserts nothing"]
fn split_against_internal_substeps() {
    for (level, steps) in [
        ("levels/kinetics/physical_pendulum.ron", 200),
        ("levels/kinematics/classic_slider_crank.ron", 200),
        ("levels/stress/ball_and_chain.ron", 100),
        ("levels/stress/joint_grid_30.ron", 30),
    ] {
        let (mut split, mut internal) = (Vec::new(), Vec::new());
        for _ in 0..9 {
            split.push(per_step_seconds(level, Substepping::Split, steps));
            internal.push(per_step_seconds(level, Substepping::Internal, steps));
        }
        let med = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let (a, b) = (med(&mut split), med(&mut internal));
        println!(
            "{level}: split {:.1} us/step, internal {:.1} us/step, ratio {:.2}",
            a * 1e6,
            b * 1e6,
            a / b
        );
    }
}
