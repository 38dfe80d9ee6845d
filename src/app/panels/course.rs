//! The course (left panel, under the open exercise): the library's levels by topic in teaching
//! order (`progress::TEACHING_ORDER`; the engine's stress levels last, marked as not exercises),
//! each level on one row of fixed height with its status, attempts and best error, each topic's
//! header with its solved/total; the *Next level* button under the questions; and the system
//! that records what the student does ([`track_progress`]) and keeps it (`progress_file.rs`).
//! The rules of the statuses are `progress.rs`'s.

use super::super::editor::Editor;
use super::super::progress::{self, Graded, LevelKey, Progress, Record, Status, TopicKind};
use super::super::progress_file::{self, Store};
use super::super::run::Run;
use super::super::ui::{color32, rich};
use super::super::view::palette;
use super::assignment_list::{self, AssignmentList};
use super::exercise::Exercise;
use super::level_browser::{version_line, Browser, Entry};
use super::state::UiState;
use crate::level::Scene;
use bevy::prelude::*;
use bevy_egui::egui;
use std::path::{Component, Path, PathBuf};

/// The student's progress through the course, where it is kept, and what the course drew last.
#[derive(Resource, Debug, Default)]
pub struct Course {
    pub progress: Progress,
    pub store: Store,
    /// The run of the exercise being recorded.
    sitting: Option<Sitting>,
    /// The store's problem was put in the status line.
    announced: bool,
    /// Each level row drawn last frame, in order (tests and the page read them).
    pub rows: Vec<DrawnRow>,
    /// The level the *Next level* button opens, as drawn last frame.
    pub next: Option<PathBuf>,
    /// The level on screen when the course was drawn last (its topic unfolds when it changes).
    shown: Option<PathBuf>,
}

/// A level's row as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnRow {
    pub path: PathBuf,
    pub status: Status,
    /// The row's text: status, title, attempts and error, as printed.
    pub text: String,
    pub rect: egui::Rect,
}

impl Course {
    /// The progress kept in the window's store (`progress_file::default_backend`).
    pub fn load() -> Course {
        Course::open(progress_file::default_backend())
    }

    /// The progress kept in `backend` (None: for this session only).
    pub fn open(backend: Option<Box<dyn progress_file::Backend>>) -> Course {
        let (progress, store) = Store::open(backend);
        Course {
            progress,
            store,
            ..Default::default()
        }
    }
}

/// One run of an exercise as recorded: the grades already taken in, and whether it counted as
/// an attempt yet.
#[derive(Debug, Clone)]
struct Sitting {
    file: PathBuf,
    generation: u64,
    key: LevelKey,
    seen: Vec<Option<(f64, f64, bool)>>,
    counted: bool,
    /// The worked solution was shown at some time in this run.
    help: bool,
}

/// A level's key: its path under the levels folder `root` (`kinetics/x.ron`), else its path as
/// given (a saved level: `saved-levels/x.ron`), and its title.
pub fn level_key(root: &Path, file: &Path, title: &str) -> LevelKey {
    let plain = |p: &Path| -> PathBuf {
        p.components()
            .filter(|c| !matches!(c, Component::CurDir))
            .collect()
    };
    let (root, file) = (plain(root), plain(file));
    let rel = file
        .strip_prefix(&root)
        .map(Path::to_path_buf)
        .ok()
        .or_else(|| {
            // `rigidlab play /abs/levels/x.ron` beside a relative root: compare real paths.
            let (r, f) = (root.canonicalize().ok()?, file.canonicalize().ok()?);
            f.strip_prefix(r).map(Path::to_path_buf).ok()
        });
    let shown = rel.unwrap_or(file);
    let parts: Vec<String> = shown
        .components()
        .map(|c| c.as_os_str().to_string_lossy().to_string())
        .collect();
    LevelKey {
        path: parts.join("/"),
        title: title.to_string(),
    }
}

