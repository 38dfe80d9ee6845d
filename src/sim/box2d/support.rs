//! What the Box2D engine runs exactly, and the located refusal of everything else.
//!
//! rigidlab runs on Box2D only the part of a level it can build and read exactly: rigid bodies
//! (fixed, dynamic, kinematic at constant velocity), circles, boxes, capsules, convex polygons of
//! up to 8 vertices, segments and compounds of these, gravity, friction, restitution, damping,
//! sleeping, continuous collision, pins, sliders and welds without motor or limits, constant or
//! tabled loads in world axes, and impulse events. Everything else (couplings, springs, curved
//! tracks, motors, limits, pins in slots, welds made on contact, prescribed motions, f64) is
//! refused here, before a world is built, with the level item that asks for it: it is never run
//! wrong. docs/engines.md lists the same subset.

use crate::level::{BodyKind, EventDef, JointKind, Level, LevelError, Locator, Precision, Shape};
use std::path::Path;

/// The largest polygon Box2D takes (`B2_MAX_POLYGON_VERTICES`).
const MAX_POLYGON_VERTICES: usize = 8;

/// Where in the level file a refused feature is written.
#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    /// A named item of a top-level list (`bodies`, `joints`, `events`...) and, if known, the
    /// field that asks for the feature.
    Item {
        section: &'static str,
        name: String,
        field: Option<&'static str>,
    },
    /// A field of `world`.
    World(&'static str),
}

/// A feature of the level that the Box2D engine does not run.
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
    pub place: Place,
    /// What is refused: "<the feature, as the docs name it> is not supported by the box2d engine".
    pub message: String,
    /// How to run the level anyway.
    pub help: String,
}

impl Refusal {
    fn item(section: &'static str, name: &str, field: Option<&'static str>, feature: &str) -> Self {
        Refusal {
            place: Place::Item {
                section,
                name: name.to_string(),
                field,
            },
            message: unsupported(feature),
            help: RUN_ON_RAPIER.to_string(),
        }
    }

    /// The refusal as a located level error (exit 2): `text` is the level's source, for the
    /// line and column (None: the file could not be read again, and the error has no position).
    pub fn locate(&self, file: &Path, text: Option<&str>) -> LevelError {
        let pos = text.map_or((0, 0), |t| {
            let loc = Locator::new(t);
            match &self.place {
                Place::Item {
                    section,
                    name,
                    field: Some(f),
                } => loc.field_pos(section, name, f),
                Place::Item { section, name, .. } => loc.item_pos(section, name),
                Place::World(field) => loc.section_field("world", field),
            }
        });
        LevelError::new(file, pos, self.message.clone(), self.help.clone())
    }
}

const RUN_ON_RAPIER: &str =
    "run this level on rapier (--engine rapier, or leave world.engine out); docs/engines.md lists what box2d runs";

fn unsupported(feature: &str) -> String {
    format!("{feature} is not supported by the box2d engine")
}

/// The first feature of `level` that the Box2D engine does not run, if any.
pub fn refusal(level: &Level) -> Option<Refusal> {
    world_refusal(level)
        .or_else(|| level.bodies.iter().find_map(body_refusal))
        .or_else(|| level.joints.iter().find_map(joint_refusal))
        .or_else(|| interaction_refusal(level))
        .or_else(|| level.events.iter().find_map(event_refusal))
}

fn world_refusal(level: &Level) -> Option<Refusal> {
    (level.world.precision == Precision::F64).then(|| Refusal {
        place: Place::World("precision"),
        message: unsupported("f64 precision"),
        help: "Box2D runs in f32 here; leave world.precision out, or run on rapier".into(),
    })
}

fn body_refusal(b: &crate::level::BodyDef) -> Option<Refusal> {
    if b.motion.is_some() {
        return Some(Refusal::item(
            "bodies",
            &b.name,
            Some("motion"),
            "a prescribed motion of a kinematic body",
        ));
    }
    if b.kind == BodyKind::Kinematic && b.omega != 0.0 {
        return Some(Refusal::item(
            "bodies",
            &b.name,
            Some("omega"),
            "a turning kinematic body",
        ));
    }
    let shape = b.shape.as_ref()?;
    shape_refusal(shape, false)
        .map(|feature| Refusal::item("bodies", &b.name, Some("shape"), &feature))
}

/// Why a shape cannot be built in Box2D (None: it can).
fn shape_refusal(shape: &Shape, in_compound: bool) -> Option<String> {
    match shape {
        Shape::Circle { .. }
        | Shape::Box { .. }
        | Shape::Capsule { .. }
        | Shape::Segment { .. } => None,
        Shape::Polygon { points } if points.len() > MAX_POLYGON_VERTICES => Some(format!(
            "a polygon of {} vertices (Box2D takes at most {MAX_POLYGON_VERTICES})",
            points.len()
        )),
        Shape::Polygon { .. } => None,
        Shape::Polyline { .. } => Some("a Polyline track".into()),
        Shape::Arc { .. } => Some("an Arc track".into()),
        Shape::Track { .. } => Some("a Track".into()),
        Shape::Compound { .. } if in_compound => Some("a compound inside a compound".into()),
        Shape::Compound { parts } => parts.iter().find_map(|p| shape_refusal(&p.shape, true)),
    }
}

fn joint_refusal(j: &crate::level::JointDef) -> Option<Refusal> {
    if j.kind == JointKind::PinSlot {
        return Some(Refusal::item(
            "joints",
            &j.name,
            Some("kind"),
            "a pin in a slot (pin_slot joint)",
        ));
    }
    if j.motor.is_some() {
        return Some(Refusal::item(
            "joints",
            &j.name,
            Some("motor"),
            "a joint motor",
        ));
    }
    if j.limits.is_some() {
        return Some(Refusal::item(
            "joints",
            &j.name,
            Some("limits"),
            "joint limits",
        ));
    }
    None
}

/// Couplings, springs and follower loads: what rigidlab applies itself inside the rapier runner.
fn interaction_refusal(level: &Level) -> Option<Refusal> {
    if let Some(c) = level.couplings.first() {
        return Some(Refusal::item(
            "couplings",
            &c.name,
            None,
            "a coupling (pulley, cable, gear)",
        ));
    }
    if let Some(s) = level.springs.first() {
        return Some(Refusal::item(
            "springs",
            &s.name,
            None,
            "a spring (rigidlab's Hooke force)",
        ));
    }
    if let Some(s) = level.torsion_springs.first() {
        return Some(Refusal::item(
            "torsion_springs",
            &s.name,
            None,
            "a torsion spring",
        ));
    }
    level
        .loads
        .iter()
        .find(|l| l.follow_body)
        .map(|l| Refusal::item("loads", &l.name, Some("follow_body"), "a follower load"))
}

/// Refused because this build has no Box2D (the `box2d` cargo feature is off, or wasm32).
pub fn not_built() -> Refusal {
    Refusal {
        place: Place::World("engine"),
        message: "the box2d engine is not in this build (made without the `box2d` feature, or for the web)".into(),
        help: "build natively with default features (cargo build --release), or run on rapier"
            .into(),
    }
}

fn event_refusal(e: &EventDef) -> Option<Refusal> {
    match e {
        EventDef::Impulse { .. } => None,
        EventDef::WeldOnContact { name, .. } => Some(Refusal::item(
            "events",
            name,
            None,
            "a weld made on contact (WeldOnContact)",
        )),
    }
}
