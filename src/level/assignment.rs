//! An assignment: a titled, ordered list of levels a teacher hands out, with an optional due
//! date. It is a folder holding `assignment.ron` and the levels it lists:
//!
//! ```ron
//! Assignment(
//!   title: "Week 3: rolling and pendulums",
//!   levels: ["simple_pendulum.ron", "rolling/classic_rolling_disc.ron"],
//!   due: "2026-12-14",
//! )
//! ```
//!
//! Level paths are relative to the manifest's folder and stay inside it (no absolute path, no
//! `..` above it), so the folder can be zipped, copied or served as it is. Errors are located
//! like a level's (`file:line:col: message` and how to fix it). This module reads the manifest
//! only; each level is loaded, and its own errors shown, where it is opened.

use super::error::{blank_comments_and_strings, find_key, LevelError};
use serde::Deserialize;
use std::path::{Component, Path, PathBuf};

/// The manifest's file name inside an assignment folder.
pub const MANIFEST: &str = "assignment.ron";

/// The largest manifest read, bytes: a list of paths, far below this.
const MAX_MANIFEST_BYTES: u64 = 1 << 20;

/// An assignment read from its manifest, its level paths resolved.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Assignment {
    /// The manifest file it was read from.
    pub file: PathBuf,
    pub title: String,
    /// The due date as written, `YYYY-MM-DD` (checked to be a calendar date).
    pub due: Option<String>,
    /// The levels in the manifest's order, each the manifest's folder joined with its entry.
    pub levels: Vec<PathBuf>,
}

/// The file as written: `Assignment(title, levels, due)`; any other field is an error.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename = "Assignment")]
struct Manifest {
    title: String,
    levels: Vec<String>,
    #[serde(default)]
    due: Option<String>,
}

impl Assignment {
    /// Reads an assignment from its manifest (`.../assignment.ron`) or its folder, and checks
    /// that every level it lists is a file inside the folder.
    pub fn load(path: &Path) -> Result<Assignment, LevelError> {
        let file = if path.is_dir() {
            path.join(MANIFEST)
        } else {
            path.to_path_buf()
        };
        let text = read_manifest(&file, path)?;
        let a = Assignment::parse(&file, &text)?;
        let code = blank_comments_and_strings(&text);
        for (k, level) in a.levels.iter().enumerate() {
            if !level.is_file() {
                let what = if level.exists() {
                    "is not a file"
                } else {
                    "does not exist"
                };
                return Err(LevelError::new(
                    &file,
                    nth_level_pos(&text, &code, k),
                    format!("level {} {what}", level.display()),
                    "write the path of a level file relative to the assignment's folder (copy the level into the folder first)",
                ));
            }
        }
        Ok(a)
    }

    /// Parses and checks a manifest's text without touching the file system (the web page
    /// fetches the levels itself): the fields, a non-empty list of `.ron` paths inside the folder,
    /// each once, and the due date. `file` is where the text came from: the levels are resolved
    /// against its folder.
    pub fn parse(file: &Path, text: &str) -> Result<Assignment, LevelError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let m: Manifest = super::ron_options()
            .from_str(text)
            .map_err(|e| syntax_error(file, &e))?;
        let code = blank_comments_and_strings(text);
        let at_key = |key: &str| find_key(&code, key, 0).map_or((1, 1), |o| pos(text, o));
        if m.title.trim().is_empty() {
            return Err(LevelError::new(
                file,
                at_key("title"),
                "the assignment's title is empty",
                "write what students will see, e.g. title: \"Week 3: rolling\"",
            ));
        }
        if m.levels.is_empty() {
            return Err(LevelError::new(
                file,
                at_key("levels"),
                "the assignment lists no levels",
                "list the level files, relative to the assignment's folder: levels: [\"a.ron\", \"sub/b.ron\"]",
            ));
        }
        if let Some(due) = &m.due {
            check_date(due).map_err(|why| {
                LevelError::new(
                    file,
                    at_key("due"),
                    format!("due date \"{due}\" {why}"),
                    "write the date as YYYY-MM-DD, e.g. due: \"2026-12-14\", or leave `due` out",
                )
            })?;
        }
        let folder = file.parent().unwrap_or(Path::new(""));
        let mut levels = Vec::with_capacity(m.levels.len());
        for (k, entry) in m.levels.iter().enumerate() {
            let at = || nth_level_pos(text, &code, k);
            let rel = relative_inside(entry).map_err(|(why, help)| {
                LevelError::new(file, at(), format!("level \"{entry}\" {why}"), help)
            })?;
            let path = folder.join(&rel);
            if levels.contains(&path) {
                return Err(LevelError::new(
                    file,
                    at(),
                    format!("level \"{entry}\" is listed twice"),
                    "list each level once",
                ));
            }
            levels.push(path);
        }
        Ok(Assignment {
            file: file.to_path_buf(),
            title: m.title,
            due: m.due,
            levels,
        })
    }

    /// The folder the assignment's levels are relative to.
    pub fn folder(&self) -> &Path {
        self.file.parent().unwrap_or(Path::new(""))
    }
}

