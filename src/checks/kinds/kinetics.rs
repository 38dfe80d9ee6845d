//! `newton_euler`: the free-body diagram against the kinetic diagram, every step (6/1, 6/2).

use super::momentum::pivot_of;
use super::{
    cached_body, cannot_judge_probe, damped_body, dynamic_body, framed, misconfigured, result,
    scale_or, subject_of, textbook_mass, v2, FrameProbe, Summary, Together, Worst,
};
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::analysis::kinetics::{
    finite_difference_resolution, gravity_point, kinetic_moment_about, kinetic_moment_fixed_axis,
};
use crate::analysis::mass::{parallel_axis, MassProps};
use crate::analysis::Motion;
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// `newton_euler`: the free-body diagram against the kinetic diagram, one body, every step.
///
/// Without `point`: sum F = m a_G and sum M_G = I_G alpha (6/1). Theory: the free-body diagram of
/// the step read from the snapshot (`analysis::kinetics`): gravity, loads, springs, event
/// impulses, every contact point's normal and friction impulse, joint reactions, couplings;
/// forces as impulse / dt. Engine: m a_G and I_G alpha with a_G and alpha by finite differences of
/// rapier's velocities over the step (`FD`), rapier's m and I_G.
/// Error, step by step: the force residual |sum F - m a_G| relative to the step's force level
/// F_s = max(|sum F|, m |a_G|, m |g|, max |F_i|, max |C_i| / k_G) over the diagram's forces F_i
/// and couples C_i (so one impulsive step does not hide the others, and a mechanism at rest,
/// where sum F and m a_G vanish, is measured against the forces that balance); the moment
/// residual relative to F_s k_G; the largest of these over the run (or its `window`). The
/// reported scale is F_s at the worst step.
///
/// With `point` P: the moment equation about P instead, as the textbook takes it to eliminate a
/// reaction: sum M_P = I_G alpha + (r_{G/P} x m a_G)_z (6/2), and when P is the body's fixed pivot
/// also sum M_O = I_O alpha (6/4) with I_O = I_G + m r_bar^2 (MP-2). Theory: the moments about P
/// of the free-body diagram (a pin at P has none). Engine: the kinetic moments with the level's
/// textbook m and I_G (shape formula) and rapier's a_G and alpha (`FD`). r_{G/P} is taken at the
/// mean of the substeps' start positions of G: with v' = v + J/m and then r' = r + v' h per
/// substep (symplectic Euler), each substep's m dv acts at its start position, so for a constant
/// a_G over the step this makes 6/2 the exact discrete moment of momentum about a fixed P (and it
/// is where the diagram puts gravity). Error relative to F_s L_P, L_P the larger of k_G and
/// |r_G - r_P|.
///
/// A joint's reaction is summed over every substep (split substeps, `sim::Settings`), so an
/// impulsive reaction in the first substep (a strike on a pinned body) is in the diagram.
/// About the pin (`point`) the reaction drops out altogether.
///
/// The diagram is the engine's impulses, which hold no body damping (`damped_body`): on a damped
/// body the check cannot judge (only linear damping counts for a locked body's sum F alone).
pub(super) fn probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    newton_euler(level, def).map_or_else(|refused| refused, framed)
}

/// The `newton_euler` probe of `def`, or the probe that refuses it (misconfigured, or it cannot
/// judge the body): a `CheckSet` runs the former with the level's other `newton_euler` probes.
pub(super) fn newton_euler(level: &Level, def: &CheckDef) -> Result<NewtonEuler, Box<dyn Probe>> {
    let moments = |b: &crate::level::BodyDef| !b.lock_rotation || def.point.is_some();
    match dynamic_body(level, def) {
        Ok(b) if damped_body(level, b, moments(b)).is_some() => Err(cannot_judge_probe(
            def,
            format!(
                "Newton-Euler's sum F = m a_G, sum M = I alpha: {}",
                damped_body(level, b, moments(b)).unwrap_or_default()
            ),
        )),
        Ok(b) if b.lock_rotation && def.point.is_some() => Err(misconfigured(
            def,
            format!(
                "body \"{}\" has lock_rotation: the couple that keeps it from turning is not in its free-body diagram, so a moment equation (`point`) cannot be checked; drop `point` to check sum F = m a_G",
                b.name
            ),
        )),
        Ok(b) => Ok(NewtonEuler {
            locked: b.lock_rotation,
            def: def.clone(),
            name: b.name.clone(),
            p: def.point.map(v2),
            textbook: textbook_mass(b),
            substeps: 1,
            pivot: None,
            index: None,
            f: Worst::over(def),
            m: Worst::over(def),
            mp: Worst::over(def),
            f_scale: 0.0,
            rel: Worst::over(def),
            k_g: 0.0,
            last: (0.0, 0.0),
        }),
        Err(e) => Err(misconfigured(def, e)),
    }
}

