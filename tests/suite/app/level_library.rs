//! Which level library the window opens (issue 42, the student trial of 2026-12-07: started
//! from another folder, `cd /tmp && rigidlab`, the window showed an empty course, "levels: no
//! such file or folder"). The folder given, else `./levels`, else a `levels` folder beside the
//! program or above it, else the library compiled in; the status line says which. The process's
//! own folder is never changed here (the suite's tests share it): `find` takes the folder and
//! the program's path as a window started elsewhere would see them.

use rigidlab::app::library::{self, Library};
use rigidlab::app::sandbox::library_browser;
use rigidlab::app::FIRST_LEVEL;
use std::path::{Path, PathBuf};

use crate::common;

/// An empty folder of this test's own (`tag`, the process id).
fn empty_folder(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-library-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The repository's library, the one `cargo build` puts the program below.
fn repo_levels() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("levels")
}

/// Started from a folder without `levels`, the program built in the repository's
/// target/release finds the repository's library above it, lists its first level without an
/// error, and says where it found it. Before, the window scanned `./levels` only.
#[test]
fn started_from_another_folder_the_window_finds_the_library_beside_the_program() {
    let cwd = empty_folder("elsewhere");
    let exe = Path::new(env!("CARGO_BIN_EXE_rigidlab"));
    let found = library::find(None, &cwd, Some(exe));
    let Library::BesideProgram(dir) = &found else {
        panic!("from {} with {}: {found:?}", cwd.display(), exe.display());
    };
    assert_eq!(
        dir.canonicalize().unwrap(),
        repo_levels().canonicalize().unwrap()
    );
    let browser = library_browser(&found);
    let note = &browser.opened_from;
    assert_eq!(browser.error, None);
    assert!(
        browser.find(&browser.root.join(FIRST_LEVEL)).is_some(),
        "no {FIRST_LEVEL} listed under {}",
        browser.root.display()
    );
    assert!(
        note.contains(&dir.display().to_string()) && note.contains("beside the program"),
        "{note}"
    );
    let _ = std::fs::remove_dir_all(&cwd);
}

/// A program with no library anywhere above it (copied out of the repository) opens the one
/// compiled in: every level the repository's folder held when the program was built is there
/// (`FIRST_LEVEL` among them, the library's 100 and more), and it opens.
#[test]
fn with_no_folder_anywhere_the_library_compiled_in_opens() {
    let cwd = empty_folder("nowhere");
    let exe = cwd.join("bin").join("rigidlab");
    let found = library::find(None, &cwd, Some(&exe));
    assert_eq!(found, Library::Compiled);
    let browser = library_browser(&found);
    let note = &browser.opened_from;
    assert!(browser.embedded && browser.error.is_none());
    let listed = browser.groups.values().flatten().count();
    assert!(listed > 100, "{listed} levels compiled in");
    let first = browser
        .open_listed(&browser.root.join(FIRST_LEVEL))
        .expect("the first level is listed")
        .expect("and it loads");
    let on_disk = common::load(Path::new("levels").join(FIRST_LEVEL));
    assert_eq!(first.level.title, on_disk.level.title);
    assert!(note.contains("compiled into rigidlab"), "{note}");
    let _ = std::fs::remove_dir_all(&cwd);
}

/// `./levels` comes before the program's, and a folder given comes before both.
#[test]
fn the_folder_given_then_the_one_here_come_first() {
    let here = empty_folder("here");
    std::fs::create_dir_all(here.join("levels")).unwrap();
    let exe = Path::new(env!("CARGO_BIN_EXE_rigidlab"));
    assert_eq!(library::find(None, &here, Some(exe)), Library::Here);
    let given = repo_levels();
    assert_eq!(
        library::find(Some(&given), &here, Some(exe)),
        Library::Given(given.clone())
    );
    let _ = std::fs::remove_dir_all(&here);
}

/// With no level named, the window and the page open the same first exercise, the tour's
/// pendulum, from the library compiled in as from a folder (the second student trial of
/// 2026-12-07: the page opened "Challenge: a fifth of g", the library's first file, on every
/// visit, while the window opened the pendulum).
#[test]
fn with_no_level_named_the_page_and_the_window_open_the_tours_pendulum() {
    use rigidlab::app::sandbox::first_exercise;
    let want = rigidlab::level::load(&repo_levels().join(FIRST_LEVEL)).unwrap();
    for found in [Library::Compiled, Library::Given(repo_levels())] {
        let opened = first_exercise(&library_browser(&found));
        assert_eq!(opened.level.title, want.level.title, "{found:?}");
    }
}
