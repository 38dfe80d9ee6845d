//! A body whose mass center G rides a circular path: the normal force a circular track gives it
//! (PN-2 along the path's normal), the radius of G's path for a disc on a circular track, the
//! least speed at the top of a vertical loop, and where a body leaves a smooth convex circle.
//!
//! PN-2 resolves Newton's law along the normal of G's path, toward its center of curvature:
//! sum F_n = m a_n = m v^2 / rho, v the speed of G along the path. On a track that pushes G
//! toward the center (the inside of a ring, a loop, a bowl) the track's normal force N adds to
//! the other forces' normal part; on one that pushes away from it (the outside of a cylinder, a
//! hump) it subtracts. With gravity alone besides the track and theta the angle of G from the
//! circle's lowest point:
//!   inside  N = m v^2 / rho + m g cos(theta),
//!   outside N = m g cos(theta') - m v^2 / rho, theta' from the highest point.
//! Friction at a round body's contact is tangent to the track, at right angles to the radius
//! through G, so it does not enter (a disc rolling inside a ring: N depends only on v_G and
//! theta).

use glam::DVec2;

/// Which side of a circular track G rides: `Inside` the circle (the track pushes G toward the
/// center: a ring, a loop, a bowl) or `Outside` it (the track pushes G away: a cylinder, a hump).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathSide {
    Inside,
    Outside,
}

/// The radius of G's path for a disc of radius `r` rolling or sliding on a circular track of
/// radius `track_radius`: R - r inside it, R + r outside it (G stays at r from the track, along
/// the radius).
pub fn disc_path_radius(track_radius: f64, r: f64, side: PathSide) -> f64 {
    match side {
        PathSide::Inside => track_radius - r,
        PathSide::Outside => track_radius + r,
    }
}

/// The normal force of a circular track on a body whose mass center G moves on a circle of
/// radius `rho` about the track's center `center`, from PN-2 along the path's normal:
/// sum F_n = m v^2 / rho with v the speed of G along the path (the part of `v_g` at right
/// angles to the radius) and sum F_n = (+-N) + F . e_n, e_n the unit vector from G toward the
/// center and F the resultant of the other forces (`applied`: the weight m g, and any load). So
///   `Inside`:  N = m v^2 / rho - F . e_n,
///   `Outside`: N = F . e_n - m v^2 / rho,
/// positive when the track pushes (a negative N is a pull the track cannot give: the body has
/// left it). Returns N and the force's direction on the body (e_n inside, -e_n outside); None
/// where G sits at the center (no normal direction).
pub fn normal_force_on_circular_path(
    m: f64,
    g_pos: DVec2,
    v_g: DVec2,
    center: DVec2,
    rho: f64,
    applied: DVec2,
    side: PathSide,
) -> Option<(f64, DVec2)> {
    let e_n = (center - g_pos).try_normalize()?;
    let v_t = v_g.dot(e_n.perp());
    let centripetal = m * v_t * v_t / rho;
    Some(match side {
        PathSide::Inside => (centripetal - applied.dot(e_n), e_n),
        PathSide::Outside => (applied.dot(e_n) - centripetal, -e_n),
    })
}

/// The least speed of G at the top of a vertical loop of path radius `rho` that keeps the
/// track pushing there: N = m v^2 / rho - m g >= 0 (PN-2 at the top, inside), so
/// v_top = sqrt(g rho).
pub fn least_speed_at_loop_top(g: f64, rho: f64) -> f64 {
    (g * rho).sqrt()
}

