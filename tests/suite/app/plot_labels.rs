//! The plots' labels print the series' true extremes (src/app/panels/plots.rs). They printed the
//! drawn range, which has an 8% margin each side: omega read 4.40 / -4.43 rad/s for a 3.84 rad/s
//! peak (issue 33). On a known series, omega(t) = 3.84 sin(2 pi t / 1 s) sampled every 1/240 s:
//! the sample at t = 0.25 s is the peak, 3.84 up to rounding (sin(pi/2) = 1 in f64 exactly).

use bevy_egui::egui;
use rigidlab::app::panels::plots::{drawn_range, extreme_labels, extremes, nearest_sample};

#[test]
fn labels_print_the_true_extremes_of_a_known_series() {
    let omega: Vec<f64> = (0..=480)
        .map(|k| 3.84 * (2.0 * std::f64::consts::PI * k as f64 / 240.0).sin())
        .collect();
    let (lo, hi) = extremes(omega.iter().copied()).unwrap();
    // The samples at t = 0.25 s and 0.75 s are the peaks: 3.84 * sin(pi/2), 3.84 * sin(3 pi/2),
    // exact to the last bits of the f64 argument (1e-12 covers them).
    assert!(
        (hi - 3.84).abs() < 1e-12 && (lo + 3.84).abs() < 1e-12,
        "{lo} {hi}"
    );
    let (top, bottom) = extreme_labels((lo, hi), "rad/s");
    assert_eq!(top, "max 3.84 rad/s");
    assert_eq!(bottom, "min -3.84 rad/s");
    // The line is drawn over a wider range (it never touches the frame); that is not printed.
    let (d0, d1) = drawn_range((lo, hi));
    assert!(d0 < lo && d1 > hi);
    assert!(!top.contains(&format!("{:.2}", d1)), "{top}");
}

#[test]
fn extremes_skip_what_is_not_a_number() {
    assert_eq!(
        extremes([1.0, f64::NAN, -2.0, f64::INFINITY, 0.5]),
        Some((-2.0, 1.0))
    );
    assert_eq!(extremes([f64::NAN]), None);
    assert_eq!(extremes(std::iter::empty()), None);
    // A flat series still gets a drawn range of some height (no division by zero).
    let (a, b) = drawn_range((2.0, 2.0));
    assert!(b > a);
}

#[test]
fn the_phase_plot_readout_picks_the_sample_under_the_pointer() {
    // A circle of 8 samples mapped 100 px to a unit: the pointer near (0, 1) picks that sample.
    let pts: Vec<(f64, f64)> = (0..8)
        .map(|k| {
            let a = k as f64 * std::f64::consts::FRAC_PI_4;
            (a.cos(), a.sin())
        })
        .collect();
    let map = |a: f64, b: f64| egui::pos2(200.0 + 100.0 * a as f32, 200.0 - 100.0 * b as f32);
    assert_eq!(nearest_sample(&pts, map, egui::pos2(203.0, 104.0)), Some(2));
    assert_eq!(nearest_sample(&pts, map, egui::pos2(120.0, 210.0)), Some(4));
    assert_eq!(nearest_sample(&[], map, egui::pos2(0.0, 0.0)), None);
}
