//! Bodies and their shapes: kinds, sizes, mass data, initial state.

use super::*;
use crate::level::curves;
use crate::level::motion;
use crate::level::shape::{self as shapes, Least};
use glam::DVec2;

pub(super) fn shape(v: &V, s: &Shape, pos: (usize, usize)) -> R {
    match s {
        Shape::Polygon { points } => polygon(v, points, pos),
        Shape::Segment { a, b } => segment(v, *a, *b, pos),
        Shape::Polyline { points, closed, .. } => polyline(v, points, *closed, pos),
        Shape::Arc {
            center,
            radius,
            start,
            end,
            chord_error,
            ..
        } => arc(v, *center, *radius, (*start, *end), *chord_error, pos),
        Shape::Track { .. } => track(v, s, pos),
        Shape::Compound { parts } => compound(v, parts, pos),
        // A shape given by sizes alone: each in its range.
        _ => sizes(v, s, pos),
    }
}

/// The sizes a shape is given by ([`shapes::sizes`]), each in its range.
fn sizes(v: &V, s: &Shape, pos: (usize, usize)) -> R {
    for size in shapes::sizes(s) {
        match size.least {
            Least::Positive => v.positive(size.value, size.what, "m", pos)?,
            Least::NonNegative => v.non_negative(size.value, size.what, "m", pos)?,
        }
    }
    Ok(())
}

/// A polygon: finite points, at least three, enclosing an area.
fn polygon(v: &V, points: &[V2], pos: (usize, usize)) -> R {
    for p in points {
        v.finite2(*p, "polygon point", pos)?;
    }
    let listed: Vec<DVec2> = points.iter().map(|&p| DVec2::from(p)).collect();
    if points.len() < 3 || shapes::polygon_area(&listed).abs() < 1e-12 {
        return Err(v.err(
            pos,
            "a polygon needs at least 3 points enclosing an area",
            "list the vertices of a convex polygon",
        ));
    }
    Ok(())
}

/// A segment: two finite, different ends.
fn segment(v: &V, a: V2, b: V2, pos: (usize, usize)) -> R {
    v.finite2(a, "segment end a", pos)?;
    v.finite2(b, "segment end b", pos)?;
    if a == b {
        return Err(v.err(
            pos,
            "a segment needs two different ends",
            "move `b` away from `a`",
        ));
    }
    Ok(())
}

/// A compound: at least one part, each placed finitely, none a track, each a valid shape.
fn compound(v: &V, parts: &[Part], pos: (usize, usize)) -> R {
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
        if curves::is_track(&p.shape) {
            return Err(v.err(
                pos,
                "a polyline or an arc cannot be a part of a compound shape",
                "give the track a fixed body of its own (several fixed bodies make a track of arcs and lines)",
            ));
        }
        shape(v, &p.shape, pos)?;
    }
    Ok(())
}