/// Whether a path names an assignment rather than a level: a folder, or a file named
/// `assignment.ron`.
pub fn is_assignment(path: &Path) -> bool {
    path.is_dir() || path.file_name().is_some_and(|n| n == MANIFEST)
}

/// Whether `path` is an assignment's manifest: a file named `assignment.ron`.
pub fn is_manifest(path: &Path) -> bool {
    path.file_name().is_some_and(|n| n == MANIFEST) && path.is_file()
}

/// The manifest's text; `given` is the path the user gave (a folder or the file).
fn read_manifest(file: &Path, given: &Path) -> Result<String, LevelError> {
    let bytes = super::read_regular(file, MAX_MANIFEST_BYTES).map_err(|e| {
        let help = if given.is_dir() {
            format!("an assignment folder holds its list of levels in {MANIFEST} (docs/teacher.md)")
        } else {
            "give an assignment folder or its assignment.ron (docs/teacher.md)".to_string()
        };
        LevelError::new(
            file,
            (0, 0),
            format!("cannot read the assignment: {e}"),
            help,
        )
    })?;
    String::from_utf8(bytes).map_err(|_| {
        LevelError::new(
            file,
            (0, 0),
            "the assignment is not UTF-8 text",
            "save it as UTF-8 text",
        )
    })
}

/// The entry as a relative path inside the folder, `.` and `..` resolved; or why not and how to
/// fix it.
fn relative_inside(entry: &str) -> Result<PathBuf, (String, &'static str)> {
    const INSIDE: &str = "write a path relative to the assignment's folder and inside it (copy the level into the folder): \"a.ron\", \"sub/b.ron\"";
    if entry.trim().is_empty() {
        return Err(("is empty".into(), INSIDE));
    }
    // Both separators, on every system: a manifest written on Windows reads the same elsewhere.
    let unified = entry.replace('\\', "/");
    if unified.starts_with('/') || unified.as_bytes().get(1) == Some(&b':') {
        return Err(("is an absolute path".into(), INSIDE));
    }
    let mut out = PathBuf::new();
    for c in Path::new(&unified).components() {
        match c {
            Component::Normal(part) => out.push(part),
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    return Err(("leaves the assignment's folder".into(), INSIDE));
                }
            }
            Component::RootDir | Component::Prefix(_) => {
                return Err(("is an absolute path".into(), INSIDE))
            }
        }
    }
    if out.extension().is_none_or(|e| e != "ron") {
        return Err((
            "is not a level file (.ron)".into(),
            "list level files, whose names end in .ron",
        ));
    }
    Ok(out)
}

