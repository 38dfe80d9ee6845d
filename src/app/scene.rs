//! The running scene drawn: body meshes, lines, the overlays and their labels, and (in renders)
//! the title, time and color key; no panels, no camera of its own. The native window, the page
//! and `rigidlab render` all draw with this plugin.

use super::ball_meshes::BallMeshes;
use super::draw::{self, DrawStep, Drawing};
use super::labels;
use super::overlay_systems::OverlaysPlugin;
use super::overlays::{self, Overlays, Scales};
use super::physics::PhysicsStep;
use super::run::Run;
use super::scene_lines;
use super::ui::color32;
use super::view::{self, palette, Outlines, View};
use bevy::app::PluginGroupBuilder;
use bevy::prelude::*;
use bevy_egui::{egui, EguiContexts, EguiPrimaryContextPass};
use glam::DVec2;

/// The running scene drawn: [`ScenePlugin`] (meshes, lines, labels) and [`OverlaysPlugin`] (one
/// system per overlay); the sandbox's `ToolsPlugin` adds the tools' marks between them and the
/// scale bar.
pub struct ScenePlugins {
    /// Paint the title/time/legend box (renders; the sandbox shows these in its panels).
    pub legend: bool,
}

impl PluginGroup for ScenePlugins {
    fn build(self) -> PluginGroupBuilder {
        PluginGroupBuilder::start::<Self>()
            .add(ScenePlugin {
                legend: self.legend,
            })
            .add(OverlaysPlugin)
    }
}

/// Drawing of the running scene: meshes, lines, labels (no overlays, no panels, no camera).
pub struct ScenePlugin {
    /// Paint the title/time/legend box (renders; the sandbox shows these in its panels).
    pub legend: bool,
}

/// The set of the scene drawing systems (after the physics step).
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct SceneDraw;

impl Plugin for ScenePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<View>()
            .init_resource::<Outlines>()
            .init_resource::<BallMeshes>()
            .init_resource::<Drawing>()
            .init_resource::<Overlays>()
            .init_resource::<Scales>()
            .configure_sets(
                Update,
                (
                    DrawStep::Scene,
                    DrawStep::Overlays,
                    DrawStep::Marks,
                    DrawStep::Finish,
                )
                    .chain()
                    .in_set(SceneDraw)
                    .after(PhysicsStep),
            )
            .add_systems(
                Update,
                (
                    view::spawn_meshes,
                    view::sync_camera,
                    view::rescale_ball_meshes,
                    view::sync_meshes,
                    build_drawing,
                )
                    .chain()
                    .in_set(DrawStep::Scene),
            )
            .add_systems(
                Update,
                (scale_bar, draw::emit_gizmos)
                    .chain()
                    .in_set(DrawStep::Finish),
            )
            .add_systems(EguiPrimaryContextPass, paint_labels);
        if self.legend {
            app.add_systems(EguiPrimaryContextPass, paint_legend.after(paint_labels));
        }
    }
}

/// The frame's drawing started: the body lines and the selection, and the arrow scales the
/// overlays and tools draw with ([`Scales`]).
pub fn build_drawing(
    phys: Res<Run>,
    mut view: ResMut<View>,
    outlines: Res<Outlines>,
    ov: Res<Overlays>,
    mut scales: ResMut<Scales>,
    mut d: ResMut<Drawing>,
) {
    let s = phys.snapshot();
    if view.generation_speed != Some(phys.generation) {
        view.generation_speed = Some(phys.generation);
        view.max_speed = 0.0;
    }
    let fastest = s
        .bodies
        .iter()
        .map(|b| b.velocity.length())
        .fold(0.0, f64::max);
    if fastest.is_finite() && fastest > view.max_speed {
        view.max_speed = fastest;
    }
    d.clear(view.m_per_px);
    scene_lines::scene_lines(
        &phys.sim.level,
        &outlines.bodies,
        &outlines.index,
        s,
        view.m_per_px,
        &mut d,
    );
    if let Some(i) = ov.selected {
        scene_lines::highlight(&outlines.bodies, s, i, &mut d);
    }
    *scales = Scales::of(s, view.scene_size(), view.max_speed, view.m_per_px);
    scales.gain = ov.arrow_scale;
    let vp = view.viewport;
    let (a, b) = (
        view.to_world(Vec2::new(vp.min.x, vp.max.y)),
        view.to_world(Vec2::new(vp.max.x, vp.min.y)),
    );
    scales.visible = Some((a.min(b), a.max(b)));
}

/// The scale bar, last, over the overlays and the tools' marks.
fn scale_bar(view: Res<View>, mut d: ResMut<Drawing>) {
    scene_lines::scale_bar(&view, &mut d);
}

fn egui_rect(r: Rect) -> egui::Rect {
    egui::Rect::from_min_max(egui::pos2(r.min.x, r.min.y), egui::pos2(r.max.x, r.max.y))
}

/// The labels of the drawing, in screen space, each on a light box so it reads over lines.
fn paint_labels(
    mut contexts: EguiContexts,
    d: Res<Drawing>,
    view: Res<View>,
    mut last: Local<Vec<(Vec2, Rect)>>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    let painter = ctx
        .layer_painter(egui::LayerId::new(
            egui::Order::Background,
            egui::Id::new("rigidlab-labels"),
        ))
        .with_clip_rect(egui_rect(view.viewport));
    let bg = color32(palette::BACKGROUND.with_alpha(0.8));
    let galleys: Vec<_> = d
        .labels
        .iter()
        .map(|l| {
            painter.layout_no_wrap(
                l.text.clone(),
                egui::FontId::proportional(l.size),
                color32(l.color),
            )
        })
        .collect();
    let wants: Vec<labels::Want> = d
        .labels
        .iter()
        .zip(&galleys)
        .map(|(l, g)| label_want(l, Vec2::new(g.size().x, g.size().y), &view))
        .collect();
    let (rects, _) = place_labels(&d, &view, &wants, &mut last);
    for ((l, galley), r) in d.labels.iter().zip(galleys).zip(rects) {
        painter.rect_filled(egui_rect(r).expand(1.5), 2.0, bg);
        painter.galley(egui::pos2(r.min.x, r.min.y), galley, color32(l.color));
    }
    Ok(())
}

