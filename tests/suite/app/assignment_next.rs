//! *Next level* inside an assignment (issue 42): it goes to the assignment's next level in the
//! teacher's order (it went to the library's next level, out of the assignment), and once every
//! level of the assignment is solved it says the assignment is finished. The button is drawn
//! into a bare egui context; `Course::next` is the level it opens.

use bevy_egui::egui;
use rigidlab::app::panels::assignment_list::AssignmentList;
use rigidlab::app::panels::{course, grade, Browser, Course, Exercise};
use rigidlab::app::progress::Graded;
use rigidlab::app::Run;
use rigidlab::level::assignment::Assignment;
use rigidlab::sim::Options;
use std::path::{Path, PathBuf};

/// The library with the example assignment (three levels) listed above it.
fn browser() -> Browser {
    let mut b = Browser::scan(Path::new("levels"));
    let a = Assignment::load(Path::new("assignments/intro")).unwrap();
    b.assignment = Some(AssignmentList::read(&a));
    b
}

/// The *Next level* row drawn for the level on screen: the level it opens, and the texts drawn.
fn next(
    browser: &Browser,
    phys: &Run,
    ex: &Exercise,
    c: &mut Course,
) -> (Option<PathBuf>, Vec<String>) {
    let ctx = egui::Context::default();
    let mut texts = Vec::new();
    for _ in 0..2 {
        let out = ctx.run_ui(egui::RawInput::default(), |ui| {
            course::next_level(ui, (browser, phys, ex), c, &mut None);
        });
        texts.clear();
        for s in &out.shapes {
            if let egui::Shape::Text(t) = &s.shape {
                texts.push(t.galley.text().to_string());
            }
        }
    }
    (c.next.clone(), texts)
}

/// Every question of the level on screen answered right, as the exercise panel grades them.
fn solved(phys: &Run) -> Exercise {
    let mut ex = Exercise::default();
    ex.start(phys.sim.level.questions.len());
    for (k, q) in phys.sim.level.questions.iter().enumerate() {
        ex.grades[k] = Some(grade(q, &format!("{}", q.expected)));
    }
    ex
}

#[test]
fn next_level_in_an_assignment_is_the_assignments_next() {
    let b = browser();
    let a = b.assignment.clone().unwrap();
    let paths: Vec<PathBuf> = a.entries.iter().map(|e| e.path.clone()).collect();
    assert_eq!(paths.len(), 3);
    let mut c = Course::default();
    // The first level of the assignment, solved: next is the assignment's second.
    let first = Run::new(a.entries[0].load().unwrap(), Options::default());
    let (to, texts) = next(&b, &first, &solved(&first), &mut c);
    assert_eq!(to.as_ref(), Some(&paths[1]), "{texts:?}");
    assert!(
        texts
            .iter()
            .any(|t| t.contains("(level 2 of the assignment)")),
        "{texts:?}"
    );

    // Every level of the assignment solved, the last on screen: finished, said, nothing next.
    for e in &a.entries {
        let run = Run::new(e.load().unwrap(), Options::default());
        let key = course::level_key(&b.root, &e.path, &run.scene.level.title);
        let n = run.sim.level.questions.len();
        c.progress.begin_attempt(&key, n);
        for k in 0..n {
            c.progress.grade(
                &key,
                n,
                k,
                Graded {
                    error: 0.0,
                    right: true,
                },
                false,
            );
        }
    }
    let last = Run::new(a.entries[2].load().unwrap(), Options::default());
    let (to, texts) = next(&b, &last, &solved(&last), &mut c);
    assert_eq!(to, None, "{texts:?}");
    assert!(
        texts
            .iter()
            .any(|t| t.contains("assignment") && t.contains("finished")),
        "{texts:?}"
    );

    // A level of the library outside the assignment keeps the course's next level.
    let lib = Run::new(
        rigidlab::level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap(),
        Options::default(),
    );
    let (to, _) = next(&b, &lib, &solved(&lib), &mut c);
    let to = to.expect("the library has unsolved levels");
    assert!(to.starts_with("levels"), "{}", to.display());
}
