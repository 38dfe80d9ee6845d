//! Evaluating one expression of a parameterized level with exmex (docs/levels.md#parameters
//! says why that crate).
//!
//! exmex's default float operators, less its constants (`e` and `E` would shadow a restitution
//! parameter named `e`; `PI`, `TAU` and their Greek letters are replaced by `pi`, which a level
//! gets as a name): `+ - * / ^`, parentheses, and its one-argument functions (sin, cos, tan,
//! asin, acos, atan, sqrt, exp, ln, log10, abs, ...), all in f64.

use exmex::{Express, FlatEx, FloatOpsFactory, MakeOperators, Operator};
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
    let ex = FlatEx::<f64, LevelOps>::parse(text).map_err(|e| e.msg().to_string())?;
    let mut vars = Vec::new();
    for name in ex.var_names() {
        vars.push(value(name).ok_or_else(|| format!("unknown name `{name}`"))?);
    }
    ex.eval(&vars).map_err(|e| e.msg().to_string())
}
