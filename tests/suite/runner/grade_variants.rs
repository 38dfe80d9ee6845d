//! `rigidlab grade` when a level's typical mistake equals its answer at some variant in its
//! ranges, and the gradebook's points-possible row.
//!
//! The level: the library's incline (a = g (sin theta - mu cos theta)) with theta from the list
//! 25, 35, 45, 55 deg and the typical mistake "sine and cosine swapped", g (cos theta -
//! mu sin theta). The two are equal where (sin theta - cos theta)(1 + mu) = 0: at 45 deg, for
//! every mu; at 35 and 55 deg they differ by 50% or more. At 45 deg the mistake could never be
//! told apart from the right answer, and a student whose seeded pick landed there had no
//! gradable variant: each of their rows was "student X's variant cannot be made". The pick now
//! draws again from the same generator (docs/teacher.md, `level::params::seed`); the test redoes
//! the published algorithm here, independently of the library's code.

use crate::common;

use common::rigidlab;
use std::path::{Path, PathBuf};

const G: f64 = 9.81;
const NAME: &str = "swapped_param";
const THETA_DEG: [f64; 4] = [25.0, 35.0, 45.0, 55.0];
/// The grid sizes: m 1.0..5.0 step 0.5 (9), theta the list (4), mu 0.1..0.3 step 0.05 (5).
const COUNTS: [u64; 3] = [9, 4, 5];

/// The library's incline with the list of angles and the mistake.
fn level_text() -> String {
    let text = std::fs::read_to_string(common::repo_path(
        "levels/kinetics/incline_friction_param.ron",
    ))
    .unwrap();
    let list = r#"list: [25.0, 30.0, 35.0, 40.0], unit: "deg", nominal: 30.0"#;
    let at = r#"quantity: Speed("block"), at: Time(1.0),"#;
    assert!(text.contains(list) && text.contains(at));
    text.replacen(list, r#"list: [25.0, 35.0, 45.0, 55.0], unit: "deg", nominal: 35.0"#, 1)
        .replacen(
            at,
            &format!(
                r#"{at} mistakes: [(value: g*(cos(theta) - mu*sin(theta))*1.0, message: "sine and cosine swapped")],"#
            ),
            1,
        )
}

fn folder(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-gradevar-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("levels")).unwrap();
    std::fs::write(dir.join("levels").join(format!("{NAME}.ron")), level_text()).unwrap();
    dir
}

/// FNV-1a 64 of `FILE|ID`, then SplitMix64, one call per parameter per draw (seed.rs's doc).
fn draws(id: &str) -> impl Iterator<Item = [u64; 3]> {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in format!("{NAME}.ron|{id}").bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
    }
    let mut state = h;
    let mut next = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    std::iter::repeat_with(move || [next() % COUNTS[0], next() % COUNTS[1], next() % COUNTS[2]])
}

/// The speed after 1 s for a draw: a = g (sin theta - mu cos theta), v = a (1 s).
fn speed(d: [u64; 3]) -> f64 {
    let theta = THETA_DEG[d[1] as usize].to_radians();
    let mu = 0.1 + 0.05 * d[2] as f64;
    G * (theta.sin() - mu * theta.cos())
}

fn grade(dir: &Path) -> (i32, String, String) {
    let o = rigidlab()
        .arg("grade")
        .arg(dir.join("levels"))
        .arg(dir.join("answers.csv"))
        .arg("--out")
        .arg(dir.join("grades.csv"))
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

#[test]
fn a_student_whose_draw_makes_a_mistake_the_answer_is_still_graded() {
    let ids: Vec<String> = (0..200).map(|i| format!("s{i:03}")).collect();
    // A student whose first draw is theta = 45 deg, and one whose is not.
    let unlucky = ids
        .iter()
        .find(|id| draws(id).next().unwrap()[1] == 2)
        .unwrap();
    let lucky = ids
        .iter()
        .find(|id| draws(id).next().unwrap()[1] != 2)
        .unwrap();
    // The variant each is graded on: the first draw off 45 deg.
    let theirs = |id: &str| draws(id).take(16).find(|d| d[1] != 2).unwrap();
    assert_ne!(theirs(unlucky), draws(unlucky).next().unwrap());
    assert_eq!(
        theirs(lucky),
        draws(lucky).next().unwrap(),
        "others keep their numbers"
    );
    let dir = folder("redraw");
    std::fs::write(
        dir.join("answers.csv"),
        format!(
            "student,level,question,answer\n{unlucky},{NAME},speed,{}\n{lucky},{NAME},speed,{}\n",
            speed(theirs(unlucky)),
            speed(theirs(lucky))
        ),
    )
    .unwrap();
    let (code, stdout, stderr) = grade(&dir);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    let mut r = csv::Reader::from_path(dir.join("grades.csv")).unwrap();
    let header = r.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 2);
    for rec in &rows {
        assert_eq!(&rec[col("verdict")], "correct", "{rec:?}");
        assert!(!rec[col("variant")].contains("theta = 45"), "{rec:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The gradebook's second row gives each level's points possible (its question count) and the
/// total's, in the `Student` column "Points Possible" as a Canvas export writes it (Canvas's
/// import reads that row for new assignments' points).
#[test]
fn the_gradebook_has_a_points_possible_row() {
    let dir = folder("points");
    let v = speed(draws("ann").take(16).find(|d| d[1] != 2).unwrap());
    std::fs::write(
        dir.join("answers.csv"),
        format!("student,level,question,answer\nann,{NAME},speed,{v}\n"),
    )
    .unwrap();
    let (code, stdout, stderr) = grade(&dir);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    let book = std::fs::read_to_string(dir.join("grades_gradebook.csv")).unwrap();
    // Two questions (speed, distance): 2 points possible, ann has 1.
    assert_eq!(
        book,
        format!(
            "Student,ID,SIS User ID,SIS Login ID,Section,{NAME},rigidlab total\nPoints Possible,,,,,2,2\nann,,ann,,,1,1\n"
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}
