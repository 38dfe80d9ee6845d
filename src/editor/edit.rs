//! The editor's verbs: what each edit does to a level, with the same steps in each (find the
//! bodies it names, change the level, declare the effects it now relies on, say what it did).

use crate::level::curves;
use crate::level::shape as shapes;
use crate::level::{
    ArcSide, BodyDef, BodyKind, Effect, JointDef, JointKind, Level, Motor, QuestionDef, Shape,
    SpringDef, TorsionSpringDef, TrackSide, V2,
};
use glam::DVec2;

/// A body the editor can make.
#[derive(Debug, Clone, PartialEq)]
pub enum NewShape {
    /// A box `width` x `height`, m.
    Box { width: f64, height: f64 },
    /// A disc of `radius`, m.
    Disc { radius: f64 },
    /// A slender bar `length` x `thickness`, m, along x.
    Bar { length: f64, thickness: f64 },
    /// A convex polygon, vertices about its center, m.
    Polygon { points: Vec<V2> },
}

/// A property of a body the inspector edits.
#[derive(Debug, Clone, PartialEq)]
pub enum Property {
    /// kg (the density is dropped: a body has one or the other).
    Mass(f64),
    /// kg/m^2 (the mass is dropped).
    Density(f64),
    /// Box or bar width, m.
    Width(f64),
    /// Box or bar height, m.
    Height(f64),
    /// Disc radius, m.
    Radius(f64),
    /// Position of the body frame origin, m.
    Position(V2),
    /// rad, counter-clockwise.
    Angle(f64),
    /// Initial velocity of G, m/s.
    Velocity(V2),
    /// Initial angular velocity, rad/s.
    Omega(f64),
    /// Coulomb coefficient; `friction` is declared when it is above zero.
    Friction(f64),
    /// Coefficient of restitution; `restitution` is declared when it is above zero.
    Restitution(f64),
    Kind(BodyKind),
    /// An arc track's center in the body frame, m.
    ArcCenter(V2),
    /// An arc track's start angle, rad (it runs counter-clockwise to its end).
    ArcStart(f64),
    /// An arc track's end angle, rad.
    ArcEnd(f64),
    /// Which side of an arc track bodies ride on.
    Side(ArcSide),
    /// A polyline track's (or a polygon's) points in the body frame, m.
    Points(Vec<V2>),
    /// Whether a polyline track closes back to its first point.
    Closed(bool),
    /// Which side of a polyline track is solid (None: two-sided).
    Solid(Option<TrackSide>),
}

/// One edit of a level.
#[derive(Debug, Clone, PartialEq)]
pub enum Edit {
    /// A fixed ground line at height `y`, `width` wide, centered on x = 0.
    AddGround { y: f64, width: f64 },
    /// A fixed wall at `x`, from y = 0 up `height`.
    AddWall { x: f64, height: f64 },
    /// A fixed incline: a right-triangle wedge whose slope rises at `angle` (rad) over a base
    /// `length` m long, its lower corner at `at`.
    AddIncline { at: V2, angle: f64, length: f64 },
    /// A fixed circular arc track (`Shape::Arc`): its body at `center` (world, m), `radius` m,
    /// counter-clockwise from `start` to `end` (rad), ridden on its `side`.
    AddArc {
        center: V2,
        radius: f64,
        start: f64,
        end: f64,
        side: ArcSide,
    },
    /// A fixed polyline track (`Shape::Polyline`) through `points` (world, m: its body at the
    /// origin), open or `closed`, one-sided with `solid` on that side of its direction from the
    /// first point, else two-sided.
    AddTrack {
        points: Vec<V2>,
        closed: bool,
        solid: Option<TrackSide>,
    },
    /// A dynamic body centered at `at`, of `mass` kg.
    AddBody { shape: NewShape, at: V2, mass: f64 },
    /// A joint at the world point `at` between `body1` (None: the ground, a fixed anchor body
    /// made there) and `body2`; anchors are computed in each body's frame so they meet.
    AddJoint {
        kind: JointKind,
        body1: Option<String>,
        body2: String,
        at: V2,
    },
    /// A linear spring from `at1` on `body1` to `at2` on `body2` (None: the ground), world
    /// points; its rest length is the distance between them (the scene starts unstretched).
    AddSpring {
        body1: String,
        at1: V2,
        body2: Option<String>,
        at2: V2,
        stiffness: f64,
    },
    /// A torsion spring between `body1` and `body2` (None: the ground), at rest at the angle
    /// the scene starts with: a couple -k (theta - theta_0) on body1, the opposite on body2.
    AddTorsionSpring {
        body1: String,
        body2: Option<String>,
        stiffness: f64,
    },
    /// A velocity motor on a joint (None removes it).
    SetMotor { joint: String, target: Option<f64> },
    /// A property of a body.
    Set { body: String, property: Property },
    /// Removes a body and everything attached to it or asking about it.
    Delete { body: String },
    /// A copy of a body moved by `offset`, m (not its joints).
    Duplicate { body: String, offset: V2 },
    /// The level's title and statement, as the user writes them.
    SetText { title: String, statement: String },
    /// Drops the exercise's checks and questions (their answers were for the scene as written).
    DropExercise,
    /// How long the run lasts, s.
    SetDuration(f64),
    /// The level's own step, s, and substeps per step (what `rigidlab check` runs it at).
    SetStep { dt: f64, substeps: usize },
    /// A question of the exercise (a teacher's, with its expected answer).
    AddQuestion(Box<QuestionDef>),
    /// The question at `index` (0-based, in the level's order) rewritten by the teacher.
    ReplaceQuestion {
        index: usize,
        question: Box<QuestionDef>,
    },
    /// Removes the question `id`.
    RemoveQuestion { id: String },
    /// The whole level at once (a new scene), undoable like any edit.
    Replace(Box<Level>),
}

