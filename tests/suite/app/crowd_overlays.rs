//! A crowd's overlays (src/app/overlays.rs, `crowd`): above `CROWD_BODIES` moving bodies the
//! trails and the velocity and acceleration arrows are the selected body's only (every body's
//! with the panel's box), and the window says so; at `CROWD_BODIES` or fewer every moving body
//! keeps them. And the label placer given only the bodies within its labels' reach
//! (`labels::reach`, `app::screen_bodies_within`) places every label where it places it given
//! them all.

use bevy::math::{Rect, Vec2};
use rigidlab::app::ball_meshes::CROWD_BODIES;
use rigidlab::app::draw::{Drawing, Prim};
use rigidlab::app::labels;
use rigidlab::app::overlays::{self, Overlays, Scales};
use rigidlab::app::view::{self, palette, View};
use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

/// `n` discs (r = 5 cm) falling onto a floor in rows of 20, after `steps` steps, and the view
/// the tests draw in: the motion bounds fitted into 1100 x 800 px.
fn discs(n: usize, steps: usize) -> (Run, View) {
    let mut bodies = String::from(
        "(name: \"floor\", kind: fixed, shape: Segment(a: (-3.0, 0.0), b: (3.0, 0.0))),\n",
    );
    for k in 0..n {
        let (x, y) = (-2.0 + 0.2 * (k % 20) as f64, 0.3 + 0.2 * (k / 20) as f64);
        bodies +=
            &format!("(name: \"d{k}\", shape: Circle(radius: 0.05), position: ({x}, {y})),\n");
    }
    let text = format!(
        "Level(title: \"{n} discs\", effects: [gravity, contacts, friction],\n\
         world: (dt: 0.016666666666666666, substeps: 4, duration: 1.0),\nbodies: [\n{bodies}])"
    );
    let scene = level::parse(Path::new("crowd-overlays.ron"), &text).expect("valid level");
    let mut v = View {
        viewport: Rect::new(0.0, 0.0, 1100.0, 800.0),
        ..Default::default()
    };
    v.fit_to(&view::motion_bounds(&scene, &Options::default()));
    let mut run = Run::new(scene, Options::default());
    for _ in 0..steps {
        assert!(run.advance(), "{:?}", run.error);
    }
    (run, v)
}

/// The overlays of `run` drawn with `ov` (scene lines included: the label placer keeps off the
/// bodies they push).
fn draw(run: &Run, ov: &Overlays, v: &View) -> Drawing {
    let outlines = view::body_outlines(&run.sim.level);
    let mut d = crate::common::app::scene_drawing(run, &outlines, v);
    let scales = Scales::of(run.snapshot(), v.scene_size(), 1.0, v.m_per_px);
    overlays::build(ov, run, &outlines, &scales, &mut d);
    d
}

/// (velocity arrows, acceleration arrows, trails) in `d`.
fn per_body(d: &Drawing) -> (usize, usize, usize) {
    let count = |want: fn(&Prim) -> bool| d.prims.iter().filter(|p| want(p)).count();
    (
        count(|p| matches!(p, Prim::Arrow(_, _, c) if *c == palette::VELOCITY)),
        count(|p| matches!(p, Prim::Arrow(_, _, c) if *c == palette::ACCEL)),
        count(|p| matches!(p, Prim::Poly(_, false, c) if *c == palette::TRAIL)),
    )
}

fn per_body_on() -> Overlays {
    Overlays {
        velocity: true,
        acceleration: true,
        trails: true,
        labels: true,
        names: false,
        ..Default::default()
    }
}

#[test]
fn a_crowd_draws_trails_and_arrows_for_the_selected_body_only() {
    // 20 steps: every disc is falling (a trail of more than one point, a nonzero velocity).
    let (run, v) = discs(CROWD_BODIES + 1, 20);
    let n = CROWD_BODIES + 1;
    let ov = per_body_on();
    assert_eq!(overlays::crowd(run.snapshot()), Some(n));
    assert_eq!(per_body(&draw(&run, &ov, &v)), (0, 0, 0), "none selected");
    let note = overlays::crowd_note(&ov, run.snapshot()).expect("the window says why");
    assert!(note.contains(&n.to_string()), "{note}");
    // Body 0 is the floor: select a disc.
    let selected = Overlays {
        selected: Some(5),
        ..per_body_on()
    };
    assert_eq!(per_body(&draw(&run, &selected, &v)), (1, 1, 1));
    let floor = Overlays {
        selected: Some(0),
        ..per_body_on()
    };
    assert_eq!(
        per_body(&draw(&run, &floor, &v)),
        (0, 0, 0),
        "a fixed body moves not"
    );
    // So with the floor selected the note still asks for a moving body, as with none.
    let asks = overlays::crowd_note(&floor, run.snapshot()).expect("the window says why");
    assert!(asks.contains("click a moving body"), "{asks}");
    let told = overlays::crowd_note(&selected, run.snapshot()).expect("the window says why");
    assert!(told.contains("the selected body only"), "{told}");
    let every = Overlays {
        every_body: true,
        ..per_body_on()
    };
    assert_eq!(
        per_body(&draw(&run, &every, &v)),
        (n, n, n),
        "the panel's box"
    );
    assert_eq!(overlays::crowd_note(&every, run.snapshot()), None);
}

#[test]
fn a_scene_of_crowd_bodies_or_fewer_draws_them_for_every_body() {
    let (run, v) = discs(CROWD_BODIES, 20);
    let ov = per_body_on();
    assert_eq!(overlays::crowd(run.snapshot()), None);
    assert_eq!(overlays::crowd_note(&ov, run.snapshot()), None);
    let n = CROWD_BODIES;
    assert_eq!(per_body(&draw(&run, &ov, &v)), (n, n, n));
}

#[test]
fn labels_placed_among_the_bodies_in_their_reach_are_placed_as_among_all() {
    // A settled heap of 400 discs, one in its middle selected with every diagram and its
    // magnitudes: its labels' spots lie on the heap, where the placer must dodge the discs.
    let (run, v) = discs(400, 90);
    let ov = Overlays {
        free_body: true,
        kinetic: true,
        instant_center: true,
        selected: Some(210),
        ..per_body_on()
    };
    let d = draw(&run, &ov, &v);
    let wants: Vec<labels::Want> = d
        .labels
        .iter()
        .map(|l| rigidlab::app::label_want(l, Vec2::new(7.0 * l.text.len() as f32, 16.0), &v))
        .collect();
    assert!(wants.len() >= 3, "{} labels", wants.len());
    let all = rigidlab::app::screen_bodies(&d, &v);
    let mut previous: Vec<(Vec2, Rect)> = Vec::new();
    for frame in 0..2 {
        let reach = labels::reach(&wants, v.viewport, &previous);
        let near = rigidlab::app::screen_bodies_within(&d, &v, &reach);
        assert!(
            near.len() < all.len() && !near.is_empty(),
            "{} of {} bodies in reach",
            near.len(),
            all.len()
        );
        let whole = labels::place_keeping(&wants, &all, v.viewport, &previous);
        let culled = labels::place_keeping(&wants, &near, v.viewport, &previous);
        assert_eq!(whole, culled, "frame {frame}");
        // The second frame keeps the first one's places (the hysteresis path).
        previous = wants.iter().map(|w| w.home).zip(whole).collect();
    }
}
