//! `rigidlab grade ASSIGNMENT answers.csv --out grades.csv`: a class's answers graded, each
//! against its student's own variant of its level, by the rule of `check --answer`; grades.csv
//! (one row per answer), a gradebook a learning-management system imports, and a summary per
//! question. Bad rows are reported with their line and column and never stop the others.

use super::{bad, SolverArgs};
use crate::level::{self, Scene};
use crate::runner;
use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

mod answers;
mod class;
mod output;

use class::{Assigned, Class};

/// Exit code when some rows were bad: reported, the others graded and written.
const BAD_ROWS: u8 = 1;

pub struct GradeArgs<'a> {
    pub assignment: &'a Path,
    pub answers: &'a Path,
    pub out: &'a Path,
    pub gradebook: Option<&'a Path>,
    pub no_run: bool,
}

pub fn grade(a: GradeArgs) -> ExitCode {
    let gradebook = a
        .gradebook
        .map_or_else(|| gradebook_beside(a.out), Path::to_path_buf);
    // Nothing is written over: both names must be free before anything is graded.
    if let Err(e) = refuse_taken(&[a.out, &gradebook]) {
        return bad(e);
    }
    let levels = match assignment_levels(a.assignment) {
        Ok(l) => l,
        Err(e) => return bad(e),
    };
    let file = a.answers.display().to_string();
    let bytes = match std::fs::read(a.answers) {
        Ok(b) => b,
        Err(e) => return bad(format!("{file}: error: cannot read the answers: {e}")),
    };
    let (layout, rows, mut bad_rows) = match answers::read(&file, &bytes) {
        Ok(r) => r,
        Err(e) => return bad(e),
    };
    let opts = match SolverArgs::default().options() {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let run = |scene: &Scene| -> Result<bool, String> {
        SolverArgs::default()
            .budget(scene, &opts)
            .map_err(|e| e.to_string())?;
        runner::run_graded(scene, &opts, &HashMap::new(), |_| {})
            .map(|r| r.passed)
            .map_err(|e| e.to_string())
    };
    let mut class = Class::new(levels, (!a.no_run).then_some(&run as _));
    let mut graded = Vec::new();
    for row in &rows {
        let (g, b) = class.grade(&layout, row);
        graded.extend(g);
        bad_rows.extend(b);
    }
    bad_rows.sort_by_key(|b| b.line);
    let students: Vec<&str> = rows.iter().map(|r| r.student.as_str()).collect();
    let written = output::grades_csv(&class.levels, &graded)
        .and_then(|g| write_fresh(a.out, &g))
        .and_then(|()| output::gradebook_csv(&class.levels, &students, &graded))
        .and_then(|b| write_fresh(&gradebook, &b));
    if let Err(e) = written {
        return bad(e);
    }
    for w in &class.warnings {
        stderr!("warning: {w}");
    }
    for b in &bad_rows {
        let col = b.column.map(|c| format!(":{c}")).unwrap_or_default();
        stderr!("{file}:{}{col}: error: {}", b.line, b.message);
    }
    let text = report(&a, &gradebook, &class, &graded, bad_rows.len());
    let code = if bad_rows.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(BAD_ROWS)
    };
    crate::report::print(&text, code)
}

/// The summary printed: per question, then the files written and the rows left out.
fn report(
    a: &GradeArgs,
    gradebook: &Path,
    class: &Class,
    graded: &[class::Graded],
    bad_rows: usize,
) -> String {
    let students: std::collections::BTreeSet<&str> =
        graded.iter().map(|g| g.student.as_str()).collect();
    let mut s = format!(
        "grade {}: {} answers of {} students on {} levels ({} points possible), {} variants made{}\n",
        a.assignment.display(),
        graded.len(),
        students.len(),
        class.levels.len(),
        output::total_questions(&class.levels),
        class.variants_made(),
        if a.no_run { "" } else { " and run" }
    );
    s += &output::summary(&class.levels, graded);
    s += &format!("wrote {} and {}\n", a.out.display(), gradebook.display());
    if bad_rows > 0 {
        s += &format!("{bad_rows} rows could not be graded (above, on stderr, by line)\n");
    }
    s
}

/// The gradebook's default name: `NAME_gradebook.csv` beside `NAME.csv`.
fn gradebook_beside(out: &Path) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(|| "grades".into(), |s| s.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}_gradebook.csv"))
}

/// An error when one of the outputs exists (or two are one name): `grade` never writes over a
/// file, since a grades file is the teacher's record, not a cache rigidlab may rewrite.
fn refuse_taken(outs: &[&Path]) -> Result<(), String> {
    if outs.len() == 2 && outs[0] == outs[1] {
        return Err(format!(
            "error: --out and --gradebook are both {}\n  help: give the gradebook another name",
            outs[0].display()
        ));
    }
    for out in outs {
        if std::fs::symlink_metadata(out).is_ok() {
            return Err(format!(
                "{}: error: the file exists; `rigidlab grade` never writes over a file\n  help: give --out (or --gradebook) a new name, or move or delete the old file yourself",
                out.display()
            ));
        }
    }
    Ok(())
}

/// Writes `bytes` as `dest` whole, only if no file has its name (made meanwhile).
fn write_fresh(dest: &Path, bytes: &[u8]) -> Result<(), String> {
    let mut p = crate::files::Pending::create(dest)
        .map_err(|e| format!("{}: error: cannot write: {e}", dest.display()))?;
    p.write_all(bytes)
        .and_then(|()| p.commit_fresh())
        .map_err(|e| format!("{}: error: cannot write: {e}", dest.display()))
}

/// The assignment's levels: an assignment manifest (`assignment.ron`, or a folder holding one)
/// in its order; a level file; or a folder's `*.ron` files (recursively, sorted). Each is named
/// by its path from the folder without `.ron`.
fn assignment_levels(path: &Path) -> Result<Vec<Assigned>, String> {
    use level::assignment::{Assignment, MANIFEST};
    let manifest = if path.is_dir() {
        path.join(MANIFEST).is_file().then(|| path.join(MANIFEST))
    } else {
        (path.file_name().is_some_and(|n| n == MANIFEST)).then(|| path.to_path_buf())
    };
    let (folder, files) = match manifest {
        Some(m) => {
            let a = Assignment::load(&m).map_err(|e| e.to_string())?;
            let folder = match a.folder() {
                f if f.as_os_str().is_empty() => PathBuf::from("."),
                f => f.to_path_buf(),
            };
            (folder, a.levels)
        }
        None => {
            let files = level::collect_files(&[path.to_path_buf()]).map_err(|e| e.to_string())?;
            (path.to_path_buf(), files)
        }
    };
    if files.is_empty() {
        return Err(format!(
            "{}: error: no level files (*.ron) found\n  help: give a level file or a folder of levels",
            path.display()
        ));
    }
    let mut errors = Vec::new();
    let mut levels = Vec::new();
    for f in &files {
        let name = if folder.is_dir() {
            f.strip_prefix(&folder).unwrap_or(f).with_extension("")
        } else {
            PathBuf::from(f.file_stem().unwrap_or_default())
        };
        let name = name
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect::<Vec<_>>()
            .join("/");
        match Assigned::load(name, f) {
            Ok(l) => levels.push(l),
            Err(e) => errors.push(e),
        }
    }
    if errors.is_empty() {
        Ok(levels)
    } else {
        Err(errors.join("\n"))
    }
}
