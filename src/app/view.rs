//! The scene view: camera (fit, pan, zoom, follow), filled body meshes, and picking the body
//! under a point. The line drawing of bodies, joints, springs and ground is `scene_lines.rs`.

use super::ball_meshes::BallMeshes;
use super::geometry::{self, Bounds, Outline};
use super::playback::Playback;
use super::run::Run;
use crate::level::{Level, Scene};
use crate::sim::Options;
use crate::simulation::AnySimulation;
use crate::snapshot::{BodyKind, Snapshot};
use bevy::asset::RenderAssetUsages;
use bevy::camera::Viewport;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll, MouseScrollUnit};
use bevy::mesh::PrimitiveTopology;
use bevy::prelude::*;
use glam::DVec2;

/// Colors of the textbook-style figure.
pub mod palette {
    use bevy::prelude::Color;
    pub const BACKGROUND: Color = Color::srgb(0.97, 0.97, 0.95);
    pub const OUTLINE: Color = Color::srgb(0.10, 0.13, 0.20);
    pub const DYNAMIC: Color = Color::srgb(0.66, 0.78, 0.93);
    pub const SELECTED: Color = Color::srgb(0.98, 0.80, 0.45);
    pub const FIXED: Color = Color::srgb(0.72, 0.72, 0.70);
    pub const KINEMATIC: Color = Color::srgb(0.70, 0.88, 0.70);
    pub const GROUND: Color = Color::srgb(0.25, 0.25, 0.25);
    pub const JOINT: Color = Color::srgb(0.15, 0.15, 0.15);
    pub const SPRING: Color = Color::srgb(0.45, 0.30, 0.10);
    pub const TEXT: Color = Color::srgb(0.10, 0.10, 0.10);
    pub const VELOCITY: Color = Color::srgb(0.05, 0.35, 0.85);
    pub const ACCEL: Color = Color::srgb(0.85, 0.35, 0.0);
    pub const CENTER: Color = Color::srgb(0.55, 0.0, 0.55);
    pub const GRAVITY: Color = Color::srgb(0.0, 0.50, 0.20);
    pub const NORMAL: Color = Color::srgb(0.85, 0.05, 0.10);
    pub const FRICTION: Color = Color::srgb(0.95, 0.50, 0.0);
    /// Joint reactions: dark gold, apart from every other force and from the instantaneous
    /// center's purple (they met at a pin, where R's arrow starts on the IC's dot).
    pub const REACTION: Color = Color::srgb(0.60, 0.48, 0.0);
    pub const LOAD: Color = Color::srgb(0.80, 0.0, 0.50);
    pub const TRAIL: Color = Color::srgba(0.20, 0.35, 0.65, 0.55);
    pub const MOMENTUM: Color = Color::srgb(0.0, 0.55, 0.55);
    pub const COUPLING: Color = Color::srgb(0.35, 0.35, 0.75);
    pub const TOOL: Color = Color::srgb(0.9, 0.1, 0.1);
}

/// The camera: world point at the viewport center and meters per logical pixel.
#[derive(Resource, Debug, Clone)]
pub struct View {
    pub center: DVec2,
    pub m_per_px: f64,
    /// The drawing area in logical pixels (top-left origin) inside the window or image.
    pub viewport: Rect,
    /// Fit the scene on the next frame.
    pub fit: bool,
    /// Bounds of the motion the fit used (also sets arrow scales).
    pub bounds: Bounds,
    /// The `Run::view_generation` the camera last refit for.
    pub generation: Option<u64>,
    /// The `Run::generation` `bounds` were computed for (a fit after a spawn or a solver
    /// change recomputes them).
    pub bounds_generation: Option<u64>,
    /// The fastest speed seen in this run (sets the velocity arrow scale), m/s.
    pub max_speed: f64,
    pub generation_speed: Option<u64>,
    /// The body the camera follows (its mass center stays at the view's center).
    pub follow: Option<usize>,
    /// Some moving body was in view last frame (the camera refits when the motion, not the
    /// user's panning, takes every one of them out).
    pub bodies_in_view: bool,
}

impl Default for View {
    fn default() -> Self {
        View {
            center: DVec2::ZERO,
            m_per_px: 0.01,
            viewport: Rect::new(0.0, 0.0, 800.0, 600.0),
            fit: true,
            bounds: Bounds::empty(),
            generation: None,
            bounds_generation: None,
            max_speed: 0.0,
            generation_speed: None,
            follow: None,
            bodies_in_view: true,
        }
    }
}

