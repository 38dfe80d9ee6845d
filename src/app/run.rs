//! The run: the core simulation of the level on screen ([`AnySimulation`], f32 or f64 as the
//! level asks) with everything recorded from its steps that the overlays and plots read (previous
//! velocities, trails, energy series, the frame's snapshots, the blows).
//!
//! A [`Run`] changes only through `physics.rs` (its step systems and the one system that applies
//! [`PhysicsCommand`](super::physics::PhysicsCommand)s); every other system reads it. Whether it
//! plays is [`Playback`](super::playback::Playback)'s, not the run's: [`Run::advance`] steps
//! whenever it is asked to. Everything per step is recorded here, step by step, so it does not
//! depend on the frame rate.

use super::quantities;
use crate::analysis::energy;
use crate::analysis::momentum::scene_angular_momentum_about;
use crate::clock::Instant;
use crate::level::Scene;
use crate::sim::Options;
use crate::simulation::AnySimulation;
use crate::snapshot::Snapshot;
use bevy::prelude::*;
use glam::DVec2;
use std::collections::VecDeque;

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

/// The running level and its records. The snapshot of the last step is `sim.snapshot()`.
#[derive(Resource)]
pub struct Run {
    /// The level as played (spawned bodies and solver changes included).
    pub scene: Scene,
    pub options: Options,
    pub sim: AnySimulation,
    /// Bumped by every reset/rebuild, so views and checks know to start over.
    pub generation: u64,
    /// Bumped when the camera should refit: a new level, not a reset, a solver change or a
    /// spawned body (those keep the user's view).
    pub view_generation: u64,
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
    /// The body the mouse spring holds, pulled before every step while the run plays.
    pub held: Option<Hold>,
}

/// A body held by the mouse spring: the point on it (body frame) pulled toward the mouse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hold {
    pub body: usize,
    /// The held point in the body frame.
    pub local: DVec2,
    /// Where the mouse is, world.
    pub target: DVec2,
}

/// Mouse spring natural frequency, Hz (critically damped).
const SPRING_HZ: f64 = 1.5;

/// An impulse the user applied between steps: before the step from `step` to `step + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intervention {
    pub step: u64,
    pub body: usize,
    pub at: DVec2,
    pub impulse: DVec2,
}

/// Beyond this many bodies, diagrams are not averaged over a frame (the copies would cost).
const RECENT_MAX_BODIES: usize = 200;

/// Trails keep this many points per body.
pub const TRAIL_LEN: usize = 240;
const SERIES_MAX: usize = 4000;

impl Run {
    pub fn new(scene: Scene, options: Options) -> Self {
        let sim = AnySimulation::new(&scene, &options);
        let initial = sim.snapshot().clone();
        let sim_initial = &initial;
        let mut p = Run {
            scene,
            options,
            sim,
            generation: 0,
            view_generation: 0,
            error: None,
            step_times: StepTimes::default(),
            prev_velocities: None,
            trails: Vec::new(),
            series: Vec::new(),
            series_every: 1,
            interfered: false,
            recent: VecDeque::new(),
            initial: Snapshot::clone(sim_initial),
            blows: Vec::new(),
            body_series: Vec::new(),
            tracked: None,
            interventions: Vec::new(),
            seek: None,
            replaying: false,
            held: None,
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

    /// A seek back is asked or replaying (the timeline dragged back, Left): not a seek forward,
    /// such as predict-first's jump to the instant a question is read, which the first-steps
    /// tour took for the student's step back (the second student trial, 2026-12-07).
    pub fn seeking_back(&self) -> bool {
        self.replaying
            || self
                .seek
                .is_some_and(|target| target < self.sim.snapshot().step)
    }

    /// The steps the drawn forces are averaged over now: the frame's window, or fewer while the
    /// run has not yet taken that many (the slider-crank's 60-step run said "the last 833
    /// steps"), and its span in seconds.
    pub fn steps_averaged(&self) -> (usize, f64) {
        let n = self.recent.len().saturating_sub(1).min(self.frame_window());
        (n, n as f64 * self.sim.dt())
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

    /// Replaces the scene like [`Run::load`] but tells the camera not to refit.
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
    /// when the seek is done (or there is none); a seek that ends leaves the run paused
    /// (`physics.rs` pauses the playback). Pushes after the step reached are dropped: the run
    /// goes on from there as a new branch, as an editor's redo is lost by a new edit.
    pub fn seek_steps(&mut self, budget_ms: f64, mut observe: impl FnMut(&Run)) -> bool {
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

    /// The mouse spring: a critically damped pull of the held point toward the mouse, applied
    /// as the impulse of the force over the coming step (rigidlab resets forces each step,
    /// impulses stay), and kept for replays as any push.
    pub fn pull_held(&mut self) {
        let Some(g) = self.held else {
            return;
        };
        let s = self.sim.snapshot();
        let Some(b) = s.bodies.get(g.body) else {
            return;
        };
        let p = b.world_point(g.local);
        let v = crate::analysis::kinematics::body_point_velocity(b, p);
        let w = std::f64::consts::TAU * SPRING_HZ;
        let m = b.mass;
        // F = m (w^2 (target - p) - 2 w v_p) - m g, limited to 30 m g (or 30 m w^2 x 1 m without gravity).
        let mut f = (w * w * (g.target - p) - 2.0 * w * v) * m - s.gravity * m;
        let limit = 30.0 * m * s.gravity.length().max(w * w);
        if f.length() > limit {
            f = f.normalize() * limit;
        }
        let dt = self.sim.dt();
        self.apply_impulse(g.body, p, f * dt);
    }

    /// One physics step and its records. Returns false when the run cannot go on (an error,
    /// kept in `error`).
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
