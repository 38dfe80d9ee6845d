//! Memory of a run grows with its questions, not with questions x bodies (issue 15): 1,000
//! bodies and 1,000 questions, each on its own body and read at a time inside the run, stay
//! under 200 MB of peak resident memory for the whole test process.
//!
//! Why it could fail: a question that kept a copy of every snapshot (1,000 bodies' state) for
//! each step it watches would hold 1,000 x 1,000 x steps body states; 240 steps of that is
//! about 50 GB. The run loop keeps one history that all questions read.
//!
//! Alone in its test binary, so the process's peak (VmHWM) is this run's.

use rigidlab::level;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

fn peak_rss_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

#[test]
fn a_thousand_questions_on_a_thousand_bodies_stay_under_200_mb() {
    let n = 1000;
    let mut bodies = String::new();
    let mut questions = String::new();
    for i in 0..n {
        // Free fall from y0 = 100 m: y(t) = y0 - g t^2 / 2 at t = 0.5 s (symplectic Euler with
        // h = dt/4 is low by g h t / 2 = 0.5e-2 m; the tolerance covers it).
        let x = (i % 100) as f64;
        let y0 = 100.0 + (i / 100) as f64;
        bodies += &format!(
            "    (name: \"b{i}\", shape: Circle(radius: 0.1), mass: 1.0, position: ({x:.1}, {y0:.1})),\n"
        );
        questions += &format!(
            "    (id: \"q{i}\", ask: \"height\", unit: \"m\", expected: {:.6}, tolerance: 1e-3, quantity: Y(\"b{i}\"), at: Time(0.5), why: \"symplectic Euler, g h t / 2\"),\n",
            y0 - 0.5 * 9.81 * 0.25
        );
    }
    let text = format!(
        "Level(\n  title: \"memory\",\n  effects: [gravity],\n  world: (dt: 0.004166666666666667, substeps: 4, duration: 1.0),\n  bodies: [\n{bodies}  ],\n  questions: [\n{questions}  ],\n)\n"
    );
    let scene = level::parse(Path::new("memory.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
    let before = peak_rss_mb();
    let report = runner::run_scene(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
    assert_eq!(report.questions.len(), n);
    assert!(
        report.passed,
        "the free-fall answers hold: {:?}",
        report.questions.iter().find(|q| !q.passed)
    );
    let (Some(before), Some(after)) = (before, peak_rss_mb()) else {
        eprintln!("no /proc/self/status here: memory not measured");
        return;
    };
    println!("peak resident memory {after:.1} MB ({before:.1} MB before the run), {n} bodies, {n} questions, 240 steps");
    assert!(after < 200.0, "peak {after:.1} MB");
}
