//! One pass over a step: what the textbook computes for every body and for the scene.
//!
//! [`FrameAnalysis::observe`] takes the snapshots in order and returns a [`Frame`]: per body its
//! kinetic energy (6/9), momenta (6/12, 6/13), instantaneous center (RK-11), accelerations by
//! finite differences, the free-body diagram's impulse sums and the Newton-Euler residuals (6/1),
//! and the non-conservative work of its forces over the step (WE-14); for the scene T, V_g, V_e,
//! G and H about the origin (6/18, 6/19), the resultant of the external impulses (forces between
//! two bodies of the scene are internal and cancel, 6/18) and the step's non-conservative work.
//!
//! The checks read this frame instead of walking the step's impulses each on its own (see
//! `checks::CheckSet`): the walk and the start-of-step states are computed once per step.
//! It costs O(bodies + contacts + joints + springs) per step.

use super::energy::{gravity_potential, kinetic_energy, work_of_contact_impulse};
use super::kinematics::{acceleration_fd, angular_acceleration_fd, instantaneous_center};
use super::kinetics::contact_arms_at_start;
use super::links::BodyLinks;
use super::momentum::{angular_momentum_g, linear_momentum};
use super::{cross, Motion};
use crate::snapshot::{BodyKind, ContactState, Snapshot};
use glam::DVec2;
use std::cell::{Cell, Ref, RefCell};

mod pushed;

/// Sums of a step's impulses on a body or a set of bodies (impulses over the step, N s and N m s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ImpulseSums {
    /// Sum of impulses, sum J = integral of sum F dt over the step (IM-2).
    pub impulse: DVec2,
    /// Sum of angular impulses about the world origin, sum (r_P x J)_z + couples (IM-7).
    pub moment_origin: f64,
    /// The largest single impulse |J_i| and couple |C_i| of the diagram: the size of the forces
    /// that balance, where their sum (a body at rest, a static mechanism) says nothing of it.
    pub largest_impulse: f64,
    pub largest_couple: f64,
}

impl ImpulseSums {
    /// Sum of angular impulses about a fixed point O: M_O = M_origin - (r_O x sum J)_z.
    pub fn moment_about(&self, o: DVec2) -> f64 {
        self.moment_origin - cross(o, self.impulse)
    }

    fn add(&mut self, j: DVec2, moment_origin: f64, couple: f64) {
        self.impulse += j;
        self.moment_origin += moment_origin;
        self.largest_impulse = self.largest_impulse.max(j.length());
        self.largest_couple = self.largest_couple.max(couple.abs());
    }
}

/// The work U' of a step's non-conservative forces (WE-14), by source, J. Weight, springs whose
/// ends are held by the subject or the ground (their V_e is in the ledger) and ideal joint
/// reactions are not in it. Motors and spring damping are not either: they need the level's
/// joint axes and spring constants (the `work_energy` check adds them).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepWork {
    /// Applied loads (forces and couples).
    pub loads: f64,
    /// Impulse events.
    pub events: f64,
    /// Contact impulses (friction, impacts; both sides of a contact inside the subject).
    pub contacts: f64,
    /// Couplings, and springs with an end on a body outside the subject that is not the ground.
    pub other: f64,
}

impl StepWork {
    pub fn total(&self) -> f64 {
        self.loads + self.events + self.contacts + self.other
    }

    fn add(&mut self, slot: Slot, u: f64) {
        *match slot {
            Slot::Loads => &mut self.loads,
            Slot::Events => &mut self.events,
            Slot::Contacts => &mut self.contacts,
            Slot::Other => &mut self.other,
        } += u;
    }
}

/// How much of the pass a run's readers need: each level includes the one before.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
pub enum FramePass {
    /// The bodies' states at the step's ends and the links only
    /// ([`FrameAnalysis::observe_motion`]).
    Motion,
    /// The frame without the work of the step's forces ([`Frame::work`] is then refused): the
    /// free-body diagrams' sums, residuals, momenta and energies.
    Diagram,
    /// Everything, the non-conservative work by source included.
    #[default]
    Work,
}

