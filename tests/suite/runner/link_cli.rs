//! `rigidlab link LEVEL` and `rigidlab play ASSIGNMENT`'s bad input: the link carries the level
//! byte for byte (what the web page decodes is the file the teacher linked), a level that does
//! not load gets no link, and an assignment with an error is refused before any window.

use crate::common;

use common::rigidlab;
use rigidlab::level::link;
use std::path::PathBuf;

/// Runs rigidlab; returns (exit code, stdout, stderr).
fn run(args: &[&str]) -> (i32, String, String) {
    let out = rigidlab().args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-link-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn link_output_decodes_to_the_identical_level() {
    for rel in [
        "levels/kinetics/simple_pendulum.ron",
        "levels/kinetics/simple_pendulum_param.ron",
        "levels/momentum/bar_struck_at_percussion.ron",
    ] {
        let file = common::repo_path(rel);
        let (code, stdout, stderr) = run(&[
            "link",
            file.to_str().unwrap(),
            "--base",
            "https://example.org/rigidlab/",
        ]);
        assert_eq!(code, 0, "{rel}: {stderr}");
        let url = stdout.trim_end();
        assert_eq!(stdout.lines().count(), 1, "one line: {stdout}");
        let fragment = url
            .strip_prefix("https://example.org/rigidlab/")
            .unwrap_or_else(|| panic!("{rel}: the base first: {url}"));
        let (data, name) = link::fragment_parts(fragment).expect("a #level= fragment");
        assert_eq!(name, file.file_name().unwrap().to_str().unwrap());
        // Byte for byte: comments, layout and all (the file has no byte-order mark).
        let text = std::fs::read_to_string(&file).unwrap();
        assert_eq!(link::decode(&data).unwrap(), text, "{rel}");
        // And it opens as the file does, under the file's name (a parameterized level's
        // student numbers depend on it).
        let scene = link::open_fragment(fragment).unwrap().unwrap();
        let direct = rigidlab::level::load(&file).unwrap();
        assert_eq!(scene.level, direct.level, "{rel}");
    }
}

#[test]
fn a_level_that_does_not_load_gets_no_link() {
    let dir = temp_dir("bad");
    let bad = dir.join("bad.ron");
    std::fs::write(
        &bad,
        "Level(title: \"x\", bodies: [(name: \"a\", mass: -1.0)])",
    )
    .unwrap();
    let (code, stdout, stderr) = run(&["link", bad.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty(), "no link printed: {stdout}");
    assert!(stderr.contains("bad.ron:1:"), "located: {stderr}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn play_refuses_a_broken_assignment_with_its_place() {
    let dir = temp_dir("assignment");
    std::fs::write(
        dir.join("assignment.ron"),
        "Assignment(\n  title: \"Week 1\",\n  levels: [\"../outside.ron\"],\n)",
    )
    .unwrap();
    // The folder and the manifest alike, with or without a display: exit 2 before a window.
    for given in [dir.clone(), dir.join("assignment.ron")] {
        let (code, _, stderr) = run(&["play", given.to_str().unwrap()]);
        assert_eq!(code, 2, "{stderr}");
        assert!(stderr.contains("assignment.ron:3:12"), "{stderr}");
        assert!(
            stderr.contains("leaves the assignment's folder"),
            "{stderr}"
        );
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_example_assignment_reads() {
    let a = rigidlab::level::assignment::Assignment::load(&common::repo_path("assignments/intro"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.due.as_deref(), Some("2026-12-14"));
    assert_eq!(a.levels.len(), 3);
    for l in &a.levels {
        rigidlab::level::load(l).unwrap_or_else(|e| panic!("{e}"));
    }
}
