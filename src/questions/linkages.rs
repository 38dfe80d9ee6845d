//! Linkage quantities: a link's angular velocity and the speed of one of its pins, analysed
//! through the link's instantaneous center (RK-11) found from the velocities the neighbouring
//! bodies give two of its pins; and where a body on a pin has its center of percussion (CP-1).

use super::meter::{EngineAndAnalysis, Meter};
use super::sample::Sample;
use super::snapshot_reading::joint_index;
use crate::analysis::kinematics::{
    body_point_velocity, instantaneous_center_from_two_points, omega_about_center,
};
use crate::analysis::mass::parallel_axis;
use crate::analysis::percussion::center_of_percussion_distance;
use crate::level::{BodyKind, Quantity};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// The quantity at the sample.
pub(super) fn read(m: &Meter, f: &Sample) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    Some(match &m.q {
        Quantity::LinkOmega { link, known, other } => {
            let (_, l) = m.named_body(s, link)?;
            let ic = link_center(s, link, known, other);
            (l.omega, ic.map(|(w, _)| w))
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
            let ic = link_center(s, link, known, other);
            (
                body_point_velocity(l, p).length(),
                ic.map(|(w, c)| (w * (p - c).length()).abs()),
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

/// The instantaneous center of a link from its two pins' velocities as points of the
/// neighbouring bodies: (omega, C). A translating link has omega 0 and C far away along the
/// normal to the pins' velocity.
fn link_center(s: &Snapshot, link: &str, known: &str, other: &str) -> Option<(f64, DVec2)> {
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
    let (p, vp) = pin(known)?;
    let (q, vq) = pin(other)?;
    match instantaneous_center_from_two_points(p, vp, q, vq) {
        Some(c) => Some((omega_about_center(p, vp, c), c)),
        None => Some((0.0, p + vp.perp() * 1e12)),
    }
}
