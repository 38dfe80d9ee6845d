//! `rigidlab study accuracy`: what accuracy costs in time.
//!
//! Method of Erez, Tassa & Todorov (ICRA 2015), adapted to one engine:
//! - **error** against an exact solution where the level has one (its questions' textbook answers,
//!   the constant_acceleration closed form), otherwise against the engine's own f64 run at a very
//!   small step, on short pieces restarted from that reference so that chaos does not dominate
//!   ([`measure::self_consistency`]); plus energy and momentum drift where the level conserves them
//!   and the joints' anchor separation;
//! - **cost** as wall time of stepping per simulated second, timed one run at a time after all
//!   error runs are done (median of repeats);
//! - one knob varied at a time from the level's settings: dt, substeps, PGS iterations,
//!   precision (f32 / f64), effects (declared / all).
//!
//! Output: `accuracy.csv`, one Pareto plot per level, `summary.md`.

pub mod measure;
pub mod metrics;
mod plot;
mod summary;

use crate::level::{self, CheckKind, Effect, Scene};
use indicatif::{ProgressBar, ProgressStyle};
use measure::{Precision, Setting};
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Level files or folders (searched recursively for *.ron).
    #[arg(default_value = "levels")]
    pub levels: Vec<PathBuf>,
    /// Folder for accuracy.csv, the plots and summary.md.
    #[arg(long)]
    pub out: PathBuf,
    /// A short sweep for CI (about a minute): fewer points, a coarser reference, fewer repeats.
    #[arg(long)]
    pub quick: bool,
    /// Plot format.
    #[arg(long, value_parser = ["png", "svg"], default_value = "png")]
    pub format: String,
}

/// The sweep: knob values, reference, pieces, timing, budgets.
#[derive(Debug, Clone)]
pub struct Plan {
    pub dts: Vec<f64>,
    pub substeps: Vec<usize>,
    pub iterations: Vec<usize>,
    /// The f64 reference: dt, substeps, PGS iterations.
    pub reference: (f64, usize, usize),
    /// Self-consistency pieces per run and their length, s.
    pub pieces: usize,
    pub piece_s: f64,
    /// Conservation runs last at least this long, s (light levels).
    pub conservation_s: f64,
    /// Timing rounds: every setting of every level is timed once per round (round-robin, so that
    /// a disturbance on this shared machine spreads over all settings); the cost is the median.
    pub rounds: usize,
    /// Each timing sample repeats the run until this much stepping has been timed and keeps the
    /// fastest run ([`measure::cost_sample`]).
    pub sample_time: Duration,
    /// Wall-time budget of a level's f64 reference, s: the reference (and the self-consistency
    /// pieces) cover a window of the level's duration short enough to fit it (at least one piece);
    /// levels without an exact answer are run and timed over that window too.
    pub reference_budget_s: f64,
    /// Runs predicted to take longer than this are not run (reported as such), s.
    pub run_cap_s: f64,
    pub quick: bool,
}

impl Plan {
    pub fn full() -> Self {
        Plan {
            dts: [30.0, 60.0, 120.0, 240.0, 480.0, 960.0]
                .iter()
                .map(|hz| 1.0 / hz)
                .collect(),
            substeps: vec![1, 2, 4, 8, 16],
            iterations: vec![1, 2, 4],
            reference: (1.0 / 3840.0, 16, 4),
            pieces: 10,
            piece_s: 0.1,
            conservation_s: 10.0,
            rounds: 7,
            sample_time: Duration::from_millis(25),
            reference_budget_s: 20.0,
            run_cap_s: 20.0,
            quick: false,
        }
    }

    pub fn quick() -> Self {
        Plan {
            dts: [30.0, 120.0, 480.0].iter().map(|hz| 1.0 / hz).collect(),
            substeps: vec![1, 4, 16],
            iterations: vec![1, 4],
            reference: (1.0 / 1920.0, 8, 4),
            pieces: 3,
            piece_s: 0.1,
            conservation_s: 1.0,
            rounds: 2,
            sample_time: Duration::from_millis(3),
            reference_budget_s: 0.15,
            run_cap_s: 0.25,
            quick: true,
        }
    }
}

/// The curve a point belongs to (one knob varied from the level's settings).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Knob {
    Dt,
    /// dt swept with the f64 engine (the precision knob).
    DtF64,
    Substeps,
    Iterations,
    Effects,
}

