//! A rolling ball's price: rigidlab's rule for splitting a spinning ball's steps into
//! one-substep rapier calls, against splitting every such step and against never splitting.
//!
//!     cargo bench --no-default-features --bench rolling
//!
//! Issue 45's target: a rolling level costs at most 1.3x what it cost before the spinning fix
//! of 2026-11-27 (one rapier call a step, `SpinSplit::Never`) at equal accuracy. Each level
//! below runs at its own settings in the three ways (`sim::SpinSplit`), interleaved over
//! `ROUNDS` rounds (a round times each way once, in turn, so a burst of load on this 2-core
//! machine falls on all three alike); a way's cost is the median over the rounds of its wall
//! time stepping the level's whole run per simulated second (`Simulation::step`, f32, what
//! `study accuracy` times), each round's sample the fastest of `RUNS` runs. Beside the ratios the bench prints each way's accuracy, measured in
//! the same binary: the largest relative error of the level's questions against their textbook
//! answers, and how many steps were split.

use rigidlab::level::{load, Scene};
use rigidlab::runner;
use rigidlab::sim::{Options, Simulation, SpinSplit};
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

/// The library's rolling levels on a flat incline, the ones docs/accuracy.md priced at 3.3x
/// after the spinning fix, and a wheel rolling on a floor.
const LEVELS: [&str; 4] = [
    "levels/kinetics/classic_rolling_disc.ron",
    "levels/kinetics/classic_rolling_hoop.ron",
    "levels/kinetics/classic_rolling_sphere_as_disc.ron",
    "levels/energy/wheel_rolling_ke_ic.ron",
];
const WAYS: [SpinSplit; 3] = [SpinSplit::Never, SpinSplit::Rule, SpinSplit::Always];
const ROUNDS: usize = 21;
/// Runs of which a round's sample is the fastest: a run is about a millisecond.
const RUNS: usize = 10;
/// Issue 45's target for the rule against one call a step.
const TARGET: f64 = 1.3;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

fn options(way: SpinSplit) -> Options {
    Options {
        spin_split: way,
        ..Options::default()
    }
}

/// Wall time of stepping the level's run, us per simulated second: the fastest of `RUNS` runs
/// (as `study accuracy` samples a round: a preempted run is slower, never faster), and its split
/// steps.
fn cost(scene: &Scene, way: SpinSplit) -> (f64, u64) {
    let (mut best, mut split) = (f64::INFINITY, 0);
    for _ in 0..RUNS {
        let mut sim = Simulation::new(scene, &options(way));
        let steps = sim.total_steps();
        let t = Instant::now();
        for _ in 0..steps {
            sim.step().expect("a library level runs");
        }
        let us = t.elapsed().as_secs_f64() * 1e6 / (steps as f64 * sim.dt());
        best = best.min(us);
        split = sim.calls.split_for_spin;
    }
    (best, split)
}

/// The largest relative error of the level's questions against their textbook answers, and
/// whether every check and question passed.
fn accuracy(scene: &Scene, way: SpinSplit) -> (f64, bool) {
    let report = runner::run_graded(scene, &options(way), &HashMap::new(), |_| {})
        .expect("a library level runs");
    let worst = report
        .questions
        .iter()
        .map(|q| q.rel_error)
        .fold(0.0, f64::max);
    (worst, report.passed)
}

fn name(way: SpinSplit) -> &'static str {
    match way {
        SpinSplit::Never => "never (one call a step)",
        SpinSplit::Rule => "rule",
        SpinSplit::Always => "always (2026-11-27)",
    }
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut worst_ratio: f64 = 0.0;
    for file in LEVELS {
        let scene = load(&root.join(file)).expect("a library level loads");
        let mut times = vec![Vec::new(); WAYS.len()];
        let mut splits = [0; WAYS.len()];
        for round in 0..ROUNDS {
            // Each round starts with the next way, so that no way always follows another.
            for k in 0..WAYS.len() {
                let i = (round + k) % WAYS.len();
                let (us, split) = cost(&scene, WAYS[i]);
                times[i].push(us);
                splits[i] = split;
            }
        }
        let fastest: Vec<f64> = times
            .iter()
            .map(|t| t.iter().copied().fold(f64::INFINITY, f64::min))
            .collect();
        let costs: Vec<f64> = times.into_iter().map(median).collect();
        println!("{file} (dt {:.6} s):", scene.level.world.dt);
        for (i, &way) in WAYS.iter().enumerate() {
            let (err, passed) = accuracy(&scene, way);
            println!(
                "  {:<24} {:>8.1} us per simulated s  {:>5.2}x never (fastest round {:.2}x)  split steps {:>4}  worst question error {:.3e}  {}",
                name(way),
                costs[i],
                costs[i] / costs[0],
                fastest[i] / fastest[0],
                splits[i],
                err,
                if passed { "passes" } else { "FAILS" }
            );
        }
        worst_ratio = worst_ratio.max(costs[1] / costs[0]);
    }
    println!(
        "rule / never, worst level: {worst_ratio:.2}x (target <= {TARGET}x) {}",
        if worst_ratio <= TARGET {
            "met"
        } else {
            "NOT met"
        }
    );
}
