//! Predict first (issue 42): the student answers before seeing the motion. The scene waits at
//! t = 0 with its diagrams drawn (play, step, the timeline and pushes are refused: the run is
//! held, `physics::refused_now`) until every question has an answer or the student gives up;
//! then the motion plays from t = 0, and at the level's end each answer shows beside the
//! engine's and the analysis's values, with the overlay that explains the quantity switched on
//! for the body it is about, at the instant it was read.
//!
//! A level asks for it with `predict_first: true`; the switch at the top of the left panel
//! turns it on for any level (and is remembered). [`follow`] moves the phases on and holds the
//! run; `predict` draws the switch and the results. The answers checked before the motion
//! are the predictions, graded with the level's student rule; their grades are held back until
//! the motion has run (`Exercise::hold_grades`), so an answer cannot be tried until it is right
//! first. An answer changed after the motion is graded as usual but is no prediction.

use super::super::overlays::Overlays;
use super::super::physics::{LiveChecks, PhysicsCommand};
use super::super::playback::Playback;
use super::super::run::Run;
use super::super::ui::{fmt, rich};
use super::super::view::palette;
use super::exercise::{grade_message, Exercise};
use crate::level::{BodyKind, Level, Quantity};
use crate::questions::{QuestionResult, StudentGrade};
use bevy::prelude::*;
use bevy_egui::egui;
use std::path::PathBuf;

/// Where a predict-first exercise is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Phase {
    /// Not predicting: the run plays as usual.
    #[default]
    Off,
    /// The run waits at t = 0 for the answers.
    Predicting,
    /// The answers are in (or the student gave up): the motion plays to the level's end.
    Watching,
    /// The end was reached: each prediction beside the run's values.
    Revealed,
}

impl Phase {
    /// As the web page's status names it.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Off => "off",
            Phase::Predicting => "predicting",
            Phase::Watching => "watching",
            Phase::Revealed => "revealed",
        }
    }
}

/// An answer checked before the motion: what was typed and its grade.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    pub typed: String,
    pub grade: StudentGrade,
}

/// The predict-first state of the open level.
#[derive(Resource, Debug, Clone, Default)]
pub struct Predict {
    /// Predict first in every level (the switch; remembered in the preferences).
    pub everywhere: bool,
    pub phase: Phase,
    /// Per question, the answer checked last before the motion.
    pub predictions: Vec<Option<Prediction>>,
    /// "I give up / show me" was pressed.
    pub gave_up: bool,
    /// The run's question results at the level's end (the checks table's, kept: a seek back
    /// starts the live checks over).
    pub results: Vec<QuestionResult>,
    /// The question whose overlay is on.
    pub shown: Option<usize>,
    /// A question to show next frame (the reveal, a row's button).
    pub show: Option<usize>,
    /// The switch was changed: predict first everywhere or not, from next frame.
    pub switch: Option<bool>,
    /// The level this state is of: its file and its `Run::view_generation` (a level opened).
    level: Option<(PathBuf, u64)>,
    /// `Playback::refused` when the panel last looked.
    refused_seen: u32,
}

impl Predict {
    /// A level opens (or the switch changed): predicting when `on` and there is a question.
    fn begin(&mut self, on: bool, questions: usize) {
        self.phase = if on && questions > 0 {
            Phase::Predicting
        } else {
            Phase::Off
        };
        self.predictions = vec![None; questions];
        self.gave_up = false;
        self.results.clear();
        self.shown = None;
        self.show = None;
    }

    /// The answers the student has checked, taken as the predictions while predicting.
    fn take_answers(&mut self, ex: &Exercise) {
        for (k, p) in self.predictions.iter_mut().enumerate() {
            if let (Some(Some(Ok(g))), Some(typed)) = (ex.grades.get(k), ex.answers.get(k)) {
                *p = Some(Prediction {
                    typed: typed.trim().to_string(),
                    grade: g.clone(),
                });
            }
        }
    }

    /// How many questions have a prediction.
    pub fn answered(&self) -> usize {
        self.predictions.iter().filter(|p| p.is_some()).count()
    }
}

