//! The shared per-step pass (`analysis::frame`) against the reference free-body diagram.
//!
//! `FrameAnalysis` reads every step's impulses source by source for speed; the reference is the
//! generic visitor of `analysis::kinetics` (`free_body`, `for_each_external_impulse`) with the
//! textbook's work of an impulse (`energy::work_of_impulse_with_arm`; a contact's, whose normal part
//! depends on whether its pair pushed the step before, `energy::work_of_contact_impulse`). Over
//! scenes that use every source (gravity, contacts between moving bodies and with the ground,
//! joints to the ground and between bodies, springs to the ground, between bodies and to a
//! kinematic body, loads with couples, impulse events, couplings) every body's sums, the
//! scene's external resultant, its non-conservative work and its totals must agree to
//! round-off (1e-12 of the terms' size).

use glam::DVec2;
use rigidlab::analysis::energy::{
    gravity_potential, kinetic_energy, work_of_contact_impulse, work_of_impulse_with_arm,
};
use rigidlab::analysis::frame::{FrameAnalysis, StepWork};
use rigidlab::analysis::kinetics::{for_each_external_impulse, free_body, Before, Source};
use rigidlab::analysis::{cross, Motion};
use rigidlab::level::{self, parse};
use rigidlab::sim::{Options, Simulation};
use rigidlab::snapshot::{BodyKind, Snapshot};
use std::path::Path;

/// Every source at once: a box and a disc joined by a spring fall on the floor, a disc falls on
/// a box (contacts with friction), a box hangs from the ground by a spring, a pushed box carries a load
/// with a couple, the disc is kicked, a double pendulum swings from a pin with its tip on a spring
/// to a moving kinematic cart.
const MIXED: &str = r#"Level(title: "every source", effects: [gravity, contacts, friction, joints, springs],
  world: (dt: 0.008333333333333333, substeps: 4, duration: 1.5),
  bodies: [
    (name: "floor", kind: fixed, shape: Box(width: 6.0, height: 0.2), position: (0.0, -0.1)),
    (name: "a", shape: Box(width: 0.4, height: 0.3), mass: 2.0, position: (-0.5, 0.4), angle: 0.3, friction: 0.5),
    (name: "b", shape: Circle(radius: 0.2), mass: 1.0, position: (0.3, 0.6), velocity: (-1.0, 0.0), omega: 4.0, friction: 0.5),
    (name: "c", shape: Box(width: 0.3, height: 0.3), mass: 1.5, position: (-0.2, 1.2), friction: 0.5),
    (name: "d", shape: Box(width: 0.2, height: 0.2), mass: 0.7, position: (-1.3, 0.8), angle: 0.2, friction: 0.5),
    (name: "e", shape: Circle(radius: 0.12), mass: 0.4, position: (-1.25, 1.3), friction: 0.5),
    (name: "cart", kind: kinematic, shape: Circle(radius: 0.05), position: (2.0, 2.0), velocity: (0.5, 0.0)),
    (name: "pin", kind: fixed, position: (1.5, 2.5)),
    (name: "bar", shape: Box(width: 0.05, height: 0.8), mass: 1.0, position: (1.8, 2.2), angle: 0.8),
    (name: "bar2", shape: Box(width: 0.05, height: 0.8), mass: 0.5, position: (2.3, 1.9), angle: 1.2),
  ],
  joints: [
    // The pins start a few cm open (the scene tests the pass, whatever the joints do).
    (name: "j1", kind: revolute, body1: "pin", body2: "bar", anchor2: (0.0, 0.4), starts_apart: true),
    (name: "j2", kind: revolute, body1: "bar", body2: "bar2", anchor1: (0.0, -0.4), anchor2: (0.0, 0.4), starts_apart: true),
  ],
  springs: [
    (name: "ab", body1: "a", point1: (0.2, 0.1), body2: "b", stiffness: 80.0, rest_length: 0.6),
    (name: "ground", body1: "c", point1: (0.1, 0.1), point2: (-0.2, 2.0), stiffness: 30.0, rest_length: 0.5),
    (name: "to_cart", body1: "bar2", point1: (0.0, -0.4), body2: "cart", stiffness: 20.0, rest_length: 0.3),
  ],
  loads: [
    (name: "push", body: "a", point: (0.1, 0.15), force: Constant((3.0, 1.0)), torque: Constant(0.4)),
  ],
  events: [
    Impulse(name: "kick", at: 0.5, body: "b", point: (0.1, 0.0), impulse: (0.5, 1.0)),
  ],
)"#;

