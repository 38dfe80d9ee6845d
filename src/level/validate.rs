//! Semantic validation: ranges, names, finiteness, and effects.
//!
//! Every error names the offending item's line and says how to fix it.

use super::error::{LevelError, Locator};
use super::format::*;
use std::collections::HashSet;
use std::path::Path;

struct V<'a> {
    file: &'a Path,
    loc: Locator<'a>,
    level: &'a Level,
}

type R = Result<(), LevelError>;

impl V<'_> {
    fn err(
        &self,
        pos: (usize, usize),
        msg: impl Into<String>,
        help: impl Into<String>,
    ) -> LevelError {
        LevelError::new(self.file, pos, msg, help)
    }

    fn has(&self, e: Effect) -> bool {
        self.level.effects.contains(&e)
    }

    fn need(&self, e: Effect, pos: (usize, usize), what: &str) -> R {
        if self.has(e) {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!(
                    "{what}, but the level does not declare the `{}` effect",
                    e.name()
                ),
                format!("add `{}` to `effects: [...]`, or remove it", e.name()),
            ))
        }
    }

    fn finite(&self, x: f64, what: &str, pos: (usize, usize)) -> R {
        if x.is_finite() {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!("{what} is {x}, not a finite number"),
                "write a finite number (NaN and inf are not allowed)",
            ))
        }
    }

    fn finite2(&self, v: V2, what: &str, pos: (usize, usize)) -> R {
        self.finite(v.0, what, pos)?;
        self.finite(v.1, what, pos)
    }

    fn positive(&self, x: f64, what: &str, unit: &str, pos: (usize, usize)) -> R {
        self.finite(x, what, pos)?;
        if x > 0.0 {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!("{what} must be positive, got {x} {unit}"),
                format!("give a value > 0 {unit}"),
            ))
        }
    }

    fn non_negative(&self, x: f64, what: &str, unit: &str, pos: (usize, usize)) -> R {
        self.finite(x, what, pos)?;
        if x >= 0.0 {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!("{what} must not be negative, got {x} {unit}"),
                format!("give a value >= 0 {unit}"),
            ))
        }
    }

    fn unique<'n>(&self, section: &str, names: impl Iterator<Item = &'n str>) -> R {
        let mut seen = HashSet::new();
        for n in names {
            if n.trim().is_empty() {
                return Err(self.err(
                    self.loc.section(section),
                    format!("an item in `{section}` has an empty name"),
                    "give every item a name",
                ));
            }
            if !seen.insert(n) {
                // Point at the second occurrence.
                let first = self.loc.duplicate_pos(section, n);
                return Err(self.err(
                    first,
                    format!("the name \"{n}\" is used twice in `{section}`"),
                    "give each item its own name",
                ));
            }
        }
        Ok(())
    }

    fn body_ref(
        &self,
        name: &str,
        section: &str,
        item: &str,
        field: &str,
    ) -> Result<&BodyDef, LevelError> {
        self.level
            .bodies
            .iter()
            .find(|b| b.name == name)
            .ok_or_else(|| {
                let known: Vec<_> = self
                    .level
                    .bodies
                    .iter()
                    .map(|b| format!("\"{}\"", b.name))
                    .collect();
                self.err(
                    self.loc.field_pos(section, item, field),
                    format!("{field} names the body \"{name}\", which does not exist"),
                    format!("use one of the bodies: {}", known.join(", ")),
                )
            })
    }
}

pub fn validate(file: &Path, text: &str, level: &Level) -> R {
    let v = V {
        file,
        loc: Locator::new(text),
        level,
    };
    world(&v)?;
    v.unique("bodies", level.bodies.iter().map(|b| b.name.as_str()))?;
    v.unique("joints", level.joints.iter().map(|j| j.name.as_str()))?;
    v.unique("springs", level.springs.iter().map(|s| s.name.as_str()))?;
    v.unique("couplings", level.couplings.iter().map(|c| c.name.as_str()))?;
    v.unique("loads", level.loads.iter().map(|l| l.name.as_str()))?;
    v.unique("events", level.events.iter().map(|e| e.name()))?;
    v.unique("questions", level.questions.iter().map(|q| q.id.as_str()))?;
    if level.bodies.is_empty() {
        return Err(v.err(
            v.loc.section("bodies"),
            "the level has no bodies",
            "add at least one body to `bodies: [...]`",
        ));
    }
    for b in &level.bodies {
        body(&v, b)?;
    }
    for j in &level.joints {
        joint(&v, j)?;
    }
    for s in &level.springs {
        spring(&v, s)?;
    }
    for c in &level.couplings {
        coupling(&v, c)?;
    }
    for l in &level.loads {
        load(&v, l)?;
    }
    for e in &level.events {
        event(&v, e)?;
    }
    for (i, c) in level.checks.iter().enumerate() {
        check(&v, i, c)?;
    }
    for q in &level.questions {
        question(&v, q)?;
    }
    effects_consistent(&v)
}

