//! What the run loop costs over a plain simulation loop (issue 15: at most 1.05x).
//!
//!     CARGO_TARGET_DIR=... cargo bench --no-default-features --bench runner
//!
//! The runner is `runner::run_scene`: the simulation plus its observers (the level's checks and
//! questions, `runner::Observers`), as `rigidlab check` runs a level. The plain loop is
//! `Simulation::new` and `Simulation::run` over the same level with nothing observing. Both
//! include building the simulation; neither includes parsing the file. The two take turns run by
//! run (this 2-core machine is noisy), and each ratio is the median over pairs of (runner time /
//! plain time):
//! 1. the 100-body scene of benches/analysis.rs with its scene checks, 250 per-body checks and
//!    100 questions (each body's speed at t = 2 s);
//!    (information: with its checks only, with its questions only);
//! 2. the same scene with every per-body check kind on every body (1,050 checks, information:
//!    the checks' own cost, bench analysis C);
//! 3. every level of the library (levels/), one after another: a round is the sum over levels;
//! 4. the 100-body scene with no checks and no questions (what the runner costs by itself);
//! 5. a typical library level, levels/kinetics/physical_pendulum.ron (3 checks, 2 questions, a
//!    few ms a run), run 10 times a round (information: with its checks only, with its question
//!    only).
//! 6. the 10,000-body stress level, levels/stress/sand_pile.ron (issue 45: at most 1.1x): a run
//!    of it takes minutes, so this case times steps, not runs, as `--bench core` does for its
//!    200-body pile: rigidlab's `Simulation::step` (what `runner::run_scene` calls each step; the
//!    level has no checks or questions, so `check` leaves its contacts unread) against a plain
//!    rapier loop (`PhysicsWorld::step` on the very same world), both settled for 4 s and then
//!    timed in interleaved blocks (information: with the contacts read, as the window reads them;
//!    and rapier at its own defaults, without the contact hook and query dispatcher rigidlab
//!    gives the world, `--bench frame` times the window's frame of the same level).
//!    `RIGIDLAB_BENCH_CASE=10` runs it alone.
//! 7. the other 10,000-body level, levels/stress/domino_field.ron (issue 45, the same 1.1x), the
//!    same way from 2.5 s (150 steps), while the waves run through rows of sleeping dominoes:
//!    the blocks take turns in the same stretch of the wave. `RIGIDLAB_BENCH_CASE=11` runs it
//!    alone.

#[path = "common/hundred_bodies.rs"]
mod hundred_bodies;

use rigidlab::level::{self, Scene};
use rigidlab::runner;
use rigidlab::sim::{Options, Simulation};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The typical library level of case 5.
const TYPICAL: &str = "levels/kinetics/physical_pendulum.ron";

/// The 10,000-body level of case 6, and its goal (issue 45).
const STRESS: &str = "levels/stress/sand_pile.ron";
const STRESS_GOAL: f64 = 1.1;
/// The other 10,000-body level, a domino field whose standing dominoes sleep (case 7).
const DOMINOES: &str = "levels/stress/domino_field.ron";

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Seconds to run `scene` plainly (`runner = false`) or through the runner.
fn time_run(scene: &Scene, runner: bool) -> f64 {
    let opts = Options::default();
    let t0 = Instant::now();
    if runner {
        let report = runner::run_scene(scene, &opts, &HashMap::new(), |_| {}).expect("it runs");
        std::hint::black_box(report);
    } else {
        let mut sim = Simulation::new(scene, &opts);
        let mut steps = 0u64;
        sim.run(|s| steps += s.step).expect("it runs");
        std::hint::black_box(steps);
    }
    t0.elapsed().as_secs_f64()
}

/// Median of runner / plain over `pairs` pairs of runs, the order alternating within pairs.
fn ratio(scenes: &[Scene], pairs: usize) -> (f64, f64, f64) {
    let (mut ratios, mut plain_s, mut runner_s) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..pairs {
        let (mut plain, mut run) = (0.0, 0.0);
        for scene in scenes {
            if k % 2 == 0 {
                plain += time_run(scene, false);
                run += time_run(scene, true);
            } else {
                run += time_run(scene, true);
                plain += time_run(scene, false);
            }
        }
        ratios.push(run / plain);
        plain_s.push(plain);
        runner_s.push(run);
    }
    (
        median(&mut ratios),
        median(&mut plain_s),
        median(&mut runner_s),
    )
}

