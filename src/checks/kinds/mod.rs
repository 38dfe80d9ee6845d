//! The probes behind each check kind.
//!
//! Every probe computes its "theory" and its "engine" value from independent inputs:
//! theory uses the textbook's data (the shape formulas of `analysis::mass`, the level's
//! givens, the free-body diagram read from the step's impulses), engine uses what rapier
//! holds (its velocities, its own mass properties) or what its motion shows. Each kind
//! documents its pair, its error scale and its known engine limitations in its module.
//!
//! | kind | theory | engine | scale |
//! |---|---|---|---|
//! | `mass_properties` | shape formulas (MP-9), parallel axis | rapier/parry mass properties | m, I_G, k_G |
//! | `kinetic_energy_g` | 6/9 with formula m, I_G and v, omega from the drawn poses | rapier's v, omega, m, I_G | max T |
//! | `kinetic_energy_ic` | 1/2 I_C omega^2 (6/10, 6/8) about the contact point / pivot / IC | rapier's 6/9 | max T |
//! | `angular_momentum_fixed_point` | sum M_O of the free-body diagram | dH_O/dt (6/15) of rapier's state | max sum M_O |
//! | `center_of_percussion` | pivot impulse of a struck pinned body (CP-3) / sum M_Q = 0 (CP-2) | joint impulse read from rapier | the blow |
//! | `newton_euler` | sum F, sum M_G of the free-body diagram | m a_G, I_G alpha by finite differences | max force |
//! | `work_energy` | E(0) + U' (non-conservative work) | T + V_g + V_e of rapier's state | energy that flows |
//! | `impulse_momentum` | G(0) + integral sum F dt (and H_O) | G, H_O of rapier's state | max G, H_O |
//! | `restitution` | e set in the level (or H_C conserved when eccentric) | e from velocities (or H_C after) | 1 (or H_C before) |
//! | `virtual_work` | the actuator effort by virtual work with inertia forces (VW-2, VW-5) | the motor's impulse / dt | max motor effort |

mod batch;
mod constant;
mod energy;
mod impact;
mod kinetics;
mod mass;
mod momentum;
mod percussion;
mod virtual_work;

use batch::Together;
pub(crate) use batch::{groups_for, Group};

use super::{kind_name, CheckResult, Probe};
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::analysis::mass::MassProps;
use crate::level::{BodyDef, CheckDef, CheckKind, Level};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// A probe that reads the shared per-step frame (`analysis::frame`) rather than walking the
/// step's impulses itself.
pub(super) trait FrameProbe {
    /// How much of the frame pass the probe reads: the states at the step's ends and the links
    /// (a fraction of the pass's cost), the frame's sums, or the work of the step's forces too.
    fn frame_pass(&self) -> FramePass {
        FramePass::Work
    }
    fn observe_frame(&mut self, snap: &Snapshot, fa: &FrameAnalysis);
    fn finish(self) -> CheckResult;
}

/// The index of the body named `name` in the run's snapshots, looked up once and kept in
/// `index` (a scene's bodies do not come or go). None while the name is not in the snapshot.
pub(super) fn cached_body(index: &mut Option<usize>, s: &Snapshot, name: &str) -> Option<usize> {
    let i = index.or_else(|| s.body_index(name))?;
    *index = Some(i);
    Some(i)
}

/// A check's subject in the snapshot: `Some(Some(i))` for the named body, `Some(None)` for the
/// whole scene (no body named), None while the named body is not in the snapshot.
pub(super) fn subject_index(s: &Snapshot, body: Option<&str>) -> Option<Option<usize>> {
    match body {
        Some(n) => s.body_index(n).map(Some),
        None => Some(None),
    }
}

/// A [`FrameProbe`] as a [`Probe`]: fed by a `CheckSet` it reads the set's frame; fed snapshots
/// alone (tests, tools) it runs its own frame pass.
pub(super) struct Framed<P> {
    inner: P,
    own: Option<FrameAnalysis>,
}

pub(super) fn framed<P: FrameProbe + 'static>(inner: P) -> Box<dyn Probe> {
    Box::new(Framed { inner, own: None })
}

impl<P: FrameProbe> Probe for Framed<P> {
    fn observe(&mut self, snap: &Snapshot) {
        let fa = self.own.get_or_insert_with(FrameAnalysis::new);
        fa.observe_as(snap, self.inner.frame_pass());
        self.inner.observe_frame(snap, fa);
    }
    fn wants_frame(&self) -> bool {
        true
    }
    fn frame_pass(&self) -> FramePass {
        self.inner.frame_pass()
    }
    fn observe_frame(&mut self, snap: &Snapshot, fa: &FrameAnalysis) {
        self.inner.observe_frame(snap, fa);
    }
    fn finish(self: Box<Self>) -> CheckResult {
        self.inner.finish()
    }
}

