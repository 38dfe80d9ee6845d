//! Located errors for level files: `file:line:col: message` plus how to fix it.

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// An error in a level file, with the position of the offending text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct LevelError {
    pub file: PathBuf,
    /// 1-based line and column (0 when the error has no position, e.g. an unreadable file).
    pub line: usize,
    pub col: usize,
    pub message: String,
    /// How to fix it.
    pub help: String,
}

impl fmt::Display for LevelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, "error")
    }
}

/// Something legal in a level but probably not meant: located and explained like an error, but
/// the level still runs.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelWarning(pub LevelError);

impl fmt::Display for LevelWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.write(f, "warning")
    }
}

impl LevelError {
    fn write(&self, f: &mut fmt::Formatter<'_>, severity: &str) -> fmt::Result {
        if self.line > 0 {
            write!(
                f,
                "{}:{}:{}: {severity}: {}",
                self.file.display(),
                self.line,
                self.col,
                self.message
            )?;
        } else {
            write!(f, "{}: {severity}: {}", self.file.display(), self.message)?;
        }
        if !self.help.is_empty() {
            write!(f, "\n  help: {}", self.help)?;
        }
        Ok(())
    }
}

impl LevelError {
    pub fn new(
        file: &Path,
        (line, col): (usize, usize),
        message: impl Into<String>,
        help: impl Into<String>,
    ) -> Self {
        LevelError {
            file: file.to_path_buf(),
            line,
            col,
            message: message.into(),
            help: help.into(),
        }
    }
}

/// Finds where an item or one of its fields is written in the source, so that
/// semantic errors (found after parsing) can point at a line. Line starts and the
/// offsets of every `name: "..."` / `id: "..."` value are indexed once, so locating
/// stays cheap on levels with thousands of items.
pub struct Locator<'a> {
    text: &'a str,
    line_starts: Vec<usize>,
    /// Offsets of the quoted value of every `name:` or `id:` field, by value, in file order.
    items: HashMap<&'a str, Vec<usize>>,
    /// Where each item of a list section begins, by section, found on first use.
    sections: std::cell::RefCell<HashMap<String, Vec<usize>>>,
}

/// Byte offset of `key:` (as a field name, not inside a longer word) in `text[from..]`.
fn find_key(text: &str, key: &str, from: usize) -> Option<usize> {
    let mut start = from;
    while let Some(i) = text.get(start..)?.find(key) {
        let at = start + i;
        let prev = if at == 0 {
            b' '
        } else {
            text.as_bytes()[at - 1]
        };
        let before_ok = !prev.is_ascii_alphanumeric() && prev != b'_';
        if before_ok && text[at + key.len()..].trim_start().starts_with(':') {
            return Some(at);
        }
        start = at + key.len();
    }
    None
}

impl<'a> Locator<'a> {
    pub fn new(text: &'a str) -> Self {
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let mut items: HashMap<&str, Vec<usize>> = HashMap::new();
        for key in ["name", "id"] {
            let mut from = 0;
            while let Some(k) = find_key(text, key, from) {
                from = k + key.len();
                let after_colon = from + text[from..].find(':').map_or(0, |c| c + 1);
                let value = text[after_colon..].trim_start();
                let start = text.len() - value.len();
                if let Some(end) = value.strip_prefix('"').and_then(|v| v.find('"')) {
                    items
                        .entry(&text[start + 1..start + 1 + end])
                        .or_default()
                        .push(start);
                }
            }
        }
        for offsets in items.values_mut() {
            offsets.sort_unstable();
        }
        Locator {
            text,
            line_starts,
            items,
            sections: Default::default(),
        }
    }

    fn pos(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let line = self.line_starts.partition_point(|&s| s <= offset).max(1);
        let start = self.line_starts[line - 1];
        (line, self.text[start..offset].chars().count() + 1)
    }

