//! `rigidlab study merge DIR... --out DIR`: joins the shards of one sweep into the accuracy.csv,
//! plots and summary.md a single run writes, with every shard's costs put on one scale by the
//! timing level each shard timed ([`shard::TimingRef`]).

use super::shard::{LevelMeta, Manifest, MANIFEST_FILE, MANIFEST_MARK};
use super::*;

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Shard folders, each written by `study accuracy --shard K/N`, all N of them.
    #[arg(required = true, value_name = "DIR")]
    pub shards: Vec<PathBuf>,
    /// Folder for the merged accuracy.csv, plots and summary.md (created if missing; files
    /// there are replaced only where rigidlab wrote them).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn main(args: MergeArgs) -> ExitCode {
    merge_dirs(&args.shards, &args.out, None)
}

/// A shard as read back: its folder, manifest and rows.
struct ShardIn {
    dir: PathBuf,
    manifest: Manifest,
    rows: Vec<Row>,
}

/// The cost scale the merge writes in, µs per simulated second of the timing level, and where it
/// comes from (for summary.md).
pub struct Basis {
    pub us_per_sim_s: f64,
    pub what: String,
}

/// Reads, checks and joins `dirs` into `out`. `basis`: the timing level's cost to scale every
/// shard to (default: the median of the shards' own timings).
pub fn merge_dirs(dirs: &[PathBuf], out: &Path, basis: Option<Basis>) -> ExitCode {
    let merged = read_all(dirs)
        .and_then(|shards| check_sweep(&shards).map(|()| shards))
        .and_then(|shards| check_out(dirs, out).map(|()| shards))
        .and_then(|shards| join(shards, basis));
    match merged {
        Ok(m) => write_outputs(
            out,
            &m.format,
            &m.studies,
            &m.skipped,
            &m.plan,
            Some(&m.note),
        ),
        Err(e) => {
            stderr!("{e}");
            ExitCode::from(2)
        }
    }
}

fn read_all(dirs: &[PathBuf]) -> Result<Vec<ShardIn>, String> {
    dirs.iter().map(|d| read_shard(d)).collect()
}

/// A shard folder's manifest and rows, or why it is not one.
fn read_shard(dir: &Path) -> Result<ShardIn, String> {
    let path = dir.join(MANIFEST_FILE);
    let not_shard = |why: String| {
        format!(
            "error: {}: {why}\n  help: give folders written by `rigidlab study accuracy ... --shard K/N --out DIR`",
            dir.display()
        )
    };
    let text = std::fs::read_to_string(&path).map_err(|e| {
        not_shard(format!(
            "no readable {MANIFEST_FILE} ({e}): not a shard folder"
        ))
    })?;
    if text.lines().next() != Some(MANIFEST_MARK) {
        return Err(not_shard(format!(
            "{MANIFEST_FILE} was not written by rigidlab (its first line is not {MANIFEST_MARK})"
        )));
    }
    let manifest: Manifest = serde_json::from_str(&text)
        .map_err(|e| not_shard(format!("{MANIFEST_FILE}:{}:{}: {e}", e.line(), e.column())))?;
    if manifest.rigidlab != env!("CARGO_PKG_VERSION") {
        return Err(not_shard(format!(
            "written by rigidlab {}, this is {}: merge with the version that ran the shards",
            manifest.rigidlab,
            env!("CARGO_PKG_VERSION")
        )));
    }
    let csv_path = dir.join("accuracy.csv");
    let mut rd = csv::Reader::from_path(&csv_path)
        .map_err(|e| not_shard(format!("cannot read accuracy.csv: {e}")))?;
    let header: Vec<String> = rd
        .headers()
        .map_err(|e| not_shard(format!("accuracy.csv: {e}")))?
        .iter()
        .map(String::from)
        .collect();
    if header != CSV_COLUMNS {
        return Err(not_shard(
            "accuracy.csv's header is not this version's (columns differ)".into(),
        ));
    }
    let rows = rd
        .deserialize()
        .collect::<Result<Vec<Row>, _>>()
        .map_err(|e| not_shard(format!("accuracy.csv: {e}")))?;
    Ok(ShardIn {
        dir: dir.to_path_buf(),
        manifest,
        rows,
    })
}

