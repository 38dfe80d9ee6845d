//! Parameterized levels (issue 43, src/level/params): expressions in numeric fields, their
//! located errors, the corners of the ranges, the statement's placeholders, and the variants a
//! student id picks (a published vector another implementation can check).

use rigidlab::level::params::{seed, textbook, Parameterized, Pick};
use rigidlab::level::{self, Shape};
use std::path::Path;

/// A falling ball whose numbers are expressions of its parameters: `fields` is spliced into
/// the ball, `params` into the parameters' list.
fn level_text(params: &str, fields: &str, expected: &str) -> String {
    format!(
        r#"Level(
  title: "t",
  statement: "A {{m}} ball falls from {{h}} (g = {{g}}).",
  parameters: [{params}],
  effects: [gravity],
  world: (duration: 1.0),
  bodies: [
    (name: "ball", shape: Circle(radius: 0.1), {fields}),
  ],
  questions: [
    (id: "v", ask: "Speed of the {{m}} ball", unit: "m/s", expected: {expected}, tolerance: 1e-3,
     quantity: Speed("ball"), at: Time(1.0)),
  ],
)"#
    )
}

const PARAMS: &str = r#"(name: "m", range: (1.0, 3.0), step: 0.5, unit: "kg"), (name: "h", list: [10.0, 20.0], unit: "m"), (name: "theta", range: (30.0, 60.0), step: 15.0, unit: "deg")"#;

fn parse(text: &str) -> Result<level::Scene, level::LevelError> {
    level::parse(Path::new("p.ron"), text)
}

