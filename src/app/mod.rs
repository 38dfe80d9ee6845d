//! The Bevy sandbox: a thin shell of plugins over the core (feature `app`).
//!
//! - [`run`] and [`physics`]: the core `Simulation` stepped in `FixedUpdate` at the level's dt, so the window
//!   computes the numbers `rigidlab check` computes;
//! - [`view`], [`draw`], [`geometry`]: camera, filled bodies, outlines, joints, springs, ground;
//! - [`overlays`]: the textbook's vectors and diagrams, from the snapshot ([`quantities`]), drawn
//!   one system each ([`overlay_systems`]);
//! - [`panels`] and [`tools`]: the egui panels and the mouse tools of the sandbox window;
//! - [`render`](mod@render): the same scene drawn into a PNG without a window.
//!
//! The run ([`Run`]) and its [`Playback`] change in one place, `physics::apply_commands`:
//! panels, keys, mouse tools and the editor ask with a [`PhysicsCommand`] and read the run
//! otherwise. Imports inside `src/app` run one way, down (`tests/app_import_rule.rs` says what
//! down means): this file only declares the modules and names what the rest of the crate uses.

pub mod advice;
pub mod ball_meshes;
pub mod blows;
pub mod draw;
pub mod editor;
pub mod frame_cost;
pub mod frame_rate;
pub mod geometry;
pub mod label_grid;
pub mod labels;
pub mod library;
pub mod names;
pub mod overlay_systems;
pub mod overlays;
#[cfg(target_arch = "wasm32")]
pub mod page_fetch;
#[cfg(target_arch = "wasm32")]
pub mod page_files;
#[cfg(target_arch = "wasm32")]
pub mod page_fonts;
#[cfg(target_arch = "wasm32")]
pub mod page_library;
pub mod panels;
pub mod physics;
pub mod playback;
pub mod power;
pub mod prefs;
pub mod progress;
pub mod progress_file;
pub mod quantities;
pub mod render;
pub mod run;
pub mod sandbox;
pub mod scene;
pub mod scene_lines;
pub mod student;
pub mod time_text;
pub mod tools;
pub mod ui;
pub mod unsaved;
pub mod user_files;
pub mod view;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use physics::{LiveChecks, PhysicsCommand, PhysicsPlugin, PhysicsStep};
pub use playback::Playback;
pub use run::Run;
pub use sandbox::{add_sandbox, sandbox, sandbox_assignment, FIRST_LEVEL};
pub use scene::{
    label_want, screen_bodies, screen_bodies_within, SceneDraw, ScenePlugin, ScenePlugins,
};

use crate::level::Scene;
use std::path::Path;

/// Renders `scene` at simulated time `time` into a PNG at `out`.
///
/// The overlays are velocity, free-body diagram, trails and labels; `RIGIDLAB_OVERLAYS=vacfkhtln`
/// (letters as the sandbox keys) picks others.
pub fn render(scene: &Scene, time: f64, out: &Path) -> Result<(), String> {
    let mut opts = render::RenderOptions::default();
    if let Ok(letters) = std::env::var("RIGIDLAB_OVERLAYS") {
        opts.overlays = render::RenderOptions::overlays_from_letters(&letters)?;
    }
    render::render_frame(scene, time, Some(out), &opts).map(|_| ())
}
