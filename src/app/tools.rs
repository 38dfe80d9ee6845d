//! Mouse tools of the sandbox: select a body and a point on it, drag a body with a mouse spring
//! (or, paused at t = 0, move it), strike it with an impulse at the clicked point, set the point O
//! for H_O; and the build tools, which send edits to the editor: place a body, join two bodies,
//! hang a spring.

use super::draw::{si, DrawStep, Drawing, Prim};
use super::editor::{EditorCommand, Placeable};
use super::overlays::{Overlays, Scales};
use super::physics::{PhysicsCommand, PhysicsStep};
use super::playback::Playback;
use super::run::{Hold, Run};
use super::view::{self, palette, Outlines, View};
use crate::editor::{Edit, NewShape, Property};
use crate::level::JointKind;
use crate::snapshot::BodyKind;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use glam::DVec2;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tool {
    /// Click: select a body and a point on it; drag: pull it with a mouse spring.
    #[default]
    Select,
    /// Click-drag on a body: an impulse at the clicked point, along the drag.
    Impulse,
    /// Click: the point O about which H_O is drawn.
    SetOrigin,
    /// Click: a new body (or ground, or wall) there.
    Place(Placeable),
    /// Click: a joint there, between the bodies under the point (or one body and the ground).
    Join(JointKind),
    /// Drag: a spring from a point on a body to a point on another body or on the ground.
    Spring,
    /// Click: a torsion spring on the body there, to the body under it or to the ground.
    Torsion,
    /// Clicks: a polygon's vertices; a click on the first vertex (or Enter) makes the body,
    /// Escape drops the outline.
    Polygon,
    /// Clicks: a fixed polyline track's points; a click on the last point again (or Enter)
    /// makes the track, Escape drops it.
    Track,
    /// Drag: a length and its angle, kept on screen.
    Ruler,
    /// Drag from the vertex along one arm, then click the other arm's end: the angle between.
    Protractor,
}

/// A body held by the mouse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grab {
    pub body: usize,
    /// Grabbed point in the body frame.
    pub local: DVec2,
    /// Where the mouse is, world.
    pub target: DVec2,
    /// Pulling (the mouse moved since the press).
    pub pulling: bool,
}

/// An impulse being aimed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aim {
    pub body: usize,
    pub local: DVec2,
    pub end: DVec2,
}

#[derive(Resource, Debug, Clone, Default)]
pub struct ToolState {
    pub tool: Tool,
    pub grab: Option<Grab>,
    pub aim: Option<Aim>,
    /// The last impulse applied (point, impulse, sim time), drawn for a while.
    pub last_impulse: Option<(DVec2, DVec2, f64)>,
    /// The ruler's last measurement (from, to), world.
    pub ruler: Option<(DVec2, DVec2)>,
    /// The mouse in the world, this frame.
    pub cursor: Option<DVec2>,
    /// A spring being drawn: the body and the world point it starts from.
    pub spring_from: Option<(usize, DVec2)>,
    /// The protractor's last measurement.
    pub protractor: Option<Protractor>,
    /// The vertices of a polygon or the points of a track being drawn, world (rounded like a
    /// placed body).
    pub polygon: Vec<DVec2>,
}

/// A protractor: a vertex, one arm's end, and the other arm's end once clicked (until then the
/// cursor).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Protractor {
    pub vertex: DVec2,
    pub arm1: DVec2,
    pub arm2: Option<DVec2>,
    /// The first arm is being dragged.
    pub dragging: bool,
}

impl Protractor {
    /// The angle from arm 1 to arm 2, 0 to 180 degrees, rad (None until both arms have length).
    pub fn angle(&self) -> Option<f64> {
        let (a, b) = (self.arm1 - self.vertex, self.arm2? - self.vertex);
        (a.length() > 0.0 && b.length() > 0.0).then(|| a.angle_to(b).abs())
    }
}

