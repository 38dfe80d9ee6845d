//! Located errors for level files: `file:line:col: message` plus how to fix it.

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
        if self.line > 0 {
            write!(
                f,
                "{}:{}:{}: error: {}",
                self.file.display(),
                self.line,
                self.col,
                self.message
            )?;
        } else {
            write!(f, "{}: error: {}", self.file.display(), self.message)?;
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
/// semantic errors (found after parsing) can point at a line.
pub struct Locator<'a> {
    text: &'a str,
}

impl<'a> Locator<'a> {
    pub fn new(text: &'a str) -> Self {
        Locator { text }
    }

    fn pos(&self, offset: usize) -> (usize, usize) {
        let before = &self.text[..offset.min(self.text.len())];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    }

    /// Byte offset of `key:` (as a field name, not inside a longer word) at or after `from`.
    fn find_key(&self, key: &str, from: usize) -> Option<usize> {
        let mut start = from;
        while let Some(i) = self.text[start..].find(key) {
            let at = start + i;
            let before_ok = at == 0
                || !self.text.as_bytes()[at - 1].is_ascii_alphanumeric()
                    && self.text.as_bytes()[at - 1] != b'_';
            let rest = self.text[at + key.len()..].trim_start();
            if before_ok && rest.starts_with(':') {
                return Some(at);
            }
            start = at + key.len();
        }
        None
    }

    /// Offset of the item named `name` inside the section `section` (e.g. "bodies").
    fn item(&self, section: &str, name: &str) -> Option<usize> {
        let from = self.find_key(section, 0).unwrap_or(0);
        let quoted = format!("\"{name}\"");
        let mut start = from;
        while let Some(i) = self.text[start..].find(&quoted) {
            let at = start + i;
            // Prefer the occurrence that is the item's `name:` / `id:` field.
            let head = self.text[..at].trim_end();
            if head.ends_with(':') {
                let key_end = head.len() - 1;
                let key_start = head[..key_end]
                    .trim_end()
                    .rfind(|c: char| !c.is_alphanumeric() && c != '_')
                    .map_or(0, |k| k + 1);
                let key = head[key_start..key_end].trim();
                if key == "name" || key == "id" {
                    return Some(at);
                }
            }
            start = at + quoted.len();
        }
        None
    }

    /// Line and column of a section's key, e.g. `world`.
    pub fn section(&self, section: &str) -> (usize, usize) {
        self.find_key(section, 0).map_or((1, 1), |o| self.pos(o))
    }

    /// Line and column of `field` in `section`'s top level (e.g. world.dt), else of the section.
    pub fn section_field(&self, section: &str, field: &str) -> (usize, usize) {
        match self.find_key(section, 0) {
            Some(s) => self.find_key(field, s).map_or(self.pos(s), |o| self.pos(o)),
            None => (1, 1),
        }
    }

    /// Line and column of the item named `name` in `section`.
    pub fn item_pos(&self, section: &str, name: &str) -> (usize, usize) {
        self.item(section, name)
            .map_or_else(|| self.section(section), |o| self.pos(o))
    }

    /// Line and column of `field` inside the item named `name` of `section`
    /// (the first `field:` after the item's name and before the next item's name).
    pub fn field_pos(&self, section: &str, name: &str, field: &str) -> (usize, usize) {
        let Some(item) = self.item(section, name) else {
            return self.section(section);
        };
        let next_item = self.find_key("name", item + 1).unwrap_or(self.text.len());
        // Fields may also precede `name:` within the item; look back to the opening paren.
        let open = self.text[..item].rfind('(').unwrap_or(item);
        let hit = self.find_key(field, open).filter(|&o| o < next_item);
        self.pos(hit.unwrap_or(item))
    }

    /// Position of the `index`-th occurrence of `Variant(` after `section:` (for unnamed items).
    pub fn nth_in_section(&self, section: &str, index: usize) -> (usize, usize) {
        let Some(s) = self.find_key(section, 0) else {
            return (1, 1);
        };
        let body = &self.text[s..];
        let Some(open) = body.find('[') else {
            return self.pos(s);
        };
        // Walk the list counting top-level items.
        let bytes = body.as_bytes();
        let mut depth = 0i32;
        let mut count = 0usize;
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
                        if count == index {
                            return self.pos(s + st);
                        }
                        count += 1;
                    }
                }
                c if depth == 0 && item_start.is_none() && !c.is_ascii_whitespace() => {
                    item_start = Some(i)
                }
                _ => {}
            }
        }
        match item_start {
            Some(st) if count == index => {
                // The item starts at its variant name: back up over identifier characters.
                let ident = body[..st]
                    .trim_end_matches(|c: char| c.is_alphanumeric() || c == '_')
                    .len();
                self.pos(s + ident.min(st))
            }
            _ => self.pos(s),
        }
    }
}
