//! Predict first's results and the exercise scroll as one column (issue 42, the student trial
//! of 2026-12-07: the results had a scroll area of their own above the column's, two scroll bars
//! side by side). The left panel is drawn as the window draws it, at 1280x800, for a
//! predict-first level whose results are shown: every text of the results and of the questions
//! under them is clipped to one rectangle, the column's scroll area.

use bevy_egui::egui;
use rigidlab::app::panels::predict::{Phase, Predict, Prediction};
use rigidlab::app::panels::{self, grade, Browser, Course, Exercise};
use rigidlab::app::{LiveChecks, Playback, Run};
use rigidlab::sim::Options;
use std::collections::HashMap;

use crate::common;
use crate::common::app::{drawn, two_frames};

#[test]
fn predict_firsts_results_scroll_with_the_questions() {
    let scene = common::load("levels/kinetics/classic_rolling_hoop.ron");
    assert!(scene.level.predict_first);
    let report = rigidlab::runner::run_scene(&scene, &Options::default(), &HashMap::new(), |_| {})
        .expect("the level runs");
    let phys = Run::new(scene, Options::default());
    let live = LiveChecks::new(&phys);
    let q = &phys.sim.level.questions[0];
    let mut ex = Exercise::default();
    ex.start(phys.sim.level.questions.len());
    ex.answers[0] = format!("{}", q.expected);
    ex.grades[0] = Some(grade(q, &ex.answers[0]));
    let mut pred = Predict::default();
    pred.phase = Phase::Revealed;
    pred.predictions = vec![Some(Prediction {
        typed: ex.answers[0].clone(),
        grade: ex.grades[0].clone().unwrap().unwrap(),
    })];
    pred.results = report.questions.clone();
    let play = Playback::new(true);
    let (mut browser, mut course) = (Browser::default(), Course::default());
    let ctx = egui::Context::default();
    let texts = two_frames(&ctx, Vec::new(), |ui| {
        egui::Panel::left("levels")
            .default_size(300.0)
            .show(ui, |ui| {
                panels::left_panel_of(
                    ui,
                    (&phys, &play, &live),
                    (&mut browser, &mut ex, &mut pred, &mut course),
                );
            });
    });
    let results = drawn(&texts, "Your predictions against the run");
    let title = drawn(&texts, &phys.sim.level.title);
    let question = drawn(&texts, &format!("1. {}", q.ask));
    for d in [title, question] {
        assert_eq!(
            results.clip, d.clip,
            "the results are clipped to {:?}, {:?} to {:?}: two scroll areas",
            results.clip, d.text, d.clip
        );
    }
}
