//! Readings about one body or a pair through `analysis::links::BodyLinks` (only the contacts and
//! joints touching them) visit exactly what a scan of the whole snapshot visits, in the same
//! order: the checks that use them (restitution, center_of_percussion) keep their values bit for
//! bit. Checked on every step of scenes with contacts and joints, for every body and for every
//! pair in contact.

use rigidlab::analysis::impact::{pair_contact, pair_contact_linked};
use rigidlab::analysis::kinetics::{
    for_each_external_impulse, for_each_external_impulse_linked, Before, StepImpulse,
};
use rigidlab::analysis::links::BodyLinks;
use rigidlab::analysis::Motion;
use rigidlab::level;
use rigidlab::sim::{Options, Simulation};
use std::path::Path;

fn visit(f: impl FnOnce(&mut dyn FnMut(StepImpulse))) -> Vec<StepImpulse> {
    let mut out = Vec::new();
    f(&mut |s| out.push(s));
    out
}

/// Compares every step of `file`; returns (impulses compared, pairs compared).
fn compare_on(file: &str, steps: usize) -> (usize, usize) {
    let scene = level::load(Path::new(file)).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Simulation::new(&scene, &Options::default());
    let mut before: Vec<Motion> = sim.snapshot().bodies.iter().map(Motion::from).collect();
    let mut links = BodyLinks::default();
    let (mut singles, mut pairs) = (0, 0);
    for _ in 0..steps {
        let s = sim.step().expect("the level runs").clone();
        links.rebuild(&s);
        let n = s.bodies.len();
        for (i, b) in before[..n].iter().enumerate() {
            let one = Before::One(i, b);
            let scanned = visit(|v| for_each_external_impulse(one, &s, s.substeps, |k| k == i, v));
            let linked = visit(|v| {
                for_each_external_impulse_linked(one, &s, s.substeps, &links, |k| k == i, v)
            });
            assert_eq!(scanned, linked, "{file}: body {i} at t = {}", s.time);
            singles += scanned.len();
        }
        // `pushed`: a body some contact pushes over the step (a scan of every contact).
        for i in 0..n {
            let scanned = s.contacts.iter().any(|c| {
                (c.body1 == i || c.body2 == i) && c.points.iter().any(|p| p.normal_impulse > 0.0)
            });
            assert_eq!(
                links.pushed(i),
                scanned,
                "{file}: body {i} at t = {}",
                s.time
            );
        }
        for c in &s.contacts {
            let (a, b) = (c.body1, c.body2);
            let in_pair = |k: usize| k == a || k == b;
            let all = visit(|v| {
                for_each_external_impulse(Before::All(&before), &s, s.substeps, in_pair, v)
            });
            let two = Before::Two([(a, &before[a]), (b, &before[b])]);
            let linked = visit(|v| {
                for_each_external_impulse_linked(two, &s, s.substeps, &links, in_pair, v)
            });
            assert_eq!(all, linked, "{file}: pair ({a}, {b}) at t = {}", s.time);
            assert_eq!(
                pair_contact(&s, a, b),
                pair_contact_linked(&s, a, b, &links),
                "{file}: pair ({a}, {b}) at t = {}",
                s.time
            );
            pairs += 1;
        }
        before = s.bodies.iter().map(Motion::from).collect();
    }
    (singles, pairs)
}

#[test]
fn linked_walks_visit_what_a_scan_visits() {
    // Contacts in a heap, joints in a chain, both in a cradle.
    let runs = [
        compare_on("levels/stress/card_house.ron", 120),
        compare_on("levels/stress/ball_and_chain.ron", 120),
        compare_on("levels/stress/newtons_cradle.ron", 240),
    ];
    assert!(runs.iter().all(|r| r.0 > 0), "{runs:?}");
    assert!(runs.iter().filter(|r| r.1 > 0).count() >= 2, "{runs:?}");
}
