//! Nothing the user made is lost (issue 32): every file rigidlab writes is checked against what it
//! reads and against what is already there. A refused `render --out` touches no file; `run --csv`
//! never writes over its level and replaces an earlier run's CSVs all together; `study accuracy`
//! says when a plot cannot be written (exit 2); the window's saves, CSV exports and screenshots
//! never replace a file (a numbered name instead); a wrong preferences file is reported at
//! path:line:col and kept as `prefs.ron.bad`, never read without limits nor silently replaced.

mod common;

use common::{repo_path, rigidlab};
use std::fs;
use std::path::{Path, PathBuf};

/// A fresh folder for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-kept-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs rigidlab in `dir`; returns (exit code, stderr).
fn run_in(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = rigidlab().current_dir(dir).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    v.sort();
    v
}

const FREE_FALL: &str = "levels/kinematics/free_fall.ron";
/// A pendulum: its run writes joints beside the bodies.
const PENDULUM: &str = "levels/kinetics/classic_physical_pendulum_small.ron";

#[test]
fn render_refuses_a_format_it_cannot_write_before_touching_the_file() {
    // Before: the image crate created (truncated) X and then found it had no encoder for it.
    let dir = temp_dir("render");
    let level = repo_path(FREE_FALL);
    for ext in [
        "jpg", "jpeg", "bmp", "gif", "tiff", "webp", "ico", "JPG", "svg",
    ] {
        let out = dir.join(format!("X.{ext}"));
        fs::write(&out, "the user's picture").unwrap();
        let (code, err) = run_in(
            &dir,
            &[
                "render",
                level.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert_eq!(code, 2, "{ext}: {err}");
        assert!(err.contains("PNG"), "{ext}: {err}");
        assert_eq!(
            fs::read_to_string(&out).unwrap(),
            "the user's picture",
            "{ext}: a refused --out must leave the file as it was"
        );
    }
    // Nor over the level drawn, whatever it is called.
    let png_level = dir.join("level.png");
    fs::copy(&level, &png_level).unwrap();
    let (code, err) = run_in(&dir, &["render", "level.png", "--out", "./level.png"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("level file"), "{err}");
    assert_eq!(fs::read(&png_level).unwrap(), fs::read(&level).unwrap());
    assert_eq!(
        names(&dir).len(),
        10,
        "no temporary file left: {:?}",
        names(&dir)
    );
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn run_refuses_a_csv_that_is_its_level() {
    // Before: `run L.ron --csv L.ron` replaced the level with the CSV and exited 0.
    let dir = temp_dir("csv-level");
    let original = fs::read(repo_path(FREE_FALL)).unwrap();
    fs::write(dir.join("L.ron"), &original).unwrap();
    fs::create_dir(dir.join("sub")).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(dir.join("L.ron"), dir.join("link.ron")).unwrap();
    fs::hard_link(dir.join("L.ron"), dir.join("hard.ron")).unwrap();
    // A level whose name is the joints file of the CSV asked for.
    fs::write(dir.join("out_joints.csv"), &original).unwrap();
    let mut cases = vec![
        ("L.ron", "L.ron"),
        ("L.ron", "./sub/../L.ron"),
        ("L.ron", "hard.ron"),
        ("out_joints.csv", "out.csv"),
    ];
    if cfg!(unix) {
        cases.push(("L.ron", "link.ron"));
        cases.push(("link.ron", "L.ron"));
    }
    for (level, csv) in cases {
        let (code, err) = run_in(&dir, &["run", level, "--csv", csv]);
        assert_eq!(code, 2, "run {level} --csv {csv}: {err}");
        assert!(err.contains("level file"), "run {level} --csv {csv}: {err}");
        assert_eq!(fs::read(dir.join("L.ron")).unwrap(), original);
        assert_eq!(fs::read(dir.join("out_joints.csv")).unwrap(), original);
        assert!(!dir.join("out.csv").exists(), "refused before the run");
    }
    // A folder is refused before the run too.
    let (code, err) = run_in(&dir, &["run", "L.ron", "--csv", "sub"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("folder"), "{err}");
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn a_runs_csv_files_are_replaced_together() {
    // What the pendulum's run writes, in a fresh folder.
    let fresh = temp_dir("csv-fresh");
    let level = repo_path(PENDULUM);
    let (code, err) = run_in(
        &fresh,
        &["run", level.to_str().unwrap(), "--csv", "out.csv"],
    );
    assert!(code == 0 || code == 1, "{err}");
    let written = names(&fresh);
    assert!(
        written.contains(&"out.csv".to_string()) && written.contains(&"out_joints.csv".to_string()),
        "{written:?}"
    );
    // In a folder holding an earlier run's files of every kind, the same run leaves the same
    // files: each rewritten or, where this run has no such rows, removed. Before: the earlier
    // run's out_contacts.csv and out_springs.csv stayed beside the new out.csv.
    let dir = temp_dir("csv-stale");
    for f in [
        "out.csv",
        "out_joints.csv",
        "out_contacts.csv",
        "out_springs.csv",
    ] {
        fs::write(dir.join(f), "an earlier run\n").unwrap();
    }
    fs::write(dir.join("notes.txt"), "the user's\n").unwrap();
    let (code, err) = run_in(&dir, &["run", level.to_str().unwrap(), "--csv", "out.csv"]);
    assert!(code == 0 || code == 1, "{err}");
    let mut expected = written.clone();
    expected.push("notes.txt".into());
    expected.sort();
    assert_eq!(names(&dir), expected, "no stale sibling, no temporary file");
    for f in &written {
        assert_eq!(
            fs::read(dir.join(f)).unwrap(),
            fs::read(fresh.join(f)).unwrap(),
            "{f} rewritten"
        );
    }
    let _ = fs::remove_dir_all(&fresh);
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn study_accuracy_exits_2_when_a_plot_cannot_be_written() {
    // Before: "cannot draw the plot" on stderr, and exit 0.
    let dir = temp_dir("study");
    let out = dir.join("out");
    // A folder where the level's plot goes.
    fs::create_dir_all(out.join("kinematics_free_fall.png")).unwrap();
    let level = repo_path(FREE_FALL);
    let (code, err) = run_in(
        &dir,
        &[
            "study",
            "accuracy",
            level.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quick",
        ],
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("cannot write the plot"), "{err}");
    // The files that could be written are.
    assert!(out.join("accuracy.csv").is_file() && out.join("summary.md").is_file());
    // And with nothing in the way, exit 0 and the plot.
    fs::remove_dir(out.join("kinematics_free_fall.png")).unwrap();
    let (code, err) = run_in(
        &dir,
        &[
            "study",
            "accuracy",
            level.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quick",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.join("kinematics_free_fall.png").is_file());
    assert_eq!(
        names(&out),
        ["accuracy.csv", "kinematics_free_fall.png", "summary.md"],
        "no temporary file left"
    );
    let _ = fs::remove_dir_all(&dir);
}
