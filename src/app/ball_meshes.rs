//! A crowd's balls drawn whole by shared meshes: the fill, the outline, the rotation spoke and
//! the mass-center ring of every ball of one radius and kind in one mesh, drawn instanced.
//!
//! Drawn as lines, each ball of a 10,000-grain pile cost the frame about 2.6 us of line building
//! and gizmo vertices every frame, more than half the frame's drawing (docs/benchmarks.md,
//! "10,000 bodies"). Bevy batches the entities that share a mesh and a material into one
//! instanced draw, so a ball moved by its `Transform` costs no line at all; what the lines showed
//! (a 2 px dark outline, the spoke, the 3 px mass-center ring) is in the mesh, in world units for
//! the view's scale, and the meshes are rebuilt when the zoom changes (a few meshes, not one
//! per ball). Scenes of at most [`CROWD_BODIES`] moving bodies keep the lines.

use super::draw::circle_resolution;
use crate::level::{BodyKind, Level, Shape};
use bevy::asset::RenderAssetUsages;
use bevy::mesh::PrimitiveTopology;
use bevy::prelude::*;
use glam::DVec2;

/// Above this many moving bodies a scene's balls are drawn by shared meshes (the engine's own
/// crowd: `sim::settings::IMPACT_CUT_BODIES`, where impacts stop being cut one by one).
pub const CROWD_BODIES: usize = crate::sim::settings::IMPACT_CUT_BODIES;

/// Width of a drawn line, logical pixels: Bevy's gizmo lines (`GizmoLineConfig::width`).
const LINE_PX: f64 = 2.0;

/// The mass-center ring's radius, pixels (`scene_lines`: `Prim::Circle(b.com, 3 px)`).
const COM_RING_PX: f64 = 3.0;

/// The smallest ball, in pixels of radius, that gets the mass-center ring and the spoke: the
/// ring (its outer edge 4 px from the center) then leaves a 3 px band of fill inside the
/// outline (which starts 1 px inside the rim). Below
/// it a grain shows its fill and a thin rim only: at 2026-12-07's first render of the sand pile
/// (grains of 1.8 px) the 2 px outline and the 3 px ring covered every grain, and the pile drew
/// as one dark band.
pub const DECORATED_PX: f64 = 8.0;

/// The crowd rule, one place for the meshes (from the level) and the overlays (from the
/// snapshot): the bodies of these `kinds` that are not fixed make a crowd when they are more
/// than [`CROWD_BODIES`]; then Some(their number).
pub fn crowd_of(kinds: impl IntoIterator<Item = BodyKind>) -> Option<usize> {
    let moving = kinds.into_iter().filter(|k| *k != BodyKind::Fixed).count();
    (moving > CROWD_BODIES).then_some(moving)
}

/// Which bodies are balls drawn whole by a shared mesh: every `Circle` of a scene of more than
/// [`CROWD_BODIES`] moving bodies; none otherwise.
pub fn meshed_balls(level: &Level) -> Vec<bool> {
    let crowd = crowd_of(level.bodies.iter().map(|b| b.kind)).is_some();
    level
        .bodies
        .iter()
        .map(|b| crowd && matches!(b.shape, Some(Shape::Circle { .. })))
        .collect()
}

/// A ball of radius `r` (m) as drawn at `m_per_px`, in its body frame: the disc filled with
/// `fill`, then in `line` (drawn over it: the mesh's triangles keep their order at one depth) the
/// outline as a ring `LINE_PX` wide centered on the rim (at most a quarter of the radius wide,
/// so a small grain keeps its fill), and on a ball of at least [`DECORATED_PX`] the spoke along
/// +x and, for a moving ball (`com`), the mass-center ring. Positions and linear RGBA vertex
/// colors, a triangle list.
pub fn ball_triangles(
    r: f64,
    m_per_px: f64,
    com: bool,
    (fill, line): ([f32; 4], [f32; 4]),
) -> (Vec<[f32; 3]>, Vec<[f32; 4]>) {
    let px = m_per_px.max(1e-12);
    let half = (0.5 * LINE_PX * px).min(0.125 * r);
    let decorated = r >= DECORATED_PX * px;
    let mut pos = Vec::new();
    let mut col = Vec::new();
    let mut tri = |ps: [DVec2; 3], c: [f32; 4]| {
        for p in ps {
            pos.push([p.x as f32, p.y as f32, 0.0]);
            col.push(c);
        }
    };
    let n = circle_resolution(r / px, 48);
    let at = |k: u32, radius: f64, n: u32| {
        DVec2::from_angle(std::f64::consts::TAU * k as f64 / n as f64) * radius
    };
    for k in 0..n {
        tri([DVec2::ZERO, at(k, r, n), at(k + 1, r, n)], fill);
    }
    let mut ring = |radius: f64, n: u32| {
        let (inner, outer) = ((radius - half).max(0.0), radius + half);
        for k in 0..n {
            let (a0, a1) = (at(k, inner, n), at(k + 1, inner, n));
            let (b0, b1) = (at(k, outer, n), at(k + 1, outer, n));
            tri([a0, b0, b1], line);
            tri([a0, b1, a1], line);
        }
    };
    ring(r, n);
    if !decorated {
        return (pos, col);
    }
    if com {
        ring(COM_RING_PX * px, circle_resolution(COM_RING_PX, 48));
    }
    let (a, b) = (DVec2::new(0.0, -half), DVec2::new(r, half));
    tri([a, DVec2::new(b.x, a.y), b], line);
    tri([a, b, DVec2::new(a.x, b.y)], line);
    (pos, col)
}

