//! Frame time of the sandbox without rendering, at 1,000 and at 10,000 bodies: physics step,
//! checks, the analysis the overlays need, the line drawing with every overlay on, its gizmo
//! vertices, the labels' placement, and the meshes' poses (a crowd's balls are drawn whole by
//! shared meshes, app/ball_meshes.rs, moved by their poses). Both scenes are crowds (more than
//! 64 moving bodies): the trails and arrows are the selected body's (`overlays::crowd`); the
//! cost of the panel's box that draws them on every body is printed beside, for information.
//!
//! `cargo bench --bench frame` (needs the `app` feature). Prints medians over the measured frames
//! (this machine is noisy: medians, not means) against each scene's goal, and the physics step's
//! share of the frame; and, stepped beside it every frame in the same run, rapier's plain step
//! (`PhysicsWorld::step`) on a second copy of the same world, which the frame cannot beat
//! (`--bench runner` compares rigidlab's stepping with it in interleaved blocks).
//! `cargo bench --bench frame -- 1000`, `-- 10000` or `-- dominoes` runs one scene.
//!
//! Scenes, all with gravity, contacts and friction, dt = 1/60 s, 4 substeps; frames 60..360 are
//! measured, while the pile forms and settles:
//! - 1,000 discs (r = 5 cm, 40 x 25 grid) dropped into a 10 m wide box; goal 8 ms (issue 15);
//! - levels/stress/sand_pile.ron: 10,000 grains (discs, r = 5 cm, 250 x 40 grid) dropped into a
//!   30 m bin; goal 16 ms, a 60 Hz frame (issue 45);
//! - levels/stress/domino_field.ron: 10,000 dominoes (5 cm x 1 cm) in 50 rows on shelves, the
//!   first of each row pushed, `sleeping` declared; frames 150..450 (2.5 s to 7.5 s) while the
//!   waves run; goal 16 ms (issue 45). `cargo bench --bench frame -- dominoes` runs it alone.

use bevy::gizmos::config::DefaultGizmoConfigGroup;
use bevy::gizmos::gizmos::GizmoBuffer;
use bevy::prelude::{Rect, Vec2};
use rigidlab::analysis::energy;
use rigidlab::analysis::momentum::scene_angular_momentum_about;
use rigidlab::app::draw::{self, Drawing};
use rigidlab::app::label_want;
use rigidlab::app::labels;
use rigidlab::app::overlays::{self, Overlays, Scales};
use rigidlab::app::physics::LiveChecks;
use rigidlab::app::quantities;
use rigidlab::app::run::Run;
use rigidlab::app::scene_lines;
use rigidlab::app::view::{self, SceneIndex, View};
use rigidlab::level;
use rigidlab::sim::{Options, Simulation};
use std::path::Path;
use std::time::Instant;

/// A moment of the frame: the wall clock and this thread's CPU time.
#[derive(Clone, Copy)]
struct Mark {
    wall: Instant,
    cpu_ns: Option<u64>,
}

/// Now. On Linux also the thread's CPU time (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, which
/// the C library std links already provides): on this shared 2-core machine another helper's
/// build takes the CPU away in the middle of a phase, and the wall clock then charges the phase
/// for it; the CPU time does not. Elsewhere only the wall clock.
fn mark() -> Mark {
    Mark {
        wall: Instant::now(),
        cpu_ns: thread_cpu_ns(),
    }
}

#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
fn thread_cpu_ns() -> Option<u64> {
    #[repr(C)]
    struct Timespec {
        tv_sec: i64,
        tv_nsec: i64,
    }
    unsafe extern "C" {
        fn clock_gettime(clock: i32, tp: *mut Timespec) -> i32;
    }
    // CLOCK_THREAD_CPUTIME_ID in linux/time.h.
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut t = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec of the C layout on 64-bit Linux.
    let ok = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0;
    ok.then(|| t.tv_sec as u64 * 1_000_000_000 + t.tv_nsec as u64)
}

#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn thread_cpu_ns() -> Option<u64> {
    None
}

