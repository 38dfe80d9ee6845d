//! The run budget (src/runner/budget.rs): runs estimated past the time or the memory budget are
//! refused with the estimate in seconds and MB (exit 2, at the level file) by `check`, `run`,
//! `study stability` and `render --time`; `--allow-long` lifts it; and the estimate is the
//! formula docs/cli.md states. No timing here: the measured times are in docs/cli.md, dated.
//!
//! The adversarial levels are in tests/budget/ (`python3 tools/budget_levels.py` writes them),
//! except 10^4 questions (1.4 MB), which is generated here.

use crate::common;

use common::{load, parse, rigidlab};
use rigidlab::runner::budget::{self, Estimate, Mode, Work};
use rigidlab::sim::Options;

/// Runs the binary; (exit code, stderr).
fn cli(args: &[&str]) -> (i32, String) {
    let out = rigidlab().args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A refusal: exit 2, located at the level file, with the estimate in s and MB.
fn assert_refused(args: &[&str], file: &str) -> String {
    let (code, err) = cli(args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(
        err.contains(&format!("{file}: error: this run is estimated to take ")),
        "{err}"
    );
    assert!(err.contains(" s and ") && err.contains(" MB ("), "{err}");
    assert!(
        err.contains("past the budget of 600 s and 4096 MB"),
        "{err}"
    );
    assert!(err.contains("--allow-long"), "{err}");
    err
}

const IM: &str = "tests/budget/impulse_momentum_1e8.ron";

#[test]
fn an_impulse_momentum_check_over_1e8_steps_is_refused_for_its_memory() {
    // 1e8 steps x 48 bytes of the ledger: 4578 MB of history, past 4096 MB; 216 s is within time.
    let e = Estimate::of(
        &load(IM).level,
        &Options {
            dt: Some(1e-5),
            ..Default::default()
        },
        Mode::Check,
        None,
    );
    assert_eq!(e.work.steps, 1e8);
    assert_eq!(e.work.history_bytes_per_step, 48.0);
    assert!(
        e.megabytes > budget::MEMORY_BUDGET_MB && e.seconds < budget::TIME_BUDGET_S,
        "{e:?}"
    );
    let err = assert_refused(&["check", IM, "--dt", "1e-5"], IM);
    assert!(err.contains("checks keeping 48 bytes a step"), "{err}");
    assert_refused(&["run", IM, "--dt", "1e-5"], IM);
}

#[test]
fn a_long_run_is_refused_for_its_time() {
    let ff = "levels/kinematics/free_fall.ron";
    let err = assert_refused(&["check", ff, "--dt", "1e-9"], ff);
    assert!(err.contains("1.000e9 steps x 4 substeps"), "{err}");
    assert_refused(&["run", ff, "--substeps", "1000", "--dt", "1e-7"], ff);
    // A step of 1e-300 s gives a number, not an overflow.
    assert_refused(&["check", ff, "--dt", "1e-300"], ff);
}

#[cfg(feature = "app")]
#[test]
fn render_at_1e12_s_is_refused() {
    let ff = "levels/kinematics/free_fall.ron";
    let out = std::env::temp_dir().join("rigidlab_run_budget.png");
    let out = out.to_str().unwrap();
    let err = assert_refused(&["render", ff, "--time", "1e12", "--out", out], ff);
    assert!(err.contains("6.000e13 steps"), "{err}");
    assert!(!std::path::Path::new(out).exists());
}

#[test]
fn study_stability_refuses_a_case_past_the_budget() {
    let err = assert_refused(
        &[
            "study",
            "stability",
            "--dt",
            "1e-8",
            "--quick",
            "spinning_disc",
        ],
        "levels/stress/spinning_disc.ron",
    );
    assert!(err.contains("steps x"), "{err}");
}

#[test]
fn allow_long_lifts_the_budget() {
    let scene = load("levels/kinematics/free_fall.ron");
    let mut args = rigidlab::cli::SolverArgs {
        dt: Some(1e-9),
        ..Default::default()
    };
    let opts = args.options().unwrap();
    let e = args.budget(&scene, &opts).unwrap_err();
    assert!(e.to_string().contains("past the budget of 600 s"), "{e}");
    args.allow_long = true;
    args.budget(&scene, &opts).unwrap();
}

/// 10^4 questions on one ball, as tools/budget_levels.py writes them.
fn ten_thousand_questions() -> String {
    let mut t = String::from(
        "Level(title: \"10^4 questions\", effects: [gravity],\n world: (dt: 0.016666666666666666, substeps: 1, duration: 10.0),\n bodies: [(name: \"ball\", shape: Circle(radius: 0.1), mass: 0.5, position: (0.0, 10.0))],\n questions: [\n",
    );
    for i in 0..10_000 {
        t += &format!(
            "  (id: \"q{i}\", ask: \"Height at the end\", unit: \"m\", expected: 10.0, tolerance: 1e9, quantity: Y(\"ball\"), at: Time(10.0), why: \"budget test\"),\n"
        );
    }
    t + " ],\n)\n"
}

#[test]
fn the_adversarial_levels_that_fit_are_priced_by_what_they_hold() {
    // 10^4 questions: 600 steps x 10^4 x 0.15 us = 0.9 s; 10^4 x 3.4 KB = 33 MB.
    let q = as_checked(&parse(&ten_thousand_questions()).level);
    assert_eq!(q.work.questions, 10_000);
    assert!(q.fits() && q.seconds > 0.9 && q.megabytes > 60.0, "{q:?}");
    // 1000 discs at one point, 1 m above the ground: every pair of discs overlaps, 499,500 of
    // them, each disc in 999: making them dominates.
    let d = as_checked(&load("tests/budget/discs_1000_one_point.ron").level);
    assert_eq!(d.work.pairs, 499_500.0);
    assert_eq!(d.work.pair_degrees, 1000.0 * 999.0 * 999.0);
    assert!(
        d.fits() && d.seconds > 10.0 && d.megabytes > 1000.0,
        "{d:?}"
    );
    // 1000 substeps of a spring are split: 1000 rapier calls a step.
    let s = as_checked(&load("tests/budget/spring_1000_substeps.ron").level);
    assert_eq!((s.work.substeps, s.work.calls_per_step), (1000, 1000));
}

#[test]
fn the_estimate_is_the_formula_docs_cli_md_states() {
    // docs/cli.md, "The cost budget": levels/energy/block_friction_work.ron.
    let e = as_checked(&load("levels/energy/block_friction_work.ron").level);
    let w: Work = e.work;
    assert_eq!(
        (
            w.steps,
            w.substeps,
            w.iterations,
            w.calls_per_step,
            w.bodies,
            w.joints
        ),
        (DOC.0, DOC.1, DOC.2, DOC.3, DOC.4, DOC.5)
    );
    assert_eq!((w.pairs, w.questions, w.checks), (DOC.6, DOC.7, DOC.8));
    let seconds_of = |w: &Work| {
        // Pairs past 800 (a core's L2) at 2.5x; split steps at their expected share.
        let pairs = w.pairs.min(800.0) + (w.pairs - 800.0).max(0.0) * 2.5;
        let calls = 1.0 + (w.calls_per_step as f64 - 1.0) * w.split_share;
        // From 256 joints, rapier solves them in its SIMD lanes, at 0.35x.
        let joints = w.joints as f64 * if w.joints >= 256 { 0.35 } else { 1.0 };
        let step_us = calls
            * (1.3
                + pairs * 0.1
                + w.couplings as f64 * 2.5
                + w.turning_couplings as f64 * 4.5
                + w.polyline_facets * 0.035
                + w.other_tracks * 9.0)
            + w.bodies as f64 * 0.05
            + w.substeps as f64
                * (0.08
                    + w.bodies as f64 * 0.008
                    + (joints + pairs) * (0.048 + w.iterations as f64 * 0.02))
            + w.questions as f64 * 0.15
            + w.checks as f64 * 0.3
            + w.virtual_work_joints as f64 * 1.0;
        // A linearization: its joints, and d^2 n^3 of its mechanism's SVDs.
        let (n, d) = (w.mechanism.0 as f64, w.mechanism.1 as f64);
        let linearize_us = 700.0 + 5500.0 * w.joints as f64 + 0.2 * d * d * n.powi(3);
        0.01 + (30.0 + w.linearizations as f64 * linearize_us + w.reference_us) * 1e-6
            + w.steps * step_us * 1e-6
            + w.pair_degrees * 17e-9
            + w.facets * 0.32e-6
    };
    let seconds = seconds_of(&w);
    assert!(
        (e.seconds - seconds).abs() < 1e-12,
        "{} vs {seconds}",
        e.seconds
    );
    // At 8 iterations the rows' iteration term counts (each iteration a biased and an unbiased
    // sweep since 2026-11-27): the same formula with I = 8, dearer than at 1.
    let e8 = Estimate::of(
        &load("levels/energy/block_friction_work.ron").level,
        &Options {
            solver_iterations: Some(8),
            ..Options::default()
        },
        Mode::Check,
        None,
    );
    assert_eq!(e8.work.iterations, 8);
    assert!(
        (e8.seconds - seconds_of(&e8.work)).abs() < 1e-12 && e8.seconds > e.seconds,
        "{} vs {} (1 iteration {})",
        e8.seconds,
        seconds_of(&e8.work),
        e.seconds
    );
    assert!((e.seconds - DOC.9).abs() < 1e-9, "{}", e.seconds);
    assert_eq!((w.pair_degrees, w.history_bytes_per_step), (2.0, 64.0));
    let mb = 32.0
        + (w.bodies as f64 * 1.5
            + w.joints as f64 * 4.0
            + w.pairs * 2.5
            + w.questions as f64 * 3.4)
            / 1024.0
        + w.steps * w.history_bytes_per_step / 1048576.0;
    assert!(
        (e.megabytes - mb).abs() < 1e-9 && (e.megabytes - DOC.10).abs() < 5e-3,
        "{}",
        e.megabytes
    );
}

/// docs/cli.md's example: steps, substeps, iterations, calls a step, bodies, joints, pairs,
/// questions, checks, seconds, MB.
const DOC: (
    f64,
    usize,
    usize,
    usize,
    usize,
    usize,
    f64,
    usize,
    usize,
    f64,
    f64,
) = (480.0, 4, 1, 1, 2, 0, 1.0, 1, 3, 0.011568914, 32.038);

/// Prints the estimate of each file in RIGIDLAB_ESTIMATE (space-separated; a folder: each level
/// in it and their sum), with RIGIDLAB_ESTIMATE_DT as --dt and RIGIDLAB_ESTIMATE_TIME as render's
/// --time. For the table in docs/cli.md:
///   RIGIDLAB_ESTIMATE="levels tests/budget/discs_1000_one_point.ron" \
///     cargo test --release --test suite -- runner::budget::print_estimates --ignored --nocapture
#[test]
#[ignore]
fn print_estimates() {
    let dt = std::env::var("RIGIDLAB_ESTIMATE_DT")
        .ok()
        .and_then(|v| v.parse().ok());
    let time: Option<f64> = std::env::var("RIGIDLAB_ESTIMATE_TIME")
        .ok()
        .and_then(|v| v.parse().ok());
    let opts = Options {
        dt,
        ..Default::default()
    };
    for arg in std::env::var("RIGIDLAB_ESTIMATE")
        .unwrap_or_default()
        .split_whitespace()
    {
        let files = rigidlab::level::collect_files(&[arg.into()]).unwrap();
        let (mut s, mut mb) = (0.0f64, 0.0f64);
        for f in &files {
            let scene = rigidlab::level::load(f).unwrap();
            let e = match time {
                Some(t) => Estimate::of(
                    &scene.level,
                    &opts,
                    Mode::Render,
                    Some((t / scene.level.world.dt).round()),
                ),
                None => Estimate::of(&scene.level, &opts, Mode::Check, None),
            };
            println!(
                "{:.3} s {:.1} MB {} {:?}",
                e.seconds,
                e.megabytes,
                f.display(),
                e.work
            );
            s += e.seconds;
            mb = mb.max(e.megabytes);
        }
        println!("TOTAL {s:.3} s {mb:.1} MB (peak) {arg}");
    }
}

/// This thread's CPU time, s, to the nanosecond (Linux: /proc/thread-self/schedstat's first
/// field, the time it ran).
fn thread_cpu_s() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns * 1e-9)
}

