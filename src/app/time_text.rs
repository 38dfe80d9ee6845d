//! Times as the window prints them: enough decimals to tell one step from the next, and an
//! instant read off a short run with its significant digits. A fixed `{:.3}` printed the
//! slider-crank's whole 1.2 ms run (dt 2e-5 s) as "t = 0.001 s" for about 30 steps, and its
//! question's instant, 0.83 ms, as "t = 0.001 s" (the second student trial of 2026-12-07).

/// Decimals that resolve one step of `dt` seconds: at least 3 (milliseconds, as before), at
/// most 9.
pub fn decimals_for_step(dt: f64) -> usize {
    if !(dt.is_finite() && dt > 0.0) {
        return 3;
    }
    // ceil(-log10 dt) decimals show a change of one step: dt = 2e-5 s needs 5 (0.00002).
    ((-dt.log10()).ceil() as i64).clamp(3, 9) as usize
}

/// The run's clock, `t` seconds, to the step `dt`: "0.83200" for t = 0.832 ms at dt = 2e-5 s,
/// "1.017" at dt = 1/60 s.
pub fn clock(t: f64, dt: f64) -> String {
    format!("{:.*}", decimals_for_step(dt), t)
}

/// A step `dt` in seconds with one decimal more than the clock, so it never reads 0.
pub fn step(dt: f64) -> String {
    format!("{:.*}", decimals_for_step(dt) + 1, dt)
}

/// An instant, `t` seconds, with at least 3 decimals and 3 significant digits: "0.533" and
/// "0.000832" (at most 9 decimals; 0 is "0.000").
pub fn instant(t: f64) -> String {
    let decimals = if t.is_finite() && t.abs() > 0.0 {
        (2 - t.abs().log10().floor() as i64).clamp(3, 9) as usize
    } else {
        3
    };
    format!("{t:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two successive steps of the slider-crank (dt 2e-5 s) print differently; a 1/60 s level
    /// prints as it did (three decimals).
    #[test]
    fn the_clock_tells_one_step_from_the_next() {
        let dt = 2e-5;
        assert_ne!(clock(41.0 * dt, dt), clock(42.0 * dt, dt));
        assert_eq!(clock(1.0 / 60.0 * 61.0, 1.0 / 60.0), "1.017");
        assert_eq!(step(2e-5), "0.000020");
        assert_eq!(step(1.0 / 60.0), "0.0167");
    }

    /// The crank reaches 40 degrees 0.83 ms into its run: three significant digits, not 0.001.
    #[test]
    fn an_instant_keeps_three_significant_digits() {
        assert_eq!(instant(0.000_832_4), "0.000832");
        assert_eq!(instant(0.533_33), "0.533");
        assert_eq!(instant(12.5), "12.500");
        assert_eq!(instant(0.0), "0.000");
    }
}
