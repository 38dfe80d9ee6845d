//! The sandbox in a web page (wasm32, WebGL2): the same plugins as the native window
//! ([`super::sandbox::add_sandbox`]) drawn into the page's `<canvas id="rigidlab">`, with the level library
//! the page fetched beside the wasm (`page_library.rs`; a page has no file system).
//!
//! The page's URL chooses what opens (`web/index.html` documents it):
//! - `#level=DATA&name=FILE.ron` opens the level carried in the link itself (`level::link`, made by
//!   `rigidlab link`); a link that does not decode says why and opens no other exercise;
//! - `?url=PATH` fetches a level or an assignment served beside the page (`page_fetch.rs`);
//! - `?level=kinetics/simple_pendulum.ron` opens that library level (default: the window's first, `sandbox::first_exercise`);
//! - `&play=1` starts it running (default: paused, as the native window opens);
//! - `&predict=1` opens it in predict-first mode: the motion waits for the student's answers
//!   (`panels/predict.rs`), for every level opened in the page;
//! - `?check=1` runs the checks and questions headless instead of opening the window, the level's
//!   or the whole library's, and writes the report `rigidlab check --json` writes into
//!   `<pre id="rigidlab-report">`: the numbers in the page are the core's.
//!
//! Every frame the app writes its state as JSON into `<pre id="rigidlab-status">` (level, time,
//! paused, frame rate, the view's mapping from metres to CSS pixels, each question's answer box
//! and grade, the predict-first phase): what a screen reader, a teacher's script or the browser test reads.

use super::frame_rate::FrameRate;
use super::panels::{self, Browser, Exercise, UiState};
use super::playback::Playback;
use super::run::Run;
use super::view::View;
use crate::level::Scene;
use bevy::prelude::*;
use std::path::{Path, PathBuf};

/// The level library, fetched by the page as `levels.json` (`page_library.rs`).
pub use super::library::library;

/// What the page's URL asks for.
#[derive(Debug, Default, Clone)]
struct PageQuery {
    level: Option<PathBuf>,
    /// The level the link carries (`#level=`), or why it does not decode.
    link: Option<Result<Scene, String>>,
    /// A level or an assignment to fetch from the page's origin (`?url=`).
    url: Option<String>,
    play: bool,
    check: bool,
    /// `?student=ID`: a level with parameters opens with this student's own numbers, the same
    /// as `rigidlab check --student ID` gives natively.
    student: Option<String>,
    predict: bool,
}

impl PageQuery {
    /// The variant the URL asks for: the student's, or the nominal one.
    fn pick(&self) -> crate::level::params::Pick {
        self.student.clone().map_or(
            crate::level::params::Pick::Nominal,
            crate::level::params::Pick::Student,
        )
    }

    fn from_page() -> PageQuery {
        let mut q = PageQuery::default();
        let search = web_sys::window().and_then(|w| w.location().search().ok());
        let params = search.and_then(|s| web_sys::UrlSearchParams::new_with_str(&s).ok());
        // The student first: every way a level opens (a link, a fetched file, the library) gives
        // their own numbers (`app/student.rs`).
        q.student = params
            .as_ref()
            .and_then(|p| p.get("student"))
            .filter(|s| !s.trim().is_empty());
        super::student::set(q.student.clone());
        let hash = web_sys::window().and_then(|w| w.location().hash().ok());
        q.link = hash
            .as_deref()
            .and_then(|h| crate::level::link::open_fragment_as(h, &q.pick()))
            .map(|r| r.map_err(|e| format!("the link did not open: {e}\n  help: {}", e.help())));
        let Some(params) = params else {
            return q;
        };
        if let Some(l) = params.get("level").filter(|l| !l.is_empty()) {
            // Both `kinetics/x.ron` and `levels/kinetics/x.ron` name the same level.
            let l = l.trim_start_matches('/');
            let l = l.strip_prefix("levels/").unwrap_or(l);
            q.level = Some(Path::new("levels").join(l));
        }
        q.url = params.get("url").filter(|u| !u.is_empty());
        let yes = |k: &str| params.get(k).is_some_and(|v| v != "0" && v != "false");
        q.play = yes("play");
        q.check = yes("check");
        q.predict = yes("predict");
        q
    }
}