fn close(a: f64, b: f64, scale: f64, what: &str, t: f64) {
    assert!(
        (a - b).abs() <= 1e-12 * (1.0 + scale),
        "{what} at t = {t}: frame {a:e}, reference {b:e}"
    );
}

fn close2(a: DVec2, b: DVec2, scale: f64, what: &str, t: f64) {
    close(a.x, b.x, scale, what, t);
    close(a.y, b.y, scale, what, t);
}

/// The reference work slot of an impulse for a body's own ledger and for the scene's
/// (None: no work in that ledger), as the `work_energy` check defines the ledgers.
fn slots(snap: &Snapshot, source: Source, other: Option<usize>) -> (Option<usize>, Option<usize>) {
    let has_mass = |i: usize| snap.bodies[i].mass > 0.0;
    match source {
        Source::Gravity | Source::Joint(_) => (None, None),
        Source::Load(_) => (Some(0), Some(0)),
        Source::Event(_) => (Some(1), Some(1)),
        Source::Contact { .. } => (Some(2), Some(2)),
        Source::Coupling(..) => (Some(3), Some(3)),
        Source::Spring(_) => {
            let ground = other.is_none_or(|o| snap.bodies[o].kind == BodyKind::Fixed);
            let internal = other.is_some_and(has_mass);
            ((!ground).then_some(3), (!ground && !internal).then_some(3))
        }
    }
}

fn as_array(w: &StepWork) -> [f64; 4] {
    [w.loads, w.events, w.contacts, w.other]
}

