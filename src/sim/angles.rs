//! Angle arithmetic the stage shares, plain f64: one copy for both precisions, below the world
//! and its guards, so neither imports the other for it.

/// Wraps an angle difference to [-pi, pi) (a half turn either way reads -pi).
pub fn wrap_pi(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let turns = (a + PI) / TAU;
    // Almost every difference is within the half turn already (a body's angle read every
    // step): then the floor is 0 and the result is `a - TAU * 0.0`, bit for bit, without the
    // call to `floor` (x86-64's baseline has no rounding instruction: the call was 8% of the
    // instructions of reading the bodies, callgrind 2026-12-07).
    if (0.0..1.0).contains(&turns) {
        return a - TAU * 0.0;
    }
    a - TAU * turns.floor()
}

#[cfg(test)]
mod tests {
    use super::wrap_pi;
    use std::f64::consts::PI;

    #[test]
    fn differences_wrap_into_the_half_open_turn() {
        // 3 pi/2 is a quarter turn back; a half turn either way is -pi (the interval [-pi, pi)).
        assert!((wrap_pi(1.5 * PI) + 0.5 * PI).abs() < 1e-15);
        assert_eq!(wrap_pi(PI), -PI);
        assert_eq!(wrap_pi(-PI), -PI);
        assert!((wrap_pi(0.25) - 0.25).abs() < 1e-15);
    }
}
