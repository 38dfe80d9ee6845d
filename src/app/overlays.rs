//! The overlays the textbook draws, built from the snapshot as lines and labels: velocity and
//! acceleration vectors, the instantaneous center of zero velocity, the free-body diagram beside
//! the kinetic diagram, angular momentum about a point, trails.

use super::draw::{si, Drawing, Prim};
use super::geometry::{self, Outline};
use super::names;
use super::quantities::{self, ForceKind};
use super::run::Run;
use super::view::palette;
use crate::analysis::frame::{diagram_balance, DiagramBalance};
use crate::analysis::kinematics::body_point_velocity;
use crate::analysis::momentum::scene_angular_momentum_about;
use crate::level::{Effect, Level};
use crate::snapshot::{BodyKind, Snapshot};
use bevy::prelude::*;
use glam::DVec2;

/// Which overlays are on (panel check boxes and keys) and what they are about.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct Overlays {
    /// V: velocity of each mass center (and of the clicked point).
    pub velocity: bool,
    /// A: acceleration of each mass center.
    pub acceleration: bool,
    /// C: instantaneous center of zero velocity, with lines to G and to the clicked point.
    pub instant_center: bool,
    /// F: free-body diagram.
    pub free_body: bool,
    /// K: kinetic diagram (m a_G, I_G alpha) beside the free-body diagram.
    pub kinetic: bool,
    /// H: angular momentum about the point O.
    pub momentum: bool,
    /// T: trails of the mass centers.
    pub trails: bool,
    /// L: magnitudes next to the arrows.
    pub labels: bool,
    /// N: each body's and joint's name beside it (on by default: the statement names them).
    pub names: bool,
    /// The body the diagrams are about (None: every moving body when there are few).
    pub selected: Option<usize>,
    /// A clicked point, in the selected body's frame.
    pub point: Option<(usize, DVec2)>,
    /// The point O for H_O, world frame.
    pub origin: DVec2,
    /// Arrow lengths times this (the panel's slider; the longest arrow stays clipped).
    pub arrow_scale: f64,
    /// Kinds of force left out of the free-body diagram (the panel's per-force boxes).
    pub hidden_forces: Vec<ForceKind>,
    /// Each force's x and y components drawn dashed, with their values.
    pub components: bool,
    /// In a [`crowd`], trails and velocity and acceleration arrows for every moving body, not
    /// only the selected one (the panel's box; off by default and again when a level opens).
    pub every_body: bool,
}

impl Default for Overlays {
    fn default() -> Self {
        Overlays {
            velocity: true,
            acceleration: false,
            instant_center: false,
            free_body: false,
            kinetic: false,
            momentum: false,
            trails: true,
            labels: true,
            names: true,
            selected: None,
            point: None,
            origin: DVec2::ZERO,
            arrow_scale: 1.0,
            hidden_forces: Vec::new(),
            components: false,
            every_body: false,
        }
    }
}

/// Diagrams are drawn for every moving body up to this many; beyond it, only for the selected one.
const FEW: usize = 4;

/// The number of moving bodies when the scene is a crowd (more than
/// [`CROWD_BODIES`](super::ball_meshes::CROWD_BODIES), where its balls are drawn by shared
/// meshes): then the per-body overlays (trails, velocity and acceleration arrows) are drawn for
/// the selected body only, unless [`Overlays::every_body`] asks for all. Every grain of a
/// 10,000-grain pile with its two arrows and its trail made 30,000 lines a frame, 16 ms of
/// drawing, and no single one could be read (docs/benchmarks.md, "10,000 bodies"). None for a
/// smaller scene.
pub fn crowd(s: &Snapshot) -> Option<usize> {
    super::ball_meshes::crowd_of(s.bodies.iter().map(|b| b.kind))
}

/// The longest arrow, as a fraction of the scene size (longer ones are clipped, their label is true).
const MAX_ARROW: f64 = 0.45;

/// Reference magnitudes that set the arrow scales: a reference maps to `REF_ARROW` of the scene.
/// As a resource, this frame's (set by the scene's drawing before the overlays draw).
#[derive(Resource, Debug, Clone, Copy, Default)]
pub struct Scales {
    /// m/s, m/s^2, N.
    pub speed: f64,
    pub accel: f64,
    pub force: f64,
    /// Scene size, m.
    pub size: f64,
    pub m_per_px: f64,
    /// The visible world rectangle (min, max), when known: diagrams drawn beside a body go to
    /// the side that has room.
    pub visible: Option<(DVec2, DVec2)>,
    /// The user's arrow scale (1: as computed).
    pub gain: f64,
}

