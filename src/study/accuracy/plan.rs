//! What a study sweeps: the command's arguments, the plan (dts, substeps, iterations,
//! precisions, effects), the knobs and the points of each level's sweep.

use super::*;

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
    /// Run only the K-th of N slices of the sweep (whole levels, every N-th of the sorted list)
    /// and write its rows, plots, summary and shard.json; join shards with `study merge`.
    #[arg(long, value_name = "K/N", conflicts_with = "jobs")]
    pub shard: Option<shard::Shard>,
    /// Run the sweep as N shards side by side on this machine (at most one per core), then
    /// merge them into --out; the shards' folders go to --out/shards.
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// The engines to sweep, comma-separated: rapier (the default), box2d, or rapier,box2d
    /// (each level on each engine that runs it; Box2D runs in f32 only, docs/engines.md).
    #[arg(long, value_delimiter = ',', value_parser = engines::parse_engine, default_value = "rapier")]
    pub engine: Vec<PhysicsEngine>,
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
    /// The engines swept, in the order given (rapier unless `--engine` says otherwise).
    pub engines: Vec<PhysicsEngine>,
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
            engines: vec![PhysicsEngine::Rapier],
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
            engines: vec![PhysicsEngine::Rapier],
        }
    }

    /// The plan sweeping `engines` (each once, in the order given; rapier if none).
    pub fn on_engines(mut self, engines: &[PhysicsEngine]) -> Self {
        let mut v: Vec<PhysicsEngine> = Vec::new();
        for e in engines {
            if !v.contains(e) {
                v.push(*e);
            }
        }
        if !v.is_empty() {
            self.engines = v;
        }
        self
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

/// The settings to run for a level on rapier: each knob's values with the others at the
/// level's settings.
pub fn points(level: &level::Level, plan: &Plan) -> Vec<Point> {
    points_on(level, plan, PhysicsEngine::Rapier)
}

/// The knobs an engine's sweep varies: Box2D has no f64 build and no PGS iterations
/// (`engines.rs`), so its sweep is dt, substeps and effects.
pub fn knobs_of(engine: PhysicsEngine) -> &'static [Knob] {
    if engine.is_rapier() {
        &Knob::ALL
    } else {
        &[Knob::Dt, Knob::Substeps, Knob::Effects]
    }
}

/// The curves the level's own settings lie on (every f32 curve of the engine's sweep).
pub fn baseline_knobs(engine: PhysicsEngine) -> Vec<Knob> {
    knobs_of(engine)
        .iter()
        .copied()
        .filter(|k| *k != Knob::DtF64)
        .collect()
}

/// The settings to run for a level on `engine`: each of the engine's knobs' values with the
/// others at the level's settings ([`knobs_of`]).
pub fn points_on(level: &level::Level, plan: &Plan, engine: PhysicsEngine) -> Vec<Point> {
    let base = Setting::of_level(level).on(engine);
    let knobs = knobs_of(engine);
    let mut out: Vec<Point> = vec![Point {
        setting: base,
        knobs: baseline_knobs(engine),
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
        if !knobs.contains(&Knob::DtF64) {
            continue;
        }
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
    let iterations: &[usize] = if knobs.contains(&Knob::Iterations) {
        &plan.iterations
    } else {
        &[]
    };
    for &n in iterations {
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
    // rapier's defaults, 1/60 s and 4 substeps, are Box2D v3's too (its samples' 60 Hz and 4
    // sub-steps): the same point on either engine.
    if Setting::rapier_default().dt <= 0.5 * level.world.duration {
        add(Setting::rapier_default().on(engine), None, true);
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
