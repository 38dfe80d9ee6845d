//! Textbook closed-form answers (concepts.md sections 8 and 9): the exact period of a physical
//! pendulum at any amplitude, the period of a mass on springs, and a round body rolling without
//! slip down a slope.
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
pub fn pendulum_period(i_o: f64, m: f64, g: f64, d: f64, theta0: f64) -> f64 {
    4.0 * (i_o / (m * g * d)).sqrt() * elliptic_k((0.5 * theta0).sin())
}

/// Period of a mass m on springs of total stiffness k: T = 2 pi sqrt(m / k) (free vibration,
/// omega_n = sqrt(k / m)).
pub fn spring_mass_period(m: f64, k: f64) -> f64 {
    2.0 * PI * (m / k).sqrt()
}

/// Reduced mass of two bodies joined by a spring, m1 m2 / (m1 + m2): their relative motion
/// vibrates as one body of that mass on the spring (T = 2 pi sqrt(mu / k)).
pub fn reduced_mass(m1: f64, m2: f64) -> f64 {
    m1 * m2 / (m1 + m2)
}

/// Acceleration of the center of a round body rolling without slip down a slope theta:
/// a = g sin(theta) / (1 + k_G^2 / r^2) (RK-8 with 6/1; disc k^2 = r^2/2, hoop k^2 = r^2).
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
