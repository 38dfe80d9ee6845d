//! The course's progress (and the first-steps tour's) kept between runs: natively `progress.ron` beside `prefs.ron` (the folder
//! `prefs::path` names, so `RIGIDLAB_PREFS` moves both), in the page the browser's localStorage
//! (key `rigidlab.progress`). Both hold the same RON text ([`to_text`], [`parse`]).
//!
//! Nothing the student earned is lost:
//! - a file is written whole (a temporary file renamed over it, `files::write_replacing`), so a
//!   crash leaves the old file or the new one, never half of one;
//! - before writing, what is stored is read again and merged in ([`Progress::merge`]): a second
//!   window's solves are kept, not written over;
//! - what cannot be read as progress (not RON, a misspelt field, a status that does not exist,
//!   a FIFO, too large) is said in the status line and the course's note and moved aside under a
//!   name of its own (`progress.ron.bad`, `progress.ron-2.bad` beside an earlier one; in the page
//!   `rigidlab.progress.bad`), which the message names; the course starts afresh;
//! - progress written by a newer rigidlab (a `version` above [`VERSION`]) is left where it is and
//!   nothing is saved over it that session;
//! - a file that cannot be read at all (no permission), or moved aside, is left as it is, and
//!   nothing is saved that session.
//!
//! No Bevy: the window holds a [`Store`] in its course state (`panels/course.rs`).

