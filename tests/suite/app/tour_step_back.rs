//! The first-steps tour ticks "Drag the timeline back" only for a step back (the second
//! student trial of 2026-12-07 saw it ticked after predict-first jumped forward to the instant
//! its questions are read: the tour took any seek for a step back).

use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

#[test]
fn only_a_seek_to_an_earlier_step_is_a_step_back() {
    let scene = level::load(Path::new("levels/kinetics/physical_pendulum.ron")).unwrap();
    let mut phys = Run::new(scene, Options::default());
    for _ in 0..10 {
        phys.advance();
    }
    assert!(!phys.seeking_back(), "no seek");
    phys.seek = Some(20);
    assert!(!phys.seeking_back(), "a seek forward, to step 20 from 10");
    phys.seek = Some(10);
    assert!(!phys.seeking_back(), "a seek to the step it is at");
    phys.seek = Some(5);
    assert!(phys.seeking_back(), "a seek back, to step 5 from 10");
}
