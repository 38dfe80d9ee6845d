//! The explosion guard: stops a run whose mechanical energy grows far beyond what the level's
//! initial state and the work put in can explain.
//!
//! Its energies and works are the guard's own engine-side sums over the snapshot, not the
//! analysis stage's readings: `sim` runs before `analysis` in the data flow and does not import it
//! (tests/suite/docs/stage_layers.rs), and a test against 1e3 times a reference needs no textbook reading.
//!
//! E = T + V_g + V_s (eqs. 6/9, 3/21, 3/23 of MK over all bodies and springs). A closed,
//! conservative system keeps E = E0; rapier's solvers only lose energy (contact and joint
//! softness dissipate). So E - E0 can grow only by the work of loads, motors, impulse events
//! and moving kinematic bodies, W, which the guard sums as an upper bound (absolute values).
//! The run is declared exploded when
//!     E - E0 > FACTOR * (E_scale + W),
//! with E_scale = T0 + V_s0 + sum over dynamic bodies of m (|g| 1 m + (1 m/s)^2 / 2): every body
//! dropping 1 m and moving at 1 m/s, so that scenes starting at rest have a scale.

//!
//! The speed cap. rapier clamps every body's speed at its `max_linear_velocity` after each
//! substep (400 m/s by default), so a scene that explodes does not diverge: a block on a spring
//! far too stiff for the step (k h^2 / m >> 1) is thrown back and forth at the cap every
//! substep, its energy bounded by the cap, and the energy test above never fires. Past that, a
//! spring so stiff that one substep's velocity change overflows f32 when rapier takes its length
//! (|F h / m| > 1.8e19 m/s) has its velocity scaled by 400 / inf = 0: the body does not move at
//! all and every check reads a quiet scene. [`EnergyGuard::check_speed_cap`] stops both:
//! a body at the cap that reverses or stays put ([`PINNED_STEPS`] steps running), and a body
//! that stays put while a spring pulls it with a force that would change its speed by more than
//! [`ENORMOUS`] times the cap in one substep.

use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;

/// Steps running a body may stay pinned at rapier's speed cap, or held still under an enormous
/// spring force, before the run stops: one step can be a blow; ten running is the engine's cap,
/// not the scene's motion.
pub const PINNED_STEPS: u32 = 10;

/// A spring force is enormous when one substep of it would change its body's speed by more than
/// this many times rapier's speed cap (4e8 m/s at the default 400 m/s).
pub const ENORMOUS: f64 = 1e6;

/// A speed within this fraction of the cap counts as at the cap (rapier scales the velocity to
/// the cap in f32).
const AT_CAP: f64 = 1e-3;

/// E - E0 may exceed the reference energy this many times, for at most [`SUSTAIN`] seconds.
///
/// rapier clamps every body's speed at `normalized_max_linear_velocity` (400 m/s), so an
/// exploding scene does not diverge: it rings at the cap (a spring at omega dt = 2.5 released
/// 0.1 m stretched settles at 1.35e3 x its reference; the 1e4 m/s speed guard can never fire).
/// A sustained gain is what tells it from stretched_chain (links start 2x apart; rapier closes
/// them with an uncapped corrective velocity): its ratio peaks at 5.6e3 in the first step, then
/// falls below 1e3 within 0.2 s and below 1 by 4.7 s: a bounded, one-off release that the
/// stability study reports as a known engine gap, so the guard lets it pass. Measured maxima on
/// the textbook levels: <= 0.99; stiff_spring 10.6 (its symplectic bound is 20).
pub const FACTOR: f64 = 1e3;

/// How long the gain must stay above FACTOR times the reference before the run stops, s.
pub const SUSTAIN: f64 = 1.0;