impl Knob {
    pub const ALL: [Knob; 5] = [
        Knob::Dt,
        Knob::DtF64,
        Knob::Substeps,
        Knob::Iterations,
        Knob::Effects,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Knob::Dt => "dt",
            Knob::DtF64 => "dt_f64",
            Knob::Substeps => "substeps",
            Knob::Iterations => "pgs_iterations",
            Knob::Effects => "effects",
        }
    }
    pub fn label(self) -> &'static str {
        match self {
            Knob::Dt => "dt (f32)",
            Knob::DtF64 => "dt (f64)",
            Knob::Substeps => "substeps",
            Knob::Iterations => "PGS iterations",
            Knob::Effects => "declared -> all effects",
        }
    }
}

/// One setting of a level's sweep and the curves it lies on.
#[derive(Debug, Clone)]
pub struct Point {
    pub setting: Setting,
    pub knobs: Vec<Knob>,
    /// The level's own settings (on every f32 curve).
    pub baseline: bool,
    pub rapier_default: bool,
}

/// The dt values swept for a level: the plan's (1/30 to 1/960 s), plus dt/2 and dt/4 of the
/// level's when fewer than two of the plan's are finer (levels that already use a tiny step),
/// minus those longer than half the level's duration (fewer than two steps).
pub fn sweep_dts(level: &level::Level, plan: &Plan) -> Vec<f64> {
    let dt = level.world.dt;
    let mut dts = plan.dts.clone();
    if dts.iter().filter(|d| **d < dt * (1.0 - 1e-9)).count() < 2 {
        dts.extend([dt / 2.0, dt / 4.0]);
    }
    dts.retain(|d| *d <= 0.5 * level.world.duration);
    dts.sort_by(|a, b| b.total_cmp(a));
    dts.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * a.abs().max(b.abs()));
    dts
}

/// The settings to run for a level: each knob's values with the others at the level's settings.
pub fn points(level: &level::Level, plan: &Plan) -> Vec<Point> {
    let base = Setting::of_level(level);
    let mut out: Vec<Point> = vec![Point {
        setting: base,
        knobs: vec![Knob::Dt, Knob::Substeps, Knob::Iterations, Knob::Effects],
        baseline: true,
        rapier_default: false,
    }];
    let mut add = |s: Setting, k: Option<Knob>, default: bool| {
        if let Some(p) = out.iter_mut().find(|p| p.setting.same(&s)) {
            if let Some(k) = k {
                if !p.knobs.contains(&k) {
                    p.knobs.push(k);
                }
            }
            p.rapier_default |= default;
        } else {
            out.push(Point {
                setting: s,
                knobs: k.into_iter().collect(),
                baseline: false,
                rapier_default: default,
            });
        }
    };
    let mut dts = sweep_dts(level, plan);
    if !dts.iter().any(|d| (d - base.dt).abs() <= 1e-9 * d) {
        dts.push(base.dt);
        dts.sort_by(|a, b| b.total_cmp(a));
    }
    for &dt in &dts {
        add(Setting { dt, ..base }, Some(Knob::Dt), false);
        add(
            Setting {
                dt,
                precision: Precision::F64,
                ..base
            },
            Some(Knob::DtF64),
            false,
        );
    }
    for &n in &plan.substeps {
        add(
            Setting {
                substeps: n,
                ..base
            },
            Some(Knob::Substeps),
            false,
        );
    }
    for &n in &plan.iterations {
        add(
            Setting {
                iterations: n,
                ..base
            },
            Some(Knob::Iterations),
            false,
        );
    }
    add(
        Setting {
            all_effects: true,
            ..base
        },
        Some(Knob::Effects),
        false,
    );
    if Setting::rapier_default().dt <= 0.5 * level.world.duration {
        add(Setting::rapier_default(), None, true);
    }
    out
}

/// What kind of scene a level is, for grouping the verdicts.
pub fn class(level: &level::Level) -> &'static str {
    let c = level.effects.contains(&Effect::Contacts);
    let j = level.effects.contains(&Effect::Joints);
    match (c, j) {
        (true, true) => "contact+joint",
        (true, false) => "contact",
        (false, true) => "joint",
        (false, false) => "contact-free",
    }
}

/// Whether the level has an exact answer to measure against (questions, closed-form checks).
pub fn has_exact(level: &level::Level) -> bool {
    !level.questions.is_empty()
        || level
            .checks
            .iter()
            .any(|c| c.kind == CheckKind::ConstantAcceleration)
}

