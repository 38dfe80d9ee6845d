//! A pinned bar striking a fixed peg (issue 34): e at the contact point, and the `restitution`
//! check's law, against theory.
//!
//! Top view (no gravity). A uniform bar (L = 1.2 m, w = 0.04 m, m = 3 kg) pinned at its end O =
//! (0, 0), lying along +x, turning counterclockwise at omega0 = 2 rad/s, strikes a fixed peg (a
//! disc of radius 0.01 m) with its upper face at distance d from O. The peg sits where the face
//! touches it after the bar has turned 2 mrad, at the bar-frame point (d, w/2 + r_p), so the
//! contact point is at distance d along the bar and the normal is the bar's face normal.
//!
//! Theory (IM-12 for the contact point of a body with one degree of freedom, 6/17 about O): the
//! contact point moves at omega d along the normal, so v_n' = -e v_n gives omega' = -e omega0,
//! whatever d is. The pin's impulse (CP-3, `pivot_impulse`) vanishes at d = q = I_O/(m L/2).
//!
//! The engine's gap (docs/known-gaps.md, the cause in rapier 0.36's source): rapier bounces a
//! contact in an end-of-step restitution pass (`apply_restitution`, solver
//! `staged_island_solver/worker.rs`) that solves the contact rows alone, after all substeps and
//! without the joints. The pass drives the contact's normal velocity to e v_n with the free
//! bar's effective mass, 1/m + (d - L/2)^2/I_G, so it gives the bar an impulse
//! P = e v_n / (1/m + (d - L/2)^2/I_G) while the pin is not there to push back. The next call's
//! joint rows bring the bar back to turning about O; that pin impulse has no moment about O, so it
//! keeps the angular momentum about O the pass gave: d_omega = P d / I_O. The rebound is then
//! e_read = e (d^2/I_O) / (1/m + (d - L/2)^2/I_G) (1 at d = q, where the free bar struck at the
//! center of percussion already turns about O; 0.75 at the tip of a thin bar).

use rigidlab::level::parse;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

const L: f64 = 1.2;
const W: f64 = 0.04;
const M: f64 = 3.0;
const R_PEG: f64 = 0.01;
const OMEGA0: f64 = 2.0;
const E: f64 = 0.5;

fn i_g() -> f64 {
    M * (L * L + W * W) / 12.0
}

fn i_o() -> f64 {
    i_g() + M * (L / 2.0).powi(2)
}

/// The center of percussion's distance from O, q = I_O / (m L/2) (CP-1): 0.80022 m.
fn q() -> f64 {
    i_o() / (M * L / 2.0)
}

/// What rapier's restitution pass followed by the pin's projection gives (the module doc).
fn e_rapier(d: f64) -> f64 {
    E * (d * d / i_o()) / (1.0 / M + (d - L / 2.0).powi(2) / i_g())
}

/// The level: the peg at distance `d` along the bar, and the `restitution` check.
fn level(d: f64) -> String {
    // The angle the bar turns before it touches (2.3 mrad, met within a step's calls; 2 mrad
    // meets it at 1e-3 s, a step's boundary at 1e-3 and 1e-4 s: see docs/known-gaps.md).
    let theta: f64 = std::env::var("PEG_THETA")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2.3e-3);
    let (px, py) = (d, W / 2.0 + R_PEG);
    let (c, s) = (theta.cos(), theta.sin());
    let peg = (c * px - s * py, s * px + c * py);
    format!(
        r#"Level(title: "pinned bar strikes a peg at d = {d}", effects: [contacts, restitution, joints],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 0.05),
        bodies: [
            (name: "pivot", kind: fixed),
            (name: "peg", kind: fixed, shape: Circle(radius: {R_PEG}), position: ({px}, {py}), restitution: {E}),
            (name: "bar", shape: Box(width: {L}, height: {W}), mass: {M}, position: ({half}, 0.0),
             velocity: (0.0, {vg}), omega: {OMEGA0}, restitution: {E}),
        ],
        joints: [(name: "pin", kind: revolute, body1: "pivot", body2: "bar", anchor2: ({minus_half}, 0.0))],
        checks: [(kind: restitution, body: "bar", other: "peg", tolerance: 1e-2,
            why: "the bar's rebound against the law that applies")],
        questions: [
            (id: "e", ask: "e at the contact", unit: "1", expected: {E}, tolerance: 1e-2,
             quantity: Restitution(body: "bar", other: "peg"), at: ContactEnds(body: "bar", other: "peg"),
             why: "IM-12 at the contact point"),
            (id: "omega", ask: "omega after", unit: "rad/s", expected: {w1}, tolerance: 1e-2,
             quantity: Omega("bar"), at: End,
             why: "omega' = -e omega0; read at the end (0.05 s, the bar turning freely about O since the rebound), after the pin has taken the bar back to turning about O"),
        ],
        )"#,
        px = peg.0,
        py = peg.1,
        half = L / 2.0,
        minus_half = -L / 2.0,
        vg = OMEGA0 * L / 2.0,
        w1 = -E * OMEGA0,
    )
}

