//! The physics plugin: the core simulation ([`AnySimulation`], f32 or f64 as the level asks) stepped in `FixedUpdate` at the level's dt.
//!
//! One `FixedUpdate` = one `Simulation::step`, with `Time<Fixed>` set to the level's dt, so the
//! window computes exactly the numbers `rigidlab check` computes (tests/suite/app/plugins.rs asserts it bit for
//! bit). Time scale acts on `Time<Virtual>`, never on dt. Everything the overlays and plots need
//! per step (previous velocities, trails, energy series) is recorded here, step by step, so it does
//! not depend on the frame rate.

use super::quantities;
use crate::analysis::energy;
use crate::analysis::momentum::scene_angular_momentum_about;
use crate::checks::CheckResult;
use crate::clock::Instant;
use crate::level::Scene;
use crate::questions::QuestionResult;
use crate::runner::Observers;
use crate::sim::Options;
use crate::simulation::AnySimulation;
use crate::snapshot::Snapshot;
use bevy::prelude::*;
use glam::DVec2;
use std::collections::VecDeque;
use std::time::Duration;

/// The set the physics step runs in (in `FixedUpdate`, and in `Update` for single steps).
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct PhysicsStep;

/// Runs a scene: inserts [`Physics`] and [`LiveChecks`] and steps in `FixedUpdate`.
pub struct PhysicsPlugin {
    pub scene: Scene,
    pub options: Options,
    /// Start paused (the sandbox waits for play; tests and renders run at once).
    pub paused: bool,
}

impl Plugin for PhysicsPlugin {
    fn build(&self, app: &mut App) {
        let phys = Physics::new(self.scene.clone(), self.options.clone(), self.paused);
        app.insert_resource(Time::<Fixed>::from_seconds(phys.sim.dt()));
        app.insert_non_send(LiveChecks::new(&phys));
        app.insert_resource(phys);
        app.add_systems(PreUpdate, new_frame);
        app.add_systems(
            FixedUpdate,
            (fixed_step, observe_checks).chain().in_set(PhysicsStep),
        );
        app.add_systems(
            Update,
            (seek, manual_steps, observe_checks, sync_fixed_timestep)
                .chain()
                .in_set(PhysicsStep),
        );
    }
}

/// Recent wall times of `Simulation::step`, for the solver panel.
#[derive(Debug, Clone, Default)]
pub struct StepTimes {
    recent: VecDeque<f64>,
}

impl StepTimes {
    const KEEP: usize = 120;
    pub fn push(&mut self, ms: f64) {
        if self.recent.len() == Self::KEEP {
            self.recent.pop_front();
        }
        self.recent.push_back(ms);
    }
    /// Median of the recent steps, ms (the machine is noisy: a median, not a mean).
    pub fn median_ms(&self) -> Option<f64> {
        if self.recent.is_empty() {
            return None;
        }
        let mut v: Vec<f64> = self.recent.iter().copied().collect();
        v.sort_by(f64::total_cmp);
        Some(v[v.len() / 2])
    }
}

/// One sample of the live plots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesPoint {
    pub t: f64,
    /// Kinetic energy T, J.
    pub kinetic: f64,
    /// Gravitational potential energy V_g (zero at y = 0), J.
    pub gravity: f64,
    /// Elastic potential energy V_e of the springs, J.
    pub elastic: f64,
    /// Angular momentum about the world origin H_O, N m s.
    pub h_o: f64,
    /// Linear momentum G = sum of m v_G, N s (moves H to any point).
    pub momentum: DVec2,
}

/// One sample of a body's plots (the graphs' choice and the CSV export).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodySample {
    pub t: f64,
    /// Mass center, m.
    pub g: DVec2,
    /// Angle, rad (the snapshot's, continuous: it keeps counting past a turn).
    pub angle: f64,
    pub omega: f64,
    /// Velocity of G, m/s.
    pub v: DVec2,
    /// The joints' reaction on the body, N: their impulses over the step / dt (the free-body
    /// diagram's R, summed over its joints).
    pub reaction: DVec2,
}

/// Every body's plots are kept in scenes up to this many bodies; beyond, only the selected one's
/// from when it was selected (4,000 samples of 64 bytes: 8 MB at this many bodies).
pub const BODY_SERIES_MAX_BODIES: usize = 32;

