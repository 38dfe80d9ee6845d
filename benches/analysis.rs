//! Analysis + checks time as a fraction of the physics step time, on a 100-body scene.
//!
//!     CARGO_TARGET_DIR=/work/target-core cargo bench --no-default-features --bench analysis
//!
//! The scene: 50 bars swinging on pins (joints) and 50 balls falling into a box and piling up
//! (contacts, friction), 300 steps at 1/60 s with rapier's default 4 substeps. Runs alternate
//! between the two configurations below (7 runs each), each run timing every step (`Instant`
//! around `sim.step()` and around `CheckSet::observe`, as `rigidlab check` calls them) summed over
//! blocks of 10 consecutive steps; each ratio is the median over its blocks of (check time in the
//! block / physics time in the block), which a burst of load on this 2-core machine moves little:
//! - A (the goal, <= 5%): the textbook quantities of every body and of the scene each step (the
//!   shared pass `analysis::frame::FrameAnalysis`: T, G, H_G, the instantaneous center, a_G and
//!   alpha, the free-body diagram's sums, the Newton-Euler residuals and the non-conservative
//!   work of all 100 bodies; scene T, V, G, H, external resultant and work) plus the scene's
//!   checks (`work_energy`, `impulse_momentum` with H about a point, `angular_momentum_fixed_point`
//!   about that point);
//! - B (information): the same with 250 per-body checks as well, `newton_euler` and
//!   `kinetic_energy_ic` on all 100 bodies and `angular_momentum_fixed_point` on the 50 bars.

use rigidlab::analysis::frame::FrameAnalysis;
use rigidlab::checks::CheckSet;
use rigidlab::level::parse;
use rigidlab::sim::{Options, Simulation};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

const BARS: usize = 50;
const BALLS: usize = 50;
const STEPS: usize = 300;
const REPEATS: usize = 7;
/// Steps per timing block.
const BLOCK: usize = 10;

