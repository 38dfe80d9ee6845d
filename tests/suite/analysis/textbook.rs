//! The analysis layer against hand-derived values (concepts.md equation numbers in each test)
//! and, with proptest, the identities that must hold on any state.

use crate::common;

use common::assert_close;
use glam::DVec2;
use proptest::prelude::*;
use rigidlab::analysis::energy::*;
use rigidlab::analysis::impact::*;
use rigidlab::analysis::kinematics::*;
use rigidlab::analysis::kinetics::*;
use rigidlab::analysis::mass::*;
use rigidlab::analysis::momentum::*;
use rigidlab::analysis::percussion::*;
use rigidlab::analysis::{cross, Motion};
use rigidlab::level::{BodyDef, BodyKind, Part, Shape};
use rigidlab::snapshot::*;
use std::f64::consts::PI;

fn body(shape: Option<Shape>) -> BodyDef {
    BodyDef {
        name: "b".into(),
        kind: BodyKind::Dynamic,
        shape,
        position: (0.0, 0.0),
        angle: 0.0,
        velocity: (0.0, 0.0),
        omega: 0.0,
        mass: None,
        density: None,
        inertia: None,
        radius_of_gyration: None,
        lock_rotation: false,
        friction: None,
        restitution: None,
        linear_damping: None,
        angular_damping: None,
        motion: None,
    }
}

// ------------------------------------------------------------------ mass properties (section 6)

#[test]
fn shape_formulas_mp9() {
    // Disc m = 2 kg, r = 0.5 m: 1/2 m r^2 = 0.25 kg m^2.
    assert_close!(disc_inertia(2.0, 0.5), 0.25, 1e-15);
    // Slender bar 3 kg, 1.2 m: m l^2/12 = 0.36 about G, m l^2/3 = 1.44 about an end (MP-6).
    assert_close!(slender_bar_inertia(3.0, 1.2), 0.36, 1e-15);
    assert_close!(slender_bar_end_inertia(3.0, 1.2), 1.44, 1e-15);
    assert_close!(
        parallel_axis(slender_bar_inertia(3.0, 1.2), 3.0, 0.6),
        1.44,
        1e-15
    );
    // Rectangle 0.4 x 0.3, 5 kg: 5 (0.16 + 0.09)/12.
    assert_close!(rectangle_inertia(5.0, 0.4, 0.3), 5.0 * 0.25 / 12.0, 1e-15);
    // Rings: annulus with r_i = 0 is the disc; r_i -> r_o is the hoop m r^2.
    assert_close!(ring_inertia(2.0, 0.0, 0.5), disc_inertia(2.0, 0.5), 1e-15);
    assert_close!(
        ring_inertia(2.0, 0.5, 0.5),
        thin_ring_inertia(2.0, 0.5),
        1e-15
    );
    assert_close!(point_mass_inertia(2.0, 3.0), 18.0, 1e-15);
    // Radius of gyration (MP-3): k = sqrt(I/m).
    assert_close!(radius_of_gyration(0.25, 2.0), 0.125_f64.sqrt(), 1e-15);
}

#[test]
fn capsule_matches_a_numerical_integral() {
    // Capsule: length 0 is a disc.
    assert_close!(
        capsule_inertia(2.0, 0.0, 0.3),
        disc_inertia(2.0, 0.3),
        1e-14
    );
    // Independent reference: midpoint-rule integral of (x^2 + y^2) over the stadium.
    let (l, r) = (0.8_f64, 0.15_f64);
    let n = 1600;
    let (x0, y0) = (-(l / 2.0 + r), -r);
    let (hx, hy) = ((l + 2.0 * r) / n as f64, 2.0 * r / n as f64);
    let (mut area, mut polar) = (0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (x0 + (i as f64 + 0.5) * hx, y0 + (j as f64 + 0.5) * hy);
            let dx = (x.abs() - l / 2.0).max(0.0);
            if dx * dx + y * y <= r * r {
                area += hx * hy;
                polar += (x * x + y * y) * hx * hy;
            }
        }
    }
    let exact_area = 2.0 * r * l + PI * r * r;
    assert_close!(area, exact_area, 2e-4);
    // Per unit mass: I/m = polar/area.
    assert_close!(capsule_inertia(1.0, l, r), polar / area, 5e-4);
}