fn world(v: &V) -> R {
    let w = &v.level.world;
    let at = |f: &str| v.loc.section_field("world", f);
    v.positive(w.dt, "world.dt", "s", at("dt"))?;
    if w.dt > 0.1 {
        return Err(v.err(
            at("dt"),
            format!("world.dt = {} s is too large for a rigid-body step", w.dt),
            "use a step of at most 0.1 s (1/60 is rapier's default)",
        ));
    }
    v.positive(w.duration, "world.duration", "s", at("duration"))?;
    if w.duration / w.dt > 1e7 {
        return Err(v.err(
            at("duration"),
            "world.duration / world.dt exceeds 1e7 steps",
            "shorten the duration or lengthen the step",
        ));
    }
    if w.substeps == 0 || w.substeps > 1000 {
        return Err(v.err(
            at("substeps"),
            format!("world.substeps = {} is out of range", w.substeps),
            "use 1 to 1000 substeps (rapier's default is 4)",
        ));
    }
    if w.solver_iterations == 0 || w.solver_iterations > 1000 {
        return Err(v.err(
            at("solver_iterations"),
            format!(
                "world.solver_iterations = {} is out of range",
                w.solver_iterations
            ),
            "use 1 to 1000 iterations (rapier's default is 1)",
        ));
    }
    if let Some(hz) = w.contact_hz {
        v.positive(hz, "world.contact_hz", "Hz", at("contact_hz"))?;
        // rapier's contact bias needs the spring resolved by the step: beyond 1/(2 dt) (Nyquist)
        // the softness saturates; 1e6 Hz is rapier's own "rigid" joint setting.
        if hz > 1e6 {
            return Err(v.err(
                at("contact_hz"),
                format!("world.contact_hz = {hz} Hz is out of range"),
                "use 0 < contact_hz <= 1e6 Hz (rapier's default is 30 Hz)",
            ));
        }
    }
    if let Some(g) = w.gravity {
        v.finite2(g, "world.gravity", at("gravity"))?;
        if g != (0.0, 0.0) {
            v.need(Effect::Gravity, at("gravity"), "world.gravity is set")?;
        }
    }
    Ok(())
}

fn shape(v: &V, s: &Shape, pos: (usize, usize)) -> R {
    match s {
        Shape::Circle { radius } => v.positive(*radius, "circle radius", "m", pos),
        Shape::Box { width, height } => {
            v.positive(*width, "box width", "m", pos)?;
            v.positive(*height, "box height", "m", pos)
        }
        Shape::Capsule { length, radius } => {
            v.non_negative(*length, "capsule length", "m", pos)?;
            v.positive(*radius, "capsule radius", "m", pos)
        }
        Shape::Polygon { points } => {
            for p in points {
                v.finite2(*p, "polygon point", pos)?;
            }
            if points.len() < 3 || polygon_area(points).abs() < 1e-12 {
                return Err(v.err(
                    pos,
                    "a polygon needs at least 3 points enclosing an area",
                    "list the vertices of a convex polygon",
                ));
            }
            Ok(())
        }
        Shape::Segment { a, b } => {
            v.finite2(*a, "segment end a", pos)?;
            v.finite2(*b, "segment end b", pos)?;
            if a == b {
                return Err(v.err(
                    pos,
                    "a segment needs two different ends",
                    "move `b` away from `a`",
                ));
            }
            Ok(())
        }
        Shape::Compound { parts } => {
            if parts.is_empty() {
                return Err(v.err(
                    pos,
                    "a compound shape needs at least one part",
                    "add parts, or use a single shape",
                ));
            }
            for p in parts {
                v.finite2(p.offset, "part offset", pos)?;
                v.finite(p.angle, "part angle", pos)?;
                shape(v, &p.shape, pos)?;
            }
            Ok(())
        }
    }
}

/// Signed area of a polygon (shoelace).
pub fn polygon_area(points: &[V2]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        / 2.0
}

/// Area of a shape, m^2 (what mass by density multiplies).
pub fn shape_area(s: &Shape) -> f64 {
    use std::f64::consts::PI;
    match s {
        Shape::Circle { radius } => PI * radius * radius,
        Shape::Box { width, height } => width * height,
        Shape::Capsule { length, radius } => 2.0 * radius * length + PI * radius * radius,
        Shape::Polygon { points } => polygon_area(points).abs(),
        Shape::Segment { .. } => 0.0,
        Shape::Compound { parts } => parts.iter().map(|p| shape_area(&p.shape)).sum(),
    }
}