/// Aiming time: a drag of D meters gives the body a velocity change of about D / AIM_TIME.
pub const AIM_TIME: f64 = 0.5;

/// The pointer as every mouse tool reads it this frame, read once by `read_pointer`.
#[derive(Resource, Debug, Clone, Default)]
pub struct Pointer {
    /// The mouse over the scene's viewport, window pixels.
    pub screen: Option<Vec2>,
    /// The same point, world.
    pub world: Option<DVec2>,
    /// How near a click must be to what it picks: 4 px, in meters.
    pub tol: f64,
    /// The left button went down this frame over the scene (not over a panel), here (world).
    pub clicked: Option<DVec2>,
    /// The left button is held, the mouse here (world).
    pub held: Option<DVec2>,
    /// The mouse moved more than 3 px since the press.
    pub moved: bool,
    /// The left button came up this frame.
    pub released: bool,
    /// Enter went down this frame, not into a text field.
    pub enter: bool,
    /// Where the left button went down, window pixels.
    press: Option<Vec2>,
}

/// What a mouse tool reads and writes: the pointer, the tools' state, the run it picks bodies
/// from, and the editor it sends edits to.
#[derive(SystemParam)]
struct ToolInput<'w> {
    pointer: Res<'w, Pointer>,
    state: ResMut<'w, ToolState>,
    run: Res<'w, Run>,
    outlines: Res<'w, Outlines>,
    view: Res<'w, View>,
    edits: MessageWriter<'w, EditorCommand>,
}

/// The mouse tools' systems, in the order they run each frame.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct MouseTools;

pub struct ToolsPlugin;

impl Plugin for ToolsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ToolState>()
            .init_resource::<Pointer>()
            .configure_sets(
                Update,
                MouseTools
                    .run_if(super::unsaved::not_asking)
                    .run_if(|windows: Query<&Window>| !windows.is_empty()),
            )
            .add_systems(Update, forget_marks.before(MouseTools))
            .add_systems(
                Update,
                (
                    (
                        read_pointer,
                        select_tool,
                        impulse_tool,
                        origin_tool,
                        place_tool,
                        join_tool,
                        ruler_tool,
                        protractor_tool,
                        torsion_tool,
                        polygon_tool,
                        track_tool,
                        spring_tool,
                    )
                        .chain()
                        .in_set(MouseTools),
                    hold_grabbed,
                )
                    .chain()
                    // Before the step, so what they ask is applied this frame (and so before the
                    // scene is drawn, which comes after the step).
                    .before(PhysicsStep),
            )
            .add_systems(Update, draw_marks.in_set(DrawStep::Marks));
    }
}

impl ToolState {
    /// Drops what was measured and drawn on the scene on screen (ruler and protractor marks,
    /// a half-drawn spring or polygon): they were about a level no longer open.
    pub fn forget_marks(&mut self) {
        self.ruler = None;
        self.protractor = None;
        self.spring_from = None;
        self.polygon.clear();
        self.grab = None;
        self.aim = None;
        self.last_impulse = None;
    }
}

/// A different level opened (`Run::view_generation`): its marks go.
fn forget_marks(phys: Res<Run>, mut state: ResMut<ToolState>, mut seen: Local<Option<u64>>) {
    if seen.is_some_and(|g| g != phys.view_generation) {
        state.forget_marks();
    }
    *seen = Some(phys.view_generation);
}

/// The impulse a drag `d` (m) aims at a body of mass `m`: J = m d / AIM_TIME, N s.
pub fn impulse_of_drag(m: f64, d: DVec2) -> DVec2 {
    d * m / AIM_TIME
}