#[test]
fn polygons_by_triangulation() {
    // A square as a polygon equals the rectangle formula (per unit density: J = A (a^2 + b^2)/12).
    let sq = [
        DVec2::new(-0.2, -0.1),
        DVec2::new(0.2, -0.1),
        DVec2::new(0.2, 0.1),
        DVec2::new(-0.2, 0.1),
    ];
    let p = polygon_area_props(&sq);
    assert_close!(p.area, 0.08, 1e-14);
    assert!(p.centroid.length() < 1e-15);
    assert_close!(p.polar, rectangle_inertia(0.08, 0.4, 0.2), 1e-14);
    // Right triangle with legs a, b: centroid (a/3, b/3), J_G = A (a^2 + b^2)/18.
    let (a, b) = (0.6, 0.3);
    let t = polygon_area_props(&[DVec2::ZERO, DVec2::new(a, 0.0), DVec2::new(0.0, b)]);
    assert_close!(t.area, a * b / 2.0, 1e-14);
    assert!((t.centroid - DVec2::new(a / 3.0, b / 3.0)).length() < 1e-14);
    assert_close!(t.polar, t.area * (a * a + b * b) / 18.0, 1e-13);
    // Clockwise order gives the same properties.
    let cw = polygon_area_props(&[DVec2::ZERO, DVec2::new(0.0, b), DVec2::new(a, 0.0)]);
    assert_close!(cw.area, t.area, 1e-14);
    assert_close!(cw.polar, t.polar, 1e-13);
    // The level's polygons use their convex hull: an interior point changes nothing.
    let hull = convex_hull(&[
        DVec2::ZERO,
        DVec2::new(a, 0.0),
        DVec2::new(0.1, 0.05),
        DVec2::new(0.0, b),
    ]);
    assert_eq!(hull.len(), 3);
}

#[test]
fn body_mass_properties_follow_the_level() {
    // Mass given: the shape spreads it; I_G from the formula.
    let mut b = body(Some(Shape::Box {
        width: 1.0,
        height: 0.04,
    }));
    b.mass = Some(2.0);
    let mp = of_body(&b, 1000.0);
    assert_close!(mp.mass, 2.0, 1e-15);
    assert_close!(mp.inertia, 2.0 * (1.0 + 0.0016) / 12.0, 1e-14);
    // Radius-of-gyration override (MP-3): I = m k^2.
    b.radius_of_gyration = Some(0.3);
    assert_close!(of_body(&b, 1000.0).inertia, 2.0 * 0.09, 1e-15);
    // Density: m = rho A.
    let mut d = body(Some(Shape::Circle { radius: 0.1 }));
    d.density = Some(500.0);
    let mp = of_body(&d, 1000.0);
    assert_close!(mp.mass, 500.0 * PI * 0.01, 1e-14);
    assert_close!(mp.inertia, disc_inertia(mp.mass, 0.1), 1e-14);
    // A dumbbell: two discs 1 m apart on a compound; G in the middle, I by MP-2.
    let disc = |x: f64| Part {
        shape: Shape::Circle { radius: 0.1 },
        offset: (x, 0.0),
        angle: 0.0,
    };
    let mut c = body(Some(Shape::Compound {
        parts: vec![disc(0.0), disc(1.0)],
    }));
    c.mass = Some(2.0);
    let mp = of_body(&c, 1000.0);
    assert!((mp.com - DVec2::new(0.5, 0.0)).length() < 1e-15);
    assert_close!(mp.inertia, 2.0 * (disc_inertia(1.0, 0.1) + 0.25), 1e-14);
}

// ------------------------------------------------------------------ kinematics (section 5)

