//! The units a question's `unit` may name, and that a student's answer may carry: SI and the US
//! engineering units, each with its size in SI and its dimension. Validation requires a question's
//! unit to be the SI unit of its quantity's dimension (`Quantity::si_unit`); `questions::units`
//! converts typed answers with the same table.
//!
//! Why not a units crate: the general ones read `lb` as the pound of mass, while the engineering
//! texts these exercises come from (MK, Hibbeler in US units) use `lb` for the pound of force and
//! `slug` for mass, so `ft*lb/s` must be a power. The table below is that convention; exact
//! definitions (1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N, g0 = 9.80665 m/s^2).

use std::f64::consts::PI;

/// A unit's size in SI and its dimension: exponents of kg, m, s, and of the angle.
///
/// The angle is dimensionless in SI (a rad/s is a 1/s), but a cycle is 2 pi rad: so that an
/// angular rate typed in Hz or rev/s converts with 2 pi, angles carry an exponent of their own
/// (rad, deg, rev, and Hz = rev/s, rpm = rev/min). An answer converts to a question's unit when
/// kg, m and s agree and either their angle exponents agree or the answer names no angle (a
/// `1/s` typed for rad/s is read in radians). An angle the question's unit does not have is
/// refused, not dropped: `m*rev/s` for a speed in m/s would be 2 pi m/s in SI, a factor the
/// student never meant (it graded 1.5614 "m*rev/s" right for 9.81 m/s, issue 41), and no
/// speed, force or energy is written with an angle in it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    pub factor: f64,
    pub dims: [i32; 3],
    pub angle: i32,
}

/// The largest power a unit may be raised to (`s^-2`, `m^3`; a kg m^2 s^-3 needs 3).
const MAX_POWER: i32 = 12;

pub const LBF: f64 = 4.448_221_615_260_5;
pub const FT: f64 = 0.3048;

/// The units an answer or a question may name: name, size in SI, exponents of kg, m, s, and
/// of the angle.
const TABLE: &[(&str, f64, [i32; 3], i32)] = &[
    ("1", 1.0, [0, 0, 0], 0),
    ("rad", 1.0, [0, 0, 0], 1),
    ("deg", PI / 180.0, [0, 0, 0], 1),
    ("rev", 2.0 * PI, [0, 0, 0], 1),
    ("m", 1.0, [0, 1, 0], 0),
    ("cm", 0.01, [0, 1, 0], 0),
    ("mm", 1e-3, [0, 1, 0], 0),
    ("km", 1e3, [0, 1, 0], 0),
    ("in", 0.0254, [0, 1, 0], 0),
    ("ft", FT, [0, 1, 0], 0),
    ("yd", 0.9144, [0, 1, 0], 0),
    ("mi", 1609.344, [0, 1, 0], 0),
    ("kg", 1.0, [1, 0, 0], 0),
    ("g", 1e-3, [1, 0, 0], 0),
    ("slug", LBF / FT, [1, 0, 0], 0),
    ("s", 1.0, [0, 0, 1], 0),
    ("ms", 1e-3, [0, 0, 1], 0),
    ("min", 60.0, [0, 0, 1], 0),
    ("h", 3600.0, [0, 0, 1], 0),
    // Cycles per second and per minute: 2 pi rad/s and 2 pi/60 rad/s as angular rates.
    ("Hz", 2.0 * PI, [0, 0, -1], 1),
    ("rpm", 2.0 * PI / 60.0, [0, 0, -1], 1),
    ("N", 1.0, [1, 1, -2], 0),
    ("mN", 1e-3, [1, 1, -2], 0),
    ("kN", 1e3, [1, 1, -2], 0),
    ("lb", LBF, [1, 1, -2], 0),
    ("lbf", LBF, [1, 1, -2], 0),
    ("kip", 1e3 * LBF, [1, 1, -2], 0),
    ("J", 1.0, [1, 2, -2], 0),
    ("mJ", 1e-3, [1, 2, -2], 0),
    ("kJ", 1e3, [1, 2, -2], 0),
    ("W", 1.0, [1, 2, -3], 0),
    ("mW", 1e-3, [1, 2, -3], 0),
    ("kW", 1e3, [1, 2, -3], 0),
    ("hp", 550.0 * FT * LBF, [1, 2, -3], 0),
];