/// Places the labels that want `wants` among `d`'s bodies, keeping `last` frame's places where
/// they still fit, and records this frame's places in `last`. Only the bodies within the labels'
/// reach are converted to the screen (none without labels). Returns each label's box and how
/// many bodies were in reach (the frame bench reports it).
pub fn place_labels(
    d: &Drawing,
    view: &View,
    wants: &[labels::Want],
    last: &mut Vec<(Vec2, Rect)>,
) -> (Vec<Rect>, usize) {
    let reach = labels::reach(wants, view.viewport, last);
    let bodies = screen_bodies_within(d, view, &reach);
    let rects = labels::place_keeping(wants, &bodies, view.viewport, last);
    *last = wants
        .iter()
        .map(|w| w.home)
        .zip(rects.iter().copied())
        .collect();
    (rects, bodies.len())
}

/// Where a label wants to be: centered on its point (plus its offset), or pushed out along
/// `dir` until its box clears the point (labels at arrow tips).
pub fn label_want(l: &draw::Label, size: Vec2, view: &View) -> labels::Want {
    let push = 5.0 + 0.5 * (l.dir.x.abs() * size.x + l.dir.y.abs() * size.y);
    let p = view.to_screen(l.at) + l.offset + l.dir * push;
    labels::Want {
        home: p - 0.5 * size,
        size,
    }
}

/// The drawing's bodies in screen coordinates, for the label placer: its polygons, then its
/// balls' octagons.
pub fn screen_bodies(d: &Drawing, view: &View) -> Vec<Vec<Vec2>> {
    let octagons = d.balls.iter().map(|b| screen_octagon(b, view));
    d.bodies
        .iter()
        .map(|poly| poly.iter().map(|p| view.to_screen(*p)).collect())
        .chain(octagons)
        .collect()
}

/// A ball's octagon (center and radius, world) on screen.
fn screen_octagon((c, r): &(DVec2, f64), view: &View) -> Vec<Vec2> {
    draw::ball_octagon(view.to_screen(*c), (*r / view.m_per_px) as f32)
}

/// [`screen_bodies`], only those that meet a rectangle of `reach` (screen coordinates,
/// `labels::reach`): the placer tests no other. A 10,000-grain pile's octagons were all
/// converted every frame for the few labels of the selected grain (docs/benchmarks.md,
/// "10,000 bodies").
pub fn screen_bodies_within(d: &Drawing, view: &View, reach: &[Rect]) -> Vec<Vec<Vec2>> {
    // A world box's corners: `to_screen` scales and shifts each axis monotonically, so they
    // bound the screen polygon as its own points would.
    let near = |lo: DVec2, hi: DVec2| {
        let corners = [view.to_screen(lo), view.to_screen(hi)];
        reach.iter().any(|r| !labels::apart(r, &corners))
    };
    let polygons = d.bodies.iter().filter(|poly| {
        let (lo, hi) = poly
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        near(lo, hi)
    });
    let octagons = d
        .balls
        .iter()
        .filter(|(c, r)| {
            // The octagon's box, exactly: its vertices at 0, 90, 180 and 270 degrees are
            // center +- reach (`draw::ball_octagon`), the others lie inside.
            let (c, big) = (
                view.to_screen(*c),
                draw::octagon_reach((*r / view.m_per_px) as f32),
            );
            reach
                .iter()
                .any(|r| !labels::apart(r, &[c - Vec2::splat(big), c + Vec2::splat(big)]))
        })
        .map(|b| screen_octagon(b, view));
    polygons
        .map(|poly| poly.iter().map(|p| view.to_screen(*p)).collect())
        .chain(octagons)
        .collect()
}

/// Title, time and the color key (renders).
fn paint_legend(mut contexts: EguiContexts, phys: Res<Run>, ov: Res<Overlays>) -> Result {
    let ctx = contexts.ctx_mut()?;
    egui::Area::new(egui::Id::new("rigidlab-legend"))
        .fixed_pos(egui::pos2(10.0, 8.0))
        .show(ctx, |ui| {
            egui::Frame::new()
                .fill(color32(palette::BACKGROUND.with_alpha(0.85)))
                .inner_margin(6.0)
                .show(ui, |ui| {
                    let s = phys.snapshot();
                    ui.label(
                        egui::RichText::new(&phys.sim.level.title)
                            .strong()
                            .color(color32(palette::TEXT)),
                    );
                    ui.label(
                        egui::RichText::new(format!(
                            "t = {} s   dt = {} s",
                            super::time_text::clock(s.time, phys.sim.dt()),
                            super::time_text::step(phys.sim.dt())
                        ))
                        .color(color32(palette::TEXT)),
                    );
                    for (text, color) in
                        overlays::legend_entries(&ov, &phys.sim.level, phys.steps_averaged())
                    {
                        ui.label(egui::RichText::new(text).color(color32(color)));
                    }
                    if let Some(note) = overlays::crowd_note(&ov, s) {
                        ui.label(egui::RichText::new(note).color(color32(palette::TEXT)));
                    }
                });
        });
    Ok(())
}