impl SeriesPoint {
    pub fn total(&self) -> f64 {
        self.kinetic + self.gravity + self.elastic
    }

    /// Angular momentum about the point `o`, N m s (6/15's transfer from the world origin).
    pub fn h_about(&self, o: DVec2) -> f64 {
        crate::analysis::momentum::transfer_angular_momentum(
            self.h_o,
            DVec2::ZERO,
            o,
            self.momentum,
        )
    }
}

/// Everything about the running level. The snapshot of the last step is `sim.snapshot()`.
#[derive(Resource)]
pub struct Physics {
    /// The level as played (spawned bodies and solver changes included).
    pub scene: Scene,
    pub options: Options,
    pub sim: AnySimulation,
    /// Bumped by every reset/rebuild, so views and checks know to start over.
    pub generation: u64,
    /// Bumped when the camera should refit: a new level, not a reset, a solver change or a
    /// spawned body (those keep the user's view).
    pub view_generation: u64,
    pub paused: bool,
    /// Single steps requested while paused (run in `Update`).
    pub steps_requested: u32,
    /// Pause when the level's duration is reached (where `rigidlab check` stops).
    pub stop_at_end: bool,
    /// Why the run stopped (an explosion), shown in the panel.
    pub error: Option<String>,
    pub step_times: StepTimes,
    /// v_G and omega of every body before the last step, and its dt (for accelerations).
    pub prev_velocities: Option<(Vec<(DVec2, f64)>, f64)>,
    /// Mass-center positions for the trails, one deque per body.
    pub trails: Vec<VecDeque<DVec2>>,
    /// Energy and momentum against time (thinned to at most `SERIES_MAX` points).
    pub series: Vec<SeriesPoint>,
    series_every: u64,
    /// Set when the user pushed or dragged a body: the run is no longer the exercise's.
    pub interfered: bool,
    /// Wall time the physics may take per frame, ms: beyond it the remaining fixed steps of the
    /// frame are dropped (the scene runs slower than real time instead of freezing the window).
    pub frame_budget_ms: f64,
    frame_ms: f64,
    /// Steps were dropped recently to keep the window responsive.
    pub behind: bool,
    /// The snapshots of the last frame's steps and the one they start from (a frame spans at
    /// least one step), oldest first, for the diagrams averaged over a frame; empty beyond
    /// `RECENT_MAX_BODIES` bodies.
    pub recent: VecDeque<Snapshot>,
    /// The state at t = 0 (checks start from it even when the first step ran before they looked).
    pub initial: Snapshot,
    /// The level's impulse events so far in this run, with the joints' share (drawn and listed).
    pub blows: Vec<super::blows::Blow>,
    /// Per body, its samples on the energy series' times (empty for a body not recorded).
    pub body_series: Vec<Vec<BodySample>>,
    /// The body the user selected (always recorded, whatever the scene's size).
    pub tracked: Option<usize>,
    /// The user's pushes and drags this run (impulses with the step they came before), so a
    /// seek back replays them where they happened.
    pub interventions: Vec<Intervention>,
    /// A step to go to (the timeline, step back): run from t = 0 (or on from now) to it, a
    /// frame's budget at a time, every step observed by the live checks.
    pub seek: Option<u64>,
    /// The run was rewound by a seek that is still going: its steps replay the pushes.
    replaying: bool,
}

/// An impulse the user applied between steps: before the step from `step` to `step + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intervention {
    pub step: u64,
    pub body: usize,
    pub at: DVec2,
    pub impulse: DVec2,
}

/// How long a frame may spend seeking, ms (the window stays responsive on a long seek).
const SEEK_BUDGET_MS: f64 = 40.0;

/// Beyond this many bodies, diagrams are not averaged over a frame (the copies would cost).
const RECENT_MAX_BODIES: usize = 200;

/// Trails keep this many points per body.
pub const TRAIL_LEN: usize = 240;
const SERIES_MAX: usize = 4000;

