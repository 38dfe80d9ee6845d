//! The build panel: new scene, undo and redo, the place / join / spring tools, an inspector for
//! the selected body, the level's title and statement, and saving. Every change goes to the
//! editor as an [`EditorCommand`] (app/editor.rs), which validates it and restarts the run.

use super::super::editor::{joint_name, Editor, EditorCommand, Placeable};
use super::super::run::Run;
use super::super::tools::{Tool, ToolState};
use super::super::ui::{fixed_rows, rich};
use super::super::view::palette;
use super::number_field::{number_field, Accepts};
use super::state::UiState;
use crate::editor::{Edit, Property};
use crate::level::{BodyDef, BodyKind, JointKind, Level, Shape};
use bevy_egui::egui;
use std::path::PathBuf;

/// Draws the panel; the commands it sends are in `out`.
pub(super) fn scene_editor(
    ui: &mut egui::Ui,
    phys: &Run,
    editor: &Editor,
    tools: &mut ToolState,
    selected: Option<usize>,
    st: &mut UiState,
    out: &mut Vec<EditorCommand>,
) {
    ui.heading("Build");
    history_buttons(ui, editor, st, out);
    tool_buttons(ui, tools, st);
    tool_hint(ui, tools);
    let r = egui::CollapsingHeader::new("curved track: arc, polyline")
        .id_salt("curved track")
        .show(ui, |ui| {
            super::track_editor::add_tracks(ui, &mut st.buttons, out)
        });
    st.buttons
        .insert("curved track".into(), r.header_response.rect);
    edit_note(ui, editor);

    let level = &phys.scene.level;
    if let Some(b) = selected.and_then(|i| level.bodies.get(i)) {
        ui.separator();
        inspector(ui, b, out);
        motors(ui, level, &b.name, out);
    }

    ui.separator();
    exercise_section(ui, level, editor, st, out);
    save_row(ui, st, out);
}

/// New scene, undo and redo.
fn history_buttons(
    ui: &mut egui::Ui,
    editor: &Editor,
    st: &mut UiState,
    out: &mut Vec<EditorCommand>,
) {
    ui.horizontal(|ui| {
        let r = ui
            .button("new scene")
            .on_hover_text("a ground line and nothing else");
        st.buttons.insert("new scene".into(), r.rect);
        if r.clicked() {
            out.push(EditorCommand::New);
        }
        if ui
            .add_enabled(editor.history.can_undo(), egui::Button::new("⟲ undo"))
            .on_hover_text("Ctrl+Z")
            .clicked()
        {
            out.push(EditorCommand::Undo);
        }
        if ui
            .add_enabled(editor.history.can_redo(), egui::Button::new("⟳ redo"))
            .on_hover_text("Ctrl+Y or Ctrl+Shift+Z")
            .clicked()
        {
            out.push(EditorCommand::Redo);
        }
    });
}

/// The place and join tools, each button's rect kept for the tour and the tests.
fn tool_buttons(ui: &mut egui::Ui, tools: &mut ToolState, st: &mut UiState) {
    ui.horizontal_wrapped(|ui| {
        ui.label("place");
        for p in Placeable::ALL {
            let r = ui.selectable_value(&mut tools.tool, Tool::Place(p), p.name());
            st.buttons.insert(format!("place {}", p.name()), r.rect);
        }
        let r = ui.selectable_value(&mut tools.tool, Tool::Polygon, "polygon");
        st.buttons.insert("place polygon".into(), r.rect);
        let r = ui
            .selectable_value(&mut tools.tool, Tool::Track, "track")
            .on_hover_text("a fixed polyline track, point by point");
        st.buttons.insert("place track".into(), r.rect);
    });
    ui.horizontal_wrapped(|ui| {
        ui.label("join");
        for k in [JointKind::Revolute, JointKind::Prismatic, JointKind::Fixed] {
            let r = ui.selectable_value(&mut tools.tool, Tool::Join(k), joint_name(k));
            st.buttons.insert(format!("join {}", joint_name(k)), r.rect);
        }
        let r = ui.selectable_value(&mut tools.tool, Tool::Spring, "spring");
        st.buttons.insert("spring".into(), r.rect);
        let r = ui.selectable_value(&mut tools.tool, Tool::Torsion, "torsion");
        st.buttons.insert("torsion".into(), r.rect);
    });
}

