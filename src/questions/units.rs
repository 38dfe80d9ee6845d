//! Answers with units: a student types `523.4 in/s`, `62 rad/s` or `79.7 ft*lb/s`, and the value
//! is converted to the question's unit before grading; a unit of another dimension is an error.
//!
//! Why not a units crate: the general ones read `lb` as the pound of mass, while the engineering
//! texts these exercises come from (MK, Hibbeler in US units) use `lb` for the pound of force and
//! `slug` for mass, so `ft*lb/s` must be a power. The table below is that convention; exact
//! definitions (1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N, g0 = 9.80665 m/s^2).

use std::f64::consts::PI;

/// A unit's size in SI and its dimension: exponents of kg, m, s (radians are dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    pub factor: f64,
    pub dims: [i32; 3],
}

const LBF: f64 = 4.448_221_615_260_5;
const FT: f64 = 0.3048;

/// The units an answer or a question may name.
const TABLE: &[(&str, f64, [i32; 3])] = &[
    ("1", 1.0, [0, 0, 0]),
    ("rad", 1.0, [0, 0, 0]),
    ("deg", PI / 180.0, [0, 0, 0]),
    ("rev", 2.0 * PI, [0, 0, 0]),
    ("m", 1.0, [0, 1, 0]),
    ("cm", 0.01, [0, 1, 0]),
    ("mm", 1e-3, [0, 1, 0]),
    ("km", 1e3, [0, 1, 0]),
    ("in", 0.0254, [0, 1, 0]),
    ("ft", FT, [0, 1, 0]),
    ("yd", 0.9144, [0, 1, 0]),
    ("mi", 1609.344, [0, 1, 0]),
    ("kg", 1.0, [1, 0, 0]),
    ("g", 1e-3, [1, 0, 0]),
    ("slug", LBF / FT, [1, 0, 0]),
    ("s", 1.0, [0, 0, 1]),
    ("ms", 1e-3, [0, 0, 1]),
    ("min", 60.0, [0, 0, 1]),
    ("h", 3600.0, [0, 0, 1]),
    ("Hz", 1.0, [0, 0, -1]),
    ("rpm", 2.0 * PI / 60.0, [0, 0, -1]),
    ("N", 1.0, [1, 1, -2]),
    ("kN", 1e3, [1, 1, -2]),
    ("lb", LBF, [1, 1, -2]),
    ("lbf", LBF, [1, 1, -2]),
    ("kip", 1e3 * LBF, [1, 1, -2]),
    ("J", 1.0, [1, 2, -2]),
    ("kJ", 1e3, [1, 2, -2]),
    ("W", 1.0, [1, 2, -3]),
    ("kW", 1e3, [1, 2, -3]),
    ("hp", 550.0 * FT * LBF, [1, 2, -3]),
];

impl Unit {
    /// Parses a unit expression: names from the table joined by `*`, `.`, `·` or spaces, with
    /// `^n` powers (n may be negative); everything after a `/` divides (`m/s^2`, `ft*lb/s`,
    /// `kg m^2`, `1/s`).
    pub fn parse(text: &str) -> Result<Unit, String> {
        let mut u = Unit {
            factor: 1.0,
            dims: [0; 3],
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
        for (part, sign) in [(num, 1), (den.unwrap_or(""), -1)] {
            for factor in part
                .split(|c: char| c == '*' || c == '.' || c == '\u{b7}' || c.is_whitespace())
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
                let (_, f, d) = TABLE.iter().find(|(n, _, _)| *n == name).ok_or_else(|| {
                    let known: Vec<&str> = TABLE.iter().map(|(n, _, _)| *n).collect();
                    format!("unknown unit `{name}`; known: {}", known.join(", "))
                })?;
                let p = sign * power;
                u.factor *= f.powi(p);
                for k in 0..3 {
                    u.dims[k] += d[k] * p;
                }
            }
        }
        Ok(u)
    }

