//! A step's joint impulses from one rapier call, where no blow can fall in the step.
//!
//! rapier 0.36 keeps a joint's impulse of a call's last substep only: its joint rows restart
//! from zero each substep (`warmstart_joints` is off; on, the rows start from the previous
//! substep's impulse and still end holding that substep's alone), and it offers no hook inside
//! its substep loop (`PhysicsHooks` and `EventHandler` see contacts, not joints). Exact sums
//! need one call per substep (`Substepping::Split`), at 2.8x to 3.0x the bare step on the
//! analysis bench. A level whose joints feel no blow needs them only where one can fall: a step
//! is split when it may hold one ([`Simulation::blow_may_fall`], or an impact the planner cuts),
//! and elsewhere it is one call of n substeps whose sum is reconstructed.
//!
//! The reconstruction. Let J_k be substep k's impulse (k = 1..n, centred at t0 + (k - 1/2) h,
//! h = dt / n) and J_0 the previous step's last (centred at t0 - h/2). Through J_0 and J_n,
//! a distance dt apart, J is taken linear; the centres' mean is t0 + dt/2, so
//! sum_k J_k = n J(t0 + dt/2) = ((n + 1) J_n + (n - 1) J_0) / 2, exact for a force linear in
//! time. For a smooth force F (J_k = h F(t_k)), the error of linear interpolation at t is
//! F''(xi) (t - t_a)(t_b - t) / 2, whose mean over the substeps' centres is
//! F'' h^2 (n^2 - 1) / 12: the step's mean force is off by at most
//! **max |F''| (dt^2 - h^2) / 12** (n J_n alone, the first-order alternative, is off by
//! F' (dt - h) / 2). A bar of 1 m released at 45 degrees (T'' of order T (w^2 + g/L)) at
//! dt = 1/60 s and 4 substeps: about 2e-4 of T. tests/suite/sim/joint_sums.rs holds it against
//! closed forms.
//!
//! J_n itself is read along rows rebuilt as rapier built them, at the poses its last substep
//! started from: the end poses stepped back by one substep at the end velocities (rapier moved
//! them with the biased pass's velocities, which the unbiased pass then corrects by the joints'
//! position error over h: the back-step is off by that error, not by a substep of motion).
//!
//! A blow (an impulse event, an impact, a weld made, a joint's first step) is not smooth: its
//! reaction falls in one substep. Such steps are split, and so are steps where the impulses
//! have not been smooth enough to interpolate, or have carried too much rounding
//! ([`SubstepHistory::record`]: in the library most joint-reading steps stay split so), and
//! every step of a level whose
//! joints can be struck at any step or are moved between calls (`why_not_reconstructed` in
//! sim/settings.rs: limits, couplings, prescribed motions, joints that start apart, sleeping).

use super::rapier::prelude::*;
use super::readings::JointPoses;
use super::world::{to_d, Simulation};
use crate::level::Effect;
use crate::snapshot::JointState;
use glam::DVec2;

/// One joint's impulses over one substep, world axes (the fields of `JointState` that sum).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct SubstepImpulses {
    on_body2: DVec2,
    angular_on_body2: f64,
    angular_on_body1: f64,
    couple_on_body2: f64,
    motor: f64,
    limit: f64,
}

impl SubstepImpulses {
    /// A reading of one substep (`read_joints_scaled(1.0, ..)`).
    pub(super) fn of(j: &JointState) -> Self {
        SubstepImpulses {
            on_body2: j.impulse_on_body2,
            angular_on_body2: j.angular_impulse_on_body2,
            angular_on_body1: j.angular_impulse_on_body1,
            couple_on_body2: j.couple_on_body2,
            motor: j.motor_impulse,
            limit: j.limit_impulse,
        }
    }
}

/// What the reconstruction keeps between steps: the last substeps of the last two steps, and
/// whether they and the step before lie on a line closely enough for the coming step.
#[derive(Debug, Clone, Default)]
pub(super) struct SubstepHistory {
    /// Each joint's impulses over the last substep of the last step (J_0, centred at t0 - h/2).
    last: Vec<SubstepImpulses>,
    /// Over the last substep of the step before it (J_-1, centred at t0 - dt - h/2).
    before: Vec<SubstepImpulses>,
    /// Whether the coming step may be reconstructed (see [`SubstepHistory::record`]).
    smooth: bool,
    /// How many steps in a row have found the impulses smooth.
    smooth_run: u32,
    /// How many are needed before a step is reconstructed: 2, doubled (to [`MOST_NEEDED`])
    /// each time the impulses are found not smooth.
    needed: u32,
}

/// The most steps in a row the impulses must be found smooth before a step is reconstructed.
const MOST_NEEDED: u32 = 1 << 12;

