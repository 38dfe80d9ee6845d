//! Stage 1 of the data flow: level file -> validated scene model.
//!
//! `load` parses RON (syntax errors and unknown fields come with ron's
//! line:col) and then `validate`s the meaning (each semantic error points at
//! the line of the offending item and says how to fix it).

pub mod assignment;
pub mod curves;
mod error;
pub mod format;
pub mod link;
pub mod motion;
pub mod params;
pub mod profiles;
mod quantity_form;
pub mod shape;
pub mod track;
mod validate;
mod warnings;

pub use error::{LevelError, LevelWarning, Locator};
pub use format::*;
pub use validate::quantity_refs;

use std::io::Read;
use std::path::{Path, PathBuf};

/// A level that parsed and validated, with the file it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub file: PathBuf,
    pub level: Level,
}

/// How deep ron reads nested brackets before it stops (its default, which keeps the parser's
/// recursion off the end of the stack).
const RECURSION_LIMIT: usize = 128;

/// The RON options every level is read and written with.
pub fn ron_options() -> ron::Options {
    ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .with_recursion_limit(RECURSION_LIMIT)
}

/// The largest level file read, bytes: 15 times the library's largest (stress/joint_grid_30,
/// 900 bodies and their joints in 273 KiB); it keeps a wrong path (a log, an image) from being
/// read whole.
pub const MAX_LEVEL_BYTES: u64 = 4 << 20;

/// Reads, parses and validates a level file. Only regular files are read (a FIFO or a device
/// would block or never end), and at most [`MAX_LEVEL_BYTES`] of them.
pub fn load(path: &Path) -> Result<Scene, LevelError> {
    parse_bytes(path, &read(path)?)
}

/// [`load`], with the warnings of a valid level (legal but probably not meant; see
/// `level/warnings.rs`). The command line prints them before it runs the level.
pub fn load_with_warnings(path: &Path) -> Result<(Scene, Vec<LevelWarning>), LevelError> {
    load_variant(path, &params::Pick::Nominal).map(|l| (l.scene, l.warnings))
}

/// A level read for a run: its scene, the variant picked (a level with parameters), and its
/// warnings.
#[derive(Debug, Clone)]
pub struct Loaded {
    pub scene: Scene,
    pub variant: Option<params::Variant>,
    pub warnings: Vec<LevelWarning>,
    /// The challenge's control, with the value the scene was made with (a level with a
    /// challenge; see [`load_challenge`]).
    pub control: Option<(params::Control, f64)>,
}

/// [`load_with_warnings`] for one variant of a level with parameters (`check --student`); a
/// level without parameters is the same for every pick.
pub fn load_variant(path: &Path, pick: &params::Pick) -> Result<Loaded, LevelError> {
    let bytes = read(path)?;
    let bytes = bytes.strip_prefix(BOM.as_bytes()).unwrap_or(&bytes);
    parse_variant(path, utf8(path, bytes)?, pick)
}

/// The picked variant of a level listed with its text (`source`: compiled into the web page or
/// fetched there) or, without one, read from its file: the window's and the page's lists open
/// their levels through this.
pub fn variant_of(
    path: &Path,
    source: Option<&str>,
    pick: &params::Pick,
) -> Result<Scene, LevelError> {
    match source {
        Some(text) => parse_variant(path, text, pick),
        None => load_variant(path, pick),
    }
    .map(|l| l.scene)
}

/// [`load_variant`] from a level's text (a level compiled into the web page); `path` is only
/// used in messages.
pub fn parse_variant(path: &Path, text: &str, pick: &params::Pick) -> Result<Loaded, LevelError> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    if let Some((p, made)) = params::make_checked(path, text, pick)? {
        let warnings = p.warnings(path, &made);
        let control = p.control(path, &made)?.map(|c| {
            let v = made.variant.values[c.index].1;
            (c, v)
        });
        return Ok(Loaded {
            scene: Scene {
                file: path.to_path_buf(),
                level: made.level,
            },
            variant: Some(made.variant),
            warnings,
            control,
        });
    }
    let scene = parse(path, text)?;
    let warnings = warnings::find(path, text, &scene.level);
    Ok(Loaded {
        scene,
        variant: None,
        warnings,
        control: None,
    })
}

/// A level with a challenge, made to be run: the picked variant with the challenge's control
/// set to `value` (in the control's unit, the student's) or, when None, to its worked value.
/// A level without a challenge loads as [`load_variant`] loads it.
pub fn load_challenge(
    path: &Path,
    pick: &params::Pick,
    value: Option<f64>,
) -> Result<Loaded, LevelError> {
    parse_challenge(path, &read_text(path)?, pick, value)
}

