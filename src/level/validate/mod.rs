//! Semantic validation: ranges, names, finiteness, and effects.
//!
//! Every error names the offending item's line and says how to fix it.

use super::error::{LevelError, Locator};
use super::format::*;
use std::collections::{HashMap, HashSet};
use std::path::Path;

mod bodies;
mod challenge;
mod effects;
mod events;
mod exercise;
mod forces;
mod hints;
mod joints;

use bodies::*;
use challenge::*;
use effects::*;
use events::*;
pub(crate) use exercise::mistake_is_answer;
/// The named items a question's quantity refers to (the window's predict-first mode shows the body).
pub use exercise::quantity_refs;
use exercise::*;
use forces::*;
use hints::*;
use joints::*;

struct V<'a> {
    file: &'a Path,
    loc: Locator<'a>,
    level: &'a Level,
    /// The bodies and joints by name (the first of a name), built once: a search of the list
    /// for every reference was quadratic in a long chain (30,000 pins: 2.0 s, 0.09 s for 5,000).
    bodies: HashMap<&'a str, &'a BodyDef>,
    joints: HashMap<&'a str, &'a JointDef>,
}

type R = Result<(), LevelError>;

impl V<'_> {
    fn err(
        &self,
        pos: (usize, usize),
        msg: impl Into<String>,
        help: impl Into<String>,
    ) -> LevelError {
        LevelError::new(self.file, pos, msg, help)
    }

    fn has(&self, e: Effect) -> bool {
        self.level.effects.contains(&e)
    }

    fn need(&self, e: Effect, pos: (usize, usize), what: &str) -> R {
        if self.has(e) {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!(
                    "{what}, but the level does not declare the `{}` effect",
                    e.name()
                ),
                format!("add `{}` to `effects: [...]`, or remove it", e.name()),
            ))
        }
    }

    fn finite(&self, x: f64, what: &str, pos: (usize, usize)) -> R {
        if x.is_finite() {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!("{what} is {x}, not a finite number"),
                "write a finite number (NaN and inf are not allowed)",
            ))
        }
    }

    fn finite2(&self, v: V2, what: &str, pos: (usize, usize)) -> R {
        self.finite(v.0, what, pos)?;
        self.finite(v.1, what, pos)
    }

    fn positive(&self, x: f64, what: &str, unit: &str, pos: (usize, usize)) -> R {
        self.finite(x, what, pos)?;
        if x > 0.0 {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!("{what} must be positive, got {x} {unit}"),
                format!("give a value > 0 {unit}"),
            ))
        }
    }

    fn non_negative(&self, x: f64, what: &str, unit: &str, pos: (usize, usize)) -> R {
        self.finite(x, what, pos)?;
        if x >= 0.0 {
            Ok(())
        } else {
            Err(self.err(
                pos,
                format!("{what} must not be negative, got {x} {unit}"),
                format!("give a value >= 0 {unit}"),
            ))
        }
    }

    fn unique<'n>(&self, section: &str, names: impl Iterator<Item = &'n str>) -> R {
        let mut seen = HashSet::new();
        for n in names {
            if n.trim().is_empty() {
                return Err(self.err(
                    self.loc.section(section),
                    format!("an item in `{section}` has an empty name"),
                    "give every item a name",
                ));
            }
            if !seen.insert(n) {
                // Point at the second occurrence.
                let first = self.loc.duplicate_pos(section, n);
                return Err(self.err(
                    first,
                    format!("the name \"{n}\" is used twice in `{section}`"),
                    "give each item its own name",
                ));
            }
        }
        Ok(())
    }

    fn body_ref(
        &self,
        name: &str,
        section: &str,
        item: &str,
        field: &str,
    ) -> Result<&BodyDef, LevelError> {
        self.bodies.get(name).copied().ok_or_else(|| {
            let known: Vec<_> = self
                .level
                .bodies
                .iter()
                .map(|b| format!("\"{}\"", b.name))
                .collect();
            self.err(
                self.loc.field_pos(section, item, field),
                format!("{field} names the body \"{name}\", which does not exist"),
                format!("use one of the bodies: {}", known.join(", ")),
            )
        })
    }
}