/// What the chosen tool does, in rows of a fixed height.
fn tool_hint(ui: &mut egui::Ui, tools: &ToolState) {
    let hint = match tools.tool {
        Tool::Place(_) => "click in the scene to place it (1 kg; set its mass below)",
        Tool::Join(_) => {
            "click where two bodies overlap to join them there; on one body alone, it is joined to the ground"
        }
        Tool::Spring => "drag from a point on a body to a point on another body or the ground",
        Tool::Torsion => {
            "click a body: a torsion spring to the body under it, or to the ground, at rest as it starts"
        }
        Tool::Polygon => {
            "click its corners (the outline is their convex hull), then the first corner again or Enter; Escape drops it"
        }
        Tool::Track => {
            "click the track's points (bodies ride its upper side), then the last point again or Enter; Escape drops it"
        }
        _ => "select a body to edit it; while paused at t = 0, drag it to move it",
    };
    fixed_rows(ui, 2.0, |ui| ui.label(rich(hint, palette::OUTLINE).small()));
}

/// The editor's answer to the last edit.
fn edit_note(ui: &mut egui::Ui, editor: &Editor) {
    // The editor's answer to the last edit, in a place of its own height: it appeared with the
    // first edit and moved the inspector below it under the pointer.
    fixed_rows(ui, 2.0, |ui| {
        let Some((note, ok)) = &editor.note else {
            return;
        };
        // A refusal can run to several lines (the validator says how to fix the level): its
        // first clause here, the whole of it on hover.
        let (short, cut) = if *ok {
            (note.clone(), false)
        } else {
            first_clause(note)
        };
        let color = if *ok {
            palette::GRAVITY
        } else {
            palette::NORMAL
        };
        let r = ui.label(rich(short, color));
        if cut {
            r.on_hover_text(note.as_str());
        }
    });
}

/// The level's title, statement and exercise (questions and checks).
fn exercise_section(
    ui: &mut egui::Ui,
    level: &Level,
    editor: &Editor,
    st: &mut UiState,
    out: &mut Vec<EditorCommand>,
) {
    egui::CollapsingHeader::new("title, statement, exercise").show(ui, |ui| {
        if st.edit_title.is_none() {
            st.edit_title = Some((level.title.clone(), level.statement.clone()));
        }
        if let Some((title, statement)) = st.edit_title.as_mut() {
            ui.add(egui::TextEdit::singleline(title).hint_text("title"));
            ui.add(
                egui::TextEdit::multiline(statement)
                    .hint_text("the problem as you would set it, givens with units")
                    .desired_rows(3),
            );
            if ui.button("set title and statement").clicked() {
                out.push(EditorCommand::Apply(Edit::SetText {
                    title: title.clone(),
                    statement: statement.clone(),
                }));
            }
        }
        let (nc, nq) = (level.checks.len(), level.questions.len());
        if nc + nq > 0 {
            ui.label(format!(
                "the exercise has {nq} question(s) and {nc} check(s): an answer worked out for the scene before an edit may no longer hold (preview them in Questions)"
            ));
            if ui.button("drop them").clicked() {
                out.push(EditorCommand::Apply(Edit::DropExercise));
            }
        }
        ui.separator();
        super::questions_editor::questions(ui, level, editor, out);
    });
}

/// The save-as path and its button.
fn save_row(ui: &mut egui::Ui, st: &mut UiState, out: &mut Vec<EditorCommand>) {
    ui.horizontal(|ui| {
        ui.label("save as");
        ui.add(egui::TextEdit::singleline(&mut st.save_path).desired_width(170.0));
        if ui
            .button("Save")
            .on_hover_text("the scene as it starts (t = 0), as a level file that `rigidlab check` runs; checked by loading it back")
            .clicked()
        {
            out.push(EditorCommand::Save(PathBuf::from(&st.save_path)));
        }
    });
}

