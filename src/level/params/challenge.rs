//! A challenge's control among the parameters (format/challenge.rs): the control names a
//! parameter, whose range, step and unit it takes; `worked` lies in that range at the nominal
//! values and every corner; and a run of the challenge is the variant with the control set to
//! `worked` or to the student's value (docs/levels.md#challenges).

use super::super::error::{LevelError, Locator};
use super::{Made, Parameterized, Values};
use std::path::Path;

/// The control a challenge hands the student, in the parameter's own unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// The parameter's name, also the id `--answer` gives it by.
    pub name: String,
    /// Its place among the parameters.
    pub index: usize,
    /// Its unit as declared ("" for a pure number) and that unit's size in SI.
    pub unit: String,
    pub factor: f64,
    /// The range the student sets it in, and the step the window's field moves by (a list's
    /// smallest gap between values).
    pub min: f64,
    pub max: f64,
    pub step: f64,
    /// Decimals its values are printed with at least.
    pub decimals: usize,
    /// The closed-form value, in the control's unit.
    pub worked: f64,
}

impl Control {
    /// Whether a value (in the control's unit) lies in the range, to rounding.
    pub fn holds(&self, v: f64) -> bool {
        let slack = 1e-9 * self.min.abs().max(self.max.abs()).max(1e-300);
        v.is_finite() && v >= self.min - slack && v <= self.max + slack
    }

    /// A value with its unit, as the statement prints it.
    pub fn show(&self, v: f64) -> String {
        let n = super::text::textbook(v, self.decimals);
        if self.unit.is_empty() {
            n
        } else {
            format!("{n} {}", self.unit)
        }
    }
}

impl Parameterized {
    /// The control of a made variant's challenge (None without a challenge): an error where
    /// it names no parameter, or where `worked` lies outside its range in this variant.
    pub fn control(&self, path: &Path, made: &Made) -> Result<Option<Control>, LevelError> {
        let Some(c) = &made.level.challenge else {
            return Ok(None);
        };
        let loc = Locator::new(&self.text);
        let Some(index) = self.params.iter().position(|p| p.name == c.control) else {
            let names: Vec<&str> = self.params.iter().map(|p| p.name.as_str()).collect();
            return Err(LevelError::new(
                path,
                loc.section_field("challenge", "control"),
                format!("the challenge's control \"{}\" names no parameter", c.control),
                format!(
                    "name one of the parameters ({}), or declare it in `parameters` with its range, step and unit",
                    names.join(", ")
                ),
            ));
        };
        let p = &self.params[index];
        let (lo, hi) = p.values.ends();
        let (min, max) = (p.values.at(lo), p.values.at(hi));
        let step = match &p.values {
            Values::Grid { step, .. } => *step,
            Values::List(l) => smallest_gap(l),
        };
        let control = Control {
            name: p.name.clone(),
            index,
            unit: p.unit.clone(),
            factor: p.factor,
            min,
            max,
            step,
            decimals: p.decimals,
            worked: c.worked / p.factor,
        };
        if !control.holds(control.worked) {
            return Err(LevelError::new(
                path,
                loc.section_field("challenge", "worked"),
                format!(
                    "the challenge's worked value {} is outside the control's range ({}, {}) [variant: {}]",
                    control.show(control.worked),
                    control.show(min),
                    control.show(max),
                    made.variant.shown
                ),
                format!(
                    "widen `{}`'s range to hold the closed-form value, or check the `worked` expression (it is in SI: a `deg` control's worked value is in radians)",
                    p.name
                ),
            ));
        }
        Ok(Some(control))
    }

    /// The variant of these indices with the challenge's control set to `value` (its unit), or
    /// to its worked value when None: the level a challenge runs. A value outside the control's
    /// range is an error, and so is a `worked` that changes with the control (it must be an
    /// expression of the other parameters).
    pub fn make_control(
        &self,
        path: &Path,
        idx: &[u64],
        value: Option<f64>,
    ) -> Result<(Made, Option<Control>), LevelError> {
        let made = self.make(path, idx)?;
        let Some(control) = self.control(path, &made)? else {
            return Ok((made, None));
        };
        let v = value.unwrap_or(control.worked);
        if !control.holds(v) {
            return Err(LevelError::new(
                path,
                (0, 0),
                format!(
                    "{} = {} is outside the control's range ({}, {})",
                    control.name,
                    control.show(v),
                    control.show(control.min),
                    control.show(control.max)
                ),
                format!(
                    "give {} from {} to {}",
                    control.name,
                    control.show(control.min),
                    control.show(control.max)
                ),
            ));
        }
        let set = self.make_set(path, idx, Some((control.index, v)))?;
        let worked = set.level.challenge.as_ref().map_or(f64::NAN, |c| c.worked) / control.factor;
        if (worked - control.worked).abs() > 1e-9 * control.worked.abs().max(1e-300) {
            let loc = Locator::new(&self.text);
            return Err(LevelError::new(
                path,
                loc.section_field("challenge", "worked"),
                format!(
                    "the challenge's worked value changes with its control {}: {} at {}, {} at {}",
                    control.name,
                    control.show(control.worked),
                    made.variant.shown,
                    control.show(worked),
                    set.variant.shown
                ),
                "write `worked` as the closed form in the other parameters and g, without the control itself",
            ));
        }
        Ok((set, Some(control)))
    }
}

/// The smallest gap between a list's distinct values (1 when it holds one value).
fn smallest_gap(list: &[f64]) -> f64 {
    let mut v = list.to_vec();
    v.sort_by(f64::total_cmp);
    let gap = v
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    if gap.is_finite() {
        gap
    } else {
        1.0
    }
}
