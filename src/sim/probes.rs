//! Measurements of the engine's own state that the snapshot does not carry, and study-only
//! settings applied to a built world (so the studies never name a rapier type).

use super::rapier::prelude::*;
use super::world::Simulation;

impl Simulation {
    /// Deepest overlap among the collider pairs in contact, m, measured on the current poses with
    /// parry's exact contact query (through the world's dispatcher, which knows arc tracks).
    ///
    /// Why not the manifolds' `dist`: rapier 0.36 recycles a pair's contacts while its relative
    /// pose drifts less than `contact_recycle_distance` (5 cm), and a recycled manifold keeps the
    /// distances of its last full update. A resting stack then reports 0 while its boxes overlap
    /// by millimetres (see the report of issue 7).
    pub fn deepest_overlap(&self) -> f64 {
        let world = &self.world;
        let mut worst: f64 = 0.0;
        for pair in world.narrow_phase.contact_pairs() {
            if !pair.has_any_active_contact() {
                continue;
            }
            let (Some(c1), Some(c2)) = (
                world.colliders.get(pair.collider1),
                world.colliders.get(pair.collider2),
            ) else {
                continue;
            };
            if let Some(c) = super::arc_contacts::contact(
                world.narrow_phase.query_dispatcher(),
                c1.position(),
                c1.shape(),
                c2.position(),
                c2.shape(),
                0.0,
            ) {
                worst = worst.max(-(c.dist as f64));
            }
        }
        worst
    }

    /// Makes every joint soft: rapier's joint softness natural frequency, Hz (rapier's default
    /// 1e6 Hz is rigid). A study-only setting (`study stability --joint-hz`).
    pub fn set_joint_softness(&mut self, hz: f64) {
        for (_, j) in self.world.impulse_joints.iter_mut() {
            j.data.softness.natural_frequency = hz as Real;
        }
    }
}
