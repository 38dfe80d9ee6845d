//! `rigidlab grade` (issue 43): a synthetic class of 30 students on two parameterized library
//! levels, each student's answers computed here from the closed forms with THEIR variant's
//! numbers (the variant taken from the library's seeded pick, never from an engine run): right
//! answers, answers with units, a typical mistake, answers of another student's variant, bad
//! rows; and outputs that are never written over.

use crate::common;

use common::rigidlab;
use rigidlab::level::params::{Parameterized, Pick};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const G: f64 = 9.81;
const INCLINE: &str = "incline_friction_param";
const ATWOOD: &str = "classic_atwood_massive_pulley_param";

/// The two levels copied into a fresh folder (the assignment), under their library names: a
/// variant depends on the file's name, not its folder.
fn assignment(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-grade-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("levels")).unwrap();
    for (folder, name) in [("kinetics", INCLINE), ("kinetics", ATWOOD)] {
        std::fs::copy(
            common::repo_path(format!("levels/{folder}/{name}.ron")),
            dir.join("levels").join(format!("{name}.ron")),
        )
        .unwrap();
    }
    dir
}

/// A student's parameter values (in SI: degrees to radians) from the library's seeded pick.
fn values(level: &str, student: &str) -> HashMap<String, f64> {
    let f = common::repo_path(format!("levels/kinetics/{level}.ron"));
    let text = std::fs::read_to_string(&f).unwrap();
    let p = Parameterized::read(&f, &text).unwrap().unwrap();
    let idx = p.indices(&Pick::Student(student.into()));
    p.variant(&idx)
        .values
        .into_iter()
        .map(|(n, v, unit)| (n, if unit == "deg" { v.to_radians() } else { v }))
        .collect()
}

/// The closed forms (derived in the levels' comments): the incline's block from rest,
/// a = g (sin theta - mu cos theta), v(1 s) = a, s(1 s) = a / 2; the Atwood machine,
/// a = (m_A - m_B) g / (m_A + m_B + M/2), a_A = -a, alpha = -a/R, T_A = m_A (g - a),
/// T_B = m_B (g + a), v(1 s) = a, R_axle = M g + T_A + T_B.
fn answers(level: &str, v: &HashMap<String, f64>) -> Vec<(&'static str, f64)> {
    if level == INCLINE {
        let a = G * (v["theta"].sin() - v["mu"] * v["theta"].cos());
        return vec![("speed", a), ("distance", a / 2.0)];
    }
    let (ma, mb, m, r) = (v["m_A"], v["m_B"], v["M"], v["R"]);
    let a = (ma - mb) * G / (ma + mb + m / 2.0);
    let (ta, tb) = (ma * (G - a), mb * (G + a));
    vec![
        ("a_A", -a),
        ("alpha", -a / r),
        ("T_A", ta),
        ("T_B", tb),
        ("v_1s", a),
        ("R_axle", m * G + ta + tb),
    ]
}

/// The Atwood level's typical mistake on a_A: the pulley's inertia forgotten.
fn atwood_mistake(v: &HashMap<String, f64>) -> f64 {
    -(v["m_A"] - v["m_B"]) * G / (v["m_A"] + v["m_B"])
}

/// The rule of check --answer with the levels' student tolerance (1 %, the default: neither
/// level sets one): correct within 1 % of the expected value.
fn rel(x: f64, expected: f64) -> f64 {
    (x - expected).abs() / expected.abs()
}

/// An answer typed with a unit: the value converted by hand with the unit's exact size.
fn with_unit(q: &str, x: f64) -> String {
    match q {
        "speed" | "v_1s" => format!("{} km/h", x * 3.6),
        "distance" => format!("{} cm", x * 100.0),
        "a_A" => format!("{} ft/s^2", x / 0.3048),
        "T_A" | "T_B" | "R_axle" => format!("{}kN", x / 1000.0),
        "alpha" => format!("{} deg/s^2", x.to_degrees()),
        _ => unreachable!(),
    }
}

/// One synthetic class: the CSV text and, for each graded line, the verdict expected.
struct Class {
    csv: String,
    expected: HashMap<u64, String>,
    /// Lines expected to be reported bad, with the column at fault.
    bad: Vec<(u64, Option<usize>)>,
    another_wrong: usize,
}

const MISTAKE: &str = "mistake:that is (m_A - m_B) g / (m_A + m_B)";

