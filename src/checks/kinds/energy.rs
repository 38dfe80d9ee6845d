//! Energy checks: `kinetic_energy_g`, `kinetic_energy_ic`, `work_energy`.

use super::{
    body_def, cached_body, cannot_judge_probe, damped_subject, dynamic_body, framed, misconfigured,
    observed_nothing, result, scale_or, subject_index, subject_of, subject_set, textbook_mass, v2,
    BodySet, FrameProbe, Summary, Together, Worst,
};
use crate::analysis::energy::{gravity_potential, kinetic_energy, kinetic_energy_about_ic};
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::analysis::kinematics::{
    omega_from_angles, relative_point_velocity, slip_velocity, velocity_from_positions, wrap_angle,
};
use crate::analysis::mass::MassProps;
use crate::analysis::Motion;
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, JointKind, Level};
use crate::snapshot::{BodyState, ContactState, Snapshot};
use glam::DVec2;

/// The engine's kinetic energy of a body: 6/9 with rapier's v_G, omega, m and I_G.
fn engine_ke(b: &BodyState) -> f64 {
    kinetic_energy(b.mass, b.velocity, b.inertia, b.omega)
}

/// The textbook mass center `local` (body frame) in world coordinates, as
/// `Motion::world_point`; a centred shape's (the body origin) is the body's position itself,
/// without the sine and cosine of its angle (the rotated zero vector adds zero): a probe on
/// every body of a 100-body scene spends most of its step on them.
fn mass_center(b: &BodyState, local: DVec2) -> DVec2 {
    if local == DVec2::ZERO {
        b.position
    } else {
        Motion::from(b).world_point(local)
    }
}

// ---------------------------------------------------------------------------------------------

/// `kinetic_energy_g`: T = 1/2 m v_G^2 + 1/2 I_G omega^2 (6/9) of the motion the engine drew,
/// against the engine's own kinetic energy.
///
/// Theory: 6/9 with the shape formula's m and I_G (`analysis::mass`) and with v_G and omega
/// taken from the engine's **poses** (G placed by the formula's mass center): the velocity that
/// the positions imply for symplectic Euler over S substeps (`kinematics::velocity_from_positions`,
/// exact for constant acceleration). Engine: 6/9 with rapier's velocity state and its own mass
/// properties. So the check fails if rapier's mass properties differ from the shape's, or if the
/// bodies do not move with the velocities the engine reports (position correction, a wrong substep
/// count). Each sample needs the steps either side, so the last step is not compared, and steps
/// with an event impulse on the body (a velocity jump) are skipped.
/// Scale: the largest kinetic energy of the run.
pub(super) fn kinetic_energy_g_probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    match dynamic_body(level, def) {
        Ok(b) => Box::new(KineticEnergyG {
            def: def.clone(),
            name: b.name.clone(),
            mass: textbook_mass(b),
            substeps: 1,
            index: None,
            history: Vec::with_capacity(2),
            worst: Worst::over(def),
            max_t: 0.0,
            skipped: 0,
            last: (0.0, 0.0),
        }),
        Err(e) => misconfigured(def, e),
    }
}

struct KineticEnergyG {
    def: CheckDef,
    name: String,
    mass: MassProps,
    substeps: usize,
    index: Option<usize>,
    /// (pose G, angle, engine T, time, had an event impulse) at steps n-1 and n.
    history: Vec<(DVec2, f64, f64, f64, bool)>,
    worst: Worst,
    max_t: f64,
    skipped: u64,
    last: (f64, f64),
}

impl Probe for KineticEnergyG {
    /// Reads the bodies only.
    fn reads_contacts(&self) -> bool {
        false
    }