use super::progress::{Progress, Record, TourRecord};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The format this rigidlab writes and reads (a file with a higher one is a newer rigidlab's).
/// 2 (2026-12-07) adds the first-steps tour (`tour:`), which a rigidlab reading 1 would refuse
/// as an unknown field and move aside; a file of version 1 reads as it did.
pub const VERSION: u32 = 2;

/// The largest progress file read, bytes (a whole library solved is about 40 KiB).
pub const MAX_PROGRESS_BYTES: u64 = 4 << 20;

/// The first line of the text: what the file is, for a student who opens it.
const HEADER: &str = "// rigidlab: the course's progress (docs/student.md#the-course). A file rigidlab cannot read is moved aside, never replaced.";

#[derive(Serialize, Deserialize)]
#[serde(rename = "Progress", deny_unknown_fields)]
struct ProgressText {
    version: u32,
    levels: Vec<Record>,
    /// The first-steps tour (format 2), left out while nothing of it is done.
    #[serde(default, skip_serializing_if = "TourRecord::is_empty")]
    tour: TourRecord,
}

/// Only the version, read before the rest so a newer format is told apart from a broken file.
#[derive(Deserialize)]
#[serde(rename = "Progress")]
struct VersionOnly {
    version: u32,
}

/// What stored text holds.
#[derive(Debug, Clone, PartialEq)]
pub enum Parsed {
    Progress(Progress),
    /// Written by a newer rigidlab, in this format version.
    Newer(u32),
}

/// The progress as stored text.
pub fn to_text(p: &Progress) -> String {
    let text = ProgressText {
        version: VERSION,
        levels: p.records.clone(),
        tour: p.tour.clone(),
    };
    // A level a line or so: its questions' answers on its `questions:` line.
    let pretty = ron::ser::PrettyConfig::default().depth_limit(3);
    let body = ron::ser::to_string_pretty(&text, pretty)
        .unwrap_or_else(|e| format!("// not written: {e}"));
    format!("{HEADER}\n{body}\n")
}

/// Reads stored text (`name` is where it came from, for the message): Err says what is wrong
/// at `name:line:col`.
pub fn parse(name: &str, text: &str) -> Result<Parsed, String> {
    let at = |e: ron::error::SpannedError| {
        format!(
            "{name}:{}:{}: {}",
            e.span.start.line, e.span.start.col, e.code
        )
    };
    let v: VersionOnly = ron::from_str(text).map_err(at)?;
    if v.version > VERSION {
        return Ok(Parsed::Newer(v.version));
    }
    if v.version == 0 {
        return Err(format!(
            "{name}: version 0 does not exist (this rigidlab writes {VERSION})"
        ));
    }
    let t: ProgressText = ron::from_str(text).map_err(at)?;
    let mut seen = std::collections::BTreeSet::new();
    for r in &t.levels {
        if let Some(q) = r
            .questions
            .iter()
            .flatten()
            .find(|q| q.error.is_nan() || q.error < 0.0)
        {
            return Err(format!(
                "{name}: {}: an error of {} is not a relative error (0 or more)",
                r.path, q.error
            ));
        }
        if !seen.insert((&r.path, &r.title)) {
            return Err(format!(
                "{name}: {} ({:?}) is listed twice",
                r.path, r.title
            ));
        }
    }
    Ok(Parsed::Progress(Progress {
        records: t.levels,
        tour: t.tour,
    }))
}

/// Why stored progress was not read.
#[derive(Debug)]
pub enum ReadFailure {
    /// It cannot be read at all (no permission, no localStorage): left as it is.
    Unreadable(String),
    /// It is not progress (a FIFO, too large, not UTF-8): moved aside.
    Bad(String),
}

/// Where progress is stored: a file, the page's localStorage, or (tests) memory.
pub trait Backend: Send + Sync {
    /// What the student is told it is (`~/.config/rigidlab/progress.ron`).
    fn name(&self) -> String;
    /// The stored text; None when nothing is stored yet.
    fn read(&self) -> Result<Option<String>, ReadFailure>;
    /// Keeps what is stored under a name of its own, which it returns; nothing is left under
    /// the usual name.
    fn move_aside(&self) -> Result<String, String>;
    /// Stores `text` whole in place of what was there.
    fn write(&self, text: &str) -> Result<(), String>;
}

/// `progress.ron` on disk.
pub struct FileBackend(pub PathBuf);

impl Backend for FileBackend {
    fn name(&self) -> String {
        self.0.display().to_string()
    }

    fn read(&self) -> Result<Option<String>, ReadFailure> {
        use crate::level::ReadError;
        let p = &self.0;
        match crate::level::read_regular(p, MAX_PROGRESS_BYTES) {
            Err(ReadError::Io(e)) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(ReadError::Io(e)) => Err(ReadFailure::Unreadable(format!("{}: {e}", p.display()))),
            Err(ReadError::TooBig(limit)) => Err(ReadFailure::Bad(format!(
                "{}: larger than {} MiB, the limit for progress",
                p.display(),
                limit >> 20
            ))),
            Err(e) => Err(ReadFailure::Bad(format!("{}: {e}", p.display()))),
            Ok(bytes) => String::from_utf8(bytes).map(Some).map_err(|e| {
                let before = &e.as_bytes()[..e.utf8_error().valid_up_to()];
                let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
                ReadFailure::Bad(format!("{}:{line}: not UTF-8 text", p.display()))
            }),
        }
    }

    fn move_aside(&self) -> Result<String, String> {
        crate::files::move_aside(&self.0, ".bad")
            .map(|p| p.display().to_string())
            .map_err(|e| e.to_string())
    }

    fn write(&self, text: &str) -> Result<(), String> {
        if let Some(dir) = self.0.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        crate::files::write_replacing(&self.0, text.as_bytes())
            .map_err(|e| format!("{}: {e}", self.0.display()))
    }
}

/// Where the window keeps progress natively: `progress.ron` in the folder of `prefs.ron`.
pub fn path() -> Option<PathBuf> {
    super::prefs::path().map(|p| p.with_file_name("progress.ron"))
}

/// The window's store: the file beside the preferences natively, localStorage in the page; none
/// without a home folder.
pub fn default_backend() -> Option<Box<dyn Backend>> {
    #[cfg(target_arch = "wasm32")]
    {
        Some(Box::new(web::LocalStorage))
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        path().map(|p| Box::new(FileBackend(p)) as Box<dyn Backend>)
    }
}

/// Progress's place, and what the window may do with it this session.
pub struct Store {
    backend: Option<Box<dyn Backend>>,
    /// False while something this rigidlab could not read is still in place (a newer format, a
    /// file it could neither read nor move aside): saving would replace it.
    pub can_save: bool,
    /// What was wrong when it was read, for the status line and the course's note.
    pub problem: Option<String>,
}

impl Default for Store {
    /// Nowhere: progress lasts the session (a test, a window without a home folder).
    fn default() -> Self {
        Store {
            backend: None,
            can_save: true,
            problem: None,
        }
    }
}

impl std::fmt::Debug for Store {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Store")
            .field("backend", &self.backend.as_ref().map(|b| b.name()))
            .field("can_save", &self.can_save)
            .field("problem", &self.problem)
            .finish()
    }
}

