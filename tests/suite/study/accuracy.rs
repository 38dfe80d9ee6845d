//! The accuracy study: the error ordering the method predicts, checked without timing anything,
//! and the CLI's output contract.
//!
//! Expected orderings come from the integrator, not from the engine's output:
//! - rapier integrates with symplectic Euler over substeps h = dt / substeps; its energy error per
//!   unit time is O(h), so halving dt must shrink a pendulum's energy drift (about halve it);
//! - joint rows are solved once per substep at the velocity level and the position error they leave
//!   is corrected over the next substeps; with more substeps the anchors separate less;
//! - f32 carries about 7 significant digits: a body 10 km from the origin has a position ulp of
//!   about 1 mm, so steps that move it less than that are lost, whereas f64 (16 digits) keeps them.

use crate::common;

use common::parse as scene;
use rigidlab::study::accuracy::measure::{
    conservation, full_run, reference, self_consistency, Precision, Setting,
};
use rigidlab::study::accuracy::metrics::{self, body_deviation, pareto_front, MassProps};
use rigidlab::study::accuracy::{points, Plan, CSV_COLUMNS};

fn setting(dt: f64, substeps: usize, precision: Precision) -> Setting {
    Setting {
        dt,
        substeps,
        iterations: 1,
        precision,
        all_effects: false,
        engine: rigidlab::level::PhysicsEngine::Rapier,
    }
}

/// A 1 kg bob on a 1 m pin link released from 60 degrees: conservative (gravity and a workless pin).
const PENDULUM: &str = r#"Level(title: "pendulum", effects: [gravity, joints],
    world: (dt: 0.016666666666666666, substeps: 4, duration: 1.0),
    bodies: [
        (name: "pivot", kind: fixed),
        (name: "bob", shape: Circle(radius: 0.05), mass: 1.0, inertia: 1e-6, position: (0.8660254037844386, -0.5)),
    ],
    joints: [(name: "rod", kind: revolute, body1: "pivot", body2: "bob", anchor2: (-0.8660254037844386, 0.5))])"#;

/// A chain of five 0.5 m links (1 kg capsules) pinned end to end, released horizontally.
fn chain() -> String {
    let mut bodies = String::from(r#"(name: "pivot", kind: fixed),"#);
    let mut joints = String::new();
    for i in 0..5 {
        bodies += &format!(
            r#"(name: "l{i}", shape: Capsule(length: 0.4, radius: 0.05), mass: 1.0, position: ({x}, 0.0)),"#,
            x = 0.25 + 0.5 * i as f64
        );
        let (b1, a1) = if i == 0 {
            ("pivot".to_string(), "(0.0, 0.0)".to_string())
        } else {
            (format!("l{}", i - 1), "(0.25, 0.0)".to_string())
        };
        joints += &format!(
            r#"(name: "j{i}", kind: revolute, body1: "{b1}", body2: "l{i}", anchor1: {a1}, anchor2: (-0.25, 0.0)),"#
        );
    }
    format!(
        r#"Level(title: "chain", effects: [gravity, joints],
        world: (dt: 0.016666666666666666, substeps: 4, duration: 1.5),
        bodies: [{bodies}], joints: [{joints}])"#
    )
}

#[test]
fn halving_dt_reduces_the_pendulums_energy_drift() {
    let s = scene(PENDULUM);
    let what = metrics::conserved(&s.level);
    assert!(what.energy, "gravity + a pin is conservative");
    // f64 so that round-off does not blur the O(h) trend; 10 s = several periods (T ~ 2.15 s).
    let drift = |dt: f64| {
        conservation(&s, &setting(dt, 4, Precision::F64), what, 10.0)
            .energy_drift_per_s
            .expect("the pendulum moves")
    };
    let d: Vec<f64> = [1.0 / 30.0, 1.0 / 60.0, 1.0 / 120.0, 1.0 / 240.0]
        .iter()
        .map(|&dt| drift(dt))
        .collect();
    eprintln!("pendulum energy drift per second, dt 1/30..1/240: {d:?}");
    for w in d.windows(2) {
        // O(h): halving dt about halves |drift|; allow up to 0.75 for the soft joint's own dt terms.
        assert!(
            w[1].abs() < 0.75 * w[0].abs(),
            "energy drift per second did not shrink with dt: {d:?}"
        );
    }
}

