//! Analysis + checks time as a fraction of the physics step time, on a 100-body scene.
//!
//!     CARGO_TARGET_DIR=/work/target-core cargo bench --no-default-features --bench analysis
//!
//! The scene: 50 bars swinging on pins (joints) and 50 balls falling into a box and piling up
//! (contacts, friction), 300 steps at 1/60 s. Checks: every body has `newton_euler` and
//! `kinetic_energy_ic`, every bar `angular_momentum_fixed_point` about its pin, and the scene
//! `work_energy` and `impulse_momentum` (253 probes). Both times are measured in the same run,
//! step by step (the step with `Instant` around `sim.step()`, the checks around the probes'
//! `observe` calls and `finish`), repeated; the ratio is the median over the repeats.
//! Goal: checks <= 5% of the step time.

use rigidlab::checks::{probe_for, Probe};
use rigidlab::level::parse;
use rigidlab::sim::{Options, Simulation};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

const BARS: usize = 50;
const BALLS: usize = 50;
const STEPS: usize = 300;
const REPEATS: usize = 7;

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
            r#"(kind: kinetic_energy_ic, body: "ball{k}", tolerance: 1.0),"#
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
            r#"(kind: kinetic_energy_ic, body: "bar{k}", tolerance: 1.0),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: angular_momentum_fixed_point, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0),"#
        );
    }
    checks += "(kind: work_energy, tolerance: 1.0),\n(kind: impulse_momentum, tolerance: 1.0),\n";
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
    println!(
        "scene: {dynamic} dynamic bodies ({BARS} pinned bars, {BALLS} balls in a box), {} checks, {STEPS} steps x {REPEATS} repeats",
        level.checks.len()
    );
    let (mut ratios, mut steps_us, mut checks_us) = (Vec::new(), Vec::new(), Vec::new());
    let mut contacts = 0;
    for _ in 0..REPEATS {
        let mut sim = Simulation::new(&scene, &Options::default());
        let mut probes: Vec<Box<dyn Probe>> =
            level.checks.iter().map(|c| probe_for(level, c)).collect();
        let t = Instant::now();
        for p in probes.iter_mut() {
            p.observe(sim.snapshot());
        }
        let mut t_checks = t.elapsed().as_secs_f64();
        let mut t_step = 0.0;
        for _ in 0..STEPS {
            let t = Instant::now();
            let s = sim.step().expect("the bench scene runs");
            t_step += t.elapsed().as_secs_f64();
            contacts = s.contacts.len();
            let t = Instant::now();
            for p in probes.iter_mut() {
                p.observe(s);
            }
            t_checks += t.elapsed().as_secs_f64();
        }
        let t = Instant::now();
        let results: Vec<_> = probes.into_iter().map(|p| p.finish()).collect();
        t_checks += t.elapsed().as_secs_f64();
        assert_eq!(results.len(), level.checks.len());
        ratios.push(t_checks / t_step);
        steps_us.push(t_step / STEPS as f64 * 1e6);
        checks_us.push(t_checks / STEPS as f64 * 1e6);
    }
    let ratio = median(&mut ratios);
    println!("contact manifolds at the end: {contacts}");
    println!(
        "per step (median of {REPEATS}): physics {:.1} us, analysis + checks {:.1} us",
        median(&mut steps_us),
        median(&mut checks_us)
    );
    println!(
        "analysis + checks / step time: {:.2}% (median; min {:.2}%, max {:.2}%); goal <= 5%: {}",
        100.0 * ratio,
        100.0 * ratios.first().copied().unwrap_or(0.0),
        100.0 * ratios.last().copied().unwrap_or(0.0),
        if ratio <= 0.05 { "met" } else { "NOT met" }
    );
}
