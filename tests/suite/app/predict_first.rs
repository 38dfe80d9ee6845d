//! Predict first (issue 42), headless (MinimalPlugins, one physics step per update): a level with
//! `predict_first: true` holds its run at t = 0, refusing play, steps and the timeline, until
//! every question has an answer; then the motion plays from t = 0, and at the level's end the
//! results are the run's own (the values `rigidlab check` reports), with the overlay that
//! explains the first question on, for its body, at the instant it was read.

use bevy::app::ScheduleRunnerPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use rigidlab::app::overlays::Overlays;
use rigidlab::app::panels::predict::{self, Explain, Phase, Predict};
use rigidlab::app::panels::{grade, Exercise};
use rigidlab::app::{PhysicsCommand, PhysicsPlugin, PhysicsStep, Playback, Run};
use rigidlab::level::{self, Quantity};
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

/// The hoop rolling down a 30 degree incline, a library level with `predict_first: true`.
const HOOP: &str = "levels/kinetics/classic_rolling_hoop.ron";

/// The physics of `file`, paused as the window opens it, with the exercise's answers, the
/// overlays and predict first's own system, as the panels plugin adds it (no egui: the
/// panel's Check button is `answer` below).
fn app(file: &str) -> App {
    let scene = level::load(Path::new(file)).unwrap();
    let mut ex = Exercise::default();
    ex.start(scene.level.questions.len());
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene,
            options: Options::default(),
            paused: true,
        })
        .insert_resource(ex)
        .init_resource::<Overlays>()
        .init_resource::<Predict>()
        .add_systems(Update, predict::follow.before(PhysicsStep));
    app.update();
    app
}

fn run(app: &App) -> &Run {
    app.world().resource::<Run>()
}

fn time(app: &App) -> f64 {
    run(app).snapshot().time
}

fn phase(app: &App) -> Phase {
    app.world().resource::<Predict>().phase
}

/// The student types `text` into question `k`'s box and presses Check (the exercise panel's
/// grading, `panels::grade`), then a frame passes.
fn answer(app: &mut App, k: usize, text: &str) {
    let q = run(app).sim.level.questions[k].clone();
    let mut ex = app.world_mut().resource_mut::<Exercise>();
    ex.answers[k] = text.to_string();
    ex.grades[k] = Some(grade(&q, text));
    app.update();
}

fn ask(app: &mut App, c: PhysicsCommand) {
    app.world_mut().write_message(c);
    app.update();
}

fn frames(app: &mut App, n: usize) {
    for _ in 0..n {
        app.update();
    }
}

/// The hoop's answers from theory: a hoop (k_G = r) rolling without slip down 30 degrees has
/// a = g sin 30 / (1 + k_G^2 / r^2) = 9.81 (0.5) / 2 = 2.4525 m/s^2, needs friction
/// F = m g sin 30 k_G^2 / (k_G^2 + r^2) = 2 (9.81) (0.5) / 2 = 4.905 N and mu >= tan 30 / 2 =
/// 0.288675; after 1 s (s = a / 2 = 1.22625 m) v = a t = 2.4525 m/s and T = 1/2 m v^2 +
/// 1/2 (m r^2)(v / r)^2 = m v^2 = 12.0295 J. The first answer is the sliding block's g sin 30
/// = 4.905, the prediction a student who forgets the rolling makes: it must be graded wrong.
const ANSWERS: [&str; 5] = ["4.905", "4.905", "0.288675", "2.4525", "12.0295"];