#[test]
fn more_substeps_reduce_joint_drift() {
    let s = scene(&chain());
    let drift = |n: usize| {
        full_run(&s, &setting(1.0 / 60.0, n, Precision::F64))
            .joint_drift_m
            .expect("the chain has joints")
    };
    let d: Vec<f64> = [1, 2, 4, 8, 16].iter().map(|&n| drift(n)).collect();
    eprintln!("chain joint separation, 1..16 substeps: {d:?} m");
    for w in d.windows(2) {
        assert!(
            w[1] < w[0],
            "joint anchor separation did not shrink with substeps: {d:?}"
        );
    }
    // 16 substeps against 1: the separation falls by well over an order of magnitude.
    assert!(d[4] < 0.1 * d[0], "{d:?}");
}

#[test]
fn f64_is_not_less_accurate_than_f32_where_round_off_dominates() {
    // 10 km from the origin, 1 m/s, no forces: x = x0 + v t exactly (closed form).
    // Each substep moves it v h = 1/(960*16) m = 65 µm, far below the f32 ulp of 1 mm there.
    let s = scene(
        r#"Level(title: "far cruise", effects: [],
        world: (dt: 0.0010416666666666667, substeps: 16, duration: 1.0),
        bodies: [(name: "puck", shape: Circle(radius: 0.1), mass: 1.0, position: (10000.0, 0.0), velocity: (1.0, 0.0))],
        checks: [(kind: constant_acceleration, body: "puck", tolerance: 1e-6, why: "closed form")])"#,
    );
    let err = |p: Precision| {
        full_run(&s, &setting(1.0 / 960.0, 16, p))
            .closed_form_error
            .expect("the closed-form check runs")
    };
    let (e32, e64) = (err(Precision::F32), err(Precision::F64));
    eprintln!("far cruise closed-form error: f32 {e32}, f64 {e64}");
    assert!(e64 <= e32, "f64 {e64} is less accurate than f32 {e32}");
    // The error is relative to the 1 m displacement. f64: at most half an ulp (2^-40 m at 10 km)
    // per substep over 15360 substeps, 1.4e-8 m. f32: half an ulp (2^-11 m = 0.49 mm) exceeds the
    // 65 µm increment, so every position update rounds back and the puck does not move at all.
    assert!(e64 < 1.4e-8, "f64 error {e64}");
    assert!(e32 > 0.5, "f32 error {e32}: round-off should dominate");
}

#[test]
fn a_piece_run_at_the_reference_setting_reproduces_the_reference() {
    // The restart (fresh simulation, body states overwritten from the reference) must not itself
    // introduce error: at the reference's own setting the pieces land on the reference.
    let s = scene(PENDULUM);
    let r = reference(&s, &setting(1.0 / 960.0, 4, Precision::F64));
    assert!(r.stopped.is_none());
    let e = self_consistency(&s, &r.setting, &r, 5, 0.1).expect("pieces run");
    eprintln!("restart at the reference setting: {e} m");
    assert!(
        e < 1e-9,
        "restarted pieces drift from the reference by {e} m"
    );
    // A coarse setting is measurably off: the measure can fail.
    let coarse = self_consistency(&s, &setting(1.0 / 30.0, 1, Precision::F32), &r, 5, 0.1)
        .expect("pieces run");
    assert!(coarse > 1e-4, "coarse setting error {coarse} m");
}

#[test]
fn self_consistency_error_shrinks_with_dt() {
    let s = scene(PENDULUM);
    let r = reference(&s, &setting(1.0 / 3840.0, 16, Precision::F64));
    let e: Vec<f64> = [1.0 / 30.0, 1.0 / 120.0, 1.0 / 480.0]
        .iter()
        .map(|&dt| self_consistency(&s, &setting(dt, 4, Precision::F64), &r, 5, 0.1).unwrap())
        .collect();
    eprintln!("pendulum self-consistency, dt 1/30, 1/120, 1/480: {e:?} m");
    assert!(e[1] < e[0] && e[2] < e[1], "{e:?}");
}