fn body(v: &V, b: &BodyDef) -> R {
    let at = |f: &str| v.loc.field_pos("bodies", &b.name, f);
    let name = &b.name;
    v.finite2(
        b.position,
        &format!("body \"{name}\" position"),
        at("position"),
    )?;
    v.finite(b.angle, &format!("body \"{name}\" angle"), at("angle"))?;
    v.finite2(
        b.velocity,
        &format!("body \"{name}\" velocity"),
        at("velocity"),
    )?;
    v.finite(b.omega, &format!("body \"{name}\" omega"), at("omega"))?;
    if let Some(s) = &b.shape {
        shape(v, s, at("shape"))?;
    }
    if b.mass.is_some() && b.density.is_some() {
        return Err(v.err(
            at("density"),
            format!("body \"{name}\" gives both mass and density"),
            "give one of them",
        ));
    }
    if b.inertia.is_some() && b.radius_of_gyration.is_some() {
        return Err(v.err(
            at("radius_of_gyration"),
            format!("body \"{name}\" gives both inertia and radius_of_gyration"),
            "give one of them",
        ));
    }
    if let Some(m) = b.mass {
        v.positive(m, &format!("body \"{name}\" mass"), "kg", at("mass"))?;
    }
    if let Some(d) = b.density {
        v.positive(
            d,
            &format!("body \"{name}\" density"),
            "kg/m^2",
            at("density"),
        )?;
    }
    if let Some(i) = b.inertia {
        v.positive(
            i,
            &format!("body \"{name}\" inertia"),
            "kg m^2",
            at("inertia"),
        )?;
    }
    if let Some(k) = b.radius_of_gyration {
        v.positive(
            k,
            &format!("body \"{name}\" radius_of_gyration"),
            "m",
            at("radius_of_gyration"),
        )?;
    }
    if b.kind != BodyKind::Dynamic {
        for (field, given) in [
            ("mass", b.mass.is_some()),
            ("density", b.density.is_some()),
            ("inertia", b.inertia.is_some()),
            ("radius_of_gyration", b.radius_of_gyration.is_some()),
        ] {
            if given {
                return Err(v.err(
                    at(field),
                    format!("body \"{name}\" is {:?} and cannot have a {field}", b.kind)
                        .to_lowercase(),
                    "remove it, or make the body `kind: dynamic`",
                ));
            }
        }
    } else {
        let area = b.shape.as_ref().map_or(0.0, shape_area);
        if b.mass.is_none() && area <= 0.0 {
            return Err(v.err(
                at("name"),
                format!("dynamic body \"{name}\" has no mass: its shape has no area"),
                "give `mass: ...` (kg), or a shape with an area",
            ));
        }
        if !b.lock_rotation && b.inertia.is_none() && b.radius_of_gyration.is_none() && area <= 0.0
        {
            return Err(v.err(
                at("name"),
                format!("dynamic body \"{name}\" has no moment of inertia: its shape has no area"),
                "give `inertia: ...` (kg m^2) or `radius_of_gyration: ...` (m), or set `lock_rotation: true`",
            ));
        }
    }
    if let Some(mu) = b.friction {
        v.non_negative(mu, &format!("body \"{name}\" friction"), "", at("friction"))?;
        if mu > 0.0 {
            v.need(
                Effect::Friction,
                at("friction"),
                &format!("body \"{name}\" sets a friction coefficient"),
            )?;
        }
    }
    if let Some(e) = b.restitution {
        v.non_negative(
            e,
            &format!("body \"{name}\" restitution"),
            "",
            at("restitution"),
        )?;
        if e > 1.0 {
            return Err(v.err(
                at("restitution"),
                format!("body \"{name}\" restitution {e} > 1 would create energy"),
                "use a coefficient between 0 and 1",
            ));
        }
        if e > 0.0 {
            v.need(
                Effect::Restitution,
                at("restitution"),
                &format!("body \"{name}\" sets a restitution coefficient"),
            )?;
        }
    }
    for (field, c) in [
        ("linear_damping", b.linear_damping),
        ("angular_damping", b.angular_damping),
    ] {
        if let Some(c) = c {
            v.non_negative(c, &format!("body \"{name}\" {field}"), "1/s", at(field))?;
            if c > 0.0 {
                v.need(
                    Effect::Damping,
                    at(field),
                    &format!("body \"{name}\" sets {field}"),
                )?;
            }
        }
    }
    Ok(())
}

