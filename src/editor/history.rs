//! Undo and redo: the levels before and after each edit (a level is small, a few KiB even with
//! a hundred bodies, so whole copies are simpler and safer than inverse edits).

use super::{apply, Edit};
use crate::level::{Level, Scene};

/// The edits of one scene, undoable.
#[derive(Debug, Clone, Default)]
pub struct History {
    undo: Vec<Level>,
    redo: Vec<Level>,
    /// The last edit applied, to merge a run of changes to one property (a slider dragged over
    /// sixty frames is one step to undo, as typing a word is in a text editor).
    last: Option<Edit>,
}

/// Undo keeps at most this many levels.
const KEEP: usize = 200;

impl History {
    /// Applies an edit; on success the scene before it can be had back with [`History::undo`].
    pub fn apply(&mut self, scene: &Scene, e: &Edit) -> Result<(Scene, String), String> {
        let (next, note) = apply(scene, e)?;
        let merges = match (&self.last, e) {
            (
                Some(Edit::Set {
                    body: a,
                    property: p,
                }),
                Edit::Set {
                    body: b,
                    property: q,
                },
            ) => a == b && std::mem::discriminant(p) == std::mem::discriminant(q),
            (
                Some(Edit::SetMotor {
                    joint: a,
                    target: Some(_),
                }),
                Edit::SetMotor {
                    joint: b,
                    target: Some(_),
                },
            ) => a == b,
            _ => false,
        };
        if !merges || self.undo.is_empty() {
            self.undo.push(scene.level.clone());
            if self.undo.len() > KEEP {
                self.undo.remove(0);
            }
        }
        self.redo.clear();
        self.last = Some(e.clone());
        Ok((next, note))
    }

    /// The scene before the last edit, or None when there is nothing to undo.
    pub fn undo(&mut self, scene: &Scene) -> Option<Scene> {
        let level = self.undo.pop()?;
        self.redo.push(scene.level.clone());
        self.last = None;
        Some(Scene {
            file: scene.file.clone(),
            level,
        })
    }

    /// The scene the last undo went back from.
    pub fn redo(&mut self, scene: &Scene) -> Option<Scene> {
        let level = self.redo.pop()?;
        self.undo.push(scene.level.clone());
        self.last = None;
        Some(Scene {
            file: scene.file.clone(),
            level,
        })
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Forgets everything (a different level was opened).
    pub fn clear(&mut self) {
        self.undo.clear();
        self.redo.clear();
        self.last = None;
    }

    /// Ends a run of merged changes (the slider was let go): the next change is its own step.
    pub fn seal(&mut self) {
        self.last = None;
    }
}
