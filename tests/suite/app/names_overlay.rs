//! The names overlay (N, src/app/names.rs) on the library's busy levels, with the overlays a
//! student meets on opening a level (velocity, trails, magnitudes, names): every body and joint
//! the statement names is written once, beside its own body or anchor, off every body, off the
//! other labels and inside the view. Text sizes are estimated as in `label_placement.rs` (7.2 px
//! a character, 16 px a line), in the 650 x 762 px scene area of a 1280 x 800 window.

use bevy::math::{Rect, Vec2};
use rigidlab::app::draw::Drawing;
use rigidlab::app::labels::{self, overlap_area, rect_hits_polygon};
use rigidlab::app::overlays::{self, Overlays, Scales};
use rigidlab::app::view::{self, View};
use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

/// The cars in lanes and the four-bars: the scenes issue 42 found unlabelled.
const BUSY: &[&str] = &[
    "levels/impact/jh_P9.10.1_rear_end_collision.ron",
    "levels/kinematics/ha_relative_motion_cars_fragment.ron",
    "levels/kinematics/classic_four_bar.ron",
    "levels/virtual-work/zh_four_bar_inverse_dynamics.ron",
];

/// How far a name may sit from its body's edge or its joint's anchor and still be read as its
/// own, px: three label heights (the placer's spiral goes out four rings; a name pushed that far
/// would be beside a neighbour instead).
const NEAR_PX: f32 = 48.0;

/// A name: its text, the screen point it names and the body it belongs to (its screen corners,
/// empty for a joint).
struct Named {
    text: String,
    point: Vec2,
    body: Vec<Vec2>,
}

/// What [`drawn`] returns: the labels (text, rectangle), the things named, the bodies on screen
/// and the view.
type Drawn = (Vec<(String, Rect)>, Vec<Named>, Vec<Vec<Vec2>>, Rect);

/// The scene's area in a 1280 x 800 window (and page), px.
const SCENE_1280: Rect = Rect {
    min: Vec2::new(300.0, 0.0),
    max: Vec2::new(950.0, 762.0),
};

/// The level `file` after `steps` steps, drawn with the student's overlays and placed: the labels'
/// texts and rectangles, the things named, the bodies on screen and the view.
fn drawn(file: &Path, steps: usize) -> Drawn {
    drawn_in(file, steps, SCENE_1280)
}

/// [`drawn`] in a scene area `viewport` (a smaller window or page).
fn drawn_in(file: &Path, steps: usize, viewport: Rect) -> Drawn {
    let scene = level::load(file).unwrap();
    let mut phys = Run::new(scene.clone(), Options::default());
    for _ in 0..steps {
        phys.advance();
    }
    let mut v = View {
        viewport,
        ..Default::default()
    };
    v.fit_to(&view::motion_bounds(&scene, &Options::default()));
    let ov = Overlays::default();
    assert!(ov.names, "the names are on when a level opens");
    let outlines = view::body_outlines(&phys.sim.level);
    let mut d = crate::common::app::scene_drawing(&phys, &outlines, &v);
    let scales = Scales::of(phys.snapshot(), v.scene_size(), 1.0, v.m_per_px);
    overlays::build(&ov, &phys, &outlines, &scales, &mut d);
    let wants: Vec<labels::Want> = d
        .labels
        .iter()
        .map(|l| {
            let chars = l.text.lines().map(|s| s.chars().count()).max().unwrap_or(0);
            let lines = l.text.lines().count().max(1);
            rigidlab::app::label_want(l, Vec2::new(7.2 * chars as f32, 16.0 * lines as f32), &v)
        })
        .collect();
    let bodies = rigidlab::app::screen_bodies(&d, &v);
    let rects = labels::place(&wants, &bodies, v.viewport);
    let s = phys.snapshot();
    let mut named: Vec<Named> = s
        .bodies
        .iter()
        .zip(&outlines)
        .filter(|(_, o)| !o.filled.is_empty())
        .map(|(b, o)| Named {
            text: b.name.clone(),
            point: v.to_screen(b.com),
            body: o
                .filled
                .iter()
                .flatten()
                .map(|p| v.to_screen(b.world_point(*p)))
                .collect(),
        })
        .collect();
    // The joints' anchors from the level (the snapshot's joint states exist only after a step).
    let find = |name: &str| s.bodies.iter().position(|b| b.name == name).unwrap();
    named.extend(phys.sim.level.joints.iter().map(|j| Named {
        text: j.name.clone(),
        point: v.to_screen(s.bodies[find(&j.body2)].world_point(j.anchor2.into())),
        body: Vec::new(),
    }));
    let texts = d.labels.iter().map(|l| l.text.clone()).zip(rects).collect();
    (texts, named, bodies, v.viewport)
}

/// Distance from point `p` to rectangle `r`, px (0 inside).
fn gap(p: Vec2, r: &Rect) -> f32 {
    (p.clamp(r.min, r.max) - p).length()
}