fn joint(v: &V, j: &JointDef) -> R {
    let at = |f: &str| v.loc.field_pos("joints", &j.name, f);
    v.need(
        Effect::Joints,
        v.loc.item_pos("joints", &j.name),
        &format!("joint \"{}\" is defined", j.name),
    )?;
    let b1 = v.body_ref(&j.body1, "joints", &j.name, "body1")?;
    let b2 = v.body_ref(&j.body2, "joints", &j.name, "body2")?;
    if j.body1 == j.body2 {
        return Err(v.err(
            at("body2"),
            format!("joint \"{}\" joins body \"{}\" to itself", j.name, j.body1),
            "name two different bodies",
        ));
    }
    if b1.kind != BodyKind::Dynamic && b2.kind != BodyKind::Dynamic {
        return Err(v.err(
            at("body2"),
            format!("joint \"{}\" joins two bodies that are not dynamic", j.name),
            "one of the bodies must be `kind: dynamic`",
        ));
    }
    v.finite2(j.anchor1, "anchor1", at("anchor1"))?;
    v.finite2(j.anchor2, "anchor2", at("anchor2"))?;
    v.finite2(j.axis, "axis", at("axis"))?;
    if j.axis.0.hypot(j.axis.1) < 1e-9 {
        return Err(v.err(
            at("axis"),
            "the joint axis has zero length",
            "give a direction such as (1.0, 0.0)",
        ));
    }
    anchors_meet(v, j, b1, b2)?;
    if let Some((lo, hi)) = j.limits {
        v.finite(lo, "lower limit", at("limits"))?;
        v.finite(hi, "upper limit", at("limits"))?;
        if lo > hi {
            return Err(v.err(
                at("limits"),
                format!("joint \"{}\" limits ({lo}, {hi}) are reversed", j.name),
                "write (lower, upper)",
            ));
        }
        if j.kind == JointKind::Fixed {
            return Err(v.err(
                at("limits"),
                "a fixed joint has no coordinate to limit",
                "remove `limits`",
            ));
        }
    }
    if let Some(m) = &j.motor {
        v.need(
            Effect::Motors,
            at("motor"),
            &format!("joint \"{}\" has a motor", j.name),
        )?;
        if j.kind == JointKind::Fixed || j.kind == JointKind::PinSlot {
            return Err(v.err(
                at("motor"),
                format!("a {:?} joint cannot carry a motor", j.kind).to_lowercase(),
                "motors go on revolute or prismatic joints",
            ));
        }
        match m {
            Motor::Velocity { target, max_force } => {
                v.finite(*target, "motor target", at("motor"))?;
                if let Some(f) = max_force {
                    v.positive(*f, "motor max_force", "", at("motor"))?;
                }
            }
            Motor::Position {
                target,
                stiffness,
                damping,
                max_force,
            } => {
                v.finite(*target, "motor target", at("motor"))?;
                v.non_negative(*stiffness, "motor stiffness", "", at("motor"))?;
                v.non_negative(*damping, "motor damping", "", at("motor"))?;
                if let Some(f) = max_force {
                    v.positive(*f, "motor max_force", "", at("motor"))?;
                }
            }
        }
    }
    Ok(())
}

/// How far apart a joint's two anchors may start, m: a gap any larger is snapped shut in the first
/// step by an impulse the textbook knows nothing of (an angle typed in degrees gave 1.8e9 N).
const ANCHOR_GAP: f64 = 1e-4;

