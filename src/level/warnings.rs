//! What is legal in a level but probably not meant: warnings, located like errors, that do not
//! stop the run.
//!
//! Bodies created at one point with contacts on: rapier finds every pair of them touching, so a
//! pile of k coincident bodies costs k(k-1)/2 contact pairs each step and is blown apart by the
//! overlap's correction (measured: 2,000 discs at one point took 114 s and 6.1 GB before this
//! warning existed). Bodies joined by a joint do not collide (sim/build.rs turns their contacts
//! off), so a pin between two coincident bodies is not warned about.

use super::{
    BodyDef, BodyKind, Coordinate, CouplingDef, Effect, JointKind, Level, LevelError, LevelWarning,
    Locator, Shape, V2,
};
use std::collections::HashMap;
use std::path::Path;

/// Centers closer than this, m, count as one point.
const SAME_POINT: f64 = 1e-6;

/// The warnings of a valid level (`text` is its source, for positions).
pub fn find(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let mut out = Vec::new();
    if level.effects.contains(&Effect::Contacts) {
        out.extend(coincident_bodies(file, text, level));
    }
    if level.effects.contains(&Effect::Joints) {
        out.extend(joint_velocities(file, text, level));
        out.extend(cables_without_carrier(file, text, level));
    }
    if level.effects.contains(&Effect::Springs) {
        out.extend(stiff_springs(file, text, level));
    }
    out.extend(f32_increments(file, text, level));
    out
}

/// The fewest ulps of f32 a body's per-substep increment may span before the level is warned
/// about: an increment of N ulps of the value it is added to is rounded by up to half an ulp,
/// 1 / (2 N) of itself, and the same way every substep while the increment and the binade stay
/// (so the errors add, not average). Below 100 ulps that is 0.5% of the change the increments
/// build; measured, a flywheel's omega at 57 ulps per substep was 1.5e-3 off in f32 (within
/// its 1e-3 in f64), free fall's height at 45 ulps 1.6e-4 and its speed at 167 ulps 2.1e-4,
/// a tenth of their bounds (the binades below the last round other ways).
pub const FEW_ULPS: f64 = 100.0;

/// The increments are warned about only where they build the value: their change over the run
/// at least this share of the value they are added to. A bullet's 401 m/s takes 5 ulps of
/// gravity a substep, and loses some of its drop, but its speed is the initial one.
pub const BUILDS_THE_VALUE: f64 = 0.1;

