//! `study accuracy --engine rapier,box2d`: every level on each engine that runs it, an engine
//! column in accuracy.csv, a level Box2D cannot run listed as refused with its feature, and
//! summary.md's "which engine is cheaper" table equal to what its rows say.
//!
//! Expected values come from definitions, not from a run: the knobs each engine sweeps (Box2D
//! has no f64 build and no PGS iterations, so no `dt_f64` or `pgs_iterations` curve), the
//! refusal of a spring by Box2D (docs/engines.md), and the table's counts recomputed here from
//! accuracy.csv by the rule summary.md states (per level run on both engines, the cheaper of the
//! two engines' cheapest declared-effects settings meeting the tolerance, or the only engine
//! meeting it); a sweep split into shards merges into the whole run's rows, now keyed by level
//! and engine, timing columns aside.

use crate::common;
use crate::common::study as study_files;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A contact-free level, a joint level, and a spring level Box2D refuses.
const LEVELS: [&str; 3] = [
    "levels/kinematics/free_fall.ron",
    "levels/kinetics/physical_pendulum.ron",
    "levels/energy/jh_spring_work.ron",
];

fn tmp(tag: &str) -> PathBuf {
    study_files::tmp_dir("engines", tag)
}

fn study(out: &Path, shard: Option<&str>) {
    let mut c = common::rigidlab();
    c.args(["study", "accuracy", "--quick", "--engine", "rapier,box2d"])
        .args(LEVELS);
    if let Some(s) = shard {
        c.args(["--shard", s]);
    }
    let o = c.arg("--out").arg(out).output().expect("the binary runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

type Record = BTreeMap<String, String>;

/// accuracy.csv's rows, keyed by column.
fn records(dir: &Path) -> Vec<Record> {
    study_files::accuracy_rows(dir)
        .into_iter()
        .map(|r| r.into_iter().collect())
        .collect()
}

fn num(r: &Record, c: &str) -> Option<f64> {
    r[c].parse().ok()
}

/// The cost of the engine's cheapest declared-effects row of `level` meeting the tolerance.
fn cheapest(rows: &[Record], level: &str, engine: &str) -> Option<f64> {
    rows.iter()
        .filter(|r| r["level"] == level && r["engine"] == engine)
        .filter(|r| r["effects"] == "declared" && r["meets_tolerance"] == "true")
        .filter_map(|r| num(r, "cost_us_per_sim_s"))
        .filter(|c| c.is_finite())
        .min_by(f64::total_cmp)
}

/// summary.md's "which engine is cheaper" table: class -> its cells.
fn engine_table(dir: &Path) -> BTreeMap<String, Vec<String>> {
    let md = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    let at = md
        .find("## Which engine is cheaper for which class of scene")
        .expect("the section is written for two engines");
    md[at..]
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| class"))
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<String> = l
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect();
            (cells[0].clone(), cells[1..].to_vec())
        })
        .collect()
}

#[test]
fn both_engines_swept_refusals_listed_and_the_verdict_from_the_rows() {
    let dir = tmp("whole");
    study(&dir, None);
    let rows = records(&dir);

    // Rows for both engines where both run; none on Box2D for the spring.
    let has = |level: &str, engine: &str| {
        rows.iter()
            .any(|r| r["level"] == level && r["engine"] == engine)
    };
    for level in ["kinematics/free_fall", "kinetics/physical_pendulum"] {
        assert!(has(level, "rapier") && has(level, "box2d"), "{level}");
    }
    assert!(has("energy/jh_spring_work", "rapier"));
    assert!(!has("energy/jh_spring_work", "box2d"));
    // Box2D's sweep: f32, no PGS-iterations curve, a single PGS value (the level's).
    for r in rows.iter().filter(|r| r["engine"] == "box2d") {
        assert_eq!(r["precision"], "f32", "{r:?}");
        assert!(
            !r["knob"].contains("dt_f64") && !r["knob"].contains("pgs_iterations"),
            "{r:?}"
        );
    }
    // The refused level listed, with the engine and the feature.
    let md = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(
        md.lines().any(
            |l| l.starts_with("- energy/jh_spring_work: refused by box2d:") && l.contains("spring")
        ),
        "{md}"
    );

    // The table, recomputed from the rows.
    let table = engine_table(&dir);
    let mut expect: BTreeMap<String, [usize; 8]> = BTreeMap::new();
    let mut levels: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r["level"].as_str(), r["class"].as_str()))
        .collect();
    levels.dedup();
    for (level, class) in levels {
        let e = expect.entry(class.to_string()).or_default();
        if !has(level, "box2d") {
            e[1] += 1; // refused by box2d
            continue;
        }
        e[0] += 1;
        let graded = rows
            .iter()
            .any(|r| r["level"] == level && !r["meets_tolerance"].is_empty());
        let slot = match (
            cheapest(&rows, level, "rapier"),
            cheapest(&rows, level, "box2d"),
        ) {
            _ if !graded => 7,
            (Some(a), Some(b)) if a < b => 2,
            (Some(a), Some(b)) if b < a => 3,
            (Some(_), Some(_)) => continue, // a tie: in neither column
            (Some(_), None) => 4,
            (None, Some(_)) => 5,
            (None, None) => 6,
        };
        e[slot] += 1;
    }
    assert_eq!(
        table.keys().collect::<Vec<_>>(),
        expect.keys().collect::<Vec<_>>(),
        "{table:?}"
    );
    for (class, counts) in &expect {
        let cells = &table[class];
        let got: Vec<usize> = cells[..8].iter().map(|c| c.parse().unwrap()).collect();
        assert_eq!(got, counts.to_vec(), "{class}: {cells:?}");
        // The verdict names the engine that wins more levels.
        let (a, b) = (counts[2] + counts[4], counts[3] + counts[5]);
        let verdict = &cells[10];
        if a != b {
            let winner = if a > b { "rapier" } else { "box2d" };
            assert!(
                verdict.starts_with(&format!("**{winner}**")),
                "{class}: {verdict}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn two_engine_shards_merge_into_the_whole_runs_rows() {
    let dir = tmp("shards");
    let whole = dir.join("whole");
    study(&whole, None);
    let shards: Vec<PathBuf> = (1..=2).map(|k| dir.join(format!("s{k}"))).collect();
    for (k, s) in shards.iter().enumerate() {
        study(s, Some(&format!("{}/2", k + 1)));
    }
    let merged = dir.join("merged");
    let o = study_files::merge(&shards, &merged);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let strip = |rows: Vec<Record>| -> Vec<Record> {
        rows.into_iter()
            .map(|mut r| {
                for c in study_files::TIMING {
                    r.remove(c);
                }
                r
            })
            .collect()
    };
    let (w, m) = (strip(records(&whole)), strip(records(&merged)));
    assert!(w.iter().any(|r| r["engine"] == "box2d"));
    assert_eq!(m.len(), w.len());
    if let Some(i) = (0..w.len()).find(|&i| w[i] != m[i]) {
        panic!("row {i} differs:\nwhole  {:?}\nmerged {:?}", w[i], m[i]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
