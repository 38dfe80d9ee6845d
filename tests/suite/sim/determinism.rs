//! The same level run twice gives the same run, step for step: in one process through the
//! library's runner, and in two processes through `rigidlab run --csv`. No golden values are
//! stored, so a legitimate change of the physics does not break this test; nondeterminism does.

use rigidlab::level;
use rigidlab::runner::run_scene;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;
use std::process::Command;

const LEVELS: [&str; 3] = [
    "levels/kinetics/simple_pendulum.ron",
    "levels/impact/central_impact.ron",
    "levels/kinetics/classic_rolling_disc.ron",
];

/// A hash of every snapshot of a run (its serde_json text), initial state first.
fn step_hashes(path: &str) -> Vec<u64> {
    let scene = level::load(Path::new(path)).unwrap_or_else(|e| panic!("{e}"));
    let mut hashes = Vec::new();
    run_scene(&scene, &Options::default(), &HashMap::new(), |s| {
        let mut h = DefaultHasher::new();
        serde_json::to_string(s).unwrap().hash(&mut h);
        hashes.push(h.finish());
    })
    .unwrap_or_else(|e| panic!("{e}"));
    hashes
}

#[test]
fn a_run_repeats_every_step_in_one_process() {
    for path in LEVELS {
        let first = step_hashes(path);
        let second = step_hashes(path);
        assert!(first.len() > 10, "{path}: {} snapshots", first.len());
        if let Some(step) = (0..first.len()).find(|&i| first[i] != second[i]) {
            panic!("{path}: the second run departs at snapshot {step}");
        }
        assert_eq!(first.len(), second.len(), "{path}");
    }
}

#[test]
fn a_run_repeats_byte_for_byte_across_processes() {
    let dir = std::env::temp_dir().join(format!("rigidlab-determinism-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for path in LEVELS {
        let stem = Path::new(path).file_stem().unwrap().to_str().unwrap();
        let mut files = Vec::new();
        for run in ["a", "b"] {
            let csv = dir.join(format!("{run}_{stem}.csv"));
            let out = Command::new(env!("CARGO_BIN_EXE_rigidlab"))
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .args(["run", path, "--csv", csv.to_str().unwrap()])
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            // The bodies' file and whichever of joints/contacts/springs the level writes.
            let mut written: Vec<_> = std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().into_string().unwrap())
                .filter(|n| n.starts_with(&format!("{run}_{stem}")))
                .collect();
            written.sort();
            files.push(written);
        }
        let (a, b) = (&files[0], &files[1]);
        assert_eq!(a.len(), b.len(), "{path}: {a:?} against {b:?}");
        assert!(
            a.len() >= 2,
            "{path}: bodies and at least one side file: {a:?}"
        );
        for (fa, fb) in a.iter().zip(b) {
            let (ba, bb) = (
                std::fs::read(dir.join(fa)).unwrap(),
                std::fs::read(dir.join(fb)).unwrap(),
            );
            assert!(ba.len() > 100, "{fa} is nearly empty");
            assert!(ba == bb, "{path}: {fa} and {fb} differ");
        }
    }
}