/// The page's entry point (`main` of the wasm build).
pub fn start() {
    let query = PageQuery::from_page();
    let browser = Browser::embedded(Path::new("levels"), library());
    let asked = query.level.is_some() || query.link.is_some();
    let (scene, note) = match (&query.link, &query.level) {
        // A link carries its level whole: it comes before a library level.
        (Some(Ok(s)), _) => (s.clone(), None),
        (Some(Err(why)), _) => (super::sandbox::empty_scene(), Some(why.clone())),
        // The fetched level or assignment opens when it arrives.
        _ if query.url.is_some() => (super::sandbox::empty_scene(), None),
        (None, Some(p)) => match browser.find(p).map(|e| e.load_variant(&query.pick())) {
            Some(Ok(s)) => (s, None),
            // A level asked for and not opened: an empty scene, the reason in the status line
            // and the library beside it, never another exercise the student would take for it.
            Some(Err(e)) => (super::sandbox::empty_scene(), Some(e.to_string())),
            None => (
                super::sandbox::empty_scene(),
                Some(format!(
                    "no level {} in the library: the URL's ?level= is a path under levels/, e.g. kinetics/simple_pendulum.ron",
                    p.display()
                )),
            ),
        },
        (None, None) => (super::sandbox::first_exercise(&browser), None),
    };
    if query.check {
        let scenes: Vec<Scene> = match (asked, note.is_none()) {
            (true, true) => vec![scene],
            _ => browser
                .groups
                .values()
                .flatten()
                .filter_map(|e| e.load().ok())
                .collect(),
        };
        let report = check(&scenes, note);
        set_text("rigidlab-report", &crate::report::json(&report));
        set_text("rigidlab-status", r#"{"check": "done"}"#);
        return;
    }
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(WindowPlugin {
        primary_window: Some(Window {
            title: "rigidlab".into(),
            canvas: Some("#rigidlab".into()),
            fit_canvas_to_parent: true,
            ..default()
        }),
        ..default()
    }));
    super::sandbox::add_sandbox(&mut app, scene, browser, !query.play || query.predict);
    app.add_plugins(super::page_fonts::PageFontsPlugin);
    if query.predict {
        app.world_mut().resource_mut::<panels::Predict>().switch = Some(true);
    }
    app.insert_resource(PageState { note });
    app.add_systems(Update, (show_page_note, open_picked_file));
    if let Some(url) = query.url {
        app.insert_resource(super::page_fetch::start(url));
        app.add_systems(Update, receive_fetched);
    }
    app.add_systems(Last, publish_status);
    app.run();
}

/// Why the URL's level did not open, in the panels' status line until something replaces it.
fn show_page_note(page: Res<PageState>, mut st: ResMut<UiState>, mut shown: Local<bool>) {
    // After the first frame: the panels set their own state up in it.
    if !*shown && st.generation.is_some() {
        *shown = true;
        if let Some(n) = &page.note {
            st.message = Some((
                format!("{n}; pick a level in the library on the left"),
                false,
            ));
        }
    }
}

/// The `?url=` fetch's status line while it is under way, and what arrived once: a level opened,
/// an assignment listed and its first level that loads opened, or why not (red), never another
/// exercise.
fn receive_fetched(
    fetch: Res<super::page_fetch::PageFetch>,
    mut st: ResMut<UiState>,
    mut browser: ResMut<Browser>,
    mut done: Local<bool>,
) {
    use super::page_fetch::Fetched;
    if *done || st.generation.is_none() {
        // Before the panels' first frame they set their own state up.
        return;
    }
    let Some(r) = fetch.take() else {
        st.message = Some((format!("opening {}…", fetch.asked), true));
        return;
    };
    *done = true;
    match r {
        Ok(Fetched::Level(s)) => {
            st.message = None;
            st.pending_open = Some(*s);
        }
        Ok(Fetched::Assignment(a, texts)) => {
            let list = panels::assignment_list::AssignmentList::from_texts(&a, texts);
            st.message = Some((format!("assignment: {}", list.title), true));
            st.pending_open = list.first_loadable();
            browser.assignment = Some(list);
        }
        Err(why) => {
            st.message = Some((
                format!("{why}; pick a level in the library on the left"),
                false,
            ))
        }
    }
}

/// Runs `scenes` with the core's runner and default settings, as `rigidlab check` does.
fn check(scenes: &[Scene], note: Option<String>) -> crate::report::Report {
    let opts = crate::sim::Options::default();
    let mut levels = Vec::new();
    for scene in scenes {
        match crate::runner::run_graded(scene, &opts, &Default::default(), |_| {}) {
            Ok(r) => levels.push(r),
            Err(e) => {
                let mut r = crate::report::LevelReport::failed(&scene.file, &e.to_string());
                r.title = scene.level.title.clone();
                levels.push(r)
            }
        }
    }
    if let Some(n) = note {
        levels.push(crate::report::LevelReport::failed(Path::new("?level="), &n));
    }
    crate::report::Report {
        passed: levels.iter().all(|l| l.passed),
        levels,
    }
}

