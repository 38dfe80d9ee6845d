//! Writing one variant of a parameterized level: every numeric value written as an expression
//! of the parameters (`2*m`, `L/2`, `sqrt(2*g*h)`) is replaced by its number, so the level
//! format itself (and serde) sees only numbers.
//!
//! The text is scanned for value slots: what follows a `:`, `(`, `[` or `,` up to the `,`, `)`
//! or `]` that ends it. A slot is an expression when it holds only numbers, names, `+ - * / ^`
//! and parentheses, and either a name of a parameter, `g` or `pi` or an operator between two
//! operands; a plain number is left as written. A bare word that names nothing (`dynamic`,
//! `Time(...)`, `y`) is a word of the format and is left alone; an expression with an unknown
//! name in it is an error. The replacement is padded to the expression's length where it is
//! shorter, so positions after it do not move; [`OffsetMap`] maps the others back.

use super::expr;
use super::text::Located;

/// What the expressions of a variant may name, each in SI (angles in radians).
pub struct Env<'a> {
    pub names: &'a [String],
    pub values: &'a [f64],
    pub g: f64,
}

impl Env<'_> {
    fn value(&self, name: &str) -> Option<f64> {
        match name {
            "g" => Some(self.g),
            "pi" => Some(std::f64::consts::PI),
            _ => self
                .names
                .iter()
                .position(|n| n == name)
                .map(|i| self.values[i]),
        }
    }

    fn knows(&self, name: &str) -> bool {
        self.value(name).is_some()
    }
}

/// Substitutions made: (original start, original end, new start, new end), in order.
#[derive(Debug, Default, Clone)]
pub struct OffsetMap(Vec<(usize, usize, usize, usize)>);

impl OffsetMap {
    /// The offset in the original text of `off` in the expanded one: inside a replaced number,
    /// the expression's start.
    pub fn to_original(&self, off: usize) -> usize {
        let i = self.0.partition_point(|e| e.2 <= off);
        match i.checked_sub(1).map(|i| self.0[i]) {
            None => off,
            Some((os, _, _, ne)) if off < ne => os,
            Some((_, oe, _, ne)) => oe + (off - ne),
        }
    }

    /// The original expression at an expanded offset, if one was replaced there.
    pub fn replaced_at(&self, off: usize) -> Option<(usize, usize)> {
        let i = self.0.partition_point(|e| e.2 <= off);
        let (os, oe, _, ne) = self.0.get(i.checked_sub(1)?)?;
        (off < *ne).then_some((*os, *oe))
    }
}

/// How a slot reads.
#[derive(Debug, PartialEq)]
enum Slot {
    /// Not an expression (a word of the format, a struct, a string...): left alone.
    Other,
    /// A number as RON reads it: left alone.
    Plain,
    /// An expression to evaluate.
    Expr,
    /// An expression naming something unknown (the name's offset in the slot).
    Unknown(usize, String),
}

/// `text` with its expressions replaced by their values; `code` is `text` with comments and
/// strings blanked (and the parameters' section blanked), same offsets.
pub fn expand(text: &str, code: &str, env: &Env) -> Result<(String, OffsetMap), Located> {
    let b = code.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut map = OffsetMap::default();
    let (mut copied, mut i) = (0, 0);
    while i < b.len() {
        if !matches!(b[i], b':' | b'(' | b'[' | b',') {
            i += 1;
            continue;
        }
        let start = i + 1 + (code[i + 1..].len() - code[i + 1..].trim_start().len());
        let end = slot_end(code, start);
        let slot = code[start..end].trim_end();
        let slot_end = start + slot.len();
        match classify(slot, env) {
            Slot::Other | Slot::Plain => {
                i += 1;
                continue;
            }
            Slot::Unknown(at, name) => {
                return Err(Located::at(
                    start + at,
                    format!("unknown name `{name}` in `{slot}`"),
                    format!(
                        "the expressions of this level may name its parameters ({}), g and pi",
                        env.names.join(", ")
                    ),
                ));
            }
            Slot::Expr => {}
        }
        let v = expr::eval(slot, |n| env.value(n)).map_err(|e| {
            Located::at(
                start,
                format!("cannot evaluate `{slot}`: {e}"),
                "write numbers, parameter names, + - * / ^, parentheses and functions such as sqrt(...), sin(...) (docs/levels.md#parameters)",
            )
        })?;
        if !v.is_finite() {
            return Err(Located::at(
                start,
                format!("`{slot}` is {v} (a division by zero, or a value too large)"),
                "change the expression or the parameters' ranges so that it stays finite",
            ));
        }
        out.push_str(&text[copied..start]);
        let number = format!("{v:?}");
        let new_start = out.len();
        out.push_str(&number);
        // Keep the expression's line breaks, and pad to its length.
        let newlines = text[start..slot_end].matches('\n').count();
        out.push_str(&"\n".repeat(newlines));
        let pad = (slot_end - start).saturating_sub(number.len() + newlines);
        out.push_str(&" ".repeat(pad));
        map.0.push((start, slot_end, new_start, out.len()));
        copied = slot_end;
        i = slot_end;
    }
    out.push_str(&text[copied..]);
    Ok((out, map))
}

/// Where the slot starting at `start` ends: the first `,`, `)` or `]` outside its own brackets.
fn slot_end(code: &str, start: usize) -> usize {
    let mut depth = 0i64;
    for (k, &c) in code.as_bytes()[start..].iter().enumerate() {
        match c {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' if depth == 0 => return start + k,
            b')' | b']' | b'}' => depth -= 1,
            b',' if depth == 0 => return start + k,
            _ => {}
        }
    }
    code.len()
}

/// Reads a slot's tokens to tell an expression from the rest (see the module's doc).
fn classify(slot: &str, env: &Env) -> Slot {
    if slot.is_empty() || slot.parse::<f64>().is_ok() {
        return Slot::Plain;
    }
    let b = slot.as_bytes();
    let (mut i, mut operators, mut names, mut operands) = (0, 0, 0, 0);
    let mut unknown = None;
    let mut last_operand = false;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == b'.' {
            i = number_end(b, i);
            operands += 1;
            last_operand = true;
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let s = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            let word = &slot[s..i];
            let call = slot[i..].trim_start().starts_with('(');
            if call && expr::is_function(word) {
                names += 1;
            } else if !call && env.knows(word) {
                names += 1;
                operands += 1;
            } else if call {
                return Slot::Other; // `Time(...)`, `Box(...)`: a word of the format.
            } else {
                unknown.get_or_insert((s, word.to_string()));
                operands += 1;
            }
            last_operand = !call;
        } else if matches!(c, b'+' | b'-' | b'*' | b'/' | b'^') {
            if last_operand {
                operators += 1;
            }
            last_operand = false;
            i += 1;
        } else if c == b'(' || c == b')' {
            last_operand = c == b')';
            i += 1;
        } else {
            return Slot::Other; // `:`, `,`, `"`, `[`: a struct, a tuple, a string...
        }
    }
    let is_expr = names > 0 || (operators > 0 && operands > 1);
    match unknown {
        // A bare unknown word alone is a word of the format (`dynamic`, `y`).
        Some(_) if names == 0 && operators == 0 => Slot::Other,
        Some((at, name)) if is_expr || operators > 0 => Slot::Unknown(at, name),
        _ if is_expr => Slot::Expr,
        _ => Slot::Other,
    }
}

/// The end of a number starting at `i`: digits, `.`, `_` and an exponent `e-3`.
fn number_end(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.' || b[i] == b'_') {
        i += 1;
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        if j < b.len() && b[j].is_ascii_digit() {
            i = j;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
        }
    }
    i
}