/// A polyline track: enough finite points, no zero-length edge, no edge crossing another.
fn polyline(v: &V, points: &[V2], closed: bool, pos: (usize, usize)) -> R {
    for (k, p) in points.iter().enumerate() {
        v.finite2(*p, &format!("polyline point {k}"), pos)?;
    }
    let least = if closed { 3 } else { 2 };
    if points.len() < least {
        return Err(v.err(
            pos,
            format!(
                "a{} polyline needs at least {least} points, this one has {}",
                if closed { " closed" } else { "n open" },
                points.len()
            ),
            "list the track's points in order (a single line is a `Segment`)",
        ));
    }
    if points.len() > curves::MAX_POLYLINE_POINTS {
        return Err(v.err(
            pos,
            format!(
                "a polyline may have at most {} points, this one has {}",
                curves::MAX_POLYLINE_POINTS,
                points.len()
            ),
            "split the track over several fixed bodies, or use `Arc` for its circular parts",
        ));
    }
    track_in_range(v, points, "polyline point", pos)?;
    let n = points.len();
    // The engine builds the track from its points rounded to its precision: test those too
    // (points 1e-300 apart are distinct in f64 and one point in f32).
    let rounded: Vec<V2> = points.iter().map(|p| engine_point(v, *p)).collect();
    let fault = curves::polyline_fault(points, closed).or_else(|| {
        v.level
            .world
            .precision
            .is_f32()
            .then(|| curves::polyline_fault(&rounded, closed))
            .flatten()
    });
    if let Some(curves::PolylineFault::ZeroEdge(k)) = &fault {
        if points[*k] != points[(*k + 1) % n] {
            return Err(v.err(
                pos,
                format!(
                    "polyline points {k} {:?} and {} {:?} are one point in f32, the engine's precision",
                    points[*k],
                    (*k + 1) % n,
                    points[(*k + 1) % n]
                ),
                "move them apart (f32 keeps about 7 significant digits), or remove one",
            ));
        }
    }
    match fault {
        None => Ok(()),
        Some(curves::PolylineFault::ZeroEdge(k)) => Err(v.err(
            pos,
            format!(
                "polyline points {k} and {} coincide at {:?}",
                (k + 1) % n,
                points[k]
            ),
            "remove one of them",
        )),
        Some(curves::PolylineFault::Crossing(i, j)) => Err(v.err(
            pos,
            format!(
                "the polyline crosses itself: its edge from point {i} {:?} to {} {:?} meets the edge from point {j} {:?} to {} {:?}",
                points[i],
                (i + 1) % n,
                points[(i + 1) % n],
                points[j],
                (j + 1) % n,
                points[(j + 1) % n]
            ),
            "move the points so that the track does not cross or fold back on itself (split a crossing track over two fixed bodies)",
        )),
    }
}

/// An arc track: finite center and angles, a positive radius, a sweep in (0, 2 pi], a chord
/// error in (0, radius) that needs at most `curves::MAX_ARC_FACETS` facets.
fn arc(
    v: &V,
    center: V2,
    radius: f64,
    (start, end): (f64, f64),
    chord_error: Option<f64>,
    pos: (usize, usize),
) -> R {
    v.finite2(center, "arc center", pos)?;
    v.positive(radius, "arc radius", "m", pos)?;
    v.finite(start, "arc start", pos)?;
    v.finite(end, "arc end", pos)?;
    let sweep = end - start;
    if !(sweep > 0.0 && sweep <= std::f64::consts::TAU + 1e-9) {
        return Err(v.err(
            pos,
            format!("an arc must sweep more than 0 and at most 2 pi rad counter-clockwise from `start` to `end`; this one sweeps {sweep} rad"),
            "give `end` greater than `start` by at most 6.283185307179586 (a full turn)",
        ));
    }
    if let Some(e) = chord_error {
        v.positive(e, "arc chord_error", "m", pos)?;
        if e >= radius {
            return Err(v.err(
                pos,
                format!("an arc's chord_error {e} m is not less than its radius {radius} m"),
                "give a chord_error well below the radius, or leave it out (1e-7 radius)",
            ));
        }
    }
    track_in_range(
        v,
        &[
            (center.0 - radius, center.1 - radius),
            (center.0 + radius, center.1 + radius),
        ],
        "arc extent (center -+ radius)",
        pos,
    )?;
    let e = curves::chord_error(radius, chord_error);
    let n = curves::arc_facets(radius, sweep, e);
    if n > curves::MAX_ARC_FACETS {
        let least = radius * (1.0 - (sweep / curves::MAX_ARC_FACETS as f64 / 2.0).cos());
        return Err(v.err(
            pos,
            format!(
                "this arc would need more than {} facets for a chord error of {e} m",
                curves::MAX_ARC_FACETS
            ),
            format!("give `chord_error: {least:.3e}` (m) or more"),
        ));
    }
    // The facets as the engine holds them: no two neighbouring vertices one point (an arc of
    // radius 1e-300 is one point in f32).
    let (points, _) = curves::arc_points(center, radius, start, end, e);
    let rounded: Vec<V2> = points.iter().map(|p| engine_point(v, *p)).collect();
    if let Some(k) = rounded.windows(2).position(|w| w[0] == w[1]) {
        return Err(v.err(
            pos,
            format!(
                "this arc's facet vertices {k} {:?} and {} {:?} are one point in {}, the engine's precision",
                points[k],
                k + 1,
                points[k + 1],
                v.level.world.precision.name()
            ),
            "give a larger radius or a larger chord_error (fewer, longer facets)",
        ));
    }
    Ok(())
}

