//! `restitution`: impacts between two bodies, e measured against e set (IM-9 to IM-15).

use super::momentum::pivot_of;
use super::{
    body_def, cached_body, dynamic_body, framed, misconfigured, result, subject_of, FrameProbe,
    Summary,
};
use crate::analysis::energy::kinetic_energy;
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::analysis::impact::{
    central_impact_energy_loss, pair_contact_linked, pair_normal_impulse, Bracket, ImpactDetector,
    PairContact,
};
use crate::analysis::kinetics::{for_each_external_impulse_linked, Before, Source};
use crate::analysis::momentum::angular_momentum_about;
use crate::analysis::percussion::strike_on_fixed_obstacle;
use crate::analysis::touching::{
    carried_back_at, flies_free, free_acceleration, impact_at_touch, Approaching, ReadAt,
};
use crate::analysis::{cross, Motion};
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckDef, Effect, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// `restitution`: every impact between `body` and `other` (or any partner) is bracketed from the
/// contact impulses (`analysis::impact::ImpactDetector`: a step whose normal impulse exceeds twice
/// what gravity gives the pair in a step starts it; it lasts while the impulse stays above 20% of
/// the first step's and the steps change the pair's relative normal velocity by more than
/// gravity does in a step, so a ball that lands on a pile and carries the balls above it is not
/// in an impact for the rest of the run), and measured at the instant the pair touches
/// (`analysis::touching`, as the questions' impact solution finds it): the states at the start
/// of its first step carried forward to the touch and those at the end of its last carried
/// back, each body at gravity while it flies free (not jointed, not pushed by a contact the step
/// before; after the touch, not resting on its partner). Read at the bracket's ends instead, e
/// was off by up to g dt / v (0.446 and 0.518 against 0.5 at 1/60 s, `tests/suite/sim/known_gaps.rs`).
/// A bracket whose pair was not approaching faster than gravity closes a gap in two steps (a
/// last, slow bounce settling) is listed in the note and not graded, unless no impact approached.
///
/// Central impact (the normal through the contact passes within 1% of k_G of each body's G):
/// theory e set in the level (the larger of the two bodies' `restitution`, the sim's combine rule),
/// engine e = -v'_n/v_n from the relative normal velocity of the contact points (IM-9); error
/// |e - e_set| on the scale 1 (perfectly elastic). The note adds the tangential velocity change, the
/// kinetic energy lost against IM-14 and the contact impulse against the momentum change.
///
/// Eccentric impact (IM-15: the textbook does not use e for it; the normal at the touch misses a
/// body's G, or a rough contact is left stuck, as a wheel pivoting onto a curb): theory H after =
/// H before plus the other forces' angular impulse over the bracket, about the point where a law
/// of angular momentum holds ([`Law`]): the pin of a body of the pair jointed to a fixed body when
/// the partner moves (the pin's reaction has no moment there and the pair's own impulses cancel),
/// else the contact point C (RM-10: the impulsive reaction passes through C); engine H after from
/// rapier's state (6/15); error relative to what the two bodies carry about that point one by
/// one (H of the pair can be near zero: a ball striking a pinned bar below its pin). The measured
/// e is shown as information only. A body turning about its pin that strikes a fixed body (a
/// pinned bar striking a peg) keeps H about neither point: the obstacle's impulse has a moment
/// about the pin, the pin's about C; where the pin's impulse vanishes (C at the center of
/// percussion, the normal perpendicular to OG: CP-3, `analysis::percussion::
/// strike_on_fixed_obstacle`), H about C of any rotation about the pin is zero, before and after,
/// and says nothing of the rebound. The body has one degree of freedom and e at the contact
/// fixes the impulse solution (IM-12, the obstacle's reaction from 6/17 about the pin), so e is
/// graded against e set, as for a central impact; the note gives the pin's share of the impulse.
pub(super) fn probe(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    let b = match dynamic_body(level, def) {
        Ok(b) => b,
        Err(e) => return misconfigured(def, e),
    };
    let other = match &def.other {
        Some(o) => match body_def(level, o) {
            Some(d) => Some(d.name.clone()),
            None => {
                return misconfigured(def, format!("`other` \"{o}\" is not a body of this level"))
            }
        },
        None => None,
    };
    let restitution = |d: &crate::level::BodyDef| {
        if level.effects.contains(&Effect::Restitution) {
            d.restitution.unwrap_or(0.0)
        } else {
            0.0
        }
    };
    framed(Restitution {
        def: def.clone(),
        name: b.name.clone(),
        e_body: restitution(b),
        disc_body: b.disc_radius(),
        // Only the bodies with a restitution or a disc's line of centers, and only the named
        // partner when there is one: a probe on every body of a large scene would otherwise
        // hold every body's name.
        partners: level
            .bodies
            .iter()
            .filter(|d| other.as_ref().is_none_or(|o| *o == d.name))
            .filter(|d| restitution(d) != 0.0 || d.disc_radius().is_some())
            .map(|d| (d.name.clone(), restitution(d), d.disc_radius()))
            .collect(),
        other,
        partner_e: 0.0,
        partner_disc: None,
        pushed: [false; 2],
        substeps: 1,
        index: None,
        partner: None,
        detector: None,
        open: None,
        impacts: Vec::new(),
    })
}

