//! Preferences the window remembers between sessions: whether the first-steps tour was finished,
//! the arrow scale, the time scale, labels, trails, predict first and the student's id ("Your
//! id", so that levels with parameters open with the student's own numbers again). A small RON file in the user's config
//! folder (`$XDG_CONFIG_HOME/rigidlab/prefs.ron`, else `~/.config/rigidlab/prefs.ron`;
//! `RIGIDLAB_PREFS` names another file); the page in a browser keeps nothing.
//!
//! The file is read as levels are (`level::read_regular`: a regular file, at most
//! [`MAX_PREFS_BYTES`]) and its values are checked against the window's own ranges. A file that
//! is wrong in any way is never fatal and never silently replaced: what is wrong (path, line,
//! column) goes to stderr and the window's status line, and the file is moved aside as
//! `prefs.ron.bad` (`prefs.ron-2.bad`, ... beside an earlier one) before the window writes its
//! own. A file that cannot be moved aside (or read at all) is left alone, and the window then
//! saves no preferences that session.

use bevy::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The largest preferences file read, bytes (a saved one is about 100).
pub const MAX_PREFS_BYTES: u64 = 64 << 10;

/// The time scales the window offers (the playback panel's slider, the - and = keys).
pub const TIME_SCALES: (f64, f64) = (1.0 / 64.0, 8.0);

/// The arrow scales the window offers (the overlay panel's slider).
pub const ARROW_SCALES: (f64, f64) = (0.25, 4.0);

#[derive(Resource, Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Prefs {
    /// The first-steps tour was finished or dismissed for good.
    pub tour_done: bool,
    pub arrow_scale: f64,
    pub time_scale: f64,
    pub labels: bool,
    pub trails: bool,
    /// Predict first in every level (the switch at the top of the left panel).
    pub predict_first: bool,
    /// The id typed in "Your id" (`app/student.rs`), empty for none. Not written while empty,
    /// so a file without an id reads in a rigidlab from before 2026-12-07 too.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub student_id: String,
}

impl Default for Prefs {
    fn default() -> Self {
        Prefs {
            tour_done: false,
            arrow_scale: 1.0,
            time_scale: 1.0,
            labels: true,
            trails: true,
            predict_first: false,
            student_id: String::new(),
        }
    }
}

/// The preferences file as the window found it at start, and whether it may write it.
#[derive(Resource, Debug, Clone, Default, PartialEq)]
pub struct PrefsFile {
    /// Where the preferences live (None in a web page, or with no home folder).
    pub path: Option<PathBuf>,
    /// What was wrong with the file, for the status line (also said on stderr at start).
    pub problem: Option<String>,
    /// False while a file the window could not read is still at `path`: saving would replace
    /// it, so the window keeps its preferences for the session only.
    pub can_save: bool,
}