#[test]
fn expressions_take_the_nominal_values_in_si() {
    let text = level_text(
        PARAMS,
        "mass: 2*m, position: (h/2, sqrt(2*g*h)), angle: theta",
        "g*1.0",
    );
    let b = &parse(&text).unwrap().level.bodies[0];
    // Nominal: the grid point at or below the middle: m = 2 (index 2 of 1, 1.5, 2, 2.5, 3),
    // theta = 45 deg (index 1 of 30, 45, 60), the list's first h = 10.
    assert_eq!(b.mass, Some(4.0));
    assert_eq!(b.position.0, 5.0);
    assert!((b.position.1 - (2.0 * 9.81 * 10.0f64).sqrt()).abs() < 1e-12);
    // A deg parameter enters expressions in radians.
    assert!((b.angle - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    assert!(matches!(b.shape, Some(Shape::Circle { radius }) if radius == 0.1));
}

#[test]
fn placeholders_print_values_and_units_as_a_textbook_does() {
    let text = level_text(PARAMS, "mass: m", "g");
    let l = parse(&text).unwrap().level;
    assert_eq!(l.statement, "A 2 kg ball falls from 10 m (g = 9.81 m/s^2).");
    assert_eq!(l.questions[0].ask, "Speed of the 2 kg ball");
    assert_eq!(l.questions[0].expected, 9.81);
    // 3 significant figures, or the step's decimals when finer; no trailing zeros.
    assert_eq!(textbook(0.30000000000000004, 2), "0.3");
    assert_eq!(textbook(1.0 / 3.0, 0), "0.333");
    assert_eq!(textbook(0.125, 3), "0.125");
    assert_eq!(textbook(12345.0, 0), "12300");
    assert_eq!(textbook(2.5, 1), "2.5");
    assert_eq!(textbook(30.0, 0), "30");
}

/// The error of `text`, which must fail to load.
fn error(text: &str) -> level::LevelError {
    parse(text).expect_err("the level must be refused")
}

/// Line and column of the first `needle` in `text` (1-based).
fn pos(text: &str, needle: &str) -> (usize, usize) {
    let at = text.find(needle).unwrap();
    let line = text[..at].matches('\n').count() + 1;
    let col = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, col)
}

#[test]
fn an_unknown_name_is_located_at_it() {
    let text = level_text(PARAMS, "mass: 2*mm", "g");
    let e = error(&text);
    assert!(e.message.contains("unknown name `mm`"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "mm)"), "{e}");
}

#[test]
fn an_expression_that_does_not_read_is_located_at_it() {
    let text = level_text(PARAMS, "mass: m*/2", "g");
    let e = error(&text);
    assert!(e.message.contains("cannot evaluate `m*/2`"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "m*/2"), "{e}");
}

#[test]
fn a_division_by_zero_at_a_corner_names_the_values() {
    // Nominal m = 2 is fine; the corner m = 1 divides by zero.
    let text = level_text(PARAMS, "mass: 1/(m - 1)", "g");
    let e = error(&text);
    assert!(e.message.contains("inf"), "{e}");
    assert!(e.message.contains("m = 1 kg"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "1/(m - 1)"), "{e}");
}

#[test]
fn a_range_that_makes_a_field_invalid_at_a_corner_is_located_at_the_field() {
    // m - 1.5 is 0.5 kg at the nominal m = 2 but -0.5 kg at the corner m = 1.
    let text = level_text(PARAMS, "mass: m - 1.5", "g");
    let e = error(&text);
    assert!(
        e.message.contains("m = 1 kg, h = 10 m, theta = 30 deg"),
        "{e}"
    );
    assert_eq!(e.line, pos(&text, "mass: m - 1.5").0, "{e}");
}

#[test]
fn bad_declarations_are_refused_where_they_are_written() {
    for (params, says) in [
        (r#"(name: "m", range: (1.0, 3.0), unit: "kg")"#, "no step"),
        (r#"(name: "m", range: (3.0, 1.0), step: 0.5)"#, "min <= max"),
        (
            r#"(name: "m", range: (1.0, 3.0), step: 0.5, nominal: 1.2)"#,
            "not one of its values",
        ),
        (r#"(name: "g", list: [1.0])"#, "is taken"),
        (
            r#"(name: "m", list: [1.0], unit: "furlong")"#,
            "unknown unit",
        ),
        (
            r#"(name: "m", list: [1.0]), (name: "m", list: [2.0])"#,
            "declared twice",
        ),
    ] {
        let text = level_text(params, "mass: 1.0", "g")
            .replace("{m}", "1 kg")
            .replace("{h}", "1 m");
        let e = error(&text);
        assert!(e.to_string().contains(says), "{params}: {e}");
        assert_eq!(e.line, 4, "{params}: the parameters' line: {e}");
    }
}

#[test]
fn a_placeholder_naming_no_parameter_is_an_error() {
    let text = level_text(PARAMS, "mass: m", "g").replace("{h}", "{height}");
    let e = error(&text);
    assert!(e.message.contains("{height}"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "{height}"), "{e}");
}

#[test]
fn the_library_levels_without_parameters_have_none() {
    // Their text is parsed exactly as before: no `parameters:` section, no expansion.
    let mut files = crate::common::ron_files("levels", &[]);
    files.extend(crate::common::ron_files("tests/newuser", &[]));
    let mut with = 0;
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let p = Parameterized::read(&f, &text).unwrap_or_else(|e| panic!("{e}"));
        // A challenge's control is a parameter (levels/challenges/, issue 42).
        let named = f
            .file_name()
            .unwrap()
            .to_string_lossy()
            .ends_with("_param.ron")
            || f.parent().is_some_and(|d| d.ends_with("challenges"));
        assert_eq!(p.is_some(), named, "{}", f.display());
        with += usize::from(named);
    }
    assert!(with >= 5, "the library's parameterized exercises: {with}");
}

fn incline() -> (Parameterized, std::path::PathBuf) {
    let f = crate::common::repo_path("levels/kinetics/incline_friction_param.ron");
    let text = std::fs::read_to_string(&f).unwrap();
    (Parameterized::read(&f, &text).unwrap().unwrap(), f)
}

fn values(p: &Parameterized, id: &str) -> Vec<f64> {
    let idx = p.indices(&Pick::Student(id.into()));
    p.variant(&idx).values.iter().map(|v| v.1).collect()
}

#[test]
fn the_published_vectors_hold() {
    // FNV-1a 64 and SplitMix64 against their published vectors (FNV: "a" and "foobar" from
    // the reference test suite; SplitMix64 seeded with 1234567, its reference's first outputs).
    assert_eq!(seed::fnv1a64(b""), 0xcbf29ce484222325);
    assert_eq!(seed::fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
    assert_eq!(seed::fnv1a64(b"foobar"), 0x85944171f73967e8);
    let mut r = seed::SplitMix64(1234567);
    assert_eq!(
        [r.next_u64(), r.next_u64(), r.next_u64()],
        [
            6457827717110365317,
            3203168211198807973,
            9817491932198370423
        ]
    );
    // The level's vector (docs/levels.md), computed by an independent Python script of the
    // documented steps: FNV-1a of "incline_friction_param.ron|s1234567" = 0xd2867c51fe7bd56a,
    // indices [1 of 9, 2 of 4, 0 of 5].
    let (p, _) = incline();
    assert_eq!(
        seed::fnv1a64(b"incline_friction_param.ron|s1234567"),
        0xd2867c51fe7bd56a
    );
    assert_eq!(values(&p, "s1234567"), [1.5, 35.0, 0.1]);
    assert_eq!(values(&p, "alice"), [3.0, 40.0, 0.1 + 4.0 * 0.05]);
    assert_eq!(values(&p, "bob"), [3.5, 25.0, 0.1 + 1.0 * 0.05]);
}

#[test]
fn the_same_id_gives_the_same_numbers_and_ids_spread_over_the_grid() {
    let (p, f) = incline();
    assert_eq!(values(&p, "s1"), values(&p, "s1"));
    assert_eq!(
        values(&p, " s1 "),
        values(&p, "s1"),
        "spaces at the ends do not count"
    );
    let all: Vec<Vec<f64>> = (0..300).map(|i| values(&p, &format!("s{i}"))).collect();
    let distinct: std::collections::HashSet<String> =
        all.iter().map(|v| format!("{v:?}")).collect();
    // 180 combinations (9 x 4 x 5): 300 ids hit far more than half of them.
    assert!(distinct.len() > 120, "{} distinct variants", distinct.len());
    for v in &all {
        let k = (v[0] - 1.0) / 0.5;
        assert!(
            (1.0..=5.0).contains(&v[0]) && (k - k.round()).abs() < 1e-9,
            "{v:?}"
        );
        assert!([25.0, 30.0, 35.0, 40.0].contains(&v[1]), "{v:?}");
        let k = (v[2] - 0.1) / 0.05;
        assert!((0.1 - 1e-12..=0.3 + 1e-12).contains(&v[2]) && (k - k.round()).abs() < 1e-9);
    }
    // A student's level carries their numbers, in its fields and its statement.
    let l = level::load_variant(&f, &Pick::Student("s1234567".into())).unwrap();
    let block = &l.scene.level.bodies[1];
    assert_eq!(block.mass, Some(1.5));
    assert!((block.angle - 35f64.to_radians()).abs() < 1e-15);
    assert!(l.scene.level.statement.starts_with("A 1.5 kg block is released from rest on a 35 deg incline; the coefficient of friction is 0.1 "));
    let q = &l.scene.level.questions[0];
    let a = 9.81 * (35f64.to_radians().sin() - 0.1 * 35f64.to_radians().cos());
    assert!((q.expected - a).abs() < 1e-12);
}

#[test]
fn a_range_that_puts_a_body_inside_another_at_a_corner_is_refused() {
    // A ball resting on a floor whose top is at y = 0; its height above the floor is
    // h - 0.1 m: 0.1 m (touching) at the nominal h = 0.2, inside the 0.2 m thick floor at the
    // corner h = 0, whose center is then 0.1 m below its top face.
    let text = r#"Level(
  title: "ball on a floor",
  parameters: [(name: "h", range: (0.0, 0.4), step: 0.1, unit: "m", nominal: 0.2)],
  effects: [gravity, contacts],
  bodies: [
    (name: "floor", kind: fixed, shape: Box(width: 4.0, height: 0.2), position: (0.0, -0.1)),
    (name: "ball", shape: Circle(radius: 0.1), mass: 1.0, position: (0.0, h - 0.1)),
  ],
)"#;
    let e = error(text);
    assert!(
        e.message
            .contains("`ball` starts with its center inside `floor`"),
        "{e}"
    );
    assert!(e.message.contains("h = 0 m"), "{e}");
    assert_eq!(e.line, pos(text, "position: (0.0, h").0, "{e}");
    // The same ball over a range that keeps it above the floor loads.
    parse(&text.replace("range: (0.0, 0.4)", "range: (0.2, 0.4)")).unwrap();
}