impl Edit {
    /// Changes `level`, or says why it cannot (a name that is not there, a bad value).
    pub fn apply_to(&self, level: &mut Level) -> Result<String, String> {
        match self {
            Edit::AddGround { y, width } => {
                let name = fresh_name(level, "ground");
                level.bodies.push(ground_body(&name, *y, width / 2.0));
                declare(level, &[Effect::Contacts]);
                Ok(format!("added {name}, a ground line at y = {y} m"))
            }
            Edit::AddWall { x, height } => add_wall(level, x, height),
            Edit::AddIncline { at, angle, length } => add_incline(level, at, angle, length),
            Edit::AddArc {
                center,
                radius,
                start,
                end,
                side,
            } => add_arc(level, center, radius, start, end, side),
            Edit::AddTrack {
                points,
                closed,
                solid,
            } => add_track(level, points, closed, solid),
            Edit::AddBody { shape, at, mass } => add_body(level, shape, at, mass),
            Edit::AddJoint {
                kind,
                body1,
                body2,
                at,
            } => add_joint(level, kind, body1, body2, at),
            Edit::AddSpring {
                body1,
                at1,
                body2,
                at2,
                stiffness,
            } => add_spring(level, body1, at1, body2, at2, stiffness),
            Edit::AddTorsionSpring {
                body1,
                body2,
                stiffness,
            } => add_torsion_spring(level, body1, body2, stiffness),
            Edit::SetMotor { joint, target } => set_motor(level, joint, target),
            Edit::Set {
                body: name,
                property,
            } => set(level, name, property),
            Edit::Delete { body: name } => delete(level, name),
            Edit::Duplicate { body: name, offset } => {
                let mut b = find(level, name)?.clone();
                let copy = fresh_name(level, &format!("{name}_copy"));
                b.name = copy.clone();
                b.position = (b.position.0 + offset.0, b.position.1 + offset.1);
                level.bodies.push(b);
                Ok(format!("added {copy}, a copy of {name}"))
            }
            Edit::SetText { title, statement } => {
                level.title = title.clone();
                level.statement = statement.clone();
                Ok("title and statement set".into())
            }
            Edit::DropExercise => {
                let n = (level.checks.len(), level.questions.len());
                level.checks.clear();
                level.questions.clear();
                Ok(format!(
                    "dropped the exercise's {} checks and {} questions",
                    n.0, n.1
                ))
            }
            Edit::AddQuestion(q) => {
                if level.questions.iter().any(|x| x.id == q.id) {
                    return Err(format!("a question \"{}\" is already there", q.id));
                }
                level.questions.push((**q).clone());
                Ok(format!("asked {}: {}", q.id, q.ask))
            }
            Edit::ReplaceQuestion { index, question } => replace_question(level, index, question),
            Edit::RemoveQuestion { id } => {
                let Some(i) = level.questions.iter().position(|q| &q.id == id) else {
                    return Err(format!("there is no question \"{id}\""));
                };
                level.questions.remove(i);
                Ok(format!("removed question {id}"))
            }
            Edit::Replace(new) => {
                *level = (**new).clone();
                Ok(format!("the scene is now \"{}\"", level.title))
            }
            Edit::SetStep { dt, substeps } => {
                level.world.dt = *dt;
                level.world.substeps = *substeps;
                Ok(format!(
                    "the level steps dt = {dt} s with {substeps} substeps"
                ))
            }
            Edit::SetDuration(d) => {
                level.world.duration = *d;
                Ok(format!("the run lasts {d} s"))
            }
        }
    }
}

/// A fixed wall: a vertical segment at `x` from y = 0 up `height`.
fn add_wall(level: &mut Level, x: &f64, height: &f64) -> Result<String, String> {
    let name = fresh_name(level, "wall");
    let mut b = ground_body(&name, 0.0, 0.0);
    b.position = (*x, 0.0);
    b.shape = Some(Shape::Segment {
        a: (0.0, 0.0),
        b: (0.0, *height),
    });
    level.bodies.push(b);
    declare(level, &[Effect::Contacts]);
    Ok(format!("added {name}, a wall at x = {x} m"))
}

