//! Box2D on a thread of its own, for the window: boxdd's `World` is `!Send` (Box2D keeps a
//! world on its owner thread), and the window's run lives in a Bevy resource that Bevy may touch
//! from any thread, so the window cannot hold a Box2D world itself. [`Threaded`] holds a thread
//! that owns the [`Simulation`] and answers each step with its snapshot over a channel, which is
//! boxdd's own advice for multi-threaded applications. The runner drives [`Simulation`]
//! directly (one thread, no copies); this costs the window one snapshot copy and a channel round
//! trip per step.

use super::world::Simulation;
use crate::level::{Level, LevelError, Scene};
use crate::sim::{Options, Settings, SimError};
use crate::snapshot::Snapshot;
use glam::DVec2;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Mutex;

/// What the window asks of the Box2D thread.
enum Ask {
    Step,
    /// A blow between steps: body index, world point (m), impulse (N s).
    Impulse(usize, DVec2, DVec2),
    ContactReadings(bool),
}

/// The thread's answers, one per ask that needs one.
enum Answer {
    /// Boxed: a snapshot is large, the other answers a bool.
    Stepped(Box<Result<Snapshot, SimError>>),
    Impulse(bool),
}

/// A Box2D simulation owned by a thread of its own (see the module's doc).
pub struct Threaded {
    pub level: Level,
    pub settings: Settings,
    snapshot: Snapshot,
    total_steps: u64,
    asks: Mutex<Sender<Ask>>,
    answers: Mutex<Receiver<Answer>>,
}

/// What the thread sends once the world is built.
type Built = Result<(Level, Settings, Snapshot, u64), LevelError>;

impl Threaded {
    /// Builds the level's Box2D world on a new thread, or refuses it as
    /// [`Simulation::new`] does (the level item Box2D cannot run, located).
    pub fn new(scene: &Scene, opts: &Options) -> Result<Self, LevelError> {
        let (scene, opts) = (scene.clone(), opts.clone());
        let (built_tx, built_rx) = channel::<Built>();
        let (ask_tx, ask_rx) = channel::<Ask>();
        let (answer_tx, answer_rx) = channel::<Answer>();
        let file = scene.file.clone();
        let spawned = std::thread::Builder::new()
            .name("rigidlab box2d".into())
            .spawn(move || {
                let mut sim = match Simulation::new(&scene, &opts) {
                    Ok(s) => s,
                    Err(e) => {
                        let _ = built_tx.send(Err(e));
                        return;
                    }
                };
                let built = (
                    sim.level.clone(),
                    sim.settings.clone(),
                    sim.snapshot().clone(),
                    sim.total_steps(),
                );
                if built_tx.send(Ok(built)).is_err() {
                    return;
                }
                serve(&mut sim, &ask_rx, &answer_tx);
            });
        let lost = |why: String| {
            LevelError::new(
                &file,
                (0, 0),
                format!("the Box2D thread could not run this level: {why}"),
                "run this level on rapier (--engine rapier)",
            )
        };
        spawned.map_err(|e| lost(e.to_string()))?;
        let (level, settings, snapshot, total_steps) = built_rx
            .recv()
            .map_err(|_| lost("it stopped while building".into()))??;
        Ok(Threaded {
            level,
            settings,
            snapshot,
            total_steps,
            asks: Mutex::new(ask_tx),
            answers: Mutex::new(answer_rx),
        })
    }

    pub fn dt(&self) -> f64 {
        self.settings.dt
    }

    pub fn total_steps(&self) -> u64 {
        self.total_steps
    }

    pub fn snapshot(&self) -> &Snapshot {
        &self.snapshot
    }

    /// Asks the thread for one step and keeps its snapshot.
    pub fn step(&mut self) -> Result<&Snapshot, SimError> {
        match self.ask(Ask::Step) {
            Some(Answer::Stepped(r)) => {
                self.snapshot = (*r)?;
                Ok(&self.snapshot)
            }
            _ => Err(SimError {
                step: self.snapshot.step + 1,
                time: self.snapshot.time,
                body: String::new(),
                quantity: "could not be stepped: the Box2D thread stopped".into(),
            }),
        }
    }

    /// Runs the whole duration, calling `each` with every snapshot (the initial one first).
    pub fn run(&mut self, mut each: impl FnMut(&Snapshot)) -> Result<(), SimError> {
        each(&self.snapshot);
        while self.snapshot.step < self.total_steps {
            each(self.step()?);
        }
        Ok(())
    }

    pub fn set_contact_readings(&mut self, on: bool) {
        let _ = self.send(Ask::ContactReadings(on));
    }

    /// A blow between steps (`Simulation::apply_impulse`); false when it could not be applied.
    pub fn apply_impulse(&mut self, i: usize, at: DVec2, j: DVec2) -> bool {
        matches!(
            self.ask(Ask::Impulse(i, at, j)),
            Some(Answer::Impulse(true))
        )
    }

    fn send(&self, a: Ask) -> Option<()> {
        self.asks.lock().ok()?.send(a).ok()
    }

    fn ask(&self, a: Ask) -> Option<Answer> {
        self.send(a)?;
        self.answers.lock().ok()?.recv().ok()
    }
}

/// The thread's loop: answers each ask until the window drops its end.
fn serve(sim: &mut Simulation, asks: &Receiver<Ask>, answers: &Sender<Answer>) {
    while let Ok(a) = asks.recv() {
        let answer = match a {
            Ask::Step => Answer::Stepped(Box::new(sim.step().cloned())),
            Ask::Impulse(i, at, j) => Answer::Impulse(sim.apply_impulse(i, at, j)),
            Ask::ContactReadings(on) => {
                sim.set_contact_readings(on);
                continue;
            }
        };
        if answers.send(answer).is_err() {
            return;
        }
    }
}
