//! Answers with units: a student types `523.4 in/s`, `62 rad/s` or `79.7 ft*lb/s`, and the value
//! is converted to the question's unit before grading; a unit of another dimension is an error.
//!
//! The unit table and its parser are the level format's (`level::units`: a question's `unit` is
//! checked against its quantity's dimension when the level is loaded).

pub use crate::level::units::Unit;

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
    if !given.converts_to(&want) {
        return Err(format!(
            "`{unit}` is {} but the question asks for {asked} ({})",
            given.dimension(),
            want.dimension()
        ));
    }
    Ok(value * given.factor / want.factor)
}

/// A student's typed answer to question `q` of `level`, converted to the quantity's SI unit, the
/// question's unit up to notation (validation holds it there): a question in `1/s` still takes an
/// answer in rad/s. `check --answer` and `grade` read answers this way.
pub fn answer_to(
    q: &crate::level::QuestionDef,
    level: &crate::level::Level,
    text: &str,
) -> Result<f64, String> {
    answer_in(text, q.quantity.si_unit(level))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::units::{FT, LBF};
    use std::f64::consts::PI;

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
        // Angular rates in cycles: 1 Hz = 1 rev/s = 2 pi rad/s = 60 rpm.
        assert!(close(answer_in("1 Hz", "rad/s").unwrap(), 2.0 * PI));
        assert!(close(answer_in("0.5 rev/s", "rad/s").unwrap(), PI));
        assert!(close(answer_in("60 rpm", "Hz").unwrap(), 1.0));
        assert!(close(
            answer_in("6.283185307179586 rad/s", "Hz").unwrap(),
            1.0
        ));
        // A rate asked in rad/s and typed in 1/s: the angle left out is read in radians.
        assert!(close(answer_in("3 1/s", "rad/s").unwrap(), 3.0));
    }

    #[test]
    fn an_angle_the_question_has_not_is_refused() {
        // Before (issue 41): 1.5614 m*rev/s was converted to 2 pi x 1.5614 = 9.8106 m/s and
        // graded right for 9.81 m/s; m*rad/s and m*deg/s were read as m/s (x 1, x pi/180).
        for typed in [
            "1.5614 m*rev/s",
            "9.81 m*rad/s",
            "562 m*deg/s",
            "9.81 m rad/s",
        ] {
            let e = answer_in(typed, "m/s").unwrap_err();
            assert!(
                e.contains("rad") && e.contains("the question asks for m/s"),
                "{typed}: {e}"
            );
        }
        // Another quantity with no angle: a force, a coefficient (dimensionless).
        assert!(answer_in("3 N*rad", "N").is_err());
        assert!(answer_in("0.5 rad", "1").is_err());
        // Where the question has the angle, every angle unit still converts.
        assert!(close(answer_in("0.5 rev/s", "rad/s").unwrap(), PI));
        assert!(close(answer_in("180 deg", "rad").unwrap(), PI));
        assert!(close(answer_in("0.5", "1").unwrap(), 0.5));
    }

    #[test]
    fn an_operator_without_a_unit_on_each_side_is_refused() {
        // Before (issue 41): `m/s*` read as m/s (empty factors were skipped).
        for typed in [
            "9.81 m/s*",
            "9.81 *m/s",
            "9.81 m**s",
            "9.81 m/",
            "9.81 /s",
            "9.81 m/s.",
        ] {
            let e = answer_in(typed, "m/s").unwrap_err();
            assert!(e.contains("needs a unit on each side"), "{typed}: {e}");
        }
        // Spaces, `*`, `.` and `·` between units still multiply; an empty unit is dimensionless.
        assert!(close(answer_in("2 N * m", "N m").unwrap(), 2.0));
        assert!(close(answer_in("2 N.m", "N m").unwrap(), 2.0));
        assert!(close(answer_in("2 kg  m^2 / s", "kg m^2/s").unwrap(), 2.0));
        assert!(Unit::parse("").is_ok());
    }

    #[test]
    fn powers_are_bounded_and_never_wrap() {
        // 2 x 2147483647 + 1 wraps to -1 in i32: read as 1/s, it graded an answer in s^... right.
        let e = answer_in("1.67 s^2147483647*s^2147483647*s", "rad/s").unwrap_err();
        assert!(e.contains("power of at most 12"), "{e}");
        let many = format!("1 {}", ["s^12"; 10].join("*"));
        let e = answer_in(&many, "s").unwrap_err();
        assert!(e.contains("too large"), "{e}");
        assert!(close(answer_in("1 m^3", "m^3").unwrap(), 1.0));
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
