//! Nothing the user made is lost (issue 32): every file rigidlab writes is checked against what it
//! reads and against what is already there. A refused `render --out` touches no file; `run --csv`
//! never writes over its level and replaces an earlier run's CSVs all together; `study accuracy`
//! says when a plot cannot be written (exit 2); `render` and `study accuracy` write over an
//! image, table or summary only when its mark shows rigidlab wrote it; the window's saves, CSV exports and screenshots
//! never replace a file (a numbered name instead); a wrong preferences file is reported at
//! path:line:col and kept as `prefs.ron.bad`, never read without limits nor silently replaced.

use crate::common;

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

/// `study accuracy FREE_FALL --out OUT --quick`, run in `dir`; returns (exit code, stderr).
fn study_quick(dir: &Path, out: &Path) -> (i32, String) {
    let level = repo_path(FREE_FALL);
    run_in(
        dir,
        &[
            "study",
            "accuracy",
            level.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quick",
        ],
    )
}
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
    for (f, header) in EARLIER_RUN {
        fs::write(dir.join(f), format!("{header}\nan earlier run's rows\n")).unwrap();
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

/// An earlier run's files, by the header line rigidlab writes first in each.
const EARLIER_RUN: [(&str, &str); 4] = [
    (
        "out.csv",
        "step,time,body,x,y,angle,com_x,com_y,vx,vy,omega,mass,inertia",
    ),
    (
        "out_joints.csv",
        "step,time,joint,anchor_x,anchor_y,impulse_x,impulse_y,angular_impulse,motor_impulse,limit_impulse,force_x,force_y,coordinate",
    ),
    (
        "out_contacts.csv",
        "step,time,body1,body2,point_x,point_y,normal_x,normal_y,distance,normal_impulse,tangent_impulse",
    ),
    (
        "out_springs.csv",
        "step,time,spring,length,extension,tension,energy",
    ),
];

#[test]
fn run_never_replaces_or_removes_a_file_it_did_not_write() {
    // Before (issue 41): `run L --csv out.csv` removed out_contacts.csv and out_springs.csv
    // whatever they held (the free fall writes neither), and replaced out.csv and
    // out_joints.csv: a user's notes, a level. Now each of the four names must be free, a
    // device, or a CSV rigidlab wrote (its first line its kind's header); else exit 2 before the
    // run, naming the file, and nothing is touched.
    let level = repo_path(FREE_FALL);
    for (i, (name, _)) in EARLIER_RUN.iter().enumerate() {
        for mine in ["my notes\n", "", "step,time,body\n"] {
            let dir = temp_dir(&format!("csv-mine-{i}"));
            fs::write(dir.join(name), mine).unwrap();
            let (code, err) = run_in(&dir, &["run", level.to_str().unwrap(), "--csv", "out.csv"]);
            assert_eq!(code, 2, "{name} holding {mine:?}: {err}");
            assert!(
                err.contains(name) && err.contains("not a CSV rigidlab wrote"),
                "{name}: {err}"
            );
            assert!(err.contains("help: give another name"), "{err}");
            assert_eq!(
                fs::read_to_string(dir.join(name)).unwrap(),
                mine,
                "{name} kept"
            );
            assert_eq!(names(&dir), [name.to_string()], "nothing written");
            let _ = fs::remove_dir_all(&dir);
        }
    }
    // A link is the user's too (replacing it loses the link), even to an earlier run's CSV.
    #[cfg(unix)]
    {
        let dir = temp_dir("csv-link");
        fs::write(dir.join("real.csv"), format!("{}\n", EARLIER_RUN[0].1)).unwrap();
        std::os::unix::fs::symlink(dir.join("real.csv"), dir.join("out.csv")).unwrap();
        let (code, err) = run_in(&dir, &["run", level.to_str().unwrap(), "--csv", "out.csv"]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("is a link"), "{err}");
        let _ = fs::remove_dir_all(&dir);
    }
    // Twin: an earlier run's CSV with a Windows line end is replaced; a device is written.
    let dir = temp_dir("csv-crlf");
    fs::write(
        dir.join("out.csv"),
        format!("{}\r\nrows\r\n", EARLIER_RUN[0].1),
    )
    .unwrap();
    let (code, err) = run_in(&dir, &["run", level.to_str().unwrap(), "--csv", "out.csv"]);
    assert_eq!(code, 0, "{err}");
    assert!(fs::read_to_string(dir.join("out.csv"))
        .unwrap()
        .starts_with(EARLIER_RUN[0].1));
    let (code, err) = run_in(
        &dir,
        &["run", level.to_str().unwrap(), "--csv", "/dev/null"],
    );
    assert_eq!(code, 0, "{err}");
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn study_accuracy_exits_2_when_a_plot_cannot_be_written() {
    // Before: "cannot draw the plot" on stderr, and exit 0.
    let dir = temp_dir("study");
    let out = dir.join("out");
    // A folder where the level's plot goes.
    fs::create_dir_all(out.join("kinematics_free_fall.png")).unwrap();
    let (code, err) = study_quick(&dir, &out);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("cannot write the plot"), "{err}");
    // The files that could be written are.
    assert!(out.join("accuracy.csv").is_file() && out.join("summary.md").is_file());
    // And with nothing in the way, exit 0 and the plot.
    fs::remove_dir(out.join("kinematics_free_fall.png")).unwrap();
    let (code, err) = study_quick(&dir, &out);
    assert_eq!(code, 0, "{err}");
    assert!(out.join("kinematics_free_fall.png").is_file());
    assert_eq!(
        names(&out),
        ["accuracy.csv", "kinematics_free_fall.png", "summary.md"],
        "no temporary file left"
    );
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn render_and_study_write_over_only_their_own_files() {
    // Before: `render --out photo.png` replaced any PNG there, and `study accuracy --out DIR`
    // replaced DIR/summary.md and DIR/<level>.png whatever they held (issue 41's attack, and
    // the standard: no output overwrites a file rigidlab cannot show it wrote).
    let dir = temp_dir("own");
    let level = repo_path(FREE_FALL);
    let photo = dir.join("photo.png");
    let photo_bytes = b"\x89PNG\r\n\x1a\n the user's photo".to_vec();
    fs::write(&photo, &photo_bytes).unwrap();
    let (code, err) = run_in(
        &dir,
        &["render", level.to_str().unwrap(), "--out", "photo.png"],
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("rigidlab did not write it"), "{err}");
    assert_eq!(fs::read(&photo).unwrap(), photo_bytes, "the photo is kept");

    let out = dir.join("out");
    fs::create_dir_all(&out).unwrap();
    // The user's notes under the summary's name: refused before the sweep, kept.
    fs::write(out.join("summary.md"), "my notes\n").unwrap();
    let (code, err) = study_quick(&dir, &out);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("summary.md exists and rigidlab did not write it"),
        "{err}"
    );
    assert_eq!(
        fs::read_to_string(out.join("summary.md")).unwrap(),
        "my notes\n"
    );
    assert_eq!(names(&out), ["summary.md"], "nothing written");
    fs::remove_file(out.join("summary.md")).unwrap();
    // A user's image under a plot's name: that plot is refused (exit 2), the image kept.
    let plot = out.join("kinematics_free_fall.png");
    fs::write(&plot, &photo_bytes).unwrap();
    let (code, err) = study_quick(&dir, &out);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("rigidlab did not write it"), "{err}");
    assert_eq!(fs::read(&plot).unwrap(), photo_bytes, "the image is kept");
    // With the image moved away, the study writes its files, and a rerun replaces them.
    fs::remove_file(&plot).unwrap();
    for run in 0..2 {
        let (code, err) = study_quick(&dir, &out);
        assert_eq!(code, 0, "run {run}: {err}");
    }
    assert_eq!(
        names(&out),
        ["accuracy.csv", "kinematics_free_fall.png", "summary.md"]
    );
    let _ = fs::remove_dir_all(&dir);
}

