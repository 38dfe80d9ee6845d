//! The course (issue 42, "Learn by playing"): progress kept in `progress.ron` and read back, a
//! file that is not progress kept aside and reported (its bytes still on disk under the name
//! the student is told), a newer rigidlab's file left alone, and, in the app run headless,
//! solving a level marking it solved in the course with the *Next level* button pointing at the
//! next unsolved level in course order. The statuses' rules are unit-tested in
//! `src/app/progress.rs`, the stored text's in `src/app/progress_file.rs`.

use bevy::app::ScheduleRunnerPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_egui::egui;
use rigidlab::app::editor::EditorPlugin;
use rigidlab::app::panels::{course, grade, Browser, Course, Exercise, UiState};
use rigidlab::app::progress::{Graded, LevelKey, Status};
use rigidlab::app::progress_file::FileBackend;
use rigidlab::app::{PhysicsPlugin, Run};
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::common::app::two_frames;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-course-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    v.sort();
    v
}

/// The course kept in `file`.
fn course_in(file: &Path) -> Course {
    Course::open(Some(Box::new(FileBackend(file.to_path_buf()))))
}

const PENDULUM: &str = "levels/kinetics/simple_pendulum.ron";

fn pendulum_key() -> LevelKey {
    LevelKey {
        path: "kinetics/simple_pendulum.ron".into(),
        title: "Simple pendulum released from 60 degrees".into(),
    }
}

#[test]
fn progress_is_saved_and_read_back() {
    let dir = temp_dir("round-trip");
    let file = dir.join("progress.ron");
    let mut c = course_in(&file);
    assert_eq!(c.store.problem, None, "no file yet is no problem");
    let k = pendulum_key();
    c.progress.begin_attempt(&k, 2);
    c.progress.grade(
        &k,
        2,
        0,
        Graded {
            error: 0.003,
            right: true,
        },
        false,
    );
    c.progress.grade(
        &k,
        2,
        1,
        Graded {
            error: 0.2,
            right: false,
        },
        false,
    );
    c.progress.begin_attempt(&k, 2);
    c.progress.grade(
        &k,
        2,
        1,
        Graded {
            error: 0.001,
            right: true,
        },
        true,
    );
    assert_eq!(c.store.save(&mut c.progress), Ok(None));
    // Written whole: no temporary file left beside it.
    assert_eq!(names(&dir), ["progress.ron"]);
    let back = course_in(&file);
    assert_eq!(back.store.problem, None);
    assert_eq!(back.progress, c.progress);
    let r = back.progress.get(&k).unwrap();
    assert_eq!(
        (r.status, r.attempts, r.right()),
        (Status::SolvedWithHelp, 2, (2, 2))
    );
    assert_eq!(r.best_error(), Some(0.003));
}

/// A file that is not progress is moved aside under the name the message gives, its bytes
/// intact, and a save afterwards writes a new progress.ron beside it, never over it; a second
/// bad file goes under the next name.
#[test]
fn a_corrupt_file_is_kept_aside_reported_and_not_lost() {
    let dir = temp_dir("corrupt");
    let file = dir.join("progress.ron");
    let bad: &[u8] =
        b"(version: 1, levels: [(path: \"kinetics/a.ron\", title: \"A\", status: sovled";
    fs::write(&file, bad).unwrap();
    let mut c = course_in(&file);
    let problem = c.store.problem.clone().expect("the bad file is reported");
    let aside = dir.join("progress.ron.bad");
    assert!(problem.contains(&aside.display().to_string()), "{problem}");
    // The message says where in the file: line 1, the column of the misspelt status.
    assert!(problem.contains("progress.ron:1:"), "{problem}");
    assert_eq!(fs::read(&aside).unwrap(), bad);
    assert_eq!(c.progress.records.len(), 0, "the course starts afresh");
    // Saving writes a new file and leaves the bad one as it was.
    let k = pendulum_key();
    c.progress.begin_attempt(&k, 2);
    assert_eq!(c.store.save(&mut c.progress), Ok(None));
    assert_eq!(names(&dir), ["progress.ron", "progress.ron.bad"]);
    assert_eq!(fs::read(&aside).unwrap(), bad);
    // A second bad file: kept under the next name, the first untouched.
    fs::write(&file, "\u{0}binary").unwrap();
    let c = course_in(&file);
    let problem = c.store.problem.unwrap();
    assert!(problem.contains("progress.ron-2.bad"), "{problem}");
    assert_eq!(fs::read(&aside).unwrap(), bad);
    assert_eq!(
        fs::read_to_string(dir.join("progress.ron-2.bad")).unwrap(),
        "\u{0}binary"
    );
}