fn compare_run(name: &str, scene: &level::Scene) -> usize {
    let substeps = scene.level.world.substeps.max(1);
    let mut sim = Simulation::new(scene, &Options::default());
    let mut fa = FrameAnalysis::new();
    fa.observe(sim.snapshot());
    let mut before: Vec<Motion> = sim.snapshot().bodies.iter().map(Motion::from).collect();
    let mut compared = 0;
    let steps = (scene.level.world.duration / scene.level.world.dt).round() as usize;
    // The pairs a contact pushed in the step before, with the pair's normal impulse: their
    // contacts are not impacts, and their normal impulses work through the bodies'
    // displacement (`work_of_contact_impulse`), unless the pair now pushes over twice as hard
    // (an impulsive push, booked at the mean velocity).
    let pushing = |s: &Snapshot| -> Vec<((usize, usize), f64)> {
        let mut pairs: Vec<((usize, usize), f64)> = Vec::new();
        for c in s
            .contacts
            .iter()
            .filter(|c| c.points.iter().any(|p| p.normal_impulse > 0.0))
        {
            let key = (c.body1.min(c.body2), c.body1.max(c.body2));
            let j: f64 = c.points.iter().map(|p| p.normal_impulse).sum();
            match pairs.iter_mut().find(|(k, _)| *k == key) {
                Some(e) => e.1 += j,
                None => pairs.push((key, j)),
            }
        }
        pairs
    };
    let impulse_of = |pairs: &[((usize, usize), f64)], key: (usize, usize)| {
        pairs.iter().find(|(k, _)| *k == key).map(|e| e.1)
    };
    let mut pushed_before = pushing(sim.snapshot());
    for _ in 0..steps {
        let s = sim.step().unwrap_or_else(|e| panic!("{name}: {e}"));
        let f = fa.observe(s).clone();
        let pushing_now = pushing(s);
        let t = s.time;
        let after: Vec<Motion> = s.bodies.iter().map(Motion::from).collect();
        let mut scene_work = [0.0; 4];
        let mut size = 0.0f64;
        for (i, b) in s.bodies.iter().enumerate() {
            if b.mass <= 0.0 {
                assert_eq!(
                    f.bodies[i],
                    Default::default(),
                    "{name}: a body without mass"
                );
                continue;
            }
            let (mut j, mut m_g, mut m_o) = (DVec2::ZERO, 0.0, 0.0);
            let mut work = [0.0; 4];
            for imp in free_body(&before, s, i, substeps) {
                j += imp.impulse;
                m_g += imp.moment_about_g();
                m_o += imp.moment_about(DVec2::ZERO);
                let u = match imp.source {
                    Source::Contact { contact, point } => {
                        let c = &s.contacts[contact];
                        let p = &c.points[point];
                        let sign = if c.body2 == i { 1.0 } else { -1.0 };
                        let (b0, b1) = (&before[i], &after[i]);
                        let mean = (
                            0.5 * (b0.velocity + b1.velocity),
                            0.5 * (b0.omega + b1.omega),
                        );
                        let moved = ((b1.com - b0.com) / s.dt, (b1.angle - b0.angle) / s.dt);
                        let key = (c.body1.min(c.body2), c.body1.max(c.body2));
                        work_of_contact_impulse(
                            c.normal * p.normal_impulse * sign,
                            c.tangent() * p.tangent_impulse * sign,
                            imp.arm,
                            mean,
                            impulse_of(&pushed_before, key)
                                .is_some_and(|before| {
                                    impulse_of(&pushing_now, key).unwrap_or(0.0) <= 2.0 * before
                                })
                                .then_some(moved),
                        )
                    }
                    _ => work_of_impulse_with_arm(
                        imp.impulse,
                        imp.arm,
                        imp.couple,
                        &before[i],
                        &after[i],
                    ),
                };
                let (own, whole) = slots(s, imp.source, imp.other);
                if let Some(k) = own {
                    work[k] += u;
                }
                if let Some(k) = whole {
                    scene_work[k] += u;
                }
                size = size
                    .max(imp.impulse.length())
                    .max(imp.moment_about(DVec2::ZERO).abs());
            }
            let bf = &f.bodies[i];
            let what = |q: &str| format!("{name}: body {} {q}", b.name);
            close2(bf.impulses.impulse, j, size, &what("sum J"), t);
            close(bf.moment_g * s.dt, m_g, size, &what("sum M_G"), t);
            close(bf.impulses.moment_origin, m_o, size, &what("sum M_O"), t);
            for (k, (a, r)) in as_array(&bf.work).iter().zip(work).enumerate() {
                close(*a, r, size, &what(&format!("work[{k}]")), t);
            }
        }
        // The scene: external impulses only (6/18), every body with mass.
        let (mut j, mut m_o) = (DVec2::ZERO, 0.0);
        for_each_external_impulse(
            Before::All(&before),
            s,
            substeps,
            |i| s.bodies[i].mass > 0.0,
            |imp| {
                j += imp.impulse;
                m_o += imp.moment_about(DVec2::ZERO);
            },
        );
        close2(f.external.impulse, j, size, &format!("{name}: scene J"), t);
        close(
            f.external.moment_origin,
            m_o,
            size,
            &format!("{name}: scene M_O"),
            t,
        );
        for (k, (a, r)) in as_array(&f.work).iter().zip(scene_work).enumerate() {
            close(*a, r, size, &format!("{name}: scene work[{k}]"), t);
        }
        // Totals from the state.
        let (mut te, mut vg, mut g, mut h) = (0.0, 0.0, DVec2::ZERO, 0.0);
        for b in s.bodies.iter().filter(|b| b.mass > 0.0) {
            te += kinetic_energy(b.mass, b.velocity, b.inertia, b.omega);
            vg += gravity_potential(b.mass, s.gravity, b.com);
            g += b.mass * b.velocity;
            h += b.inertia * b.omega + cross(b.com, b.mass * b.velocity);
        }
        let big = te.abs() + vg.abs() + g.length() + h.abs();
        close(f.totals.kinetic_energy, te, big, "T", t);
        close(f.totals.gravity_potential, vg, big, "V_g", t);
        close2(f.totals.linear_momentum, g, big, "G", t);
        close(f.totals.angular_momentum_origin, h, big, "H_O", t);
        before = after;
        pushed_before = pushing_now;
        compared += 1;
    }
    compared
}