#[test]
fn names_on_busy_levels_sit_beside_their_own_body_clear_of_the_rest() {
    for file in BUSY {
        for steps in [0, 120] {
            let (labels, named, bodies, view) = drawn(Path::new(file), steps);
            let at = format!("{file} after {steps} steps");
            assert!(named.len() >= 2, "{at}: nothing to name");
            for n in &named {
                let mine: Vec<&Rect> = labels
                    .iter()
                    .filter(|(t, _)| *t == n.text)
                    .map(|(_, r)| r)
                    .collect();
                assert_eq!(
                    mine.len(),
                    1,
                    "{at}: `{}` written {} times",
                    n.text,
                    mine.len()
                );
                let r = mine[0];
                // Beside its own thing: within NEAR_PX of the body's edge (its farthest corner
                // from G bounds the edge) or of the joint's anchor.
                let reach = n
                    .body
                    .iter()
                    .map(|c| (*c - n.point).length())
                    .fold(0.0, f32::max);
                let d = gap(n.point, r);
                assert!(
                    d <= reach + NEAR_PX,
                    "{at}: `{}` {d:.0} px from its point, its body reaches {reach:.0} px",
                    n.text
                );
                // Never on the body's own center, where it would hide G and the arrows.
                assert!(d > 0.0, "{at}: `{}` covers its own mass center", n.text);
                for b in &bodies {
                    assert!(
                        !rect_hits_polygon(r, b),
                        "{at}: `{}` at {r:?} lies on a body",
                        n.text
                    );
                }
            }
            for (k, (t, r)) in labels.iter().enumerate() {
                assert!(
                    view.contains(r.min) && view.contains(r.max),
                    "{at}: `{t}` at {r:?} leaves the view {view:?}"
                );
                for (u, q) in labels.iter().take(k) {
                    assert_eq!(overlap_area(r, q), 0.0, "{at}: `{u}` and `{t}` overlap");
                }
            }
        }
    }
}

/// The least distance from rectangle `r` to the corners of an outline on screen, px (0 inside
/// the rectangle). A disc's outline has 40 corners: its chords lie within r (1 - cos 4.5 deg),
/// 0.1 px for a 32 px ball, of its circle.
fn gap_to(r: &Rect, corners: &[Vec2]) -> f32 {
    corners
        .iter()
        .map(|c| gap(*c, r))
        .fold(f32::INFINITY, f32::min)
}

/// Newton's cradle: five balls touching in a row. Each ball's name is nearer its own ball than
/// any other, in the scene of a 1280 x 800 window or page and of a smaller one (1024 x 640,
/// the panels' widths kept), at the start (held there by predict first) and mid-swing. Before,
/// a name went away from the scene's middle, onto the next ball, and the placer moved it under
/// that ball: the page showed `ball3` under ball 4 and `ball4` under ball 5.
#[test]
fn names_in_a_row_of_touching_balls_sit_by_their_own_ball() {
    let file = Path::new("levels/impact/classic_newtons_cradle.ron");
    let small = Rect::new(300.0, 0.0, 694.0, 602.0);
    for viewport in [SCENE_1280, small] {
        for steps in [0, 1500] {
            let (labels, named, _, _) = drawn_in(file, steps, viewport);
            let balls: Vec<&Named> = named.iter().filter(|n| !n.body.is_empty()).collect();
            assert_eq!(balls.len(), 5, "five balls named");
            for n in &balls {
                let r = labels
                    .iter()
                    .find(|(t, _)| *t == n.text)
                    .map(|(_, r)| r)
                    .unwrap_or_else(|| panic!("`{}` not written", n.text));
                let own = gap_to(r, &n.body);
                for m in balls.iter().filter(|m| m.text != n.text) {
                    let other = gap_to(r, &m.body);
                    assert!(
                        own < other,
                        "{viewport:?} after {steps} steps: `{}` at {r:?} is {own:.1} px from its ball \
                         and {other:.1} px from {}",
                        n.text,
                        m.text
                    );
                }
            }
        }
    }
}

/// N turns the names off and leaves every other label where it was asked for.
#[test]
fn names_off_draws_no_name() {
    let file = Path::new("levels/kinematics/classic_four_bar.ron");
    let scene = level::load(file).unwrap();
    let phys = Run::new(scene.clone(), Options::default());
    let outlines = view::body_outlines(&phys.sim.level);
    let scales = Scales::of(phys.snapshot(), 1.0, 1.0, 0.001);
    let texts = |names: bool| {
        let ov = Overlays {
            names,
            ..Default::default()
        };
        let mut d = Drawing::default();
        d.clear(0.001);
        overlays::build(&ov, &phys, &outlines, &scales, &mut d);
        d.labels.into_iter().map(|l| l.text).collect::<Vec<_>>()
    };
    let (on, off) = (texts(true), texts(false));
    for name in ["crank", "coupler", "rocker", "O2", "A", "B", "O4"] {
        assert!(on.iter().any(|t| t == name), "`{name}` missing with N on");
        assert!(!off.iter().any(|t| t == name), "`{name}` drawn with N off");
    }
    // The ground is a point: named by its joints O2 and O4, not by a label of its own.
    assert!(!on.iter().any(|t| t == "ground"));
}