/// Records the exercise's grades into the progress, once the panels have started the exercise
/// for the run on screen (after them in the frame), and keeps it: a newly graded answer is taken
/// in, the run's first one counts an attempt. A scene with edits not saved is not the level its
/// file holds (its answers may be edited too) and is not recorded.
pub fn track_progress(
    run: Res<Run>,
    ex: Res<Exercise>,
    browser: Res<Browser>,
    editor: Option<Res<Editor>>,
    mut st: ResMut<UiState>,
    mut course: ResMut<Course>,
) {
    let course = &mut *course;
    if !course.announced {
        course.announced = true;
        if let Some(p) = course.store.problem.clone() {
            say(&mut st, p);
        }
    }
    if st.generation != Some(run.generation) || editor.is_some_and(|e| e.unsaved(&run)) {
        return;
    }
    let n = run.scene.level.questions.len();
    if n == 0 || ex.grades.len() != n {
        return;
    }
    let fresh = course
        .sitting
        .as_ref()
        .is_none_or(|s| s.file != run.scene.file || s.generation != run.generation);
    if fresh {
        course.sitting = Some(Sitting {
            file: run.scene.file.clone(),
            generation: run.generation,
            key: level_key(&browser.root, &run.scene.file, &run.scene.level.title),
            seen: vec![None; n],
            counted: false,
            help: false,
        });
    }
    let s = course.sitting.as_mut().expect("a sitting was just made");
    s.help |= ex.help_used;
    let mut changed = false;
    for (k, g) in ex.grades.iter().enumerate() {
        let Some(Ok(g)) = g else { continue };
        let now = Some((g.answer, g.rel_error, g.passed));
        if s.seen[k] == now {
            continue;
        }
        s.seen[k] = now;
        if !s.counted {
            s.counted = true;
            course.progress.begin_attempt(&s.key, n);
        }
        let graded = Graded {
            error: g.rel_error,
            right: g.passed,
        };
        course.progress.grade(&s.key, n, k, graded, s.help);
        changed = true;
    }
    if changed {
        match course.store.save(&mut course.progress) {
            Ok(None) => {}
            Ok(Some(note)) | Err(note) => say(&mut st, note),
        }
    }
}

/// A problem in the status line, beside one already there (the preferences' at the first frame).
fn say(st: &mut UiState, problem: String) {
    st.message = Some(match st.message.take() {
        Some((m, false)) if m != problem => (format!("{m} · {problem}"), false),
        _ => (problem, false),
    });
}

/// The course's exercises in order, each with its key: levels that load and ask a question, in
/// the topics that are the course (not the saved levels, not the stress levels).
fn exercises(browser: &Browser) -> Vec<(LevelKey, &Entry)> {
    topics(browser)
        .into_iter()
        .filter(|(t, _)| TopicKind::of(t).is_course())
        .flat_map(|(_, entries)| entries)
        .filter(|e| e.is_exercise())
        .map(|e| (level_key(&browser.root, &e.path, &e.title), e))
        .collect()
}

/// The browser's topics in course order.
fn topics(browser: &Browser) -> Vec<(&str, &[Entry])> {
    let mut t: Vec<(&str, &[Entry])> = browser
        .groups
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_slice()))
        .collect();
    t.sort_by(|a, b| progress::topic_order(a.0, b.0));
    t
}

/// The course's exercises solved, of all of them.
pub fn solved_count(browser: &Browser, course: &Course) -> (usize, usize) {
    let all = exercises(browser);
    let solved = all
        .iter()
        .filter(|(k, _)| course.progress.status(k).is_solved())
        .count();
    (solved, all.len())
}

/// The *Next level* button under the questions: enabled once every question of the open level
/// has been answered right (now, or in an earlier attempt), it opens the next level of the
/// course not solved yet. Its row is there whenever the level asks a question, so nothing below
/// moves when it turns on.
pub fn next_level(
    ui: &mut egui::Ui,
    (browser, phys, ex): (&Browser, &Run, &Exercise),
    course: &mut Course,
    load: &mut Option<Scene>,
) {
    course.next = None;
    let level = &phys.scene.level;
    if level.questions.is_empty() && level.challenge.is_none() {
        return;
    }
    let key = level_key(&browser.root, &phys.scene.file, &level.title);
    let right_now = !level.questions.is_empty()
        && ex.grades.len() == level.questions.len()
        && ex
            .grades
            .iter()
            .all(|g| matches!(g, Some(Ok(g)) if g.passed));
    let done = right_now || course.progress.status(&key).is_solved();
    if let Some(a) = browser.assignment.as_ref() {
        if a.entries.iter().any(|e| e.path == phys.scene.file) {
            // Inside an assignment the next level is the assignment's, in the teacher's order:
            // it went to the library's next, out of the assignment.
            assignment_next(ui, (browser, a, phys), done, course, load);
            return;
        }
    }
    let order = exercises(browser);
    let keys: Vec<LevelKey> = order.iter().map(|(k, _)| k.clone()).collect();
    let here = order.iter().position(|(_, e)| e.path == phys.scene.file);
    let next = progress::next_unsolved(&keys, here, &course.progress).map(|i| order[i].1);
    ui.horizontal(|ui| match next {
        Some(e) => {
            course.next = Some(e.path.clone());
            let file = e.path.file_name().unwrap_or_default().to_string_lossy();
            let label = if e.title == level.title {
                // A variant of this level (simple_pendulum_param.ron): the title alone reads as
                // this one.
                format!("Next level ▶ {} ({file})", e.title)
            } else {
                format!("Next level ▶ {}", e.title)
            };
            let b = ui
                .add_enabled(done, egui::Button::new(label).truncate())
                .on_hover_text(format!("{}\n\n{}", e.path.display(), e.statement))
                .on_disabled_hover_text("answer every question right first");
            if b.clicked() {
                open_next(ui, e.load(), load);
            }
        }
        None if done => {
            ui.label(rich(
                "✔ every exercise of the course is solved",
                palette::GRAVITY,
            ));
        }
        None => {
            ui.label(rich(
                "the last exercise of the course left to solve",
                palette::OUTLINE,
            ));
        }
    });
}