/// A joint's anchors must meet at t = 0 (along the slide axis a prismatic or pin-in-slot joint may
/// start anywhere: that is its coordinate).
fn anchors_meet(v: &V, j: &JointDef, b1: &BodyDef, b2: &BodyDef) -> R {
    let world = |b: &BodyDef, a: V2| {
        let (s, c) = b.angle.sin_cos();
        (
            b.position.0 + c * a.0 - s * a.1,
            b.position.1 + s * a.0 + c * a.1,
        )
    };
    let (p1, p2) = (world(b1, j.anchor1), world(b2, j.anchor2));
    let mut gap = (p2.0 - p1.0, p2.1 - p1.1);
    if matches!(j.kind, JointKind::Prismatic | JointKind::PinSlot) {
        let (s, c) = b1.angle.sin_cos();
        let n = j.axis.0.hypot(j.axis.1);
        let axis = (
            (c * j.axis.0 - s * j.axis.1) / n,
            (s * j.axis.0 + c * j.axis.1) / n,
        );
        let along = gap.0 * axis.0 + gap.1 * axis.1;
        gap = (gap.0 - along * axis.0, gap.1 - along * axis.1);
    }
    let d = gap.0.hypot(gap.1);
    if d <= ANCHOR_GAP || j.starts_apart {
        return Ok(());
    }
    // The body2 position that closes the gap, keeping its angle.
    let fix = (b2.position.0 - gap.0, b2.position.1 - gap.1);
    Err(v.err(
        v.loc.field_pos("joints", &j.name, "anchor2"),
        format!(
            "joint \"{}\": its anchors are {d:.4} m apart at t = 0 (body1's at ({:.4}, {:.4}), body2's at ({:.4}, {:.4}) in the world); rapier would snap them together in the first step with an impulse no textbook has",
            j.name, p1.0, p1.1, p2.0, p2.1
        ),
        format!(
            "anchors are in each body's frame, from its `position`, turned by its `angle` (radians); to keep the anchors, put body \"{}\" at position: ({:.6}, {:.6}) (or, to test how the engine snaps a stretched joint shut, add `starts_apart: true`)",
            b2.name, fix.0, fix.1
        ),
    ))
}

fn coupling(v: &V, c: &CouplingDef) -> R {
    let pos = v.loc.item_pos("couplings", &c.name);
    v.need(
        Effect::Joints,
        pos,
        &format!("coupling \"{}\" is defined", c.name),
    )?;
    if c.terms.len() < 2 {
        return Err(v.err(
            pos,
            format!("coupling \"{}\" has {} term(s)", c.name, c.terms.len()),
            "a coupling ties at least two coordinates: add terms",
        ));
    }
    let mut any_dynamic = false;
    for t in &c.terms {
        let b = v.body_ref(&t.body, "couplings", &c.name, "body")?;
        any_dynamic |=
            b.kind == BodyKind::Dynamic && !(t.coordinate == Coordinate::Angle && b.lock_rotation);
        v.finite(t.ratio, "coupling ratio", pos)?;
        if t.ratio == 0.0 {
            return Err(v.err(
                pos,
                format!(
                    "coupling \"{}\" has a zero ratio for body \"{}\"",
                    c.name, t.body
                ),
                "remove the term or give it a non-zero ratio",
            ));
        }
    }
    if !any_dynamic {
        return Err(v.err(
            pos,
            format!("coupling \"{}\" ties no coordinate that can move", c.name),
            "include a dynamic body's free coordinate",
        ));
    }
    Ok(())
}

fn spring(v: &V, s: &SpringDef) -> R {
    let at = |f: &str| v.loc.field_pos("springs", &s.name, f);
    v.need(
        Effect::Springs,
        v.loc.item_pos("springs", &s.name),
        &format!("spring \"{}\" is defined", s.name),
    )?;
    v.body_ref(&s.body1, "springs", &s.name, "body1")?;
    if let Some(b2) = &s.body2 {
        v.body_ref(b2, "springs", &s.name, "body2")?;
        if *b2 == s.body1 {
            return Err(v.err(
                at("body2"),
                "a spring joins a body to itself",
                "name two different bodies, or leave body2 out to anchor it to the ground",
            ));
        }
    }
    v.finite2(s.point1, "point1", at("point1"))?;
    v.finite2(s.point2, "point2", at("point2"))?;
    v.positive(
        s.stiffness,
        &format!("spring \"{}\" stiffness", s.name),
        "N/m",
        at("stiffness"),
    )?;
    v.non_negative(
        s.rest_length,
        &format!("spring \"{}\" rest_length", s.name),
        "m",
        at("rest_length"),
    )?;
    v.non_negative(
        s.damping,
        &format!("spring \"{}\" damping", s.name),
        "N s/m",
        at("damping"),
    )?;
    if s.damping > 0.0 {
        v.need(
            Effect::Damping,
            at("damping"),
            &format!("spring \"{}\" has damping", s.name),
        )?;
    }
    Ok(())
}

fn profile_times<T>(v: &V, p: &Profile<T>, pos: (usize, usize)) -> R {
    if let Profile::Table(rows) = p {
        if rows.is_empty() {
            return Err(v.err(
                pos,
                "a Table profile needs at least one (t, value) row",
                "add rows, or use Constant(...)",
            ));
        }
        for w in rows.windows(2) {
            if w[1].0 <= w[0].0 {
                return Err(v.err(
                    pos,
                    format!(
                        "table times must increase, but {} follows {}",
                        w[1].0, w[0].0
                    ),
                    "sort the rows by time",
                ));
            }
        }
        for r in rows {
            v.finite(r.0, "table time", pos)?;
        }
    }
    Ok(())
}

