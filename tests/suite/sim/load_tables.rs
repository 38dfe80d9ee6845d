//! Load tables are interpolated linearly and held at their ends, found by bisection so a table of
//! any length costs O(log n) a step (issue 16: a 100k-row table was searched linearly, 85 s;
//! the cost is a benchmark matter, this file holds the values).

use rigidlab::level::Profile;
use rigidlab::sim::{scalar_profile_at, vector_profile_at};

#[test]
fn a_long_table_interpolates_linearly_and_holds_its_ends() {
    // f(t) = 3 t + 1 on rows every 1e-3 s: linear interpolation reproduces it exactly between rows.
    let rows: Vec<(f64, f64)> = (0..100_000)
        .map(|k| (k as f64 * 1e-3, 3.0 * k as f64 * 1e-3 + 1.0))
        .collect();
    let p = Profile::Table(rows.clone());
    for &t in &[0.0, 1e-3, 0.0125, 7.3456, 50.0, 99.9985, 99.999] {
        assert!(
            (scalar_profile_at(&p, t) - (3.0 * t + 1.0)).abs() < 1e-9,
            "t = {t}"
        );
    }
    // Held beyond the ends.
    assert_eq!(scalar_profile_at(&p, -5.0), 1.0);
    assert_eq!(scalar_profile_at(&p, 1e6), rows[rows.len() - 1].1);
    // On a row exactly: that row's value.
    assert_eq!(scalar_profile_at(&p, rows[4321].0), rows[4321].1);
}

#[test]
fn vector_tables_interpolate_each_component() {
    let p = Profile::Table(vec![
        (0.0, (0.0, 10.0)),
        (2.0, (4.0, 6.0)),
        (3.0, (4.0, 0.0)),
    ]);
    assert_eq!(vector_profile_at(&p, 1.0), (2.0, 8.0));
    assert_eq!(vector_profile_at(&p, 2.5), (4.0, 3.0));
    assert_eq!(vector_profile_at(&p, 9.0), (4.0, 0.0));
}
