//! Advice a teacher can reproduce (issue 41): the search for settings that pass is bounded by
//! the run budget's estimates, not by wall time, so the same level gets the same advice on an
//! idle machine and on a busy one.

use crate::common;

use rigidlab::level::Scene;
use rigidlab::report::{Advice, LevelReport};
use rigidlab::runner;
use rigidlab::sim::Options;
use rigidlab::study::advice::{advise, engine_failed};
use std::collections::HashMap;
use std::time::Instant;

fn run(scene: &Scene) -> LevelReport {
    runner::run_graded(scene, &Options::default(), &HashMap::new(), |_| {}).unwrap()
}

/// The CPU time this thread has used, s (Linux: /proc/thread-self/stat, utime + stime in clock
/// ticks of 10 ms).
fn thread_cpu_s() -> f64 {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |x| x.1);
    let f: Vec<f64> = after
        .split_whitespace()
        .map(|x| x.parse().unwrap_or(0.0))
        .collect();
    // Fields 14 and 15 of the line; after the ")" the state is field 3.
    f.get(11)
        .zip(f.get(12))
        .map_or(0.0, |(u, s)| (u + s) / 100.0)
}

/// Busy processes, two per core, each a shell spinning in an empty loop until the test kills it
/// (by its own child handle, when dropped): a machine loaded by other work, as other users'
/// builds load it.
struct Load {
    spinners: Vec<std::process::Child>,
}

impl Load {
    fn start() -> Load {
        let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
        let spinners = (0..2 * cores)
            .map(|_| {
                std::process::Command::new("sh")
                    .args(["-c", "while :; do :; done"])
                    .stdin(std::process::Stdio::null())
                    .spawn()
                    .expect("a shell to keep a core busy")
            })
            .collect();
        Load { spinners }
    }
}

