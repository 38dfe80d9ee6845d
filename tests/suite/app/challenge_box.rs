//! Where the Challenge box opens (`panels::challenge::box_corner`): the scene's corner farthest
//! from the bodies. Always at the top-left it hid the cylinder of "leave at 30 degrees" and the
//! Atwood challenge's pulley (the student trial of 2026-12-07).

use bevy_egui::egui;
use rigidlab::app::panels::challenge::{box_corner, BOX_SIZE};

fn scene() -> egui::Rect {
    // The scene between the panels of a 1280x800 window.
    egui::Rect::from_min_max(egui::pos2(320.0, 30.0), egui::pos2(930.0, 710.0))
}

#[test]
fn the_box_opens_in_the_corner_farthest_from_the_bodies() {
    let s = scene();
    // A cylinder and a puck up left (as "leave at 30 degrees" is drawn): not the top-left.
    let up_left = [egui::pos2(430.0, 150.0), egui::pos2(470.0, 90.0)];
    let at = box_corner(s, BOX_SIZE, &up_left);
    let r = egui::Rect::from_min_size(at, BOX_SIZE);
    for b in up_left {
        assert!(!r.contains(b), "the box at {at:?} covers the body at {b:?}");
    }
    assert!(
        at.x > 600.0 || at.y > 400.0,
        "the box stayed up left: {at:?}"
    );
    // Bodies down the middle and the right: the top-left corner, which is clear.
    let right = [
        egui::pos2(800.0, 150.0),
        egui::pos2(620.0, 600.0),
        egui::pos2(880.0, 650.0),
    ];
    let at = box_corner(s, BOX_SIZE, &right);
    assert_eq!(at, s.left_top() + egui::vec2(12.0, 12.0));
    // Every corner's box stays inside the scene.
    for bodies in [&up_left[..], &right[..], &[]] {
        let r = egui::Rect::from_min_size(box_corner(s, BOX_SIZE, bodies), BOX_SIZE);
        assert!(s.contains_rect(r), "{r:?} leaves the scene {s:?}");
    }
}