/// Moves predict first on, once a frame before the physics: a level opened or the switch
/// changed starts predicting; every answer in (or "I give up") plays the motion; the end
/// reached shows the results and the first question's overlay. Holds the run at t = 0 while
/// predicting.
#[allow(clippy::too_many_arguments)]
pub fn follow(
    phys: Res<Run>,
    play: Res<Playback>,
    live: NonSend<LiveChecks>,
    mut ex: ResMut<Exercise>,
    mut pred: ResMut<Predict>,
    mut ov: ResMut<Overlays>,
    mut out: MessageWriter<PhysicsCommand>,
) {
    let level = &phys.sim.level;
    let n = level.questions.len();
    let key = (phys.scene.file.clone(), phys.view_generation);
    if pred.level.as_ref() != Some(&key) {
        pred.level = Some(key);
        let on = level.predict_first || pred.everywhere;
        pred.begin(on, n);
    }
    if let Some(on) = pred.switch.take() {
        pred.everywhere = on;
        pred.begin(on, n);
        // Answers checked before the switch was on were not predictions.
        ex.grades.iter_mut().for_each(|g| *g = None);
    }
    let mut start_motion = false;
    match pred.phase {
        Phase::Predicting => {
            pred.take_answers(&ex);
            if pred.gave_up || pred.answered() == n {
                pred.phase = Phase::Watching;
                start_motion = true;
            }
        }
        Phase::Watching => {
            if let Some(answers) = &live.answers {
                pred.results = answers.clone();
                pred.phase = Phase::Revealed;
                pred.show = Some(0);
            }
        }
        Phase::Off | Phase::Revealed => {}
    }
    if let Some(k) = pred.show.take() {
        pred.shown = Some(k);
        show(k, &phys, &pred.results, &mut ov, &mut out);
    }
    let hold = pred.phase == Phase::Predicting;
    if play.answer_first != hold {
        out.write(PhysicsCommand::AnswerFirst(hold));
    }
    if start_motion && play.paused {
        out.write(PhysicsCommand::TogglePlay);
    }
    // The grades show with the results, at the end of the motion.
    ex.hold_grades = matches!(pred.phase, Phase::Predicting | Phase::Watching);
    ex.revealed = pred.phase == Phase::Revealed;
}

/// What explains a quantity: one of the window's overlays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Explain {
    Velocity,
    Acceleration,
    InstantCenter,
    FreeBody,
    Momentum,
    Trails,
}

/// The overlay that explains a quantity, by the quantity's SI unit: speeds the velocity
/// arrows, accelerations the acceleration arrows, forces, torques and impulses the free-body
/// diagram, angular momentum H about its point, positions, angles and times the trails. Any
/// other unit (energies, works, powers, ratios) gets the velocities, the sandbox's default.
const EXPLAINS: [(&str, Explain); 11] = [
    ("m/s", Explain::Velocity),
    ("rad/s", Explain::Velocity),
    ("m/s^2", Explain::Acceleration),
    ("rad/s^2", Explain::Acceleration),
    ("N", Explain::FreeBody),
    ("N m", Explain::FreeBody),
    ("N s", Explain::FreeBody),
    ("kg m^2/s", Explain::Momentum),
    ("m", Explain::Trails),
    ("rad", Explain::Trails),
    ("s", Explain::Trails),
];

impl Explain {
    /// The overlay for `q` (the table `EXPLAINS`); a link's speed read through its instantaneous
    /// center shows that center.
    pub fn of(q: &Quantity, level: &Level) -> Explain {
        if matches!(q, Quantity::LinkOmega { .. } | Quantity::PinSpeed { .. }) {
            return Explain::InstantCenter;
        }
        let unit = q.si_unit(level);
        EXPLAINS
            .iter()
            .find(|(u, _)| *u == unit)
            .map_or(Explain::Velocity, |(_, e)| *e)
    }

    /// The overlay's name and key, as the help lists it.
    pub fn name(self) -> &'static str {
        match self {
            Explain::Velocity => "velocity (V)",
            Explain::Acceleration => "acceleration (A)",
            Explain::InstantCenter => "instantaneous center (C)",
            Explain::FreeBody => "free-body diagram (F)",
            Explain::Momentum => "angular momentum (H)",
            Explain::Trails => "trail (T)",
        }
    }

    /// Switches the overlay on, with the magnitudes beside the arrows.
    fn switch_on(self, ov: &mut Overlays) {
        match self {
            Explain::Velocity => ov.velocity = true,
            Explain::Acceleration => ov.acceleration = true,
            Explain::InstantCenter => {
                ov.instant_center = true;
                ov.velocity = true;
            }
            Explain::FreeBody => ov.free_body = true,
            Explain::Momentum => ov.momentum = true,
            Explain::Trails => ov.trails = true,
        }
        ov.labels = true;
    }
}

