//! `center_of_percussion`: the pivot reaction of a struck pinned body (CP-3), or the resultant
//! through the center of percussion (CP-2).

use super::{
    body_def, cached_body, cannot_judge, cannot_judge_probe, contact_pushing, damped_body,
    dynamic_body, framed, misconfigured, result, scale_or, subject_of, textbook_mass, v2,
    FrameProbe, Summary, Worst,
};
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::analysis::kinetics::{for_each_external_impulse_linked, gravity_point, Before, Source};
use crate::analysis::mass::{parallel_axis, MassProps};
use crate::analysis::percussion::{
    center_of_percussion_distance, moment_about_center_of_percussion, pivot_impulse, Blow,
};
use crate::analysis::Motion;
use crate::checks::{CheckResult, Probe};
use crate::level::{BodyKind, CheckDef, EventDef, JointKind, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// `center_of_percussion` for a body pinned to a fixed body.
///
/// With an `Impulse` event on the body (a strike), every strike step compares:
/// - theory: the pivot's reaction impulse predicted for rotation about the fixed pivot O
///   (`percussion::pivot_impulse`: angular impulse about O gives d_omega = (r_{Q/O} x P)/I_O,
///   then J_O = m dv_G - P, plus gravity and the centripetal term over the step), with the
///   shape formula's m, I_G and G (I_O by MP-2); zero for a blow at q = k_O^2/r_bar;
/// - engine: the joint's reaction impulse over that step, read from rapier (`sim::joints`).
///
/// Compared: the tangential component (perpendicular to OG), which CP-3 is about; the radial part
/// (weight, the centripetal m r_bar w^2 dt that rapier's velocity-level pin supplies a step late) is
/// in the note. Scale: the blow's impulse |P|. Without events it checks CP-2 every step: the moment of all
/// forces (gravity, the pin reaction, loads, contacts) about Q is zero; theory 0, engine
/// sum M_Q from the free-body diagram; scale: the largest |sum M_O| of the run and m g q.
///
/// The pin is the joint named by `other` (a joint, or the joint to the body `other`), else the
/// body's first joint. O is `point` or that joint's anchor. The joint's impulse is summed over
/// every substep (split substeps, `sim::Settings`), so the impulsive reaction, which falls in the
/// first substep, is seen at any number of substeps.
///
/// Both forms assume rotation about a pin fixed in the world, and the strike form that the blow,
/// gravity and the body's loads are all that act on it besides the pin. Verified on the scene,
/// else the check cannot judge, with the reason: the joint is a pin (`revolute`) whose other body
/// is not dynamic and does not move at any step compared (a kinematic body that moves fails it);
/// the body is not damped (the diagram holds no damping); and in each strike step no other joint
/// acts on the body, nor a contact or spring or coupling with an impulse on it, nor the pin's
/// motor or limit.
pub(super) fn probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    let b = match dynamic_body(level, def) {
        Ok(b) => b,
        Err(e) => return misconfigured(def, e),
    };
    let joint = match &def.other {
        Some(o) => level.joints.iter().find(|j| &j.name == o).or_else(|| {
            level.joints.iter().find(|j| {
                (j.body1 == b.name && &j.body2 == o) || (j.body2 == b.name && &j.body1 == o)
            })
        }),
        None => level
            .joints
            .iter()
            .find(|j| j.body1 == b.name || j.body2 == b.name),
    };
    let Some(joint) = joint else {
        return misconfigured(
            def,
            format!(
                "body \"{}\" has no pin joint to take the pivot reaction from",
                b.name
            ),
        );
    };
    if joint.kind != JointKind::Revolute {
        return cannot_judge_probe(
            def,
            format!(
                "joint \"{}\" is a {}, not a pin: the center of percussion assumes rotation about a pin fixed in the world",
                joint.name,
                joint.kind.describe()
            ),
        );
    }
    let other = if joint.body1 == b.name {
        &joint.body2
    } else {
        &joint.body1
    };
    if body_def(level, other).is_some_and(|o| o.kind == BodyKind::Dynamic) {
        return cannot_judge_probe(
            def,
            format!(
                "the pin \"{}\" joins \"{}\" to \"{other}\", a dynamic body: the center of percussion assumes rotation about a pin fixed in the world",
                joint.name, b.name
            ),
        );
    }
    if let Some(why) = damped_body(level, b, true) {
        return cannot_judge_probe(def, why);
    }
    let strikes = level
        .events
        .iter()
        .filter(|e| matches!(e, EventDef::Impulse { body, .. } if body == &b.name))
        .count();
    framed(CenterOfPercussion {
        def: def.clone(),
        name: b.name.clone(),
        joint: joint.name.clone(),
        joint_index: None,
        mass: textbook_mass(b),
        substeps: 1,
        strikes,
        o: def.point.map(v2),
        index: None,
        before: None,
        worst: Worst::over(def),
        blow: 0.0,
        max_moment: 0.0,
        q: 0.0,
        strike_notes: Vec::new(),
        last: (0.0, 0.0),
        broken: None,
    })
}