fn run(d: f64, opts: &Options) -> rigidlab::report::LevelReport {
    let scene = parse(Path::new("peg.ron"), &level(d)).unwrap_or_else(|e| panic!("{e}"));
    runner::run_scene(&scene, opts, &HashMap::new(), |_| {}).unwrap()
}

fn at(dt: f64, substeps: usize, iterations: Option<usize>) -> Options {
    Options {
        dt: Some(dt),
        substeps: Some(substeps),
        solver_iterations: iterations,
        ..Options::default()
    }
}

/// The analysis alone: the obstacle's impulse and the pin's from `strike_on_fixed_obstacle`
/// against CP-3's closed form J_O = lambda (m r_bar h / I_O - 1) for a blow lambda perpendicular
/// to OG at h (the impulse on the bar: I_O (omega' - omega0) = -lambda h with omega' = -e
/// omega0). To 1e-12 (rounding of a few products).
#[test]
fn the_pin_impulse_of_a_strike_vanishes_only_at_the_center_of_percussion() {
    use glam::DVec2;
    use rigidlab::analysis::percussion::strike_on_fixed_obstacle;
    let (o, g) = (DVec2::ZERO, DVec2::new(L / 2.0, 0.0));
    for h in [0.3, 0.6, q(), 1.0, L] {
        // The peg above the bar: the normal on the bar is -y.
        let (blow, j_o, w1) = strike_on_fixed_obstacle(
            M,
            i_o(),
            o,
            g,
            OMEGA0,
            (DVec2::new(h, W / 2.0), DVec2::NEG_Y),
            E,
        )
        .unwrap();
        let lambda = i_o() * (1.0 + E) * OMEGA0 / h;
        assert!((w1 + E * OMEGA0).abs() < 1e-12, "{w1}");
        assert!((blow - DVec2::new(0.0, -lambda)).length() < 1e-12, "{blow}");
        let cp3 = -lambda * (M * (L / 2.0) * h / i_o() - 1.0);
        assert!(
            (j_o - DVec2::new(0.0, cp3)).length() < 1e-12,
            "h {h}: {j_o} against {cp3}"
        );
        assert_eq!(j_o.length() < 1e-9, (h - q()).abs() < 1e-12, "h {h}: {j_o}");
    }
    // A normal through the pin cannot stop the bar's turning.
    assert!(
        strike_on_fixed_obstacle(M, i_o(), o, g, OMEGA0, (DVec2::new(1.0, 0.0), DVec2::X), E)
            .is_none()
    );
}

/// Struck at its center of percussion the pin takes no impulse: the free bar's bounce is the
/// pinned bar's, so rapier's rebound is exact (e_rapier(q) = e). The `restitution` check grades
/// e at the contact (IM-12) and says the pin takes no impulse; before issue 34 it took H about
/// the pin as kept and failed by 1.5 (H_O reverses: -e omega0 I_O for omega0 I_O), and H about C
/// cannot stand in for it: it is zero for any rotation about the pin (I_O - q m r_bar = 0).
/// Tolerances: the rebound at 1/240 s, 4 substeps reads 0.49999 (1e-4 allowed: rapier's soft
/// pin gives a little in the impact call); the check's own tolerance in the level, 1e-2.
#[test]
fn a_bar_striking_a_peg_at_its_center_of_percussion_is_graded_on_e_and_rebounds_right() {
    assert!((e_rapier(q()) - E).abs() < 1e-12);
    for opts in [
        Options::default(),
        at(1.0 / 480.0, 4, None),
        at(1e-3, 4, None),
    ] {
        let r = run(q(), &opts);
        let check = &r.checks[0];
        assert!(check.passed, "{check:?}");
        assert_eq!(check.theory, E, "{check:?}");
        assert!(
            check
                .note
                .contains("center of percussion, the pin takes no impulse"),
            "{}",
            check.note
        );
        let omega = &r.questions[1];
        assert!((omega.engine + E * OMEGA0).abs() < 1e-4, "{omega:?}");
    }
}

