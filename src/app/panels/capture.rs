//! The current state as a level file: [`capture`] turns the running scene into a level that
//! starts now, the tools panel spawns bodies into it, and [`save`] writes it after checking that
//! it loads back identically.

use super::super::physics::Physics;
use super::super::view::View;
use crate::level::{self, BodyDef, BodyKind, Effect, Level, Scene, Shape};
use crate::snapshot::Snapshot;
use bevy::prelude::*;
use std::path::Path;

#[derive(Debug, Clone, Copy)]
pub(super) enum Spawn {
    Box,
    Disc,
    Bar,
}

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
            let now = crate::sim::sample2(&level::Profile::Table(rows.clone()), t);
            let mut new = vec![(0.0, now)];
            new.extend(
                rows.iter()
                    .filter(|(ti, _)| *ti > t)
                    .map(|(ti, v)| (ti - t, *v)),
            );
            *rows = new;
        }
        if let Some(level::Profile::Table(rows)) = &mut l.torque {
            let now = crate::sim::sample1(&level::Profile::Table(rows.clone()), t);
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

pub(super) fn spawn(
    scene: &Scene,
    s: &Snapshot,
    what: Spawn,
    view: &View,
    n: usize,
) -> (Scene, String) {
    let mut level = capture(&scene.level, s);
    let size = view.scene_size();
    let top = view.to_world(Vec2::new(
        view.viewport.center().x,
        view.viewport.min.y + 0.2 * view.viewport.height(),
    ));
    let (name, shape) = match what {
        Spawn::Box => (
            "box",
            Shape::Box {
                width: 0.12 * size,
                height: 0.08 * size,
            },
        ),
        Spawn::Disc => (
            "disc",
            Shape::Circle {
                radius: 0.05 * size,
            },
        ),
        Spawn::Bar => (
            "bar",
            Shape::Box {
                width: 0.35 * size,
                height: 0.03 * size,
            },
        ),
    };
    let mut name = format!("{name}{}", n + 1);
    while level.bodies.iter().any(|b| b.name == name) {
        name.push('_');
    }
    level.bodies.push(BodyDef {
        name: name.clone(),
        kind: BodyKind::Dynamic,
        shape: Some(shape),
        position: (top.x, top.y),
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
    });
    let mut note = format!("spawned {name}");
    for e in [Effect::Gravity, Effect::Contacts] {
        if !level.effects.contains(&e) {
            level.effects.push(e);
            note += &format!(" (turned on `{}`)", e.name());
        }
    }
    if s.step > 0 {
        note += "; the scene restarts from the current state (checks and questions apply from t = 0 only)";
    }
    (
        Scene {
            file: scene.file.clone(),
            level,
        },
        note,
    )
}

/// Writes the current state as a level and reads it back: it must parse, validate, and be equal.
pub fn save(phys: &Physics, path: &Path) -> Result<String, String> {
    let level = capture(&phys.scene.level, phys.snapshot());
    let text = level::to_ron(&level);
    let back = level::parse(path, &text)
        .map_err(|e| format!("not saved: the level would not load back:\n{e}"))?;
    if back.level != level {
        return Err("not saved: the level read back differs from the scene".into());
    }
    let done = super::super::user_files::deliver(path, text.as_bytes(), "text/plain")?;
    Ok(format!("{done} (loads back identically)"))
}

/// The file name the save field starts with: the level's own stem with `-saved`.
pub(super) fn default_save_path(scene: &Scene) -> String {
    let stem = scene
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "scene".into());
    format!("{stem}-saved.ron")
}
