//! Curved tracks in the editor (issue 30): a loop-the-loop built from nothing with the editor's
//! edits alone (a polyline floor, an arc loop, a disc launched along the floor), saved, and run by
//! `rigidlab check` against the speeds energy gives; the validator's refusals of bad tracks come
//! back as messages and leave the scene as it was; track edits undo, redo and round-trip as RON.
//! The same loop is built in the window's editor headless (MinimalPlugins) and saved there.

#[cfg(feature = "app")]
use crate::common;

use rigidlab::editor::{self, parse_points, Edit, History, NewShape, Property};
use rigidlab::level::{self, ArcSide, Quantity, QuestionDef, Scene, Shape, TrackSide, When};
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};
use std::process::Command;

const G: f64 = 9.81;
/// The loop's radius and the disc's, m; the disc's center rides a circle of rho = R - r.
const R: f64 = 1.0;
const DISC_R: f64 = 0.1;
/// The launch speed along the floor, m/s.
const V0: f64 = 7.0;

/// The expected speeds, from energy (RE-7) for a smooth disc that slides without turning (no
/// friction is declared, so nothing turns it and T = 1/2 m v^2): with G's rise h above the
/// floor, v^2 = v0^2 - 2 g h.
///   side (G level with the loop's center, h = rho):  v^2 = 49 - 2 (9.81) 0.9 = 31.342,
///     v = 5.598393 m/s;
///   top (h = 2 rho):  v^2 = 49 - 4 (9.81) 0.9 = 13.684, v = 3.699189 m/s.
/// It stays on the loop: at the top v^2 / rho = 15.2 m/s^2 > g, so N = m (v^2 / rho - g) > 0.
fn speeds() -> (f64, f64) {
    let rho = R - DISC_R;
    let side = (V0 * V0 - 2.0 * G * rho).sqrt();
    let top = (V0 * V0 - 4.0 * G * rho).sqrt();
    assert!(top * top / rho > G, "the disc would leave the loop");
    (side, top)
}

/// The loop-the-loop as a teacher builds it: the new scene's ground line swapped for a
/// one-sided polyline floor from x = -3 m to the loop's foot at the origin (solid below: on its
/// right looking along +x), a loop of radius 1 m on its inside from its bottom (-90 degrees)
/// round to its left side (180 degrees), a 0.2 kg disc of radius 0.1 m on the floor launched
/// at 7 m/s, and two questions.
fn loop_edits() -> Vec<Edit> {
    let (v_side, v_top) = speeds();
    // dt = 1/4800 s, as the library's loop: a body riding a faceted concave track fast loses
    // kinetic energy in proportion to dt (docs/known-gaps.md).
    let dt = 1.0 / 4800.0;
    let question = |id: &str, ask: &str, expected: f64, at: When| {
        Edit::AddQuestion(Box::new(QuestionDef {
            id: id.into(),
            ask: ask.into(),
            unit: "m/s".into(),
            expected,
            // 1%: the loop's facets take energy in proportion to dt (docs/known-gaps.md);
            // measured at this dt: v_side 0.20% low, v_top 0.63% low (v_top^2 is a quarter of
            // v0^2, so the energy lost shows four times larger in it).
            tolerance: 0.01,
            student_tolerance: 0.01,
            quantity: Quantity::Speed("disc1".into()),
            at,
            why: "the loop's facets take energy in proportion to dt (docs/known-gaps.md)".into(),
            mistakes: Vec::new(),
        }))
    };
    vec![
        Edit::AddTrack {
            points: vec![(-3.0, 0.0), (0.0, 0.0)],
            closed: false,
            solid: Some(TrackSide::Right),
        },
        // After the floor: a level without bodies is refused.
        Edit::Delete {
            body: "ground".into(),
        },
        Edit::AddArc {
            center: (0.0, R),
            radius: R,
            start: -FRAC_PI_2,
            end: PI,
            side: ArcSide::Inside,
        },
        Edit::AddBody {
            shape: NewShape::Disc { radius: DISC_R },
            at: (-2.0, DISC_R),
            mass: 0.2,
        },
        Edit::Set {
            body: "disc1".into(),
            property: Property::Velocity((V0, 0.0)),
        },
        Edit::SetStep { dt, substeps: 4 },
        // On the floor 2 m (0.29 s), round the loop to its left side (about 0.75 s more).
        Edit::SetDuration(1.2),
        Edit::SetText {
            title: "Loop the loop, built in the editor".into(),
            statement: "A smooth disc of 0.2 kg and radius 0.1 m slides along the floor at 7 m/s into a vertical loop of radius 1 m. Find its speed level with the loop's center and at the top (g = 9.81 m/s^2).".into(),
        },
        question(
            "v_side",
            "Speed with G level with the loop's center",
            v_side,
            When::Crossing {
                of: Quantity::Y("disc1".into()),
                value: R,
                after: 0.0,
            },
        ),
        question(
            "v_top",
            "Speed at the top of the loop",
            v_top,
            When::MaxOf {
                of: Quantity::Y("disc1".into()),
                after: 0.0,
            },
        ),
    ]
}

