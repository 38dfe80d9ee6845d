//! A challenge in the window (issue 42, docs/student.md#playing-a-challenge): the control's field
//! with its unit and range, a Launch button that rebuilds the run with the value set, the goal's
//! region or point drawn in the scene, and after the run "success" or "missed by ..." drawn at
//! the miss, with stars: 3 for a success in one or two launches, 2 in three or four, 1 after.

use super::super::draw::{DrawStep, Drawing, Prim};
use super::super::physics::{LiveChecks, PhysicsCommand};
use super::super::run::Run;
use super::super::student;
use super::super::ui::rich;
use super::super::view::{palette, View};
use super::course::{self, Course};
use super::level_browser::Browser;
use crate::level::params::Control;
use crate::level::{self, Goal, Region};
use crate::questions::ChallengeResult;
use bevy::prelude::*;
use bevy_egui::egui;
use glam::DVec2;
use std::path::PathBuf;

/// What the panel keeps between frames, in egui's memory, for the level file on screen.
#[derive(Clone, Default)]
struct Play {
    file: PathBuf,
    /// The level's text (compiled into the page or fetched there; read from the file natively).
    text: String,
    /// The control as the level declares it, or why it could not be read.
    control: Option<Result<Control, String>>,
    /// The value in the field, in the control's unit.
    value: f64,
    /// Launches whose run has ended, and the generation of the run a launch replaced (its
    /// own run is the next one).
    tries: u32,
    launched: Option<u64>,
    last: Option<ChallengeResult>,
    stars: Option<u8>,
    /// Why the last launch could not be made.
    error: Option<String>,
}

/// Stars for a success at the `tries`-th launch (`progress.rs`: the course gives the same).
pub use super::super::progress::stars;

/// The challenge's window over the scene (`scene`: the scene's viewport), when the level on
/// screen has a challenge; what it asks of the run.
pub fn window(
    ctx: &egui::Context,
    (phys, browser, view, tour_open): (&Run, &Browser, &View, bool),
    (live, course, message): (&LiveChecks, &mut Course, &mut Option<(String, bool)>),
    scene: egui::Rect,
) -> Vec<PhysicsCommand> {
    let mut asked = Vec::new();
    let Some(c) = &phys.sim.level.challenge else {
        return asked;
    };
    let id = egui::Id::new("challenge play");
    let mut play: Play = ctx.data(|d| d.get_temp(id)).unwrap_or_default();
    if play.file != phys.scene.file || play.control.is_none() {
        play = start(&phys.scene.file, level_text(browser, &phys.scene.file));
        // The launches and stars the course has for it, so both say the same.
        let (launches, stars) = course::challenge_record(course, browser, phys);
        (play.tries, play.stars) = (launches, stars);
    }
    if let Some((met, error)) = tally(&mut play, phys, live) {
        if let Some(note) = course::record_launch(course, browser, phys, met, error) {
            *message = Some((note, false));
        }
    }
    let bodies: Vec<egui::Pos2> = phys
        .snapshot()
        .bodies
        .iter()
        .map(|b| {
            let p = view.to_screen(b.com);
            egui::pos2(p.x, p.y)
        })
        .collect();
    // One window per level, so that each opens at its own scene's free corner, off the
    // first-steps tour (open over the scene's bottom-right corner); a box that grew onto the
    // tour (a verdict and a note after a launch) or was dragged onto it goes to a free corner.
    let win = window_id(&phys.scene.file);
    let tour = ctx.memory(|m| m.area_rect(egui::Id::new(super::tour::TOUR_ID)));
    let tour = tour.filter(|_| tour_open);
    let last = ctx.memory(|m| m.area_rect(win));
    let size = last.map_or(BOX_SIZE, |r| r.size().max(BOX_SIZE));
    let avoid: Vec<egui::Rect> = tour.into_iter().collect();
    let corner = box_corner_avoiding(scene, size, &bodies, &avoid);
    let mut w = egui::Window::new("Challenge")
        .id(win)
        .default_pos(corner)
        .max_width(BOX_SIZE.x - 16.0);
    if let (Some(r), Some(t)) = (last, tour) {
        if r.intersects(t) {
            w = w.current_pos(corner);
        }
    }
    w.resizable(false).collapsible(true).show(ctx, |ui| {
        if !c.ask.is_empty() {
            ui.label(&c.ask);
        }
        match play.control.clone() {
            Some(Ok(control)) => controls(ui, &mut play, &control, phys.generation, &mut asked),
            Some(Err(why)) => {
                ui.label(rich(why, palette::NORMAL));
            }
            None => {}
        }
        verdict(ui, &play);
    });
    ctx.data_mut(|d| d.insert_temp(id, play));
    asked
}

