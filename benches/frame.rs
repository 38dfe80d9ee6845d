//! Frame time of the sandbox without rendering, at 1000 bodies: physics step, checks, the
//! analysis the overlays need, the line drawing with every overlay on, and its gizmo vertices.
//!
//! `cargo bench --bench frame` (needs the `app` feature). Prints medians over the measured frames
//! (this machine is noisy: medians, not means) against the 8 ms goal.
//!
//! Scene: 1000 discs (r = 5 cm, 40 x 25 grid) dropped into a 10 m wide box with gravity, contacts
//! and friction, dt = 1/60 s, 4 substeps; frames 60..360 are measured, while the pile forms.

use bevy::gizmos::config::DefaultGizmoConfigGroup;
use bevy::gizmos::gizmos::GizmoBuffer;
use bevy::prelude::{Rect, Vec2};
use rigidlab::analysis::energy;
use rigidlab::analysis::momentum::scene_angular_momentum_about;
use rigidlab::app::draw::{self, Drawing};
use rigidlab::app::overlays::{self, Overlays, Scales};
use rigidlab::app::physics::LiveChecks;
use rigidlab::app::quantities;
use rigidlab::app::run::Run;
use rigidlab::app::scene_lines;
use rigidlab::app::view::{self, SceneIndex, View};
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;
use std::time::Instant;

const BODIES: usize = 1000;
const WARMUP: usize = 60;
const FRAMES: usize = 300;
const GOAL_MS: f64 = 8.0;