/// Milliseconds from `a` to `b`: CPU time where both have it, else wall time.
fn ms(a: Mark, b: Mark) -> f64 {
    match (a.cpu_ns, b.cpu_ns) {
        (Some(x), Some(y)) => y.saturating_sub(x) as f64 * 1e-6,
        _ => (b.wall - a.wall).as_secs_f64() * 1e3,
    }
}

const BODIES: usize = 1000;
const WARMUP: usize = 60;
const FRAMES: usize = 300;
const GOAL_MS: f64 = 8.0;
/// The 10,000-body scene and its goal: a frame at 60 Hz.
const STRESS_LEVEL: &str = "levels/stress/sand_pile.ron";
const STRESS_GOAL_MS: f64 = 16.0;
/// The other 10,000-body scene, and the frames measured there: from 2.5 s, when the dominoes
/// the wave has not reached are asleep (rapier puts a body to sleep after 0.5 s still), to
/// 7.5 s, while the wave runs (it reaches the rows' ends at 10.6 s). The fallen dominoes stay
/// awake with their row's front (rapier sleeps an island whole): about 2,400 bodies move at
/// 2.5 s, 7,100 at 7.5 s.
const DOMINO_LEVEL: &str = "levels/stress/domino_field.ron";
const DOMINO_WARMUP: usize = 150;
const DOMINO_FRAMES: usize = 300;
/// What the drawing may take of a frame (issue 45: the 10,000-body frame's drawing and gizmo
/// vertices within 3 ms, leaving the rest of the 16 ms to the physics; the labels' placement,
/// timed since 2026-12-07, counts in it too).
const DRAW_GOAL_MS: f64 = 3.0;

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
    // `cargo bench` passes `--bench`; a number picks one scene by its body count, `dominoes` the
    // domino field.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let only: Option<usize> = args.iter().find_map(|a| a.parse().ok());
    let dominoes = args.iter().any(|a| a == "dominoes");
    let all = only.is_none() && !dominoes;
    if all || only == Some(BODIES) {
        measure(scene(), GOAL_MS, WARMUP, FRAMES);
    }
    if all || only == Some(10_000) {
        let stress = level::load(Path::new(STRESS_LEVEL)).unwrap_or_else(|e| panic!("{e}"));
        measure(stress, STRESS_GOAL_MS, WARMUP, FRAMES);
    }
    if all || dominoes {
        let field = level::load(Path::new(DOMINO_LEVEL)).unwrap_or_else(|e| panic!("{e}"));
        measure(field, STRESS_GOAL_MS, DOMINO_WARMUP, DOMINO_FRAMES);
    }
}