pub fn probe_for(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    match def.kind {
        CheckKind::ConstantAcceleration => {
            Box::new(constant::ConstantAcceleration::new(level, def))
        }
        CheckKind::MassProperties => mass::probe(level, def),
        CheckKind::KineticEnergyG => energy::kinetic_energy_g_probe(level, def),
        CheckKind::KineticEnergyIc => energy::kinetic_energy_ic_probe(level, def),
        CheckKind::WorkEnergy => energy::work_energy(level, def),
        CheckKind::AngularMomentumFixedPoint => momentum::angular_momentum_fixed_point(level, def),
        CheckKind::ImpulseMomentum => momentum::impulse_momentum(level, def),
        CheckKind::NewtonEuler => kinetics::probe(level, def),
        CheckKind::CenterOfPercussion => percussion::probe(level, def),
        CheckKind::Restitution => impact::probe(level, def),
        CheckKind::VirtualWork => virtual_work::probe(level, def),
    }
}

pub(super) fn body_def<'a>(level: &'a Level, name: &str) -> Option<&'a BodyDef> {
    level.bodies.iter().find(|b| b.name == name)
}

/// The textbook mass properties of a body (shape formula, level's mass/density/overrides).
pub(super) fn textbook_mass(def: &BodyDef) -> MassProps {
    crate::analysis::mass::of_body(def, crate::level::DEFAULT_DENSITY)
}

/// Everything a result needs beyond the level's check definition.
#[derive(Debug, Clone, Default)]
pub(super) struct Summary {
    pub theory: f64,
    pub engine: f64,
    pub max_abs: f64,
    pub max_rel: f64,
    pub final_abs: f64,
    pub final_rel: f64,
    pub samples: u64,
    pub scale: f64,
    pub note: String,
}

impl Summary {
    /// The usual summary: the last (theory, engine) pair, and the worst and final absolute
    /// errors of `worst` against `scale`.
    pub fn from_worst(last: (f64, f64), worst: &Worst, scale: f64, note: String) -> Summary {
        Summary {
            theory: last.0,
            engine: last.1,
            max_abs: worst.max,
            max_rel: worst.max / scale,
            final_abs: worst.last,
            final_rel: worst.last / scale,
            samples: worst.samples,
            scale,
            note,
        }
    }
}

/// A check's result, held to what never passes ([`CheckResult::never_absurd`]).
pub(super) fn result(def: &CheckDef, subject: String, s: Summary) -> CheckResult {
    unchecked_result(def, subject, s).never_absurd()
}

/// A check whose quantity was zero at every step it compared (a body that never moved, energy
/// that never flowed) observed nothing: it fails, and says so (docs/analysis-and-checks.md,
/// "What never passes"); 0 against 0 is no agreement.
pub(super) fn observed_nothing(mut r: CheckResult, what: &str) -> CheckResult {
    r.passed = false;
    r.note = format!("FAILS: it compared nothing: {what}; {}", r.note);
    r
}

/// A check's result as its probe summed it up (a misconfigured check, which fails already and
/// says why).
fn unchecked_result(def: &CheckDef, subject: String, s: Summary) -> CheckResult {
    CheckResult {
        kind: kind_name(def.kind).to_string(),
        subject,
        theory: s.theory,
        engine: s.engine,
        max_abs_error: s.max_abs,
        max_rel_error: s.max_rel,
        final_abs_error: s.final_abs,
        final_rel_error: s.final_rel,
        tolerance: def.tolerance,
        passed: s.samples > 0 && s.max_rel.is_finite() && s.max_rel <= def.tolerance,
        samples: s.samples,
        scale: s.scale,
        why: def.why.clone(),
        note: s.note,
    }
}

/// Largest-error bookkeeping with a scale known only at the end of the run, over the check's
/// `window` (every kind takes one): samples outside it are not counted.
#[derive(Debug, Clone)]
pub(super) struct Worst {
    pub max: f64,
    pub last: f64,
    pub at_time: f64,
    pub samples: u64,
    /// [t1, t2] in s; the whole run by default.
    window: (f64, f64),
    /// For a running balance (the work-energy ledger): errors are taken from the balance's
    /// value at the window's first sample, so a window measures the balance over [t1', t] as
    /// the textbook writes it between two positions (T1 + V1 + U'12 = T2 + V2), not what
    /// happened before it.
    from_window_start: Option<Option<f64>>,
}

impl Default for Worst {
    fn default() -> Self {
        Worst {
            max: 0.0,
            last: 0.0,
            at_time: 0.0,
            samples: 0,
            window: (f64::NEG_INFINITY, f64::INFINITY),
            from_window_start: None,
        }
    }
}