impl View {
    /// World (m) to logical pixels in the window (y down).
    pub fn to_screen(&self, p: DVec2) -> Vec2 {
        let c = self.viewport.center();
        c + Vec2::new(
            ((p.x - self.center.x) / self.m_per_px) as f32,
            (-(p.y - self.center.y) / self.m_per_px) as f32,
        )
    }

    /// Logical pixels in the window to world (m).
    pub fn to_world(&self, s: Vec2) -> DVec2 {
        let d = s - self.viewport.center();
        self.center + DVec2::new(d.x as f64, -d.y as f64) * self.m_per_px
    }

    /// Centers `b` in the viewport with a margin.
    pub fn fit_to(&mut self, b: &Bounds) {
        let (w, h) = (
            self.viewport.width().max(50.0) as f64,
            self.viewport.height().max(50.0) as f64,
        );
        let size = b.size();
        let extent = size.max(DVec2::splat(size.max_element().max(0.5) * 0.25));
        self.center = b.center();
        self.m_per_px = (extent.x / w).max(extent.y / h) * 1.4;
    }

    /// The characteristic length of the scene, m (arrow scales).
    pub fn scene_size(&self) -> f64 {
        if self.bounds.is_empty() {
            1.0
        } else {
            self.bounds.size().max_element().max(0.1)
        }
    }
}

/// The world camera (the scene; egui draws on its own context).
#[derive(Component)]
pub struct WorldCamera;

/// A body's filled mesh.
#[derive(Component)]
pub struct BodyMesh(pub usize);

/// Outlines of every body of the running scene, body frame, and who joins whom.
#[derive(Resource, Default)]
pub struct Outlines {
    pub generation: Option<u64>,
    pub bodies: Vec<Outline>,
    pub index: SceneIndex,
}

/// Body indices of the level's joints and couplings (names resolved once per scene).
#[derive(Debug, Clone, Default)]
pub struct SceneIndex {
    /// (body1, body2) per joint; empty when the level does not simulate joints.
    pub joints: Vec<(usize, usize)>,
    pub couplings: Vec<Vec<usize>>,
    /// Bodies with a joint on them.
    pub jointed: Vec<bool>,
    /// Balls drawn whole by a shared mesh, their lines included (`ball_meshes::meshed_balls`).
    pub meshed: Vec<bool>,
}

impl SceneIndex {
    pub fn of(level: &Level) -> SceneIndex {
        let idx: std::collections::HashMap<&str, usize> = level
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.name.as_str(), i))
            .collect();
        let mut out = SceneIndex {
            jointed: vec![false; level.bodies.len()],
            meshed: super::ball_meshes::meshed_balls(level),
            ..Default::default()
        };
        if level.effects.contains(&crate::level::Effect::Joints) {
            for j in &level.joints {
                if let (Some(&a), Some(&b)) = (idx.get(j.body1.as_str()), idx.get(j.body2.as_str()))
                {
                    out.joints.push((a, b));
                    out.jointed[a] = true;
                    out.jointed[b] = true;
                } else {
                    // Keep the zip with level.joints aligned: validation makes this unreachable.
                    out.joints.push((0, 0));
                }
            }
            for c in &level.couplings {
                out.couplings.push(
                    c.terms
                        .iter()
                        .filter_map(|t| idx.get(t.body.as_str()).copied())
                        .collect(),
                );
            }
        }
        out
    }
}