/// Checks `YYYY-MM-DD` is a date of the Gregorian calendar; says what is wrong otherwise.
fn check_date(s: &str) -> Result<(), &'static str> {
    let b = s.as_bytes();
    let digits = |r: std::ops::Range<usize>| b[r].iter().all(u8::is_ascii_digit);
    if b.len() != 10
        || b[4] != b'-'
        || b[7] != b'-'
        || !digits(0..4)
        || !digits(5..7)
        || !digits(8..10)
    {
        return Err("is not written YYYY-MM-DD");
    }
    let n = |r: std::ops::Range<usize>| s[r].parse::<u32>().expect("digits");
    let (year, month, day) = (n(0..4), n(5..7), n(8..10));
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    let days = match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if leap => 29,
        2 => 28,
        _ => return Err("has no month 01 to 12"),
    };
    if day == 0 || day > days {
        return Err("is not a day of that month");
    }
    Ok(())
}

/// Line and column of the `k`-th string of the `levels:` list (its opening quote), else of the
/// key. `code` is `text` with comments and string contents blanked (quotes kept).
fn nth_level_pos(text: &str, code: &str, k: usize) -> (usize, usize) {
    let Some(key) = find_key(code, "levels", 0) else {
        return (1, 1);
    };
    let quotes = code[key..]
        .char_indices()
        .take_while(|&(_, c)| c != ']')
        .filter(|&(_, c)| c == '"')
        .map(|(i, _)| key + i);
    // Quotes come in pairs: the k-th string opens at the 2k-th.
    quotes
        .step_by(2)
        .nth(k)
        .map_or(pos(text, key), |o| pos(text, o))
}

/// 1-based line and column (in characters) of a byte offset.
fn pos(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count()
        + 1;
    (line, col)
}

