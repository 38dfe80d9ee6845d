//! A run whose checks and questions read no contacts leaves them unread
//! (`runner::run_graded`, `sim::Simulation::set_contact_readings`): every library level must
//! grade the same either way, or a probe that reads contacts said it does not.

use rigidlab::level::{self, collect_files, Effect};
use rigidlab::runner::{run_graded, run_scene, Observers};
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::PathBuf;

#[test]
fn every_level_grades_the_same_with_contacts_read_only_where_read() {
    let files = collect_files(&[PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("levels")])
        .expect("the library is readable");
    let (mut unread, mut with_contacts) = (0, 0);
    for f in &files {
        let scene = level::load(f).unwrap_or_else(|e| panic!("{e}"));
        let opts = Options::default();
        let answers = HashMap::new();
        if scene.level.effects.contains(&Effect::Contacts) {
            with_contacts += 1;
            if !Observers::new(&scene.level).reads_contacts() {
                unread += 1;
            }
        }
        let all = run_scene(&scene, &opts, &answers, |_| {});
        let graded = run_graded(&scene, &opts, &answers, |_| {});
        let (all, graded) = match (all, graded) {
            (Ok(a), Ok(g)) => (a, g),
            (a, g) => panic!("{}: {:?} against {:?}", f.display(), a.err(), g.err()),
        };
        assert_eq!(all.checks, graded.checks, "{}", f.display());
        assert_eq!(all.questions, graded.questions, "{}", f.display());
        assert_eq!(all.passed, graded.passed, "{}", f.display());
    }
    // The comparison means something only if some levels with contacts ran without reading them.
    assert!(
        unread > 0,
        "no level of the {with_contacts} with contacts ran with its contacts unread"
    );
    eprintln!("{unread} of {with_contacts} levels with contacts graded without reading them");
}