/// Bounds of what the level shows over its run: the moving bodies along their simulated paths
/// (a short headless pre-run), the fixed bodies near them, and the nearest part of the ground.
pub fn motion_bounds(scene: &Scene, options: &Options) -> Bounds {
    let level = &scene.level;
    let outlines: Vec<Outline> = level
        .bodies
        .iter()
        .map(|b| b.shape.as_ref().map(Outline::of).unwrap_or_default())
        .collect();
    let mut moving = Bounds::empty();
    let mut sim = AnySimulation::new(scene, options);
    let steps = sim
        .total_steps()
        .min((200_000 / level.bodies.len().max(1)) as u64)
        .min(5000);
    let add_moving = |s: &Snapshot, m: &mut Bounds| {
        for (i, b) in s.bodies.iter().enumerate() {
            if b.kind == BodyKind::Fixed {
                continue;
            }
            geometry::body_bounds(&level.bodies[i], &outlines[i], b.position, b.angle, m);
        }
    };
    add_moving(sim.snapshot(), &mut moving);
    for k in 0..steps {
        match sim.step() {
            Ok(s) if k % 2 == 1 || k + 1 == steps => add_moving(s, &mut moving),
            Ok(_) => {}
            Err(_) => break,
        }
    }
    let mut all = moving;
    // Around the motion, fixed shapes are shown as far as they reach into this box.
    let window = if moving.is_empty() {
        None
    } else {
        let margin = DVec2::splat((0.5 * moving.size().max_element()).max(0.25));
        Some(Bounds {
            min: moving.min - margin,
            max: moving.max + margin,
        })
    };
    for (i, b) in level.bodies.iter().enumerate() {
        if b.kind != BodyKind::Fixed {
            continue;
        }
        let pos = DVec2::new(b.position.0, b.position.1);
        let o = &outlines[i];
        let to_world = geometry::place(o, pos, b.angle);
        if o.filled.is_empty() && o.segments.is_empty() {
            // A point support: what shows is where joints attach to it.
            let anchors: Vec<DVec2> = level
                .joints
                .iter()
                .filter_map(|j| {
                    if j.body1 == b.name {
                        Some(to_world(DVec2::new(j.anchor1.0, j.anchor1.1)))
                    } else if j.body2 == b.name {
                        Some(to_world(DVec2::new(j.anchor2.0, j.anchor2.1)))
                    } else {
                        None
                    }
                })
                .collect();
            if anchors.is_empty() {
                all.add(pos);
            }
            anchors.into_iter().for_each(|a| all.add(a));
            continue;
        }
        let edges = o
            .segments
            .iter()
            .map(|(a, bb)| (to_world(*a), to_world(*bb)))
            .chain(
                o.filled
                    .iter()
                    .flat_map(|poly| {
                        (0..poly.len()).map(move |k| (poly[k], poly[(k + 1) % poly.len()]))
                    })
                    .map(|(a, bb)| (to_world(a), to_world(bb))),
            );
        match window {
            None => edges.for_each(|(a, bb)| {
                all.add(a);
                all.add(bb);
            }),
            Some(w) => {
                let mut seen = false;
                for (a, bb) in edges {
                    if let Some((p, q)) = geometry::clip_segment(a, bb, &w) {
                        all.add(p);
                        all.add(q);
                        seen = true;
                    }
                }
                if !seen {
                    // A ground below the motion but outside the box: its nearest point.
                    let c = moving.center();
                    let mut best: Option<DVec2> = None;
                    for (a, bb) in o
                        .segments
                        .iter()
                        .map(|(a, bb)| (to_world(*a), to_world(*bb)))
                    {
                        let e = bb - a;
                        let t = ((c - a).dot(e) / e.length_squared().max(1e-300)).clamp(0.0, 1.0);
                        let p = a + e * t;
                        if best.is_none_or(|q| (q - c).length() > (p - c).length()) {
                            best = Some(p);
                        }
                    }
                    if let Some(p) = best
                        .filter(|p| (*p - c).length() < 3.0 * moving.size().max_element().max(0.5))
                    {
                        all.add(p);
                    }
                }
            }
        }
    }
    for s in &level.springs {
        if s.body2.is_none() {
            all.add(DVec2::new(s.point2.0, s.point2.1));
        }
    }
    if all.is_empty() {
        all = geometry::level_bounds(level);
    }
    if all.is_empty() {
        all.add(DVec2::ZERO);
    }
    all
}