/// Reads the mouse and the keys the tools answer into [`Pointer`]; drops a half-drawn outline
/// when its tool is left or Escape is pressed.
fn read_pointer(
    mut pointer: ResMut<Pointer>,
    mut state: ResMut<ToolState>,
    view: Res<View>,
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    windows: Query<&Window>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
) {
    let Some(window) = windows.iter().next() else {
        return;
    };
    let p = &mut *pointer;
    if !matches!(state.tool, Tool::Polygon | Tool::Track) || keys.just_pressed(KeyCode::Escape) {
        state.polygon.clear();
    }
    let typing = egui_input
        .as_ref()
        .is_some_and(|e| e.wants_any_keyboard_input());
    p.enter = keys.just_pressed(KeyCode::Enter) && !typing;
    let over_ui = egui_input.is_some_and(|e| e.wants_any_pointer_input());
    p.screen = view::scene_cursor(&view, window);
    p.world = p.screen.map(|c| view.to_world(c));
    p.tol = 4.0 * view.m_per_px;
    state.cursor = p.world;
    p.clicked = None;
    if buttons.just_pressed(MouseButton::Left) && !over_ui {
        if let (Some(c), Some(w)) = (p.screen, p.world) {
            p.press = Some(c);
            p.clicked = Some(w);
        }
    }
    p.held = p.world.filter(|_| buttons.pressed(MouseButton::Left));
    p.moved = match (p.press, p.screen) {
        (Some(a), Some(b)) => a.distance(b) > 3.0,
        _ => false,
    };
    p.released = buttons.just_released(MouseButton::Left);
    if p.released {
        p.press = None;
    }
}

/// Select: a click selects the body there and the point on it and grabs a moving body; a drag
/// pulls it with the mouse spring, or, paused at t = 0 where the scene is being set up, moves it
/// (an edit, undoable).
fn select_tool(mut t: ToolInput, mut ov: ResMut<Overlays>, playback: Res<Playback>) {
    let (p, tol) = (&*t.pointer, t.pointer.tol);
    if let (Tool::Select, Some(at)) = (t.state.tool, p.clicked) {
        let s = t.run.snapshot();
        match view::body_at(&t.outlines.bodies, s, at, tol, false) {
            Some(i) => {
                let b = &s.bodies[i];
                let local = DVec2::from_angle(-b.angle).rotate(at - b.position);
                ov.selected = Some(i);
                ov.point = Some((i, local));
                if b.kind == BodyKind::Dynamic {
                    t.state.grab = Some(Grab {
                        body: i,
                        local,
                        target: at,
                        pulling: false,
                    });
                }
            }
            None => {
                ov.selected = None;
                ov.point = None;
            }
        }
    }
    let (held, moved, released, world) = (p.held, p.moved, p.released, p.world);
    if let (Some(g), Some(at)) = (t.state.grab.as_mut(), held) {
        g.target = at;
        g.pulling |= moved;
    }
    if !released {
        return;
    }
    let grab = t.state.grab.take();
    if let (Some(g), Some(to)) = (grab.filter(|g| g.pulling), world) {
        if playback.paused && t.run.snapshot().is_initial() {
            if let Some(def) = t.run.scene.level.bodies.get(g.body) {
                let b = &t.run.snapshot().bodies[g.body];
                let d = to - b.world_point(g.local);
                t.edits.write(EditorCommand::Apply(Edit::Set {
                    body: def.name.clone(),
                    property: Property::Position((def.position.0 + d.x, def.position.1 + d.y)),
                }));
            }
        }
    }
}