fn load(v: &V, l: &LoadDef) -> R {
    let at = |f: &str| v.loc.field_pos("loads", &l.name, f);
    v.body_ref(&l.body, "loads", &l.name, "body")?;
    v.finite2(l.point, "load point", at("point"))?;
    if l.force.is_none() && l.torque.is_none() {
        return Err(v.err(
            v.loc.item_pos("loads", &l.name),
            format!("load \"{}\" has neither force nor torque", l.name),
            "add `force: Constant((fx, fy))` or `torque: Constant(m)`",
        ));
    }
    if let Some(f) = &l.force {
        profile_times(v, f, at("force"))?;
        match f {
            Profile::Constant(x) => v.finite2(*x, "force", at("force"))?,
            Profile::Table(rows) => rows
                .iter()
                .try_for_each(|r| v.finite2(r.1, "force", at("force")))?,
        }
    }
    if let Some(t) = &l.torque {
        profile_times(v, t, at("torque"))?;
        match t {
            Profile::Constant(x) => v.finite(*x, "torque", at("torque"))?,
            Profile::Table(rows) => rows
                .iter()
                .try_for_each(|r| v.finite(r.1, "torque", at("torque")))?,
        }
    }
    Ok(())
}

fn event(v: &V, e: &EventDef) -> R {
    match e {
        EventDef::WeldOnContact { name, body1, body2 } => {
            let pos = v.loc.item_pos("events", name);
            v.need(
                Effect::Contacts,
                pos,
                &format!("event \"{name}\" welds on contact"),
            )?;
            v.need(
                Effect::Joints,
                pos,
                &format!("event \"{name}\" creates a fixed joint"),
            )?;
            v.body_ref(body1, "events", name, "body1")?;
            v.body_ref(body2, "events", name, "body2")?;
            if body1 == body2 {
                return Err(v.err(
                    pos,
                    format!("event \"{name}\" welds body \"{body1}\" to itself"),
                    "name two different bodies",
                ));
            }
            Ok(())
        }
        EventDef::Impulse {
            name,
            at: t,
            body,
            point,
            impulse,
            angular,
        } => {
            let at = |f: &str| v.loc.field_pos("events", name, f);
            v.body_ref(body, "events", name, "body")?;
            v.non_negative(*t, &format!("event \"{name}\" time"), "s", at("at"))?;
            v.finite2(*point, "impulse point", at("point"))?;
            v.finite2(*impulse, "impulse", at("impulse"))?;
            v.finite(*angular, "angular impulse", at("angular"))
        }
    }
}

fn check(v: &V, i: usize, c: &CheckDef) -> R {
    let pos = v.loc.nth_in_section("checks", i);
    for (field, name) in [("body", &c.body), ("other", &c.other)] {
        if let Some(n) = name {
            let is_body = v.level.bodies.iter().any(|b| &b.name == n);
            let is_joint = v.level.joints.iter().any(|j| &j.name == n);
            if !is_body && !is_joint {
                return Err(v.err(
                    pos,
                    format!("check {field} names \"{n}\", which is neither a body nor a joint"),
                    "name a body or joint of this level",
                ));
            }
        }
    }
    if let Some(p) = c.point {
        v.finite2(p, "check point", pos)?;
    }
    if c.kind == CheckKind::KineticEnergyIc && c.point.is_none() && c.other.is_none() {
        // An instantaneous center found from the engine's own velocities makes 1/2 I_C w^2
        // equal 1/2 m v^2 + 1/2 I_G w^2 identically: the check would compare a number with itself.
        return Err(v.err(
            pos,
            "check kinetic_energy_ic has neither `point` nor `other`: it would compare the engine's kinetic energy with itself",
            "give `point: (x, y)` for a body turning about a fixed pivot, or `other: \"ground\"` for a body rolling on it",
        ));
    }
    if let Some((t1, t2)) = c.window {
        if c.kind != CheckKind::ImpulseMomentum {
            return Err(v.err(
                pos,
                format!(
                    "check {} has a `window`; only impulse_momentum takes one",
                    c.kind.name()
                ),
                "remove `window`, or make the check `kind: impulse_momentum`",
            ));
        }
        v.non_negative(t1, "check window start", "s", pos)?;
        v.finite(t2, "check window end", pos)?;
        if t2 <= t1 {
            return Err(v.err(
                pos,
                format!("check window ({t1}, {t2}) ends before it starts"),
                "write `window: (t1, t2)` with t1 < t2, in seconds",
            ));
        }
        let d = v.level.world.duration;
        if t2 > d * (1.0 + 1e-12) {
            return Err(v.err(
                pos,
                format!("check window ({t1}, {t2}) ends after the run (world.duration = {d} s)"),
                "end the window at or before world.duration, or lengthen the run",
            ));
        }
    }
    v.positive(c.tolerance, "check tolerance", "", pos)?;
    if c.why.trim().is_empty() {
        return Err(v.err(
            pos,
            format!("check {} gives no `why` for its tolerance {}", c.kind.name(), c.tolerance),
            "add `why: \"...\"`: the engine limitation or the discretization error the tolerance covers, with its size",
        ));
    }
    Ok(())
}

