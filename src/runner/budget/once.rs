//! What a run pays once, priced for the run budget ([`super`]): the reference trajectory's
//! integrations for the questions it serves, and the size of the mechanism a period question
//! linearizes.

use super::{
    REFERENCE_BODY_EVAL_US, REFERENCE_EVALS_PER_S, REFERENCE_EVALS_PER_SEGMENT, REFERENCE_EVAL_US,
    REFERENCE_ROW_EVAL_US,
};
use crate::level::{BodyKind, Level, When};

/// The reference trajectory's price, us, over a run of `duration` s: where a question that the
/// reference can serve is read at a time (as `questions::LevelFacts` prepares it) and the scene
/// fits the reference (`Reference::of_level`; no touch at the start that it cannot hold), each
/// such question integrates it from the start to its time (its window's end), at
/// [`REFERENCE_EVALS_PER_S`] evaluations a second and [`REFERENCE_EVALS_PER_SEGMENT`] a segment
/// (`Reference::stretch`), each evaluation priced by the bodies and rows it solves. A question
/// the textbook's closed form answers does not read the reference, and one read after a contact
/// the reference does not hold stops at it: both are known only as the run goes, and priced.
pub(super) fn reference_us(level: &Level, duration: f64) -> f64 {
    use crate::analysis::reference::{Reference, MAX_MOVING_BODIES};
    use crate::questions::level_facts::served_by_reference;
    let spans: Vec<f64> = level
        .questions
        .iter()
        .filter(|q| served_by_reference(&q.quantity))
        .filter_map(|q| {
            let t = match q.at {
                When::Time(t) => t.min(duration),
                When::End => duration,
                _ => return None,
            };
            Some(t + 0.5 * q.quantity.averaging_window())
        })
        .filter(|&t| t > 0.0)
        .collect();
    let moving = level
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Dynamic)
        .count();
    if spans.is_empty() || moving > MAX_MOVING_BODIES {
        return 0.0;
    }
    let Ok(model) = Reference::of_level(level) else {
        return 0.0;
    };
    if model.refused_after_start().is_some() {
        return 0.0;
    }
    let moving = (0..level.bodies.len()).filter(|&i| model.moves(i)).count();
    let eval_us = REFERENCE_EVAL_US
        + moving as f64 * REFERENCE_BODY_EVAL_US
        + model.row_count() as f64 * REFERENCE_ROW_EVAL_US;
    let per_s = REFERENCE_EVALS_PER_S + REFERENCE_EVALS_PER_SEGMENT / model.stretch();
    spans.iter().sum::<f64>() * per_s * eval_us
}

/// The largest mechanism of dynamic bodies that joints hold together (a lone body is one): its
/// coordinates n (3 a body) and degrees of freedom d = n less its joints' rows (a pin's and a
/// slider's 2, a weld's 3, a pin in a slot's 1), at least 1. Joints to fixed or kinematic
/// bodies count their rows but join nothing.
pub(super) fn largest_mechanism(level: &Level) -> (usize, usize) {
    use crate::level::JointKind;
    let index: std::collections::HashMap<&str, usize> = level
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| (b.name.as_str(), i))
        .collect();
    let dynamic = |i: usize| level.bodies[i].kind == BodyKind::Dynamic;
    let mut root: Vec<usize> = (0..level.bodies.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let ends: Vec<(Option<usize>, Option<usize>, usize)> = level
        .joints
        .iter()
        .map(|j| {
            let rows = match j.kind {
                JointKind::Revolute | JointKind::Prismatic => 2,
                JointKind::Fixed => 3,
                JointKind::PinSlot => 1,
            };
            let end = |name: &str| index.get(name).copied().filter(|&i| dynamic(i));
            (end(&j.body1), end(&j.body2), rows)
        })
        .collect();
    for &(a, b, _) in &ends {
        if let (Some(a), Some(b)) = (a, b) {
            let (ra, rb) = (find(&mut root, a), find(&mut root, b));
            root[ra] = rb;
        }
    }
    let mut size: std::collections::HashMap<usize, (usize, usize)> = Default::default();
    for i in (0..level.bodies.len()).filter(|&i| dynamic(i)) {
        size.entry(find(&mut root, i)).or_default().0 += 3;
    }
    for &(a, b, rows) in &ends {
        if let Some(i) = a.or(b) {
            size.entry(find(&mut root, i)).or_default().1 += rows;
        }
    }
    size.values()
        .map(|&(n, rows)| (n, n.saturating_sub(rows).max(1)))
        // In f64: d^2 n^3 of a chain of 10,000 bodies is past a u64.
        .max_by(|a, b| {
            let size = |&(n, d): &(usize, usize)| (d as f64).powi(2) * (n as f64).powi(3);
            size(a).total_cmp(&size(b))
        })
        .unwrap_or((0, 0))
}
