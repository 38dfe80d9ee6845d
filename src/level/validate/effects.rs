//! Effects: what the level uses must be declared, and what is declared must be used.

use super::*;

pub(super) fn effects_consistent(v: &V) -> R {
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