/// One sweep, every shard once: same fingerprint and N, K = 1..N each exactly once.
fn check_sweep(shards: &[ShardIn]) -> Result<(), String> {
    let first = &shards[0];
    let (fp, n) = (&first.manifest.fingerprint, first.manifest.shards);
    let who = |s: &ShardIn| {
        format!(
            "{} (shard {}/{}, sweep {})",
            s.dir.display(),
            s.manifest.shard,
            s.manifest.shards,
            s.manifest.fingerprint
        )
    };
    if let Some(other) = shards.iter().find(|s| &s.manifest.fingerprint != fp) {
        return Err(format!(
            "error: shards of different sweeps: {} and {}\n  help: a sweep is its level files' names and bytes, the plan (--quick or not) and rigidlab's version; rerun the odd shard with the same levels and flags",
            who(first),
            who(other)
        ));
    }
    if let Some(other) = shards.iter().find(|s| s.manifest.shards != n) {
        return Err(format!(
            "error: shards of different splits: {} and {}\n  help: merge the N shards of one --shard K/N split",
            who(first),
            who(other)
        ));
    }
    for k in 1..=n {
        let with_k: Vec<&ShardIn> = shards.iter().filter(|s| s.manifest.shard == k).collect();
        match with_k.as_slice() {
            [] => {
                let missing: Vec<String> = (1..=n)
                    .filter(|k| shards.iter().all(|s| s.manifest.shard != *k))
                    .map(|k| format!("{k}/{n}"))
                    .collect();
                return Err(format!(
                    "error: missing shard(s) {} of sweep {fp}\n  help: run `study accuracy ... --shard K/{n}` for each and give every folder",
                    missing.join(", ")
                ));
            }
            [_] => {}
            [a, b, ..] => {
                return Err(format!(
                    "error: shard {k}/{n} given twice: {} and {}\n  help: give each shard's folder once",
                    a.dir.display(),
                    b.dir.display()
                ))
            }
        }
    }
    Ok(())
}

/// --out: not a shard's folder, writable, and no accuracy.csv or summary.md rigidlab did not write.
fn check_out(dirs: &[PathBuf], out: &Path) -> Result<(), String> {
    if let Some(d) = dirs.iter().find(|d| crate::files::same_file(d, out)) {
        return Err(format!(
            "error: --out {} is one of the shards' folders\n  help: give another folder for the merged study (the shards are kept)",
            d.display()
        ));
    }
    writable_folder(out).and_then(|()| own_outputs(out))
}

/// What the merge writes.
struct Merged {
    studies: Vec<LevelStudy>,
    skipped: Vec<(String, String)>,
    plan: Plan,
    format: String,
    note: String,
}

/// The shards' studies in the order a whole run writes them, costs on one scale.
fn join(shards: Vec<ShardIn>, basis: Option<Basis>) -> Result<Merged, String> {
    let m0 = &shards[0].manifest;
    let plan = if m0.quick {
        Plan::quick()
    } else {
        Plan::full()
    }
    .on_engines(&m0.engines);
    let format = m0.format.clone();
    let basis = basis.or_else(|| median_basis(&shards));
    let note = scale_note(&shards, basis.as_ref());
    let mut levels: Vec<(usize, LevelStudy)> = Vec::new();
    let mut skipped: Vec<(usize, String, String)> = Vec::new();
    for s in shards {
        let factor = match (&basis, &s.manifest.timing) {
            (Some(b), Some(t)) if t.cost_us_per_sim_s > 0.0 => b.us_per_sim_s / t.cost_us_per_sim_s,
            _ => 1.0,
        };
        let mut rows = s.rows;
        for r in rows.iter_mut() {
            r.cost_us_per_sim_s = r.cost_us_per_sim_s.map(|c| c * factor);
            r.cost_min_us_per_sim_s = r.cost_min_us_per_sim_s.map(|c| c * factor);
        }
        for meta in &s.manifest.levels {
            let mine: Vec<Row> = rows
                .iter()
                .filter(|r| r.level == meta.name && r.engine == meta.engine.name())
                .cloned()
                .collect();
            let st = level_study(meta, mine, s.manifest.load)
                .map_err(|e| format!("error: {}: {e}", s.dir.display()))?;
            levels.push((meta.order, st));
        }
        let known = |r: &Row| {
            s.manifest
                .levels
                .iter()
                .any(|m| m.name == r.level && m.engine.name() == r.engine)
        };
        if let Some(r) = rows.iter().find(|r| !known(r)) {
            return Err(format!(
                "error: {}: accuracy.csv has rows of {} on {} that shard.json does not list\n  help: rerun the shard (its files were changed after it ran)",
                s.dir.display(),
                r.level,
                r.engine
            ));
        }
        skipped.extend(
            s.manifest
                .skipped
                .into_iter()
                .map(|k| (k.order, k.name, k.why)),
        );
    }
    // A whole run writes a level's engines in the plan's order, after one another.
    let rank = |e: PhysicsEngine| plan.engines.iter().position(|x| *x == e);
    levels.sort_by(|a, b| {
        (a.0, &a.1.name, rank(a.1.engine)).cmp(&(b.0, &b.1.name, rank(b.1.engine)))
    });
    skipped.sort();
    Ok(Merged {
        studies: levels.into_iter().map(|(_, st)| st).collect(),
        skipped: skipped.into_iter().map(|(_, n, w)| (n, w)).collect(),
        plan,
        format,
        note,
    })
}