/// The longest arrow on screen, px (an impact's contact force would leave the view).
const MAX_ARROW_PX: f64 = 170.0;

const REF_ARROW: f64 = 0.15;

impl Scales {
    /// Scales from the scene: gravity and the heaviest body set forces; the fastest speed so far
    /// sets velocities (it only grows, so arrows do not flicker).
    pub fn of(s: &Snapshot, size: f64, speed_so_far: f64, m_per_px: f64) -> Scales {
        let g = s.gravity.length();
        let heaviest = s
            .bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Dynamic)
            .map(|b| b.mass)
            .fold(0.0, f64::max);
        let loads = s.loads.iter().map(|l| l.force.length()).fold(0.0, f64::max);
        let springs = s
            .springs
            .iter()
            .map(|l| l.tension.abs())
            .fold(0.0, f64::max);
        let force = (heaviest * g).max(loads).max(springs);
        Scales {
            speed: speed_so_far.max((g * size).sqrt() * 0.5).max(1e-3),
            accel: if g > 0.0 { g } else { 1.0 },
            force: if force > 0.0 { force } else { 1.0 },
            size,
            m_per_px,
            visible: None,
            gain: 1.0,
        }
    }

    fn len(&self, magnitude: f64, reference: f64) -> f64 {
        (self.gain * magnitude / reference * REF_ARROW * self.size)
            .min(MAX_ARROW * self.size)
            .min(MAX_ARROW_PX * self.m_per_px)
    }

    /// An arrow of `vector` (with reference `reference`) from `from`.
    fn arrow(&self, from: DVec2, vector: DVec2, reference: f64) -> DVec2 {
        let m = vector.length();
        if m == 0.0 {
            return from;
        }
        from + vector / m * self.len(m, reference)
    }
}

/// What the window says of a [`crowd`] while a per-body overlay is on: whose trails and arrows
/// are drawn. None outside a crowd or with those overlays off.
pub fn crowd_note(ov: &Overlays, s: &Snapshot) -> Option<String> {
    let n = crowd(s)?;
    let per_body = ov.velocity || ov.acceleration || ov.trails;
    // A fixed body selected has no trail or arrow to show: the note asks for a moving one.
    let moving_selected = ov
        .selected
        .and_then(|i| s.bodies.get(i))
        .is_some_and(|b| b.kind != BodyKind::Fixed);
    (per_body && !ov.every_body).then(|| {
        if moving_selected {
            format!("trails and arrows: the selected body only (a crowd of {n})")
        } else {
            format!("trails and arrows: click a moving body (a crowd of {n}: one at a time)")
        }
    })
}

/// The bodies the diagrams are about.
fn subjects(ov: &Overlays, s: &Snapshot) -> Vec<usize> {
    if let Some(i) = ov.selected.filter(|i| *i < s.bodies.len()) {
        return vec![i];
    }
    let moving: Vec<usize> = s
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| b.kind == BodyKind::Dynamic)
        .map(|(i, _)| i)
        .collect();
    if moving.len() <= FEW {
        moving
    } else {
        Vec::new()
    }
}

fn force_color(k: ForceKind) -> Color {
    match k {
        ForceKind::Gravity => palette::GRAVITY,
        ForceKind::ContactNormal => palette::NORMAL,
        ForceKind::Friction => palette::FRICTION,
        ForceKind::Joint => palette::REACTION,
        ForceKind::Spring => palette::SPRING,
        ForceKind::Load | ForceKind::Blow => palette::LOAD,
        ForceKind::Coupling => palette::COUPLING,
    }
}

/// What every overlay of a frame reads: the switches, the run, the shapes and scales, and which
/// bodies get arrows and labels.
struct Frame<'a> {
    ov: &'a Overlays,
    run: &'a Run,
    s: &'a Snapshot,
    outlines: &'a [Outline],
    scales: &'a Scales,
    /// The bodies the per-body overlays are drawn for ([`subjects`]).
    few: Vec<usize>,
    labels: bool,
    /// Every moving body is a subject: each gets its labels.
    label_all: bool,
    /// The bodies that get trails and velocity and acceleration arrows: every moving one, or in
    /// a [`crowd`] the subjects only.
    per_body: Vec<usize>,
    /// Meters per pixel.
    px: f64,
}

