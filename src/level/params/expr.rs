//! Evaluating one expression of a parameterized level with exmex (docs/levels.md#parameters
//! says why that crate).
//!
//! exmex's default float operators, less its constants (`e` and `E` would shadow a restitution
//! parameter named `e`; `PI`, `TAU` and their Greek letters are replaced by `pi`, which a level
//! gets as a name): `+ - * / ^`, parentheses, and its one-argument functions (sin, cos, tan,
//! asin, acos, atan, sqrt, exp, ln, log10, abs, ...), all in f64.
//!
//! Parsed as exmex's `DeepEx` (a tree), not its `FlatEx`: exmex 0.21's flattened form evaluates a
//! function of a sum or product of a name and two numbers wrongly, `sqrt(x*2*1)` as sqrt(18) at
//! x = 3 and `sqrt(g*1.05*0.598)` as 7.77 for 2.48 (found 2026-12-07 writing a challenge's
//! worked value; the unit test below holds both forms to their values).

use exmex::{DeepEx, Express, FloatOpsFactory, MakeOperators, Operator};
use std::sync::OnceLock;

#[derive(Clone, Debug)]
struct LevelOps;

/// exmex's constants, dropped (see the module's doc).
const DROPPED: [&str; 6] = ["e", "E", "PI", "π", "TAU", "τ"];

impl MakeOperators<f64> for LevelOps {
    fn make<'a>() -> Vec<Operator<'a, f64>> {
        FloatOpsFactory::<f64>::make()
            .into_iter()
            .filter(|o| !DROPPED.contains(&o.repr()))
            .collect()
    }
}

/// The functions an expression may call, `name(...)`: exmex's unary operators with a name.
fn functions() -> &'static [String] {
    static NAMES: OnceLock<Vec<String>> = OnceLock::new();
    NAMES.get_or_init(|| {
        LevelOps::make()
            .iter()
            .filter(|o| o.has_unary() && !o.has_bin())
            .map(|o| o.repr().to_string())
            .filter(|n| n.chars().all(|c| c.is_ascii_alphanumeric()))
            .collect()
    })
}

/// Whether `name(...)` is a function an expression may call.
pub fn is_function(name: &str) -> bool {
    functions().iter().any(|f| f == name)
}

/// The value of `text`, each name read through `value`; an error in words.
pub fn eval(text: &str, value: impl Fn(&str) -> Option<f64>) -> Result<f64, String> {
    let ex = DeepEx::<f64, LevelOps>::parse(text).map_err(|e| e.msg().to_string())?;
    let mut vars = Vec::new();
    for name in ex.var_names() {
        vars.push(value(name).ok_or_else(|| format!("unknown name `{name}`"))?);
    }
    ex.eval(&vars).map_err(|e| e.msg().to_string())
}

#[cfg(test)]
mod tests {
    use super::eval;

    fn at(text: &str) -> f64 {
        eval(text, |n| match n {
            "x" => Some(3.0),
            "g" => Some(9.81),
            _ => None,
        })
        .unwrap()
    }

    /// A function of a name and two numbers: exmex 0.21's `FlatEx` read `sqrt(x*2*1)` at x = 3
    /// as sqrt(18), `sqrt(x+2+1)` as 4.73 and `sqrt(g*1.05*0.598)` as 7.77; the values below are
    /// the arithmetic's.
    #[test]
    fn a_function_of_a_name_and_two_numbers_is_evaluated_as_written() {
        let cases = [
            ("sqrt(x*2*1)", 6f64.sqrt()),
            ("sqrt(x+2+1)", 6f64.sqrt()),
            ("sqrt(g*1.05*0.598)", (9.81f64 * 1.05 * 0.598).sqrt()),
            ("sqrt(1.05*g*0.598)", (9.81f64 * 1.05 * 0.598).sqrt()),
            ("sin(x*2*1)", 6f64.sin()),
            ("2*sqrt(x*2*1)*3", 6.0 * 6f64.sqrt()),
            ("sqrt(2*x*3*4)", 72f64.sqrt()),
            ("x^2*3*4", 108.0),
            ("cos(x/2/3)", 0.5f64.cos()),
        ];
        for (text, want) in cases {
            let got = at(text);
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                "{text}: {got} for {want}"
            );
        }
    }
}
