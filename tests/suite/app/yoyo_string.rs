//! The yo-yo (levels/kinetics/classic_yoyo.ron, issue 42's student trial): its string is drawn,
//! in the window and the page (both draw the scene with `scene_lines`), and its questions say
//! which way is positive.
//!
//! The string is a coupling of the yo-yo's own coordinates, y - r theta = const with the axle's
//! radius r = 0.01 m: it had no line (a coupling's dashed line joins two bodies, and this one has
//! one). Differentiating, v_y = r omega: the axle point at offset (s, 0) from G moves up at
//! v_y + omega s, zero for s = -r. So the string leaves the axle on its left, at (x_G - r, y_G),
//! and runs straight up to its fixed end.

use rigidlab::app::draw::{Drawing, Prim};
use rigidlab::app::view;
use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

const LEVEL: &str = "levels/kinetics/classic_yoyo.ron";
/// The axle's radius, m (the level's statement: 10 mm).
const R: f64 = 0.01;
/// The yo-yo's outer radius, m (its Circle).
const OUTER: f64 = 0.05;

/// The vertical lines of the scene drawn after `steps` steps whose lower end is at `at`
/// (within 1e-9 m: the drawing's own arithmetic), with the yo-yo's center and velocity.
fn strings_after(steps: usize) -> (Vec<(glam::DVec2, glam::DVec2)>, glam::DVec2) {
    let scene = level::load(Path::new(LEVEL)).unwrap();
    let mut phys = Run::new(scene, Options::default());
    for _ in 0..steps {
        phys.advance();
    }
    let outlines = view::body_outlines(&phys.sim.level);
    let index = view::SceneIndex::of(&phys.sim.level);
    let mut d = Drawing::default();
    d.clear(0.001);
    rigidlab::app::scene_lines::scene_lines(
        &phys.sim.level,
        &outlines,
        &index,
        phys.snapshot(),
        0.001,
        &mut d,
    );
    let g = phys.snapshot().bodies[0].com;
    let tangent = g + glam::DVec2::new(-R, 0.0);
    let lines = d
        .prims
        .iter()
        .filter_map(|p| match p {
            Prim::Line(a, b, _) => Some((*a, *b)),
            _ => None,
        })
        .filter_map(|(a, b)| {
            let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
            ((lo - tangent).length() < 1e-9 && (hi.x - lo.x).abs() < 1e-12).then_some((lo, hi))
        })
        .collect();
    (lines, g)
}

#[test]
fn the_yoyo_string_runs_up_from_the_axle_to_a_fixed_end() {
    let (at_start, g0) = strings_after(0);
    // 120 steps of 1/240 s: 0.5 s, the yo-yo 0.072 m lower (a t^2 / 2, a = 0.577 m/s^2).
    let (later, g1) = strings_after(120);
    assert!(g1.y < g0.y - 0.05, "the yo-yo did not fall: {g0} -> {g1}");
    for (lines, g, when) in [(&at_start, g0, "at the start"), (&later, g1, "after 0.5 s")] {
        assert_eq!(
            lines.len(),
            1,
            "{when}: one string from the axle's left edge straight up, found {lines:?}"
        );
        let (_, top) = lines[0];
        assert!(
            top.y > g.y + OUTER,
            "{when}: the string ends at {top}, inside the yo-yo (center {g})"
        );
    }
    // The string's upper end is fixed: the same point while the yo-yo falls.
    assert!(
        (at_start[0].1 - later[0].1).length() < 1e-9,
        "the string's top moved: {} -> {}",
        at_start[0].1,
        later[0].1
    );
}

/// The answers of a_G and omega are negative (the yo-yo falls and turns clockwise): the question
/// a student reads says which way is positive, or "0.577" is graded wrong for a right magnitude.
#[test]
fn the_yoyo_questions_say_which_way_is_positive() {
    let scene = level::load(Path::new(LEVEL)).unwrap();
    let ask = |id: &str| {
        scene
            .level
            .questions
            .iter()
            .find(|q| q.id == id)
            .unwrap()
            .ask
            .to_lowercase()
    };
    assert!(ask("a_G").contains("up"), "{}", ask("a_G"));
    assert!(
        ask("omega_1s").contains("counterclockwise"),
        "{}",
        ask("omega_1s")
    );
}
