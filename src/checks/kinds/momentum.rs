//! Momentum checks: `angular_momentum_fixed_point`, `impulse_momentum`.

use super::{
    cannot_judge_probe, damped_subject, dynamic_body, framed, misconfigured, result, scale_or,
    subject_index, subject_of, subject_set, v2, BodySet, FrameProbe, Summary, Together, Worst,
};
use crate::analysis::cross;
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::analysis::kinetics::finite_difference_resolution;
use crate::analysis::momentum::{
    angular_momentum_about, linear_momentum, ImpulseMomentumLedger, WindowBalance,
};
use crate::analysis::Motion;
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// The body's pivot: the anchor of its first joint to a body that does not move (fixed or
/// kinematic at rest), at the first snapshot.
pub(super) fn pivot_of(s: &Snapshot, i: usize) -> Option<DVec2> {
    s.joints.iter().find_map(|j| {
        if j.body2 == i && s.bodies[j.body1].mass == 0.0 {
            Some(j.anchor1)
        } else if j.body1 == i && s.bodies[j.body2].mass == 0.0 {
            Some(j.anchor)
        } else {
            None
        }
    })
}

/// The subject of a momentum check: one dynamic body or the whole scene.
fn resolve(level: &Level, def: &CheckDef) -> Result<Option<String>, String> {
    match &def.body {
        Some(_) => dynamic_body(level, def).map(|b| Some(b.name.clone())),
        None => Ok(None),
    }
}

// ---------------------------------------------------------------------------------------------

/// `angular_momentum_fixed_point`: sum M_O = dH_O/dt about a fixed point O (6/17, IM-7), step by step.
///
/// Theory: the moments about O of every external force of the free-body diagram over the step
/// (gravity at G, the joint reactions at their anchors, contacts, loads, springs, events,
/// couplings), divided by dt. Engine: the change of H_O = I_G omega + r_{G/O} x m v_G (6/15) of
/// rapier's state over the step, divided by dt: a finite difference of the engine's motion.
/// O is `point`, or else the body's pivot (its joint to a fixed body). For a pin at O the pivot
/// reaction has (almost) no moment, so the check tests gravity's moment against the motion
/// (PL-5); the note gives the largest moment the reactions did have about O.
/// Scale, step by step: the step's moment level max(|sum M_O|, |dH_O/dt|, m |g| |r_G - O|,
/// (max |F_i| |r_G - O| + max |C_i|)) over the diagram's single forces F_i and couples C_i (so one
/// blow does not hide the other steps, and a body spinning freely on its pin, where the sums
/// vanish, is measured against the pin's pull); the reported scale is the one at the worst step.
///
/// The diagram holds no body damping (`damped_body`): with a damped body in the subject (the
/// body, or for the scene any dynamic body) the check cannot judge.
pub(super) fn angular_momentum_fixed_point(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    angular_momentum_fixed_point_of(level, def).map_or_else(|refused| refused, framed)
}

/// The `angular_momentum_fixed_point` probe of `def`, or the probe that refuses it: a
/// `CheckSet` runs the former with the level's other probes of the kind.
pub(super) fn angular_momentum_fixed_point_of(
    level: &Level,
    def: &CheckDef,
) -> Result<AngularMomentumFixedPoint, Box<dyn Probe>> {
    let body = match resolve(level, def) {
        Ok(b) => b,
        Err(e) => return Err(misconfigured(def, e)),
    };
    if let Some(why) = damped_subject(level, body.as_deref()) {
        return Err(cannot_judge_probe(def, format!("sum M_O = dH_O/dt: {why}")));
    }
    if body.is_none() && def.point.is_none() {
        return Err(misconfigured(
            def,
            "a scene-wide angular_momentum_fixed_point check needs `point: (x, y)`",
        ));
    }
    Ok(AngularMomentumFixedPoint {
        def: def.clone(),
        body,
        o: def.point.map(v2),
        index: None,
        set: BodySet::default(),
        set_joints: Vec::new(),
        worst: Worst::over(def),
        rel: Worst::over(def),
        scale_at_worst: 0.0,
        max_moment: 0.0,
        max_reaction_moment: 0.0,
        last: (0.0, 0.0),
        unresolved: None,
    })
}

