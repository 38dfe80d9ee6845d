//! The study's command and files: `main`, the output folder, accuracy.csv.

use super::*;

fn plot_file(name: &str, format: &str) -> String {
    format!("{}.{format}", name.replace(['/', '\\'], "_"))
}

pub fn main(args: Args) -> ExitCode {
    // Before the sweep, which takes minutes: an --out that cannot take the files, or holds
    // a summary or table rigidlab did not write (kept, and the study refused).
    let out_ok = writable_folder(&args.out)
        .and_then(|()| own_outputs(&args.out))
        .and_then(|()| match args.shard {
            Some(_) => shard::Manifest::replaceable(&args.out),
            None => Ok(()),
        });
    if let Err(e) = out_ok {
        stderr!("{e}");
        return ExitCode::from(2);
    }
    let paths = if args.levels.is_empty() {
        vec![PathBuf::from("levels")]
    } else {
        args.levels.clone()
    };
    let files = match level::collect_files(&paths) {
        Ok(f) => f,
        Err(e) => {
            stderr!("{e}");
            return ExitCode::from(2);
        }
    };
    if files.is_empty() {
        stderr!("no level files (*.ron) found in the given paths");
        return ExitCode::from(2);
    }
    let plan = if args.quick {
        Plan::quick()
    } else {
        Plan::full()
    }
    .on_engines(&args.engine);
    if let Some(j) = args.jobs {
        return jobs::main(&args, &plan, j);
    }
    let mine = match args.shard {
        Some(s) => shard::slice(&files, s),
        None => files.clone(),
    };
    let progress = ProgressBar::new(0);
    progress.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} runs  {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let (studies, skipped, timing) = run_study_timed(&mine, &plan, &progress, args.shard.is_some());
    let code = write_outputs(&args.out, &args.format, &studies, &skipped, &plan, None);
    if let Some(s) = args.shard {
        let manifest =
            shard::Manifest::of(s, &files, &plan, &args.format, &studies, &skipped, timing);
        if let Err(e) = manifest.write(&args.out) {
            stderr!("error: {e}");
            return ExitCode::from(2);
        }
        stderr!(
            "shard {s} of sweep {}: {} of {} level file(s); timing level {} at {}",
            manifest.fingerprint,
            mine.len(),
            files.len(),
            shard::TIMING_LEVEL,
            manifest
                .timing
                .as_ref()
                .map_or("- (not timed)".into(), |t| format!(
                    "{:.1} µs per simulated second",
                    t.cost_us_per_sim_s
                ))
        );
    }
    code
}

/// accuracy.csv, the plots and summary.md of `studies` in `out` (`note`, if any, right under
/// summary.md's title), and what was written said on stderr; exit 2 if any file could not be
/// written or a level did not load.
pub fn write_outputs(
    out: &Path,
    format: &str,
    studies: &[LevelStudy],
    skipped: &[(String, String)],
    plan: &Plan,
    note: Option<&str>,
) -> ExitCode {
    let csv_path = out.join("accuracy.csv");
    if let Err(e) = write_csv(&csv_path, studies) {
        stderr!("cannot write {}: {e}", csv_path.display());
        return ExitCode::from(2);
    }
    // Every file the study writes is checked: a plot that cannot be written is said and makes
    // the exit code 2, after the other files are written.
    let mut plots = Vec::new();
    let mut failed_plots = 0;
    // One plot per level, every engine that ran it on the same axes.
    let mut names: Vec<&str> = studies.iter().map(|st| st.name.as_str()).collect();
    names.dedup();
    for name in names {
        let group: Vec<&LevelStudy> = studies.iter().filter(|st| st.name == name).collect();
        let st = group[0];
        let file = plot_file(&st.name, format);
        match summary::plot_level(&group, &out.join(&file)) {
            Ok(()) => plots.push((st.name.clone(), file)),
            Err(e) => {
                stderr!("error: {}: cannot write the plot: {e}", st.name);
                failed_plots += 1;
            }
        }
    }
    let mut md = summary::markdown(studies, skipped, plan, &plots);
    if let Some(note) = note {
        let at = md.find("\n\n").map_or(0, |i| i + 2);
        md.insert_str(at, &format!("{note}\n\n"));
    }
    let md_path = out.join("summary.md");
    let md = format!("{}\n{md}", crate::files::TEXT_MARK);
    if let Err(e) = crate::files::write_over_own(&md_path, md.as_bytes(), SUMMARY_MARK) {
        stderr!("cannot write {}: {e}", md_path.display());
        return ExitCode::from(2);
    }
    stderr!(
        "wrote {}, {} and {} plot(s) in {}",
        csv_path.display(),
        md_path.display(),
        plots.len(),
        out.display()
    );
    for (name, why) in skipped {
        stderr!("skipped {name}: {why}");
    }
    if failed_plots > 0 {
        stderr!("error: {failed_plots} plot(s) could not be written");
        return ExitCode::from(2);
    }
    if skipped
        .iter()
        .any(|(_, why)| why.starts_with("does not load"))
    {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    }
}

/// Creates `dir` if missing and checks that a file can be written in it.
/// How summary.md shows rigidlab wrote it: its first line.
const SUMMARY_MARK: crate::files::Mark<'static> =
    crate::files::Mark::FirstLine(crate::files::TEXT_MARK);

/// accuracy.csv's header line, its mark.
fn csv_header() -> String {
    CSV_COLUMNS.join(",")
}

/// Err when accuracy.csv or summary.md in `dir` is a file rigidlab did not write: a user's
/// notes under either name are kept, and the study refused before it runs.
pub fn own_outputs(dir: &Path) -> Result<(), String> {
    let header = csv_header();
    crate::files::replaceable(
        &dir.join("accuracy.csv"),
        crate::files::Mark::FirstLine(&header),
    )
    .and_then(|()| crate::files::replaceable(&dir.join("summary.md"), SUMMARY_MARK))
    .map_err(|e| format!("error: --out {e}"))
}

pub fn writable_folder(dir: &Path) -> Result<(), String> {
    let d = dir.display();
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "error: --out {d} is a file, not a folder\n  help: give a folder for accuracy.csv, the plots and summary.md (created if missing)"
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| {
        format!("error: cannot create the folder {d}: {e}\n  help: give a folder you can write to")
    })?;
    // A probe of a name of its own, created new: a file of that name is never written over or
    // removed.
    let probe = dir.join(format!(".rigidlab-write-test-{}", std::process::id()));
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .and_then(|_| std::fs::remove_file(&probe))
        .map_err(|e| {
            format!("error: cannot write in {d}: {e}\n  help: give a folder you can write to")
        })
}

/// accuracy.csv, written whole (crate::files): a failure leaves an earlier one as it was.
fn write_csv(path: &Path, studies: &[LevelStudy]) -> Result<(), String> {
    let header = csv_header();
    crate::files::replaceable(path, crate::files::Mark::FirstLine(&header))
        .map_err(|e| e.to_string())?;
    let file = crate::files::Pending::create(path).map_err(|e| e.to_string())?;
    let mut w = csv::Writer::from_writer(file);
    // A study with no level still gets its header.
    if studies.iter().all(|s| s.rows.is_empty()) {
        w.write_record(CSV_COLUMNS).map_err(|e| e.to_string())?;
    }
    for st in studies {
        for r in &st.rows {
            w.serialize(r).map_err(|e| e.to_string())?;
        }
    }
    let file = w.into_inner().map_err(|e| e.error().to_string())?;
    file.commit().map_err(|e| e.to_string())
}