fn library_levels(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("levels/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            library_levels(&p, out);
        } else if p.extension().is_some_and(|e| e == "ron") {
            out.push(p);
        }
    }
}

fn main() {
    let mut hundred = level::parse(Path::new("bench.ron"), &hundred_bodies::scene_ron())
        .unwrap_or_else(|e| panic!("{e}"));
    let questions: Vec<String> = hundred
        .level
        .bodies
        .iter()
        .filter(|b| b.kind == level::BodyKind::Dynamic)
        .map(|b| {
            format!(
                r#"(id: "v_{0}", ask: "speed", unit: "m/s", expected: 1.0, tolerance: 1e9, quantity: Speed("{0}"), at: Time(2.0), why: "bench")"#,
                b.name
            )
        })
        .collect();
    let text = hundred_bodies::scene_ron().replacen(
        "checks: [",
        &format!("questions: [{}], checks: [", questions.join(",\n")),
        1,
    );
    hundred = level::parse(Path::new("bench.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
    // Information: the same scene with only its checks, and with only its questions.
    let mut checks_only = hundred.clone();
    checks_only.level.questions.clear();
    let mut questions_only = hundred.clone();
    questions_only.level.checks.clear();
    let every = level::parse(
        Path::new("bench-every-kind.ron"),
        &hundred_bodies::every_kind_ron(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut bare = hundred.clone();
    bare.level.checks.clear();
    bare.level.questions.clear();
    let typical = vec![level::load(Path::new(TYPICAL)).unwrap_or_else(|e| panic!("{e}")); 10];
    // Information: the typical level with only its checks, and with only its questions.
    let typical_checks: Vec<Scene> = typical
        .iter()
        .map(|s| {
            let mut s = s.clone();
            s.level.questions.clear();
            s
        })
        .collect();
    let typical_questions: Vec<Scene> = typical
        .iter()
        .map(|s| {
            let mut s = s.clone();
            s.level.checks.clear();
            s
        })
        .collect();
    let mut files = Vec::new();
    library_levels(Path::new("levels"), &mut files);
    // The 10,000-body levels have their own cases (6, the pile; 7, the domino field): a run of
    // either takes longer than the rest of the library together.
    files.retain(|p| p != Path::new(STRESS) && p != Path::new(DOMINOES));
    let library: Vec<Scene> = files
        .iter()
        .map(|p| level::load(p).unwrap_or_else(|e| panic!("{e}")))
        .collect();

    println!("runner::run_scene against a plain Simulation::run, median of runner/plain over pairs of runs:");
    // RIGIDLAB_BENCH_CASE=1: only the first case (2, 3, ...: the others, in order), to profile it.
    let only: Option<usize> = std::env::var("RIGIDLAB_BENCH_CASE")
        .ok()
        .and_then(|c| c.parse().ok());
    if only.is_none_or(|c| c == 10) {
        ten_thousand_bodies(STRESS, 240);
    }
    if only.is_none_or(|c| c == 11) {
        // From 2.5 s: the dominoes the wave has not reached are asleep, the wave runs.
        ten_thousand_bodies(DOMINOES, 150);
    }
    for (case, (label, scenes, pairs)) in [
        (
            format!(
                "100 bodies, {} checks, {} questions",
                hundred.level.checks.len(),
                hundred.level.questions.len()
            ),
            std::slice::from_ref(&hundred),
            15,
        ),
        (
            "  the same, its checks only".to_string(),
            std::slice::from_ref(&checks_only),
            9,
        ),
        (
            "  the same, its questions only".to_string(),
            std::slice::from_ref(&questions_only),
            9,
        ),
        (
            format!(
                "100 bodies, every per-body check kind ({} checks)",
                every.level.checks.len()
            ),
            std::slice::from_ref(&every),
            9,
        ),
        (
            format!("the library, {} levels", library.len()),
            &library[..],
            5,
        ),
        (
            "100 bodies, no checks, no questions".to_string(),
            std::slice::from_ref(&bare),
            15,
        ),
        (
            format!(
                "{TYPICAL} ({} checks, {} questions) x 10",
                typical[0].level.checks.len(),
                typical[0].level.questions.len()
            ),
            &typical[..],
            15,
        ),
        (
            "  the same, its checks only".to_string(),
            &typical_checks[..],
            9,
        ),
        (
            "  the same, its questions only".to_string(),
            &typical_questions[..],
            9,
        ),
    ]
    .into_iter()
    .enumerate()
    {
        if only.is_some_and(|c| c != case + 1) {
            continue;
        }
        let (r, plain, run) = ratio(scenes, pairs);
        println!(
            "  {label:<52} {r:.3}x  (plain {:.1} ms, runner {:.1} ms; {pairs} pairs){}",
            plain * 1e3,
            run * 1e3,
            if r <= 1.05 { "" } else { "  over 1.05x" }
        );
    }
}

/// Seconds per step over `steps` steps: rigidlab's step (`ours`) or rapier's alone.
fn time_steps(sim: &mut Simulation, steps: usize, ours: bool) -> f64 {
    let t = Instant::now();
    for _ in 0..steps {
        if ours {
            sim.step().expect("the stress level stays finite");
        } else {
            sim.world.step();
        }
    }
    t.elapsed().as_secs_f64() / steps as f64
}

/// The same world as rapier at its own defaults would step it: parry's query dispatcher instead
/// of rigidlab's (sim/arc_contacts.rs), no contact-modification hook on the discs
/// (sim/contact_points.rs; `PhysicsWorld::step` runs no hooks anyway), contact recycling on.
fn rapier_defaults(sim: &mut Simulation) {
    use rapier2d::prelude::*;
    let w = &mut sim.world;
    w.narrow_phase
        .set_query_dispatcher(rapier2d::parry::query::DefaultQueryDispatcher);
    for (_, co) in w.colliders.iter_mut() {
        co.set_active_hooks(ActiveHooks::empty());
    }
    w.integration_parameters.contact_recycling = true;
}

/// Cases 6 and 7: a 10,000-body stress level, stepped by rigidlab and by a plain rapier loop
/// after `settle` steps.
fn ten_thousand_bodies(path: &str, settle: usize) {
    const BLOCK: usize = 5;
    const ROUNDS: usize = 15;
    let scene = level::load(Path::new(path)).unwrap_or_else(|e| panic!("{e}"));
    let opts = Options::default();
    // [rigidlab, contacts unread (as `check` runs it)], [rigidlab, contacts read (the window)],
    // [plain rapier loop], [rapier at its defaults]
    let mut sims: Vec<Simulation> = (0..4).map(|_| Simulation::new(&scene, &opts)).collect();
    sims[0].set_contact_readings(false);
    rapier_defaults(&mut sims[3]);
    let ours = [true, true, false, false];
    for (sim, ours) in sims.iter_mut().zip(ours) {
        time_steps(sim, settle, ours);
    }
    // Blocks interleaved, the order rotated every round, so drifts in load hit each alike.
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); sims.len()];
    for r in 0..ROUNDS {
        for k in 0..sims.len() {
            let i = (k + r) % sims.len();
            times[i].push(time_steps(&mut sims[i], BLOCK, ours[i]));
        }
    }
    let m: Vec<f64> = times.iter_mut().map(|t| median(t)).collect();
    let contacts = sims[1].snapshot().contacts.len();
    println!(
        "{path}: {} bodies, {contacts} contact manifolds after {settle} steps; median of {ROUNDS} blocks of {BLOCK} steps:",
        scene.level.bodies.len()
    );
    println!(
        "  plain rapier loop (the same world)           {:>8.2} ms/step",
        m[2] * 1e3
    );
    println!(
        "  rigidlab's step, contacts unread (check)      {:>8.2} ms/step   ratio {:.3}x   goal <= {STRESS_GOAL}x: {}",
        m[0] * 1e3,
        m[0] / m[2],
        if m[0] / m[2] <= STRESS_GOAL { "met" } else { "NOT met" }
    );
    println!(
        "  rigidlab's step, contacts read (the window)   {:>8.2} ms/step   ratio {:.3}x",
        m[1] * 1e3,
        m[1] / m[2]
    );
    println!(
        "  rapier at its own defaults (information)      {:>8.2} ms/step   ratio {:.3}x",
        m[3] * 1e3,
        m[3] / m[2]
    );
}
