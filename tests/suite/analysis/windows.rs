//! Impulse-momentum over any window, the moment about the center of percussion, and the formulas
//! earlier tests reached only at zero (a_G = 0, omega = 0, dt = 0): each against a value derived
//! by hand in the comment (concepts.md ids and MK equation numbers name the formula).

use crate::common;

use common::assert_close;
use glam::DVec2;
use rigidlab::analysis::kinematics::point_acceleration;
use rigidlab::analysis::kinetics::{kinetic_moment_about, newton_euler_residual};
use rigidlab::analysis::mass::slender_bar_end_inertia;
use rigidlab::analysis::momentum::{
    angular_impulse_momentum_residual, angular_momentum_about, linear_impulse_momentum_residual,
    transfer_angular_momentum, ImpulseMomentumLedger,
};
use rigidlab::analysis::percussion::{
    center_of_percussion, moment_about_center_of_percussion, pivot_impulse, Blow,
};
use rigidlab::analysis::Motion;

#[test]
fn impulse_momentum_residuals_over_a_window() {
    // IM-2: a 2 kg puck at (1, 0) m/s pushed by F = (3, -1) N for 0.5 s: G goes from (2, 0) to
    // (3.5, -0.5) N s, the impulse is (1.5, -0.5) N s, the residual zero.
    let (g1, g2, j) = (
        DVec2::new(2.0, 0.0),
        DVec2::new(3.5, -0.5),
        DVec2::new(1.5, -0.5),
    );
    assert_eq!(linear_impulse_momentum_residual(g1, g2, j), DVec2::ZERO);
    // A solver that delivered 10% less impulse than it reported leaves -0.15 N s along x.
    let short = g1 + 0.9 * j;
    assert_close!(linear_impulse_momentum_residual(g1, short, j).x, -0.15);
    // IM-7: a disc with I_O = 0.5 kg m^2 spun up from 0 to 4 rad/s by a couple of 1 N m for 2 s:
    // H_O 0 -> 2 N m s, angular impulse 2 N m s.
    assert_close!(
        angular_impulse_momentum_residual(0.0, 0.5 * 4.0, 1.0 * 2.0),
        0.0
    );
    assert_close!(angular_impulse_momentum_residual(0.0, 1.9, 2.0), -0.1);
}

/// A 2 kg puck under F = (3, -1) N with a blow J = (0, 4) N s at the step ending at t = 0.5 s,
/// recorded step by step at dt = 0.1 s, exactly as the engine's impulse update does it:
/// G_{k+1} = G_k + F dt (+ J). Returns the ledger about O = (0, 0) and the positions of G.
fn pushed_puck(leak: impl Fn(usize) -> DVec2) -> ImpulseMomentumLedger {
    let (m, dt, f) = (2.0, 0.1, DVec2::new(3.0, -1.0));
    let o = DVec2::ZERO;
    let mut v = DVec2::new(1.0, 0.0);
    let mut r = DVec2::new(0.0, 1.0);
    let h = |r: DVec2, v: DVec2| angular_momentum_about(m, 0.1, r, v, 0.0, o);
    let mut ledger = ImpulseMomentumLedger::new(0.0, m * v, h(r, v));
    for k in 1..=10 {
        let blow = if k == 5 {
            DVec2::new(0.0, 4.0)
        } else {
            DVec2::ZERO
        };
        let impulse = f * dt + blow;
        // The moment about O of the step's impulse, taken at the step's start position: with
        // v_{k+1} = v_k + J/m and then r_{k+1} = r_k + v_{k+1} dt (symplectic Euler),
        // r_{k+1} x v_{k+1} = r_k x v_{k+1}, so H_O(k+1) - H_O(k) = r_k x J exactly.
        let moment = (r - o).perp_dot(impulse);
        v += (impulse + leak(k)) / m;
        r += v * dt;
        ledger.record(k as f64 * dt, impulse, moment, m * v, h(r, v));
    }
    ledger
}