fn question(v: &V, q: &QuestionDef) -> R {
    let at = |f: &str| v.loc.field_pos("questions", &q.id, f);
    v.finite(
        q.expected,
        &format!("question \"{}\" expected", q.id),
        at("expected"),
    )?;
    v.positive(
        q.tolerance,
        &format!("question \"{}\" tolerance", q.id),
        "",
        at("tolerance"),
    )?;
    for (kind, name) in quantity_refs(&q.quantity) {
        question_ref(v, q, kind, name, "quantity")?;
    }
    match &q.at {
        When::Time(t) | When::Max(t) | When::Min(t) => {
            v.non_negative(*t, "question time", "s", at("at"))?
        }
        When::End => {}
        When::Angle { body, angle } => {
            question_ref(v, q, "body", body, "at")?;
            v.finite(*angle, "question angle", at("at"))?;
        }
        When::Crossing { of, value, after } => {
            for (kind, name) in quantity_refs(of) {
                question_ref(v, q, kind, name, "at")?;
            }
            if matches!(of, Quantity::Time) {
                return Err(v.err(
                    at("at"),
                    format!("question \"{}\" waits for `Time` to cross a value", q.id),
                    "use `at: Time(t)` to read at a time",
                ));
            }
            v.finite(*value, "crossing value", at("at"))?;
            v.non_negative(*after, "crossing `after`", "s", at("at"))?;
        }
        When::FirstContact { body, other } | When::ContactEnds { body, other } => {
            v.need(
                Effect::Contacts,
                at("at"),
                &format!("question \"{}\" waits for a contact", q.id),
            )?;
            question_ref(v, q, "body", body, "at")?;
            if let Some(o) = other {
                question_ref(v, q, "body", o, "at")?;
            }
        }
        When::AfterEvent(e) => question_ref(v, q, "event", e, "at")?,
        When::FirstStep => {}
    }
    if matches!(q.quantity, Quantity::Time)
        && matches!(q.at, When::End | When::Max(_) | When::Min(_))
    {
        return Err(v.err(
            at("at"),
            format!("question \"{}\" asks for the time of `{:?}`, which is not an event", q.id, q.at),
            "give an event: `at: Angle(..)`, `Crossing(..)`, `FirstContact(..)`, `ContactEnds(..)` or `AfterEvent(..)`",
        ));
    }
    let needs = |e: Effect, what: &str| {
        v.need(
            e,
            at("quantity"),
            &format!("question \"{}\" asks for {what}", q.id),
        )
    };
    match &q.quantity {
        Quantity::RollingAcceleration { .. }
        | Quantity::RollingFriction { .. }
        | Quantity::RollingFrictionNeeded { .. }
        | Quantity::ContactNormalForce { .. }
        | Quantity::FrictionWork { .. }
        | Quantity::ReboundHeight { .. }
        | Quantity::Restitution { .. }
        | Quantity::EnergyLost { .. } => needs(Effect::Contacts, "a contact quantity")?,
        Quantity::PendulumPeriod { .. }
        | Quantity::LinkOmega { .. }
        | Quantity::PinSpeed { .. }
        | Quantity::JointReaction { .. }
        | Quantity::JointImpulse { .. }
        | Quantity::JointForce(_) => needs(Effect::Joints, "a joint quantity")?,
        Quantity::MotorTorque { .. } => needs(Effect::Motors, "a motor torque")?,
        Quantity::SpringPeriod(_) | Quantity::SpringWork(_) | Quantity::SpringExtension(_) => {
            needs(Effect::Springs, "a spring quantity")?
        }
        _ => {}
    }
    match &q.quantity {
        Quantity::JointReaction { window, .. } | Quantity::MotorTorque { window, .. } => {
            v.non_negative(*window, "averaging window", "s", at("quantity"))?
        }
        _ => {}
    }
    if let Quantity::MotorTorque { joint: j, .. } = &q.quantity {
        if v.level
            .joints
            .iter()
            .any(|d| &d.name == j && d.motor.is_none())
        {
            return Err(v.err(
                at("quantity"),
                format!("question \"{}\" asks for the motor torque of joint \"{j}\", which has no motor", q.id),
                "give the joint a `motor`, or ask for its reaction",
            ));
        }
    }
    Ok(())
}