pub fn validate(file: &Path, text: &str, level: &Level) -> R {
    let v = V {
        file,
        loc: Locator::new(text),
        level,
        bodies: level
            .bodies
            .iter()
            .rev()
            .map(|b| (b.name.as_str(), b))
            .collect(),
        joints: level
            .joints
            .iter()
            .rev()
            .map(|j| (j.name.as_str(), j))
            .collect(),
    };
    world(&v)?;
    hints_and_solution(&v)?;
    v.unique("bodies", level.bodies.iter().map(|b| b.name.as_str()))?;
    v.unique("joints", level.joints.iter().map(|j| j.name.as_str()))?;
    // Linear and torsion springs share one name space: a quantity names either.
    v.unique(
        "springs",
        level
            .springs
            .iter()
            .map(|s| s.name.as_str())
            .chain(level.torsion_springs.iter().map(|t| t.name.as_str())),
    )?;
    v.unique("couplings", level.couplings.iter().map(|c| c.name.as_str()))?;
    v.unique("loads", level.loads.iter().map(|l| l.name.as_str()))?;
    v.unique("events", level.events.iter().map(|e| e.name()))?;
    v.unique("questions", level.questions.iter().map(|q| q.id.as_str()))?;
    if level.bodies.is_empty() {
        return Err(v.err(
            v.loc.section("bodies"),
            "the level has no bodies",
            "add at least one body to `bodies: [...]`",
        ));
    }
    for b in &level.bodies {
        body(&v, b)?;
    }
    for j in &level.joints {
        joint(&v, j)?;
    }
    for s in &level.springs {
        spring(&v, s)?;
    }
    for t in &level.torsion_springs {
        torsion_spring(&v, t)?;
    }
    for c in &level.couplings {
        coupling(&v, c)?;
    }
    for l in &level.loads {
        load(&v, l)?;
    }
    for e in &level.events {
        event(&v, e)?;
    }
    if let Some(c) = &level.challenge {
        challenge(&v, c)?;
    }
    for (i, c) in level.checks.iter().enumerate() {
        check(&v, i, c)?;
    }
    for q in &level.questions {
        question(&v, q)?;
    }
    effects_consistent(&v)
}

fn world(v: &V) -> R {
    let w = &v.level.world;
    let at = |f: &str| v.loc.section_field("world", f);
    v.positive(w.dt, "world.dt", "s", at("dt"))?;
    if w.dt > 0.1 {
        return Err(v.err(
            at("dt"),
            format!("world.dt = {} s is too large for a rigid-body step", w.dt),
            "use a step of at most 0.1 s (1/60 is rapier's default)",
        ));
    }
    v.positive(w.duration, "world.duration", "s", at("duration"))?;
    if w.duration / w.dt > 1e7 {
        return Err(v.err(
            at("duration"),
            "world.duration / world.dt exceeds 1e7 steps",
            "shorten the duration or lengthen the step",
        ));
    }
    if w.substeps == 0 || w.substeps > 1000 {
        return Err(v.err(
            at("substeps"),
            format!("world.substeps = {} is out of range", w.substeps),
            "use 1 to 1000 substeps (rapier's default is 4)",
        ));
    }
    if w.solver_iterations == 0 || w.solver_iterations > 1000 {
        return Err(v.err(
            at("solver_iterations"),
            format!(
                "world.solver_iterations = {} is out of range",
                w.solver_iterations
            ),
            "use 1 to 1000 iterations (rapier's default is 1)",
        ));
    }
    if let Some(hz) = w.contact_hz {
        v.positive(hz, "world.contact_hz", "Hz", at("contact_hz"))?;
        // rapier's contact bias needs the spring resolved by the step: beyond 1/(2 dt) (Nyquist)
        // the softness saturates; 1e6 Hz is rapier's own "rigid" joint setting.
        if hz > 1e6 {
            return Err(v.err(
                at("contact_hz"),
                format!("world.contact_hz = {hz} Hz is out of range"),
                "use 0 < contact_hz <= 1e6 Hz (rapier's default is 30 Hz)",
            ));
        }
    }
    if let Some(g) = w.gravity {
        v.finite2(g, "world.gravity", at("gravity"))?;
        if g != (0.0, 0.0) {
            v.need(Effect::Gravity, at("gravity"), "world.gravity is set")?;
        }
    }
    Ok(())
}
