//! The exercise: checks (kind, body, tolerance and why) and questions (quantity, when, answer).

use super::*;

pub(super) fn check(v: &V, i: usize, c: &CheckDef) -> R {
    let pos = v.loc.nth_in_section("checks", i);
    for (field, name) in [("body", &c.body), ("other", &c.other)] {
        if let Some(n) = name {
            let is_body = v.bodies.contains_key(n.as_str());
            let is_joint = v.joints.contains_key(n.as_str());
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
        if c.kind == CheckKind::MassProperties {
            return Err(v.err(
                pos,
                "check mass_properties has a `window`: mass properties do not change in time",
                "remove `window`",
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

/// A question: its answer and tolerance, the references of its quantity, its unit, its
/// mistakes, when it is read ([`question_at`]), and what its quantity needs of the scene.
pub(super) fn question(v: &V, q: &QuestionDef) -> R {
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
    question_unit(v, q)?;
    question_mistakes(v, q)?;
    question_at(v, q)?;
    if matches!(q.quantity, Quantity::Time)
        && matches!(q.at, When::End | When::Max(_) | When::Min(_))
    {
        return Err(v.err(
            at("at"),
            format!("question \"{}\" asks for the time of `{:?}`, which is not an event", q.id, q.at),
            "give an event: `at: Angle(..)`, `Crossing(..)`, `MaxOf(of: ..)`, `MinOf(of: ..)`, `SlipEnds(..)`, `FirstContact(..)`, `ContactEnds(..)`, `Leaves(..)` or `AfterEvent(..)`",
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
        | Quantity::ContactForceFrom { .. }
        | Quantity::SlipSpeed { .. }
        | Quantity::FrictionWork { .. }
        | Quantity::FrictionLoss { .. }
        | Quantity::ReboundHeight { .. }
        | Quantity::Restitution { .. }
        | Quantity::EnergyLost { .. }
        | Quantity::ContactImpulse { .. } => needs(Effect::Contacts, "a contact quantity")?,
        Quantity::PendulumPeriod { .. }
        | Quantity::LinkOmega { .. }
        | Quantity::PinSpeed { .. }
        | Quantity::JointReaction { .. }
        | Quantity::JointImpulse { .. }
        | Quantity::JointForce(_)
        | Quantity::PercussionDistance { .. } => needs(Effect::Joints, "a joint quantity")?,
        Quantity::MotorTorque { .. } => needs(Effect::Motors, "a motor torque")?,
        Quantity::SpringPeriod(_)
        | Quantity::SpringWork(_)
        | Quantity::DamperWork(_)
        | Quantity::SpringForce(_)
        | Quantity::SpringExtension(_) => needs(Effect::Springs, "a spring quantity")?,
        _ => {}
    }
    match &q.quantity {
        Quantity::JointReaction { window, .. }
        | Quantity::MotorTorque { window, .. }
        | Quantity::ContactForceFrom { window, .. } => {
            // 0 is the default (the two steps around the sample); a window longer than the run
            // could never be filled.
            v.non_negative(*window, "averaging window", "s", at("quantity"))?;
            if *window > v.level.world.duration {
                return Err(v.err(
                    at("quantity"),
                    format!(
                        "question \"{}\" averages over a window of {window} s, longer than the run (world.duration = {} s)",
                        q.id, v.level.world.duration
                    ),
                    "give `window` in seconds, at most world.duration (0, the default, is the two steps around the sample)",
                ));
            }
        }
        _ => {}
    }
    same_body_twice(v, q)?;
    match &q.quantity {
        Quantity::GroupKineticEnergy(b) | Quantity::GroupMomentum(b) if b.is_empty() => {
            return Err(v.err(
                at("quantity"),
                format!("question \"{}\" asks about a group of no bodies", q.id),
                "list the bodies: GroupKineticEnergy([\"bar\", \"bullet\"])",
            ));
        }
        Quantity::GroupKineticEnergy(b) | Quantity::GroupMomentum(b) => {
            if let Some(twice) = b
                .iter()
                .enumerate()
                .find_map(|(k, n)| b[..k].contains(n).then_some(n))
            {
                return Err(v.err(
                    at("quantity"),
                    format!(
                        "question \"{}\" lists body \"{twice}\" twice in its group",
                        q.id
                    ),
                    "name each body of the group once",
                ));
            }
        }
        Quantity::RelativePointSpeed {
            point, of_point, ..
        } => {
            v.finite2(*point, "question point", at("quantity"))?;
            v.finite2(*of_point, "question of_point", at("quantity"))?;
        }
        _ => {}
    }
    if let Quantity::MotorTorque { joint: j, .. } = &q.quantity {
        if v.joints.get(j.as_str()).is_some_and(|d| d.motor.is_none()) {
            return Err(v.err(
                at("quantity"),
                format!("question \"{}\" asks for the motor torque of joint \"{j}\", which has no motor", q.id),
                "give the joint a `motor`, or ask for its reaction",
            ));
        }
    }
    Ok(())
}

/// When a question is read (`at`): a time, an angle, a crossing, an extreme, a slip or contact
/// event, each with the bodies and values it names.
fn question_at(v: &V, q: &QuestionDef) -> R {
    let at = |f: &str| v.loc.field_pos("questions", &q.id, f);
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
        When::MaxOf { of, after } | When::MinOf { of, after } => {
            for (kind, name) in quantity_refs(of) {
                question_ref(v, q, kind, name, "at")?;
            }
            if matches!(of, Quantity::Time) {
                return Err(v.err(
                    at("at"),
                    format!("question \"{}\" waits for the extreme of `Time`", q.id),
                    "name the quantity whose extreme you mean: `at: MaxOf(of: Y(\"ball\"))`",
                ));
            }
            v.non_negative(*after, "extreme's `after`", "s", at("at"))?;
        }
        When::SlipEnds { body, other, after } | When::SlipStarts { body, other, after } => {
            v.need(
                Effect::Contacts,
                at("at"),
                &format!(
                    "question \"{}\" waits for a contact to slip or stop slipping",
                    q.id
                ),
            )?;
            question_ref(v, q, "body", body, "at")?;
            question_ref(v, q, "body", other, "at")?;
            v.non_negative(*after, "slip event's `after`", "s", at("at"))?;
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
        When::Leaves { body, other, after } => {
            v.need(
                Effect::Contacts,
                at("at"),
                &format!("question \"{}\" waits for a body to leave another", q.id),
            )?;
            question_ref(v, q, "body", body, "at")?;
            question_ref(v, q, "body", other, "at")?;
            v.non_negative(*after, "`Leaves`'s `after`", "s", at("at"))?;
            leaves_shapes(v, q, body, other)?;
        }
        When::AfterEvent(e) => question_ref(v, q, "event", e, "at")?,
        When::FirstStep => {}
    }
    Ok(())
}

/// A question's `unit` must parse and be its quantity's SI unit (`Quantity::si_unit`): the same
/// dimension and size, since `expected` is compared with the engine's SI value as it is and a
/// student's answer is converted to this unit (a `furlong` was accepted, and `N` for a speed).
fn question_unit(v: &V, q: &QuestionDef) -> R {
    use crate::level::units::Unit;
    let si = q.quantity.si_unit(v.level);
    let want = Unit::parse(si).expect("every quantity's SI unit is in the unit table");
    let what = q.quantity.variant_name();
    let at = || v.loc.field_pos("questions", &q.id, "unit");
    let help = format!(
        "write `unit: \"{si}\"`, {what}'s unit (levels are in SI units; docs/levels.md lists each quantity's), and give `expected` in it"
    );
    let given = Unit::parse(&q.unit).map_err(|e| {
        v.err(
            at(),
            format!(
                "question \"{}\" has the unit \"{}\", which is not a unit: {e}",
                q.id, q.unit
            ),
            help.clone(),
        )
    })?;
    if !given.converts_to(&want) {
        return Err(v.err(
            at(),
            format!(
                "question \"{}\" gives {what} in \"{}\" ({}), but {what} is {} ({si})",
                q.id,
                q.unit,
                given.dimension(),
                want.dimension()
            ),
            help,
        ));
    }
    if (given.factor - 1.0).abs() > 1e-12 {
        return Err(v.err(
            at(),
            format!(
                "question \"{}\" gives {what} in \"{}\", which is {} {si}: not the SI unit the engine's value is compared in",
                q.id, q.unit, given.factor
            ),
            help,
        ));
    }
    Ok(())
}

/// The named items a quantity refers to, as (kind, name).
pub fn quantity_refs(q: &Quantity) -> Vec<(&'static str, &String)> {
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
        | Q::ModePeriod { body: b, .. }
        | Q::EquilibriumAngle(b)
        | Q::PointX { body: b, .. }
        | Q::PointY { body: b, .. }
        | Q::PointSpeed { body: b, .. }
        | Q::PolarAngle { body: b, .. }
        | Q::PointAccel { body: b, .. } => vec![("body", b)],
        Q::CouplingForce(c) => vec![("coupling", c)],
        Q::RelativeDistance(a, b)
        | Q::RelativeSpeed(a, b)
        | Q::RelativeAngle(a, b)
        | Q::RelativeAccel(a, b) => {
            vec![("body", a), ("body", b)]
        }
        Q::AngularMomentumAbout { body, .. } => vec![("body", body)],
        Q::Efficiency { input, output } => {
            vec![("load or motorized joint", input), ("load", output)]
        }
        Q::FrictionWork { body, other }
        | Q::FrictionLoss { body, other }
        | Q::ContactNormalForce { body, other }
        | Q::ContactForceFrom { body, other, .. }
        | Q::SlipSpeed { body, other }
        | Q::ReboundHeight { body, other }
        | Q::Restitution { body, other }
        | Q::EnergyLost { body, other }
        | Q::ContactImpulse { body, other, .. } => vec![("body", body), ("body", other)],
        Q::RelativePointSpeed { body, of, .. } => vec![("body", body), ("body", of)],
        Q::PercussionDistance { body, joint } => vec![("body", body), ("joint", joint)],
        Q::GroupKineticEnergy(bodies) | Q::GroupMomentum(bodies) => {
            bodies.iter().map(|b| ("body", b)).collect()
        }
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
        Q::SpringWork(s) | Q::DamperWork(s) | Q::SpringForce(s) | Q::SpringExtension(s) => {
            vec![("spring", s)]
        }
        Q::LoadWork(l) | Q::LoadPower(l) => vec![("load", l)],
        Q::Time => vec![],
    }
}

/// Checks that a question's reference names an item of the level.
pub(super) fn question_ref(v: &V, q: &QuestionDef, kind: &str, name: &str, field: &str) -> R {
    let l = v.level;
    let known = match kind {
        "body" => v.bodies.contains_key(name),
        "joint" => v.joints.contains_key(name),
        "spring" => {
            l.springs.iter().any(|s| s.name == name)
                || l.torsion_springs.iter().any(|t| t.name == name)
        }
        "load" => l.loads.iter().any(|x| x.name == name),
        "coupling" => l.couplings.iter().any(|x| x.name == name),
        "load or motorized joint" => {
            l.loads.iter().any(|x| x.name == name)
                || l.joints.iter().any(|j| j.name == name && j.motor.is_some())
        }
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

/// A pair quantity or event must name two bodies: a body's slip, contact or impact against
/// itself, or its motion relative to itself, is no reading (`SlipSpeed` of a body against
/// itself was accepted, issue 41).
fn same_body_twice(v: &V, q: &QuestionDef) -> R {
    use Quantity as Q;
    let pair = |q: &Quantity| -> Option<(String, String)> {
        match q {
            Q::FrictionWork { body, other }
            | Q::FrictionLoss { body, other }
            | Q::ContactNormalForce { body, other }
            | Q::ContactForceFrom { body, other, .. }
            | Q::SlipSpeed { body, other }
            | Q::ReboundHeight { body, other }
            | Q::Restitution { body, other }
            | Q::EnergyLost { body, other }
            | Q::ContactImpulse { body, other, .. } => Some((body.clone(), other.clone())),
            Q::RollingAcceleration { body, ground }
            | Q::RollingFriction { body, ground }
            | Q::RollingFrictionNeeded { body, ground } => Some((body.clone(), ground.clone())),
            Q::RelativeDistance(a, b)
            | Q::RelativeSpeed(a, b)
            | Q::RelativeAngle(a, b)
            | Q::RelativeAccel(a, b) => Some((a.clone(), b.clone())),
            _ => None,
        }
    };
    let event = match &q.at {
        When::SlipEnds { body, other, .. }
        | When::SlipStarts { body, other, .. }
        | When::Leaves { body, other, .. } => Some((body.clone(), other.clone())),
        When::FirstContact {
            body,
            other: Some(other),
        }
        | When::ContactEnds {
            body,
            other: Some(other),
        } => Some((body.clone(), other.clone())),
        When::Crossing { of, .. } | When::MaxOf { of, .. } | When::MinOf { of, .. } => pair(of),
        _ => None,
    };
    for (field, p) in [("quantity", pair(&q.quantity)), ("at", event)] {
        if let Some((a, b)) = p.filter(|(a, b)| a == b) {
            return Err(v.err(
                v.loc.field_pos("questions", &q.id, field),
                format!(
                    "question \"{}\" pairs the body \"{a}\" with itself (its `{field}` names \"{b}\" twice)",
                    q.id
                ),
                "name the other body of the pair: the one it touches, slips or rolls on, or moves relative to",
            ));
        }
    }
    Ok(())
}

/// `Leaves` follows the gap between the two surfaces in closed form: a `Circle` leaving an
/// `Arc` on a fixed body (its true circle) or another `Circle`. Other pairs have no gap rigidlab
/// follows yet: say so, and name `ContactEnds` (the end of the contact's push) instead.
fn leaves_shapes(v: &V, q: &QuestionDef, body: &str, other: &str) -> R {
    if body == other {
        // same_body_twice says what is wrong.
        return Ok(());
    }
    let (Some(b), Some(o)) = (v.bodies.get(body), v.bodies.get(other)) else {
        return Ok(());
    };
    let circle = |d: &BodyDef| matches!(d.shape, Some(Shape::Circle { .. }));
    let fixed_arc =
        |d: &BodyDef| d.kind == BodyKind::Fixed && matches!(d.shape, Some(Shape::Arc { .. }));
    if circle(b) && (circle(o) || fixed_arc(o)) {
        return Ok(());
    }
    Err(v.err(
        v.loc.field_pos("questions", &q.id, "at"),
        format!(
            "question \"{}\" waits for \"{body}\" to leave \"{other}\", but `Leaves` follows the gap between a `Circle` and an `Arc` on a fixed body or another `Circle` only",
            q.id
        ),
        "make `body` the Circle and `other` the fixed Arc (or Circle) it rides, or read the end of the contact's push with `at: ContactEnds(body: .., other: ..)`",
    ))
}

/// Each typical mistake: a finite value that an answer can be told apart from the right one by
/// (a mistake within the student tolerance of the expected answer would be graded right, or the
/// right answer given its message), and a message to show.
fn question_mistakes(v: &V, q: &QuestionDef) -> R {
    let tol = q.student_tolerance;
    for (i, m) in q.mistakes.iter().enumerate() {
        let at = v
            .loc
            .list_field_pos("questions", &q.id, "mistakes", i, "value");
        let what = format!("question \"{}\" mistakes[{i}] value", q.id);
        v.finite(m.value, &what, at)?;
        if m.message.trim().is_empty() {
            return Err(v.err(
                at,
                format!("question \"{}\" mistakes[{i}] has an empty `message`", q.id),
                "write what the student probably did wrong: `message: \"...\"`",
            ));
        }
        if indistinct(q.expected, m.value, tol) {
            return Err(v.err(
                at,
                format!(
                    "{what} {} is within the student tolerance {tol} of the expected answer {}: an answer there is graded right, so the mistake could never be told apart",
                    m.value, q.expected
                ),
                "give the wrong answer the mistake leads to (derive it in a comment), or remove the mistake",
            ));
        }
    }
    Ok(())
}

/// Whether one of the question's typical mistakes is within the student tolerance of its
/// expected answer ([`question_mistakes`] refuses such a level): a student's variant is drawn
/// again where this holds (`params::Parameterized::indices`).
pub(crate) fn mistake_is_answer(q: &QuestionDef) -> bool {
    q.mistakes
        .iter()
        .any(|m| indistinct(q.expected, m.value, q.student_tolerance))
}

/// Whether `value` is within `tol` of `expected` by the grading rule (`questions::grade_answer`:
/// relative, absolute against 0), measured from either one.
fn indistinct(expected: f64, value: f64, tol: f64) -> bool {
    let rel = |reference: f64, x: f64| {
        if reference == 0.0 {
            x.abs()
        } else {
            (x - reference).abs() / reference.abs()
        }
    };
    rel(expected, value) <= tol || rel(value, expected) <= tol
}
