//! `mass_properties`: the shape's textbook mass properties against rapier's.
//!
//! Theory: m, G and I_G from the level's shape by the formulas of concepts.md MP-9 (disc,
//! rectangle, capsule, polygon by triangulation, compounds by the parallel-axis theorem),
//! with the level's mass or density and its I_G / k_G override. With `point`, also
//! I_O = I_G + m d^2 about that world point (MP-2) and k_O.
//! Engine: the mass, local mass center and I_G rapier holds for the body (computed by parry
//! from the same shape at unit density and scaled by the sim).
//! Error: the largest of |dm|/m, |dI_G|/I_G, |dG|/k_G (and |dI_O|/I_O): each relative to the
//! theory value, the mass-center offset relative to the radius of gyration k_G.
//! Compared once, on the first snapshot (mass properties do not change).

use super::{dynamic_body, misconfigured, result, subject_of, textbook_mass, v2, Summary};
use crate::analysis::mass::{parallel_axis, radius_of_gyration, MassProps};
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, Level};
use crate::snapshot::Snapshot;

pub(super) fn probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    match dynamic_body(level, def) {
        Ok(b) => Box::new(MassProperties {
            def: def.clone(),
            name: b.name.clone(),
            theory: textbook_mass(b),
            rotation_locked: b.lock_rotation,
            out: None,
        }),
        Err(e) => misconfigured(def, e),
    }
}

struct MassProperties {
    def: CheckDef,
    name: String,
    theory: MassProps,
    rotation_locked: bool,
    out: Option<Summary>,
}

impl Probe for MassProperties {
    /// Reads the bodies only.
    fn reads_contacts(&self) -> bool {
        false
    }

    fn observe(&mut self, s: &Snapshot) {
        if self.out.is_some() {
            return;
        }
        let Some(i) = s.body_index(&self.name) else {
            return;
        };
        let b = &s.bodies[i];
        // rapier fills in mass properties during the first step: the initial snapshot has none.
        if b.mass <= 0.0 && s.step == 0 {
            return;
        }
        let t = self.theory;
        let k_g = radius_of_gyration(t.inertia, t.mass);
        // NaN (inf against inf) is infinitely wrong: f64::max would drop it.
        let rel = |a: f64, b: f64| {
            let e = (a - b).abs() / a.abs().max(f64::MIN_POSITIVE);
            if e.is_nan() {
                f64::INFINITY
            } else {
                e
            }
        };
        let e_m = rel(t.mass, b.mass);
        let e_c = (b.local_com - t.com).length() / if k_g > 0.0 { k_g } else { 1.0 };
        let e_c = if e_c.is_nan() { f64::INFINITY } else { e_c };
        let e_i = if self.rotation_locked {
            0.0
        } else {
            rel(t.inertia, b.inertia)
        };
        let mut note = format!(
            "m {:.6} kg (rapier {:.6}); I_G {:.6e} kg m^2 (rapier {:.6e}){}; G ({:.4}, {:.4}) m in the body frame, off by {:.1e} m; k_G {:.4} m",
            t.mass,
            b.mass,
            t.inertia,
            b.inertia,
            if self.rotation_locked { ", rotation locked: not compared" } else { "" },
            t.com.x,
            t.com.y,
            (b.local_com - t.com).length(),
            k_g
        );
        let (mut theory, mut engine) = (t.inertia, b.inertia);
        let mut e_o = 0.0;
        if let Some(p) = self.def.point {
            // I_O about the world point, G placed by the body's pose (MP-2).
            let o = v2(p);
            let g_t = crate::analysis::Motion::from(b).world_point(t.com);
            let i_o = parallel_axis(t.inertia, t.mass, (g_t - o).length());
            let i_o_engine = parallel_axis(b.inertia, b.mass, (b.com - o).length());
            e_o = rel(i_o, i_o_engine);
            note += &format!(
                "; I_O {:.6e} kg m^2 (rapier {:.6e}), k_O {:.4} m",
                i_o,
                i_o_engine,
                radius_of_gyration(i_o, t.mass)
            );
            theory = i_o;
            engine = i_o_engine;
        }
        let max_rel = e_m.max(e_c).max(e_i).max(e_o);
        self.out = Some(Summary {
            theory,
            engine,
            max_abs: (theory - engine).abs(),
            max_rel,
            final_abs: (theory - engine).abs(),
            final_rel: max_rel,
            samples: 1,
            scale: theory.abs(),
            note,
        });
    }

    fn finish(self: Box<Self>) -> CheckResult {
        let subject = subject_of(&self.def);
        match self.out {
            Some(s) => result(&self.def, subject, s),
            None => result(
                &self.def,
                subject,
                Summary {
                    note: format!("body \"{}\" never appeared in a snapshot", self.name),
                    ..Summary::default()
                },
            ),
        }
    }
}