/// The named items a quantity refers to, as (kind, name).
fn quantity_refs(q: &Quantity) -> Vec<(&'static str, &String)> {
    use Quantity as Q;
    match q {
        Q::X(b)
        | Q::Y(b)
        | Q::Angle(b)
        | Q::Vx(b)
        | Q::Vy(b)
        | Q::Speed(b)
        | Q::Omega(b)
        | Q::KineticEnergy(b)
        | Q::ContactForce(b)
        | Q::Distance(b)
        | Q::Ax(b)
        | Q::Ay(b)
        | Q::Accel(b)
        | Q::Alpha(b)
        | Q::Direction(b)
        | Q::GravityWork(b)
        | Q::SpringPeriod(b)
        | Q::PointX { body: b, .. }
        | Q::PointY { body: b, .. }
        | Q::PointSpeed { body: b, .. }
        | Q::PointAccel { body: b, .. } => vec![("body", b)],
        Q::CouplingForce(c) => vec![("coupling", c)],
        Q::RelativeDistance(a, b) | Q::RelativeSpeed(a, b) | Q::RelativeAngle(a, b) => {
            vec![("body", a), ("body", b)]
        }
        Q::FrictionWork { body, other }
        | Q::ContactNormalForce { body, other }
        | Q::ReboundHeight { body, other }
        | Q::Restitution { body, other }
        | Q::EnergyLost { body, other } => vec![("body", body), ("body", other)],
        Q::RollingAcceleration { body, ground }
        | Q::RollingFriction { body, ground }
        | Q::RollingFrictionNeeded { body, ground } => vec![("body", body), ("body", ground)],
        Q::JointForce(j)
        | Q::MotorTorque { joint: j, .. }
        | Q::JointReaction { joint: j, .. }
        | Q::JointImpulse { joint: j, .. } => vec![("joint", j)],
        Q::PendulumPeriod { body, joint } => vec![("body", body), ("joint", joint)],
        Q::LinkOmega { link, known, other } => {
            vec![("body", link), ("joint", known), ("joint", other)]
        }
        Q::PinSpeed {
            link,
            known,
            other,
            pin,
        } => {
            vec![
                ("body", link),
                ("joint", known),
                ("joint", other),
                ("joint", pin),
            ]
        }
        Q::SpringWork(s) | Q::SpringExtension(s) => vec![("spring", s)],
        Q::LoadWork(l) | Q::LoadPower(l) => vec![("load", l)],
        Q::Time => vec![],
    }
}

/// Checks that a question's reference names an item of the level.
fn question_ref(v: &V, q: &QuestionDef, kind: &str, name: &str, field: &str) -> R {
    let l = v.level;
    let known = match kind {
        "body" => l.bodies.iter().any(|b| b.name == name),
        "joint" => l.joints.iter().any(|j| j.name == name),
        "spring" => l.springs.iter().any(|s| s.name == name),
        "load" => l.loads.iter().any(|x| x.name == name),
        "coupling" => l.couplings.iter().any(|x| x.name == name),
        _ => l.events.iter().any(|e| e.name() == name),
    };
    if known {
        return Ok(());
    }
    Err(v.err(
        v.loc.field_pos("questions", &q.id, field),
        format!(
            "question \"{}\" asks about the {kind} \"{name}\", which does not exist",
            q.id
        ),
        format!("name a {kind} of this level"),
    ))
}

fn effects_consistent(v: &V) -> R {
    let pos = v.loc.section("effects");
    let mut seen = HashSet::new();
    for e in &v.level.effects {
        if !seen.insert(e) {
            return Err(v.err(
                pos,
                format!("the effect `{}` is listed twice", e.name()),
                "list each effect once",
            ));
        }
    }
    for (e, needs) in [
        (Effect::Friction, Effect::Contacts),
        (Effect::Restitution, Effect::Contacts),
        (Effect::Ccd, Effect::Contacts),
        (Effect::Motors, Effect::Joints),
    ] {
        if v.has(e) && !v.has(needs) {
            return Err(v.err(
                pos,
                format!("the effect `{}` needs `{}`", e.name(), needs.name()),
                format!(
                    "add `{}` to the effects, or remove `{}`",
                    needs.name(),
                    e.name()
                ),
            ));
        }
    }
    Ok(())
}
