//! `sim::angles::wrap_pi` takes a shortcut for a difference already within the half turn
//! (2026-12-07): it must give the formula's result bit for bit everywhere, the edges of the
//! interval, signed zeros, whole turns and non-finite values included, since every body's
//! continuous angle is summed from it step after step.

use rigidlab::sim::angles::wrap_pi;
use std::f64::consts::{PI, TAU};

/// The definition: a - 2 pi floor((a + pi) / 2 pi), into [-pi, pi).
fn formula(a: f64) -> f64 {
    a - TAU * ((a + PI) / TAU).floor()
}

#[test]
fn the_shortcut_gives_the_formula_bit_for_bit() {
    let mut values = vec![
        0.0,
        -0.0,
        PI,
        -PI,
        TAU,
        -TAU,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE,
        1e300,
        -1e300,
    ];
    // The neighbours of the interval's edges, where (a + pi) / 2 pi rounds to 0 or 1.
    for edge in [PI, -PI, 3.0 * PI, -3.0 * PI] {
        let mut below = edge;
        let mut above = edge;
        for _ in 0..64 {
            below = f64::from_bits(below.to_bits() - 1);
            above = f64::from_bits(above.to_bits() + 1);
            values.extend([below, above]);
        }
    }
    // A sweep of differences a body's angle meets: small, near a half turn, several turns.
    let mut x = 0.123_456_789_f64;
    for k in 0..20_000 {
        x = (x * 3.987_654_321 + 0.271_828).fract();
        let scale = [1e-9, 1e-3, 1.0, 3.2, 40.0][k % 5];
        values.extend([x * scale, -x * scale]);
    }
    for a in values {
        assert_eq!(
            wrap_pi(a).to_bits(),
            formula(a).to_bits(),
            "wrap_pi({a:e}) = {:e}, the formula {:e}",
            wrap_pi(a),
            formula(a)
        );
    }
}