#[test]
fn rolling_disc_kinematics() {
    // Disc of radius r rolling to the right at v: omega = -v/r (RK-8), C at the contact (RK-11).
    let (r, v) = (0.25, 2.0);
    let g = DVec2::new(1.0, r);
    let omega = -v / r;
    let c = instantaneous_center(g, DVec2::new(v, 0.0), omega, 1e9).unwrap();
    assert!((c - DVec2::new(1.0, 0.0)).length() < 1e-15);
    // The top point moves at 2 v, the contact point not at all (RK-6).
    assert!(
        (point_velocity(DVec2::new(v, 0.0), omega, DVec2::new(0.0, r)) - DVec2::new(2.0 * v, 0.0))
            .length()
            < 1e-15
    );
    assert!(point_velocity(DVec2::new(v, 0.0), omega, DVec2::new(0.0, -r)).length() < 1e-15);
    // Pure translation: C at infinity.
    assert_eq!(instantaneous_center(g, DVec2::new(v, 0.0), 0.0, 1e9), None);
    // RK-10 for rotation about a fixed point: a = alpha k x r - omega^2 r.
    let a = point_acceleration(DVec2::ZERO, 3.0, 2.0, DVec2::new(0.5, 0.0));
    assert!((a - DVec2::new(-2.0, 1.5)).length() < 1e-15);
    assert_close!(
        omega_from_two_points(
            DVec2::ZERO,
            DVec2::ZERO,
            DVec2::new(0.5, 0.0),
            DVec2::new(0.0, 1.5)
        ),
        3.0,
        1e-15
    );
    assert_close!(wrap_angle(3.0 * PI), PI, 1e-15);
}

#[test]
fn velocity_from_positions_is_exact_for_symplectic_euler_under_constant_force() {
    // Reference: a plain symplectic-Euler integration with S substeps per step (independent of the sim).
    for s in [1usize, 2, 4, 8] {
        let (dt, a) = (1.0 / 60.0, DVec2::new(1.5, -9.81));
        let h = dt / s as f64;
        let (mut x, mut v) = (DVec2::new(0.0, 10.0), DVec2::new(3.0, 1.0));
        let mut xs = vec![x];
        let mut vs = vec![v];
        for _ in 0..3 {
            for _ in 0..s {
                v += a * h;
                x += v * h;
            }
            xs.push(x);
            vs.push(v);
        }
        let est = velocity_from_positions(xs[1] - xs[0], xs[2] - xs[1], dt, s);
        assert!(
            (est - vs[1]).length() < 1e-11,
            "S = {s}: {est} vs {}",
            vs[1]
        );
    }
}

// ------------------------------------------------------------------ energy (section 9)

#[test]
fn kinetic_energy_forms() {
    // Disc rolling without slip: T about C = 1/2 (3/2 m r^2) (v/r)^2 = 3/4 m v^2 (6/10).
    let (m, r, v) = (2.0, 0.25, 3.0);
    let g = DVec2::new(0.0, r);
    let t_ic = kinetic_energy_about_ic(m, disc_inertia(m, r), g, DVec2::ZERO, -v / r);
    assert_close!(t_ic, 0.75 * m * v * v, 1e-15);
    assert_close!(
        kinetic_energy(m, DVec2::new(v, 0.0), disc_inertia(m, r), -v / r),
        0.75 * m * v * v,
        1e-15
    );
    // Slender bar pinned at an end: 1/2 (m l^2/3) w^2 (6/8) = 6/9 with v_G = w l/2.
    let (l, w) = (1.2, 2.0);
    let t_axis = kinetic_energy_fixed_axis(slender_bar_end_inertia(m, l), w);
    let t_g = kinetic_energy(
        m,
        DVec2::new(w * l / 2.0, 0.0),
        slender_bar_inertia(m, l),
        w,
    );
    assert_close!(t_axis, t_g, 1e-15);
    assert_close!(
        kinetic_energy_translation(m, DVec2::new(3.0, 4.0)),
        25.0,
        1e-15
    );
    // Potentials (WE-13): V_g = W y; V_e = 1/2 k x^2. Power (WE-10): F.v + M w.
    assert_close!(
        gravity_potential(2.0, DVec2::new(0.0, -9.81), DVec2::new(5.0, 3.0)),
        2.0 * 9.81 * 3.0,
        1e-15
    );
    assert_close!(spring_potential(200.0, 0.1), 1.0, 1e-15);
    assert_close!(
        power(DVec2::new(1.0, 2.0), DVec2::new(3.0, 4.0), 5.0, 6.0),
        41.0,
        1e-15
    );
}

