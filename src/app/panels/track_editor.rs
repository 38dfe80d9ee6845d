//! Curved tracks in the Build panel: a form that adds a fixed arc or a fixed polyline track (its
//! points typed as a list of x, y pairs), and the inspector's rows for a selected track. Each
//! change is one edit through the editor (undoable); what the validator refuses (a polyline that
//! crosses itself, too few points, a sweep outside (0, 360] degrees) comes back as the editor's
//! note at the top of the panel, and the scene stays as it was.

use super::super::editor::EditorCommand;
use super::super::ui::rich;
use super::super::view::palette;
use super::number_field::{number_field, Accepts};
use crate::editor::{parse_points, points_text, side_name, solid_name, Edit, Property};
use crate::level::{curves, ArcSide, BodyDef, Shape, TrackSide};
use bevy_egui::egui;
use std::collections::BTreeMap;

/// The add form's values between frames (egui's memory: they are the panel's alone).
#[derive(Debug, Clone)]
struct Form {
    center: (f64, f64),
    radius: f64,
    /// Degrees, as the inspector shows angles.
    start: f64,
    end: f64,
    side: ArcSide,
    points: String,
    closed: bool,
    solid: Option<TrackSide>,
    /// Why the typed points could not be read.
    error: Option<String>,
}

/// A loop of radius 1 m standing on the origin, open from its left side down to its bottom, and
/// a floor leading into it from the left: a loop-the-loop in two clicks.
impl Default for Form {
    fn default() -> Self {
        Form {
            center: (0.0, 1.0),
            radius: 1.0,
            start: -90.0,
            end: 180.0,
            side: ArcSide::Inside,
            points: "-3, 0\n0, 0".into(),
            closed: false,
            solid: Some(TrackSide::Right),
            error: None,
        }
    }
}

const SIDES: [ArcSide; 2] = [ArcSide::Inside, ArcSide::Outside];

fn side_label(s: ArcSide) -> &'static str {
    match s {
        ArcSide::Inside => "inside (a loop, a bowl)",
        ArcSide::Outside => "outside (a hump)",
    }
}

fn solid_label(s: Option<TrackSide>) -> String {
    match s {
        None => "two-sided".into(),
        Some(s) => format!("solid on the {}", solid_name(s)),
    }
}

/// The form that adds a fixed arc or polyline track.
pub(super) fn add_tracks(
    ui: &mut egui::Ui,
    buttons: &mut BTreeMap<String, egui::Rect>,
    out: &mut Vec<EditorCommand>,
) {
    let id = egui::Id::new("track form");
    let mut f: Form = ui.data_mut(|d| d.get_temp(id)).unwrap_or_default();
    let field = |ui: &mut egui::Ui, what: &str, x: f64, a: &Accepts| {
        number_field(ui, egui::Id::new(("track form", what)), x, a)
    };
    let at = Accepts::closed(-1e6, 1e6, "m");
    let deg = Accepts::closed(-3600.0, 3600.0, "°");
    ui.label(rich("arc: a fixed circular track", palette::OUTLINE).small());
    egui::Grid::new("track form arc")
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("center x, y, m");
            ui.horizontal(|ui| {
                if let Some(x) = field(ui, "cx", f.center.0, &at) {
                    f.center.0 = x;
                }
                if let Some(y) = field(ui, "cy", f.center.1, &at) {
                    f.center.1 = y;
                }
            });
            ui.end_row();
            ui.label("radius, m");
            if let Some(r) = field(ui, "radius", f.radius, &Accepts::above(0.0, 1e4, "m")) {
                f.radius = r;
            }
            ui.end_row();
            ui.label("from, to, degrees");
            ui.horizontal(|ui| {
                if let Some(a) = field(ui, "start", f.start, &deg) {
                    f.start = a;
                }
                if let Some(a) = field(ui, "end", f.end, &deg) {
                    f.end = a;
                }
            });
            ui.end_row();
            ui.label("bodies ride its");
            side_combo(ui, "track form side", &mut f.side);
            ui.end_row();
        });
    let r = ui
        .button("add arc")
        .on_hover_text("counter-clockwise from `from` to `to`; 0 degrees points along +x");
    buttons.insert("add arc".into(), r.rect);
    if r.clicked() {
        out.push(EditorCommand::Apply(Edit::AddArc {
            center: f.center,
            radius: f.radius,
            start: f.start.to_radians(),
            end: f.end.to_radians(),
            side: f.side,
        }));
    }

    ui.label(
        rich(
            "polyline: a fixed track through points, x, y in m, one pair a line",
            palette::OUTLINE,
        )
        .small(),
    );
    let r = ui.add(
        egui::TextEdit::multiline(&mut f.points)
            .hint_text("-3, 0\n0, 0")
            .desired_rows(3)
            .desired_width(170.0),
    );
    buttons.insert("track points".into(), r.rect);
    ui.horizontal(|ui| {
        ui.checkbox(&mut f.closed, "closed");
        solid_combo(ui, "track form solid", &mut f.solid);
    });
    let r = ui
        .button("add track")
        .on_hover_text("a one-sided track collides on the side away from its solid; give a concave track its solid side (docs/levels.md)");
    buttons.insert("add track".into(), r.rect);
    if r.clicked() {
        match parse_points(&f.points) {
            Ok(points) => {
                f.error = None;
                out.push(EditorCommand::Apply(Edit::AddTrack {
                    points,
                    closed: f.closed,
                    solid: f.solid,
                }));
            }
            Err(e) => f.error = Some(e),
        }
    }
    if let Some(e) = &f.error {
        ui.label(rich(e.as_str(), palette::NORMAL));
    }
    ui.data_mut(|d| d.insert_temp(id, f));
}

