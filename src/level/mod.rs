//! Stage 1 of the data flow: level file -> validated scene model.
//!
//! `load` parses RON (syntax errors and unknown fields come with ron's
//! line:col) and then `validate`s the meaning (each semantic error points at
//! the line of the offending item and says how to fix it).

mod error;
pub mod format;
mod validate;

pub use error::{LevelError, Locator};
pub use format::*;

use std::path::{Path, PathBuf};

/// A level that parsed and validated, with the file it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub file: PathBuf,
    pub level: Level,
}

/// The RON options every level is read and written with.
pub fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
}

/// Reads, parses and validates a level file.
pub fn load(path: &Path) -> Result<Scene, LevelError> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        LevelError::new(
            path,
            (0, 0),
            format!("cannot read the level file: {e}"),
            "check the path and that the file is UTF-8 text",
        )
    })?;
    parse(path, &text)
}

/// Parses and validates level text; `path` is only used in messages.
pub fn parse(path: &Path, text: &str) -> Result<Scene, LevelError> {
    let level: Level = ron_options()
        .from_str(text)
        .map_err(|e| syntax_error(path, &e))?;
    validate::validate(path, text, &level)?;
    Ok(Scene {
        file: path.to_path_buf(),
        level,
    })
}

/// Writes a level as RON that `parse` reads back to the same value.
pub fn to_ron(level: &Level) -> String {
    let pretty = ron::ser::PrettyConfig::new()
        .struct_names(true)
        .depth_limit(6)
        .indentor("  ".to_string());
    ron_options()
        .to_string_pretty(level, pretty)
        .expect("a Level always serializes")
}

fn syntax_error(path: &Path, e: &ron::error::SpannedError) -> LevelError {
    use ron::error::Error as E;
    let help = match &e.code {
        E::NoSuchStructField { expected, .. } => {
            format!("remove it or use one of: {}", expected.join(", "))
        }
        E::NoSuchEnumVariant { expected, .. } => format!("use one of: {}", expected.join(", ")),
        E::MissingStructField { field, .. } => format!("add `{field}: ...` (see docs/levels.md)"),
        E::DuplicateStructField { .. } => "write each field once".to_string(),
        E::ExpectedFloat | E::ExpectedInteger => "write a number, e.g. 1.0".to_string(),
        _ => "see docs/levels.md for the level format".to_string(),
    };
    LevelError {
        file: path.to_path_buf(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: e.code.to_string(),
        help,
    }
}

/// Every `*.ron` file under the given files and folders (recursively), sorted.
pub fn collect_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, LevelError> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            walk(p, &mut out).map_err(|e| {
                LevelError::new(
                    p,
                    (0, 0),
                    format!("cannot read the folder: {e}"),
                    "check the path",
                )
            })?;
        } else if p.exists() {
            out.push(p.clone());
        } else {
            return Err(LevelError::new(
                p,
                (0, 0),
                "no such file or folder",
                "give a level file (.ron) or a folder of them",
            ));
        }
    }
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)?.collect::<Result<_, _>>()?;
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let p = e.path();
        if p.is_dir() {
            walk(&p, out)?;
        } else if p.extension().is_some_and(|x| x == "ron") {
            out.push(p);
        }
    }
    Ok(())
}