/// The moving body a quantity is about: the first moving body it names, else the moving body
/// of the first joint it names (a pin's reaction, a motor's torque).
pub fn subject(q: &Quantity, level: &Level) -> Option<usize> {
    let moving = |name: &str| {
        level
            .bodies
            .iter()
            .position(|b| b.name == name && b.kind != BodyKind::Fixed)
    };
    crate::level::quantity_refs(q)
        .into_iter()
        .find_map(|(kind, name)| match kind {
            "body" => moving(name),
            "joint" => level
                .joints
                .iter()
                .find(|j| j.name == *name)
                .and_then(|j| moving(&j.body2).or_else(|| moving(&j.body1))),
            _ => None,
        })
}

/// Shows question `k`: its overlay on, its body selected (the diagrams are then drawn for it
/// alone), O at its point for H, and the run at the instant the question was read.
fn show(
    k: usize,
    phys: &Run,
    results: &[QuestionResult],
    ov: &mut Overlays,
    out: &mut MessageWriter<PhysicsCommand>,
) {
    let level = &phys.sim.level;
    let Some(q) = level.questions.get(k) else {
        return;
    };
    Explain::of(&q.quantity, level).switch_on(ov);
    ov.selected = subject(&q.quantity, level);
    ov.point = None;
    if let Quantity::AngularMomentumAbout { point, .. } = q.quantity {
        ov.origin = glam::DVec2::new(point.0, point.1);
    }
    let Some(r) = results.get(k).filter(|r| r.time.is_finite()) else {
        return;
    };
    let step = (r.time / phys.sim.dt()).round().max(0.0) as u64;
    if step != phys.snapshot().step {
        out.write(PhysicsCommand::Seek(step));
    }
}

/// What the status line says when the held run refused play, a step, the timeline or a push.
pub const ANSWER_FIRST: &str =
    "answer first: the motion plays once every question has an answer (or press \"I give up / show me\" at the top left)";

/// The top of the left panel: the switch, then what to do now (predict, watch) or the results.
pub(super) fn predict(
    ui: &mut egui::Ui,
    (phys, play): (&Run, &Playback),
    ex: &Exercise,
    pred: &mut Predict,
    message: &mut Option<(String, bool)>,
) {
    let level = &phys.sim.level;
    if level.questions.is_empty() {
        return;
    }
    if play.refused != pred.refused_seen {
        pred.refused_seen = play.refused;
        *message = Some((ANSWER_FIRST.to_string(), false));
    }
    if pred.phase != Phase::Predicting && message.as_ref().is_some_and(|m| m.0 == ANSWER_FIRST) {
        // Answered: the note no longer holds.
        *message = None;
    }
    let mut on = pred.phase != Phase::Off;
    ui.horizontal_wrapped(|ui| {
        let switch = ui.checkbox(&mut on, "Predict first").on_hover_text(
            "Answer the questions before you see the motion: the scene waits at t = 0, then \
             plays, and your answers show beside the run's values.",
        );
        if switch.changed() {
            pred.switch = Some(on);
        }
        if level.predict_first {
            ui.label(rich("(this exercise asks for it)", palette::OUTLINE).small());
        }
    });
    match pred.phase {
        Phase::Off => {}
        Phase::Predicting => predicting(ui, level, pred),
        Phase::Watching => {
            ui.label(rich(
                format!(
                    "Watch: the motion plays from t = 0. Your answers and the run's values show at its end (t = {:.2} s).",
                    level.world.duration
                ),
                palette::VELOCITY,
            ));
            if let Some(e) = &phys.error {
                ui.label(rich(e.clone(), palette::NORMAL));
            }
        }
        // In the left column's scroll area, with the questions under it: one scroll bar.
        Phase::Revealed => results(ui, level, ex, pred),
    }
    ui.separator();
}