/// f32 increments of a few ulps: per substep h = dt / substeps, each dynamic body's position,
/// angle, velocity and omega change by v h, omega h, a h and alpha h, with a and alpha its
/// expected accelerations (gravity, unless a joint or coupling holds the body; its loads'
/// largest values; its joints' motors at their force limits) and v, omega its expected speeds
/// (the initial state plus what those accelerations give over the run). An increment of fewer
/// than `FEW_ULPS` ulps of the value it is added to (ulp = value x f32 epsilon), where the
/// increments build that value, is warned about with `precision: f64` as the fix.
fn f32_increments(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    if level.world.precision != super::Precision::F32 {
        return Vec::new();
    }
    let (t, h) = (
        level.world.duration,
        level.world.dt / level.world.substeps.max(1) as f64,
    );
    let eps = f32::EPSILON as f64;
    let fewest = FEW_ULPS;
    let g = if level.effects.contains(&Effect::Gravity) {
        let g = level.world.gravity.unwrap_or((0.0, -9.81));
        g.0.hypot(g.1)
    } else {
        0.0
    };
    let peak = |p: &super::Profile<f64>| match p {
        super::Profile::Constant(x) => x.abs(),
        super::Profile::Table(rows) => rows.iter().map(|r| r.1.abs()).fold(0.0, f64::max),
    };
    let peak_v = |p: &super::Profile<V2>| match p {
        super::Profile::Constant(x) => x.0.hypot(x.1),
        super::Profile::Table(rows) => rows
            .iter()
            .map(|r| r.1 .0.hypot(r.1 .1))
            .fold(0.0, f64::max),
    };
    let loc = Locator::new(text);
    // By name, once: a search per body was quadratic in a long chain.
    let mut held_bodies = std::collections::HashSet::new();
    let mut joints_on: HashMap<&str, Vec<&super::JointDef>> = HashMap::new();
    for j in &level.joints {
        for n in [j.body1.as_str(), j.body2.as_str()] {
            held_bodies.insert(n);
            joints_on.entry(n).or_default().push(j);
        }
    }
    for c in &level.couplings {
        held_bodies.extend(c.terms.iter().map(|t| t.body.as_str()));
    }
    let mut loads_on: HashMap<&str, Vec<&super::LoadDef>> = HashMap::new();
    for l in &level.loads {
        loads_on.entry(l.body.as_str()).or_default().push(l);
    }
    let mut worst: Option<(f64, String, String)> = None;
    for b in &level.bodies {
        let Some(m) = body_mass(b) else { continue };
        let inertia = b
            .inertia
            .or(b.radius_of_gyration.map(|k| m * k * k))
            .or(match &b.shape {
                Some(Shape::Circle { radius }) => Some(0.5 * m * radius * radius),
                Some(Shape::Box { width, height }) => {
                    Some(m * (width * width + height * height) / 12.0)
                }
                _ => None,
            });
        // A body on a joint or coupling swings or is carried: gravity does not build its speed
        // over the run (a pendulum's stays below sqrt(2 g L)).
        let held = held_bodies.contains(b.name.as_str());
        let mut a = if held { 0.0 } else { g };
        let mut alpha = 0.0;
        let mut omega_motor: f64 = 0.0;
        for l in loads_on.get(b.name.as_str()).into_iter().flatten() {
            let f = l.force.as_ref().map_or(0.0, peak_v);
            a += f / m;
            let arm = l.point.0.hypot(l.point.1);
            alpha += inertia.map_or(0.0, |i| (l.torque.as_ref().map_or(0.0, peak) + f * arm) / i);
        }
        if level.effects.contains(&Effect::Motors) {
            for j in joints_on.get(b.name.as_str()).into_iter().flatten() {
                let (target, max) = match &j.motor {
                    Some(super::Motor::Velocity { target, max_force }) => {
                        (target.abs(), *max_force)
                    }
                    Some(super::Motor::Position { max_force, .. }) => (0.0, *max_force),
                    None => continue,
                };
                if j.kind == JointKind::Revolute {
                    omega_motor = omega_motor.max(target);
                    alpha += max.zip(inertia).map_or(0.0, |(f, i)| f / i);
                } else {
                    a += max.map_or(0.0, |f| f / m);
                }
            }
        }
        if b.lock_rotation {
            alpha = 0.0;
        }
        let v0 = b.velocity.0.hypot(b.velocity.1);
        let v = v0 + a * t;
        let w = (b.omega.abs() + alpha * t).max(omega_motor);
        let x = b.position.0.hypot(b.position.1) + 0.5 * (v0 + v) * t;
        let th = b.angle.abs() + 0.5 * (b.omega.abs() + w) * t;
        // (increment per substep, the value it is added to, what it is).
        // (increment per substep, the value it is added to, its change over the run).
        let p0 = b.position.0.hypot(b.position.1);
        let rows = [
            (0.5 * (v0 + v) * h, x, x - p0, "position", "m"),
            (
                0.5 * (b.omega.abs() + w) * h,
                th,
                th - b.angle.abs(),
                "angle",
                "rad",
            ),
            (a * h, v, v - v0, "velocity", "m/s"),
            (alpha * h, w, w - b.omega.abs(), "omega", "rad/s"),
        ];
        for (inc, value, change, what, unit) in rows {
            if inc <= 0.0 || value <= 0.0 || !(inc / value).is_finite() {
                continue;
            }
            if change < BUILDS_THE_VALUE * value {
                continue;
            }
            let ulps = inc / (value * eps);
            if ulps >= fewest || worst.as_ref().is_some_and(|w| w.0 <= ulps) {
                continue;
            }
            worst = Some((
                ulps,
                b.name.clone(),
                format!(
                    "body \"{}\": its {what} changes by {inc:.3e} {unit} a substep (h = dt / substeps = {h:.3e} s) on a value up to {value:.3e} {unit}, {ulps:.0} ulps of f32: each substep rounds up to 1/(2 x {ulps:.0}) = {:.1e} of the change, the same way every substep (past {FEW_ULPS} ulps, 0.5%)",
                    b.name,
                    0.5 / ulps
                ),
            ));
        }
    }
    let Some((ulps, _, message)) = worst else {
        return Vec::new();
    };
    // The coarsest step at which every increment spans `fewest` ulps.
    let h_ok = h * fewest / ulps;
    vec![LevelWarning(LevelError::new(
        file,
        loc.section_field("world", "dt"),
        message,
        format!(
            "add `precision: f64` to `world` (rapier2d-f64 resolves these increments), or take h = dt / substeps of at least {h_ok:.3e} s"
        ),
    ))]
}