/// A fixed right-triangle wedge rising at `angle` over `length`, its lower corner at `at`.
fn add_incline(level: &mut Level, at: &V2, angle: &f64, length: &f64) -> Result<String, String> {
    if !(*angle > 0.0 && *angle < std::f64::consts::FRAC_PI_2) {
        return Err(format!(
            "an incline's angle must be between 0 and 90 degrees, not {:.1}",
            angle.to_degrees()
        ));
    }
    let name = fresh_name(level, "incline");
    let h = length * angle.tan();
    // Vertices about the lower corner: base along x, the vertical side at the far end.
    let shape = Shape::Polygon {
        points: vec![(0.0, 0.0), (*length, 0.0), (*length, h)],
    };
    level
        .bodies
        .push(body(&name, BodyKind::Fixed, Some(shape), *at));
    declare(level, &[Effect::Contacts]);
    Ok(format!(
        "added {name}, an incline at {:.1} degrees, {length} m long",
        angle.to_degrees()
    ))
}

/// A fixed circular arc track about `center`.
fn add_arc(
    level: &mut Level,
    center: &V2,
    radius: &f64,
    start: &f64,
    end: &f64,
    side: &ArcSide,
) -> Result<String, String> {
    let name = fresh_name(level, "arc");
    let shape = Shape::Arc {
        center: (0.0, 0.0),
        radius: *radius,
        start: *start,
        end: *end,
        side: *side,
        chord_error: None,
    };
    level
        .bodies
        .push(body(&name, BodyKind::Fixed, Some(shape), *center));
    declare(level, &[Effect::Contacts]);
    Ok(format!(
        "added {name}, an arc track of radius {radius} m about ({}, {}) m from {:.1} to {:.1} degrees, ridden on its {}",
        center.0,
        center.1,
        start.to_degrees(),
        end.to_degrees(),
        side_name(*side)
    ))
}

/// A fixed polyline track through `points`.
fn add_track(
    level: &mut Level,
    points: &[V2],
    closed: &bool,
    solid: &Option<TrackSide>,
) -> Result<String, String> {
    let name = fresh_name(level, "track");
    let shape = Shape::Polyline {
        points: points.to_vec(),
        closed: *closed,
        solid: *solid,
    };
    level
        .bodies
        .push(body(&name, BodyKind::Fixed, Some(shape), (0.0, 0.0)));
    declare(level, &[Effect::Contacts]);
    Ok(format!(
        "added {name}, a{} polyline track of {} points{}",
        if *closed { " closed" } else { "n open" },
        points.len(),
        match solid {
            None => ", two-sided".to_string(),
            Some(s) => format!(", solid on its {}", solid_name(*s)),
        }
    ))
}

/// A dynamic body at `at`: a disc is set onto a fixed surface it was placed into; another shape overlapping one is placed with a warning.
fn add_body(level: &mut Level, shape: &NewShape, at: &V2, mass: &f64) -> Result<String, String> {
    let (stem, shape) = match shape {
        NewShape::Box { width, height } => (
            "box",
            Shape::Box {
                width: *width,
                height: *height,
            },
        ),
        NewShape::Disc { radius } => ("disc", Shape::Circle { radius: *radius }),
        NewShape::Bar { length, thickness } => (
            "bar",
            Shape::Box {
                width: *length,
                height: *thickness,
            },
        ),
        NewShape::Polygon { points } => (
            "polygon",
            Shape::Polygon {
                points: points.clone(),
            },
        ),
    };
    let name = fresh_name(level, stem);
    // A disc placed into a fixed body (a click inside an incline's wedge) is set
    // onto the surface under it; another shape is placed as asked, with a warning.
    let (at, placed) = match &shape {
        Shape::Circle { radius } => match snap_disc(level, DVec2::from(*at), *radius) {
            Some((c, onto)) => ((c.x, c.y), format!(", set onto {onto}'s surface")),
            None => (*at, String::new()),
        },
        _ => match overlapped(level, DVec2::from(*at), shapes::inscribed_radius(&shape)) {
            Some(o) => (
                *at,
                format!("; it overlaps {o}: drag it clear while paused at t = 0"),
            ),
            None => (*at, String::new()),
        },
    };
    let mut b = body(&name, BodyKind::Dynamic, Some(shape), at);
    b.mass = Some(*mass);
    level.bodies.push(b);
    let added = declare(level, &[Effect::Gravity, Effect::Contacts]);
    Ok(format!(
        "added {name} ({mass} kg) at ({:.3}, {:.3}) m{placed}{added}",
        at.0, at.1
    ))
}

