//! `rigidlab check` and an assignment's manifest (docs/teacher.md): `check FOLDER` read
//! `assignment.ron` as a level and reported it as one that does not load ("Expected struct
//! `Level` but found `Assignment`", exit 2). The manifest is read as a manifest: given by name
//! it stands for its levels in its order; met in a folder it is left out with a note (its levels
//! are that folder's files); one that does not read is bad input at its line and column.

use crate::common;

use common::rigidlab;
use std::path::PathBuf;

/// The example assignment's three levels, as its manifest lists them.
const INTRO: [&str; 3] = [
    "simple_pendulum.ron",
    "rolling/classic_rolling_disc.ron",
    "bar_struck_at_percussion.ron",
];

fn check(args: &[&str]) -> (i32, String, String) {
    let o = rigidlab().arg("check").args(args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

/// The levels a JSON report ran, by file.
fn files(json: &str) -> Vec<String> {
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    v["levels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["file"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn check_of_an_assignment_folder_checks_its_levels_not_its_manifest() {
    let (code, stdout, stderr) = check(&["assignments/intro", "--json"]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    let ran = files(&stdout);
    assert_eq!(ran.len(), 3, "{ran:?}");
    assert!(
        !ran.iter().any(|f| f.ends_with("assignment.ron")),
        "{ran:?}"
    );
    for l in INTRO {
        assert!(ran.iter().any(|f| f.ends_with(l)), "{l} not run: {ran:?}");
    }
    assert!(
        stderr.contains("note: assignments/intro/assignment.ron: an assignment's manifest"),
        "{stderr}"
    );
}

#[test]
fn check_of_a_manifest_checks_its_levels_in_its_order() {
    let (code, stdout, stderr) = check(&["assignments/intro/assignment.ron", "--json"]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    let ran = files(&stdout);
    let want: Vec<String> = INTRO
        .iter()
        .map(|l| format!("assignments/intro/{l}"))
        .collect();
    assert_eq!(ran, want);
}

#[test]
fn check_reports_a_broken_manifest_at_its_place_and_checks_the_rest() {
    let dir = std::env::temp_dir().join(format!("rigidlab-check-manifest-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        common::repo_path("assignments/intro/simple_pendulum.ron"),
        dir.join("simple_pendulum.ron"),
    )
    .unwrap();
    // Line 3, column 4: a level the folder does not have.
    std::fs::write(
        dir.join("assignment.ron"),
        "Assignment(\n  title: \"Week 1\",\n  levels: [\"simple_pendulum.ron\", \"missing.ron\"],\n)\n",
    )
    .unwrap();
    let folder: PathBuf = dir.clone();
    let o = rigidlab()
        .arg("check")
        .arg(&folder)
        .arg("--json")
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(2), "{stdout}\n{stderr}");
    assert!(stderr.contains("assignment.ron:3:"), "{stderr}");
    assert!(stderr.contains("missing.ron"), "{stderr}");
    assert!(!stderr.contains("Expected struct"), "{stderr}");
    // The level beside it is checked all the same, and passes.
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let pendulum = v["levels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|l| l["file"].as_str().unwrap().ends_with("simple_pendulum.ron"))
        .expect("the level beside the manifest was not checked");
    assert_eq!(pendulum["passed"], true);
    let _ = std::fs::remove_dir_all(&dir);
}
