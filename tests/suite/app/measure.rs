//! The window's measuring tools against theory: the period timer on the physical pendulum
//! (levels/kinetics/physical_pendulum.ron) against the exact large-amplitude period, and the
//! selected body's recorded series against the snapshot it came from.

use crate::common;

use rigidlab::analysis::closed_forms::pendulum_period;
use rigidlab::app::panels::measure::period_of;
use rigidlab::app::panels::plots::body_csv;
use rigidlab::app::Run;
use rigidlab::sim::Options;

/// The level played to its end, where the window stops it.
fn played(file: &str) -> Run {
    let scene = common::load(file);
    let mut phys = Run::new(scene, Options::default());
    while !phys.at_end() {
        assert!(phys.advance());
    }
    phys
}

#[test]
fn the_period_timer_reads_the_pendulums_exact_period() {
    let phys = played("levels/kinetics/physical_pendulum.ron");
    let bar = common::body_index(&phys.scene.level, "bar");
    let (t, n) = period_of(&phys, bar).expect("a period over 3.6 s of swinging");
    assert!(n >= 1, "{n} periods");
    // The level's bar, read from the level so the theory follows it: a uniform box w x h of
    // mass m pinned at anchor2 (body frame, from G), I_O = m (w^2 + h^2)/12 + m d^2 (MP-2);
    // 0.6669333 kg m^2 for 1 m x 0.04 m, 2 kg, d = 0.5 m. Released at its level angle.
    let level = &phys.scene.level;
    let b = &level.bodies[bar];
    let Some(rigidlab::level::Shape::Box { width, height }) = b.shape else {
        panic!("the pendulum's bar is a box: {:?}", b.shape)
    };
    let m = b.mass.expect("the bar states its mass");
    let pin = level
        .joints
        .iter()
        .find(|j| j.body2 == "bar")
        .expect("the bar's pin");
    let d = pin.anchor2.0.hypot(pin.anchor2.1);
    let i_o = m * (width * width + height * height) / 12.0 + m * d * d;
    let exact = pendulum_period(i_o, m, 9.81, d, b.angle);
    // rapier loses 1.3% of the energy a period at this dt (the level's own note); the amplitude
    // falls by 0.0075 rad a period (dE/E = sin(theta0) d theta0 / (1 - cos(theta0))) and the
    // large-amplitude period with it, by theta0 d theta0 / 8 = 0.1% a period: 0.5% covers the two periods measured and the crossings' linear
    // interpolation (omega is sampled every 1/120 s).
    let rel = (t - exact).abs() / exact;
    eprintln!("period timer {t:.5} s over {n} periods, exact {exact:.5} s: {rel:.2e}");
    assert!(
        rel < 5e-3,
        "period {t:.5} s against {exact:.5} s: {rel:.2e}"
    );
}

#[test]
fn the_body_series_follows_the_snapshot_and_exports_every_sample() {
    let phys = played("levels/kinetics/physical_pendulum.ron");
    let bar = common::body_index(&phys.scene.level, "bar");
    let series = &phys.body_series[bar];
    let last = series.last().unwrap();
    let s = phys.snapshot();
    assert_eq!(last.t, s.time);
    assert_eq!(last.omega, s.bodies[bar].omega);
    // The pin's reaction peaks at the bottom, m g + m omega^2 d = 19.62 + 2 (3.835)^2 0.5 = 34.3 N
    // (energy, 6/8), and never drops below half of m g on this swing; an impulse not divided by
    // dt (60x smaller) or counted twice would leave these bounds.
    assert!(series.iter().all(|p| p.reaction.length() < 1.2 * 34.3));
    assert!(series.iter().any(|p| p.reaction.length() > 0.9 * 34.3));
    assert!(series
        .iter()
        .skip(1)
        .any(|p| p.reaction.length() > 2.0 * 9.81 * 0.5));
    let csv = body_csv(series);
    assert_eq!(csv.lines().count(), series.len() + 1);
    assert!(csv.starts_with("t_s,"));
}

/// H about the chosen O in the plots: moved from the world origin with the linear momentum
/// (6/15), it equals the sum over the bodies about O computed directly (6/19).
#[test]
fn h_about_any_point_is_the_direct_sum_about_it() {
    let phys = played("levels/kinetics/physical_pendulum.ron");
    let p = phys.series.last().unwrap();
    let s = phys.snapshot();
    for o in [
        glam::DVec2::ZERO,
        glam::DVec2::new(1.0, -2.0),
        glam::DVec2::new(-3.5, 0.25),
    ] {
        let direct = rigidlab::analysis::momentum::scene_angular_momentum_about(s, o);
        let moved = p.h_about(o);
        assert!(
            (moved - direct).abs() <= 1e-12 * (1.0 + direct.abs()),
            "about {o}: {moved} against {direct}"
        );
    }
}

/// The protractor reads the angle between its arms, 0 to 180 degrees, whichever way round they
/// were drawn: 90 degrees between the axes, 135 from x to (-1, 1) and back, 60 between a 60
/// degree ray and the x axis from a vertex away from the origin.
#[test]
fn the_protractor_reads_the_angle_between_its_arms() {
    use glam::DVec2;
    use rigidlab::app::tools::Protractor;
    let deg = |v: DVec2, a1: DVec2, a2: DVec2| {
        Protractor {
            vertex: v,
            arm1: a1,
            arm2: Some(a2),
            dragging: false,
        }
        .angle()
        .unwrap()
        .to_degrees()
    };
    let o = DVec2::ZERO;
    assert!((deg(o, DVec2::X, DVec2::new(0.0, 2.0)) - 90.0).abs() < 1e-12);
    assert!((deg(o, DVec2::X, DVec2::new(-1.0, 1.0)) - 135.0).abs() < 1e-12);
    assert!((deg(o, DVec2::new(-1.0, 1.0), DVec2::X) - 135.0).abs() < 1e-12);
    let v = DVec2::new(3.0, -2.0);
    let ray = v + DVec2::from_angle(60f64.to_radians()) * 0.7;
    assert!((deg(v, ray, v + DVec2::X * 5.0) - 60.0).abs() < 1e-9);
    // No angle until both arms have length.
    let half = Protractor {
        vertex: o,
        arm1: o,
        arm2: Some(DVec2::X),
        dragging: false,
    };
    assert_eq!(half.angle(), None);
}