#[cfg(feature = "app")]
mod window {
    use super::*;
    use bevy::app::ScheduleRunnerPlugin;
    use bevy::asset::RenderAssetUsages;
    use bevy::prelude::*;
    use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
    use bevy::time::TimeUpdateStrategy;
    use rigidlab::app::editor::{Editor, EditorCommand, EditorPlugin};
    use rigidlab::app::prefs::{self, Prefs};
    use rigidlab::app::user_files;
    use rigidlab::app::PhysicsPlugin;
    use std::time::Duration;

    #[test]
    fn every_new_scene_is_saved_beside_the_others() {
        // Before: each new scene saved to saved-levels/my-scene-saved.ron, the second over the
        // first.
        let dir = temp_dir("editor");
        let mut app = App::new();
        app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
            .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
            .add_plugins(PhysicsPlugin {
                scene: rigidlab::editor::empty_scene(PathBuf::from("my-scene.ron")),
                options: Default::default(),
                paused: true,
            })
            .add_plugins(EditorPlugin);
        app.update();
        let path = dir.join("saved-levels/my-scene-saved.ron");
        let mut saved = Vec::new();
        for i in 0..3 {
            app.world_mut().write_message(EditorCommand::New);
            app.update();
            // Each scene different: a bar at a height of its own.
            app.world_mut().write_message(EditorCommand::Apply(
                rigidlab::app::editor::Placeable::Bar
                    .edit_at(glam::DVec2::new(0.0, 1.0 + i as f64), 4.0),
            ));
            app.update();
            app.world_mut()
                .write_message(EditorCommand::Save(path.clone()));
            app.update();
            let ed = app.world().resource::<Editor>();
            let (note, ok) = ed.note.clone().unwrap();
            assert!(ok, "{note}");
            let used = ed.just_saved.clone().unwrap();
            assert!(note.contains(&used.display().to_string()), "{note}");
            saved.push(used);
        }
        assert_eq!(
            saved,
            [
                path.clone(),
                dir.join("saved-levels/my-scene-saved-2.ron"),
                dir.join("saved-levels/my-scene-saved-3.ron")
            ]
        );
        for (i, f) in saved.iter().enumerate() {
            let level = rigidlab::level::load(f).unwrap().level;
            let y = level
                .bodies
                .iter()
                .find(|b| b.name == "bar1")
                .unwrap()
                .position
                .1;
            assert!(
                (y - (1.0 + i as f64)).abs() < 1e-9,
                "{}: y = {y}",
                f.display()
            );
        }
        assert_eq!(names(&dir.join("saved-levels")).len(), 3);
        let _ = fs::remove_dir_all(&dir);
    }