/// One row of accuracy.csv.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub level: String,
    pub class: String,
    /// The curve(s) the setting lies on: `baseline` (the level's settings, on every curve),
    /// `dt`, `dt_f64`, `substeps`, `pgs_iterations`, `effects`, `rapier_default`.
    pub knob: String,
    pub dt: f64,
    pub dt_label: String,
    pub substeps: usize,
    pub pgs_iterations: usize,
    pub precision: String,
    pub effects: String,
    /// `ok`, why a run stopped (an explosion), or why it was not run (over the time cap).
    pub status: String,
    /// Simulated span of the level's runs and timings, s: its duration, or for big levels without
    /// an exact answer the window that fits the reference budget.
    pub window_s: f64,
    /// The plotted error: `exact_rel` (worst relative error against the textbook answers and the
    /// closed form) or, without an exact solution, `self_consistency_m`.
    pub error: Option<f64>,
    pub error_kind: String,
    pub meets_tolerance: Option<bool>,
    pub tolerance_ratio: Option<f64>,
    pub question_error: Option<f64>,
    pub closed_form_error: Option<f64>,
    /// Self-consistency against the f64 reference, mean over restarted pieces, m.
    pub position_error_m: Option<f64>,
    /// Signed drift of mechanical energy over the peak kinetic energy, per second (conservative scenes).
    pub energy_drift_per_s: Option<f64>,
    pub energy_drift_per_period: Option<f64>,
    /// Energy gained beyond the precision's round-off floor ([`gain_floor`]): unphysical.
    pub energy_gain: Option<bool>,
    pub momentum_drift_per_s: Option<f64>,
    pub angular_momentum_drift_per_s: Option<f64>,
    /// Largest joint anchor separation over the run, m.
    pub joint_drift_m: Option<f64>,
    /// Median over the timing rounds, µs of wall time per simulated second.
    pub cost_us_per_sim_s: Option<f64>,
    /// Fastest round, µs per simulated second.
    pub cost_min_us_per_sim_s: Option<f64>,
    /// (max - min) / median over the rounds.
    pub cost_spread: Option<f64>,
    pub cost_rounds: Option<usize>,
}

/// The CSV header (the fields of [`Row`], in order).
pub const CSV_COLUMNS: [&str; 28] = [
    "level",
    "class",
    "knob",
    "dt",
    "dt_label",
    "substeps",
    "pgs_iterations",
    "precision",
    "effects",
    "status",
    "window_s",
    "error",
    "error_kind",
    "meets_tolerance",
    "tolerance_ratio",
    "question_error",
    "closed_form_error",
    "position_error_m",
    "energy_drift_per_s",
    "energy_drift_per_period",
    "energy_gain",
    "momentum_drift_per_s",
    "angular_momentum_drift_per_s",
    "joint_drift_m",
    "cost_us_per_sim_s",
    "cost_min_us_per_sim_s",
    "cost_spread",
    "cost_rounds",
];

/// A relative energy drift above this, per second, is more than round-off: a gain is flagged as
/// unphysical. f32 keeps 7 digits and rounds once per substep (about 10^3 per second): measured
/// round-off drifts of a free fall reach 4e-5/s in f32 against 1e-6/s of true O(h) drift in f64.
pub fn gain_floor(p: Precision) -> f64 {
    match p {
        Precision::F32 => 1e-4,
        Precision::F64 => 1e-9,
    }
}

/// One level's study.
#[derive(Debug, Clone)]
pub struct LevelStudy {
    pub name: String,
    pub title: String,
    pub class: &'static str,
    /// The scene as studied (its duration cut to the window).
    pub scene: Scene,
    pub points: Vec<Point>,
    pub rows: Vec<Row>,
    pub has_exact: bool,
    pub conserved: metrics::Conserved,
    /// Why the level was skipped or what is missing.
    pub notes: Vec<String>,
    pub reference: Setting,
    pub window_s: f64,
    /// Per point: the full run ran to the end (so its cost can be timed).
    pub timeable: Vec<bool>,
    /// The machine's 1-minute load average before and after the timing phase.
    pub load: Option<(f64, f64)>,
}

/// "kinetics/simple_pendulum" from ".../kinetics/simple_pendulum.ron".
pub fn level_name(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    match path.parent().and_then(|p| p.file_name()) {
        Some(d) => format!("{}/{stem}", d.to_string_lossy()),
        None => stem,
    }
}

