//! A level's `parameters: [...]`: reading the section out of the text, checking each
//! declaration (name, range and step or list, unit, nominal) and the values it allows.

use super::super::error::blank_comments_and_strings;
use super::super::format::units::Unit;
use super::expr;
use super::text::Located;
use serde::Deserialize;

/// One parameter as written: `(name: "m", range: (1.0, 5.0), step: 0.5, unit: "kg")` or
/// `(name: "theta", list: [20.0, 30.0, 45.0], unit: "deg")`, with an optional `nominal`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterDef {
    pub name: String,
    #[serde(default)]
    pub range: Option<(f64, f64)>,
    #[serde(default)]
    pub step: Option<f64>,
    #[serde(default)]
    pub list: Option<Vec<f64>>,
    #[serde(default)]
    pub unit: String,
    #[serde(default)]
    pub nominal: Option<f64>,
}

/// The values a parameter may take, in its own unit.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// `min + k step` for k = 0 .. n-1.
    Grid {
        min: f64,
        step: f64,
        n: u64,
    },
    List(Vec<f64>),
}

impl Values {
    /// The number of values (at least one: validation refuses an empty list).
    pub fn count(&self) -> u64 {
        match self {
            Values::Grid { n, .. } => *n,
            Values::List(l) => l.len() as u64,
        }
    }

    /// The `k`-th value (k < len), in the parameter's unit: `min + k * step` in f64 arithmetic
    /// (one product, one sum, each correctly rounded, so any IEEE 754 tool gets the same number).
    pub fn at(&self, k: u64) -> f64 {
        match self {
            Values::Grid { min, step, .. } => min + (k as f64) * step,
            Values::List(l) => l[k as usize],
        }
    }

    /// The indices of the lowest and the highest value.
    pub fn ends(&self) -> (u64, u64) {
        match self {
            Values::Grid { n, .. } => (0, n - 1),
            Values::List(l) => {
                let by = |a: &(usize, &f64), b: &(usize, &f64)| a.1.total_cmp(b.1);
                let lo = l.iter().enumerate().min_by(by).map_or(0, |(i, _)| i);
                let hi = l.iter().enumerate().max_by(by).map_or(0, |(i, _)| i);
                (lo as u64, hi as u64)
            }
        }
    }
}

/// A checked parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    pub name: String,
    pub values: Values,
    /// The unit as written ("" for a pure number) and its size in SI: expressions see
    /// `value * factor` (an angle in `deg` enters them in radians).
    pub unit: String,
    pub factor: f64,
    pub nominal: u64,
    /// Decimals the statement prints at least: those of the step or of the list's values.
    pub decimals: usize,
}

/// The most parameters a level may declare: its 2^k range corners are each validated.
pub const MAX_PARAMETERS: usize = 10;

/// The most values a range may hold (its grid points).
pub const MAX_GRID: u64 = 1_000_000;

