//! Text of a variant: an error's place in the file, the `{m}` placeholders of the statement and
//! questions, and numbers rounded as a textbook prints them.

use super::decl::Parameter;

/// An error at a byte offset of the level's text (turned into line and column by the caller).
#[derive(Debug, Clone, PartialEq)]
pub struct Located {
    pub offset: usize,
    pub message: String,
    pub help: String,
}

impl Located {
    pub fn at(offset: usize, message: impl Into<String>, help: impl Into<String>) -> Self {
        Located {
            offset,
            message: message.into(),
            help: help.into(),
        }
    }
}

/// Significant figures a value is printed with (more where the step has more decimals).
pub const SIGNIFICANT: i32 = 3;

/// A value as a textbook prints it: rounded to 3 significant figures, or to the decimals of the
/// parameter's step (or list) when those are more, without trailing zeros: 2.5, 30, 0.125, 1250.
pub fn textbook(v: f64, decimals: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    let for_figures = (SIGNIFICANT - 1 - magnitude).max(0) as usize;
    let d = for_figures.max(decimals).min(15);
    let s = format!("{v:.d$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    // Rounding to figures above the decimal point (12345 -> 12300).
    if for_figures == 0 && decimals == 0 && magnitude >= SIGNIFICANT {
        let unit = 10f64.powi(magnitude + 1 - SIGNIFICANT);
        return format!("{}", (v / unit).round() * unit);
    }
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// `value unit` as the statement prints it: "2.5 kg", "30 deg", "0.2" (no unit).
pub fn with_unit(p: &Parameter, value: f64) -> String {
    let n = textbook(value, p.decimals);
    if p.unit.is_empty() {
        n
    } else {
        format!("{n} {}", p.unit)
    }
}

/// `text` with each `{name}` of a parameter replaced by its value and unit, and `{g}` by the
/// gravity in m/s^2. Other braces are left as written.
pub fn fill(text: &str, params: &[Parameter], values: &[f64], g: f64) -> String {
    if !text.contains('{') {
        return text.to_string();
    }
    let mut out = text.to_string();
    for (p, v) in params.iter().zip(values) {
        out = out.replace(&format!("{{{}}}", p.name), &with_unit(p, *v));
    }
    out.replace("{g}", &format!("{} m/s^2", textbook(g, 2)))
}

/// The `{name}`s of `text` that name no parameter (nor `g`): an identifier in braces.
pub fn unknown_placeholders<'a>(text: &'a str, params: &[Parameter]) -> Vec<(usize, &'a str)> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(i) = text[from..].find('{') {
        let open = from + i;
        from = open + 1;
        let Some(len) = text[open + 1..].find('}') else {
            break;
        };
        let name = &text[open + 1..open + 1 + len];
        let ident = name
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if ident && name != "g" && !params.iter().any(|p| p.name == name) {
            out.push((open, name));
        }
    }
    out
}