#[test]
fn work_of_a_steps_impulses_adds_up_to_the_kinetic_energy_change() {
    // A body gets impulses J_i at arms r_i over a step; its velocities change by Newton-Euler.
    // Then sum of J_i . v_P,mid (RE-5 per step) equals T1 - T0 exactly (WE-9).
    let (m, i) = (2.0, 0.3);
    let before = Motion {
        velocity: DVec2::new(1.0, -0.5),
        omega: 0.7,
        ..Default::default()
    };
    let js = [
        (DVec2::new(0.3, 0.1), DVec2::new(0.2, -0.4)),
        (DVec2::new(-0.1, 0.5), DVec2::new(-0.3, 0.1)),
    ];
    let dp: DVec2 = js.iter().map(|j| j.0).sum();
    let dh: f64 = js.iter().map(|j| cross(j.1, j.0)).sum();
    let after = Motion {
        velocity: before.velocity + dp / m,
        omega: before.omega + dh / i,
        ..Default::default()
    };
    let work: f64 = js
        .iter()
        .map(|j| work_of_impulse_with_arm(j.0, j.1, 0.0, &before, &after))
        .sum();
    let dt = kinetic_energy(m, after.velocity, i, after.omega)
        - kinetic_energy(m, before.velocity, i, before.omega);
    assert_close!(work, dt, 1e-14);
    // Kelvin (RM-11): a body at rest struck by P at Q gets T = 1/2 P . v_Q,after.
    let rest = Motion::default();
    let (p, q) = (DVec2::new(3.0, 0.0), DVec2::new(0.0, -0.5));
    let struck = Motion {
        velocity: p / m,
        omega: cross(q, p) / i,
        ..Default::default()
    };
    assert_close!(
        work_of_impulse_with_arm(p, q, 0.0, &rest, &struck),
        kinetic_energy(m, struck.velocity, i, struck.omega),
        1e-14
    );
    let ledger = Ledger {
        kinetic: 3.0,
        gravity: -1.0,
        elastic: 0.5,
        work_nc: -0.25,
    };
    assert_close!(ledger.mechanical(), 2.5, 1e-15);
    assert_close!(ledger.balance(), 2.75, 1e-15);
}

// ------------------------------------------------------------------ momentum (section 10)

#[test]
fn angular_momentum_about_points() {
    // Bar rotating at w about a fixed end O: H_O = I_O w (6/16) = I_G w + r x m v_G (6/15).
    let (m, l, w) = (3.0, 1.2, 2.0);
    let g = DVec2::new(0.0, -l / 2.0);
    let v_g = point_velocity(DVec2::ZERO, w, g);
    let h = angular_momentum_about(m, slender_bar_inertia(m, l), g, v_g, w, DVec2::ZERO);
    assert_close!(
        h,
        angular_momentum_fixed_axis(slender_bar_end_inertia(m, l), w),
        1e-15
    );
    assert_close!(angular_momentum_g(0.3, 2.0), 0.6, 1e-15);
    assert_eq!(
        linear_momentum(2.0, DVec2::new(1.0, 2.0)),
        DVec2::new(2.0, 4.0)
    );
    // System totals (6/18, 6/19): two equal balls moving apart have G = 0.
    let bodies = [
        BodyMomentum {
            m: 1.0,
            i_g: 0.0,
            r_g: DVec2::new(0.0, 1.0),
            v_g: DVec2::new(1.0, 0.0),
            omega: 0.0,
        },
        BodyMomentum {
            m: 1.0,
            i_g: 0.0,
            r_g: DVec2::new(0.0, -1.0),
            v_g: DVec2::new(-1.0, 0.0),
            omega: 0.0,
        },
    ];
    assert_eq!(system_linear_momentum(bodies), DVec2::ZERO);
    assert_close!(system_angular_momentum(bodies, DVec2::ZERO), -2.0, 1e-15);
}

// ------------------------------------------------------------------ percussion (section 8)

#[test]
fn slender_bar_center_of_percussion_is_two_thirds_of_its_length() {
    let (m, l) = (3.0, 1.2);
    let q = center_of_percussion_distance(slender_bar_end_inertia(m, l), m, l / 2.0).unwrap();
    assert_close!(q, 2.0 * l / 3.0, 1e-15);
    let o = DVec2::ZERO;
    let g = DVec2::new(0.0, -l / 2.0);
    let qpt = center_of_percussion(o, g, slender_bar_inertia(m, l), m).unwrap();
    assert!((qpt - DVec2::new(0.0, -0.8)).length() < 1e-15);
    // Rotation about G has no center of percussion.
    assert_eq!(center_of_percussion_distance(1.0, m, 0.0), None);

    // CP-3: a blow P perpendicular to OG at h from O on a bar at rest: J_O = P (h/q - 1).
    let i_o = slender_bar_end_inertia(m, l);
    let p = DVec2::new(3.0, 0.0);
    for h in [0.8, 1.2, 0.4] {
        let blow = Blow {
            impulse: p,
            point: DVec2::new(0.0, -h),
            couple: 0.0,
        };
        let (j, w) = pivot_impulse(m, i_o, o, g, 0.0, &[blow], 0.0);
        assert_close!(j.x, 3.0 * (h / q - 1.0), 1e-14);
        assert!(j.y.abs() < 1e-15);
        assert_close!(w, 3.0 * h / i_o, 1e-15);
    }
}

