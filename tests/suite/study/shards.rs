//! A sweep split into shards (`study accuracy --shard K/N`) and joined (`study merge`) gives the
//! rows a whole run gives; the merge refuses what is not one whole sweep; slices do not depend
//! on the order of the files.
//!
//! Expected values come from the definitions, not from a run: a slice is every N-th level of
//! the sorted work list, so N slices are disjoint and cover the sweep whatever order the files
//! came in; the rows of a level depend on the level and the plan alone (its window and the runs
//! over the cap are priced by the run budget's estimate, not timed), so merged and whole rows
//! are equal exactly, timing columns aside; a shard's costs are scaled by (median of the shards'
//! timing-level costs) / (its own), which the test recomputes from the shards' files.

use crate::common;
use crate::common::study::{self as study_files, accuracy_rows as records, merge, without_timing};
use rigidlab::study::accuracy::shard::{fingerprint, slice, Shard};
use rigidlab::study::accuracy::Plan;
use std::path::{Path, PathBuf};
use std::process::Output;

/// Four small library levels: two with exact answers and no joints, two energy levels.
const LEVELS: [&str; 4] = [
    "levels/kinematics/free_fall.ron",
    "levels/kinematics/projectile.ron",
    "levels/energy/jh_spring_work.ron",
    "levels/energy/jh_pendulum_gravity_work.ron",
];

fn tmp(tag: &str) -> PathBuf {
    study_files::tmp_dir("shards", tag)
}

fn rigidlab(args: &[&str], extra: &[&Path]) -> Output {
    common::rigidlab()
        .args(args)
        .args(extra)
        .output()
        .expect("the binary runs")
}

fn study(levels: &[&str], out: &Path, shard: Option<&str>) -> Output {
    let mut args = vec!["study", "accuracy", "--quick"];
    args.extend(levels);
    if let Some(s) = shard {
        args.extend(["--shard", s]);
    }
    args.push("--out");
    let o = rigidlab(&args, &[out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn col<'a>(row: &'a [(String, String)], c: &str) -> &'a str {
    &row.iter().find(|(k, _)| k == c).unwrap().1
}

fn manifest(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("shard.json")).unwrap()).unwrap()
}

/// summary.md's headings (its tables hold costs, which differ between runs).
fn headings(dir: &Path) -> Vec<String> {
    std::fs::read_to_string(dir.join("summary.md"))
        .unwrap()
        .lines()
        .filter(|l| l.starts_with('#'))
        .map(String::from)
        .collect()
}