/// [`load_challenge`] from a level's text (a level compiled into the web page); `path` is only
/// used in messages.
pub fn parse_challenge(
    path: &Path,
    text: &str,
    pick: &params::Pick,
    value: Option<f64>,
) -> Result<Loaded, LevelError> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    let plain = parse_variant(path, text, pick)?;
    if plain.control.is_none() {
        return Ok(plain);
    }
    let Some(p) = params::Parameterized::read(path, text)? else {
        return Ok(plain);
    };
    let (made, control) = p.make_control(path, &p.indices(pick), value)?;
    let warnings = p.warnings(path, &made);
    let control = control.map(|c| {
        let v = made.variant.values[c.index].1;
        (c, v)
    });
    Ok(Loaded {
        scene: Scene {
            file: path.to_path_buf(),
            level: made.level,
        },
        variant: Some(made.variant),
        warnings,
        control,
    })
}

/// A challenge in a level without parameters: its control can name none.
fn control_without_parameters(path: &Path, text: &str, level: &Level) -> Result<(), LevelError> {
    let Some(c) = &level.challenge else {
        return Ok(());
    };
    Err(LevelError::new(
        path,
        Locator::new(text).section_field("challenge", "control"),
        format!(
            "the challenge's control \"{}\" names no parameter: the level declares none",
            c.control
        ),
        "declare the control in `parameters: [(name: ..., range: (min, max), step: ..., unit: ...)]` and write the scene's values that depend on it as expressions of it (docs/levels.md#challenges)",
    ))
}

/// A level file's text (UTF-8, without a byte-order mark), read as [`load`] reads it.
pub fn read_text(path: &Path) -> Result<String, LevelError> {
    let bytes = read(path)?;
    let bytes = bytes.strip_prefix(BOM.as_bytes()).unwrap_or(&bytes);
    utf8(path, bytes).map(str::to_string)
}

/// A level file's bytes: a regular file of at most [`MAX_LEVEL_BYTES`].
fn read(path: &Path) -> Result<Vec<u8>, LevelError> {
    read_regular(path, MAX_LEVEL_BYTES).map_err(|e| match e {
        ReadError::Io(e) => LevelError::new(
            path,
            (0, 0),
            format!("cannot read the level file: {e}"),
            "check the path and the file's permissions",
        ),
        ReadError::NotRegular(kind) => LevelError::new(
            path,
            (0, 0),
            format!("not a regular file: {kind}"),
            "give a level file (.ron) or a folder of them",
        ),
        ReadError::TooBig(_) => LevelError::new(
            path,
            (0, 0),
            format!(
                "the file is larger than {} MiB, the limit for a level",
                MAX_LEVEL_BYTES >> 20
            ),
            "check that this is a level file (the library's largest, 900 bodies, is 273 KiB)",
        ),
    })
}

/// Why [`read_regular`] read nothing.
#[derive(Debug)]
pub enum ReadError {
    /// The file could not be opened or read (missing, no permission, ...).
    Io(std::io::Error),
    /// A FIFO, a device, a socket or a folder: what [`file_kind`] calls it.
    NotRegular(&'static str),
    /// Larger than the limit, bytes.
    TooBig(u64),
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadError::Io(e) => write!(f, "{e}"),
            ReadError::NotRegular(kind) => write!(f, "not a regular file: {kind}"),
            ReadError::TooBig(limit) => write!(f, "the file is larger than {limit} bytes"),
        }
    }
}

/// The bytes of a regular file of at most `limit` bytes, as levels are read (and the window's
/// preferences): the path is stat'ed before it is opened (opening a FIFO would wait for a
/// writer), a device or a link to one is refused, and no more than `limit` + 1 bytes are read
/// (a file that grows after the stat is still refused).
pub fn read_regular(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    let meta = std::fs::metadata(path).map_err(ReadError::Io)?;
    if !meta.is_file() {
        return Err(ReadError::NotRegular(file_kind(&meta)));
    }
    if meta.len() > limit {
        return Err(ReadError::TooBig(limit));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
        .map_err(ReadError::Io)?;
    if bytes.len() as u64 > limit {
        // It grew after the stat.
        return Err(ReadError::TooBig(limit));
    }
    Ok(bytes)
}

/// What a path that is not a regular file is, for messages.
pub fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        } else if t.is_char_device() || t.is_block_device() {
            return "a device";
        } else if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a folder"
    } else {
        "not a regular file"
    }
}