    fn observe(&mut self, s: &Snapshot) {
        // The step's substeps as the engine ran them (overrides included).
        self.substeps = s.substeps.max(1);
        let Some(i) = cached_body(&mut self.index, s, &self.name) else {
            return;
        };
        let b = &s.bodies[i];
        let g = mass_center(b, self.mass.com);
        let t_engine = engine_ke(b);
        self.max_t = self.max_t.max(t_engine);
        let event = s.impulses.iter().any(|e| e.body == i);
        if self.history.len() == 2 {
            let (g0, a0, _, _, _) = self.history[0];
            let (g1, a1, t1, time1, ev1) = self.history[1];
            if !s.is_initial() && !ev1 && !event {
                let v = velocity_from_positions(g1 - g0, g - g1, s.dt, self.substeps);
                let w = omega_from_angles(
                    wrap_angle(a1 - a0),
                    wrap_angle(b.angle - a1),
                    s.dt,
                    self.substeps,
                );
                let t_theory = kinetic_energy(self.mass.mass, v, self.mass.inertia, w);
                self.worst.add(t_theory - t1, time1);
                self.last = (t_theory, t1);
            } else {
                self.skipped += 1;
            }
            self.history.remove(0);
        }
        self.history.push((g, b.angle, t_engine, s.time, event));
    }

    fn finish(self: Box<Self>) -> CheckResult {
        let scale = scale_or(self.max_t, 1.0);
        let note = format!(
            "T from the drawn poses (S = {} substeps) vs rapier's state; worst {:.2e} J at t = {:.3} s; max T {:.4} J{}",
            self.substeps,
            self.worst.max,
            self.worst.at_time,
            self.max_t,
            if self.skipped > 0 {
                format!("; {} samples skipped (event impulses or start)", self.skipped)
            } else {
                String::new()
            }
        );
        let r = result(
            &self.def,
            subject_of(&self.def),
            Summary::from_worst(self.last, &self.worst, scale, note),
        );
        if self.max_t == 0.0 {
            observed_nothing(r, "T was 0 at every step (the body never moved)")
        } else {
            r
        }
    }
}

// ---------------------------------------------------------------------------------------------

/// Where the instantaneous center comes from.
#[derive(Debug, Clone, PartialEq)]
enum Center {
    /// A fixed pivot O (`point`): fixed-axis rotation, T = 1/2 I_O omega^2 (6/8).
    Fixed(DVec2),
    /// Rolling without slipping on `other` (a fixed body): C is the contact point (RK-8).
    Contact(String),
    // No third way: the kinematic center r_C = r_G + (k x v_G)/omega (RK-11) of the engine's own
    // velocities makes 1/2 I_C w^2 equal 1/2 m v^2 + 1/2 I_G w^2 identically (a number compared
    // with itself), so a check without `point` or `other` is refused here and in validation.
}

/// `kinetic_energy_ic`: T = 1/2 I_C omega^2 about the instantaneous center C (6/10), against
/// the engine's T.
///
/// Theory: I_C = I_G + m |r_G - r_C|^2 (MP-2) with the shape formula's m, I_G and mass center,
/// times the engine's omega. C is, by the check's fields:
/// - `point`: a fixed pivot O, so T = 1/2 I_O omega^2 (6/8);
/// - `other`: the contact point with that body, the center of a body rolling without slipping
///   on it (the body's own surface point); steps without contact are skipped. When `other`
///   moves, C is the center of the motion relative to it, and the energies compared are those
///   of that relative motion (omega - omega_o, v_G - v_O(G));
/// - neither: the kinematic center from v_G and omega (then only the mass properties differ
///   from the engine's side).
///
/// Engine: 6/9 with rapier's v_G, omega, m and I_G. The two agree only if the engine's motion has
/// its instantaneous center where the textbook puts it: no slip at the contact, no drift at the pivot.
/// Scale: the largest kinetic energy of the run. The note gives the largest slip velocity.
pub(super) fn kinetic_energy_ic_probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    kinetic_energy_ic(level, def).map_or_else(|refused| refused, framed)
}