/// A mesh of [`ball_triangles`].
pub fn ball_mesh(r: f64, m_per_px: f64, com: bool, fill: Color, line: Color) -> Mesh {
    let lin = |c: Color| LinearRgba::from(c).to_f32_array();
    let (pos, col) = ball_triangles(r, m_per_px, com, (lin(fill), lin(line)));
    let n = pos.len();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, pos)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 0.0, 1.0]; n])
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.0f32, 0.0]; n])
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, col)
}

/// The shared ball meshes of the running scene, one per radius, fill color and mass-center ring,
/// and the zoom they were built for.
#[derive(Resource, Default)]
pub struct BallMeshes {
    /// The view's m_per_px the meshes were built for (0: not yet).
    pub built_for: f64,
    /// (radius, fill, mass-center ring, mesh) of each shared mesh.
    pub meshes: Vec<(f64, Color, bool, Handle<Mesh>)>,
    /// One white material for them all: the colors are the vertices'.
    pub material: Option<Handle<ColorMaterial>>,
}

impl BallMeshes {
    /// Forgets the previous scene's meshes.
    pub fn clear(&mut self) {
        self.built_for = 0.0;
        self.meshes.clear();
    }

    /// The shared mesh of a ball of radius `r` filled with `fill`, with its mass-center ring or
    /// not (`com`), built now if new, and the shared material.
    pub fn get(
        &mut self,
        (r, com): (f64, bool),
        fill: Color,
        line: Color,
        meshes: &mut Assets<Mesh>,
        materials: &mut Assets<ColorMaterial>,
    ) -> (Handle<Mesh>, Handle<ColorMaterial>) {
        let material = self
            .material
            .get_or_insert_with(|| materials.add(ColorMaterial::from_color(Color::WHITE)))
            .clone();
        let same =
            |(rr, f, c, _): &&(f64, Color, bool, Handle<Mesh>)| *rr == r && *f == fill && *c == com;
        if let Some((_, _, _, h)) = self.meshes.iter().find(same) {
            return (h.clone(), material);
        }
        let px = if self.built_for > 0.0 {
            self.built_for
        } else {
            r / 10.0
        };
        let h = meshes.add(ball_mesh(r, px, com, fill, line));
        self.meshes.push((r, fill, com, h.clone()));
        (h, material)
    }

    /// Rebuilds the meshes for the view's scale when it moved more than 2% (a 2 px line then
    /// stays within 0.04 px of its width).
    pub fn rescale(&mut self, m_per_px: f64, line: Color, meshes: &mut Assets<Mesh>) {
        if self.meshes.is_empty()
            || (self.built_for > 0.0 && (m_per_px / self.built_for - 1.0).abs() <= 0.02)
        {
            return;
        }
        self.built_for = m_per_px;
        for (r, fill, com, h) in &self.meshes {
            if let Some(mut m) = meshes.get_mut(h) {
                *m = ball_mesh(*r, m_per_px, *com, *fill, line);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_mesh_covers_the_disc_and_its_lines() {
        // A ball of 20 px radius at 1 mm/px: every vertex within the outline's outer edge
        // (r + 1 px), the fill's first, the lines' after it.
        let (r, px) = (0.02, 0.001);
        let (pos, col) = ball_triangles(r, px, true, ([1.0; 4], [0.0, 0.0, 0.0, 1.0]));
        assert_eq!(pos.len() % 3, 0);
        assert_eq!(pos.len(), col.len());
        let far = pos
            .iter()
            .map(|p| (p[0] as f64).hypot(p[1] as f64))
            .fold(0.0, f64::max);
        assert!((far - (r + px)).abs() < 1e-7, "{far}");
        let first_line = col.iter().position(|c| c[0] == 0.0).unwrap();
        assert!(col[..first_line].iter().all(|c| c[0] == 1.0));
        assert!(col[first_line..].iter().all(|c| c[0] == 0.0));
        // The fill is a fan of circle_resolution(20 px) triangles.
        assert_eq!(first_line, 3 * circle_resolution(20.0, 48) as usize);
    }

    #[test]
    fn a_small_grain_keeps_its_fill() {
        // A grain of 1.8 px radius (the sand pile's, fitted to the window): its outline at most
        // r/4 wide (from 7r/8 to 9r/8), no spoke, no mass-center ring, so every line vertex lies
        // at 7r/8 or 9r/8 and the fill inside 7r/8 stays uncovered.
        let (r, px) = (0.05, 0.05 / 1.8);
        let (pos, col) = ball_triangles(r, px, true, ([1.0; 4], [0.0, 0.0, 0.0, 1.0]));
        let first_line = col.iter().position(|c| c[0] == 0.0).unwrap();
        for p in &pos[first_line..] {
            let d = (p[0] as f64).hypot(p[1] as f64);
            let on_rim = (d - 0.875 * r).abs() < 1e-6 || (d - 1.125 * r).abs() < 1e-6;
            assert!(on_rim, "a line vertex at {d} m of a {r} m grain");
        }
    }
}