#[test]
fn the_ledger_closes_over_every_window_of_an_exact_run() {
    let ledger = pushed_puck(|_| DVec2::ZERO);
    assert_eq!(ledger.instants(), 11);
    // [0.2, 0.7] s holds five steps: F dt 5 times plus the blow = (1.5, 3.5) N s.
    let w = ledger.window(0.2, 0.7).unwrap();
    assert_close!(w.t1, 0.2);
    assert_close!(w.t2, 0.7);
    assert_close!(w.linear_impulse.x, 1.5);
    assert_close!(w.linear_impulse.y, 3.5);
    assert_close!(w.delta_g.x, 1.5);
    assert_close!(w.delta_g.y, 3.5);
    assert!(w.linear_residual().length() < 1e-12);
    // H_O: the moment taken at the step's start position is exact for this update (see
    // `pushed_puck`).
    assert!(
        w.angular_residual().abs() < 1e-12,
        "{}",
        w.angular_residual()
    );
    // Ends between recorded instants go to the nearest one.
    let w2 = ledger.window(0.19, 0.71).unwrap();
    assert_eq!(w, w2);
    // Every window's worst is zero too.
    let worst = ledger.worst_windows();
    assert!(worst.linear.linear_residual().length() < 1e-12);
    assert!(worst.angular.angular_residual().abs() < 1e-12);
    assert!(ledger.window(0.5, 0.4).is_none());
}

#[test]
fn the_worst_window_is_found_between_the_extremes_of_the_residual() {
    // The engine gains +0.3 N s along x in step 3 and loses 0.5 N s in step 8 that the diagram
    // does not hold: the residual from the start is 0 up to 0.2 s, +0.3 from 0.3 s to 0.7 s and
    // -0.2 from 0.8 s. The windows from the start see at most 0.3; the worst window runs from an
    // instant in [0.3, 0.7] s to one in [0.8, 1.0] s (round-off picks which) and sees
    // r(t2) - r(t1) = -0.2 - 0.3 = -0.5.
    let ledger = pushed_puck(|k| match k {
        3 => DVec2::new(0.3, 0.0),
        8 => DVec2::new(-0.5, 0.0),
        _ => DVec2::ZERO,
    });
    let max_from_start = ledger.from_start().map(|w| w.linear_residual().length());
    let max_from_start = common::worst(max_from_start);
    assert_close!(max_from_start, 0.3);
    let worst = ledger.worst_windows().linear;
    assert_close!(worst.linear_residual().length(), 0.5);
    assert!(
        (0.3 - 1e-9..=0.7 + 1e-9).contains(&worst.t1),
        "{}",
        worst.t1
    );
    assert!(
        (0.8 - 1e-9..=1.0 + 1e-9).contains(&worst.t2),
        "{}",
        worst.t2
    );
    assert_close!(worst.linear_residual().x, -0.5);
}

#[test]
fn the_moment_about_the_center_of_percussion_vanishes_in_fixed_axis_rotation() {
    // CP-2 on a slender bar (m = 3 kg, L = 1.2 m) pinned at its end O = (0, 0), at 40 degrees from
    // the downward vertical, swinging at omega = 2.5 rad/s. By 6/4 about O:
    // I_O alpha = -m g (L/2) sin(theta), I_O = m L^2/3, so alpha = -3 g sin(theta)/(2 L).
    let (m, l, g, theta, omega) = (3.0, 1.2, 9.81, 40f64.to_radians(), 2.5);
    let e = DVec2::new(theta.sin(), -theta.cos()); // unit vector O -> G
    let r_g = 0.5 * l * e;
    let alpha = -3.0 * g * theta.sin() / (2.0 * l);
    // a_G = alpha k x r - omega^2 r (RK-10 at the pivot, a_O = 0).
    let a_g = point_acceleration(DVec2::ZERO, alpha, omega, r_g);
    // The pin reaction from 6/1: R = m a_G - m g_vec.
    let weight = DVec2::new(0.0, -m * g);
    let reaction = m * a_g - weight;
    let diagram = [
        Blow {
            impulse: weight,
            point: r_g,
            couple: 0.0,
        },
        Blow {
            impulse: reaction,
            point: DVec2::ZERO,
            couple: 0.0,
        },
    ];
    // Q lies on OG at q = 2L/3 = 0.8 m (CP-1).
    let q = center_of_percussion(DVec2::ZERO, r_g, m * l * l / 12.0, m).unwrap();
    assert_close!(q.length(), 0.8);
    let m_q = moment_about_center_of_percussion(q, diagram);
    // Every term is of order m g L = 35 N m; the sum is zero to round-off.
    assert!(m_q.abs() < 1e-12 * m * g * l, "sum M_Q = {m_q}");
    // Anywhere else on OG it is not: about G it is I_G alpha = m L^2/12 alpha.
    let m_g = moment_about_center_of_percussion(r_g, diagram);
    assert_close!(m_g, m * l * l / 12.0 * alpha, 1e-12);
    // And the resultant's moment about any P equals the kinetic moment (6/2).
    let p = DVec2::new(0.3, 0.7);
    assert_close!(
        moment_about_center_of_percussion(p, diagram),
        kinetic_moment_about(m, m * l * l / 12.0, alpha, r_g, a_g, p),
        1e-12
    );
}