/// k h^2 / m above this warns: symplectic Euler, the engine's update, is unstable past
/// omega h = 2, k h^2 / m = 4 (the one-step map's trace 2 - k h^2 / m leaves [-2, 2]).
pub const STIFF_SPRING: f64 = 4.0;

/// A body's mass as the level gives it (its `mass`, else density times area), kg; None for a
/// body that is not dynamic or has no area.
fn body_mass(b: &BodyDef) -> Option<f64> {
    if b.kind != BodyKind::Dynamic {
        return None;
    }
    let m = b.mass.unwrap_or_else(|| {
        b.density.unwrap_or(super::DEFAULT_DENSITY)
            * b.shape.as_ref().map_or(0.0, super::shape::area)
    });
    (m > 0.0).then_some(m)
}

/// Springs too stiff for the step: k h^2 / m far above 1 (h = dt / substeps, m the body's mass,
/// or the pair's reduced mass m1 m2 / (m1 + m2) between two moving bodies). The engine's update
/// then grows the motion every substep until rapier's 400 m/s speed cap holds it (k h^2 / m of
/// 1e10 and more throws the body back and forth at the cap), and far beyond, where one substep's
/// velocity change overflows f32, the body does not move at all: the run then stops
/// (`sim::explosion_guard`), and this says why before it starts.
fn stiff_springs(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let h = level.world.dt / level.world.substeps.max(1) as f64;
    // By name, once: a search per joint was quadratic in a long chain.
    let bodies: HashMap<&str, &BodyDef> = level
        .bodies
        .iter()
        .map(|b| (b.name.as_str(), b))
        .rev()
        .collect();
    let body = |n: &str| bodies.get(n).copied();
    let loc = Locator::new(text);
    let mut out = Vec::new();
    for s in &level.springs {
        let m1 = body(&s.body1).and_then(body_mass);
        let m2 = s.body2.as_deref().and_then(body).and_then(body_mass);
        let m = match (m1, m2) {
            (Some(a), Some(b)) => a * b / (a + b),
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => continue,
        };
        let ratio = s.stiffness * h * h / m;
        if ratio.is_nan() || ratio <= STIFF_SPRING {
            continue;
        }
        // The stiffness at which k h^2 / m = 1, and the step at which it is 1 for this k.
        let k_ok = m / (h * h);
        let dt_ok = (m / s.stiffness).sqrt() * level.world.substeps.max(1) as f64;
        out.push(LevelWarning(LevelError::new(
            file,
            loc.field_pos("springs", &s.name, "stiffness"),
            format!(
                "spring \"{}\": k h^2 / m = {ratio:.3e} (k = {:.3e} N/m, h = dt / substeps = {h:.3e} s, m = {m:.4e} kg), far above 1: the engine's update is unstable past 4, so the spring throws its body about until rapier's 400 m/s speed cap holds it (or, past f32's range, does not move it at all)",
                s.name, s.stiffness
            ),
            format!(
                "lower the stiffness to about {k_ok:.3e} N/m or less, or make dt at most {dt_ok:.3e} s (or add substeps) so that k h^2 / m is 1 or less"
            ),
        )));
    }
    out
}

