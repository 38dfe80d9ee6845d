//! Hints and the worked solution: no empty text, each error at its own line.

use super::*;

pub(super) fn hints_and_solution(v: &V) -> R {
    let n = v.level.hints.len();
    for (i, h) in v.level.hints.iter().enumerate() {
        if h.trim().is_empty() {
            return Err(v.err(
                v.loc.nth_string_in_section("hints", i),
                format!("hint {} of {n} is empty", i + 1),
                "write the hint's text, or remove the empty string from `hints: [...]`",
            ));
        }
    }
    // An absent solution is the empty default; one written but blank is a mistake.
    if v.level.solution.trim().is_empty() && v.loc.has_section("solution") {
        return Err(v.err(
            v.loc.section("solution"),
            "the solution is empty",
            "write the worked solution, one step per line, or remove `solution`",
        ));
    }
    Ok(())
}