/// Where the preferences live (None in a web page).
pub fn path() -> Option<PathBuf> {
    if cfg!(target_arch = "wasm32") {
        return None;
    }
    if let Some(p) = std::env::var_os("RIGIDLAB_PREFS") {
        return Some(PathBuf::from(p));
    }
    let base = std::env::var_os("XDG_CONFIG_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
    Some(base.join("rigidlab").join("prefs.ron"))
}

/// The 1-based line and column of `key:` in `text` (of its first character), else 1:1.
fn position_of(text: &str, key: &str) -> (usize, usize) {
    for (i, line) in text.lines().enumerate() {
        if let Some(c) = line.find(key) {
            let rest = line[c + key.len()..].trim_start();
            if rest.starts_with(':') {
                return (i + 1, line[..c].chars().count() + 1);
            }
        }
    }
    (1, 1)
}

impl Prefs {
    /// Parses and checks a preferences file's text: `Err` says what is wrong at `path:line:col`.
    pub fn parse(path: &Path, text: &str) -> Result<Prefs, String> {
        let p: Prefs = ron::from_str(text).map_err(|e| {
            format!(
                "{}:{}:{}: {}",
                path.display(),
                e.span.start.line,
                e.span.start.col,
                e.code
            )
        })?;
        for (key, v, (lo, hi), range) in [
            ("time_scale", p.time_scale, TIME_SCALES, "1/64 to 8"),
            ("arrow_scale", p.arrow_scale, ARROW_SCALES, "0.25 to 4"),
        ] {
            if !(v.is_finite() && (lo..=hi).contains(&v)) {
                let (line, col) = position_of(text, key);
                return Err(format!(
                    "{}:{line}:{col}: {key} {v} is out of range: the window takes {range}",
                    path.display()
                ));
            }
        }
        if let Some(c) = p.student_id.chars().find(|c| c.is_control()) {
            let (line, col) = position_of(text, "student_id");
            return Err(format!(
                "{}:{line}:{col}: student_id holds the control character {:?}: an id is one line of text",
                path.display(),
                c
            ));
        }
        Ok(p)
    }

    /// The saved preferences and what the window found in their file (see [`load_from`]).
    pub fn load() -> (Prefs, PrefsFile) {
        match path() {
            Some(p) => load_from(&p),
            None => (Prefs::default(), PrefsFile::default()),
        }
    }

    /// Writes them to `file`'s path, whole (a temporary file renamed over it once written).
    /// A failure is returned for the status line (the window goes on).
    pub fn save(&self, file: &PrefsFile) -> Result<(), String> {
        let Some(p) = &file.path else {
            return Ok(());
        };
        if !file.can_save {
            return Err(format!(
                "{} was not read and is kept as it is; fix or remove it",
                p.display()
            ));
        }
        if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        let text =
            ron::ser::to_string_pretty(self, Default::default()).map_err(|e| e.to_string())?;
        crate::files::write_replacing(p, text.as_bytes())
            .map_err(|e| format!("{}: {e}", p.display()))
    }
}

/// Reads the preferences at `path`. None there: the defaults. A file that is wrong (not a
/// regular file, too large, not UTF-8, not RON, an unknown field, a value out of range): the
/// defaults, the problem said on stderr and returned for the status line, and the file moved
/// aside to `path.bad` (numbered beside an earlier one) so that saving does not replace it. A
/// file that cannot be read or moved aside is left where it is, and saving is off.
pub fn load_from(path: &Path) -> (Prefs, PrefsFile) {
    let mut file = PrefsFile {
        path: Some(path.to_path_buf()),
        problem: None,
        can_save: true,
    };
    let wrong = match crate::level::read_regular(path, MAX_PREFS_BYTES) {
        Err(crate::level::ReadError::Io(e)) if e.kind() == std::io::ErrorKind::NotFound => {
            return (Prefs::default(), file);
        }
        Err(crate::level::ReadError::Io(e)) => {
            // Unreadable (permissions): left alone, and not written over.
            file.can_save = false;
            let why = format!(
                "preferences not read: {}: {e}; the defaults are used and nothing is saved this session",
                path.display()
            );
            stderr!("rigidlab: {why}");
            file.problem = Some(why);
            return (Prefs::default(), file);
        }
        Err(crate::level::ReadError::TooBig(limit)) => format!(
            "{}: larger than {} KiB, the limit for preferences",
            path.display(),
            limit >> 10
        ),
        Err(e) => format!("{}: {e}", path.display()),
        Ok(bytes) => match std::str::from_utf8(&bytes) {
            Err(e) => {
                let before = &bytes[..e.valid_up_to()];
                let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
                let col = before.rsplit(|&b| b == b'\n').next().map_or(0, |l| l.len()) + 1;
                format!("{}:{line}:{col}: not UTF-8 text", path.display())
            }
            Ok(text) => match Prefs::parse(path, text) {
                Ok(p) => return (p, file),
                Err(e) => e,
            },
        },
    };
    let why = match crate::files::move_aside(path, ".bad") {
        Ok(aside) => format!(
            "preferences not read: {wrong}; the file is kept as {} and the defaults are used",
            aside.display()
        ),
        Err(e) => {
            file.can_save = false;
            format!(
                "preferences not read: {wrong}; it could not be moved aside ({e}), so it is left as it is and nothing is saved this session"
            )
        }
    };
    stderr!("rigidlab: {why}");
    file.problem = Some(why);
    (Prefs::default(), file)
}