/// Why a level has nothing to measure, if so.
pub fn nothing_to_measure(level: &level::Level) -> Option<String> {
    if !level
        .bodies
        .iter()
        .any(|b| b.kind == level::BodyKind::Dynamic)
    {
        return Some("no dynamic body: nothing moves".into());
    }
    if level.world.duration.is_nan() || level.world.duration <= 0.0 {
        return Some("zero duration".into());
    }
    None
}

/// The error part of a level's study (runs in parallel with other levels).
pub fn measure_errors(scene: &Scene, plan: &Plan, tick: &(dyn Fn() + Sync)) -> LevelStudy {
    let level = &scene.level;
    let name = level_name(&scene.file);
    let pts = points(level, plan);
    let exact = has_exact(level);
    let conserved = metrics::conserved(level);
    let base = Setting::of_level(level);
    // The reference steps at least 4 times finer than the finest swept dt.
    let finest = sweep_dts(level, plan)
        .into_iter()
        .fold(level.world.dt, f64::min);
    let ref_setting = Setting {
        dt: plan.reference.0.min(finest / 4.0),
        substeps: plan.reference.1,
        iterations: plan.reference.2.max(level.world.solver_iterations),
        precision: Precision::F64,
        all_effects: false,
    };
    let mut notes = Vec::new();
    let duration = level.world.duration;

    // Budget: time a short run at the level's settings, then size the window so that the f64
    // reference fits its budget. Levels with an exact answer always run their whole duration
    // (questions may be asked at its end).
    let probe = duration.min(0.25);
    let unit = measure::unit_cost(scene, &base, probe).unwrap_or(1e-6);
    let ref_per_s = measure::predicted(&ref_setting, 1.0, unit);
    let piece_s = plan.piece_s.min(duration / 4.0);
    let window = (plan.reference_budget_s / ref_per_s)
        .max(piece_s)
        .min(duration);
    if window < duration {
        notes.push(format!(
            "self-consistency{} over the first {window:.3} s of {duration} s (the f64 reference costs about {ref_per_s:.1} s of wall time per simulated second)",
            if exact { "" } else { ", joint drift and cost" }
        ));
    }
    let windowed = measure::with_duration(scene, window);
    // Questions may be asked at the end: levels with an exact answer run their whole duration.
    let studied = if exact {
        scene.clone()
    } else {
        windowed.clone()
    };
    let run_span = if exact { duration } else { window };
    let reference = measure::reference(&windowed, &ref_setting);
    if let Some(e) = &reference.stopped {
        notes.push(format!(
            "the f64 reference ({}) stopped: {e}; self-consistency uses the {:.3} s before",
            ref_setting.label(),
            reference.duration()
        ));
    }
    // Light levels run their conservation variant for longer (several periods).
    let span = if window < duration {
        window
    } else {
        duration.max(plan.conservation_s)
    };
    let mut rows = Vec::new();
    let mut timeable = Vec::new();
    for p in &pts {
        let s = &p.setting;
        let mut status = Vec::new();
        let over = |what: &str, t: f64, status: &mut Vec<String>| {
            let over = t > plan.run_cap_s;
            if over {
                status.push(format!(
                    "{what} not run: predicted {t:.1} s > {:.1} s cap",
                    plan.run_cap_s
                ));
            }
            over
        };
        let full = if over("run", measure::predicted(s, run_span, unit), &mut status) {
            measure::FullRun::default()
        } else {
            measure::full_run(&studied, s)
        };
        let pos = if over(
            "pieces",
            plan.pieces as f64 * measure::predicted(s, piece_s, unit),
            &mut status,
        ) {
            Err(String::new())
        } else {
            measure::self_consistency(&windowed, s, &reference, plan.pieces, piece_s)
        };
        let cons = if conserved.any()
            && !over(
                "conservation run",
                measure::predicted(s, span, unit),
                &mut status,
            ) {
            Some(measure::conservation(scene, s, conserved, span))
        } else {
            None
        };
        if let Some(e) = &full.stopped {
            status.push(format!("run stopped: {e}"));
        }
        timeable.push(full.ran && full.stopped.is_none());
        if let Err(e) = &pos {
            if !e.is_empty() {
                status.push(format!("piece stopped: {e}"));
            }
        }
        if let Some(e) = cons.as_ref().and_then(|c| c.stopped.clone()) {
            status.push(format!("{span} s run stopped: {e}"));
        }
        let position_error_m = pos.ok();
        let error = if exact {
            match (full.question_error, full.closed_form_error) {
                (Some(a), Some(b)) => Some(a.max(b)),
                (a, b) => a.or(b),
            }
        } else {
            position_error_m
        };
        let cons = cons.unwrap_or_default();
        let knob = if p.baseline {
            "baseline".to_string()
        } else {
            let mut k: Vec<&str> = p.knobs.iter().map(|k| k.name()).collect();
            if p.rapier_default {
                k.push("rapier_default");
            }
            k.join("+")
        };
        rows.push(Row {
            level: name.clone(),
            class: class(level).into(),
            knob,
            dt: s.dt,
            dt_label: s.dt_label(),
            substeps: s.substeps,
            pgs_iterations: s.iterations,
            precision: s.precision.name().into(),
            effects: s.effects_name().into(),
            status: if status.is_empty() {
                "ok".into()
            } else {
                status.join("; ")
            },
            window_s: run_span,
            error,
            error_kind: if exact {
                "exact_rel".into()
            } else {
                "self_consistency_m".into()
            },
            meets_tolerance: full.meets_tolerance,
            tolerance_ratio: full.tolerance_ratio,
            question_error: full.question_error,
            closed_form_error: full.closed_form_error,
            position_error_m,
            energy_drift_per_s: cons.energy_drift_per_s,
            energy_drift_per_period: cons.energy_drift_per_period,
            energy_gain: cons.energy_drift_per_s.map(|d| d > gain_floor(s.precision)),
            momentum_drift_per_s: cons.momentum_drift_per_s,
            angular_momentum_drift_per_s: cons.angular_momentum_drift_per_s,
            joint_drift_m: full.joint_drift_m,
            cost_us_per_sim_s: None,
            cost_min_us_per_sim_s: None,
            cost_spread: None,
            cost_rounds: None,
        });
        tick();
    }
    if !exact {
        notes.push(
            "no textbook answer or closed-form check: the error is self-consistency against the f64 reference".into(),
        );
    }
    LevelStudy {
        name,
        title: level.title.clone(),
        class: class(level),
        scene: studied,
        points: pts,
        rows,
        has_exact: exact,
        conserved,
        notes,
        reference: ref_setting,
        window_s: run_span,
        timeable,
        load: None,
    }
}

