//! Placing a body into a fixed one (issue 33): a disc clicked inside an incline's wedge is set
//! onto the slope, touching it; a box placed through a ground line is placed with a warning.

use rigidlab::editor::{self, Edit, NewShape};
use rigidlab::level::Shape;
use std::path::PathBuf;

fn scene_with_incline() -> rigidlab::level::Scene {
    let scene = editor::empty_scene(PathBuf::from("placement.ron"));
    editor::apply(
        &scene,
        &Edit::AddIncline {
            at: (-2.0, 0.0),
            angle: 30f64.to_radians(),
            length: 4.0,
        },
    )
    .unwrap()
    .0
}

#[test]
fn a_disc_placed_inside_an_incline_lands_on_its_slope() {
    let scene = scene_with_incline();
    let r = 0.2;
    // (0.5, 0.3) is inside the wedge: 0.3 m above its base, 0.99 m below the slope.
    let (scene, note) = editor::apply(
        &scene,
        &Edit::AddBody {
            shape: NewShape::Disc { radius: r },
            at: (0.5, 0.3),
            mass: 1.0,
        },
    )
    .unwrap();
    assert!(note.contains("onto incline1"), "{note}");
    let disc = scene
        .level
        .bodies
        .iter()
        .find(|b| b.name == "disc1")
        .unwrap();
    assert!(matches!(disc.shape, Some(Shape::Circle { .. })));
    // Expected: the click's foot on the slope line through (-2, 0) along u = (cos 30, sin 30),
    // then r along the outward normal n = (-sin 30, cos 30); the shortest move onto the slope.
    let t = 30f64.to_radians();
    let (u, n) = ((t.cos(), t.sin()), (-t.sin(), t.cos()));
    let s = (0.5 + 2.0) * u.0 + 0.3 * u.1;
    let want = (-2.0 + s * u.0 + r * n.0, s * u.1 + r * n.1);
    // 1e-9 m: plain arithmetic on numbers near 1.
    assert!(
        (disc.position.0 - want.0).abs() < 1e-9 && (disc.position.1 - want.1).abs() < 1e-9,
        "{:?} against {want:?}",
        disc.position
    );
    // Touching the slope: the center r from the slope's line, on its outer side.
    let d = (disc.position.0 + 2.0) * n.0 + disc.position.1 * n.1;
    assert!((d - r).abs() < 1e-9, "{d}");
}

#[test]
fn a_disc_clear_of_fixed_bodies_stays_where_it_was_put() {
    let scene = scene_with_incline();
    let (scene, note) = editor::apply(
        &scene,
        &Edit::AddBody {
            shape: NewShape::Disc { radius: 0.2 },
            at: (3.0, 1.0),
            mass: 1.0,
        },
    )
    .unwrap();
    assert!(!note.contains("onto"), "{note}");
    let disc = scene
        .level
        .bodies
        .iter()
        .find(|b| b.name == "disc1")
        .unwrap();
    assert_eq!(disc.position, (3.0, 1.0));
}

#[test]
fn a_disc_through_the_ground_line_sits_on_it_and_a_box_warns() {
    let scene = editor::empty_scene(PathBuf::from("placement.ron"));
    // The new scene's ground line is y = 0: a disc of 0.2 m at y = 0.05 goes up to y = 0.2.
    let (scene, note) = editor::apply(
        &scene,
        &Edit::AddBody {
            shape: NewShape::Disc { radius: 0.2 },
            at: (1.0, 0.05),
            mass: 1.0,
        },
    )
    .unwrap();
    assert!(note.contains("onto ground"), "{note}");
    let disc = scene
        .level
        .bodies
        .iter()
        .find(|b| b.name == "disc1")
        .unwrap();
    assert!((disc.position.1 - 0.2).abs() < 1e-12 && disc.position.0 == 1.0);
    let (_, note) = editor::apply(
        &scene,
        &Edit::AddBody {
            shape: NewShape::Box {
                width: 0.5,
                height: 0.2,
            },
            at: (-1.0, 0.05),
            mass: 1.0,
        },
    )
    .unwrap();
    assert!(note.contains("overlaps ground"), "{note}");
}
