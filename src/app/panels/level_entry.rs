//! One level listed in the window: the library's browser and an assignment list both hold
//! these (`level_browser.rs`, `assignment_list.rs`), below both (the assignment's rows were a
//! near copy of the browser's entries).

use crate::level::{self, Scene};
use std::path::PathBuf;
use std::sync::Arc;

/// One level file in the browser.
#[derive(Debug, Clone)]
pub struct Entry {
    pub path: PathBuf,
    pub title: String,
    pub statement: String,
    /// Why it does not load (shown instead of opening it).
    pub error: Option<String>,
    /// How many questions it asks (0 where it does not load).
    pub questions: usize,
    /// It is a challenge (a control the student sets and a goal judged on the run): the course
    /// counts it, met as solved.
    pub challenge: bool,
    /// The file's text when it is compiled in (the web page has no file system).
    pub source: Option<Arc<str>>,
    /// When the file was last written (a file on disk; the listing shows it for saved levels,
    /// whose versions share one title).
    pub modified: Option<std::time::SystemTime>,
}

impl Entry {
    /// It is an exercise of the course: it loads, and asks a question or sets a challenge.
    pub fn is_exercise(&self) -> bool {
        self.error.is_none() && (self.questions > 0 || self.challenge)
    }

    /// The level as the student opens it (`app/student.rs`: their own numbers for a level with
    /// parameters): parsed from the compiled-in text, or read from its file.
    pub fn load(&self) -> Result<Scene, level::LevelError> {
        self.load_variant(&super::super::student::pick())
    }

    /// The level as `pick` makes it (a student's own numbers for a level with parameters; the
    /// same level for every pick otherwise).
    pub fn load_variant(&self, pick: &level::params::Pick) -> Result<Scene, level::LevelError> {
        level::variant_of(&self.path, self.source.as_deref(), pick)
    }
}

impl Entry {
    /// The entry of the level at `path`, loaded (or why not), with its text where it was
    /// compiled in or fetched.
    pub(super) fn from_load(
        path: PathBuf,
        loaded: Result<Scene, level::LevelError>,
        source: Option<Arc<str>>,
    ) -> Entry {
        let modified = source
            .is_none()
            .then(|| std::fs::metadata(&path).and_then(|m| m.modified()).ok())
            .flatten();
        match loaded {
            Ok(s) => Entry {
                path,
                questions: s.level.questions.len(),
                challenge: s.level.challenge.is_some(),
                title: s.level.title,
                statement: s.level.statement,
                error: None,
                source,
                modified,
            },
            Err(e) => Entry {
                title: path
                    .file_stem()
                    .map(|s| s.to_string_lossy().to_string())
                    .unwrap_or_default(),
                path,
                statement: String::new(),
                error: Some(e.to_string()),
                questions: 0,
                challenge: false,
                source,
                modified,
            },
        }
    }
}
