//! Mouse tools of the sandbox: select a body and a point on it, drag a body with a mouse spring,
//! strike it with an impulse at the clicked point, set the point O for H_O.

use super::draw::{si, Drawing, Prim};
use super::overlays::{Overlays, Scales};
use super::physics::{Physics, PhysicsStep};
use super::view::{self, palette, Outlines, View};
use crate::snapshot::BodyKind;
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
    press: Option<Vec2>,
}

/// Aiming time: a drag of D meters gives the body a velocity change of about D / AIM_TIME.
pub const AIM_TIME: f64 = 0.5;

/// Mouse spring natural frequency, Hz (critically damped).
const SPRING_HZ: f64 = 1.5;

pub struct ToolsPlugin;

impl Plugin for ToolsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ToolState>()
            .add_systems(Update, mouse_tools.before(super::SceneDraw))
            .add_systems(FixedUpdate, apply_grab.before(PhysicsStep));
    }
}

/// The impulse a drag `d` (m) aims at a body of mass `m`: J = m d / AIM_TIME, N s.
pub fn impulse_of_drag(m: f64, d: DVec2) -> DVec2 {
    d * m / AIM_TIME
}

#[allow(clippy::too_many_arguments)]
fn mouse_tools(
    mut state: ResMut<ToolState>,
    mut phys: ResMut<Physics>,
    mut ov: ResMut<Overlays>,
    view: Res<View>,
    outlines: Res<Outlines>,
    buttons: Res<ButtonInput<MouseButton>>,
    windows: Query<&Window>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
) {
    let Some(window) = windows.iter().next() else {
        return;
    };
    let over_ui = egui_input.is_some_and(|e| e.wants_any_pointer_input());
    let cursor = view::scene_cursor(&view, window);
    let world = cursor.map(|c| view.to_world(c));
    let tol = 4.0 * view.m_per_px;

    if buttons.just_pressed(MouseButton::Left) && !over_ui {
        if let (Some(c), Some(p)) = (cursor, world) {
            state.press = Some(c);
            let s = phys.snapshot();
            match state.tool {
                Tool::Select => match view::body_at(&outlines.bodies, s, p, tol, false) {
                    Some(i) => {
                        let b = &s.bodies[i];
                        let local = DVec2::from_angle(-b.angle).rotate(p - b.position);
                        ov.selected = Some(i);
                        ov.point = Some((i, local));
                        if b.kind == BodyKind::Dynamic {
                            state.grab = Some(Grab {
                                body: i,
                                local,
                                target: p,
                                pulling: false,
                            });
                        }
                    }
                    None => {
                        ov.selected = None;
                        ov.point = None;
                    }
                },
                Tool::Impulse => {
                    if let Some(i) = view::body_at(&outlines.bodies, s, p, tol, true) {
                        let b = &s.bodies[i];
                        let local = DVec2::from_angle(-b.angle).rotate(p - b.position);
                        state.aim = Some(Aim {
                            body: i,
                            local,
                            end: p,
                        });
                    }
                }
                Tool::SetOrigin => ov.origin = p,
            }
        }
    }
    if buttons.pressed(MouseButton::Left) {
        if let Some(p) = world {
            let moved = match (state.press, cursor) {
                (Some(a), Some(b)) => a.distance(b) > 3.0,
                _ => false,
            };
            if let Some(g) = state.grab.as_mut() {
                g.target = p;
                g.pulling |= moved;
            }
            if let Some(a) = state.aim.as_mut() {
                a.end = p;
            }
        }
    }
    if buttons.just_released(MouseButton::Left) {
        state.grab = None;
        state.press = None;
        if let Some(a) = state.aim.take() {
            let s = phys.snapshot();
            if let Some(b) = s.bodies.get(a.body) {
                let at = b.world_point(a.local);
                let j = impulse_of_drag(b.mass, a.end - at);
                let time = s.time;
                if j.length() > 0.0 {
                    apply_impulse(&mut phys, a.body, at, j);
                    state.last_impulse = Some((at, j, time));
                }
            }
        }
    }
}

/// Applies an impulse `j` (N s) at world point `at` to body `i`, between steps: J on the mass
/// center and the angular impulse r_{P/G} x J (from the snapshot's G, which is current between steps).
pub fn apply_impulse(phys: &mut Physics, i: usize, at: DVec2, j: DVec2) {
    if phys.sim.apply_impulse(i, at, j) {
        phys.interfered = true;
    }
}

/// The mouse spring: a critically damped pull of the grabbed point toward the mouse, applied as the
/// impulse of the force over the coming step (rigidlab resets forces each step, impulses stay).
fn apply_grab(state: Res<ToolState>, mut phys: ResMut<Physics>) {
    let Some(g) = state.grab.filter(|g| g.pulling) else {
        return;
    };
    if phys.paused {
        return;
    }
    let s = phys.snapshot();
    let Some(b) = s.bodies.get(g.body) else {
        return;
    };
    let p = b.world_point(g.local);
    let v = super::quantities::point_velocity(b, p);
    let w = std::f64::consts::TAU * SPRING_HZ;
    let m = b.mass;
    // F = m (w^2 (target - p) - 2 w v_p) - m g, limited to 30 m g (or 30 m w^2 x 1 m without gravity).
    let mut f = (w * w * (g.target - p) - 2.0 * w * v) * m - s.gravity * m;
    let limit = 30.0 * m * s.gravity.length().max(w * w);
    if f.length() > limit {
        f = f.normalize() * limit;
    }
    let dt = phys.sim.dt();
    apply_impulse(&mut phys, g.body, p, f * dt);
}

/// What the tools draw: the mouse spring, the aimed impulse, the last impulse.
pub fn preview(state: &ToolState, phys: &Physics, scales: &Scales, d: &mut Drawing) {
    let s = phys.snapshot();
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
