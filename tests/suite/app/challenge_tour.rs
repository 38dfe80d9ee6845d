//! The Challenge box and the first-steps tour never overlap at 1280x800 (issue 42, the student
//! trial of 2026-12-07): the box keeps off the tour's rect. Each of the library's challenges is
//! drawn with the tour open, between side panels at their default widths, in a bare egui
//! context of a 1280x800 screen.

use bevy_egui::egui;
use rigidlab::app::editor::Editor;
use rigidlab::app::overlays::Overlays;
use rigidlab::app::panels::challenge::{self, box_corner, BOX_SIZE};
use rigidlab::app::panels::tour::{self, Tour, TOUR_ID};
use rigidlab::app::panels::{Browser, Course};
use rigidlab::app::view::{motion_bounds, View};
use rigidlab::app::{LiveChecks, Run};
use rigidlab::sim::Options;
use std::path::Path;

use crate::common::app::{frames, SCREEN};

/// The tour's and the box's rects after a few frames of the level in `file`, the scene's
/// rect, and where the box's old rule (the corner farthest from the bodies, the tour aside)
/// put it.
fn drawn(file: &Path) -> (egui::Rect, egui::Rect, egui::Rect, egui::Rect) {
    let phys = Run::new(rigidlab::level::load(file).unwrap(), Options::default());
    let live = LiveChecks::new(&phys);
    let browser = Browser::default();
    let mut course = Course::default();
    let mut message = None;
    let mut t = Tour {
        open: true,
        ..Default::default()
    };
    let ctx = egui::Context::default();
    let mut scene = egui::Rect::NOTHING;
    let mut old_rule = egui::Pos2::ZERO;
    // Four frames: the windows settle where they go.
    frames(&ctx, SCREEN, vec![Vec::new(); 4], |ui| {
        egui::Panel::left("levels")
            .default_size(300.0)
            .show(ui, |ui| ui.label("levels"));
        egui::Panel::right("controls")
            .default_size(330.0)
            .show(ui, |ui| ui.label("controls"));
        egui::Panel::bottom("status").show(ui, |ui| ui.label("status"));
        scene = ui.available_rect_before_wrap();
        let mut view = View {
            viewport: bevy::math::Rect::new(scene.min.x, scene.min.y, scene.max.x, scene.max.y),
            ..View::default()
        };
        view.fit_to(&motion_bounds(&phys.scene, &Options::default()));
        let ctx = ui.ctx().clone();
        tour::tour(
            &ctx,
            scene,
            &mut t,
            &phys,
            &Overlays::default(),
            (false, false),
            &Editor::default(),
        );
        let bodies: Vec<egui::Pos2> = phys
            .snapshot()
            .bodies
            .iter()
            .map(|b| {
                let p = view.to_screen(b.com);
                egui::pos2(p.x, p.y)
            })
            .collect();
        old_rule = box_corner(scene, BOX_SIZE, &bodies);
        challenge::window(
            &ctx,
            (&phys, &browser, &view, true),
            (&live, &mut course, &mut message),
            scene,
        );
    });
    let rect = |id: egui::Id| {
        ctx.memory(|m| m.area_rect(id))
            .unwrap_or_else(|| panic!("{}: nothing drawn for {id:?}", file.display()))
    };
    (
        rect(egui::Id::new(TOUR_ID)),
        rect(challenge::window_id(&phys.scene.file)),
        scene,
        egui::Rect::from_min_size(old_rule, BOX_SIZE),
    )
}

#[test]
fn the_challenge_box_never_covers_the_tour_at_1280x800() {
    let files = crate::common::ron_files("levels/challenges", &[]);
    assert_eq!(files.len(), 10);
    let mut seen = None;
    for f in &files {
        let (tour, boxed, scene, old) = drawn(f);
        println!(
            "{}: tour {tour:?}, box {boxed:?}, the old rule's box {old:?}",
            f.display()
        );
        assert!(
            !boxed.intersects(tour),
            "{}: the box {boxed:?} covers the tour {tour:?}",
            f.display()
        );
        // Inside the scene, off the panels (a pixel for egui's rounding).
        assert!(
            scene.expand(1.0).contains_rect(boxed),
            "{}: the box {boxed:?} leaves the scene {scene:?}",
            f.display()
        );
        seen = Some((tour, scene));
    }
    // A tour grown over the corner the bodies leave free (the trial saw it drawn larger than
    // at its default size): the rule that ignores the tour takes that corner, the rule now
    // another one.
    let (_, scene) = seen.unwrap();
    let bodies = [scene.left_bottom() + egui::vec2(80.0, -80.0)];
    let old = egui::Rect::from_min_size(box_corner(scene, BOX_SIZE, &bodies), BOX_SIZE);
    let tour = old.expand(20.0);
    let now = egui::Rect::from_min_size(
        challenge::box_corner_avoiding(scene, BOX_SIZE, &bodies, &[tour]),
        BOX_SIZE,
    );
    assert!(!now.intersects(tour), "now {now:?}, tour {tour:?}");
}