/// A joint at `at` between `body1` (None: a fixed anchor made there) and `body2`.
fn add_joint(
    level: &mut Level,
    kind: &JointKind,
    body1: &Option<String>,
    body2: &str,
    at: &V2,
) -> Result<String, String> {
    let b2 = find(level, body2)?.clone();
    let (b1, note) = match body1 {
        Some(n) => (find(level, n)?.clone(), String::new()),
        None => {
            let name = fresh_name(level, "anchor");
            let b = body(&name, BodyKind::Fixed, None, *at);
            level.bodies.push(b.clone());
            (b, format!(" to {name}, a fixed point"))
        }
    };
    if b1.name == b2.name {
        return Err(format!(
            "a joint needs two bodies; both ends are on {}",
            b1.name
        ));
    }
    let name = fresh_name(level, joint_stem(*kind));
    level.joints.push(JointDef {
        name: name.clone(),
        kind: *kind,
        body1: b1.name.clone(),
        body2: b2.name.clone(),
        anchor1: local_point(&b1, *at),
        anchor2: local_point(&b2, *at),
        axis: (1.0, 0.0),
        limits: None,
        motor: None,
        starts_apart: false,
    });
    let added = declare(level, &[Effect::Joints]);
    Ok(format!(
        "added {name} joining {} and {}{note}{added}",
        b1.name, b2.name
    ))
}

/// A linear spring, unstretched as the scene starts.
fn add_spring(
    level: &mut Level,
    body1: &str,
    at1: &V2,
    body2: &Option<String>,
    at2: &V2,
    stiffness: &f64,
) -> Result<String, String> {
    let b1 = find(level, body1)?.clone();
    let (p2, b2name) = match body2 {
        Some(n) => {
            let b2 = find(level, n)?;
            (local_point(b2, *at2), Some(b2.name.clone()))
        }
        None => (*at2, None),
    };
    let rest = DVec2::from(*at1).distance(DVec2::from(*at2));
    let name = fresh_name(level, "spring");
    level.springs.push(SpringDef {
        name: name.clone(),
        body1: b1.name.clone(),
        point1: local_point(&b1, *at1),
        body2: b2name,
        point2: p2,
        stiffness: *stiffness,
        rest_length: rest,
        damping: 0.0,
    });
    let added = declare(level, &[Effect::Springs]);
    Ok(format!(
        "added {name}, k = {stiffness} N/m, rest length {rest:.4} m{added}"
    ))
}

/// A torsion spring at rest at the angle the scene starts with.
fn add_torsion_spring(
    level: &mut Level,
    body1: &str,
    body2: &Option<String>,
    stiffness: &f64,
) -> Result<String, String> {
    let b1 = find(level, body1)?.name.clone();
    let b2 = match body2 {
        Some(n) => Some(find(level, n)?.name.clone()),
        None => None,
    };
    if b2.as_deref() == Some(b1.as_str()) {
        return Err(format!(
            "a torsion spring needs two bodies; both ends are on {b1}"
        ));
    }
    let name = fresh_name(level, "coil");
    level.torsion_springs.push(TorsionSpringDef {
        name: name.clone(),
        body1: b1.clone(),
        body2: b2.clone(),
        stiffness: *stiffness,
        rest_angle: None,
        damping: 0.0,
    });
    let added = declare(level, &[Effect::Springs]);
    Ok(format!(
        "added {name}, a torsion spring of k = {stiffness} N m/rad between {b1} and {}, at rest as it starts{added}",
        b2.as_deref().unwrap_or("the ground")
    ))
}

/// A velocity motor on a joint, or none.
fn set_motor(level: &mut Level, joint: &str, target: &Option<f64>) -> Result<String, String> {
    let j = level
        .joints
        .iter_mut()
        .find(|j| j.name == joint)
        .ok_or_else(|| format!("there is no joint named \"{joint}\""))?;
    j.motor = target.map(|t| Motor::Velocity {
        target: t,
        max_force: None,
    });
    let added = if target.is_some() {
        declare(level, &[Effect::Motors])
    } else {
        String::new()
    };
    Ok(match target {
        Some(t) => format!("{joint} drives at {t} per second{added}"),
        None => format!("{joint} has no motor"),
    })
}