pub(super) struct NewtonEuler {
    def: CheckDef,
    /// The body's rotation is locked (`lock_rotation`): the locking couple is not in the diagram,
    /// so only sum F = m a_G is checked.
    locked: bool,
    name: String,
    p: Option<DVec2>,
    /// The level's m, G and I_G (shape formula): the kinetic side of 6/2 and 6/4.
    textbook: MassProps,
    substeps: usize,
    /// With `point`: whether P is the body's fixed pivot, and r_bar = |r_G - r_O| there.
    pivot: Option<Option<f64>>,
    index: Option<usize>,
    /// Force residual (6/1; without `point` only).
    f: Worst,
    /// Moment residual about G (6/1), or with `point` about the pivot (6/4).
    m: Worst,
    /// Moment residual about P (6/2; with `point` only).
    mp: Worst,
    /// F_s at the worst step.
    f_scale: f64,
    /// The per-step relative error.
    rel: Worst,
    k_g: f64,
    last: (f64, f64),
}

/// Each probe as on its own, in one loop.
impl Together for NewtonEuler {
    type Shared = ();
}

impl FrameProbe for NewtonEuler {
    /// The frame's sums and residuals, not the work of the forces.
    fn frame_pass(&self) -> FramePass {
        FramePass::Diagram
    }

    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        // The step's substeps as the engine ran them (overrides included).
        self.substeps = s.substeps.max(1);
        let Some(i) = cached_body(&mut self.index, s, &self.name) else {
            return;
        };
        let b = &s.bodies[i];
        let f = fa.frame();
        if !f.stepped {
            return;
        }
        if self.k_g == 0.0 {
            // m and I_G do not change during a run.
            self.k_g = crate::analysis::mass::radius_of_gyration(b.inertia, b.mass);
        }
        let now = Motion::from(b);
        let before = fa.start_of_step()[i];
        if let (Some(p), None) = (self.p, self.pivot) {
            // A pivot at P: the body's joint to a fixed body, anchored at P (to 1e-4 of the
            // textbook k_G: the anchor comes through rapier's f32 pose). Joints are reported from
            // the first step on; r_bar is G's distance from O at the step's start (the level's).
            let tol = 1e-4 * self.textbook.radius_of_gyration().max(1e-3);
            self.pivot = Some(
                pivot_of(s, i)
                    .filter(|o| o.distance(p) <= tol)
                    .map(|o| before.com.distance(o)),
            );
        }
        // The step's free-body and kinetic diagrams, from the shared frame pass: sum F and
        // sum M_G (impulses / dt), a_G and alpha by finite differences (`FD`), and their
        // residuals (6/1), computed there once for every reader.
        let bf = &f.bodies[i];
        let sums = &bf.impulses;
        let inv_dt = 1.0 / s.dt;
        let ma = b.mass * bf.acceleration;
        // The residual the engine's precision cannot resolve is not held against it: a body
        // coasting force-free after an impact has F_s at f32 noise otherwise, and reads 100 %.
        let (res_f, res_m) = finite_difference_resolution(
            b.mass,
            b.inertia,
            &before,
            &now,
            s.precision.epsilon(),
            self.substeps,
            s.dt,
        );
        // A residual that is not finite (1/dt overflowing at a tiny dt, forces past f32's
        // range) is infinitely wrong: inf - inf would be NaN, which max(0) turned into 0.
        let beyond = |r: f64, res: f64| {
            if r.is_finite() {
                (r - res).max(0.0)
            } else {
                f64::INFINITY
            }
        };
        // The force level: the largest of the sum, m a_G, the weight and the largest single
        // force of the diagram (in statics the sum and m a_G vanish while a piston's force and
        // the pin's reaction balancing it do not), and a couple's size over k_G.
        let k = self.k_g.max(1e-9);
        let fs = bf
            .force
            .length()
            .max(ma.length())
            .max(b.mass * s.gravity.length())
            .max(sums.largest_impulse * inv_dt)
            .max(sums.largest_couple * inv_dt / k)
            .max(res_f)
            .max(1e-12);
        // A ratio that is NaN (an infinite residual against an infinite force level) is an
        // infinite error: f64::max would drop it in favour of the other ratio.
        let ratio = |num: f64, den: f64| {
            let r = num / den;
            if r.is_nan() {
                f64::INFINITY
            } else {
                r
            }
        };
        let rel = match self.p {
            None => {
                // 6/1: the body's free-body diagram over the step, from the shared frame.
                let (df, dm) = (bf.force_residual.length(), bf.moment_residual);
                self.f.add(df, s.time);
                self.last = (bf.force.length(), ma.length());
                let force = ratio(beyond(df, res_f), fs);
                if self.locked {
                    force
                } else {
                    self.m.add(dm, s.time);
                    force.max(ratio(beyond(dm.abs(), res_m), fs * k))
                }
            }
            Some(p) => {
                // 6/2 about P (and 6/4 about the pivot) with the textbook m and I_G.
                let t = self.textbook;
                let sum_m = sums.moment_about(p) * inv_dt;
                // G where the step's impulses act on average: the mean of the substeps' start
                // positions, as for gravity in the diagram (each substep's m dv acts there).
                let r_g = gravity_point(before.com, now.com, self.substeps);
                let alpha = bf.angular_acceleration;
                let kinetic =
                    kinetic_moment_about(t.mass, t.inertia, alpha, r_g, bf.acceleration, p);
                let mut worst = (sum_m - kinetic).abs();
                if let Some(Some(r_bar)) = self.pivot {
                    let i_o = parallel_axis(t.inertia, t.mass, r_bar);
                    let d4 = sum_m - kinetic_moment_fixed_axis(i_o, alpha);
                    self.m.add(d4, s.time);
                    worst = worst.max(d4.abs());
                }
                self.mp.add(sum_m - kinetic, s.time);
                self.last = (sum_m, kinetic);
                let res_p = res_m + res_f * (r_g - p).length();
                ratio(beyond(worst, res_p), fs * k.max((b.com - p).length()))
            }
        };
        if self.rel.covers(s.time) && (rel > self.rel.max || self.rel.samples == 0) {
            self.f_scale = fs;
        }
        self.rel.add(rel, s.time);
    }

    fn finish(self) -> CheckResult {
        let fs = scale_or(self.f_scale, 1.0);
        let (note, max_abs, final_abs) = match self.p {
            None => (
                format!(
                    "worst step at t = {:.3} s (F_s {:.4} N there); largest residuals: force {:.2e} N at t = {:.3} s, moment about G {:.2e} N m at t = {:.3} s (k_G {:.4} m)",
                    self.rel.at_time, fs, self.f.max, self.f.at_time, self.m.max, self.m.at_time, self.k_g
                ),
                self.f.max,
                self.f.last,
            ),
            Some(p) => {
                let mut note = format!(
                    "moments about P = ({:.4}, {:.4}), textbook m {:.6} kg, I_G {:.6e} kg m^2; worst step at t = {:.3} s (F_s {:.4} N there); sum M_P - (I_G alpha + r_G/P x m a_G) (6/2) largest {:.2e} N m at t = {:.3} s",
                    p.x, p.y, self.textbook.mass, self.textbook.inertia, self.rel.at_time, fs, self.mp.max, self.mp.at_time
                );
                match self.pivot {
                    Some(Some(r_bar)) => {
                        note += &format!(
                            "; P is the pivot (r_bar {:.4} m, I_O {:.6e} kg m^2): sum M_O - I_O alpha (6/4) largest {:.2e} N m at t = {:.3} s",
                            r_bar,
                            parallel_axis(self.textbook.inertia, self.textbook.mass, r_bar),
                            self.m.max,
                            self.m.at_time
                        );
                    }
                    _ => note += "; P is not a fixed pivot of the body (6/4 not applied)",
                }
                (note, self.mp.max.max(self.m.max), self.mp.last)
            }
        };
        result(
            &self.def,
            subject_of(&self.def),
            Summary {
                theory: self.last.0,
                engine: self.last.1,
                max_abs,
                max_rel: self.rel.max,
                final_abs,
                final_rel: self.rel.last,
                samples: self.rel.samples,
                scale: fs,
                note,
            },
        )
    }
}
