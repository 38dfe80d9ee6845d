//! A level's challenge (format/challenge.rs): the goal's references and geometry. That the
//! control names a parameter, and that `worked` lies in its range, is checked where the
//! parameters are known (`level/params/challenge.rs`).

use super::*;

pub(super) fn challenge(v: &V, c: &ChallengeDef) -> R {
    let at = |f: &str| v.loc.section_field("challenge", f);
    v.finite(c.worked, "challenge worked", at("worked"))?;
    match &c.goal {
        Goal::EndsInside { body, region } | Goal::StaysInside { body, region } => {
            goal_body(v, body)?;
            self::region(v, region)
        }
        Goal::Reaches {
            body,
            point,
            radius,
        } => {
            goal_body(v, body)?;
            v.finite2(*point, "challenge goal point", at("point"))?;
            v.positive(*radius, "challenge goal radius", "m", at("radius"))
        }
        Goal::Reads {
            quantity,
            at: when,
            value,
            tolerance,
        } => {
            v.finite(*value, "challenge goal value", at("value"))?;
            v.positive(*tolerance, "challenge goal tolerance", "", at("tolerance"))?;
            // The quantity and its moment are a question's: validated as one, the error moved
            // to the goal.
            let q = c
                .goal
                .as_question(v.level)
                .expect("a `Reads` goal is read as a question");
            let _ = (quantity, when);
            question(v, &q).map_err(|e| LevelError {
                line: at("quantity").0,
                col: at("quantity").1,
                message: e
                    .message
                    .replace("question \"challenge\"", "the challenge's goal"),
                ..e
            })
        }
        Goal::PinFeelsNoBlow {
            joint,
            blow,
            tolerance,
        } => {
            v.positive(*tolerance, "challenge goal tolerance", "", at("tolerance"))?;
            let pin = v.joints.get(joint.as_str()).ok_or_else(|| {
                v.err(
                    at("joint"),
                    format!(
                        "the challenge's goal names the joint \"{joint}\", which does not exist"
                    ),
                    "name a revolute joint of this level",
                )
            })?;
            if pin.kind != JointKind::Revolute {
                return Err(v.err(
                    at("joint"),
                    format!("the challenge's goal names the joint \"{joint}\", which is not a pin"),
                    "name a revolute joint: a pin's impulsive reaction is what a blow at the center of percussion cancels",
                ));
            }
            let is_blow = v.level.events.iter().any(|e| {
                matches!(e, EventDef::Impulse { name, impulse, .. }
                    if name == blow && impulse.0.hypot(impulse.1) > 0.0)
            });
            if !is_blow {
                return Err(v.err(
                    at("blow"),
                    format!("the challenge's goal names the blow \"{blow}\", which is no `Impulse` event of this level with an impulse"),
                    "name an `Impulse` event with a non-zero `impulse`",
                ));
            }
            v.need(
                Effect::Joints,
                at("joint"),
                "the challenge's goal reads a pin",
            )
        }
    }
}

fn goal_body(v: &V, body: &str) -> R {
    if v.bodies.contains_key(body) {
        return Ok(());
    }
    let known: Vec<_> = v
        .level
        .bodies
        .iter()
        .map(|b| format!("\"{}\"", b.name))
        .collect();
    Err(v.err(
        v.loc.section_field("challenge", "body"),
        format!("the challenge's goal names the body \"{body}\", which does not exist"),
        format!("use one of the bodies: {}", known.join(", ")),
    ))
}

fn region(v: &V, r: &Region) -> R {
    let at = v.loc.section_field("challenge", "region");
    match *r {
        Region::Rect { min, max } => {
            v.finite2(min, "challenge region min", at)?;
            v.finite2(max, "challenge region max", at)?;
            if min.0 > max.0 || min.1 > max.1 {
                return Err(v.err(
                    at,
                    format!(
                        "the challenge's region Rect(min: ({}, {}), max: ({}, {})) has min past max",
                        min.0, min.1, max.0, max.1
                    ),
                    "write `min` as the lower left corner and `max` as the upper right one: min.x <= max.x and min.y <= max.y",
                ));
            }
            Ok(())
        }
        Region::Circle { center, radius } => {
            v.finite2(center, "challenge region center", at)?;
            v.positive(radius, "challenge region radius", "m", at)
        }
        Region::Ring {
            center,
            inner,
            outer,
        } => {
            v.finite2(center, "challenge region center", at)?;
            v.non_negative(inner, "challenge region inner radius", "m", at)?;
            v.positive(outer, "challenge region outer radius", "m", at)?;
            if inner >= outer {
                return Err(v.err(
                    at,
                    format!("the challenge's region Ring has inner {inner} m >= outer {outer} m"),
                    "give `inner` < `outer`, both in metres",
                ));
            }
            Ok(())
        }
    }
}
