//! Which level library the window opens, and the library compiled into the program. Started
//! from another folder (`cd /tmp && rigidlab`), the window looked for `./levels` only and showed
//! an empty course, "levels: no such file or folder" (issue 42, the student trial of
//! 2026-12-07). It now takes, in order: the folder given (`--levels DIR`), `./levels`, a
//! `levels` folder beside the program or in a folder above it (a `cargo build` binary in
//! `target/release` finds the repository's), and last the library compiled in (2.9 MB of RON in
//! a binary of about 130 MB). The status line says which one opened. The web page compiled it in
//! too until 2026-12-07; it now fetches it beside the wasm (`app/page_library.rs`).

#[cfg(not(target_arch = "wasm32"))]
use include_dir::{include_dir, Dir};
use std::path::{Path, PathBuf};
#[cfg(not(target_arch = "wasm32"))]
use std::sync::Arc;

/// The page's library, fetched as `levels.json` beside the wasm.
#[cfg(target_arch = "wasm32")]
pub use super::page_library::library;

/// The level library, compiled in: the folder as it was when the crate was last compiled
/// (Cargo does not watch the folder for it: include_dir tracks files on nightly Rust only, and
/// a build script watching it would rebuild rigidlab after every level edited). A folder, found
/// first wherever there is one, has the levels as they are now.
#[cfg(not(target_arch = "wasm32"))]
static LEVELS: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/levels");

/// The compiled-in library as `(levels/<topic>/<file>.ron, text)`, the paths `rigidlab check
/// levels` prints.
#[cfg(not(target_arch = "wasm32"))]
pub fn library() -> Vec<(PathBuf, Arc<str>)> {
    fn walk(d: &Dir<'static>, out: &mut Vec<(PathBuf, Arc<str>)>) {
        for f in d.files() {
            if f.path().extension().is_some_and(|e| e == "ron") {
                if let Some(text) = f.contents_utf8() {
                    out.push((Path::new("levels").join(f.path()), Arc::from(text)));
                }
            }
        }
        for sub in d.dirs() {
            walk(sub, out);
        }
    }
    let mut out = Vec::new();
    walk(&LEVELS, &mut out);
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Where the library was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Library {
    /// The folder named with `--levels`.
    Given(PathBuf),
    /// `levels` in the folder the program was started from.
    Here,
    /// A `levels` folder beside the program, or in a folder above it.
    BesideProgram(PathBuf),
    /// No folder: the library compiled into the program.
    Compiled,
}

/// The library to open: `given`, else `cwd/levels`, else `levels` in the program's folder
/// (`exe`'s) or one above it, holding at least one level, else the compiled-in one.
pub fn find(given: Option<&Path>, cwd: &Path, exe: Option<&Path>) -> Library {
    if let Some(dir) = given {
        return Library::Given(dir.to_path_buf());
    }
    if cwd.join("levels").is_dir() {
        return Library::Here;
    }
    let beside = exe
        .and_then(Path::parent)
        .into_iter()
        .flat_map(Path::ancestors)
        .map(|dir| dir.join("levels"))
        .find(|dir| holds_levels(dir));
    beside.map_or(Library::Compiled, Library::BesideProgram)
}

/// A folder holding at least one level file: a `levels` folder above the program that holds
/// none (another program's) is not taken for the library.
fn holds_levels(dir: &Path) -> bool {
    dir.is_dir()
        && crate::level::collect_files(&[dir.to_path_buf()]).is_ok_and(|files| !files.is_empty())
}

impl Library {
    /// The folder to list, or None for the compiled-in library.
    pub fn folder(&self) -> Option<PathBuf> {
        match self {
            Library::Given(dir) | Library::BesideProgram(dir) => Some(dir.clone()),
            Library::Here => Some(PathBuf::from("levels")),
            Library::Compiled => None,
        }
    }

    /// What the status line says of it.
    pub fn note(&self) -> String {
        match self {
            Library::Given(dir) => format!("levels from {} (--levels)", dir.display()),
            Library::Here => "levels from ./levels".to_string(),
            Library::BesideProgram(dir) => format!(
                "levels from {} (beside the program: no ./levels here)",
                dir.display()
            ),
            Library::Compiled => "levels compiled into rigidlab (no ./levels here nor beside \
                                  the program; --levels DIR opens a folder)"
                .to_string(),
        }
    }
}

/// The library the window opens from where it was started: [`find`] with this process's folder
/// and program.
pub fn here(given: Option<&Path>) -> Library {
    let cwd = std::env::current_dir().unwrap_or_default();
    let exe = std::env::current_exe().ok();
    find(given, &cwd, exe.as_deref())
}