    /// Offset of the `nth` item named `name` after the key of `section` (e.g. "bodies").
    fn item(&self, section: &str, name: &str, nth: usize) -> Option<usize> {
        let from = find_key(self.text, section, 0).unwrap_or(0);
        self.items
            .get(name)?
            .iter()
            .copied()
            .filter(|&o| o >= from)
            .nth(nth)
    }

    /// Line and column of a section's key, e.g. `world`.
    pub fn section(&self, section: &str) -> (usize, usize) {
        find_key(self.text, section, 0).map_or((1, 1), |o| self.pos(o))
    }

    /// Line and column of `field` in `section`'s top level (e.g. world.dt), else of the section.
    pub fn section_field(&self, section: &str, field: &str) -> (usize, usize) {
        match find_key(self.text, section, 0) {
            Some(s) => find_key(self.text, field, s).map_or(self.pos(s), |o| self.pos(o)),
            None => (1, 1),
        }
    }

    /// Line and column of the item named `name` in `section`.
    pub fn item_pos(&self, section: &str, name: &str) -> (usize, usize) {
        self.item(section, name, 0)
            .map_or_else(|| self.section(section), |o| self.pos(o))
    }

    /// Line and column of the second item named `name` in `section` (a duplicate).
    pub fn duplicate_pos(&self, section: &str, name: &str) -> (usize, usize) {
        self.item(section, name, 1)
            .map_or_else(|| self.item_pos(section, name), |o| self.pos(o))
    }

    /// Line and column of `field` inside the item named `name` of `section`: the first
    /// `field:` between the item's opening parenthesis and the next item's name.
    pub fn field_pos(&self, section: &str, name: &str, field: &str) -> (usize, usize) {
        let Some(item) = self.item(section, name, 0) else {
            return self.section(section);
        };
        let next_item = find_key(self.text, "name", item + 1).unwrap_or(self.text.len());
        let open = self.text[..item].rfind('(').unwrap_or(item);
        let hit = find_key(&self.text[..next_item], field, open);
        self.pos(hit.unwrap_or(item))
    }

    /// Position of the `index`-th occurrence of `Variant(` after `section:` (for unnamed items).
    /// The section's items are found in one walk, the first time it is asked about, so locating
    /// every item of a long list costs one pass (it walked the list again for every item).
    pub fn nth_in_section(&self, section: &str, index: usize) -> (usize, usize) {
        let Some(s) = find_key(self.text, section, 0) else {
            return (1, 1);
        };
        let mut cache = self.sections.borrow_mut();
        let starts = cache
            .entry(section.to_string())
            .or_insert_with(|| item_starts(&self.text[s..]));
        match starts.get(index) {
            Some(&st) => self.pos(s + st),
            None => self.pos(s),
        }
    }
}

/// Offsets (within `body`, which starts at a section's key) where each top-level item of the
/// section's list begins: its `(` or its variant name.
fn item_starts(body: &str) -> Vec<usize> {
    let mut out = Vec::new();
    let Some(open) = body.find('[') else {
        return out;
    };
    let bytes = body.as_bytes();
    let mut depth = 0i32;
    let mut item_start = None;
    for (i, &b) in bytes.iter().enumerate().skip(open + 1) {
        match b {
            b'(' | b'[' => {
                if depth == 0 && item_start.is_none() {
                    item_start = Some(i);
                }
                depth += 1;
            }
            b')' | b']' => {
                if depth == 0 {
                    break;
                }
                depth -= 1;
            }
            b',' if depth == 0 => {
                if let Some(st) = item_start.take() {
                    out.push(st);
                }
            }
            c if depth == 0 && item_start.is_none() && !c.is_ascii_whitespace() => {
                item_start = Some(i)
            }
            _ => {}
        }
    }
    if let Some(st) = item_start {
        // The item starts at its variant name: back up over identifier characters.
        let ident = body[..st]
            .trim_end_matches(|c: char| c.is_alphanumeric() || c == '_')
            .len();
        out.push(ident.min(st));
    }
    out
}