/// One body's textbook quantities at the end of a step (zero for bodies without mass).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BodyFrame {
    /// T = 1/2 m v_G^2 + 1/2 I_G w^2 (6/9), J.
    pub kinetic_energy: f64,
    /// G = m v_G (6/12), N s.
    pub linear_momentum: DVec2,
    /// H_G = I_G w (6/13), N m s.
    pub angular_momentum_g: f64,
    /// The instantaneous center of zero velocity (RK-11); None in translation.
    pub instantaneous_center: Option<DVec2>,
    /// a_G and alpha by finite differences over the step (`FD`).
    pub acceleration: DVec2,
    pub angular_acceleration: f64,
    /// Sum of forces and of moments about G from the free-body diagram (impulse / dt), N and N m.
    pub force: DVec2,
    pub moment_g: f64,
    /// sum F - m a_G and sum M_G - I_G alpha (6/1).
    pub force_residual: DVec2,
    pub moment_residual: f64,
    /// Every impulse of the body's free-body diagram over the step, summed.
    pub impulses: ImpulseSums,
    /// The non-conservative work done on the body over the step (springs count when their other
    /// end is on another body that is not the ground).
    pub work: StepWork,
}

/// Scene totals at one instant (the bodies with mass).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Totals {
    /// Sum of T, J.
    pub kinetic_energy: f64,
    /// Sum of V_g = -m g . r_G, J (WE-13).
    pub gravity_potential: f64,
    /// System G (6/18), N s.
    pub linear_momentum: DVec2,
    /// System H about the world origin (6/19), N m s; about O: H_origin - (r_O x G)_z.
    pub angular_momentum_origin: f64,
}

impl Totals {
    /// System H about a point O (6/15 summed): H_O = H_origin - (r_O x G)_z.
    pub fn angular_momentum_about(&self, o: DVec2) -> f64 {
        self.angular_momentum_origin - cross(o, self.linear_momentum)
    }
}

/// The whole scene at the end of a step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Frame {
    pub time: f64,
    /// The step's length (0 for the initial state).
    pub dt: f64,
    /// Indexed like `Snapshot::bodies`.
    pub bodies: Vec<BodyFrame>,
    /// T, V_g, G, H of the bodies with mass at the end of the step.
    pub totals: Totals,
    /// The same at the start of the step (the previous frame's; equal to `totals` initially).
    pub totals_before: Totals,
    /// Sum of the springs' V_e = 1/2 k x^2, J.
    pub elastic_potential: f64,
    /// The external impulses on the system of all bodies with mass over the step (6/18).
    pub external: ImpulseSums,
    /// The non-conservative work done on that system over the step, internal contacts included.
    pub work: StepWork,
    /// Whether this frame closes a step (false for the initial state).
    pub stepped: bool,
    /// Whether the pass computed the work (`FramePass::Work`); else the work fields are zero.
    pub work_computed: bool,
}

impl Frame {
    /// The non-conservative work of the step on body i, or on the scene with None.
    ///
    /// Panics when the pass left the work out (`FramePass::Diagram`): its reader must ask for
    /// `FramePass::Work`.
    pub fn work(&self, body: Option<usize>) -> StepWork {
        assert!(
            self.work_computed,
            "the work of this step was not computed (FramePass::Diagram): ask for FramePass::Work"
        );
        match body {
            Some(i) => self.bodies[i].work,
            None => self.work,
        }
    }
}

/// Computes a [`Frame`] per snapshot, keeping what it needs from the previous one.
#[derive(Debug, Clone, Default)]
pub struct FrameAnalysis {
    /// Every body's state at the start of the last step observed.
    before: Vec<Motion>,
    /// ... and at its end (swapped into `before` at the next step).
    after: Vec<Motion>,
    /// Per body: has it mass; and the bodies with mass (set at the initial snapshot: masses do not
    /// change during a run).
    has_mass: Vec<bool>,
    massive: Vec<usize>,
    /// The bodies that are not fixed.
    moving: Vec<usize>,
    /// Scratch for the pass, per body.
    mids: Vec<Mid>,
    /// The pairs of bodies a contact pushed in the last step observed and in the step before
    /// it: which contacts rest (`pushed`).
    pushed: pushed::Pushed,
    /// Which contacts and joints touch each body in the last snapshot, built when first asked
    /// for in a step (`fresh` says it is): most levels' checks never ask.
    links: RefCell<BodyLinks>,
    fresh: Cell<bool>,
    frame: Frame,
    /// Whether the last snapshot closes a step, and whether `frame` is its frame.
    stepped: bool,
    frame_current: bool,
}