/// A `Track`: every value finite, every piece of some length and less than a whole turn, a
/// `Turn` with a heading to turn from, facets within the limits, and no piece crossing another;
/// each error names the piece (from 1, in the order written).
fn track(v: &V, s: &Shape, pos: (usize, usize)) -> R {
    use crate::level::track::{self as tracks, Facets, TrackFault as F};
    let Shape::Track {
        start,
        heading,
        pieces,
        solid,
        chord_error,
    } = s
    else {
        return Ok(());
    };
    if let Some(e) = chord_error {
        v.positive(*e, "track chord_error", "m", pos)?;
    }
    let kind = |k: usize| match pieces.get(k) {
        Some(TrackPiece::Line { .. }) => "Line",
        Some(TrackPiece::Arc { .. }) => "Arc",
        Some(TrackPiece::Turn { .. }) => "Turn",
        None => "piece",
    };
    let piece = |k: usize| format!("track piece {} ({})", k + 1, kind(k));
    let fault = tracks::walk(
        *start,
        *heading,
        pieces,
        *solid,
        Facets::Engine(*chord_error),
    )
    .and_then(|path| match tracks::crossing(&path) {
        Some(f) => Err(f),
        None => Ok(path),
    });
    let (message, help) = match fault {
        Ok(path) => {
            track_in_range(v, &path.points, "track point", pos)?;
            return track_engine_points(v, &path.points, pos);
        }
        Err(F::Empty) => (
            "a track needs at least one piece".to_string(),
            "list its pieces: `pieces: [Line(to: (x, y)), Arc(center: (x, y), sweep: a), Turn(radius: r, angle: a)]`".to_string(),
        ),
        Err(F::NotFinite(None, what)) => (
            format!("the track's {what} is not a finite number"),
            "give a number".to_string(),
        ),
        Err(F::NotFinite(Some(k), what)) => (
            format!("{}: its {what} is not a finite number", piece(k)),
            "give a number".to_string(),
        ),
        Err(F::ZeroLength(k)) => (
            format!("{} has no length", piece(k)),
            "a Line must go somewhere else than where it starts, an Arc's center must be away from where it starts and its sweep not 0, a Turn's angle not 0; or remove the piece".to_string(),
        ),
        Err(F::WholeTurn(k, a)) => (
            format!("{} turns {a} rad, a whole turn or more", piece(k)),
            "turn less than 6.283185307179586 rad (a ring is an `Arc` of its own body)".to_string(),
        ),
        Err(F::NoHeading(k)) => (
            format!("{} has no heading to turn from", piece(k)),
            "give the track a `heading` (rad, the way it starts: 0 east, 1.5707963267948966 north), or start it with a Line or an Arc".to_string(),
        ),
        Err(F::Radius(k, r)) => (
            format!("{}: its radius {r} m is not positive", piece(k)),
            "give a radius greater than 0 (the angle's sign says which way it turns)".to_string(),
        ),
        Err(F::TooManyFacets(k)) => (
            format!("{} would need more than {} facets", piece(k), curves::MAX_ARC_FACETS),
            "give the track a larger `chord_error` (m)".to_string(),
        ),
        Err(F::TooManyPoints(n)) => (
            format!("this track would have {n} points, more than {}", tracks::MAX_TRACK_POINTS),
            "give the track a larger `chord_error` (m), or split it over two fixed bodies".to_string(),
        ),
        Err(F::FoldsBack(i, j, p)) => (
            format!("{} folds back on {} near {p:?}", piece(j), piece(i)),
            "turn the piece the other way, or move its end".to_string(),
        ),
        Err(F::Crossing(i, j, p)) => (
            format!("the track crosses itself: {} meets {} near {p:?}", piece(i), piece(j)),
            "move the pieces so that the track does not cross itself (split a crossing track over two fixed bodies)".to_string(),
        ),
    };
    Err(v.err(pos, message, help))
}