/// The law an impact is graded on (IM-15, RM-10, IM-12).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Law {
    /// H of the pair about the pin of one of them jointed to a fixed body, the partner moving:
    /// the pin's reaction is the only impulse from outside the pair, with no moment there.
    AboutPin,
    /// H about the contact point C: the impulsive reaction passes through it (RM-10).
    AboutContact,
    /// A body turning about its pin strikes a fixed body: no angular momentum law fixes the
    /// rebound. About the pin the obstacle's impulse has a moment; about C the pin's has, except
    /// at the center of percussion, where the pin takes no impulse (CP-3) but H about C of any
    /// rotation about the pin is zero (I_O omega - q m r_bar omega), before and after alike. e
    /// at the contact fixes the impulse solution (IM-12): e is graded. `pin_share`: the pin's
    /// impulse by that solution over the obstacle's, for a body on a pin alone.
    EAtContact { pin_share: Option<f64> },
}

/// The pin's impulse, as a fraction of the obstacle's, below which a body turning about its pin
/// that strikes a fixed body is said (in the note) to be struck at its center of percussion (a
/// peg placed at q to about 1e-3 of q).
const PIN_IMPULSE_VANISHES: f64 = 1e-3;

/// An impact in progress.
struct Open {
    start_time: f64,
    /// The states at the start of the impact's first step and at the end of its last (the
    /// angular-momentum balance about C is taken over that whole bracket).
    a0: Motion,
    b0: Motion,
    a1: Motion,
    b1: Motion,
    /// When the last step of the bracket ended, s.
    end_time: f64,
    /// The touching instant (`analysis::touching`), the states carried to it from the start
    /// of the step, and each body's acceleration over the carry (gravity while it flies free):
    /// e, the energy lost and m dv are read at the touch. None when the pair was not
    /// approaching: the states at the bracket's ends are read.
    touch: Option<Touch>,
    /// The engine's contact normal and point C at the first step.
    normal: DVec2,
    point: DVec2,
    /// The point H is balanced about (IM-15) and the law graded ([`Law`]).
    about: DVec2,
    law: Law,
    impulse: DVec2,
    /// Angular impulse about `about` of the other forces over the bracket.
    other_moment: f64,
    steps: u32,
    points: usize,
    /// The two bodies' mass properties at the start.
    body_a: MassOf,
    body_b: MassOf,
}

/// An impact's touching instant, with the states carried to it.
#[derive(Clone, Copy)]
struct Touch {
    time: f64,
    /// The normal and the touching point there (the material point carried with the body).
    normal: DVec2,
    point: DVec2,
    a: Motion,
    b: Motion,
    acc: [DVec2; 2],
}

/// A body's mass and I_G (copied at the start of an impact, without the name a `BodyState` clones).
#[derive(Clone, Copy)]
struct MassOf {
    mass: f64,
    inertia: f64,
}

impl MassOf {
    fn of(b: &crate::snapshot::BodyState) -> Self {
        MassOf {
            mass: b.mass,
            inertia: b.inertia,
        }
    }
}

