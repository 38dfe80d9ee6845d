//! `world.contact_hz` and `world.allow_fast_rotation`: validated, kept by save/load, and applied
//! by the simulation itself (so `rigidlab check` runs the stress levels as the study records).

use rigidlab::level::{parse, to_ron};
use rigidlab::sim::{Options, Simulation};
use std::f64::consts::FRAC_PI_4;
use std::path::Path;

fn disc(world_extra: &str) -> String {
    // A torque-free disc spinning at 100 rad/s, nothing else.
    format!(
        r#"Level(title: "disc", effects: [],
        world: (dt: 0.016666666666666666, duration: 0.5{world_extra}),
        bodies: [(name: "d", shape: Circle(radius: 0.5), mass: 1.0, omega: 100.0)])"#
    )
}

#[test]
fn bad_contact_hz_is_a_located_error() {
    for value in ["0.0", "-5.0", "NaN", "1e9"] {
        let text = disc(&format!(",\n        contact_hz: {value}"));
        let err = parse(Path::new("bad.ron"), &text).unwrap_err().to_string();
        assert!(err.contains("world.contact_hz"), "{value}: {err}");
        // Located at the field: line 3 of the text (file:line:col).
        assert!(err.contains("bad.ron:3:"), "{value}: {err}");
    }
}

#[test]
fn save_and_load_keep_the_fields() {
    let scene = parse(
        Path::new("a.ron"),
        &disc(", contact_hz: 120.0, allow_fast_rotation: true"),
    )
    .unwrap();
    let text = to_ron(&scene.level);
    let back = parse(Path::new("b.ron"), &text).unwrap();
    assert_eq!(back.level.world.contact_hz, Some(120.0));
    assert!(back.level.world.allow_fast_rotation);
    assert_eq!(back.level, scene.level);
}

#[test]
fn contact_hz_reaches_rapier() {
    // rapier's contact softness: the level's frequency, twice it against fixed bodies (as its
    // 30/60 Hz defaults); absent, rapier's own defaults stay.
    let s = Simulation::new(
        &parse(Path::new("a.ron"), &disc(", contact_hz: 120.0")).unwrap(),
        &Options::default(),
    );
    let p = &s.world.integration_parameters;
    assert_eq!(p.contact_softness.natural_frequency, 120.0);
    assert_eq!(p.static_contact_softness.natural_frequency, 240.0);
    let s = Simulation::new(
        &parse(Path::new("a.ron"), &disc("")).unwrap(),
        &Options::default(),
    );
    let p = &s.world.integration_parameters;
    assert_eq!(p.contact_softness.natural_frequency, 30.0);
    assert_eq!(p.static_contact_softness.natural_frequency, 60.0);
}

#[test]
fn allow_fast_rotation_lifts_the_spin_cap() {
    // Without the flag rapier caps |omega| at (pi/4)/dt = 47.12 rad/s at dt = 1/60; with it a
    // torque-free disc keeps omega = 100 rad/s (dH_G/dt = 0, eq. 6/4) up to f32 round-off.
    let run = |extra: &str| {
        let mut s = Simulation::new(
            &parse(Path::new("a.ron"), &disc(extra)).unwrap(),
            &Options::default(),
        );
        let mut w = 0.0;
        s.run(|snap| w = snap.bodies[0].omega).unwrap();
        w
    };
    let cap = FRAC_PI_4 * 60.0;
    let capped = run("");
    assert!(
        (capped - cap).abs() < cap * 1e-5,
        "omega {capped}, cap {cap}"
    );
    let free = run(", allow_fast_rotation: true");
    assert!((free - 100.0).abs() < 1e-4, "omega {free}");
}
