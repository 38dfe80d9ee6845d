//! The level browser (left panel, under the exercise): the levels folder grouped by topic (a
//! sub-folder each), each level with its title, statement and number of questions, or why it
//! does not load; the course (`course.rs`) draws them.

use super::super::ui::rich;
use super::super::view::palette;
use crate::level::{self, Scene};
use bevy::prelude::*;
use bevy_egui::egui;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use super::level_entry::Entry;

/// The levels folder, grouped by topic (sub-folder).
#[derive(Resource, Debug, Clone, Default)]
pub struct Browser {
    pub root: PathBuf,
    pub groups: BTreeMap<String, Vec<Entry>>,
    pub error: Option<String>,
    /// The levels are compiled in (the web page): nothing to rescan.
    pub embedded: bool,
    /// The assignment opened, listed above the library (`assignment_list.rs`).
    pub assignment: Option<super::assignment_list::AssignmentList>,
    /// Which library this is and where it was found, for the status line (`app/library.rs`).
    pub opened_from: String,
}

impl Browser {
    /// The browser over levels compiled into the program: `(path, text)` with paths under `root`.
    pub fn embedded(root: &Path, files: Vec<(PathBuf, Arc<str>)>) -> Browser {
        let mut b = Browser {
            root: root.to_path_buf(),
            embedded: true,
            ..Default::default()
        };
        for (path, text) in files {
            let entry = Entry::from_load(path.clone(), level::parse(&path, &text), Some(text));
            b.groups
                .entry(group_of(root, &path))
                .or_default()
                .push(entry);
        }
        for entries in b.groups.values_mut() {
            entries.sort_by(|a, b| a.path.cmp(&b.path));
        }
        b
    }

    /// The entry for `path` (as written in the browser, e.g. `levels/kinetics/x.ron`).
    pub fn find(&self, path: &Path) -> Option<&Entry> {
        self.groups.values().flatten().find(|e| e.path == path)
    }

    /// The text of the level listed for `file`, where the list holds it (compiled into the
    /// page, or fetched there): the library's entry first, then the assignment's row.
    pub fn listed_text(&self, file: &Path) -> Option<Arc<str>> {
        let assigned = || {
            self.assignment
                .iter()
                .flat_map(|a| a.entries.iter())
                .find(|e| e.path == file)
                .and_then(|e| e.source.clone())
        };
        self.find(file)
            .and_then(|e| e.source.clone())
            .or_else(assigned)
    }

    /// The level listed for `file`, opened again as the student opens it (their own numbers):
    /// the library's entry, else the assignment's row; None where neither lists it as loading.
    pub fn open_listed(&self, file: &Path) -> Option<Result<Scene, level::LevelError>> {
        let listed = self
            .find(file)
            .filter(|e| e.error.is_none())
            .map(Entry::load);
        let assigned = || {
            self.assignment
                .iter()
                .flat_map(|a| a.entries.iter())
                .find(|e| e.path == file && e.error.is_none())
                .map(|e| e.load())
        };
        listed.or_else(assigned)
    }

    pub fn scan(root: &Path) -> Browser {
        let mut b = Browser {
            root: root.to_path_buf(),
            ..Default::default()
        };
        let files = match level::collect_files(&[root.to_path_buf()]) {
            Ok(f) => f,
            Err(e) => {
                // Still list the saved levels below.
                b.error = Some(e.to_string());
                Vec::new()
            }
        };
        for f in files {
            let entry = Entry::from_load(f.clone(), level::load(&f), None);
            b.groups.entry(group_of(root, &f)).or_default().push(entry);
        }
        b.list_saved();
        b
    }

    /// Lists the levels the user saved from the window (`saved-levels/` in the folder the
    /// program runs in), apart from the library.
    pub fn list_saved(&mut self) {
        let saved = Path::new(crate::app::user_files::SAVED_LEVELS);
        if saved.is_dir() {
            if let Ok(files) = level::collect_files(&[saved.to_path_buf()]) {
                for f in files {
                    let entry = Entry::from_load(f.clone(), level::load(&f), None);
                    self.groups
                        .entry(format!("saved ({}/)", saved.display()))
                        .or_default()
                        .push(entry);
                }
            }
        }
    }

    /// Reads the levels folder again, and the assignment's levels, keeping the assignment listed
    /// and the note of where the library was found.
    pub fn rescan(&mut self) {
        let assignment = self.assignment.take().map(|a| a.reread());
        let opened_from = std::mem::take(&mut self.opened_from);
        *self = Browser::scan(&self.root.clone());
        self.assignment = assignment;
        self.opened_from = opened_from;
    }

    pub fn first_loadable(&self) -> Option<Scene> {
        self.groups
            .values()
            .flatten()
            .filter(|e| e.error.is_none())
            .find_map(|e| e.load().ok())
    }
}

/// How a listed level is told from another with the same title: its file name, and when it was
/// written where that is known (`my-scene-saved-2.ron · 2026-12-07 00:10 UTC`). Saved versions of
/// one level were listed under one title, nothing to tell them apart.
pub fn version_line(e: &Entry) -> String {
    let name = e
        .path
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().to_string());
    match e.modified.and_then(utc_minute) {
        Some(date) => format!("{name} · {date}"),
        None => name,
    }
}

/// A time as `YYYY-MM-DD HH:MM UTC` (None before 1970). The civil date from the day count is
/// Howard Hinnant's `civil_from_days` (proleptic Gregorian calendar, eras of 400 years).
pub fn utc_minute(t: std::time::SystemTime) -> Option<String> {
    let secs = t.duration_since(std::time::UNIX_EPOCH).ok()?.as_secs();
    let (days, rem) = ((secs / 86_400) as i64, secs % 86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    Some(format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    ))
}

/// The topic a level is listed under: its folder below the root.
fn group_of(root: &Path, f: &Path) -> String {
    f.parent()
        .and_then(|p| p.strip_prefix(root).ok())
        .map(|p| p.display().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "(top)".into())
}

/// Draws the browser's controls (rescan, open a file) and why the folder could not be listed;
/// the levels themselves are the course's rows (`course.rs`), drawn under this.
pub(super) fn level_browser(ui: &mut egui::Ui, browser: &mut Browser) {
    ui.horizontal(|ui| {
        if !browser.embedded
            && ui
                .small_button("⟳")
                .on_hover_text("rescan the levels folder")
                .clicked()
        {
            browser.rescan();
        }
        #[cfg(target_arch = "wasm32")]
        if ui
            .small_button("open a file…")
            .on_hover_text("open a .ron level file from this computer")
            .clicked()
        {
            super::super::page_files::pick_file();
        }
    });
    if let Some(e) = &browser.error {
        ui.label(rich(e.clone(), palette::NORMAL));
    }
    if browser.groups.is_empty() && browser.error.is_none() {
        ui.label(format!("no *.ron levels under {}", browser.root.display()));
    }
}
