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