impl Physics {
    pub fn new(scene: Scene, options: Options, paused: bool) -> Self {
        let sim = AnySimulation::new(&scene, &options);
        let initial = sim.snapshot().clone();
        let sim_initial = &initial;
        let mut p = Physics {
            scene,
            options,
            sim,
            generation: 0,
            view_generation: 0,
            paused,
            steps_requested: 0,
            stop_at_end: true,
            error: None,
            step_times: StepTimes::default(),
            prev_velocities: None,
            trails: Vec::new(),
            series: Vec::new(),
            series_every: 1,
            interfered: false,
            frame_budget_ms: 30.0,
            recent: VecDeque::new(),
            frame_ms: 0.0,
            behind: false,
            initial: Snapshot::clone(sim_initial),
            blows: Vec::new(),
            body_series: Vec::new(),
            tracked: None,
            interventions: Vec::new(),
            seek: None,
            replaying: false,
        };
        p.start_records();
        p
    }

    fn start_records(&mut self) {
        self.initial = self.sim.snapshot().clone();
        let s = self.sim.snapshot();
        self.trails = s.bodies.iter().map(|b| VecDeque::from([b.com])).collect();
        self.series = vec![series_point(s)];
        self.body_series = vec![Vec::new(); s.bodies.len()];
        self.series_every = 1;
        self.record_bodies();
        self.prev_velocities = None;
        self.recent.clear();
        self.blows.clear();
    }

    /// Selects the body whose plots are kept whatever the scene's size (in a small scene every
    /// body's already are).
    pub fn track(&mut self, body: Option<usize>) {
        if self.tracked != body {
            self.tracked = body;
            self.record_bodies();
        }
    }

    /// A sample of each recorded body at the current snapshot.
    fn record_bodies(&mut self) {
        let s = self.sim.snapshot();
        let all = s.bodies.len() <= BODY_SERIES_MAX_BODIES;
        for (i, b) in s.bodies.iter().enumerate() {
            if !(all || self.tracked == Some(i)) || b.kind != crate::snapshot::BodyKind::Dynamic {
                continue;
            }
            if self.body_series[i].last().is_some_and(|l| l.t == s.time) {
                continue;
            }
            let (arrows, _) = quantities::free_body_arrows(None, s, i);
            let reaction = arrows
                .iter()
                .filter(|f| f.kind == quantities::ForceKind::Joint)
                .map(|f| f.force)
                .sum();
            self.body_series[i].push(BodySample {
                t: s.time,
                g: b.com,
                angle: b.angle,
                omega: b.omega,
                v: b.velocity,
                reaction,
            });
        }
    }

    /// How many steps one displayed frame (1/60 s) spans: the window of the averaged diagrams
    /// (1 beyond `RECENT_MAX_BODIES` bodies, where they are not averaged).
    pub fn frame_window(&self) -> usize {
        if self.sim.snapshot().bodies.len() > RECENT_MAX_BODIES {
            return 1;
        }
        ((1.0 / 60.0) / self.sim.dt()).round().max(1.0) as usize
    }

    /// Back to t = 0 with the current scene and options; the user's pushes are forgotten.
    pub fn reset(&mut self) {
        self.interventions.clear();
        self.seek = None;
        self.replaying = false;
        self.rewind();
    }

    /// Back to t = 0 keeping the user's pushes, which a run forward applies again at their steps.
    fn rewind(&mut self) {
        self.sim = AnySimulation::new(&self.scene, &self.options);
        self.generation += 1;
        self.error = None;
        self.steps_requested = 0;
        self.interfered = !self.interventions.is_empty();
        self.step_times = StepTimes::default();
        self.start_records();
    }

    /// Replaces the scene (level browser, spawned body) and resets.
    pub fn load(&mut self, scene: Scene) {
        self.scene = scene;
        self.reset();
        self.view_generation = self.generation;
    }

    /// Replaces the scene like [`Physics::load`] but tells the camera not to refit.
    pub fn load_keep_view(&mut self, scene: Scene) {
        self.scene = scene;
        self.reset();
    }

    pub fn snapshot(&self) -> &Snapshot {
        self.sim.snapshot()
    }

    /// True once the level's duration has been simulated.
    pub fn at_end(&self) -> bool {
        self.sim.snapshot().step >= self.sim.total_steps()
    }