/// The question at `index` rewritten, its id kept unique.
fn replace_question(
    level: &mut Level,
    index: &usize,
    question: &QuestionDef,
) -> Result<String, String> {
    if level
        .questions
        .iter()
        .enumerate()
        .any(|(i, x)| i != *index && x.id == question.id)
    {
        return Err(format!("a question \"{}\" is already there", question.id));
    }
    let Some(slot) = level.questions.get_mut(*index) else {
        return Err(format!(
            "there is no question {} (the level has {})",
            index + 1,
            level.questions.len()
        ));
    };
    // The window's question form has no place for typical mistakes: a rewrite that leaves
    // them out keeps the old ones while the question still asks for the same quantity in the
    // same unit (their values are answers to it); a new quantity makes them meaningless.
    let mut question = question.clone();
    if question.mistakes.is_empty()
        && question.quantity == slot.quantity
        && question.unit == slot.unit
    {
        question.mistakes = std::mem::take(&mut slot.mistakes);
    }
    // Nor for the student tolerance: the form writes a placeholder, and a rewrite keeps the
    // level's (until 2026-12-07 every rewrite reset it to 1%).
    question.student_tolerance = slot.student_tolerance;
    *slot = question.clone();
    Ok(format!(
        "question {} rewritten: {}",
        question.id, question.ask
    ))
}

/// A fixed body's outline in world coordinates: a convex polygon counter-clockwise (boxes and
/// polygons) or a segment (two points); None for shapes placement does not look at.
fn fixed_outline(b: &BodyDef) -> Option<Vec<DVec2>> {
    let local = shapes::flat_outline(b.shape.as_ref()?)?;
    let rot = DVec2::from_angle(b.angle);
    let at = DVec2::from(b.position);
    Some(local.into_iter().map(|p| at + rot.rotate(p)).collect())
}

/// The point of an outline nearest to `p`, and whether `p` is inside it (a polygon only).
fn nearest(outline: &[DVec2], p: DVec2) -> (DVec2, bool) {
    let n = outline.len();
    let edges = if n == 2 { 1 } else { n };
    let mut best = (outline[0], f64::INFINITY);
    let mut inside = n >= 3;
    for i in 0..edges {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared().max(1e-300)).clamp(0.0, 1.0);
        let q = a + ab * t;
        let d = (p - q).length();
        if d < best.1 {
            best = (q, d);
        }
        if ab.perp_dot(p - a) < 0.0 {
            inside = false;
        }
    }
    (best.0, inside)
}

/// Where a disc of radius `r` centered at `c` goes when it overlaps a fixed body: moved the
/// least distance to touch the surface nearest its center, outside, and that body's name.
pub(crate) fn snap_disc(level: &Level, c: DVec2, r: f64) -> Option<(DVec2, String)> {
    let mut best: Option<(DVec2, String, f64)> = None;
    for b in level.bodies.iter().filter(|b| b.kind == BodyKind::Fixed) {
        if let Some(moved) = onto_track(b, c, r) {
            let shift = (moved - c).length();
            if best.as_ref().is_none_or(|(_, _, s)| shift > *s) {
                best = Some((moved, b.name.clone(), shift));
            }
            continue;
        }
        let Some(outline) = fixed_outline(b) else {
            continue;
        };
        let (q, inside) = nearest(&outline, c);
        let d = (c - q).length();
        if !inside && d >= r {
            continue;
        }
        if inside {
            // Clicked inside (a disc in an incline's wedge): onto the upward face nearest above,
            // never out through the bottom or a side.
            if let Some(m) = onto_top(&outline, c, r) {
                let shift = (m - c).length();
                if best.as_ref().is_none_or(|(_, _, s)| shift > *s) {
                    best = Some((m, b.name.clone(), shift));
                }
                continue;
            }
        }
        let out = if inside {
            (q - c).normalize_or_zero()
        } else if d > 1e-12 {
            (c - q) / d
        } else {
            // On a ground line or a wall exactly: to its upper (or left) side.
            let ab = outline[outline.len() - 1] - outline[0];
            let n = ab.perp().normalize_or_zero();
            if n.y < 0.0 || (n.y == 0.0 && n.x > 0.0) {
                -n
            } else {
                n
            }
        };
        let moved = q + out * r;
        let shift = (moved - c).length();
        if best.as_ref().is_none_or(|(_, _, s)| shift > *s) {
            best = Some((moved, b.name.clone(), shift));
        }
    }
    best.map(|(c, name, _)| (c, name))
}