/// Parses and validates a level file's bytes: text that is not UTF-8 is an error at the line and
/// column of the first bad byte.
pub fn parse_bytes(path: &Path, bytes: &[u8]) -> Result<Scene, LevelError> {
    let bytes = bytes.strip_prefix(BOM.as_bytes()).unwrap_or(bytes);
    parse(path, utf8(path, bytes)?)
}

/// The bytes as UTF-8 text, or an error at the line and column of the first bad byte.
fn utf8<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str, LevelError> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text),
        Err(e) => {
            let valid = &bytes[..e.valid_up_to()];
            // The valid prefix is UTF-8, so lines and columns count characters as elsewhere.
            let valid = std::str::from_utf8(valid).expect("valid up to here");
            let line = valid.matches('\n').count() + 1;
            let col = valid[valid.rfind('\n').map_or(0, |i| i + 1)..]
                .chars()
                .count()
                + 1;
            Err(LevelError::new(
                path,
                (line, col),
                format!("invalid UTF-8 (byte 0x{:02x})", bytes[e.valid_up_to()]),
                "save the level as UTF-8 text",
            ))
        }
    }
}

/// The byte-order mark some editors (Notepad) put before UTF-8 text. It is not part of the
/// text: a level that starts with one is read without it, and its line and column numbers count
/// from the first character after it, as the editor shows them.
const BOM: &str = "\u{feff}";

/// Parses and validates level text; `path` is only used in messages. A leading byte-order mark
/// is skipped (ron refused it as "Expected opening `(`").
pub fn parse(path: &Path, text: &str) -> Result<Scene, LevelError> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    // A level with parameters: its nominal variant, once every corner of its ranges is valid.
    if let Some((_, made)) = params::make_checked(path, text, &params::Pick::Nominal)? {
        return Ok(Scene {
            file: path.to_path_buf(),
            level: made.level,
        });
    }
    let level: Level = ron_options()
        .from_str(text)
        .map_err(|e| syntax_error(path, text, &e))?;
    validate::validate(path, text, &level)?;
    control_without_parameters(path, text, &level)?;
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