/// Progress from a newer rigidlab is not this one's to rewrite: it stays, byte for byte, and
/// this session's progress is not saved over it.
#[test]
fn a_newer_file_is_left_as_it_is() {
    let dir = temp_dir("newer");
    let file = dir.join("progress.ron");
    let newer = "(version: 3, levels: [], streak: 12)\n";
    fs::write(&file, newer).unwrap();
    let mut c = course_in(&file);
    let problem = c.store.problem.clone().unwrap();
    assert!(problem.contains("newer rigidlab"), "{problem}");
    c.progress.begin_attempt(&pendulum_key(), 2);
    assert!(c.store.save(&mut c.progress).is_err());
    assert_eq!(fs::read_to_string(&file).unwrap(), newer);
    assert_eq!(names(&dir), ["progress.ron"]);
}

/// The sandbox's pieces under MinimalPlugins, on `scene`: the run, the editor, the browser over
/// the library, the exercise and the course kept in `course`; the course's recorder in Update
/// (the window runs it right after the panels).
fn course_app(scene: &str, course: Course) -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene: rigidlab::level::load(Path::new(scene)).unwrap(),
            options: Default::default(),
            paused: true,
        })
        .add_plugins(EditorPlugin)
        .insert_resource(Browser::scan(Path::new("levels")))
        .init_resource::<Exercise>()
        .init_resource::<UiState>()
        .insert_resource(course)
        .add_systems(Update, course::track_progress);
    app.update();
    start_exercise(&mut app);
    app
}

/// What the panels do as a run starts: the exercise's grades cleared for it.
fn start_exercise(app: &mut App) {
    let (generation, n) = {
        let run = app.world().resource::<Run>();
        (run.generation, run.scene.level.questions.len())
    };
    app.world_mut().resource_mut::<UiState>().generation = Some(generation);
    app.world_mut().resource_mut::<Exercise>().start(n);
}

/// Types `text` into question `k`'s box and presses Check, then runs a frame.
fn answer(app: &mut App, k: usize, text: &str) {
    let q = app.world().resource::<Run>().scene.level.questions[k].clone();
    let mut ex = app.world_mut().resource_mut::<Exercise>();
    ex.answers[k] = text.to_string();
    ex.grades[k] = Some(grade(&q, text));
    app.update();
}

/// The course as drawn at 1280x800 into a bare egui context (the left panel's column without
/// the fold around it): the rows and the *Next level* target.
fn draw(app: &mut App) -> (Vec<course::DrawnRow>, Option<PathBuf>) {
    let ctx = egui::Context::default();
    let world = app.world_mut();
    world.resource_scope(|world, mut c: Mut<Course>| {
        let (browser, run, ex) = (
            world.resource::<Browser>(),
            world.resource::<Run>(),
            world.resource::<Exercise>(),
        );
        two_frames(&ctx, Vec::new(), |ui| {
            egui::Panel::left("levels")
                .default_size(300.0)
                .show(ui, |ui| {
                    let mut load = None;
                    course::next_level(ui, (browser, run, ex), &mut c, &mut load);
                    course::course(ui, browser, run, &mut c, &mut load);
                });
        });
        (c.rows.clone(), c.next.clone())
    })
}

fn row<'a>(rows: &'a [course::DrawnRow], path: &str) -> &'a course::DrawnRow {
    rows.iter()
        .find(|r| r.path == Path::new(path))
        .unwrap_or_else(|| panic!("no row drawn for {path}"))
}