impl SubstepHistory {
    /// Forgets the impulses seen: the coming steps are split until three are seen again (a blow
    /// from outside the step, a restart). How many smooth steps are needed is kept.
    pub(super) fn clear(&mut self) {
        *self = SubstepHistory {
            needed: self.needed,
            ..SubstepHistory::default()
        };
    }

    /// Takes a step's last substep's impulses `now` (J_n) and judges whether the coming step
    /// can be interpolated. The three last substeps, a step apart, have the second difference
    /// D = J_n - 2 J_0 + J_-1 = h F'' dt^2 to leading order; a step interpolated under the same
    /// F'' is off by dt F'' (dt^2 - h^2) / 12 = D (n^2 - 1) / (12 n) in its sum. The coming step
    /// is reconstructed when that is within `tolerance` of the step's impulse (n times the
    /// largest of the three, per part: force, each moment, motor, limit); else it is split and
    /// summed exactly. This also catches what is not smooth at the step's scale though no blow
    /// falls (a motor's start, a stiff servo's ringing, readings dominated by rounding noise),
    /// and it must hold for two steps in a row, twice as many after each step that fails it.
    fn record(&mut self, now: Vec<SubstepImpulses>, n: f64, tolerance: f64) {
        let k = (n * n - 1.0) / (12.0 * n);
        let fits = |(a, (b, c)): (&SubstepImpulses, (&SubstepImpulses, &SubstepImpulses))| {
            let scalars = |f: fn(&SubstepImpulses) -> f64| {
                let (x, y, z) = (f(a), f(b), f(c));
                ((z - 2.0 * y + x).abs(), x.abs().max(y.abs()).max(z.abs()))
            };
            let force = (
                (c.on_body2 - 2.0 * b.on_body2 + a.on_body2).length(),
                a.on_body2
                    .length()
                    .max(b.on_body2.length())
                    .max(c.on_body2.length()),
            );
            [
                force,
                scalars(|j| j.angular_on_body2),
                scalars(|j| j.angular_on_body1),
                scalars(|j| j.couple_on_body2),
                scalars(|j| j.motor),
                scalars(|j| j.limit),
            ]
            .iter()
            .all(|&(second, scale)| k * second <= tolerance * n * scale)
        };
        let judged = now.len() == self.last.len() && now.len() == self.before.len();
        let fit = judged && self.before.iter().zip(self.last.iter().zip(&now)).all(fits);
        // Twice in a row at first; each step found not smooth doubles that. A single substep's
        // impulse carries the engine's rounding, which an exact sum cancels: a joint's position
        // correction at f32 poses (a cart's pin 2 m out of the origin) or a motor's impulse at
        // 0.2 ms steps fluctuates from step to step, and a second difference of such readings
        // passes now and then by chance. Where it keeps failing, the steps stay split.
        self.needed = self.needed.max(2);
        if judged && !fit {
            self.needed = (2 * self.needed).min(MOST_NEEDED);
        }
        self.smooth_run = if fit { self.smooth_run + 1 } else { 0 };
        self.smooth = self.smooth_run >= self.needed;
        self.before = std::mem::replace(&mut self.last, now);
    }
}

/// The step's sum from its last substep's impulse (in `j`) and the previous step's last
/// substep's `before`, over `n` substeps: ((n + 1) J_n + (n - 1) J_0) / 2 (the module doc).
fn reconstruct(j: &mut JointState, before: &SubstepImpulses, n: f64) {
    let (a, b) = (0.5 * (n + 1.0), 0.5 * (n - 1.0));
    j.impulse_on_body2 = a * j.impulse_on_body2 + b * before.on_body2;
    j.angular_impulse_on_body2 = a * j.angular_impulse_on_body2 + b * before.angular_on_body2;
    j.angular_impulse_on_body1 = a * j.angular_impulse_on_body1 + b * before.angular_on_body1;
    j.couple_on_body2 = a * j.couple_on_body2 + b * before.couple_on_body2;
    j.motor_impulse = a * j.motor_impulse + b * before.motor;
    j.limit_impulse = a * j.limit_impulse + b * before.limit;
}

impl Simulation {
    /// Whether a blow can fall in the coming step of length `dt` through a joint: the run's
    /// first step (no substep before it to interpolate from, and a motor's first pull is a
    /// blow), an impulse event this step, a joint made since the last step (a weld's first
    /// impulse), the last steps' impulses not smooth enough to interpolate
    /// ([`SubstepHistory::record`]), or a collider of a jointed dynamic body within reach of another's over the
    /// step (an impact or a contact's push; impacts the planner cuts are split too, `plan.rs`).
    pub(super) fn blow_may_fall(&self, dt: f64) -> bool {
        self.snapshot.step == 0
            || !self.snapshot.impulses.is_empty()
            || !self.substeps_seen.smooth
            || self.substeps_seen.last.len() != self.joints.len()
            || self.jointed_body_within_reach(dt)
    }

