//! Readings of a contact that several families share: a force's component as a question names
//! it, when a contact slides, when the ground under it curves, and what else acts on a body on
//! the ground.

use crate::analysis::cross;
use crate::level::ContactComponent;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// A contact's force or impulse `v` on a body as `c` names it, with `n` the contact normal into
/// the body and t = k x n.
pub(super) fn contact_component(c: ContactComponent, v: DVec2, n: DVec2) -> f64 {
    match c {
        ContactComponent::Normal => v.dot(n),
        ContactComponent::Tangential => v.dot(n.perp()),
        ContactComponent::Friction => v.dot(n.perp()).abs(),
        ContactComponent::X => v.x,
        ContactComponent::Y => v.y,
        ContactComponent::Magnitude => v.length(),
    }
}

/// A slip speed above which a contact counts as sliding for Coulomb's law, m/s. rapier's sticking
/// contacts creep at up to a few mm/s (a disc on a pulled plank: 3.2 mm/s, docs/known-gaps.md),
/// and a sliding contact that stops passes through this speed within a step or two.
pub(super) const SLIDING: f64 = 1e-2;

/// A turn of the contact normal in one step that means the ground curves, rad. rapier's normal
/// on a straight slope wobbles by up to 2.4e-6 rad from step to step in f32 (a disc on a 25
/// degree incline, tests/newuser/rolling/n4_02); a turn of 1e-4 rad per step is a curve of radius
/// v dt / 1e-4, whose m v^2 / rho is v 1e-4 / dt: 0.5% of g at 2 m/s and 1/240 s.
pub(super) const CURVED: f64 = 1e-4;

/// How far the contact normal between i and the ground turned over the step, rad.
pub(super) fn turned(prev: &Snapshot, s: &Snapshot, i: usize, o: usize) -> Option<f64> {
    let n = |x: &Snapshot| {
        x.contacts
            .iter()
            .find(|c| (c.body1 == i && c.body2 == o) || (c.body1 == o && c.body2 == i))
            .map(|c| c.normal)
    };
    let (a, b) = (n(prev)?, n(s)?);
    Some(cross(a, b).abs().atan2(a.dot(b).abs()))
}

/// What besides its weight and the ground acts on body i in `s`: a joint, a spring, a load, a
/// coupling, or another body pushing on it (damping is in the level's facts, not the
/// snapshot). The rolling closed forms and the slide-to-roll closed form share this test.
pub(super) fn also_acting(s: &Snapshot, i: usize, ground: usize) -> Option<&'static str> {
    if s.joints.iter().any(|j| j.body1 == i || j.body2 == i) {
        Some("a joint")
    } else if s.springs.iter().any(|x| x.body1 == i || x.body2 == Some(i)) {
        Some("a spring")
    } else if s.loads.iter().any(|l| l.body == i) {
        Some("a load")
    } else if s.couplings.iter().any(|c| c.terms.iter().any(|t| t.0 == i)) {
        Some("a coupling")
    } else if s.contacts.iter().any(|c| {
        (c.body1 == i || c.body2 == i) && c.body1 != ground && c.body2 != ground && c.pushes()
    }) {
        Some("another contact")
    } else {
        None
    }
}
