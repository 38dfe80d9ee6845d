//! The legend says over how many steps the drawn forces are averaged (the second student
//! trial of 2026-12-07): the window averages a displayed frame's steps, 1/60 s, which at the
//! slider-crank's dt = 2e-5 s is 833 steps, more than its whole 60-step run; the legend said
//! "the last 833 steps (1/60 s)" while the run had taken 42.

use rigidlab::app::overlays::{legend_entries, Overlays};
use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

/// After 42 steps of 2e-5 s, the mean spans the steps recorded, at most 42, never 833; after
/// one displayed frame's worth of a 1/120 s level's steps (2), exactly that frame.
#[test]
fn the_legend_counts_the_steps_the_mean_has_taken() {
    let scene = level::load(Path::new("levels/kinematics/classic_slider_crank.ron")).unwrap();
    let mut phys = Run::new(scene, Options::default());
    for _ in 0..42 {
        phys.advance();
    }
    let (n, span) = phys.steps_averaged();
    assert!((1..=42).contains(&n), "{n} steps averaged after 42");
    // n steps of dt = 2e-5 s, to the last bit of the product.
    assert!(
        (span - n as f64 * 2e-5).abs() < 1e-15,
        "{span} s for {n} steps"
    );
    let ov = Overlays {
        free_body: true,
        ..Default::default()
    };
    let legend: Vec<String> = legend_entries(&ov, &phys.sim.level, (n, span))
        .into_iter()
        .map(|(t, _)| t)
        .collect();
    let line = legend
        .iter()
        .find(|t| t.starts_with("forces: mean"))
        .unwrap();
    assert!(line.contains(&format!("last {n} steps")), "{line}");
    assert!(!line.contains("833") && !line.contains("1/60"), "{line}");

    let scene = level::load(Path::new("levels/kinetics/physical_pendulum.ron")).unwrap();
    let mut phys = Run::new(scene, Options::default());
    for _ in 0..10 {
        phys.advance();
    }
    // dt = 1/120 s: a displayed frame is 2 steps, all recorded after 10.
    assert_eq!(phys.steps_averaged().0, 2);
}
