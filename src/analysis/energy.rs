//! Work and energy (concepts.md sections 3 and 9): kinetic energy in its textbook forms,
//! potential energy, power, the work of a step's impulse, and the work-energy ledger.

use super::{cross, Motion};
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;

/// Kinetic energy of a translating body: T = 1/2 m v^2 (6/7, WE-8).
pub fn kinetic_energy_translation(m: f64, v: DVec2) -> f64 {
    0.5 * m * v.length_squared()
}

/// Kinetic energy in fixed-axis rotation about O: T = 1/2 I_O omega^2 (6/8).
pub fn kinetic_energy_fixed_axis(i_o: f64, omega: f64) -> f64 {
    0.5 * i_o * omega * omega
}

/// Kinetic energy in general plane motion: T = 1/2 m v_G^2 + 1/2 I_G omega^2 (6/9, the König theorem).
///
/// # Examples
///
/// The 2 kg disc (I_G = 0.25 kg m^2) rolling at 2 m/s, omega = -4 rad/s:
/// T = 1/2 (2)(4) + 1/2 (0.25)(16) = 6 J, which is 1/2 I_C omega^2 about its contact point (6/10).
/// ```
/// use glam::DVec2;
/// use rigidlab::analysis::energy::{kinetic_energy, kinetic_energy_about_ic};
/// let t = kinetic_energy(2.0, DVec2::new(2.0, 0.0), 0.25, -4.0);
/// assert_eq!(t, 6.0);
/// assert_eq!(kinetic_energy_about_ic(2.0, 0.25, DVec2::new(0.0, 0.5), DVec2::ZERO, -4.0), t);
/// ```
pub fn kinetic_energy(m: f64, v_g: DVec2, i_g: f64, omega: f64) -> f64 {
    0.5 * m * v_g.length_squared() + 0.5 * i_g * omega * omega
}

/// 6/9 for a body of a snapshot (its mass properties as the engine holds them).
pub fn body_kinetic_energy(b: &BodyState) -> f64 {
    kinetic_energy(b.mass, b.velocity, b.inertia, b.omega)
}

/// Rate of change of the kinetic energy in general plane motion, 6/9 differentiated:
/// dT/dt = m a_G . v_G + I_G alpha omega (the left side of the power balance, RE-11).
pub fn kinetic_energy_rate(
    m: f64,
    v_g: DVec2,
    a_g: DVec2,
    i_g: f64,
    omega: f64,
    alpha: f64,
) -> f64 {
    m * a_g.dot(v_g) + i_g * alpha * omega
}

/// The angular speed of a body in fixed-axis rotation about O after the forces on it did work U,
/// from omega_1: work-energy (WE-9) with T = 1/2 I_O omega^2 (6/8),
/// |omega_2| = sqrt(omega_1^2 + 2 U / I_O); zero when U takes more than T_1 (the body stops).
pub fn fixed_axis_speed_after_work(i_o: f64, omega1: f64, work: f64) -> f64 {
    (omega1 * omega1 + 2.0 * work / i_o).max(0.0).sqrt()
}

/// Kinetic energy about the instantaneous center C: T = 1/2 I_C omega^2 with
/// I_C = I_G + m |r_G - r_C|^2 (6/10 with MP-2).
pub fn kinetic_energy_about_ic(m: f64, i_g: f64, r_g: DVec2, r_c: DVec2, omega: f64) -> f64 {
    let i_c = super::mass::parallel_axis(i_g, m, (r_g - r_c).length());
    0.5 * i_c * omega * omega
}

/// Gravitational potential energy V_g = -m g . r_G (WE-13: V_g = W y with y up when g = (0, -g)).
pub fn gravity_potential(m: f64, gravity: DVec2, r_g: DVec2) -> f64 {
    -m * gravity.dot(r_g)
}

/// Elastic potential energy of a linear spring, V_e = 1/2 k x^2 (WE-13).
pub fn spring_potential(k: f64, x: f64) -> f64 {
    0.5 * k * x * x
}

/// The mass data a scene total uses for one body: m, I_G and where G is. The engine's are the
/// snapshot's own ([`engine_mass`]); the studies and checks may use the level's textbook values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMass {
    pub m: f64,
    pub i_g: f64,
    pub r_g: DVec2,
}

/// A body's mass data as the engine holds it (the snapshot's m, I_G and G).
pub fn engine_mass(_: usize, b: &BodyState) -> BodyMass {
    BodyMass {
        m: b.mass,
        i_g: b.inertia,
        r_g: b.com,
    }
}

/// T of a scene: 6/9 summed over its bodies (RE-3), with each body's mass data from `mass`.
pub fn system_kinetic_energy(s: &Snapshot, mass: impl Fn(usize, &BodyState) -> BodyMass) -> f64 {
    s.bodies
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let bm = mass(i, b);
            kinetic_energy(bm.m, b.velocity, bm.i_g, b.omega)
        })
        .sum()
}