/// Struck at its tip the bar keeps H about neither the pin nor C: the check grades e at the
/// contact (theory e = 0.5, IM-12), and rapier's rebound falls short by the published gap
/// (docs/known-gaps.md), whose size the cause predicts: e_rapier(1.19) = 0.37836 (module doc).
/// At 16 solver iterations the pin acts fully within the impact call and the prediction holds
/// to 1e-4 (measured 0.37836 at 1/240 s and 0.37796 at 1e-3 s); at 4 iterations the pin acts in
/// part there, and the rebound reads 0.3774 to 0.4014 over dt 1/240 s to 1e-4 s and 4 to 16
/// substeps (3e-2 allowed). Any of these fails the check (its tolerance 1e-2): the check says
/// so honestly, and a rapier that bounced jointed bodies right would fail this test, calling for
/// the gap's row to go.
#[test]
fn a_bar_striking_a_peg_at_its_tip_is_graded_on_e_and_rebounds_short() {
    let d = L - R_PEG;
    let predicted = e_rapier(d);
    assert!((predicted - 0.37836).abs() < 1e-5, "{predicted}");
    let cases = [
        (at(1.0 / 240.0, 4, Some(16)), 4e-3),
        (at(1e-3, 4, Some(16)), 4e-3),
        (Options::default(), 3e-2),
        (at(1.0 / 960.0, 4, None), 3e-2),
        (at(1.0 / 240.0, 16, None), 3e-2),
    ];
    for (opts, tol) in cases {
        let r = run(d, &opts);
        let check = &r.checks[0];
        assert!(check.note.contains("e at the contact"), "{}", check.note);
        assert_eq!(check.theory, E, "{check:?}");
        assert!(
            (check.engine - predicted).abs() < tol,
            "{opts:?}: e {} against {predicted}",
            check.engine
        );
        assert!(!check.passed, "{check:?}");
        // The bar's own rebound once the pin has it turning about O again (the end of the run).
        let omega = r.questions[1].engine;
        assert!(
            (-omega / OMEGA0 - predicted).abs() < tol,
            "{opts:?}: omega' {omega}"
        );
    }
}

/// The measurement behind the gap (run with `--ignored --nocapture`): e read against d and the
/// settings, beside the cause's prediction.
#[test]
#[ignore]
fn measure_e_against_d_and_settings() {
    let dt = |x: f64| Options {
        dt: Some(x),
        ..Options::default()
    };
    let settings: [(&str, Options); 10] = [
        ("1/480 s, 4 substeps", dt(1.0 / 480.0)),
        ("1/960 s, 4 substeps", dt(1.0 / 960.0)),
        ("1e-3 s, 4 substeps", dt(1e-3)),
        (
            "1e-3 s, 4 substeps, 16 iterations",
            Options {
                dt: Some(1e-3),
                solver_iterations: Some(16),
                ..Options::default()
            },
        ),
        ("1/240 s, 4 substeps", Options::default()),
        (
            "1/240 s, 16 substeps",
            Options {
                substeps: Some(16),
                ..Options::default()
            },
        ),
        (
            "1e-4 s, 4 substeps",
            Options {
                dt: Some(1e-4),
                ..Options::default()
            },
        ),
        (
            "1/240 s, 4 substeps, 16 iterations",
            Options {
                solver_iterations: Some(16),
                ..Options::default()
            },
        ),
        (
            "1/240 s, no impact cuts",
            Options {
                impact_cuts: Some(false),
                ..Options::default()
            },
        ),
        (
            "1/240 s, f64",
            Options {
                precision: Some(rigidlab::level::Precision::F64),
                ..Options::default()
            },
        ),
    ];
    for d in [q(), 0.9, 1.0, L - R_PEG] {
        for (name, o) in &settings {
            let r = run(d, o);
            let e = r.questions[0].engine;
            let w = r.questions[1].engine;
            println!(
                "d = {d:.5}: {name}: e {e:.5} at ContactEnds, -omega'/omega0 at the end {:.5} (cause predicts {:.5}); check {} {:.4e}",
                -w / OMEGA0,
                e_rapier(d),
                r.checks[0].passed,
                r.checks[0].max_rel_error
            );
        }
    }
}