#[test]
fn three_shards_merged_give_the_whole_runs_rows() {
    let dir = tmp("three");
    let whole = dir.join("whole");
    study(&LEVELS, &whole, None);
    let shards: Vec<PathBuf> = (1..=3).map(|k| dir.join(format!("s{k}"))).collect();
    for (k, s) in shards.iter().enumerate() {
        // Same command as the whole run (rows are merged in the order the files were given;
        // the slices' independence of that order is the last test's).
        study(&LEVELS, s, Some(&format!("{}/3", k + 1)));
    }
    let merged = dir.join("merged");
    let refs: Vec<&Path> = shards.iter().map(PathBuf::as_path).collect();
    let o = merge(&refs, &merged);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    let (w, m) = (records(&whole), records(&merged));
    assert!(
        w.len() >= 4 * 10,
        "every level sweeps its points: {} rows",
        w.len()
    );
    let (wt, mt) = (without_timing(&w), without_timing(&m));
    assert_eq!(mt.len(), wt.len());
    if let Some(i) = (0..wt.len()).find(|&i| wt[i] != mt[i]) {
        panic!("row {i} differs:\nwhole  {:?}\nmerged {:?}", wt[i], mt[i]);
    }
    // Each level in exactly one shard, all levels in some shard.
    let mut names: Vec<String> = shards
        .iter()
        .flat_map(|s| manifest(s)["levels"].as_array().unwrap().clone())
        .map(|l| l["name"].as_str().unwrap().to_string())
        .collect();
    names.sort();
    let n = names.len();
    names.dedup();
    assert_eq!((n, names.len()), (4, 4), "{names:?}");
    assert!(
        shards.iter().all(|s| !records(s).is_empty()),
        "4 levels over 3 shards: none empty"
    );
    // Costs on one scale: raw cost x (median timing / the shard's timing), to rounding.
    let timing = |s: &Path| manifest(s)["timing"]["cost_us_per_sim_s"].as_f64().unwrap();
    let mut t: Vec<f64> = shards.iter().map(|s| timing(s)).collect();
    t.sort_by(f64::total_cmp);
    let basis = t[1];
    for s in &shards {
        for raw in records(s) {
            let key = |r: &[(String, String)]| {
                [
                    "level",
                    "knob",
                    "dt",
                    "substeps",
                    "pgs_iterations",
                    "precision",
                    "effects",
                ]
                .map(|c| col(r, c).to_string())
            };
            let out = m.iter().find(|r| key(r) == key(&raw)).expect("row merged");
            let (c_raw, c_out) = (
                col(&raw, "cost_us_per_sim_s"),
                col(out, "cost_us_per_sim_s"),
            );
            if c_raw.is_empty() {
                assert!(c_out.is_empty());
                continue;
            }
            let expect = c_raw.parse::<f64>().unwrap() * basis / timing(s);
            // 1e-12: two f64 roundings of the product and its decimal print.
            common::assert_close!(c_out.parse::<f64>().unwrap(), expect, 1e-12 * expect);
        }
    }
    assert_eq!(headings(&merged), headings(&whole));
    for l in ["kinematics_free_fall", "energy_jh_spring_work"] {
        assert!(merged.join(format!("{l}.png")).is_file(), "plot of {l}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A falling ball: the cheapest level there is (contact-free, 0.1 s).
fn tiny(dir: &Path, name: &str, g: f64) -> PathBuf {
    let p = dir.join(format!("{name}.ron"));
    std::fs::write(
        &p,
        format!(
            r#"Level(title: "{name}", effects: [gravity],
    world: (dt: 0.016666666666666666, substeps: 4, duration: 0.1, gravity: (0.0, -{g})),
    bodies: [(name: "ball", shape: Circle(radius: 0.1), mass: 1.0)])"#
        ),
    )
    .unwrap();
    p
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

#[test]
fn merge_refuses_what_is_not_one_whole_sweep() {
    let dir = tmp("refuse");
    let a = tiny(&dir, "a", 9.81);
    let b = tiny(&dir, "b", 1.62);
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let (s1, s2) = (dir.join("s1"), dir.join("s2"));
    study(&[a, b], &s1, Some("1/2"));
    study(&[a, b], &s2, Some("2/2"));
    // Another sweep: b's bytes changed (g on the Moon to g on Mars).
    let other = dir.join("other");
    std::fs::create_dir_all(&other).unwrap();
    let b2 = tiny(&other, "b", 3.71);
    let o2 = dir.join("o2");
    study(&[a, b2.to_str().unwrap()], &o2, Some("2/2"));
    let out = dir.join("out");

    let o = merge(&[&s1], &out);
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(err(&o).contains("missing shard(s) 2/2"), "{}", err(&o));

    let o = merge(&[&s1, &s2, &s2], &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(err(&o).contains("shard 2/2 given twice"), "{}", err(&o));

    let o = merge(&[&s1, &o2], &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        err(&o).contains("shards of different sweeps"),
        "{}",
        err(&o)
    );

    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let o = merge(&[&s1, &empty], &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(err(&o).contains("not a shard folder"), "{}", err(&o));

    // The merged study is not written into a shard's folder.
    let before = std::fs::read(s1.join("accuracy.csv")).unwrap();
    let o = merge(&[&s1, &s2], &s1);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        err(&o).contains("one of the shards' folders"),
        "{}",
        err(&o)
    );
    assert_eq!(std::fs::read(s1.join("accuracy.csv")).unwrap(), before);

    // Notes of the user's under summary.md are kept, and nothing is merged.
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("summary.md"), "my notes\n").unwrap();
    let o = merge(&[&s1, &s2], &mine);
    assert_eq!(o.status.code(), Some(2));
    assert!(err(&o).contains("rigidlab did not write it"), "{}", err(&o));
    assert_eq!(
        std::fs::read_to_string(mine.join("summary.md")).unwrap(),
        "my notes\n"
    );
    assert!(!mine.join("accuracy.csv").exists());

    // The whole sweep merges (and again over its own output).
    for _ in 0..2 {
        let o = merge(&[&s2, &s1], &out);
        assert!(o.status.success(), "{}", err(&o));
    }
    assert_eq!(records(&out).len(), records(&s1).len() + records(&s2).len());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_shard_argument_outside_1_to_n_is_refused() {
    let out = tmp("badk");
    for bad in ["0/3", "4/3", "3", "a/b"] {
        let o = rigidlab(
            &[
                "study", "accuracy", LEVELS[0], "--quick", "--shard", bad, "--out",
            ],
            &[&out],
        );
        assert_eq!(o.status.code(), Some(2), "--shard {bad}");
        assert!(err(&o).contains("is not K/N"), "{}", err(&o));
    }
    let o = rigidlab(
        &[
            "study", "accuracy", LEVELS[0], "--quick", "--jobs", "100000", "--out",
        ],
        &[&out],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        err(&o).contains("the timing method needs a core per shard"),
        "{}",
        err(&o)
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn slices_partition_the_sweep_whatever_the_order_of_the_files() {
    let files: Vec<PathBuf> = common::ron_files("levels/kinematics", &[]);
    assert!(files.len() >= 5);
    let mut rev = files.clone();
    rev.reverse();
    let plan = Plan::quick();
    assert_eq!(fingerprint(&files, &plan), fingerprint(&rev, &plan));
    assert_ne!(
        fingerprint(&files, &plan),
        fingerprint(&files, &Plan::full())
    );
    assert_ne!(fingerprint(&files, &plan), fingerprint(&files[1..], &plan));
    for n in [1, 3, files.len() + 2] {
        let mut all: Vec<PathBuf> = Vec::new();
        for k in 1..=n {
            let mut s = slice(&files, Shard { k, n });
            let mut r = slice(&rev, Shard { k, n });
            s.sort();
            r.sort();
            assert_eq!(s, r, "shard {k}/{n} depends on the order of the files");
            // Every N-th of the list: sizes differ by at most one.
            assert!(s.len() <= files.len().div_ceil(n) && s.len() >= files.len() / n);
            all.extend(s);
        }
        all.sort();
        let mut want = files.clone();
        want.sort();
        assert_eq!(all, want, "the {n} slices are disjoint and cover the sweep");
    }
}
