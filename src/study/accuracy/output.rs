//! The study's command and files: `main`, the output folder, accuracy.csv.

use super::*;

fn plot_file(name: &str, format: &str) -> String {
    format!("{}.{format}", name.replace(['/', '\\'], "_"))
}

pub fn main(args: Args) -> ExitCode {
    // Before the sweep, which takes minutes: an --out that cannot take the files.
    if let Err(e) = writable_folder(&args.out) {
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
    };
    let progress = ProgressBar::new(0);
    progress.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} runs  {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let (studies, skipped) = run_study(&files, &plan, &progress);

    let csv_path = args.out.join("accuracy.csv");
    if let Err(e) = write_csv(&csv_path, &studies) {
        stderr!("cannot write {}: {e}", csv_path.display());
        return ExitCode::from(2);
    }
    let mut plots = Vec::new();
    for st in &studies {
        let file = plot_file(&st.name, &args.format);
        match summary::plot_level(st, &args.out.join(&file)) {
            Ok(()) => plots.push((st.name.clone(), file)),
            Err(e) => stderr!("{}: cannot draw the plot: {e}", st.name),
        }
    }
    let md = summary::markdown(&studies, &skipped, &plan, &plots);
    let md_path = args.out.join("summary.md");
    if let Err(e) = std::fs::write(&md_path, md) {
        stderr!("cannot write {}: {e}", md_path.display());
        return ExitCode::from(2);
    }
    stderr!(
        "wrote {}, {} and {} plot(s) in {}",
        csv_path.display(),
        md_path.display(),
        plots.len(),
        args.out.display()
    );
    for (name, why) in &skipped {
        stderr!("skipped {name}: {why}");
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
    let probe = dir.join(".rigidlab-write-test");
    std::fs::write(&probe, b"")
        .and_then(|()| std::fs::remove_file(&probe))
        .map_err(|e| {
            format!("error: cannot write in {d}: {e}\n  help: give a folder you can write to")
        })
}

fn write_csv(path: &Path, studies: &[LevelStudy]) -> Result<(), String> {
    let mut w = csv::Writer::from_path(path).map_err(|e| e.to_string())?;
    for st in studies {
        for r in &st.rows {
            w.serialize(r).map_err(|e| e.to_string())?;
        }
    }
    // A study with no level still gets its header.
    if studies.iter().all(|s| s.rows.is_empty()) {
        drop(w);
        std::fs::write(path, format!("{}\n", CSV_COLUMNS.join(","))).map_err(|e| e.to_string())?;
        return Ok(());
    }
    w.flush().map_err(|e| e.to_string())
}