/// The inspector's rows for a track (inside its grid); None when the body is not one.
pub(super) fn inspector_rows(
    ui: &mut egui::Ui,
    b: &BodyDef,
    set: &mut dyn FnMut(Property),
) -> Option<()> {
    let field = |ui: &mut egui::Ui, what: &str, x: f64, a: &Accepts| {
        number_field(
            ui,
            egui::Id::new(("inspector", b.name.as_str(), what)),
            x,
            a,
        )
    };
    match b.shape.as_ref()? {
        Shape::Arc {
            center,
            radius,
            start,
            end,
            side,
            chord_error,
        } => {
            ui.label("arc center, m");
            let at = Accepts::closed(-1e6, 1e6, "m");
            ui.horizontal(|ui| {
                if let Some(x) = field(ui, "arc cx", center.0, &at) {
                    set(Property::ArcCenter((x, center.1)));
                }
                if let Some(y) = field(ui, "arc cy", center.1, &at) {
                    set(Property::ArcCenter((center.0, y)));
                }
            })
            .response
            .on_hover_text("in the body's frame: the body's position moves the whole arc");
            ui.end_row();
            ui.label("radius, m");
            if let Some(r) = field(ui, "arc radius", *radius, &Accepts::above(0.0, 1e4, "m")) {
                set(Property::Radius(r));
            }
            ui.end_row();
            ui.label("from, to, degrees");
            let deg = Accepts::closed(-3600.0, 3600.0, "°");
            ui.horizontal(|ui| {
                if let Some(a) = field(ui, "arc start", start.to_degrees(), &deg) {
                    set(Property::ArcStart(a.to_radians()));
                }
                if let Some(a) = field(ui, "arc end", end.to_degrees(), &deg) {
                    set(Property::ArcEnd(a.to_radians()));
                }
            });
            ui.end_row();
            ui.label("bodies ride its");
            let mut s = *side;
            side_combo(ui, ("inspector side", b.name.as_str()), &mut s);
            if s != *side {
                set(Property::Side(s));
            }
            ui.end_row();
            let e = curves::chord_error(*radius, *chord_error);
            let n = curves::arc_facets(*radius, end - start, e);
            if n <= curves::MAX_ARC_FACETS {
                ui.label("facets");
                ui.label(rich(format!("{n}, chords within {e:.1e} m"), palette::OUTLINE).small());
                ui.end_row();
            }
        }
        Shape::Polyline {
            points,
            closed,
            solid,
        } => {
            // The typed text is kept apart from the level until applied, and started over when
            // the level's points change (an undo, another edit).
            let id = egui::Id::new(("inspector points", b.name.as_str()));
            let current = points_text(points);
            let mut draft: (String, String, Option<String>) = ui
                .data_mut(|d| d.get_temp(id))
                .filter(|(from, _, _): &(String, String, Option<String>)| *from == current)
                .unwrap_or_else(|| (current.clone(), current.clone(), None));
            ui.label(format!("points, m ({})", points.len()))
                .on_hover_text("x, y in the body's frame, one pair a line");
            ui.vertical(|ui| {
                ui.add(
                    egui::TextEdit::multiline(&mut draft.1)
                        .desired_rows(3)
                        .desired_width(150.0),
                );
                if ui
                    .add_enabled(draft.1 != current, egui::Button::new("apply points"))
                    .clicked()
                {
                    match parse_points(&draft.1) {
                        Ok(p) => {
                            draft.2 = None;
                            set(Property::Points(p));
                        }
                        Err(e) => draft.2 = Some(e),
                    }
                }
                if let Some(e) = &draft.2 {
                    ui.label(rich(e.as_str(), palette::NORMAL));
                }
            });
            ui.data_mut(|d| d.insert_temp(id, draft));
            ui.end_row();
            ui.label("track");
            ui.horizontal(|ui| {
                let mut c = *closed;
                if ui.checkbox(&mut c, "closed").changed() {
                    set(Property::Closed(c));
                }
                let mut s = *solid;
                solid_combo(ui, ("inspector solid", b.name.as_str()), &mut s);
                if s != *solid {
                    set(Property::Solid(s));
                }
            });
            ui.end_row();
        }
        _ => return None,
    }
    Some(())
}

fn side_combo(ui: &mut egui::Ui, id: impl std::hash::Hash + std::fmt::Debug, side: &mut ArcSide) {
    egui::ComboBox::from_id_salt(id)
        .selected_text(side_name(*side))
        .show_ui(ui, |ui| {
            for s in SIDES {
                ui.selectable_value(side, s, side_label(s));
            }
        });
}

fn solid_combo(
    ui: &mut egui::Ui,
    id: impl std::hash::Hash + std::fmt::Debug,
    solid: &mut Option<TrackSide>,
) {
    egui::ComboBox::from_id_salt(id)
        .selected_text(solid_label(*solid))
        .show_ui(ui, |ui| {
            for s in [None, Some(TrackSide::Left), Some(TrackSide::Right)] {
                ui.selectable_value(solid, s, solid_label(s));
            }
        })
        .response
        .on_hover_text("looking along the track from its first point");
}
