//! `rigidlab verify` and `check --student` (issue 43): verify finds a deliberately broken
//! variant, names its values and fails; a level whose range breaks a field is bad input.

use crate::common;

use common::rigidlab;
use std::path::PathBuf;

/// Free fall with a mass parameter whose expected speed is right only for m = 1 kg: the answer
/// writes a made-up (1 + (m - 1)/2) factor, so the corner m = 2 kg expects 1.5 g t, not g t.
const BROKEN: &str = r#"Level(
  title: "Free fall, broken for heavy balls",
  statement: "A {m} ball falls from rest for 1 s.",
  parameters: [(name: "m", list: [1.0, 2.0], unit: "kg")],
  effects: [gravity],
  world: (duration: 1.0),
  bodies: [(name: "ball", shape: Circle(radius: 0.1), mass: m, position: (0.0, 10.0))],
  questions: [
    (id: "v", ask: "Speed after 1 s", unit: "m/s", expected: g*1.0*(1 + (m - 1)/2), tolerance: 1e-3,
     quantity: Speed("ball"), at: Time(1.0)),
  ],
)"#;

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-verify-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join(name);
    std::fs::write(&f, text).unwrap();
    f
}

fn out(args: &[&str]) -> (i32, String, String) {
    let o = rigidlab().args(args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

#[test]
fn verify_finds_the_broken_variant_and_names_its_values() {
    let f = write("broken_free_fall.ron", BROKEN);
    let f = f.to_str().unwrap();
    // The nominal variant (m = 1 kg) passes: check alone does not see the mistake.
    assert_eq!(out(&["check", f]).0, 0);
    let (code, stdout, _) = out(&["verify", f, "--variants", "5", "--json", "--no-advice"]);
    assert_eq!(code, 1, "{stdout}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["passed"], false);
    let failing: Vec<&serde_json::Value> = v["variants"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|o| o["passed"] == false)
        .collect();
    assert!(!failing.is_empty());
    for o in &failing {
        assert_eq!(o["values"][0]["value"], 2.0, "only m = 2 kg is broken: {o}");
    }
    assert!(failing.iter().any(|o| o["kind"] == "corner"));
    let (code, text, _) = out(&["verify", f, "--variants", "5", "--no-advice"]);
    assert_eq!(code, 1);
    assert!(text.contains("FAIL corner: m = 2 kg"), "{text}");
}

#[test]
fn verify_passes_the_library_exercises() {
    // Every parameterized exercise of the library (8 on 2026-12-07), so a new one is covered.
    let files: Vec<PathBuf> = common::ron_files("levels", &[])
        .into_iter()
        .filter(|f| f.to_string_lossy().ends_with("_param.ron"))
        .collect();
    assert!(files.len() >= 8, "{files:?}");
    for f in &files {
        let f = f.to_str().unwrap();
        let (code, text, err) = out(&["verify", f, "--variants", "20"]);
        assert_eq!(code, 0, "{f}:\n{text}{err}");
        assert!(text.contains(", 0 fail"), "{text}");
    }
}

#[test]
fn a_range_that_breaks_a_field_is_bad_input_located_with_its_values() {
    let text = BROKEN
        .replace("mass: m,", "mass: m - 1.5,")
        .replace("[1.0, 2.0]", "[2.0, 1.0]");
    let f = write("negative_mass.ron", &text);
    let (code, _, err) = out(&["check", f.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    let line = text
        .lines()
        .position(|l| l.contains("mass: m - 1.5"))
        .unwrap()
        + 1;
    assert!(err.contains(&format!("negative_mass.ron:{line}:")), "{err}");
    assert!(err.contains("m = 1 kg"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn check_student_runs_that_students_numbers() {
    let f = "levels/kinetics/incline_friction_param.ron";
    let (code, _, err) = out(&["check", f, "--student", "s1234567"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("student s1234567: m = 1.5 kg, theta = 35 deg, mu = 0.1"),
        "{err}"
    );
    assert!(err.contains("statement: A 1.5 kg block"), "{err}");
    let (_, again, _) = out(&["check", f, "--student", "s1234567", "--json"]);
    let (_, other, _) = out(&["check", f, "--student", "bob", "--json"]);
    let expected = |s: &str| {
        let v: serde_json::Value = serde_json::from_str(s).unwrap();
        v["levels"][0]["questions"][0]["expected"].as_f64().unwrap()
    };
    let a = 9.81 * (35f64.to_radians().sin() - 0.1 * 35f64.to_radians().cos());
    assert!((expected(&again) - a).abs() < 1e-9);
    assert_ne!(expected(&other), expected(&again));
    // `run` takes the same id to the same variant.
    let (code, table, err) = out(&["run", f, "--student", "s1234567"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("m = 1.5 kg, theta = 35 deg, mu = 0.1"),
        "{err}"
    );
    assert!(table.contains(&format!("{a:.5}")), "{table}");
}

#[test]
fn verify_refuses_a_level_without_parameters() {
    let (code, _, err) = out(&["verify", "levels/kinetics/incline_friction.ron"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("declares no parameters"), "{err}");
}

#[test]
fn check_student_json_carries_the_variant_picked() {
    // The published vector (docs/levels.md#variants-from-a-student-id): incline_friction_param
    // for s1234567 is m = 1.5 kg, theta = 35 deg, mu = 0.1.
    let (_, stdout, stderr) = out(&[
        "check",
        "levels/kinetics/incline_friction_param.ron",
        "levels/kinetics/incline_friction.ron",
        "--student",
        " s1234567 ",
        "--json",
        "--no-advice",
    ]);
    let v: serde_json::Value =
        serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("{e}: {stderr}"));
    let levels = v["levels"].as_array().unwrap();
    let param = levels
        .iter()
        .find(|l| l["file"].as_str().unwrap().ends_with("_param.ron"))
        .unwrap();
    let variant = &param["variant"];
    assert_eq!(variant["student"], "s1234567");
    let values: Vec<(String, f64, String)> = variant["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| {
            (
                x["name"].as_str().unwrap().to_string(),
                x["value"].as_f64().unwrap(),
                x["unit"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(
        values,
        [
            ("m".to_string(), 1.5, "kg".to_string()),
            ("theta".to_string(), 35.0, "deg".to_string()),
            ("mu".to_string(), 0.1, String::new()),
        ]
    );
    assert_eq!(variant["shown"], "m = 1.5 kg, theta = 35 deg, mu = 0.1");
    // A level without parameters ran as written: no variant.
    let fixed = levels
        .iter()
        .find(|l| !l["file"].as_str().unwrap().ends_with("_param.ron"))
        .unwrap();
    assert!(fixed.get("variant").is_none(), "{fixed}");
}
