//! Textbook closed-form answers (concepts.md sections 8 and 9): the exact period of a physical
//! pendulum at any amplitude, the period of a mass on springs, a round body rolling without
//! slip down a slope, and a row of dominoes: the angle a block tips at and the angle a fallen row
//! leans at.
//!
//! Each function is the formula a textbook exercise ends with, applied to numbers the caller
//! takes from the engine's state; the questions compare them with what the engine did.

use std::f64::consts::PI;

/// The complete elliptic integral of the first kind,
/// K(k) = int_0^{pi/2} dphi / sqrt(1 - k^2 sin^2 phi),
/// by the arithmetic-geometric mean: K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).max(0.0).sqrt());
    for _ in 0..40 {
        let (a1, b1) = (0.5 * (a + b), (a * b).sqrt());
        a = a1;
        b = b1;
        if (a - b).abs() < 1e-16 * a {
            break;
        }
    }
    PI / (2.0 * a)
}

/// Period of a physical pendulum at amplitude theta0 (rad):
/// T = 4 sqrt(I_O / (m g d)) K(sin(theta0/2)), with d = |OG|; at small amplitude this is
/// 2 pi sqrt(I_O / (m g d)) (PL-5 with the exact energy integral).
///
/// # Examples
///
/// A 1 m simple pendulum (I_O = m l^2, d = l): at small amplitude T = 2 pi sqrt(l/g) =
/// 2.0061 s; released from 90 degrees the exact period is 1.18034 times that (4 K(sin 45)/(2 pi)).
/// ```
/// use rigidlab::analysis::closed_forms::pendulum_period;
/// let small = pendulum_period(1.0, 1.0, 9.81, 1.0, 1e-6);
/// assert!((small - 2.0 * std::f64::consts::PI * (1.0f64 / 9.81).sqrt()).abs() < 1e-9);
/// let wide = pendulum_period(1.0, 1.0, 9.81, 1.0, std::f64::consts::FRAC_PI_2);
/// assert!((wide / small - 1.180_340_6).abs() < 1e-7);
/// ```
pub fn pendulum_period(i_o: f64, m: f64, g: f64, d: f64, theta0: f64) -> f64 {
    4.0 * (i_o / (m * g * d)).sqrt() * elliptic_k((0.5 * theta0).sin())
}

