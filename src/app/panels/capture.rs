//! The current state as a level file: [`capture`] turns the running scene into a level that
//! starts now, and [`save`] writes it after checking that it loads back identically.

use super::super::physics::Physics;
use crate::level::{self, BodyKind, Level, Scene};
use crate::snapshot::Snapshot;
use std::path::{Path, PathBuf};

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
            let now = crate::sim::vector_profile_at(&level::Profile::Table(rows.clone()), t);
            let mut new = vec![(0.0, now)];
            new.extend(
                rows.iter()
                    .filter(|(ti, _)| *ti > t)
                    .map(|(ti, v)| (ti - t, *v)),
            );
            *rows = new;
        }
        if let Some(level::Profile::Table(rows)) = &mut l.torque {
            let now = crate::sim::scalar_profile_at(&level::Profile::Table(rows.clone()), t);
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

/// Writes the current state as a level (t becomes 0; at t = 0 the scene as edited).
pub fn save(phys: &Physics, path: &Path) -> Result<String, String> {
    let level = capture(&phys.scene.level, phys.snapshot());
    save_level(
        &Scene {
            file: phys.scene.file.clone(),
            level,
        },
        path,
    )
}

/// Writes a level and reads it back: it must parse, validate, and be equal; then it goes to the
/// user's file (a download in the browser). A file already at `path` is kept: the level goes under
/// a numbered name beside it (`user_files::deliver`).
pub fn save_level(scene: &Scene, path: &Path) -> Result<String, String> {
    save_level_as(scene, path).map(|(_, m)| m)
}

/// [`save_level`], with the file the level was written to.
pub fn save_level_as(scene: &Scene, path: &Path) -> Result<(PathBuf, String), String> {
    let level = &scene.level;
    let text = level::to_ron(level);
    let back = level::parse(path, &text)
        .map_err(|e| format!("not saved: the level would not load back:\n{e}"))?;
    if &back.level != level {
        return Err("not saved: the level read back differs from the scene".into());
    }
    let (used, done) = super::super::user_files::deliver_as(path, text.as_bytes(), "text/plain")?;
    Ok((used, format!("{done} (loads back identically)")))
}

/// The file name the save field starts with: the level's own stem with `-saved`, in the folder
/// the level browser lists (natively; the page downloads it).
pub(super) fn default_save_path(scene: &Scene) -> String {
    let stem = scene
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "scene".into());
    if cfg!(target_arch = "wasm32") {
        format!("{stem}-saved.ron")
    } else {
        format!(
            "{}/{stem}-saved.ron",
            super::super::user_files::SAVED_LEVELS
        )
    }
}