impl Worst {
    /// Bookkeeping over the check's `window` (the whole run without one).
    pub fn over(def: &CheckDef) -> Self {
        Worst {
            window: window_of(def),
            ..Worst::default()
        }
    }

    /// As [`Worst::over`], for a running balance whose error is counted from the window's start.
    pub fn over_from_start(def: &CheckDef) -> Self {
        Worst {
            from_window_start: def.window.map(|_| None),
            ..Worst::over(def)
        }
    }

    /// Whether time `t` (a step's end) lies in the window.
    pub fn covers(&self, t: f64) -> bool {
        in_window(self.window, t)
    }

    pub fn add(&mut self, err: f64, time: f64) {
        if !self.covers(time) {
            return;
        }
        let err = match &mut self.from_window_start {
            Some(base) => err - *base.get_or_insert(err),
            None => err,
        };
        let err = if err.is_nan() {
            f64::INFINITY
        } else {
            err.abs()
        };
        if err > self.max || self.samples == 0 {
            self.max = self.max.max(err);
            self.at_time = time;
        }
        self.last = err;
        self.samples += 1;
    }
}

/// A check's window [t1, t2] in s, the whole run without one.
pub(super) fn window_of(def: &CheckDef) -> (f64, f64) {
    def.window.unwrap_or((f64::NEG_INFINITY, f64::INFINITY))
}

/// Whether a step ending at `t` is inside `window`; a window's ends are step times typed in
/// decimal, so they carry a nanosecond of slack for the float sum of the steps.
pub(super) fn in_window(window: (f64, f64), t: f64) -> bool {
    t >= window.0 - 1e-9 && t <= window.1 + 1e-9
}

/// " over the window [t1, t2] s" for a note, or nothing.
pub(super) fn window_note(def: &CheckDef) -> String {
    def.window
        .map(|(a, b)| format!("; compared over the window [{a}, {b}] s"))
        .unwrap_or_default()
}

/// A positive scale: the given one, or `fallback` when it is zero or not finite.
pub(super) fn scale_or(scale: f64, fallback: f64) -> f64 {
    if scale.is_finite() && scale > 0.0 {
        scale
    } else {
        fallback
    }
}

/// A check that cannot run as declared: it fails and says why (never passes silently).
pub(super) struct Misconfigured {
    pub def: CheckDef,
    pub subject: String,
    pub why: String,
}

impl Probe for Misconfigured {
    fn reads_contacts(&self) -> bool {
        false
    }
    fn observe(&mut self, _: &Snapshot) {}
    fn finish(self: Box<Self>) -> CheckResult {
        unchecked_result(
            &self.def,
            self.subject,
            Summary {
                note: self.why,
                max_rel: f64::INFINITY,
                ..Summary::default()
            },
        )
    }
}

pub(super) fn misconfigured(def: &CheckDef, why: impl Into<String>) -> Box<dyn Probe> {
    Box::new(Misconfigured {
        def: def.clone(),
        subject: subject_of(def),
        why: why.into(),
    })
}

/// A check whose formula does not hold on the scene (an assumption docs/levels.md lists for
/// the kind, verified on the run and found broken): it fails, and its note says it cannot judge
/// and why. It neither passes nor fails on the wrong formula: it compares nothing
/// (samples 0, its error not finite, as a misconfigured check).
pub(super) fn cannot_judge(def: &CheckDef, subject: String, why: impl AsRef<str>) -> CheckResult {
    unchecked_result(
        def,
        subject,
        Summary {
            note: format!("cannot judge: {}", why.as_ref()),
            max_rel: f64::INFINITY,
            ..Summary::default()
        },
    )
}

/// A probe for a check that cannot judge its scene, known from the level alone ([`cannot_judge`]).
pub(super) fn cannot_judge_probe(def: &CheckDef, why: impl AsRef<str>) -> Box<dyn Probe> {
    misconfigured(def, format!("cannot judge: {}", why.as_ref()))
}

/// The body's damping in effect, (linear, angular) in 1/s: the level's `linear_damping` and
/// `angular_damping`, which rapier applies only under the `damping` effect (`sim::build`).
pub(super) fn damping_of(level: &Level, b: &BodyDef) -> (f64, f64) {
    if level.effects.contains(&crate::level::Effect::Damping) {
        (
            b.linear_damping.unwrap_or(0.0),
            b.angular_damping.unwrap_or(0.0),
        )
    } else {
        (0.0, 0.0)
    }
}

