//! Text bound for a terminal: control characters escaped. A level's names (its file's, its
//! bodies', its questions' ids and units) reach stdout and stderr, and an escape sequence in one
//! (`"\u{1b}]0;title\u{7}"`, `"\u{1b}[2J"`) would drive the terminal: retitle it, clear it,
//! hide a line behind a carriage return. Here each such character is written as Rust writes it
//! (`\u{1b}`), visible and harmless. The JSON report is left exact (serde escapes what JSON must).
//!
//! Imports nothing of rigidlab: the `stderr!` macro and the report's table both use it.

use std::borrow::Cow;

/// Whether `c` is escaped: C0 and C1 controls and DEL, and the bidirectional overrides that
/// reorder what a terminal shows (U+202A-U+202E, U+2066-U+2069); newline and tab too unless
/// `lines` keeps them.
fn escaped(c: char, lines: bool) -> bool {
    let kept = lines && (c == '\n' || c == '\t');
    (c.is_control() && !kept) || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

fn escape(s: &str, lines: bool) -> Cow<'_, str> {
    if !s.chars().any(|c| escaped(c, lines)) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if escaped(c, lines) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// Text of several lines for a terminal: every control character escaped but newline and tab.
pub fn text(s: &str) -> Cow<'_, str> {
    escape(s, true)
}

/// One field of a line (a name, an id, a unit): every control character escaped, newline and
/// tab too, so a name cannot start a line of its own in a table.
pub fn field(s: &str) -> Cow<'_, str> {
    escape(s, false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_are_escaped_and_the_rest_kept() {
        assert_eq!(text("plain é ü\nline\ttab"), "plain é ü\nline\ttab");
        assert_eq!(text("a\u{1b}[2Jb\r"), "a\\u{1b}[2Jb\\u{d}");
        assert_eq!(field("a\nb\u{9b}c\u{202e}"), "a\\u{a}b\\u{9b}c\\u{202e}");
    }
}