struct CenterOfPercussion {
    def: CheckDef,
    name: String,
    joint: String,
    /// The joint's index in the snapshots, once found.
    joint_index: Option<usize>,
    mass: MassProps,
    substeps: usize,
    strikes: usize,
    o: Option<DVec2>,
    index: Option<usize>,
    before: Option<Motion>,
    worst: Worst,
    /// Largest blow |P| (strike mode).
    blow: f64,
    /// Largest |sum M_O| (moment mode), N m.
    max_moment: f64,
    q: f64,
    strike_notes: Vec<String>,
    last: (f64, f64),
    /// Why rotation about a fixed pin under the blow alone does not hold (the first reason found).
    broken: Option<String>,
}

impl CenterOfPercussion {
    fn pivot_reaction(&mut self, s: &Snapshot, i: usize) -> Option<DVec2> {
        // Looked up by name once: a scene's joints do not come or go.
        let k = self
            .joint_index
            .or_else(|| s.joints.iter().position(|j| j.name == self.joint))?;
        self.joint_index = Some(k);
        let j = &s.joints[k];
        Some(if j.body2 == i {
            j.impulse_on_body2
        } else {
            -j.impulse_on_body2
        })
    }

    /// Why the pin's other body is not fixed at the step that led to `s`, if it moves.
    fn pin_moves(&self, s: &Snapshot, i: usize) -> Option<String> {
        let j = &s.joints[self.joint_index?];
        let o = if j.body2 == i { j.body1 } else { j.body2 };
        let ob = &s.bodies[o];
        (ob.velocity != DVec2::ZERO || ob.omega != 0.0).then(|| {
            format!(
                "the pin \"{}\"'s other body \"{}\" moves at t = {:.4} s (v ({:.3e}, {:.3e}) m/s, omega {:.3e} rad/s): the center of percussion assumes a pin fixed in the world",
                j.name, ob.name, s.time, ob.velocity.x, ob.velocity.y, ob.omega
            )
        })
    }

    /// What acts on body i in the strike step that led to `s` besides the blow, gravity, the
    /// body's loads and the pin's reaction, if anything does.
    fn other_action(&self, s: &Snapshot, i: usize) -> Option<String> {
        let at = format!("in the strike step at t = {:.4} s", s.time);
        let pin = self.joint_index;
        for (k, j) in s.joints.iter().enumerate() {
            if Some(k) == pin {
                if j.motor_impulse != 0.0 || j.limit_impulse != 0.0 {
                    return Some(format!(
                        "the pin \"{}\"'s motor or limit acts {at} (impulse {:.3e}, {:.3e})",
                        j.name, j.motor_impulse, j.limit_impulse
                    ));
                }
            } else if j.body1 == i || j.body2 == i {
                return Some(format!("joint \"{}\" also holds the body {at}", j.name));
            }
        }
        if let Some(why) = contact_pushing(s, i, &at) {
            return Some(why);
        }
        if let Some(sp) = s.springs.iter().find(|sp| {
            (sp.body1 == i || sp.body2 == Some(i))
                && (sp.force_on_body1 != DVec2::ZERO || sp.couple_on_body1 != 0.0)
        }) {
            return Some(format!("spring \"{}\" pulls on it {at}", sp.name));
        }
        if let Some(c) = s
            .couplings
            .iter()
            .find(|c| c.impulse != 0.0 && c.terms.iter().any(|t| t.0 == i))
        {
            return Some(format!("coupling \"{}\" acts on it {at}", c.name));
        }
        None
    }
}

