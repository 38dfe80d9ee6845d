//! Where a file the user asks for goes: written to disk in the native window, downloaded by the
//! browser in the web page (which has no file system). One writer for saved levels, CSV exports
//! and F12 screenshots: natively it never replaces a file (a name that is taken gets a counter,
//! `name-2.ext`; `crate::files::write_new`), writes the file whole before it takes its name, and
//! says where it went or why it could not, for the status line.

use crate::level::Scene;
use bevy::prelude::*;
use std::path::{Path, PathBuf};

/// Where the window saves levels (and the level browser lists them): a folder of the working
/// directory, apart from the library in levels/ that the tests run.
pub const SAVED_LEVELS: &str = "saved-levels";

/// Where F12 puts screenshots natively (made if missing).
pub const SCREENSHOTS: &str = "screenshots";

/// Writes `bytes` as `path` (native) or offers them as a download named after `path`'s file name
/// (web). Natively a file already there is never replaced: the bytes go under the first free
/// numbered name (`name-2.ext`, `name-3.ext`, ...). Returns what happened, for the status line.
pub fn deliver(path: &Path, bytes: &[u8], mime: &str) -> Result<String, String> {
    deliver_as(path, bytes, mime).map(|(_, m)| m)
}

/// [`deliver`], with the path the file was written to (natively) or the name offered (web).
pub fn deliver_as(path: &Path, bytes: &[u8], mime: &str) -> Result<(PathBuf, String), String> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = mime;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("not saved: cannot make the folder {}: {e}", dir.display()))?;
        }
        let used = crate::files::write_new(path, bytes)
            .map_err(|e| format!("not saved: cannot write {}: {e}", path.display()))?;
        let message = if used == path {
            format!("saved {}", used.display())
        } else {
            format!(
                "saved {} ({} is taken and was kept)",
                used.display(),
                path.display()
            )
        };
        Ok((used, message))
    }
    #[cfg(target_arch = "wasm32")]
    {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_else(|| "rigidlab-file".into());
        super::page_files::download(&name, bytes, mime)?;
        Ok((PathBuf::from(&name), format!("downloaded {name}")))
    }
}

/// The name F12 gives a screenshot: the level's file stem and the simulated time
/// (`screenshots/simple_pendulum-1.250s.png`); [`deliver`] adds a counter where it is taken.
pub fn screenshot_path(level_file: &Path, t: f64) -> PathBuf {
    let stem = level_file
        .file_stem()
        .map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().to_string());
    let name = format!("{stem}-{t:.3}s.png");
    if cfg!(target_arch = "wasm32") {
        PathBuf::from(name)
    } else {
        Path::new(SCREENSHOTS).join(name)
    }
}

/// Writes a captured screenshot as `path` through [`deliver`]: what happened, or why not.
pub fn save_screenshot(image: &Image, path: &Path) -> Result<String, String> {
    let rgb = image
        .clone()
        .try_into_dynamic()
        .map_err(|e| format!("screenshot not saved: cannot read the image: {e}"))?
        .to_rgb8();
    let bytes = crate::files::png_bytes(rgb.width(), rgb.height(), false, rgb.as_raw())
        .map_err(|e| format!("screenshot not saved: cannot encode it: {e}"))?;
    deliver(path, &bytes, "image/png")
        .map(|m| format!("screenshot {m}"))
        .map_err(|e| format!("screenshot {e}"))
}

/// Writes a level, checked first to load back identically (`editor::checked_text`), to the
/// user's file (a download in the browser). A file already at `path` is kept: the level goes
/// under a numbered name beside it ([`deliver`]).
pub fn save_level(scene: &Scene, path: &Path) -> Result<String, String> {
    save_level_as(scene, path).map(|(_, m)| m)
}

/// [`save_level`], with the file the level was written to.
pub fn save_level_as(scene: &Scene, path: &Path) -> Result<(PathBuf, String), String> {
    let text = crate::editor::checked_text(scene, path)?;
    let (used, done) = deliver_as(path, text.as_bytes(), "text/plain")?;
    Ok((used, format!("{done} (loads back identically)")))
}

/// The file name the save field starts with: the level's own stem with `-saved`, in the folder
/// the level browser lists (natively; the page downloads it).
pub fn default_save_path(scene: &Scene) -> String {
    let stem = scene
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "scene".into());
    if cfg!(target_arch = "wasm32") {
        format!("{stem}-saved.ron")
    } else {
        format!("{SAVED_LEVELS}/{stem}-saved.ron")
    }
}
