//! The analysis functions tests/suite/analysis/textbook.rs did not reach, each against a value derived by hand
//! (the derivation is in the comment; concepts.md ids and MK equation numbers name the formula).

use crate::common;

use common::assert_close;
use glam::DVec2;
use rigidlab::analysis::energy::{
    kinetic_energy, kinetic_energy_about_ic, moment_about, work_of_impulse, work_of_pair_impulse,
};
use rigidlab::analysis::impact::{measure_impact, pair_contact};
use rigidlab::analysis::kinematics::{
    acceleration_fd, angular_acceleration_fd, omega_from_angles, relative_point_velocity,
    slip_velocity,
};
use rigidlab::analysis::mass::{parallel_axis, slender_bar_inertia};
use rigidlab::analysis::momentum::{angular_momentum_about, angular_momentum_fixed_axis};
use rigidlab::analysis::Motion;
use rigidlab::snapshot::{ContactPoint, ContactState, Snapshot};

fn motion(com: DVec2, v: DVec2, omega: f64) -> Motion {
    Motion {
        position: com,
        angle: 0.0,
        com,
        velocity: v,
        omega,
    }
}

#[test]
fn accelerations_by_finite_differences() {
    // FD over one step: v_G from (1, 2) to (1.5, 1) m/s in 0.5 s gives a_G = (0.5, -1)/0.5 =
    // (1, -2) m/s^2; omega from 2 to 3 rad/s in 0.25 s gives alpha = 4 rad/s^2 (RK-3).
    let a = acceleration_fd(DVec2::new(1.0, 2.0), DVec2::new(1.5, 1.0), 0.5);
    assert_close!(a.x, 1.0);
    assert_close!(a.y, -2.0);
    assert_close!(angular_acceleration_fd(2.0, 3.0, 0.25), 4.0);
}

#[test]
fn omega_from_angles_is_exact_for_symplectic_euler_under_constant_alpha() {
    // Reference: an independent symplectic Euler run (w += alpha h; theta += w h, S substeps of
    // h = dt/S per step). With the angle steps of steps n and n+1, omega_from_angles must return
    // the engine's omega at the end of step n exactly (its derivation assumes constant alpha).
    let (alpha, dt, s) = (2.0, 0.1, 4usize);
    let h = dt / s as f64;
    let (mut w, mut th) = (0.3, 0.0);
    let mut ends = vec![(th, w)];
    for _ in 0..3 {
        for _ in 0..s {
            w += alpha * h;
            th += w * h;
        }
        ends.push((th, w));
    }
    let (d1, d2) = (ends[2].0 - ends[1].0, ends[3].0 - ends[2].0);
    assert_close!(omega_from_angles(d1, d2, dt, s), ends[2].1);
}

#[test]
fn slip_velocity_of_a_rolling_and_of_a_skidding_disc() {
    // Disc r = 0.5 m on fixed ground (body A at rest), contact at the origin, n = +y from the
    // ground to the disc, t = n.perp() = (-1, 0). Rolling (RK-8): v_G = (2, 0), omega = -v/r = -4,
    // so the contact point's velocity is v_G + omega k x (0, -0.5) = (2, 0) + (-4)(0.5, 0) = 0:
    // no slip. Skidding without turning: the contact point moves at (2, 0), slip = (2,0).(-1,0) = -2.
    let ground = motion(DVec2::new(0.0, -1.0), DVec2::ZERO, 0.0);
    let (p, n) = (DVec2::ZERO, DVec2::Y);
    let rolling = motion(DVec2::new(0.0, 0.5), DVec2::new(2.0, 0.0), -4.0);
    assert_close!(relative_point_velocity(&ground, &rolling, p).length(), 0.0);
    assert_close!(slip_velocity(&ground, &rolling, p, n), 0.0);
    let skidding = motion(DVec2::new(0.0, 0.5), DVec2::new(2.0, 0.0), 0.0);
    assert_close!(slip_velocity(&ground, &skidding, p, n), -2.0);
}