/// What reading found.
enum Found {
    Nothing,
    Progress(Progress),
    /// A problem said, and whether saving may go on.
    Problem(String, bool),
}

impl Store {
    /// Reads the progress stored in `backend` (None: nowhere). What was wrong is in
    /// [`Store::problem`] (and on stderr); a bad file has been moved aside.
    pub fn open(backend: Option<Box<dyn Backend>>) -> (Progress, Store) {
        let mut store = Store {
            backend,
            ..Default::default()
        };
        let progress = match store.read() {
            Found::Nothing => Progress::default(),
            Found::Progress(p) => p,
            Found::Problem(why, can_save) => {
                store.can_save = can_save;
                let why = format!("progress not read: {why}");
                stderr!("rigidlab: {why}");
                store.problem = Some(why);
                Progress::default()
            }
        };
        (progress, store)
    }

    /// Where progress lives, as the student is told.
    pub fn name(&self) -> Option<String> {
        self.backend.as_ref().map(|b| b.name())
    }

    /// Reads what is stored; moves aside what is not progress.
    fn read(&self) -> Found {
        let Some(b) = &self.backend else {
            return Found::Nothing;
        };
        let wrong = match b.read() {
            Ok(None) => return Found::Nothing,
            Err(ReadFailure::Unreadable(e)) => {
                return Found::Problem(
                    format!("{e}; it is left as it is and progress is kept for this session only"),
                    false,
                )
            }
            Err(ReadFailure::Bad(e)) => e,
            Ok(Some(text)) => match parse(&b.name(), &text) {
                Ok(Parsed::Progress(p)) => return Found::Progress(p),
                Ok(Parsed::Newer(v)) => {
                    return Found::Problem(
                        format!(
                            "{} was written by a newer rigidlab (format {v}; this one reads {VERSION}): it is kept as it is, and progress is kept for this session only",
                            b.name()
                        ),
                        false,
                    )
                }
                Err(e) => e,
            },
        };
        match b.move_aside() {
            Ok(aside) => Found::Problem(
                format!("{wrong}; it is kept as {aside}, and the course starts afresh"),
                true,
            ),
            Err(e) => Found::Problem(
                format!("{wrong}; it could not be moved aside ({e}), so it is left as it is and progress is kept for this session only"),
                false,
            ),
        }
    }

    /// Stores `progress`, whole, after taking in what was stored meanwhile (another window's
    /// solves). Ok with a note when something had to be moved aside first; Err when nothing was
    /// stored, and why.
    pub fn save(&mut self, progress: &mut Progress) -> Result<Option<String>, String> {
        let Some(name) = self.name() else {
            return Ok(None);
        };
        if !self.can_save {
            return Err(format!(
                "progress not saved: {name} was not read and is kept as it is"
            ));
        }
        let mut note = None;
        match self.read() {
            Found::Nothing => {}
            Found::Progress(stored) => progress.merge(&stored),
            Found::Problem(why, can_save) => {
                let why = format!("stored progress changed: {why}");
                self.problem = Some(why.clone());
                if !can_save {
                    self.can_save = false;
                    return Err(why);
                }
                note = Some(why);
            }
        }
        let b = self
            .backend
            .as_ref()
            .expect("a store with a name has a backend");
        b.write(&to_text(progress))
            .map_err(|e| format!("progress not saved: {e}"))?;
        Ok(note)
    }
}

/// The course's progress as the page's status publishes it: each level tried (its path, status
/// and attempts, as the course lists them), the first-steps tour's steps ticked, and what was
/// wrong with what was stored (the browser test reloads the page, and corrupts the store, and
/// reads them).
pub fn status_json(progress: &Progress, store: &Store) -> serde_json::Value {
    let levels: Vec<serde_json::Value> = progress
        .records
        .iter()
        .map(|r| {
            serde_json::json!({
                "path": r.path,
                "status": r.status,
                "attempts": r.attempts,
            })
        })
        .collect();
    serde_json::json!({
        "levels": levels,
        "problem": store.problem,
        "tour": { "ticked": progress.tour.ticked, "done": progress.tour.done },
    })
}

