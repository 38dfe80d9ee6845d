//! Where the kinetic diagram's copy of a body goes (src/app/overlays.rs, `free_side`), on the
//! library's levels at mid-run with velocity, the free-body and kinetic diagrams and magnitudes
//! on, in the 650 x 762 px scene area of a 1280 x 800 window: the labels (its own sums box
//! first) are kept off the copy (issue 42: the copy landed on other bodies, outside the view or
//! under its own sums box; the last is fixed, the first two are counted and printed). Text sizes are
//! estimated as in `label_placement.rs`.

use bevy::math::{Rect, Vec2};
use rigidlab::app::draw::{Drawing, Prim};
use rigidlab::app::labels::{self, rect_hits_polygon};
use rigidlab::app::overlays::{self, Overlays, Scales};
use rigidlab::app::view::{self, View};
use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::{Path, PathBuf};

/// The closed outlines a drawing holds, screen coordinates.
fn outlines_of(d: &Drawing, v: &View) -> Vec<Vec<Vec2>> {
    d.prims
        .iter()
        .filter_map(|p| match p {
            Prim::Poly(pts, true, _) => Some(pts.iter().map(|p| v.to_screen(*p)).collect()),
            _ => None,
        })
        .collect()
}

/// Counts on `file`: (copies, labels over a copy, copies over another body, copies leaving the
/// view).
fn counts(file: &Path) -> (usize, usize, usize, usize) {
    let scene = level::load(file).unwrap();
    let mut phys = Run::new(scene.clone(), Options::default());
    for _ in 0..(phys.sim.total_steps() / 2).min(600) {
        if !phys.advance() {
            break;
        }
    }
    let mut v = View {
        viewport: Rect::new(300.0, 0.0, 950.0, 762.0),
        ..Default::default()
    };
    v.fit_to(&view::motion_bounds(&scene, &Options::default()));
    let outlines = view::body_outlines(&phys.sim.level);
    let draw = |kinetic: bool| {
        let ov = Overlays {
            velocity: true,
            free_body: true,
            kinetic,
            labels: true,
            ..Default::default()
        };
        let mut d = crate::common::app::scene_drawing(&phys, &outlines, &v);
        let mut scales = Scales::of(phys.snapshot(), v.scene_size(), 1.0, v.m_per_px);
        let vp = v.viewport;
        let (a, b) = (
            v.to_world(Vec2::new(vp.min.x, vp.max.y)),
            v.to_world(Vec2::new(vp.max.x, vp.min.y)),
        );
        scales.visible = Some((a.min(b), a.max(b)));
        overlays::build(&ov, &phys, &outlines, &scales, &mut d);
        d
    };
    let (with, without) = (draw(true), draw(false));
    let scene_outlines = outlines_of(&without, &v);
    let copies: Vec<Vec<Vec2>> = outlines_of(&with, &v)
        .into_iter()
        .filter(|p| !scene_outlines.contains(p))
        .collect();
    let wants: Vec<labels::Want> = with
        .labels
        .iter()
        .map(|l| {
            let chars = l.text.lines().map(|s| s.chars().count()).max().unwrap_or(0);
            let lines = l.text.lines().count().max(1);
            rigidlab::app::label_want(l, Vec2::new(7.2 * chars as f32, 16.0 * lines as f32), &v)
        })
        .collect();
    let rects = labels::place(&wants, &rigidlab::app::screen_bodies(&with, &v), v.viewport);
    let on_copies = rects
        .iter()
        .filter(|r| copies.iter().any(|c| rect_hits_polygon(r, c)))
        .count();
    let bounds = |c: &[Vec2]| {
        let (lo, hi) = c.iter().fold(
            (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        Rect::from_corners(lo, hi)
    };
    let scene_bodies = rigidlab::app::screen_bodies(&without, &v);
    let over_bodies = copies
        .iter()
        .filter(|c| {
            let r = bounds(c).inflate(-1.0);
            scene_bodies.iter().any(|b| rect_hits_polygon(&r, b))
        })
        .count();
    let vp = v.viewport.inflate(1.0);
    let outside = copies
        .iter()
        .filter(|c| c.iter().any(|p| !vp.contains(*p)))
        .count();
    (copies.len(), on_copies, over_bodies, outside)
}

#[test]
fn labels_stay_off_the_kinetic_copy() {
    let mut files = level::collect_files(&[PathBuf::from("levels")]).unwrap();
    files.retain(|f| !f.starts_with("levels/stress"));
    let (mut copies, mut on_copies, mut over, mut outside) = (0, 0, 0, 0);
    for f in &files {
        let (c, l, b, o) = counts(f);
        if l + b + o > 0 {
            println!(
                "{}: {c} copies, {l} labels on them, {b} over bodies, {o} leave the view",
                f.display()
            );
        }
        copies += c;
        on_copies += l;
        over += b;
        outside += o;
    }
    println!(
        "{} levels: {copies} copy parts, {on_copies} labels over a copy, {over} copies over another body, {outside} leaving the view",
        files.len()
    );
    assert!(copies > 50, "too few copies to judge: {copies}");
    // Measured 2026-12-07 on 97 levels (132 copy parts): 190 labels over a copy while the label
    // placer did not know the copies, 11 once they are bodies to it (8 on
    // rubbing_discs_friction_work, whose discs and copies fill the view; one each on the two
    // struck bars and the two rotors, where no free spot lay within four label sizes). Held
    // there; the copies over other bodies (9) and leaving the view (5) are printed, not yet
    // fixed (free_side's four sides at one gap). On 110 levels (the challenges and three more
    // parameterized copies, 147 copy parts), 12: the struck bar's parameterized copy has the
    // struck bar's one.
    assert!(
        on_copies <= 12,
        "{on_copies} labels laid over a kinetic copy (12 on 110 levels, 2026-12-07)"
    );
}
