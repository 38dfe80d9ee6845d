//! A level's challenge (issue 42, "learn by playing"): instead of asking for a number, the level
//! hands the student a control, one of its declared parameters, and a goal the run must meet.
//! `worked` is the control's closed-form value; `rigidlab check` runs it, and `--answer` runs the
//! student's (docs/levels.md#challenges).

use super::*;

/// `challenge: (control: "v0", worked: sqrt(g*R), goal: Reaches(...), ask: "...")`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChallengeDef {
    /// The name of the parameter (in `parameters`) the student sets: its range, step and unit
    /// are the control's.
    pub control: String,
    /// The control's closed-form value, in SI as every expression (a `deg` control's is in
    /// radians): a number, or an expression of the other parameters and `g`.
    pub worked: f64,
    /// What the run must do.
    pub goal: Goal,
    /// What the student is asked to do, in words (the statement says the rest).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub ask: String,
}

/// What a challenge's run must do. A position goal reads the body's mass center G.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Goal {
    /// G is inside `region` at the end of the run. Miss: G's distance to the region, m.
    EndsInside { body: String, region: Region },
    /// G is inside `region` at every step of the run. Miss: G's largest distance outside it, m.
    StaysInside { body: String, region: Region },
    /// G passes within `radius` of `point` at some time (between steps, the straight path
    /// between them). Miss: the closest approach less the radius, m.
    Reaches {
        body: String,
        point: V2,
        radius: f64,
    },
    /// A question's quantity, read at `at` as a question reads it, is `value` within `tolerance`
    /// (relative; absolute when `value` is 0). Miss: the reading's error, as a question's.
    Reads {
        quantity: Quantity,
        #[serde(default)]
        at: When,
        value: f64,
        tolerance: f64,
    },
    /// The pin `joint` takes no impulsive reaction from the `Impulse` event `blow`: its impulse
    /// across the line from the pin to the struck body's G (the joint's `Tangential` impulse
    /// over the blow's step, `JointImpulse` at `AfterEvent`) is at most `tolerance` times the
    /// blow's impulse. Miss: that impulse as a fraction of the blow's.
    PinFeelsNoBlow {
        joint: String,
        blow: String,
        tolerance: f64,
    },
}

/// A region of the plane, world frame, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Region {
    /// The axis-aligned rectangle from `min` to `max` (corners included).
    Rect { min: V2, max: V2 },
    /// The disc of `radius` about `center`.
    Circle { center: V2, radius: f64 },
    /// The ring between `inner` and `outer` radii about `center`.
    Ring { center: V2, inner: f64, outer: f64 },
}

impl Region {
    /// How far the point (x, y) lies outside the region, m: 0 inside or on its edge.
    pub fn distance(&self, p: V2) -> f64 {
        match *self {
            Region::Rect { min, max } => {
                let dx = (min.0 - p.0).max(p.0 - max.0).max(0.0);
                let dy = (min.1 - p.1).max(p.1 - max.1).max(0.0);
                dx.hypot(dy)
            }
            Region::Circle { center, radius } => {
                ((p.0 - center.0).hypot(p.1 - center.1) - radius).max(0.0)
            }
            Region::Ring {
                center,
                inner,
                outer,
            } => {
                let r = (p.0 - center.0).hypot(p.1 - center.1);
                (inner - r).max(r - outer).max(0.0)
            }
        }
    }

    /// The point of the region nearest (x, y): where a miss is drawn to.
    pub fn nearest(&self, p: V2) -> V2 {
        match *self {
            Region::Rect { min, max } => (p.0.clamp(min.0, max.0), p.1.clamp(min.1, max.1)),
            Region::Circle { center, radius } => toward(center, p, 0.0, radius),
            Region::Ring {
                center,
                inner,
                outer,
            } => toward(center, p, inner, outer),
        }
    }
}

/// The point at a distance from `center` clamped to [lo, hi] on the ray toward p.
fn toward(center: V2, p: V2, lo: f64, hi: f64) -> V2 {
    let (dx, dy) = (p.0 - center.0, p.1 - center.1);
    let r = dx.hypot(dy);
    if r == 0.0 {
        return (center.0 + lo, center.1);
    }
    let k = r.clamp(lo, hi) / r;
    (center.0 + dx * k, center.1 + dy * k)
}

impl Goal {
    /// The goal in words, for the report: "ball ends inside the region".
    pub fn describe(&self) -> String {
        match self {
            Goal::EndsInside { body, .. } => format!("{body} ends inside the region"),
            Goal::StaysInside { body, .. } => format!("{body} stays inside the region"),
            Goal::Reaches {
                body,
                point,
                radius,
            } => format!(
                "{body} passes within {radius} m of ({}, {})",
                point.0, point.1
            ),
            Goal::Reads {
                quantity, value, ..
            } => format!("{} reads {value}", quantity.variant_name()),
            Goal::PinFeelsNoBlow { joint, blow, .. } => {
                format!("pin {joint} feels no impulsive reaction at {blow}")
            }
        }
    }

    /// The question a goal read as one is (id "challenge"): a `Reads` goal's quantity at its
    /// moment; a `PinFeelsNoBlow` goal's `JointImpulse(joint, Tangential)` at `AfterEvent(blow)`,
    /// expected 0 within `tolerance` times the blow's impulse (absolute, N s). None for a
    /// position goal.
    pub fn as_question(&self, level: &Level) -> Option<QuestionDef> {
        let (quantity, at, value, tolerance) = match self {
            Goal::Reads {
                quantity,
                at,
                value,
                tolerance,
            } => (quantity.clone(), at.clone(), *value, *tolerance),
            Goal::PinFeelsNoBlow {
                joint,
                blow,
                tolerance,
            } => (
                Quantity::JointImpulse {
                    joint: joint.clone(),
                    component: Component::Tangential,
                },
                When::AfterEvent(blow.clone()),
                0.0,
                tolerance * blow_size(level, blow),
            ),
            _ => return None,
        };
        Some(QuestionDef {
            id: "challenge".into(),
            ask: String::new(),
            unit: quantity.si_unit(level).to_string(),
            expected: value,
            tolerance,
            student_tolerance: tolerance,
            quantity,
            at,
            why: String::new(),
            mistakes: Vec::new(),
        })
    }

    /// The body a position goal follows.
    pub fn body(&self) -> Option<&str> {
        match self {
            Goal::EndsInside { body, .. }
            | Goal::StaysInside { body, .. }
            | Goal::Reaches { body, .. } => Some(body),
            _ => None,
        }
    }
}

/// The size of the impulse of the `Impulse` event named `blow`, N s (NaN when there is none:
/// validation refuses that level).
pub fn blow_size(level: &Level, blow: &str) -> f64 {
    level
        .events
        .iter()
        .find_map(|e| match e {
            EventDef::Impulse { name, impulse, .. } if name == blow => {
                Some(impulse.0.hypot(impulse.1))
            }
            _ => None,
        })
        .unwrap_or(f64::NAN)
}
