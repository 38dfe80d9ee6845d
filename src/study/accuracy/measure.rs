//! Running one level at one solver setting: errors (full runs, conservation runs,
//! self-consistency pieces against a reference) and cost (timed stepping).

use super::metrics;
use crate::analysis::energy;
use crate::checks::CheckResult;
use crate::clock::Instant;
use crate::level::{CheckKind, EventDef, Level, PhysicsEngine, Profile, Scene};
use crate::questions::QuestionResult;
use crate::runner::Observers;
use crate::sim::{Engine, Options};
use crate::snapshot::{BodyState, Snapshot};
use std::time::Duration;

/// The engine precision the sweep varies: the simulation stage's own.
pub use crate::sim::Precision;

/// One point of the sweep: the solver knobs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting {
    /// Physics step, s.
    pub dt: f64,
    /// rapier's num_solver_iterations.
    pub substeps: usize,
    /// rapier's num_internal_pgs_iterations.
    pub iterations: usize,
    pub precision: Precision,
    /// Every effect stage on (`Options::all_effects`) instead of only the declared ones.
    pub all_effects: bool,
    /// The engine that runs it: rapier (f32 or f64), or Box2D v3 (f32 only; `engines.rs`).
    pub engine: PhysicsEngine,
}

impl Setting {
    /// The level's own settings (f32, declared effects).
    pub fn of_level(level: &Level) -> Self {
        Setting {
            dt: level.world.dt,
            substeps: level.world.substeps,
            iterations: level.world.solver_iterations,
            precision: Precision::F32,
            all_effects: false,
            engine: PhysicsEngine::Rapier,
        }
    }

    /// rapier's defaults: dt 1/60 s, 4 substeps, 1 PGS iteration (f32, declared effects).
    pub fn rapier_default() -> Self {
        Setting {
            dt: 1.0 / 60.0,
            substeps: 4,
            iterations: 1,
            precision: Precision::F32,
            all_effects: false,
            engine: PhysicsEngine::Rapier,
        }
    }

    /// The same knobs on `engine`.
    pub fn on(self, engine: PhysicsEngine) -> Self {
        Setting { engine, ..self }
    }

    pub fn options(&self) -> Options {
        Options {
            dt: Some(self.dt),
            substeps: Some(self.substeps),
            solver_iterations: Some(self.iterations),
            all_effects: self.all_effects,
            substepping: None,
            // The study builds each precision's engine itself (`with_engine!`).
            precision: None,
            impact_cuts: None,
            // rapier's runs build their precision's engine themselves; other engines are
            // built through the runner's entry (`runner::engine_for`, `engines.rs`).
            engine: Some(self.engine),
            spin_split: crate::sim::SpinSplit::Rule,
        }
    }

    /// Same knobs (dt compared to a part in 1e9).
    pub fn same(&self, o: &Setting) -> bool {
        (self.dt - o.dt).abs() <= 1e-9 * self.dt.max(o.dt)
            && self.substeps == o.substeps
            && self.iterations == o.iterations
            && self.precision == o.precision
            && self.all_effects == o.all_effects
            && self.engine == o.engine
    }

    /// "1/60" when 1/dt is a whole number, else the step in seconds.
    pub fn dt_label(&self) -> String {
        dt_label(self.dt)
    }

    pub fn effects_name(&self) -> &'static str {
        if self.all_effects {
            "all"
        } else {
            "declared"
        }
    }

    /// "dt 1/60 s, 4 substeps, 1 iteration, f32" (", box2d" on Box2D)
    pub fn label(&self) -> String {
        format!(
            "dt {} s, {} substep{}, {} iteration{}, {}{}{}",
            self.dt_label(),
            self.substeps,
            if self.substeps == 1 { "" } else { "s" },
            self.iterations,
            if self.iterations == 1 { "" } else { "s" },
            self.precision.name(),
            if self.all_effects {
                ", all effects"
            } else {
                ""
            },
            if self.engine.is_rapier() {
                String::new()
            } else {
                format!(", {}", self.engine.name())
            }
        )
    }
}

