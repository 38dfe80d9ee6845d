//! What `grade` writes: grades.csv (one row per answer), the gradebook (one row per student,
//! the columns a learning-management system imports), and the summary per question.

use super::class::{Assigned, Graded, Verdict};
use std::collections::BTreeMap;

/// grades.csv's header: the file's first line.
pub const GRADES_HEADER: [&str; 12] = [
    "line",
    "student",
    "level",
    "question",
    "answer",
    "value",
    "expected",
    "unit",
    "verdict",
    "rel_error",
    "variant",
    "variant_passed",
];

/// grades.csv: one row per graded answer, in the order of answers.csv.
pub fn grades_csv(levels: &[Assigned], graded: &[Graded]) -> Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let err = |e: csv::Error| e.to_string();
    w.write_record(GRADES_HEADER).map_err(err)?;
    for g in graded {
        let num = |x: Option<f64>| x.map(|v| format!("{v}")).unwrap_or_default();
        w.write_record([
            g.line.to_string(),
            g.student.clone(),
            levels[g.level].name.clone(),
            g.question.clone(),
            g.answer.clone(),
            num(g.value),
            format!("{}", g.expected),
            g.unit.clone(),
            g.verdict.text(),
            num(g.rel_error),
            g.variant.clone(),
            g.variant_passed.map(|p| p.to_string()).unwrap_or_default(),
        ])
        .map_err(err)?;
    }
    w.into_inner().map_err(|e| e.to_string())
}

/// The gradebook's first five columns: those of a Canvas gradebook export, the file Canvas's
/// import reads back (the student's id goes in `SIS User ID`; Moodle maps its import from that
/// column to the users' ID number). docs/teacher.md#grading-a-class says how to import it.
pub const GRADEBOOK_IDS: [&str; 5] = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"];

/// The gradebook's last column: the points of every level.
pub const TOTAL: &str = "rigidlab total";

/// The `Student` cell of the gradebook's second row, the points possible of each level (its
/// question count) and of the total.
pub const POINTS_POSSIBLE: &str = "Points Possible";

/// The gradebook: the points possible of each level and of the total, then a row per student
/// named in answers.csv (sorted by id; one whose every row was bad scores 0), their points per
/// level (one per question answered right; a question not answered scores 0) and their total.
pub fn gradebook_csv(
    levels: &[Assigned],
    students: &[&str],
    graded: &[Graded],
) -> Result<Vec<u8>, String> {
    let mut points: BTreeMap<&str, Vec<u32>> = students
        .iter()
        .map(|s| (*s, vec![0; levels.len()]))
        .collect();
    for g in graded {
        let row = points
            .entry(g.student.as_str())
            .or_insert_with(|| vec![0; levels.len()]);
        if g.verdict == Verdict::Correct {
            row[g.level] += 1;
        }
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    let err = |e: csv::Error| e.to_string();
    let mut header: Vec<String> = GRADEBOOK_IDS.iter().map(|s| s.to_string()).collect();
    header.extend(levels.iter().map(level_column));
    header.push(TOTAL.to_string());
    w.write_record(&header).map_err(err)?;
    // The points possible, as a Canvas export's second row writes them (Canvas's import reads
    // the row whose first cell is "Points Possible" as each new assignment's points).
    let possible: Vec<usize> = levels.iter().map(|l| l.nominal.questions.len()).collect();
    let mut row = vec![POINTS_POSSIBLE.to_string()];
    row.extend(std::iter::repeat_n(String::new(), GRADEBOOK_IDS.len() - 1));
    row.extend(possible.iter().map(usize::to_string));
    row.push(possible.iter().sum::<usize>().to_string());
    w.write_record(&row).map_err(err)?;
    for (student, pts) in &points {
        let mut rec = vec![
            student.to_string(),
            String::new(),
            student.to_string(),
            String::new(),
            String::new(),
        ];
        rec.extend(pts.iter().map(u32::to_string));
        rec.push(pts.iter().sum::<u32>().to_string());
        w.write_record(&rec).map_err(err)?;
    }
    w.into_inner().map_err(|e| e.to_string())
}

/// A level's gradebook column: its name, without parentheses (Canvas reads `Name (123)` as the
/// assignment of id 123; a name without them becomes a new assignment).
fn level_column(l: &Assigned) -> String {
    l.name.replace(['(', ')'], "")
}

/// The points possible of the whole assignment: one per question.
pub fn total_questions(levels: &[Assigned]) -> usize {
    levels.iter().map(|l| l.nominal.questions.len()).sum()
}

/// The summary per question: answers, the share right, unreadable ones, and each typical
/// mistake matched with its count.
pub fn summary(levels: &[Assigned], graded: &[Graded]) -> String {
    let mut s = String::new();
    for (li, l) in levels.iter().enumerate() {
        s += &format!("{}\n", l.name);
        for q in &l.nominal.questions {
            let of: Vec<&Graded> = graded
                .iter()
                .filter(|g| g.level == li && g.question == q.id)
                .collect();
            let count = |v: &dyn Fn(&Verdict) -> bool| of.iter().filter(|g| v(&g.verdict)).count();
            let right = count(&|v| *v == Verdict::Correct);
            let unreadable = count(&|v| *v == Verdict::Unreadable);
            let share = if of.is_empty() {
                "-".to_string()
            } else {
                format!("{:.0}%", 100.0 * right as f64 / of.len() as f64)
            };
            s += &format!(
                "  {:<14} {:>4} answers  {:>4} correct ({share})  {:>4} wrong  {:>4} unreadable\n",
                q.id,
                of.len(),
                right,
                of.len() - right - unreadable,
                unreadable
            );
            let mut mistakes: BTreeMap<&str, usize> = BTreeMap::new();
            for g in &of {
                if let Verdict::Mistake(m) = &g.verdict {
                    *mistakes.entry(m.as_str()).or_default() += 1;
                }
            }
            for (m, n) in mistakes {
                s += &format!("      {n:>4} x typical mistake: {m}\n");
            }
        }
    }
    s
}