/// Impulse: a click on a moving body aims from the point clicked, a drag sets the impulse, the
/// release strikes.
fn impulse_tool(mut t: ToolInput, mut run_commands: MessageWriter<PhysicsCommand>) {
    if let (Tool::Impulse, Some(at)) = (t.state.tool, t.pointer.clicked) {
        let s = t.run.snapshot();
        if let Some(i) = view::body_at(&t.outlines.bodies, s, at, t.pointer.tol, true) {
            let b = &s.bodies[i];
            let local = DVec2::from_angle(-b.angle).rotate(at - b.position);
            t.state.aim = Some(Aim {
                body: i,
                local,
                end: at,
            });
        }
    }
    if let (Some(a), Some(at)) = (t.state.aim.as_mut(), t.pointer.held) {
        a.end = at;
    }
    if !t.pointer.released {
        return;
    }
    if let Some(a) = t.state.aim.take() {
        let s = t.run.snapshot();
        if let Some(b) = s.bodies.get(a.body) {
            let at = b.world_point(a.local);
            let j = impulse_of_drag(b.mass, a.end - at);
            let time = s.time;
            if j.length() > 0.0 {
                run_commands.write(PhysicsCommand::Impulse {
                    body: a.body,
                    at,
                    impulse: j,
                });
                t.state.last_impulse = Some((at, j, time));
            }
        }
    }
}

/// Set O: a click puts the point O of H_O there.
fn origin_tool(pointer: Res<Pointer>, state: Res<ToolState>, mut ov: ResMut<Overlays>) {
    if let (Tool::SetOrigin, Some(at)) = (state.tool, pointer.clicked) {
        ov.origin = at;
    }
}

/// Place: a click adds the chosen body there.
fn place_tool(mut t: ToolInput) {
    if let (Tool::Place(what), Some(at)) = (t.state.tool, t.pointer.clicked) {
        let edit = what.edit_at(at, t.view.scene_size());
        t.edits.write(EditorCommand::Apply(edit));
    }
}

/// Join: a click adds the chosen joint there ([`join_at`]).
fn join_tool(mut t: ToolInput) {
    if let (Tool::Join(kind), Some(p)) = (t.state.tool, t.pointer.clicked) {
        let at = super::editor::round_point(p, t.view.scene_size());
        if let Some(e) = join_at(&t.run, &t.outlines, at, t.pointer.tol, kind) {
            t.edits.write(EditorCommand::Apply(e));
        }
    }
}

/// Ruler: a drag measures from the press to the mouse.
fn ruler_tool(pointer: Res<Pointer>, mut state: ResMut<ToolState>) {
    if let (Tool::Ruler, Some(at)) = (state.tool, pointer.clicked) {
        state.ruler = Some((at, at));
    }
    if let (Tool::Ruler, Some(at)) = (state.tool, pointer.held) {
        if let Some((_, to)) = state.ruler.as_mut() {
            *to = at;
        }
    }
}

/// Protractor: a drag from the vertex lays the first arm, the next click ends the second.
fn protractor_tool(pointer: Res<Pointer>, mut state: ResMut<ToolState>) {
    if let (Tool::Protractor, Some(p)) = (state.tool, pointer.clicked) {
        state.protractor = match state.protractor {
            // The second click ends the second arm.
            Some(pr) if !pr.dragging && pr.arm2.is_none() => Some(Protractor {
                arm2: Some(p),
                ..pr
            }),
            _ => Some(Protractor {
                vertex: p,
                arm1: p,
                arm2: None,
                dragging: true,
            }),
        }
    }
    if let Some(at) = pointer.held {
        if let Some(pr) = state.protractor.as_mut().filter(|pr| pr.dragging) {
            pr.arm1 = at;
        }
    }
    if pointer.released {
        if let Some(pr) = state.protractor.as_mut() {
            pr.dragging = false;
        }
    }
}

/// Torsion: a click adds a torsion spring on the body there ([`torsion_at`]).
fn torsion_tool(mut t: ToolInput) {
    if let (Tool::Torsion, Some(at)) = (t.state.tool, t.pointer.clicked) {
        if let Some(e) = torsion_at(&t.run, &t.outlines, at, t.pointer.tol) {
            t.edits.write(EditorCommand::Apply(e));
        }
    }
}