/// Where a disc of radius `r` centered at `c` within `r` of a track (`Polyline` or `Arc`) goes:
/// touching the track at its nearest point, on the side bodies ride (a one-sided track's free
/// side; a two-sided one's side the center is on). None when it is clear of the track or `b`
/// is no track.
fn onto_track(b: &BodyDef, c: DVec2, r: f64) -> Option<DVec2> {
    let (points, closed) = curves::track_points(b.shape.as_ref()?)?;
    let rot = DVec2::from_angle(b.angle);
    let at = DVec2::from(b.position);
    let w: Vec<DVec2> = points
        .iter()
        .map(|&p| at + rot.rotate(DVec2::from(p)))
        .collect();
    let edges = if closed {
        w.len()
    } else {
        w.len().saturating_sub(1)
    };
    // The nearest point of the track and the left normal of its edge there.
    let mut best: Option<(DVec2, DVec2, f64)> = None;
    for k in 0..edges {
        let (a, e) = (w[k], w[(k + 1) % w.len()]);
        let ab = e - a;
        let t = ((c - a).dot(ab) / ab.length_squared().max(1e-300)).clamp(0.0, 1.0);
        let q = a + ab * t;
        let d = (c - q).length();
        if best.as_ref().is_none_or(|(_, _, bd)| d < *bd) {
            best = Some((q, ab.perp().normalize_or_zero(), d));
        }
    }
    let (q, left, d) = best?;
    if d >= r {
        return None;
    }
    let ride = match curves::solid_side(b.shape.as_ref()?) {
        Some(true) => -left,
        Some(false) => left,
        None if left.dot(c - q) >= 0.0 => left,
        None => -left,
    };
    // On the riding side, the least move: straight away from the nearest point (at a vertex,
    // between its two edges' normals); from the solid side, out along the edge's normal.
    let out = if d > 1e-12 && ride.dot(c - q) > 0.0 {
        (c - q) / d
    } else {
        ride
    };
    Some(q + out * r)
}

/// A disc of radius `r` centered at `c` inside a convex outline (counter-clockwise), set on the
/// upward-facing edge (outward normal above 10 degrees from horizontal) nearest to it.
fn onto_top(outline: &[DVec2], c: DVec2, r: f64) -> Option<DVec2> {
    let n = outline.len();
    (0..n)
        .filter_map(|i| {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let ab = b - a;
            let normal = DVec2::new(ab.y, -ab.x).normalize_or_zero();
            if normal.y <= 0.17 {
                return None;
            }
            let t = ((c - a).dot(ab) / ab.length_squared().max(1e-300)).clamp(0.0, 1.0);
            Some(a + ab * t + normal * r)
        })
        .min_by(|x, y| (*x - c).length().total_cmp(&(*y - c).length()))
}

/// The first fixed body a new body centered at `c` overlaps, its inscribed radius `r` taken
/// as its size (a box placed on a ground line by its center overlaps it).
fn overlapped(level: &Level, c: DVec2, r: f64) -> Option<String> {
    level
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Fixed)
        .find(|b| {
            fixed_outline(b).is_some_and(|o| {
                let (q, inside) = nearest(&o, c);
                inside || (c - q).length() < r
            })
        })
        .map(|b| b.name.clone())
}

/// A fixed body holding a ground line `half_width` either side of x = 0 at height `y`.
pub(crate) fn ground_body(name: &str, y: f64, half_width: f64) -> BodyDef {
    let mut b = body(name, BodyKind::Fixed, None, (0.0, y));
    if half_width > 0.0 {
        b.shape = Some(Shape::Segment {
            a: (-half_width, 0.0),
            b: (half_width, 0.0),
        });
    }
    b
}

fn body(name: &str, kind: BodyKind, shape: Option<Shape>, at: V2) -> BodyDef {
    BodyDef {
        name: name.into(),
        kind,
        shape,
        position: at,
        angle: 0.0,
        velocity: (0.0, 0.0),
        omega: 0.0,
        mass: None,
        density: None,
        inertia: None,
        radius_of_gyration: None,
        lock_rotation: false,
        friction: None,
        restitution: None,
        linear_damping: None,
        angular_damping: None,
        motion: None,
    }
}

fn joint_stem(kind: JointKind) -> &'static str {
    match kind {
        JointKind::Revolute => "pin",
        JointKind::Prismatic => "slider",
        JointKind::Fixed => "weld",
        JointKind::PinSlot => "pin_slot",
    }
}

/// `stem1`, `stem2`, ...: the first name no body, joint or spring of the level has.
fn fresh_name(level: &Level, stem: &str) -> String {
    let taken = |n: &str| {
        level.bodies.iter().any(|b| b.name == n)
            || level.joints.iter().any(|j| j.name == n)
            || level.springs.iter().any(|s| s.name == n)
    };
    (1..)
        .map(|i| format!("{stem}{i}"))
        .find(|n| !taken(n))
        .expect("an unused name exists")
}

fn find<'a>(level: &'a Level, name: &str) -> Result<&'a BodyDef, String> {
    level
        .bodies
        .iter()
        .find(|b| b.name == name)
        .ok_or_else(|| format!("there is no body named \"{name}\""))
}

/// A world point in a body's frame (where a joint or spring is anchored on it).
fn local_point(b: &BodyDef, world: V2) -> V2 {
    let d = DVec2::from(world) - DVec2::from(b.position);
    let local = DVec2::from_angle(-b.angle).rotate(d);
    (local.x, local.y)
}

/// Declares the effects an edit relies on (promise 3: nothing undeclared runs, so the editor
/// declares what the user adds) and says which were new.
fn declare(level: &mut Level, effects: &[Effect]) -> String {
    let mut added = Vec::new();
    for e in effects {
        if !level.effects.contains(e) {
            level.effects.push(*e);
            added.push(format!("`{}`", e.name()));
        }
    }
    if added.is_empty() {
        String::new()
    } else {
        format!(" (declared {})", added.join(", "))
    }
}

