//! The physics plugin: the [`Run`] stepped in `FixedUpdate` at the level's dt, as the
//! [`Playback`] says, and the one system that changes the run on request ([`PhysicsCommand`]).
//!
//! One `FixedUpdate` = one `Simulation::step`, with `Time<Fixed>` set to the level's dt, so the
//! window computes exactly the numbers `rigidlab check` computes (tests/suite/app/plugins.rs asserts it bit for
//! bit). Time scale acts on `Time<Virtual>`, never on dt.
//!
//! Panels, keys, mouse tools and the editor never change the run themselves: they write a
//! [`PhysicsCommand`], which [`apply_commands`] applies in `Update` before the frame's manual
//! steps and seeks (in the [`PhysicsStep`] set). Every way the window changes the run is a
//! variant of that enum.

use super::playback::{self, Playback};
use super::run::{Hold, Run};
use crate::checks::CheckResult;
use crate::clock::Instant;
use crate::level::Scene;
use crate::questions::QuestionResult;
use crate::runner::Observers;
use crate::sim::Options;
use bevy::prelude::*;
use glam::DVec2;
use std::time::Duration;

/// The set the physics step runs in (in `FixedUpdate`, and in `Update` for the commands, single
/// steps and seeks). A system that writes [`PhysicsCommand`]s in `Update` runs before it, so its
/// commands are applied in the same frame.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct PhysicsStep;

/// A change to the run or its playback, asked for by a panel, a key, a mouse tool or the editor,
/// applied by [`apply_commands`].
#[derive(Message, Debug, Clone, PartialEq)]
pub enum PhysicsCommand {
    /// Play or pause; at the level's end (when the run stops there) play starts over
    /// ([`playback::toggle_play`]).
    TogglePlay,
    /// One physics step (dt), paused.
    Step,
    /// One step back, paused: the run replayed to the step before ([`playback::step_back`]).
    StepBack,
    /// Back to t = 0 as the level opened ([`playback::restart`]).
    Restart,
    /// Go to this step (the timeline): back is replayed from t = 0.
    Seek(u64),
    /// Pause at the level's end (where `rigidlab check` stops), or run past it.
    StopAtEnd(bool),
    /// Run with these solver settings from t = 0 (the solver panel, the advice; the default is
    /// the level's own).
    Settings(Options),
    /// Another level (the level browser, a file picked in the page): paused, at the level's
    /// settings, the camera refitted.
    Open(Box<Scene>),
    /// The scene as the editor left it, from t = 0, paused; `refit`: the camera fits it (a new
    /// scene) rather than keeping the user's view.
    Edited { scene: Box<Scene>, refit: bool },
    /// An impulse (N s) at a world point of a body, now (the impulse tool).
    Impulse {
        body: usize,
        at: DVec2,
        impulse: DVec2,
    },
    /// The body the mouse spring holds, or none (the select tool's drag).
    Hold(Option<Hold>),
    /// The body whose plots are kept whatever the scene's size (the selected one).
    Track(Option<usize>),
    /// Hold the run at t = 0 until the student's answers are in (predict first), paused and
    /// from the start; or let it run again. Held, [`refused_now`] says what is refused.
    AnswerFirst(bool),
}

/// Runs a scene: inserts [`Run`], [`Playback`] and [`LiveChecks`] and steps in `FixedUpdate`.
pub struct PhysicsPlugin {
    pub scene: Scene,
    pub options: Options,
    /// Start paused (the sandbox waits for play; tests and renders run at once).
    pub paused: bool,
}

impl Plugin for PhysicsPlugin {
    fn build(&self, app: &mut App) {
        let run = Run::new(self.scene.clone(), self.options.clone());
        app.insert_resource(Time::<Fixed>::from_seconds(run.sim.dt()));
        app.insert_non_send(LiveChecks::new(&run));
        app.insert_resource(run);
        app.insert_resource(Playback::new(self.paused));
        app.add_message::<PhysicsCommand>();
        app.add_systems(PreUpdate, new_frame);
        app.add_systems(
            FixedUpdate,
            (fixed_step, observe_checks).chain().in_set(PhysicsStep),
        );
        app.add_systems(
            Update,
            (
                apply_commands,
                seek,
                manual_steps,
                observe_checks,
                sync_fixed_timestep,
            )
                .chain()
                .in_set(PhysicsStep),
        );
    }
}

/// How long a frame may spend seeking, ms (the window stays responsive on a long seek).
const SEEK_BUDGET_MS: f64 = 40.0;

/// The one place the window's requests change the run: each [`PhysicsCommand`] in the order
/// written.
pub fn apply_commands(
    mut commands: MessageReader<PhysicsCommand>,
    mut run: ResMut<Run>,
    mut playback: ResMut<Playback>,
) {
    for c in commands.read() {
        apply(c.clone(), &mut run, &mut playback);
    }
}

/// What would run a run held at t = 0 for the student's answers: play (pausing is allowed),
/// single steps either way, the timeline, and the impulse tool's pushes, which would change the
/// motion to be predicted.
pub fn refused_now(c: &PhysicsCommand, playback: &Playback) -> bool {
    playback.answer_first
        && match c {
            PhysicsCommand::TogglePlay => playback.paused,
            PhysicsCommand::Step
            | PhysicsCommand::StepBack
            | PhysicsCommand::Seek(_)
            | PhysicsCommand::Impulse { .. } => true,
            _ => false,
        }
}

