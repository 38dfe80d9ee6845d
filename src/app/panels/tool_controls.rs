//! The tools panel: the mouse tool (select and drag, impulse, set O), spawning a body into the
//! scene, and saving the current state as a level file.

use super::super::physics::Physics;
use super::super::tools::{Tool, ToolState};
use super::super::view::{palette, View};
use super::capture::{save, spawn, Spawn};
use super::{rich, UiState};
use bevy_egui::egui;
use std::path::Path;

/// Draws the panel.
pub(super) fn tool_controls(
    ui: &mut egui::Ui,
    tools: &mut ToolState,
    phys: &mut Physics,
    view: &View,
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
    };
    ui.label(rich(help, palette::OUTLINE).small());
    ui.horizontal(|ui| {
        ui.label("spawn");
        for (name, what) in [
            ("box", Spawn::Box),
            ("disc", Spawn::Disc),
            ("bar", Spawn::Bar),
        ] {
            if ui.button(name).clicked() {
                let (scene, note) = spawn(&phys.scene, phys.snapshot(), what, view, st.spawned);
                st.spawned += 1;
                st.message = Some((note, true));
                let paused = phys.paused;
                // Keep the camera where the user put it: the new body appears in view.
                phys.load_keep_view(scene);
                phys.paused = paused;
            }
        }
    });
    ui.horizontal(|ui| {
        ui.label("save as");
        ui.add(egui::TextEdit::singleline(&mut st.save_path).desired_width(170.0));
        if ui
            .button("Save")
            .on_hover_text("the current state as a level file (checked by loading it back)")
            .clicked()
        {
            st.message = Some(match save(phys, Path::new(&st.save_path)) {
                Ok(m) => (m, true),
                Err(e) => (e, false),
            });
        }
    });
}
