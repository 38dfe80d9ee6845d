//! The settings record in the report says how each step was really called (issue 41): rapier's
//! substeps inside one call, or several calls, and why. On 088f4b7 a rolling disc's report said
//! `"substepping": "internal"` while nearly every step of it was split into one-substep calls for
//! its spinning contact (sim/contact_points.rs; since 2026-12-07 only the last 41 of its steps).

use crate::common;

use rigidlab::sim::{Options, Substepping};
use std::collections::HashMap;

/// A uniform disc (r = 0.2 m, m = 2 kg) rolls from rest down a 30 degree incline at dt = 1/240 s
/// and 4 substeps: a = (2/3) g sin 30 = 3.27 m/s^2, w = a t / r = 16.35 t rad/s. No question reads
/// a contact's start, end or slip, so a step is split (sim/contact_points.rs, `spin_calls`) where
/// the turn's residual over one call, r w^2 dt^2 / 8, passes 1.5 sags of the contact under its
/// load, N / m = g cos 30 = 8.496 m/s^2 over (2 pi 60 Hz)^2 (rapier's static softness):
/// sag = 5.978e-5 m, so w^2 > 1.5 sag 8 / (r dt^2) = 206.6, w > 14.37 rad/s, from t = 0.8791 s:
/// the steps starting at t >= 211/240 s, steps 212 to 252, 41 of 252 (step 1 starts at w = 0 and
/// is one call). The boundary has 0.4% of margin in w (the step before starts at 14.30 rad/s);
/// the load read from the soft contact's impulses may shift it a step: 40 to 42 allowed.
#[test]
fn a_rolling_disc_reports_its_steps_split_for_its_spin() {
    let scene = common::load("levels/kinetics/classic_rolling_disc.ron");
    let r =
        rigidlab::runner::run_graded(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
    let s = r.settings.as_ref().unwrap();
    assert_eq!(r.steps, 252);
    assert_eq!(s.substepping, Substepping::Mixed, "{s:?}");
    assert!((40..=42).contains(&s.split_steps), "{s:?}");
    assert!(
        s.substepping_why.contains("spinning") && s.substepping_why.contains("of 252 steps"),
        "{}",
        s.substepping_why
    );
    // The JSON says the same.
    let json = serde_json::to_value(s).unwrap();
    assert_eq!(json["substepping"], "mixed", "{json}");
    assert_eq!(json["split_steps"].as_u64(), Some(s.split_steps), "{json}");
}

/// Every level of the library states how its steps were called, consistently: `split` for
/// every step split, `internal` for none, `mixed` for some; with a reason each.
#[test]
fn every_level_says_how_its_steps_were_called_and_why() {
    let mut kinds = HashMap::new();
    for f in common::ron_files("levels", &["stress"]) {
        let scene = common::load(&f);
        let Ok(r) =
            rigidlab::runner::run_graded(&scene, &Options::default(), &HashMap::new(), |_| {})
        else {
            continue;
        };
        let s = r.settings.as_ref().unwrap();
        let name = f.display();
        assert!(!s.substepping_why.is_empty(), "{name}: no reason");
        match s.substepping {
            Substepping::Split => assert_eq!(s.split_steps, r.steps, "{name}: {s:?}"),
            Substepping::Internal => assert_eq!(s.split_steps, 0, "{name}: {s:?}"),
            Substepping::Mixed => {
                assert!(
                    s.split_steps > 0 && s.split_steps < r.steps,
                    "{name}: {s:?}"
                )
            }
        }
        assert!(s.cut_steps <= r.steps, "{name}: {s:?}");
        *kinds.entry(format!("{:?}", s.substepping)).or_insert(0) += 1;
    }
    println!("{kinds:?}");
    assert!(
        kinds.len() >= 3,
        "the library has split, internal and mixed levels: {kinds:?}"
    );
}