/// The median of the shards' timing-level costs (the scale of a typical node of the run).
fn median_basis(shards: &[ShardIn]) -> Option<Basis> {
    let mut v: Vec<f64> = shards
        .iter()
        .filter_map(|s| s.manifest.timing.as_ref().map(|t| t.cost_us_per_sim_s))
        .filter(|c| c.is_finite() && *c > 0.0)
        .collect();
    v.sort_by(f64::total_cmp);
    let m = *v.get(v.len().checked_sub(1)? / 2)?;
    Some(Basis {
        us_per_sim_s: m,
        what: "the median of the shards' timings".into(),
    })
}

/// summary.md's paragraph on where the rows come from and how their costs were scaled.
fn scale_note(shards: &[ShardIn], basis: Option<&Basis>) -> String {
    let m0 = &shards[0].manifest;
    let mut s = format!(
        "Merged by `rigidlab study merge` from {} shards of sweep {} ({} level files). ",
        m0.shards, m0.fingerprint, m0.work
    );
    match basis {
        Some(b) => s += &format!(
            "Costs are on one scale: every shard timed the built-in timing level ({}, at its own settings) in the same rounds as its levels, and its costs are multiplied by {:.1} / its own timing of that level, {:.1} µs per simulated second being {}. Per shard, timing level µs/sim s (factor): ",
            shard::TIMING_LEVEL, b.us_per_sim_s, b.us_per_sim_s, b.what
        ),
        None => s += "No shard timed the timing level: costs are as each shard measured them, on its own machine. Per shard: ",
    }
    let mut sorted: Vec<&ShardIn> = shards.iter().collect();
    sorted.sort_by_key(|s| s.manifest.shard);
    let parts: Vec<String> = sorted
        .iter()
        .map(|sh| {
            let m = &sh.manifest;
            let load = m
                .load
                .map_or(String::new(), |(b, a)| format!(", load {b:.2} -> {a:.2}"));
            match (&m.timing, basis) {
                (Some(t), Some(b)) => format!(
                    "{}/{} {:.1} (x{:.3}{load})",
                    m.shard,
                    m.shards,
                    t.cost_us_per_sim_s,
                    b.us_per_sim_s / t.cost_us_per_sim_s
                ),
                _ => format!("{}/{} not timed (x1{load})", m.shard, m.shards),
            }
        })
        .collect();
    s += &parts.join("; ");
    s.push('.');
    s
}

/// A level's study rebuilt from its shard's rows and manifest entry.
fn level_study(
    meta: &LevelMeta,
    rows: Vec<Row>,
    load: Option<(f64, f64)>,
) -> Result<LevelStudy, String> {
    let lvl: level::Level = level::ron_options().from_str(&meta.level).map_err(|e| {
        format!(
            "shard.json: the level {} does not read back: {e}",
            meta.name
        )
    })?;
    let points = rows
        .iter()
        .map(point_of)
        .collect::<Result<Vec<Point>, String>>()
        .map_err(|e| format!("accuracy.csv, level {}: {e}", meta.name))?;
    let (dt, substeps, iterations) = meta.reference;
    Ok(LevelStudy {
        name: meta.name.clone(),
        engine: meta.engine,
        title: lvl.title.clone(),
        class: class(&lvl),
        points,
        timeable: rows.iter().map(|r| r.cost_us_per_sim_s.is_some()).collect(),
        rows,
        has_exact: has_exact(&lvl),
        conserved: metrics::conserved(&lvl),
        notes: meta.notes.clone(),
        reference: Setting {
            dt,
            substeps,
            iterations,
            precision: Precision::F64,
            all_effects: false,
            engine: meta.engine,
        },
        window_s: meta.window_s,
        load,
        scene: Scene {
            file: PathBuf::from(format!("{}.ron", meta.name)),
            level: lvl,
        },
    })
}

/// A row's point of the sweep: its setting from the setting columns, its curves from `knob`.
fn point_of(r: &Row) -> Result<Point, String> {
    let precision = match r.precision.as_str() {
        "f32" => Precision::F32,
        "f64" => Precision::F64,
        p => return Err(format!("unknown precision `{p}`")),
    };
    let engine = match r.engine.as_str() {
        "rapier" => PhysicsEngine::Rapier,
        "box2d" => PhysicsEngine::Box2d,
        e => return Err(format!("unknown engine `{e}`")),
    };
    let setting = Setting {
        dt: r.dt,
        substeps: r.substeps,
        iterations: r.pgs_iterations,
        precision,
        all_effects: r.effects == "all",
        engine,
    };
    if r.knob == "baseline" {
        // The level's own settings lie on every f32 curve of the engine's sweep (`points_on`).
        return Ok(Point {
            setting,
            knobs: baseline_knobs(engine),
            baseline: true,
            rapier_default: false,
        });
    }
    let mut p = Point {
        setting,
        knobs: Vec::new(),
        baseline: false,
        rapier_default: false,
    };
    for name in r.knob.split('+') {
        if name == "rapier_default" {
            p.rapier_default = true;
        } else {
            let k = Knob::ALL
                .into_iter()
                .find(|k| k.name() == name)
                .ok_or_else(|| format!("unknown knob `{name}`"))?;
            p.knobs.push(k);
        }
    }
    Ok(p)
}