/// Refits on a new scene, then applies the view to the camera.
pub fn sync_camera(
    (phys, playback): (Res<Run>, Res<Playback>),
    mut view: ResMut<View>,
    mut cams: Query<(&mut Transform, &mut Projection, &mut Camera), With<WorldCamera>>,
    windows: Query<&Window>,
) {
    if view.generation != Some(phys.view_generation) {
        view.generation = Some(phys.view_generation);
        view.fit = true;
    }
    if view.fit && view.bounds_generation != Some(phys.generation) {
        view.bounds_generation = Some(phys.generation);
        view.bounds = motion_bounds(&phys.scene, &phys.options);
    }
    if view.fit {
        let b = view.bounds;
        view.fit_to(&b);
        if std::env::var_os("RIGIDLAB_DEBUG_FIT").is_some() {
            eprintln!(
                "fit {:?} viewport {:?} -> center {} m/px {}",
                b, view.viewport, view.center, view.m_per_px
            );
        }
        view.fit = false;
    }
    let s = phys.snapshot();
    if let Some(b) = view.follow.and_then(|i| s.bodies.get(i)) {
        view.center = b.com;
    }
    // Everything that moves has left the view while the scene runs (a body thrown past the
    // fitted motion, a run past the level's end): fit again.
    let world = |p: DVec2| view.viewport.contains(view.to_screen(p));
    let moving: Vec<DVec2> = s
        .bodies
        .iter()
        .filter(|b| b.kind == crate::snapshot::BodyKind::Dynamic)
        .map(|b| b.com)
        .collect();
    let in_view = moving.is_empty() || moving.iter().any(|&p| world(p));
    if view.bodies_in_view && !in_view && !playback.paused {
        view.fit = true;
        view.bounds = current_bounds(s);
        view.bounds_generation = Some(phys.generation);
        let b = view.bounds;
        view.fit_to(&b);
        view.fit = false;
    }
    view.bodies_in_view = in_view;
    let scale = windows.iter().next().map_or(1.0, |w| w.scale_factor());
    for (mut t, mut proj, mut cam) in cams.iter_mut() {
        t.translation = Vec3::new(view.center.x as f32, view.center.y as f32, t.translation.z);
        if let Projection::Orthographic(o) = proj.as_mut() {
            if o.scale != view.m_per_px as f32 {
                o.scale = view.m_per_px as f32;
            }
        }
        let vp = view.viewport;
        let pos = (vp.min * scale).max(Vec2::ZERO).as_uvec2();
        let size = (vp.size() * scale).max(Vec2::ONE).as_uvec2();
        let same = cam
            .viewport
            .as_ref()
            .is_some_and(|v| v.physical_position == pos && v.physical_size == size);
        if windows.iter().next().is_some() && !same {
            cam.viewport = Some(Viewport {
                physical_position: pos,
                physical_size: size,
                ..default()
            });
        }
    }
}

/// The bodies' mass centers now, with a margin of a tenth of their spread (at least 1 m).
fn current_bounds(s: &crate::snapshot::Snapshot) -> Bounds {
    let mut b = Bounds::empty();
    for x in &s.bodies {
        b.add(x.com);
    }
    let pad = (0.1 * b.size().max_element()).max(1.0);
    b.add(b.min - DVec2::splat(pad));
    b.add(b.max + DVec2::splat(pad));
    b
}

/// Where the mouse is, in window logical pixels, if inside the scene viewport and not over a panel.
pub fn scene_cursor(view: &View, window: &Window) -> Option<Vec2> {
    let p = window.cursor_position()?;
    view.viewport.contains(p).then_some(p)
}

/// Pan with the right or middle button, zoom about the cursor with the wheel.
pub fn pan_zoom(
    mut view: ResMut<View>,
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    windows: Query<&Window>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
) {
    let Some(window) = windows.iter().next() else {
        return;
    };
    let over_ui = egui_input.is_some_and(|e| e.wants_any_pointer_input());
    let Some(cursor) = scene_cursor(&view, window) else {
        return;
    };
    if buttons.pressed(MouseButton::Right) || buttons.pressed(MouseButton::Middle) {
        let d = motion.delta;
        let m = view.m_per_px;
        view.center -= DVec2::new(d.x as f64, -d.y as f64) * m;
    }
    if over_ui || scroll.delta.y == 0.0 {
        return;
    }
    let steps = match scroll.unit {
        MouseScrollUnit::Line => scroll.delta.y as f64,
        MouseScrollUnit::Pixel => scroll.delta.y as f64 / 40.0,
    };
    // Keep the world point under the cursor fixed while zooming.
    let before = view.to_world(cursor);
    view.m_per_px = (view.m_per_px * 0.85f64.powf(steps)).clamp(1e-6, 1e4);
    let after = view.to_world(cursor);
    view.center += before - after;
}

