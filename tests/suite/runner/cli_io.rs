//! The command line's input and output: closed pipes and full disks, files that are not level
//! files (FIFOs, devices, link loops, huge or non-UTF-8 files), an --out that cannot take files.

use crate::common;

use common::rigidlab;
use rigidlab::level::{self, MAX_LEVEL_BYTES};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Runs with stdout sent to `stdout`; returns (exit code, stderr).
fn run_to(args: &[&str], stdout: Stdio) -> (i32, String) {
    let out = rigidlab()
        .args(args)
        .stdout(stdout)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// A fresh folder for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-io-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {}", path.display());
}

const FREE_FALL: &str = "levels/kinematics/free_fall.ron";

/// Every command that prints, with output cheap enough to produce in a test.
const PRINTING: &[&[&str]] = &[
    &["check", FREE_FALL],
    &["check", FREE_FALL, "--json"],
    &["run", FREE_FALL],
    &["study", "stability", "spinning_disc", "--quick"],
    &["study", "stability", "spinning_disc", "--quick", "--json"],
];

#[test]
fn a_closed_pipe_ends_quietly() {
    // `rigidlab check levels | head -1`: the reader is gone before rigidlab writes (closed before
    // the start, so that the test does not race the child).
    for args in PRINTING {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let (code, err) = run_to(args, Stdio::from(writer));
        assert_eq!(code, 141, "{args:?}: {err}");
        assert!(
            err.is_empty(),
            "{args:?}: a closed pipe is not worth a message: {err}"
        );
    }
}

#[test]
fn a_full_disk_is_an_error() {
    for args in PRINTING {
        let full = std::fs::File::create("/dev/full").unwrap();
        let (code, err) = run_to(args, Stdio::from(full));
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains("cannot write the output") && err.contains("No space left"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn a_fifo_or_device_given_directly_is_refused() {
    let fifo = temp_dir("fifo").join("level.ron");
    mkfifo(&fifo);
    for path in [fifo.to_str().unwrap(), "/dev/zero"] {
        // Opening the FIFO or reading /dev/zero would never end; the refusal comes first.
        let (code, err) = run_to(&["check", path], Stdio::null());
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("not a regular file"), "{err}");
        let (code, err) = run_to(&["run", path], Stdio::null());
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("not a regular file"), "{err}");
    }
}

#[test]
fn a_folder_search_skips_fifos_and_follows_a_link_loop_once() {
    let dir = temp_dir("search");
    std::fs::copy(FREE_FALL, dir.join("free_fall.ron")).unwrap();
    mkfifo(&dir.join("pipe.ron"));
    std::os::unix::fs::symlink(&dir, dir.join("loop")).unwrap();
    let found = level::find_files(std::slice::from_ref(&dir)).unwrap();
    assert_eq!(found.files, vec![dir.join("free_fall.ron")]);
    assert_eq!(found.skipped.len(), 2, "{:?}", found.skipped);
    assert!(found
        .skipped
        .iter()
        .any(|w| w.contains("pipe.ron") && w.contains("FIFO")));
    assert!(found
        .skipped
        .iter()
        .any(|w| w.contains("loop") && w.contains("already searched")));

    let out = rigidlab()
        .args(["check", dir.to_str().unwrap()])
        .output()
        .unwrap();
    let (stdout, err) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert_eq!(out.status.code(), Some(0), "{stdout}{err}");
    assert!(stdout.contains("1/1 levels passed"), "{stdout}");
    assert!(err.contains("warning:") && err.contains("FIFO"), "{err}");
}

#[test]
fn a_file_past_the_size_limit_is_refused() {
    let path = temp_dir("size").join("huge.ron");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(MAX_LEVEL_BYTES + 1).unwrap();
    let e = level::load(&path).unwrap_err();
    assert!(e.to_string().contains("larger than 4 MiB"), "{e}");
    assert!(!e.help.is_empty());
    // At the limit it is read (and fails as RON, not as too big).
    f.set_len(MAX_LEVEL_BYTES).unwrap();
    let e = level::load(&path).unwrap_err();
    assert!(!e.to_string().contains("larger than"), "{e}");
}

#[test]
fn invalid_utf8_is_located_at_the_first_bad_byte() {
    let mut bytes = std::fs::read(FREE_FALL).unwrap();
    // Line 3, after two characters (one of them multi-byte, counted once).
    let line3 = bytes
        .iter()
        .enumerate()
        .filter(|(_, &b)| b == b'\n')
        .nth(1)
        .unwrap()
        .0
        + 1;
    bytes.splice(line3..line3, "é".bytes().chain([b'x', 0xff]));
    let e = level::parse_bytes(Path::new("bad.ron"), &bytes).unwrap_err();
    assert_eq!((e.line, e.col), (3, 3), "{e}");
    assert!(
        e.to_string()
            .starts_with("bad.ron:3:3: error: invalid UTF-8 (byte 0xff)"),
        "{e}"
    );
    // The same through a file and the binary.
    let path = temp_dir("utf8").join("bad.ron");
    std::fs::write(&path, &bytes).unwrap();
    let (code, err) = run_to(&["check", path.to_str().unwrap()], Stdio::null());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("bad.ron:3:3: error: invalid UTF-8"), "{err}");
}