pub(super) struct AngularMomentumFixedPoint {
    def: CheckDef,
    body: Option<String>,
    o: Option<DVec2>,
    /// The body's index (None for the scene).
    index: Option<usize>,
    set: BodySet,
    /// The joints with exactly one side on the set: those whose reaction is external.
    set_joints: Vec<usize>,
    worst: Worst,
    rel: Worst,
    scale_at_worst: f64,
    max_moment: f64,
    max_reaction_moment: f64,
    last: (f64, f64),
    unresolved: Option<String>,
}

/// Each probe as on its own, in one loop.
impl Together for AngularMomentumFixedPoint {
    type Shared = ();
}

impl FrameProbe for AngularMomentumFixedPoint {
    /// The frame's impulse sums and momenta, not the work of the forces.
    fn frame_pass(&self) -> FramePass {
        FramePass::Diagram
    }

    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        if self.unresolved.is_some() {
            return;
        }
        if self.set.is_empty() {
            let Some(index) = subject_index(s, self.body.as_deref()) else {
                return;
            };
            self.index = index;
            self.set = subject_set(s, self.index);
            // The joints with a side on the set (a scene's joints do not come or go).
            self.set_joints = (0..s.joints.len())
                .filter(|&k| {
                    let j = &s.joints[k];
                    self.set.contains(&j.body1) != self.set.contains(&j.body2)
                })
                .collect();
            if self.o.is_none() {
                self.o = self.index.and_then(|i| pivot_of(s, i));
                if self.o.is_none() {
                    self.unresolved = Some(
                        "no `point` given and the body has no joint to a fixed body: give the fixed point O".into(),
                    );
                    return;
                }
            }
        }
        let o = self.o.unwrap_or_default();
        let f = fa.frame();
        if !f.stepped {
            return;
        }
        // The step's external impulses on the set and H_O at both ends (6/15).
        let (sums, h, h_before) = match self.index {
            Some(i) => {
                let b = &s.bodies[i];
                let h = |m: &Motion| {
                    angular_momentum_about(b.mass, b.inertia, m.com, m.velocity, m.omega, o)
                };
                (
                    f.bodies[i].impulses,
                    h(&Motion::from(b)),
                    h(&fa.start_of_step()[i]),
                )
            }
            None => (
                f.external,
                f.totals.angular_momentum_about(o),
                f.totals_before.angular_momentum_about(o),
            ),
        };
        let theory = sums.moment_about(o) / s.dt;
        let engine = (h - h_before) / s.dt;
        // The joint reactions' angular impulse about O (for the note): per joint side on the set
        // whose other side is not, H_G's share plus (r_G - r_O) x J.
        let mut reaction = 0.0;
        for &k in &self.set_joints {
            let j = &s.joints[k];
            let (in1, in2) = (self.set.contains(&j.body1), self.set.contains(&j.body2));
            if in2 && !in1 {
                let r = s.bodies[j.body2].com - o;
                reaction += j.angular_impulse_on_body2 + cross(r, j.impulse_on_body2);
            }
            if in1 && !in2 {
                let r = s.bodies[j.body1].com - o;
                reaction += j.angular_impulse_on_body1 - cross(r, j.impulse_on_body2);
            }
        }
        // The weights' moment arms summed, and the set's reach from O, in one pass.
        let (mass_arms, reach) = self.set.iter().fold((0.0, 0.0f64), |(m, r), &i| {
            let d = (s.bodies[i].com - o).length();
            (m + s.bodies[i].mass * d, r.max(d))
        });
        let weight = mass_arms * s.gravity.length();
        // The forces that balance count too (as in `newton_euler`): a bar spinning freely on
        // its pin has sum M_O and dH_O/dt near zero, while the pin pulls it round with m r w^2;
        // a residual that small a force's moment at the set's reach explains is not 100 %.
        let balanced = (sums.largest_impulse * reach + sums.largest_couple) / s.dt;
        let level = theory
            .abs()
            .max(engine.abs())
            .max(weight)
            .max(balanced)
            .max(1e-12);
        let rel = (theory - engine).abs() / level;
        if rel > self.rel.max || self.rel.samples == 0 {
            self.scale_at_worst = level;
        }
        self.rel.add(rel, s.time);
        self.worst.add(theory - engine, s.time);
        self.max_moment = self.max_moment.max(theory.abs()).max(engine.abs());
        self.max_reaction_moment = self.max_reaction_moment.max((reaction / s.dt).abs());
        self.last = (theory, engine);
    }

    fn finish(self) -> CheckResult {
        if let Some(why) = self.unresolved {
            return misconfigured(&self.def, why).finish();
        }
        let scale = scale_or(self.scale_at_worst, 1.0);
        let o = self.o.unwrap_or_default();
        let note = format!(
            "O = ({:.4}, {:.4}); worst step t = {:.3} s (moment level {:.4} N m there); largest residual {:.2e} N m at t = {:.3} s; max |sum M_O| {:.4} N m; the joint reactions' largest moment about O {:.2e} N m",
            o.x, o.y, self.rel.at_time, scale, self.worst.max, self.worst.at_time, self.max_moment, self.max_reaction_moment
        );
        let mut subject = subject_of(&self.def);
        if self.def.point.is_none() {
            subject += &format!(" about its pivot ({:.3}, {:.3})", o.x, o.y);
        }
        result(
            &self.def,
            subject,
            Summary {
                theory: self.last.0,
                engine: self.last.1,
                max_abs: self.worst.max,
                max_rel: self.rel.max,
                final_abs: self.worst.last,
                final_rel: self.rel.last,
                samples: self.rel.samples,
                scale,
                note,
            },
        )
    }
}

