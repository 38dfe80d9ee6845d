//! The step's settings, resolved once.
//!
//! A level states its solver settings in `world`; the command line, the window's solver panel
//! and the studies override some of them ([`Options`]). [`Settings::resolve`] folds the two into
//! one record, in f64, when a [`Simulation`](crate::sim::Simulation) is built. From then on every
//! consumer reads that record (through `Simulation::settings`) or the copy of the per-step
//! values each [`Snapshot`](crate::snapshot::Snapshot) carries (`dt`, `substeps`): the engine,
//! the checks and questions, the window's panels and both studies see the same numbers. Before
//! this record existed, checks read the level's own `world.substeps` while the engine ran the
//! override, so more accuracy could turn a pass into a failure.
//!
//! Like rapier's `IntegrationParameters`, it is one plain record of what a step does; unlike it,
//! it is engine-independent (no rapier type) and names what the textbook analysis needs.

use crate::level::{Effect, Level};
use crate::sim::options::{Effects, Options, SpinSplit};
use crate::snapshot::Precision;
use serde::{Deserialize, Serialize};

/// How a step's substeps are taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Substepping {
    /// One rapier call per step with `substeps` internal substeps (rapier's own TGS-soft loop).
    Internal,
    /// One rapier call per substep, each at dt/substeps with one internal substep. rigidlab then
    /// sees every substep: springs are evaluated before each (so they integrate symplectically),
    /// and joint impulses are summed over all of them (rapier keeps only the last substep's, so a
    /// blow through a pin, whose reaction falls in the first substep, would be lost), with each
    /// substep's joint rows rebuilt from the poses rapier built them from.
    Split,
    /// In a report only: some steps split, the others one call (`StepCalls` counts them). As
    /// an override it is `Internal`, whose steps are split where a spinning ball touches.
    Mixed,
}

/// How a run's steps were really called, counted as it ran: the plan (`Settings::substepping`)
/// is one call a step of `substeps` internal substeps where nothing needs to see inside a step,
/// but a step in which a ball spinning in contact (sim/contact_points.rs) or a smooth ball on an
/// `Arc`'s circle (sim/arc_split.rs) is split all the same, and an impact cut divides a call in
/// two (sim/impacts.rs).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StepCalls {
    /// Steps taken.
    pub steps: u64,
    /// Steps split for a spinning ball in contact, where the plan was one call: into one-substep
    /// calls, or fewer calls of several substeps where those keep its contact
    /// (sim/contact_points.rs, `spin_calls`).
    pub split_for_spin: u64,
    /// Steps split into one-substep calls for a smooth ball riding an `Arc`'s circle (and no
    /// spinning ball), where the plan was one call.
    pub split_for_arc: u64,
    /// Steps whose calls an impact cut divided.
    pub cut: u64,
    /// Steps split into one-substep calls because a blow could fall in them, where the plan
    /// reconstructs the joint impulses from one call (`Settings::split_at_blows`).
    pub split_for_blow: u64,
    /// The rapier calls planned for the run's steps, before impact cuts divided any.
    pub calls: u64,
}

