//! A level from a running scene, and a level's file text checked before it is written.
//!
//! [`capture`] turns the state of a run into a level that starts at that moment (the window's
//! "save this moment"); [`checked_text`] is the level as RON, refused unless it loads back
//! identically, so nothing is written that rigidlab would not read back as the scene on screen.

use crate::level::{self, BodyKind, Level, Scene};
use crate::snapshot::Snapshot;
use std::path::Path;

/// The current state as a level (t becomes 0): poses and velocities from the snapshot; events still
/// to come are shifted; checks and questions, which are about the exercise from its start, are
/// kept only at t = 0.
pub fn capture(level: &Level, s: &Snapshot) -> Level {
    let mut out = level.clone();
    if s.step == 0 {
        return out;
    }
    let t = s.time;
    for (def, b) in out.bodies.iter_mut().zip(&s.bodies) {
        def.position = (b.position.x, b.position.y);
        def.angle = b.angle;
        if def.kind == BodyKind::Dynamic {
            def.velocity = (b.velocity.x, b.velocity.y);
            def.omega = b.omega;
        }
    }
    // Impulses still to come keep their time from now; a weld on contact stays armed (bodies
    // already welded and touching weld again at once).
    out.events.retain(|e| match e {
        level::EventDef::Impulse { at, .. } => *at >= t,
        _ => true,
    });
    for e in out.events.iter_mut() {
        if let level::EventDef::Impulse { at, .. } = e {
            *at -= t;
        }
    }
    let remaining = out.world.duration - t;
    out.world.duration = if remaining >= 0.5 {
        remaining
    } else {
        out.world.duration
    };
    // Load tables continue from now: the value at t first, then the rows still to come.
    for l in out.loads.iter_mut() {
        if let Some(level::Profile::Table(rows)) = &mut l.force {
            let now = level::profiles::vector_profile_at(&level::Profile::Table(rows.clone()), t);
            let mut new = vec![(0.0, now)];
            new.extend(
                rows.iter()
                    .filter(|(ti, _)| *ti > t)
                    .map(|(ti, v)| (ti - t, *v)),
            );
            *rows = new;
        }
        if let Some(level::Profile::Table(rows)) = &mut l.torque {
            let now = level::profiles::scalar_profile_at(&level::Profile::Table(rows.clone()), t);
            let mut new = vec![(0.0, now)];
            new.extend(
                rows.iter()
                    .filter(|(ti, _)| *ti > t)
                    .map(|(ti, v)| (ti - t, *v)),
            );
            *rows = new;
        }
    }
    out.checks.clear();
    out.questions.clear();
    out
}

/// The level's file text, if it loads back from `path` as the same level: it must parse,
/// validate and be equal; else why not, for the status line.
pub fn checked_text(scene: &Scene, path: &Path) -> Result<String, String> {
    let level = &scene.level;
    let text = level::to_ron(level);
    let back = level::parse(path, &text)
        .map_err(|e| format!("not saved: the level would not load back:\n{e}"))?;
    if &back.level != level {
        return Err("not saved: the level read back differs from the scene".into());
    }
    Ok(text)
}