/// A measured impact.
struct Done {
    /// When the impact began (the start of its first step), s.
    start_time: f64,
    steps: u32,
    points: usize,
    /// The touching instant, s: None when the pair did not approach faster than gravity closes
    /// a gap in a step or two, a contact settling at step resolution, which the textbook's e
    /// does not describe (the questions call it no impact).
    touch_time: Option<f64>,
    eccentric: bool,
    e: f64,
    e_set: f64,
    /// The approach speed along the normal, m/s, and the tangential relative velocity before
    /// and after.
    approach: f64,
    tangential: (f64, f64),
    /// T lost, measured and by IM-14, J.
    lost: f64,
    lost_theory: f64,
    /// The normal impulse on the body and its m dv_n, N s.
    impulse_and_dp: (f64, f64),
    h_before: f64,
    h_theory: f64,
    h_engine: f64,
    /// What the two bodies carry about that point one by one, before or after (the larger).
    h_scale: f64,
    /// The law an eccentric impact is graded on.
    law: Law,
}

impl Done {
    fn approached(&self) -> bool {
        self.touch_time.is_some()
    }

    /// Whether the impact is graded on H (else on e).
    fn graded_on_h(&self) -> bool {
        self.eccentric && !matches!(self.law, Law::EAtContact { .. })
    }
}

struct Restitution {
    def: CheckDef,
    name: String,
    other: Option<String>,
    e_body: f64,
    /// The body's radius when it is a disc (the line of centers of an impact is then exact).
    disc_body: Option<f64>,
    /// The possible partners' restitution and disc radius, by name: the named one, or the
    /// level's bodies with a nonzero restitution or a disc's shape.
    partners: Vec<(String, f64, Option<f64>)>,
    /// The partner's restitution and disc radius (set with `partner`).
    partner_e: f64,
    partner_disc: Option<f64>,
    /// Whether a contact pushed the body and the partner in the last step observed: a body
    /// held up by its floor until it strikes is not carried with g to the touch.
    pushed: [bool; 2],
    substeps: usize,
    index: Option<usize>,
    partner: Option<usize>,
    detector: Option<ImpactDetector>,
    open: Option<Open>,
    impacts: Vec<Done>,
}

impl Restitution {
    /// The touching instant of the impact that starts in this step between bodies `[i, k]`
    /// (`analysis::touching`, as the questions' impact solution finds it), with the normal and
    /// point there; None when the pair was not approaching.
    fn touching(
        &self,
        s: &Snapshot,
        fa: &FrameAnalysis,
        [i, k]: [usize; 2],
        c: &PairContact,
    ) -> Option<Touch> {
        let before = fa.start_of_step();
        // Free over the approach: under gravity alone, not pushed by a contact the step before.
        let acc = [(i, self.pushed[0]), (k, self.pushed[1])].map(|(x, pushed)| {
            if !pushed && flies_free(s, x) {
                free_acceleration(s, x)
            } else {
                DVec2::ZERO
            }
        });
        // The material points that touch, found at the step's end, taken back to its start.
        let local = [
            Motion::from(&s.bodies[i]).local_point(c.surfaces.0),
            Motion::from(&s.bodies[k]).local_point(c.surfaces.1),
        ];
        let (pa, pb) = (&before[i], &before[k]);
        let approach = Approaching {
            pre: [pa, pb],
            acc,
            points: [pa.world_point(local[0]), pb.world_point(local[1])],
            normal: c.normal,
            discs: [self.disc_body, self.partner_disc],
        };
        let t = approach.touching(s.gravity.length(), s.dt)?;
        let (a, b) = (pa.carried(t.tau, acc[0]), pb.carried(t.tau, acc[1]));
        Some(Touch {
            time: s.time - s.dt + t.tau,
            normal: t.normal,
            point: t.disc_point.unwrap_or_else(|| a.world_point(local[0])),
            a,
            b,
            acc,
        })
    }

    /// The point an eccentric impact of `[i, k]` is balanced about and the law graded
    /// ([`Law`]), from the state `a0` of `i` before it and the contact (C, n) at the touch; H
    /// about C is taken about `engine_point`, the engine's contact point at the impact's first
    /// step.
    fn law(
        &self,
        s: &Snapshot,
        [i, k]: [usize; 2],
        a0: &Motion,
        (c, n): (DVec2, DVec2),
        engine_point: DVec2,
    ) -> (DVec2, Law) {
        let fixed = |x: usize| s.bodies[x].mass == 0.0;
        if !fixed(k) {
            return match pivot_of(s, i).or_else(|| pivot_of(s, k)) {
                Some(o) => (o, Law::AboutPin),
                None => (engine_point, Law::AboutContact),
            };
        }
        let Some(o) = pivot_of(s, i) else {
            return (engine_point, Law::AboutContact);
        };
        // The body turns about its pin alone (one joint): where does the impulse solution put
        // the pin's impulse (CP-3)?
        let joints = s
            .joints
            .iter()
            .filter(|j| j.body1 == i || j.body2 == i)
            .count();
        let b = &s.bodies[i];
        let i_o = crate::analysis::mass::parallel_axis(b.inertia, b.mass, (a0.com - o).length());
        let e = self.e_body.max(self.partner_e);
        let pin_share = strike_on_fixed_obstacle(b.mass, i_o, o, a0.com, a0.omega, (c, n), e)
            .filter(|_| joints == 1)
            .map(|(blow, j_o, _)| j_o.length() / blow.length().max(f64::MIN_POSITIVE));
        (o, Law::EAtContact { pin_share })
    }

