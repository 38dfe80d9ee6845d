//! A challenge's goal is drawn as what it is (issue 42, the student trial of 2026-12-07: the
//! ball passed through the cup's drawing in `challenges/projectile_into_cup.ron`). A goal is a
//! region of the plane the run is judged on, not a body: nothing collides with it. So it is
//! drawn dashed (solid outlines are the bodies'), and no body of the level stands where it is,
//! for every challenge of the library.

use bevy::prelude::Color;
use glam::DVec2;
use rigidlab::app::draw::Prim;
use rigidlab::app::panels::challenge::goal_prims;
use rigidlab::level::{self, Goal, Region};
use std::path::PathBuf;

/// The library's challenges.
fn challenges() -> Vec<(PathBuf, level::Scene)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("levels/challenges");
    let files = level::collect_files(&[dir]).unwrap();
    assert!(files.len() >= 10, "{} challenges", files.len());
    files
        .into_iter()
        .map(|f| {
            let s = level::load(&f).unwrap_or_else(|e| panic!("{e}"));
            (f, s)
        })
        .collect()
}

/// A point of the goal: the point to reach, a region's centre.
fn goal_point(goal: &Goal) -> Option<DVec2> {
    match goal {
        Goal::Reaches { point, .. } => Some(DVec2::new(point.0, point.1)),
        Goal::EndsInside { region, .. } | Goal::StaysInside { region, .. } => Some(match *region {
            Region::Rect { min, max } => DVec2::new(min.0 + max.0, min.1 + max.1) / 2.0,
            Region::Circle { center, .. } | Region::Ring { center, .. } => {
                DVec2::new(center.0, center.1)
            }
        }),
        _ => None,
    }
}

#[test]
fn every_goal_is_drawn_dashed_and_no_body_stands_on_it() {
    let mut drawn_goals = 0;
    for (file, scene) in challenges() {
        let c = scene.level.challenge.as_ref().expect("a challenge");
        let mut prims = Vec::new();
        let named = goal_prims(&c.goal, Color::BLACK, &mut prims);
        if named.is_none() {
            continue;
        }
        drawn_goals += 1;
        for p in &prims {
            assert!(
                matches!(p, Prim::Line(..) | Prim::Dashed(..) | Prim::Dot(..)),
                "{}: the goal drawn as a solid outline, as a wall is: {p:?}",
                file.display()
            );
        }
        // Drawn dashed, with gaps: a circle is every other chord, not a closed ring.
        let lines = prims.iter().filter(|p| matches!(p, Prim::Line(..))).count();
        assert!(
            lines == 0 || lines % 12 == 0,
            "{}: {lines} chords",
            file.display()
        );
        // Nothing there to collide with: the goal's point lies inside no fixed body.
        let at = goal_point(&c.goal).unwrap();
        for b in &scene.level.bodies {
            if b.kind != level::BodyKind::Fixed {
                continue;
            }
            if let Some(shape) = &b.shape {
                let local =
                    DVec2::from_angle(-b.angle).rotate(at - DVec2::new(b.position.0, b.position.1));
                assert!(
                    !level::shape::Outline::of(shape).contains(local, 0.0),
                    "{}: the goal at {at:?} is inside the fixed body {}",
                    file.display(),
                    b.name
                );
            }
        }
    }
    // The regions and the points of the library (the cup among them); the readings draw none.
    assert!(drawn_goals >= 3, "{drawn_goals} goals drawn");
}