/// Play pressed, frames pass: the run stays at t = 0 (not one step) until the last answer is
/// checked; then it advances. The end shows the run's own values, `rigidlab check`'s.
#[test]
fn a_predict_first_level_waits_at_t0_until_every_question_is_answered() {
    let mut app = app(HOOP);
    assert!(
        run(&app).sim.level.predict_first,
        "{HOOP} asks to predict first"
    );
    assert_eq!(phase(&app), Phase::Predicting);
    ask(&mut app, PhysicsCommand::TogglePlay);
    frames(&mut app, 30);
    // Each way of running it: a step, a step back, the timeline, a push.
    ask(&mut app, PhysicsCommand::Step);
    ask(&mut app, PhysicsCommand::Seek(100));
    frames(&mut app, 5);
    let play = app.world().resource::<Playback>();
    assert!(play.paused, "play was not refused");
    assert_eq!(play.refused, 3, "play, step and seek each refused once");
    assert_eq!(time(&app), 0.0, "the run moved before the answers");
    assert_eq!(run(&app).snapshot().step, 0);

    // Four of five answers: still held, the grades not shown.
    for (k, a) in ANSWERS.iter().enumerate().take(4) {
        answer(&mut app, k, a);
    }
    ask(&mut app, PhysicsCommand::TogglePlay);
    frames(&mut app, 10);
    assert_eq!(time(&app), 0.0, "the run moved with a question unanswered");
    assert!(app.world().resource::<Exercise>().hold_grades);

    // The last one: the motion plays, from t = 0, one step a frame.
    answer(&mut app, 4, ANSWERS[4]);
    frames(&mut app, 20);
    assert_eq!(phase(&app), Phase::Watching);
    let step = run(&app).snapshot().step;
    assert!(
        step >= 19,
        "the run is at step {step} after 20 frames of play"
    );
    // The grades show with the results, at the end.
    assert!(app.world().resource::<Exercise>().hold_grades);

    // To the end (252 steps): the results are the run's, equal to the core's bit for bit (the
    // window computes what `rigidlab check` computes, tests/suite/app/plugins.rs).
    frames(&mut app, 260);
    assert_eq!(phase(&app), Phase::Revealed);
    assert!(!app.world().resource::<Exercise>().hold_grades);
    let scene = level::load(Path::new(HOOP)).unwrap();
    let core =
        rigidlab::runner::run_graded(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
    let pred = app.world().resource::<Predict>();
    assert_eq!(pred.results.len(), 5);
    for (mine, theirs) in pred.results.iter().zip(&core.questions) {
        assert_eq!(
            (mine.engine, mine.analysis),
            (theirs.engine, theirs.analysis),
            "{}",
            mine.id
        );
    }
    // The predictions: the sliding block's answer wrong, the four others right.
    let right: Vec<bool> = pred
        .predictions
        .iter()
        .map(|p| p.as_ref().unwrap().grade.passed)
        .collect();
    assert_eq!(right, [false, true, true, true, true]);

    // The first question (the center's acceleration, read at t = 0.5 s): the acceleration
    // arrows on, for the hoop, with the run back at 0.5 s.
    frames(&mut app, 3);
    let ov = app.world().resource::<Overlays>();
    assert!(ov.acceleration && ov.labels);
    let roller = scene.level.bodies.iter().position(|b| b.name == "roller");
    assert_eq!(ov.selected, roller);
    assert!(
        (time(&app) - 0.5).abs() < 0.5 * run(&app).sim.dt(),
        "t = {}",
        time(&app)
    );
}

/// An answer changed after the motion was seen is graded, but the prediction stays the one
/// checked before it.
#[test]
fn an_answer_changed_after_the_motion_is_not_a_prediction() {
    let mut app = app(HOOP);
    for (k, a) in ANSWERS.iter().enumerate() {
        answer(&mut app, k, a);
    }
    frames(&mut app, 300);
    assert_eq!(phase(&app), Phase::Revealed);
    answer(&mut app, 0, "2.4525");
    let pred = app.world().resource::<Predict>();
    let first = pred.predictions[0].as_ref().unwrap();
    assert_eq!(first.typed, "4.905");
    assert!(!first.grade.passed);
    let ex = app.world().resource::<Exercise>();
    assert!(ex.grades[0].as_ref().unwrap().as_ref().unwrap().passed);
}

/// "I give up / show me" plays the motion with no answer; the questions count as not
/// predicted.
#[test]
fn giving_up_plays_the_motion_without_predictions() {
    let mut app = app(HOOP);
    app.world_mut().resource_mut::<Predict>().gave_up = true;
    frames(&mut app, 20);
    assert!(time(&app) > 0.0);
    let pred = app.world().resource::<Predict>();
    assert_eq!(pred.phase, Phase::Watching);
    assert_eq!(pred.answered(), 0);
}

/// A level that does not ask for it plays at once; the switch turns predict first on for it
/// mid-run (back to t = 0, paused, held) and off again.
#[test]
fn the_switch_holds_any_level_and_lets_it_go() {
    let mut app = app("levels/kinetics/simple_pendulum.ron");
    assert_eq!(phase(&app), Phase::Off);
    ask(&mut app, PhysicsCommand::TogglePlay);
    frames(&mut app, 10);
    assert!(time(&app) > 0.0, "a level without predict first plays");
    app.world_mut().resource_mut::<Predict>().switch = Some(true);
    frames(&mut app, 2);
    assert_eq!(phase(&app), Phase::Predicting);
    assert_eq!(time(&app), 0.0, "switched on mid-run: back to t = 0");
    ask(&mut app, PhysicsCommand::TogglePlay);
    frames(&mut app, 10);
    assert_eq!(time(&app), 0.0, "held");
    app.world_mut().resource_mut::<Predict>().switch = Some(false);
    frames(&mut app, 2);
    ask(&mut app, PhysicsCommand::TogglePlay);
    frames(&mut app, 10);
    assert!(time(&app) > 0.0, "switched off: plays");
}

/// The table from a question's quantity to the overlay that explains it, and the body it is
/// about: a speed the velocity arrows, a reaction the free-body diagram of the pin's moving
/// body, a period the trail, H about O the momentum overlay, a link's omega its instantaneous
/// center, and an energy (no row of its own) the default, the velocities.
#[test]
fn each_quantity_has_the_overlay_that_explains_it() {
    let pendulum = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    let l = &pendulum.level;
    let bob = l.bodies.iter().position(|b| b.name == "bob");
    let cases = [
        (Quantity::Speed("bob".into()), Explain::Velocity),
        (Quantity::JointForce("rod".into()), Explain::FreeBody),
        (Quantity::Alpha("bob".into()), Explain::Acceleration),
        (
            Quantity::PendulumPeriod {
                body: "bob".into(),
                joint: "rod".into(),
            },
            Explain::Trails,
        ),
        (
            Quantity::AngularMomentumAbout {
                body: "bob".into(),
                point: (0.0, 0.0),
            },
            Explain::Momentum,
        ),
        (Quantity::KineticEnergy("bob".into()), Explain::Velocity),
        (
            Quantity::LinkOmega {
                link: "bob".into(),
                known: "rod".into(),
                other: "rod".into(),
            },
            Explain::InstantCenter,
        ),
    ];
    for (q, explain) in cases {
        assert_eq!(Explain::of(&q, l), explain, "{q:?}");
        assert_eq!(predict::subject(&q, l), bob, "{q:?}");
    }
}

/// `predict_first` is written only when true: a level without it saves as before.
#[test]
fn predict_first_is_saved_only_when_true() {
    let hoop = level::load(Path::new(HOOP)).unwrap();
    let text = level::to_ron(&hoop.level);
    assert!(text.contains("predict_first: true"), "{text}");
    let pendulum = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    assert!(!level::to_ron(&pendulum.level).contains("predict_first"));
}