    /// H about C of a body (6/15); nothing for a body without mass.
    fn h_about(b: &MassOf, m: &Motion, c: DVec2) -> f64 {
        if b.mass > 0.0 {
            angular_momentum_about(b.mass, b.inertia, m.com, m.velocity, m.omega, c)
        } else {
            0.0
        }
    }

    /// Ends the impact in progress; `resting`: the pair's contact pushed on after it.
    fn close(&mut self, resting: bool) {
        let Some(o) = self.open.take() else { return };
        // Just before and just after (IM-9): at the touch, the states after carried back to it
        // from the bracket's end as the states before were carried forward from its start; a
        // body that rests on its partner after the touch is held there, not flying free (a
        // ball with e = 0 carried back with g would read e = g (t_end - t_touch) / v).
        // (`analysis::touching::impact_at_touch`, the reading the `Restitution` question takes.)
        let (point, normal) = match &o.touch {
            Some(t) => (t.point, t.normal),
            None => (o.point, o.normal),
        };
        let (time, before, acc) = match &o.touch {
            // t.acc is gravity for a body that flew free into the touch, else zero.
            Some(t) => (
                t.time,
                [(&t.a, t.time), (&t.b, t.time)],
                t.acc.map(|a| carried_back_at(a != DVec2::ZERO, resting, a)),
            ),
            None => (
                o.end_time,
                [(&o.a0, o.end_time), (&o.b0, o.end_time)],
                [DVec2::ZERO; 2],
            ),
        };
        fn read((motion, time): (&Motion, f64), acc: DVec2) -> ReadAt<'_> {
            ReadAt { motion, time, acc }
        }
        let m = impact_at_touch(
            time,
            [read(before[0], DVec2::ZERO), read(before[1], DVec2::ZERO)],
            [
                read((&o.a1, o.end_time), acc[0]),
                read((&o.b1, o.end_time), acc[1]),
            ],
            point,
            normal,
            o.impulse,
        );
        let [a0, b0] = [*before[0].0, *before[1].0];
        let [a1, b1] = [
            o.a1.carried(time - o.end_time, acc[0]),
            o.b1.carried(time - o.end_time, acc[1]),
        ];
        let (ba, bb) = (&o.body_a, &o.body_b);
        let e_set = self.e_body.max(self.partner_e);
        let k_g = |b: &MassOf| crate::analysis::mass::radius_of_gyration(b.inertia, b.mass);
        // Eccentric when the normal's line of action misses a body's G by more than 1% of its
        // k_G. At the touch, from the normal and point there; without one (a pair that did not
        // approach), from what the impulse did (its moment about G, I_G dw, against m |dv|),
        // since rapier takes the contact's normal and point up to a step before touching. (The
        // impulse's effect alone called a spinning disc striking a rough wall eccentric: its
        // friction turns it, though the normal passes through G.) A rough impact that leaves
        // the contact stuck (a wheel pivoting onto a curb, RM-10) is taken about C too: friction
        // then acts as hard as the normal, and the textbook solves it by H about C, not by e.
        // Stuck: the slip speed fell by 95% or more (rapier leaves a wheel at a curb's corner
        // with 3% of it, 0.017 of 0.508 m/s; a disc sliding along a wall keeps 55%).
        let slip = 1e-3 * m.v_n_before.abs() + 1e-9;
        let stuck = m.v_t_before.abs() > slip && m.v_t_after.abs() <= 0.05 * m.v_t_before.abs();
        let eccentric = stuck
            || [(ba, &a0, &a1), (bb, &b0, &b1)]
                .iter()
                .any(|(b, st0, st1)| {
                    b.mass > 0.0
                        && b.inertia > 0.0
                        && match &o.touch {
                            Some(_) => cross(point - st0.com, normal).abs() > 0.01 * k_g(b),
                            None => {
                                b.inertia * (st1.omega - st0.omega).abs()
                                    > 0.01
                                        * k_g(b)
                                        * b.mass
                                        * (st1.velocity - st0.velocity).length()
                            }
                        }
                });
        let h = |st: [&Motion; 2]| {
            [
                Self::h_about(ba, st[0], o.about),
                Self::h_about(bb, st[1], o.about),
            ]
        };
        let (hb, ha) = (h([&o.a0, &o.b0]), h([&o.a1, &o.b1]));
        let h_before = hb[0] + hb[1];
        let h_engine = ha[0] + ha[1];
        let h_theory = h_before + o.other_moment;
        // The scale: what the bodies carry one by one (a ball striking a bar below its pin can
        // bring H about the contact point near zero, and a relative error on it blew up).
        let h_scale = (hb[0].abs() + hb[1].abs()).max(ha[0].abs() + ha[1].abs());
        let t = |b: &MassOf, st: &Motion| {
            if b.mass > 0.0 {
                kinetic_energy(b.mass, st.velocity, b.inertia, st.omega)
            } else {
                0.0
            }
        };
        let lost = t(ba, &a0) + t(bb, &b0) - t(ba, &a1) - t(bb, &b1);
        let mb = if bb.mass > 0.0 {
            bb.mass
        } else {
            f64::INFINITY
        };
        let lost_theory = central_impact_energy_loss(ba.mass, mb, 0.0, m.v_n_before, e_set);
        // Momentum along n of the body against the contact impulse on it (IM-9).
        let dp = ba.mass * (a1.velocity - a0.velocity).dot(m.normal);
        let j_on_a = -o.impulse.dot(m.normal);
        self.impacts.push(Done {
            start_time: o.start_time,
            steps: o.steps,
            points: o.points,
            touch_time: o.touch.map(|t| t.time),
            eccentric,
            e: m.e,
            e_set,
            approach: -m.v_n_before,
            tangential: (m.v_t_before, m.v_t_after),
            lost,
            lost_theory,
            impulse_and_dp: (j_on_a, dp),
            h_before,
            h_theory,
            h_engine,
            h_scale,
            law: o.law,
        });
    }
}