pub fn dt_label(dt: f64) -> String {
    let hz = 1.0 / dt;
    if (hz - hz.round()).abs() < 1e-6 * hz {
        format!("1/{}", hz.round() as u64)
    } else {
        format!("{dt}")
    }
}

/// What the study needs from each precision's `Simulation`, beyond [`Engine`].
pub trait StudyEngine: Engine + Sized {
    fn build(scene: &Scene, opts: &Options) -> Self;
    /// Overwrites every non-fixed body's pose and velocity (restarting a piece from a reference state).
    fn restart(&mut self, bodies: &[BodyState]);
}

macro_rules! study_engine {
    ($sim:ty) => {
        impl StudyEngine for $sim {
            fn build(scene: &Scene, opts: &Options) -> Self {
                <$sim>::new(scene, opts)
            }
            fn restart(&mut self, bodies: &[BodyState]) {
                self.restart_from(bodies);
            }
        }
    };
}

study_engine!(crate::sim::Simulation);
study_engine!(crate::sim64::Simulation);

/// Calls `f` with the engine of the setting's precision.
macro_rules! with_engine {
    ($precision:expr, $f:ident ( $($arg:expr),* )) => {
        match $precision {
            Precision::F32 => $f::<crate::sim::Simulation>($($arg),*),
            Precision::F64 => $f::<crate::sim64::Simulation>($($arg),*),
        }
    };
}

/// A copy of the scene whose clock starts at `t0` of the original: events before it (already
/// applied by a reference that stepped with `h_ref`) are dropped, later ones and load tables shifted.
pub fn shifted(scene: &Scene, t0: f64, h_ref: f64) -> Scene {
    let mut level = scene.level.clone();
    level.checks.clear();
    level.questions.clear();
    // The reference applied an event at the start of the step nearest to it.
    // Events without a time (welds on contact) stay: the fresh simulation re-detects them.
    level.events.retain(|e| match e {
        EventDef::Impulse { at, .. } => *at >= t0 - 0.5 * h_ref,
        _ => true,
    });
    for e in &mut level.events {
        if let EventDef::Impulse { at, .. } = e {
            *at = (*at - t0).max(0.0);
        }
    }
    for l in &mut level.loads {
        if let Some(Profile::Table(rows)) = &mut l.force {
            for r in rows.iter_mut() {
                r.0 -= t0;
            }
        }
        if let Some(Profile::Table(rows)) = &mut l.torque {
            for r in rows.iter_mut() {
                r.0 -= t0;
            }
        }
    }
    Scene {
        file: scene.file.clone(),
        level,
    }
}

/// A scene whose duration is `duration` (conservation runs go on longer than the exercise).
pub fn with_duration(scene: &Scene, duration: f64) -> Scene {
    let mut s = scene.clone();
    s.level.world.duration = duration;
    s
}

/// The results of running the level's whole duration at one setting.
#[derive(Debug, Clone, Default)]
pub struct FullRun {
    /// The run was made (false: skipped over the time cap).
    pub ran: bool,
    /// Why the run stopped early (an explosion), if it did.
    pub stopped: Option<String>,
    /// Largest relative error of the level's questions against their textbook answers.
    pub question_error: Option<f64>,
    /// Largest relative error of the level's closed-form (constant_acceleration) checks.
    pub closed_form_error: Option<f64>,
    /// Largest error / tolerance over the level's graded checks and questions.
    pub tolerance_ratio: Option<f64>,
    /// Every graded check and question within its tolerance (None: the level grades nothing).
    pub meets_tolerance: Option<bool>,
    /// Largest separation of joint anchors over the run, m.
    pub joint_drift_m: Option<f64>,
}

fn graded(c: &CheckResult) -> bool {
    // Kinds not implemented yet observe nothing (samples 0) and are not a tolerance.
    c.samples > 0
}

/// The accuracy study's error of one run, from its check and question results: the one
/// definition, which the window's solver panel shows too.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunGrade {
    /// The worst relative error of the questions against their answers.
    pub question_error: Option<f64>,
    /// The worst relative error of the closed-form (constant-acceleration) checks.
    pub closed_form_error: Option<f64>,
    /// The worst error-to-tolerance ratio of all graded checks and questions.
    pub tolerance_ratio: Option<f64>,
}

