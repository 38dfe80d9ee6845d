//! The page's `?url=PATH` (wasm32): a level file or an assignment served beside the page, fetched
//! from the page's own origin. An assignment (`.../assignment.ron`, or a folder ending in `/`)
//! fetches each of its levels, relative to its folder, and lists them in order in the level
//! browser. Only the page's own origin: a teacher's files on the same host, never a third
//! party's address put into a link.
//!
//! The fetch is asynchronous: the app starts on the empty scene, and `web.rs` opens what arrived
//! (or says why it did not) on the frame after. Below the panels: it hands over a level or an
//! assignment and the texts of its levels, which `web.rs` puts in the panels.

use crate::level::assignment::{Assignment, MANIFEST};
use crate::level::{self, Scene};
use bevy::prelude::*;
use std::path::Path;
use std::sync::{Arc, Mutex};
use wasm_bindgen::JsCast;
use wasm_bindgen_futures::JsFuture;

/// What a fetch brought: a level, or an assignment with each of its levels' text (`Err`: why
/// that level could not be fetched).
pub enum Fetched {
    Level(Box<Scene>),
    Assignment(Assignment, Vec<Result<Arc<str>, String>>),
}

/// The fetch under way: its result once it arrived (`Err`: why nothing opened).
#[derive(Resource, Clone)]
pub struct PageFetch {
    pub asked: String,
    slot: Arc<Mutex<Option<Result<Fetched, String>>>>,
}

impl PageFetch {
    /// What arrived, once (`None` while it is under way, and after it was taken).
    pub fn take(&self) -> Option<Result<Fetched, String>> {
        self.slot.lock().expect("one thread").take()
    }
}

/// Starts fetching `asked` (the URL's `url=` value); refused at once when it is not the page's
/// own origin.
pub fn start(asked: String) -> PageFetch {
    let fetch = PageFetch {
        asked: asked.clone(),
        slot: Arc::new(Mutex::new(None)),
    };
    let slot = fetch.slot.clone();
    wasm_bindgen_futures::spawn_local(async move {
        let r = match same_origin_path(&asked) {
            Ok(path) => open(&path).await,
            Err(e) => Err(e),
        };
        *slot.lock().expect("one thread") = Some(r);
    });
    fetch
}

/// The path of `asked` on the page's origin (path and query kept), or why it is refused.
fn same_origin_path(asked: &str) -> Result<String, String> {
    let refuse = |why: &str| format!("?url={asked} did not open: {why}");
    let location = web_sys::window()
        .map(|w| w.location())
        .ok_or_else(|| refuse("no page location"))?;
    let href = location.href().map_err(|_| refuse("no page address"))?;
    let url =
        web_sys::Url::new_with_base(asked, &href).map_err(|_| refuse("not a path or address"))?;
    let origin = location.origin().map_err(|_| refuse("no page origin"))?;
    if url.origin() != origin {
        return Err(refuse(
            "only files served beside the page open (its own origin); give a path such as assignments/intro/assignment.ron",
        ));
    }
    Ok(url.pathname())
}

/// The level or the assignment at `path` (a path on the page's origin).
async fn open(path: &str) -> Result<Fetched, String> {
    let is_assignment = path.ends_with('/') || path.ends_with(MANIFEST);
    let path = if path.ends_with('/') {
        format!("{path}{MANIFEST}")
    } else {
        path.to_string()
    };
    let text = fetch_text(&path).await?;
    if !is_assignment {
        return level::parse_variant(Path::new(&path), &text, &super::student::pick())
            .map(|l| Fetched::Level(Box::new(l.scene)))
            .map_err(|e| format!("{path} did not open:\n{e}"));
    }
    let a = Assignment::parse(Path::new(&path), &text)
        .map_err(|e| format!("the assignment did not open:\n{e}"))?;
    let mut texts = Vec::with_capacity(a.levels.len());
    for p in &a.levels {
        texts.push(fetch_text(&p.to_string_lossy()).await.map(Arc::from));
    }
    Ok(Fetched::Assignment(a, texts))
}

/// The text of the file at `path` on the page's origin, or why not (not found, not text).
async fn fetch_text(path: &str) -> Result<String, String> {
    let fail = |why: String| format!("cannot fetch {path}: {why}");
    let window = web_sys::window().ok_or_else(|| fail("no window".into()))?;
    let resp = JsFuture::from(window.fetch_with_str(path))
        .await
        .map_err(|e| fail(format!("{e:?}")))?;
    let resp: web_sys::Response = resp.dyn_into().map_err(|_| fail("no response".into()))?;
    if !resp.ok() {
        return Err(fail(format!("the server answered {}", resp.status())));
    }
    let text = resp.text().map_err(|_| fail("no text".into()))?;
    let text = JsFuture::from(text)
        .await
        .map_err(|_| fail("the body is not text".into()))?;
    let text = text
        .as_string()
        .ok_or_else(|| fail("the body is not text".into()))?;
    if text.len() as u64 > level::MAX_LEVEL_BYTES {
        return Err(fail("larger than a level may be".into()));
    }
    Ok(text)
}