impl<'a> Frame<'a> {
    /// The frame of `phys` drawn at `px` meters per pixel.
    fn new(
        ov: &'a Overlays,
        phys: &'a Run,
        outlines: &'a [Outline],
        scales: &'a Scales,
        px: f64,
    ) -> Frame<'a> {
        let s = phys.snapshot();
        let few = subjects(ov, s);
        let label_all = ov.labels
            && few.len()
                == s.bodies
                    .iter()
                    .filter(|b| b.kind == BodyKind::Dynamic)
                    .count();
        let crowded = crowd(s).is_some() && !ov.every_body;
        let per_body = s
            .bodies
            .iter()
            .enumerate()
            .filter(|(i, b)| b.kind != BodyKind::Fixed && (!crowded || few.contains(i)))
            .map(|(i, _)| i)
            .collect();
        Frame {
            ov,
            run: phys,
            s,
            outlines,
            scales,
            few,
            labels: ov.labels,
            label_all,
            per_body,
            px,
        }
    }
}

/// One overlay: what draws it and the switch that turns it on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Overlay {
    Names,
    Trails,
    Velocity,
    Acceleration,
    InstantCenters,
    CentersOfPercussion,
    Diagrams,
    Blows,
    Momentum,
}

impl Overlay {
    /// Every overlay in drawing order (later ones over earlier ones, their labels placed after).
    /// The names come first: their labels take the spots beside the bodies, the magnitudes
    /// find room around them.
    pub const ALL: [Overlay; 9] = [
        Overlay::Names,
        Overlay::Trails,
        Overlay::Velocity,
        Overlay::Acceleration,
        Overlay::InstantCenters,
        Overlay::CentersOfPercussion,
        Overlay::Diagrams,
        Overlay::Blows,
        Overlay::Momentum,
    ];

    /// Whether `ov` turns it on (the blows of the last step are always drawn).
    pub fn is_on(self, ov: &Overlays) -> bool {
        match self {
            Overlay::Names => ov.names,
            Overlay::Trails => ov.trails,
            Overlay::Velocity => ov.velocity,
            Overlay::Acceleration => ov.acceleration,
            Overlay::InstantCenters | Overlay::CentersOfPercussion => ov.instant_center,
            Overlay::Diagrams => ov.free_body || ov.kinetic,
            Overlay::Blows => true,
            Overlay::Momentum => ov.momentum,
        }
    }

    /// Draws it into `d` (whether or not it is on).
    pub fn draw(
        self,
        ov: &Overlays,
        phys: &Run,
        outlines: &[Outline],
        scales: &Scales,
        d: &mut Drawing,
    ) {
        let f = Frame::new(ov, phys, outlines, scales, d.m_per_px);
        match self {
            Overlay::Names => names::names(f.s, &phys.sim.level.joints, outlines, ov.selected, d),
            Overlay::Trails => trails(&f, d),
            Overlay::Velocity => velocities(&f, d),
            Overlay::Acceleration => accelerations(&f, d),
            Overlay::InstantCenters => instant_centers(&f, d),
            Overlay::CentersOfPercussion => centers_of_percussion(&f, d),
            Overlay::Diagrams => diagrams(&f, d),
            Overlay::Blows => blows(phys, scales, ov.labels, d),
            Overlay::Momentum => momentum(&f, d),
        }
    }
}

/// Builds every enabled overlay into `d`, in drawing order ([`Overlay::ALL`]): names, trails,
/// velocities, accelerations, instantaneous centers, centers of percussion, free-body and
/// kinetic diagrams, blows, H_O. The window draws them with one system each
/// (`overlay_systems.rs`), in the same order.
pub fn build(ov: &Overlays, phys: &Run, outlines: &[Outline], scales: &Scales, d: &mut Drawing) {
    for o in Overlay::ALL {
        if o.is_on(ov) {
            o.draw(ov, phys, outlines, scales, d);
        }
    }
}

/// The trail of each moving body's mass center (of the selected one in a crowd).
fn trails(f: &Frame, d: &mut Drawing) {
    for &i in &f.per_body {
        let Some(trail) = f.run.trails.get(i) else {
            continue;
        };
        if trail.len() > 1 {
            d.prims.push(Prim::Poly(
                trail.iter().copied().collect(),
                false,
                palette::TRAIL,
            ));
        }
    }
}

