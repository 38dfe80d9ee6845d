//! The tools panel: the mouse tool (select and drag, impulse, set O) and saving the current state
//! (mid-run) as a level file; building scenes is the build panel's (scene_editor.rs).

use super::super::run::Run;
use super::super::tools::{Tool, ToolState};
use super::super::ui::{fixed_rows, rich};
use super::super::user_files::save_level;
use super::super::view::palette;
use super::state::UiState;
use bevy_egui::egui;
use std::path::Path;

/// Draws the panel.
pub(super) fn tool_controls(
    ui: &mut egui::Ui,
    tools: &mut ToolState,
    phys: &Run,
    st: &mut UiState,
) {
    ui.heading("Tools");
    ui.horizontal(|ui| {
        ui.selectable_value(&mut tools.tool, Tool::Select, "1 select / drag");
        ui.selectable_value(&mut tools.tool, Tool::Impulse, "2 impulse");
        ui.selectable_value(&mut tools.tool, Tool::SetOrigin, "3 set O");
    });
    let help = match tools.tool {
        Tool::Select => {
            "click a body to select it and a point on it (v_P, IC lines); drag it while playing"
        }
        Tool::Impulse => {
            "click-drag on a body: J = m × drag / 0.5 s at the clicked point, applied on release"
        }
        Tool::SetOrigin => "click: the point O for the angular momentum H_O",
        _ => "a build tool (see Build below)",
    };
    // Hints of different lengths in the same height, and the save button always there (greyed
    // at t = 0): the Build tools below never move under the pointer.
    fixed_rows(ui, 2.0, |ui| ui.label(rich(help, palette::OUTLINE).small()));
    let t = phys.snapshot().time;
    if ui
        .add_enabled(
            t > 0.0,
            egui::Button::new(format!("save this moment (t = {t:.3} s) as a level")),
        )
        .on_hover_text("the bodies' poses and velocities now become the new level's start")
        .on_disabled_hover_text("play the run first: the moment is saved as a new level's start")
        .clicked()
    {
        let stem = st.save_path.trim_end_matches(".ron").to_string();
        let path = format!("{stem}-at-{t:.3}s.ron");
        // The bodies' poses and velocities now as the new level's start (t = 0 at the scene as
        // edited).
        let scene = crate::level::Scene {
            file: phys.scene.file.clone(),
            level: crate::editor::capture(&phys.scene.level, phys.snapshot()),
        };
        st.message = Some(match save_level(&scene, Path::new(&path)) {
            Ok(m) => (m, true),
            Err(e) => (e, false),
        });
    }
}