/// Polygon: clicks add vertices; a click on the first one, or Enter, makes the body.
fn polygon_tool(mut t: ToolInput) {
    // The outline is shared with the track tool (read_pointer keeps it while either is
    // chosen), so Enter makes a body only under this tool: under Track it makes the track.
    if t.pointer.enter && t.state.tool == Tool::Polygon && t.state.polygon.len() >= 3 {
        let points = std::mem::take(&mut t.state.polygon);
        t.edits.write(EditorCommand::Apply(polygon_body(&points)));
    }
    let (Tool::Polygon, Some(p)) = (t.state.tool, t.pointer.clicked) else {
        return;
    };
    let closes = t.state.polygon.len() >= 3 && t.state.polygon[0].distance(p) < 2.0 * t.pointer.tol;
    if closes {
        let points = std::mem::take(&mut t.state.polygon);
        t.edits.write(EditorCommand::Apply(polygon_body(&points)));
    } else {
        let at = super::editor::round_point(p, t.view.scene_size());
        if t.state.polygon.last() != Some(&at) {
            t.state.polygon.push(at);
        }
    }
}

/// Track: clicks add points; a click on the last one again, or Enter, makes the track.
fn track_tool(mut t: ToolInput) {
    if t.pointer.enter && t.state.tool == Tool::Track && t.state.polygon.len() >= 2 {
        let points = std::mem::take(&mut t.state.polygon);
        t.edits.write(EditorCommand::Apply(track_edit(&points)));
    }
    let (Tool::Track, Some(p)) = (t.state.tool, t.pointer.clicked) else {
        return;
    };
    let ends = t.state.polygon.len() >= 2
        && t.state
            .polygon
            .last()
            .is_some_and(|l| l.distance(p) < 2.0 * t.pointer.tol);
    if ends {
        let points = std::mem::take(&mut t.state.polygon);
        t.edits.write(EditorCommand::Apply(track_edit(&points)));
    } else {
        let at = super::editor::round_point(p, t.view.scene_size());
        if t.state.polygon.last() != Some(&at) {
            t.state.polygon.push(at);
        }
    }
}

/// Spring: a drag from a point on a moving body to a point on another body, or on the ground,
/// hangs a spring between them.
fn spring_tool(mut t: ToolInput) {
    let tol = t.pointer.tol;
    if let (Tool::Spring, Some(p)) = (t.state.tool, t.pointer.clicked) {
        t.state.spring_from =
            view::body_at(&t.outlines.bodies, t.run.snapshot(), p, tol, true).map(|i| (i, p));
    }
    if !t.pointer.released {
        return;
    }
    if let (Some((i, from)), Some(to)) = (t.state.spring_from.take(), t.pointer.world) {
        let s = t.run.snapshot();
        let level = &t.run.scene.level;
        let other = view::bodies_under(&t.outlines.bodies, s, to, tol)
            .into_iter()
            .find(|&k| k != i);
        if from.distance(to) > tol {
            let m = s.bodies[i].mass;
            let edit = Edit::AddSpring {
                body1: level.bodies[i].name.clone(),
                at1: (from.x, from.y),
                body2: other.map(|k| level.bodies[k].name.clone()),
                at2: (to.x, to.y),
                stiffness: spring_stiffness(m),
            };
            t.edits.write(EditorCommand::Apply(edit));
        }
    }
}

/// The joint the join tool makes at `p`: between the topmost moving body there and the next body
/// under it, or that body and the ground (a fixed point made there) when it is alone.
fn join_at(phys: &Run, outlines: &Outlines, p: DVec2, tol: f64, kind: JointKind) -> Option<Edit> {
    let (moving, other) = moving_and_partner(phys, outlines, p, tol)?;
    let name = |i: usize| phys.scene.level.bodies[i].name.clone();
    Some(Edit::AddJoint {
        kind,
        body1: other.map(name),
        body2: name(moving),
        at: (p.x, p.y),
    })
}

