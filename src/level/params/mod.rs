//! Parameterized levels: `parameters: [...]` declares a level's givens (a range on a step grid,
//! or a list, with a unit), and any numeric field, expected answer or tolerance may be an
//! expression of them and of `g` (docs/levels.md#parameters).
//!
//! A variant is one value per parameter. It is made by writing the level's text with every
//! expression replaced by its number (`params::expand`), then parsing and validating that text as any
//! level, so the level format, serde and validation see only numbers and a level without
//! parameters is read exactly as before. Errors point back at the original text. A level is
//! valid when its nominal variant and every corner of its ranges (each parameter at its lowest
//! and its highest value) are.

mod challenge;
mod decl;
mod expand;
pub mod expr;
mod overlap;
pub mod seed;
mod text;

pub use challenge::Control;
pub use decl::{Parameter, Values, MAX_PARAMETERS};
pub use text::textbook;

use super::error::{blank_comments_and_strings, LevelError, LevelWarning};
use super::format::Level;
use decl::offset_of;
use expand::{Env, OffsetMap};
use std::path::Path;
use text::Located;

/// Which variant of a level to make.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Pick {
    /// The nominal values (each parameter's `nominal`, else its middle grid point or first
    /// list value).
    #[default]
    Nominal,
    /// The variant of a student id (see [`seed`]).
    Student(String),
    /// Given value indices, one per parameter.
    Indices(Vec<u64>),
}

/// The values of one variant, for messages and reports.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// (name, value in its unit, unit), in the order declared.
    pub values: Vec<(String, f64, String)>,
    /// As the statement prints them: "m = 2.5 kg, theta = 30 deg".
    pub shown: String,
}

/// A level with parameters, read once, from which variants are made.
pub struct Parameterized {
    pub params: Vec<Parameter>,
    file_name: String,
    /// The level's text, and the same with comments, strings and the parameters' section
    /// blanked (same offsets): the section is not part of the level format.
    text: String,
    code: String,
    /// The text with the section blanked, what ron reads.
    body: String,
}

/// One variant's level and the text it was read from.
pub struct Made {
    pub level: Level,
    pub variant: Variant,
    expanded: String,
    map: OffsetMap,
}

/// The default gravity's magnitude, m/s^2 (`World::gravity`'s default).
const DEFAULT_G: f64 = 9.81;

impl Parameterized {
    /// The level's parameters, or None for a level without a `parameters:` section.
    pub fn read(path: &Path, text: &str) -> Result<Option<Parameterized>, LevelError> {
        let code = blank_comments_and_strings(text);
        let Some((key, value, end)) = decl::find_section(&code) else {
            return Ok(None);
        };
        let params = decl::read(text, value, end).map_err(|e| locate(path, text, e))?;
        // Multi-byte characters in the section become one space each: pad them back to their
        // byte length so every later offset stays put.
        let pad = |s: &str| -> String {
            let mut out = s[..key].to_string();
            for c in s[key..end].chars() {
                let fill = if c == '\n' { "\n" } else { " " };
                out.push_str(fill);
                out.push_str(&" ".repeat(c.len_utf8() - 1));
            }
            out.push_str(&s[end..]);
            out
        };
        Ok(Some(Parameterized {
            params,
            file_name: path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            body: pad(text),
            code: pad(&code),
            text: text.to_string(),
        }))
    }

    /// The value indices of a pick.
    pub fn indices(&self, pick: &Pick) -> Vec<u64> {
        match pick {
            Pick::Nominal => self.params.iter().map(|p| p.nominal).collect(),
            Pick::Student(id) => self.student_indices(id),
            Pick::Indices(i) => i.clone(),
        }
    }

    /// Student `id`'s value indices: the seeded draw, drawn again while a typical mistake equals
    /// its answer at the draw (`seed`'s step 4). Such a variant does not validate, and every
    /// answer of the student whose pick landed there was ungradable ("student X's variant
    /// cannot be made"); `verify` finds such variants only where its sample hits one.
    fn student_indices(&self, id: &str) -> Vec<u64> {
        let mut draws = seed::student_draws(&self.file_name, id, &self.params);
        let first = draws.next().unwrap_or_default();
        std::iter::once(first.clone())
            .chain(draws)
            .take(seed::MAX_DRAWS)
            .find(|idx| !self.mistake_is_answer(idx))
            .unwrap_or(first)
    }

    /// Whether at the values `idx` a question's typical mistake is within the student tolerance
    /// of its expected answer (false where the variant does not read: its own error shows
    /// where it is made).
    fn mistake_is_answer(&self, idx: &[u64]) -> bool {
        let values: Vec<f64> = self.variant(idx).values.iter().map(|v| v.1).collect();
        let path = Path::new(&self.file_name);
        self.read_with_g(path, &self.si(&values))
            .is_ok_and(|((level, ..), _)| {
                level
                    .questions
                    .iter()
                    .any(super::validate::mistake_is_answer)
            })
    }