fn class() -> Class {
    let mut c = Class {
        csv: "student,level,question,answer\n".into(),
        expected: HashMap::new(),
        bad: Vec::new(),
        another_wrong: 0,
    };
    // The line a row lands on: the lines written so far (the header is line 1).
    let row = |c: &mut Class, s: &str, l: &str, q: &str, a: &str, verdict: Option<&str>| {
        writeln!(c.csv, "{s},{l},{q},\"{a}\"").unwrap();
        let line = c.csv.lines().count() as u64;
        if let Some(v) = verdict {
            c.expected.insert(line, v.to_string());
        }
        line
    };
    let id = |i: usize| format!("s{:07}", 2_400_000 + i * 37);
    for i in 0..30 {
        let student = id(i);
        for level in [INCLINE, ATWOOD] {
            let mine = values(level, &student);
            let right = answers(level, &mine);
            match i % 5 {
                // Right answers, plain numbers in the question's unit.
                0 => {
                    for (q, x) in &right {
                        row(&mut c, &student, level, q, &format!("{x}"), Some("correct"));
                    }
                }
                // Right answers with units (a speed in km/h, a force in kN, ...).
                1 => {
                    for (q, x) in &right {
                        row(
                            &mut c,
                            &student,
                            level,
                            q,
                            &with_unit(q, *x),
                            Some("correct"),
                        );
                    }
                }
                // Right to three significant figures (at most 0.5 % off).
                2 => {
                    for (q, x) in &right {
                        row(
                            &mut c,
                            &student,
                            level,
                            q,
                            &format!("{x:.2e}"),
                            Some("correct"),
                        );
                    }
                }
                // The typical mistake on a_A; on the incline, friction forgotten (a wrong
                // answer no mistake lists: tan theta >= 0.466 > mu, so it is > 1 % off).
                3 => {
                    if level == ATWOOD {
                        let x = atwood_mistake(&mine);
                        row(
                            &mut c,
                            &student,
                            level,
                            "a_A",
                            &format!("{x}"),
                            Some(MISTAKE),
                        );
                    } else {
                        let x = G * mine["theta"].sin();
                        row(
                            &mut c,
                            &student,
                            level,
                            "speed",
                            &format!("{x}"),
                            Some("wrong"),
                        );
                    }
                }
                // Another student's variant's answers: wrong where the numbers differ by
                // more than the 1 % tolerance, right where they happen to agree.
                _ => {
                    let other = answers(level, &values(level, &id((i + 7) % 30)));
                    for ((q, x), (_, theirs)) in right.iter().zip(&other) {
                        let v = if rel(*theirs, *x) <= 1e-2 {
                            "correct"
                        } else {
                            "wrong"
                        };
                        c.another_wrong += usize::from(v == "wrong");
                        row(&mut c, &student, level, q, &format!("{theirs}"), Some(v));
                    }
                }
            }
        }
    }
    // Bad rows, each reported at its line and column; the rows around them are graded.
    let s0 = id(0);
    let l = row(&mut c, &s0, "no_such_level", "speed", "1.0", None);
    c.bad.push((l, Some(2)));
    let l = row(&mut c, &s0, INCLINE, "no_such_question", "1.0", None);
    c.bad.push((l, Some(3)));
    let l = row(
        &mut c,
        &id(3),
        INCLINE,
        "distance",
        "about two",
        Some("unreadable"),
    );
    c.bad.push((l, Some(4)));
    let l = row(&mut c, &id(3), ATWOOD, "T_A", "30 m/s", Some("unreadable"));
    c.bad.push((l, Some(4)));
    // s0 answered speed already (right, above): the repeat is reported, not graded.
    let l = row(&mut c, &s0, INCLINE, "speed", "0.0", None);
    c.bad.push((l, Some(3)));
    writeln!(c.csv, "{},{INCLINE}", id(4)).unwrap();
    c.bad.push((c.csv.lines().count() as u64, Some(3)));
    let x = answers(ATWOOD, &values(ATWOOD, &id(8)))[1].1;
    row(
        &mut c,
        &id(8),
        ATWOOD,
        "alpha",
        &format!("{x}"),
        Some("correct"),
    );
    c
}

