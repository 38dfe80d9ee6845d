//! The page's level library: `web/build.sh` writes it beside the wasm as `levels.json` (the
//! library's level files as `[path, text]` pairs), `web/index.html` fetches it while the wasm
//! comes and leaves its text in `globalThis.rigidlabLibrary` before starting the app. Compiled
//! into the wasm it was 1.8 MB of its raw size (docs/web.md, "A lighter page"); served as its
//! own file it goes compressed like the wasm (0.14 MB as brotli, 2026-12-07), and the native
//! program keeps it compiled in (`app/library.rs`).

use std::path::PathBuf;
use std::sync::Arc;

/// The global `web/index.html` leaves the library's JSON in.
const GLOBAL: &str = "rigidlabLibrary";

/// The library as `(levels/<topic>/<file>.ron, text)`, sorted by path; empty when the page
/// started without it (`web/index.html` refuses to start when `levels.json` does not load).
pub fn library() -> Vec<(PathBuf, Arc<str>)> {
    let json = js_sys::Reflect::get(&js_sys::global(), &GLOBAL.into())
        .ok()
        .and_then(|v| v.as_string())
        .unwrap_or_default();
    let mut out: Vec<(PathBuf, Arc<str>)> = parse(&json)
        .into_iter()
        .map(|(path, text)| (PathBuf::from(path), Arc::from(text)))
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// `levels.json`'s pairs; nothing for text that is not that.
fn parse(json: &str) -> Vec<(String, String)> {
    serde_json::from_str(json).unwrap_or_default()
}