/// The cost part, one run at a time: `plan.rounds` rounds, each timing every setting of every
/// level once (round-robin), then the median per setting. Settings whose error run was not run
/// (over the cap) or stopped are not timed.
pub fn measure_costs(studies: &mut [LevelStudy], plan: &Plan, tick: &dyn Fn()) {
    let mut samples: Vec<Vec<Vec<f64>>> = studies
        .iter()
        .map(|st| vec![Vec::new(); st.points.len()])
        .collect();
    let mut dead: Vec<Vec<bool>> = studies
        .iter()
        .map(|st| st.timeable.iter().map(|t| !t).collect())
        .collect();
    for _ in 0..plan.rounds {
        for (si, st) in studies.iter().enumerate() {
            for (pi, p) in st.points.iter().enumerate() {
                if !dead[si][pi] {
                    match measure::cost_sample(&st.scene, &p.setting, plan.sample_time) {
                        Some(x) => samples[si][pi].push(x),
                        None => dead[si][pi] = true,
                    }
                }
                tick();
            }
        }
    }
    for (si, st) in studies.iter_mut().enumerate() {
        for (pi, row) in st.rows.iter_mut().enumerate() {
            let mut v = std::mem::take(&mut samples[si][pi]);
            if v.is_empty() || dead[si][pi] {
                continue;
            }
            v.sort_by(f64::total_cmp);
            let median = v[v.len() / 2];
            row.cost_us_per_sim_s = Some(median);
            row.cost_min_us_per_sim_s = Some(v[0]);
            row.cost_spread = Some((v[v.len() - 1] - v[0]) / median);
            row.cost_rounds = Some(v.len());
        }
    }
}

