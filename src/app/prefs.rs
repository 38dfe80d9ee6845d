//! Preferences the window remembers between sessions: whether the first-steps tour was finished,
//! the arrow scale, the time scale, labels and trails. A small RON file in the user's config
//! folder (`$XDG_CONFIG_HOME/rigidlab/prefs.ron`, else `~/.config/rigidlab/prefs.ron`;
//! `RIGIDLAB_PREFS` names another file). A file that cannot be read is ignored, never fatal, and
//! the page in a browser keeps nothing.

use bevy::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

#[derive(Resource, Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Prefs {
    /// The first-steps tour was finished or dismissed for good.
    pub tour_done: bool,
    pub arrow_scale: f64,
    pub time_scale: f64,
    pub labels: bool,
    pub trails: bool,
}

impl Default for Prefs {
    fn default() -> Self {
        Prefs {
            tour_done: false,
            arrow_scale: 1.0,
            time_scale: 1.0,
            labels: true,
            trails: true,
        }
    }
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

impl Prefs {
    /// The saved preferences, or the defaults where there are none or they cannot be read.
    pub fn load() -> Prefs {
        path()
            .and_then(|p| std::fs::read_to_string(p).ok())
            .and_then(|t| ron::from_str(&t).ok())
            .unwrap_or_default()
    }

    /// Writes them; a failure is returned for the status line (the window goes on).
    pub fn save(&self) -> Result<(), String> {
        let Some(p) = path() else {
            return Ok(());
        };
        if let Some(dir) = p.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        let text =
            ron::ser::to_string_pretty(self, Default::default()).map_err(|e| e.to_string())?;
        std::fs::write(&p, text).map_err(|e| format!("{}: {e}", p.display()))
    }
}