#[test]
fn study_accuracy_checks_its_out_folder_before_the_sweep() {
    // An existing regular file, and a folder that cannot be created under it. Either is refused
    // at once (the sweep over every library level would take minutes).
    for (out, needle) in [
        ("README.md", "is a file, not a folder"),
        ("README.md/plots", "cannot create the folder"),
    ] {
        let start = std::time::Instant::now();
        let (code, err) = run_to(
            &["study", "accuracy", "levels", "--out", out],
            Stdio::null(),
        );
        assert_eq!(code, 2, "{err}");
        assert!(err.contains(needle), "{err}");
        assert!(
            start.elapsed().as_secs() < 10,
            "refused only after the sweep"
        );
    }
    // A writable folder passes the check and is left without the probe file.
    let dir = temp_dir("out").join("new");
    rigidlab::study::accuracy::writable_folder(&dir).unwrap();
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

/// A pile of bodies at one point with contacts on is legal but costs k(k-1)/2 contact pairs and
/// blows apart: the command line warns at the first body's line, and still runs the level.
#[test]
fn coincident_bodies_are_warned_about_and_the_library_has_none() {
    let discs: String = (0..12)
        .map(|i| {
            format!("    (name: \"d{i}\", shape: Circle(radius: 0.1), position: (0.0, 1.0)),\n")
        })
        .collect();
    let text = format!(
        "Level(\n  title: \"pile\",\n  effects: [gravity, contacts],\n  world: (dt: 0.01, substeps: 1, solver_iterations: 1, duration: 0.1),\n  bodies: [\n    (name: \"ground\", kind: fixed, shape: Box(width: 10.0, height: 0.2), position: (0.0, 0.0)),\n{discs}  ],\n)\n"
    );
    let path = temp_dir("pile").join("pile.ron");
    std::fs::write(&path, &text).unwrap();
    let (code, err) = run_to(&["check", path.to_str().unwrap()], Stdio::null());
    assert_eq!(code, 0, "a warning does not fail the level: {err}");
    assert!(
        err.contains("pile.ron:7:12: warning: 12 bodies start at the same point (0, 1)")
            && err.contains("66 contact pairs"),
        "{err}"
    );
    // Joined by a pin, two coincident bodies do not collide: no warning.
    let pinned = "Level(\n  title: \"pinned\",\n  effects: [gravity, contacts, joints],\n  world: (dt: 0.01, substeps: 1, solver_iterations: 1, duration: 0.1),\n  bodies: [\n    (name: \"d0\", kind: fixed, shape: Circle(radius: 0.1), position: (0.0, 1.0)),\n    (name: \"d1\", shape: Circle(radius: 0.1), position: (0.0, 1.0)),\n  ],\n  joints: [(name: \"pin\", kind: revolute, body1: \"d0\", body2: \"d1\")],\n)\n";
    let (_, warnings) = level::load_with_warnings(&write(pinned, "pinned")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    // Not pinned, the same two are warned about.
    let loose = pinned
        .replace(
            "  joints: [(name: \"pin\", kind: revolute, body1: \"d0\", body2: \"d1\")],\n",
            "",
        )
        .replace(", joints]", "]");
    let (_, warnings) = level::load_with_warnings(&write(&loose, "loose")).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    // Without contacts nothing collides: no warning either.
    let ghosts = text.replace("[gravity, contacts]", "[gravity]");
    let (_, warnings) = level::load_with_warnings(&write(&ghosts, "ghosts")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    // The library's levels (polygons written in world coordinates on bodies at the origin
    // included) start apart.
    let found = level::find_files(&[PathBuf::from("levels")]).unwrap();
    for f in found.files {
        let (_, warnings) = level::load_with_warnings(&f).unwrap();
        assert!(warnings.is_empty(), "{}: {warnings:?}", f.display());
    }
}

/// A body whose starting velocity disagrees with its joint (a disc pinned 0.1 m above its
/// center given only omega: its pin point would move at omega x 0.1) is warned about at the
/// joint, with the velocity that matches; matched, or declared `starts_apart`, it is not.
#[test]
fn a_jointed_body_started_against_its_joint_is_warned_about() {
    let level = |disc: &str, extra: &str| {
        format!(
            "Level(\n  title: \"kicked\",\n  effects: [gravity, joints],\n  world: (dt: 0.01, duration: 0.1),\n  bodies: [\n    (name: \"ground\", kind: fixed),\n    (name: \"disc\", shape: Circle(radius: 0.15), mass: 1.5, position: (0.0, -0.1), {disc}),\n  ],\n  joints: [(name: \"pin\", kind: revolute, body1: \"ground\", body2: \"disc\", anchor2: (0.0, 0.1){extra})],\n)\n"
        )
    };
    // omega 0.35 about G: the pin point (0.1 above G) moves at -0.35 x 0.1 = -0.035 m/s in x.
    let (_, warnings) =
        level::load_with_warnings(&write(&level("omega: 0.35", ""), "kicked")).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let w = warnings[0].to_string();
    assert!(
        w.contains("kicked.ron:9:")
            && w.contains("joint \"pin\"")
            && w.contains("(-0.0350, 0.0000) m/s")
            && w.contains("give it velocity: (0.035000, 0.000000)"),
        "{w}"
    );
    // With that velocity the disc turns about its pin: no warning.
    let matched = level("velocity: (0.035, 0.0), omega: 0.35", "");
    let (_, warnings) = level::load_with_warnings(&write(&matched, "matched")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    // A pivot meant to catch the moving body says so.
    let caught = level("omega: 0.35", ", starts_apart: true");
    let (_, warnings) = level::load_with_warnings(&write(&caught, "caught")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
}

fn write(text: &str, name: &str) -> PathBuf {
    let path = temp_dir(name).join(format!("{name}.ron"));
    std::fs::write(&path, text).unwrap();
    path
}

/// A stderr that cannot take the message (a full disk) does not turn an error into a panic: the
/// exit code still tells (2: bad input).
#[test]
fn a_full_stderr_keeps_the_exit_code() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = rigidlab()
        .args(["check", "no/such/level.ron"])
        .stdout(Stdio::null())
        .stderr(full)
        .status()
        .unwrap();
    assert_eq!(out.code(), Some(2));
}

/// `study accuracy` writes its results to files and prints nothing on stdout (its progress and
/// the list of files go to stderr): a closed or full stdout does not stop it, and its files are
/// written; a full stderr does not make it panic.
#[test]
fn study_accuracy_writes_its_files_whatever_stdout_and_stderr_are() {
    let dir = temp_dir("accuracy-io");
    let cases: [(&str, Stdio, Stdio); 3] = [
        (
            "closed",
            {
                let (r, w) = std::io::pipe().unwrap();
                drop(r);
                Stdio::from(w)
            },
            Stdio::piped(),
        ),
        (
            "full",
            Stdio::from(std::fs::File::create("/dev/full").unwrap()),
            Stdio::piped(),
        ),
        (
            "full-stderr",
            Stdio::null(),
            Stdio::from(
                std::fs::OpenOptions::new()
                    .write(true)
                    .open("/dev/full")
                    .unwrap(),
            ),
        ),
    ];
    for (name, stdout, stderr) in cases {
        let out = dir.join(name);
        let o = rigidlab()
            .args([
                "study",
                "accuracy",
                FREE_FALL,
                "--quick",
                "--out",
                out.to_str().unwrap(),
            ])
            .stdout(stdout)
            .stderr(stderr)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(
            out.join("accuracy.csv").is_file() && out.join("summary.md").is_file(),
            "{name}"
        );
    }
}

#[test]
fn escape_sequences_in_a_levels_names_never_reach_the_terminal_raw() {
    // Before (issue 41): a question id "sp\u{1b}]0;pwned\u{7}\u{1b}[2J" retitled and cleared the
    // terminal from `check`'s table; a body's name did the same from an error on stderr. Now
    // every control character is written as `\u{..}`; the JSON keeps the names exact.
    let dir = temp_dir("escapes");
    let free_fall = std::fs::read_to_string(common::repo_path(FREE_FALL)).unwrap();
    let hostile = "sp\\u{1b}]0;pwned\\u{7}\\u{1b}[2J\\u{9b}31m\\r";
    let ok = dir.join("ok.ron");
    std::fs::write(
        &ok,
        free_fall.replace("id: \"speed\"", &format!("id: \"{hostile}\"")),
    )
    .unwrap();
    let out = rigidlab()
        .args(["check", ok.to_str().unwrap(), "--no-advice"])
        .output()
        .unwrap();
    let table = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(0), "{table}");
    for raw in ['\u{1b}', '\u{7}', '\u{9b}', '\r'] {
        assert!(!table.contains(raw), "{raw:?} in {table:?}");
    }
    assert!(
        table.contains("sp\\u{1b}]0;pwned\\u{7}\\u{1b}[2J"),
        "{table}"
    );
    // The JSON report holds the id as it is (serde escapes what JSON must).
    let out = rigidlab()
        .args(["check", ok.to_str().unwrap(), "--no-advice", "--json"])
        .output()
        .unwrap();
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let ids: Vec<&str> = json["levels"][0]["questions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|q| q["id"].as_str().unwrap())
        .collect();
    assert!(
        ids.contains(&"sp\u{1b}]0;pwned\u{7}\u{1b}[2J\u{9b}31m\r"),
        "{ids:?}"
    );
    // An error naming a body: on stderr, escaped too (a body named twice).
    let bad = dir.join("bad.ron");
    let twice = "    (name: \"b\\u{1b}[31m\", shape: Circle(radius: 0.1), mass: 0.5),\n";
    std::fs::write(
        &bad,
        free_fall.replace("  bodies: [\n", &format!("  bodies: [\n{twice}{twice}")),
    )
    .unwrap();
    let (code, err) = run_to(&["check", bad.to_str().unwrap()], Stdio::null());
    assert_eq!(code, 2, "{err}");
    assert!(!err.contains('\u{1b}'), "{err:?}");
    assert!(err.contains("b\\u{1b}[31m"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
