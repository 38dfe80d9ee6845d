//! Blows a student can see: every impulse event of the level, with what each joint of the struck
//! body transmitted in that step, split into its impulsive part and the steady part the joint
//! carries anyway (about the step before's impulse: weight and centripetal load times dt).
//!
//! A blow lasts one step (1/60 s at most), under one rendered frame, so the window keeps the
//! run's blows and draws them from their time on (MK art. 6/10's impulse and the pin's response,
//! e.g. the center-of-percussion demo: struck at q, the impulsive part at the pin is near zero).

use crate::snapshot::Snapshot;
use glam::DVec2;

/// One impulse event as it happened in the run.
#[derive(Debug, Clone, PartialEq)]
pub struct Blow {
    pub time: f64,
    pub name: String,
    pub body: usize,
    /// Where it struck (world, at the step it was applied), m.
    pub point: DVec2,
    /// The impulse, N s.
    pub impulse: DVec2,
    pub joints: Vec<JointShare>,
}

/// What one joint of the struck body transmitted to it during the blow's step.
#[derive(Debug, Clone, PartialEq)]
pub struct JointShare {
    pub joint: String,
    /// Where the joint holds the body (world), m.
    pub anchor: DVec2,
    /// The joint's impulse on the struck body over the step, N s.
    pub total: DVec2,
    /// The part it carried the step before (steady loads times dt); None before the first step.
    pub steady: Option<DVec2>,
}

impl JointShare {
    /// The impulsive part: the step's impulse less the steady part.
    pub fn impulsive(&self) -> DVec2 {
        self.total - self.steady.unwrap_or(DVec2::ZERO)
    }
}

/// The blows applied in the step that led to `s`; `before` is the snapshot before that step.
pub fn in_step(before: &Snapshot, s: &Snapshot) -> Vec<Blow> {
    s.impulses
        .iter()
        .map(|imp| {
            let joints = s
                .joints
                .iter()
                .enumerate()
                .filter(|(_, j)| j.body1 == imp.body || j.body2 == imp.body)
                .map(|(k, j)| {
                    // The joint's impulse on the struck body (rapier reports it on body 2).
                    let sign = if j.body2 == imp.body { 1.0 } else { -1.0 };
                    let anchor = if j.body2 == imp.body {
                        j.anchor
                    } else {
                        j.anchor1
                    };
                    let steady = (!before.is_initial())
                        .then(|| before.joints.get(k).map(|b| sign * b.impulse_on_body2))
                        .flatten();
                    JointShare {
                        joint: j.name.clone(),
                        anchor,
                        total: sign * j.impulse_on_body2,
                        steady,
                    }
                })
                .collect();
            Blow {
                time: s.time,
                name: imp.name.clone(),
                body: imp.body,
                point: imp.point,
                impulse: imp.impulse,
                joints,
            }
        })
        .collect()
}