/// v_G of each moving body (of the selected one in a crowd), and v_P of the point the user
/// picked.
fn velocities(f: &Frame, d: &mut Drawing) {
    for &i in &f.per_body {
        let b = &f.s.bodies[i];
        let tip = f.scales.arrow(b.com, b.velocity, f.scales.speed);
        d.prims.push(Prim::Arrow(b.com, tip, palette::VELOCITY));
        if f.labels && (f.label_all || f.few.contains(&i)) && b.velocity.length() > 1e-9 {
            d.tip_label(
                tip,
                b.velocity,
                format!("v_G = {}", si(b.velocity.length(), "m/s")),
                palette::VELOCITY,
            );
        }
    }
    if let Some((i, local)) = f.ov.point.filter(|(i, _)| *i < f.s.bodies.len()) {
        let b = &f.s.bodies[i];
        let p = b.world_point(local);
        let v = body_point_velocity(b, p);
        let tip = f.scales.arrow(p, v, f.scales.speed);
        d.prims.push(Prim::Dot(p, 3.0, palette::VELOCITY));
        d.prims.push(Prim::Arrow(p, tip, palette::VELOCITY));
        if f.labels {
            d.tip_label(
                tip,
                v,
                format!("v_P = {}", si(v.length(), "m/s")),
                palette::VELOCITY,
            );
        }
    }
}

/// a_G of each moving body (of the selected one in a crowd), from the velocities before the
/// last step.
fn accelerations(f: &Frame, d: &mut Drawing) {
    let s = f.s;
    let acc = f
        .run
        .prev_velocities
        .as_ref()
        .map(|(prev, dt)| quantities::accelerations(s, prev, *dt));
    if let Some(acc) = &acc {
        for &i in &f.per_body {
            let (Some(b), Some((a, _))) = (f.s.bodies.get(i), acc.get(i)) else {
                continue;
            };
            let tip = f.scales.arrow(b.com, *a, f.scales.accel);
            d.prims.push(Prim::Arrow(b.com, tip, palette::ACCEL));
            if f.labels && (f.label_all || f.few.contains(&i)) && a.length() > 1e-9 {
                d.tip_label(
                    tip,
                    *a,
                    format!("a_G = {}", si(a.length(), "m/s²")),
                    palette::ACCEL,
                );
            }
        }
    }
}

/// The instantaneous center of each subject, with its lines to G and to the picked point.
fn instant_centers(f: &Frame, d: &mut Drawing) {
    for &i in &f.few {
        let b = &f.s.bodies[i];
        let size = f
            .outlines
            .get(i)
            .map_or(0.0, |o| extent(o, b.local_com))
            .max(0.01);
        match quantities::instant_center(b, size) {
            Some(c) if (c - b.com).length() < 50.0 * f.scales.size => {
                d.prims.push(Prim::Dot(c, 4.0, palette::CENTER));
                d.prims.push(Prim::Dashed(c, b.com, palette::CENTER));
                if let Some((_, local)) = f.ov.point.filter(|(j, _)| *j == i) {
                    d.prims
                        .push(Prim::Dashed(c, b.world_point(local), palette::CENTER));
                }
                if f.labels {
                    let r = (b.com - c).length();
                    d.label(
                        c,
                        Vec2::new(0.0, 14.0),
                        format!(
                            "IC  (r_G/IC = {}, ω = {})",
                            si(r, "m"),
                            si(b.omega, "rad/s")
                        ),
                        palette::CENTER,
                    );
                }
            }
            _ => {
                if f.labels && b.velocity.length() > 1e-3 * f.scales.speed {
                    // Beside the body, across from the velocity arrow.
                    let r = f.outlines.get(i).map_or(0.0, |o| extent(o, b.local_com));
                    let away = -b.velocity.perp().normalize_or(DVec2::Y);
                    d.tip_label(
                        b.com + away * r,
                        away,
                        "IC at infinity (translation)",
                        palette::CENTER,
                    );
                }
            }
        }
    }
}

/// The center of percussion of each subject turning about a fixed pivot.
fn centers_of_percussion(f: &Frame, d: &mut Drawing) {
    for &i in &f.few {
        if let Some((o, p, q)) = center_of_percussion(f.run, i) {
            d.prims.push(Prim::Dashed(o, p, palette::CENTER));
            d.prims.push(Prim::Circle(p, 5.0 * f.px, palette::CENTER));
            d.prims.push(Prim::Line(
                p - DVec2::new(5.0, 5.0) * f.px,
                p + DVec2::new(5.0, 5.0) * f.px,
                palette::CENTER,
            ));
            d.prims.push(Prim::Line(
                p - DVec2::new(5.0, -5.0) * f.px,
                p + DVec2::new(5.0, -5.0) * f.px,
                palette::CENTER,
            ));
            if f.labels {
                d.tip_label(
                    p,
                    p - o,
                    format!("center of percussion, q = {}", si(q, "m")),
                    palette::CENTER,
                );
            }
        }
    }
}

