//! The Bevy sandbox: a thin shell of plugins over the core (feature `app`).

use crate::level::Scene;
use std::path::{Path, PathBuf};

/// Opens the sandbox window: the level browser over `levels`, or `level` directly.
pub fn sandbox(levels: PathBuf, level: Option<PathBuf>) -> Result<(), String> {
    let _ = (levels, level);
    Err("the sandbox window is not built yet".into())
}

/// Renders `scene` at simulated time `time` into a PNG at `out`.
pub fn render(scene: &Scene, time: f64, out: &Path) -> Result<(), String> {
    let _ = (scene, time, out);
    Err("rendering is not built yet".into())
}