/// Every solver setting of a run, resolved from the level and the overrides.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// The physics step, s.
    pub dt: f64,
    /// Substeps per step (rapier's `num_solver_iterations`); h = dt / substeps.
    pub substeps: usize,
    /// Solver sweeps per substep, of both rapier's biased pass (`num_internal_pgs_iterations`)
    /// and its unbiased pass (`num_internal_stabilization_iterations`, where friction is solved).
    pub solver_iterations: usize,
    pub precision: Precision,
    pub substepping: Substepping,
    /// Why the steps are called as `substepping` says; in a report, with how many of the run's
    /// steps were called so (`Settings::as_run`).
    #[serde(default)]
    pub substepping_why: String,
    /// In a report: how many of the run's steps were split into `substeps` rapier calls of one
    /// substep each (0 before a run).
    #[serde(default)]
    pub split_steps: u64,
    /// In a report: how many of the run's steps had a call divided at an impact (impact cuts).
    #[serde(default)]
    pub cut_steps: u64,
    /// The effects the world was built with (the level's, or all with `--all-effects`).
    pub effects: Effects,
    /// Contact stiffness, Hz (None: rapier's default).
    pub contact_hz: Option<f64>,
    pub allow_fast_rotation: bool,
    /// rapier's `contact_recycling`: keep a pair's contact points and normal while the pair has
    /// moved less than 5 cm since its last full narrow-phase update. Off: two bodies approaching
    /// each other get the manifold rapier first computed within its prediction distance, whose
    /// normal and lever arms are those of the approach, not of the impact (a wheel meeting a
    /// curb 6.7 mm after the pair was first seen pivoted 1.5% too slowly).
    pub contact_recycling: bool,
    /// Each rapier call is planned around the impacts in it (sim/impacts.rs): cut at the first
    /// time of impact, with no contact for an approaching pair before it touches, so an impact's
    /// normal and lever arms are those of the instant the bodies touch, whatever gap they approached from. On in scenes with contacts
    /// and at most [`IMPACT_CUT_BODIES`] moving bodies, or as `Options::impact_cuts` says
    /// (`--impact-cuts`, `--no-impact-cuts`): every nearby pair is tried each call.
    #[serde(default)]
    pub impact_cuts: bool,
    /// Joint impulses are read, but a step is split into one-substep calls only where a blow
    /// can fall in it (sim/joint_sums.rs); elsewhere it is one call, and the step's joint
    /// impulses are reconstructed from that call's last substep and the previous step's.
    /// Planned with `substepping: Internal`; false whenever substepping is overridden.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub split_at_blows: bool,
    /// With `split_at_blows`: how far a reconstructed step's joint impulse may be predicted off,
    /// relative to it, before the steps are split (sim/joint_sums.rs): a fiftieth of the
    /// tightest tolerance of the checks and questions that read joint impulses, and 1e-3 at
    /// most. (A single substep's impulse carries the engine's rounding, which a split step's sum
    /// cancels: with a tenth, and two smooth steps always enough, a cart's pendulum in
    /// equilibrium, tests/newuser/oscillations/n8_06, read its newton_euler at 1.5e-3 against
    /// its tolerance of 2e-3, and failed it at 8 and 16 substeps.)
    #[serde(skip)]
    pub smooth_tolerance: f64,
    /// When a spinning ball's steps are split (`Options::spin_split`); not in a report.
    #[serde(skip)]
    pub spin_split: SpinSplit,
    /// Whether a question is read when a contact starts, ends or slips (`FirstContact`,
    /// `ContactEnds`, `Leaves`, `SlipStarts`, `SlipEnds`): a spinning ball's contact is then
    /// split by the strict rule (sim/contact_points.rs, `spin_calls`); not in a report.
    #[serde(skip)]
    pub reads_contact_events: bool,
}

/// Whether a question of the level is read when a contact starts, ends or slips.
fn reads_contact_events(level: &Level) -> bool {
    use crate::level::When;
    level.questions.iter().any(|q| {
        matches!(
            q.at,
            When::FirstContact { .. }
                | When::ContactEnds { .. }
                | When::Leaves { .. }
                | When::SlipStarts { .. }
                | When::SlipEnds { .. }
        )
    })
}

/// Why a level that reads joint impulses takes one rapier call a step (`Settings::split_at_blows`).
const BLOW_SPLITS: &str = "one rapier call a step with its substeps inside: a check or question \
    reads joint impulses, and a step's sum is reconstructed from its last substep's and the \
    previous step's (second order: at most |F''| (dt^2 - h^2) / 12 off in the step's mean \
    force, sim/joint_sums.rs), except in the steps where a blow can fall or the impulses are not \
    smooth enough to interpolate, which are split into one rapier call per substep";

/// The largest predicted error of a reconstructed step's joint impulse, relative to it
/// (`Settings::smooth_tolerance`).
const SMOOTH: f64 = 1e-3;

/// The most moving bodies a scene may have for its impacts to be cut by default.
pub const IMPACT_CUT_BODIES: usize = 64;