/// The free-body diagram and the kinetic diagram beside it, of each moving subject.
fn diagrams(fr: &Frame, d: &mut Drawing) {
    let s = fr.s;
    // Kinetic diagrams already placed this frame: the next one keeps off them too.
    let mut copies: Vec<geometry::Bounds> = Vec::new();
    for &i in &fr.few {
        let b = &fr.s.bodies[i];
        if b.kind != BodyKind::Dynamic {
            continue;
        }
        // Mean forces over the last frame's steps when the step is short
        // (see free_body_arrows_mean): the steps between the snapshots kept, the same
        // steps the kinetic diagram's balance is taken over.
        let (forces, couple) = if fr.run.recent.len() > 1 {
            quantities::free_body_arrows_mean(quantities::with_previous(&fr.run.recent).skip(1), i)
        } else {
            quantities::free_body_arrows(None, s, i)
        };
        if fr.ov.free_body {
            for f in forces
                .iter()
                .filter(|f| !fr.ov.hidden_forces.contains(&f.kind))
            {
                let color = force_color(f.kind);
                let len = fr.scales.len(f.force.length(), fr.scales.force);
                let u = f.force.normalize_or_zero();
                // Textbook convention: a push (contact, or any force toward G) is drawn ending at
                // its point, from outside; a pull (tension) starts at its point.
                // A force at the end of a light link (off the body's shape) is drawn along the
                // link, ending at its point, so it stays beside the body it acts on.
                let local = DVec2::from_angle(-b.angle).rotate(f.point - b.position);
                let off_shape = fr
                    .outlines
                    .get(i)
                    .is_some_and(|o| !o.filled.is_empty() && !o.contains(local, 2.0 * fr.px));
                // Reactions (contacts, pins, cables) are drawn ending at their point.
                let pushes = matches!(
                    f.kind,
                    ForceKind::ContactNormal
                        | ForceKind::Friction
                        | ForceKind::Joint
                        | ForceKind::Coupling
                ) || (f.kind != ForceKind::Gravity
                    && (off_shape || f.force.dot(b.com - f.point) > 0.0));
                let (mut a, mut z) = if pushes {
                    (f.point - u * len, f.point)
                } else {
                    (f.point, f.point + u * len)
                };
                if f.kind == ForceKind::Friction {
                    // Friction lies along the contact surface, right on the other body's
                    // outline, which hid it: drawn a few pixels off the surface, on the
                    // body's side.
                    let to_g = b.com - f.point;
                    let side = (to_g - u * to_g.dot(u)).normalize_or_zero();
                    a += side * 5.0 * fr.px;
                    z += side * 5.0 * fr.px;
                }
                if len < 2.0 * fr.px {
                    continue;
                }
                d.prims.push(Prim::Arrow(a, z, color));
                if fr.ov.components {
                    // x and y components from the arrow's tail, dashed, each with its value.
                    let v = z - a;
                    for (c, axis, value) in [
                        (DVec2::new(v.x, 0.0), "x", f.force.x),
                        (DVec2::new(0.0, v.y), "y", f.force.y),
                    ] {
                        if c.length() > 4.0 * fr.px {
                            d.prims.push(Prim::Dashed(a, a + c, color));
                            if fr.labels {
                                d.tip_label(
                                    a + c,
                                    c,
                                    format!("{}_{axis} = {}", f.kind.symbol(), si(value, "N")),
                                    color,
                                );
                            }
                        }
                    }
                }
                if fr.labels {
                    // At the free end of the arrow: the tail for pushes, the head for pulls.
                    let (at, dir) = if pushes { (a, -u) } else { (z, u) };
                    d.tip_label(
                        at,
                        dir,
                        format!("{} = {}", f.kind.symbol(), si(f.force.length(), "N")),
                        color,
                    );
                }
            }
            if couple.abs() > 1e-9 {
                d.prims.push(Prim::Curl(b.com, 16.0, couple, palette::LOAD));
                if fr.labels {
                    d.label(
                        b.com,
                        Vec2::new(24.0, 20.0),
                        format!("M = {}", si(couple, "N m")),
                        palette::LOAD,
                    );
                }
            }
        }
        if fr.ov.kinetic {
            // sum F, sum M_G, m a_G and I_G alpha as the newton_euler check sums them, over
            // the same steps as the arrows (analysis::frame::diagram_balance).
            let balance = if fr.run.recent.len() > 1 {
                diagram_balance(&fr.run.recent, i)
            } else {
                None
            };
            if let Some(balance) = balance {
                kinetic_diagram(
                    i,
                    s,
                    fr.outlines,
                    &balance,
                    fr.scales,
                    fr.labels,
                    &mut copies,
                    d,
                );
            }
        }
    }
}

