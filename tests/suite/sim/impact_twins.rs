//! Impacts that approach from a distance (issue 13): every impact level of the library whose
//! bodies start touching gets a twin that starts a few milliseconds earlier, carried back along
//! its free flight, so that the same impact happens after an approach of centimetres.
//!
//! The twin is exact up to the impact: every moving body is taken back by T along the motion it
//! has when nothing touches it (p - v T + g T^2 / 2, v - g T, theta - omega T; these levels'
//! bodies turn about their centers or do not turn), times in the exercise are moved by T, and
//! the run lasts T longer. It is run with impacts cut at their time of impact (the default for
//! scenes of up to 64 moving bodies; sim/impacts.rs) and must pass every check and question its
//! library level passes. T = 5.3 ms, not a multiple of any level's step, so the
//! impact falls inside a step: gaps of 1.9 cm (the bar on the ledge) to 14 cm (the cars).
//!
//! Without the cuts (`impact_cuts: Some(false)`, rapier's speculative contact) the twins are
//! printed for comparison: 5 of the 7 failed, by up to 1.7e-2.

use crate::common;

use common::run;
use rigidlab::level::{BodyKind, Effect, EventDef, Scene, When};
use rigidlab::report::LevelReport;
use rigidlab::sim::Options;

/// How much earlier the twins start, s.
const T: f64 = 5.3e-3;

/// The impact levels that start touching (the joint-caught plates are not contact impacts).
const LEVELS: &[&str] = &[
    "levels/impact/jh_P9.11.1_oblique_spheres.ron",
    "levels/impact/jh_P9.11.2_oblique_spheres_variant.ron",
    "levels/impact/jh_P9.11.3_car_angled_barrier_30.ron",
    "levels/impact/jh_P9.11.5_intersection_collision.ron",
    "levels/impact/jh_P9.11.7_intersection_SI.ron",
    "levels/impact/ha_oblique_impact_fragment.ron",
    "levels/impact/bar_on_ledge.ron",
];

/// The level started T earlier (see the module doc).
fn twin(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    let l = &mut s.level;
    let g = if l.effects.contains(&Effect::Gravity) {
        l.world.gravity.unwrap_or((0.0, -9.81))
    } else {
        (0.0, 0.0)
    };
    for b in l.bodies.iter_mut().filter(|b| b.kind != BodyKind::Fixed) {
        let g = if b.kind == BodyKind::Dynamic {
            g
        } else {
            (0.0, 0.0)
        };
        b.position = (
            b.position.0 - b.velocity.0 * T + 0.5 * g.0 * T * T,
            b.position.1 - b.velocity.1 * T + 0.5 * g.1 * T * T,
        );
        b.velocity = (b.velocity.0 - g.0 * T, b.velocity.1 - g.1 * T);
        b.angle -= b.omega * T;
    }
    l.world.duration += T;
    for q in &mut l.questions {
        match &mut q.at {
            When::Time(t) | When::Max(t) | When::Min(t) => *t += T,
            When::Crossing { after, .. } => *after += T,
            _ => {}
        }
    }
    for c in &mut l.checks {
        if let Some((a, b)) = c.window.as_mut() {
            *a += T;
            *b += T;
        }
    }
    for e in &mut l.events {
        if let EventDef::Impulse { at, .. } = e {
            *at += T;
        }
    }
    s
}

/// The worst question error of a report, and the ids that failed.
fn summary(r: &LevelReport) -> (f64, Vec<String>) {
    let worst = common::worst(r.questions.iter().map(|q| q.rel_error));
    let failed = r
        .questions
        .iter()
        .filter(|q| !q.passed)
        .map(|q| q.id.clone())
        .chain(
            r.checks
                .iter()
                .filter(|c| !c.passed)
                .map(|c| c.kind.clone()),
        )
        .collect();
    (worst, failed)
}

#[test]
fn impact_levels_pass_when_their_bodies_approach_from_a_distance() {
    let cuts = Options {
        impact_cuts: Some(true),
        ..Default::default()
    };
    let mut bad = Vec::new();
    for file in LEVELS {
        let scene = common::load(file);
        let base = run(&scene, &cuts);
        assert!(base.passed, "{file} fails as it is");
        let t = twin(&scene);
        let with = run(&t, &cuts);
        let without = run(
            &t,
            &Options {
                impact_cuts: Some(false),
                ..Default::default()
            },
        );
        let (w, failed) = summary(&with);
        let (wo, failed_wo) = summary(&without);
        println!(
            "{file}: level {:.2e}; twin from T = {T} s earlier: with cuts {w:.2e} {failed:?}, without {wo:.2e} {failed_wo:?}",
            summary(&base).0
        );
        if !with.passed {
            bad.push(format!("{file}: {failed:?} (worst question error {w:.3e})"));
        }
    }
    assert!(
        bad.is_empty(),
        "twins that fail with impact cuts:\n{}",
        bad.join("\n")
    );
}