fn scene_ron() -> String {
    let mut bodies = String::new();
    let mut joints = String::new();
    let mut checks = String::new();
    // The box for the balls: floor and two walls.
    bodies += r#"(name: "floor", kind: fixed, shape: Box(width: 4.0, height: 0.2), position: (0.0, -0.1)),
        (name: "wall_l", kind: fixed, shape: Box(width: 0.2, height: 6.0), position: (-2.1, 3.0)),
        (name: "wall_r", kind: fixed, shape: Box(width: 0.2, height: 6.0), position: (2.1, 3.0)),
"#;
    for k in 0..BALLS {
        let (x, y) = (-1.6 + 0.36 * (k % 10) as f64, 0.5 + 0.4 * (k / 10) as f64);
        let _ = writeln!(
            bodies,
            r#"(name: "ball{k}", shape: Circle(radius: 0.15), mass: 1.0, position: ({x}, {y}), friction: 0.4),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: newton_euler, body: "ball{k}", tolerance: 1.0, why: "bench"),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: kinetic_energy_ic, body: "ball{k}", other: "floor", tolerance: 1.0, why: "bench"),"#
        );
    }
    for k in 0..BARS {
        // Pins 1.5 m apart, far from the box; each bar starts 45 degrees out.
        let px = 10.0 + 1.5 * k as f64;
        let a = std::f64::consts::FRAC_PI_4;
        let (cx, cy) = (px + 0.5 * a.sin(), 5.0 - 0.5 * a.cos());
        let _ = writeln!(
            bodies,
            r#"(name: "pin{k}", kind: fixed, position: ({px}, 5.0)),"#
        );
        let _ = writeln!(
            bodies,
            r#"(name: "bar{k}", shape: Box(width: 0.04, height: 1.0), mass: 2.0, angle: {a}, position: ({cx}, {cy})),"#
        );
        let _ = writeln!(
            joints,
            r#"(name: "j{k}", kind: revolute, body1: "pin{k}", body2: "bar{k}", anchor2: (0.0, 0.5)),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: newton_euler, body: "bar{k}", tolerance: 1.0, why: "bench"),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: kinetic_energy_ic, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0, why: "bench"),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: angular_momentum_fixed_point, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0, why: "bench"),"#
        );
    }
    checks += r#"(kind: work_energy, tolerance: 1.0, why: "bench"),
(kind: impulse_momentum, point: (0.0, 0.0), tolerance: 1.0, why: "bench"),
(kind: angular_momentum_fixed_point, point: (0.0, 0.0), tolerance: 1.0, why: "bench"),
"#;
    format!(
        r#"Level(title: "bench: 100 bodies", effects: [gravity, contacts, friction, joints],
        world: (dt: 0.016666666666666666, substeps: 4, duration: 5.0),
        bodies: [{bodies}], joints: [{joints}], checks: [{checks}])"#
    )
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let scene = parse(Path::new("bench.ron"), &scene_ron()).unwrap_or_else(|e| panic!("{e}"));
    let level = &scene.level;
    let dynamic = level
        .bodies
        .iter()
        .filter(|b| b.kind == rigidlab::level::BodyKind::Dynamic)
        .count();
    // A's level: the same scene with its scene-wide checks only.
    let mut scene_level = level.clone();
    scene_level.checks.retain(|c| c.body.is_none());
    let per_body = level.checks.len() - scene_level.checks.len();
    println!(
        "scene: {dynamic} dynamic bodies ({BARS} pinned bars, {BALLS} balls in a box); {} scene checks, {per_body} per-body probes; {STEPS} steps x {REPEATS} repeats",
        scene_level.checks.len(),
    );
    let (mut ratio_a, mut ratio_b) = (Vec::new(), Vec::new());
    let (mut step_us, mut a_us, mut b_us) = (Vec::new(), Vec::new(), Vec::new());
    let mut contacts = 0;
    let mut rows = 0;
    // Runs alternate: one with A's checks, one with all of B's, so each run has the cache and
    // the analysis work of that configuration alone, and both see the same machine noise.
    for k in 0..2 * REPEATS {
        let with_b = k % 2 == 1;
        let mut sim = Simulation::new(&scene, &Options::default());
        let mut checks = CheckSet::new(if with_b { level } else { &scene_level });
        checks.observe(sim.snapshot());
        let (mut t_step, mut t_checks) = (0.0, 0.0);
        for k in 0..STEPS {
            let t0 = Instant::now();
            let s = sim.step().expect("the bench scene runs");
            t_step += t0.elapsed().as_secs_f64();
            contacts = s.contacts.len();
            let t0 = Instant::now();
            checks.observe(s);
            t_checks += t0.elapsed().as_secs_f64();
            rows += s.bodies.len();
            if (k + 1) % BLOCK == 0 {
                let per_step = 1e6 / BLOCK as f64;
                step_us.push(t_step * per_step);
                if with_b {
                    ratio_b.push(t_checks / t_step);
                    b_us.push(t_checks * per_step);
                } else {
                    ratio_a.push(t_checks / t_step);
                    a_us.push(t_checks * per_step);
                }
                (t_step, t_checks) = (0.0, 0.0);
            }
        }
        let n = if with_b {
            level.checks.len()
        } else {
            scene_level.checks.len()
        };
        assert_eq!(checks.finish().len(), n);
    }
    // The shared frame pass alone, on the same steps (information: how much of A it is).
    let mut frame_us = Vec::new();
    for _ in 0..REPEATS {
        let mut sim = Simulation::new(&scene, &Options::default());
        let mut frame = FrameAnalysis::new();
        frame.observe(sim.snapshot());
        let mut t_f = 0.0;
        for k in 0..STEPS {
            let s = sim.step().expect("the bench scene runs");
            let t0 = Instant::now();
            rows += frame.observe(s).bodies.len();
            t_f += t0.elapsed().as_secs_f64();
            if (k + 1) % BLOCK == 0 {
                frame_us.push(t_f * 1e6 / BLOCK as f64);
                t_f = 0.0;
            }
        }
    }
    assert!(rows > 0);
    let blocks = ratio_a.len() + ratio_b.len();
    let (ra, rb) = (median(&mut ratio_a), median(&mut ratio_b));
    let quartiles = |v: &[f64]| (100.0 * v[v.len() / 4], 100.0 * v[3 * v.len() / 4]);
    println!("contact manifolds at the end: {contacts}; {blocks} blocks of {BLOCK} steps");
    println!(
        "per step (block medians): physics {:.1} us; A: all-body analysis + scene checks {:.1} us (the shared frame pass alone: {:.1} us); B: every check of the level {:.1} us",
        median(&mut step_us),
        median(&mut a_us),
        median(&mut frame_us),
        median(&mut b_us)
    );
    let (qa, qb) = (quartiles(&ratio_a), quartiles(&ratio_b));
    println!(
        "A  analysis + checks / step time: {:.2}% (median of blocks; quartiles {:.2}%..{:.2}%); goal <= 5%: {}",
        100.0 * ra,
        qa.0,
        qa.1,
        if ra <= 0.05 { "met" } else { "NOT met" }
    );
    println!(
        "B  with the {per_body} per-body probes as well:    {:.2}% (median of blocks; quartiles {:.2}%..{:.2}%)",
        100.0 * rb,
        qb.0,
        qb.1
    );
}
