//! The level browser (left panel, top): the levels folder grouped by topic, each level with its
//! title and statement on hover; a level that does not load shows why instead of opening.

use super::super::physics::Physics;
use super::super::view::palette;
use super::rich;
use crate::level::{self, Scene};
use bevy::prelude::*;
use bevy_egui::egui;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One level file in the browser.
#[derive(Debug, Clone)]
pub struct Entry {
    pub path: PathBuf,
    pub title: String,
    pub statement: String,
    /// Why it does not load (shown instead of opening it).
    pub error: Option<String>,
}

/// The levels folder, grouped by topic (sub-folder).
#[derive(Resource, Debug, Clone, Default)]
pub struct Browser {
    pub root: PathBuf,
    pub groups: BTreeMap<String, Vec<Entry>>,
    pub error: Option<String>,
}

impl Browser {
    pub fn scan(root: &Path) -> Browser {
        let mut b = Browser {
            root: root.to_path_buf(),
            ..Default::default()
        };
        let files = match level::collect_files(&[root.to_path_buf()]) {
            Ok(f) => f,
            Err(e) => {
                b.error = Some(e.to_string());
                return b;
            }
        };
        for f in files {
            let group = f
                .parent()
                .and_then(|p| p.strip_prefix(root).ok())
                .map(|p| p.display().to_string())
                .filter(|s| !s.is_empty())
                .unwrap_or_else(|| "(top)".into());
            let entry = match level::load(&f) {
                Ok(s) => Entry {
                    path: f.clone(),
                    title: s.level.title,
                    statement: s.level.statement,
                    error: None,
                },
                Err(e) => Entry {
                    path: f.clone(),
                    title: f
                        .file_stem()
                        .map(|s| s.to_string_lossy().to_string())
                        .unwrap_or_default(),
                    statement: String::new(),
                    error: Some(e.to_string()),
                },
            };
            b.groups.entry(group).or_default().push(entry);
        }
        b
    }

    pub fn first_loadable(&self) -> Option<Scene> {
        self.groups
            .values()
            .flatten()
            .filter(|e| e.error.is_none())
            .find_map(|e| level::load(&e.path).ok())
    }
}

/// Draws the panel; a clicked level that loads is put in `load` for the layout to open.
pub(super) fn level_browser(
    ui: &mut egui::Ui,
    browser: &mut Browser,
    phys: &Physics,
    load: &mut Option<Scene>,
) {
    ui.horizontal(|ui| {
        ui.heading("Levels");
        if ui
            .small_button("⟳")
            .on_hover_text("rescan the levels folder")
            .clicked()
        {
            *browser = Browser::scan(&browser.root.clone());
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
                        match level::load(&e.path) {
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
