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
//! - B (the goal of issue 45, <= 5%): the same with 250 per-body checks as well, `newton_euler`
//!   and `kinetic_energy_ic` on all 100 bodies and `angular_momentum_fixed_point` on the 50 bars.
//!   Beside B's ratio, its probes' own cost: (B - A) / 250 in ns a probe a step (B's time
//!   beyond A's, whose shared pass and scene checks B runs too), a figure that does not move
//!   when the physics step gets cheaper or dearer. `RIGIDLAB_BENCH_ONLY=A` (or B, C) runs one
//!   configuration once and nothing else, to count its instructions under callgrind.
//! - C (the goal of issue 15, <= 5%): every per-body check kind on every body it applies to, on
//!   its own (no scene checks): `mass_properties`, `constant_acceleration`, `kinetic_energy_g`,
//!   `kinetic_energy_ic`, `angular_momentum_fixed_point`, `newton_euler` (about G and about a
//!   point), `work_energy`, `impulse_momentum` and `restitution` on all 100 bodies, and
//!   `center_of_percussion` on the 50 pinned bars (1,050 probes). The scene adds the `restitution`
//!   effect (every body keeps e = 0) for the `restitution` checks.
//! - C check by check (issue 15's done-when: each check on every body <= 5% of the physics
//!   step): each check's probes alone (a kind with two forms, `newton_euler` about G and about a
//!   point, form by form: each form is one check on every body), against the physics step its
//!   level runs and, beside it, the bare scene's (C's level with no checks) run in the same
//!   round. A check that reads joint impulses makes its level read them summed over the
//!   substeps (so a blow through a pin is not lost): one rapier call a step, split into one call
//!   per substep only where a blow can fall (sim/joint_sums.rs). The bench prices that step on
//!   its own line against the bare step, with its target (issue 45: at most 1.5x), and judges
//!   the analysis against the step the level runs.

use rigidlab::analysis::frame::FrameAnalysis;
use rigidlab::checks::CheckSet;
use rigidlab::level::{parse, CheckDef, CheckKind, Scene};
use rigidlab::sim::{Options, Simulation, Substepping};
use std::path::Path;
use std::time::Instant;

#[path = "common/hundred_bodies.rs"]
mod hundred_bodies;
use hundred_bodies::{every_kind_ron, scene_ron, BALLS, BARS};

const STEPS: usize = 300;
const REPEATS: usize = 7;
/// Steps per timing block.
const BLOCK: usize = 10;

/// One block of `BLOCK` steps: physics and checks time per step, us; the scene at its end.
struct Block {
    step_us: f64,
    checks_us: f64,
    contacts: usize,
    rows: usize,
}

