//! The closed-form constant-acceleration check (free fall, projectile).

use super::super::{kind_name, CheckResult, ErrorTrack, Probe};
use super::{in_window, window_note, window_of};
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
}

impl ConstantAcceleration {
    pub(super) fn new(level: &Level, def: &CheckDef) -> Self {
        // Constant loads on the body add F/m to g.
        let body = def.body.clone().unwrap_or_default();
        let _ = level;
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
        }
    }
}

impl Probe for ConstantAcceleration {
    /// Reads the bodies only.
    fn reads_contacts(&self) -> bool {
        false
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
    let load: DVec2 = s
        .loads
        .iter()
        .filter(|l| l.body == i)
        .map(|l| l.force)
        .sum();
    s.gravity
        + if b.mass > 0.0 {
            load / b.mass
        } else {
            DVec2::ZERO
        }
}