/// The `kinetic_energy_ic` probe of `def`, or the misconfigured probe that refuses it: a
/// `CheckSet` runs the former with the level's other `kinetic_energy_ic` probes.
pub(super) fn kinetic_energy_ic(
    level: &Level,
    def: &CheckDef,
) -> Result<KineticEnergyIc, Box<dyn Probe>> {
    let b = match dynamic_body(level, def) {
        Ok(b) => b,
        Err(e) => return Err(misconfigured(def, e)),
    };
    let center = match (&def.point, &def.other) {
        (Some(p), _) => Center::Fixed(v2(*p)),
        (None, Some(o)) => {
            if body_def(level, o).is_none() {
                return Err(misconfigured(
                    def,
                    format!("`other` \"{o}\" is not a body of this level"),
                ));
            }
            Center::Contact(o.clone())
        }
        (None, None) => {
            return Err(misconfigured(
                def,
                "kinetic_energy_ic needs `point` (a fixed pivot) or `other` (the body it rolls on): \
                 an instantaneous center from the engine's own velocities would compare its kinetic energy with itself",
            ))
        }
    };
    Ok(KineticEnergyIc {
        def: def.clone(),
        name: b.name.clone(),
        mass: textbook_mass(b),
        center,
        worst: Worst::over(def),
        max_t: 0.0,
        skipped: 0,
        max_slip: 0.0,
        max_normal: 0.0,
        at_infinity: 0,
        relative_steps: 0,
        index: None,
        other_index: None,
        touch: Touch::default(),
        last: (0.0, 0.0),
    })
}

pub(super) struct KineticEnergyIc {
    def: CheckDef,
    name: String,
    mass: MassProps,
    center: Center,
    worst: Worst,
    max_t: f64,
    skipped: u64,
    max_slip: f64,
    /// Largest relative normal velocity at the contact (rapier lets it differ from zero).
    max_normal: f64,
    at_infinity: u64,
    /// Steps compared in the moving `other` body's frame.
    relative_steps: u64,
    index: Option<usize>,
    /// The index of the `other` body, looked up once.
    other_index: Option<usize>,
    /// Run with the level's other probes of the kind: its contact with `other` this step.
    touch: Touch,
    last: (f64, f64),
}

impl FrameProbe for KineticEnergyIc {
    /// The contact point comes from the body's own contacts (the frame's links), not the sums.
    fn frame_pass(&self) -> FramePass {
        FramePass::Motion
    }

    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        // Among the body's own contacts (the frame's index): a scan of every contact of the
        // scene for every probe made 100 probes cost O(N x contacts) a step.
        self.observe_touching(s, |i, k, com| {
            let mut touch = Touch::default();
            for c in fa
                .links(s)
                .contacts_of(i)
                .iter()
                .map(|&c| &s.contacts[c as usize])
            {
                if (c.body1 == i && c.body2 == k) || (c.body1 == k && c.body2 == i) {
                    touch.add(c, c.body1 == i, com);
                }
            }
            touch
        });
    }

    fn finish(self) -> CheckResult {
        self.finish_result()
    }
}

/// A body's own contact point(s) with the `other` body of a `kinetic_energy_ic` check over a
/// step, weighted by normal impulse: G plus the lever arm the solver used (recorded points go
/// stale while rapier recycles the manifold; the arm of a rolling disc stays -r n).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Touch {
    sum: DVec2,
    w: f64,
    n: usize,
    normal: DVec2,
}

impl Touch {
    /// Contact `c`'s points, the body being its `body1` when `first`; `com` its G.
    fn add(&mut self, c: &ContactState, first: bool, com: DVec2) {
        for p in &c.points {
            let own = match (p.arms, first) {
                (Some((a1, _)), true) => com + a1,
                (Some((_, a2)), false) => com + a2,
                (None, true) => p.point,
                (None, false) => p.point + c.normal * p.distance,
            };
            let wt = p.normal_impulse.max(1e-12);
            self.sum += own * wt;
            self.w += wt;
            self.n += 1;
            self.normal = c.normal;
        }
    }
}

/// The `kinetic_energy_ic` probes of a run together: one walk over the step's contacts gives
/// every rolling probe its contact with its `other` body (in the snapshot's order, as
/// [`BodyLinks`](crate::analysis::links::BodyLinks) lists a body's own: the same sums to the
/// last bit), where each probe alone would look up its body's contacts.
impl Together for KineticEnergyIc {
    type Shared = Rolling;