// ------------------------------------------------------------------ impact (section 4)

#[test]
fn central_impact_jh_p9_10_1() {
    // JH P9.10.1: A 3220 lb at 20 mph into B 2800 lb at rest (weights stand in for masses).
    for (e, va, vb) in [
        (0.0, 10.698, 10.698),
        (0.5, 6.047, 16.047),
        (1.0, 1.395, 21.395),
    ] {
        let (a, b) = central_impact_velocities(3220.0, 2800.0, 20.0, 0.0, e);
        assert!(
            (a - va).abs() < 5e-4 && (b - vb).abs() < 5e-4,
            "e {e}: {a} {b}"
        );
        assert_close!(coefficient_of_restitution(0.0 - 20.0, b - a), e, 1e-12);
        // IM-14 against the direct energy difference.
        let t0 = 0.5 * 3220.0 * 400.0;
        let lost = t0 - 0.5 * 3220.0 * a * a - 0.5 * 2800.0 * b * b;
        assert!(
            (central_impact_energy_loss(3220.0, 2800.0, 20.0, 0.0, e) - lost).abs() < 1e-12 * t0
        );
    }
    // A fixed barrier: the whole approach energy times (1 - e^2).
    assert_close!(
        central_impact_energy_loss(2.0, f64::INFINITY, 3.0, 0.0, 0.5),
        0.5 * 2.0 * 9.0 * 0.75,
        1e-15
    );
    assert!(is_eccentric(
        DVec2::new(-0.4, 0.025),
        DVec2::ZERO,
        DVec2::Y,
        1e-3
    ));
    assert!(!is_eccentric(
        DVec2::new(0.0, 0.1),
        DVec2::ZERO,
        DVec2::Y,
        1e-3
    ));
}

#[test]
fn impact_detector_brackets_impulsive_steps() {
    let mut d = ImpactDetector::new(0.1, 0.2);
    let seq: Vec<Bracket> = [0.0, 0.05, 5.0, 2.0, 0.05, 0.05, 0.0, 3.0, 0.0]
        .iter()
        .map(|&x| d.step(x, true))
        .collect();
    use Bracket::*;
    assert_eq!(
        seq,
        vec![Quiet, Quiet, Start, Continue, End, Quiet, Quiet, Start, End]
    );
    // A contact that goes on carrying a load after the impact (a ball landing on a pile) ends
    // the impact at the first step that no longer changes the pair's motion, whatever its
    // impulse; a step that still does continues it.
    let mut d = ImpactDetector::new(0.1, 0.2);
    let seq: Vec<Bracket> = [
        (0.0, true),
        (5.0, true),
        (3.0, true),
        (3.0, false),
        (3.0, false),
    ]
    .iter()
    .map(|&(x, moves)| d.step(x, moves))
    .collect();
    assert_eq!(seq, vec![Quiet, Start, Continue, End, Quiet]);
}

// ------------------------------------------------------------------ kinetics (section 7)

fn state(
    name: &str,
    com: DVec2,
    velocity: DVec2,
    omega: f64,
    mass: f64,
    inertia: f64,
) -> BodyState {
    BodyState {
        name: name.into(),
        kind: if mass > 0.0 {
            BodyKind::Dynamic
        } else {
            BodyKind::Fixed
        },
        position: com,
        angle: 0.0,
        com,
        velocity,
        omega,
        mass,
        inertia,
        local_com: DVec2::ZERO,
    }
}

fn snapshot(bodies: Vec<BodyState>, contacts: Vec<ContactState>, dt: f64) -> Snapshot {
    Snapshot {
        step: 1,
        time: dt,
        dt,
        substeps: 1,
        precision: rigidlab::snapshot::Precision::F32,
        gravity: DVec2::new(0.0, -9.81),
        bodies,
        contacts,
        joints: Vec::new(),
        springs: Vec::new(),
        couplings: Vec::new(),
        loads: Vec::new(),
        impulses: Vec::new(),
    }
}