    /// Applies an impulse `j` (N s) at world point `at` to body `i` now, between steps, and keeps
    /// it for replays. True if the body could take it (a dynamic body).
    pub fn apply_impulse(&mut self, i: usize, at: DVec2, j: DVec2) -> bool {
        let done = self.sim.apply_impulse(i, at, j);
        if done {
            self.interfered = true;
            self.interventions.push(Intervention {
                step: self.sim.snapshot().step,
                body: i,
                at,
                impulse: j,
            });
        }
        done
    }

    /// Goes toward the step asked for in `seek` (back: from t = 0 again, the user's pushes
    /// replayed; rapier is deterministic, so the states are the run's own bit for bit), calling
    /// `observe` after every step; stops after `budget_ms` and goes on next time. Returns true
    /// when the seek is done (or there is none). Pushes after the step reached are dropped: the
    /// run goes on from there as a new branch, as an editor's redo is lost by a new edit.
    pub fn seek_steps(&mut self, budget_ms: f64, mut observe: impl FnMut(&Physics)) -> bool {
        let Some(target) = self.seek else {
            return true;
        };
        let target = target.min(self.sim.total_steps().max(self.sim.snapshot().step));
        if target < self.sim.snapshot().step {
            self.rewind();
            self.replaying = true;
            observe(self);
        }
        let t0 = Instant::now();
        while self.sim.snapshot().step < target {
            // Forward from a live state, its pushes are already in it: only a rewound run
            // replays them.
            let ok = if self.replaying {
                self.advance_replaying()
            } else {
                self.advance()
            };
            if !ok {
                break;
            }
            observe(self);
            if t0.elapsed().as_secs_f64() * 1e3 > budget_ms {
                return false;
            }
        }
        let now = self.sim.snapshot().step;
        self.interventions.retain(|x| x.step < now);
        self.replaying = false;
        self.interfered = !self.interventions.is_empty();
        self.seek = None;
        self.paused = true;
        true
    }

    /// One step, with the user's pushes recorded before it applied again (a seek's steps).
    fn advance_replaying(&mut self) -> bool {
        let step = self.sim.snapshot().step;
        for x in self.interventions.iter().filter(|x| x.step == step) {
            self.sim.apply_impulse(x.body, x.at, x.impulse);
        }
        self.advance()
    }

    /// One physics step and its records. Returns false when the run cannot go on.
    pub fn advance(&mut self) -> bool {
        if self.error.is_some() {
            return false;
        }
        let before: Vec<(DVec2, f64)> = self
            .sim
            .snapshot()
            .bodies
            .iter()
            .map(|b| (b.velocity, b.omega))
            .collect();
        // The joints' impulses of the step before, for a blow's steady part (cheap: only kept
        // when the level has impulse events).
        let before_blow =
            (!self.scene.level.events.is_empty()).then(|| self.sim.snapshot().clone());
        let t0 = Instant::now();
        let result = self.sim.step().map(|_| ());
        self.step_times.push(t0.elapsed().as_secs_f64() * 1e3);
        if let Err(e) = result {
            self.error = Some(format!("the simulation stopped at {e}"));
            self.paused = true;
            return false;
        }
        if let Some(before) = before_blow {
            let new = super::blows::in_step(&before, self.sim.snapshot());
            self.blows.extend(new);
        }
        // The frame's steps and the state they start from: the diagrams are averaged over
        // them, the forces and m a_G over the same steps (analysis::frame::diagram_balance).
        let window = if self.sim.snapshot().bodies.len() > RECENT_MAX_BODIES {
            0
        } else {
            self.frame_window() + 1
        };
        if window > 1 {
            if self.recent.len() >= window {
                self.recent.pop_front();
            }
            self.recent.push_back(self.sim.snapshot().clone());
        } else if !self.recent.is_empty() {
            self.recent.clear();
        }
        let s = self.sim.snapshot();
        self.prev_velocities = Some((before, s.dt));
        // Trails: one point every step, but no closer than needed for a smooth curve.
        let keep_every = ((1.0 / 120.0) / s.dt).round().max(1.0) as u64;
        if s.step.is_multiple_of(keep_every) {
            for (trail, b) in self.trails.iter_mut().zip(&s.bodies) {
                if trail.len() == TRAIL_LEN {
                    trail.pop_front();
                }
                trail.push_back(b.com);
            }
        }
        if s.step.is_multiple_of(self.series_every) {
            let p = series_point(s);
            self.series.push(p);
            self.record_bodies();
            if self.series.len() >= SERIES_MAX {
                // Keep every other point: the plot stays within SERIES_MAX over any run length.
                let thinned: Vec<SeriesPoint> = self.series.iter().step_by(2).copied().collect();
                self.series = thinned;
                for b in self.body_series.iter_mut() {
                    *b = b.iter().step_by(2).copied().collect();
                }
                self.series_every *= 2;
            }
        }
        if self.stop_at_end && self.at_end() {
            self.paused = true;
        }
        true
    }
}

