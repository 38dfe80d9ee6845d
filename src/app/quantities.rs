//! What the overlays and plots show, shaped for the eye. Every formula is the analysis layer's
//! (`crate::analysis`): the free-body diagram is `analysis::kinetics::free_body`, point velocities
//! RK-6, accelerations the step's finite differences, momenta 6/19. This file only groups a
//! diagram's impulses into the arrows a student draws (one normal force and one friction force per
//! contact, one reaction per joint) and averages them over a rendered frame.

use crate::analysis::kinematics::{acceleration_fd, angular_acceleration_fd, instantaneous_center};
use crate::analysis::kinetics::{self, Before, Source, StepImpulse};
use crate::analysis::Motion;
use crate::snapshot::{BodyKind, BodyState, Snapshot};
use glam::DVec2;

/// Instantaneous center of zero velocity C (RK-11), drawn only within a million body sizes of G:
/// farther, the body translates to the eye (the center is at infinity).
pub fn instant_center(b: &BodyState, size: f64) -> Option<DVec2> {
    instantaneous_center(b.com, b.velocity, b.omega, 1e6 * size.max(1e-9))
}

/// Every body's a_G and alpha over the last step by finite differences (`FD`), from its v_G and
/// omega before the step; zero before the first step.
pub fn accelerations(now: &Snapshot, prev: &[(DVec2, f64)], dt: f64) -> Vec<(DVec2, f64)> {
    now.bodies
        .iter()
        .zip(prev)
        .map(|(b, (v0, w0))| {
            if dt > 0.0 {
                (
                    acceleration_fd(*v0, b.velocity, dt),
                    angular_acceleration_fd(*w0, b.omega, dt),
                )
            } else {
                (DVec2::ZERO, 0.0)
            }
        })
        .collect()
}

/// What an arrow of the free-body diagram is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ForceKind {
    Gravity,
    ContactNormal,
    Friction,
    Joint,
    Spring,
    Load,
    /// An impulse event (a blow), drawn as its mean force over the step.
    Blow,
    /// A coupling's reaction (cable tension, gear tooth force) on the mass center.
    Coupling,
}

impl ForceKind {
    pub fn symbol(self) -> &'static str {
        match self {
            ForceKind::Gravity => "mg",
            ForceKind::ContactNormal => "N",
            ForceKind::Friction => "F",
            ForceKind::Joint => "R",
            ForceKind::Spring => "Fs",
            ForceKind::Load => "P",
            ForceKind::Blow => "P̂/Δt",
            ForceKind::Coupling => "T",
        }
    }
}

/// One arrow of the free-body diagram: a mean force, N, at its point of application.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Force {
    pub kind: ForceKind,
    /// Which one of its kind: the other body (contacts), or the index of the joint, coupling,
    /// spring, load or event. With `kind` it identifies the arrow from step to step.
    pub source: usize,
    pub point: DVec2,
    pub force: DVec2,
}

/// Body `i`'s free-body diagram over the step that led to `s` (`prev`: the snapshot before it,
/// when kept), as arrows: mean forces (impulse / dt) and the sum of its couples, N m. Before the
/// first step it shows the forces known without a step: weight, springs and loads.
pub fn free_body_arrows(prev: Option<&Snapshot>, s: &Snapshot, i: usize) -> (Vec<Force>, f64) {
    if s.is_initial() {
        // analysis reads a step's impulses; over a nominal 1 s step a held force's impulse is
        // the force itself (contacts and joints carry no impulse yet).
        let nominal = Snapshot {
            dt: 1.0,
            ..s.clone()
        };
        return free_body_arrows_mean([(None, &nominal)], i);
    }
    free_body_arrows_mean([(prev, s)], i)
}

/// The free-body diagram averaged over consecutive snapshots (each with the one before it, if
/// kept): each arrow's impulse over the window divided by its duration (the mean force), at its
/// impulse-weighted mean point; couples likewise. With a step much shorter than a frame, rapier
/// delivers contact impulses in bursts (many steps carry none); the mean over a frame is what the
/// eye can follow.
pub fn free_body_arrows_mean<'a>(
    steps: impl IntoIterator<Item = (Option<&'a Snapshot>, &'a Snapshot)>,
    i: usize,
) -> (Vec<Force>, f64) {
    let mut mean = MeanDiagram::default();
    for (prev, s) in steps {
        mean.add_step(prev, s, i);
    }
    mean.finish()
}

/// Each item of a run of snapshots with the one before it (None for the first).
pub fn with_previous<'a, T: 'a>(
    items: impl IntoIterator<Item = &'a T>,
) -> impl Iterator<Item = (Option<&'a T>, &'a T)> {
    let mut last: Option<&T> = None;
    items.into_iter().map(move |s| (last.replace(s), s))
}

/// Impulses summed per arrow over a window of steps.
#[derive(Default)]
struct MeanDiagram {
    /// Per arrow: the summed impulse (in `force`), point x |impulse| (in `point`), and sum |impulse|.
    arrows: Vec<(Force, f64)>,
    angular_impulse: f64,
    time: f64,
}