#[test]
fn free_body_of_a_block_on_the_floor_balances() {
    // A 2 kg block resting on a floor: the floor's two points carry m g dt; friction none.
    let dt = 0.01;
    let floor = state("floor", DVec2::new(0.0, -0.5), DVec2::ZERO, 0.0, 0.0, 0.0);
    let block = state("block", DVec2::new(0.0, 0.2), DVec2::ZERO, 0.0, 2.0, 0.05);
    let pt = |x: f64| ContactPoint {
        point: DVec2::new(x, 0.0),
        distance: 0.0,
        normal_impulse: 2.0 * 9.81 * dt / 2.0,
        tangent_impulse: 0.0,
        arms: None,
        local: None,
    };
    let c = ContactState {
        body1: 0,
        body2: 1,
        normal: DVec2::Y,
        points: vec![pt(-0.2), pt(0.2)],
    };
    let s = snapshot(vec![floor, block.clone()], vec![c], dt);
    let before: Vec<Motion> = s.bodies.iter().map(Motion::from).collect();
    let fbd = free_body(&before, &s, 1, 4);
    assert_eq!(fbd.len(), 3); // gravity and two contact points
    let mut r = Resultant::default();
    fbd.iter().for_each(|i| r.add(i, DVec2::ZERO));
    assert!(r.impulse.length() < 1e-15 && r.moment_g.abs() < 1e-15);
    let now = Motion::from(&block);
    let (df, dm) = newton_euler_residual(2.0, 0.05, &now, &now, r.impulse, r.moment_g, dt);
    assert!(df.length() < 1e-12 && dm.abs() < 1e-12);
    // 6/2 and 6/4 forms.
    assert_close!(
        kinetic_moment_about(
            2.0,
            0.05,
            1.0,
            DVec2::new(0.0, -1.0),
            DVec2::new(2.0, 0.0),
            DVec2::ZERO
        ),
        0.05 + 4.0,
        1e-15
    );
    assert_close!(kinetic_moment_fixed_axis(1.44, 2.0), 2.88, 1e-15);
    assert_eq!(
        kinetic_force(2.0, DVec2::new(1.0, 0.0)),
        DVec2::new(2.0, 0.0)
    );
    // Gravity acts at the mean of the substeps' start positions.
    assert!(
        (gravity_point(DVec2::ZERO, DVec2::new(8.0, 0.0), 4) - DVec2::new(3.0, 0.0)).length()
            < 1e-15
    );
}

#[test]
fn contact_impulses_act_at_the_solver_arms_when_the_snapshot_has_them() {
    // A block moving at 1 m/s over the floor. The engine's arms (from a manifold update two steps
    // ago, point (0.3, 0) then, G at (0.0, 0.2)) differ from the recorded point carried back to
    // the start of the step: the free-body diagram must use the engine's.
    let dt = 0.01;
    let floor = state("floor", DVec2::ZERO, DVec2::ZERO, 0.0, 0.0, 0.0);
    let block = |x: f64| state("block", DVec2::new(x, 0.2), DVec2::X, 0.0, 1.0, 0.1);
    let point = ContactPoint {
        point: DVec2::new(0.32, 0.0),
        distance: 0.0,
        normal_impulse: 0.1,
        tangent_impulse: 0.0,
        arms: Some((DVec2::new(0.3, 0.0), DVec2::new(0.3, -0.2))),
        local: None,
    };
    let contact = |p: ContactPoint| ContactState {
        body1: 0,
        body2: 1,
        normal: DVec2::Y,
        points: vec![p],
    };
    let before: Vec<Motion> = [floor.clone(), block(0.01)]
        .iter()
        .map(Motion::from)
        .collect();
    let snap = snapshot(
        vec![floor.clone(), block(0.02)],
        vec![contact(point.clone())],
        dt,
    );
    let fbd = free_body(&before, &snap, 1, 1);
    let c = fbd
        .iter()
        .find(|i| matches!(i.source, Source::Contact { .. }))
        .unwrap();
    assert!((c.arm - DVec2::new(0.3, -0.2)).length() < 1e-15);
    // Moment about G of the normal impulse 0.1 N s at arm (0.3, -0.2): (r x J)_z = 0.3 * 0.1.
    assert!((c.moment_about_g() - 0.03).abs() < 1e-15);
    // Without the engine's arms: the point at the start of the step, (0.32, 0) - (0.01, 0.2).
    let snap = snapshot(
        vec![floor, block(0.02)],
        vec![contact(ContactPoint {
            arms: None,
            local: None,
            ..point
        })],
        dt,
    );
    let fbd = free_body(&before, &snap, 1, 1);
    let c = fbd
        .iter()
        .find(|i| matches!(i.source, Source::Contact { .. }))
        .unwrap();
    assert!((c.arm - DVec2::new(0.31, -0.2)).length() < 1e-15);
}