/// The level's text: compiled into the page or fetched there (the browser's entry), else read
/// from its file. Before 2026-12-07 the file only, so in the page every challenge showed "the
/// level's file cannot be read" instead of Launch.
fn level_text(browser: &Browser, file: &std::path::Path) -> Result<String, String> {
    match browser.listed_text(file) {
        Some(text) => Ok(text.to_string()),
        None => level::read_text(file).map_err(|e| e.to_string()),
    }
}

/// The Challenge box's egui id for the level in `file` (its area's, where egui keeps its rect).
pub fn window_id(file: &std::path::Path) -> egui::Id {
    egui::Id::new(("challenge", file))
}

/// About the size the Challenge box draws at (measured on screenshots of the library's ten).
pub const BOX_SIZE: egui::Vec2 = egui::vec2(340.0, 175.0);

/// Where the Challenge box opens (its top-left corner): the corner of the scene (top-left,
/// top-right or bottom-left; the tour has the fourth) whose box lies farthest from the bodies'
/// mass centers on screen. At the scene's top-left corner, always,
/// it hid the cylinder of "leave at 30 degrees" and the pulley of the Atwood challenge (the
/// student trial of 2026-12-07).
pub fn box_corner(scene: egui::Rect, size: egui::Vec2, bodies: &[egui::Pos2]) -> egui::Pos2 {
    box_corner_avoiding(scene, size, bodies, &[])
}

/// [`box_corner`] among the corners whose box overlaps none of `avoid` (the first-steps tour's
/// rect: at 1280x800 the tour, 450 px wide, reached under the bottom-left corner's box, and the
/// box covered its steps); where every corner overlaps one, the corner that overlaps least.
pub fn box_corner_avoiding(
    scene: egui::Rect,
    size: egui::Vec2,
    bodies: &[egui::Pos2],
    avoid: &[egui::Rect],
) -> egui::Pos2 {
    let gap = egui::vec2(12.0, 12.0);
    // Not the bottom-right corner: the first-steps tour sits there (tour.rs).
    let corners = [
        scene.left_top() + gap,
        egui::pos2(scene.right() - size.x - gap.x, scene.top() + gap.y),
        egui::pos2(scene.left() + gap.x, scene.bottom() - size.y - gap.y),
    ];
    let overlap = |at: &egui::Pos2| {
        let r = egui::Rect::from_min_size(*at, size);
        avoid
            .iter()
            .map(|a| {
                let i = r.intersect(*a);
                if i.is_positive() {
                    i.area()
                } else {
                    0.0
                }
            })
            .sum::<f32>()
    };
    let clearance = |at: &egui::Pos2| {
        let r = egui::Rect::from_min_size(*at, size);
        bodies
            .iter()
            .map(|b| r.distance_to_pos(*b))
            .fold(f32::INFINITY, f32::min)
    };
    // Least overlap with what it must avoid first, then the farthest from the bodies (the
    // first corner on a tie: top-left, as before).
    let mut best = corners[0];
    for c in &corners[1..] {
        let (oc, ob) = (overlap(c), overlap(&best));
        if oc < ob || (oc == ob && clearance(c) > clearance(&best)) {
            best = *c;
        }
    }
    best
}

