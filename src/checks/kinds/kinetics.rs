//! `newton_euler`: the free-body diagram against the kinetic diagram, every step (6/1, 6/2).

use super::{
    dynamic_body, framed, misconfigured, result, scale_or, subject_of, v2, FrameProbe, Summary,
    Worst,
};
use crate::analysis::frame::FrameAnalysis;
use crate::analysis::kinetics::newton_euler_residual;
use crate::analysis::momentum::angular_momentum_about;
use crate::analysis::Motion;
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// `newton_euler`: sum F = m a_G and sum M_G = I_G alpha (6/1) for one body, every step; with
/// `point` also the moment equation about that fixed point P (6/2 in its momentum form,
/// sum M_P = dH_P/dt with H_P by 6/15).
///
/// Theory: the free-body diagram of the step read from the snapshot (`analysis::kinetics`):
/// gravity, loads, springs, event impulses, every contact point's normal and friction impulse,
/// joint reactions, couplings; forces as impulse / dt. Engine: m a_G and I_G alpha with a_G and
/// alpha by finite differences of rapier's velocities over the step (`FD`), rapier's m and I_G.
/// Error, step by step: the force residual |sum F - m a_G| relative to the step's force level
/// F_s = max(|sum F|, m |a_G|, m |g|) (so one impulsive step does not hide the others); the moment
/// residual relative to F_s k_G (F_s L_P about P, L_P the larger of k_G and |r_G - r_P|); the
/// largest of these over the run. The reported scale is F_s at the worst step.
///
/// Known engine limitation: a joint's reaction is read from its last substep (`sim::joints`),
/// so when the reaction changes within the step the diagram is off by O(h) dJ/dt; an impulsive
/// reaction in the first substep (a strike on a pinned body with substeps > 1) is missed entirely.
pub(super) fn probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    match dynamic_body(level, def) {
        Ok(b) => framed(
            level,
            NewtonEuler {
                def: def.clone(),
                name: b.name.clone(),
                p: def.point.map(v2),
                index: None,
                f: Worst::default(),
                m: Worst::default(),
                mp: Worst::default(),
                f_scale: 0.0,
                rel: Worst::default(),
                k_g: 0.0,
                last: (0.0, 0.0),
            },
        ),
        Err(e) => misconfigured(def, e),
    }
}

struct NewtonEuler {
    def: CheckDef,
    name: String,
    p: Option<DVec2>,
    index: Option<usize>,
    f: Worst,
    m: Worst,
    mp: Worst,
    /// F_s at the worst step.
    f_scale: f64,
    /// The per-step relative error.
    rel: Worst,
    k_g: f64,
    last: (f64, f64),
}

impl FrameProbe for NewtonEuler {
    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        let Some(i) = self.index.or_else(|| s.body_index(&self.name)) else {
            return;
        };
        self.index = Some(i);
        let b = &s.bodies[i];
        let now = Motion::from(b);
        self.k_g = crate::analysis::mass::radius_of_gyration(b.inertia, b.mass);
        let f = fa.frame();
        if f.stepped {
            let before = fa.start_of_step()[i];
            // The body's free-body diagram over the step, from the shared frame.
            let sums = f.bodies[i].impulses;
            let moment_g = f.bodies[i].moment_g * s.dt;
            let (df, dm) = newton_euler_residual(
                b.mass,
                b.inertia,
                &before,
                &now,
                sums.impulse,
                moment_g,
                s.dt,
            );
            let sum_f = sums.impulse / s.dt;
            let ma = b.mass * (now.velocity - before.velocity) / s.dt;
            let fs = sum_f
                .length()
                .max(ma.length())
                .max(b.mass * s.gravity.length())
                .max(1e-12);
            let k = self.k_g.max(1e-9);
            let mut rel = (df.length() / fs).max(dm.abs() / (fs * k));
            self.f.add(df.length(), s.time);
            self.m.add(dm, s.time);
            if let Some(p) = self.p {
                let h = |m: &Motion| {
                    angular_momentum_about(b.mass, b.inertia, m.com, m.velocity, m.omega, p)
                };
                let dmp = sums.moment_about(p) / s.dt - (h(&now) - h(&before)) / s.dt;
                self.mp.add(dmp, s.time);
                rel = rel.max(dmp.abs() / (fs * k.max((b.com - p).length())));
            }
            if rel > self.rel.max || self.rel.samples == 0 {
                self.f_scale = fs;
            }
            self.rel.add(rel, s.time);
            self.last = (sum_f.length(), ma.length());
        }
    }

    fn finish(self) -> CheckResult {
        let fs = scale_or(self.f_scale, 1.0);
        let mut note = format!(
            "worst step at t = {:.3} s (F_s {:.4} N there); largest residuals: force {:.2e} N at t = {:.3} s, moment about G {:.2e} N m at t = {:.3} s (k_G {:.4} m)",
            self.rel.at_time, fs, self.f.max, self.f.at_time, self.m.max, self.m.at_time, self.k_g
        );
        if let Some(p) = self.p {
            note += &format!(
                ", moment about ({:.3}, {:.3}) {:.2e} N m at t = {:.3} s",
                p.x, p.y, self.mp.max, self.mp.at_time
            );
        }
        result(
            &self.def,
            subject_of(&self.def),
            Summary {
                theory: self.last.0,
                engine: self.last.1,
                max_abs: self.f.max,
                max_rel: self.rel.max,
                final_abs: self.f.last,
                final_rel: self.rel.last,
                samples: self.rel.samples,
                scale: fs,
                note,
            },
        )
    }
}
