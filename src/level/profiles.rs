//! Time tables of loads: linear interpolation, held constant beyond the ends. A part of the
//! level's data (the simulation reads it, and so does a level captured mid-run, `editor::capture`).

use super::{Profile, V2};

/// Linear interpolation in a time table, held constant beyond its ends. Times increase
/// (validated), so the row is found by bisection: O(log n) a step for a table of any length.
fn interp<T: Copy>(rows: &[(f64, T)], t: f64, lerp: impl Fn(T, T, f64) -> T) -> T {
    if t <= rows[0].0 {
        return rows[0].1;
    }
    // The first row at or after t; rows[k - 1].0 < t <= rows[k].0.
    let k = rows.partition_point(|r| r.0 < t);
    if k >= rows.len() {
        return rows[rows.len() - 1].1;
    }
    let (a, b) = (rows[k - 1], rows[k]);
    lerp(a.1, b.1, (t - a.0) / (b.0 - a.0))
}

/// The value at time t of a vector profile (a load's force): its constant, or its table
/// interpolated linearly and held beyond its ends.
pub fn vector_profile_at(p: &Profile<V2>, t: f64) -> V2 {
    match p {
        Profile::Constant(v) => *v,
        Profile::Table(rows) => interp(rows, t, |a, b, s| {
            (a.0 + (b.0 - a.0) * s, a.1 + (b.1 - a.1) * s)
        }),
    }
}

/// The value at time t of a scalar profile (a load's torque), as [`vector_profile_at`].
pub fn scalar_profile_at(p: &Profile<f64>, t: f64) -> f64 {
    match p {
        Profile::Constant(v) => *v,
        Profile::Table(rows) => interp(rows, t, |a, b, s| a + (b - a) * s),
    }
}