/// H about the point O.
fn momentum(f: &Frame, d: &mut Drawing) {
    let s = f.s;
    let o = f.ov.origin;
    let h = scene_angular_momentum_about(s, o);
    d.prims.push(Prim::Dot(o, 3.0, palette::MOMENTUM));
    d.prims.push(Prim::Curl(
        o,
        22.0,
        if h == 0.0 { 1.0 } else { h },
        palette::MOMENTUM,
    ));
    if f.labels {
        d.label(
            o,
            Vec2::new(0.0, 34.0),
            format!("H_O = {}", si(h, "N m s")),
            palette::MOMENTUM,
        );
    }
}

/// The level's blows from their time on: the impulse as an arrow ending where it struck (fixed
/// length: a blow has no force scale) and, at each joint of the struck body, the joint's impulsive
/// response over the blow's step.
fn blows(phys: &Run, scales: &Scales, labels: bool, d: &mut Drawing) {
    let now = phys.snapshot().time;
    let len = (0.2 * scales.size).max(30.0 * d.m_per_px);
    for blow in phys.blows.iter().filter(|b| b.time <= now + 1e-12) {
        let u = blow.impulse.normalize_or_zero();
        d.prims
            .push(Prim::Arrow(blow.point - u * len, blow.point, palette::TOOL));
        if labels {
            d.label(
                blow.point - u * len,
                Vec2::new(0.0, -12.0),
                format!(
                    "P = {} at t = {:.3} s",
                    si(blow.impulse.length(), "N s"),
                    blow.time
                ),
                palette::TOOL,
            );
        }
        for j in &blow.joints {
            let imp = j.impulsive();
            if imp.length() * 1e3 < blow.impulse.length() {
                // Under a thousandth of the blow: the joint felt none of it (a strike at the
                // center of percussion). Say so rather than draw nothing.
                if labels {
                    d.label(
                        j.anchor,
                        Vec2::new(0.0, 18.0),
                        format!("{}: no impulsive reaction", j.joint),
                        palette::REACTION,
                    );
                }
                continue;
            }
            let v = imp.normalize_or_zero() * len * (imp.length() / blow.impulse.length()).min(1.0);
            d.prims
                .push(Prim::Arrow(j.anchor - v, j.anchor, palette::REACTION));
            if labels {
                d.label(
                    j.anchor - v,
                    Vec2::new(0.0, 18.0),
                    format!("{}: ∫R dt = {}", j.joint, si(imp.length(), "N s")),
                    palette::REACTION,
                );
            }
        }
    }
}

/// The center of percussion of body `i` if it is pinned to a fixed body: on the line from the pin O
/// through G at q = k_O^2 / r_G from O (MK art. 6/4, eq. 6/5 with I_O = I_G + m r_G^2). A blow
/// there leaves the pin without reaction. Returns (O, P, q).
pub fn center_of_percussion(phys: &Run, i: usize) -> Option<(DVec2, DVec2, f64)> {
    let s = phys.snapshot();
    let b = s.bodies.get(i)?;
    if b.kind != BodyKind::Dynamic || b.mass <= 0.0 {
        return None;
    }
    let level = &phys.sim.level;
    s.joints.iter().enumerate().find_map(|(k, j)| {
        let revolute = level
            .joints
            .get(k)
            .is_some_and(|d| d.kind == crate::level::JointKind::Revolute);
        let o = if j.body2 == i && s.bodies[j.body1].kind == BodyKind::Fixed {
            j.anchor
        } else if j.body1 == i && s.bodies[j.body2].kind == BodyKind::Fixed {
            j.anchor1
        } else {
            return None;
        };
        if !revolute || (b.com - o).length() < 1e-9 {
            return None;
        }
        let p = crate::analysis::percussion::center_of_percussion(o, b.com, b.inertia, b.mass)?;
        Some((o, p, (p - o).length()))
    })
}

/// Largest distance of the outline from the mass center, m.
fn extent(o: &Outline, com: DVec2) -> f64 {
    o.points().map(|p| (p - com).length()).fold(0.0, f64::max)
}

