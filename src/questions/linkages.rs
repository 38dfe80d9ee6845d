//! Linkage quantities: a link's angular velocity and the speed of one of its pins, analysed
//! through the link's instantaneous center (RK-11) found from the velocities the neighbouring
//! bodies give two of its pins; and where a body on a pin has its center of percussion (CP-1).

use super::meter::{EngineAndAnalysis, Meter};
use super::sample::Sample;
use super::snapshot_reading::joint_index;
use crate::analysis::kinematics::{body_point_velocity, omega_from_two_points, point_velocity};
use crate::analysis::mass::parallel_axis;
use crate::analysis::percussion::center_of_percussion_distance;
use crate::level::{BodyKind, JointKind, Quantity};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Records why the quantity's analysis does not apply to the scene: `PercussionDistance`'s
/// q = k_O^2 / r_bar (CP-1) is for a body turning about a pin, so a joint of another kind (a
/// slider, a weld, a pin in a slot) makes it "not applicable".
pub(super) fn advance(m: &mut Meter) {
    if m.inapplicable.is_some() {
        return;
    }
    if let Quantity::PercussionDistance { joint, .. } = &m.q {
        if let Some(j) = m.facts.joints.iter().find(|j| &j.name == joint) {
            if j.kind != JointKind::Revolute {
                m.inapplicable = Some(format!(
                    "joint \"{joint}\" is {:?}, not a revolute pin: the center of percussion q = k_O^2 / r_bar (CP-1) is for a body turning about a pin",
                    j.kind
                ));
            }
        }
    }
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, f: &Sample) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    Some(match &m.q {
        Quantity::LinkOmega { link, known, other } => {
            let (_, l) = m.named_body(s, link)?;
            let w = link_motion(s, link, known, other);
            (l.omega, w.map(|(w, _, _)| w))
        }
        Quantity::PinSpeed {
            link,
            known,
            other,
            pin,
        } => {
            let (li, l) = m.named_body(s, link)?;
            let k = joint_index(s, pin)?;
            let j = &s.joints[k];
            let p = if j.body2 == li { j.anchor } else { j.anchor1 };
            // RK-6 from the known pin A: v_P = v_A + omega k x r_{P/A}. Where the instantaneous
            // center exists this is |omega| |P - C| (RK-11); it also holds where A's and B's
            // velocities are parallel and normal to AB, which the center's construction cannot
            // place (its two normals coincide).
            let motion = link_motion(s, link, known, other);
            (
                body_point_velocity(l, p).length(),
                motion.map(|(w, a, v_a)| point_velocity(v_a, w, p - a).length()),
            )
        }
        Quantity::PercussionDistance { body, joint } => {
            let (i, b) = m.named_body(s, body)?;
            // The pin where the engine reports it; at t = 0, where the level puts it.
            let pin = match joint_index(s, joint) {
                Some(k) => {
                    let j = &s.joints[k];
                    if j.body2 == i {
                        j.anchor
                    } else {
                        j.anchor1
                    }
                }
                None => m.facts.joint_anchor(s, joint)?,
            };
            let r_bar = (b.com - pin).length();
            let q = |i_g: f64, mass: f64| {
                center_of_percussion_distance(parallel_axis(i_g, mass, r_bar), mass, r_bar)
            };
            // The textbook's G: the formula's mass center carried to the body's pose.
            let t = &m.facts.bodies.get(i)?.textbook;
            let g_text = b.world_point(t.com);
            let r_text = (g_text - pin).length();
            let analysis = center_of_percussion_distance(
                parallel_axis(t.inertia, t.mass, r_text),
                t.mass,
                r_text,
            );
            (q(b.inertia, b.mass)?, analysis)
        }
        q => unreachable!("{q:?} is not a linkage quantity"),
    })
}

/// A link's angular velocity from its two pins' velocities as points of the neighbouring
/// bodies, omega = (r_{B/A} x (v_B - v_A))_z / |r_{B/A}|^2 (RK-6 solved for omega: the pins
/// hold, so the link's points A and B move with them), with the known pin A and its velocity:
/// (omega, A, v_A). Unlike the instantaneous center's construction (RK-11), it needs no case
/// for parallel velocities: a translating link gets 0, and one whose pins move parallel, normal
/// to AB and unequal gets its rotation about a center on AB.
fn link_motion(s: &Snapshot, link: &str, known: &str, other: &str) -> Option<(f64, DVec2, DVec2)> {
    let li = s.body_index(link)?;
    let pin = |name: &str| -> Option<(DVec2, DVec2)> {
        let j = &s.joints[joint_index(s, name)?];
        let (nb, p) = if j.body1 == li {
            (j.body2, j.anchor)
        } else {
            (j.body1, j.anchor1)
        };
        let b = &s.bodies[nb];
        let v = if b.kind == BodyKind::Fixed {
            DVec2::ZERO
        } else {
            body_point_velocity(b, p)
        };
        Some((p, v))
    };
    let (a, v_a) = pin(known)?;
    let (b, v_b) = pin(other)?;
    if (b - a).length_squared() == 0.0 {
        return None;
    }
    Some((omega_from_two_points(a, v_a, b, v_b), a, v_a))
}