/// Editable fields of one body. A field commits on Enter or when the focus leaves it, and only
/// a value it accepts (number_field.rs); a committed field sends one `Set`.
fn inspector(ui: &mut egui::Ui, b: &BodyDef, out: &mut Vec<EditorCommand>) {
    let name = b.name.clone();
    let mut set = |p: Property| {
        out.push(EditorCommand::Apply(Edit::Set {
            body: name.clone(),
            property: p,
        }))
    };
    let field = |ui: &mut egui::Ui, what: &str, x: f64, a: &Accepts| {
        number_field(
            ui,
            egui::Id::new(("inspector", b.name.as_str(), what)),
            x,
            a,
        )
    };
    ui.label(egui::RichText::new(format!("{} ({})", b.name, kind_name(b.kind))).strong());
    egui::Grid::new("inspector").num_columns(2).show(ui, |ui| {
        if b.kind == BodyKind::Dynamic {
            if let Some(m) = b.mass {
                ui.label("mass, kg");
                if let Some(m) = field(ui, "mass", m, &Accepts::above(0.0, 1e9, "kg")) {
                    set(Property::Mass(m));
                }
                ui.end_row();
            } else {
                let d = b.density.unwrap_or(crate::level::DEFAULT_DENSITY);
                ui.label("density, kg/m²");
                if let Some(d) = field(ui, "density", d, &Accepts::above(0.0, 1e9, "kg/m²")) {
                    set(Property::Density(d));
                }
                ui.end_row();
            }
        }
        let size = Accepts::above(0.0, 1e4, "m");
        match &b.shape {
            Some(Shape::Box { width, height }) => {
                ui.label("width × height, m");
                ui.horizontal(|ui| {
                    if let Some(w) = field(ui, "width", *width, &size) {
                        set(Property::Width(w));
                    }
                    if let Some(h) = field(ui, "height", *height, &size) {
                        set(Property::Height(h));
                    }
                });
                ui.end_row();
            }
            Some(Shape::Circle { radius }) => {
                ui.label("radius, m");
                if let Some(r) = field(ui, "radius", *radius, &size) {
                    set(Property::Radius(r));
                }
                ui.end_row();
            }
            Some(Shape::Arc { .. } | Shape::Polyline { .. }) => {
                super::track_editor::inspector_rows(ui, b, &mut set);
            }
            _ => {}
        }
        ui.label("position, m");
        let (x, y) = b.position;
        let at = Accepts::closed(-1e6, 1e6, "m");
        ui.horizontal(|ui| {
            if let Some(x) = field(ui, "x", x, &at) {
                set(Property::Position((x, y)));
            }
            if let Some(y) = field(ui, "y", y, &at) {
                set(Property::Position((x, y)));
            }
        });
        ui.end_row();
        ui.label("angle, degrees");
        let deg = b.angle.to_degrees();
        if let Some(d) = field(ui, "angle", deg, &Accepts::closed(-3600.0, 3600.0, "°")) {
            set(Property::Angle(d.to_radians()));
        }
        ui.end_row();
        if b.kind == BodyKind::Dynamic {
            ui.label("velocity, m/s");
            let (vx, vy) = b.velocity;
            let v = Accepts::closed(-1e4, 1e4, "m/s");
            ui.horizontal(|ui| {
                if let Some(vx) = field(ui, "vx", vx, &v) {
                    set(Property::Velocity((vx, vy)));
                }
                if let Some(vy) = field(ui, "vy", vy, &v) {
                    set(Property::Velocity((vx, vy)));
                }
            });
            ui.end_row();
            ui.label("ω, rad/s");
            if let Some(w) = field(ui, "omega", b.omega, &Accepts::closed(-1e4, 1e4, "rad/s")) {
                set(Property::Omega(w));
            }
            ui.end_row();
        }
        if b.shape.is_some() {
            ui.label("friction μ");
            let mu = b.friction.unwrap_or(0.0);
            if let Some(mu) = field(ui, "friction", mu, &Accepts::closed(0.0, 10.0, "")) {
                set(Property::Friction(mu));
            }
            ui.end_row();
            ui.label("restitution e");
            let e = b.restitution.unwrap_or(0.0);
            if let Some(e) = field(ui, "restitution", e, &Accepts::closed(0.0, 1.0, "")) {
                set(Property::Restitution(e));
            }
            ui.end_row();
        }
        let mut kind = b.kind;
        ui.label("kind");
        egui::ComboBox::from_id_salt("kind")
            .selected_text(kind_name(kind))
            .show_ui(ui, |ui| {
                for k in [BodyKind::Dynamic, BodyKind::Fixed, BodyKind::Kinematic] {
                    ui.selectable_value(&mut kind, k, kind_name(k));
                }
            });
        if kind != b.kind {
            set(Property::Kind(kind));
        }
        ui.end_row();
    });
    ui.label(
        rich(
            "Enter or a click elsewhere applies a field; Escape drops it",
            palette::OUTLINE,
        )
        .small(),
    );
    ui.horizontal(|ui| {
        if ui.button("duplicate").clicked() {
            out.push(EditorCommand::Apply(Edit::Duplicate {
                body: b.name.clone(),
                offset: (0.0, duplicate_offset(b)),
            }));
        }
        if ui.button("delete").on_hover_text("Delete key").clicked() {
            out.push(EditorCommand::Apply(Edit::Delete {
                body: b.name.clone(),
            }));
        }
    });
}

