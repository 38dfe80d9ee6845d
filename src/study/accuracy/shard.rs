//! `study accuracy --shard K/N`: the K-th of N deterministic slices of a sweep, its manifest
//! (what slice, of which sweep) and the reference level every shard times so that costs from
//! different machines can be put on one scale.
//!
//! A slice is a set of whole levels, not of (level, setting) pairs: a level's settings share its
//! f64 reference run (the study's dearest run, up to `Plan::reference_budget_s` of wall time) and
//! its window, which is sized from a timed probe; split over nodes, every node holding one of
//! its settings would run the reference again and could size a different window.

use super::*;
use serde::Deserialize;

/// K of N, 1-based, as `--shard 2/8` writes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub k: usize,
    pub n: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || {
            format!("`{s}` is not K/N\n  help: give the shard's number and the number of shards, 1 <= K <= N, e.g. --shard 2/8")
        };
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (k, n): (usize, usize) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if k == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// One level file of the sweep: its name in the study and a hash of its bytes.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Work {
    name: String,
    content: u64,
    /// Position in the files given (the order a whole run writes its rows in).
    order: usize,
}

/// FNV-1a, 64 bits: a fixed, documented hash (std's `DefaultHasher` may change between Rust
/// releases, and nodes of a cluster may run different builds of the same version).
fn fnv1a(bytes: &[u8], mut h: u64) -> u64 {
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// The sweep's work list, sorted (by level name, then content), whatever order the files came in.
fn work_list(files: &[PathBuf]) -> Vec<Work> {
    let mut w: Vec<Work> = files
        .iter()
        .enumerate()
        .map(|(order, f)| Work {
            name: level_name(f),
            // A file that cannot be read hashes as empty; the run says why it was skipped.
            content: fnv1a(&std::fs::read(f).unwrap_or_default(), FNV_OFFSET),
            order,
        })
        .collect();
    w.sort_by(|a, b| (&a.name, a.content).cmp(&(&b.name, b.content)));
    w
}

/// What makes two sweeps the same: rigidlab's version, the plan (every knob value, the reference,
/// the timing), and each level's name and bytes. Neither the order of the files nor the paths
/// they were read from (a cluster's nodes mount the levels in different places) count.
pub fn fingerprint(files: &[PathBuf], plan: &Plan) -> String {
    let mut h = fnv1a(
        format!("rigidlab {}\n{plan:?}\n", env!("CARGO_PKG_VERSION")).as_bytes(),
        FNV_OFFSET,
    );
    for w in work_list(files) {
        h = fnv1a(format!("{}\0{:016x}\n", w.name, w.content).as_bytes(), h);
    }
    format!("fnv1a64:{h:016x}")
}

/// The files of shard K of N: every N-th of the sorted work list, starting at the K-th, in the
/// order they were given.
pub fn slice(files: &[PathBuf], shard: Shard) -> Vec<PathBuf> {
    let mut mine: Vec<Work> = work_list(files)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| i % shard.n == shard.k - 1)
        .map(|(_, w)| w)
        .collect();
    mine.sort_by_key(|w| w.order);
    mine.into_iter().map(|w| files[w.order].clone()).collect()
}

/// The level every shard times beside its own, built into the binary so that every node times
/// the same scene whatever levels it was given: Newton's cradle from the library (five balls
/// on pins striking each other at dt 0.1 ms), because it exercises the three parts of rapier
/// that the library's costs are made of (contacts, joints, restitution) in a run short enough
/// to time in every round.
pub const TIMING_LEVEL: &str = "impact/classic_newtons_cradle";
const TIMING_LEVEL_RON: &str = include_str!("../../../levels/impact/classic_newtons_cradle.ron");

/// The timing level as a scene.
pub fn timing_scene() -> Scene {
    level::parse(Path::new("classic_newtons_cradle.ron"), TIMING_LEVEL_RON)
        .expect("the built-in timing level parses (tests/suite/study/shards.rs)")
}

/// The timing level as a one-point study, timed by `measure_costs` among the levels' settings.
pub fn timing_study() -> LevelStudy {
    let scene = timing_scene();
    let setting = Setting::of_level(&scene.level);
    LevelStudy {
        name: TIMING_LEVEL.into(),
        engine: PhysicsEngine::Rapier,
        title: scene.level.title.clone(),
        class: class(&scene.level),
        conserved: metrics::conserved(&scene.level),
        points: vec![Point {
            setting,
            knobs: Vec::new(),
            baseline: true,
            rapier_default: false,
        }],
        rows: vec![Row::default()],
        has_exact: false,
        notes: Vec::new(),
        reference: setting,
        window_s: scene.level.world.duration,
        timeable: vec![true],
        load: None,
        scene,
    }
}

/// The timing level's cost in one shard: median and fastest over the shard's timing rounds.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TimingRef {
    pub level: String,
    pub cost_us_per_sim_s: f64,
    pub cost_min_us_per_sim_s: f64,
    pub cost_spread: f64,
    pub rounds: usize,
}

