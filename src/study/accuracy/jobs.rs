//! `study accuracy --jobs N`: the N shards of a sweep run side by side on this machine, each a
//! process of this binary (`--shard K/N`), then merged.
//!
//! What that does to the timings: a study times one run at a time so that nothing of its own
//! disturbs them. Side by side, each shard's timing runs while the other shards run on the other
//! cores (shared caches, memory bandwidth, a shared core under SMT), so its raw costs are higher
//! and scatter more. The timing method allows it only with a core per shard: more shards than
//! cores would preempt the timed runs themselves, so that is refused. Every shard times the
//! built-in timing level in its own rounds, under the same disturbance; after the shards are
//! done the timing level is timed again alone, and the merge scales every shard's costs to that
//! quiet timing (docs/accuracy.md, "Sharding").

use super::merge::{merge_dirs, Basis};
use super::*;
use std::io::BufRead;
use std::process::{Command, Stdio};

pub fn main(args: &Args, plan: &Plan, jobs: usize) -> ExitCode {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if jobs == 0 || jobs > cores {
        stderr!(
            "error: --jobs {jobs} on a machine with {cores} core(s)\n  help: give 1 to {cores}: the timing method needs a core per shard (more shards than cores would preempt the timed runs); on a cluster, run `--shard K/N` per task and `study merge`"
        );
        return ExitCode::from(2);
    }
    let shards_dir = args.out.join("shards");
    let dirs: Vec<PathBuf> = (1..=jobs)
        .map(|k| shards_dir.join(format!("{k}-of-{jobs}")))
        .collect();
    let threads = (cores / jobs).max(1);
    stderr!(
        "running {jobs} shard(s) side by side, {threads} thread(s) each, into {}: their costs are timed beside each other and scaled to the timing level ({}) timed alone afterwards",
        shards_dir.display(),
        shard::TIMING_LEVEL
    );
    let children: Vec<_> = dirs
        .iter()
        .enumerate()
        .map(|(i, dir)| spawn_shard(args, shard::Shard { k: i + 1, n: jobs }, dir, threads))
        .collect();
    let mut failed = Vec::new();
    for (i, child) in children.into_iter().enumerate() {
        let ok = child.is_ok_and(|c| c.join().is_ok_and(|status| status));
        if !ok {
            failed.push(format!("{}/{jobs}", i + 1));
        }
    }
    if !failed.is_empty() {
        stderr!(
            "error: shard(s) {} failed (their messages above); the shards' folders are kept in {}",
            failed.join(", "),
            shards_dir.display()
        );
        return ExitCode::from(2);
    }
    let alone = time_alone(plan);
    merge_dirs(&dirs, &args.out, alone)
}

/// Starts shard `s` as a child process, its stderr relayed line by line with its name; the
/// thread's result is whether it succeeded.
fn spawn_shard(
    args: &Args,
    s: shard::Shard,
    dir: &Path,
    threads: usize,
) -> Result<std::thread::JoinHandle<bool>, ()> {
    let exe = std::env::current_exe()
        .map_err(|e| stderr!("error: cannot find rigidlab's own binary: {e}"))?;
    let mut cmd = Command::new(exe);
    cmd.args(["study", "accuracy"])
        .args(&args.levels)
        .arg("--shard")
        .arg(s.to_string())
        .arg("--out")
        .arg(dir)
        .args(["--format", &args.format])
        .env("RAYON_NUM_THREADS", threads.to_string())
        .stdout(Stdio::inherit())
        .stderr(Stdio::piped());
    if args.quick {
        cmd.arg("--quick");
    }
    let engines: Vec<&str> = args.engine.iter().map(|e| e.name()).collect();
    if !engines.is_empty() {
        cmd.arg("--engine").arg(engines.join(","));
    }
    let mut child = cmd
        .spawn()
        .map_err(|e| stderr!("error: cannot start shard {s}: {e}"))?;
    let err = child.stderr.take();
    Ok(std::thread::spawn(move || {
        if let Some(err) = err {
            for line in std::io::BufReader::new(err).lines().map_while(Result::ok) {
                stderr!("shard {s}: {line}");
            }
        }
        child.wait().is_ok_and(|st| st.success())
    }))
}

/// The timing level timed alone (nothing else of ours running), as many rounds as a shard.
fn time_alone(plan: &Plan) -> Option<Basis> {
    let mut one = vec![shard::timing_study()];
    measure_costs(&mut one, plan, &|| {});
    let t = shard::TimingRef::of(&one[0])?;
    stderr!(
        "timing level {} alone: {:.1} µs per simulated second",
        shard::TIMING_LEVEL,
        t.cost_us_per_sim_s
    );
    Some(Basis {
        us_per_sim_s: t.cost_us_per_sim_s,
        what: "its timing alone on this machine after the side-by-side shards (`--jobs`)".into(),
    })
}
