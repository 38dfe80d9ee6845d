//! The panels' own state that is neither the run nor the exercise: the status line, the save
//! field, the time scale, the help and tour windows, the stopwatch, the body plot's choice.
//! Panels take it from here (a sibling), not from `panels/mod.rs` above them.

use super::measure::Stopwatch;
use super::plots::BodyPlot;
use super::tour::Tour;
use crate::level::Scene;
use bevy::prelude::*;
use bevy_egui::egui;
use std::path::PathBuf;

/// Panel state that is not the simulation's, nor the exercise's (`exercise::Exercise`).
#[derive(Resource, Debug, Clone)]
pub struct UiState {
    /// A level opened from outside the panels (the web page's file picker), opened next frame as
    /// a click in the level browser is.
    pub pending_open: Option<Scene>,
    /// The help window is open (F1 or ?).
    pub help: bool,
    pub time_scale: f64,
    pub save_path: String,
    pub message: Option<(String, bool)>,
    pub generation: Option<u64>,
    /// The title and statement being typed in the build panel (read from the level when it changes).
    pub edit_title: Option<(String, String)>,
    /// The first-steps tour.
    pub tour: Tour,
    /// Where the build panel's buttons were drawn last frame, by name (the web page publishes
    /// them so a browser test can build a scene as a user would, by clicking).
    pub buttons: std::collections::BTreeMap<String, egui::Rect>,
    /// The level file the save field was filled for.
    pub save_for: Option<PathBuf>,
    /// The measuring panel's stopwatch.
    pub stopwatch: Stopwatch,
    /// What the selected body's plot shows.
    pub body_plot: BodyPlot,
    /// What it is plotted against (None: time).
    pub body_plot_against: Option<BodyPlot>,
}

impl Default for UiState {
    fn default() -> Self {
        UiState {
            pending_open: None,
            help: false,
            time_scale: 1.0,
            save_path: String::new(),
            message: None,
            generation: None,
            edit_title: None,
            body_plot: Default::default(),
            body_plot_against: None,
            stopwatch: Default::default(),
            save_for: None,
            tour: Default::default(),
            buttons: Default::default(),
        }
    }
}