#[test]
fn pivot_impulse_with_spin_and_a_finite_window() {
    // CP-3 generalized: the bar of the previous test hanging (r_G = (0, -0.6) m), already turning
    // at omega0 = 2 rad/s, struck at its tip (0, -1.2) m by P = (2, 0) N s over a window dt = 0.01 s.
    //   angular impulse about O: (r x P)_z = 0*0 - (-1.2)(2) = 2.4 N m s; I_O = m L^2/3 = 1.44 kg m^2
    //   d_omega = 2.4/1.44 = 5/3 rad/s, omega1 = 11/3 rad/s
    //   dv_G = d_omega k x r_G - omega1^2 r_G dt = (5/3)(0.6, 0) - (121/9)(0, -0.6)(0.01) = (1, 0.080667)
    //   J_O = m dv_G - P = (3 - 2, 0.242) = (1, 0.242) N s
    let (m, l) = (3.0, 1.2);
    let i_o = slender_bar_end_inertia(m, l);
    assert_close!(i_o, 1.44);
    let blows = [Blow {
        impulse: DVec2::new(2.0, 0.0),
        point: DVec2::new(0.0, -1.2),
        couple: 0.0,
    }];
    let (j_o, omega1) = pivot_impulse(
        m,
        i_o,
        DVec2::ZERO,
        DVec2::new(0.0, -0.6),
        2.0,
        &blows,
        0.01,
    );
    assert_close!(omega1, 11.0 / 3.0);
    assert_close!(j_o.x, 1.0);
    assert_close!(j_o.y, 3.0 * 121.0 / 9.0 * 0.6 * 0.01);
    // Struck at q = 0.8 m instead, the tangential reaction vanishes and only the centripetal
    // part is left: d_omega = 1.6/1.44 = 10/9, omega1 = 28/9, J_O = (0, m omega1^2 0.6 dt).
    let at_q = [Blow {
        impulse: DVec2::new(2.0, 0.0),
        point: DVec2::new(0.0, -0.8),
        couple: 0.0,
    }];
    let (j_q, w1) = pivot_impulse(m, i_o, DVec2::ZERO, DVec2::new(0.0, -0.6), 2.0, &at_q, 0.01);
    assert_close!(w1, 28.0 / 9.0);
    assert!(j_q.x.abs() < 1e-12, "{}", j_q.x);
    assert_close!(j_q.y, 3.0 * (28.0f64 / 9.0).powi(2) * 0.6 * 0.01);
}

#[test]
fn point_acceleration_with_a_moving_mass_center() {
    // RK-10: a_P = a_G + alpha k x r - omega^2 r. a_G = (1, -2), alpha = 3, omega = 2, r = (0.5, 0.25):
    // k x r = (-0.25, 0.5); alpha k x r = (-0.75, 1.5); -omega^2 r = (-2, -1);
    // a_P = (1 - 0.75 - 2, -2 + 1.5 - 1) = (-1.75, -1.5).
    let a = point_acceleration(DVec2::new(1.0, -2.0), 3.0, 2.0, DVec2::new(0.5, 0.25));
    assert_close!(a.x, -1.75);
    assert_close!(a.y, -1.5);
}