/// The estimate against the run's counted rapier calls and its CPU time: each file of
/// RIGIDLAB_ESTIMATE (space-separated) run RIGIDLAB_REPS times (default 5) in this thread by
/// `runner::run_graded` (the process's start is not in it: the estimate's START_S is), their
/// mean CPU time (the kernel books a thread's time at its ticks and switches: a run of a few ms
/// needs several to be measured). For docs/cli.md's table of curved tracks and split steps:
///   RIGIDLAB_ESTIMATE="tests/newuser/curved/n7_02_ball_rolling_in_bowl.ron" \
///     cargo test --release --test suite -- runner::budget::measure_estimates --ignored --nocapture
#[test]
#[ignore = "a measurement"]
fn measure_estimates() {
    let reps: usize = std::env::var("RIGIDLAB_REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5);
    for arg in std::env::var("RIGIDLAB_ESTIMATE")
        .unwrap_or_default()
        .split_whitespace()
    {
        let scene = load(arg);
        let e = as_checked(&scene.level);
        let c0 = thread_cpu_s();
        for _ in 0..reps {
            rigidlab::runner::run_graded(
                &scene,
                &Options::default(),
                &std::collections::HashMap::new(),
                |_| {},
            )
            .unwrap();
        }
        let mean = (thread_cpu_s() - c0) / reps as f64;
        let counted = counted_calls(&scene);
        let w = &e.work;
        println!(
            "{arg}: estimate {:.4} s ({:.4} s past the start), measured CPU {mean:.4} s: ratio \
             {:.2}; calls estimated {:.0}, counted {counted:.0}; {w:?}",
            e.seconds,
            e.seconds - budget::START_S,
            (e.seconds - budget::START_S) / mean,
            w.steps * w.calls(),
        );
    }
}

/// The rapier calls a run made, as the simulation counts them (`StepCalls::calls`, the calls
/// planned for its steps: one, `substeps`, or for a spinning ball as few as keep its contact),
/// and a step an impact cut divides about two more (the call before the impact, the short call
/// that makes it, the rest).
fn counted_calls(scene: &rigidlab::level::Scene) -> f64 {
    let mut sim = rigidlab::sim::Simulation::new(scene, &Options::default());
    for _ in 0..sim.total_steps() {
        sim.step().expect("the level runs");
    }
    sim.calls.calls as f64 + 2.0 * sim.calls.cut as f64
}

/// The estimate prices the rapier calls a run makes: its calls (steps x calls a step) within
/// 20% of those the run counts (`counted_calls`), on a plain level, a frictionless puck in a ring
/// (never split), a ball and a disc rolling (one call a step, priced so: since 2026-12-07 a
/// ball's steps are split only where its turn over a call would disturb its loaded contact, a
/// choice the run makes late: the disc's last 41 of 252 steps into 2 calls, 16% more calls than
/// priced; hence 20%; the ball in a bowl none) and a drum hauling a block by a cable (split for
/// its joint's impulses, with one coupling solved after each call). Until 2026-12-06 the
/// rolling ball was priced at 624 calls for 2388 (tests/newuser/curved/n7_02, 3.8x). The time
/// each call costs is measured, not asserted (`measure_estimates`; docs/cli.md).
#[test]
fn the_estimate_counts_the_calls_a_run_makes() {
    for (file, couplings) in [
        ("levels/energy/block_friction_work.ron", 0),
        ("tests/newuser/curved/n13_05_ball_in_vertical_ring.ron", 0),
        ("tests/newuser/curved/n7_02_ball_rolling_in_bowl.ron", 0),
        ("levels/kinetics/classic_rolling_disc.ron", 0),
        (
            "tests/newuser/linkages/n8_10_drum_hauls_block_efficiency.ron",
            1,
        ),
    ] {
        let scene = load(file);
        let w = as_checked(&scene.level).work;
        let (priced, counted) = (w.steps * w.calls(), counted_calls(&scene));
        assert!(
            (priced / counted - 1.0).abs() <= 0.2,
            "{file}: {priced} calls priced, {counted} made"
        );
        assert_eq!(w.couplings, couplings, "{file}");
    }
}

/// A curved track's facets are priced once, as built, not in every call: a ball on an `Arc`
/// touches its circle (sim/arc_track.rs), so halving the step adds the steps' price alone. The
/// puck in a ring of 7025 facets (n13_05, 1000 steps): its facets 2.2 ms, its steps 2.5 ms,
/// and at dt / 2 its steps twice that (0.32 us a facet, measured 2026-12-07 from one-step runs,
/// and the step's terms: docs/cli.md). On 2026-12-06 before this, each call paid 0.04 us a
/// facet: 0.29 s for a run of 10 ms.
#[test]
fn a_curved_tracks_facets_are_priced_once() {
    let level = load("tests/newuser/curved/n13_05_ball_in_vertical_ring.ron").level;
    let at = |dt: f64| {
        Estimate::of(
            &level,
            &Options {
                dt: Some(dt),
                ..Options::default()
            },
            Mode::Check,
            None,
        )
    };
    let (e1, e2) = (at(level.world.dt), at(level.world.dt / 2.0));
    assert_eq!(e1.work.facets, 7025.0);
    let steps = |e: &Estimate| e.work.steps * e.work.step_us() * 1e-6;
    let facets_s = e1.seconds
        - budget::START_S
        - budget::RUN_US * 1e-6
        - steps(&e1)
        - e1.work.pair_degrees * 17e-9;
    assert!((facets_s - 7025.0 * 0.32e-6).abs() < 1e-9, "{facets_s}");
    assert!(
        (e2.seconds - e1.seconds - (steps(&e2) - steps(&e1))).abs() < 1e-9,
        "{e1:?} {e2:?}"
    );
    assert!(e1.seconds < 0.02, "{}", e1.seconds);
}

/// The estimate at `dt` of a level.
/// The estimate of `level` as `rigidlab check` makes it, at the level's own settings.
fn as_checked(level: &rigidlab::level::Level) -> Estimate {
    Estimate::of(level, &Options::default(), Mode::Check, None)
}

fn at_dt(level: &rigidlab::level::Level, dt: f64) -> Estimate {
    Estimate::of(
        level,
        &Options {
            dt: Some(dt),
            ..Options::default()
        },
        Mode::Check,
        None,
    )
}

/// A windowed question reads its whole window again at every step (questions/probe.rs): its
/// price is steps x window / dt, so halving dt quadruples it, where a plain question's price
/// doubles. The slotted arm (a `MotorTorque` over 10 ms) at dt 1e-6 was priced 0.61 s before and
/// ran past 226 s of CPU (issue 45; 1.4 to 1.7 us a snapshot measured 2026-12-07 with `check`
/// at dt 2e-5 to 5e-6, 0.6 us by benches/budget.rs at 2e-5, priced 1.0: src/runner/budget.rs):
/// 80,000 steps x 10,001 snapshots x 1.0 us (to its reading at 30 degrees, 0.07 s of the
/// 0.08 s, priced to the end: a crossing's time is not known before) is 800 s, past the budget.
#[test]
fn a_windowed_questions_price_grows_with_the_square_of_the_steps() {
    let arm = "levels/virtual-work/zh_slider_slotted_arm.ron";
    let level = load(arm).level;
    let (e1, e2) = (at_dt(&level, 1e-5), at_dt(&level, 5e-6));
    // 0.01 s window: 2 x round(0.005 / dt) + 1 snapshots a step.
    assert_eq!(e1.work.windows.motor, 1001.0);
    assert_eq!(e2.work.windows.motor, 2001.0);
    let windows_s = |e: &Estimate| e.work.steps * e.work.windows.step_us() * 1e-6;
    let ratio = windows_s(&e2) / windows_s(&e1);
    // (2 x 2001) / 1001 = 3.998: the square of the steps' ratio, within the window's odd count.
    assert!((ratio - 4.0).abs() < 0.01, "{ratio}");
    assert!(
        windows_s(&e1) > 0.9 * e1.seconds,
        "the window is most of the run: {e1:?}"
    );
    let e = at_dt(&level, 1e-6);
    assert!(!e.fits() && e.seconds > 800.0, "{e:?}");
    let err = assert_refused(&["check", arm, "--dt", "1e-6"], arm);
    assert!(err.contains("1 windowed question"), "{err}");
}

/// A question read at a time stops reading its window there (a settled probe does no work):
/// priced to its time and half its window, not to the end.
#[test]
fn a_windowed_question_read_at_a_time_is_priced_to_that_time() {
    let text = |at: &str| {
        format!(
            "Level(title: \"window\", effects: [gravity, contacts],\n world: (dt: 0.001, substeps: 1, duration: 1.0),\n bodies: [(name: \"floor\", kind: fixed, shape: Box(width: 2.0, height: 0.2), position: (0.0, -0.1)), (name: \"box\", shape: Box(width: 0.2, height: 0.2), mass: 1.0, position: (0.0, 0.1))],\n questions: [(id: \"N\", ask: \"N\", unit: \"N\", expected: 9.81, tolerance: 0.01, quantity: ContactForceFrom(body: \"box\", other: \"floor\", window: 0.02), at: {at}, why: \"budget test\")],\n)\n"
        )
    };
    let end = as_checked(&parse(&text("End")).level);
    let early = as_checked(&parse(&text("Time(0.24)")).level);
    // 21 snapshots a step; to t = 0.24 + 0.01 of 1 s: a quarter of the run.
    assert_eq!(end.work.windows.contact, 21.0);
    assert!(
        (early.work.windows.contact - 21.0 * 0.25).abs() < 1e-9,
        "{early:?}"
    );
}

/// A ball on a fixed `Arc`, riding it or rolling on it, is cast against the arc before each
/// call once calls are short (sim/impacts.rs plans the impact cuts: a cast whenever the pair
/// closes faster than 2 g h + 1 mm/s and is more than 10 um apart). Measured
/// 2026-12-07 with `cargo bench --no-default-features --bench budget` (CPU time of the run's
/// thread): the puck in a ring of tests/newuser/curved/n13_05 at dt 1e-5 (calls of 2.5 us) 17 us
/// a call; the rolling disc of levels/kinetics/curve_disc_rolling_in_ring at dt 2e-6 (calls of
/// 0.5 us) 2.6 us a call, as at its own dt. (On 2026-12-07 before this, that disc measured 31 us
/// a call at 2e-6 with `check`, and every body on a curved track was priced a cast.) So the
/// ring at dt 4.2e-8 (issue 45: accepted then for what was 11 hours of CPU) is priced its calls
/// alone, 4.3e7 steps x its calls, linear in the steps, and the puck's casts make its price per
/// call jump by the cast's 15 us once calls are 2.5 us or shorter. Measured again 2026-12-07
/// (the bench, load average 4 to 6): the disc at dt 2e-6, one call a step, 10.0 to 10.7 us a
/// step where 2.5 were priced, most of it in the planner's nonlinear casts (`perf`); the puck at
/// 1e-5 priced 1.80x with 15 us. Since then both are priced a cast, 10 us, from calls of 2.5 us
/// down.
#[test]
fn a_ball_on_an_arc_is_priced_its_casts_at_fine_steps() {
    let ring = load("levels/kinetics/curve_disc_rolling_in_ring.ron").level;
    let dt = ring.world.dt;
    // Its dt, 4.2e-3 s, and dt / 10^4, one call a step (the disc's spin splits no step where no
    // question reads a contact's start, end or slip).
    let (coarse, fine) = (at_dt(&ring, dt), at_dt(&ring, dt / 1e4));
    assert_eq!((coarse.work.track_pairs, fine.work.track_pairs), (1.0, 1.0));
    assert_eq!(fine.work.calls_per_step, 1);
    assert_eq!(coarse.work.track_cast_us(), 0.0);
    assert_eq!(fine.work.track_cast_us(), budget::TRACK_CAST_US);
    // At dt / 10^4 the steps are 10^4 times as many, each dearer by the cast alone.
    let steps_s = |e: &Estimate| e.work.steps * (e.work.step_us() - e.work.track_cast_us()) * 1e-6;
    let ratio = steps_s(&fine) / steps_s(&coarse);
    assert!((ratio / 1e4 - 1.0).abs() < 1e-9, "{ratio}");
    // Issue 45's case: the ring at dt 4.2e-8 (4.3e7 steps), accepted for about 11 hours before
    // its disc's contact was exact. Measured 2026-12-07 (`check` on copies of the level cut to
    // 0.004 s and 0.04 s at that dt, CPU time, load about 3): 0.65 s and 2.97 s, the dearer
    // start included, so the whole 1.8 s costs at most 1.8 / 0.04 x 2.97 = 134 s. The price,
    // 1.7e8 calls of 3.4 us (585 s), is within 4.4x of that, on the safe side, and inside the
    // 600 s budget: accepted, as a run of a couple of minutes should be.
    let edge = at_dt(&ring, 4.2e-8);
    assert!(edge.fits(), "{edge:?}");
    assert!((134.0..600.0).contains(&edge.seconds), "{}", edge.seconds);
    let puck = load("tests/newuser/curved/n13_05_ball_in_vertical_ring.ron").level;
    // A call's price, its windowed question's snapshots aside (their number follows dt).
    let call_us = |e: &Estimate| (e.work.step_us() - e.work.windows.step_us()) / e.work.calls();
    // Calls of dt / 4: 2.5 us at dt 1e-5 cast, 2.75 us at 1.1e-5 do not.
    let (long, short) = (at_dt(&puck, 1.1e-5), at_dt(&puck, 1e-5));
    assert_eq!(short.work.track_pairs, 1.0);
    assert_eq!(long.work.track_cast_us(), 0.0);
    let jump = call_us(&short) - call_us(&long);
    assert!(
        (jump - budget::TRACK_CAST_US).abs() < 1e-9,
        "{jump} {long:?} {short:?}"
    );
}

/// A loop's ramp and its circle are two curved tracks: a body that starts on the ramp meets the
/// circle on its way, and the impact planner queries and casts against it as it comes near.
/// Measured 2026-12-07 (as for the polylines below): the loops of two `Arc`s (levels/energy/
/// curve_loop_the_loop and its rolling twin, levels/challenges/loop_least_height,
/// tests/newuser/curved/n7_01, n14_01, n14_02, n14_03, n14_23) 12 to 19 us a call past the
/// other terms, priced 0.09x to 0.3x before; a ramp, a floor and a loop apart (n15_01a-c) 2.4
/// us. Priced 9 us a call for each other curved track: the loops at 0.57x to 0.76x, the
/// ramp-floor-loops at 1.78x to 1.84x. A bowl, a single `Arc`, has none.
#[test]
fn a_second_curved_track_is_priced_at_every_call() {
    let work = |file: &str| as_checked(&load(file).level).work;
    let w = work("tests/newuser/curved/n7_01_loop_min_height.ron");
    assert_eq!(w.other_tracks, 1.0);
    let without = Work {
        other_tracks: 0.0,
        ..w
    };
    let per_call = (w.step_us() - without.step_us()) / w.calls();
    assert!((per_call - budget::OTHER_TRACK_CALL_US).abs() < 1e-9);
    assert_eq!(
        work("tests/newuser/curved/n7_02_ball_rolling_in_bowl.ron").other_tracks,
        0.0
    );
}

/// A pile poured into a bin has no contact pair at its start and tens of thousands once it rests
/// (issue 45: levels/stress/sand_pile.ron, 10,000 grains, priced 0.02x its 25 s before this,
/// 2026-12-07). The estimate counts the pairs n loose bodies make as they come to rest as a heap
/// of discs holds them: n equal discs packed in a triangle of side k, n = k (k + 1) / 2, touch
/// in 3 k (k - 1) / 2 pairs and rest on the floor in k, 3 n - 2.83 sqrt(n) in all (at least n:
/// each rests on something). Bodies in a pair at the start (a stack, an arch) are not loose;
/// without gravity nothing comes to rest.
#[test]
fn loose_bodies_are_priced_the_pairs_of_the_heap_they_make() {
    let heap = |n: f64| (3.0 * n - 2.83 * n.sqrt()).max(n);
    let grains = |cols: usize, rows: usize, effects: &str| {
        let mut bodies = String::from(
            "(name: \"floor\", kind: fixed, shape: Box(width: 100.0, height: 1.0), position: (0.0, -0.5)),\n",
        );
        for k in 0..cols * rows {
            // 12 cm apart, 2 cm above the floor: no two boxes within 1 cm.
            let (x, y) = (0.12 * (k % cols) as f64, 0.07 + 0.12 * (k / cols) as f64);
            bodies += &format!(
                "(name: \"g{k}\", shape: Circle(radius: 0.05), position: ({x}, {y}), friction: 0.5),\n"
            );
        }
        parse(&format!(
            "Level(title: \"grains\", effects: [{effects}],\n world: (dt: 0.016666666666666666, substeps: 4, duration: 1.0),\n bodies: [\n{bodies} ],\n)\n"
        ))
        .level
    };
    let work = |level: &rigidlab::level::Level| as_checked(level).work;
    for (cols, rows) in [(1, 1), (10, 1), (50, 20)] {
        let n = (cols * rows) as f64;
        let w = work(&grains(cols, rows, "gravity, contacts, friction"));
        assert_eq!(w.resting_pairs, heap(n), "{n} grains");
        assert_eq!(w.pairs, heap(n), "none at the start");
        // Loose balls that can spin roll as they settle, but no question reads when a contact
        // starts, ends or slips: their steps are priced one call (sim/contact_points.rs,
        // `spin_calls`, splits a lenient step only where a turn's residual passes the sag).
        assert_eq!(w.calls_per_step, 1);
    }
    assert_eq!(heap(10_000.0), 30_000.0 - 283.0);
    // Without gravity the grains stay where they are, apart.
    assert_eq!(work(&grains(50, 20, "contacts, friction")).pairs, 0.0);
    // A pair past the 800 whose rapier data fit a core's 2 MB L2 costs 2.5x one within
    // (measured 2026-12-07: `budget::PAIR_FAR_COST`), in every term a pair is priced in.
    let w = work(&grains(50, 20, "gravity, contacts, friction"));
    let at = |pairs: f64| Work { pairs, ..w }.step_us();
    let (near, far) = (at(400.0) - at(300.0), at(5000.0) - at(4900.0));
    assert!((far / near - 2.5).abs() < 1e-9, "{far} / {near}");
    // So twice the grains cost more than twice as much a step: 2000 grains make 5873 pairs,
    // priced 800 + 2.5 x 5073 = 13,482, against 1000 grains' 2911, priced 6078: 2.2x.
    let step = |cols| {
        let w = work(&grains(cols, 20, "gravity, contacts, friction"));
        w.step_us()
    };
    let ratio = step(100) / step(50);
    assert!((2.1..2.3).contains(&ratio), "{ratio}");
    // A stack rests from the start: its bodies are in pairs, none loose.
    for stacked in ["levels/stress/pyramid_20.ron", "levels/stress/arch.ron"] {
        let w = work(&load(stacked).level);
        assert_eq!(w.resting_pairs, 0.0, "{stacked}");
    }
}

/// A body on a `Polyline` pays, at every call, the impact planner's query and cast against the
/// polyline's points (sim/impacts.rs walks them; an `Arc` is met by its circle instead). Measured
/// 2026-12-07 (`cargo bench --no-default-features --bench budget`, CPU time of the run's
/// thread, over the calls its report counts, less what the other terms price): a ball round a
/// loop of 6150 points (tests/newuser/curved/n12_01a, n12_01b) 195 and 187 us a call, 0.032 and
/// 0.030 us a point; a puck down a ramp of 4002 (n9_05) 209 us, 0.052; two pucks on cycloids of
/// 4001 each (n9_07) 131 us a puck, 0.033: 0.035 us a point and a call. They were priced 0.02x
/// to 0.05x their cost before (the facets built once only).
#[test]
fn a_polylines_points_are_priced_at_every_call() {
    let loop_ = load("tests/newuser/curved/n12_01a_loop_least_release_height.ron").level;
    let w = as_checked(&loop_).work;
    assert_eq!((w.polyline_facets, w.facets), (6150.0, 6150.0));
    let without = Work {
        polyline_facets: 0.0,
        ..w
    };
    let per_call = (w.step_us() - without.step_us()) / w.calls();
    assert!(
        (per_call - 6150.0 * budget::POLYLINE_FACET_CALL_US).abs() < 1e-9,
        "{per_call}"
    );
    // Halving dt doubles the calls, and their price with them.
    let (e1, e2) = (
        at_dt(&loop_, loop_.world.dt),
        at_dt(&loop_, loop_.world.dt / 2.0),
    );
    let polyline_s =
        |e: &Estimate| e.work.steps * e.work.calls() * e.work.polyline_facets * 0.035e-6;
    assert!((polyline_s(&e2) / polyline_s(&e1) - 2.0).abs() < 1e-3);
    // Two pucks, each on its own cycloid: each pair pays its polyline's points.
    let two = load("tests/newuser/curved/n9_07_two_pucks_on_cycloid_tracks.ron").level;
    let w2 = as_checked(&two).work;
    assert_eq!((w2.polyline_facets, w2.facets), (8002.0, 8002.0));
}

/// A question that linearizes its mechanism (`PendulumPeriod`, `ModePeriod`, `SpringPeriod`,
/// `EquilibriumAngle`: `analysis::small_oscillations`) pays it once: measured 2026-12-07 as the
/// CPU time of one-step runs (`BUDGET_DURATION=1e-9 cargo bench --no-default-features --bench
/// budget`) less a step, 0.4 to 1.6 ms a question on a spring's blocks, 4.6 to 5.7 ms with one
/// joint, 10.6 ms with two, 27 ms with four: priced 0.7 ms + 5.5 ms a joint (and its
/// mechanism's SVDs, below).
#[test]
fn a_linearizing_question_is_priced_once_by_its_joints() {
    let cart = load("levels/kinetics/linearized_pendulum_on_cart.ron").level;
    let e = as_checked(&cart);
    assert_eq!((e.work.linearizations, e.work.joints), (1, 2));
    let without = Estimate::price(
        Work {
            linearizations: 0,
            ..e.work
        },
        Mode::Check,
    );
    let once = e.seconds - without.seconds;
    // The cart and its pendulum: 6 coordinates less a slider's and a pin's 2 rows each, 2 degrees
    // of freedom: 0.2 us x 2^2 x 6^3 = 0.17 ms of SVDs.
    assert_eq!(e.work.mechanism, (6, 2));
    let svd = 0.2e-6 * 4.0 * 216.0;
    assert!(
        (once - (0.7e-3 + 2.0 * 5.5e-3 + svd)).abs() < 1e-12,
        "{once}"
    );
    // Not a step's cost: twice the steps add only the steps' price.
    let twice = Estimate::of(
        &cart,
        &Options::default(),
        Mode::Check,
        Some(2.0 * e.work.steps),
    );
    let steps_s = e.work.steps * e.work.step_us() * 1e-6;
    assert!((twice.seconds - e.seconds - steps_s).abs() < 1e-12);
}

/// A chain of `n` bars of 0.5 m hanging from a pin, turned 0.01 rad as one, with one period
/// question: the mechanism `analysis::small_oscillations` linearizes has n degrees of freedom.
fn chain(n: usize) -> String {
    let (l, a) = (0.5f64, 0.01f64);
    let mut bodies = String::from("(name: \"ground\", kind: fixed),\n");
    let mut joints = String::new();
    for i in 0..n {
        let d = (i as f64 + 0.5) * l;
        bodies += &format!(
            "(name: \"bar{}\", shape: Box(width: 0.04, height: {l}), mass: 1.0, angle: {a}, position: ({:?}, {:?})),\n",
            i + 1,
            d * a.sin(),
            -d * a.cos()
        );
        let (b1, a1) = if i == 0 {
            ("ground".to_string(), 0.0)
        } else {
            (format!("bar{i}"), -0.5 * l)
        };
        joints += &format!(
            "(name: \"pin{}\", kind: revolute, body1: \"{b1}\", body2: \"bar{}\", anchor1: (0.0, {a1}), anchor2: (0.0, {})),\n",
            i + 1,
            i + 1,
            0.5 * l
        );
    }
    format!(
        "Level(title: \"a chain of {n} bars\", effects: [gravity, joints],\n world: (dt: 0.002, substeps: 4, duration: 1.0),\n bodies: [\n{bodies}],\n joints: [\n{joints}],\n questions: [(id: \"T\", ask: \"Period\", unit: \"s\", expected: 1.0, tolerance: 1.0, quantity: PendulumPeriod(body: \"bar1\", joint: \"pin1\"), at: End)],\n)\n"
    )
}

/// A linearization's Hessian takes 2 d^2 values of the potential along the constraints, each a
/// projection by SVDs of the n-column Jacobian: d^2 n^3 (d degrees of freedom, n = 3 a body).
/// Measured 2026-12-07 on `chain(n)` (one-step runs, `BUDGET_DURATION=1e-9 cargo bench
/// --no-default-features --bench budget -- DIR`, load average 5 to 11): 2, 5, 10, 20 and 30 bars
/// 11.1 ms, 61.5 ms, 0.535 s, 23.5 s and 137 s, priced 0.012, 0.028, 0.056, 0.111 and 0.166 s
/// by 0.7 ms + 5.5 ms a joint alone (30 bars 0.001x); with 0.2 us d^2 n^3 0.012, 0.045, 0.60,
/// 17.4 and 131 s (1.07x, 0.73x, 1.11x, 0.74x, 0.96x).
#[test]
fn a_linearization_is_priced_by_its_mechanisms_size() {
    for (bars, at_least_s) in [(2, 0.0115), (10, 0.59), (30, 131.0)] {
        let scene = parse(&chain(bars));
        let w = as_checked(&scene.level).work;
        assert_eq!(w.mechanism, (3 * bars, bars), "{bars} bars");
        let (n, d) = (3.0 * bars as f64, bars as f64);
        let us = 700.0 + 5500.0 * d + 0.2 * d * d * n.powi(3);
        assert!((w.linearize_us() - us).abs() < 1e-6 * us, "{bars} bars");
        assert!(w.linearize_us() * 1e-6 > at_least_s, "{bars} bars");
    }
    // 45 bars: 997 s of linearization, refused, and the refusal names it.
    let scene = parse(&chain(45));
    let e = as_checked(&scene.level);
    let err = e
        .within_budget(std::path::Path::new("chain_45.ron"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains(
            "1 question linearizing a mechanism of 45 degrees of freedom and 135 coordinates"
        ),
        "{err}"
    );
    // A welded pair of free bodies: two bodies' 6 coordinates less the weld's 3 rows, 3 degrees
    // of freedom (the pair moves as one free body).
    let weld = parse(
        "Level(title: \"weld\", effects: [gravity, joints], world: (dt: 0.01, duration: 0.1),\n bodies: [(name: \"a\", shape: Circle(radius: 0.1), position: (0.0, 0.0)), (name: \"b\", shape: Circle(radius: 0.1), position: (0.3, 0.0))],\n joints: [(name: \"w\", kind: fixed, body1: \"a\", body2: \"b\", anchor1: (0.15, 0.0), anchor2: (-0.15, 0.0))],\n)\n",
    );
    assert_eq!(as_checked(&weld.level).work.mechanism, (6, 3));
}

/// A question the reference trajectory can serve, read at a time, integrates it from the start
/// (`analysis::reference`, Dop853 at rtol 1e-10): measured 2026-12-07 (the CPU time of
/// `Reference::integrate` to each such question's time in the 38 levels whose runs read it,
/// repeated to 20 ms, load average 5 to 7): 690 evaluations a second of span in segments of
/// 0.05 s, 1800 in the rolling contacts' 0.01 s (13.5 a segment's restart, 450 a second beyond),
/// 0.2 us an evaluation for one body, 0.26 to 0.30 for two, 0.5 to 0.6 with a pin or a rolling
/// contact, 0.7 to 1.0 with 4 rows: 0.1 + 0.1 a body + 0.15 a row us. The runs it made cheap
/// before: `n5_12` 5.0 of its 7.0 ms (priced 0.21x), `n4_02` 2.8 of 3.7 (0.32x),
/// `cycloid_rim_point` 1.1 of 1.7 (0.38x), `ha_relative_motion_cars_fragment` 1.4 of 2.2 (0.35x).
#[test]
fn the_reference_trajectory_is_priced_by_its_span_and_size() {
    use rigidlab::analysis::reference::Reference;
    let wheel = load("levels/kinematics/cycloid_rim_point.ron").level;
    let w = as_checked(&wheel).work;
    let model = Reference::of_level(&wheel).unwrap();
    assert_eq!(model.stretch(), 0.01, "the wheel rolls");
    let moving = (0..wheel.bodies.len()).filter(|&i| model.moves(i)).count();
    let eval_us = 0.1 + 0.1 * moving as f64 + 0.15 * model.row_count() as f64;
    // Its three questions read at 0.25, 0.5 and 0.25 s (PointX and PointY at 0.25, PointX at 0.5).
    let span: f64 = wheel
        .questions
        .iter()
        .map(|q| match q.at {
            rigidlab::level::When::Time(t) => t,
            _ => panic!("read at a time"),
        })
        .sum();
    let us = span * (450.0 + 13.5 / 0.01) * eval_us;
    assert!(
        (w.reference_us - us).abs() < 1e-9 * us,
        "{} vs {us}",
        w.reference_us
    );
    // Free flight: segments of 0.05 s.
    let ff = load("levels/kinematics/free_fall.ron").level;
    assert_eq!(Reference::of_level(&ff).unwrap().stretch(), 0.05);
    assert!(as_checked(&ff).work.reference_us > 0.0);
    // An impulse event is outside the reference: not priced.
    let struck = load("tests/newuser/impacts/n4_06_plate_percussion.ron").level;
    assert!(Reference::of_level(&struck).is_err());
    assert_eq!(as_checked(&struck).work.reference_us, 0.0);
    // Once a run, not a step: twice the steps add only the steps' price.
    let e = as_checked(&wheel);
    let twice = Estimate::of(
        &wheel,
        &Options::default(),
        Mode::Check,
        Some(2.0 * e.work.steps),
    );
    let steps_s = e.work.steps * e.work.step_us() * 1e-6;
    assert!((twice.seconds - e.seconds - steps_s).abs() < 1e-9);
}

/// A coupling solved after every call costs by its terms: measured 2026-12-06 and 2026-12-07 (the
/// run's CPU time past the other terms, over its calls and couplings): a cable over a massive
/// pulley or a drum (a term in an angle) 6.7 to 7.7 us a call, a cable between blocks' x and y
/// 1.9 to 3.0 (ha_blocks_A_B_pulley_C, ha_hoist_power_efficiency, ha_collars_pulley_dependent_motion,
/// ha_three_block_dependent_motion, priced 1.7x to 2.4x at 7).
#[test]
fn a_coupling_is_priced_by_whether_it_turns_a_body() {
    let cord = as_checked(&load("levels/kinetics/ha_blocks_A_B_pulley_C.ron").level).work;
    assert_eq!((cord.couplings, cord.turning_couplings), (1, 0));
    let pulley = as_checked(&load("levels/kinetics/classic_atwood_massive_pulley.ron").level).work;
    assert_eq!((pulley.couplings, pulley.turning_couplings), (2, 2));
    let per_call = |w: Work| {
        let none = Work {
            couplings: 0,
            turning_couplings: 0,
            ..w
        };
        (w.step_us() - none.step_us()) / w.calls()
    };
    assert!((per_call(cord) - 2.5).abs() < 1e-9);
    assert!((per_call(pulley) - 2.0 * 7.0).abs() < 1e-9);
}

/// A ball that can spin, in contact at the start of a level whose questions read a contact's
/// start, end or slip, may have its steps split (the strict rule, sim/contact_points.rs): priced
/// at `substeps` calls for half of them (`budget::SPIN_SPLIT_SHARE`; measured 2026-12-07 on the
/// library's such levels: 3% to 99% of their steps split, 40% to 50% in the middle). Steps split
/// for any other reason (planned, a smooth ball on an arc) are priced split whole.
#[test]
fn a_spinning_balls_steps_are_priced_split_at_their_share() {
    let wheel = load("tests/newuser/impacts/wheel_curb_gap_1mm.ron").level;
    let w = as_checked(&wheel).work;
    assert_eq!((w.calls_per_step, w.split_share), (4, 0.5));
    assert!((w.calls() - 2.5).abs() < 1e-12);
    let puck = load("tests/newuser/curved/n13_05_ball_in_vertical_ring.ron").level;
    let p = as_checked(&puck).work;
    assert_eq!((p.calls_per_step, p.split_share), (4, 1.0));
}

/// rapier 0.36's staged solver sends a joint color (joints that share no body) of at least 64
/// joints to its SIMD lanes and a smaller one to a serial tail, and a 2D scene's joints take 2
/// (a chain) to 4 (a net) colors: from 256 joints a joint's rows are priced 0.35x. Measured
/// 2026-12-07 (`cargo bench --no-default-features --bench budget -- FILE...`, the nets of
/// levels/stress/generate.py's `joint_grid` at n = 6, 10, 15, 22, 30, 600 steps of 16 substeps):
/// 55 and 174 joints priced 0.94x and 0.89x, 414, 918 and 1734 joints 2.21x, 2.32x and 2.30x
/// before this (the joints' rows 90% of those estimates); the chains of 40 to 81 joints 0.87x to
/// 0.94x.
#[test]
fn many_joints_are_priced_in_the_solvers_lanes() {
    let grid = load("levels/stress/joint_grid_30.ron").level;
    let w = as_checked(&grid).work;
    assert_eq!(w.joints, 1734);
    assert!((w.priced_joints() - 1734.0 * budget::JOINT_LANE_COST).abs() < 1e-9);
    let bridge = load("levels/stress/bridge_80.ron").level;
    let b = as_checked(&bridge).work;
    assert_eq!(b.priced_joints(), 81.0);
    // A joint more never lowers the price, across the step into the lanes too.
    let price = |joints: usize| budget::Work { joints, ..w }.priced_joints();
    for n in 1..2000 {
        assert!(
            price(n) >= price(n - 1),
            "{n} joints priced {} < {}",
            price(n),
            price(n - 1)
        );
    }
}

/// A `virtual_work` check finds the mechanism's virtual velocities at every step: priced 1.0 us
/// a joint and a step beyond a check's 0.3 (fitted 2026-12-07 on the bench's runs of
/// zh_slider_crank_static_servo, 0.96 us, and tests/newuser/statics/i14_02, 1.6 us).
#[test]
fn a_virtual_work_check_is_priced_by_the_joints() {
    let crank = load("levels/virtual-work/zh_slider_crank_static_servo.ron").level;
    let w = as_checked(&crank).work;
    let checks = crank
        .checks
        .iter()
        .filter(|c| c.kind == rigidlab::level::CheckKind::VirtualWork)
        .count();
    assert_eq!(w.virtual_work_joints, checks * crank.joints.len());
    assert!(checks > 0 && crank.joints.len() > 4);
    let none = Work {
        virtual_work_joints: 0,
        ..w
    };
    let per = (w.step_us() - none.step_us()) / w.virtual_work_joints as f64;
    assert!(
        (per - budget::VIRTUAL_WORK_JOINT_STEP_US).abs() < 1e-9,
        "{per}"
    );
}