/// The kinetic diagram of body `i` drawn to the right of it: m a_G at G and I_G alpha as a curl
/// (MK art. 6/2: the free-body diagram "equals" the kinetic diagram). The label gives sum F and
/// sum M_G too, from the same sums the `newton_euler` check compares (`balance`), so the student
/// sees Newton's law hold to the check's residual.
#[allow(clippy::too_many_arguments)]
fn kinetic_diagram(
    i: usize,
    s: &Snapshot,
    outlines: &[Outline],
    balance: &DiagramBalance,
    scales: &Scales,
    labels: bool,
    copies: &mut Vec<geometry::Bounds>,
    d: &mut Drawing,
) {
    let b = &s.bodies[i];
    let px = d.m_per_px;
    let o = &outlines[i];
    let r = extent(o, b.local_com).max(8.0 * px);
    // Beside the body: its current width plus a gap.
    let here = geometry::place(o, b.position, b.angle);
    let mut aabb = geometry::Bounds::empty();
    o.points().for_each(|p| aabb.add(here(p)));
    let width = if aabb.is_empty() {
        2.0 * r
    } else {
        aabb.size().x
    };
    let height = if aabb.is_empty() {
        2.0 * r
    } else {
        aabb.size().y
    };
    let shift = free_side(
        i,
        s,
        outlines,
        copies,
        &aabb,
        width,
        height,
        scales.visible,
        px,
    );
    if !aabb.is_empty() {
        copies.push(geometry::Bounds {
            min: aabb.min + shift,
            max: aabb.max + shift,
        });
    }
    let to_world = geometry::place(o, b.position + shift, b.angle);
    for poly in &o.filled {
        let copy: Vec<DVec2> = poly.iter().map(|p| to_world(*p)).collect();
        // The copy is a body to the label placer: its sums box and the other labels were laid
        // over it (issue 42: 190 labels over a copy on the library, 11 after).
        d.bodies.push(copy.clone());
        d.prims.push(Prim::Poly(copy, true, palette::OUTLINE));
    }
    let g = b.com + shift;
    d.prims.push(Prim::Circle(g, 3.0 * px, palette::OUTLINE));
    let ma = balance.mass_acceleration;
    let tip = scales.arrow(g, ma, scales.force);
    d.prims.push(Prim::Arrow(g, tip, palette::ACCEL));
    let ia = balance.inertia_alpha;
    // alpha is a difference quotient: a couple below 1e-3 of (force scale x body size) is noise
    // (a sliding block shows 1e-7 N m), drawn as none; the label keeps the number.
    if ia.abs() > 1e-3 * scales.force * r {
        d.prims.push(Prim::Curl(g, 14.0, ia, palette::ACCEL));
    }
    let (sum, sum_m) = (balance.force, balance.moment_g);
    d.label(b.com + 0.5 * shift, Vec2::ZERO, "=", palette::TEXT);
    if labels {
        d.tip_label(
            tip,
            ma,
            format!("m a_G = {}", si(ma.length(), "N")),
            palette::ACCEL,
        );
        // Under the "=" between the two diagrams: free space by construction (free_side).
        d.label(
            b.com + 0.5 * shift,
            Vec2::new(0.0, 30.0),
            format!(
                "ΣF = {} · m a_G = {}\nΣM_G = {} · I_G α = {}",
                si(sum.length(), "N"),
                si(ma.length(), "N"),
                si(sum_m, "N m"),
                si(ia, "N m")
            ),
            palette::TEXT,
        );
    }
}

