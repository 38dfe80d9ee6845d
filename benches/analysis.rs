//! Analysis + checks time as a fraction of the physics step time, on a 100-body scene.
//!
//!     CARGO_TARGET_DIR=/work/target-core cargo bench --no-default-features --bench analysis
//!
//! The scene: 50 bars swinging on pins (joints) and 50 balls falling into a box and piling up
//! (contacts, friction), 300 steps at 1/60 s with 4 substeps, repeated 7 times. Measured in the
//! same run, step by step (`Instant` around `sim.step()` and around each group of analysis work,
//! so physics and analysis interleave), summed over blocks of 10 consecutive steps; each ratio is
//! the median over all blocks of (analysis time in the block / physics time in the block), which
//! a burst of load from other processes on this 2-core machine moves little:
//! - A (the goal, <= 5%): the textbook quantities of every body and of the scene each step
//!   (`analysis::frame::FrameAnalysis`: T, G, H_G, the instantaneous center, a_G and alpha, the
//!   free-body diagram's sums and the Newton-Euler residuals of all 100 bodies; scene T, V, G, H)
//!   plus the scene's checks (`work_energy`, `impulse_momentum` with H about a point,
//!   `angular_momentum_fixed_point` about that point);
//! - B (information): A plus one probe per body and kind, `newton_euler` and
//!   `kinetic_energy_ic` on all 100 bodies and `angular_momentum_fixed_point` on the 50 bars
//!   (250 independent probes, each reading the whole snapshot).

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
            r#"(kind: newton_euler, body: "ball{k}", tolerance: 1.0),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: kinetic_energy_ic, body: "ball{k}", other: "floor", tolerance: 1.0),"#
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
            r#"(kind: newton_euler, body: "bar{k}", tolerance: 1.0),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: kinetic_energy_ic, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: angular_momentum_fixed_point, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0),"#
        );
    }
    checks += "(kind: work_energy, tolerance: 1.0),\n(kind: impulse_momentum, point: (0.0, 0.0), tolerance: 1.0),\n(kind: angular_momentum_fixed_point, point: (0.0, 0.0), tolerance: 1.0),\n";
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
    let (mut step_us, mut a_us, mut b_us, mut frame_us) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut contacts = 0;
    let mut rows = 0;
    for _ in 0..REPEATS {
        let mut sim = Simulation::new(&scene, &Options::default());
        let mut a = CheckSet::new(&scene_level);
        let mut b = CheckSet::new(level);
        let mut frame = FrameAnalysis::new(level.world.substeps);
        let (mut t_step, mut t_a, mut t_b, mut t_f) = (0.0, 0.0, 0.0, 0.0);
        let mut each = |s: &rigidlab::snapshot::Snapshot, t: &mut [f64; 3]| {
            let t0 = Instant::now();
            a.observe(s);
            t[0] += t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            b.observe(s);
            t[1] += t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            rows += frame.observe(s).bodies.len();
            t[2] += t0.elapsed().as_secs_f64();
        };
        let mut t = [0.0; 3];
        each(sim.snapshot(), &mut t);
        for k in 0..STEPS {
            let t0 = Instant::now();
            let s = sim.step().expect("the bench scene runs");
            t_step += t0.elapsed().as_secs_f64();
            contacts = s.contacts.len();
            each(s, &mut t);
            if (k + 1) % BLOCK == 0 {
                // Close the block (the initial snapshot's analysis counts in the first one).
                t_a += t[0];
                t_b += t[1];
                t_f += t[2];
                ratio_a.push(t_a / t_step);
                ratio_b.push(t_b / t_step);
                let per_step = 1e6 / BLOCK as f64;
                step_us.push(t_step * per_step);
                a_us.push(t_a * per_step);
                b_us.push(t_b * per_step);
                frame_us.push(t_f * per_step);
                (t_step, t_a, t_b, t_f) = (0.0, 0.0, 0.0, 0.0);
                t = [0.0; 3];
            }
        }
        let (done_a, done_b) = (a.finish(), b.finish());
        assert_eq!(done_a.len(), scene_level.checks.len());
        assert_eq!(done_b.len(), level.checks.len());
    }
    assert!(rows > 0);
    let blocks = ratio_a.len();
    let (ra, rb) = (median(&mut ratio_a), median(&mut ratio_b));
    let quartiles = |v: &[f64]| (100.0 * v[v.len() / 4], 100.0 * v[3 * v.len() / 4]);
    println!("contact manifolds at the end: {contacts}; {blocks} blocks of {BLOCK} steps");
    println!(
        "per step (block medians): physics {:.1} us; A: all-body analysis + scene checks {:.1} us (of which the shared frame pass alone {:.1} us); B: every check of the level {:.1} us",
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