impl FrameAnalysis {
    /// An analysis with no step seen yet. Where gravity acts within a step depends on the
    /// step's substeps, which each snapshot carries (`Snapshot::substeps`).
    pub fn new() -> Self {
        FrameAnalysis::default()
    }

    /// The bodies' states at the start of the step of the last frame (at its end for the initial
    /// state).
    pub fn start_of_step(&self) -> &[Motion] {
        &self.before
    }

    /// The last frame computed.
    ///
    /// Panics when the run observes its snapshots with [`Self::observe_motion`], which computes
    /// none: a reader of the frame must be declared (`checks::Probe::frame_pass`).
    pub fn frame(&self) -> &Frame {
        assert!(
            self.frame_current,
            "the frame of this step was not computed (observe_motion): declare the reader"
        );
        &self.frame
    }

    /// Which contacts and joints touch each body in `snap`, the last snapshot observed (for
    /// readings about one body or a pair: `kinetics::for_each_external_impulse_linked`).
    pub fn links(&self, snap: &Snapshot) -> Ref<'_, BodyLinks> {
        if !self.fresh.get() {
            self.links.borrow_mut().rebuild(snap);
            self.fresh.set(true);
        }
        self.links.borrow()
    }

    /// Whether the last snapshot observed closes a step (false for the initial state).
    pub fn stepped(&self) -> bool {
        self.stepped
    }

    /// Only the bodies' states at the start and end of the step ([`Self::start_of_step`]) and
    /// the links ([`Self::links`]), without the frame: for a run whose readers need no more
    /// (an impact's bracket, a blow's pivot), at a fraction of [`Self::observe`]'s cost. A run
    /// takes one or the other for every snapshot: [`Self::frame`] refuses a frame not computed.
    pub fn observe_motion(&mut self, snap: &Snapshot) {
        self.advance(snap);
        self.frame_current = false;
    }

    /// The pass its readers need: [`Self::observe_motion`], or the frame with or without the
    /// work of the step's forces.
    pub fn observe_as(&mut self, snap: &Snapshot, pass: FramePass) {
        match pass {
            FramePass::Motion => self.observe_motion(snap),
            _ => {
                self.observe_pass(snap, pass == FramePass::Work);
            }
        }
    }

    /// Swaps the end of the last step into its start and reads this step's end.
    fn advance(&mut self, snap: &Snapshot) {
        let n = snap.bodies.len();
        self.stepped = !snap.is_initial() && self.before.len() == n;
        self.fresh.set(false);
        if self.stepped {
            // The end of the last step is the start of this one. Fixed bodies do not move: their
            // entries in both buffers stay as first copied.
            std::mem::swap(&mut self.before, &mut self.after);
            for &i in &self.moving {
                self.after[i] = Motion::from(&snap.bodies[i]);
            }
        } else {
            // The initial state (or a new scene): everything from scratch.
            self.after.clear();
            self.after.extend(snap.bodies.iter().map(Motion::from));
            self.before.clone_from(&self.after);
            self.frame.bodies.clear();
            self.frame.bodies.resize(n, BodyFrame::default());
            self.has_mass.clear();
            self.has_mass
                .extend(snap.bodies.iter().map(|b| b.mass > 0.0));
            self.massive.clear();
            self.massive.extend((0..n).filter(|&i| self.has_mass[i]));
            self.mids.clear();
            self.mids.resize(n, Mid::default());
            self.moving.clear();
            self.moving
                .extend((0..n).filter(|&i| snap.bodies[i].kind != BodyKind::Fixed));
        }
    }

    /// The frame of `snap` (the snapshots must come in order, the initial one first).
    ///
    /// Bodies without mass keep an all-zero entry: a body's mass does not change during a run.
    pub fn observe(&mut self, snap: &Snapshot) -> &Frame {
        self.observe_pass(snap, true)
    }

    /// [`Self::observe`], with the work of the step's forces only when `work`.
    fn observe_pass(&mut self, snap: &Snapshot, work: bool) -> &Frame {
        self.advance(snap);
        self.frame_current = true;
        let stepped = self.stepped;
        let f = &mut self.frame;
        f.time = snap.time;
        f.dt = snap.dt;
        f.stepped = stepped;
        f.external = ImpulseSums::default();
        f.work = StepWork::default();
        f.work_computed = work;
        f.elastic_potential = snap.springs.iter().map(|s| s.energy).sum();
        // The pairs a contact pushed: this step's, and the step before's (for the contacts'
        // work; a run's pass is the same at every step, so the lists are whole when read).
        if work {
            self.pushed
                .observe(&snap.contacts, snap.bodies.len(), stepped);
        }
        if stepped {
            let mut pass = Pass {
                snap,
                before: &self.before,
                after: &self.after,
                bodies: &mut f.bodies,
                external: &mut f.external,
                work: &mut f.work,
                s_frac: {
                    let s = snap.substeps.max(1) as f64;
                    (s - 1.0) / (2.0 * s)
                },
                has_mass: &self.has_mass,
                massive: &self.massive,
                mids: &mut self.mids,
                pushed: &self.pushed,
                with_work: work,
            };
            pass.run();
        }
        f.totals_before = f.totals;
        let mut totals = Totals::default();
        let inv_dt = if stepped { 1.0 / snap.dt } else { 0.0 };
        for &i in &self.massive {
            let b = &snap.bodies[i];
            let bf = &mut f.bodies[i];
            let g = linear_momentum(b.mass, b.velocity);
            let h_g = angular_momentum_g(b.inertia, b.omega);
            bf.kinetic_energy = kinetic_energy(b.mass, b.velocity, b.inertia, b.omega);
            bf.linear_momentum = g;
            bf.angular_momentum_g = h_g;
            bf.instantaneous_center = instantaneous_center(b.com, b.velocity, b.omega, 1e9);
            if stepped {
                let m0 = &self.before[i];
                let a_g = acceleration_fd(m0.velocity, b.velocity, snap.dt);
                let alpha = angular_acceleration_fd(m0.omega, b.omega, snap.dt);
                // The pass left the impulse sums; the mean forces are those over dt.
                bf.force = bf.impulses.impulse * inv_dt;
                bf.moment_g *= inv_dt;
                bf.acceleration = a_g;
                bf.angular_acceleration = alpha;
                bf.force_residual = bf.force - b.mass * a_g;
                bf.moment_residual = bf.moment_g - b.inertia * alpha;
            }
            totals.kinetic_energy += bf.kinetic_energy;
            totals.gravity_potential += gravity_potential(b.mass, snap.gravity, b.com);
            totals.linear_momentum += g;
            // H_O = I_G w + (r_G x m v_G)_z about the origin (6/15).
            totals.angular_momentum_origin += h_g + cross(b.com, g);
        }
        f.totals = totals;
        if !stepped {
            f.totals_before = totals;
        }
        &self.frame
    }
}

