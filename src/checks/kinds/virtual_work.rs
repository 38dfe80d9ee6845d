//! `virtual_work`: a one-degree-of-freedom mechanism's motor against virtual work, every step.

use super::{misconfigured, result, scale_or, subject_of, Summary, Worst};
use crate::analysis::kinetics::finite_difference_resolution;
use crate::analysis::virtual_work::{
    actuator_effort, applied_forces, links_of, not_a_mechanism, virtual_velocities,
};
use crate::analysis::Motion;
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, JointKind, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// `virtual_work` on the joint named by `body` (a pin or slider with a motor, the mechanism's
/// driver). Theory: the actuator effort that virtual work gives (VW-2 with the inertia forces of
/// VW-5, MK 6/11a), Q = sum (m a_G . v_G + I_G alpha omega) - sum (F . v_P + C omega), the
/// virtual velocities from the mechanism's joints at the step's end pose for a unit driver rate
/// (`analysis::virtual_work`), a_G and alpha the change of rapier's velocities over the step / dt,
/// the applied forces those the engine held over the step (weights, loads, springs, other
/// motors). Engine: the motor's impulse over the step / dt. At rest the inertia terms vanish and
/// this is the principle of virtual work of statics. The field is taken at the step's middle
/// (poses and joint anchors averaged between its start and end), where the mean of the step's
/// accelerations acts: from its end pose instead, a crank at 209 rad/s read 78% off (the rod's
/// and piston's large reactions do virtual work on a field a step of motion away from the one
/// the solver used). Error: |Q - engine| relative to the largest |Q| or |engine| of the run (or
/// of its `window`), after discounting what the engine's precision cannot resolve in the step
/// (each body's rounding of m dv and I dw, `kinetics::finite_difference_resolution`, weighted by
/// its virtual velocity, twice: the motor's impulse is rounded the same way). A run whose
/// rounding exceeds half the effort fails and says to use `world.precision: f64`: a 10 kg m^2
/// flywheel crank at 209 rad/s in f32 rounds its velocity in steps worth 7.6 N m of motor torque
/// at dt = 2e-5 s, against a true effort of 53 N m.
pub(super) fn probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    let Some(name) = def.body.as_deref() else {
        return misconfigured(
            def,
            "a virtual_work check needs `body: \"...\"`: the motor's joint",
        );
    };
    let Some(k) = level.joints.iter().position(|j| j.name == name) else {
        return misconfigured(
            def,
            format!("\"{name}\" is not a joint: a virtual_work check names the joint whose motor drives the mechanism"),
        );
    };
    let j = &level.joints[k];
    if j.motor.is_none() || !matches!(j.kind, JointKind::Revolute | JointKind::Prismatic) {
        return misconfigured(
            def,
            format!("joint \"{name}\" is not a pin or slider with a motor: virtual work gives the effort of the actuator that drives a mechanism"),
        );
    }
    Box::new(VirtualWork {
        def: def.clone(),
        driver: k,
        kinds: level
            .joints
            .iter()
            .map(|j| (j.kind, DVec2::new(j.axis.0, j.axis.1)))
            .collect(),
        before: Vec::new(),
        prev: None,
        worst: Worst::over(def),
        scale: 0.0,
        resolution: 0.0,
        raw_max: 0.0,
        last: (0.0, 0.0),
        why_not: None,
    })
}

struct VirtualWork {
    def: CheckDef,
    driver: usize,
    kinds: Vec<(JointKind, DVec2)>,
    /// Every body's (v_G, omega) at the start of the step.
    before: Vec<(DVec2, f64)>,
    /// The snapshot at the start of the step (its poses and joint anchors).
    prev: Option<Snapshot>,
    worst: Worst,
    scale: f64,
    /// The largest effort the engine's precision cannot resolve in a step (see `observe`).
    resolution: f64,
    /// The largest |Q - motor| before that discount.
    raw_max: f64,
    last: (f64, f64),
    /// Why virtual work did not apply, the first time it did not.
    why_not: Option<String>,
}