#[test]
fn newton_euler_residual_reads_a_missing_force() {
    // 6/1 over one step of 0.01 s: a 2 kg body (I_G = 0.5) goes from v = (1, 0), omega = 0 to
    // v = (1.02, -0.1), omega = 0.3: m a_G = 2 (2, -10) = (4, -20) N, I_G alpha = 0.5 * 30 = 15 N m.
    // The diagram holds only gravity (0, -19.62) N (impulse (0, -0.1962) N s) and no moment: the
    // residual is sum F - m a_G = (-4, 0.38) N and sum M_G - I_G alpha = -15 N m.
    let before = Motion {
        velocity: DVec2::new(1.0, 0.0),
        ..Default::default()
    };
    let after = Motion {
        velocity: DVec2::new(1.02, -0.1),
        omega: 0.3,
        ..Default::default()
    };
    let (df, dm) = newton_euler_residual(
        2.0,
        0.5,
        &before,
        &after,
        DVec2::new(0.0, -0.1962),
        0.0,
        0.01,
    );
    assert_close!(df.x, -4.0, 1e-9);
    assert_close!(df.y, 0.38, 1e-9);
    assert_close!(dm, -15.0, 1e-9);
}

#[test]
fn angular_momentum_moves_with_the_linear_momentum() {
    // 6/15: H_{O'} = H_O + (r_{O/O'} x G)_z. A 4 kg body at G = (1, 1) with v = (0.5, 0) and
    // omega = 2, I_G = 0.25: about O = (0, 0), H_O = 0.5 + (1*0 - 1*2) = -1.5 N m s; about
    // O' = (2, 0): r_{O/O'} = (-2, 0), G = (2, 0), so H_O' = -1.5 + 0 = -1.5... and directly
    // 0.5 + ((-1)(0) - (1)(2)) = -1.5. About O'' = (0, 3): r_{O/O''} = (0, -3):
    // (0)(0) - (-3)(2) = 6, H = 4.5; directly 0.5 + (1*0 - (-2)(2)) = 4.5.
    let (m, i_g, r_g, v, w) = (4.0, 0.25, DVec2::new(1.0, 1.0), DVec2::new(0.5, 0.0), 2.0);
    let h_o = angular_momentum_about(m, i_g, r_g, v, w, DVec2::ZERO);
    assert_close!(h_o, -1.5);
    let g = m * v;
    assert_close!(
        transfer_angular_momentum(h_o, DVec2::ZERO, DVec2::new(2.0, 0.0), g),
        -1.5
    );
    assert_close!(
        transfer_angular_momentum(h_o, DVec2::ZERO, DVec2::new(0.0, 3.0), g),
        4.5
    );
    assert_close!(
        angular_momentum_about(m, i_g, r_g, v, w, DVec2::new(0.0, 3.0)),
        4.5
    );
}

/// A ledger given per-step rounding bounds discounts them window by window: a steady leak of
/// 1e-3 N s per step (a rounding bias) inside a bound of 1e-3 per step is no residual, a leak of
/// 3e-3 is 2e-3 per step beyond it, over the whole run (10 steps: 2e-2 N s).
#[test]
fn a_ledger_discounts_rounding_window_by_window() {
    for (leak, beyond) in [(1e-3, 0.0), (3e-3, 2e-2)] {
        let mut ledger = ImpulseMomentumLedger::new(0.0, DVec2::ZERO, 0.0);
        let mut g = DVec2::ZERO;
        for k in 1..=10 {
            // Impulse 0.1 N s per step along x; the momentum gains it plus the leak.
            g += DVec2::new(0.1 + leak, 0.0);
            ledger.record_rounded(
                0.1 * k as f64,
                DVec2::new(0.1, 0.0),
                0.0,
                g,
                0.0,
                (1e-3, 0.0),
            );
        }
        let w = ledger.worst_windows_beyond_rounding().linear;
        assert!(
            (w.linear_beyond_rounding() - beyond).abs() < 1e-12,
            "leak {leak}: {w:?}"
        );
        // Without the bounds, the whole run's residual is 10 leaks.
        let raw = ledger.worst_windows().linear.linear_residual().length();
        assert!((raw - 10.0 * leak).abs() < 1e-12, "{raw}");
    }
}

