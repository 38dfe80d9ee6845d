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

/// Finds where an item or one of its fields is written in the source, so that semantic errors
/// (found after parsing) can point at a line.
///
/// Everything is indexed once, in a few passes over the text, so that every question costs a
/// binary search or a walk over one item, whatever the file's size and however it is broken into
/// lines: the top-level keys (`bodies:`, `world:`, ...), the offsets of every `name: "..."` and
/// `id: "..."` value, the line starts, and the UTF-8 continuation bytes (a column counts
/// characters). Before, a column was counted from its line's start and an item's end was searched
/// for to the end of the file, once per field validated: 60,000 bodies written on one line took
/// 24.7 s to validate, and 30,000 questions 11.4 s.
///
/// Structure is looked for in a copy of the text whose comments and string contents are blanked
/// (same byte offsets), so a comment or a string that mentions `bodies: [(name: "bob"` is not
/// taken for the list.
pub struct Locator<'a> {
    /// The text with comments and the contents of strings blanked to spaces (newlines kept).
    code: String,
    line_starts: Vec<usize>,
    /// Offsets of the bytes that continue a multi-byte UTF-8 character, in order.
    continuations: Vec<usize>,
    /// Offsets of the quoted value of every `name:` or `id:` field, by value, in file order.
    items: HashMap<&'a str, Vec<usize>>,
    /// Offsets of the keys of the top level (`Level(...)`'s fields), in file order, and the
    /// first one of each name.
    top_keys: Vec<usize>,
    sections_at: HashMap<&'a str, usize>,
    /// Where each item of a list section begins, by section, found on first use.
    sections: std::cell::RefCell<HashMap<String, Vec<usize>>>,
}

pub(super) fn is_ident(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// Byte offset of `key:` (as a field name, not inside a longer word) in `text[from..]`.
pub(super) fn find_key(text: &str, key: &str, from: usize) -> Option<usize> {
    let mut start = from;
    while let Some(i) = text.get(start..)?.find(key) {
        let at = start + i;
        let before_ok = at == 0 || !is_ident(text.as_bytes()[at - 1]);
        if before_ok && text[at + key.len()..].trim_start().starts_with(':') {
            return Some(at);
        }
        start = at + key.len();
    }
    None
}

/// `text` with its comments (`//` to the end of the line, `/* */` nested as RON nests them) and
/// the contents of its strings and characters (`"..."` with escapes, raw `r#"..."#`, `'c'`)
/// replaced by spaces, newlines kept: the same byte offsets, lines and columns, and only the
/// structure left to search.
pub(crate) fn blank_comments_and_strings(text: &str) -> String {
    let b = text.as_bytes();
    let n = b.len();
    let mut out = b.to_vec();
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for c in &mut out[from.min(n)..to.min(n)] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
    };
    // Walks a quoted run from `open` (the opening quote) to its closing `quote`, past escapes;
    // returns the closing quote's offset (n when unclosed).
    let closing = |open: usize, quote: u8| {
        let mut j = open + 1;
        while j < n && b[j] != quote {
            j += if b[j] == b'\\' { 2 } else { 1 };
        }
        j.min(n)
    };
    let mut i = 0;
    while i < n {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => {
                let end = text[i..].find('\n').map_or(n, |k| i + k);
                blank(&mut out, i, end);
                i = end;
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                let (mut j, mut level) = (i + 2, 1);
                while j < n && level > 0 {
                    if b[j] == b'/' && b.get(j + 1) == Some(&b'*') {
                        level += 1;
                        j += 2;
                    } else if b[j] == b'*' && b.get(j + 1) == Some(&b'/') {
                        level -= 1;
                        j += 2;
                    } else {
                        j += 1;
                    }
                }
                blank(&mut out, i, j);
                i = j;
            }
            q @ (b'"' | b'\'') => {
                let end = closing(i, q);
                blank(&mut out, i + 1, end);
                i = end + 1;
            }
            b'r' if i == 0
                || !is_ident(b[i - 1])
                || (b[i - 1] == b'b' && (i < 2 || !is_ident(b[i - 2]))) =>
            {
                // A raw string r"..." or r#"..."# (or br"..."); else an identifier, r#ident.
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                if b.get(i + 1 + hashes) != Some(&b'"') {
                    i += 1;
                    continue;
                }
                let open = i + 1 + hashes;
                let close = "\"".to_string() + &"#".repeat(hashes);
                let end = text[open + 1..].find(&close).map_or(n, |k| open + 1 + k);
                blank(&mut out, open + 1, end);
                i = end + close.len();
            }
            _ => i += 1,
        }
    }
    String::from_utf8(out).expect("only whole characters are blanked, to ASCII spaces")
}

