//! Joints: bodies, anchors that meet at t = 0, limits and motors.

use super::*;

pub(super) fn joint(v: &V, j: &JointDef) -> R {
    let at = |f: &str| v.loc.field_pos("joints", &j.name, f);
    v.need(
        Effect::Joints,
        v.loc.item_pos("joints", &j.name),
        &format!("joint \"{}\" is defined", j.name),
    )?;
    let b1 = v.body_ref(&j.body1, "joints", &j.name, "body1")?;
    let b2 = v.body_ref(&j.body2, "joints", &j.name, "body2")?;
    if j.body1 == j.body2 {
        return Err(v.err(
            at("body2"),
            format!("joint \"{}\" joins body \"{}\" to itself", j.name, j.body1),
            "name two different bodies",
        ));
    }
    if b1.kind != BodyKind::Dynamic && b2.kind != BodyKind::Dynamic {
        return Err(v.err(
            at("body2"),
            format!("joint \"{}\" joins two bodies that are not dynamic", j.name),
            "one of the bodies must be `kind: dynamic`",
        ));
    }
    v.finite2(j.anchor1, "anchor1", at("anchor1"))?;
    v.finite2(j.anchor2, "anchor2", at("anchor2"))?;
    v.finite2(j.axis, "axis", at("axis"))?;
    if j.axis.0.hypot(j.axis.1) < 1e-9 {
        return Err(v.err(
            at("axis"),
            "the joint axis has zero length",
            "give a direction such as (1.0, 0.0)",
        ));
    }
    anchors_meet(v, j, b1, b2)?;
    if let Some((lo, hi)) = j.limits {
        v.finite(lo, "lower limit", at("limits"))?;
        v.finite(hi, "upper limit", at("limits"))?;
        if lo > hi {
            return Err(v.err(
                at("limits"),
                format!("joint \"{}\" limits ({lo}, {hi}) are reversed", j.name),
                "write (lower, upper)",
            ));
        }
        if j.kind == JointKind::Fixed {
            return Err(v.err(
                at("limits"),
                "a fixed joint has no coordinate to limit",
                "remove `limits`",
            ));
        }
    }
    if let Some(m) = &j.motor {
        v.need(
            Effect::Motors,
            at("motor"),
            &format!("joint \"{}\" has a motor", j.name),
        )?;
        if j.kind == JointKind::Fixed || j.kind == JointKind::PinSlot {
            return Err(v.err(
                at("motor"),
                format!("a {:?} joint cannot carry a motor", j.kind).to_lowercase(),
                "motors go on revolute or prismatic joints",
            ));
        }
        match m {
            Motor::Velocity { target, max_force } => {
                v.finite(*target, "motor target", at("motor"))?;
                if let Some(f) = max_force {
                    v.positive(*f, "motor max_force", "", at("motor"))?;
                }
            }
            Motor::Position {
                target,
                stiffness,
                damping,
                max_force,
            } => {
                v.finite(*target, "motor target", at("motor"))?;
                v.non_negative(*stiffness, "motor stiffness", "", at("motor"))?;
                v.non_negative(*damping, "motor damping", "", at("motor"))?;
                if let Some(f) = max_force {
                    v.positive(*f, "motor max_force", "", at("motor"))?;
                }
            }
        }
    }
    Ok(())
}

/// How far apart a joint's two anchors may start, m: a gap any larger is snapped shut in the first
/// step by an impulse the textbook knows nothing of (an angle typed in degrees gave 1.8e9 N).
const ANCHOR_GAP: f64 = 1e-4;

/// A joint's anchors must meet at t = 0 (along the slide axis a prismatic or pin-in-slot joint may
/// start anywhere: that is its coordinate).
pub(super) fn anchors_meet(v: &V, j: &JointDef, b1: &BodyDef, b2: &BodyDef) -> R {
    let world = |b: &BodyDef, a: V2| {
        let (s, c) = b.angle.sin_cos();
        (
            b.position.0 + c * a.0 - s * a.1,
            b.position.1 + s * a.0 + c * a.1,
        )
    };
    let (p1, p2) = (world(b1, j.anchor1), world(b2, j.anchor2));
    let mut gap = (p2.0 - p1.0, p2.1 - p1.1);
    if matches!(j.kind, JointKind::Prismatic | JointKind::PinSlot) {
        let (s, c) = b1.angle.sin_cos();
        let n = j.axis.0.hypot(j.axis.1);
        let axis = (
            (c * j.axis.0 - s * j.axis.1) / n,
            (s * j.axis.0 + c * j.axis.1) / n,
        );
        let along = gap.0 * axis.0 + gap.1 * axis.1;
        gap = (gap.0 - along * axis.0, gap.1 - along * axis.1);
    }
    let d = gap.0.hypot(gap.1);
    if d <= ANCHOR_GAP || j.starts_apart {
        return Ok(());
    }
    // The body2 position that closes the gap, keeping its angle.
    let fix = (b2.position.0 - gap.0, b2.position.1 - gap.1);
    Err(v.err(
        v.loc.field_pos("joints", &j.name, "anchor2"),
        format!(
            "joint \"{}\": its anchors are {d:.4} m apart at t = 0 (body1's at ({:.4}, {:.4}), body2's at ({:.4}, {:.4}) in the world); rapier would snap them together in the first step with an impulse no textbook has",
            j.name, p1.0, p1.1, p2.0, p2.1
        ),
        format!(
            "anchors are in each body's frame, from its `position`, turned by its `angle` (radians); to keep the anchors, put body \"{}\" at position: ({:.6}, {:.6}) (or, to test how the engine snaps a stretched joint shut, add `starts_apart: true`)",
            b2.name, fix.0, fix.1
        ),
    ))
}
