//! What a study records: one row of accuracy.csv per setting, and each level's study.

use super::*;

/// One row of accuracy.csv (read back by `study merge`).
#[derive(Debug, Clone, Default, Serialize, serde::Deserialize)]
pub struct Row {
    pub level: String,
    /// The engine that ran the row: `rapier` or `box2d` (`--engine`).
    pub engine: String,
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
pub const CSV_COLUMNS: [&str; 29] = [
    "level",
    "engine",
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
    /// The engine of every row of this study (a level swept on two engines has two studies).
    pub engine: PhysicsEngine,
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

impl LevelStudy {
    /// The level's name as the summary's tables show it: with the engine beside it when not
    /// rapier ("kinetics/simple_pendulum \[box2d\]").
    pub fn label(&self) -> String {
        if self.engine.is_rapier() {
            self.name.clone()
        } else {
            format!("{} [{}]", self.name, self.engine.name())
        }
    }
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