/// Where a body whose G rides the outside of a smooth circle (path radius `rho`, gravity `g`
/// alone besides the track) leaves it: cos(phi*) of G's angle from the circle's highest point.
/// From a point at phi_a (cos `cos_phi_a`) with speed `v_a` along the path, WE-14 gives
/// v^2 = v_a^2 + 2 g rho (cos phi_a - cos phi), and PN-2 along the normal,
/// m g cos phi - N = m v^2 / rho, has N = 0 where g rho cos phi = v^2:
///   cos phi* = (v_a^2 / (g rho) + 2 cos phi_a) / 3,
/// the textbook's cos phi* = (v0^2 / (g rho) + 2) / 3 for a release at the top with v0 (2/3 at
/// rest). None where the body leaves at once (cos phi* >= cos phi_a: the weight's normal part
/// cannot turn it even there) or the radicand leaves [-1, 1].
pub fn leaving_angle_cos_on_convex_circle(
    g: f64,
    rho: f64,
    v_a: f64,
    cos_phi_a: f64,
) -> Option<f64> {
    let c = (v_a * v_a / (g * rho) + 2.0 * cos_phi_a) / 3.0;
    (c.is_finite() && c < cos_phi_a && c > -1.0).then_some(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;

    #[test]
    fn inside_a_ring_n_is_m_v2_over_rho_plus_m_g_cos_theta() {
        // m = 2 kg, rho = 0.5 m, G at theta = 60 degrees from the bottom of a ring centered at
        // the origin, moving counter-clockwise at 3 m/s (any radial velocity is left out).
        // N = m v^2 / rho + m g cos(theta) = 2 * 9 / 0.5 + 2 * 9.81 * 0.5 = 36 + 9.81 = 45.81 N.
        let (m, rho, th) = (2.0, 0.5, 60f64.to_radians());
        let g_pos = DVec2::new(rho * th.sin(), -rho * th.cos());
        let t = DVec2::new(th.cos(), th.sin());
        let v = 3.0 * t + 0.2 * g_pos.normalize();
        let (n, dir) = normal_force_on_circular_path(
            m,
            g_pos,
            v,
            DVec2::ZERO,
            rho,
            DVec2::new(0.0, -m * G),
            PathSide::Inside,
        )
        .unwrap();
        assert!((n - 45.81).abs() < 1e-12, "{n}");
        assert!((dir + g_pos.normalize()).length() < 1e-12, "{dir}");
    }

    #[test]
    fn outside_a_cylinder_n_is_m_g_cos_theta_minus_m_v2_over_rho() {
        // G 30 degrees past the top of a cylinder's path of rho = 1.05 m at 1.5 m/s, m = 1 kg:
        // N = m g cos(30 deg) - m v^2 / rho = 8.4957 - 2.1429 = 6.3529 N, pushing outward.
        let (m, rho, th) = (1.0, 1.05, 30f64.to_radians());
        let g_pos = DVec2::new(rho * th.sin(), rho * th.cos());
        let v = 1.5 * DVec2::new(th.cos(), -th.sin());
        let (n, dir) = normal_force_on_circular_path(
            m,
            g_pos,
            v,
            DVec2::ZERO,
            rho,
            DVec2::new(0.0, -m * G),
            PathSide::Outside,
        )
        .unwrap();
        let expected = m * G * th.cos() - m * 1.5 * 1.5 / rho;
        assert!((n - expected).abs() < 1e-12, "{n} for {expected}");
        assert!((dir - g_pos.normalize()).length() < 1e-12);
        assert_eq!(disc_path_radius(1.0, 0.05, PathSide::Outside), 1.05);
        assert_eq!(disc_path_radius(1.0, 0.2, PathSide::Inside), 0.8);
    }

    #[test]
    fn at_the_least_top_speed_the_loop_does_not_push() {
        let rho = 0.9;
        let v = least_speed_at_loop_top(G, rho);
        let (n, _) = normal_force_on_circular_path(
            1.0,
            DVec2::new(0.0, rho),
            DVec2::new(-v, 0.0),
            DVec2::ZERO,
            rho,
            DVec2::new(0.0, -G),
            PathSide::Inside,
        )
        .unwrap();
        assert!(n.abs() < 1e-12, "{n}");
    }

    #[test]
    fn a_particle_released_at_rest_on_top_leaves_at_cos_two_thirds() {
        // The textbook's particle on a smooth hemisphere, nudged from rest at the top: N = 0
        // where cos phi = 2/3 (48.19 degrees); with v0^2 = g rho, cos phi = 1 (it leaves at once).
        let c = leaving_angle_cos_on_convex_circle(G, 0.5, 0.0, 1.0).unwrap();
        assert!((c - 2.0 / 3.0).abs() < 1e-15, "{c}");
        assert!(leaving_angle_cos_on_convex_circle(G, 0.5, (G * 0.5f64).sqrt(), 1.0).is_none());
        // n14_14's puck: v0 = 0.5 m/s, rho = 0.55 m: cos phi* = (0.25 / 5.3955 + 2) / 3.
        let c = leaving_angle_cos_on_convex_circle(G, 0.55, 0.5, 1.0).unwrap();
        assert!((c - 0.682111636).abs() < 1e-9, "{c}");
    }
}