impl Done {
    /// What the impact measured, for the result's note (written once, at the end of the run:
    /// a pile's resting contacts open and close brackets every few steps).
    fn note(&self, body: &str) -> String {
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        let touch = match self.touch_time {
            Some(t) => format!(", touching at {t:.5} s"),
            None => ", not approaching: read at the bracket's ends".into(),
        };
        let mut note = format!(
            "t = {:.4} s ({} step{}, {} point{}{touch}): approach {:.4} m/s, e measured {:.5} (set {:.3}), tangential {:+.4} -> {:+.4} m/s, T lost {:.4e} J",
            self.start_time,
            self.steps,
            plural(self.steps as usize),
            self.points,
            plural(self.points),
            self.approach,
            self.e,
            self.e_set,
            self.tangential.0,
            self.tangential.1,
            self.lost
        );
        if self.graded_on_h() {
            note += &format!(
                ", eccentric: H about {} before {:.5}, after theory {:.5}, engine {:.5} N m s (scale {:.5}; e not a textbook quantity here, IM-15)",
                match self.law {
                    Law::AboutPin => "the pin O",
                    _ => "the contact point C",
                },
                self.h_before, self.h_theory, self.h_engine, self.h_scale
            );
        } else if let (true, Law::EAtContact { pin_share }) = (self.eccentric, self.law) {
            note += &format!(
                ", eccentric, turning about its pin against a fixed body: {}, so e at the contact, which fixes the impulse solution, is graded (IM-12)",
                match pin_share {
                    Some(x) if x <= PIN_IMPULSE_VANISHES => format!("struck at its center of percussion, the pin takes no impulse ({x:.1e} of the obstacle's, CP-3), but H about C is zero before and after for any rebound, and about the pin the obstacle's impulse has a moment"),
                    Some(x) => format!("H is kept about neither the pin (the obstacle's impulse has a moment there) nor C (the pin's has: {x:.4} of the obstacle's by the impulse solution, CP-3)"),
                    None => "H is kept about neither the pin (the obstacle's impulse has a moment there) nor C (the pin's, or the other joints', have)".to_string(),
                }
            );
        } else {
            note += &format!(
                " (IM-14: {:.4e} J), normal impulse on \"{body}\" {:.4e} N s vs m dv_n {:.4e} N s",
                self.lost_theory, self.impulse_and_dp.0, self.impulse_and_dp.1
            );
        }
        note
    }
}