// ---------------------------------------------------------------------------------------------

/// `impulse_momentum`: G(t2) - G(t1) = integral of sum F dt (6/12, IM-2, IM-3), and with `point`
/// also H_O(t2) - H_O(t1) = integral of sum M_O dt about that fixed point (6/17, IM-7), over every
/// window [t1, t2] of the run (or of the level's `window`), by the running ledger of
/// `analysis::momentum::ImpulseMomentumLedger`.
///
/// Theory: the sum of every external impulse of the free-body diagram over the window (for the
/// scene: forces between its bodies are internal and cancel, 6/18). Engine: G and H_O of rapier's
/// state at both ends. A system with no external impulse shows the conservation laws (IM-4, IM-8).
/// The error is the worst window: the residual over [t1, t2] is r(t2) - r(t1), r the residual
/// from the start, so it is at most twice the worst [start, t] residual, and the ledger finds it
/// exactly. Scale: the largest |G| (and |H_O|) of the window, theory or engine; the reported
/// relative error is the larger of the two.
pub(super) fn impulse_momentum(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    let body = match resolve(level, def) {
        Ok(b) => b,
        Err(e) => return misconfigured(def, e),
    };
    // The diagram's impulses hold no body damping (rapier's velocity scaling), as for
    // `angular_momentum_fixed_point`.
    if let Some(why) = damped_subject(level, body.as_deref()) {
        return cannot_judge_probe(def, format!("the impulse-momentum ledger: {why}"));
    }
    framed(ImpulseMomentum {
        def: def.clone(),
        body,
        o: def.point.map(v2),
        window: def.window.unwrap_or((0.0, f64::INFINITY)),
        duration: level.world.duration,
        index: None,
        subject: BodySet::default(),
        resolved: false,
        ledger: None,
        // Its own windows (every [t1', t2'] inside `window`, see `ImpulseMomentumLedger`).
        g_worst: Worst::default(),
        h_worst: Worst::default(),
        g_scale: 0.0,
        h_scale: 0.0,
        last: (0.0, 0.0),
    })
}