/// What the page adds to the app's state: why the URL's level did not open.
#[derive(Resource, Default)]
struct PageState {
    note: Option<String>,
}

fn publish_status(
    phys: Res<Run>,
    playback: Res<Playback>,
    view: Res<View>,
    st: Res<UiState>,
    ex: Res<Exercise>,
    rate: Res<FrameRate>,
    page: Res<PageState>,
    editor: Res<super::editor::Editor>,
    predict: Res<panels::Predict>,
    browser: Res<Browser>,
    course: Res<panels::Course>,
) {
    let s = phys.snapshot();
    let answers: Vec<serde_json::Value> = phys
        .sim
        .level
        .questions
        .iter()
        .enumerate()
        .map(|(k, q)| {
            let rect = ex.answer_boxes.get(k).copied().flatten();
            // A grade held back while predicting is not on the screen: not here either.
            let grade = ex
                .grades
                .get(k)
                .cloned()
                .flatten()
                .filter(|g| !(ex.hold_grades && g.is_ok()));
            let (message, right) = match &grade {
                Some(g) => {
                    let (m, r) = panels::grade_message(q, g);
                    (Some(m), Some(r))
                }
                None => (None, None),
            };
            serde_json::json!({
                "id": q.id,
                "box": rect.map(|r| [r.min.x, r.min.y, r.width(), r.height()]),
                "typed": ex.answers.get(k),
                "grade": message,
                "right": right,
            })
        })
        .collect();
    let status = serde_json::json!({
        "level": phys.scene.file.display().to_string(),
        "title": phys.sim.level.title,
        "t": s.time,
        "step": s.step,
        "paused": playback.paused,
        "at_end": s.time >= phys.sim.level.world.duration - 0.5 * phys.sim.dt(),
        "frames": rate.frames,
        "frame_ms_median": rate.median_ms(),
        "fps": rate.fps(),
        "view": {
            "center": [view.center.x, view.center.y],
            "m_per_px": view.m_per_px,
            "viewport": [view.viewport.min.x, view.viewport.min.y, view.viewport.max.x, view.viewport.max.y],
        },
        "answers": answers,
        "predict": predict.phase.name(),
        "bodies": phys.scene.level.bodies.len(),
        "joints": phys.scene.level.joints.len(),
        "buttons": st
            .buttons
            .iter()
            .map(|(k, r)| (k.clone(), serde_json::json!([r.min.x, r.min.y, r.width(), r.height()])))
            .collect::<serde_json::Map<String, serde_json::Value>>(),
        "editor": editor.note.as_ref().map(|(m, ok)| serde_json::json!({"text": m, "ok": ok})),
        "message": st.message.as_ref().map(|(m, ok)| serde_json::json!({"text": m, "ok": ok})),
        "error": phys.error,
        "note": page.note,
        "course": super::progress_file::status_json(&course.progress, &course.store),
        "assignment": browser.assignment.as_ref().map(|a| serde_json::json!({
            "title": a.title,
            "due": a.due,
            "levels": a.entries.iter().map(|e| serde_json::json!({
                "path": e.path.display().to_string(),
                "title": e.title,
                "error": e.error,
            })).collect::<Vec<_>>(),
        })),
    });
    set_text("rigidlab-status", &status.to_string());
}

/// A level file the user picked in the page (`web/index.html` puts its text into
/// `<textarea id="rigidlab-open" data-name="...">`): parsed and opened like a click in the level
/// browser, or its error (with line and column) shown in the panel's message line.
fn open_picked_file(mut st: ResMut<UiState>) {
    let Some(el) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("rigidlab-open"))
    else {
        return;
    };
    let text = el.text_content().unwrap_or_default();
    if text.is_empty() {
        return;
    }
    let name = el
        .get_attribute("data-name")
        .unwrap_or_else(|| "picked.ron".into());
    el.set_text_content(None);
    match crate::level::parse(Path::new(&name), &text) {
        Ok(scene) => st.pending_open = Some(scene),
        Err(e) => st.message = Some((format!("{name} did not open:\n{e}"), false)),
    }
}

/// Sets the text of the page element `id` (absent: nothing to do; the page may not have it).
fn set_text(id: &str, text: &str) {
    if let Some(el) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(id))
    {
        el.set_text_content(Some(text));
    }
}