/// An in-memory store, for tests of what the page's storage does: its keys and texts.
#[derive(Default, Clone)]
pub struct MemoryBackend(
    pub std::sync::Arc<std::sync::Mutex<std::collections::BTreeMap<String, String>>>,
);

/// The key progress is kept under in the page's localStorage (and in [`MemoryBackend`]).
pub const STORAGE_KEY: &str = "rigidlab.progress";

/// The first free key `rigidlab.progress.bad`, `rigidlab.progress-2.bad`, ... among `taken`.
pub fn aside_key(taken: impl Fn(&str) -> bool) -> Option<String> {
    (1..=9999u32)
        .map(|n| match n {
            1 => format!("{STORAGE_KEY}.bad"),
            n => format!("{STORAGE_KEY}-{n}.bad"),
        })
        .find(|k| !taken(k))
}

impl Backend for MemoryBackend {
    fn name(&self) -> String {
        format!("storage key {STORAGE_KEY}")
    }
    fn read(&self) -> Result<Option<String>, ReadFailure> {
        Ok(self
            .0
            .lock()
            .map_err(|e| ReadFailure::Unreadable(e.to_string()))?
            .get(STORAGE_KEY)
            .cloned())
    }
    fn move_aside(&self) -> Result<String, String> {
        let mut m = self.0.lock().map_err(|e| e.to_string())?;
        let key = aside_key(|k| m.contains_key(k)).ok_or("no free key")?;
        let text = m.remove(STORAGE_KEY).unwrap_or_default();
        m.insert(key.clone(), text);
        Ok(key)
    }
    fn write(&self, text: &str) -> Result<(), String> {
        self.0
            .lock()
            .map_err(|e| e.to_string())?
            .insert(STORAGE_KEY.into(), text.into());
        Ok(())
    }
}

#[cfg(target_arch = "wasm32")]
mod web {
    //! The page's localStorage, reached through `js_sys::Reflect` (`localStorage.getItem`,
    //! `setItem`, `removeItem`): web-sys's `Storage` binding is a feature no dependency turns on,
    //! and turning it on rebuilds web-sys and everything above it for the page (Bevy's web crates).
    use super::{aside_key, Backend, ReadFailure, STORAGE_KEY};
    use wasm_bindgen::{JsCast, JsValue};

    pub struct LocalStorage;

    fn storage() -> Result<JsValue, String> {
        let w = web_sys::window().ok_or("no window")?;
        // Reading `localStorage` throws where the browser refuses it (private modes, a sandbox).
        let s = js_sys::Reflect::get(&w, &JsValue::from_str("localStorage"))
            .map_err(|e| format!("localStorage refused: {e:?}"))?;
        if s.is_null() || s.is_undefined() {
            return Err("this browser has no localStorage".into());
        }
        Ok(s)
    }

    fn call(s: &JsValue, method: &str, args: &[&str]) -> Result<JsValue, String> {
        let f: js_sys::Function = js_sys::Reflect::get(s, &JsValue::from_str(method))
            .map_err(|e| format!("{e:?}"))?
            .dyn_into()
            .map_err(|_| format!("localStorage.{method} is not a function"))?;
        let r = match args {
            [a] => f.call1(s, &JsValue::from_str(a)),
            [a, b] => f.call2(s, &JsValue::from_str(a), &JsValue::from_str(b)),
            _ => f.call0(s),
        };
        // setItem throws when the storage is full.
        r.map_err(|e| format!("localStorage.{method}: {e:?}"))
    }

    fn get(s: &JsValue, key: &str) -> Result<Option<String>, String> {
        call(s, "getItem", &[key]).map(|v| v.as_string())
    }

