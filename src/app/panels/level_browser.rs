//! The level browser (left panel, top): the levels folder grouped by topic, each level with its
//! title and statement on hover; a level that does not load shows why instead of opening.

use super::super::run::Run;
use super::super::ui::rich;
use super::super::view::palette;
use crate::level::{self, Scene};
use bevy::prelude::*;
use bevy_egui::egui;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One level file in the browser.
#[derive(Debug, Clone)]
pub struct Entry {
    pub path: PathBuf,
    pub title: String,
    pub statement: String,
    /// Why it does not load (shown instead of opening it).
    pub error: Option<String>,
    /// The file's text when it is compiled in (the web page has no file system).
    pub source: Option<Arc<str>>,
}

impl Entry {
    /// The level: parsed from the compiled-in text, or read from its file.
    pub fn load(&self) -> Result<Scene, level::LevelError> {
        match &self.source {
            Some(text) => level::parse(&self.path, text),
            None => level::load(&self.path),
        }
    }
}

/// The levels folder, grouped by topic (sub-folder).
#[derive(Resource, Debug, Clone, Default)]
pub struct Browser {
    pub root: PathBuf,
    pub groups: BTreeMap<String, Vec<Entry>>,
    pub error: Option<String>,
    /// The levels are compiled in (the web page): nothing to rescan.
    pub embedded: bool,
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
        // The levels the user saved from the window, listed apart from the library.
        let saved = Path::new(crate::app::user_files::SAVED_LEVELS);
        if saved.is_dir() {
            if let Ok(files) = level::collect_files(&[saved.to_path_buf()]) {
                for f in files {
                    let entry = Entry::from_load(f.clone(), level::load(&f), None);
                    b.groups
                        .entry(format!("saved ({}/)", saved.display()))
                        .or_default()
                        .push(entry);
                }
            }
        }
        b
    }

    pub fn first_loadable(&self) -> Option<Scene> {
        self.groups
            .values()
            .flatten()
            .filter(|e| e.error.is_none())
            .find_map(|e| e.load().ok())
    }
}

impl Entry {
    fn from_load(
        path: PathBuf,
        loaded: Result<Scene, level::LevelError>,
        source: Option<Arc<str>>,
    ) -> Entry {
        match loaded {
            Ok(s) => Entry {
                path,
                title: s.level.title,
                statement: s.level.statement,
                error: None,
                source,
            },
            Err(e) => Entry {
                title: path
                    .file_stem()
                    .map(|s| s.to_string_lossy().to_string())
                    .unwrap_or_default(),
                path,
                statement: String::new(),
                error: Some(e.to_string()),
                source,
            },
        }
    }
}

/// The topic a level is listed under: its folder below the root.
fn group_of(root: &Path, f: &Path) -> String {
    f.parent()
        .and_then(|p| p.strip_prefix(root).ok())
        .map(|p| p.display().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "(top)".into())
}

/// Draws the panel; a clicked level that loads is put in `load` for the layout to open.
pub(super) fn level_browser(
    ui: &mut egui::Ui,
    browser: &mut Browser,
    phys: &Run,
    load: &mut Option<Scene>,
) {
    ui.horizontal(|ui| {
        ui.heading("Levels");
        if !browser.embedded
            && ui
                .small_button("⟳")
                .on_hover_text("rescan the levels folder")
                .clicked()
        {
            *browser = Browser::scan(&browser.root.clone());
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
    for (group, entries) in &browser.groups {
        egui::CollapsingHeader::new(group.as_str())
            .default_open(
                entries.iter().any(|e| e.path == phys.scene.file) || browser.groups.len() <= 6,
            )
            .show(ui, |ui| {
                for e in entries {
                    let current = e.path == phys.scene.file;
                    let text = if e.error.is_some() {
                        rich(format!("⚠ {}", e.title), palette::NORMAL)
                    } else {
                        egui::RichText::new(&e.title)
                    };
                    let r = ui.selectable_label(current, text);
                    let r = match &e.error {
                        Some(err) => r.on_hover_text(err),
                        None if !e.statement.is_empty() => r.on_hover_text(&e.statement),
                        None => r,
                    };
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