    fn observe_all(probes: &mut [Self], rolling: &mut Rolling, s: &Snapshot, _fa: &FrameAnalysis) {
        if !rolling.resolved {
            rolling.index(probes, s);
        }
        for &k in &rolling.rolls {
            probes[k as usize].touch = Touch::default();
        }
        for c in &s.contacts {
            for (i, k, first) in [(c.body1, c.body2, true), (c.body2, c.body1, false)] {
                if !first && i == k {
                    continue;
                }
                let mut p = rolling.first.get(i).copied().unwrap_or(NONE);
                while p != NONE {
                    let probe = &mut probes[p as usize];
                    if probe.other_index == Some(k) {
                        probe.touch.add(c, first, s.bodies[i].com);
                    }
                    p = rolling.next[p as usize];
                }
            }
        }
        for p in probes.iter_mut() {
            let touch = p.touch;
            p.observe_touching(s, |_, _, _| touch);
        }
    }
}

/// No probe (the end of a chain in [`Rolling`]).
const NONE: u32 = u32::MAX;

/// Which `kinetic_energy_ic` probes roll on which body: per body the first probe about a
/// contact of it, and per probe the next one on the same body (built once the bodies are
/// found: a scene's bodies do not come or go).
#[derive(Debug, Default)]
pub(super) struct Rolling {
    first: Vec<u32>,
    next: Vec<u32>,
    /// The probes about a contact.
    rolls: Vec<u32>,
    /// Whether every rolling probe's bodies were found.
    resolved: bool,
}

impl Rolling {
    fn index(&mut self, probes: &mut [KineticEnergyIc], s: &Snapshot) {
        self.first.clear();
        self.first.resize(s.bodies.len(), NONE);
        self.next.clear();
        self.next.resize(probes.len(), NONE);
        self.rolls.clear();
        self.resolved = true;
        for (k, p) in probes.iter_mut().enumerate().rev() {
            let Center::Contact(other) = &p.center else {
                continue;
            };
            let i = cached_body(&mut p.index, s, &p.name);
            let o = cached_body(&mut p.other_index, s, other);
            let Some(i) = i.filter(|_| o.is_some()) else {
                self.resolved = false;
                continue;
            };
            self.next[k] = self.first[i];
            self.first[i] = k as u32;
            self.rolls.push(k as u32);
        }
    }
}

impl KineticEnergyIc {
    /// One step's comparison; `touch(i, k, G)` gives body i's contact with `other` (body k).
    fn observe_touching(&mut self, s: &Snapshot, touch: impl FnOnce(usize, usize, DVec2) -> Touch) {
        let Some(i) = cached_body(&mut self.index, s, &self.name) else {
            return;
        };
        let b = &s.bodies[i];
        if b.mass <= 0.0 {
            // The initial snapshot: rapier computes mass properties inside the first step.
            return;
        }
        let motion = Motion::from(b);
        let g = mass_center(b, self.mass.com);
        let mut t_engine = engine_ke(b);
        let (m, i_g) = (self.mass.mass, self.mass.inertia);
        // The body's angular velocity relative to the frame C is at rest in: the world's, or
        // the `other` body's when that moves.
        let mut omega = b.omega;
        let c = match &self.center {
            Center::Fixed(o) => Some(*o),
            Center::Contact(other) => {
                let Some(k) = cached_body(&mut self.other_index, s, other) else {
                    return;
                };
                let Touch { sum, w, n, normal } = touch(i, k, b.com);
                if n == 0 {
                    self.skipped += 1;
                    return;
                }
                let c = sum / w;
                let other = Motion::from(&s.bodies[k]);
                let slip = slip_velocity(&other, &motion, c, normal);
                let v_rel = relative_point_velocity(&other, &motion, c);
                self.max_slip = self.max_slip.max(slip.abs());
                self.max_normal = self.max_normal.max(v_rel.dot(normal).abs());
                if other.velocity != DVec2::ZERO || other.omega != 0.0 {
                    // On a moving body the contact point is the center of the motion relative
                    // to it (its velocity field is rigid, with omega - omega_o, and zero at C
                    // while rolling), not the world's instantaneous center: compare the
                    // kinetic energy of that relative motion, 1/2 m |v_G - v_O(G)|^2 +
                    // 1/2 I_G (omega - omega_o)^2 = 1/2 I_C (omega - omega_o)^2 (6/10).
                    omega = b.omega - other.omega;
                    let v = b.velocity - other.velocity_at(b.com);
                    t_engine = kinetic_energy(b.mass, v, b.inertia, omega);
                    self.relative_steps += 1;
                }
                Some(c)
            }
        };
        self.max_t = self.max_t.max(t_engine);
        let t_theory = match c {
            Some(c) => kinetic_energy_about_ic(m, i_g, g, c, omega),
            None => {
                // Pure translation: C at infinity, T = 1/2 m v^2 (6/7).
                self.at_infinity += 1;
                crate::analysis::energy::kinetic_energy_translation(m, b.velocity)
            }
        };
        self.worst.add(t_theory - t_engine, s.time);
        self.last = (t_theory, t_engine);
    }