#[test]
fn body_deviation_is_the_mass_weighted_rms_distance() {
    use glam::DVec2;
    use rigidlab::snapshot::{BodyKind, BodyState};
    // A uniform disk of radius r turned by pi about G: every point at rho moves 2 rho, so the
    // RMS distance is 2 k with k^2 = r^2 / 2 (MP-3).
    let r = 0.3;
    let m = 2.0;
    let disk = |angle: f64, com: DVec2| BodyState {
        name: "d".into(),
        kind: BodyKind::Dynamic,
        position: com,
        angle,
        com,
        velocity: DVec2::ZERO,
        omega: 0.0,
        mass: m,
        inertia: 0.5 * m * r * r,
        local_com: DVec2::ZERO,
    };
    let props = MassProps {
        mass: m,
        inertia: 0.5 * m * r * r,
        local_com: DVec2::ZERO,
    };
    let k = (0.5f64).sqrt() * r;
    let d = body_deviation(
        &disk(std::f64::consts::PI, DVec2::ZERO),
        &disk(0.0, DVec2::ZERO),
        &props,
    );
    assert!((d - 2.0 * k).abs() < 1e-12, "{d}");
    // A pure translation moves every point by the same distance.
    let d = body_deviation(
        &disk(0.0, DVec2::new(0.3, 0.4)),
        &disk(0.0, DVec2::ZERO),
        &props,
    );
    assert!((d - 0.5).abs() < 1e-12, "{d}");
    // With G off the body origin, a turn about the origin moves G too: G at (0.1, 0) turned by pi
    // lands at (-0.1, 0), 0.2 m away, on top of the 2 k of the turn about G.
    let off = MassProps {
        local_com: DVec2::new(0.1, 0.0),
        ..props
    };
    let d = body_deviation(
        &disk(std::f64::consts::PI, DVec2::ZERO),
        &disk(0.0, DVec2::ZERO),
        &off,
    );
    assert!((d - (0.04 + 4.0 * k * k).sqrt()).abs() < 1e-12, "{d}");
}

#[test]
fn pareto_front_keeps_only_undominated_points() {
    let pts = [
        (1.0, 10.0),
        (2.0, 5.0),
        (3.0, 6.0),
        (4.0, 1.0),
        (0.5, f64::NAN),
    ];
    assert_eq!(pareto_front(&pts), vec![0, 1, 3]);
}

#[test]
fn the_sweep_varies_one_knob_at_a_time() {
    let s = scene(PENDULUM);
    let base = Setting::of_level(&s.level);
    for p in points(&s.level, &Plan::full()) {
        let q = p.setting;
        let changed = [
            q.dt != base.dt,
            q.substeps != base.substeps,
            q.iterations != base.iterations,
            q.precision != base.precision,
            q.all_effects != base.all_effects,
        ]
        .iter()
        .filter(|c| **c)
        .count();
        // dt (f64) changes dt and precision together; rapier's defaults may differ in three knobs.
        let allowed = if p.rapier_default && !p.baseline {
            3
        } else {
            2
        };
        assert!(changed <= allowed, "{:?}", p);
        if q.precision == base.precision && !p.rapier_default {
            assert!(changed <= 1, "{:?}", p);
        }
    }
}

#[test]
fn quick_study_writes_the_csv_with_the_required_columns() {
    let dir = std::env::temp_dir().join(format!("rigidlab-accuracy-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let level = dir.join("pendulum.ron");
    std::fs::write(&level, PENDULUM.replace("duration: 1.0", "duration: 0.3")).unwrap();
    let out = dir.join("out");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_rigidlab"))
        .args(["study", "accuracy"])
        .arg(&level)
        .arg("--out")
        .arg(&out)
        .arg("--quick")
        .status()
        .expect("the binary runs");
    assert!(status.success(), "{status}");
    let csv = std::fs::read_to_string(out.join("accuracy.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    for col in [
        "level",
        "dt",
        "substeps",
        "pgs_iterations",
        "precision",
        "effects",
        "error",
        "cost_us_per_sim_s",
        "energy_drift_per_s",
        "position_error_m",
    ] {
        assert!(header.contains(&col), "missing column {col} in {header:?}");
    }
    assert_eq!(header, CSV_COLUMNS.to_vec());
    let rows: Vec<&str> = lines.collect();
    let quick = points(&scene(PENDULUM).level, &Plan::quick()).len();
    assert_eq!(rows.len(), quick, "one row per swept setting");
    assert!(out.join("summary.md").exists());
    let pngs = std::fs::read_dir(&out)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "png")
        })
        .count();
    assert_eq!(pngs, 1, "one Pareto plot for the one level");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_paths_exit_2_without_panicking() {
    let out = std::env::temp_dir().join(format!("rigidlab-accuracy-bad-{}", std::process::id()));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_rigidlab"))
        .args(["study", "accuracy", "/no/such/level.ron", "--out"])
        .arg(&out)
        .output()
        .expect("the binary runs");
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no such file"));
}