    /// The dimension in words, for error messages: "kg m^2 s^-3".
    pub fn dimension(&self) -> String {
        let parts: Vec<String> = ["kg", "m", "s"]
            .iter()
            .zip(self.dims)
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

/// Reads a typed answer, `VALUE` or `VALUE UNIT` (`523.4in/s`, `62 rad/s`, `1,5 m`), as a value in
/// the question's unit `asked`. A plain number is taken in the question's unit.
pub fn answer_in(text: &str, asked: &str) -> Result<f64, String> {
    let t = text.trim().replace(',', ".");
    // The longest prefix that is a number (digits, sign, point, exponent).
    let end = (1..=t.len())
        .rev()
        .filter(|&i| t.is_char_boundary(i))
        .find(|&i| t[..i].trim().parse::<f64>().is_ok())
        .ok_or_else(|| format!("`{}` does not start with a number", text.trim()))?;
    let value: f64 = t[..end].trim().parse().expect("checked above");
    if !value.is_finite() {
        return Err("give a finite number".into());
    }
    let unit = t[end..].trim();
    if unit.is_empty() {
        return Ok(value);
    }
    let given = Unit::parse(unit)?;
    let want = Unit::parse(asked).map_err(|e| {
        format!("the question's unit `{asked}` cannot be converted to ({e}); give a plain number in {asked}")
    })?;
    if given.dims != want.dims {
        return Err(format!(
            "`{unit}` is {} but the question asks for {asked} ({})",
            given.dimension(),
            want.dimension()
        ));
    }
    Ok(value * given.factor / want.factor)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn us_units_convert_to_the_questions_si_unit() {
        // 523.4 in/s = 523.4 x 0.0254 m/s = 13.29436 m/s.
        assert!(close(answer_in("523.4in/s", "m/s").unwrap(), 13.294_36));
        // 79.7 ft lbf/s = 79.7 x 0.3048 x 4.4482216152605 W = 108.0586... W.
        assert!(close(
            answer_in("79.7 ft*lb/s", "W").unwrap(),
            79.7 * 0.3048 * LBF
        ));
        // 2000 rpm = 2000 x 2 pi / 60 rad/s.
        assert!(close(
            answer_in("2000 rpm", "rad/s").unwrap(),
            2000.0 * 2.0 * PI / 60.0
        ));
        // 1 slug ft^2 = 1.3558179... kg m^2 (lbf s^2/ft x ft^2).
        assert!(close(answer_in("1 slug*ft^2", "kg m^2").unwrap(), LBF * FT));
        // 90 deg in rad; 1 hp = 550 ft lbf/s = 745.6999 W.
        assert!(close(answer_in("90deg", "rad").unwrap(), PI / 2.0));
        assert!(close(
            answer_in("1 hp", "W").unwrap(),
            745.699_871_582_270_2
        ));
        // Plain numbers stay in the question's unit; the question's unit may be N m.
        assert_eq!(answer_in("5.08", "N m").unwrap(), 5.08);
        assert!(close(answer_in("1 ft*lb", "N m").unwrap(), FT * LBF));
        assert!(close(answer_in("-3,5 m/s^2", "m/s^2").unwrap(), -3.5));
        assert!(close(answer_in("1e3 g", "kg").unwrap(), 1.0));
    }

    #[test]
    fn a_wrong_dimension_or_unknown_unit_is_a_clear_error() {
        let e = answer_in("62 rad/s", "m/s").unwrap_err();
        assert!(e.contains("s^-1") && e.contains("m s^-1"), "{e}");
        let e = answer_in("3 furlongs", "m").unwrap_err();
        assert!(e.contains("unknown unit `furlongs`"), "{e}");
        let e = answer_in("m/s", "m/s").unwrap_err();
        assert!(e.contains("does not start with a number"), "{e}");
        let e = answer_in("1 m/s/s", "m/s^2").unwrap_err();
        assert!(e.contains("one `/`"), "{e}");
    }
}