    /// Whether a collider of a dynamic body in a joint may touch another collider within `dt`:
    /// their boxes, each grown by the farthest any of its points can move over the step (at its
    /// speed, plus gravity's gain) and by rapier's prediction distance, overlap. Pairs rapier
    /// never collides (a joint's two bodies with their contacts off) are passed over.
    fn jointed_body_within_reach(&self, dt: f64) -> bool {
        if !self.settings.effects.has(Effect::Contacts) {
            return false;
        }
        let w = &self.world;
        let margin = w.integration_parameters.prediction_distance() as f64
            + w.gravity.length() as f64 * dt * dt;
        let grown = |co: &Collider| {
            let aabb = co.compute_aabb();
            let speed = co.parent().map(|h| &w.bodies[h]).map_or(0.0, |rb| {
                let reach = aabb.half_extents().length() * 2.0;
                (rb.linvel().length() + rb.angvel().abs() * reach) as f64
            });
            aabb.loosened((speed * dt + margin) as Real)
        };
        let mut jointed = Vec::new();
        for h in &self.joints {
            let Some(j) = w.impulse_joints.get(*h) else {
                continue;
            };
            for b in [j.body1(), j.body2()] {
                let rb = &w.bodies[b];
                if rb.is_dynamic() {
                    jointed.extend(rb.colliders().iter().map(|c| (*c, b)));
                }
            }
        }
        if jointed.is_empty() {
            return false;
        }
        let all: Vec<_> = w
            .colliders
            .iter()
            .map(|(h, co)| (h, co.parent(), grown(co)))
            .collect();
        jointed.iter().any(|&(c, body)| {
            let mine = grown(&w.colliders[c]);
            all.iter().any(|(other, parent, aabb)| {
                *other != c
                    && *parent != Some(body)
                    && mine.intersects(aabb)
                    && !parent.is_some_and(|p| {
                        w.impulse_joints
                            .joints_between(body, p)
                            .any(|(_, j)| !j.data.contacts_enabled)
                    })
            })
        })
    }

    /// The poses each joint's bodies started the last substep of the step just made from: the
    /// end poses stepped back over `h` at the end velocities, undoing rapier's integration
    /// (`integrate_linearized`: G moves by h v, the rotation turns by atan(h w)).
    fn last_substep_poses(&self, h: f64) -> Vec<JointPoses> {
        self.joint_poses_by(|rb| {
            let com = to_d(rb.center_of_mass());
            if !rb.is_dynamic() {
                return (*rb.position(), com);
            }
            let com = com - h * to_d(rb.linvel());
            let angle = rb.rotation().angle() as f64 - (h * rb.angvel() as f64).atan();
            let rot = Rotation::new(angle as Real);
            let local_com = rb.mass_properties().local_mprops.local_com;
            let at = Vector::new(com.x as Real, com.y as Real);
            (Pose::from_parts(at - rot * local_com, rot), com)
        })
    }

    /// The joints of a step made in one call of n substeps, their impulses reconstructed from
    /// its last substep's and the previous step's (the module doc); keeps this step's last
    /// substep's for the next.
    pub(super) fn read_reconstructed_joints(&mut self) {
        let n = self.substeps() as f64;
        let poses = self.last_substep_poses(self.dt() / n);
        self.read_joints_scaled(1.0, Some(&poses));
        let now: Vec<SubstepImpulses> = self
            .snapshot
            .joints
            .iter()
            .map(SubstepImpulses::of)
            .collect();
        for (k, j) in self.snapshot.joints.iter_mut().enumerate() {
            // A weld made this step has no substep before it (its impulses are zero this step).
            let before = self.substeps_seen.last.get(k).copied().unwrap_or(now[k]);
            reconstruct(j, &before, n);
        }
        self.substeps_seen
            .record(now, n, self.settings.smooth_tolerance);
    }

    /// Keeps the impulses of a step's last call, just read, when that call was of one substep
    /// (`sub == 1`); a call of several leaves none to interpolate from (the next step is split).
    pub(super) fn keep_last_substep(&mut self, sub: usize) {
        if sub == 1 {
            let now = self
                .snapshot
                .joints
                .iter()
                .map(SubstepImpulses::of)
                .collect();
            let n = self.substeps() as f64;
            self.substeps_seen
                .record(now, n, self.settings.smooth_tolerance);
        } else {
            self.substeps_seen.clear();
        }
    }
}