impl Settings {
    /// Folds the overrides into the level's settings.
    pub fn resolve(level: &Level, opts: &Options, precision: Precision) -> Settings {
        let effects = Effects::of(level, opts.all_effects);
        let moving = level
            .bodies
            .iter()
            .filter(|b| b.kind != crate::level::BodyKind::Fixed)
            .count();
        let impact_cuts = effects.has(Effect::Contacts)
            && opts.impact_cuts.unwrap_or(moving <= IMPACT_CUT_BODIES);
        let substeps = opts.substeps.unwrap_or(level.world.substeps).max(1);
        let (substepping, substepping_why, split_at_blows) = match opts.substepping {
            Some(s) => (s, "asked for by the run's options".to_string(), false),
            None => Self::substepping_for(level, &effects, substeps),
        };
        Settings {
            dt: opts.dt.unwrap_or(level.world.dt),
            substeps,
            solver_iterations: opts
                .solver_iterations
                .unwrap_or(level.world.solver_iterations)
                .max(1),
            precision,
            substepping,
            substepping_why,
            split_steps: 0,
            cut_steps: 0,
            effects,
            contact_hz: level.world.contact_hz,
            allow_fast_rotation: level.world.allow_fast_rotation,
            contact_recycling: false,
            impact_cuts,
            split_at_blows,
            smooth_tolerance: joint_impulse_tolerance(level)
                .map_or(SMOOTH, |t| (t / 50.0).min(SMOOTH)),
            spin_split: opts.spin_split,
            reads_contact_events: reads_contact_events(level),
        }
    }

    /// Split substeps where rigidlab must see inside the step: springs (forces refreshed before
    /// every substep) and joints or welds whose impulses a check or question reads (summed over
    /// every substep), and then only in the steps where a blow can fall when the level allows
    /// the others' sums to be reconstructed (sim/joint_sums.rs). Other scenes keep rapier's
    /// internal substeps, which cost less. With the reason, as the report says it, and whether
    /// the steps are split at blows only.
    fn substepping_for(
        level: &Level,
        effects: &Effects,
        substeps: usize,
    ) -> (Substepping, String, bool) {
        let springs = effects.has(Effect::Springs)
            && !(level.springs.is_empty() && level.torsion_springs.is_empty());
        let welds = level
            .events
            .iter()
            .any(|e| matches!(e, crate::level::EventDef::WeldOnContact { .. }));
        let joints = effects.has(Effect::Joints) && (!level.joints.is_empty() || welds);
        // With one substep a joint scene still takes this path: its rows are then rebuilt from the
        // poses the step began with (from the poses at its end they are a step of motion off).
        // It costs 2.3x to 3.7x rapier's internal substeps (one pipeline call per substep:
        // tests/suite/sim/substepping_cost.rs, medians of 2026-11-25 in docs/reading-rapier.md), so a joint
        // scene pays it only when it reads joint impulses, and, where the level allows it, only
        // in the steps where a blow can fall (sim/joint_sums.rs).
        if substeps > 1 && springs {
            (
                Substepping::Split,
                "one rapier call per substep: the springs' forces are evaluated before each \
                 substep (held over several they gain energy)"
                    .into(),
                false,
            )
        } else if joints && joint_impulse_tolerance(level).is_some() {
            let read = "one rapier call per substep: a check or question reads joint impulses, \
                        summed over every substep (rapier keeps a call's last substep's only)";
            match why_not_reconstructed(level, effects) {
                // One substep: every call is one substep already.
                _ if substeps == 1 => (Substepping::Split, read.into(), false),
                Some(why) => (Substepping::Split, format!("{read}, and {why}"), false),
                None => (Substepping::Internal, BLOW_SPLITS.into(), true),
            }
        } else {
            (
                Substepping::Internal,
                "one rapier call a step with its substeps inside: nothing reads inside a step (no \
                 springs over several substeps, no joint impulses read)"
                    .into(),
                false,
            )
        }
    }