/// While predicting: what to do, how many answers are in, and the way out.
fn predicting(ui: &mut egui::Ui, level: &Level, pred: &mut Predict) {
    let n = level.questions.len();
    ui.label(rich(
        "The scene waits at t = 0. Answer every question below (Check or Enter) before you \
         see the motion: it plays once all are answered, and your answers are graded after it.",
        palette::VELOCITY,
    ));
    ui.horizontal_wrapped(|ui| {
        ui.label(format!("answered {} of {n}", pred.answered()));
        if ui
            .button("I give up / show me")
            .on_hover_text(
                "play the motion now; the questions you did not answer count as not predicted",
            )
            .clicked()
        {
            pred.gave_up = true;
        }
    });
}

/// After the motion: each question's prediction beside the engine's, the analysis's and the
/// textbook's values, whether the answer changed since, and the button that shows it.
fn results(ui: &mut egui::Ui, level: &Level, ex: &Exercise, pred: &mut Predict) {
    ui.strong("Your predictions against the run");
    ui.label(
        rich(
            "engine: what the simulation did · analysis: the textbook's formula applied to the \
             engine's state · textbook: the exercise's answer",
            palette::OUTLINE,
        )
        .small(),
    );
    for (k, q) in level.questions.iter().enumerate() {
        let r = pred.results.get(k).cloned();
        ui.group(|ui| {
            ui.label(format!("{}. {}", k + 1, q.ask));
            match pred.predictions.get(k).cloned().flatten() {
                Some(p) => {
                    let (text, right) = grade_message(q, &Ok(p.grade.clone()));
                    let color = if right {
                        palette::GRAVITY
                    } else {
                        palette::NORMAL
                    };
                    // The unit only after a bare number: "0.067 m" typed with its unit read
                    // "0.067 m m" (the student trial, 2026-12-07).
                    let shown = if p.typed.trim().parse::<f64>().is_ok() {
                        format!("{} {}", p.typed, q.unit)
                    } else {
                        p.typed.clone()
                    };
                    ui.label(rich(format!("your prediction {shown}: {text}"), color));
                    let now = ex.answers.get(k).map(|a| a.trim()).unwrap_or_default();
                    if now != p.typed {
                        ui.label(rich(
                            "Your answer below has changed since the motion: it is graded as \
                             usual, but it is not a prediction.",
                            palette::FRICTION,
                        ));
                    }
                }
                None => {
                    let why = if pred.gave_up { " (you gave up)" } else { "" };
                    ui.label(rich(format!("no prediction{why}"), palette::OUTLINE));
                }
            }
            if let Some(r) = &r {
                ui.label(values(r));
            }
            explain_button(ui, level, k, pred);
        });
    }
}

/// The engine's, the analysis's and the textbook's values of a question, and when it was read.
fn values(r: &QuestionResult) -> String {
    let analysis = r
        .analysis
        .map(|a| format!(" · analysis {}", fmt(a)))
        .unwrap_or_default();
    format!(
        "engine {}{analysis} · textbook {} {}, at t = {} s",
        fmt(r.engine),
        fmt(r.expected),
        r.unit,
        crate::app::time_text::instant(r.time)
    )
}

/// "Show" for question `k`: its overlay, its body, its instant; marked when it is the one shown.
fn explain_button(ui: &mut egui::Ui, level: &Level, k: usize, pred: &mut Predict) {
    let q = &level.questions[k];
    let explain = Explain::of(&q.quantity, level);
    let body = subject(&q.quantity, level)
        .and_then(|i| level.bodies.get(i))
        .map(|b| format!(" of {}", b.name))
        .unwrap_or_default();
    let what = format!("{}{body}", explain.name());
    ui.horizontal_wrapped(|ui| {
        if pred.shown == Some(k) {
            let at = pred
                .results
                .get(k)
                .map(|r| format!(" at t = {} s", crate::app::time_text::instant(r.time)))
                .unwrap_or_default();
            ui.label(rich(format!("shown{at}: the {what}"), palette::VELOCITY));
        } else if ui
            .button(format!("show the {what}"))
            .on_hover_text("the overlay that explains this answer, at the instant it was read")
            .clicked()
        {
            pred.show = Some(k);
        }
    });
}
