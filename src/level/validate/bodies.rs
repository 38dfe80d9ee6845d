//! Bodies and their shapes: kinds, sizes, mass data, initial state.

use super::*;

pub(super) fn shape(v: &V, s: &Shape, pos: (usize, usize)) -> R {
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
pub(super) fn polygon_area(points: &[V2]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        / 2.0
}

/// Area of a shape, m^2 (what mass by density multiplies; also `level::warnings`'s masses).
pub(in crate::level) fn shape_area(s: &Shape) -> f64 {
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

pub(super) fn body(v: &V, b: &BodyDef) -> R {
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
