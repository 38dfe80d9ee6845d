//! Where a file the user asks for goes: written to disk in the native window, downloaded by the
//! browser in the web page (which has no file system). Screenshots need nothing here: Bevy's
//! `save_to_disk` already downloads in a page.

use std::path::Path;

/// Where the window saves levels (and the level browser lists them): a folder of the working
/// directory, apart from the library in levels/ that the tests run.
pub const SAVED_LEVELS: &str = "saved-levels";

/// Writes `bytes` as `path` (native) or offers them as a download named after `path`'s file name
/// (web). Returns what happened, for the status line.
pub fn deliver(path: &Path, bytes: &[u8], mime: &str) -> Result<String, String> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = mime;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("cannot make the folder {}: {e}", dir.display()))?;
        }
        std::fs::write(path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        Ok(format!("saved {}", path.display()))
    }
    #[cfg(target_arch = "wasm32")]
    {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_else(|| "rigidlab-file".into());
        super::web::download(&name, bytes, mime)?;
        Ok(format!("downloaded {name}"))
    }
}