impl TimingRef {
    pub fn of(study: &LevelStudy) -> Option<TimingRef> {
        let r = study.rows.first()?;
        Some(TimingRef {
            level: TIMING_LEVEL.into(),
            cost_us_per_sim_s: r.cost_us_per_sim_s?,
            cost_min_us_per_sim_s: r.cost_min_us_per_sim_s?,
            cost_spread: r.cost_spread?,
            rounds: r.cost_rounds?,
        })
    }
}

/// What `study merge` needs of a level besides its rows.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LevelMeta {
    pub name: String,
    /// The engine of the level's rows (shards written before `--engine` have rapier's only).
    #[serde(default)]
    pub engine: PhysicsEngine,
    /// Position in the files the shard was given (rows are merged in this order).
    pub order: usize,
    /// The level as studied (its duration cut to the window), as `level::to_ron` writes it.
    pub level: String,
    pub notes: Vec<String>,
    /// The f64 reference run's dt, substeps and PGS iterations.
    pub reference: (f64, usize, usize),
    pub window_s: f64,
}

/// A level skipped by the shard, and why.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SkippedMeta {
    pub name: String,
    pub order: usize,
    pub why: String,
}

/// shard.json: what slice of which sweep a folder holds.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Manifest {
    /// First field, so that the file's first line is its mark ([`MANIFEST_MARK`]).
    pub written_by: String,
    pub rigidlab: String,
    pub shard: usize,
    pub shards: usize,
    pub fingerprint: String,
    /// Level files in the whole sweep.
    pub work: usize,
    pub quick: bool,
    /// The engines swept (`--engine`; shards written before it swept rapier only).
    #[serde(default = "rapier_only")]
    pub engines: Vec<PhysicsEngine>,
    pub format: String,
    pub timing: Option<TimingRef>,
    /// The machine's 1-minute load average before and after the timing phase.
    pub load: Option<(f64, f64)>,
    pub levels: Vec<LevelMeta>,
    pub skipped: Vec<SkippedMeta>,
}

fn rapier_only() -> Vec<PhysicsEngine> {
    vec![PhysicsEngine::Rapier]
}

pub const MANIFEST_FILE: &str = "shard.json";
/// shard.json's first line: how a manifest shows rigidlab wrote it.
pub const MANIFEST_MARK: &str = r#"{"written_by": "rigidlab study accuracy --shard","#;

impl Manifest {
    /// The manifest of a finished shard.
    pub fn of(
        shard: Shard,
        all_files: &[PathBuf],
        plan: &Plan,
        format: &str,
        studies: &[LevelStudy],
        skipped: &[(String, String)],
        timing: Option<TimingRef>,
    ) -> Manifest {
        let order = |name: &str| {
            all_files
                .iter()
                .position(|f| level_name(f) == name)
                .unwrap_or(usize::MAX)
        };
        Manifest {
            written_by: "rigidlab study accuracy --shard".into(),
            rigidlab: env!("CARGO_PKG_VERSION").into(),
            shard: shard.k,
            shards: shard.n,
            fingerprint: fingerprint(all_files, plan),
            work: all_files.len(),
            quick: plan.quick,
            engines: plan.engines.clone(),
            format: format.into(),
            timing,
            load: studies.iter().find_map(|s| s.load),
            levels: studies
                .iter()
                .map(|st| LevelMeta {
                    name: st.name.clone(),
                    engine: st.engine,
                    order: order(&st.name),
                    level: level::to_ron(&st.scene.level),
                    notes: st.notes.clone(),
                    reference: (
                        st.reference.dt,
                        st.reference.substeps,
                        st.reference.iterations,
                    ),
                    window_s: st.window_s,
                })
                .collect(),
            skipped: skipped
                .iter()
                .map(|(name, why)| SkippedMeta {
                    name: name.clone(),
                    order: order(name),
                    why: why.clone(),
                })
                .collect(),
        }
    }

    /// The manifest as JSON whose first line is [`MANIFEST_MARK`].
    pub fn to_text(&self) -> String {
        let pretty = serde_json::to_string_pretty(self).expect("a manifest serializes");
        // `{\n  "written_by": ...` -> `{"written_by": ...`: still JSON, and marked on line 1.
        match pretty.strip_prefix("{\n  ") {
            Some(rest) => format!("{{{rest}\n"),
            None => pretty,
        }
    }

    /// Err when `dir/shard.json` is a file rigidlab did not write.
    pub fn replaceable(dir: &Path) -> Result<(), String> {
        crate::files::replaceable(
            &dir.join(MANIFEST_FILE),
            crate::files::Mark::FirstLine(MANIFEST_MARK),
        )
        .map_err(|e| format!("error: --out {e}"))
    }

    pub fn write(&self, dir: &Path) -> Result<(), String> {
        let path = dir.join(MANIFEST_FILE);
        crate::files::write_over_own(
            &path,
            self.to_text().as_bytes(),
            crate::files::Mark::FirstLine(MANIFEST_MARK),
        )
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
    }
}
