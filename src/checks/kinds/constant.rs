//! The closed-form constant-acceleration check (free fall, projectile).

use super::super::{kind_name, CheckResult, ErrorTrack, Probe};
use super::{
    body_def, cannot_judge, contact_pushing, damping_of, in_window, window_note, window_of,
};
use crate::level::{CheckDef, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Closed-form motion under a constant force (free fall, projectile: MK 2/x, HA 11.x):
/// r(t) = r0 + v0 t + 1/2 a t^2 with a = g + F/m. Theory is the closed form from the initial
/// state; engine is the mass center's position. Scale: the largest displacement |r - r0| of the run.
///
/// With a `window` (t1, t2) the closed form starts from the state at the window's first step
/// (the flight of a ball after it leaves a hand, before it lands) and is compared up to t2.
///
/// Error budget: symplectic Euler over substeps of h = dt/substeps gives x_n = x0 + v0 t + 1/2 a t (t + h),
/// so the position error grows as 1/2 |a| h t: relative to 1/2 |a| t^2 it is h / t.
///
/// The closed form assumes gravity and the body's constant loads act alone. Every compared step
/// verifies it on the scene: a joint, spring or coupling on the body, a contact with an impulse
/// on it, an impulse event on it, its loads' resultant changing from the first step's (by more
/// than 1e-9 of the larger of it and the weight), or linear damping (the level's `damping`
/// effect; angular damping does not move G) makes the check say it cannot judge, with the
/// first such step: it does not pass or fail on a formula that does not hold there.
pub(super) struct ConstantAcceleration {
    def: CheckDef,
    body: String,
    index: Option<usize>,
    r0: DVec2,
    v0: DVec2,
    /// Time and step of the state the closed form starts from.
    t0: f64,
    step0: u64,
    window: (f64, f64),
    track: ErrorTrack,
    max_disp: f64,
    accel: DVec2,
    /// The loads' resultant the closed form holds constant (after the first step).
    load: Option<DVec2>,
    /// Why the closed form does not hold on the scene (the first reason found), if it does not.
    broken: Option<String>,
}

impl ConstantAcceleration {
    pub(super) fn new(level: &Level, def: &CheckDef) -> Self {
        // Constant loads on the body add F/m to g.
        let body = def.body.clone().unwrap_or_default();
        // Linear damping scales v_G by 1/(1 + h c) every substep: a force the closed form lacks.
        let broken = body_def(level, &body).and_then(|b| {
            let (c, _) = damping_of(level, b);
            (c != 0.0).then(|| {
                format!(
                    "body \"{body}\" has linear_damping {c} 1/s: rapier takes m c v / (1 + h c) off it every substep h, a force the closed form a = g + F/m does not have"
                )
            })
        });
        ConstantAcceleration {
            def: def.clone(),
            body,
            index: None,
            r0: DVec2::ZERO,
            v0: DVec2::ZERO,
            t0: 0.0,
            step0: 0,
            window: window_of(def),
            track: ErrorTrack::default(),
            max_disp: 0.0,
            accel: DVec2::ZERO,
            load: None,
            broken,
        }
    }

    /// Why gravity and constant loads are not all that acts on body i over the step that led
    /// to `s`, if they are not.
    fn other_action(&mut self, s: &Snapshot, i: usize) -> Option<String> {
        let at = format!("at t = {:.4} s", s.time);
        if let Some(j) = s.joints.iter().find(|j| j.body1 == i || j.body2 == i) {
            return Some(format!("joint \"{}\" acts on it", j.name));
        }
        if let Some(sp) = s
            .springs
            .iter()
            .find(|sp| sp.body1 == i || sp.body2 == Some(i))
        {
            return Some(format!("spring \"{}\" acts on it", sp.name));
        }
        if let Some(c) = s
            .couplings
            .iter()
            .find(|c| c.terms.iter().any(|t| t.0 == i))
        {
            return Some(format!("coupling \"{}\" acts on it", c.name));
        }
        if let Some(why) = contact_pushing(s, i, &at) {
            return Some(why);
        }
        if let Some(e) = s.impulses.iter().find(|e| e.body == i) {
            return Some(format!("the impulse event \"{}\" strikes it {at}", e.name));
        }
        let load = loads_on(s, i);
        match self.load {
            None => self.load = Some(load),
            Some(l0) => {
                let b = &s.bodies[i];
                let size = l0.length().max(b.mass * s.gravity.length());
                if (load - l0).length() > 1e-9 * size {
                    return Some(format!(
                        "its loads' resultant changes from ({:.4}, {:.4}) N to ({:.4}, {:.4}) N {at}",
                        l0.x, l0.y, load.x, load.y
                    ));
                }
            }
        }
        None
    }
}

impl Probe for ConstantAcceleration {
    /// Reads the contacts: one that pushes on the body breaks the closed form's assumption.
    fn reads_contacts(&self) -> bool {
        true
    }

    fn observe(&mut self, s: &Snapshot) {
        if !in_window(self.window, s.time) {
            return;
        }
        let Some(i) = self.index.or_else(|| s.body_index(&self.body)) else {
            return;
        };
        let b = &s.bodies[i];
        if self.index.is_none() {
            self.index = Some(i);
            self.r0 = b.com;
            self.v0 = b.velocity;
            self.t0 = s.time;
            self.step0 = s.step;
            self.accel = constant_acceleration(s, i);
            return;
        }
        if s.step == self.step0 + 1 && b.mass > 0.0 {
            // Loads are known only once a step applied them.
            self.accel = constant_acceleration(s, i);
        }
        if self.broken.is_none() {
            self.broken = self.other_action(s, i);
        }
        let t = s.time - self.t0;
        let theory = self.r0 + self.v0 * t + 0.5 * self.accel * t * t;
        let err = (b.com - theory).length();
        self.max_disp = self.max_disp.max((theory - self.r0).length());
        // Track the vector error through the scalar tracker: theory distance vs engine distance along the error.
        self.track.add(0.0, err);
        self.track.last_theory = (theory - self.r0).length();
        self.track.last_engine = (b.com - self.r0).length();
    }

    fn finish(self: Box<Self>) -> CheckResult {
        if let Some(why) = &self.broken {
            return cannot_judge(
                &self.def,
                format!("body \"{}\" mass center", self.body),
                format!(
                    "the closed form r0 + v0 t + a t^2 / 2 assumes gravity and constant loads act alone, and {why}{}",
                    window_note(&self.def)
                ),
            );
        }
        let note = format!(
            "position error |r_engine - r_theory|; displacement scale {:.4} m{}",
            self.max_disp,
            window_note(&self.def)
        );
        self.track.result(
            &self.def,
            kind_name(self.def.kind),
            format!("body \"{}\" mass center", self.body),
            self.max_disp,
            note,
        )
    }
}

/// a = g + F/m for body i under the snapshot's loads (g alone for a body without mass: the
/// initial snapshot, before rapier computed its mass properties).
fn constant_acceleration(s: &Snapshot, i: usize) -> DVec2 {
    let b = &s.bodies[i];
    let load = loads_on(s, i);
    s.gravity
        + if b.mass > 0.0 {
            load / b.mass
        } else {
            DVec2::ZERO
        }
}

/// The resultant of the snapshot's loads on body i, N.
fn loads_on(s: &Snapshot, i: usize) -> DVec2 {
    s.loads
        .iter()
        .filter(|l| l.body == i)
        .map(|l| l.force)
        .sum()
}