/// Where a body's mass center is in its frame, when its shape alone says (a circle, box or
/// capsule at the origin, a segment at its middle); None for polygons and compounds, whose
/// centroid is the analysis layer's to compute (the warning below then stays silent).
fn simple_mass_center(b: &BodyDef) -> Option<V2> {
    match &b.shape {
        None | Some(Shape::Circle { .. } | Shape::Box { .. } | Shape::Capsule { .. }) => {
            Some((0.0, 0.0))
        }
        Some(Shape::Segment { a, b }) => Some(((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0)),
        Some(_) => None,
    }
}

/// Joints whose two bodies' starting velocities disagree at the joint: a pinned disc given only
/// its omega, its mass center left at rest. rapier then jerks them together in the first step
/// with an impulse no textbook has (a new user's pendulum swung 0.0273 rad instead of 0.0515).
fn joint_velocities(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let body = |n: &str| level.bodies.iter().find(|b| b.name == n);
    // Velocity of the body point at world `p`, and the body's omega (fixed bodies at rest).
    let motion = |b: &BodyDef, g_local: V2, p: V2| {
        if b.kind == BodyKind::Fixed {
            return ((0.0, 0.0), 0.0);
        }
        let g = rotate(g_local, b.angle);
        let r = (p.0 - b.position.0 - g.0, p.1 - b.position.1 - g.1);
        (
            (b.velocity.0 - b.omega * r.1, b.velocity.1 + b.omega * r.0),
            b.omega,
        )
    };
    let loc = Locator::new(text);
    let mut out = Vec::new();
    for j in &level.joints {
        // `starts_apart`: the joint is meant to start broken (a pivot that catches a moving
        // plate: its first step is the impact).
        let (Some(b1), Some(b2), false) = (body(&j.body1), body(&j.body2), j.starts_apart) else {
            continue;
        };
        let (Some(g1), Some(g2)) = (simple_mass_center(b1), simple_mass_center(b2)) else {
            continue;
        };
        // At body2's anchor: on a slot that is the point of body1's slot line the pin is at
        // (for a pin or a weld the two anchors coincide, `validate::joints::anchors_meet`).
        let a2 = rotate(j.anchor2, b2.angle);
        let p = (b2.position.0 + a2.0, b2.position.1 + a2.1);
        let ((v1, w1), (v2, w2)) = (motion(b1, g1, p), motion(b2, g2, p));
        let mut dv = (v2.0 - v1.0, v2.1 - v1.1);
        if matches!(j.kind, JointKind::Prismatic | JointKind::PinSlot) {
            // Sliding along the axis is the joint's own motion.
            let ax = rotate(j.axis, b1.angle);
            let n = ax.0.hypot(ax.1).max(1e-300);
            let along = (dv.0 * ax.0 + dv.1 * ax.1) / (n * n);
            dv = (dv.0 - along * ax.0, dv.1 - along * ax.1);
        }
        let turns_with = matches!(j.kind, JointKind::Fixed | JointKind::Prismatic);
        let dw = if turns_with { w2 - w1 } else { 0.0 };
        let scale = v1.0.hypot(v1.1).max(v2.0.hypot(v2.1)).max(1.0);
        let slips = dv.0.hypot(dv.1) > 1e-6 * scale;
        if !slips && dw.abs() <= 1e-6 * w1.abs().max(w2.abs()).max(1.0) {
            continue;
        }
        // The body2 velocity that matches body1 at the joint (body2's omega kept).
        let fix = (b2.velocity.0 - dv.0, b2.velocity.1 - dv.1);
        let what = if slips {
            format!(
                "at t = 0 body \"{}\"'s point at the joint moves at ({:.4}, {:.4}) m/s and body \"{}\"'s at ({:.4}, {:.4}) m/s",
                b1.name, v1.0, v1.1, b2.name, v2.0, v2.1
            )
        } else {
            format!(
                "at t = 0 body \"{}\" turns at {w1} rad/s and body \"{}\" at {w2} rad/s",
                b1.name, b2.name
            )
        };
        out.push(LevelWarning(LevelError::new(
            file,
            loc.item_pos("joints", &j.name),
            format!(
                "joint \"{}\": {what}; rapier makes them agree in the first step with an impulse no textbook has",
                j.name
            ),
            if slips {
                format!(
                    "`velocity` is the mass center's and `omega` turns the body about it (v_P = v_G + omega x r_P/G); to start \"{}\" moving with \"{}\" at the joint, give it velocity: ({:.6}, {:.6}) (or, for a joint meant to catch it as an impact, add `starts_apart: true`)",
                    b2.name, b1.name, fix.0, fix.1
                )
            } else {
                format!(
                    "a {} keeps its bodies turning together: give both the same `omega`",
                    j.kind.describe()
                )
            },
        )));
    }
    out
}

/// Couplings that turn a pulley but name no `over`: the cable's pull on the bodies of its x and
/// y terms is then borne by no axle, and the pulley's joints read without it (issue 30: an
/// Atwood machine's axle read 19.62 N, the pulley's weight, for 67.04 N until `over` was added).
/// A pulley is a dynamic body the coupling turns (an angle term) and does not also pull (a yo-yo,
/// a block-and-tackle sheave, move with the cable); gears pull along no x or y term.
fn cables_without_carrier(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let candidates: Vec<&CouplingDef> = level
        .couplings
        .iter()
        .filter(|c| c.over.is_none() && !c.gears)
        .filter(|c| c.terms.iter().any(|t| t.coordinate != Coordinate::Angle))
        .collect();
    if candidates.is_empty() {
        return Vec::new();
    }
    let bodies: HashMap<&str, &BodyDef> =
        level.bodies.iter().map(|b| (b.name.as_str(), b)).collect();
    let turns = |b: &str| {
        bodies
            .get(b)
            .is_some_and(|b| b.kind == BodyKind::Dynamic && !b.lock_rotation)
    };
    let loc = Locator::new(text);
    let mut out = Vec::new();
    for c in candidates {
        let pulls = |b: &str| {
            c.terms
                .iter()
                .any(|t| t.body == b && t.coordinate != Coordinate::Angle)
        };
        let Some(pulley) = c
            .terms
            .iter()
            .find(|t| t.coordinate == Coordinate::Angle && turns(&t.body) && !pulls(&t.body))
        else {
            continue;
        };
        let mut pulled: Vec<&str> = Vec::new();
        for t in c.terms.iter().filter(|t| t.coordinate != Coordinate::Angle) {
            if !pulled.contains(&t.body.as_str()) {
                pulled.push(&t.body);
            }
        }
        let p = &pulley.body;
        out.push(LevelWarning(LevelError::new(
            file,
            loc.item_pos("couplings", &c.name),
            format!(
                "coupling \"{}\" turns \"{p}\" but names no `over`: its pull on {} is borne by no axle, so \"{p}\"'s joints read without the cable (an Atwood pulley's axle read 19.62 N, its weight, for 67.04 N)",
                c.name,
                pulled.join(", ")
            ),
            format!(
                "add `over: Some(\"{p}\")` to the coupling: the pulley then carries the cable and its axle bears the strands' pull (leave it out only for a massless peg whose load no check or question reads)"
            ),
        )));
    }
    out
}

/// `p` turned by `a` rad counter-clockwise.
fn rotate(p: V2, a: f64) -> V2 {
    let (s, c) = a.sin_cos();
    (p.0 * c - p.1 * s, p.0 * s + p.1 * c)
}

/// Where a body's collider is centered in the world.
fn world_center(b: &BodyDef, shape: &Shape) -> V2 {
    let c = rotate(super::shape::center(shape), b.angle);
    (b.position.0 + c.0, b.position.1 + c.1)
}

/// Groups of at least two colliding bodies (one of them moving) whose colliders are centered
/// at one point.
fn coincident_bodies(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let key = |p: (f64, f64)| {
        (
            (p.0 / SAME_POINT).round() as i64,
            (p.1 / SAME_POINT).round() as i64,
        )
    };
    let mut groups: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, b) in level.bodies.iter().enumerate() {
        if let Some(shape) = &b.shape {
            groups
                .entry(key(world_center(b, shape)))
                .or_default()
                .push(i);
        }
    }
    let joined = |a: &str, b: &str| {
        level
            .joints
            .iter()
            .any(|j| (j.body1 == a && j.body2 == b) || (j.body1 == b && j.body2 == a))
    };
    let mut found: Vec<Vec<usize>> = groups
        .into_values()
        .filter(|g| g.iter().any(|&i| level.bodies[i].kind == BodyKind::Dynamic))
        .filter(|g| {
            g.iter().enumerate().any(|(n, &i)| {
                g[n + 1..]
                    .iter()
                    .any(|&k| !joined(&level.bodies[i].name, &level.bodies[k].name))
            })
        })
        .collect();
    found.sort();
    if found.is_empty() {
        return Vec::new();
    }
    let loc = Locator::new(text);
    found
        .iter()
        .map(|g| {
            let first = &level.bodies[g[0]];
            let at = first
                .shape
                .as_ref()
                .map_or(first.position, |s| world_center(first, s));
            let k = g.len();
            let names: Vec<&str> = g
                .iter()
                .take(4)
                .map(|&i| level.bodies[i].name.as_str())
                .collect();
            LevelWarning(LevelError::new(
                file,
                loc.item_pos("bodies", &first.name),
                format!(
                    "{k} bodies start at the same point ({}, {}): {}{}; their colliders overlap, \
                     rapier pushes them apart violently and checks {} contact pairs every step",
                    at.0,
                    at.1,
                    names.join(", "),
                    if k > names.len() { ", ..." } else { "" },
                    k * (k - 1) / 2
                ),
                "give each body its own position, or join bodies that are one part with a weld",
            ))
        })
        .collect()
}