impl FrameProbe for CenterOfPercussion {
    /// The pivot's reaction and the body's own impulses are read from the snapshot and the links.
    fn frame_pass(&self) -> FramePass {
        FramePass::Motion
    }

    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        // The step's substeps as the engine ran them (overrides included).
        self.substeps = s.substeps.max(1);
        let Some(i) = cached_body(&mut self.index, s, &self.name) else {
            return;
        };
        let b = &s.bodies[i];
        let now = Motion::from(b);
        if self.o.is_none() {
            self.o = s.joints.iter().find(|j| j.name == self.joint).map(|j| {
                if j.body2 == i {
                    j.anchor
                } else {
                    j.anchor1
                }
            });
        }
        let (Some(o), Some(before)) = (self.o, self.before) else {
            self.before = Some(now);
            return;
        };
        let m = self.mass;
        let g_before = before.world_point(m.com);
        let r_bar = (g_before - o).length();
        let i_o = parallel_axis(m.inertia, m.mass, r_bar);
        self.q = center_of_percussion_distance(i_o, m.mass, r_bar).unwrap_or(f64::INFINITY);
        if !s.is_initial() {
            let reaction = self.pivot_reaction(s, i);
            if self.broken.is_none() && self.worst.covers(s.time) {
                self.broken = self.pin_moves(s, i);
            }
            if self.strikes > 0 {
                let events: Vec<Blow> = s
                    .impulses
                    .iter()
                    .filter(|e| e.body == i)
                    .map(|e| Blow {
                        impulse: e.impulse,
                        point: e.point,
                        couple: e.angular_impulse,
                    })
                    .collect();
                if let (false, Some(reaction)) = (events.is_empty(), reaction) {
                    if self.broken.is_none() && self.worst.covers(s.time) {
                        self.broken = self.other_action(s, i);
                    }
                    let p: DVec2 = events.iter().map(|e| e.impulse).sum();
                    // Non-impulsive forces over the step: gravity at G and the loads on the body.
                    let mut blows = events.clone();
                    let g_now = now.world_point(m.com);
                    blows.push(Blow {
                        impulse: m.mass * s.gravity * s.dt,
                        point: gravity_point(g_before, g_now, self.substeps),
                        couple: 0.0,
                    });
                    for l in s.loads.iter().filter(|l| l.body == i) {
                        blows.push(Blow {
                            impulse: l.force * s.dt,
                            point: l.point,
                            couple: l.torque * s.dt,
                        });
                    }
                    let (theory, omega1) =
                        pivot_impulse(m.mass, i_o, o, g_before, before.omega, &blows, s.dt);
                    self.blow = self.blow.max(p.length());
                    // CP-3 is about the tangential reaction (perpendicular to OG): the radial part
                    // (weight, centripetal m r_bar w^2) is non-impulsive, and rapier's velocity-level
                    // pin supplies the centripetal part a step late. Compare along t, report both.
                    let radial = (g_before - o).normalize_or(DVec2::NEG_Y);
                    let mut t = radial.perp();
                    if t.dot(p) < 0.0 {
                        t = -t;
                    }
                    self.worst.add((theory - reaction).dot(t), s.time);
                    self.last = (theory.dot(t), reaction.dot(t));
                    let r = g_before - o;
                    let h = events
                        .iter()
                        .map(|e| (e.point - o).dot(r.normalize_or(DVec2::ZERO)))
                        .sum::<f64>()
                        / events.len() as f64;
                    self.strike_notes.push(format!(
                        "t = {:.4} s: blow {:.4} N s at h = {:.4} m (h/q = {:.4}); tangential pivot impulse theory {:+.4e}, engine {:+.4e} N s (radial {:+.4e} / {:+.4e}); omega after theory {:.5}, engine {:.5} rad/s",
                        s.time, p.length(), h, h / self.q, self.last.0, self.last.1, theory.dot(radial), reaction.dot(radial), omega1, now.omega
                    ));
                }
            } else {
                // CP-2: the resultant of all forces passes through Q, so sum M_Q = 0.
                let dir = (g_before - o).normalize_or(DVec2::ZERO);
                let q_point = o + dir * self.q;
                let (mut m_q, mut m_o) = (0.0, 0.0);
                for_each_external_impulse_linked(
                    Before::One(i, &before),
                    s,
                    self.substeps,
                    &fa.links(s),
                    |k| k == i,
                    |imp| {
                        m_q += moment_about_center_of_percussion(
                            q_point,
                            [Blow {
                                impulse: imp.impulse,
                                point: imp.point,
                                couple: imp.couple,
                            }],
                        );
                        if !matches!(imp.source, Source::Joint(_)) {
                            m_o += imp.moment_about(o);
                        }
                    },
                );
                let engine = m_q / s.dt;
                self.max_moment = self
                    .max_moment
                    .max((m_o / s.dt).abs())
                    .max(m.mass * s.gravity.length() * self.q);
                self.worst.add(engine, s.time);
                self.last = (0.0, engine);
            }
        }
        self.before = Some(now);
    }

    fn finish(self) -> CheckResult {
        let o = self.o.unwrap_or_default();
        let mut subject = subject_of(&self.def);
        subject += &format!(" pinned at ({:.3}, {:.3})", o.x, o.y);
        if let Some(why) = &self.broken {
            return cannot_judge(&self.def, subject, why);
        }
        let (scale, mut note) = if self.strikes > 0 {
            (
                scale_or(self.blow, 1.0),
                format!(
                    "q = k_O^2/r_bar = {:.5} m; worst tangential |J_O theory - engine| {:.2e} N s",
                    self.q, self.worst.max
                ),
            )
        } else {
            (
                scale_or(self.max_moment, 1.0),
                format!(
                    "sum M_Q about Q at q = {:.5} m: worst {:.2e} N m at t = {:.3} s",
                    self.q, self.worst.max, self.worst.at_time
                ),
            )
        };
        for n in &self.strike_notes {
            note += "; ";
            note += n;
        }
        if self.strikes > 0 && self.worst.samples == 0 {
            note += "; no strike step was seen";
        }
        result(
            &self.def,
            subject,
            Summary::from_worst(self.last, &self.worst, scale, note),
        )
    }
}