    /// These settings as a report states them after a run: `substepping` as the steps were
    /// really called (`Split` when every step was split, `Mixed` when some were), and why.
    pub fn as_run(&self, calls: &StepCalls) -> Settings {
        let n = self.substeps;
        let mut s = self.clone();
        let planned_split = self.substepping == Substepping::Split;
        let in_run = calls.split_for_spin + calls.split_for_arc + calls.split_for_blow;
        s.split_steps = if planned_split { calls.steps } else { in_run };
        s.cut_steps = calls.cut;
        let spin = "a ball spinning in contact turned enough over a call to disturb its \
                    contact (its residual r w^2 T^2 / 8 past the contact's sag under its load, \
                    sim/contact_points.rs: split into as few calls as keep it)";
        let arc = "a smooth ball rode an Arc's circle (its chord contact is exact only at a \
                   call's ends, sim/arc_split.rs)";
        let blow = "a blow could fall (the first step, an impulse event, a body near a jointed \
                    one, a weld made) or the joints' impulses were not smooth enough over the \
                    last steps to interpolate (sim/joint_sums.rs)";
        let reasons: Vec<&str> = [
            (calls.split_for_spin > 0, spin),
            (calls.split_for_arc > 0, arc),
            (calls.split_for_blow > 0, blow),
        ]
        .into_iter()
        .filter_map(|(counted, why)| counted.then_some(why))
        .collect();
        let why = reasons.join(", or ");
        if !planned_split && in_run > 0 {
            if in_run == calls.steps {
                s.substepping = Substepping::Split;
                s.substepping_why = format!("several rapier calls in every step: {why}");
            } else {
                s.substepping = Substepping::Mixed;
                s.substepping_why = format!(
                    "{} of {} steps in several rapier calls, where {why}; the others in one \
                     call with {n} substeps inside ({})",
                    in_run, calls.steps, self.substepping_why
                );
            }
        }
        if n == 1 {
            s.substepping_why = format!(
                "one substep: every step is one rapier call of one substep ({})",
                s.substepping_why
            );
        }
        if calls.cut > 0 {
            s.substepping_why += &format!(
                "; in {} of {} steps an impact cut divided a call at the instant the bodies \
                 touch (sim/impacts.rs)",
                calls.cut, calls.steps
            );
        }
        s
    }

    /// The substep, s.
    pub fn h(&self) -> f64 {
        self.dt / self.substeps as f64
    }
}

/// Whether a level's checks or questions read joint impulses: the checks built on the free-body
/// diagram, and the quantities that are a joint's reaction, a motor's torque, or an acceleration
/// whose analysis is the free-body diagram's sum. With the tightest of their tolerances.
fn joint_impulse_tolerance(level: &Level) -> Option<f64> {
    use crate::level::{CheckKind as K, Quantity as Q};
    let checks = level.checks.iter().filter(|c| {
        matches!(
            c.kind,
            K::NewtonEuler
                | K::ImpulseMomentum
                | K::AngularMomentumFixedPoint
                | K::CenterOfPercussion
                | K::WorkEnergy
                | K::VirtualWork
        )
    });
    let questions = level
        .questions
        .iter()
        .cloned()
        // A challenge's goal read as a question reads as one.
        .chain(
            level
                .challenge
                .iter()
                .filter_map(|c| c.goal.as_question(level)),
        )
        .filter(|q| {
            matches!(
                q.quantity,
                Q::JointForce(_)
                    | Q::JointReaction { .. }
                    | Q::JointImpulse { .. }
                    | Q::MotorTorque { .. }
                    | Q::Ax(_)
                    | Q::Ay(_)
                    | Q::Accel(_)
                    | Q::Alpha(_)
                    | Q::PointAccel { .. }
            )
        })
        .map(|q| q.tolerance);
    checks
        .map(|c| c.tolerance)
        .chain(questions)
        .reduce(f64::min)
}

/// Why a level that reads joint impulses cannot have its steps' sums reconstructed from one call
/// (sim/joint_sums.rs), if it cannot: its joints may be struck at any step, or rigidlab moves
/// them between calls so that one call a step is another motion than one call a substep.
fn why_not_reconstructed(level: &Level, effects: &Effects) -> Option<String> {
    let moved = |name: &str| {
        level
            .bodies
            .iter()
            .any(|b| b.name == name && b.motion.is_some())
    };
    if effects.has(Effect::Joints) && !level.couplings.is_empty() {
        Some("the couplings are projected after every call (sim/couplings.rs)".into())
    } else if let Some(j) = level.joints.iter().find(|j| j.limits.is_some()) {
        Some(format!(
            "joint `{}` has limits, which strike at any step",
            j.name
        ))
    } else if effects.has(Effect::Sleeping) {
        Some(
            "bodies may fall asleep and wake, which starts and stops their joints' pull at once"
                .into(),
        )
    } else if let Some(j) = level.joints.iter().find(|j| j.starts_apart) {
        Some(format!("joint `{}` starts apart and snaps shut", j.name))
    } else {
        level
            .joints
            .iter()
            .find(|j| moved(&j.body1) || moved(&j.body2))
            .map(|j| {
                format!(
                    "joint `{}` holds a body whose motion is prescribed, at its mean rates over \
                     each call (a change of rate at every call's start)",
                    j.name
                )
            })
    }
}
