//! Couplings, springs and loads, and the time profiles of loads.

use super::*;

/// The smallest and largest size of a coupling ratio: a strand count, or a radius in m. Outside,
/// the coupling's effective mass (ratio^2 / m) leaves what f64 and the f32 engine hold: a ratio of
/// 1e200 squared to inf, and the coupling applied no impulse at all.
pub(super) const RATIO_MIN: f64 = 1e-6;
pub(super) const RATIO_MAX: f64 = 1e6;

pub(super) fn coupling(v: &V, c: &CouplingDef) -> R {
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
    // A cable over a pulley names the pulley's angle once per strand; but a coupling whose
    // every term names one coordinate ties it to itself (issue 41): it holds it still, or, with
    // ratios summing to 0, does nothing.
    if let Some(t) = c.terms.first().filter(|t| {
        c.terms
            .iter()
            .all(|u| u.body == t.body && u.coordinate == t.coordinate)
    }) {
        return Err(v.err(
            pos,
            format!(
                "coupling \"{}\" ties the {} of body \"{}\" to itself: every term names it",
                c.name,
                format!("{:?}", t.coordinate).to_lowercase(),
                t.body
            ),
            "name the other coordinates the coupling ties it to (another body's, or another coordinate of this one)",
        ));
    }
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
        if !(RATIO_MIN..=RATIO_MAX).contains(&t.ratio.abs()) {
            return Err(v.err(
                pos,
                format!(
                    "coupling \"{}\" has the ratio {:?} for body \"{}\", outside the {RATIO_MIN:e} to {RATIO_MAX:e} a ratio may be in size",
                    c.name, t.ratio, t.body
                ),
                "a ratio is a strand count (x and y terms) or a drum's or gear's radius in m (angle \
                 terms); past this range the coupling's effective mass (ratio^2 / m) over- or \
                 underflows and the coupling does nothing (a ratio of 1e200 squares to inf): write \
                 the ratio in SI, within 1e-6 to 1e6 in size",
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
    if c.gears {
        let at = v.loc.field_pos("couplings", &c.name, "gears");
        let both_angles = c.terms.len() == 2
            && c.terms.iter().all(|t| t.coordinate == Coordinate::Angle)
            && c.terms[0].body != c.terms[1].body;
        if !both_angles || c.terms[0].ratio.signum() != c.terms[1].ratio.signum() {
            return Err(v.err(
                at,
                format!("coupling \"{}\" has `gears` but is not two angle terms of two bodies with ratios of one sign", c.name),
                "a pair of external gears is r1 angle1 + r2 angle2 = const with r1, r2 their pitch radii (m, the same sign)",
            ));
        }
        let pos = |n: &str| v.bodies.get(n).map_or((0.0, 0.0), |b| b.position);
        let (p1, p2) = (pos(&c.terms[0].body), pos(&c.terms[1].body));
        let d = ((p2.0 - p1.0).powi(2) + (p2.1 - p1.1).powi(2)).sqrt();
        let sum = c.terms[0].ratio.abs() + c.terms[1].ratio.abs();
        if (sum - d).abs() > 1e-2 * d.max(1e-9) {
            return Err(v.err(
                at,
                format!(
                    "coupling \"{}\": the gears' pitch radii add up to {sum} m but their centers are {d} m apart",
                    c.name
                ),
                "with `gears` the ratios are the pitch radii: make |r1| + |r2| the distance between the gears' positions (within 1%)",
            ));
        }
    }
    if let Some(over) = &c.over {
        v.body_ref(over, "couplings", &c.name, "over")?;
        let pulled = c
            .terms
            .iter()
            .any(|t| t.body == *over && t.coordinate != Coordinate::Angle);
        if pulled {
            return Err(v.err(
                v.loc.field_pos("couplings", &c.name, "over"),
                format!(
                    "coupling \"{}\" runs over \"{over}\", which one of its x or y terms also pulls",
                    c.name
                ),
                "`over` names the pulley that carries the cable (it bears the pull on the other \
                 bodies); a pulley that moves with the cable (block and tackle) takes an x or y \
                 term instead: drop `over`",
            ));
        }
        if !c.terms.iter().any(|t| t.coordinate != Coordinate::Angle) {
            return Err(v.err(
                v.loc.field_pos("couplings", &c.name, "over"),
                format!(
                    "coupling \"{}\" runs over \"{over}\" but pulls along no x or y term",
                    c.name
                ),
                "`over` is for a cable whose strands pull bodies along x or y; a gear pair \
                 (angle terms only) exerts no net pull: drop `over`",
            ));
        }
        let turns = |t: &CouplingTerm| t.body == *over && t.coordinate == Coordinate::Angle;
        let turned =
            c.terms.iter().any(turns) || v.level.couplings.iter().flat_map(|k| &k.terms).any(turns);
        if !turned {
            return Err(v.err(
                v.loc.field_pos("couplings", &c.name, "over"),
                format!(
                    "coupling \"{}\" runs over \"{over}\", which no coupling term turns: it is not a pulley",
                    c.name
                ),
                format!(
                    "`over` names the pulley the cable wraps, which the cable turns: add its angle \
                     term, `(body: \"{over}\", coordinate: angle, ratio: r)` with r its radius in m \
                     (signed as the cable winds), or drop `over`"
                ),
            ));
        }
    }
    Ok(())
}

pub(super) fn spring(v: &V, s: &SpringDef) -> R {
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

pub(super) fn torsion_spring(v: &V, t: &TorsionSpringDef) -> R {
    let at = |f: &str| v.loc.field_pos("torsion_springs", &t.name, f);
    v.need(
        Effect::Springs,
        v.loc.item_pos("torsion_springs", &t.name),
        &format!("torsion spring \"{}\" is defined", t.name),
    )?;
    v.body_ref(&t.body1, "torsion_springs", &t.name, "body1")?;
    if let Some(b2) = &t.body2 {
        v.body_ref(b2, "torsion_springs", &t.name, "body2")?;
        if *b2 == t.body1 {
            return Err(v.err(
                at("body2"),
                "a torsion spring joins a body to itself",
                "name two different bodies, or leave body2 out to hold it by the ground",
            ));
        }
    }
    v.positive(
        t.stiffness,
        &format!("torsion spring \"{}\" stiffness", t.name),
        "N m/rad",
        at("stiffness"),
    )?;
    if let Some(r) = t.rest_angle {
        v.finite(r, "torsion spring rest_angle", at("rest_angle"))?;
    }
    v.non_negative(
        t.damping,
        &format!("torsion spring \"{}\" damping", t.name),
        "N m s/rad",
        at("damping"),
    )?;
    if t.damping > 0.0 {
        v.need(
            Effect::Damping,
            at("damping"),
            &format!("torsion spring \"{}\" has damping", t.name),
        )?;
    }
    Ok(())
}

pub(super) fn profile_times<T>(v: &V, p: &Profile<T>, pos: (usize, usize)) -> R {
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

pub(super) fn load(v: &V, l: &LoadDef) -> R {
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