impl RunGrade {
    pub fn of(checks: &[CheckResult], answers: &[QuestionResult]) -> RunGrade {
        let checks: Vec<&CheckResult> = checks.iter().filter(|c| graded(c)).collect();
        let max = |it: &mut dyn Iterator<Item = f64>| {
            it.fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))))
        };
        let closed_form = crate::checks::kind_name(CheckKind::ConstantAcceleration);
        let ratio = |e: f64, tol: f64| {
            if tol > 0.0 {
                e / tol
            } else if e == 0.0 {
                0.0
            } else {
                f64::INFINITY
            }
        };
        RunGrade {
            question_error: max(&mut answers.iter().map(|q| q.rel_error)),
            closed_form_error: max(&mut checks
                .iter()
                .filter(|c| c.kind == closed_form)
                .map(|c| c.max_rel_error)),
            tolerance_ratio: max(&mut checks
                .iter()
                .map(|c| ratio(c.max_rel_error, c.tolerance))
                .chain(answers.iter().map(|q| ratio(q.rel_error, q.tolerance)))),
        }
    }

    /// The study's error: the worst of the question and closed-form errors.
    pub fn error(&self) -> Option<f64> {
        match (self.question_error, self.closed_form_error) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        }
    }
}

/// Runs the level's duration at `setting`, with its checks and questions.
pub fn full_run(scene: &Scene, setting: &Setting) -> FullRun {
    if !setting.engine.is_rapier() {
        return super::engines::full_run(scene, setting);
    }
    with_engine!(setting.precision, full_run_on(scene, setting))
}

fn full_run_on<E: StudyEngine>(scene: &Scene, setting: &Setting) -> FullRun {
    let mut sim = E::build(scene, &setting.options());
    let level = &scene.level;
    let mut observers = Observers::new(level);
    let mut joint_drift: Option<f64> = None;
    let mut observe = |s: &Snapshot| {
        observers.observe(s);
        if let Some(d) = metrics::max_joint_separation(s, level) {
            joint_drift = Some(joint_drift.map_or(d, |m: f64| m.max(d)));
        }
    };
    observe(sim.snapshot());
    let mut stopped = None;
    for _ in 0..sim.total_steps() {
        match sim.step() {
            Ok(s) => observe(s),
            Err(e) => {
                stopped = Some(e.to_string());
                break;
            }
        }
    }
    if stopped.is_some() {
        return FullRun {
            ran: true,
            stopped,
            ..FullRun::default()
        };
    }
    graded_run(observers, joint_drift)
}

/// A finished run's grade: its checks and questions against their tolerances, and the joints'
/// largest anchor separation (`joint_drift`), whichever engine ran it.
pub(super) fn graded_run(observers: Observers, joint_drift: Option<f64>) -> FullRun {
    let (checks, answers) = observers.finish(&Default::default());
    let checks: Vec<CheckResult> = checks.into_iter().filter(graded).collect();
    let grade = RunGrade::of(&checks, &answers);
    let meets_tolerance = (!checks.is_empty() || !answers.is_empty())
        .then(|| checks.iter().all(|c| c.passed) && answers.iter().all(|q| q.passed));
    FullRun {
        ran: true,
        stopped: None,
        question_error: grade.question_error,
        closed_form_error: grade.closed_form_error,
        tolerance_ratio: grade.tolerance_ratio,
        meets_tolerance,
        joint_drift_m: joint_drift,
    }
}

/// Drift rates from a conservation run (relative to the scale of the conserved quantity).
#[derive(Debug, Clone, Default)]
pub struct Conservation {
    pub stopped: Option<String>,
    /// Signed least-squares slope of E(t) divided by the peak kinetic energy, 1/s.
    pub energy_drift_per_s: Option<f64>,
    /// The same times the oscillation period, where the motion has one.
    pub energy_drift_per_period: Option<f64>,
    pub period_s: Option<f64>,
    /// Slope of |L(t) - L(0)| (conserved components) over the momentum scale sum m|v|, 1/s.
    pub momentum_drift_per_s: Option<f64>,
    /// Slope of H_O(t) over its scale, 1/s (signed).
    pub angular_momentum_drift_per_s: Option<f64>,
}