/// The worst windows beyond rounding, found in O(n) per direction, against every pair of
/// instants tried one by one (the brute force the ledger used to run, O(n^2)): the angular
/// window exactly, the linear one short of the true excess by at most 7.5e-5 of that window's
/// residual (256 directions: 1 - cos(pi / 256) = 7.5e-5), never above it.
#[test]
fn worst_windows_beyond_rounding_match_every_pair_tried() {
    // A deterministic pseudo-random walk (64-bit LCG): residuals that wander in both axes, with
    // rounding bounds of the same order, so the worst window is neither the whole run nor one step.
    let mut state = 0x2545F4914F6CDD1Du64;
    let mut rand = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for trial in 0..20 {
        let n = 50 + 20 * trial;
        let mut ledger = ImpulseMomentumLedger::new(0.0, DVec2::ZERO, 0.0);
        let (mut g, mut h) = (DVec2::ZERO, 0.0);
        for k in 1..=n {
            let impulse = DVec2::new(rand(), rand());
            let moment = rand();
            g += impulse + 0.01 * DVec2::new(rand(), rand());
            h += moment + 0.01 * rand();
            let rounding = (0.004 * (rand() + 0.5), 0.004 * (rand() + 0.5));
            ledger.record_rounded(0.01 * k as f64, impulse, moment, g, h, rounding);
        }
        let (mut lin, mut ang, mut lin_residual) = (f64::NEG_INFINITY, f64::NEG_INFINITY, 0.0);
        for a in 0..=n {
            for b in a + 1..=n {
                let w = ledger.window(0.01 * a as f64, 0.01 * b as f64).unwrap();
                let l = w.linear_residual().length() - w.rounding_g;
                if l > lin {
                    (lin, lin_residual) = (l, w.linear_residual().length());
                }
                ang = ang.max(w.angular_residual().abs() - w.rounding_h);
            }
        }
        let fast = ledger.worst_windows_beyond_rounding();
        let fast_lin = fast.linear.linear_residual().length() - fast.linear.rounding_g;
        let fast_ang = fast.angular.angular_residual().abs() - fast.angular.rounding_h;
        assert!(
            (fast_ang - ang).abs() <= 1e-12,
            "trial {trial}: angular {fast_ang} against every pair's {ang}"
        );
        assert!(
            fast_lin <= lin + 1e-12 && fast_lin >= lin - 7.5e-5 * lin_residual,
            "trial {trial}: linear {fast_lin} against every pair's {lin} (residual {lin_residual})"
        );
    }
}

/// A ledger of G alone (a check about no point) finds the same linear windows as one that keeps
/// H_O too, with rounding or without, and keeps no angular part.
#[test]
fn a_ledger_of_g_alone_finds_the_same_linear_windows() {
    let (m, dt) = (2.0, 0.1);
    let mut full = ImpulseMomentumLedger::new(0.0, DVec2::new(m, 0.0), 0.5);
    let mut linear = ImpulseMomentumLedger::linear_only(0.0, DVec2::new(m, 0.0), 4);
    let mut g = DVec2::new(m, 0.0);
    for k in 1..=30 {
        // A leak that comes and goes, so the worst window is inside the run.
        let leak = DVec2::new((k as f64 * 0.7).sin(), (k as f64 * 0.3).cos()) * 1e-3;
        let impulse = DVec2::new(0.3, -0.2) * dt;
        g += impulse + leak;
        let rounding = (1e-4, 2e-4);
        full.record_rounded(
            k as f64 * dt,
            impulse,
            0.01 * k as f64,
            g,
            0.5 + 0.02 * k as f64,
            rounding,
        );
        linear.record_rounded(
            k as f64 * dt,
            impulse,
            0.01 * k as f64,
            g,
            0.5 + 0.02 * k as f64,
            rounding,
        );
    }
    assert_eq!(linear.instants(), full.instants());
    for (a, b) in [
        (full.worst_windows(), linear.worst_windows()),
        (
            full.worst_windows_beyond_rounding(),
            linear.worst_windows_beyond_rounding(),
        ),
    ] {
        let lin = |w: &rigidlab::analysis::momentum::WindowBalance| {
            (w.t1, w.t2, w.delta_g, w.linear_impulse, w.rounding_g)
        };
        assert_eq!(lin(&a.linear), lin(&b.linear));
        assert_eq!(b.angular.angular_residual(), 0.0);
        assert_eq!(b.angular.rounding_h, 0.0);
    }
    assert_eq!(
        full.since_start().linear_residual(),
        linear.since_start().linear_residual()
    );
    assert_eq!(linear.since_start().delta_h, 0.0);
    let (w, v) = (
        full.window(0.5, 2.2).unwrap(),
        linear.window(0.5, 2.2).unwrap(),
    );
    assert_eq!(
        (w.delta_g, w.linear_impulse, w.rounding_g),
        (v.delta_g, v.linear_impulse, v.rounding_g)
    );
}