/// What one command does to the run and its playback (nothing, counted in `refused`, when
/// the run is held for the answers and the command would run it).
pub fn apply(c: PhysicsCommand, run: &mut Run, playback: &mut Playback) {
    if refused_now(&c, playback) {
        playback.refused += 1;
        return;
    }
    match c {
        PhysicsCommand::TogglePlay => playback::toggle_play(run, playback),
        PhysicsCommand::Step => {
            playback.paused = true;
            playback.steps_requested += 1;
        }
        PhysicsCommand::StepBack => playback::step_back(run, playback),
        PhysicsCommand::Restart => playback::restart(run, playback),
        PhysicsCommand::Seek(step) => run.seek = Some(step),
        PhysicsCommand::StopAtEnd(on) => playback.stop_at_end = on,
        PhysicsCommand::Settings(options) => {
            run.options = options;
            playback.steps_requested = 0;
            run.reset();
        }
        PhysicsCommand::Open(scene) => {
            run.options = Default::default();
            playback.stop_at_end = true;
            playback.paused = true;
            playback.steps_requested = 0;
            run.load(*scene);
        }
        PhysicsCommand::Edited { scene, refit } => {
            playback.steps_requested = 0;
            if refit {
                run.load(*scene);
            } else {
                run.load_keep_view(*scene);
            }
            playback.paused = true;
        }
        PhysicsCommand::Impulse { body, at, impulse } => {
            run.apply_impulse(body, at, impulse);
        }
        PhysicsCommand::Hold(h) => run.held = h,
        PhysicsCommand::Track(body) => run.track(body),
        PhysicsCommand::AnswerFirst(hold) => {
            playback.answer_first = hold;
            if hold {
                playback.paused = true;
                playback.steps_requested = 0;
                if run.snapshot().step > 0 || run.interfered || run.seek.is_some() {
                    playback::restart(run, playback);
                }
            }
        }
    }
}

/// One step of a playing run: the step, then a pause at an error or at the level's end (when
/// the run stops there). False when the run cannot go on.
pub fn play_step(run: &mut Run, playback: &mut Playback) -> bool {
    if !run.advance() {
        playback.paused = true;
        return false;
    }
    if playback.stop_at_end && run.at_end() {
        playback.paused = true;
    }
    true
}

fn fixed_step(mut run: ResMut<Run>, mut playback: ResMut<Playback>) {
    if playback.paused {
        return;
    }
    // The mouse spring pulls before every fixed update of a playing run.
    run.pull_held();
    // The first step of a frame always runs, so one FixedUpdate is always one step.
    if playback.frame_ms > playback.frame_budget_ms {
        playback.behind = true;
        return;
    }
    let t0 = Instant::now();
    play_step(&mut run, &mut playback);
    playback.frame_ms += t0.elapsed().as_secs_f64() * 1e3;
}

fn new_frame(mut playback: ResMut<Playback>) {
    playback.frame_ms = 0.0;
}

/// The timeline and step back: seeks within a frame's budget, the live checks seeing every step;
/// a seek that ends leaves the run paused.
fn seek(mut run: ResMut<Run>, mut playback: ResMut<Playback>, mut live: NonSendMut<LiveChecks>) {
    if run.seek.is_none() {
        return;
    }
    let generation = run.generation;
    let done = run.seek_steps(SEEK_BUDGET_MS, |p| live.observe(p));
    if run.generation != generation {
        // Rewound: single steps asked for the run before are dropped, as by a reset.
        playback.steps_requested = 0;
    }
    if done {
        playback.paused = true;
    }
}

fn manual_steps(mut run: ResMut<Run>, mut playback: ResMut<Playback>) {
    while playback.steps_requested > 0 {
        playback.steps_requested -= 1;
        if !play_step(&mut run, &mut playback) {
            playback.steps_requested = 0;
        }
    }
}

/// Keeps `Time<Fixed>` at the simulation's dt after solver changes.
fn sync_fixed_timestep(run: Res<Run>, mut fixed: ResMut<Time<Fixed>>) {
    let dt = Duration::from_secs_f64(run.sim.dt());
    if fixed.timestep() != dt {
        fixed.set_timestep(dt);
    }
}

/// The level's checks and questions, fed every snapshot as `rigidlab check` feeds them.
///
/// Non-send because `checks::Probe` is not `Send`; results appear when the level's duration is
/// reached (a probe reports only when finished).
pub struct LiveChecks {
    generation: u64,
    last_step: Option<u64>,
    /// None once finished.
    observers: Option<Observers>,
    /// Set at the level's end: the same results `rigidlab check` prints.
    pub checks: Option<Vec<CheckResult>>,
    pub answers: Option<Vec<QuestionResult>>,
    /// The level's challenge: its goal's verdict, at the level's end.
    pub challenge: Option<crate::questions::ChallengeResult>,
}

impl LiveChecks {
    pub fn new(phys: &Run) -> Self {
        let level = &phys.sim.level;
        let mut live = LiveChecks {
            generation: phys.generation,
            last_step: Some(0),
            observers: Some(Observers::new(level)),
            checks: None,
            answers: None,
            challenge: None,
        };
        if let Some(o) = live.observers.as_mut() {
            o.observe(&phys.initial);
        }
        live
    }

    /// Feeds the current snapshot once (idempotent within a step), finishing at the level's end.
    pub fn observe(&mut self, phys: &Run) {
        if self.generation != phys.generation {
            *self = LiveChecks::new(phys);
        }
        let s = phys.snapshot();
        if self.last_step == Some(s.step) || self.checks.is_some() {
            return;
        }
        self.last_step = Some(s.step);
        if let Some(o) = self.observers.as_mut() {
            o.observe(s);
        }
        if phys.at_end() {
            if let Some(o) = self.observers.take() {
                let (checks, answers, challenge) = o.finish_all(&Default::default());
                self.checks = Some(checks);
                self.answers = Some(answers);
                self.challenge = challenge;
            }
        }
    }
}

fn observe_checks(phys: Res<Run>, mut live: NonSendMut<LiveChecks>) {
    live.observe(&phys);
}