/// A track's points as the engine holds them: no two neighbours one point.
fn track_engine_points(v: &V, points: &[V2], pos: (usize, usize)) -> R {
    let rounded: Vec<V2> = points.iter().map(|p| engine_point(v, *p)).collect();
    if let Some(k) = rounded.windows(2).position(|w| w[0] == w[1]) {
        return Err(v.err(
            pos,
            format!(
                "this track's points {k} {:?} and {} {:?} are one point in {}, the engine's precision",
                points[k],
                k + 1,
                points[k + 1],
                v.level.world.precision.name()
            ),
            "give larger pieces or a larger chord_error (fewer, longer facets)",
        ));
    }
    Ok(())
}

/// The largest size of a track coordinate at each precision, m: the largest power of two
/// whose ulp is within rapier's allowed contact error (`normalized_allowed_linear_error`,
/// 0.005 m at `length_unit` 1). Past it the engine cannot place a contact on the track to its own
/// tolerance: f32 spaces numbers 0.0078 m apart from 65,536 m on; f64 5.9e-3 m from 3.5e13 m.
pub(super) fn track_limit(precision: Precision) -> f64 {
    match precision {
        Precision::F32 => 65_536.0,
        Precision::F64 => 35_184_372_088_832.0, // 2^45
    }
}

/// The point as the engine holds it: rounded to f32 unless the level runs in f64.
fn engine_point(v: &V, p: V2) -> V2 {
    if v.level.world.precision.is_f32() {
        (p.0 as f32 as f64, p.1 as f32 as f64)
    } else {
        p
    }
}

/// Every coordinate of a track within [`track_limit`] of its body's origin (issue 41: a
/// polyline at 1e39 m, past f32's range, was validated in f64 and built as infinities).
fn track_in_range(v: &V, points: &[V2], what: &str, pos: (usize, usize)) -> R {
    let precision = v.level.world.precision;
    let limit = track_limit(precision);
    for p in points {
        let size = p.0.abs().max(p.1.abs());
        if size.is_nan() || size >= limit {
            let ulp = |x: f64| match precision {
                Precision::F32 => (x as f32).abs() * f32::EPSILON,
                Precision::F64 => (x * f64::EPSILON) as f32,
            };
            return Err(v.err(
                pos,
                format!(
                    "{what} {p:?} is {size:.4e} m from its body's origin, past the {limit} m where {} spaces numbers more than rapier's allowed contact error of 0.005 m apart ({:.2e} m there)",
                    precision.name(),
                    ulp(limit)
                ),
                match precision {
                    Precision::F32 => format!(
                        "keep track coordinates within {limit} m of the body's origin, or set `precision: f64` in `world` (up to {:.2e} m)",
                        track_limit(Precision::F64)
                    ),
                    Precision::F64 => format!(
                        "keep track coordinates within {limit:.2e} m of the body's origin"
                    ),
                },
            ));
        }
    }
    Ok(())
}

/// One body, its fields validated in file order, so errors come in the order a user reads:
/// where and how fast it starts, its shape, its mass data, its surface, its damping, its motion.
pub(super) fn body(v: &V, b: &BodyDef) -> R {
    initial_state(v, b)?;
    body_shape(v, b)?;
    mass_data(v, b)?;
    surface(v, b)?;
    damping(v, b)?;
    if let Some(m) = &b.motion {
        motion(v, b, m, field(v, b, "motion"))?;
    }
    Ok(())
}

/// Where a field of body `b` is written.
fn field(v: &V, b: &BodyDef, f: &str) -> (usize, usize) {
    v.loc.field_pos("bodies", &b.name, f)
}