#[test]
fn the_shared_pass_equals_the_reference_free_body_diagrams_with_every_source() {
    let scene = parse(Path::new("mixed.ron"), MIXED).unwrap_or_else(|e| panic!("{e}"));
    // The scene does use every source: check before trusting the comparison.
    let mut sim = Simulation::new(&scene, &Options::default());
    let (mut contacts_between, mut events) = (false, false);
    for _ in 0..180 {
        let s = sim.step().unwrap();
        contacts_between |= s
            .contacts
            .iter()
            .any(|c| s.bodies[c.body1].mass > 0.0 && s.bodies[c.body2].mass > 0.0);
        events |= !s.impulses.is_empty();
    }
    assert!(contacts_between, "no contact between two moving bodies");
    assert!(events, "no impulse event");
    assert!(compare_run("mixed", &scene) > 100);
}

#[test]
fn the_shared_pass_equals_the_reference_on_library_levels() {
    for file in [
        "levels/stress/vertical_stack.ron",
        "levels/stress/stretched_chain.ron",
        "levels/impact/central_impact.ron",
        "levels/momentum/bar_struck_below_percussion.ron",
        "levels/kinematics/ha_double_pulley_cable.ron",
        "levels/kinematics/ha_collars_pulley_dependent_motion.ron",
        "levels/virtual-work/zh_four_bar_inverse_dynamics.ron",
    ] {
        let scene = level::load(Path::new(file)).unwrap_or_else(|e| panic!("{e}"));
        assert!(compare_run(file, &scene) > 0, "{file}");
    }
}

/// A run whose readers need no work takes the pass without it (`FramePass::Diagram`): the same
/// sums, residuals and momenta to the last bit, and a refusal, not zeros, for a reader that asks
/// for the work anyway.
#[test]
fn the_pass_without_work_has_the_same_sums_and_refuses_the_work() {
    use rigidlab::analysis::frame::FramePass;
    let scene = parse(Path::new("mixed.ron"), MIXED).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Simulation::new(&scene, &Options::default());
    let (mut full, mut sums) = (FrameAnalysis::new(), FrameAnalysis::new());
    let mut nonzero_work = false;
    for k in 0..180 {
        let s = if k == 0 {
            sim.snapshot().clone()
        } else {
            sim.step().unwrap().clone()
        };
        full.observe_as(&s, FramePass::Work);
        sums.observe_as(&s, FramePass::Diagram);
        let (a, b) = (full.frame(), sums.frame());
        for (x, y) in a.bodies.iter().zip(&b.bodies) {
            assert_eq!(x.impulses, y.impulses, "t = {}", s.time);
            assert_eq!(x.force_residual, y.force_residual);
            assert_eq!(x.moment_residual, y.moment_residual);
            assert_eq!(x.kinetic_energy, y.kinetic_energy);
        }
        assert_eq!(a.external, b.external);
        assert_eq!(a.totals, b.totals);
        nonzero_work |= a.work(None).total() != 0.0;
        let refused = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| b.work(None)));
        assert!(
            refused.is_err(),
            "the work of a Diagram pass was handed out"
        );
    }
    assert!(
        nonzero_work,
        "the scene's forces did no work: the comparison says nothing"
    );
}