    fn finish_result(self) -> CheckResult {
        let scale = scale_or(self.max_t, 1.0);
        let how = match &self.center {
            Center::Fixed(o) => format!("1/2 I_O w^2 about the pivot ({:.3}, {:.3}) (6/8)", o.x, o.y),
            Center::Contact(o) => format!(
                "1/2 I_C w^2 about the contact with \"{o}\" (rolling, 6/10); largest slip {:.2e} m/s, largest normal velocity at C {:.2e} m/s",
                self.max_slip, self.max_normal
            ),
        };
        let mut note = format!(
            "{how}; worst {:.2e} J at t = {:.3} s; max T {:.4} J",
            self.worst.max, self.worst.at_time, self.max_t
        );
        if self.skipped > 0 {
            note += &format!("; {} steps without contact skipped", self.skipped);
        }
        if self.relative_steps > 0 {
            note += &format!(
                "; {} steps on a moving body: T of the motion relative to it, 1/2 I_C (w - w_o)^2",
                self.relative_steps
            );
        }
        if self.at_infinity > 0 {
            note += &format!(
                "; {} steps in translation (C at infinity)",
                self.at_infinity
            );
        }
        let r = result(
            &self.def,
            subject_of(&self.def),
            Summary::from_worst(self.last, &self.worst, scale, note),
        );
        if self.max_t == 0.0 {
            observed_nothing(r, "T was 0 at every step (the body never moved)")
        } else {
            r
        }
    }
}

// ---------------------------------------------------------------------------------------------

/// `work_energy`: the ledger T1 + V1 + U'_{1-2} = T2 + V2 (WE-14, RE-7) of a body or the scene.
///
/// Engine: E = T + V_g + V_e from rapier's state (T by 6/9 with rapier's m, I_G; V_g = -m g . r_G;
/// V_e = 1/2 k x^2 of the springs counted in the ledger).
/// Theory: E(0) + U', U' the work of the non-conservative forces summed step by step from the
/// free-body diagram: applied loads and couples, event impulses, contact impulses (friction, and
/// the normal impulse of an inelastic impact) at the contact points, joint motors, spring
/// damping, couplings. Each step's impulse does work J . v_P,mid (`energy::work_of_impulse`, exact
/// for a rigid body when the impulses balance the momentum change). Ideal joints do no work in
/// theory, so E - E(0) - U' is the engine's energy error (soft joints, the substep integrator);
/// the note gives it and its drift per period when the body oscillates.
///
/// Springs count in V_e when all their attached bodies are in the ledger (or the other end is
/// the ground); otherwise their force is external and its work goes into U'.
/// Scale: the energy that flows, max over the run of T, |V_g - V_g0|, |V_e - V_e0|, |U'| and the
/// sum over U's sources (loads, events, contacts, motors, damping, others) of |U' of the source|.
pub(super) fn work_energy(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    let body = match &def.body {
        Some(_) => match dynamic_body(level, def) {
            Ok(b) => Some(b.name.clone()),
            Err(e) => return misconfigured(def, e),
        },
        None => None,
    };
    // U' sums the diagram's impulses, which hold no body damping (rapier's velocity scaling
    // takes energy the ledger cannot book).
    if let Some(why) = damped_subject(level, body.as_deref()) {
        return cannot_judge_probe(def, format!("the work-energy ledger: {why}"));
    }
    framed(WorkEnergy {
        def: def.clone(),
        // Only the joints with a motor do work: a level without motors skips the joint scan.
        level_joints: level
            .joints
            .iter()
            .filter(|j| j.motor.is_some())
            .map(|j| (j.name.clone(), j.kind, v2(j.axis)))
            .collect(),
        springs: {
            // A spring's damping works only where the level declares `damping`.
            let c = |c: f64| {
                if level.effects.contains(&crate::level::Effect::Damping) {
                    c
                } else {
                    0.0
                }
            };
            level
                .springs
                .iter()
                .map(|s| (s.stiffness, c(s.damping)))
                .chain(
                    level
                        .torsion_springs
                        .iter()
                        .map(|t| (t.stiffness, c(t.damping))),
                )
                .collect()
        },
        body,
        index: None,
        set: BodySet::default(),
        springs_before: Vec::new(),
        e0: None,
        u_nc: 0.0,
        by_source: [0.0; 6],
        worst: Worst::over_from_start(def),
        scale: 0.0,
        v_g0: 0.0,
        v_e0: 0.0,
        last: (0.0, 0.0),
        residual: Vec::new(),
        crossings: Vec::new(),
        last_omega: 0.0,
    })
}