// ------------------------------------------------------------------ identities on random states

fn v2() -> impl Strategy<Value = DVec2> {
    (-10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

proptest! {
    /// 6/10 = 6/9: KE about the instantaneous center equals KE about G whenever omega != 0.
    #[test]
    fn ke_about_ic_equals_ke_about_g(m in 0.1..50.0f64, i_g in 0.001..10.0f64, g in v2(), v in v2(),
                                    w in prop_oneof![-20.0..-0.05f64, 0.05..20.0f64]) {
        let c = instantaneous_center(g, v, w, 1e12).unwrap();
        // C has zero velocity (RK-11).
        prop_assert!(point_velocity(v, w, c - g).length() <= 1e-9 * (1.0 + v.length()));
        let t_ic = kinetic_energy_about_ic(m, i_g, g, c, w);
        let t_g = kinetic_energy(m, v, i_g, w);
        prop_assert!((t_ic - t_g).abs() <= 1e-9 * (1.0 + t_g));
    }

    /// 6/15: H about O' = H about O + r_{O/O'} x G for any two points.
    #[test]
    fn angular_momentum_transfers_between_points(m in 0.1..50.0f64, i_g in 0.001..10.0f64, g in v2(),
                                                 v in v2(), w in -20.0..20.0f64, o in v2(), o2 in v2()) {
        let h_o = angular_momentum_about(m, i_g, g, v, w, o);
        let h_o2 = angular_momentum_about(m, i_g, g, v, w, o2);
        let moved = transfer_angular_momentum(h_o, o, o2, linear_momentum(m, v));
        prop_assert!((moved - h_o2).abs() <= 1e-9 * (1.0 + h_o2.abs()));
        prop_assert!((h_o2 - (h_o + cross(o - o2, m * v))).abs() <= 1e-9 * (1.0 + h_o2.abs()));
    }

    /// Rotation about a fixed point O: 6/8 (I_O by MP-2) equals 6/9, and 6/16 equals 6/15.
    #[test]
    fn fixed_axis_forms_agree(m in 0.1..50.0f64, i_g in 0.001..10.0f64, o in v2(), r in v2(), w in -20.0..20.0f64) {
        let g = o + r;
        let v = point_velocity(DVec2::ZERO, w, r);
        let i_o = parallel_axis(i_g, m, r.length());
        let t = kinetic_energy(m, v, i_g, w);
        prop_assert!((kinetic_energy_fixed_axis(i_o, w) - t).abs() <= 1e-9 * (1.0 + t));
        let h = angular_momentum_about(m, i_g, g, v, w, o);
        prop_assert!((angular_momentum_fixed_axis(i_o, w) - h).abs() <= 1e-9 * (1.0 + h.abs()));
    }

    /// A polygon's area properties do not depend on where its vertex list starts.
    #[test]
    fn polygon_props_are_independent_of_the_starting_vertex(n in 3usize..9, shift in 0usize..9,
                                                             rx in 0.2..3.0f64, ry in 0.2..3.0f64) {
        let pts: Vec<DVec2> = (0..n).map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            DVec2::new(rx * a.cos(), ry * a.sin()) + DVec2::new(1.0, -2.0)
        }).collect();
        let mut rot = pts.clone();
        rot.rotate_left(shift % n);
        let (a, b) = (polygon_area_props(&pts), polygon_area_props(&rot));
        prop_assert!((a.area - b.area).abs() < 1e-12);
        prop_assert!((a.polar - b.polar).abs() < 1e-10);
        prop_assert!((a.centroid - DVec2::new(1.0, -2.0)).length() < 1e-9);
    }
}