/// Runs `span` seconds and measures the drift of what the level conserves.
pub fn conservation(
    scene: &Scene,
    setting: &Setting,
    what: metrics::Conserved,
    span: f64,
) -> Conservation {
    let long = with_duration(scene, span);
    if !setting.engine.is_rapier() {
        return super::engines::conservation(&long, setting, what);
    }
    with_engine!(setting.precision, conservation_on(&long, setting, what))
}

fn conservation_on<E: StudyEngine>(
    scene: &Scene,
    setting: &Setting,
    what: metrics::Conserved,
) -> Conservation {
    let mut sim = E::build(scene, &setting.options());
    let n = sim.total_steps() as usize + 1;
    let mut log = ConservationLog::new(scene, n);
    log.observe(sim.snapshot());
    for _ in 1..n {
        match sim.step() {
            Ok(s) => log.observe(s),
            Err(err) => {
                return Conservation {
                    stopped: Some(err.to_string()),
                    ..Conservation::default()
                }
            }
        }
    }
    log.finish(what)
}

/// The conserved quantities of a conservation run, snapshot by snapshot, and their drift rates
/// at its end (whichever engine ran it).
pub(super) struct ConservationLog {
    m: Vec<metrics::MassProps>,
    t: Vec<f64>,
    e: Vec<f64>,
    ke: Vec<f64>,
    l: Vec<glam::DVec2>,
    h: Vec<f64>,
    l_scale: f64,
    h_scale: f64,
}

impl ConservationLog {
    pub(super) fn new(scene: &Scene, n: usize) -> Self {
        ConservationLog {
            m: metrics::mass_props(&scene.level),
            t: Vec::with_capacity(n),
            e: Vec::with_capacity(n),
            ke: Vec::with_capacity(n),
            l: Vec::with_capacity(n),
            h: Vec::with_capacity(n),
            l_scale: 0.0,
            h_scale: 0.0,
        }
    }

    pub(super) fn observe(&mut self, s: &Snapshot) {
        let m = &self.m;
        self.t.push(s.time);
        self.e.push(energy::system_mechanical_energy(
            s,
            metrics::textbook_mass(m),
        ));
        self.ke
            .push(energy::system_kinetic_energy(s, metrics::textbook_mass(m)));
        self.l.push(metrics::linear_momentum(s, m));
        self.h.push(metrics::angular_momentum(s, m));
        self.l_scale = self.l_scale.max(metrics::momentum_scale(s, m));
        self.h_scale = self.h_scale.max(metrics::angular_momentum_scale(s, m));
    }

    pub(super) fn finish(self, what: metrics::Conserved) -> Conservation {
        let (t, e, ke, l, h) = (&self.t, &self.e, &self.ke, &self.l, &self.h);
        let ke_peak = ke.iter().cloned().fold(0.0, f64::max);
        let mut out = Conservation::default();
        if what.energy && ke_peak > 0.0 {
            out.energy_drift_per_s = metrics::slope(t, e).map(|s| s / ke_peak);
            out.period_s = metrics::oscillation_period(t, ke);
            out.energy_drift_per_period =
                out.energy_drift_per_s.zip(out.period_s).map(|(d, p)| d * p);
        }
        if let (Some(axes), true) = (what.momentum, self.l_scale > 0.0) {
            let l0 = metrics::conserved_momentum(l[0], axes);
            let dev: Vec<f64> = l
                .iter()
                .map(|x| (metrics::conserved_momentum(*x, axes) - l0).length())
                .collect();
            out.momentum_drift_per_s = metrics::slope(t, &dev).map(|s| s / self.l_scale);
        }
        if what.angular_momentum && self.h_scale > 0.0 {
            out.angular_momentum_drift_per_s = metrics::slope(t, h).map(|s| s / self.h_scale);
        }
        out
    }
}