/// Energy bookkeeping of one run.
#[derive(Debug, Clone, Default)]
pub struct EnergyGuard {
    pub e0: f64,
    pub scale: f64,
    /// Upper bound on the work put in so far, J.
    pub work: f64,
    /// Largest (E - E0) / (E_scale + W) seen so far.
    pub max_ratio: f64,
    /// Start of the current stretch of time above FACTOR, s.
    above_since: Option<f64>,
    /// Longest stretch above FACTOR so far, s.
    pub longest_above: f64,
    /// State before the step: (mass center, velocity, omega) per body, joint coordinates.
    prev: Vec<(DVec2, DVec2, f64)>,
    prev_coord: Vec<f64>,
    /// Per body: steps running pinned at the speed cap ([`EnergyGuard::check_speed_cap`]).
    at_cap: Vec<u32>,
    /// Per body: steps running held still under an enormous spring force.
    held: Vec<u32>,
    /// Whether a body of the run is kinematic (kinds do not change during a run): only then do
    /// the step's contacts carry work ([`Self::add_work`] walks them).
    has_kinematic: bool,
    /// Per body: the largest velocity change per substep a spring asks of it, which spring,
    /// and its force ([`Self::check_speed_cap`]); kept between steps so that a step allocates
    /// nothing.
    pull: Vec<(f64, usize, f64)>,
}

/// Why [`EnergyGuard::check_speed_cap`] stopped a run: the body's index and what happened.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedCapStop {
    pub body: usize,
    pub what: String,
}

/// The guard's energy scale: T + V_g + V_s of a snapshot, J (V_g from the origin), with each
/// body's T as [`motion_energy`] and each spring's energy as the snapshot reports it.
pub fn energy_scale(s: &Snapshot) -> f64 {
    let bodies: f64 = s
        .bodies
        .iter()
        .map(|b| motion_energy(b) - b.mass * s.gravity.dot(b.com))
        .sum();
    bodies + s.springs.iter().map(|sp| sp.energy).sum::<f64>()
}

/// The energy of a body's motion as the engine holds it, 1/2 m v_G^2 + 1/2 I_G omega^2 from the
/// snapshot's m, I_G, v_G and omega, J: the guard's one sum of it (see the module's note).
pub fn motion_energy(b: &BodyState) -> f64 {
    0.5 * b.mass * b.velocity.length_squared() + 0.5 * b.inertia * b.omega * b.omega
}

/// The velocity of the body point now at p, from G's velocity and omega (`perp` is k x), for the
/// guard's work sums (see the module's note).
fn velocity_at((com, v, w): (DVec2, DVec2, f64), p: DVec2) -> DVec2 {
    v + (p - com).perp() * w
}

fn kin(s: &Snapshot, i: usize) -> (DVec2, DVec2, f64) {
    let b = &s.bodies[i];
    (b.com, b.velocity, b.omega)
}

impl EnergyGuard {
    pub fn new(s: &Snapshot) -> Self {
        let g = s.gravity.length();
        let t0: f64 = s.bodies.iter().map(motion_energy).sum();
        let v0: f64 = s.springs.iter().map(|sp| sp.energy).sum();
        let unit: f64 = s.bodies.iter().map(|b| b.mass * (g + 0.5)).sum();
        EnergyGuard {
            e0: energy_scale(s),
            scale: t0 + v0 + unit,
            work: 0.0,
            max_ratio: 0.0,
            above_since: None,
            longest_above: 0.0,
            prev: Vec::new(),
            prev_coord: Vec::new(),
            at_cap: Vec::new(),
            held: Vec::new(),
            has_kinematic: s
                .bodies
                .iter()
                .any(|b| b.kind == crate::level::BodyKind::Kinematic),
            pull: Vec::new(),
        }
    }

    /// Remembers the state at the start of a step (before impulse events act).
    pub fn record(&mut self, s: &Snapshot) {
        self.prev.clear();
        self.prev.extend((0..s.bodies.len()).map(|i| kin(s, i)));
        self.prev_coord.clear();
        self.prev_coord
            .extend(s.joints.iter().map(|j| j.coordinate));
    }