/// The simple pendulum from 60 degrees, answered from the textbook: v = sqrt(2 g L (1 - cos 60))
/// = sqrt(g L) = 3.1321 m/s, T = m g + m v^2 / L = 2 m g = 19.62 N (m = 1 kg, L = 1 m,
/// g = 9.81 m/s^2). A wrong first answer makes the level "tried"; both right, "solved", in the
/// course's row and in progress.ron; the rows do not move; *Next level* points at the next
/// unsolved level of the course, past a solved one.
#[test]
fn solving_a_level_marks_it_solved_in_the_course() {
    let dir = temp_dir("app");
    let file = dir.join("progress.ron");
    let mut app = course_app(PENDULUM, course_in(&file));
    let (rows, next) = draw(&mut app);
    let before = row(&rows, PENDULUM).clone();
    assert_eq!(before.status, Status::NotTried);
    assert_eq!(
        next.as_deref(),
        Some(Path::new("levels/kinetics/simple_pendulum_param.ron")),
        "the next level of the course after the pendulum"
    );

    // A wrong answer: g itself, 9.81 m/s (213% off).
    answer(&mut app, 0, "9.81");
    let (rows, _) = draw(&mut app);
    let tried = row(&rows, PENDULUM);
    assert_eq!(tried.status, Status::Tried);
    assert!(
        tried.text.contains("tried") && tried.text.contains("1× 0/2"),
        "{}",
        tried.text
    );

    let (g, l, m) = (9.81_f64, 1.0, 1.0);
    let v = (2.0 * g * l * (1.0 - 60f64.to_radians().cos())).sqrt();
    answer(&mut app, 0, &format!("{v:.4}"));
    answer(&mut app, 1, &format!("{:.3} N", 2.0 * m * g));
    let (rows, next) = draw(&mut app);
    let solved = row(&rows, PENDULUM);
    assert_eq!(solved.status, Status::Solved, "{}", solved.text);
    assert!(solved.text.contains("✔ solved"), "{}", solved.text);
    // Still one attempt: both answers came in the same run.
    assert!(solved.text.contains("1×"), "{}", solved.text);
    // The rows stay where they were: a click aimed at a row lands on it.
    assert_eq!(solved.rect, before.rect);
    assert_eq!(
        next.as_deref(),
        Some(Path::new("levels/kinetics/simple_pendulum_param.ron"))
    );

    // Kept on disk: a window opened later reads it solved.
    let later = course_in(&file);
    assert_eq!(later.progress.status(&pendulum_key()), Status::Solved);

    // The next level once simple_pendulum_param is solved too: the one after it.
    {
        let mut c = app.world_mut().resource_mut::<Course>();
        let k = LevelKey {
            path: "kinetics/simple_pendulum_param.ron".into(),
            title: rigidlab::level::load(Path::new("levels/kinetics/simple_pendulum_param.ron"))
                .unwrap()
                .level
                .title,
        };
        c.progress.begin_attempt(&k, 2);
        for q in 0..2 {
            c.progress.grade(
                &k,
                2,
                q,
                Graded {
                    error: 0.0,
                    right: true,
                },
                false,
            );
        }
    }
    let (_, next) = draw(&mut app);
    assert_eq!(
        next.as_deref(),
        Some(Path::new(
            "levels/kinetics/two_rotor_torsional_vibration.ron"
        ))
    );
}

/// The last kinetics level's next is the first of energy, the topic after it in teaching
/// order (alphabetically energy comes before kinetics, and the next level was kinetics' first).
#[test]
fn the_next_level_follows_the_teaching_order() {
    let mut app = course_app(
        "levels/kinetics/zh_rotating_beam_distributed_inertia.ron",
        Course::default(),
    );
    let (rows, next) = draw(&mut app);
    assert_eq!(
        next.as_deref(),
        Some(Path::new("levels/energy/block_friction_work.ron"))
    );
    // Only the open level's topic is unfolded among seven: its rows are drawn, the others'
    // headers only.
    assert!(rows.iter().all(|r| r.path.starts_with("levels/kinetics")));
}

/// A bad progress file, reported in the status line at the first frame with the name it is
/// kept under.
#[test]
fn a_bad_file_is_reported_in_the_status_line() {
    let dir = temp_dir("status");
    let file = dir.join("progress.ron");
    fs::write(&file, "not progress").unwrap();
    let app = course_app(PENDULUM, course_in(&file));
    let (message, ok) = app
        .world()
        .resource::<UiState>()
        .message
        .clone()
        .expect("a status line");
    assert!(!ok && message.contains("progress.ron.bad"), "{message}");
    assert_eq!(
        fs::read_to_string(dir.join("progress.ron.bad")).unwrap(),
        "not progress"
    );
}