/// *Next level* for a level of the assignment: the next one of it not solved yet, in the
/// teacher's order after this one (round to its start), or, once every level of it is solved,
/// that the assignment is finished. A level of it that does not load is not offered.
fn assignment_next(
    ui: &mut egui::Ui,
    (browser, a, phys): (&Browser, &AssignmentList, &Run),
    done: bool,
    course: &mut Course,
    load: &mut Option<Scene>,
) {
    let rows: Vec<&assignment_list::Row> = a.entries.iter().filter(|e| e.error.is_none()).collect();
    let keys: Vec<LevelKey> = rows
        .iter()
        .map(|e| level_key(&browser.root, &e.path, &e.title))
        .collect();
    let here = rows.iter().position(|e| e.path == phys.scene.file);
    let next = progress::next_unsolved(&keys, here, &course.progress).map(|i| rows[i]);
    ui.horizontal(|ui| match next {
        Some(e) => {
            course.next = Some(e.path.clone());
            let n = a
                .entries
                .iter()
                .position(|r| r.path == e.path)
                .map_or(0, |k| k + 1);
            let b = ui
                .add_enabled(
                    done,
                    egui::Button::new(format!(
                        "Next level ▶ {} (level {n} of the assignment)",
                        e.title
                    ))
                    .truncate(),
                )
                .on_hover_text(format!(
                    "level {n} of the assignment “{}”\n{}\n\n{}",
                    a.title,
                    e.path.display(),
                    e.statement
                ))
                .on_disabled_hover_text("answer every question right first");
            if b.clicked() {
                open_next(ui, e.load(), load);
            }
        }
        None if done => {
            ui.label(rich(
                format!(
                    "✔ the assignment “{}” is finished: every level of it is solved",
                    a.title
                ),
                palette::GRAVITY,
            ));
        }
        None => {
            ui.label(rich(
                "the last level of the assignment left to solve",
                palette::OUTLINE,
            ));
        }
    });
}

/// The course's body: where progress is kept and what went wrong with it, then each topic with
/// its levels. A clicked level that loads is put in `load`.
pub fn course(
    ui: &mut egui::Ui,
    browser: &Browser,
    phys: &Run,
    course: &mut Course,
    load: &mut Option<Scene>,
) {
    course.rows.clear();
    let new_level = course.shown.as_ref() != Some(&phys.scene.file);
    course.shown = Some(phys.scene.file.clone());
    if let Some(p) = &course.store.problem {
        ui.label(rich(p.clone(), palette::NORMAL).small());
    }
    let many = browser.groups.len() > 6;
    for (topic, entries) in topics(browser) {
        let kind = TopicKind::of(topic);
        let title = match kind {
            TopicKind::Stress => format!("{topic}: engine tests, not exercises"),
            TopicKind::Saved => topic.to_string(),
            _ => {
                let keys: Vec<LevelKey> = entries
                    .iter()
                    .filter(|e| e.is_exercise())
                    .map(|e| level_key(&browser.root, &e.path, &e.title))
                    .collect();
                let solved = keys
                    .iter()
                    .filter(|k| course.progress.status(k).is_solved())
                    .count();
                format!("{topic}   {solved}/{} solved", keys.len())
            }
        };
        let here = entries.iter().any(|e| e.path == phys.scene.file);
        let mut header = egui::CollapsingHeader::new(title)
            .id_salt(("course topic", topic))
            .default_open(here || !many);
        if here && new_level {
            // A level opened from elsewhere (Next level into the next topic): its topic shows.
            header = header.open(Some(true));
        }
        header.show(ui, |ui| {
                if kind == TopicKind::Stress {
                    ui.label(
                        rich(
                            "scenes that push the engine (rigidlab check runs their checks); no questions",
                            palette::OUTLINE,
                        )
                        .small(),
                    );
                }
                for e in entries {
                    let key = level_key(&browser.root, &e.path, &e.title);
                    let rec = course.progress.get(&key);
                    let look = RowLook::of(e, rec, kind);
                    let r = row(ui, &look, e.path == phys.scene.file, kind == TopicKind::Saved);
                    course.rows.push(DrawnRow {
                        path: e.path.clone(),
                        status: rec.map_or(Status::NotTried, |r| r.status),
                        text: format!("{} {} {}", look.status, e.title, look.numbers),
                        rect: r.rect,
                    });
                    let r = r.on_hover_text(hover_text(e, rec, kind));
                    if r.clicked() && e.error.is_none() {
                        match e.load() {
                            Ok(s) => *load = Some(s),
                            Err(err) => {
                                ui.label(rich(err.to_string(), palette::NORMAL));
                            }
                        }
                    }
                }
            });
    }
}