    /// Adds the step's work bound (`now`: the state after the step; see [`Self::record`]).
    pub fn add_work(&mut self, now: &Snapshot) {
        let dt = now.dt;
        let prev = &self.prev;
        let mean_v =
            |i: usize, p: DVec2| 0.5 * (velocity_at(prev[i], p) + velocity_at(kin(now, i), p));
        let mean_w = |i: usize| 0.5 * (prev[i].2 + now.bodies[i].omega);
        let mut w = 0.0;
        for l in &now.loads {
            w += (l.force.dot(mean_v(l.body, l.point)) + l.torque * mean_w(l.body)).abs() * dt;
        }
        for e in &now.impulses {
            // Work of an impulse on a free body: J . (v_before + v_after)/2 at its point, bounded by
            // |J . v_before| + |J|^2/(2m) + (r x J + H)^2/(2 I_G).
            let b = &now.bodies[e.body];
            let r = e.point - prev[e.body].0;
            let h = r.perp_dot(e.impulse) + e.angular_impulse;
            w += e.impulse.dot(velocity_at(prev[e.body], e.point)).abs();
            if b.mass > 0.0 {
                w += e.impulse.length_squared() / (2.0 * b.mass);
            }
            if b.inertia > 0.0 {
                w += h * h / (2.0 * b.inertia);
            }
            w += (e.angular_impulse * prev[e.body].2).abs();
        }
        for (j, p) in now.joints.iter().zip(&self.prev_coord) {
            // Motor work: its generalized impulse times the joint coordinate's change (a pin's
            // coordinate wraps at +-pi: the change is the short way round).
            w += (j.motor_impulse * coordinate_change(j.coordinate, *p)).abs();
        }
        // Moving kinematic bodies push with their contact and joint impulses (a run without
        // one skips the walk over its contacts: it would add nothing).
        let kinematic = |i: usize| now.bodies[i].kind == crate::level::BodyKind::Kinematic;
        let contacts = if self.has_kinematic {
            &now.contacts[..]
        } else {
            &[]
        };
        for c in contacts {
            for k in [c.body1, c.body2] {
                if !kinematic(k) {
                    continue;
                }
                for p in &c.points {
                    let imp = p.normal_impulse.abs() + p.tangent_impulse.abs();
                    w += imp * mean_v(k, p.point).length();
                }
            }
        }
        for j in &now.joints {
            for k in [j.body1, j.body2] {
                if kinematic(k) {
                    w += j.impulse_on_body2.length() * mean_v(k, j.anchor).length()
                        + (j.angular_impulse_on_body2.abs() + j.angular_impulse_on_body1.abs())
                            * mean_w(k).abs();
                }
            }
        }
        self.work += w;
    }

    /// (E - E0, reference energy) once the gain has stayed above FACTOR times the reference
    /// for SUSTAIN seconds.
    pub fn check(&mut self, now: &Snapshot) -> Option<(f64, f64)> {
        let gain = energy_scale(now) - self.e0;
        let reference = self.scale + self.work;
        let ratio = gain / reference;
        if ratio.is_finite() {
            self.max_ratio = self.max_ratio.max(ratio);
        }
        if ratio > FACTOR {
            // The stretch began when the step before this one ended.
            let since = *self.above_since.get_or_insert(now.time - now.dt);
            self.longest_above = self.longest_above.max(now.time - since);
            (now.time - since >= SUSTAIN - 1e-9).then_some((gain, reference))
        } else {
            self.above_since = None;
            None
        }
    }
}