/// Indices into `WorkEnergy::by_source`.
const LOADS: usize = 0;
const EVENTS: usize = 1;
const CONTACTS: usize = 2;
const MOTORS: usize = 3;
const DAMPING: usize = 4;
const OTHER: usize = 5;

/// The `work_energy` probe (see [`work_energy`]). The step's work of loads, events, contacts,
/// couplings and springs outside the ledger comes from the shared frame (`frame::StepWork`);
/// motors and spring damping, which need the level's joint axes and spring constants, are added here.
struct WorkEnergy {
    def: CheckDef,
    /// (name, kind, axis in body1's frame) of the level's joints that have a motor.
    level_joints: Vec<(String, JointKind, DVec2)>,
    /// (stiffness, damping in effect) per spring, in the snapshot's order (linear, then torsion).
    springs: Vec<(f64, f64)>,
    body: Option<String>,
    /// The body's index (None for the scene).
    index: Option<usize>,
    set: BodySet,
    /// (extension, length) per spring at the start of the step.
    springs_before: Vec<(f64, f64)>,
    e0: Option<f64>,
    u_nc: f64,
    by_source: [f64; 6],
    worst: Worst,
    scale: f64,
    v_g0: f64,
    v_e0: f64,
    last: (f64, f64),
    /// (time, E_engine - E_theory) per step, for the drift rate.
    residual: Vec<(f64, f64)>,
    /// Times at which omega of the first body of the set changed sign (oscillation periods).
    crossings: Vec<f64>,
    last_omega: f64,
}

impl WorkEnergy {
    fn in_set(&self, i: usize) -> bool {
        self.set.contains(&i)
    }

    /// Does a spring's elastic energy belong to the ledger? When each end is on a body of the
    /// set or on the fixed ground.
    fn spring_in_ledger(&self, s: &crate::snapshot::SpringState, snap: &Snapshot) -> bool {
        let held =
            |i: usize| self.in_set(i) || snap.bodies[i].kind == crate::snapshot::BodyKind::Fixed;
        (self.in_set(s.body1) || s.body2.is_some_and(|b| self.in_set(b)))
            && held(s.body1)
            && s.body2.is_none_or(held)
    }