fn series_point(s: &Snapshot) -> SeriesPoint {
    SeriesPoint {
        t: s.time,
        kinetic: energy::system_kinetic_energy(s, energy::engine_mass),
        gravity: energy::system_gravity_potential(s, energy::engine_mass),
        elastic: s.springs.iter().map(|sp| sp.energy).sum(),
        h_o: scene_angular_momentum_about(s, DVec2::ZERO),
        momentum: crate::analysis::momentum::scene_linear_momentum(s),
    }
}

fn fixed_step(mut phys: ResMut<Physics>) {
    if phys.paused {
        return;
    }
    // The first step of a frame always runs, so one FixedUpdate is always one step.
    if phys.frame_ms > phys.frame_budget_ms {
        phys.behind = true;
        return;
    }
    let t0 = Instant::now();
    phys.advance();
    phys.frame_ms += t0.elapsed().as_secs_f64() * 1e3;
}

fn new_frame(mut phys: ResMut<Physics>) {
    phys.frame_ms = 0.0;
}

/// The timeline and step back: seeks within a frame's budget, the live checks seeing every step.
fn seek(mut phys: ResMut<Physics>, mut live: NonSendMut<LiveChecks>) {
    if phys.seek.is_some() {
        phys.seek_steps(SEEK_BUDGET_MS, |p| live.observe(p));
    }
}

fn manual_steps(mut phys: ResMut<Physics>) {
    while phys.steps_requested > 0 {
        phys.steps_requested -= 1;
        if !phys.advance() {
            phys.steps_requested = 0;
        }
    }
}

/// Keeps `Time<Fixed>` at the simulation's dt after solver changes.
fn sync_fixed_timestep(phys: Res<Physics>, mut fixed: ResMut<Time<Fixed>>) {
    let dt = Duration::from_secs_f64(phys.sim.dt());
    if fixed.timestep() != dt {
        fixed.set_timestep(dt);
    }
}

/// The level's checks and questions, fed every snapshot as `rigidlab check` feeds them.
///
/// Non-send because `checks::Probe` is not `Send`; results appear when the level's duration is
/// reached (a probe reports only when finished).
pub struct LiveChecks {
    generation: u64,
    last_step: Option<u64>,
    /// None once finished.
    observers: Option<Observers>,
    /// Set at the level's end: the same results `rigidlab check` prints.
    pub checks: Option<Vec<CheckResult>>,
    pub answers: Option<Vec<QuestionResult>>,
}

impl LiveChecks {
    pub fn new(phys: &Physics) -> Self {
        let level = &phys.sim.level;
        let mut live = LiveChecks {
            generation: phys.generation,
            last_step: Some(0),
            observers: Some(Observers::new(level)),
            checks: None,
            answers: None,
        };
        if let Some(o) = live.observers.as_mut() {
            o.observe(&phys.initial);
        }
        live
    }

    /// Feeds the current snapshot once (idempotent within a step), finishing at the level's end.
    pub fn observe(&mut self, phys: &Physics) {
        if self.generation != phys.generation {
            *self = LiveChecks::new(phys);
        }
        let s = phys.snapshot();
        if self.last_step == Some(s.step) || self.checks.is_some() {
            return;
        }
        self.last_step = Some(s.step);
        if let Some(o) = self.observers.as_mut() {
            o.observe(s);
        }
        if phys.at_end() {
            if let Some(o) = self.observers.take() {
                let (checks, answers) = o.finish(&Default::default());
                self.checks = Some(checks);
                self.answers = Some(answers);
            }
        }
    }
}

fn observe_checks(phys: Res<Physics>, mut live: NonSendMut<LiveChecks>) {
    live.observe(&phys);
}