impl MeanDiagram {
    fn add_step(&mut self, prev: Option<&Snapshot>, s: &Snapshot, i: usize) {
        let b = &s.bodies[i];
        if s.dt <= 0.0 || b.kind != BodyKind::Dynamic {
            return;
        }
        self.time += s.dt;
        let start = prev.map(|p| Motion::from(&p.bodies[i]));
        let before = match &start {
            Some(m) => Before::One(i, m),
            None => Before::All(&[]),
        };
        for imp in kinetics::free_body(before, s, i, s.substeps) {
            self.angular_impulse += drawn_couple(s, &imp);
            // Drawn on the body where it is now: G at the end of the step plus the lever arm.
            let point = b.com + imp.arm;
            for (kind, source, impulse) in arrows_of(s, &imp) {
                self.add(kind, source, point, impulse);
            }
        }
    }

    fn add(&mut self, kind: ForceKind, source: usize, point: DVec2, impulse: DVec2) {
        let w = impulse.length();
        if w == 0.0 {
            return;
        }
        match self
            .arrows
            .iter_mut()
            .find(|(g, _)| g.kind == kind && g.source == source)
        {
            Some((g, wsum)) => {
                g.force += impulse;
                g.point += point * w;
                *wsum += w;
            }
            None => self.arrows.push((
                Force {
                    kind,
                    source,
                    point: point * w,
                    force: impulse,
                },
                w,
            )),
        }
    }

    fn finish(self) -> (Vec<Force>, f64) {
        if self.time == 0.0 {
            return (Vec::new(), 0.0);
        }
        let t = self.time;
        let out = self
            .arrows
            .into_iter()
            .map(|(f, w)| Force {
                force: f.force / t,
                point: f.point / w,
                ..f
            })
            .collect();
        (out, self.angular_impulse / t)
    }
}

/// The couple drawn with an impulse. A joint's is its constraint couple (a weld's, a slider's):
/// analysis's `couple` for a joint also holds the moment of the reaction's drift within the step
/// (its arm from G turns with the body over the substeps), which the arrow at the anchor shows and
/// a curl would misread (a pendulum's pin would show 0.5 N m).
fn drawn_couple(s: &Snapshot, imp: &StepImpulse) -> f64 {
    match imp.source {
        Source::Joint(k) if s.joints[k].body2 == imp.body => s.joints[k].couple_on_body2,
        Source::Joint(k) => -s.joints[k].couple_on_body2,
        _ => imp.couple,
    }
}

/// The arrows one impulse of the diagram is drawn as: a contact point's impulse as its normal and
/// its friction part (one arrow each per contact, keyed by the other body), anything else as one.
fn arrows_of(s: &Snapshot, imp: &StepImpulse) -> Vec<(ForceKind, usize, DVec2)> {
    let one = |kind, source| vec![(kind, source, imp.impulse)];
    match imp.source {
        Source::Gravity => one(ForceKind::Gravity, 0),
        Source::Load(k) => one(ForceKind::Load, k),
        Source::Spring(k) => one(ForceKind::Spring, k),
        Source::Event(k) => one(ForceKind::Blow, k),
        Source::Joint(k) => one(ForceKind::Joint, k),
        Source::Coupling(k, _) => one(ForceKind::Coupling, k),
        Source::Contact { contact, .. } => {
            let c = &s.contacts[contact];
            let other = imp.other.unwrap_or(usize::MAX);
            let normal = c.normal * imp.impulse.dot(c.normal);
            vec![
                (ForceKind::ContactNormal, other, normal),
                (ForceKind::Friction, other, imp.impulse - normal),
            ]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::kinematics::body_point_velocity;

    fn body(v: DVec2, w: f64) -> BodyState {
        BodyState {
            name: "b".into(),
            kind: BodyKind::Dynamic,
            position: DVec2::new(1.0, 2.0),
            angle: 0.0,
            com: DVec2::new(1.0, 2.0),
            velocity: v,
            omega: w,
            mass: 2.0,
            inertia: 0.5,
            local_com: DVec2::ZERO,
        }
    }

    #[test]
    fn rolling_wheel_has_its_instant_center_at_the_contact() {
        // A wheel of radius r rolling to the right without slip: v_G = omega r, omega = -v/r (CW).
        let r = 0.5;
        let b = body(DVec2::new(3.0, 0.0), -3.0 / r);
        let c = instant_center(&b, 1.0).unwrap();
        assert!((c - DVec2::new(1.0, 2.0 - r)).length() < 1e-12, "{c}");
        assert!(body_point_velocity(&b, c).length() < 1e-12);
        // The top point moves at 2 v_G.
        let top = body_point_velocity(&b, DVec2::new(1.0, 2.0 + r));
        assert!((top - DVec2::new(6.0, 0.0)).length() < 1e-12);
    }

    #[test]
    fn translation_has_no_instant_center() {
        assert!(instant_center(&body(DVec2::new(1.0, 0.0), 0.0), 1.0).is_none());
        // A turn so slow that C is beyond a million sizes is drawn as translation too.
        assert!(instant_center(&body(DVec2::new(1.0, 0.0), 1e-7), 1.0).is_none());
    }

    #[test]
    fn pairs_each_item_with_the_one_before() {
        let steps: Vec<(Option<&u32>, &u32)> = with_previous(&[0, 1, 2]).collect();
        assert_eq!(steps, vec![(None, &0), (Some(&0), &1), (Some(&1), &2)]);
    }
}