/// Runs `scene` for WARMUP + FRAMES frames as the window does, every overlay on, and prints the
/// medians of each phase against `goal_ms`.
// One frame's phases in order, each timed, then the table: splitting it would hide the order.
#[allow(clippy::too_many_lines)]
fn measure(scene: level::Scene, goal_ms: f64, warmup: usize, frames: usize) {
    let dynamic = scene
        .level
        .bodies
        .iter()
        .filter(|b| b.kind == level::BodyKind::Dynamic)
        .count();
    // The diagrams are about one body in the middle of the pile (the fixed bodies come first).
    let middle = scene.level.bodies.len() - dynamic + dynamic / 2;
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
        selected: Some(middle),
        point: Some((middle, glam::DVec2::new(0.03, 0.0))),
        origin: glam::DVec2::ZERO,
        // The arrow scale, hidden forces and components at the window's defaults.
        ..Default::default()
    };
    // The meshes' poses, as `view::sync_meshes` moves them each frame (a crowd's balls are
    // drawn whole by their meshes, app/ball_meshes.rs).
    let mut poses = vec![bevy::prelude::Transform::default(); scene.level.bodies.len()];
    // rapier's plain step on the same world, stepped beside the run each frame (not in the
    // frame's total): what the physics step costs without rigidlab around it.
    let mut plain = Simulation::new(&scene, &Options::default());
    let mut drawing = Drawing::default();
    let mut gizmos = GizmoBuffer::<DefaultGizmoConfigGroup, ()>::new();
    let (mut step, mut checks, mut analysis, mut lines, mut verts, mut meshes, mut total) = (
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
    );
    let (mut rapier, mut wall, mut every, mut placing) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    // The panel's box: trails and arrows on every body of the crowd.
    let ov_every = Overlays {
        every_body: true,
        ..ov.clone()
    };
    let mut drawing_every = Drawing::default();
    let mut gizmos_every = GizmoBuffer::<DefaultGizmoConfigGroup, ()>::new();
    let (mut last, mut last_every) = (Vec::new(), Vec::new());
    let mut near = 0;
    // Bodies moving in each measured frame (a sleeping body's velocities are zero): the crowd
    // the physics step works on, a domino field's wave fronts.
    let mut moving = Vec::new();
    let mut max_speed: f64 = 0.0;
    let mut sink = 0.0;
    for frame in 0..warmup + frames {
        let t0 = mark();
        assert!(phys.advance(), "the bench scene exploded: {:?}", phys.error);
        let t1 = mark();
        live.observe(&phys);
        let t2 = mark();
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
        let t3 = mark();
        // As the window draws a frame: app::scene::build_drawing, one system per overlay
        // (app/overlay_systems.rs, the order of overlays::build), the scale bar.
        let lines_of = Lines {
            phys: &phys,
            outlines: &outlines,
            ov: &ov,
            view: &view,
            visible,
            max_speed,
        };
        lines_of.build(&index, &mut drawing);
        let t4 = mark();
        emit_anew(&drawing, &mut gizmos);
        let t5 = mark();
        near = place_labels(&drawing, &view, &mut last);
        let t5b = mark();
        for (b, t) in s.bodies.iter().zip(poses.iter_mut()) {
            view::place_mesh(b, t);
        }
        let t6 = mark();
        plain.world.step();
        let t7 = mark();
        // For information, the panel's box: every body's trails and arrows.
        Lines {
            ov: &ov_every,
            ..lines_of
        }
        .build(&index, &mut drawing_every);
        emit_anew(&drawing_every, &mut gizmos_every);
        place_labels(&drawing_every, &view, &mut last_every);
        let t8 = mark();
        if frame >= warmup {
            wall.push((t6.wall - t0.wall).as_secs_f64() * 1e3);
            step.push(ms(t0, t1));
            checks.push(ms(t1, t2));
            analysis.push(ms(t2, t3));
            lines.push(ms(t3, t4));
            verts.push(ms(t4, t5));
            placing.push(ms(t5, t5b));
            meshes.push(ms(t5b, t6));
            total.push(ms(t0, t6));
            rapier.push(ms(t6, t7));
            every.push(ms(t7, t8));
            moving.push(
                s.bodies
                    .iter()
                    .filter(|b| b.velocity != glam::DVec2::ZERO || b.omega != 0.0)
                    .count() as f64,
            );
        }
    }
    std::hint::black_box(&poses);
    let s = phys.snapshot();
    println!(
        "frame: {} ({dynamic} moving bodies), {} contact manifolds at the end, {} line primitives, {} labels ({near} bodies in their reach), {} gizmo vertices",
        scene.level.title,
        s.contacts.len(),
        drawing.prims.len(),
        drawing.labels.len(),
        gizmos.list_positions.len() + gizmos.strip_positions.len()
    );
    println!(
        "median over frames {warmup}..{} (ms per frame, {}; load average {}):",
        warmup + frames,
        if mark().cpu_ns.is_some() {
            "the thread's CPU time"
        } else {
            "wall clock"
        },
        std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|l| l.split_whitespace().next().map(str::to_string))
            .unwrap_or_else(|| "unknown".into())
    );
    println!(
        "  bodies moving in a frame: median {:.0}, most {:.0} (sleeping ones still)",
        median(&mut moving),
        moving.last().copied().unwrap_or(0.0)
    );
    let physics = median(&mut step);
    println!(
        "  {:<44} {:>8.3}",
        "physics step (rapier + snapshot + records)", physics
    );
    for (name, v) in [
        ("checks and questions", &mut checks),
        ("analysis (a_G, IC, T, V, H_O, free body)", &mut analysis),
        ("drawing: bodies + every overlay", &mut lines),
        ("gizmo vertices", &mut verts),
        ("label placement (sizes estimated)", &mut placing),
        ("mesh poses", &mut meshes),
    ] {
        println!("  {name:<44} {:>8.3}", median(v));
    }
    let drawn = median(&mut lines) + median(&mut verts) + median(&mut placing);
    println!(
        "  {:<44} {:>8.3}   goal <= {DRAW_GOAL_MS} ms: {}",
        "drawing + gizmo vertices + labels",
        drawn,
        if drawn <= DRAW_GOAL_MS {
            "met"
        } else {
            "NOT met"
        }
    );
    let m = median(&mut total);
    println!(
        "  {:<44} {:>8.3}   goal <= {goal_ms} ms: {} ({:.2} of the budget; physics step {:.0}% of the frame)",
        "total (excluding rendering)",
        m,
        if m <= goal_ms { "met" } else { "NOT met" },
        m / goal_ms,
        100.0 * physics / m
    );
    println!(
        "  {:<44} {:>8.3}",
        "total, wall clock (the machine's load in it)",
        median(&mut wall)
    );
    let r = median(&mut rapier);
    println!(
        "  {:<44} {:>8.3}   (information: rigidlab's physics step {:.2}x of it; the frame {:.2}x)",
        "rapier's plain step on the same world",
        r,
        physics / r,
        m / r
    );
    let e = median(&mut every);
    println!(
        "  {:<44} {:>8.3}   (information: the panel's box; {} line primitives, {} gizmo vertices; the frame's drawing + vertices + labels above are {:.2}x of it)",
        "trails and arrows on every body: drawn",
        e,
        drawing_every.prims.len(),
        gizmos_every.list_positions.len() + gizmos_every.strip_positions.len(),
        drawn / e
    );
    std::hint::black_box(sink);
}