    /// The non-conservative work of the step that led to `s`.
    fn step_work(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        let f = fa.frame();
        let w = f.work(self.index);
        let mut add = [0.0; 6];
        add[LOADS] = w.loads;
        add[EVENTS] = w.events;
        add[CONTACTS] = w.contacts;
        add[OTHER] = w.other;
        let before = fa.start_of_step();
        let state = |i: usize| -> (Motion, Motion) { (before[i], Motion::from(&s.bodies[i])) };
        // Joints: motors do work; the rest of the reaction is ideal (no work) in theory.
        let motorized = if self.level_joints.is_empty() {
            &[][..]
        } else {
            &s.joints[..]
        };
        for j in motorized {
            if j.motor_impulse == 0.0 {
                continue;
            }
            let (in1, in2) = (self.in_set(j.body1), self.in_set(j.body2));
            if !in1 && !in2 {
                continue;
            }
            let mut motor = 0.0;
            let def = self.level_joints.iter().find(|d| d.0 == j.name);
            if let Some((_, kind, axis)) = def {
                let rate = |i: usize, p: DVec2| -> (f64, f64) {
                    let (b0, b1) = state(i);
                    let mid = Motion::mid(&b0, &b1);
                    let world_axis = DVec2::from_angle(s.bodies[j.body1].angle)
                        .rotate(axis.normalize_or(DVec2::X));
                    (mid.omega, world_axis.dot(mid.velocity_at(p)))
                };
                let slide = matches!(kind, JointKind::Prismatic | JointKind::PinSlot);
                let mut term = |i: usize, p: DVec2, sign: f64| {
                    let (w, v) = rate(i, p);
                    motor += sign * j.motor_impulse * if slide { v } else { w };
                };
                if in2 {
                    term(j.body2, j.anchor, 1.0);
                }
                if in1 {
                    term(j.body1, j.anchor1, -1.0);
                }
            }
            add[MOTORS] += motor;
        }
        // Spring damping (the c dx/dt part of the held tension) for springs in the ledger: the
        // held tension less its elastic part k x at the step's mean extension, times the change
        // of length. Only for springs that damp: the held tension of an undamped spring differs
        // from k x0 by its change over the split substeps, (1 - 1/n) k dx / 2, which this used to
        // count as damping work (0.95 J false in a 4-substep oscillator).
        for (k, sp) in s.springs.iter().enumerate() {
            if !self.spring_in_ledger(sp, s) {
                continue;
            }
            if let (Some(&(x0, l0)), Some(&(stiff, c))) =
                (self.springs_before.get(k), self.springs.get(k))
            {
                if c > 0.0 {
                    let elastic = stiff * 0.5 * (x0 + sp.extension);
                    add[DAMPING] += -(sp.tension - elastic) * (sp.length - l0);
                }
            }
        }
        for (k, a) in add.iter().enumerate() {
            self.by_source[k] += a;
        }
        self.u_nc += add.iter().sum::<f64>();
    }
}