/// Runs `scene` for `STEPS` steps, timing each step (`Instant` around `sim.step()` and around
/// `CheckSet::observe`, as `rigidlab check` calls them), summed over blocks of `BLOCK` steps.
fn time_blocks(scene: &Scene) -> Vec<Block> {
    let mut sim = Simulation::new(scene, &Options::default());
    let mut checks = CheckSet::new(&scene.level);
    checks.observe(sim.snapshot());
    let (mut t_step, mut t_checks, mut rows) = (0.0, 0.0, 0);
    let mut blocks = Vec::new();
    for k in 0..STEPS {
        let t0 = Instant::now();
        let s = sim.step().expect("the bench scene runs");
        t_step += t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        checks.observe(s);
        t_checks += t0.elapsed().as_secs_f64();
        rows += s.bodies.len();
        if (k + 1) % BLOCK == 0 {
            let per_step = 1e6 / BLOCK as f64;
            blocks.push(Block {
                step_us: t_step * per_step,
                checks_us: t_checks * per_step,
                contacts: s.contacts.len(),
                rows,
            });
            (t_step, t_checks, rows) = (0.0, 0.0, 0);
        }
    }
    assert_eq!(checks.finish().len(), scene.level.checks.len());
    blocks
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The bench's script: each measurement in turn, then the report, so the ratios of one run
/// stand together.
fn main() {
    let scene = parse(Path::new("bench.ron"), &scene_ron()).unwrap_or_else(|e| panic!("{e}"));
    let every = parse(Path::new("bench-every-kind.ron"), &every_kind_ron())
        .unwrap_or_else(|e| panic!("{e}"));
    // A's level: the same scene with its scene-wide checks only.
    let mut scene_only = scene.clone();
    scene_only.level.checks.retain(|c| c.body.is_none());
    print_scene(&scene, &scene_only, &every);
    // RIGIDLAB_BENCH_ONLY=A (or B, C): that configuration's run once, and nothing else (to count
    // its instructions: `valgrind --tool=callgrind --toggle-collect='*CheckSet*observe*'`).
    if let Ok(only) = std::env::var("RIGIDLAB_BENCH_ONLY") {
        let c = ["A", "B", "C"].iter().position(|&c| c == only);
        let c = c.unwrap_or_else(|| panic!("RIGIDLAB_BENCH_ONLY={only}: A, B or C"));
        time_blocks([&scene_only, &scene, &every][c]);
        return;
    }
    // RIGIDLAB_BENCH_KIND=restitution: only that kind's runs below (to profile it).
    let profiling = std::env::var("RIGIDLAB_BENCH_KIND").is_ok();
    let mut configs = time_configs([&scene_only, &scene, &every], profiling);
    let forms = Forms::of(&every);
    let (mut by_form, mut bare_us) = forms.time();
    let (mut frame_us, frame_rows) = time_frame_pass(&scene, profiling);
    if profiling {
        print_profile(&forms, &mut by_form);
        return;
    }
    assert!(configs.rows + frame_rows > 0);
    let per_body = scene.level.checks.len() - scene_only.level.checks.len();
    print_configs(&mut configs, &mut frame_us, per_body);
    print_forms(&forms, &mut by_form, &mut bare_us);
}

/// What the scene holds and what A, B and C run.
fn print_scene(scene: &Scene, scene_only: &Scene, every: &Scene) {
    let level = &scene.level;
    let dynamic = level
        .bodies
        .iter()
        .filter(|b| b.kind == rigidlab::level::BodyKind::Dynamic)
        .count();
    let per_body = level.checks.len() - scene_only.level.checks.len();
    println!(
        "scene: {dynamic} dynamic bodies ({BARS} pinned bars, {BALLS} balls in a box); A: {} scene checks; B: {per_body} per-body probes as well; C: {} per-body probes of every kind; {STEPS} steps x {REPEATS} repeats",
        scene_only.level.checks.len(),
        every.level.checks.len(),
    );
}

/// A, B and C's blocks: per configuration the ratios and the check times, and the physics
/// times of all.
#[derive(Default)]
struct Configs {
    ratios: [Vec<f64>; 3],
    check_us: [Vec<f64>; 3],
    step_us: Vec<f64>,
    /// Contact manifolds at the end of the last run.
    contacts: usize,
    rows: usize,
}

fn time_configs(configs: [&Scene; 3], profiling: bool) -> Configs {
    let mut out = Configs::default();
    // Runs take turns (A, B, C, A, ...), so each run has the cache and the analysis work of
    // that configuration alone, and all see the same machine noise.
    for k in 0..if profiling { 0 } else { 3 * REPEATS } {
        let c = k % 3;
        for block in time_blocks(configs[c]) {
            out.step_us.push(block.step_us);
            out.ratios[c].push(block.checks_us / block.step_us);
            out.check_us[c].push(block.checks_us);
            (out.contacts, out.rows) = (block.contacts, out.rows + block.rows);
        }
    }
    out
}

/// Issue 15's goal, check by check: each check on every body it applies to, alone, <= 5% of
/// the physics step. A kind with two forms (newton_euler about G and about a point) is timed
/// form by form: each form is one check on every body.
struct Forms {
    every: Scene,
    /// The kinds with two forms.
    split_kinds: Vec<CheckKind>,
    /// Each form (its kind, and whether about a point where the kind has two) and its label.
    forms: Vec<((CheckKind, bool), String)>,
}

impl Forms {
    fn of(every: &Scene) -> Forms {
        // Two forms of a kind are two checks where a body has both (newton_euler about G and
        // about a point); a kind whose balls take one form and whose bars the other is one check.
        let two_forms_of = |k| {
            let checks = &every.level.checks;
            checks.iter().any(|a| {
                checks.iter().any(|b| {
                    a.kind == k
                        && b.kind == k
                        && a.body == b.body
                        && a.point.is_some() != b.point.is_some()
                })
            })
        };
        let mut split_kinds: Vec<_> = every.level.checks.iter().map(|c| c.kind).collect();
        split_kinds.sort_by_key(|k| k.name());
        split_kinds.dedup();
        split_kinds.retain(|&k| two_forms_of(k));
        let mut out = Forms {
            every: every.clone(),
            split_kinds,
            forms: Vec::new(),
        };
        let mut forms: Vec<_> = every.level.checks.iter().map(|c| out.form_of(c)).collect();
        forms.sort_by_key(|(k, p)| (k.name(), *p));
        forms.dedup();
        let labels: Vec<String> = forms
            .iter()
            .map(|&(k, p)| match (out.split_kinds.contains(&k), p) {
                (true, true) => format!("{} about a point", k.name()),
                (true, false) => format!("{} about G", k.name()),
                _ => k.name().to_string(),
            })
            .collect();
        out.forms = forms.into_iter().zip(labels).collect();
        if let Ok(only) = std::env::var("RIGIDLAB_BENCH_KIND") {
            out.forms.retain(|((k, _), _)| k.name() == only);
        }
        out
    }

    fn form_of(&self, c: &CheckDef) -> (CheckKind, bool) {
        (
            c.kind,
            self.split_kinds.contains(&c.kind) && c.point.is_some(),
        )
    }

    /// C's level with the checks of one form only.
    fn of_form(&self, form: (CheckKind, bool)) -> Scene {
        let mut only = self.every.clone();
        only.level.checks.retain(|c| self.form_of(c) == form);
        only
    }

    /// A round runs the bare scene (C's level with no checks) and then each form once, so
    /// block k of a form's run is compared with block k of the same round's bare run (the same
    /// steps of the same scene, seconds apart). Two denominators: the physics step the check's
    /// level runs, and the bare scene's. They differ where the check reads joint impulses: its
    /// level then advances rapier one substep per call (`Substepping::Split`) so that a blow
    /// through a pin is not lost, several times the bare step. That is a simulation setting the
    /// reading needs, priced on its own line in the report; the analysis's cost is judged
    /// against the step the level runs.
    ///
    /// Per form: checks / its own step, checks / the bare step, checks us per step, and its own
    /// step, us; and the bare scene's steps, us.
    fn time(&self) -> (Vec<[Vec<f64>; 4]>, Vec<f64>) {
        let mut bare = self.every.clone();
        bare.level.checks.clear();
        let mut by_form: Vec<[Vec<f64>; 4]> = vec![Default::default(); self.forms.len()];
        let mut bare_us = Vec::new();
        for _ in 0..REPEATS {
            let bare_blocks = time_blocks(&bare);
            bare_us.extend(bare_blocks.iter().map(|b| b.step_us));
            for ((form, _), r) in self.forms.iter().zip(by_form.iter_mut()) {
                for (block, b) in time_blocks(&self.of_form(*form)).iter().zip(&bare_blocks) {
                    r[0].push(block.checks_us / block.step_us);
                    r[1].push(block.checks_us / b.step_us);
                    r[2].push(block.checks_us);
                    r[3].push(block.step_us);
                }
            }
        }
        (by_form, bare_us)
    }
}

/// The shared frame pass alone, on the same steps (information: how much of A it is): its time
/// per step, us, per block, and the body rows it read.
fn time_frame_pass(scene: &Scene, profiling: bool) -> (Vec<f64>, usize) {
    let mut frame_us = Vec::new();
    let mut rows = 0;
    for _ in 0..if profiling { 0 } else { REPEATS } {
        let mut sim = Simulation::new(scene, &Options::default());
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
    (frame_us, rows)
}

/// With RIGIDLAB_BENCH_KIND: the profiled kind's forms only.
fn print_profile(forms: &Forms, by_form: &mut [[Vec<f64>; 4]]) {
    for ((_, label), r) in forms.forms.iter().zip(by_form.iter_mut()) {
        println!(
            "   {:<42} {:>7.2} us {:>7.2}% of its own step {:>7.2}% of the bare step",
            label,
            median(&mut r[2]),
            100.0 * median(&mut r[0]),
            100.0 * median(&mut r[1])
        );
    }
}

/// A, B and C against the physics step, with their goals; and B's probes' own cost, ns a probe
/// a step, which does not move when the step gets cheaper or dearer.
fn print_configs(configs: &mut Configs, frame_us: &mut [f64], per_body: usize) {
    let Configs {
        ratios,
        check_us,
        step_us,
        contacts,
        ..
    } = configs;
    let blocks: usize = ratios.iter().map(Vec::len).sum();
    println!("contact manifolds at the end: {contacts}; {blocks} blocks of {BLOCK} steps");
    println!(
        "per step (block medians): physics {:.1} us; A: all-body analysis + scene checks {:.1} us (the shared frame pass alone: {:.1} us); B: every check of the level {:.1} us; C: every per-body kind {:.1} us",
        median(step_us),
        median(&mut check_us[0]),
        median(frame_us),
        median(&mut check_us[1]),
        median(&mut check_us[2]),
    );
    let quartiles = |v: &[f64]| (100.0 * v[v.len() / 4], 100.0 * v[3 * v.len() / 4]);
    for (c, label, goal) in [
        (0, "A  analysis + scene checks / step time:", true),
        (1, "B  with the per-body probes as well:    ", true),
        (2, "C  every per-body kind on every body:   ", true),
    ] {
        let r = median(&mut ratios[c]);
        let q = quartiles(&ratios[c]);
        let verdict = if !goal {
            String::new()
        } else if r <= 0.05 {
            "; goal <= 5%: met".into()
        } else {
            "; goal <= 5%: NOT met".into()
        };
        println!(
            "{label} {:.2}% (median of blocks; quartiles {:.2}%..{:.2}%){verdict}",
            100.0 * r,
            q.0,
            q.1
        );
        if c == 1 {
            // B's time beyond A's (the same shared pass and scene checks), per probe.
            let (a, b) = (median(&mut check_us[0]), median(&mut check_us[1]));
            println!(
                "   B per probe: {:.1} ns a probe a step beyond A ({per_body} probes; B {:.1} ns a probe a step with the shared pass and scene checks counted in)",
                1e3 * (b - a) / per_body as f64,
                1e3 * b / per_body as f64,
            );
        }
    }
}

/// C check by check, each against the step its level runs and the bare scene's, with the goal.
fn print_forms(forms: &Forms, by_form: &mut [[Vec<f64>; 4]], bare_us: &mut [f64]) {
    let bare_step = median(bare_us);
    println!(
        "C check by check, the goal (each check on every body, alone; medians of blocks; the bare scene's physics step {bare_step:.1} us):"
    );
    println!(
        "   {:<42} {:>6} {:>10} {:>16} {:>14}  physics",
        "check", "probes", "checks us", "of its own step", "of bare step"
    );
    let mut missed = Vec::new();
    let mut split_steps = Vec::new();
    for (((kind, point), label), r) in forms.forms.iter().zip(by_form.iter_mut()) {
        let n = forms
            .every
            .level
            .checks
            .iter()
            .filter(|c| forms.form_of(c) == (*kind, *point))
            .count();
        let (own, of_bare, us) = (median(&mut r[0]), median(&mut r[1]), median(&mut r[2]));
        if own > 0.05 {
            missed.push(label.clone());
        }
        let settings =
            Simulation::new(&forms.of_form((*kind, *point)), &Options::default()).settings;
        let split = settings.substepping == Substepping::Split || settings.split_at_blows;
        if split {
            split_steps.extend(r[3].iter().copied());
        }
        println!(
            "   {label:<42} {n:>6} {us:>10.2} {:>15.2}% {:>13.2}%  {}",
            100.0 * own,
            100.0 * of_bare,
            if split {
                "reads joint impulses"
            } else {
                "rapier's substeps"
            }
        );
    }
    if missed.is_empty() {
        println!("   goal, every check <= 5% of the physics step its level runs: met");
    } else {
        println!(
            "   goal, every check <= 5% of the physics step its level runs: NOT met by {}",
            missed.join(", ")
        );
    }
    if !split_steps.is_empty() {
        let ratio = median(&mut split_steps) / bare_step;
        println!(
            "   reading joint impulses (one rapier call a step, split where a blow can fall): the step costs {ratio:.2}x the bare step ({:.1} us), paid only by levels whose checks or questions read them; target <= 1.5x: {}",
            median(&mut split_steps),
            if ratio <= 1.5 { "met" } else { "NOT met" }
        );
    }
}
