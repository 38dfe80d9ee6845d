//! Welds created at run time, when two bodies first touch (`EventDef::WeldOnContact`).

use super::rapier::prelude::*;
use super::world::Simulation;
use crate::level::*;

impl Simulation {
    /// Creates the fixed joint of a `WeldOnContact` event once its bodies touch.
    pub(super) fn weld_on_contact(&mut self) {
        let mut k = 0;
        while k < self.pending_welds.len() {
            let (name, b1, b2) = self.pending_welds[k].clone();
            let touch = self
                .snapshot
                .contacts
                .iter()
                .find(|c| (c.body1 == b1 && c.body2 == b2) || (c.body1 == b2 && c.body2 == b1));
            let Some(point) = touch
                .and_then(|c| {
                    c.points
                        .iter()
                        .find(|p| p.normal_impulse > 0.0 || p.distance <= 0.0)
                })
                .map(|p| p.point)
            else {
                k += 1;
                continue;
            };
            let (h1, h2) = (self.bodies[b1], self.bodies[b2]);
            let p = Pose::from_parts(
                Vector::new(point.x as Real, point.y as Real),
                Rotation::IDENTITY,
            );
            let f1 = self.world.bodies[h1].position().inverse() * p;
            let f2 = self.world.bodies[h2].position().inverse() * p;
            let joint = GenericJointBuilder::new(JointAxesMask::LOCKED_FIXED_AXES)
                .local_frame1(f1)
                .local_frame2(f2)
                .contacts_enabled(false)
                .build();
            self.joints
                .push(self.world.insert_impulse_joint(h1, h2, joint));
            let (n1, n2) = (
                self.level.bodies[b1].name.clone(),
                self.level.bodies[b2].name.clone(),
            );
            let to_v2 = |v: Vector| (v.x as f64, v.y as f64);
            self.joint_defs.push(JointDef {
                name,
                kind: JointKind::Fixed,
                body1: n1,
                body2: n2,
                anchor1: to_v2(f1.translation),
                anchor2: to_v2(f2.translation),
                axis: (1.0, 0.0),
                limits: None,
                motor: None,
                starts_apart: false,
            });
            self.pending_welds.remove(k);
        }
    }
}