/// `drawing`'s gizmo vertices in `gizmos`, emptied first (as Bevy empties them each frame).
fn emit_anew(drawing: &Drawing, gizmos: &mut GizmoBuffer<DefaultGizmoConfigGroup, ()>) {
    gizmos.list_positions.clear();
    gizmos.list_colors.clear();
    gizmos.strip_positions.clear();
    gizmos.strip_colors.clear();
    draw::emit(drawing, gizmos);
}

/// Places `d`'s labels by the window's own `place_labels` (app/scene.rs), each label's size
/// estimated (7 px a character, 16 px high: the bench has no fonts), keeping `last` frame's
/// places. Returns how many bodies were in the labels' reach.
fn place_labels(d: &Drawing, view: &View, last: &mut Vec<(Vec2, Rect)>) -> usize {
    let wants: Vec<labels::Want> = d
        .labels
        .iter()
        .map(|l| {
            let size = Vec2::new(7.0 * l.text.chars().count() as f32, 16.0);
            label_want(l, size, view)
        })
        .collect();
    rigidlab::app::scene::place_labels(d, view, &wants, last).1
}

/// What the window's line drawing reads in a frame.
#[derive(Clone, Copy)]
struct Lines<'a> {
    phys: &'a Run,
    outlines: &'a [rigidlab::app::geometry::Outline],
    ov: &'a Overlays,
    view: &'a View,
    visible: (glam::DVec2, glam::DVec2),
    max_speed: f64,
}

impl Lines<'_> {
    /// The frame's lines, as app::scene::build_drawing, the overlays' systems and the scale
    /// bar draw them, with `index` saying which balls their meshes draw.
    fn build(&self, index: &SceneIndex, drawing: &mut Drawing) {
        let (phys, view, ov) = (self.phys, self.view, self.ov);
        let s = phys.snapshot();
        drawing.clear(view.m_per_px);
        scene_lines::scene_lines(
            &phys.sim.level,
            self.outlines,
            index,
            s,
            view.m_per_px,
            drawing,
        );
        if let Some(i) = ov.selected {
            scene_lines::highlight(self.outlines, s, i, drawing);
        }
        let mut scales = Scales::of(s, view.scene_size(), self.max_speed, view.m_per_px);
        scales.gain = ov.arrow_scale;
        scales.visible = Some(self.visible);
        overlays::build(ov, phys, self.outlines, &scales, drawing);
        scene_lines::scale_bar(view, drawing);
    }
}