/// Where the section is: the offsets of `parameters` (the key) and of the end of its value
/// (past the closing `]` and a comma after it), in `text`.
pub fn find_section(code: &str) -> Option<(usize, usize, usize)> {
    let b = code.as_bytes();
    let (mut i, mut depth) = (0, 0i64);
    while i < b.len() {
        match b[i] {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            c if c.is_ascii_alphabetic() || c == b'_' => {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                let rest = code[i..].trim_start();
                if depth == 1 && &code[start..i] == "parameters" && rest.starts_with(':') {
                    let value = code.len() - rest.len() + 1;
                    let end = value_end(code, value);
                    return Some((start, value, end));
                }
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    None
}

/// The end of the value starting at `from`: past its closing bracket and one comma after it.
fn value_end(code: &str, from: usize) -> usize {
    let b = code.as_bytes();
    let mut depth = 0i64;
    let mut i = from;
    while i < b.len() {
        match b[i] {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => {
                depth -= 1;
                if depth <= 0 {
                    i += 1;
                    break;
                }
            }
            _ => {}
        }
        i += 1;
    }
    let rest = &code[i.min(code.len())..];
    let trimmed = rest.trim_start();
    if trimmed.starts_with(',') {
        code.len() - trimmed.len() + 1
    } else {
        i.min(code.len())
    }
}

/// Reads and checks the declarations written at `text[value..end]`.
pub fn read(text: &str, value: usize, end: usize) -> Result<Vec<Parameter>, Located> {
    let section = text[value..end].trim_end().trim_end_matches(',');
    let defs: Vec<ParameterDef> = super::super::ron_options()
        .from_str(section)
        .map_err(|e| {
            // ron counts from the section's start: back to the file's offsets.
            let off = offset_of(section, e.span.start.line, e.span.start.col);
            Located::at(
                value + off,
                format!("parameters: {}", e.code),
                "write `parameters: [(name: \"m\", range: (1.0, 5.0), step: 0.5, unit: \"kg\"), ...]` (docs/levels.md#parameters)",
            )
        })?;
    if defs.len() > MAX_PARAMETERS {
        return Err(Located::at(
            value,
            format!("{} parameters: at most {MAX_PARAMETERS}", defs.len()),
            "each of the 2^k corners of the ranges is validated: keep the parameters a student's numbers need",
        ));
    }
    let code = blank_comments_and_strings(section);
    let mut out: Vec<Parameter> = Vec::new();
    for d in defs {
        let at = value + name_offset(section, &code, &d.name);
        let p = check(&d).map_err(|(msg, help)| Located::at(at, msg, help))?;
        if out.iter().any(|q| q.name == p.name) {
            return Err(Located::at(
                at,
                format!("parameter `{}` is declared twice", p.name),
                "give each parameter its own name",
            ));
        }
        out.push(p);
    }
    Ok(out)
}

/// The offset in `section` of the `name: "NAME"` of a declaration, for messages.
fn name_offset(section: &str, code: &str, name: &str) -> usize {
    let quoted = format!("\"{name}\"");
    let mut from = 0;
    while let Some(i) = section[from..].find(&quoted) {
        let at = from + i;
        if code[..at].trim_end().ends_with(':') {
            return code[..at].trim_end().trim_end_matches(':').trim_end().len() - "name".len();
        }
        from = at + 1;
    }
    0
}

/// Byte offset of 1-based (line, col) (col in characters) in `text`.
pub fn offset_of(text: &str, line: usize, col: usize) -> usize {
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

type Why = (String, String);

fn check(d: &ParameterDef) -> Result<Parameter, Why> {
    check_name(&d.name)?;
    let name = &d.name;
    let factor = if d.unit.trim().is_empty() {
        1.0
    } else {
        Unit::parse(&d.unit)
            .map_err(|e| {
                (
                    format!("parameter `{name}`: {e}"),
                    "give a unit from docs/levels.md#the-unit-of-a-question (kg, m, deg, N, ...) or none".to_string(),
                )
            })?
            .factor
    };
    let (values, decimals) = match (&d.range, &d.step, &d.list) {
        (Some(r), Some(step), None) => (grid(name, *r, *step)?, decimals_of(&[*step, r.0])),
        (None, None, Some(list)) => (list_of(name, list)?, decimals_of(list)),
        (Some(_), None, None) => {
            return Err((
                format!("parameter `{name}` has a range but no step"),
                "add `step: ...`: a student's value is one of min, min + step, ... up to max"
                    .into(),
            ))
        }
        _ => {
            return Err((
                format!("parameter `{name}` needs either `range` with `step`, or `list`"),
                "write `range: (1.0, 5.0), step: 0.5` or `list: [20.0, 30.0, 45.0]`".into(),
            ))
        }
    };
    let nominal = nominal_index(name, &values, d.nominal)?;
    Ok(Parameter {
        name: name.clone(),
        values,
        unit: d.unit.trim().to_string(),
        factor,
        nominal,
        decimals,
    })
}

/// A name expressions can use: ASCII letters, digits and `_`, not starting with a digit, and
/// not `g`, `pi` or a function's name.
fn check_name(name: &str) -> Result<(), Why> {
    let ok = name
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && name.len() <= 32;
    if !ok {
        return Err((
            format!("parameter name `{name}`: use letters, digits and `_` (at most 32), starting with a letter"),
            "e.g. `m`, `theta`, `m_A`".into(),
        ));
    }
    if name == "g" || name == "pi" || expr::is_function(name) {
        return Err((
            format!("parameter name `{name}` is taken: `g` is the level's gravity, `pi` is pi, and functions (sin, sqrt, ...) keep their names"),
            "choose another name".into(),
        ));
    }
    Ok(())
}

fn grid(name: &str, (min, max): (f64, f64), step: f64) -> Result<Values, Why> {
    let finite = min.is_finite() && max.is_finite() && step.is_finite();
    if !finite || step <= 0.0 || max < min {
        return Err((
            format!("parameter `{name}`: range ({min}, {max}) with step {step}"),
            "the range is (min, max) with min <= max, the step a positive number".into(),
        ));
    }
    // Grid points up to max, allowing for the rounding of (max - min) / step (1e-9 of a step).
    let steps = ((max - min) / step + 1e-9).floor();
    if steps + 1.0 > MAX_GRID as f64 {
        return Err((
            format!("parameter `{name}`: {} values in the range", steps + 1.0),
            format!("at most {MAX_GRID}: a larger step"),
        ));
    }
    Ok(Values::Grid {
        min,
        step,
        n: steps as u64 + 1,
    })
}

fn list_of(name: &str, list: &[f64]) -> Result<Values, Why> {
    if list.is_empty() || list.iter().any(|v| !v.is_finite()) {
        return Err((
            format!("parameter `{name}`: the list needs at least one value, all finite"),
            "e.g. `list: [20.0, 30.0, 45.0]`".into(),
        ));
    }
    Ok(Values::List(list.to_vec()))
}

/// The nominal value's index: the one written (it must be one of the values), else the grid
/// point at or just below the range's middle, or the list's first value.
fn nominal_index(name: &str, values: &Values, nominal: Option<f64>) -> Result<u64, Why> {
    let Some(v) = nominal else {
        return Ok(match values {
            Values::Grid { n, .. } => (n - 1) / 2,
            Values::List(_) => 0,
        });
    };
    let close = |k: u64| {
        let x = values.at(k);
        (x - v).abs() <= 1e-9 * x.abs().max(v.abs()).max(1e-300)
    };
    let found = match values {
        Values::Grid { min, step, n } => {
            let k = ((v - min) / step).round();
            (k >= 0.0 && k < *n as f64 && close(k as u64)).then_some(k as u64)
        }
        Values::List(l) => (0..l.len() as u64).find(|&k| close(k)),
    };
    found.ok_or_else(|| {
        (
            format!("parameter `{name}`: nominal {v} is not one of its values"),
            "give a value on the step grid (min + k step) or in the list, or leave `nominal` out"
                .into(),
        )
    })
}

/// Decimals written in the shortest form of these numbers (0.25 -> 2, 5.0 -> 0, 1e-3 -> 3).
fn decimals_of(values: &[f64]) -> usize {
    values
        .iter()
        .map(|v| {
            let s = format!("{}", v.abs());
            s.split_once('.').map_or(0, |(_, d)| d.len())
        })
        .max()
        .unwrap_or(0)
        .min(12)
}