/// Which `StepWork` entry an impulse's work goes to.
#[derive(Clone, Copy)]
enum Slot {
    Loads,
    Events,
    Contacts,
    Other,
}

/// One step's free-body diagrams of every body, summed as they are read.
///
/// The same impulses, points and lever arms as `kinetics::for_each_body_impulse` (which stays the
/// reference: tests/suite/analysis/frame.rs holds the two equal), read source by source without building a
/// `StepImpulse` per impulse, so that the pass costs a few percent of the physics step.
struct Pass<'a> {
    snap: &'a Snapshot,
    before: &'a [Motion],
    after: &'a [Motion],
    /// Where the sums accumulate: `impulses`, `moment_g` (as an impulse) and `work`.
    bodies: &'a mut [BodyFrame],
    external: &'a mut ImpulseSums,
    work: &'a mut StepWork,
    /// (S - 1)/(2S): where in the step gravity acts (`kinetics::gravity_point`).
    s_frac: f64,
    /// Per body: has it mass? (Masses do not change during a run.)
    has_mass: &'a [bool],
    /// The bodies with mass, in order.
    massive: &'a [usize],
    /// Per body with mass, filled first: where gravity acts and the mean velocities.
    mids: &'a mut [Mid],
    /// Which contacts of the step rest (`pushed`).
    pushed: &'a pushed::Pushed,
    /// Whether to compute the work of the impulses (`FramePass::Work`).
    with_work: bool,
}

