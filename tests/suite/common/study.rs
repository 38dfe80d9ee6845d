//! What the study tests share: a fresh output folder, accuracy.csv's rows read against the
//! columns the study declares, those rows without their timing columns (the only ones a rerun
//! or a merge may change), `study merge`, and what a stability run failed.

use super::rigidlab;
use rigidlab::level::Scene;
use rigidlab::runner::{Estimate, Mode, MEMORY_BUDGET_MB, TIME_BUDGET_S};
use rigidlab::study::accuracy::CSV_COLUMNS;
use rigidlab::study::stability::RunResult;
use std::path::{Path, PathBuf};
use std::process::Output;

/// The timing columns: the only ones a merge may change or a rerun may give otherwise.
pub const TIMING: [&str; 4] = [
    "cost_us_per_sim_s",
    "cost_min_us_per_sim_s",
    "cost_spread",
    "cost_rounds",
];

/// An accuracy.csv row, as text: (column, value) in the file's order.
pub type Row = Vec<(String, String)>;

/// An empty folder in the temporary directory for the test `group`'s case `tag`.
pub fn tmp_dir(group: &str, tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rigidlab-{group}-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `dir/accuracy.csv`'s rows, its header checked against the study's declared columns.
pub fn accuracy_rows(dir: &Path) -> Vec<Row> {
    let mut rd = csv::Reader::from_path(dir.join("accuracy.csv")).unwrap();
    let header: Vec<String> = rd.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, CSV_COLUMNS.to_vec());
    rd.records()
        .map(|r| {
            header
                .iter()
                .cloned()
                .zip(r.unwrap().iter().map(String::from))
                .collect()
        })
        .collect()
}

/// `rows` without their timing columns.
pub fn without_timing(rows: &[Row]) -> Vec<Row> {
    rows.iter()
        .map(|r| {
            r.iter()
                .filter(|(c, _)| !TIMING.contains(&c.as_str()))
                .cloned()
                .collect()
        })
        .collect()
}

/// `rigidlab study merge SHARDS... --out OUT`, its output whatever its exit.
pub fn merge(shards: &[impl AsRef<Path>], out: &Path) -> Output {
    rigidlab()
        .args(["study", "merge"])
        .args(shards.iter().map(AsRef::as_ref))
        .arg("--out")
        .arg(out)
        .output()
        .expect("the binary runs")
}

/// A stability run's failed criteria, `name = value (limit L)` each, for an assertion's message.
pub fn failed_criteria(r: &RunResult) -> Vec<String> {
    r.failed()
        .iter()
        .map(|c| format!("{} = {:.4e} (limit {:.4e})", c.name, c.value, c.limit))
        .collect()
}

/// Asserts a stability run passed every criterion and simulated its whole `duration`, s.
pub fn assert_passed_to_the_end(r: &RunResult, duration: f64) {
    let failed = failed_criteria(r);
    assert!(r.passed, "failed {failed:?}, stopped: {:?}", r.error);
    assert!(r.figure("sim_time").unwrap_or(0.0) >= duration - 1e-9);
}

/// Asserts `check` would run `scene` at its own settings: it refuses a level estimated past the
/// run budget (src/runner/budget.rs).
pub fn assert_check_would_run(scene: &Scene) {
    let e = Estimate::of(&scene.level, &Default::default(), Mode::Check, None);
    assert!(
        e.seconds < TIME_BUDGET_S && e.megabytes < MEMORY_BUDGET_MB,
        "{e:?}"
    );
}