/// The topmost moving body at `p` and the next body under it (None: the ground), as the join
/// and torsion tools connect them.
fn moving_and_partner(
    phys: &Run,
    outlines: &Outlines,
    p: DVec2,
    tol: f64,
) -> Option<(usize, Option<usize>)> {
    let s = phys.snapshot();
    let under = view::bodies_under(&outlines.bodies, s, p, tol);
    let moving = *under
        .iter()
        .find(|&&i| s.bodies[i].kind == BodyKind::Dynamic)?;
    Some((moving, under.iter().copied().find(|&i| i != moving)))
}

/// The torsion spring the torsion tool makes at `p`: on the topmost moving body there, to the
/// next body under it or to the ground; k puts the body alone on it at about 1 Hz about G
/// (k = I_G (2 pi)^2, rounded).
fn torsion_at(phys: &Run, outlines: &Outlines, p: DVec2, tol: f64) -> Option<Edit> {
    let (moving, other) = moving_and_partner(phys, outlines, p, tol)?;
    let name = |i: usize| phys.scene.level.bodies[i].name.clone();
    let k = phys.snapshot().bodies[moving].inertia * std::f64::consts::TAU.powi(2);
    Some(Edit::AddTorsionSpring {
        body1: name(moving),
        body2: other.map(name),
        stiffness: super::editor::nice_length(k, 1.0),
    })
}

/// A 1 kg body whose outline is the clicked vertices (their convex hull, as the level format
/// takes it), its frame at their mean.
fn polygon_body(points: &[DVec2]) -> Edit {
    let mean = points.iter().copied().sum::<DVec2>() / points.len().max(1) as f64;
    Edit::AddBody {
        shape: NewShape::Polygon {
            points: points
                .iter()
                .map(|q| (q.x - mean.x, q.y - mean.y))
                .collect(),
        },
        at: (mean.x, mean.y),
        mass: 1.0,
    }
}

/// A fixed polyline track through the clicked points (world: its body at the origin), solid
/// below: on its right when it runs to +x overall, on its left when it runs to -x, so bodies
/// ride its upper side (the inspector changes it).
pub fn track_edit(points: &[DVec2]) -> Edit {
    let run = points.last().map_or(0.0, |l| l.x) - points.first().map_or(0.0, |f| f.x);
    Edit::AddTrack {
        points: points.iter().map(|q| (q.x, q.y)).collect(),
        closed: false,
        solid: Some(if run >= 0.0 {
            crate::level::TrackSide::Right
        } else {
            crate::level::TrackSide::Left
        }),
    }
}

/// A new spring's stiffness: the body on it oscillates at about 1 Hz (k = m (2 pi)^2), rounded to
/// a number a level file reads well.
fn spring_stiffness(m: f64) -> f64 {
    let k = m * std::f64::consts::TAU.powi(2);
    super::editor::nice_length(k, 1.0)
}

/// The body being dragged with the mouse spring, told to the run when it changes (the run pulls
/// it before every step while it plays, `Run::pull_held`).
fn hold_grabbed(
    state: Res<ToolState>,
    run: Res<Run>,
    mut run_commands: MessageWriter<PhysicsCommand>,
) {
    let hold = state.grab.filter(|g| g.pulling).map(|g| Hold {
        body: g.body,
        local: g.local,
        target: g.target,
    });
    if hold != run.held {
        run_commands.write(PhysicsCommand::Hold(hold));
    }
}

/// The tools' marks on this frame's drawing, over the overlays ([`preview`]).
fn draw_marks(state: Res<ToolState>, run: Res<Run>, scales: Res<Scales>, mut d: ResMut<Drawing>) {
    preview(&state, &run, &scales, &mut d);
}