fn temp_dir(what: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-{what}-{}", std::process::id()));
    // Fresh: a save never replaces a file, so an old one would be the one checked.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `rigidlab check --json` on a saved level: it must pass, and each question's engine value is
/// returned (id, engine, expected).
fn check(path: &Path) -> Vec<(String, f64, f64)> {
    let out = Command::new(env!("CARGO_BIN_EXE_rigidlab"))
        .args(["check", "--json", "--no-advice", path.to_str().unwrap()])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "rigidlab check failed the saved loop:\n{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let questions = report["levels"][0]["questions"].as_array().unwrap();
    questions
        .iter()
        .map(|q| {
            (
                q["id"].as_str().unwrap().to_string(),
                q["engine"].as_f64().unwrap(),
                q["expected"].as_f64().unwrap(),
            )
        })
        .collect()
}

fn assert_speeds(read: &[(String, f64, f64)]) {
    let (v_side, v_top) = speeds();
    assert_eq!(read.len(), 2, "{read:?}");
    for (id, engine, expected) in read {
        let want = if id == "v_side" { v_side } else { v_top };
        assert!((expected - want).abs() < 1e-12, "{id}: {expected}");
        assert!(engine.is_finite() && *engine > 1.0, "{id}: {engine}");
        // The tolerance the questions carry (1%), checked here too so the figures show.
        let err = (engine - want).abs() / want;
        assert!(
            err < 0.01,
            "{id}: engine {engine} m/s, energy {want} m/s ({err:.2e})"
        );
        eprintln!("{id}: engine {engine:.6} m/s, energy {want:.6} m/s, {err:.2e}");
    }
}

#[test]
fn the_editor_builds_a_loop_the_loop_saves_it_and_check_passes_it() {
    let mut scene = editor::empty_scene(PathBuf::from("my-scene.ron"));
    let mut history = History::default();
    for e in loop_edits() {
        let (next, note) = history
            .apply(&scene, &e)
            .unwrap_or_else(|why| panic!("{e:?} refused: {why}"));
        eprintln!("{note}");
        scene = next;
    }
    let level = &scene.level;
    assert!(matches!(
        level
            .bodies
            .iter()
            .find(|b| b.name == "track1")
            .unwrap()
            .shape,
        Some(Shape::Polyline { .. })
    ));
    assert!(matches!(
        level
            .bodies
            .iter()
            .find(|b| b.name == "arc1")
            .unwrap()
            .shape,
        Some(Shape::Arc { .. })
    ));
    let dir = temp_dir("editor-loop");
    let path = dir.join("loop.ron");
    std::fs::write(&path, level::to_ron(level)).unwrap();
    // Saved as it is built: the file loads back to the same level.
    assert_eq!(level::load(&path).unwrap().level, *level);
    assert_speeds(&check(&path));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_disc_placed_on_a_track_is_set_onto_its_riding_side() {
    // The loop's floor and loop, without the disc.
    let mut scene = editor::empty_scene(PathBuf::from("my-scene.ron"));
    for e in loop_edits().into_iter().take(3) {
        scene = editor::apply(&scene, &e).unwrap().0;
    }
    let place = |at: (f64, f64)| {
        let e = Edit::AddBody {
            shape: NewShape::Disc { radius: DISC_R },
            at,
            mass: 0.2,
        };
        let (s, note) = editor::apply(&scene, &e).unwrap();
        let b = s.level.bodies.iter().find(|b| b.name == "disc1").unwrap();
        (b.position, note)
    };
    // The disc is set touching the facet nearest its center, along that facet's normal, which
    // is off the radius through the center by up to half a facet angle, a / 2 = 4.5e-4 rad
    // (a = 2 acos(1 - 1e-7), the default chord error): a move of at most r = 0.1 m along it
    // lands at most 0.1 (4.5e-4) = 4.5e-5 m from where the true circle would put it (and the
    // vertices' 1e-7 R outside the circle adds 1e-7 m).
    let near = |got: (f64, f64), want: (f64, f64)| {
        (got.0 - want.0).abs() < 5e-5 && (got.1 - want.1).abs() < 5e-5
    };
    // Clicked into the floor, from above and from below (its solid side): onto its top.
    for at in [(-2.0, 0.05), (-2.0, -0.05)] {
        let (p, note) = place(at);
        assert!(near(p, (-2.0, DISC_R)), "{at:?} went to {p:?}");
        assert!(note.contains("track1"), "{note}");
    }
    // Clicked into the loop's right side, from within and from without: inside the loop.
    for at in [(0.97, R), (1.05, R)] {
        let (p, note) = place(at);
        assert!(near(p, (R - DISC_R, R)), "{at:?} went to {p:?}");
        assert!(note.contains("arc1"), "{note}");
    }
    // Clear of every track: where it was clicked.
    assert_eq!(place((-1.0, 0.5)).0, (-1.0, 0.5));
}

/// A refused edit: an error that says why, and the scene and its history as they were.
fn refused(scene: &Scene, history: &mut History, e: Edit, says: &str) {
    let could_undo = history.can_undo();
    match history.apply(scene, &e) {
        Ok((_, note)) => panic!("{e:?} was applied: {note}"),
        Err(why) => assert!(why.contains(says), "{e:?}: {why:?} does not say {says:?}"),
    }
    assert_eq!(history.can_undo(), could_undo);
}

#[test]
fn bad_tracks_are_refused_with_why() {
    let scene = editor::empty_scene(PathBuf::from("my-scene.ron"));
    let mut h = History::default();
    let track = |points: Vec<(f64, f64)>, closed| Edit::AddTrack {
        points,
        closed,
        solid: None,
    };
    // A bow tie: its first and third edges cross.
    let bow = vec![(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)];
    refused(&scene, &mut h, track(bow, false), "crosses itself");
    refused(
        &scene,
        &mut h,
        track(vec![(0.0, 1.0)], false),
        "at least 2 points",
    );
    refused(
        &scene,
        &mut h,
        track(vec![(0.0, 1.0), (1.0, 1.0)], true),
        "at least 3 points",
    );
    refused(
        &scene,
        &mut h,
        track(vec![(0.0, 1.0), (0.0, 1.0), (1.0, 1.0)], false),
        "coincide",
    );
    let arc = |radius, start, end| Edit::AddArc {
        center: (0.0, 1.0),
        radius,
        start,
        end,
        side: ArcSide::Inside,
    };
    refused(&scene, &mut h, arc(0.0, 0.0, PI), "radius");
    refused(&scene, &mut h, arc(-1.0, 0.0, PI), "radius");
    refused(&scene, &mut h, arc(1.0, PI, PI), "sweep");
    refused(&scene, &mut h, arc(1.0, PI, 0.0), "sweep");
    refused(&scene, &mut h, arc(1.0, 0.0, 7.0), "sweep");
    refused(&scene, &mut h, arc(f64::NAN, 0.0, PI), "radius");

    // On a track placed, edits that would spoil it are refused the same way.
    let (scene, _) = h.apply(&scene, &arc(1.0, PI, 2.0 * PI)).unwrap();
    let set = |property| Edit::Set {
        body: "arc1".into(),
        property,
    };
    refused(&scene, &mut h, set(Property::ArcEnd(PI)), "sweep");
    refused(&scene, &mut h, set(Property::ArcStart(-PI)), "sweep");
    refused(&scene, &mut h, set(Property::Radius(0.0)), "radius");
    refused(
        &scene,
        &mut h,
        set(Property::Closed(true)),
        "not a polyline",
    );
    refused(
        &scene,
        &mut h,
        set(Property::Kind(level::BodyKind::Dynamic)),
        "fixed",
    );
    let (scene, _) = h
        .apply(&scene, &track(vec![(-2.0, 0.0), (2.0, 0.0)], false))
        .unwrap();
    let points = |p: Vec<(f64, f64)>| Edit::Set {
        body: "track1".into(),
        property: Property::Points(p),
    };
    refused(
        &scene,
        &mut h,
        points(vec![(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]),
        "crosses itself",
    );
    refused(&scene, &mut h, points(vec![]), "at least 2 points");

    // Typed points: read in any of the usual layouts, refused with the word or the count.
    let want = vec![(-3.0, 0.0), (0.0, 0.5)];
    for text in [
        "-3, 0\n0, 0.5",
        "-3,0; 0,0.5",
        "(-3, 0), (0, 0.5)",
        " -3 0 0 0.5 ",
    ] {
        assert_eq!(parse_points(text).unwrap(), want, "{text:?}");
    }
    let e = parse_points("1, 2\n3").unwrap_err();
    assert!(e.contains("no y"), "{e}");
    let e = parse_points("1, 2\n3, x").unwrap_err();
    assert!(e.contains("`x`") && e.contains("point 1"), "{e}");
    assert!(parse_points("1, inf").is_err());
}

#[test]
fn track_edits_undo_redo_and_round_trip() {
    let start = editor::empty_scene(PathBuf::from("my-scene.ron"));
    let mut h = History::default();
    let mut scene = start.clone();
    let edits = [
        Edit::AddArc {
            center: (1.0, 2.0),
            radius: 0.5,
            start: PI,
            end: 2.0 * PI,
            side: ArcSide::Inside,
        },
        Edit::Set {
            body: "arc1".into(),
            property: Property::Radius(0.75),
        },
        Edit::Set {
            body: "arc1".into(),
            property: Property::Side(ArcSide::Outside),
        },
        Edit::Set {
            body: "arc1".into(),
            property: Property::ArcCenter((0.0, 0.25)),
        },
        Edit::Set {
            body: "arc1".into(),
            property: Property::ArcStart(0.0),
        },
        Edit::AddTrack {
            points: vec![(-1.0, 1.0), (0.0, 0.5), (1.0, 1.0)],
            closed: false,
            solid: None,
        },
        Edit::Set {
            body: "track1".into(),
            property: Property::Points(vec![(-1.0, 1.0), (0.0, 0.25), (1.0, 1.0)]),
        },
        Edit::Set {
            body: "track1".into(),
            property: Property::Closed(true),
        },
        Edit::Set {
            body: "track1".into(),
            property: Property::Solid(Some(TrackSide::Left)),
        },
    ];
    let mut levels = vec![scene.level.clone()];
    for e in &edits {
        scene = h.apply(&scene, e).unwrap().0;
        levels.push(scene.level.clone());
    }
    let arc = scene
        .level
        .bodies
        .iter()
        .find(|b| b.name == "arc1")
        .unwrap();
    assert_eq!(arc.position, (1.0, 2.0));
    assert_eq!(
        arc.shape,
        Some(Shape::Arc {
            center: (0.0, 0.25),
            radius: 0.75,
            start: 0.0,
            end: 2.0 * PI,
            side: ArcSide::Outside,
            chord_error: None,
        })
    );
    let track = scene
        .level
        .bodies
        .iter()
        .find(|b| b.name == "track1")
        .unwrap();
    assert_eq!(
        track.shape,
        Some(Shape::Polyline {
            points: vec![(-1.0, 1.0), (0.0, 0.25), (1.0, 1.0)],
            closed: true,
            solid: Some(TrackSide::Left),
        })
    );
    // Saved and read back as `rigidlab check` reads it: the same level.
    let back = level::parse(Path::new("tracks.ron"), &level::to_ron(&scene.level)).unwrap();
    assert_eq!(back.level, scene.level);

    // Every edit above is its own step (no two change one property of one body in a row):
    // undo walks back through each level, redo forward again.
    for want in levels.iter().rev().skip(1) {
        scene = h.undo(&scene).expect("an edit to undo");
        assert_eq!(&scene.level, want);
    }
    assert!(!h.can_undo());
    assert_eq!(scene.level, start.level);
    for want in levels.iter().skip(1) {
        scene = h.redo(&scene).expect("an edit to redo");
        assert_eq!(&scene.level, want);
    }
}

/// The same loop built in the window's editor, headless, and saved by its Save command.
#[cfg(feature = "app")]
#[test]
fn the_window_builds_and_saves_the_loop() {
    use bevy::prelude::*;
    use common::app::{editor_app, send};
    use rigidlab::app::editor::{EditorCommand, Placeable};
    use rigidlab::app::tools::track_edit;
    use rigidlab::app::Run;

    let mut app = editor_app();
    // The place tool's arc: a half-circle bowl whose bottom is the click, sized for the scene
    // (a quarter of a 4 m scene, rounded: 1 m), then undone.
    let bowl = Placeable::Arc.edit_at(glam::DVec2::new(0.5, 1.0), 4.0);
    assert_eq!(
        bowl,
        Edit::AddArc {
            center: (0.5, 2.0),
            radius: 1.0,
            start: PI,
            end: 2.0 * PI,
            side: ArcSide::Inside,
        }
    );
    // The track tool's clicks: bodies ride the upper side whichever way they were clicked.
    let clicks = [glam::DVec2::new(-1.0, 1.0), glam::DVec2::new(1.0, 0.0)];
    let solid = |e: Edit| match e {
        Edit::AddTrack { solid, .. } => solid,
        e => panic!("{e:?}"),
    };
    assert_eq!(solid(track_edit(&clicks)), Some(TrackSide::Right));
    let back: Vec<_> = clicks.iter().rev().copied().collect();
    assert_eq!(solid(track_edit(&back)), Some(TrackSide::Left));
    let (note, ok) = send(&mut app, EditorCommand::Apply(bowl));
    assert!(ok && note.contains("arc1"), "{note}");
    send(&mut app, EditorCommand::Undo);
    // A refusal is a note, not a panic, and changes nothing.
    let before = app.world().resource::<Run>().scene.level.clone();
    let (why, ok) = send(
        &mut app,
        EditorCommand::Apply(Edit::AddTrack {
            points: vec![(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)],
            closed: false,
            solid: None,
        }),
    );
    assert!(!ok && why.contains("crosses itself"), "{why}");
    assert_eq!(app.world().resource::<Run>().scene.level, before);

    for e in loop_edits() {
        let (note, ok) = send(&mut app, EditorCommand::Apply(e));
        assert!(ok, "{note}");
    }
    let dir = temp_dir("window-loop");
    let path = dir.join("saved-levels/loop.ron");
    let (note, ok) = send(&mut app, EditorCommand::Save(path.clone()));
    assert!(ok, "{note}");
    let saved = level::load(&path).unwrap();
    assert_eq!(saved.level, app.world().resource::<Run>().scene.level);
    assert_speeds(&check(&path));
    let _ = std::fs::remove_dir_all(&dir);
}