impl Probe for VirtualWork {
    fn observe(&mut self, s: &Snapshot) {
        let now: Vec<(DVec2, f64)> = s.bodies.iter().map(|b| (b.velocity, b.omega)).collect();
        let before = std::mem::replace(&mut self.before, now);
        let prev = self.prev.replace(s.clone());
        if s.is_initial() || before.len() != s.bodies.len() || s.joints.len() <= self.driver {
            return;
        }
        let mid = prev.map_or_else(|| s.clone(), |p| middle_of_step(&p, s));
        let links = links_of(&mid, &self.kinds);
        let field = match virtual_velocities(&mid.bodies, &links, self.driver) {
            Ok(f) => f,
            Err(e) => {
                self.why_not.get_or_insert(e);
                return;
            }
        };
        if let Some(e) = not_a_mechanism(s, &field) {
            self.why_not.get_or_insert(e);
            return;
        }
        let acc: Vec<(DVec2, f64)> = s
            .bodies
            .iter()
            .zip(&before)
            .map(|(b, (v0, w0))| ((b.velocity - *v0) / s.dt, (b.omega - w0) / s.dt))
            .collect();
        let theory = actuator_effort(
            &mid.bodies,
            &field,
            applied_forces(s, &links, self.driver),
            Some(&acc),
        );
        let engine = s.joints[self.driver].motor_impulse / s.dt;
        // What the engine's precision resolves: each body's m dv and I dw over the step carry
        // rounding (`finite_difference_resolution`), weighted by its virtual velocity; the
        // motor's impulse is rounded as its body's velocity is, so the sum counts twice.
        let resolution: f64 = 2.0
            * s.bodies
                .iter()
                .zip(&before)
                .enumerate()
                .map(|(i, (b, (v0, w0)))| {
                    let start = Motion {
                        velocity: *v0,
                        omega: *w0,
                        ..Motion::from(b)
                    };
                    let (rf, rm) = finite_difference_resolution(
                        b.mass,
                        b.inertia,
                        &start,
                        &Motion::from(b),
                        s.precision.epsilon(),
                        s.substeps,
                        s.dt,
                    );
                    rf * field.velocity[i].length() + rm * field.omega[i].abs()
                })
                .sum::<f64>();
        if self.worst.covers(s.time) {
            self.scale = self.scale.max(engine.abs()).max(theory.abs());
            self.resolution = self.resolution.max(resolution);
        }
        let err = theory - engine;
        if self.worst.covers(s.time) {
            self.raw_max = self.raw_max.max(err.abs());
        }
        self.worst
            .add(err.signum() * (err.abs() - resolution).max(0.0), s.time);
        self.last = (theory, engine);
    }

    fn finish(self: Box<Self>) -> CheckResult {
        let scale = scale_or(self.scale, 1.0);
        let mut note = format!(
            "actuator effort by virtual work (with the inertia forces) against the motor; largest |Q - motor| {:.3e} at t = {:.4} s, scale {:.4e}",
            self.worst.max, self.worst.at_time, scale
        );
        if self.resolution > 0.0 {
            note += &format!(
                "; discounted per step: the engine's rounding of velocities, up to {:.3e} ({:.2}% of the effort; before the discount |Q - motor| reached {:.3e}, {:.2e} of the effort){}",
                self.resolution,
                100.0 * self.resolution / scale,
                self.raw_max,
                self.raw_max / scale,
                if self.worst.max == 0.0 && self.raw_max > 0.0 {
                    ": every step within the rounding, so the check could fail only above it (world.precision: f64 resolves it)"
                } else {
                    ""
                }
            );
        }
        // Mostly rounding: nothing was compared.
        let unresolved = self.resolution > 0.5 * scale;
        if unresolved {
            note = format!(
                "the engine's precision cannot resolve the effort: its velocities' rounding amounts to {:.3e} against an effort of {:.3e} (a heavy flywheel at speed, say); give the level world.precision: f64; {note}",
                self.resolution, scale
            );
        }
        if let Some(w) = &self.why_not {
            note = format!("{w}; {note}");
        }
        let mut summary = Summary::from_worst(self.last, &self.worst, scale, note);
        if self.why_not.is_some() || unresolved {
            // A step the principle could not be applied to is not a pass.
            summary.max_rel = f64::INFINITY;
        }
        result(&self.def, subject_of(&self.def), summary)
    }
}

/// The step's middle: `end` with every body's G and angle, and every joint's anchors, halfway
/// from where they were at the step's start (`start`; the initial snapshot has no joints, so
/// the first step keeps the end's anchors).
fn middle_of_step(start: &Snapshot, end: &Snapshot) -> Snapshot {
    let mut mid = end.clone();
    for (m, a) in mid.bodies.iter_mut().zip(&start.bodies) {
        m.com = 0.5 * (m.com + a.com);
        m.position = 0.5 * (m.position + a.position);
        m.angle = 0.5 * (m.angle + a.angle);
    }
    if start.joints.len() == end.joints.len() {
        for (m, a) in mid.joints.iter_mut().zip(&start.joints) {
            m.anchor = 0.5 * (m.anchor + a.anchor);
            m.anchor1 = 0.5 * (m.anchor1 + a.anchor1);
        }
    }
    mid
}