/// V_g of a scene: WE-13 summed over its bodies, datum through the origin.
pub fn system_gravity_potential(s: &Snapshot, mass: impl Fn(usize, &BodyState) -> BodyMass) -> f64 {
    s.bodies
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let bm = mass(i, b);
            gravity_potential(bm.m, s.gravity, bm.r_g)
        })
        .sum()
}

/// V_e of a scene: WE-13 summed over its springs, as the snapshot reports each.
pub fn system_spring_potential(s: &Snapshot) -> f64 {
    s.springs.iter().map(|sp| sp.energy).sum()
}

/// E = T + V_g + V_e of a scene (WE-14).
pub fn system_mechanical_energy(
    s: &Snapshot,
    mass: impl Fn(usize, &BodyState) -> BodyMass + Copy,
) -> f64 {
    system_kinetic_energy(s, mass) + system_gravity_potential(s, mass) + system_spring_potential(s)
}

/// Power of a force F at a point moving with v_P plus a couple M on a body turning at omega:
/// P = F . v_P + M omega (WE-10, RE-8).
pub fn power(force: DVec2, v_p: DVec2, couple: f64, omega: f64) -> f64 {
    force.dot(v_p) + couple * omega
}

/// Work of an impulse J applied over a step at world point p (plus an angular impulse `couple`),
/// with the body's states at the two ends of the step: U = J . v_P,mid + couple omega_mid, where
/// v_P,mid = v_G,mid + omega_mid k x r_{P/G}.
///
/// Why the mean velocity: for a rigid body, 1/2 m (v1^2 - v0^2) = m (v1 - v0) . (v0 + v1)/2 and
/// 1/2 I (w1^2 - w0^2) = I (w1 - w0)(w0 + w1)/2, so with these works T1 - T0 equals the sum of the
/// step's works exactly whenever the step's impulses balance m dv and I dw (WE-9 per step).
pub fn work_of_impulse(j: DVec2, p: DVec2, couple: f64, before: &Motion, after: &Motion) -> f64 {
    let mid = Motion::mid(before, after);
    j.dot(mid.velocity_at(p)) + couple * mid.omega
}

/// Work of an impulse J acting with lever arm r_{P/G} from the mass center (plus an angular impulse):
/// U = J . (v_G,mid + omega_mid k x r_{P/G}) + couple omega_mid. With the arms the step's moments
/// were taken with, the works of all a body's impulses add up to T1 - T0 exactly when
/// sum J = m dv_G and sum (r x J) + couples = I_G d_omega (see [`work_of_impulse`]).
pub fn work_of_impulse_with_arm(
    j: DVec2,
    arm: DVec2,
    couple: f64,
    before: &Motion,
    after: &Motion,
) -> f64 {
    let mid = Motion::mid(before, after);
    j.dot(super::kinematics::point_velocity(
        mid.velocity,
        mid.omega,
        arm,
    )) + couple * mid.omega
}

/// Work of one contact point's impulse on a body over a step, with the solver's lever arm
/// `arm` from G: the friction part `j_t` at the step's mean velocities `mean` (v_G, omega), as
/// [`work_of_impulse_with_arm`]; the normal part `j_n` too when the contact is new (an impact:
/// the mean velocity makes it exact for an impulsive change), but for a contact that already
/// pushed the step before (a body resting, rolling or sliding on it) at the velocities of the
/// body's displacement over the step, `moved` = (dr_G / dt, dtheta / dt) (WE-1: U = F . dr).
///
/// Why: rapier reports a round body resting on a soft contact with a step-end velocity of
/// about -g h while its position stays (a disc rolling on a floor: v_y -0.0102 m/s at h =
/// 1/960 s, y constant to 1e-8 m), so at the mean velocity the floor's normal force did work
/// the positions never show (0.15 J of a 3 J ledger for a disc sliding to rolling). The
/// displacement of the material point that is at the contact mid-step is dr_G + 2 sin(dtheta/2)
/// k x arm, which dtheta k x arm gives to second order.
pub fn work_of_contact_impulse(
    j_n: DVec2,
    j_t: DVec2,
    arm: DVec2,
    mean: (DVec2, f64),
    moved: Option<(DVec2, f64)>,
) -> f64 {
    let at = |(v, w): (DVec2, f64)| super::kinematics::point_velocity(v, w, arm);
    let v_mean = at(mean);
    j_t.dot(v_mean) + j_n.dot(moved.map_or(v_mean, at))
}

/// Work of a friction impulse on one body over a step: the friction force on that body dotted
/// with the velocity of that body's material point at the contact (WE-1 with dr of the point the
/// force acts at), U = J_t . (v_G,mid + omega_mid k x arm), `arm` from G to the point (the
/// solver's lever arm), `mean` = (v_G, omega) at the step's mean. Summed over the steps, the
/// friction work on the body. For a body on a fixed floor it is the Coulomb loss -mu N s (WE-6);
/// for one of two moving bodies it may be positive (a belt carrying a block forward), and the
/// two bodies' works add up to the pair's loss ([`friction_pair_loss`]).
pub fn friction_work_on_body(j_t: DVec2, arm: DVec2, mean: (DVec2, f64)) -> f64 {
    j_t.dot(super::kinematics::point_velocity(mean.0, mean.1, arm))
}