/// What a row shows: the status word and its color, the title (with the file and time for a
/// saved version), and the numbers on the right.
struct RowLook {
    status: String,
    color: Option<Color>,
    title: String,
    numbers: String,
}

impl RowLook {
    fn of(e: &Entry, rec: Option<&Record>, kind: TopicKind) -> RowLook {
        let title = if kind == TopicKind::Saved {
            format!("{}\n{}", e.title, version_line(e))
        } else {
            e.title.clone()
        };
        let plain = |status: &str, numbers: &str, color| RowLook {
            status: status.into(),
            color,
            title: title.clone(),
            numbers: numbers.into(),
        };
        if e.error.is_some() {
            return plain("⚠", "does not load", Some(palette::NORMAL));
        }
        if kind == TopicKind::Stress {
            return plain("", "engine test", None);
        }
        if !e.is_exercise() {
            return plain("", "no questions", None);
        }
        let Some(r) = rec else {
            return plain(Status::NotTried.word(), "", None);
        };
        let color = match r.status {
            Status::NotTried => None,
            Status::Tried => Some(palette::ACCEL),
            Status::SolvedWithHelp => Some(palette::VELOCITY),
            Status::Solved => Some(palette::GRAVITY),
        };
        let mut numbers = String::new();
        if r.attempts > 0 {
            numbers = format!("{}×", r.attempts);
        }
        if e.challenge {
            // Launches, and the stars of the launch that met it (as the Challenge box shows).
            if r.status.is_solved() {
                numbers.push_str(&format!(
                    " {}",
                    "*".repeat(progress::stars(r.attempts).into())
                ));
            }
            return plain(r.status.word(), numbers.trim(), color);
        }
        match r.best_error() {
            Some(err) => numbers.push_str(&format!(" {}", percent(err))),
            None if r.attempts > 0 => {
                let (right, n) = r.right();
                numbers.push_str(&format!(" {right}/{n}"));
            }
            None => {}
        }
        plain(r.status.word(), numbers.trim(), color)
    }
}

/// A challenge row's hover: met at which launch with its stars, or the launches so far.
fn challenge_hover(rec: Option<&Record>) -> String {
    match rec {
        Some(r) if r.status.is_solved() => format!(
            "\n\nchallenge met at launch {}: {} star{}",
            r.attempts,
            progress::stars(r.attempts),
            if progress::stars(r.attempts) == 1 {
                ""
            } else {
                "s"
            }
        ),
        Some(r) if r.attempts > 0 => format!(
            "\n\nchallenge not met yet: {} launch{}",
            r.attempts,
            if r.attempts == 1 { "" } else { "es" }
        ),
        _ => "\n\nchallenge: not launched yet".into(),
    }
}

/// A challenge's launch ended on the level on screen: `met` its goal, `error` the control's
/// relative distance from the worked value. Recorded as an attempt until the challenge is met
/// (`progress::launch`) and kept; a problem keeping it, for the status line.
pub fn record_launch(
    course: &mut Course,
    browser: &Browser,
    phys: &Run,
    met: bool,
    error: f64,
) -> Option<String> {
    let key = level_key(&browser.root, &phys.scene.file, &phys.scene.level.title);
    if !progress::launch(&mut course.progress, &key, met, error) {
        return None;
    }
    match course.store.save(&mut course.progress) {
        Ok(None) => None,
        Ok(Some(note)) | Err(note) => Some(note),
    }
}