    impl Backend for LocalStorage {
        fn name(&self) -> String {
            format!("the browser's localStorage ({STORAGE_KEY})")
        }
        fn read(&self) -> Result<Option<String>, ReadFailure> {
            let s = storage().map_err(ReadFailure::Unreadable)?;
            get(&s, STORAGE_KEY).map_err(ReadFailure::Unreadable)
        }
        fn move_aside(&self) -> Result<String, String> {
            let s = storage()?;
            let text = get(&s, STORAGE_KEY)?.unwrap_or_default();
            let key = aside_key(|k| get(&s, k).ok().flatten().is_some()).ok_or("no free key")?;
            call(&s, "setItem", &[&key, &text])?;
            call(&s, "removeItem", &[STORAGE_KEY])?;
            Ok(format!("localStorage {key}"))
        }
        fn write(&self, text: &str) -> Result<(), String> {
            let s = storage()?;
            call(&s, "setItem", &[STORAGE_KEY, text]).map(|_| ())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::progress::{Graded, LevelKey, Status};
    use super::*;

    fn solved() -> (Progress, LevelKey) {
        let k = LevelKey {
            path: "kinetics/simple_pendulum.ron".into(),
            title: "Simple pendulum".into(),
        };
        let mut p = Progress::default();
        p.begin_attempt(&k, 1);
        p.grade(
            &k,
            1,
            0,
            Graded {
                error: 0.002,
                right: true,
            },
            false,
        );
        (p, k)
    }

    #[test]
    fn the_text_reads_back_as_written() {
        let (mut p, _) = solved();
        // An answer to a question whose answer is 0 can be infinitely off.
        let k = LevelKey {
            path: "impact/x.ron".into(),
            title: "x".into(),
        };
        p.begin_attempt(&k, 1);
        p.grade(
            &k,
            1,
            0,
            Graded {
                error: f64::INFINITY,
                right: false,
            },
            false,
        );
        assert!(to_text(&p).contains("inf"));
        let text = to_text(&p);
        assert_eq!(parse("t", &text), Ok(Parsed::Progress(p)));
    }

    #[test]
    fn a_newer_version_is_told_apart_from_a_broken_file() {
        let newer = "(version: 7, levels: [], stars: 3)";
        assert_eq!(parse("t", newer), Ok(Parsed::Newer(7)));
        let typo = to_text(&solved().0).replace("attempts", "atempts");
        let e = parse("p.ron", &typo).unwrap_err();
        assert!(e.starts_with("p.ron:") && e.contains("atempts"), "{e}");
        let e = parse("p.ron", &to_text(&solved().0).replace("solved", "aced")).unwrap_err();
        assert!(e.contains("aced"), "{e}");
    }

    #[test]
    fn a_bad_stored_text_is_kept_under_a_key_of_its_own() {
        let m = MemoryBackend::default();
        m.write("not ( progress").unwrap();
        m.0.lock()
            .unwrap()
            .insert(format!("{STORAGE_KEY}.bad"), "older".into());
        let (p, store) = Store::open(Some(Box::new(m.clone())));
        assert_eq!(p, Progress::default());
        let why = store.problem.clone().unwrap();
        let aside = format!("{STORAGE_KEY}-2.bad");
        assert!(why.contains(&aside), "{why}");
        let stored = m.0.lock().unwrap().clone();
        assert_eq!(
            stored.get(&aside).map(String::as_str),
            Some("not ( progress")
        );
        assert_eq!(
            stored
                .get(&format!("{STORAGE_KEY}.bad"))
                .map(String::as_str),
            Some("older")
        );
        assert!(!stored.contains_key(STORAGE_KEY));
        assert!(store.can_save);
    }

    #[test]
    fn newer_progress_is_never_written_over() {
        let m = MemoryBackend::default();
        let newer = "(version: 3, levels: [])";
        m.write(newer).unwrap();
        let (mut p, mut store) = Store::open(Some(Box::new(m.clone())));
        assert!(store.problem.as_deref().unwrap().contains("newer"));
        let (solved, _) = solved();
        p.merge(&solved);
        assert!(store.save(&mut p).is_err());
        assert_eq!(m.read().unwrap().as_deref(), Some(newer));
    }

    #[test]
    fn saving_takes_in_another_windows_progress() {
        let m = MemoryBackend::default();
        let (mut mine, mut store) = Store::open(Some(Box::new(m.clone())));
        // Another window solved a level meanwhile.
        let (theirs, k) = solved();
        m.write(&to_text(&theirs)).unwrap();
        let other = LevelKey {
            path: "energy/x.ron".into(),
            title: "x".into(),
        };
        mine.begin_attempt(&other, 1);
        assert_eq!(store.save(&mut mine), Ok(None));
        let Ok(Parsed::Progress(stored)) = parse("m", &m.read().unwrap().unwrap()) else {
            panic!("stored progress reads back");
        };
        assert_eq!(stored.status(&k), Status::Solved);
        assert_eq!(stored.status(&other), Status::Tried);
    }
}