impl Unit {
    /// Parses a unit expression: names from the table joined by `*`, `.`, `·` or spaces, with
    /// `^n` powers (n may be negative); everything after a `/` divides (`m/s^2`, `ft*lb/s`,
    /// `kg m^2`, `1/s`). An operator needs a unit on each side (`m/s*`, `*m`, `m**s` and `m/`
    /// are refused, not read as `m/s`, `m`, `m s`, `m`).
    pub fn parse(text: &str) -> Result<Unit, String> {
        let mut u = Unit {
            factor: 1.0,
            dims: [0; 3],
            angle: 0,
        };
        let (num, den) = match text.split_once('/') {
            Some((n, d)) => (n, Some(d)),
            None => (text, None),
        };
        if den.is_some_and(|d| d.contains('/')) {
            return Err(format!(
                "`{text}`: write one `/` at most (everything after it divides)"
            ));
        }
        let lonely = |op: &str| {
            format!("`{text}`: `{op}` needs a unit on each side (write e.g. `m/s`, `N*m`, `1/s`)")
        };
        if den.is_some_and(|d| num.trim().is_empty() || d.trim().is_empty()) {
            return Err(lonely("/"));
        }
        let is_op = |c: char| c == '*' || c == '.' || c == '\u{b7}';
        // An empty unit is dimensionless (`unit: ""`), as `1` is.
        let parts = [(num, 1)].into_iter().chain(den.map(|d| (d, -1)));
        for (part, sign) in parts.filter(|(p, _)| !p.trim().is_empty()) {
            // Between two operators, or an operator and an end, there must be a unit.
            if part.split(is_op).any(|piece| piece.trim().is_empty()) {
                let op = part.chars().find(|c| is_op(*c)).unwrap_or('*');
                return Err(lonely(&op.to_string()));
            }
            for factor in part
                .split(|c: char| is_op(c) || c.is_whitespace())
                .filter(|s| !s.is_empty())
            {
                let (name, power) = match factor.split_once('^') {
                    Some((n, p)) => (
                        n,
                        p.parse::<i32>().map_err(|_| {
                            format!("`{factor}`: the power after ^ must be a whole number")
                        })?,
                    ),
                    None => (factor, 1),
                };
                if power.abs() > MAX_POWER {
                    return Err(format!(
                        "`{factor}`: a power of at most {MAX_POWER} (and at least -{MAX_POWER})"
                    ));
                }
                let (_, f, d, a) =
                    TABLE
                        .iter()
                        .find(|(n, _, _, _)| *n == name)
                        .ok_or_else(|| {
                            let known: Vec<&str> = TABLE.iter().map(|(n, _, _, _)| *n).collect();
                            format!("unknown unit `{name}`; known: {}", known.join(", "))
                        })?;
                let p = sign * power;
                u.factor *= f.powi(p);
                // Bounded powers of bounded exponents, summed over a bounded text: no overflow
                // but for texts of millions of factors, which checked sums refuse too.
                let add =
                    |e: i32, x: i32| e.checked_add(x * p).filter(|v| v.abs() <= 4 * MAX_POWER);
                for (dim, x) in u.dims.iter_mut().zip(d) {
                    *dim = add(*dim, *x).ok_or_else(|| {
                        format!("`{text}`: the unit's powers are too large to be a unit")
                    })?;
                }
                u.angle = add(u.angle, *a).ok_or_else(|| {
                    format!("`{text}`: the unit's powers are too large to be a unit")
                })?;
            }
        }
        Ok(u)
    }

    /// Whether an answer in this unit converts to a question's unit `other`: kg, m and s agree,
    /// and the angle does or this unit names none (then it is taken in radians). An angle that
    /// `other` does not have is refused (see [`Unit`]).
    pub fn converts_to(&self, other: &Unit) -> bool {
        self.dims == other.dims && (self.angle == other.angle || self.angle == 0)
    }

    /// The dimension in words, for error messages: "kg m^2 s^-3", "rad s^-1".
    pub fn dimension(&self) -> String {
        let parts: Vec<String> = ["kg", "m", "s", "rad"]
            .iter()
            .zip(self.dims.into_iter().chain([self.angle]))
            .filter(|(_, e)| *e != 0)
            .map(|(n, e)| {
                if e == 1 {
                    n.to_string()
                } else {
                    format!("{n}^{e}")
                }
            })
            .collect();
        if parts.is_empty() {
            "dimensionless".into()
        } else {
            parts.join(" ")
        }
    }
}
