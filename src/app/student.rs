//! The student the window and the page open levels for: a level with parameters opens with that
//! student's own numbers (the variant `rigidlab check --student ID` runs), the nominal ones with
//! no id. Set by the window's "Your id" field and the page's `&student=`; read wherever a level
//! is opened (the course, an assignment, a link, a fetched file), so every way in gives the
//! numbers `rigidlab grade` grades the student against.
//!
//! A leaf of the window: it imports nothing from it.

use crate::level::params::Pick;
use std::sync::RwLock;

static STUDENT: RwLock<Option<String>> = RwLock::new(None);

/// Levels open for `id` from now on (None, or an id of spaces only: the nominal numbers).
pub fn set(id: Option<String>) {
    let id = id.map(|s| s.trim().to_string()).filter(|s| !s.is_empty());
    if let Ok(mut s) = STUDENT.write() {
        *s = id;
    }
}

/// The id levels open for, if any.
pub fn id() -> Option<String> {
    STUDENT.read().ok().and_then(|s| s.clone())
}

/// The variant a level opens as: the student's, or the nominal one.
pub fn pick() -> Pick {
    id().map_or(Pick::Nominal, Pick::Student)
}
