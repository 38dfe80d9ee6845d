//! Core benchmarks, printed as ratios measured in one run (this machine is noisy: medians of
//! interleaved repeats).
//!
//! 1. Overhead of rigidlab's runner (forces, couplings, snapshot with converted joint and
//!    contact impulses, guard) over a plain rapier loop on the very same 200-body world, with
//!    the contacts read and with them unread (a run none of whose readers reads contacts).
//!    Goals (issue 45): at most 1.05x with the contacts unread, 1.08x with them read.
//! 2. What undeclared effects cost: a 50-link pendulum chain with its declared effects
//!    (gravity, joints) against `--all-effects` (colliders in collision detection, CCD,
//!    sleeping). Promise 3: the declared run must be cheaper.
//!
//! Run: `cargo bench --no-default-features --bench core`

use rigidlab::level::parse;
use rigidlab::sim::{Options, Simulation};
use std::path::Path;
use std::time::Instant;

/// Issue 45's goals for the runner against a plain rapier loop: with the contacts unread (a
/// run none of whose readers reads them) and with them read.
const UNREAD_GOAL: f64 = 1.05;
const READ_GOAL: f64 = 1.08;

fn verdict(ratio: f64, goal: f64) -> &'static str {
    if ratio <= goal {
        "met"
    } else {
        "NOT met"
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// 200 boxes dropped in 10 columns onto a ground box: contacts, friction, gravity.
fn pile() -> String {
    let mut bodies = String::from("(name: \"ground\", kind: fixed, shape: Box(width: 40.0, height: 1.0), position: (0.0, -0.5)),\n");
    for i in 0..200 {
        let (col, row) = (i % 10, i / 10);
        bodies += &format!(
            "(name: \"b{i}\", shape: Box(width: 0.5, height: 0.5), mass: 1.0, friction: 0.6, position: ({:.3}, {:.3})),\n",
            -5.0 + col as f64 * 1.1,
            0.3 + row as f64 * 0.55
        );
    }
    format!("Level(title: \"pile\", effects: [gravity, contacts, friction], world: (duration: 10.0), bodies: [{bodies}])")
}

/// A chain of `n` links 0.1 m long hanging from a fixed point, released horizontal.
fn chain(n: usize) -> String {
    let mut bodies = String::from("(name: \"anchor\", kind: fixed),\n");
    let mut joints = String::new();
    for i in 0..n {
        bodies += &format!("(name: \"l{i}\", shape: Box(width: 0.08, height: 0.02), mass: 0.1, position: ({:.3}, 0.0)),\n", 0.05 + 0.1 * i as f64);
        let prev = if i == 0 {
            "anchor".to_string()
        } else {
            format!("l{}", i - 1)
        };
        let a1 = if i == 0 { "(0.0, 0.0)" } else { "(0.05, 0.0)" };
        joints += &format!("(name: \"j{i}\", kind: revolute, body1: \"{prev}\", body2: \"l{i}\", anchor1: {a1}, anchor2: (-0.05, 0.0)),\n");
    }
    format!("Level(title: \"chain\", effects: [gravity, joints], world: (duration: 10.0), bodies: [{bodies}], joints: [{joints}])")
}

fn time_steps(sim: &mut Simulation, steps: usize, ours: bool) -> f64 {
    let t = Instant::now();
    for _ in 0..steps {
        if ours {
            sim.step().expect("the benchmark scene stays finite");
        } else {
            sim.world.step();
        }
    }
    t.elapsed().as_secs_f64() / steps as f64
}

/// Times `a` and `b` in short alternating blocks (order swapped each round, so that drifts in
/// machine load hit both alike) and returns the median per-step time of each.
fn paired(
    a: &mut Simulation,
    a_ours: bool,
    b: &mut Simulation,
    b_ours: bool,
    rounds: usize,
) -> (f64, f64) {
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for r in 0..rounds {
        if r % 2 == 0 {
            ta.push(time_steps(a, 10, a_ours));
            tb.push(time_steps(b, 10, b_ours));
        } else {
            tb.push(time_steps(b, 10, b_ours));
            ta.push(time_steps(a, 10, a_ours));
        }
    }
    (median(ta), median(tb))
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let rounds = if quick { 11 } else { 61 };

    // 1. Runner overhead on 200 bodies: both worlds built from the same scene, stepped
    //    through the same settling phase, then timed in interleaved blocks.
    let scene = parse(Path::new("pile.ron"), &pile()).expect("the bench scene is valid");
    let opts = Options::default();
    let (mut ours, mut plain) = (
        Simulation::new(&scene, &opts),
        Simulation::new(&scene, &opts),
    );
    // Let the pile settle (4 s) so both are timed on the same steady workload.
    time_steps(&mut ours, 240, true);
    time_steps(&mut plain, 240, false);
    let (mo, mp) = paired(&mut ours, true, &mut plain, false, rounds);
    // The same runner where no reader wants the contacts (a run whose checks read none:
    // `runner::run_graded` turns their reading off).
    let mut unread = Simulation::new(&scene, &opts);
    unread.set_contact_readings(false);
    time_steps(&mut unread, 240, true);
    let (mu, mp2) = paired(&mut unread, true, &mut plain, false, rounds);
    println!(
        "runner overhead, 200-body pile ({} contact manifolds):",
        ours.snapshot().contacts.len()
    );
    println!(
        "  plain rapier loop  {:>9.1} us/step (median of {rounds} blocks of 10 steps)",
        mp * 1e6
    );
    println!("  rigidlab runner    {:>9.1} us/step", mo * 1e6);
    println!(
        "  contacts read      ratio ours/plain {:>6.3}x   goal <= {READ_GOAL}x: {}",
        mo / mp,
        verdict(mo / mp, READ_GOAL)
    );
    println!(
        "  contacts unread    {:>9.1} us/step against {:.1}: ratio {:.3}x   goal <= {UNREAD_GOAL}x: {}",
        mu * 1e6,
        mp2 * 1e6,
        mu / mp2,
        verdict(mu / mp2, UNREAD_GOAL)
    );

    // 2. Declared effects against all effects on a 50-link chain.
    let scene = parse(Path::new("chain.ron"), &chain(50)).expect("the bench scene is valid");
    let mut declared = Simulation::new(&scene, &Options::default());
    let mut all = Simulation::new(
        &scene,
        &Options {
            all_effects: true,
            ..Default::default()
        },
    );
    let (md, ma) = paired(&mut declared, true, &mut all, true, rounds);
    println!("declared effects against --all-effects, 50-link pendulum chain:");
    println!("  declared [gravity, joints]  {:>9.1} us/step", md * 1e6);
    println!("  all effects                 {:>9.1} us/step", ma * 1e6);
    println!("  ratio all/declared          {:>9.2}x", ma / md);
}