/// Why the free-body diagram of body `b` misses a force, if `b` is damped: rapier scales a
/// damped body's v_G by 1/(1 + h c) and omega by 1/(1 + h c_w) every substep h, the force
/// -m c v / (1 + h c) at G and the couple -I_G c_w omega / (1 + h c_w), with v and omega the
/// substeps' own. The snapshot holds the step's ends, not the substeps' velocities, so the
/// diagram (the engine's impulses) has no damping term. With `moments` false only the linear
/// damping counts (a check of sum F alone).
pub(super) fn damped_body(level: &Level, b: &BodyDef, moments: bool) -> Option<String> {
    let (c, cw) = damping_of(level, b);
    let mut parts = Vec::new();
    if c != 0.0 {
        parts.push(format!("linear_damping {c} 1/s"));
    }
    if moments && cw != 0.0 {
        parts.push(format!("angular_damping {cw} 1/s"));
    }
    (!parts.is_empty()).then(|| {
        format!(
            "body \"{}\" is damped ({}): rapier scales its velocities by 1/(1 + h c) every substep h, a force -m c v / (1 + h c) and a couple -I_G c_w omega / (1 + h c_w) that the free-body diagram (the engine's impulses) does not hold",
            b.name,
            parts.join(", ")
        )
    })
}

/// Why body i is not free in step `s`: a contact that gave it a normal or friction impulse
/// ("a contact with \"floor\" pushes on it" and `at`, where in the run), if one did. For the
/// checks whose formula holds only with no contact on the body (`constant_acceleration`, a
/// `center_of_percussion` strike).
pub(super) fn contact_pushing(s: &crate::snapshot::Snapshot, i: usize, at: &str) -> Option<String> {
    let c = s.contacts.iter().find(|c| {
        (c.body1 == i || c.body2 == i)
            && c.points
                .iter()
                .any(|p| p.normal_impulse != 0.0 || p.tangent_impulse != 0.0)
    })?;
    let o = if c.body1 == i { c.body2 } else { c.body1 };
    Some(format!(
        "a contact with \"{}\" pushes on it {at}",
        s.bodies[o].name
    ))
}

/// [`damped_body`] for a check's subject: the named body, or any dynamic body of the scene.
pub(super) fn damped_subject(level: &Level, body: Option<&str>) -> Option<String> {
    match body {
        Some(name) => body_def(level, name).and_then(|b| damped_body(level, b, true)),
        None => level
            .bodies
            .iter()
            .filter(|b| b.kind == crate::level::BodyKind::Dynamic)
            .find_map(|b| damped_body(level, b, true)),
    }
}

/// "body \"bar\"", "the scene", plus the point when given.
pub(super) fn subject_of(def: &CheckDef) -> String {
    let mut s = match &def.body {
        Some(b) => format!("body \"{b}\""),
        None => "the scene".to_string(),
    };
    if let Some(o) = &def.other {
        s += &format!(" with \"{o}\"");
    }
    if let Some(p) = def.point {
        s += &format!(" about ({:.3}, {:.3})", p.0, p.1);
    }
    s
}

/// Resolves a check's `body` to a dynamic body of the level, or says why it cannot.
pub(super) fn dynamic_body<'a>(level: &'a Level, def: &CheckDef) -> Result<&'a BodyDef, String> {
    let Some(name) = &def.body else {
        return Err(format!(
            "a {} check needs `body: \"...\"`",
            kind_name(def.kind)
        ));
    };
    let Some(b) = body_def(level, name) else {
        return Err(format!("\"{name}\" is not a body of this level"));
    };
    if b.kind != crate::level::BodyKind::Dynamic {
        return Err(format!(
            "body \"{name}\" is not dynamic: a {} check needs a body that moves under forces",
            kind_name(def.kind)
        ));
    }
    Ok(b)
}

pub(super) fn v2(p: (f64, f64)) -> DVec2 {
    DVec2::new(p.0, p.1)
}

/// Body indices of a check's subject: the named body, or every dynamic body.
pub(super) fn subject_set(snap: &Snapshot, body: Option<usize>) -> BodySet {
    let list: Vec<usize> = match body {
        Some(i) => vec![i],
        None => (0..snap.bodies.len())
            .filter(|&i| snap.bodies[i].mass > 0.0)
            .collect(),
    };
    let mut mask = vec![false; snap.bodies.len()];
    for &i in &list {
        if let Some(m) = mask.get_mut(i) {
            *m = true;
        }
    }
    BodySet { list, mask }
}

/// A check's subject bodies, in order, with O(1) membership: the scene-wide checks ask
/// "is this body in the set?" for every impulse of every step.
#[derive(Debug, Clone, Default)]
pub(super) struct BodySet {
    list: Vec<usize>,
    mask: Vec<bool>,
}

impl BodySet {
    pub(super) fn contains(&self, i: &usize) -> bool {
        self.mask.get(*i).copied().unwrap_or(false)
    }
}

impl<'a> IntoIterator for &'a BodySet {
    type Item = &'a usize;
    type IntoIter = std::slice::Iter<'a, usize>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter()
    }
}

impl std::ops::Deref for BodySet {
    type Target = [usize];
    fn deref(&self) -> &[usize] {
        &self.list
    }
}
