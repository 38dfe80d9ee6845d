//! A `Track` of pieces (docs/levels.md, "Shapes"; level/track.rs): validation refuses what cannot
//! be walked into a track, each error at the shape's file:line:col, naming the piece (from 1, in
//! the order written), with the fix; a good track is accepted, and the window draws it as a
//! one-sided track (level::shape::outline, which src/app draws).

use crate::common;

use common::parse;
use glam::DVec2;
use rigidlab::level::shape::outline;
use rigidlab::level::{self, LevelError};
use std::path::Path;

fn refuse(text: &str) -> LevelError {
    match level::parse(Path::new("test.ron"), text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

fn level_with(track: &str) -> String {
    format!(
        "Level(\n  title: \"t\",\n  effects: [gravity, contacts],\n  bodies: [\n    (name: \"ball\", shape: Circle(radius: 0.1), mass: 1.0, position: (0.0, 2.0)),\n    (name: \"track\", kind: fixed, shape: {track}),\n  ],\n)\n"
    )
}

#[test]
fn bad_tracks_are_refused_at_their_shape_naming_the_piece() {
    let cases = [
        (
            "Track(start: (0.0, 0.0), pieces: [Line(to: (1.0, 0.0)), Line(to: (1.0, 0.0))])",
            "track piece 2 (Line) has no length",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Line(to: (1.0, 0.0)), Arc(center: (1.0, 0.0), sweep: 1.0)])",
            "track piece 2 (Arc) has no length",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Line(to: (1.0, 0.0)), Turn(radius: 1.0, angle: 0.0)])",
            "track piece 2 (Turn) has no length",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Line(to: (1.0, NaN))])",
            "track piece 1 (Line): its to is not a finite number",
        ),
        (
            "Track(start: (0.0, inf), pieces: [Line(to: (1.0, 0.0))])",
            "the track's start is not a finite number",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Turn(radius: 1.0, angle: 1.0)])",
            "track piece 1 (Turn) has no heading",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Line(to: (2.0, 0.0)), Line(to: (1.0, 1.0)), Line(to: (1.0, -1.0))])",
            "crosses itself: track piece 1 (Line) meets track piece 3 (Line)",
        ),
        (
            // A loop turning a full 2 pi from the floor's end meets the floor again.
            "Track(start: (0.0, 0.0), pieces: [Line(to: (2.0, 0.0)), Arc(center: (2.0, 1.0), sweep: 5.5), Line(to: (3.0, 1.0))])",
            "crosses itself",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Line(to: (2.0, 0.0)), Line(to: (1.0, 0.0))])",
            "track piece 2 (Line) folds back on track piece 1 (Line)",
        ),
        (
            "Track(start: (0.0, 0.0), pieces: [Arc(center: (0.0, 1.0), sweep: 7.0)])",
            "a whole turn",
        ),
        ("Track(start: (0.0, 0.0), pieces: [])", "at least one piece"),
    ];
    for (track, message) in cases {
        let text = level_with(track);
        let e = refuse(&text);
        let shape = text.find("shape: Track").unwrap();
        let line = text[..shape].matches('\n').count() + 1;
        let col = shape - text[..shape].rfind('\n').unwrap();
        assert_eq!((e.line, e.col), (line, col), "not at the shape: {e}");
        assert!(e.message.contains(message), "{track}: {e}");
        assert!(!e.help.is_empty(), "no fix: {e}");
    }
}

/// The n15 ramp, floor and loop as one track is accepted, and drawn as one-sided segments
/// hatched on the ground's side: below the floor (normal -y on the floor's segments).
#[test]
fn a_ramp_floor_and_loop_is_drawn_with_its_ground() {
    let track = "Track(start: (-2.0, 2.0), pieces: [Arc(center: (0.0, 2.0), sweep: 1.5707963267948966), Line(to: (1.0, 0.0)), Arc(center: (1.0, 0.6), sweep: 4.71238898038469)])";
    let scene = parse(&level_with(track));
    let o = outline(scene.level.bodies[1].shape.as_ref().unwrap());
    // Drawn in pieces of at most 2 degrees: 45 on the ramp, 1 floor, 135 on the loop.
    assert_eq!(o.segments.len(), 45 + 1 + 135);
    assert_eq!(o.solid_side.len(), o.segments.len());
    let floor = o
        .segments
        .iter()
        .position(|(a, b)| a.y.abs() < 1e-12 && b.y.abs() < 1e-12 && (b.x - a.x) > 0.5)
        .expect("the floor's segment");
    let (_, n) = o.solid_side.iter().find(|(k, _)| *k == floor).unwrap();
    assert!((*n - DVec2::new(0.0, -1.0)).length() < 1e-12, "{n}");
}