impl FrameProbe for WorkEnergy {
    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        if self.set.is_empty() {
            let Some(index) = subject_index(s, self.body.as_deref()) else {
                return;
            };
            self.index = index;
            self.set = subject_set(s, self.index);
        }
        let f = fa.frame();
        let v_e: f64 = s
            .springs
            .iter()
            .filter(|sp| self.spring_in_ledger(sp, s))
            .map(|sp| sp.energy)
            .sum();
        // T and V_g of the set, with rapier's m, I_G and the motions given.
        let index = self.index;
        let energies = |motions: Option<&[Motion]>| -> (f64, f64) {
            match index {
                Some(i) => {
                    let b = &s.bodies[i];
                    let m = motions.map_or_else(|| Motion::from(b), |v| v[i]);
                    (
                        kinetic_energy(b.mass, m.velocity, b.inertia, m.omega),
                        gravity_potential(b.mass, s.gravity, m.com),
                    )
                }
                None => {
                    let t = if motions.is_some() {
                        &f.totals_before
                    } else {
                        &f.totals
                    };
                    (t.kinetic_energy, t.gravity_potential)
                }
            }
        };
        if !f.stepped {
            // The initial state.
            self.v_e0 = v_e;
            self.springs_before = s
                .springs
                .iter()
                .map(|sp| (sp.extension, sp.length))
                .collect();
            return;
        }
        if self.e0.is_none() {
            let (t0, vg0) = energies(Some(fa.start_of_step()));
            self.v_g0 = vg0;
            self.e0 = Some(t0 + vg0 + self.v_e0);
        }
        self.step_work(s, fa);
        let (t, v_g) = energies(None);
        let e = t + v_g + v_e;
        let theory = self.e0.unwrap_or(e) + self.u_nc;
        self.worst.add(e - theory, s.time);
        self.residual.push((s.time, e - theory));
        self.last = (theory, e);
        // The energy that flows: T, the changes of V, and U' source by source (a motor driving
        // a crank against a gas load puts in 3.13 J that the load takes out: their net U' of
        // 0.02 J measured a 0.5% residual as 64%).
        let by_source: f64 = self.by_source.iter().map(|w| w.abs()).sum();
        self.scale = self
            .scale
            .max(t)
            .max((v_g - self.v_g0).abs())
            .max((v_e - self.v_e0).abs())
            .max(self.u_nc.abs())
            .max(by_source);
        if let Some(&i) = self.set.first() {
            let w = s.bodies[i].omega;
            if w != 0.0 && self.last_omega != 0.0 && w.signum() != self.last_omega.signum() {
                self.crossings.push(s.time);
            }
            if w != 0.0 {
                self.last_omega = w;
            }
        }
        self.springs_before.clear();
        self.springs_before
            .extend(s.springs.iter().map(|sp| (sp.extension, sp.length)));
    }

    fn finish(self) -> CheckResult {
        let scale = scale_or(self.scale, 1.0);
        let names = ["loads", "events", "contacts", "motors", "damping", "other"];
        let works: Vec<String> = names
            .iter()
            .zip(self.by_source)
            .filter(|(_, w)| *w != 0.0)
            .map(|(n, w)| format!("{n} {w:+.4e}"))
            .collect();
        let mut note = format!(
            "U' {:+.4e} J ({}); E(end) - E(0) - U' = {:+.3e} J (ideal joints and springs do no net work: this is the engine's energy error)",
            self.u_nc,
            if works.is_empty() { "none".to_string() } else { works.join(", ") },
            self.last.1 - self.last.0,
        );
        // Drift rate: least-squares slope of the residual over time.
        if self.residual.len() >= 2 {
            let n = self.residual.len() as f64;
            let (st, se) = self
                .residual
                .iter()
                .fold((0.0, 0.0), |(a, b), (t, e)| (a + t, b + e));
            let (mt, me) = (st / n, se / n);
            let (num, den) = self.residual.iter().fold((0.0, 0.0), |(a, b), (t, e)| {
                (a + (t - mt) * (e - me), b + (t - mt).powi(2))
            });
            let slope = if den > 0.0 { num / den } else { 0.0 };
            // Per period only where the body swings: its omega's sign changes come at regular
            // half periods (within 25 %). A puck sliding round a loop has omega ~ 0 whose sign
            // flips on rounding, at random: n14's loop read "drift per period (period 0.0191
            // s)", a period the motion does not have.
            let halves: Vec<f64> = self.crossings.windows(2).map(|w| w[1] - w[0]).collect();
            let (shortest, longest) = halves
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(a, b), &h| (a.min(h), b.max(h)));
            let regular = longest <= 1.25 * shortest;
            if self.crossings.len() >= 3 && regular {
                let k = self.crossings.len() - 1;
                let period = 2.0 * (self.crossings[k] - self.crossings[0]) / k as f64;
                note += &format!(
                    "; drift {:+.3e} J per period ({:+.2e} of the scale; period {:.4} s, {:.1} periods)",
                    slope * period,
                    slope * period / scale,
                    period,
                    self.residual.last().map_or(0.0, |r| r.0) / period
                );
            } else {
                note += &format!("; drift rate {:+.3e} J/s", slope);
            }
        }
        let r = result(
            &self.def,
            subject_of(&self.def),
            Summary::from_worst(self.last, &self.worst, scale, note),
        );
        if self.scale == 0.0 {
            observed_nothing(
                r,
                "no energy flowed: T, the changes of V and the work stayed 0 at every step (the subject never moved)",
            )
        } else {
            r
        }
    }
}