fn set(level: &mut Level, name: &str, property: &Property) -> Result<String, String> {
    let i = level
        .bodies
        .iter()
        .position(|b| b.name == name)
        .ok_or_else(|| format!("there is no body named \"{name}\""))?;
    let mut effects = Vec::new();
    {
        let b = &mut level.bodies[i];
        match property {
            Property::Mass(m) => {
                b.mass = Some(*m);
                b.density = None;
            }
            Property::Density(d) => {
                b.density = Some(*d);
                b.mass = None;
            }
            Property::Width(w) => match &mut b.shape {
                Some(Shape::Box { width, .. }) => *width = *w,
                _ => return Err(format!("{name} is not a box or a bar: it has no width")),
            },
            Property::Height(h) => match &mut b.shape {
                Some(Shape::Box { height, .. }) => *height = *h,
                _ => return Err(format!("{name} is not a box or a bar: it has no height")),
            },
            Property::Radius(r) => match &mut b.shape {
                Some(Shape::Circle { radius }) | Some(Shape::Arc { radius, .. }) => *radius = *r,
                _ => return Err(format!("{name} is not a disc or an arc: it has no radius")),
            },
            Property::ArcCenter(c) => match &mut b.shape {
                Some(Shape::Arc { center, .. }) => *center = *c,
                _ => return Err(not_a(name, "an arc", "center")),
            },
            Property::ArcStart(a) => match &mut b.shape {
                Some(Shape::Arc { start, .. }) => *start = *a,
                _ => return Err(not_a(name, "an arc", "start angle")),
            },
            Property::ArcEnd(a) => match &mut b.shape {
                Some(Shape::Arc { end, .. }) => *end = *a,
                _ => return Err(not_a(name, "an arc", "end angle")),
            },
            Property::Side(s) => match &mut b.shape {
                Some(Shape::Arc { side, .. }) => *side = *s,
                _ => return Err(not_a(name, "an arc", "side")),
            },
            Property::Points(p) => match &mut b.shape {
                Some(Shape::Polyline { points, .. }) | Some(Shape::Polygon { points }) => {
                    *points = p.clone()
                }
                _ => return Err(not_a(name, "a polyline track or a polygon", "points")),
            },
            Property::Closed(c) => match &mut b.shape {
                Some(Shape::Polyline { closed, .. }) => *closed = *c,
                _ => return Err(not_a(name, "a polyline track", "closed flag")),
            },
            Property::Solid(s) => match &mut b.shape {
                Some(Shape::Polyline { solid, .. }) => *solid = *s,
                _ => return Err(not_a(name, "a polyline track", "solid side")),
            },
            Property::Position(p) => b.position = *p,
            Property::Angle(a) => b.angle = *a,
            Property::Velocity(v) => b.velocity = *v,
            Property::Omega(w) => b.omega = *w,
            Property::Friction(mu) => {
                b.friction = (*mu > 0.0).then_some(*mu);
                effects.push(Effect::Friction);
            }
            Property::Restitution(e) => {
                b.restitution = (*e > 0.0).then_some(*e);
                effects.push(Effect::Restitution);
            }
            Property::Kind(k) => b.kind = *k,
        }
    }
    // Declare an effect only while some body uses it; drop it when none does any more.
    let used = |e: Effect, l: &Level| match e {
        Effect::Friction => l.bodies.iter().any(|b| b.friction.is_some()),
        _ => l.bodies.iter().any(|b| b.restitution.is_some()),
    };
    let mut note = format!("{name}: {}", describe(property));
    for e in effects {
        if used(e, level) {
            note += &declare(level, &[e]);
        } else if let Some(k) = level.effects.iter().position(|x| *x == e) {
            level.effects.remove(k);
            note += &format!(" (no body uses `{}` now: undeclared)", e.name());
        }
    }
    Ok(note)
}

fn describe(p: &Property) -> String {
    match p {
        Property::Mass(m) => format!("mass {m} kg"),
        Property::Density(d) => format!("density {d} kg/m^2"),
        Property::Width(w) => format!("width {w} m"),
        Property::Height(h) => format!("height {h} m"),
        Property::Radius(r) => format!("radius {r} m"),
        Property::Position(p) => format!("position ({:.4}, {:.4}) m", p.0, p.1),
        Property::Angle(a) => format!("angle {:.4} rad", a),
        Property::Velocity(v) => format!("velocity ({}, {}) m/s", v.0, v.1),
        Property::Omega(w) => format!("omega {w} rad/s"),
        Property::Friction(mu) => format!("friction {mu}"),
        Property::Restitution(e) => format!("restitution {e}"),
        Property::Kind(k) => format!("kind {k:?}").to_lowercase(),
        Property::ArcCenter(c) => format!("arc center ({}, {}) m", c.0, c.1),
        Property::ArcStart(a) => format!("arc start {:.2} degrees", a.to_degrees()),
        Property::ArcEnd(a) => format!("arc end {:.2} degrees", a.to_degrees()),
        Property::Side(s) => format!("ridden on its {}", side_name(*s)),
        Property::Points(p) => format!("{} points", p.len()),
        Property::Closed(c) => if *c { "closed" } else { "open" }.to_string(),
        Property::Solid(None) => "two-sided".to_string(),
        Property::Solid(Some(s)) => format!("solid on its {}", solid_name(*s)),
    }
}