fn grade(dir: &Path, out: &str) -> (i32, String, String) {
    let o = rigidlab()
        .args(["grade"])
        .arg(dir.join("levels"))
        .arg(dir.join("answers.csv"))
        .arg("--out")
        .arg(dir.join(out))
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

#[test]
fn a_class_of_30_is_graded_against_each_students_own_variant() {
    let dir = assignment("class");
    let c = class();
    std::fs::write(dir.join("answers.csv"), &c.csv).unwrap();
    let (code, stdout, stderr) = grade(&dir, "grades.csv");
    // Bad rows: exit 1, each reported at its line and column, the rest graded.
    assert_eq!(code, 1, "{stdout}\n{stderr}");
    for (line, col) in &c.bad {
        let at = match col {
            Some(col) => format!("answers.csv:{line}:{col}: error:"),
            None => format!("answers.csv:{line}: error:"),
        };
        assert!(stderr.contains(&at), "{at} not in\n{stderr}");
    }
    assert_eq!(stderr.matches(": error:").count(), c.bad.len(), "{stderr}");
    let mut r = csv::Reader::from_path(dir.join("grades.csv")).unwrap();
    let header = r.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let mut got = HashMap::new();
    for rec in r.records() {
        let rec = rec.unwrap();
        let line: u64 = rec[col("line")].parse().unwrap();
        got.insert(line, rec[col("verdict")].to_string());
    }
    assert_eq!(got.len(), c.expected.len());
    for (line, want) in &c.expected {
        let verdict = &got[line];
        assert!(
            verdict.starts_with(want.as_str()),
            "line {line}: {verdict}, expected {want}"
        );
    }
    // Another student's numbers were wrong for most answers (the variants differ).
    assert!(c.another_wrong >= 10, "{}", c.another_wrong);
    // The summary counts the mistake: 6 students (i % 5 == 3) gave it.
    assert!(
        stdout.contains("6 x typical mistake: that is (m_A - m_B) g / (m_A + m_B)"),
        "{stdout}"
    );
    // The gradebook: Canvas's identifier columns, a column per level and the total; a
    // student of the first group has every question right (2 + 6).
    let book = std::fs::read_to_string(dir.join("grades_gradebook.csv")).unwrap();
    let mut lines = book.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("Student,ID,SIS User ID,SIS Login ID,Section,{ATWOOD},{INCLINE},rigidlab total")
    );
    // The points possible: the questions of each level (6 and 2), 8 in all.
    assert_eq!(lines.next().unwrap(), "Points Possible,,,,,6,2,8");
    assert!(book.contains("s2400000,,s2400000,,,6,2,8"), "{book}");
    assert_eq!(lines.count(), 30);
}

#[test]
fn grade_never_writes_over_a_file() {
    let dir = assignment("over");
    std::fs::write(
        dir.join("answers.csv"),
        format!("student,level,question,answer\nalice,{INCLINE},speed,1.0\n"),
    )
    .unwrap();
    std::fs::write(dir.join("grades.csv"), "my notes\n").unwrap();
    let (code, _, stderr) = grade(&dir, "grades.csv");
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("never writes over a file"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(dir.join("grades.csv")).unwrap(),
        "my notes\n"
    );
    assert!(!dir.join("grades_gradebook.csv").exists());
    // A name that is free is written; run again, the file rigidlab wrote is refused too.
    assert_eq!(grade(&dir, "new.csv").0, 0);
    let first = std::fs::read(dir.join("new.csv")).unwrap();
    assert_eq!(grade(&dir, "new.csv").0, 2);
    assert_eq!(std::fs::read(dir.join("new.csv")).unwrap(), first);
}

#[test]
fn an_assignment_manifest_orders_the_gradebook() {
    let dir = assignment("manifest");
    // The manifest lists the incline first (a folder alone would sort the Atwood machine first).
    std::fs::write(
        dir.join("levels/assignment.ron"),
        format!("Assignment(title: \"Week 3\", levels: [\"{INCLINE}.ron\", \"{ATWOOD}.ron\"])"),
    )
    .unwrap();
    let v = values(INCLINE, "bob");
    let right = answers(INCLINE, &v)[0].1;
    std::fs::write(
        dir.join("answers.csv"),
        format!("student,level,question,answer\nbob,{INCLINE}.ron,speed,{right}\n"),
    )
    .unwrap();
    let (code, stdout, stderr) = grade(&dir, "grades.csv");
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    let book = std::fs::read_to_string(dir.join("grades_gradebook.csv")).unwrap();
    assert_eq!(
        book,
        format!("Student,ID,SIS User ID,SIS Login ID,Section,{INCLINE},{ATWOOD},rigidlab total\nPoints Possible,,,,,2,6,8\nbob,,bob,,,1,0,1\n")
    );
}