    /// Every corner of the ranges: each parameter at its lowest or its highest value (a
    /// parameter of one value has one corner), in a fixed order.
    pub fn corners(&self) -> Vec<Vec<u64>> {
        let mut out: Vec<Vec<u64>> = vec![Vec::new()];
        for p in &self.params {
            let (lo, hi) = p.values.ends();
            let ends: &[u64] = if lo == hi { &[lo][..] } else { &[lo, hi][..] };
            out = out
                .into_iter()
                .flat_map(|c| {
                    ends.iter().map(move |&e| {
                        let mut c = c.clone();
                        c.push(e);
                        c
                    })
                })
                .collect();
        }
        out
    }

    /// The variant of these value indices: its values as shown.
    pub fn variant(&self, idx: &[u64]) -> Variant {
        let values: Vec<(String, f64, String)> = self
            .params
            .iter()
            .zip(idx)
            .map(|(p, &k)| (p.name.clone(), p.values.at(k), p.unit.clone()))
            .collect();
        let shown = self.shown(&values);
        Variant { values, shown }
    }

    /// The values as shown: "m = 2.5 kg, theta = 30 deg".
    fn shown(&self, values: &[(String, f64, String)]) -> String {
        self.params
            .iter()
            .zip(values)
            .map(|(p, (n, v, _))| format!("{n} = {}", text::with_unit(p, *v)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Makes, parses and validates one variant; an error names its values.
    pub fn make(&self, path: &Path, idx: &[u64]) -> Result<Made, LevelError> {
        self.make_set(path, idx, None)
    }

    /// [`Parameterized::make`] with one parameter set to a value of its own (in its unit, any
    /// number: a challenge's control as the student sets it, `params::challenge`).
    pub fn make_set(
        &self,
        path: &Path,
        idx: &[u64],
        set: Option<(usize, f64)>,
    ) -> Result<Made, LevelError> {
        let fits = idx.len() == self.params.len()
            && self
                .params
                .iter()
                .zip(idx)
                .all(|(p, &k)| k < p.values.count());
        if !fits {
            return Err(LevelError::new(
                path,
                (0, 0),
                format!(
                    "no variant {idx:?}: the level has {} parameters",
                    self.params.len()
                ),
                "give one value index per parameter, each below its number of values",
            ));
        }
        let mut variant = self.variant(idx);
        if let Some((k, v)) = set.filter(|(k, _)| *k < self.params.len()) {
            variant.values[k].1 = v;
            variant.shown = self.shown(&variant.values);
        }
        let own: Vec<f64> = variant.values.iter().map(|v| v.1).collect();
        let with = |e: LevelError| LevelError {
            message: format!("{} [variant: {}]", e.message, variant.shown),
            ..e
        };
        let ((mut level, expanded, map), g) =
            self.read_with_g(path, &self.si(&own)).map_err(with)?;
        self.fill_texts(path, &mut level, &own, g)?;
        super::validate::validate(path, &expanded, &level)
            .map_err(|e| self.remap(&expanded, &map, e))
            .map_err(with)?;
        Ok(Made {
            level,
            variant,
            expanded,
            map,
        })
    }

    /// Values in the parameters' units, in SI (degrees to radians).
    fn si(&self, own: &[f64]) -> Vec<f64> {
        self.params
            .iter()
            .zip(own)
            .map(|(p, v)| v * p.factor)
            .collect()
    }

    /// The variant of SI values `si`, expanded and parsed (not validated), and the g it was
    /// read with: the level's gravity, so read with the default, then again with its own.
    fn read_with_g(
        &self,
        path: &Path,
        si: &[f64],
    ) -> Result<((Level, String, OffsetMap), f64), LevelError> {
        let names: Vec<String> = self.params.iter().map(|p| p.name.clone()).collect();
        let mut g = DEFAULT_G;
        let mut made = self.once(path, &names, si, g)?;
        if let Some((gx, gy)) = made.0.world.gravity {
            let own_g = gx.hypot(gy);
            if own_g != g && own_g.is_finite() {
                g = own_g;
                made = self.once(path, &names, si, g)?;
            }
        }
        Ok((made, g))
    }

    /// The level text of one variant, parsed (not validated).
    fn once(
        &self,
        path: &Path,
        names: &[String],
        si: &[f64],
        g: f64,
    ) -> Result<(Level, String, OffsetMap), LevelError> {
        let env = Env {
            names,
            values: si,
            g,
        };
        let (expanded, map) = expand::expand(&self.body, &self.code, &env)
            .map_err(|e| locate(path, &self.text, e))?;
        let level: Level = super::ron_options()
            .from_str(&expanded)
            .map_err(|e| super::syntax_error(path, &expanded, &e))
            .map_err(|e| self.remap(&expanded, &map, e))?;
        Ok((level, expanded, map))
    }

    /// The statement's, the hints', the solution's and the questions' `{name}` placeholders
    /// filled with the variant's values; a placeholder naming no parameter is an error at it.
    fn fill_texts(
        &self,
        path: &Path,
        level: &mut Level,
        own: &[f64],
        g: f64,
    ) -> Result<(), LevelError> {
        let texts = std::iter::once(&level.statement)
            .chain(level.hints.iter())
            .chain(std::iter::once(&level.solution))
            .chain(level.questions.iter().map(|q| &q.ask));
        for t in texts {
            if let Some((_, name)) = text::unknown_placeholders(t, &self.params).first() {
                let at = self.text.find(&format!("{{{name}}}")).unwrap_or(0);
                return Err(locate(
                    path,
                    &self.text,
                    Located::at(
                        at,
                        format!("`{{{name}}}` names no parameter"),
                        "declare it in `parameters`, or write the number itself",
                    ),
                ));
            }
        }
        level.statement = text::fill(&level.statement, &self.params, own, g);
        for h in &mut level.hints {
            *h = text::fill(h, &self.params, own, g);
        }
        level.solution = text::fill(&level.solution, &self.params, own, g);
        for q in &mut level.questions {
            q.ask = text::fill(&q.ask, &self.params, own, g);
        }
        Ok(())
    }

    /// An error found in the expanded text, moved to the original's line and column.
    fn remap(&self, expanded: &str, map: &OffsetMap, e: LevelError) -> LevelError {
        if e.line == 0 {
            return e;
        }
        let off = offset_of(expanded, e.line, e.col);
        let help = match map.replaced_at(off) {
            Some((s, end)) if is_word(&self.text[s..end]) => format!(
                "{} (`{}` here is read as the parameter's number: if it is meant as a word of the level format, rename the parameter)",
                e.help,
                &self.text[s..end]
            ),
            _ => e.help.clone(),
        };
        let (line, col) = line_col(&self.text, map.to_original(off));
        LevelError {
            line,
            col,
            help,
            ..e
        }
    }

    /// The warnings of a made variant, at the original text's positions.
    pub fn warnings(&self, path: &Path, made: &Made) -> Vec<LevelWarning> {
        super::warnings::find(path, &made.expanded, &made.level)
            .into_iter()
            .map(|w| LevelWarning(self.remap(&made.expanded, &made.map, w.0)))
            .collect()
    }

    /// Checks the nominal variant and every corner of the ranges: the first that fails, as an
    /// error naming its values. A corner also fails where it puts a colliding body's center
    /// inside another body that the nominal variant does not (`params::overlap`).
    pub fn check_corners(&self, path: &Path) -> Result<(), LevelError> {
        let nominal = self.make(path, &self.indices(&Pick::Nominal))?;
        let known = overlap::inside_pairs(&nominal.level);
        self.control(path, &nominal)?;
        for c in self.corners() {
            let made = self.make(path, &c)?;
            self.control(path, &made)?;
            let new = overlap::inside_pairs(&made.level)
                .into_iter()
                .find(|pair| !known.contains(pair));
            if let Some((outer, inner)) = new {
                let loc = super::error::Locator::new(&self.text);
                return Err(LevelError::new(
                    path,
                    loc.field_pos("bodies", &inner, "position"),
                    format!(
                        "body `{inner}` starts with its center inside `{outer}` [variant: {}]",
                        made.variant.shown
                    ),
                    "the parameters' ranges move one body into the other: narrow the ranges, or write the positions so that they follow the parameters",
                ));
            }
        }
        Ok(())
    }
}

fn is_word(s: &str) -> bool {
    s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Line and column (1-based, characters) of a byte offset.
fn line_col(text: &str, off: usize) -> (usize, usize) {
    let off = off.min(text.len());
    let before = &text[..off];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

fn locate(path: &Path, text: &str, e: Located) -> LevelError {
    LevelError::new(path, line_col(text, e.offset), e.message, e.help)
}

/// A level of the given pick: for a level without parameters, None; else the picked variant,
/// after the nominal one and every corner were checked.
pub fn make_checked(
    path: &Path,
    text: &str,
    pick: &Pick,
) -> Result<Option<(Parameterized, Made)>, LevelError> {
    let Some(p) = Parameterized::read(path, text)? else {
        return Ok(None);
    };
    p.check_corners(path)?;
    let made = p.make(path, &p.indices(pick))?;
    Ok(Some((p, made)))
}
