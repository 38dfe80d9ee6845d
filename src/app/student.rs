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

/// The window starts with the id kept in the preferences (`kept`, empty for none) unless one is
/// set already (the page's `&student=`): the level it opens with, `scene`, opens again with the
/// student's own numbers ([`kept_variant`]). Before 2026-12-07 the id was not kept, and each
/// session opened with the nominal numbers until the student typed it again.
pub fn resume(kept: &str, scene: crate::level::Scene) -> crate::level::Scene {
    if id().is_some() || kept.trim().is_empty() {
        return scene;
    }
    set(Some(kept.to_string()));
    kept_variant(kept, scene)
}

/// `scene` as the student `kept` opens it: read again from its file as their variant where it
/// has parameters (the same level where it has none); as it is where its file cannot be read
/// again (a scene with no file).
pub fn kept_variant(kept: &str, scene: crate::level::Scene) -> crate::level::Scene {
    let pick = Pick::Student(kept.trim().to_string());
    crate::level::variant_of(&scene.file, None, &pick).unwrap_or(scene)
}