impl<'a> Locator<'a> {
    pub fn new(text: &'a str) -> Self {
        let code = blank_comments_and_strings(text);
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let continuations = text
            .bytes()
            .enumerate()
            .filter(|&(_, c)| c & 0xc0 == 0x80)
            .map(|(i, _)| i)
            .collect();
        let mut items: HashMap<&str, Vec<usize>> = HashMap::new();
        let mut top_keys = Vec::new();
        let mut sections_at = HashMap::new();
        let b = code.as_bytes();
        let (mut i, mut depth) = (0, 0i64);
        while i < b.len() {
            match b[i] {
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' | b'}' => depth -= 1,
                c if c.is_ascii_alphabetic() || c == b'_' => {
                    let start = i;
                    while i < b.len() && is_ident(b[i]) {
                        i += 1;
                    }
                    let after = code[i..].trim_start();
                    let Some(value) = after.strip_prefix(':') else {
                        continue;
                    };
                    let key = &text[start..i];
                    if depth == 1 {
                        top_keys.push(start);
                        sections_at.entry(key).or_insert(start);
                    }
                    if key == "name" || key == "id" {
                        let value = value.trim_start();
                        let open = code.len() - value.len();
                        if let Some(quoted) = value.strip_prefix('"') {
                            if let Some(len) = quoted.find('"') {
                                items
                                    .entry(&text[open + 1..open + 1 + len])
                                    .or_default()
                                    .push(open);
                            }
                        }
                    }
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
        Locator {
            code,
            line_starts,
            continuations,
            items,
            top_keys,
            sections_at,
            sections: Default::default(),
        }
    }

    fn pos(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.code.len());
        let line = self.line_starts.partition_point(|&s| s <= offset).max(1);
        let start = self.line_starts[line - 1];
        let continued = self.continuations.partition_point(|&c| c < offset)
            - self.continuations.partition_point(|&c| c < start);
        (line, offset - start - continued + 1)
    }

    /// Offset of a top-level key (a section such as `bodies` or `world`).
    fn section_key(&self, section: &str) -> Option<usize> {
        self.sections_at.get(section).copied()
    }

    /// Where a section's value ends: at the next top-level key, or at the end of the text.
    fn section_end(&self, key: usize) -> usize {
        let next = self.top_keys.partition_point(|&k| k <= key);
        self.top_keys.get(next).copied().unwrap_or(self.code.len())
    }

    /// Offset of the `nth` item named `name` after the key of `section` (e.g. "bodies").
    fn item(&self, section: &str, name: &str, nth: usize) -> Option<usize> {
        let from = self.section_key(section).unwrap_or(0);
        let offsets = self.items.get(name)?;
        offsets[offsets.partition_point(|&o| o < from)..]
            .get(nth)
            .copied()
    }

    /// Line and column of a section's key, e.g. `world`.
    pub fn section(&self, section: &str) -> (usize, usize) {
        self.section_key(section).map_or((1, 1), |o| self.pos(o))
    }

    /// Line and column of `field` in `section`'s top level (e.g. world.dt), else of the section.
    pub fn section_field(&self, section: &str, field: &str) -> (usize, usize) {
        match self.section_key(section) {
            Some(s) => {
                let end = self.section_end(s);
                find_key(&self.code[..end], field, s).map_or(self.pos(s), |o| self.pos(o))
            }
            None => (1, 1),
        }
    }

    /// Whether the level writes the top-level key `section` (e.g. `solution`).
    pub fn has_section(&self, section: &str) -> bool {
        self.section_key(section).is_some()
    }

    /// Line and column of the `index`-th string of the top-level list `section` (a level's
    /// `hints[index]`), else of the section's key.
    pub fn nth_string_in_section(&self, section: &str, index: usize) -> (usize, usize) {
        let Some(s) = self.section_key(section) else {
            return (1, 1);
        };
        let end = self.section_end(s);
        // String contents are blanked, their quotes kept: every other quote opens one.
        let opening = self.code[s..end]
            .match_indices('"')
            .map(|(i, _)| s + i)
            .nth(2 * index);
        self.pos(opening.unwrap_or(s))
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

    /// Line and column of `field` inside the item named `name` of `section`: the first `field:`
    /// between the item's opening parenthesis and its closing one.
    pub fn field_pos(&self, section: &str, name: &str, field: &str) -> (usize, usize) {
        let Some(item) = self.item(section, name, 0) else {
            return self.section(section);
        };
        let open = self.code[..item].rfind('(').unwrap_or(item);
        let close = matching_close(&self.code, open);
        let hit = find_key(&self.code[..close], field, open);
        self.pos(hit.unwrap_or(item))
    }

    /// Line and column of the `index`-th `field:` inside the list `list:` of the item named
    /// `name` of `section` (a question's `mistakes[index].value`), else of `list:`, else of the item.
    pub fn list_field_pos(
        &self,
        section: &str,
        name: &str,
        list: &str,
        index: usize,
        field: &str,
    ) -> (usize, usize) {
        let Some(item) = self.item(section, name, 0) else {
            return self.section(section);
        };
        let open = self.code[..item].rfind('(').unwrap_or(item);
        let close = matching_close(&self.code, open);
        let Some(key) = find_key(&self.code[..close], list, open) else {
            return self.pos(item);
        };
        let mut at = key;
        for _ in 0..=index {
            match find_key(&self.code[..close], field, at + 1) {
                Some(hit) => at = hit,
                None => return self.pos(key),
            }
        }
        self.pos(at)
    }

    /// Position of the `index`-th occurrence of `Variant(` after `section:` (for unnamed items).
    /// The section's items are found in one walk, the first time it is asked about, so locating
    /// every item of a long list costs one pass (it walked the list again for every item).
    pub fn nth_in_section(&self, section: &str, index: usize) -> (usize, usize) {
        let Some(s) = self.section_key(section) else {
            return (1, 1);
        };
        let mut cache = self.sections.borrow_mut();
        let starts = cache
            .entry(section.to_string())
            .or_insert_with(|| item_starts(&self.code[s..]));
        match starts.get(index) {
            Some(&st) => self.pos(s + st),
            None => self.pos(s),
        }
    }
}

/// Offset of the bracket that closes the one at `open` (the end of the text if none does).
fn matching_close(code: &str, open: usize) -> usize {
    let mut depth = 0i64;
    for (i, &c) in code.as_bytes().iter().enumerate().skip(open) {
        match c {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => {
                depth -= 1;
                if depth <= 0 {
                    return i;
                }
            }
            _ => {}
        }
    }
    code.len()
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
