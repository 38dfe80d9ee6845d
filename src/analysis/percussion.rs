//! The center of percussion of a body in fixed-axis rotation (concepts.md section 8, MK Art. 6/4).

use super::{cross, k_cross};
use glam::DVec2;

/// Distance from the pivot O to the center of percussion Q along OG: q = I_O/(m r_bar) =
/// k_O^2 / r_bar (CP-1). `None` when r_bar = 0: rotation about G has no Q (a pure couple).
///
/// # Examples
///
/// A uniform bar of length l pinned at its end: q = (m l^2/3) / (m l/2) = 2l/3 (JH P9.7.13;
/// for l = 1.2 m the center of percussion is 0.8 m below the pin).
/// ```
/// use rigidlab::analysis::percussion::center_of_percussion_distance;
/// let (m, l) = (3.0, 1.2);
/// let q = center_of_percussion_distance(m * l * l / 3.0, m, l / 2.0).unwrap();
/// assert!((q - 0.8).abs() < 1e-12);
/// assert_eq!(center_of_percussion_distance(1.0, m, 0.0), None); // turning about G
/// ```
pub fn center_of_percussion_distance(i_o: f64, m: f64, r_bar: f64) -> Option<f64> {
    if r_bar > 0.0 && m > 0.0 {
        Some(i_o / (m * r_bar))
    } else {
        None
    }
}

/// The center of percussion Q in world coordinates, on the line from the pivot O through G
/// at q = (I_G + m r_bar^2)/(m r_bar) from O (CP-1 with MP-2).
pub fn center_of_percussion(o: DVec2, r_g: DVec2, i_g: f64, m: f64) -> Option<DVec2> {
    let d = r_g - o;
    let r_bar = d.length();
    let i_o = super::mass::parallel_axis(i_g, m, r_bar);
    center_of_percussion_distance(i_o, m, r_bar).map(|q| o + d / r_bar * q)
}

/// The moment about the center of percussion Q of the forces on a body in rotation about a
/// fixed pivot (CP-2): sum M_Q = sum (r_{P/Q} x F)_z + couples. The resultant of all the forces,
/// the pin reaction included, passes through Q, so this is zero at every instant: about O it is
/// I_O alpha (6/4), and the resultant m a_G has its tangential part m r_bar alpha acting at
/// q = I_O/(m r_bar) along OG and its normal part along OG itself. Works for impulses as well
/// (the angular impulse about Q).
pub fn moment_about_center_of_percussion(q: DVec2, forces: impl IntoIterator<Item = Blow>) -> f64 {
    forces
        .into_iter()
        .map(|f| cross(f.point - q, f.impulse) + f.couple)
        .sum()
}

/// One impulse (or force) acting on the pinned body during a window: J at world point p, plus a couple.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blow {
    pub impulse: DVec2,
    pub point: DVec2,
    pub couple: f64,
}

/// The pivot's reaction impulse on a body in rotation about the fixed pivot O over a window
/// of length `dt` that starts with the blows (CP-3, generalized from JH P9.7.13):
/// - angular impulse about O (the pivot has no moment there, 6/17): I_O d_omega = sum (r_{P/O} x J) + couples;
/// - linear impulse (6/12): m dv_G = sum J + J_O, with dv_G = d_omega k x r_{G/O} - omega_1^2 r_{G/O} dt
///   (the tangential jump plus the centripetal part over the window, PL-8).
///
/// Returns (J_O, omega_1). With a single blow perpendicular to OG at distance h from O on a body at
/// rest, J_O = P (m r_bar h / I_O - 1), zero exactly at h = q (the center of percussion).
pub fn pivot_impulse(
    m: f64,
    i_o: f64,
    o: DVec2,
    r_g: DVec2,
    omega0: f64,
    blows: &[Blow],
    dt: f64,
) -> (DVec2, f64) {
    let r = r_g - o;
    let angular: f64 = blows
        .iter()
        .map(|b| cross(b.point - o, b.impulse) + b.couple)
        .sum();
    let d_omega = angular / i_o;
    let omega1 = omega0 + d_omega;
    let dv_g = k_cross(d_omega, r) - omega1 * omega1 * r * dt;
    let sum_j: DVec2 = blows.iter().map(|b| b.impulse).sum();
    (m * dv_g - sum_j, omega1)
}

/// A body in rotation about the fixed pivot O strikes a fixed obstacle at C along the normal
/// `n` (a pinned bar striking a peg). The body has one degree of freedom, so e at the contact
/// point fixes the rebound (IM-12: v_n' = -e v_n, with v_n = omega (k x r_{C/O}) . n), and
/// omega' = -e omega0; the obstacle's impulse lambda n then follows from the angular impulse
/// about O, where the pivot has no moment (6/17: I_O (omega' - omega0) = lambda (r_{C/O} x n)),
/// and the pivot's from the linear impulse ([`pivot_impulse`], CP-3).
///
/// Neither angular momentum is conserved in general: about O the obstacle's impulse has a
/// moment, about C the pivot's, except where the pivot's vanishes (C at the center of
/// percussion, the normal perpendicular to OG, CP-3). `contact`: (C, n). Returns (lambda n,
/// J_O, omega'); None when the normal passes through O (the obstacle cannot stop the body's
/// turning).
pub fn strike_on_fixed_obstacle(
    m: f64,
    i_o: f64,
    o: DVec2,
    r_g: DVec2,
    omega0: f64,
    (c, n): (DVec2, DVec2),
    e: f64,
) -> Option<(DVec2, DVec2, f64)> {
    let arm = cross(c - o, n);
    if arm.abs() <= 1e-12 * (c - o).length().max(1e-12) {
        return None;
    }
    let omega1 = -e * omega0;
    let lambda = i_o * (omega1 - omega0) / arm;
    let blow = Blow {
        impulse: lambda * n,
        point: c,
        couple: 0.0,
    };
    let (j_o, w1) = pivot_impulse(m, i_o, o, r_g, omega0, &[blow], 0.0);
    Some((blow.impulse, j_o, w1))
}
