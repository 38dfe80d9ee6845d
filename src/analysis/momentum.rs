//! Linear and angular momentum (concepts.md sections 4 and 10).

use super::cross;
use glam::DVec2;

/// Linear momentum G = m v_G (6/12, IM-1).
pub fn linear_momentum(m: f64, v_g: DVec2) -> DVec2 {
    m * v_g
}

/// Angular momentum about the mass center, H_G = I_G omega (6/13).
pub fn angular_momentum_g(i_g: f64, omega: f64) -> f64 {
    i_g * omega
}

/// Angular momentum about any point O, fixed or moving: H_O = I_G omega + (r_{G/O} x m v_G)_z
/// (6/15, JH's addition theorem).
pub fn angular_momentum_about(
    m: f64,
    i_g: f64,
    r_g: DVec2,
    v_g: DVec2,
    omega: f64,
    o: DVec2,
) -> f64 {
    i_g * omega + cross(r_g - o, m * v_g)
}

/// Angular momentum in rotation about a fixed axis O: H_O = I_O omega (6/16).
pub fn angular_momentum_fixed_axis(i_o: f64, omega: f64) -> f64 {
    i_o * omega
}

/// Moves an angular momentum to another point: H_{O'} = H_O + (r_{O/O'} x G)_z (from 6/15:
/// the I_G omega part does not depend on the point).
pub fn transfer_angular_momentum(h_o: f64, o: DVec2, o_new: DVec2, g: DVec2) -> f64 {
    h_o + cross(o - o_new, g)
}

/// One body's contribution to system totals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMomentum {
    pub m: f64,
    pub i_g: f64,
    pub r_g: DVec2,
    pub v_g: DVec2,
    pub omega: f64,
}

/// System linear momentum, G = sum of m_i v_Gi (6/18, RM-8).
pub fn system_linear_momentum(bodies: impl IntoIterator<Item = BodyMomentum>) -> DVec2 {
    bodies.into_iter().map(|b| b.m * b.v_g).sum()
}

/// System angular momentum about one point O, H_O = sum of (H_O)_i (6/19, RM-8).
pub fn system_angular_momentum(bodies: impl IntoIterator<Item = BodyMomentum>, o: DVec2) -> f64 {
    bodies
        .into_iter()
        .map(|b| angular_momentum_about(b.m, b.i_g, b.r_g, b.v_g, b.omega, o))
        .sum()
}
