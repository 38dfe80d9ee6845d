//! The written form of a question's quantity, for a syntax error inside one.
//!
//! ron names what it expected at the error ("Expected identifier"), not what the quantity
//! needs: a new user wrote `PolarAngle("puck")` as `Speed("puck")` is written, and the error
//! gave no hint that it takes `(body:, about:)` (issue 41). The form comes from the format
//! itself: a quantity with named fields, parsed with a field it does not have, lists its
//! fields (serde's unknown-field error), so no list here can fall out of step with
//! `format/exercise.rs`.

use super::error::{blank_comments_and_strings, find_key, is_ident};
use super::format::Quantity;

/// The keys whose value is a quantity: a question's `quantity`, an event's `of`.
const QUANTITY_KEYS: [&str; 2] = ["quantity", "of"];

/// For a syntax error at byte `at` of `text` inside the value of a `quantity:` (or an event's
/// `of:`) that names a quantity with named fields: how that quantity is written, e.g.
/// "`PolarAngle` is written `PolarAngle(body: .., about: ..)`". None elsewhere.
pub fn hint(text: &str, at: usize) -> Option<String> {
    let code = blank_comments_and_strings(text);
    let at = at.min(code.len());
    let key = QUANTITY_KEYS
        .iter()
        .filter_map(|k| last_key_before(&code, k, at).map(|o| o + k.len()))
        .max()?;
    // The value: past the colon and the blanks, the variant's name.
    let value = key + code[key..].find(':')? + 1;
    let name_at = value + (code[value..].len() - code[value..].trim_start().len());
    let name_len = code[name_at..].bytes().take_while(|b| is_ident(*b)).count();
    let name = &code[name_at..name_at + name_len];
    if name.is_empty() || !still_inside(&code[name_at + name_len..at.max(name_at + name_len)]) {
        return None;
    }
    form(name).map(|f| format!("`{name}` is written `{f}` (docs/levels.md, \"Questions\")"))
}

/// The last `key:` that starts before `at`.
fn last_key_before(code: &str, key: &str, at: usize) -> Option<usize> {
    let mut found = None;
    let mut from = 0;
    while let Some(o) = find_key(code, key, from) {
        if o >= at {
            break;
        }
        found = Some(o);
        from = o + key.len();
    }
    found
}

/// Whether text after a value's name has not yet closed that value (no bracket closed below
/// its level, no comma at its level).
fn still_inside(after_name: &str) -> bool {
    let mut depth = 0i64;
    for b in after_name.bytes() {
        match b {
            b'(' | b'[' => depth += 1,
            b')' | b']' => {
                depth -= 1;
                if depth <= 0 {
                    return false;
                }
            }
            b',' if depth == 0 => return false,
            _ => {}
        }
    }
    true
}

/// `Name(field: .., ...)` for a quantity with named fields; None for the others and for a name
/// that is no quantity.
fn form(name: &str) -> Option<String> {
    let probe = format!("{name}(rigidlab_no_such_field: 0)");
    match super::ron_options().from_str::<Quantity>(&probe) {
        Err(e) => match e.code {
            ron::error::Error::NoSuchStructField { expected, .. } => Some(format!(
                "{name}({})",
                expected
                    .iter()
                    .map(|f| format!("{f}: .."))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
            _ => None,
        },
        Ok(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_named_quantity_gets_its_form_and_a_positional_one_none() {
        let text = "questions: [(id: \"a\", quantity: PolarAngle(\"puck\"), at: End)]";
        let at = text.find("\"puck\"").unwrap();
        let h = hint(text, at).expect("a hint");
        assert!(h.contains("PolarAngle(body: .., about: ..)"), "{h}");
        // Speed takes its body by position: no named form to give.
        let text = "questions: [(id: \"a\", quantity: Speed(body: \"puck\"), at: End)]";
        assert_eq!(hint(text, text.find("body").unwrap()), None);
        // Past the quantity's value, in the question's `at`: none.
        let text = "questions: [(id: \"a\", quantity: PolarAngle(body: \"p\", about: (0.0, 0.0)), at: Time(x))]";
        assert_eq!(hint(text, text.find("x))").unwrap()), None);
    }
}