/// A body's gravity point (`kinetics::gravity_point`) and mean velocities over the step
/// (`Motion::mid`), computed once per step for all its impulses.
#[derive(Debug, Clone, Copy, Default)]
struct Mid {
    g_point: DVec2,
    velocity: DVec2,
    omega: f64,
    /// The velocities of the body's displacement over the step, dr_G / dt and dtheta / dt.
    moved: (DVec2, f64),
}

impl Pass<'_> {
    fn has_mass(&self, i: usize) -> bool {
        self.has_mass[i]
    }

    /// The mean of the substeps' start positions of G (`kinetics::gravity_point`).
    fn g_point(&self, i: usize) -> DVec2 {
        self.mids[i].g_point
    }

    /// U = J . v_P,mid + couple omega_mid (`energy::work_of_impulse_with_arm`).
    fn work_of(&self, i: usize, j: DVec2, arm: DVec2, couple: f64) -> f64 {
        let Mid {
            velocity: v,
            omega: w,
            ..
        } = self.mids[i];
        j.dot(v + super::k_cross(w, arm)) + couple * w
    }

    /// Adds an impulse J on body i acting at `point` with lever arm `arm` from G, plus a couple.
    /// `internal`: its reaction acts on another body with mass. `work`: where its work goes
    /// (for the body, and whether for the scene too).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn add(
        &mut self,
        i: usize,
        j: DVec2,
        point: DVec2,
        arm: DVec2,
        couple: f64,
        internal: bool,
        work: Option<(Slot, bool)>,
    ) {
        self.add_sums(i, j, point, arm, couple, internal);
        if let Some(to) = work.filter(|_| self.with_work) {
            let u = self.work_of(i, j, arm, couple);
            self.add_work(i, to, u);
        }
    }

    /// The impulse's part in body i's sums and, when it comes from outside, the scene's.
    #[inline]
    fn add_sums(
        &mut self,
        i: usize,
        j: DVec2,
        point: DVec2,
        arm: DVec2,
        couple: f64,
        internal: bool,
    ) {
        let m_origin = cross(point, j) + couple;
        let acc = &mut self.bodies[i];
        acc.moment_g += cross(arm, j) + couple;
        acc.impulses.add(j, m_origin, couple);
        if !internal {
            self.external.add(j, m_origin, couple);
        }
    }

    /// Work `u` done on body i, in its `slot` of the body's ledger and, with `scene`, the scene's.
    #[inline]
    fn add_work(&mut self, i: usize, (slot, scene): (Slot, bool), u: f64) {
        self.bodies[i].work.add(slot, u);
        if scene {
            self.work.add(slot, u);
        }
    }

    /// The shared per-step pass every check reads, one section per source of impulses.
    fn run(&mut self) {
        self.weights();
        self.loads();
        self.springs();
        self.events();
        let snap = self.snap;
        for (k, c) in snap.contacts.iter().enumerate() {
            self.contact(k, c);
        }
        self.joints();
        self.couplings();
    }

    fn start(&self, i: usize) -> DVec2 {
        self.before[i].com
    }

    /// Every body with mass starts from its weight, m g dt at the gravity point (external),
    /// and gets its gravity point and mean velocities, used by all its impulses.
    fn weights(&mut self) {
        let snap = self.snap;
        let dt = snap.dt;
        let (mut weight, mut weight_moment) = (DVec2::ZERO, 0.0);
        for &i in self.massive {
            let (m0, m1) = (&self.before[i], &self.after[i]);
            let mid = Mid {
                g_point: m0.com + (m1.com - m0.com) * self.s_frac,
                velocity: 0.5 * (m0.velocity + m1.velocity),
                omega: 0.5 * (m0.omega + m1.omega),
                moved: ((m1.com - m0.com) / dt, (m1.angle - m0.angle) / dt),
            };
            self.mids[i] = mid;
            let j = snap.bodies[i].mass * snap.gravity * dt;
            let m_origin = cross(mid.g_point, j);
            let bf = &mut self.bodies[i];
            bf.impulses = ImpulseSums {
                impulse: j,
                moment_origin: m_origin,
                largest_impulse: j.length(),
                largest_couple: 0.0,
            };
            bf.moment_g = 0.0;
            bf.work = StepWork::default();
            weight += j;
            weight_moment += m_origin;
        }
        self.external.impulse += weight;
        self.external.moment_origin += weight_moment;
        self.external.largest_impulse = self.external.largest_impulse.max(weight.length());
    }

    /// A force held over the step: rapier applies it at G plus the couple of its start-of-step
    /// arm, so its line of action moves with G (`kinetics` module doc).
    fn loads(&mut self) {
        let snap = self.snap;
        let dt = snap.dt;
        for l in &snap.loads {
            if self.has_mass(l.body) {
                let arm = l.point - self.start(l.body);
                let at = self.g_point(l.body) + arm;
                let j = l.force * dt;
                let work = Some((Slot::Loads, true));
                self.add(l.body, j, at, arm, l.torque * dt, false, work);
            }
        }
    }

    fn springs(&mut self) {
        let snap = self.snap;
        let dt = snap.dt;
        for sp in &snap.springs {
            // A linear spring's force at each end, or a torsion spring's couple.
            let ends = [
                (
                    sp.body1,
                    sp.body2,
                    sp.applied_at1,
                    sp.force_on_body1,
                    sp.couple_on_body1,
                ),
                (
                    sp.body2.unwrap_or(usize::MAX),
                    Some(sp.body1),
                    sp.applied_at2,
                    -sp.force_on_body1,
                    -sp.couple_on_body1,
                ),
            ];
            for (i, other, p, force, couple) in ends {
                if i == usize::MAX || !self.has_mass(i) {
                    continue;
                }
                let internal = other.is_some_and(|o| self.has_mass(o));
                // Held at the other end by the ground: V_e is in the ledger. By another body with
                // mass: in the scene's ledger, not in the body's own. By a kinematic body: in neither.
                let ground = other.is_none_or(|o| snap.bodies[o].kind == BodyKind::Fixed);
                let work = (!ground).then_some((Slot::Other, !internal));
                let arm = p - self.start(i);
                let at = self.g_point(i) + arm;
                self.add(i, force * dt, at, arm, couple * dt, internal, work);
            }
        }
    }

    fn events(&mut self) {
        let snap = self.snap;
        for e in &snap.impulses {
            if self.has_mass(e.body) {
                let arm = e.point - self.start(e.body);
                let work = Some((Slot::Events, true));
                self.add(
                    e.body,
                    e.impulse,
                    e.point,
                    arm,
                    e.angular_impulse,
                    false,
                    work,
                );
            }
        }
    }

    /// A contact whose pair pushed the step before is no impact: its normal impulse works
    /// through the bodies' displacement (`energy::work_of_contact_impulse`).
    /// Unless it now pushes impulsively, over twice its last step's (a floor under a
    /// block struck down into it, a support under a body struck from above): that
    /// impulse changes the velocities within the step, and the mean velocity books it
    /// exactly, where the displacement books the soft contact's sink. The tenth new
    /// user's block struck down by (4, -6) N s (tests/newuser/impacts/n10_05b): the floor's
    /// 6 N s against the 0.041 N s of resting, booked at the block's 0.35 mm sink, gave
    /// the work-energy ledger 1.0 J of 1.6 J too much.
    fn rests(&self, k: usize) -> bool {
        self.with_work && self.pushed.rests(k)
    }

    /// Contact k of the step, `c`.
    fn contact(&mut self, k: usize, c: &ContactState) {
        let snap = self.snap;
        let (in1, in2) = (self.has_mass(c.body1), self.has_mass(c.body2));
        if !in1 && !in2 {
            return;
        }
        let internal = in1 && in2;
        let t = c.tangent();
        let resting = self.rests(k);
        let work = (Slot::Contacts, true);
        for p in &c.points {
            let (j_n, j_t) = (c.normal * p.normal_impulse, t * p.tangent_impulse);
            let j2 = j_n + j_t;
            let (arm1, arm2) = p
                .arms
                .unwrap_or_else(|| contact_arms_at_start(snap, self.before, c, p));
            let u = |pass: &Self, i: usize, sign: f64, arm: DVec2| {
                let m = &pass.mids[i];
                let moved = resting.then_some(m.moved);
                work_of_contact_impulse(j_n * sign, j_t * sign, arm, (m.velocity, m.omega), moved)
            };
            if in2 {
                let at = self.g_point(c.body2) + arm2;
                self.add_sums(c.body2, j2, at, arm2, 0.0, internal);
                if self.with_work {
                    let w = u(self, c.body2, 1.0, arm2);
                    self.add_work(c.body2, work, w);
                }
            }
            if in1 {
                let at = self.g_point(c.body1) + arm1;
                self.add_sums(c.body1, -j2, at, arm1, 0.0, internal);
                if self.with_work {
                    let w = u(self, c.body1, -1.0, arm1);
                    self.add_work(c.body1, work, w);
                }
            }
        }
    }

    fn joints(&mut self) {
        let snap = self.snap;
        for j in &snap.joints {
            let (in1, in2) = (self.has_mass(j.body1), self.has_mass(j.body2));
            let internal = in1 && in2;
            // The reaction at the anchor; its couple is the row solver's angular impulse about G
            // less the moment of the linear part. The angular impulse is about G where each
            // substep's rows acted, so, like a contact's, the arm is placed at the gravity point.
            if in2 {
                let (i, imp) = (j.body2, j.impulse_on_body2);
                let arm = j.anchor - self.after[i].com;
                let couple = j.angular_impulse_on_body2 - cross(arm, imp);
                let at = self.g_point(i) + arm;
                self.add(i, imp, at, arm, couple, internal, None);
            }
            if in1 {
                let (i, imp) = (j.body1, -j.impulse_on_body2);
                let arm = j.anchor1 - self.after[i].com;
                let couple = j.angular_impulse_on_body1 - cross(arm, imp);
                let at = self.g_point(i) + arm;
                self.add(i, imp, at, arm, couple, internal, None);
            }
        }
    }

    fn couplings(&mut self) {
        let snap = self.snap;
        for c in &snap.couplings {
            for (i, j, couple) in c.body_impulses() {
                if !self.has_mass(i) {
                    continue;
                }
                let at = self.g_point(i);
                let work = Some((Slot::Other, true));
                self.add(i, j, at, DVec2::ZERO, couple, false, work);
            }
        }
    }
}