impl Drop for Load {
    fn drop(&mut self) {
        for mut c in self.spinners.drain(..) {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

/// The advice's JSON, as `rigidlab check --json` writes it, and the search's wall time, s.
fn advice_json(scene: &Scene) -> (String, f64) {
    let own = run(scene);
    assert!(
        engine_failed(&own),
        "{} passes: pick a failing level",
        scene.file.display()
    );
    let t0 = Instant::now();
    let a = advise(scene, &Options::default(), Some(&own));
    let took = t0.elapsed().as_secs_f64();
    (serde_json::to_string(&a).unwrap(), took)
}

/// The eighth new user's drum hauling a block (tests/newuser/n8_10): a run of about 30 ms of
/// CPU whose search tries fifteen candidates, to 8x the level's cost, before its bound of 2
/// estimated seconds stops it (0.036 s a run, priced with its cable since 2026-12-06). On
/// 088f4b7, bounded by 2 s of wall time, it was searched up to 8x on a busy machine and said
/// "none passes within the search's 2 s" (docs/teacher.md: 3 of the 6 such verdicts on the new
/// users' levels came from load). Run twice, once with every core kept busy by two spinning
/// processes, the advice is the same JSON.
///
/// The test can fail: with the bound in wall time instead (an experiment of 2026-12-06, not
/// kept: `search` stopping once 0.1 s of wall time had passed since it began, in place of the
/// estimates' sum), the search stopped after the 2x candidates on the machine as it was (0.14
/// s) and before them under load (0.34 s), and the two JSONs differed in the setting they named
/// next (`--dt 0.002 --substeps 8 --precision f64` against `--dt 0.001 --substeps 4`).
#[test]
fn the_same_failing_level_gets_the_same_advice_on_a_busy_machine() {
    let scene = common::load("tests/newuser/linkages/n8_10_drum_hauls_block_efficiency.ron");
    let (idle, idle_s) = advice_json(&scene);
    let (busy, busy_s) = {
        let _load = Load::start();
        advice_json(&scene)
    };
    println!("search: {idle_s:.2} s as the machine was, {busy_s:.2} s under load");
    println!("idle: {idle}\nbusy: {busy}");
    assert_eq!(idle, busy, "the advice changed with the machine's load");
    // A search of several candidates, where a bound in wall time would have cut it at a point
    // that depends on the load: it searched to 4x the level's cost or past (the candidates to 4x
    // are eight runs: 1.25x, 2x and 2.5x twice each, 4x three times).
    let a: serde_json::Value = serde_json::from_str(&idle).unwrap();
    assert!(
        a["none_within"].as_f64().is_some_and(|x| x >= 4.0)
            || a["cost_ratio"].as_f64().is_some_and(|x| x >= 4.0),
        "{idle}"
    );
}

/// The search's time at its bound (docs/cli.md): every level of tests/newuser the engine fails
/// at its own settings, one at a time, with the search's verdict, CPU time and wall time (CPU
/// time stands for an idle machine's wall time: a run uses one thread).
/// `cargo test --release --test suite -- --ignored --nocapture study::advice_reproducible`
#[test]
#[ignore = "a measurement: about a minute"]
fn search_time_at_the_bound() {
    let files = common::ron_files("tests/newuser", &[]);
    let mut rows = Vec::new();
    for f in &files {
        let scene = common::load(f);
        let own = run(&scene);
        if !engine_failed(&own) {
            continue;
        }
        let (c0, t0) = (thread_cpu_s(), Instant::now());
        let a = advise(&scene, &Options::default(), Some(&own));
        let (cpu, wall) = (thread_cpu_s() - c0, t0.elapsed().as_secs_f64());
        let kind = match &a {
            Advice::Settings { cost_ratio, .. } => format!("settings at {cost_ratio}x"),
            Advice::NoneWithin {
                within_estimated_seconds: Some(_),
                none_within,
                ..
            } => format!("bound reached, tried to {none_within}x"),
            Advice::NoneWithin { none_within, .. } => format!("none within {none_within}x"),
        };
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        println!(
            "{name:60} own {:7.1} ms  search {cpu:6.2} s CPU {wall:6.2} s wall  {kind}",
            own.wall_ms
        );
        rows.push((kind.starts_with("bound"), cpu, wall));
    }
    let mut at_bound: Vec<f64> = rows.iter().filter(|r| r.0).map(|r| r.1).collect();
    at_bound.sort_by(f64::total_cmp);
    let total: f64 = rows.iter().map(|r| r.1).sum();
    println!(
        "{} failing levels, searches {total:.1} s CPU in all; {} stopped at the bound: CPU {:?} s",
        rows.len(),
        at_bound.len(),
        at_bound
    );
}

/// A ball (m = 0.6 kg, r = 0.1 m, e = 0.8 on a fixed floor, no friction) dropped from rest 1 m
/// above the floor (to its lowest point), asked for its kinetic energy when it has travelled
/// 1.1 m: down 1 m, then 0.1 m up after the bounce. By hand: it strikes at v1^2 = 2 g h and
/// leaves at e v1, so at d = 0.1 m up T = m g (e^2 h - d) = 0.6 x 9.81 x (0.64 - 0.1) = 3.17844
/// J. The engine reads low by what its bounce loses beyond e (its rebound falls short first
/// order in dt, docs/known-gaps.md): measured 0.0213 J at d = 0.3 m (1.06e-2 of the 2.00 J
/// there, 2026-12-06), so about 0.67e-2 of T here, within the tolerance 1e-2. The analysis of
/// `KineticEnergy` at a configuration
/// event is work-energy, T0 plus the work of gravity, springs, loads and events (RE-7), and it
/// counts a normal contact with a fixed body as workless (docs/levels.md says so): m g (h - d)
/// = 5.2974 J, 67 % off (measured 105 % at d = 0.3 m), at any step. The level's answer is right and its analysis cannot fit
/// (an impact's loss): the advice says so at once, naming the question, instead of searching.
const BOUNCED_BALL: &str = r#"Level(
  title: "A ball's kinetic energy after its bounce",
  statement: "A 0.6 kg ball is dropped from rest 1 m above a rigid floor (to its lowest point); e = 0.8. Find its kinetic energy 0.1 m above the floor on the way up.",
  effects: [gravity, contacts, restitution],
  world: (dt: 0.0010416666666666667, substeps: 4, duration: 0.7),
  bodies: [
    (name: "floor", kind: fixed, shape: Segment(a: (-5.0, 0.0), b: (5.0, 0.0))),
    (name: "ball", shape: Circle(radius: 0.1), mass: 0.6, position: (0.0, 1.1), restitution: 0.8, lock_rotation: true),
  ],
  questions: [
    (id: "T_up", ask: "Kinetic energy 0.1 m above the floor after the bounce", unit: "J", expected: 3.17844, tolerance: 1e-2,
     quantity: KineticEnergy("ball"), at: Crossing(of: Distance("ball"), value: 1.1), why: "m g (e^2 h - d); the bounce loses 0.02 J beyond e at this dt (first order)"),
  ],
)"#;

#[test]
fn an_analysis_that_cannot_fit_is_said_at_once_without_a_search() {
    let scene = common::parse(BOUNCED_BALL);
    let own = run(&scene);
    let q = &own.questions[0];
    // The premise: the engine agrees with the answer, the analysis does not, by far (over 50x
    // the tolerance: the derivation above gives 67 %).
    assert!(q.rel_error <= q.tolerance, "{q:?}");
    assert!(
        q.analysis_rel_error.is_some_and(|a| a > 50.0 * q.tolerance),
        "{q:?}"
    );
    let a = advise(&scene, &Options::default(), Some(&own));
    let Advice::NoneWithin {
        none_within,
        why,
        within_estimated_seconds,
        ..
    } = &a
    else {
        panic!("settings advised for an analysis that cannot fit: {a:?}")
    };
    assert!(
        why.starts_with("the analysis does not fit this scene; no setting helps")
            && why.contains("`T_up`"),
        "{why}"
    );
    // Not a search: nothing past the first finer setting was tried.
    assert_eq!(
        (*none_within, *within_estimated_seconds),
        (0.0, None),
        "{why}"
    );
}

/// The rule does not fire where accuracy brings the analysis to the answer: a level whose
/// question fails on its analysis alone at its own settings and passes at the first finer one
/// gets settings. No level of the library or of tests/newuser fails so since 2026-12-06 (the
/// last, the eighth new user's damped pair, read `W_c`'s analysis -sum c (dL)^2 / dt, first
/// order in the substep, 2.0e-3 against 2e-3; now the trapezoid, 8e-6), so its own report is
/// given that failure here (its analysis 1.5 tolerances off, the engine's left as measured)
/// and the search reruns the level itself at the finer settings, where it passes. (Until
/// 2026-12-06 the report was the level's own; before that, the wheel meeting a curb from 8 mm,
/// n2_03b.)
#[test]
fn an_analysis_that_accuracy_fixes_still_gets_settings() {
    let scene = common::load("tests/newuser/oscillations/n8_16_two_blocks_spring_damper_pair.ron");
    let mut own = run(&scene);
    assert!(own.passed, "the damped pair passes at its own settings");
    let q = own
        .questions
        .iter_mut()
        .find(|q| q.id == "W_c")
        .expect("W_c");
    q.analysis_rel_error = Some(1.5 * q.tolerance);
    q.passed = false;
    own.passed = false;
    assert!(rigidlab::study::advice::failed_by_analysis_alone(&own).is_some());
    let a = advise(&scene, &Options::default(), Some(&own));
    assert!(matches!(a, Advice::Settings { .. }), "{a:?}");
}
