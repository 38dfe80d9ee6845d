//! The sweep on an engine other than rapier (Box2D v3), reached only through the runner's entry
//! (`runner::engine_for`, `sim::Drive`): the same runs as rapier's (`measure.rs`), each a whole
//! `Drive::run_each`.
//!
//! What differs from rapier's sweep, and why:
//! - **precision**: Box2D runs in f32 only, so its sweep has no f64 curve and its baseline is
//!   f32 (as rapier's is); a level whose `world.precision` is f64 is studied in f32 on both
//!   engines, the precision axis being the study's own ([`prepared`]);
//! - **PGS iterations**: Box2D v3's soft-step solver has no such knob (one relax iteration per
//!   substep), so its sweep has no iterations curve (`plan::points_on`);
//! - **reference**: the self-consistency reference is the engine's own run at the reference's
//!   dt and substeps, in f32 (rapier's is its f64 build): the method's "engine's own run at a
//!   very small step";
//! - **restarted pieces**: `Drive` has no way to set a running world's state, so a piece is a
//!   fresh run of the scene whose bodies *start* at the reference's state (pose of the body
//!   frame, velocity of the mass center, angular velocity; the level's own initial-state fields),
//!   with its clock shifted as rapier's pieces are ([`restarted`]).

use super::measure::{self, graded_run, Conservation, ConservationLog, FullRun, Reference};
use super::{metrics, Setting};
use crate::clock::Instant;
use crate::level::{BodyKind, PhysicsEngine, Scene};
use crate::runner::{engine_for, Observers, RunError};
use crate::sim::Drive;
use crate::snapshot::{BodyState, Snapshot};
use std::time::Duration;

/// One engine of `--engine` (a comma-separated list: "rapier,box2d").
pub fn parse_engine(s: &str) -> Result<PhysicsEngine, String> {
    match s.trim() {
        "rapier" => Ok(PhysicsEngine::Rapier),
        "box2d" => Ok(PhysicsEngine::Box2d),
        other => Err(format!("\"{other}\": write rapier, box2d or rapier,box2d")),
    }
}

/// The scene as `engine` studies it: on Box2D, in f32 (the study's precision axis is its own;
/// Box2D has no f64 build).
pub fn prepared(scene: &Scene, engine: PhysicsEngine) -> Scene {
    let mut s = scene.clone();
    if !engine.is_rapier() {
        s.level.world.precision = crate::level::Precision::F32;
    }
    s
}

/// Why `engine` refuses the (prepared) scene, with the level item and the feature, or None
/// when it runs it: asked of the runner's entry at the level's own settings.
pub fn refused(scene: &Scene, engine: PhysicsEngine) -> Option<String> {
    if engine.is_rapier() {
        return None;
    }
    let setting = Setting::of_level(&scene.level).on(engine);
    match engine_for(scene, &setting.options()) {
        Ok(_) => None,
        Err(RunError::Level(e)) => Some(format!(
            "refused by {}: {}:{}: {}",
            engine.name(),
            e.line,
            e.col,
            e.message
        )),
        Err(e) => Some(format!("refused by {}: {e}", engine.name())),
    }
}

/// The engine of `setting` built for `scene`, or why not.
fn built(scene: &Scene, setting: &Setting) -> Result<Box<dyn Drive>, String> {
    engine_for(scene, &setting.options()).map_err(|e| e.to_string())
}

/// [`measure::full_run`] on another engine.
pub fn full_run(scene: &Scene, setting: &Setting) -> FullRun {
    let mut sim = match built(scene, setting) {
        Ok(s) => s,
        Err(e) => return stopped_run(e),
    };
    let level = &scene.level;
    let mut observers = Observers::new(level);
    let mut joint_drift: Option<f64> = None;
    let ran = sim.run_each(&mut |s: &Snapshot| {
        observers.observe(s);
        if let Some(d) = metrics::max_joint_separation(s, level) {
            joint_drift = Some(joint_drift.map_or(d, |m: f64| m.max(d)));
        }
    });
    match ran {
        Ok(()) => graded_run(observers, joint_drift),
        Err(e) => stopped_run(e.to_string()),
    }
}