/// What the tools draw: the mouse spring, the aimed impulse, the last impulse.
pub fn preview(state: &ToolState, phys: &Run, scales: &Scales, d: &mut Drawing) {
    let s = phys.snapshot();
    if let (Some((_, from)), Some(g)) = (state.spring_from, state.cursor) {
        d.prims.push(Prim::Dashed(from, g, palette::TOOL));
    }
    if let Some(&first) = state.polygon.first() {
        let mut pts = state.polygon.clone();
        pts.extend(state.cursor);
        d.prims.push(Prim::Poly(pts, false, palette::TOOL));
        // The point a click ends on: a polygon's first corner, a track's last point.
        let end = match state.tool {
            Tool::Track => state.polygon.last().copied().unwrap_or(first),
            _ => first,
        };
        d.prims.push(Prim::Dot(end, 4.0, palette::TOOL));
    }
    if let Some(pr) = state.protractor {
        protractor(pr, state.cursor, d);
    }
    if let Some((a, b)) = state.ruler.filter(|(a, b)| a != b) {
        d.prims.push(Prim::Line(a, b, palette::TOOL));
        d.prims.push(Prim::Dot(a, 3.0, palette::TOOL));
        d.prims.push(Prim::Dot(b, 3.0, palette::TOOL));
        let v = b - a;
        d.label(
            (a + b) / 2.0,
            Vec2::new(0.0, -12.0),
            format!(
                "{} at {:.1}°",
                si(v.length(), "m"),
                v.y.atan2(v.x).to_degrees()
            ),
            palette::TOOL,
        );
    }
    if let Some(g) = state.grab.filter(|g| g.pulling) {
        if let Some(b) = s.bodies.get(g.body) {
            let p = b.world_point(g.local);
            d.prims.push(Prim::Dashed(p, g.target, palette::TOOL));
            d.prims.push(Prim::Dot(g.target, 3.0, palette::TOOL));
        }
    }
    if let Some(a) = state.aim {
        if let Some(b) = s.bodies.get(a.body) {
            let p = b.world_point(a.local);
            let j = impulse_of_drag(b.mass, a.end - p);
            d.prims.push(Prim::Arrow(p, a.end, palette::TOOL));
            d.label(
                a.end,
                Vec2::new(0.0, -12.0),
                format!("J = {}", si(j.length(), "N s")),
                palette::TOOL,
            );
        }
    }
    if let Some((p, j, t)) = state.last_impulse {
        if s.time >= t && s.time - t < 1.0 {
            let len = (0.2 * scales.size).max(30.0 * d.m_per_px);
            let u = j.normalize_or_zero();
            d.prims.push(Prim::Arrow(p - u * len, p, palette::TOOL));
            d.label(
                p - u * len,
                Vec2::new(0.0, -12.0),
                format!("J = {}", si(j.length(), "N s")),
                palette::TOOL,
            );
        }
    }
}

/// The protractor's arms, the arc between them and the angle; before the second click the second
/// arm follows the cursor.
fn protractor(pr: Protractor, cursor: Option<DVec2>, d: &mut Drawing) {
    let arm2 = pr.arm2.or(cursor.filter(|_| !pr.dragging));
    d.prims.push(Prim::Line(pr.vertex, pr.arm1, palette::TOOL));
    let Some(arm2) = arm2 else {
        return;
    };
    d.prims.push(Prim::Line(pr.vertex, arm2, palette::TOOL));
    let shown = Protractor {
        arm2: Some(arm2),
        ..pr
    };
    let Some(angle) = shown.angle() else {
        return;
    };
    let (a, b) = (pr.arm1 - pr.vertex, arm2 - pr.vertex);
    let r = (0.3 * a.length().min(b.length())).max(20.0 * d.m_per_px);
    let start = a.y.atan2(a.x);
    let sweep = a.angle_to(b);
    let arc: Vec<DVec2> = (0..=24)
        .map(|k| pr.vertex + DVec2::from_angle(start + sweep * k as f64 / 24.0) * r)
        .collect();
    let mid = arc[12];
    d.prims.push(Prim::Poly(arc, false, palette::TOOL));
    d.label(
        mid,
        Vec2::new(0.0, -10.0),
        format!("{:.1}°", angle.to_degrees()),
        palette::TOOL,
    );
}