impl EnergyGuard {
    /// Stops a run that rapier's speed cap (`cap`, m/s) holds rather than the scene's forces
    /// (see the module's note), once it has held for [`PINNED_STEPS`] steps running:
    /// - a dynamic body at the cap at the step's end that reversed or stayed put over the step
    ///   (|v - v_before| > cap / 2, or it moved less than cap dt / 2 where the precision
    ///   resolves that much travel): thrown back and forth at the cap, not cruising at it as a
    ///   fast bullet or a long free fall does;
    /// - a dynamic body that did not move at all (same mass center, zero velocity) while a spring
    ///   pulled it with a force F whose velocity change over one substep, |F| h / m with
    ///   h = dt / substeps, exceeds [`ENORMOUS`] times the cap.
    ///
    /// Called after [`Self::record`] and the step (`now`: the state after it).
    pub fn check_speed_cap(&mut self, now: &Snapshot, cap: f64) -> Option<SpeedCapStop> {
        let n = now.bodies.len();
        if self.prev.len() != n || !(cap.is_finite() && cap > 0.0) {
            return None;
        }
        self.at_cap.resize(n, 0);
        self.held.resize(n, 0);
        let dynamic = |b: &BodyState| b.kind == crate::level::BodyKind::Dynamic && b.mass > 0.0;
        let h = now.dt / now.substeps.max(1) as f64;
        // The largest velocity change per substep a spring asks of each body, and which spring
        // (none without springs: then no body is held).
        let pull = &mut self.pull;
        pull.clear();
        if !now.springs.is_empty() {
            pull.resize(n, (0.0, 0, 0.0));
        }
        for (k, sp) in now.springs.iter().enumerate() {
            if sp.torsion {
                continue;
            }
            let f = sp.force_on_body1.length();
            for i in std::iter::once(sp.body1).chain(sp.body2) {
                let b = &now.bodies[i];
                if dynamic(b) {
                    let dv = f * h / b.mass;
                    if dv.is_nan() || dv > pull[i].0 {
                        pull[i] = (dv, k, f);
                    }
                }
            }
        }
        for (i, b) in now.bodies.iter().enumerate() {
            if !dynamic(b) {
                self.at_cap[i] = 0;
                self.held[i] = 0;
                continue;
            }
            let (com0, v0, _) = self.prev[i];
            let speed = b.velocity.length();
            // Staying put is judged only where the precision resolves the step's travel: far
            // from the origin in f32 a body cruising at the cap can move by whole ulps or not at
            // all (a free fall at 400 m/s, 1e-5 s steps, 1e5 m down: 4 mm a step, ulp 8 mm).
            // (Computed only for a body at the cap: the others cannot be pinned.)
            let resolved =
                || 0.5 * cap * now.dt > 4.0 * now.precision.epsilon() * b.com.length().max(1.0);
            let pinned = speed >= (1.0 - AT_CAP) * cap
                && ((b.velocity - v0).length() > 0.5 * cap
                    || (resolved() && (b.com - com0).length() < 0.5 * cap * now.dt));
            self.at_cap[i] = if pinned { self.at_cap[i] + 1 } else { 0 };
            let still = b.com == com0 && b.velocity == DVec2::ZERO;
            let (dv, k, f) = pull.get(i).copied().unwrap_or((0.0, 0, 0.0));
            let held = still && (dv.is_nan() || dv > ENORMOUS * cap);
            self.held[i] = if held { self.held[i] + 1 } else { 0 };
            if self.at_cap[i] >= PINNED_STEPS {
                return Some(SpeedCapStop {
                    body: i,
                    what: format!(
                        "has been held at rapier's speed cap of {cap} m/s for {PINNED_STEPS} \
                         steps running, thrown back and forth rather than moving: its motion is \
                         the cap's, not the scene's; the scene exploded (a spring or a contact \
                         too stiff for the step); try a smaller dt or more substeps"
                    ),
                });
            }
            if self.held[i] >= PINNED_STEPS {
                let name = &now.springs[k].name;
                return Some(SpeedCapStop {
                    body: i,
                    what: format!(
                        "has not moved for {PINNED_STEPS} steps while spring \"{name}\" pulls it \
                         with {f:.3e} N, a speed change of {dv:.3e} m/s per substep \
                         (h = {h:.3e} s, m = {m} kg), past rapier's speed cap of {cap} m/s: \
                         the engine cannot integrate this spring at this step (k h^2 / m far \
                         above 1) and dropped the motion; lower the spring's stiffness, or \
                         the step",
                        m = b.mass
                    ),
                });
            }
        }
        None
    }
}

/// The change of a joint coordinate over a step: a pin's wraps to (-pi, pi], so a change is
/// taken the short way round (a slider moves far less than pi metres in a step).
pub fn coordinate_change(now: f64, before: f64) -> f64 {
    crate::sim::angles::wrap_pi(now - before)
}