#[test]
fn work_of_a_blow_is_half_the_impulse_times_the_struck_points_speed() {
    // Slender bar m = 2 kg, L = 1 m along x, G at the origin, at rest; blow P = (0, 3) N s at the
    // end Q = (0.5, 0). Then v_G = P/m = (0, 1.5) m/s, omega = (r x P)/I_G = 0.5*3/(1/6) = 9 rad/s,
    // v_Q = v_G + omega k x r = (0, 1.5 + 4.5) = (0, 6). T after = 1/2 2 1.5^2 + 1/2 (1/6) 81 = 9 J,
    // and RM-11 (Kelvin): T = 1/2 P . v_Q = 1/2 * 3 * 6 = 9 J. work_of_impulse uses v_Q at the mean
    // of the step's ends, (0 + 6)/2, so it also gives 3 * 3 = 9 J.
    let i_g = slender_bar_inertia(2.0, 1.0);
    assert_close!(i_g, 1.0 / 6.0);
    let rest = motion(DVec2::ZERO, DVec2::ZERO, 0.0);
    let after = motion(DVec2::ZERO, DVec2::new(0.0, 1.5), 9.0);
    let (p, q) = (DVec2::new(0.0, 3.0), DVec2::new(0.5, 0.0));
    assert_close!(after.velocity_at(q).y, 6.0);
    assert_close!(kinetic_energy(2.0, after.velocity, i_g, after.omega), 9.0);
    assert_close!(work_of_impulse(p, q, 0.0, &rest, &after), 9.0);
}

#[test]
fn friction_work_on_a_sliding_block_is_the_kinetic_energy_lost() {
    // Block m = 2 kg sliding on fixed ground, v from 2 to 1.9 m/s over one step: the friction
    // impulse on it is m dv = (-0.2, 0) N s at the contact. Its work on the pair (WE-6 over a
    // step) is J . v_rel,mid = -0.2 * (2 + 1.9)/2 = -0.39 J, which is 1/2 m (1.9^2 - 2^2) = -0.39 J.
    let ground = motion(DVec2::new(0.0, -1.0), DVec2::ZERO, 0.0);
    let b0 = motion(DVec2::new(0.0, 0.1), DVec2::new(2.0, 0.0), 0.0);
    let b1 = motion(DVec2::new(0.0, 0.1), DVec2::new(1.9, 0.0), 0.0);
    let u = work_of_pair_impulse(
        DVec2::new(-0.2, 0.0),
        DVec2::ZERO,
        (&ground, &ground),
        (&b0, &b1),
    );
    assert_close!(u, -0.39);
    assert_close!(0.5 * 2.0 * (1.9f64.powi(2) - 4.0), -0.39);
}

#[test]
fn moment_of_a_force_about_a_point() {
    // F = (3, 0) N at P = (1, 2), about O = (1, 0): r_{P/O} = (0, 2), (r x F)_z = 0*0 - 2*3 = -6 N m
    // (clockwise, as the force above O pushing +x turns it).
    assert_close!(
        moment_about(
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 2.0),
            DVec2::new(3.0, 0.0)
        ),
        -6.0
    );
}

#[test]
fn measure_impact_reads_e_and_the_tangential_change_along_the_normal() {
    // A hits B along n = +x (A to B). Contact point velocities: A (2, 0.3) -> (0.5, 0.3), B at rest
    // -> (1.5, 0). Relative B over A along n: before 0 - 2 = -2, after 1.5 - 0.5 = 1, so
    // e = -1/-2 = 0.5 (IM-9). Along t = n.perp() = (0, 1): before 0 - 0.3 = -0.3, after -0.3
    // (unchanged: a smooth impact, IM-11).
    let p = DVec2::new(1.0, 0.0);
    let a0 = motion(DVec2::ZERO, DVec2::new(2.0, 0.3), 0.0);
    let a1 = motion(DVec2::ZERO, DVec2::new(0.5, 0.3), 0.0);
    let b0 = motion(DVec2::new(2.0, 0.0), DVec2::ZERO, 0.0);
    let b1 = motion(DVec2::new(2.0, 0.0), DVec2::new(1.5, 0.0), 0.0);
    let m = measure_impact((&a0, &a1), (&b0, &b1), p, DVec2::X, DVec2::new(1.5, 0.0));
    assert_close!(m.v_n_before, -2.0);
    assert_close!(m.v_n_after, 1.0);
    assert_close!(m.e, 0.5);
    assert_close!(m.v_t_before, -0.3);
    assert_close!(m.v_t_after, -0.3);
}