/// The engine's own f64 run at a very small step: the states every reference step.
#[derive(Debug, Clone)]
pub struct Reference {
    pub setting: Setting,
    /// `states[k]` = bodies at t = k dt.
    pub states: Vec<Vec<BodyState>>,
    pub stopped: Option<String>,
}

impl Reference {
    pub fn duration(&self) -> f64 {
        (self.states.len().saturating_sub(1)) as f64 * self.setting.dt
    }

    /// The bodies at time t, interpolated between reference steps (exact on the grid).
    pub fn at(&self, t: f64) -> Option<Vec<BodyState>> {
        let x = t / self.setting.dt;
        let k = x.floor();
        let s = x - k;
        let k = k as usize;
        if s < 1e-6 {
            return self.states.get(k).cloned();
        }
        if 1.0 - s < 1e-6 {
            return self.states.get(k + 1).cloned();
        }
        let (a, b) = (self.states.get(k)?, self.states.get(k + 1)?);
        Some(
            a.iter()
                .zip(b)
                .map(|(x, y)| metrics::lerp_body(x, y, s))
                .collect(),
        )
    }
}

/// Runs the f64 reference (its `precision` is ignored: always f64) over the level's duration;
/// on Box2D, which runs in f32 only, the engine's own f32 run at the reference's step and
/// substeps (`engines::reference`).
pub fn reference(scene: &Scene, setting: &Setting) -> Reference {
    if !setting.engine.is_rapier() {
        return super::engines::reference(scene, setting);
    }
    let setting = Setting {
        precision: Precision::F64,
        ..*setting
    };
    let mut sim = crate::sim64::Simulation::new(scene, &setting.options());
    let mut states = vec![sim.snapshot().bodies.clone()];
    let mut stopped = None;
    for _ in 0..sim.total_steps() {
        match sim.step() {
            Ok(s) => states.push(s.bodies.clone()),
            Err(e) => {
                stopped = Some(e.to_string());
                break;
            }
        }
    }
    Reference {
        setting,
        states,
        stopped,
    }
}

/// Where the pieces start: `count` times spread evenly over [0, duration - piece] on the reference grid.
pub fn piece_starts(duration: f64, piece: f64, count: usize, h_ref: f64) -> Vec<usize> {
    let last = ((duration - piece).max(0.0) / h_ref).floor() as usize;
    let mut out: Vec<usize> = (0..count.max(1))
        .map(|i| {
            if count <= 1 {
                0
            } else {
                ((i as f64 / (count - 1) as f64) * last as f64).round() as usize
            }
        })
        .collect();
    out.dedup();
    out
}

/// Self-consistency error (Erez, Tassa & Todorov 2015): the mean, over short pieces restarted from
/// the reference, of the bodies' deviation from the reference at the end of each piece, m.
///
/// Each piece builds a fresh simulation of the scene with its clock shifted to the piece's start,
/// overwrites every body's pose and velocity with the reference state there (through
/// `sim.world.bodies`), takes round(piece / dt) steps and compares with the reference at that time
/// ([`metrics::scene_deviation`]: mass-weighted RMS distance, so orientation counts too). Restarting
/// keeps chaos from amplifying differences over the run.
pub fn self_consistency(
    scene: &Scene,
    setting: &Setting,
    reference: &Reference,
    pieces: usize,
    piece: f64,
) -> Result<f64, String> {
    if !setting.engine.is_rapier() {
        return super::engines::self_consistency(scene, setting, reference, pieces, piece);
    }
    with_engine!(
        setting.precision,
        self_consistency_on(scene, setting, reference, pieces, piece)
    )
}

fn self_consistency_on<E: StudyEngine>(
    scene: &Scene,
    setting: &Setting,
    reference: &Reference,
    pieces: usize,
    piece: f64,
) -> Result<f64, String> {
    let h_ref = reference.setting.dt;
    mean_piece_deviation(
        scene,
        setting,
        reference,
        pieces,
        piece,
        |t0, steps, start| {
            let mut sim = E::build(&shifted(scene, t0, h_ref), &setting.options());
            sim.restart(start);
            for _ in 0..steps {
                sim.step().map_err(|e| e.to_string())?;
            }
            Ok(sim.snapshot().bodies.clone())
        },
    )
}