fn not_a(name: &str, what: &str, field: &str) -> String {
    format!("{name} is not {what}: it has no {field}")
}

/// How the panel and the notes name an arc's side.
pub fn side_name(s: ArcSide) -> &'static str {
    match s {
        ArcSide::Inside => "inside",
        ArcSide::Outside => "outside",
    }
}

/// How the panel and the notes name a polyline's solid side.
pub fn solid_name(s: TrackSide) -> &'static str {
    match s {
        TrackSide::Left => "left",
        TrackSide::Right => "right",
    }
}

/// A track's points typed as text: numbers in x, y order, separated by commas, semicolons,
/// spaces, new lines or parentheses (`-3, 0; 0, 0`, one pair a line, or `(-3, 0), (0, 0)`).
/// An odd count or a word that is not a finite number is refused, saying which.
pub fn parse_points(text: &str) -> Result<Vec<V2>, String> {
    let mut numbers = Vec::new();
    for word in text
        .split(|c: char| c == ',' || c == ';' || c == '(' || c == ')' || c.is_whitespace())
        .filter(|w| !w.is_empty())
    {
        match word.parse::<f64>() {
            Ok(x) if x.is_finite() => numbers.push(x),
            _ => {
                return Err(format!(
                    "`{word}` is not a number (point {}): write each point as x, y in m",
                    numbers.len() / 2
                ))
            }
        }
    }
    if numbers.len() % 2 == 1 {
        return Err(format!(
            "{} numbers: each point needs an x and a y (the last point has no y)",
            numbers.len()
        ));
    }
    Ok(numbers.chunks(2).map(|p| (p[0], p[1])).collect())
}

/// Points as [`parse_points`] reads them back, one `x, y` pair a line.
pub fn points_text(points: &[V2]) -> String {
    points
        .iter()
        .map(|p| format!("{}, {}", p.0, p.1))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Removes a body with its joints, springs, couplings, loads and events, and the checks and
/// questions that name it (their answers were about it), listing what went.
fn delete(level: &mut Level, name: &str) -> Result<String, String> {
    find(level, name)?;
    let quoted = format!("\"{name}\"");
    // The exercise names bodies in many places (45 quantities, groups, partners); the
    // serialized item is the one form where every such name appears, quoted.
    let names = |s: String| s.contains(&quoted);
    let before = (
        level.joints.len() + level.springs.len() + level.torsion_springs.len(),
        level.checks.len(),
        level.questions.len(),
    );
    level.bodies.retain(|b| b.name != name);
    let gone_joints: Vec<String> = level
        .joints
        .iter()
        .filter(|j| j.body1 == name || j.body2 == name)
        .map(|j| j.name.clone())
        .collect();
    level.joints.retain(|j| j.body1 != name && j.body2 != name);
    level
        .springs
        .retain(|s| s.body1 != name && s.body2.as_deref() != Some(name));
    let names_any = |s: String| {
        s.contains(&quoted) || gone_joints.iter().any(|j| s.contains(&format!("\"{j}\"")))
    };
    level.torsion_springs.retain(|s| !names(ron_of(s)));
    // A coupling is over joints' coordinates as well as bodies'.
    level.couplings.retain(|c| !names_any(ron_of(c)));
    level.loads.retain(|l| !names(ron_of(l)));
    level.events.retain(|e| !names(ron_of(e)));
    level.checks.retain(|c| !names_any(ron_of(c)));
    level.questions.retain(|q| !names_any(ron_of(q)));
    let after = (
        level.joints.len() + level.springs.len() + level.torsion_springs.len(),
        level.checks.len(),
        level.questions.len(),
    );
    let mut note = format!("deleted {name}");
    let lost = [
        (before.0 - after.0, "joints and springs"),
        (before.1 - after.1, "checks"),
        (before.2 - after.2, "questions"),
    ];
    let lost: Vec<String> = lost
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    if !lost.is_empty() {
        note += &format!(" with its {}", lost.join(", "));
    }
    Ok(note)
}

/// An item of a level as RON text, for finding the names it mentions.
fn ron_of<T: serde::Serialize>(item: &T) -> String {
    ron::to_string(item).unwrap_or_default()
}