#[test]
fn eccentric_impact_of_a_falling_bar_on_a_ledge_conserves_h_about_the_ledge() {
    // RM-10 (JH P9.7.11): a horizontal slender bar m = 2 kg, L = 1 m falls flat at v = 3 m/s and
    // its end lands on a ledge C that it pivots about (plastic). Gravity is not impulsive, so
    // H_C is conserved: before H_C = (r_{G/C} x m v)_z with r_{G/C} = (-0.5, 0), m v = (0, -6):
    // (-0.5)(-6) - 0 = 3 N m s. After, fixed-axis rotation about C (6/16): I_C = 1/12 + 2 * 0.25 =
    // 2/3, omega = 3/(2/3) = 4.5 rad/s = 3 v/(2 L). KE: 1/2 2 9 = 9 J before, 1/2 (2/3) 4.5^2 =
    // 6.75 J after: 2.25 J lost (a quarter).
    let (m, l, v) = (2.0, 1.0, 3.0);
    let i_g = slender_bar_inertia(m, l);
    let (g, c) = (DVec2::ZERO, DVec2::new(0.5, 0.0));
    let h_before = angular_momentum_about(m, i_g, g, DVec2::new(0.0, -v), 0.0, c);
    assert_close!(h_before, 3.0);
    let i_c = parallel_axis(i_g, m, 0.5);
    assert_close!(i_c, 2.0 / 3.0);
    let omega = h_before / i_c;
    assert_close!(omega, 3.0 * v / (2.0 * l));
    // The state after: G turns about C at omega, v_G = omega k x r_{G/C} = 4.5 (0, -0.5).
    let v_after = DVec2::new(0.0, -0.5 * omega);
    assert_close!(angular_momentum_about(m, i_g, g, v_after, omega, c), 3.0);
    assert_close!(angular_momentum_fixed_axis(i_c, omega), 3.0);
    let t_after = kinetic_energy(m, v_after, i_g, omega);
    assert_close!(t_after, 6.75);
    assert_close!(kinetic_energy_about_ic(m, i_g, g, c, omega), 6.75);
    assert_close!(
        kinetic_energy(m, DVec2::new(0.0, -v), i_g, 0.0) - t_after,
        2.25
    );
}

#[test]
fn pair_contact_orients_the_normal_and_weights_the_point_by_impulse() {
    // One manifold, body1 = 1 (B), body2 = 0 (A), normal (0, -1) from B to A; points at x = 0
    // (impulse 1) and x = 3 (impulse 3). Asked for the pair (A, B): the normal from A to B is
    // (0, 1), the mean point is (0*1 + 3*3)/4 = 2.25, and the impulse on B is -(impulse on body2)
    // = -(0, -4) = (0, 4).
    let pt = |x: f64, j: f64| ContactPoint {
        point: DVec2::new(x, 0.0),
        distance: 0.0,
        normal_impulse: j,
        tangent_impulse: 0.0,
        arms: None,
        local: None,
    };
    let snap = Snapshot {
        step: 1,
        time: 0.1,
        dt: 0.1,
        substeps: 1,
        precision: rigidlab::snapshot::Precision::F32,
        gravity: DVec2::ZERO,
        bodies: Vec::new(),
        contacts: vec![ContactState {
            body1: 1,
            body2: 0,
            normal: DVec2::new(0.0, -1.0),
            points: vec![pt(0.0, 1.0), pt(3.0, 3.0)],
        }],
        joints: Vec::new(),
        springs: Vec::new(),
        couplings: Vec::new(),
        loads: Vec::new(),
        impulses: Vec::new(),
    };
    let c = pair_contact(&snap, 0, 1).expect("the pair touches");
    assert_close!(c.normal.y, 1.0);
    assert_close!(c.point.x, 2.25);
    assert_close!(c.impulse_on_b.y, 4.0);
    assert_close!(c.normal_impulse, 4.0);
    assert_eq!(c.points, 2);
    assert!(pair_contact(&snap, 0, 2).is_none());
}