fn syntax_error(path: &Path, text: &str, e: &ron::error::SpannedError) -> LevelError {
    use ron::error::Error as E;
    let mut help = match &e.code {
        E::NoSuchStructField { expected, .. } => {
            format!("remove it or use one of: {}", expected.join(", "))
        }
        E::NoSuchEnumVariant { expected, .. } => format!("use one of: {}", expected.join(", ")),
        E::MissingStructField { field, .. } => format!("add `{field}: ...` (see docs/levels.md)"),
        E::DuplicateStructField { .. } => "write each field once".to_string(),
        E::ExpectedFloat | E::ExpectedInteger => "write a number, e.g. 1.0".to_string(),
        E::ExceededRecursionLimit => {
            // ron's own message names its API (`recursion_limit`, `serde_stacker`): a hint for
            // the program, not for the level's author.
            return LevelError {
                file: path.to_path_buf(),
                line: e.span.start.line,
                col: e.span.start.col,
                message: format!(
                    "the level nests brackets more than {RECURSION_LIMIT} deep here"
                ),
                help: "a level needs a few levels of brackets (a compound's parts nest one shape in another): check for brackets opened and never closed, and flatten compounds nested in compounds into one list of parts".to_string(),
            };
        }
        _ => "see docs/levels.md for the level format".to_string(),
    };
    // Inside a question's quantity, how that quantity is written (issue 41: `PolarAngle("puck")`
    // got "Expected identifier" and no word of its `(body:, about:)`).
    if !matches!(e.code, E::NoSuchEnumVariant { .. }) {
        let at = byte_offset(text, e.span.start.line, e.span.start.col);
        if let Some(form) = quantity_form::hint(text, at) {
            help = format!("{form}; {help}");
        }
    }
    LevelError {
        file: path.to_path_buf(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: e.code.to_string(),
        help,
    }
}

/// The byte offset of a 1-based line and column (a column counts characters, as ron's do).
fn byte_offset(text: &str, line: usize, col: usize) -> usize {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let rest = &text[start.min(text.len())..];
    start
        + rest
            .char_indices()
            .nth(col.saturating_sub(1))
            .map_or(rest.len(), |(i, _)| i)
}

/// Every `*.ron` file under the given files and folders (recursively), sorted. Warnings about
/// what the search skipped go to stderr (see [`find_files`]), and an assignment manifest that
/// does not read is a warning here (`rigidlab check` makes it an error: [`collect_levels`]).
pub fn collect_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, LevelError> {
    let (files, bad) = collect_levels(paths)?;
    for e in &bad {
        stderr!("warning: {e}");
    }
    Ok(files)
}

/// [`find_files`] with its skips (warnings) and notes written to stderr: the level files, and
/// the assignment manifests met that do not read, with their located errors.
pub fn collect_levels(paths: &[PathBuf]) -> Result<(Vec<PathBuf>, Vec<LevelError>), LevelError> {
    let found = find_files(paths)?;
    for w in &found.skipped {
        stderr!("warning: {w}");
    }
    for n in &found.notes {
        stderr!("note: {n}");
    }
    Ok((found.files, found.bad_manifests))
}

/// The level files a search found, and what it skipped (with why).
#[derive(Debug, Default)]
pub struct Found {
    pub files: Vec<PathBuf>,
    pub skipped: Vec<String>,
    /// What each assignment manifest met stood for (it is read as a manifest, not as a level).
    pub notes: Vec<String>,
    /// The manifests met that do not read.
    pub bad_manifests: Vec<LevelError>,
}

/// Every `*.ron` file under the given files and folders (recursively), sorted. Paths given
/// directly are kept as they are (`load` refuses what is not a regular file); inside folders, a
/// `*.ron` that is not a regular file (a FIFO, a device, a broken link) is skipped, and a folder
/// reached twice (a symlink loop, or given twice) is searched once.
///
/// An assignment's manifest (`assignment.ron`, docs/teacher.md) is not a level: given by name,
/// it stands for its levels in its order; met in a folder, it is read (a manifest that does not
/// read goes to `bad_manifests`) and left out with a note, its levels being files of that
/// folder and found with them. (It was read as a level that does not load: "Expected struct
/// `Level` but found `Assignment`".)
pub fn find_files(paths: &[PathBuf]) -> Result<Found, LevelError> {
    let mut found = Found::default();
    let mut seen = std::collections::HashSet::new();
    for p in paths {
        if p.is_dir() {
            walk(p, &mut seen, &mut found).map_err(|e| {
                LevelError::new(
                    p,
                    (0, 0),
                    format!("cannot read the folder: {e}"),
                    "check the path",
                )
            })?;
        } else if assignment::is_manifest(p) {
            manifest(p, true, &mut found);
        } else if p.exists() {
            found.files.push(p.clone());
        } else {
            return Err(LevelError::new(
                p,
                (0, 0),
                "no such file or folder",
                "give a level file (.ron) or a folder of them",
            ));
        }
    }
    Ok(found)
}

/// An assignment manifest met by the search: read; `given` (named by the user), its levels join
/// the files in its order; met in a folder, a note (its levels are that folder's files).
fn manifest(p: &Path, given: bool, found: &mut Found) {
    match assignment::Assignment::load(p) {
        Ok(a) if given => {
            found.notes.push(format!(
                "{}: an assignment; its {} levels in its order",
                p.display(),
                a.levels.len()
            ));
            found.files.extend(a.levels);
        }
        Ok(a) => found.notes.push(format!(
            "{}: an assignment's manifest ({} levels), read as one and not as a level; its levels are files of its folder",
            p.display(),
            a.levels.len()
        )),
        Err(e) => found.bad_manifests.push(e),
    }
}

fn walk(
    dir: &Path,
    seen: &mut std::collections::HashSet<PathBuf>,
    found: &mut Found,
) -> std::io::Result<()> {
    if !seen.insert(dir.canonicalize()?) {
        found.skipped.push(format!(
            "{}: a folder already searched (a link back up, or given twice), skipped",
            dir.display()
        ));
        return Ok(());
    }
    let mut entries: Vec<_> = std::fs::read_dir(dir)?.collect::<Result<_, _>>()?;
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let p = e.path();
        if p.is_dir() {
            walk(&p, seen, found)?;
        } else if assignment::is_manifest(&p) {
            manifest(&p, false, found);
        } else if p.extension().is_some_and(|x| x == "ron") {
            match std::fs::metadata(&p) {
                Ok(m) if m.is_file() => found.files.push(p),
                Ok(m) => found.skipped.push(format!(
                    "{}: {}, not a level file, skipped",
                    p.display(),
                    file_kind(&m)
                )),
                Err(e) => found
                    .skipped
                    .push(format!("{}: cannot read it ({e}), skipped", p.display())),
            }
        }
    }
    Ok(())
}
