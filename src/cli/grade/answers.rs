//! A class's answers file, `answers.csv`: a header naming the columns `student`, `level`,
//! `question` and `answer` (in any order, any case, other columns ignored), then one answer a
//! row. Read with the `csv` crate (quoted fields, commas inside quotes, CRLF line ends, a
//! spreadsheet's byte-order mark), each row with its line so a bad one is reported where the
//! teacher can find it.

/// The four columns, as the header names them.
pub const COLUMNS: [&str; 4] = ["student", "level", "question", "answer"];

/// One answer as written: its fields trimmed, and where it is.
#[derive(Debug, Clone)]
pub struct Row {
    /// The line of answers.csv the row starts on (1 = the header).
    pub line: u64,
    pub student: String,
    pub level: String,
    pub question: String,
    pub answer: String,
}

/// A row that cannot be graded: its line, the column at fault (1-based, when one is), why.
#[derive(Debug, Clone, PartialEq)]
pub struct BadRow {
    pub line: u64,
    pub column: Option<usize>,
    pub message: String,
}

/// Where each of the four columns is in a row (0-based).
#[derive(Debug, Clone, Copy)]
pub struct Layout {
    pub at: [usize; 4],
}

impl Layout {
    /// The 1-based column of `name` (one of [`COLUMNS`]).
    pub fn column(&self, name: &str) -> Option<usize> {
        COLUMNS
            .iter()
            .position(|c| *c == name)
            .map(|i| self.at[i] + 1)
    }
}

/// The rows of answers.csv and those that cannot be read; an error (the file as a whole cannot
/// be read: not UTF-8, no header, a column missing) with how to fix it.
pub fn read(file: &str, bytes: &[u8]) -> Result<(Layout, Vec<Row>, Vec<BadRow>), String> {
    let bytes = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
    if let Err(e) = std::str::from_utf8(bytes) {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        return Err(format!(
            "{file}:{line}: error: the answers file is not UTF-8 text\n  help: save it as CSV UTF-8 (a spreadsheet's \"CSV UTF-8\" format)"
        ));
    }
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(bytes);
    let header = reader
        .headers()
        .map_err(|e| format!("{file}:1: error: the header cannot be read: {e}"))?
        .clone();
    let layout = layout(file, &header)?;
    let mut rows = Vec::new();
    let mut bad = Vec::new();
    // The csv crate's own line count is one short after CRLF line ends (csv 1.4: a spreadsheet's
    // export numbered 8 for its line 9): lines are counted here from the record's byte offset.
    let line_at = |p: Option<&csv::Position>| {
        p.map_or(0, |p| {
            // A record's offset may sit on the line end before it (after CRLF): its first
            // character is past any line ends there.
            let mut end = (p.byte() as usize).min(bytes.len());
            while end < bytes.len() && matches!(bytes[end], b'\r' | b'\n') {
                end += 1;
            }
            1 + bytes[..end].iter().filter(|&&b| b == b'\n').count() as u64
        })
    };
    for record in reader.records() {
        match record {
            Ok(r) => match row(&layout, &r, line_at(r.position())) {
                Ok(Some(row)) => rows.push(row),
                Ok(None) => {}
                Err(b) => bad.push(b),
            },
            Err(e) => bad.push(BadRow {
                line: line_at(e.position()),
                column: None,
                message: format!("the row cannot be read: {e}"),
            }),
        }
    }
    Ok((layout, rows, bad))
}

/// Where the header puts each column; an error naming those missing.
fn layout(file: &str, header: &csv::StringRecord) -> Result<Layout, String> {
    let names: Vec<String> = header.iter().map(|h| h.trim().to_lowercase()).collect();
    let mut at = [0; 4];
    let mut missing = Vec::new();
    for (i, want) in COLUMNS.iter().enumerate() {
        match names.iter().position(|n| n == want) {
            Some(k) => at[i] = k,
            None => missing.push(*want),
        }
    }
    if missing.is_empty() {
        return Ok(Layout { at });
    }
    Err(format!(
        "{file}:1: error: the header has no column {} (it has: {})\n  help: the first line names the columns: student,level,question,answer",
        missing.join(", "),
        header.iter().collect::<Vec<_>>().join(", ")
    ))
}

/// One record as a row; None for a blank line; a bad row when a field is missing or empty.
fn row(layout: &Layout, r: &csv::StringRecord, line: u64) -> Result<Option<Row>, BadRow> {
    if r.iter().all(str::is_empty) {
        return Ok(None);
    }
    let mut fields = [""; 4];
    for (i, name) in COLUMNS.iter().enumerate() {
        match r.get(layout.at[i]) {
            Some(v) if !v.is_empty() => fields[i] = v,
            got => {
                return Err(BadRow {
                    line,
                    column: Some(layout.at[i] + 1),
                    message: if got.is_none() {
                        format!(
                            "the row has {} fields and no `{name}` (column {})",
                            r.len(),
                            layout.at[i] + 1
                        )
                    } else {
                        format!("the `{name}` field is empty")
                    },
                })
            }
        }
    }
    Ok(Some(Row {
        line,
        student: fields[0].to_string(),
        level: fields[1].to_string(),
        question: fields[2].to_string(),
        answer: fields[3].to_string(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_in_any_order_quoted_fields_and_lines() {
        let text = "\u{feff}Answer,Student,Question,Level,notes\r\n\
                    \"4,2 m/s\",s1,speed,incline_friction_param,\"a, b\"\r\n\
                    \r\n\
                    3.1,s2,speed\r\n\
                    1.0,s3,distance,incline_friction_param\r\n";
        let (layout, rows, bad) = read("a.csv", text.as_bytes()).unwrap();
        assert_eq!(layout.at, [1, 3, 2, 0]);
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].answer, "4,2 m/s");
        assert_eq!(rows[0].line, 2);
        assert_eq!(rows[1].line, 5);
        // Line 4 lacks the level: reported at its column (the 4th).
        assert_eq!(bad.len(), 1);
        assert_eq!((bad[0].line, bad[0].column), (4, Some(4)));
    }

    #[test]
    fn a_missing_column_is_an_error_of_the_file() {
        let e = read("a.csv", b"student,level,answer\ns1,x,1\n").unwrap_err();
        assert!(
            e.starts_with("a.csv:1: error: the header has no column question"),
            "{e}"
        );
    }

    #[test]
    fn bytes_that_are_not_utf8_are_located() {
        let e = read("a.csv", b"student,level,question,answer\ns1,x,q,\xff\n").unwrap_err();
        assert!(e.starts_with("a.csv:2: error:"), "{e}");
    }
}