fn scene() -> level::Scene {
    let mut bodies = String::new();
    bodies += "(name: \"floor\", kind: fixed, shape: Segment(a: (-5.0, 0.0), b: (5.0, 0.0))),\n";
    bodies += "(name: \"left\", kind: fixed, shape: Segment(a: (-5.0, 0.0), b: (-5.0, 12.0))),\n";
    bodies += "(name: \"right\", kind: fixed, shape: Segment(a: (5.0, 0.0), b: (5.0, 12.0))),\n";
    for k in 0..BODIES {
        let (i, j) = (k % 40, k / 40);
        // Staggered rows so the discs do not stack in columns.
        let x = -4.4 + 0.22 * i as f64 + if j % 2 == 1 { 0.08 } else { 0.0 };
        let y = 0.3 + 0.22 * j as f64;
        bodies += &format!("(name: \"d{k}\", shape: Circle(radius: 0.05), position: ({x}, {y}), density: 500.0, friction: 0.4),\n");
    }
    let text = format!(
        "Level(title: \"{BODIES} discs in a box\", effects: [gravity, contacts, friction],\n\
         world: (dt: 0.016666666666666666, substeps: 4, duration: 10.0),\nbodies: [\n{bodies}])"
    );
    level::parse(Path::new("bench-frame.ron"), &text).expect("the bench level is valid")
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let scene = scene();
    // The run alone: stopping at the level's end is `Playback`'s, which the bench leaves out.
    let mut phys = Run::new(scene.clone(), Options::default());
    let mut live = LiveChecks::new(&phys);
    let outlines = view::body_outlines(&phys.sim.level);
    let index = SceneIndex::of(&phys.sim.level);
    let mut view = View {
        viewport: Rect::new(0.0, 0.0, 1100.0, 800.0),
        ..Default::default()
    };
    let bounds = view::motion_bounds(&scene, &Options::default());
    view.bounds = bounds;
    view.fit_to(&bounds);
    // The visible world rectangle, as the window computes it each frame (the view does not move).
    let visible = {
        let vp = view.viewport;
        let (a, b) = (
            view.to_world(Vec2::new(vp.min.x, vp.max.y)),
            view.to_world(Vec2::new(vp.max.x, vp.min.y)),
        );
        (a.min(b), a.max(b))
    };
    // Every overlay on; the diagrams are about one body in the middle of the pile.
    let ov = Overlays {
        velocity: true,
        acceleration: true,
        instant_center: true,
        free_body: true,
        kinetic: true,
        momentum: true,
        trails: true,
        labels: true,
        selected: Some(3 + BODIES / 2),
        point: Some((3 + BODIES / 2, glam::DVec2::new(0.03, 0.0))),
        origin: glam::DVec2::ZERO,
        // The arrow scale, hidden forces and components at the window's defaults.
        ..Default::default()
    };
    let mut drawing = Drawing::default();
    let mut gizmos = GizmoBuffer::<DefaultGizmoConfigGroup, ()>::new();
    let (mut step, mut checks, mut analysis, mut lines, mut verts, mut total) = (
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
    );
    let mut max_speed: f64 = 0.0;
    let mut sink = 0.0;
    for frame in 0..WARMUP + FRAMES {
        let t0 = Instant::now();
        assert!(phys.advance(), "the bench scene exploded: {:?}", phys.error);
        let t1 = Instant::now();
        live.observe(&phys);
        let t2 = Instant::now();
        // The analysis behind the overlays, for every body: accelerations, instantaneous centers,
        // energy and momentum; the free-body diagram of the selected body.
        let s = phys.snapshot();
        if let Some((prev, dt)) = &phys.prev_velocities {
            let acc = quantities::accelerations(s, prev, *dt);
            sink += acc.iter().map(|(a, _)| a.x).sum::<f64>();
        }
        for b in &s.bodies {
            if let Some(c) = quantities::instant_center(b, 0.05) {
                sink += c.x;
            }
            max_speed = max_speed.max(b.velocity.length());
        }
        sink += energy::system_kinetic_energy(s, energy::engine_mass)
            + energy::system_gravity_potential(s, energy::engine_mass);
        sink += scene_angular_momentum_about(s, glam::DVec2::ZERO);
        sink += quantities::free_body_arrows(None, s, ov.selected.unwrap()).1;
        let t3 = Instant::now();
        // As the window draws a frame: app::scene::build_drawing, one system per overlay
        // (app/overlay_systems.rs, the order of overlays::build), the scale bar.
        drawing.clear(view.m_per_px);
        scene_lines::scene_lines(
            &phys.sim.level,
            &outlines,
            &index,
            s,
            view.m_per_px,
            &mut drawing,
        );
        if let Some(i) = ov.selected {
            scene_lines::highlight(&outlines, s, i, &mut drawing);
        }
        let mut scales = Scales::of(s, view.scene_size(), max_speed, view.m_per_px);
        scales.gain = ov.arrow_scale;
        scales.visible = Some(visible);
        overlays::build(&ov, &phys, &outlines, &scales, &mut drawing);
        scene_lines::scale_bar(&view, &mut drawing);
        let t4 = Instant::now();
        gizmos.list_positions.clear();
        gizmos.list_colors.clear();
        gizmos.strip_positions.clear();
        gizmos.strip_colors.clear();
        draw::emit(&drawing, &mut gizmos);
        let t5 = Instant::now();
        if frame >= WARMUP {
            let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
            step.push(ms(t0, t1));
            checks.push(ms(t1, t2));
            analysis.push(ms(t2, t3));
            lines.push(ms(t3, t4));
            verts.push(ms(t4, t5));
            total.push(ms(t0, t5));
        }
    }
    let s = phys.snapshot();
    println!(
        "frame: {BODIES} discs, {} contact manifolds at the end, {} line primitives, {} labels, {} gizmo vertices",
        s.contacts.len(),
        drawing.prims.len(),
        drawing.labels.len(),
        gizmos.list_positions.len() + gizmos.strip_positions.len()
    );
    println!(
        "median over frames {WARMUP}..{} (ms per frame):",
        WARMUP + FRAMES
    );
    for (name, v) in [
        ("physics step (rapier + snapshot + records)", &mut step),
        ("checks and questions", &mut checks),
        ("analysis (a_G, IC, T, V, H_O, free body)", &mut analysis),
        ("drawing: bodies + every overlay", &mut lines),
        ("gizmo vertices", &mut verts),
    ] {
        println!("  {name:<44} {:>8.3}", median(v));
    }
    let m = median(&mut total);
    println!(
        "  {:<44} {:>8.3}   goal <= {GOAL_MS} ms: {} ({:.2} of the budget)",
        "total (excluding rendering)",
        m,
        if m <= GOAL_MS { "met" } else { "NOT met" },
        m / GOAL_MS
    );
    std::hint::black_box(sink);
}
