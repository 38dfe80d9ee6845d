//! Events: impulses, welds on contact, and when they happen.

use super::*;

pub(super) fn event(v: &V, e: &EventDef) -> R {
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