/// The work a pair's friction does on both bodies together over a step, J_t . v_slip: J_t the
/// friction impulse on body B, v_slip the velocity of B's contact point relative to A's
/// (WE-6: never positive under Coulomb's law, U_f = -mu_k N s with s the slip distance).
pub fn friction_pair_loss(j_t_on_b: DVec2, v_slip_b_over_a: DVec2) -> f64 {
    j_t_on_b.dot(v_slip_b_over_a)
}

/// Coulomb's friction work on one body over a step (WE-6 with WE-1): the kinetic friction
/// mu N opposes the slip of the body's contact point relative to the other's, so on the body
/// U = -mu j_n sgn(slip) (v_P . t), with j_n the step's normal impulse, `slip` the slip velocity
/// of the body over the other along t and `v_p_t` the body's contact point velocity along t.
/// None while the contact does not slip (|slip| <= `slip_floor`) on a moving other body: static
/// friction has no Coulomb law to give its force. On a fixed other body v_P . t = slip, so the
/// work is -mu j_n |slip| (zero while rolling).
pub fn coulomb_friction_work_on_body(
    mu: f64,
    j_n: f64,
    slip: f64,
    v_p_t: f64,
    other_fixed: bool,
    slip_floor: f64,
) -> Option<f64> {
    if other_fixed {
        return Some(-mu * j_n.max(0.0) * slip.abs());
    }
    (slip.abs() > slip_floor).then(|| -mu * j_n.max(0.0) * slip.signum() * v_p_t)
}

/// Mechanical efficiency over an interval, energy form (WE-12): the energy a mechanism delivers
/// to its output over the energy its input puts in, e = U_out / U_in (e < 1 where friction or
/// damping takes some). NaN when the input did no work.
pub fn mechanical_efficiency(u_out: f64, u_in: f64) -> f64 {
    if u_in == 0.0 {
        f64::NAN
    } else {
        u_out / u_in
    }
}

/// Work a linear viscous damper does on the bodies over a step, U = -integral of c (dL/dt)^2 dt
/// (WE-1 with the damper force c dL/dt opposing the stretching: always negative), by the
/// trapezoid rule from the rates dL/dt at the step's start and end: second order in the step.
///
/// (Until 2026-12-06 it took the step's mean rate, U = -c dL^2 / dt: a mean squared is less
/// than the mean of the squares, and the difference summed to a boundary term of the order of
/// c h v0^2, 8e-3 of the work on a damped pair at 1 ms.)
///
/// # Examples
///
/// A damper (c = 4 N s/m) whose rate falls from 1 to 0.5 m/s over 1 ms:
///
/// ```
/// use rigidlab::analysis::energy::damper_work;
/// let u = damper_work(4.0, 1.0, 0.5, 1e-3);
/// assert!((u - (-4.0 * 0.5 * (1.0 + 0.25) * 1e-3)).abs() < 1e-15);
/// ```
pub fn damper_work(c: f64, rate0: f64, rate1: f64, dt: f64) -> f64 {
    -c * 0.5 * (rate0 * rate0 + rate1 * rate1) * dt
}

/// Work of a pair of equal and opposite impulses (J on body B at p, -J on body A at p):
/// U = J . v_{B/A,mid}. This is the energy a contact dissipates (friction, an inelastic impact).
pub fn work_of_pair_impulse(
    j: DVec2,
    p: DVec2,
    a: (&Motion, &Motion),
    b: (&Motion, &Motion),
) -> f64 {
    work_of_impulse(j, p, 0.0, b.0, b.1) - work_of_impulse(j, p, 0.0, a.0, a.1)
}

/// Moment of a force about a point O: M_O = (r_{P/O} x F)_z.
pub fn moment_about(o: DVec2, p: DVec2, f: DVec2) -> f64 {
    cross(p - o, f)
}

/// The work-energy ledger T1 + V1 + U'_{1-2} = T2 + V2 (WE-14, RE-7 in MK's form): U' is the
/// work of every force except weight and springs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Ledger {
    /// Kinetic energy T, J.
    pub kinetic: f64,
    /// Gravitational potential V_g, J.
    pub gravity: f64,
    /// Elastic potential V_e, J.
    pub elastic: f64,
    /// Work of the non-conservative forces since the start, U', J.
    pub work_nc: f64,
}

impl Ledger {
    /// Mechanical energy E = T + V_g + V_e.
    pub fn mechanical(&self) -> f64 {
        self.kinetic + self.gravity + self.elastic
    }

    /// E - U': constant when the ledger balances (E(0) by WE-14).
    pub fn balance(&self) -> f64 {
        self.mechanical() - self.work_nc
    }
}