/// The starting pose and velocities: finite.
fn initial_state(v: &V, b: &BodyDef) -> R {
    let name = &b.name;
    v.finite2(
        b.position,
        &format!("body \"{name}\" position"),
        field(v, b, "position"),
    )?;
    v.finite(
        b.angle,
        &format!("body \"{name}\" angle"),
        field(v, b, "angle"),
    )?;
    v.finite2(
        b.velocity,
        &format!("body \"{name}\" velocity"),
        field(v, b, "velocity"),
    )?;
    v.finite(
        b.omega,
        &format!("body \"{name}\" omega"),
        field(v, b, "omega"),
    )
}

/// The shape: valid, and a track only on a body that does not move under forces.
fn body_shape(v: &V, b: &BodyDef) -> R {
    let Some(s) = &b.shape else { return Ok(()) };
    let at = field(v, b, "shape");
    shape(v, s, at)?;
    if curves::is_track(s) && b.kind == BodyKind::Dynamic {
        return Err(v.err(
            at,
            format!("dynamic body \"{}\" has a polyline, arc or track shape: these are static tracks", b.name),
            "make the body `kind: fixed` (or `kinematic`), or give a dynamic body a convex shape (Circle, Box, Capsule, Polygon, Compound)",
        ));
    }
    Ok(())
}

/// Mass, density, inertia and radius of gyration: not two of a pair, each positive, on a
/// dynamic body only, and a dynamic body left with a mass and a moment of inertia.
fn mass_data(v: &V, b: &BodyDef) -> R {
    let name = &b.name;
    let at = |f: &str| field(v, b, f);
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
    for (f, value, unit) in [
        ("mass", b.mass, "kg"),
        ("density", b.density, "kg/m^2"),
        ("inertia", b.inertia, "kg m^2"),
        ("radius_of_gyration", b.radius_of_gyration, "m"),
    ] {
        if let Some(x) = value {
            v.positive(x, &format!("body \"{name}\" {f}"), unit, at(f))?;
        }
    }
    if b.kind == BodyKind::Dynamic {
        dynamic_mass(v, b)
    } else {
        no_mass_data(v, b)
    }
}

/// A body that is not dynamic takes no mass data: the engine would ignore it.
fn no_mass_data(v: &V, b: &BodyDef) -> R {
    for (f, given) in [
        ("mass", b.mass.is_some()),
        ("density", b.density.is_some()),
        ("inertia", b.inertia.is_some()),
        ("radius_of_gyration", b.radius_of_gyration.is_some()),
    ] {
        if given {
            return Err(v.err(
                field(v, b, f),
                format!("body \"{}\" is {:?} and cannot have a {f}", b.name, b.kind).to_lowercase(),
                "remove it, or make the body `kind: dynamic`",
            ));
        }
    }
    Ok(())
}

/// A dynamic body's mass and moment of inertia: given, or from a shape with an area.
fn dynamic_mass(v: &V, b: &BodyDef) -> R {
    let name = &b.name;
    let area = b.shape.as_ref().map_or(0.0, shapes::area);
    if b.mass.is_none() && area <= 0.0 {
        return Err(v.err(
            field(v, b, "name"),
            format!("dynamic body \"{name}\" has no mass: its shape has no area"),
            "give `mass: ...` (kg), or a shape with an area",
        ));
    }
    if !b.lock_rotation && b.inertia.is_none() && b.radius_of_gyration.is_none() && area <= 0.0 {
        return Err(v.err(
            field(v, b, "name"),
            format!("dynamic body \"{name}\" has no moment of inertia: its shape has no area"),
            "give `inertia: ...` (kg m^2) or `radius_of_gyration: ...` (m), or set `lock_rotation: true`",
        ));
    }
    Ok(())
}

/// Friction and restitution coefficients: in range, and their effect declared when nonzero.
fn surface(v: &V, b: &BodyDef) -> R {
    let name = &b.name;
    let at = |f: &str| field(v, b, f);
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
    Ok(())
}

/// Linear and angular damping: not negative, and `damping` declared when nonzero.
fn damping(v: &V, b: &BodyDef) -> R {
    for (f, c) in [
        ("linear_damping", b.linear_damping),
        ("angular_damping", b.angular_damping),
    ] {
        let Some(c) = c else { continue };
        let at = field(v, b, f);
        v.non_negative(c, &format!("body \"{}\" {f}", b.name), "1/s", at)?;
        if c > 0.0 {
            v.need(
                Effect::Damping,
                at,
                &format!("body \"{}\" sets {f}", b.name),
            )?;
        }
    }
    Ok(())
}

