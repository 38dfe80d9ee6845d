//! The settings record in the report says how each step was really called (issue 41): rapier's
//! substeps inside one call, or one substep per call, and why. On 088f4b7 a rolling disc's
//! report said `"substepping": "internal"` while nearly every step of it was split into
//! one-substep calls for its spinning contact (sim/contact_points.rs).

use crate::common;

use rigidlab::sim::{Options, Substepping};
use std::collections::HashMap;

/// A uniform disc (r = 0.2 m) rolls from rest down a 30 degree incline at dt = 1/240 s and 4
/// substeps: a = (2/3) g sin 30 = 3.27 m/s^2, w = a t / r = 16.35 t rad/s. A step is split when
/// the ball touches and r w^2 >= 1e-3 g at its start (w >= 0.2215 rad/s, reached at t = 13.5 ms,
/// 3.25 steps), and the first step always is (any ball, before rapier has met a pair). So step 1
/// is split, steps 2 to 4 start at w = 0.068, 0.136, 0.204 rad/s and are one call, and steps 5
/// to 252 start at w >= 0.2725 and are split: 249 of 252 steps split, the others one call. The
/// boundary at step 4 has 8% of margin (0.204 against 0.2215) and step 5 23%; the soft contact's
/// start may shift one step: 248 to 250 allowed.
#[test]
fn a_rolling_disc_reports_its_steps_split_for_its_spin() {
    let scene = common::load("levels/kinetics/classic_rolling_disc.ron");
    let r =
        rigidlab::runner::run_graded(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
    let s = r.settings.as_ref().unwrap();
    assert_eq!(r.steps, 252);
    assert_eq!(s.substepping, Substepping::Mixed, "{s:?}");
    assert!((248..=250).contains(&s.split_steps), "{s:?}");
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