impl FrameProbe for Restitution {
    /// The impact's bracket reads the step's contacts and start states, not the frame's sums.
    fn frame_pass(&self) -> FramePass {
        FramePass::Motion
    }

    fn observe_frame(&mut self, s: &Snapshot, fa: &FrameAnalysis) {
        // The step's substeps as the engine ran them (overrides included).
        self.substeps = s.substeps.max(1);
        let Some(i) = cached_body(&mut self.index, s, &self.name) else {
            return;
        };
        if self.partner.is_none() {
            self.partner = match &self.other {
                Some(o) => s.body_index(o),
                // Any partner: the one with the largest normal impulse this step, among the
                // body's own contacts (the frame's index: a scan of every contact, every step,
                // for each body that touches nothing made 100 probes cost O(N x contacts)).
                None => fa
                    .links(s)
                    .contacts_of(i)
                    .iter()
                    .map(|&c| &s.contacts[c as usize])
                    .max_by(|a, b| {
                        let n = |c: &crate::snapshot::ContactState| {
                            c.points.iter().map(|p| p.normal_impulse).sum::<f64>()
                        };
                        n(a).total_cmp(&n(b))
                    })
                    .map(|c| if c.body1 == i { c.body2 } else { c.body1 }),
            };
            if let Some(k) = self.partner {
                let name = &s.bodies[k].name;
                if let Some((_, e, disc)) = self.partners.iter().find(|(n, ..)| n == name) {
                    (self.partner_e, self.partner_disc) = (*e, *disc);
                }
            }
        }
        // The bodies' states at the start of the step, copied once per step for every check
        // (the shared frame pass): a copy per probe made 100 probes on 100 bodies cost O(N^2).
        let before = fa.start_of_step();
        if let (Some(k), true) = (self.partner, fa.stepped()) {
            let detector = self.detector.get_or_insert_with(|| {
                let weight: f64 = [i, k]
                    .iter()
                    .map(|&x| s.bodies[x].mass * s.gravity.length())
                    .sum();
                ImpactDetector::new(2.0 * weight * s.dt + 1e-12, 0.2)
            });
            // The pair's contact in full only where an impact may start or goes on: most
            // steps of most pairs need its normal impulse alone.
            let links = fa.links(s);
            let j_n = pair_normal_impulse(s, i, Some(k), Some(&links));
            let pc = (detector.in_impact() || j_n > detector.threshold)
                .then(|| pair_contact_linked(s, i, k, &links))
                .flatten();
            drop(links);
            let now = |x: usize| Motion::from(&s.bodies[x]);
            // Whether the step changed the pair's relative normal velocity at the contact by
            // more than gravity does in a step (an impact in progress; a load carried is not).
            let changes_motion = pc.is_some_and(|c| {
                let v_n = |a: &Motion, b: &Motion| {
                    (b.velocity_at(c.point) - a.velocity_at(c.point)).dot(c.normal)
                };
                let dv = v_n(&now(i), &now(k)) - v_n(&before[i], &before[k]);
                dv.abs() > s.gravity.length() * s.dt
            });
            let bracket = detector.step(j_n, changes_motion);
            match (bracket, pc) {
                (Bracket::Start, Some(c)) => {
                    let touch = self.touching(s, fa, [i, k], &c);
                    let (point, normal) =
                        touch.map_or((c.point, c.normal), |t| (t.point, t.normal));
                    // The bar's state at the touch where there is one (its G then on the line
                    // the normal is perpendicular to, at the center of percussion).
                    let at = touch.as_ref().map_or(&before[i], |t| &t.a);
                    let (about, law) = self.law(s, [i, k], at, (point, normal), c.point);
                    self.open = Some(Open {
                        start_time: s.time - s.dt,
                        a0: before[i],
                        b0: before[k],
                        a1: now(i),
                        b1: now(k),
                        end_time: s.time,
                        touch,
                        normal: c.normal,
                        point: c.point,
                        about,
                        law,
                        impulse: DVec2::ZERO,
                        other_moment: 0.0,
                        steps: 0,
                        points: c.points,
                        body_a: MassOf::of(&s.bodies[i]),
                        body_b: MassOf::of(&s.bodies[k]),
                    });
                }
                // Resting after the impact when the pair's contact still pushes (e = 0, a bar
                // that pivots on its ledge): then held, not flying free, after the touch.
                (Bracket::End, _) => self.close(pc.is_some_and(|c| c.normal_impulse > 0.0)),
                _ => {}
            }
            if let (Some(o), Some(c)) = (self.open.as_mut(), pc) {
                o.a1 = now(i);
                o.b1 = now(k);
                o.end_time = s.time;
                o.impulse += c.impulse_on_b;
                o.steps += 1;
                o.points = o.points.max(c.points);
                let about = o.about;
                let mut other_moment = 0.0;
                for_each_external_impulse_linked(
                    Before::Two([(i, &before[i]), (k, &before[k])]),
                    s,
                    self.substeps,
                    &fa.links(s),
                    |x| x == i || x == k,
                    |imp| {
                        let between = match imp.source {
                            Source::Contact { contact, .. } => {
                                let c = &s.contacts[contact];
                                (c.body1 == i && c.body2 == k) || (c.body1 == k && c.body2 == i)
                            }
                            _ => false,
                        };
                        if !between {
                            other_moment += imp.moment_about(about);
                        }
                    },
                );
                o.other_moment += other_moment;
            }
            // For the next step's impact, if it is one: which of the two a contact pushed.
            let links = fa.links(s);
            self.pushed = [links.pushed(i), links.pushed(k)];
        }
    }