/// A new level's play: its control read from its text.
fn start(file: &std::path::Path, text: Result<String, String>) -> Play {
    // The field starts at the value of the scene on screen, the control's nominal one.
    let loaded = text
        .clone()
        .and_then(|t| level::parse_variant(file, &t, &student::pick()).map_err(|e| e.to_string()));
    let (control, value) = match loaded {
        Ok(l) => match l.control {
            Some((c, v)) => (Ok(c), v),
            None => (
                Err("this level's challenge has no control".to_string()),
                0.0,
            ),
        },
        Err(e) => (
            Err(format!("the level cannot be read for its control: {e}")),
            0.0,
        ),
    };
    Play {
        file: file.to_path_buf(),
        text: text.unwrap_or_default(),
        control: Some(control),
        value,
        ..Default::default()
    }
}

/// Counts a launched run once it has ended, and its stars on the first success: whether it
/// met the goal, and the control's relative distance from the worked value, for the course.
fn tally(play: &mut Play, phys: &Run, live: &LiveChecks) -> Option<(bool, f64)> {
    let from = play.launched?;
    let result = live.challenge.as_ref()?;
    if phys.generation == from {
        return None;
    }
    // The control and the value launched, as `check --answer` sets them: the verdict says
    // which way the value was off (the run's result carries neither).
    let mut result = result.clone();
    if let Some(Ok(c)) = &play.control {
        result.set_control(c, play.value, true);
    }
    play.launched = None;
    play.tries += 1;
    if result.success && play.stars.is_none() {
        play.stars = Some(stars(play.tries));
    }
    play.last = Some(result.clone());
    let error = ((result.value - result.worked) / result.worked).abs();
    Some((
        result.success,
        if error.is_nan() { f64::INFINITY } else { error },
    ))
}

/// The control's field with its unit and range, and the Launch button.
fn controls(
    ui: &mut egui::Ui,
    play: &mut Play,
    c: &Control,
    generation: u64,
    asked: &mut Vec<PhysicsCommand>,
) {
    ui.horizontal(|ui| {
        ui.label(&c.name);
        ui.add(
            egui::DragValue::new(&mut play.value)
                .range(c.min..=c.max)
                .speed(c.step)
                .max_decimals(c.decimals.max(3)),
        );
        ui.label(&c.unit);
    });
    ui.label(egui::RichText::new(format!("from {} to {}", c.show(c.min), c.show(c.max))).small());
    let launch = ui
        .add_enabled(play.launched.is_none(), egui::Button::new("Launch"))
        .on_hover_text("run the scene from the start with this value");
    if launch.clicked() {
        match level::parse_challenge(&play.file, &play.text, &student::pick(), Some(play.value)) {
            Ok(l) => {
                asked.push(PhysicsCommand::Edited {
                    scene: Box::new(l.scene),
                    refit: false,
                });
                asked.push(PhysicsCommand::TogglePlay);
                play.last = None;
                play.error = None;
                play.launched = Some(generation);
            }
            Err(e) => play.error = Some(e.to_string()),
        }
    }
}

/// The last launch's verdict, the tries and the stars.
fn verdict(ui: &mut egui::Ui, play: &Play) {
    if play.launched.is_some() {
        ui.label("running...");
    }
    if let Some(e) = &play.error {
        ui.label(rich(e, palette::NORMAL).small());
    }
    if let Some(r) = &play.last {
        let color = if r.success {
            palette::GRAVITY
        } else {
            palette::NORMAL
        };
        ui.label(rich(r.verdict(), color).strong());
        if !r.note.is_empty() {
            ui.label(egui::RichText::new(&r.note).small());
        }
    }
    let stars = play
        .stars
        .map_or(String::new(), |s| format!("  {}", "*".repeat(s as usize)));
    ui.label(format!("launches: {}{stars}", play.tries));
}