/// Period of a one-degree-of-freedom conservative oscillation from the energy integral: a
/// coordinate q with constant generalized inertia `inertia` in a potential `v(q)`, started at
/// q0 with rate qdot0, swings between the turning points q_a < q_b where V = E, and
/// T = 2 ∫_{q_a}^{q_b} dq / sqrt(2 (E - V(q)) / I), with E = 1/2 I qdot0^2 + V(q0)
/// (the work-energy equation RE-7, T1 + V1 = T2 + V2, solved for the rate and integrated over a
/// swing). For the pendulum V = m g d (1 - cos q) it is [`pendulum_period`]; it also takes a
/// torsion spring on the pivot, V = m g d (1 - cos q) + 1/2 k (q - q_s)^2, which no closed form
/// does.
///
/// None when the motion does not turn back within `reach` of q0 on both sides (it goes over
/// the top) or q0 is an equilibrium at rest.
pub fn energy_integral_period(
    inertia: f64,
    v: impl Fn(f64) -> f64,
    q0: f64,
    qdot0: f64,
    reach: f64,
) -> Option<f64> {
    let e = 0.5 * inertia * qdot0 * qdot0 + v(q0);
    // E - V, positive inside the swing.
    let room = |q: f64| e - v(q);
    let scale = e.abs().max(v(q0 + reach).abs()).max(f64::MIN_POSITIVE);
    let at_rest = room(q0) <= 1e-14 * scale;
    // Started at rest, q0 is one turning point: the swing goes downhill from it.
    let h = reach * 1e-6;
    let downhill_right = v(q0 + h) < v(q0 - h);
    let turning = |dir: f64| -> Option<f64> {
        if at_rest && (dir > 0.0) != downhill_right {
            return Some(q0);
        }
        // March out until V passes E, then bisect the bracket to the last bit.
        let n = 4096;
        let step = reach / n as f64;
        let mut inside = q0;
        for k in 1..=n {
            let q = q0 + dir * step * k as f64;
            if room(q) <= 0.0 {
                let (mut a, mut b) = (inside, q);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if m == a || m == b {
                        break;
                    }
                    if room(m) > 0.0 {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                return Some(0.5 * (a + b));
            }
            inside = q;
        }
        None
    };
    // At rest where the slope is below what the curvature gives over h: an equilibrium.
    if at_rest && (v(q0 + h) - v(q0 - h)).abs() <= (v(q0 + h) + v(q0 - h) - 2.0 * v(q0)).abs() {
        return None;
    }
    let (qa, qb) = (turning(-1.0)?, turning(1.0)?);
    if qb <= qa {
        return None;
    }
    // q = c + r sin(u): the square-root ends of 1/sqrt(E - V) become a smooth integrand in u,
    // integrated by the midpoint rule (no evaluation at the ends, where it is 0/0).
    let (c, r) = (0.5 * (qa + qb), 0.5 * (qb - qa));
    let n = 8192;
    let du = PI / n as f64;
    let mut sum = 0.0;
    for k in 0..n {
        let u = -0.5 * PI + (k as f64 + 0.5) * du;
        let w = room(c + r * u.sin()).max(0.0);
        if w > 0.0 {
            sum += r * u.cos() / (2.0 * w / inertia).sqrt();
        }
    }
    Some(2.0 * sum * du)
}

/// Period of a mass m on springs of total stiffness k: T = 2 pi sqrt(m / k) (free vibration,
/// omega_n = sqrt(k / m)).
pub fn spring_mass_period(m: f64, k: f64) -> f64 {
    2.0 * PI * (m / k).sqrt()
}

/// Period of a mass m on springs of total stiffness k with viscous dampers of total c, while
/// underdamped: T_d = 2 pi / omega_d, omega_d = sqrt(k / m - (c / 2m)^2) = omega_n sqrt(1 -
/// zeta^2), zeta = c / (2 sqrt(k m)) (damped free vibration; the velocity's zero crossings are
/// T_d apart). None at or past critical damping, where the motion does not oscillate.
pub fn damped_period(m: f64, k: f64, c: f64) -> Option<f64> {
    let w2 = k / m - (c / (2.0 * m)).powi(2);
    (w2 > 0.0).then(|| 2.0 * PI / w2.sqrt())
}

/// Reduced mass of two bodies joined by a spring, m1 m2 / (m1 + m2): their relative motion
/// vibrates as one body of that mass on the spring (T = 2 pi sqrt(mu / k)).
pub fn reduced_mass(m1: f64, m2: f64) -> f64 {
    m1 * m2 / (m1 + m2)
}

/// Acceleration of the center of a round body rolling without slip down a slope theta:
/// a = g sin(theta) / (1 + k_G^2 / r^2) (RK-8 with 6/1; disc k^2 = r^2/2, hoop k^2 = r^2).
///
/// # Examples
///
/// A disc (k_G^2 = r^2/2) rolling down 30 degrees: a = g sin(30)/(3/2) = 2/3 x 9.81 x 0.5 =
/// 3.27 m/s^2; a hoop (k_G = r) rolls at half of g sin(theta).
/// ```
/// use rigidlab::analysis::closed_forms::rolling_acceleration;
/// let (g, th, r) = (9.81, 30f64.to_radians(), 0.2);
/// assert!((rolling_acceleration(g, th, r / 2f64.sqrt(), r) - 3.27).abs() < 1e-12);
/// assert!((rolling_acceleration(g, th, r, r) - 9.81 * 0.25).abs() < 1e-12);
/// ```
pub fn rolling_acceleration(g: f64, theta: f64, k_g: f64, r: f64) -> f64 {
    g * theta.sin() / (1.0 + k_g * k_g / (r * r))
}

/// The friction force rolling without slip needs on a slope theta:
/// F = m g sin(theta) k_G^2 / (k_G^2 + r^2) (6/1 with RK-8).
pub fn rolling_friction(m: f64, g: f64, theta: f64, k_g: f64, r: f64) -> f64 {
    m * g * theta.sin() * k_g * k_g / (k_g * k_g + r * r)
}

/// The least coefficient of friction for rolling without slip on a slope theta, F / N:
/// mu = tan(theta) k_G^2 / (k_G^2 + r^2) ([`rolling_friction`] over N = m g cos(theta)).
pub fn rolling_friction_needed(theta: f64, k_g: f64, r: f64) -> f64 {
    theta.tan() * k_g * k_g / (k_g * k_g + r * r)
}

/// A round body (radius r, centroidal radius of gyration k_G) sliding on a level floor, its
/// contact point slipping at `slip0`, m/s: the time until it rolls,
/// t = |slip0| / (mu g (1 + r^2 / k_G^2)). Friction mu m g decelerates G at mu g and turns the
/// body at mu m g r / I_G, so the slip v_G + omega r falls at mu g (1 + r^2/k_G^2) (6/1 with
/// F = mu N, RK-8 when it stops): v0 / (3 mu g) for a disc, 2 v0 / (7 mu g) for a sphere.
pub fn slide_to_roll_time(slip0: f64, mu: f64, g: f64, k_g: f64, r: f64) -> f64 {
    slip0.abs() / (mu * g * (1.0 + r * r / (k_g * k_g)))
}

/// The same body's mass-center velocity once it rolls, from v0 along the floor and omega0
/// (counterclockwise): friction's line passes through the contact line, so the angular
/// momentum about a point of it, I_G omega - m r v, is kept (6/15), and rolling means
/// omega = -v / r: v = r (r v0 - k_G^2 omega0) / (k_G^2 + r^2) (2/3 v0 for a disc without spin).
pub fn speed_when_rolling(v0: f64, omega0: f64, k_g: f64, r: f64) -> f64 {
    r * (r * v0 - k_g * k_g * omega0) / (k_g * k_g + r * r)
}

/// The tipping angle of a block of width b and height h standing on a level floor: tilted about
/// the edge it pivots on by theta = atan(b / h), its mass center is straight above that edge
/// (statics: the weight's line of action leaves the base, and past it the weight's moment about
/// the edge turns the block further over).
///
/// # Examples
///
/// A domino 5 cm tall and 1 cm thick tips at atan(0.2) = 11.31 degrees.
/// ```
/// use rigidlab::analysis::closed_forms::tipping_angle;
/// assert!((tipping_angle(0.01, 0.05).to_degrees() - 11.3099).abs() < 1e-4);
/// ```
pub fn tipping_angle(b: f64, h: f64) -> f64 {
    (b / h).atan()
}

/// The angle from the vertical at which a domino of thickness t, tilted about its front bottom
/// edge, first touches the next one standing d further on (pivot to pivot): its front top corner
/// reaches the next one's back face when h sin(theta) = d - t (h its height). NaN where it
/// never does (d - t > h: the gap is wider than the domino is tall; or d < t: they overlap).
pub fn domino_contact_angle(t: f64, d: f64, h: f64) -> f64 {
    let s = (d - t) / h;
    if (0.0..=1.0).contains(&s) {
        s.asin()
    } else {
        f64::NAN
    }
}

/// The angle from the vertical of a row of dominoes of thickness t, pivots d apart, each
/// leaning on the next at the same angle: the front top corner of one lies on the back face of
/// the next, whose normal is (cos theta, -sin theta); the corner is at x_i + h (sin, cos), the
/// face passes through x_i + d - t (cos, -sin), and their offset along the normal is
/// t - d cos(theta), which is zero at cos(theta) = t / d, whatever the height.
///
/// # Examples
///
/// Dominoes 1 cm thick, pivots 3.25 cm apart, lean at acos(0.3077) = 72.08 degrees.
/// ```
/// use rigidlab::analysis::closed_forms::leaning_row_angle;
/// assert!((leaning_row_angle(0.01, 0.0325).to_degrees() - 72.08).abs() < 0.01);
/// ```
///
/// NaN where no such row exists (t > d: the dominoes overlap; d <= 0).
pub fn leaning_row_angle(t: f64, d: f64) -> f64 {
    let c = t / d;
    if (0.0..=1.0).contains(&c) {
        c.acos()
    } else {
        f64::NAN
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn domino_angles_are_nan_where_the_geometry_has_none() {
        // A gap wider than the domino is tall: it never reaches the next one.
        assert!(domino_contact_angle(0.01, 0.07, 0.05).is_nan());
        // Overlapping dominoes (t > d): no contact angle and no leaning row.
        assert!(domino_contact_angle(0.02, 0.01, 0.05).is_nan());
        assert!(leaning_row_angle(0.02, 0.01).is_nan());
        // Touching face to face: upright.
        assert_eq!(domino_contact_angle(0.01, 0.01, 0.05), 0.0);
    }

    #[test]
    fn elliptic_k_matches_tables() {
        // K(0) = pi/2; K(sin 45 deg) = 1.8540746773 (Abramowitz & Stegun table 17.1).
        assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
        assert!((elliptic_k(0.5f64.sqrt()) - 1.854_074_677_301_372).abs() < 1e-13);
        // K(sin 30 deg) = 1.6857503548.
        assert!((elliptic_k(0.5) - 1.685_750_354_812_596).abs() < 1e-13);
    }

    #[test]
    fn rolling_and_pendulum_formulas() {
        // Disc: a = 2/3 g sin(theta), F = 1/3 m g sin(theta); hoop: a = g sin(theta) / 2.
        let (g, th) = (9.81, 0.5235987755982988);
        assert!(
            (rolling_acceleration(g, th, 0.2 / 2f64.sqrt(), 0.2) - 9.81 * 0.5 * 2.0 / 3.0).abs()
                < 1e-12
        );
        assert!((rolling_acceleration(g, th, 0.2, 0.2) - 9.81 * 0.25).abs() < 1e-12);
        assert!(
            (rolling_friction(2.0, g, th, 0.2 / 2f64.sqrt(), 0.2) - 2.0 * 9.81 * 0.5 / 3.0).abs()
                < 1e-12
        );
        // Slender bar pinned at its end released from 90 deg: T = 2 pi sqrt(2L/3g) x 2K(sin 45)/pi.
        let t0 = 2.0 * PI * (2.0 / (3.0 * g)).sqrt();
        let t = pendulum_period(2.0 / 3.0, 2.0, g, 0.5, PI / 2.0);
        assert!((t / t0 - 1.180_340_599_016_096).abs() < 1e-12, "{}", t / t0);
        // Small amplitude tends to the linear period.
        assert!((pendulum_period(2.0 / 3.0, 2.0, g, 0.5, 1e-4) / t0 - 1.0).abs() < 1e-8);
    }

    #[test]
    fn energy_integral_period_is_the_elliptic_period_and_the_spring_period() {
        let (g, m, d, i_o) = (9.81, 2.0, 0.5, 2.0 / 3.0);
        // Gravity alone: the elliptic-integral period at every amplitude, from rest at the
        // amplitude or from the bottom with the speed that reaches it.
        for deg in [5.0f64, 60.0, 120.0, 170.0] {
            let a = deg.to_radians();
            let exact = pendulum_period(i_o, m, g, d, a);
            let v = |q: f64| m * g * d * (1.0 - q.cos());
            let from_rest = energy_integral_period(i_o, v, a, 0.0, 2.0 * PI).unwrap();
            let w0 = (2.0 * m * g * d * (1.0 - a.cos()) / i_o).sqrt();
            let from_bottom = energy_integral_period(i_o, v, 0.0, -w0, 2.0 * PI).unwrap();
            assert!(
                (from_rest / exact - 1.0).abs() < 1e-8,
                "{deg}: {from_rest} {exact}"
            );
            assert!(
                (from_bottom / exact - 1.0).abs() < 1e-8,
                "{deg}: {from_bottom} {exact}"
            );
        }
        // A torsion spring alone: 2 pi sqrt(I / k) at any amplitude and about any rest angle.
        let k = 5.0;
        let t = energy_integral_period(i_o, |q: f64| 0.5 * k * (q - 0.3).powi(2), 1.2, 0.7, 20.0);
        assert!((t.unwrap() / (2.0 * PI * (i_o / k).sqrt()) - 1.0).abs() < 1e-8);
        // Small swings with both: 2 pi sqrt(I_O / (m g d + k)).
        let v = |q: f64| m * g * d * (1.0 - q.cos()) + 0.5 * k * q * q;
        let t = energy_integral_period(i_o, v, 1e-3, 0.0, 2.0 * PI).unwrap();
        assert!((t / (2.0 * PI * (i_o / (m * g * d + k)).sqrt()) - 1.0).abs() < 1e-6);
        // Over the top (no turning point) and at rest at the equilibrium: no period.
        let v = |q: f64| m * g * d * (1.0 - q.cos());
        assert!(energy_integral_period(i_o, v, 0.0, 20.0, 2.0 * PI).is_none());
        assert!(energy_integral_period(i_o, v, 0.0, 0.0, 2.0 * PI).is_none());
    }
}