/// A velocity motor on each pin or slider of the body: on or off, and its target rate.
fn motors(
    ui: &mut egui::Ui,
    level: &crate::level::Level,
    body: &str,
    out: &mut Vec<EditorCommand>,
) {
    for j in level.joints.iter().filter(|j| {
        (j.body1 == body || j.body2 == body)
            && matches!(j.kind, JointKind::Revolute | JointKind::Prismatic)
    }) {
        let unit = if j.kind == JointKind::Revolute {
            "rad/s"
        } else {
            "m/s"
        };
        let current = match &j.motor {
            Some(crate::level::Motor::Velocity { target, .. }) => Some(*target),
            Some(_) => None,
            None => None,
        };
        ui.horizontal(|ui| {
            let mut on = current.is_some();
            if ui.checkbox(&mut on, format!("{} motor", j.name)).changed() {
                out.push(EditorCommand::Apply(Edit::SetMotor {
                    joint: j.name.clone(),
                    target: on.then_some(1.0),
                }));
            }
            if let Some(t) = current {
                let id = egui::Id::new(("motor", j.name.as_str()));
                if let Some(t) = number_field(ui, id, t, &Accepts::closed(-1e4, 1e4, unit)) {
                    out.push(EditorCommand::Apply(Edit::SetMotor {
                        joint: j.name.clone(),
                        target: Some(t),
                    }));
                }
                ui.label(unit);
            }
        });
    }
}

/// A note up to its first `;` (or 140 characters), and whether it was cut.
pub(super) fn first_clause(note: &str) -> (String, bool) {
    let end = note.find(';').unwrap_or(note.len());
    let mut short: String = note[..end].chars().take(140).collect();
    let cut = short.len() < note.len();
    if cut {
        short.push_str(" … (hover for the rest)");
    }
    (short, cut)
}

fn kind_name(k: BodyKind) -> &'static str {
    match k {
        BodyKind::Dynamic => "dynamic",
        BodyKind::Fixed => "fixed",
        BodyKind::Kinematic => "kinematic",
    }
}

/// A copy goes just above the original, clear of it.
fn duplicate_offset(b: &BodyDef) -> f64 {
    match &b.shape {
        Some(Shape::Circle { radius }) => 2.5 * radius,
        Some(Shape::Box { height, .. }) => 1.5 * height.max(0.01),
        _ => 0.5,
    }
}