/// A body's free-body diagram against its kinetic diagram over consecutive steps, as the
/// `newton_euler` check sums them (6/1): the mean sum F and sum M_G of the steps' impulses, and
/// the mean m a_G and I_G alpha of the velocity change over the same steps. The window draws
/// these, so its "=" holds exactly where the check's residuals are small.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DiagramBalance {
    /// Mean sum F over the steps, N.
    pub force: DVec2,
    /// Mean sum M_G (moments of the forces about G and couples), N m.
    pub moment_g: f64,
    /// m a_G with a_G = (v_G at the end - v_G at the start) / the steps' time, N.
    pub mass_acceleration: DVec2,
    /// I_G alpha likewise, N m.
    pub inertia_alpha: f64,
    /// The steps' total time, s.
    pub time: f64,
}

impl DiagramBalance {
    /// sum F - m a_G, N.
    pub fn force_residual(&self) -> DVec2 {
        self.force - self.mass_acceleration
    }

    /// sum M_G - I_G alpha, N m.
    pub fn moment_residual(&self) -> f64 {
        self.moment_g - self.inertia_alpha
    }
}

/// The [`DiagramBalance`] of body i over the steps between consecutive `snapshots` (the first
/// only starts the first step), each step's [`BodyFrame`] weighted by its length. None when the
/// snapshots close no step or the body has no mass.
pub fn diagram_balance<'a>(
    snapshots: impl IntoIterator<Item = &'a Snapshot>,
    i: usize,
) -> Option<DiagramBalance> {
    let mut pass = FrameAnalysis::new();
    let mut sum = DiagramBalance::default();
    for s in snapshots {
        pass.observe_as(s, FramePass::Diagram);
        let b = s.bodies.get(i)?;
        if !pass.stepped() || b.mass <= 0.0 {
            continue;
        }
        let f = &pass.frame().bodies[i];
        let dt = s.dt;
        sum.force += f.force * dt;
        sum.moment_g += f.moment_g * dt;
        sum.mass_acceleration += b.mass * f.acceleration * dt;
        sum.inertia_alpha += b.inertia * f.angular_acceleration * dt;
        sum.time += dt;
    }
    (sum.time > 0.0).then(|| {
        let t = sum.time;
        DiagramBalance {
            force: sum.force / t,
            moment_g: sum.moment_g / t,
            mass_acceleration: sum.mass_acceleration / t,
            inertia_alpha: sum.inertia_alpha / t,
            time: t,
        }
    })
}
