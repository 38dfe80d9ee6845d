//! The library's challenges (issue 42, levels/challenges/): each one's goal is met at its
//! closed-form value and missed 3% off on either side, at the level's own settings. The closed
//! forms are written again here, independently of the levels' `worked` expressions, and checked
//! against them first: an engine run never supplies an expected value.

use rigidlab::level::{self, params::Pick};
use rigidlab::runner;
use std::collections::HashMap;

const G: f64 = 9.81;

/// Each challenge with its control's closed-form value (derived in the level's comment).
fn closed_forms() -> Vec<(&'static str, f64)> {
    let k2 = 0.06957010852370435_f64.powi(2); // the bowling ball's k_G^2 = 2 r^2 / 5
    vec![
        // range v0^2 / g = 2 m at 45 degrees
        ("projectile_into_cup.ron", (G * 2.0).sqrt()),
        // q = r_bar + (l^2 + t^2) / (12 r_bar), the bar's center of percussion below its pin
        (
            "strike_at_percussion.ron",
            0.6 + (1.2f64.powi(2) + 0.04f64.powi(2)) / (12.0 * 0.6),
        ),
        // (m_A - m_B) g / (m_A + m_B + M/2) = g/5: m_A = (6 m_B + M/2) / 4, m_B = M = 2 kg
        ("atwood_at_g_over_5.ron", {
            let (m_b, m) = (2.0, 2.0);
            (6.0 * m_b + m / 2.0) / 4.0
        }),
        // 1/2 m v0^2 = 1/2 k d^2 with m = 2 kg, v0 = 2 m/s, d = 0.5 m
        ("spring_stops_at_mark.ron", 2.0 * 4.0 / 0.25),
        // h = 2.5 rho, rho = 0.9 m
        ("loop_least_height.ron", 2.5 * 0.9),
        // cos 30 = (v0^2 / (g rho) + 2) / 3, rho = 1.05 m
        (
            "leave_cylinder_at_30deg.ron",
            (G * 1.05 * (3.0 * 30f64.to_radians().cos() - 2.0)).sqrt(),
        ),
        // omega0 = v0 r / k_G^2, v0 = 4 m/s, r = 0.11 m
        ("bowling_stop_dead.ron", 4.0 * 0.11 / k2),
        // mu = tan 30
        ("incline_steady_slide.ron", 30f64.to_radians().tan()),
        // e = sqrt(h2 / h1)
        ("rebound_to_height.ron", (0.49f64 / 1.0).sqrt()),
        // m v0^2 / r0 = k (r0 - L0)
        (
            "tethered_puck_orbit.ron",
            (50.0 * 0.3 * 0.8 / 0.5f64).sqrt(),
        ),
    ]
}

/// The challenge's verdict with its control at `value` (None: its worked value), at the
/// level's settings.
fn play(file: &str, value: Option<f64>) -> (f64, rigidlab::questions::ChallengeResult) {
    let path = crate::common::repo_path(format!("levels/challenges/{file}"));
    let loaded =
        level::load_challenge(&path, &Pick::Nominal, value).unwrap_or_else(|e| panic!("{e}"));
    let (control, _) = loaded.control.expect("a challenge level");
    let r = runner::run_graded(&loaded.scene, &Default::default(), &HashMap::new(), |_| {})
        .unwrap_or_else(|e| panic!("{file}: {e}"));
    let c = r.challenge.expect("the report carries the challenge");
    (control.worked, c)
}

#[test]
fn every_challenge_is_met_at_its_closed_form_and_missed_3_percent_off() {
    let forms = closed_forms();
    // Every level of the folder has its closed form here.
    let files = crate::common::ron_files("levels/challenges", &[]);
    assert_eq!(files.len(), forms.len(), "{files:?}");
    for (file, form) in forms {
        let (worked, at_worked) = play(file, None);
        // The level's `worked` is the closed form (to rounding: 1e-9).
        assert!(
            (worked - form).abs() <= 1e-9 * form.abs(),
            "{file}: worked {worked}, closed form {form}"
        );
        assert!(
            at_worked.success,
            "{file}: worked value missed: {at_worked:?}"
        );
        assert!(at_worked.miss.is_finite(), "{file}: {at_worked:?}");
        for k in [0.97, 1.03] {
            let (_, off) = play(file, Some(form * k));
            assert!(
                !off.success,
                "{file}: {k} x the closed form met the goal: {off:?}"
            );
            assert!(
                off.miss.is_finite() && off.miss != 0.0,
                "{file}: a miss is measured: {off:?}"
            );
        }
    }
}

#[test]
fn a_body_that_never_moves_never_meets_a_goal() {
    // A ball at rest inside its region all run: the goal names a motion, and none happened.
    let text = r#"Level(
  title: "t",
  parameters: [(name: "v", range: (0.0, 1.0), step: 0.1, nominal: 0.0)],
  world: (duration: 0.1),
  bodies: [(name: "ball", shape: Circle(radius: 0.1), velocity: (v, 0.0))],
  challenge: (control: "v", worked: 0.0,
    goal: StaysInside(body: "ball", region: Rect(min: (-1.0, -1.0), max: (1.0, 1.0)))),
)"#;
    let dir = std::env::temp_dir().join(format!("rigidlab-challenge-still-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("still.ron");
    std::fs::write(&path, text).unwrap();
    let run = |v: Option<f64>| {
        let loaded =
            level::load_challenge(&path, &Pick::Nominal, v).unwrap_or_else(|e| panic!("{e}"));
        runner::run_graded(&loaded.scene, &Default::default(), &HashMap::new(), |_| {})
            .unwrap()
            .challenge
            .unwrap()
    };
    let still = run(None);
    assert!(
        !still.success && still.note.contains("never moved"),
        "{still:?}"
    );
    let moving = run(Some(0.5));
    assert!(moving.success, "{moving:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn check_answer_grades_the_students_value_with_its_unit() {
    // The cup's worked value is sqrt(2 g) = 4.4294 m/s = 15.946 km/h; 4.6 m/s is 3.9% fast.
    let out = crate::common::rigidlab()
        .args([
            "check",
            "levels/challenges/projectile_into_cup.ron",
            "--json",
            "--no-advice",
            "--answer",
            "v0=15.946 km/h",
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let c = &json["levels"][0]["challenge"];
    assert_eq!(c["student"], true);
    assert_eq!(c["success"], true);
    assert!(
        (c["value"].as_f64().unwrap() - 15.946 / 3.6).abs() < 1e-9,
        "{c}"
    );
    let out = crate::common::rigidlab()
        .args([
            "check",
            "levels/challenges/projectile_into_cup.ron",
            "--answer",
            "v0=4.6",
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "a missed goal exits as a wrong answer"
    );
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("missed by") && table.contains("(student;"),
        "{table}"
    );
    // Out of the control's range, or of another dimension: bad input.
    for bad in ["v0=20", "v0=4 N"] {
        let out = crate::common::rigidlab()
            .args([
                "check",
                "levels/challenges/projectile_into_cup.ron",
                "--answer",
                bad,
            ])
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(2),
            "{bad}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