/// The mean over the pieces of [`metrics::scene_deviation`] between where `run_piece` ends and
/// the reference at that instant, m: the loop both engines' [`self_consistency`] share.
/// `run_piece(t0, steps, start)` runs `steps` steps of `setting.dt` from the reference's bodies
/// `start` at `t0` and returns the bodies at the end.
pub(super) fn mean_piece_deviation(
    scene: &Scene,
    setting: &Setting,
    reference: &Reference,
    pieces: usize,
    piece: f64,
    mut run_piece: impl FnMut(f64, usize, &[BodyState]) -> Result<Vec<BodyState>, String>,
) -> Result<f64, String> {
    let h_ref = reference.setting.dt;
    let span = reference.duration();
    let piece = piece.min(span);
    let steps = ((piece / setting.dt).round() as usize).max(1);
    let m = metrics::mass_props(&scene.level);
    let mut sum = 0.0;
    let mut n = 0;
    for k0 in piece_starts(span, steps as f64 * setting.dt, pieces, h_ref) {
        let t0 = k0 as f64 * h_ref;
        let t1 = t0 + steps as f64 * setting.dt;
        let Some(end) = reference.at(t1) else {
            continue;
        };
        let bodies = run_piece(t0, steps, &reference.states[k0])?;
        sum += metrics::scene_deviation(&bodies, &end, &m);
        n += 1;
    }
    if n == 0 {
        return Err("the reference is shorter than one step".into());
    }
    Ok(sum / n as f64)
}

/// One timing sample: wall time of stepping per simulated second, µs. The level's duration is run
/// again and again until `min_total` of stepping has been timed (at least once), and the fastest
/// run is kept: on a shared machine a run that was preempted is slower, never faster. The
/// simulation is built outside the timer. None if a run stops (an explosion).
pub fn cost_sample(scene: &Scene, setting: &Setting, min_total: Duration) -> Option<f64> {
    if !setting.engine.is_rapier() {
        return super::engines::cost_sample(scene, setting, min_total);
    }
    with_engine!(setting.precision, cost_sample_on(scene, setting, min_total))
}

fn cost_sample_on<E: StudyEngine>(
    scene: &Scene,
    setting: &Setting,
    min_total: Duration,
) -> Option<f64> {
    fastest_run(min_total, || {
        let mut sim = E::build(scene, &setting.options());
        let steps = sim.total_steps();
        let start = Instant::now();
        for _ in 0..steps {
            sim.step().ok()?;
        }
        Some((start.elapsed(), steps as f64 * sim.dt()))
    })
}

/// The fastest of `timed_run`'s runs, µs of wall time per simulated second, run until
/// `min_total` of wall time has been timed (at least once): the loop both engines'
/// [`cost_sample`] share. `timed_run` builds its engine outside its timer and returns the time
/// it stepped and the seconds it simulated, or None if the run stopped.
pub(super) fn fastest_run(
    min_total: Duration,
    mut timed_run: impl FnMut() -> Option<(Duration, f64)>,
) -> Option<f64> {
    let mut total = Duration::ZERO;
    let mut best = f64::INFINITY;
    while total < min_total || best.is_infinite() {
        let (wall, simulated) = timed_run()?;
        total += wall;
        best = best.min(wall.as_secs_f64() * 1e6 / simulated);
    }
    Some(best)
}

/// Wall time per substep at `setting`, s, from one run of `span` seconds (a budget probe, not a
/// reported cost). None if the run stops.
pub fn unit_cost(scene: &Scene, setting: &Setting, span: f64) -> Option<f64> {
    let short = with_duration(scene, span);
    let steps = (span / setting.dt).round().max(1.0);
    cost_sample(&short, setting, Duration::ZERO)
        .map(|us_per_s| us_per_s * 1e-6 * span / (steps * setting.substeps as f64))
}

/// Predicted wall time of a run of `span` seconds at `setting`, s, from a [`unit_cost`].
pub fn predicted(setting: &Setting, span: f64, unit: f64) -> f64 {
    (span / setting.dt).round().max(1.0) * setting.substeps as f64 * unit
}