/// Runs the whole study; returns the studies and the files skipped (with why).
pub fn run_study(
    files: &[PathBuf],
    plan: &Plan,
    progress: &ProgressBar,
) -> (Vec<LevelStudy>, Vec<(String, String)>) {
    let mut skipped = Vec::new();
    let mut scenes = Vec::new();
    for f in files {
        match level::load(f) {
            Ok(s) => match nothing_to_measure(&s.level) {
                Some(why) => skipped.push((level_name(f), why)),
                None => scenes.push(s),
            },
            Err(e) => {
                progress.suspend(|| stderr!("{e}"));
                skipped.push((level_name(f), format!("does not load: {}", e.message)));
            }
        }
    }
    let jobs: u64 = scenes
        .iter()
        .map(|s| (1 + plan.rounds as u64) * points(&s.level, plan).len() as u64)
        .sum();
    progress.set_length(jobs);
    progress.set_message("errors (parallel across levels)");
    let tick = || progress.inc(1);
    let mut studies: Vec<LevelStudy> = scenes
        .par_iter()
        .map(|s| measure_errors(s, plan, &tick))
        .collect();
    // Timings only now, one run at a time, so that nothing of ours disturbs them.
    progress.set_message("timing (one run at a time)");
    let before = load_average();
    measure_costs(&mut studies, plan, &tick);
    let after = load_average();
    progress.finish_with_message("done");
    if let (Some(b), Some(a)) = (before, after) {
        for st in studies.iter_mut() {
            st.load = Some((b, a));
        }
    }
    (studies, skipped)
}

/// The machine's 1-minute load average (Linux), to judge how disturbed the timings were.
fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

fn plot_file(name: &str, format: &str) -> String {
    format!("{}.{format}", name.replace(['/', '\\'], "_"))
}

pub fn main(args: Args) -> ExitCode {
    // Before the sweep, which takes minutes: an --out that cannot take the files.
    if let Err(e) = writable_folder(&args.out) {
        stderr!("{e}");
        return ExitCode::from(2);
    }
    let paths = if args.levels.is_empty() {
        vec![PathBuf::from("levels")]
    } else {
        args.levels.clone()
    };
    let files = match level::collect_files(&paths) {
        Ok(f) => f,
        Err(e) => {
            stderr!("{e}");
            return ExitCode::from(2);
        }
    };
    if files.is_empty() {
        stderr!("no level files (*.ron) found in the given paths");
        return ExitCode::from(2);
    }
    let plan = if args.quick {
        Plan::quick()
    } else {
        Plan::full()
    };
    let progress = ProgressBar::new(0);
    progress.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} runs  {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let (studies, skipped) = run_study(&files, &plan, &progress);

    let csv_path = args.out.join("accuracy.csv");
    if let Err(e) = write_csv(&csv_path, &studies) {
        stderr!("cannot write {}: {e}", csv_path.display());
        return ExitCode::from(2);
    }
    let mut plots = Vec::new();
    for st in &studies {
        let file = plot_file(&st.name, &args.format);
        match summary::plot_level(st, &args.out.join(&file)) {
            Ok(()) => plots.push((st.name.clone(), file)),
            Err(e) => stderr!("{}: cannot draw the plot: {e}", st.name),
        }
    }
    let md = summary::markdown(&studies, &skipped, &plan, &plots);
    let md_path = args.out.join("summary.md");
    if let Err(e) = std::fs::write(&md_path, md) {
        stderr!("cannot write {}: {e}", md_path.display());
        return ExitCode::from(2);
    }
    stderr!(
        "wrote {}, {} and {} plot(s) in {}",
        csv_path.display(),
        md_path.display(),
        plots.len(),
        args.out.display()
    );
    for (name, why) in &skipped {
        stderr!("skipped {name}: {why}");
    }
    if skipped
        .iter()
        .any(|(_, why)| why.starts_with("does not load"))
    {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    }
}

/// Creates `dir` if missing and checks that a file can be written in it.
pub fn writable_folder(dir: &Path) -> Result<(), String> {
    let d = dir.display();
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "error: --out {d} is a file, not a folder\n  help: give a folder for accuracy.csv, the plots and summary.md (created if missing)"
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| {
        format!("error: cannot create the folder {d}: {e}\n  help: give a folder you can write to")
    })?;
    let probe = dir.join(".rigidlab-write-test");
    std::fs::write(&probe, b"")
        .and_then(|()| std::fs::remove_file(&probe))
        .map_err(|e| {
            format!("error: cannot write in {d}: {e}\n  help: give a folder you can write to")
        })
}

fn write_csv(path: &Path, studies: &[LevelStudy]) -> Result<(), String> {
    let mut w = csv::Writer::from_path(path).map_err(|e| e.to_string())?;
    for st in studies {
        for r in &st.rows {
            w.serialize(r).map_err(|e| e.to_string())?;
        }
    }
    // A study with no level still gets its header.
    if studies.iter().all(|s| s.rows.is_empty()) {
        drop(w);
        std::fs::write(path, format!("{}\n", CSV_COLUMNS.join(","))).map_err(|e| e.to_string())?;
        return Ok(());
    }
    w.flush().map_err(|e| e.to_string())
}