/// Where the kinetic diagram of body `i` goes: beside the body (right, left, below, above, in
/// that order of preference), a gap of 90 px away, at the first side where the copy lies inside
/// the view and over no other body; failing that, the side that overlaps least (bodies first,
/// then the view's edge). Returns the shift from the body to its copy, m.
#[allow(clippy::too_many_arguments)]
fn free_side(
    i: usize,
    s: &Snapshot,
    outlines: &[Outline],
    copies: &[geometry::Bounds],
    aabb: &geometry::Bounds,
    width: f64,
    height: f64,
    visible: Option<(DVec2, DVec2)>,
    px: f64,
) -> DVec2 {
    let gap = 90.0 * px;
    let sides = [
        DVec2::new(width + gap, 0.0),
        DVec2::new(-(width + gap), 0.0),
        DVec2::new(0.0, -(height + gap)),
        DVec2::new(0.0, height + gap),
    ];
    if aabb.is_empty() {
        return sides[0];
    }
    // The other bodies' boxes (ground and walls included: a diagram inside the incline is the
    // issue this avoids).
    let mut others: Vec<geometry::Bounds> = s
        .bodies
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != i)
        .filter_map(|(k, b)| {
            let o = outlines.get(k)?;
            let here = geometry::place(o, b.position, b.angle);
            let mut bb = geometry::Bounds::empty();
            o.points().for_each(|p| bb.add(here(p)));
            (!bb.is_empty()).then_some(bb)
        })
        .collect();
    others.extend_from_slice(copies);
    let overlap = |a: &geometry::Bounds, b: &geometry::Bounds| -> f64 {
        let w = (a.max.x.min(b.max.x) - a.min.x.max(b.min.x)).max(0.0);
        let h = (a.max.y.min(b.max.y) - a.min.y.max(b.min.y)).max(0.0);
        w * h
    };
    let cost = |shift: DVec2| -> (f64, f64) {
        let copy = geometry::Bounds {
            min: aabb.min + shift,
            max: aabb.max + shift,
        };
        let on_bodies: f64 = others.iter().map(|o| overlap(&copy, o)).sum();
        let outside = match visible {
            Some((lo, hi)) => {
                let view = geometry::Bounds { min: lo, max: hi };
                (copy.size().x * copy.size().y - overlap(&copy, &view)).max(0.0)
            }
            None => 0.0,
        };
        (on_bodies, outside)
    };
    let mut best = (sides[0], (f64::INFINITY, f64::INFINITY));
    for side in sides {
        let c = cost(side);
        if c.0 <= 0.0 && c.1 <= 0.0 {
            return side;
        }
        // Least area over the view's edge first (a clipped diagram cannot be read), then over bodies.
        if (c.1, c.0) < (best.1 .1, best.1 .0) {
            best = (side, c);
        }
    }
    best.0
}

/// Keys: V A C F K H T L N toggle the overlays.
pub fn overlay_keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut ov: ResMut<Overlays>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
    typing: Option<Res<super::ui::Typing>>,
) {
    // Not while a text field has or had the keyboard (a typed path toggled overlays).
    let egui_wants = egui_input.is_some_and(|e| e.wants_any_keyboard_input());
    if !super::ui::Typing::shortcuts_on(typing.as_deref(), egui_wants) {
        return;
    }
    let ov = &mut *ov;
    for (key, flag) in [
        (KeyCode::KeyV, &mut ov.velocity),
        (KeyCode::KeyA, &mut ov.acceleration),
        (KeyCode::KeyC, &mut ov.instant_center),
        (KeyCode::KeyF, &mut ov.free_body),
        (KeyCode::KeyK, &mut ov.kinetic),
        (KeyCode::KeyH, &mut ov.momentum),
        (KeyCode::KeyT, &mut ov.trails),
        (KeyCode::KeyL, &mut ov.labels),
        (KeyCode::KeyN, &mut ov.names),
    ] {
        if keys.just_pressed(key) {
            *flag = !*flag;
        }
    }
}

/// The color key of the overlays that are on (force kinds only where the scene has them).
/// `averaged`: the steps the forces are averaged over and their span, s (`Run::steps_averaged`).
pub fn legend_entries(
    ov: &Overlays,
    level: &Level,
    averaged: (usize, f64),
) -> Vec<(String, Color)> {
    let (window, span) = averaged;
    let mut v = Vec::new();
    let mut add = |on: bool, text: &str, c: Color| {
        if on {
            v.push((format!("— {text}"), c));
        }
    };
    add(ov.velocity, "velocity v_G", palette::VELOCITY);
    add(ov.acceleration, "acceleration a_G", palette::ACCEL);
    add(
        ov.instant_center,
        "instantaneous center IC",
        palette::CENTER,
    );
    if ov.free_body {
        let has = |e: Effect| level.effects.contains(&e);
        add(has(Effect::Gravity), "weight mg", palette::GRAVITY);
        add(has(Effect::Contacts), "contact normal N", palette::NORMAL);
        add(has(Effect::Friction), "friction F", palette::FRICTION);
        add(
            !level.joints.is_empty(),
            "joint reaction R",
            palette::REACTION,
        );
        add(!level.couplings.is_empty(), "coupling T", palette::COUPLING);
        add(!level.springs.is_empty(), "spring Fs", palette::SPRING);
        add(!level.loads.is_empty(), "load P", palette::LOAD);
    }
    add(ov.kinetic, "kinetic diagram m a_G, I_G α", palette::ACCEL);
    add(ov.momentum, "angular momentum H_O", palette::MOMENTUM);
    add(ov.trails, "trail of G", palette::TRAIL);
    if (ov.free_body || ov.kinetic) && window > 1 {
        v.push((
            format!(
                "forces: mean over the last {window} steps ({} s)",
                super::time_text::instant(span)
            ),
            palette::TEXT,
        ));
    }
    v
}