    fn image(rgba: [u8; 4]) -> Image {
        Image::new_fill(
            Extent3d {
                width: 4,
                height: 2,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &rgba,
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::default(),
        )
    }

    #[test]
    fn screenshots_are_named_by_level_and_never_overwritten() {
        // Before: named by time alone (rigidlab-0.000s.png), the second level's over the first's.
        let a = user_files::screenshot_path(Path::new("levels/kinetics/simple_pendulum.ron"), 0.0);
        let b = user_files::screenshot_path(Path::new("levels/energy/spring.ron"), 0.0);
        assert_ne!(a, b);
        assert_eq!(a, Path::new("screenshots/simple_pendulum-0.000s.png"));
        let dir = temp_dir("screenshots");
        let path = dir.join("shots").join(a.file_name().unwrap());
        let m1 = user_files::save_screenshot(&image([255, 0, 0, 255]), &path).unwrap();
        let m2 = user_files::save_screenshot(&image([0, 0, 255, 255]), &path).unwrap();
        assert!(
            m1.contains("saved") && m1.contains(&path.display().to_string()),
            "{m1}"
        );
        let second = dir.join("shots/simple_pendulum-0.000s-2.png");
        assert!(m2.contains(&second.display().to_string()), "{m2}");
        let first = fs::read(&path).unwrap();
        assert_eq!(&first[..8], b"\x89PNG\r\n\x1a\n");
        assert_ne!(first, fs::read(&second).unwrap(), "each its own picture");
        // A folder that cannot take it (a file where the folder goes): said, not "saved".
        fs::write(dir.join("blocked"), "a file").unwrap();
        let e =
            user_files::save_screenshot(&image([0; 4]), &dir.join("blocked/shot.png")).unwrap_err();
        assert!(e.contains("not saved") && e.contains("blocked"), "{e}");
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_csv_export_never_replaces_an_earlier_one() {
        let dir = temp_dir("exports");
        let path = dir.join("exports/pendulum-bar.csv");
        let m1 = user_files::deliver(&path, b"first\n", "text/csv").unwrap();
        let m2 = user_files::deliver(&path, b"second\n", "text/csv").unwrap();
        assert!(m1.starts_with("saved"), "{m1}");
        assert!(
            m2.contains("pendulum-bar-2.csv") && m2.contains("kept"),
            "{m2}"
        );
        assert_eq!(fs::read_to_string(&path).unwrap(), "first\n");
        assert_eq!(
            fs::read_to_string(dir.join("exports/pendulum-bar-2.csv")).unwrap(),
            "second\n"
        );
        assert_eq!(
            names(&dir.join("exports")).len(),
            2,
            "no temporary file left"
        );
        let _ = fs::remove_dir_all(&dir);
    }

    const GOOD: &str = "(\n    tour_done: true,\n    arrow_scale: 2.0,\n    time_scale: 0.5,\n    labels: false,\n    trails: true,\n)\n";

    #[test]
    fn good_preferences_load_and_save_whole() {
        let dir = temp_dir("prefs-good");
        let path = dir.join("rigidlab/prefs.ron");
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, GOOD).unwrap();
        let (p, file) = prefs::load_from(&path);
        assert_eq!(file.problem, None);
        assert!(file.can_save);
        assert_eq!(p.time_scale, 0.5);
        assert!(!p.labels && p.tour_done);
        let changed = Prefs { trails: false, ..p };
        changed.save(&file).unwrap();
        assert_eq!(prefs::load_from(&path).0, changed);
        assert_eq!(names(path.parent().unwrap()), ["prefs.ron"]);
        let _ = fs::remove_dir_all(&dir);
    }

    /// Loads `text` as prefs.ron in a fresh folder: the problem said, and the folder's files.
    fn load_bad(name: &str, text: &str) -> (String, PathBuf) {
        let dir = temp_dir(name);
        let path = dir.join("prefs.ron");
        fs::write(&path, text).unwrap();
        let (p, file) = prefs::load_from(&path);
        assert_eq!(p, Prefs::default(), "{name}");
        let problem = file
            .problem
            .clone()
            .unwrap_or_else(|| panic!("{name}: no problem said"));
        assert!(
            file.can_save,
            "{name}: moved aside, so the window may write its own"
        );
        assert!(!path.exists(), "{name}: moved aside");
        assert_eq!(
            fs::read_to_string(dir.join("prefs.ron.bad")).unwrap(),
            text,
            "{name}: kept whole"
        );
        (problem, dir)
    }

    #[test]
    fn a_preferences_file_with_a_typo_is_reported_and_kept() {
        // Before: ignored whole, and at the first toggle replaced by the defaults, silently.
        let typo = GOOD.replace("labels: false", "labels: flase");
        let (problem, dir) = load_bad("prefs-typo", &typo);
        let path = dir.join("prefs.ron");
        assert!(
            problem.contains(&format!("{}:5:", path.display())),
            "path:line:col: {problem}"
        );
        assert!(problem.contains("prefs.ron.bad"), "{problem}");
        // The window then saves its own; the user's file stays as .bad.
        let (p, file) = prefs::load_from(&path);
        assert_eq!(
            file.problem, None,
            "no file now: the defaults, nothing to say"
        );
        p.save(&file).unwrap();
        assert_eq!(fs::read_to_string(dir.join("prefs.ron.bad")).unwrap(), typo);
        // A second bad file does not replace the first .bad: a counter.
        fs::write(&path, "(time_scale: )").unwrap();
        let (_, file) = prefs::load_from(&path);
        let problem = file.problem.unwrap();
        assert!(problem.contains("prefs.ron-2.bad"), "{problem}");
        assert_eq!(fs::read_to_string(dir.join("prefs.ron.bad")).unwrap(), typo);
        assert_eq!(
            fs::read_to_string(dir.join("prefs.ron-2.bad")).unwrap(),
            "(time_scale: )"
        );
        // A misspelt field name is a typo too (it was dropped without a word).
        let (problem, _) = load_bad("prefs-field", &GOOD.replace("trails:", "trials:"));
        assert!(
            problem.contains(":6:") && problem.contains("trials"),
            "{problem}"
        );
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_time_scale_the_window_cannot_run_at_is_refused_with_its_line() {
        // Before: -1.0 or inf panicked at start (exit 101) without naming the file.
        for (name, v) in [
            ("prefs-negative", "-1.0"),
            ("prefs-inf", "inf"),
            ("prefs-nan", "NaN"),
            ("prefs-zero", "0.0"),
        ] {
            let (problem, dir) = load_bad(name, &GOOD.replace("0.5", v));
            let path = dir.join("prefs.ron");
            assert!(
                problem.contains(&format!("{}:4:5: time_scale", path.display()))
                    && problem.contains("takes 1/64 to 8"),
                "{name}: {problem}"
            );
            let _ = fs::remove_dir_all(&dir);
        }
        let (problem, dir) = load_bad("prefs-arrow", &GOOD.replace("2.0", "1e9"));
        assert!(problem.contains(":3:5: arrow_scale"), "{problem}");
        let _ = fs::remove_dir_all(&dir);
    }

    /// `load_from` on another thread, which must answer within 10 s.
    fn load_within(path: PathBuf) -> (Prefs, prefs::PrefsFile) {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(prefs::load_from(&path));
        });
        rx.recv_timeout(Duration::from_secs(10))
            .expect("prefs are read without blocking")
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_a_device_or_a_huge_file_is_not_read_as_preferences() {
        // Before: a FIFO blocked the window's start; a link to /dev/zero was read without end.
        let dir = temp_dir("prefs-special");
        let fifo = dir.join("fifo.ron");
        assert!(std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        let (p, file) = load_within(fifo.clone());
        assert_eq!(p, Prefs::default());
        let problem = file.problem.unwrap();
        assert!(
            problem.contains("FIFO") && problem.contains("fifo.ron"),
            "{problem}"
        );
        assert!(dir.join("fifo.ron.bad").exists() && !fifo.exists());

        let zero = dir.join("zero.ron");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let (_, file) = load_within(zero.clone());
        let problem = file.problem.unwrap();
        assert!(problem.contains("device"), "{problem}");

        let big = dir.join("big.ron");
        fs::write(&big, " ".repeat(prefs::MAX_PREFS_BYTES as usize + 1)).unwrap();
        let (_, file) = load_within(big.clone());
        let problem = file.problem.unwrap();
        assert!(problem.contains("larger than"), "{problem}");
        assert!(dir.join("big.ron.bad").exists());
        let _ = fs::remove_dir_all(&dir);
    }
}