/// Spawns the filled meshes of a new scene (and refreshes outlines).
pub fn spawn_meshes(
    mut commands: Commands,
    phys: Res<Run>,
    mut outlines: ResMut<Outlines>,
    old: Query<Entity, With<BodyMesh>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<ColorMaterial>>,
    mut balls: ResMut<BallMeshes>,
) {
    if outlines.generation == Some(phys.generation) {
        return;
    }
    balls.clear();
    outlines.generation = Some(phys.generation);
    outlines.bodies = body_outlines(&phys.sim.level);
    outlines.index = SceneIndex::of(&phys.sim.level);
    for e in old.iter() {
        commands.entity(e).despawn();
    }
    let fixed = materials.add(ColorMaterial::from_color(palette::FIXED));
    let dynamic = materials.add(ColorMaterial::from_color(palette::DYNAMIC));
    let kinematic = materials.add(ColorMaterial::from_color(palette::KINEMATIC));
    for (i, (def, o)) in phys
        .sim
        .level
        .bodies
        .iter()
        .zip(&outlines.bodies)
        .enumerate()
    {
        let fill = match def.kind {
            BodyKind::Fixed => palette::FIXED,
            BodyKind::Dynamic => palette::DYNAMIC,
            BodyKind::Kinematic => palette::KINEMATIC,
        };
        let pose = Transform::from_xyz(
            def.position.0 as f32,
            def.position.1 as f32,
            -(i as f32) * 1e-4,
        );
        if let (true, Some(crate::level::Shape::Circle { radius })) =
            (outlines.index.meshed[i], &def.shape)
        {
            // One mesh for every ball of this radius and kind: drawn instanced.
            let (mesh, material) = balls.get(
                (*radius, def.kind != BodyKind::Fixed),
                fill,
                palette::OUTLINE,
                &mut meshes,
                &mut materials,
            );
            commands.spawn((Mesh2d(mesh), MeshMaterial2d(material), pose, BodyMesh(i)));
            continue;
        }
        let tris = geometry::triangles(o);
        if tris.is_empty() {
            continue;
        }
        let n = tris.len();
        let mesh = Mesh::new(
            PrimitiveTopology::TriangleList,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, tris)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 0.0, 1.0]; n])
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.0f32, 0.0]; n]);
        let material = match def.kind {
            BodyKind::Fixed => fixed.clone(),
            BodyKind::Dynamic => dynamic.clone(),
            BodyKind::Kinematic => kinematic.clone(),
        };
        commands.spawn((
            Mesh2d(meshes.add(mesh)),
            MeshMaterial2d(material),
            pose,
            BodyMesh(i),
        ));
    }
}

/// Rebuilds the shared ball meshes for the view's scale (their lines are drawn in world units).
pub fn rescale_ball_meshes(
    view: Res<View>,
    mut balls: ResMut<BallMeshes>,
    mut meshes: ResMut<Assets<Mesh>>,
) {
    balls.rescale(view.m_per_px, palette::OUTLINE, &mut meshes);
}

pub fn body_outlines(level: &Level) -> Vec<Outline> {
    level
        .bodies
        .iter()
        .map(|b| b.shape.as_ref().map(Outline::of).unwrap_or_default())
        .collect()
}

/// Moves the meshes to the bodies' poses.
pub fn sync_meshes(phys: Res<Run>, mut q: Query<(&BodyMesh, &mut Transform)>) {
    let s = phys.snapshot();
    for (m, mut t) in q.iter_mut() {
        if let Some(b) = s.bodies.get(m.0) {
            place_mesh(b, &mut t);
        }
    }
}

/// A body's mesh moved to the body's pose (its depth kept).
pub fn place_mesh(b: &crate::snapshot::BodyState, t: &mut Transform) {
    t.translation.x = b.position.x as f32;
    t.translation.y = b.position.y as f32;
    t.rotation = Quat::from_rotation_z(b.angle as f32);
}

/// Whether the world point `p` is on body `i`'s outline (within `tol`, m).
fn on_outline(outlines: &[Outline], s: &Snapshot, i: usize, p: DVec2, tol: f64) -> bool {
    let b = &s.bodies[i];
    let local = DVec2::from_angle(-b.angle).rotate(p - b.position);
    outlines.get(i).is_some_and(|o| o.contains(local, tol))
}

/// Which body (if any) is under a world point: topmost first (last drawn).
pub fn body_at(
    outlines: &[Outline],
    s: &Snapshot,
    p: DVec2,
    tol: f64,
    only_moving: bool,
) -> Option<usize> {
    s.bodies
        .iter()
        .enumerate()
        .rev()
        .filter(|(_, b)| !only_moving || b.kind == BodyKind::Dynamic)
        .find(|(i, b)| {
            on_outline(outlines, s, *i, p, tol)
                || (outlines
                    .get(*i)
                    .is_some_and(|o| o.filled.is_empty() && o.segments.is_empty())
                    && (p - b.position).length() <= tol)
        })
        .map(|(i, _)| i)
}

/// Every body whose outline is under a world point, topmost first (the join and spring tools).
pub fn bodies_under(outlines: &[Outline], s: &Snapshot, p: DVec2, tol: f64) -> Vec<usize> {
    (0..s.bodies.len())
        .rev()
        .filter(|&i| on_outline(outlines, s, i, p, tol))
        .collect()
}