/// A prescribed motion: on a kinematic body only, finite, an oscillation with a frequency.
fn motion(v: &V, b: &BodyDef, m: &Motion, pos: (usize, usize)) -> R {
    let name = &b.name;
    if b.kind != BodyKind::Kinematic {
        return Err(v.err(
            pos,
            format!(
                "body \"{name}\" is {} and cannot have a prescribed motion",
                format!("{:?}", b.kind).to_lowercase()
            ),
            "make the body `kind: kinematic` (a prescribed motion drives it regardless of forces), or remove `motion`",
        ));
    }
    match *m {
        Motion::Accelerate {
            acceleration,
            angular,
        } => {
            v.finite2(
                acceleration,
                &format!("body \"{name}\" motion acceleration"),
                pos,
            )?;
            v.finite(angular, &format!("body \"{name}\" motion angular"), pos)?;
        }
        Motion::Oscillate {
            amplitude,
            angular_amplitude,
            omega,
            phase,
        } => {
            v.finite2(amplitude, &format!("body \"{name}\" motion amplitude"), pos)?;
            v.finite(
                angular_amplitude,
                &format!("body \"{name}\" motion angular_amplitude"),
                pos,
            )?;
            v.finite(phase, &format!("body \"{name}\" motion phase"), pos)?;
            v.positive(
                omega,
                &format!("body \"{name}\" motion omega (the circular frequency)"),
                "rad/s",
                pos,
            )?;
        }
    }
    motion_within_caps(v, b, m, pos)
}

/// A prescribed motion within what the engine moves a body at: rapier clamps every body's
/// speed after each substep, a kinematic body's too, at 400 m/s ([`motion::SPEED_CAP`]) and its
/// angular rate at (pi/4) / dt unless `world.allow_fast_rotation`. Past either the body stays
/// behind its motion (at 1e3 m/s^2 for 1 s it was 180 m short; past f32's range it did not move
/// at all) while the snapshot reads the motion's own rates, so a question on them passed. The
/// caps are the same in f32 and f64 (rapier2d-f64 clamps alike), so `precision` does not lift
/// them. The rates are the body's `velocity` and `omega` plus the motion's, at their largest over
/// `world.duration`.
fn motion_within_caps(v: &V, b: &BodyDef, m: &Motion, pos: (usize, usize)) -> R {
    let w = &v.level.world;
    let speed = motion::largest_speed(b, m, w.duration);
    if speed.is_nan() || speed > motion::SPEED_CAP {
        return Err(v.err(
            pos,
            format!(
                "body \"{}\"'s prescribed motion reaches {speed:.3e} m/s within world.duration, past the engine's speed cap of {} m/s: rapier clamps every body's speed there, a kinematic body's too, so the body would stay behind its motion",
                b.name,
                motion::SPEED_CAP
            ),
            format!(
                "keep the speed within {} m/s over world.duration: `velocity` plus the acceleration times the duration (Accelerate), or plus the amplitude times omega (Oscillate); the cap is the same in f32 and f64",
                motion::SPEED_CAP
            ),
        ));
    }
    if w.allow_fast_rotation {
        return Ok(());
    }
    let rate = motion::largest_rate(b, m, w.duration);
    let cap = std::f64::consts::FRAC_PI_4 / w.dt;
    if rate.is_nan() || rate > cap {
        return Err(v.err(
            pos,
            format!(
                "body \"{}\"'s prescribed motion turns at {rate:.3e} rad/s within world.duration, past the engine's cap of (pi/4) / dt = {cap:.4} rad/s at world.dt = {} s: rapier clamps every body's angular rate there, so the body would stay behind its motion",
                b.name, w.dt
            ),
            "lower the motion's angular rate, shorten world.dt, or set `allow_fast_rotation: true` in `world` (which lifts the cap)",
        ));
    }
    Ok(())
}