fn stopped_run(why: String) -> FullRun {
    FullRun {
        ran: true,
        stopped: Some(why),
        ..FullRun::default()
    }
}

/// [`measure::conservation`] on another engine (`scene` already lasts the span).
pub fn conservation(scene: &Scene, setting: &Setting, what: metrics::Conserved) -> Conservation {
    let stopped = |e: String| Conservation {
        stopped: Some(e),
        ..Conservation::default()
    };
    let mut sim = match built(scene, setting) {
        Ok(s) => s,
        Err(e) => return stopped(e),
    };
    let n = (scene.level.world.duration / setting.dt).round().max(1.0) as usize + 1;
    let mut log = ConservationLog::new(scene, n);
    match sim.run_each(&mut |s: &Snapshot| log.observe(s)) {
        Ok(()) => log.finish(what),
        Err(e) => stopped(e.to_string()),
    }
}

/// The engine's own run at the reference's dt and substeps, in f32 (Box2D has no f64).
pub fn reference(scene: &Scene, setting: &Setting) -> Reference {
    let setting = Setting {
        precision: measure::Precision::F32,
        ..*setting
    };
    let mut states = Vec::new();
    let stopped = match built(scene, &setting) {
        Ok(mut sim) => sim
            .run_each(&mut |s: &Snapshot| states.push(s.bodies.clone()))
            .err()
            .map(|e| e.to_string()),
        Err(e) => Some(e),
    };
    Reference {
        setting,
        states,
        stopped,
    }
}

/// A copy of `scene` whose clock starts at `t0` (as [`measure::shifted`]), lasting `span`, with
/// every non-fixed body starting at its state in `bodies` (the reference's at `t0`).
pub fn restarted(scene: &Scene, t0: f64, h_ref: f64, span: f64, bodies: &[BodyState]) -> Scene {
    let mut s = measure::with_duration(&measure::shifted(scene, t0, h_ref), span);
    for b in s.level.bodies.iter_mut() {
        if b.kind == BodyKind::Fixed {
            continue;
        }
        if let Some(r) = bodies.iter().find(|r| r.name == b.name) {
            b.position = (r.position.x, r.position.y);
            b.angle = r.angle;
            b.velocity = (r.velocity.x, r.velocity.y);
            b.omega = r.omega;
        }
    }
    s
}

/// [`measure::self_consistency`] on another engine: each piece a fresh run of the scene
/// restarted at the reference's state ([`restarted`]).
pub fn self_consistency(
    scene: &Scene,
    setting: &Setting,
    reference: &Reference,
    pieces: usize,
    piece: f64,
) -> Result<f64, String> {
    let h_ref = reference.setting.dt;
    measure::mean_piece_deviation(
        scene,
        setting,
        reference,
        pieces,
        piece,
        |t0, steps, start| {
            let span = steps as f64 * setting.dt;
            let mut sim = built(&restarted(scene, t0, h_ref, span, start), setting)?;
            sim.run_each(&mut |_| {}).map_err(|e| e.to_string())?;
            Ok(sim.snapshot().bodies.clone())
        },
    )
}

/// [`measure::cost_sample`] on another engine: the engine built outside the timer, the whole
/// run (`Drive::run_each`, its snapshots handed to nobody) timed, the fastest run kept.
pub fn cost_sample(scene: &Scene, setting: &Setting, min_total: Duration) -> Option<f64> {
    measure::fastest_run(min_total, || {
        let mut sim = built(scene, setting).ok()?;
        let steps = (scene.level.world.duration / setting.dt).round().max(1.0);
        let start = Instant::now();
        sim.run_each(&mut |_| {}).ok()?;
        Some((start.elapsed(), steps * setting.dt))
    })
}
