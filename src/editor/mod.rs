//! The scene editor's core: edits of a level, each checked by the validator, with undo and redo.
//!
//! The editor works on the level's t = 0 state (the exercise as written), never on a state in the
//! middle of a run: every edit gives a new level, which must load as `rigidlab check` would load
//! it (a level that does not validate is refused and the scene stays as it was), and the run
//! starts over from it. So a scene built in the window is a valid level file by construction.
//! The window (`app::editor`) sends [`Edit`]s; tests send the same ones without a window.

pub mod capture;
mod edit;
mod history;

pub use capture::{capture, checked_text};
pub use edit::{parse_points, points_text, side_name, solid_name, Edit, NewShape, Property};
pub use history::History;

use crate::level::{self, Level, Scene};

/// Applies one edit to a scene: the edited level if it validates, with a note for the user
/// (what was added, which effects were declared, what was dropped), else the validator's
/// message. The scene given is not changed.
pub fn apply(scene: &Scene, e: &Edit) -> Result<(Scene, String), String> {
    let mut level = scene.level.clone();
    let note = e.apply_to(&mut level)?;
    let scene = validated(scene, level)?;
    Ok((scene, note))
}

/// The level as a scene if it loads back: written as RON and read with the file's own reader
/// and validator, so what the editor accepts is what `rigidlab check` accepts.
pub fn validated(scene: &Scene, level: Level) -> Result<Scene, String> {
    let text = level::to_ron(&level);
    match level::parse(&scene.file, &text) {
        Ok(back) => Ok(back),
        Err(e) => Err(format!(
            "not applied: the scene would not be a valid level: {}; {}",
            e.message, e.help
        )),
    }
}

/// A new scene: a ground line 8 m wide at y = 0 and nothing else, gravity declared (new bodies
/// are sized for the scene: an 8 m ground gives a 2 m bar and a 0.5 m box).
pub fn empty_scene(file: std::path::PathBuf) -> Scene {
    let level = Level {
        title: "My scene".into(),
        source: Default::default(),
        statement: String::new(),
        hints: Vec::new(),
        solution: String::new(),
        effects: vec![level::Effect::Gravity, level::Effect::Contacts],
        world: level::World {
            duration: 5.0,
            ..Default::default()
        },
        bodies: vec![edit::ground_body("ground", 0.0, 4.0)],
        joints: vec![],
        springs: vec![],
        torsion_springs: vec![],
        couplings: vec![],
        loads: vec![],
        events: vec![],
        challenge: None,
        checks: vec![],
        questions: vec![],
        predict_first: false,
    };
    Scene { file, level }
}