    fn finish(mut self) -> CheckResult {
        let subject = subject_of(&self.def);
        // An impact still in progress at the end is measured with the last states (its
        // contact still pushing).
        self.close(true);
        if self.impacts.is_empty() {
            return result(
                &self.def,
                subject,
                Summary {
                    note: "no impact was detected (no step with an impulsive contact between the pair)".into(),
                    max_rel: f64::INFINITY,
                    ..Summary::default()
                },
            );
        }
        // With a `window`, only the impacts that begin inside it.
        let window = super::window_of(&self.def);
        self.impacts
            .retain(|d| super::in_window(window, d.start_time));
        if self.impacts.is_empty() {
            return result(
                &self.def,
                subject,
                Summary {
                    note: format!(
                        "no impact began inside the window {window:?} s (the run's impacts are outside it)"
                    ),
                    max_rel: f64::INFINITY,
                    ..Summary::default()
                },
            );
        }
        // Only the impacts that approached are graded, when there are any: a ball's last
        // bounces, slower than gravity closes a gap in two steps, settle in a few steps of
        // contact that step resolution cannot tell from a landing (kept in the note).
        let some_approached = self.impacts.iter().any(Done::approached);
        let note = self
            .impacts
            .iter()
            .map(|d| match some_approached && !d.approached() {
                true => format!("{} (not graded)", d.note(&self.name)),
                false => d.note(&self.name),
            })
            .collect::<Vec<_>>()
            .join("; ");
        if some_approached {
            self.impacts.retain(Done::approached);
        }
        let errors: Vec<(f64, f64)> = self
            .impacts
            .iter()
            .map(|d| {
                if d.graded_on_h() {
                    let scale = d.h_scale.max(f64::MIN_POSITIVE);
                    (
                        (d.h_engine - d.h_theory).abs(),
                        (d.h_engine - d.h_theory).abs() / scale,
                    )
                } else {
                    ((d.e - d.e_set).abs(), (d.e - d.e_set).abs())
                }
            })
            .collect();
        let first = &self.impacts[0];
        let (theory, engine, scale) = if first.graded_on_h() {
            (first.h_theory, first.h_engine, first.h_scale)
        } else {
            (first.e_set, first.e, 1.0)
        };
        let max_rel = errors.iter().map(|e| e.1).fold(0.0, f64::max);
        let max_abs = errors.iter().map(|e| e.0).fold(0.0, f64::max);
        let last = errors.last().copied().unwrap_or_default();
        result(
            &self.def,
            subject,
            Summary {
                theory,
                engine,
                max_abs,
                max_rel,
                final_abs: last.0,
                final_rel: last.1,
                samples: self.impacts.len() as u64,
                scale,
                note,
            },
        )
    }
}