struct ImpulseMomentum {
    def: CheckDef,
    body: Option<String>,
    o: Option<DVec2>,
    /// [t1, t2]: the steps that start at or after t1 and end at or before t2 (within half a step).
    window: (f64, f64),
    /// The level's run, s (to size the ledger).
    duration: f64,
    /// The body's index (None for the scene).
    index: Option<usize>,
    /// The subject's bodies (the one body, or every dynamic body), resolved with `index`.
    subject: BodySet,
    resolved: bool,
    ledger: Option<ImpulseMomentumLedger>,
    /// Residuals over [t1, t], step by step (these also catch a non-finite state).
    g_worst: Worst,
    h_worst: Worst,
    g_scale: f64,
    h_scale: f64,
    /// Theory (momentum at t1 plus the impulses since) and engine (momentum now), last step.
    last: (f64, f64),
}

impl FrameProbe for ImpulseMomentum {
    /// The frame's impulse sums and momenta, not the work of the forces.
    fn frame_pass(&self) -> FramePass {
        FramePass::Diagram
    }

    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        let o = self.o.unwrap_or_default();
        if !self.resolved {
            let Some(index) = subject_index(s, self.body.as_deref()) else {
                return;
            };
            self.index = index;
            self.subject = subject_set(s, index);
            self.resolved = true;
        }
        let f = fa.frame();
        if !f.stepped {
            return;
        }
        // Only steps inside the window (half a step of slack for the float times).
        let (t1, t2) = self.window;
        let start = s.time - s.dt;
        if start < t1 - 0.5 * s.dt || s.time > t2 + 0.5 * s.dt {
            return;
        }
        // G and H_O of the set from rapier's state, at the start of the step or at its end.
        let momenta = |start: bool| -> (DVec2, f64) {
            match self.index {
                Some(i) => {
                    let b = &s.bodies[i];
                    let m = if start {
                        fa.start_of_step()[i]
                    } else {
                        Motion::from(b)
                    };
                    (
                        linear_momentum(b.mass, m.velocity),
                        angular_momentum_about(b.mass, b.inertia, m.com, m.velocity, m.omega, o),
                    )
                }
                None => {
                    let t = if start { &f.totals_before } else { &f.totals };
                    (t.linear_momentum, t.angular_momentum_about(o))
                }
            }
        };
        let duration = self.duration;
        let ledger = self.ledger.get_or_insert_with(|| {
            let (g0, h0) = momenta(true);
            // Room for the window's steps in the level's run (at most a million instants: a
            // longer run grows the ledger as it goes).
            let end = t2.min(duration);
            let steps = ((end - start) / s.dt).ceil();
            let instants = if steps.is_finite() && steps > 0.0 {
                (steps as usize).min(1 << 20) + 2
            } else {
                1
            };
            // About no point, G alone: the ledger then stores two thirds of the bytes a step.
            match self.o {
                Some(_) => ImpulseMomentumLedger::with_capacity(start, g0, h0, instants),
                None => ImpulseMomentumLedger::linear_only(start, g0, instants),
            }
        });
        let sums = match self.index {
            Some(i) => f.bodies[i].impulses,
            None => f.external,
        };
        let (g, h) = momenta(false);
        // What the engine's floating point may round away from G and H_O in this step: each
        // body's m dv and I dw carry up to m (|v0| + |v1|) eps n and I (|w0| + |w1|) eps n
        // (`kinetics::finite_difference_resolution`). A block sliding to rest in f32 at 16
        // substeps has its velocity decrement, a few ulps, rounded the same way every substep:
        // a bias of 1.1e-3 N s over the run that f64 does not show (3e-15).
        let rounding = {
            let (mut rg, mut rh) = (0.0, 0.0);
            for &i in &self.subject {
                let b = &s.bodies[i];
                let (rf, rm) = finite_difference_resolution(
                    b.mass,
                    b.inertia,
                    &fa.start_of_step()[i],
                    &Motion::from(b),
                    s.precision.epsilon(),
                    s.substeps,
                    s.dt,
                );
                rg += rf * s.dt;
                rh += (rm + rf * (b.com - o).length()) * s.dt;
            }
            (rg, rh)
        };
        ledger.record_rounded(s.time, sums.impulse, sums.moment_about(o), g, h, rounding);
        let from_t1 = ledger.since_start();
        let theory_g = g - from_t1.delta_g + from_t1.linear_impulse;
        self.g_worst.add(from_t1.linear_beyond_rounding(), s.time);
        // Scales: the set's G and H_O, and the momenta its bodies carry one by one (two discs
        // swapping H through a torsion spring have H_O = 0 throughout, yet each carries some).
        // (One body: its own G and H_O, computed above.)
        let (g_bodies, h_bodies) = match self.index {
            Some(_) => (g.length(), h.abs()),
            None => self
                .subject
                .iter()
                .map(|&i| &s.bodies[i])
                .filter(|b| b.mass > 0.0)
                .fold((0.0, 0.0), |(gs, hs), b| {
                    (
                        gs + linear_momentum(b.mass, b.velocity).length(),
                        hs + angular_momentum_about(
                            b.mass, b.inertia, b.com, b.velocity, b.omega, o,
                        )
                        .abs(),
                    )
                }),
        };
        self.g_scale = self
            .g_scale
            .max(g.length())
            .max(theory_g.length())
            .max(g_bodies);
        if self.o.is_some() {
            let theory_h = h - from_t1.delta_h + from_t1.angular_impulse;
            self.h_worst.add(from_t1.angular_beyond_rounding(), s.time);
            self.h_scale = self.h_scale.max(h.abs()).max(theory_h.abs()).max(h_bodies);
            self.last = (theory_h, h);
        } else {
            self.last = (theory_g.length(), g.length());
        }
    }

    fn finish(self) -> CheckResult {
        let g_scale = scale_or(self.g_scale, 1.0);
        let h_scale = scale_or(self.h_scale, 1.0);
        let (worst, last) = match &self.ledger {
            Some(l) => (l.worst_windows_beyond_rounding(), l.since_start()),
            None => (Default::default(), WindowBalance::default()),
        };
        // The worst window, or the worst [t1, t] residual if that is larger (never smaller, but a
        // non-finite residual only shows there).
        let g_abs = worst.linear.linear_beyond_rounding().max(self.g_worst.max);
        let mut note = format!(
            "window [{:.3}, {:.3}] s; G: worst window [{:.3}, {:.3}] s, |dG - integral of F dt| {:.2e} N s beyond the {:.2e} N s the engine's rounding may explain there; from the start {:.2e} N s at t = {:.3} s (scale {:.4} N s)",
            last.t1,
            last.t2,
            worst.linear.t1,
            worst.linear.t2,
            g_abs,
            worst.linear.rounding_g,
            self.g_worst.max,
            self.g_worst.at_time,
            g_scale
        );
        let (mut max_rel, mut final_rel, mut max_abs, mut final_abs, mut scale) = (
            g_abs / g_scale,
            self.g_worst.last / g_scale,
            g_abs,
            self.g_worst.last,
            g_scale,
        );
        if let Some(o) = self.o {
            let h_abs = worst
                .angular
                .angular_beyond_rounding()
                .max(self.h_worst.max);
            note += &format!(
                "; H about ({:.4}, {:.4}): worst window [{:.3}, {:.3}] s, |dH_O - integral of M_O dt| {:.2e} N m s; from the start {:.2e} N m s at t = {:.3} s (scale {:.4} N m s)",
                o.x, o.y, worst.angular.t1, worst.angular.t2, h_abs, self.h_worst.max, self.h_worst.at_time, h_scale
            );
            // The headline is H_O (theory/engine report it); the error is the worse of the two.
            max_abs = h_abs;
            final_abs = self.h_worst.last;
            scale = h_scale;
            final_rel = final_rel.max(self.h_worst.last / h_scale);
            max_rel = max_rel.max(h_abs / h_scale);
        }
        result(
            &self.def,
            subject_of(&self.def),
            Summary {
                theory: self.last.0,
                engine: self.last.1,
                max_abs,
                max_rel,
                final_abs,
                final_rel,
                samples: self.g_worst.samples,
                scale,
                note,
            },
        )
    }
}
