//! The first-steps tour's count survives a restart (issue 42's student trial of 2026-12-07: the
//! page's tour started again at "0 of 7" on every reload): its steps ticked and its finish are
//! kept with the course's progress, natively in `progress.ron` beside the preferences and in
//! the page in localStorage (`rigidlab.progress`), and what cannot be read is reported and kept
//! aside as the course's progress is. The page's side: tests/suite/app/web_page.rs.

use rigidlab::app::panels::tour::{self, Tour, STEP_IDS};
use rigidlab::app::panels::Course;
use rigidlab::app::progress_file::{FileBackend, MemoryBackend, STORAGE_KEY};

/// The tour with the steps `ids` ticked.
fn ticked(ids: &[&str]) -> Tour {
    let mut t = Tour {
        open: true,
        ..Tour::default()
    };
    t.restore(&ids.iter().map(|s| s.to_string()).collect::<Vec<_>>());
    t
}

fn stored(m: &MemoryBackend) -> Option<String> {
    m.0.lock().unwrap().get(STORAGE_KEY).cloned()
}

#[test]
fn ticked_steps_come_back_in_a_new_session() {
    let m = MemoryBackend::default();
    let mut course = Course::open(Some(Box::new(m.clone())));
    let t = ticked(&["play", "answer"]);
    assert_eq!(t.ticked_ids(), ["play", "answer"]);
    assert_eq!(
        tour::keep(&t, false, (&mut course.progress, &mut course.store)),
        None
    );
    let text = stored(&m).expect("the tour's progress was stored");
    assert!(
        text.contains("\"play\"") && text.contains("\"answer\""),
        "{text}"
    );
    // Nothing new: nothing written (the store is not rewritten every frame).
    m.0.lock()
        .unwrap()
        .insert(STORAGE_KEY.into(), text.clone() + "// untouched\n");
    assert_eq!(
        tour::keep(&t, false, (&mut course.progress, &mut course.store)),
        None
    );
    assert!(stored(&m).unwrap().ends_with("// untouched\n"));

    // A new session (a reload): the same two steps ticked, the tour still open.
    let again = Course::open(Some(Box::new(m.clone())));
    assert_eq!(again.store.problem, None);
    let mut fresh = Tour {
        open: true,
        ..Tour::default()
    };
    tour::restore(&mut fresh, &again.progress);
    assert_eq!(fresh.ticked_ids(), ["play", "answer"]);
    assert!(fresh.open);
    // The count the tour's title shows: ticks stay when the live state says not done.
    let live: Vec<(&'static str, bool)> = STEP_IDS.iter().map(|s| (*s, false)).collect();
    assert_eq!(fresh.tick(live).iter().filter(|(_, d)| *d).count(), 2);

    // Finished ("done" or "hide for good"): closed in the next session.
    let mut course = again;
    tour::keep(&fresh, true, (&mut course.progress, &mut course.store));
    let mut next = Tour {
        open: true,
        ..Tour::default()
    };
    tour::restore(&mut next, &Course::open(Some(Box::new(m.clone()))).progress);
    assert!(!next.open, "the finished tour opened again");
}

#[test]
fn natively_it_is_kept_in_progress_ron_and_old_files_still_read() {
    let dir = std::env::temp_dir().join(format!("rigidlab-tour-kept-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("progress.ron");
    // A file of format 1 (before the tour was kept) reads, with nothing of the tour done.
    std::fs::write(
        &file,
        "(version: 1, levels: [(path: \"kinetics/a.ron\", title: \"A\", status: solved, attempts: 1, questions: [])])\n",
    )
    .unwrap();
    let mut course = Course::open(Some(Box::new(FileBackend(file.clone()))));
    assert_eq!(course.store.problem, None);
    assert_eq!(course.progress.records.len(), 1);
    assert!(course.progress.tour.is_empty());
    assert_eq!(
        tour::keep(
            &ticked(&["select", "help"]),
            false,
            (&mut course.progress, &mut course.store)
        ),
        None
    );
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        text.contains("tour:") && text.contains("\"help\""),
        "{text}"
    );
    assert!(
        text.contains("kinetics/a.ron"),
        "the level's record was lost: {text}"
    );
    let mut t = Tour::default();
    tour::restore(
        &mut t,
        &Course::open(Some(Box::new(FileBackend(file)))).progress,
    );
    assert_eq!(t.ticked_ids(), ["select", "help"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_corrupt_store_is_reported_kept_aside_and_the_tour_starts_afresh() {
    let m = MemoryBackend::default();
    let corrupt = "Progress(version: 2, levels: [], tour: (ticked: [\"play\" ";
    m.0.lock()
        .unwrap()
        .insert(STORAGE_KEY.into(), corrupt.to_string());
    let mut course = Course::open(Some(Box::new(m.clone())));
    let problem = course
        .store
        .problem
        .clone()
        .expect("the corrupt value reported");
    assert!(problem.contains("rigidlab.progress.bad"), "{problem}");
    let mut t = Tour::default();
    tour::restore(&mut t, &course.progress);
    assert!(t.ticked_ids().is_empty());
    // The next tick is saved afresh; the value kept aside is not touched.
    tour::keep(
        &ticked(&["play"]),
        false,
        (&mut course.progress, &mut course.store),
    );
    let all = m.0.lock().unwrap().clone();
    assert_eq!(all["rigidlab.progress.bad"], corrupt);
    assert!(all[STORAGE_KEY].contains("\"play\""));
}

/// An id this rigidlab does not know (a later one's step) ticks nothing, and is kept.
#[test]
fn an_unknown_step_ticks_nothing() {
    let mut t = Tour::default();
    t.restore(&["replay_a_blow".to_string(), "build".to_string()]);
    assert_eq!(t.ticked_ids(), ["build"]);
    assert_eq!(t.ticked.len(), STEP_IDS.len());
}