/// The launches recorded for the challenge on screen, and its stars once met.
pub fn challenge_record(course: &Course, browser: &Browser, phys: &Run) -> (u32, Option<u8>) {
    let key = level_key(&browser.root, &phys.scene.file, &phys.scene.level.title);
    let launches = course.progress.get(&key).map_or(0, |r| r.attempts);
    (launches, progress::challenge_stars(&course.progress, &key))
}

/// A relative error as the course prints it: `0.42%`, `<0.01%`.
pub fn percent(err: f64) -> String {
    if err < 5e-5 {
        "<0.01%".into()
    } else {
        format!("{:.2}%", err * 100.0)
    }
}

/// The width of the status column, points.
const STATUS_WIDTH: f32 = 58.0;

/// One level's row: a fixed height (one line, two for a saved version), the whole row a click
/// target; the status on the left, the numbers on the right, the title cut to fit between them.
fn row(ui: &mut egui::Ui, look: &RowLook, current: bool, two_lines: bool) -> egui::Response {
    let line = ui.text_style_height(&egui::TextStyle::Body);
    let pad = 3.0;
    let lines = if two_lines { 2.0 } else { 1.0 };
    let size = egui::vec2(ui.available_width(), line * lines + 2.0 * pad);
    let (rect, r) = ui.allocate_exact_size(size, egui::Sense::click());
    if !ui.is_rect_visible(rect) {
        return r;
    }
    let v = ui.visuals();
    let fill = if current {
        Some(v.selection.bg_fill)
    } else if r.hovered() {
        Some(v.widgets.hovered.weak_bg_fill)
    } else {
        None
    };
    let painter = ui.painter_at(rect);
    if let Some(f) = fill {
        painter.rect_filled(rect, 2.0, f);
    }
    let text_color = v.text_color();
    let weak = v.weak_text_color();
    let font = egui::TextStyle::Body.resolve(ui.style());
    let top = rect.top() + pad;
    let status_color = look.color.map_or(weak, color32);
    painter.text(
        egui::pos2(rect.left() + 2.0, top),
        egui::Align2::LEFT_TOP,
        &look.status,
        font.clone(),
        status_color,
    );
    let numbers = painter.layout_no_wrap(look.numbers.clone(), font.clone(), weak);
    let right = rect.right() - 4.0;
    painter.galley(
        egui::pos2(right - numbers.size().x, top),
        numbers.clone(),
        weak,
    );
    let title_left = rect.left() + STATUS_WIDTH;
    let room = (right - numbers.size().x - 8.0 - title_left).max(20.0);
    let mut job = egui::text::LayoutJob::simple(look.title.clone(), font, text_color, room);
    job.wrap.max_rows = lines as usize;
    job.wrap.break_anywhere = true;
    job.wrap.overflow_character = Some('…');
    let title = painter.layout_job(job);
    painter.galley(egui::pos2(title_left, top), title, text_color);
    r
}

/// A row's hover: the title whole, the statement (or why it does not load), the status and the
/// numbers explained.
fn hover_text(e: &Entry, rec: Option<&Record>, kind: TopicKind) -> String {
    if let Some(err) = &e.error {
        return err.clone();
    }
    let mut t = e.title.clone();
    if !e.statement.is_empty() {
        t.push_str("\n\n");
        t.push_str(&e.statement);
    }
    if kind == TopicKind::Stress || !e.is_exercise() {
        return t;
    }
    let status = rec.map_or(Status::NotTried, |r| r.status);
    if e.challenge {
        t.push_str(&challenge_hover(rec));
        return t;
    }
    t.push_str(&format!("\n\n{}", status.meaning()));
    if let Some(r) = rec {
        let (right, n) = r.right();
        t.push_str(&format!(
            "\n{} attempt{}; {right} of {n} question{} answered right",
            r.attempts,
            if r.attempts == 1 { "" } else { "s" },
            if n == 1 { "" } else { "s" }
        ));
        if let Some(err) = r.best_error() {
            t.push_str(&format!(
                "\nbest error {}: the worst question's best answer",
                percent(err)
            ));
        }
    }
    t
}

/// *Next level* clicked: the level opens, or the reason it does not shows under the button.
fn open_next<E: std::fmt::Display>(
    ui: &mut egui::Ui,
    loaded: Result<Scene, E>,
    load: &mut Option<Scene>,
) {
    match loaded {
        Ok(s) => *load = Some(s),
        Err(err) => {
            ui.label(rich(err.to_string(), palette::NORMAL));
        }
    }
}