/// Draws the goal's region or point in the scene, and after a run its verdict at the miss.
pub fn draw(phys: Res<Run>, live: NonSend<LiveChecks>, mut d: ResMut<Drawing>) {
    let Some(c) = &phys.sim.level.challenge else {
        return;
    };
    let color = palette::GRAVITY;
    if let Some((at, name)) = goal_prims(&c.goal, color, &mut d.prims) {
        d.label(at, Vec2::new(0.0, 16.0), name, color);
    }
    let Some(r) = live.challenge.as_ref() else {
        return;
    };
    let text = r.verdict();
    let shade = if r.success { color } else { palette::NORMAL };
    match (r.at, r.target) {
        (Some(a), Some(t)) => {
            let (a, t) = (DVec2::new(a.0, a.1), DVec2::new(t.0, t.1));
            if !r.success {
                d.prims.push(Prim::Dashed(a, t, shade));
            }
            d.label((a + t) / 2.0, Vec2::new(0.0, -14.0), text, shade);
        }
        _ => {
            // A reading: at the first moving body.
            let s = phys.snapshot();
            if let Some(b) = s.bodies.iter().find(|b| b.mass > 0.0) {
                d.label(b.com, Vec2::new(0.0, -24.0), text, shade);
            }
        }
    }
}

/// The goal's drawing, dashed: a goal is a region of the plane the run is judged on, never a
/// body, and nothing collides with it (the cup of `challenges/projectile_into_cup.ron` is the
/// point its mouth is at; drawn as a solid ring, the ball seemed to fly through a wall, the
/// student trial of 2026-12-07). Solid outlines are the bodies'. Where to name it, and its name.
pub fn goal_prims(goal: &Goal, color: Color, out: &mut Vec<Prim>) -> Option<(DVec2, &'static str)> {
    match goal {
        Goal::EndsInside { region, .. } | Goal::StaysInside { region, .. } => {
            Some((region_prims(region, color, out), "goal region"))
        }
        Goal::Reaches { point, radius, .. } => {
            let p = DVec2::new(point.0, point.1);
            dashed_circle(p, *radius, color, out);
            out.push(Prim::Dot(p, 3.0, color));
            Some((p, "target"))
        }
        _ => None,
    }
}

/// A circle drawn as every other one of 24 chords: dashed at any zoom, even a 3 cm target.
fn dashed_circle(c: DVec2, r: f64, color: Color, out: &mut Vec<Prim>) {
    const CHORDS: usize = 24;
    let at = |k: usize| c + r * DVec2::from_angle(std::f64::consts::TAU * k as f64 / CHORDS as f64);
    out.extend(
        (0..CHORDS)
            .step_by(2)
            .map(|k| Prim::Line(at(k), at(k + 1), color)),
    );
}

/// A region's outline, dashed; the point to name it at (its lowest middle).
fn region_prims(region: &Region, color: Color, out: &mut Vec<Prim>) -> DVec2 {
    match *region {
        Region::Rect { min, max } => {
            let corners = [
                DVec2::new(min.0, min.1),
                DVec2::new(max.0, min.1),
                DVec2::new(max.0, max.1),
                DVec2::new(min.0, max.1),
            ];
            for k in 0..4 {
                out.push(Prim::Dashed(corners[k], corners[(k + 1) % 4], color));
            }
            DVec2::new((min.0 + max.0) / 2.0, min.1)
        }
        Region::Circle { center, radius } => {
            let c = DVec2::new(center.0, center.1);
            dashed_circle(c, radius, color, out);
            c - DVec2::new(0.0, radius)
        }
        Region::Ring {
            center,
            inner,
            outer,
        } => {
            let c = DVec2::new(center.0, center.1);
            dashed_circle(c, inner, color, out);
            dashed_circle(c, outer, color, out);
            c - DVec2::new(0.0, outer)
        }
    }
}

/// The drawing system's place: with the tools' marks, after the scene's lines.
pub fn plugin(app: &mut App) {
    app.add_systems(Update, draw.in_set(DrawStep::Marks));
}