/// A syntax error (or an unknown or missing field) where ron found it, with how to fix it.
fn syntax_error(file: &Path, e: &ron::error::SpannedError) -> LevelError {
    use ron::error::Error as E;
    let help = match &e.code {
        E::NoSuchStructField { .. } => {
            "remove it: an assignment has title, levels and due (optional)".to_string()
        }
        E::MissingStructField { field, .. } => {
            format!("add `{field}: ...`: Assignment(title: \"...\", levels: [\"a.ron\"], due: \"2026-12-14\")")
        }
        E::DuplicateStructField { .. } => "write each field once".to_string(),
        _ => "an assignment is written Assignment(title: \"...\", levels: [\"a.ron\", \"sub/b.ron\"], due: \"2026-12-14\") (docs/teacher.md)".to_string(),
    };
    LevelError {
        file: file.to_path_buf(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: e.code.to_string(),
        help,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Assignment, LevelError> {
        Assignment::parse(Path::new("hw/assignment.ron"), text)
    }

    #[test]
    fn a_manifest_resolves_its_levels_in_order() {
        let a = parse(
            "Assignment(title: \"Week 3\", levels: [\"b.ron\", \"./sub/a.ron\", \"sub/x/../c.ron\"], due: \"2028-02-29\")",
        )
        .unwrap();
        assert_eq!(a.title, "Week 3");
        assert_eq!(a.due.as_deref(), Some("2028-02-29"));
        let want: Vec<PathBuf> = ["hw/b.ron", "hw/sub/a.ron", "hw/sub/c.ron"]
            .iter()
            .map(PathBuf::from)
            .collect();
        assert_eq!(a.levels, want);
        assert_eq!(a.folder(), Path::new("hw"));
    }

    #[test]
    fn due_is_optional() {
        let a = parse("Assignment(title: \"t\", levels: [\"a.ron\"])").unwrap();
        assert_eq!(a.due, None);
    }

    #[test]
    fn an_unknown_field_is_located_with_the_fields_there_are() {
        let e = parse("Assignment(\n  title: \"t\",\n  levls: [\"a.ron\"],\n)").unwrap_err();
        assert_eq!((e.line, e.col), (3, 3), "{e}");
        assert!(e.to_string().contains("levls"), "{e}");
        assert!(e.help.contains("title, levels and due"), "{e}");
    }

    #[test]
    fn an_empty_list_is_refused_at_its_key() {
        let e = parse("Assignment(\n  title: \"t\",\n  levels: [],\n)").unwrap_err();
        assert_eq!((e.line, e.col), (3, 3), "{e}");
        assert!(e.message.contains("no levels"), "{e}");
    }

    #[test]
    fn a_path_out_of_the_folder_is_refused_at_its_entry() {
        for (entry, why) in [
            ("../x.ron", "leaves"),
            ("a/../../x.ron", "leaves"),
            ("/etc/x.ron", "absolute"),
            ("C:\\\\x.ron", "absolute"),
            ("notes.txt", "not a level file"),
            ("", "empty"),
        ] {
            let text =
                format!("Assignment(title: \"t\", levels: [\n  \"ok.ron\",\n    \"{entry}\",\n])");
            let e = parse(&text).unwrap_err();
            assert_eq!((e.line, e.col), (3, 5), "{entry}: {e}");
            assert!(e.message.contains(why), "{entry}: {e}");
        }
    }

    #[test]
    fn a_level_listed_twice_is_refused() {
        let e = parse("Assignment(title: \"t\", levels: [\"a.ron\", \"./a.ron\"])").unwrap_err();
        assert!(e.message.contains("twice"), "{e}");
        // `Assignment(title: "t", levels: [` is 32 characters, `"a.ron", ` 9 more.
        assert_eq!((e.line, e.col), (1, 42), "{e}");
    }

    #[test]
    fn a_bad_date_says_what_is_wrong() {
        for (due, why) in [
            ("14/12/2026", "YYYY-MM-DD"),
            ("2026-13-01", "month"),
            ("2026-02-29", "day"),
            ("2100-02-29", "day"),
            ("2026-04-31", "day"),
            ("2026-12-00", "day"),
        ] {
            let text = format!("Assignment(title: \"t\", levels: [\"a.ron\"],\n due: \"{due}\")");
            let e = parse(&text).unwrap_err();
            assert_eq!((e.line, e.col), (2, 2), "{due}: {e}");
            assert!(e.message.contains(why), "{due}: {e}");
        }
        // 2000 is a leap year (divisible by 400), 2100 is not (by 100 only).
        assert!(check_date("2000-02-29").is_ok());
    }

    #[test]
    fn a_missing_title_is_asked_for() {
        let e = parse("Assignment(levels: [\"a.ron\"])").unwrap_err();
        assert!(e.to_string().contains("title"), "{e}");
        assert!(e.line > 0, "{e}");
    }

    /// A fresh folder of this test process's own under the system's temporary folder.
    fn temp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("rigidlab-assignment-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn load_takes_the_folder_or_the_file_and_checks_the_levels_exist() {
        let dir = temp("load");
        std::fs::create_dir(dir.as_path().join("sub")).unwrap();
        std::fs::write(dir.as_path().join("sub/a.ron"), "Level()").unwrap();
        let manifest = dir.as_path().join(MANIFEST);
        std::fs::write(
            &manifest,
            "Assignment(title: \"t\", levels: [\"sub/a.ron\"])",
        )
        .unwrap();
        let from_folder = Assignment::load(dir.as_path()).unwrap();
        let from_file = Assignment::load(&manifest).unwrap();
        assert_eq!(from_folder, from_file);
        assert_eq!(from_file.levels, vec![dir.as_path().join("sub/a.ron")]);

        std::fs::write(
            &manifest,
            "Assignment(title: \"t\",\n levels: [\"sub/a.ron\", \"sub/gone.ron\"])",
        )
        .unwrap();
        let e = Assignment::load(dir.as_path()).unwrap_err();
        assert_eq!((e.line, e.col), (2, 24), "{e}");
        assert!(e.message.contains("does not exist"), "{e}");

        let empty = temp("empty");
        let e = Assignment::load(&empty).unwrap_err();
        assert!(e.to_string().contains(MANIFEST), "{e}");
        std::fs::remove_dir_all(dir).unwrap();
        std::fs::remove_dir_all(empty).unwrap();
    }
}
