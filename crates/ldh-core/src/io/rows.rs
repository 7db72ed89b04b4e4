//! The reader's row stage (SPEC §2): the data rows after the header, parsed into columns of raw
//! numbers (the file's units, before the format's scale), each row remembering its file line.
//! A row with the wrong number of fields, a cell that is not a finite number or a magnitude
//! beyond [`super::MAX_ABS_SIGNAL`] is refused with FILE:LINE[:COL].

use std::io::BufRead;
use std::path::Path;

use super::columns::Columns;
use super::format::{FormatSpec, TimeUnit};
use super::limits::reserve;
use super::number::{parse_number, CellAt};
use super::start_time::parse_iso8601;
use super::text::{split_fields, Lines};
use crate::error::{LdhError, Location, Result};

/// The data rows, column by column, as read.
pub(super) struct Rows {
    /// The time cells in the format's time unit (ISO 8601: seconds since 1970); empty when the
    /// format has no time column.
    pub time_raw: Vec<f64>,
    /// acc x, y, z then gyro x, y, z, in the file's units before the format's scale.
    pub raw: [Vec<f64>; 6],
    /// The 1-based file line of each row.
    pub row_lines: RowLines,
}

/// The 1-based file line of each row, stored as runs of consecutive lines (a few bytes for a
/// whole file without comment or blank lines between its rows).
#[derive(Debug, Default)]
pub(super) struct RowLines {
    /// (first row, its line) of each run.
    runs: Vec<(usize, u64)>,
    /// Rows.
    n: usize,
}

impl RowLines {
    /// Append the next row's line.
    pub fn push(&mut self, line: u64) {
        let follows = self
            .runs
            .last()
            .is_some_and(|&(r, l)| l + (self.n - r) as u64 == line);
        if !follows {
            self.runs.push((self.n, line));
        }
        self.n += 1;
    }

    /// The line of row `i` (< [`Self::len`]).
    pub fn get(&self, i: usize) -> u64 {
        let k = self.runs.partition_point(|&(r, _)| r <= i) - 1;
        let (r, l) = self.runs[k];
        l + (i - r) as u64
    }

    /// Rows.
    pub fn len(&self) -> usize {
        self.n
    }
}

impl FromIterator<u64> for RowLines {
    fn from_iter<I: IntoIterator<Item = u64>>(iter: I) -> Self {
        let mut r = RowLines::default();
        for l in iter {
            r.push(l);
        }
        r
    }
}

/// Where and how to read the data rows: the header's fields, the delimiter and the columns.
pub(super) struct Layout<'a> {
    /// The file (for messages).
    pub path: &'a Path,
    /// The format.
    pub spec: &'a FormatSpec,
    /// The delimiter byte.
    pub delim: u8,
    /// The header's field names (`#n` when the file has no header row).
    pub header_fields: &'a [String],
    /// The columns the format reads.
    pub cols: Columns,
}

/// An empty vector with `v`'s allocation, for borrows of another lifetime.
fn recycle<'b>(mut v: Vec<&str>) -> Vec<&'b str> {
    v.clear();
    v.into_iter().map(|_| "").collect()
}

/// Parse the data rows: `first` (a row already read, for a file without a header row), then
/// the lines left in `lines`; blank lines and comment lines are skipped. Only the format's
/// columns are kept; the buffers grow fallibly. More than `max_rows` rows are refused
/// ([`LdhError::TooManySamples`], the rows left counted without parsing them).
pub(super) fn parse_rows<R: BufRead>(
    lines: &mut Lines<R>,
    first: Option<(u64, String)>,
    layout: &Layout,
    max_rows: usize,
) -> Result<Rows> {
    let mut rows = Rows {
        time_raw: Vec::new(),
        raw: Default::default(),
        row_lines: RowLines::default(),
    };
    let mut fields: Vec<&str> = Vec::with_capacity(layout.header_fields.len() + 1);
    if let Some((lineno, line)) = &first {
        if !parse_row(*lineno, line, &mut fields, &mut rows, layout, max_rows)? {
            let line = line.clone();
            return Err(field_count_error(lines, *lineno, &line, layout));
        }
    }
    loop {
        let mut f = recycle(fields);
        let Some((lineno, line)) = lines.next_line()? else {
            return Ok(rows);
        };
        match parse_row(lineno, line, &mut f, &mut rows, layout, max_rows) {
            Ok(true) => {}
            Ok(false) => {
                let line = line.to_string();
                return Err(field_count_error(lines, lineno, &line, layout));
            }
            Err(LdhError::TooManySamples { path, limit, .. }) => {
                let left = lines.count_rows_left(&layout.spec.comment_prefixes)?;
                return Err(LdhError::TooManySamples {
                    path,
                    rows: limit as u64 + 1 + left,
                    limit,
                });
            }
            Err(e) => return Err(e),
        }
        fields = recycle(f);
    }
}

/// Parse one line into `rows` (`fields`: a reused buffer). `Ok(false)`: the line has the wrong
/// number of fields (one trailing empty field, a trailing delimiter, is tolerated).
fn parse_row<'l>(
    lineno: u64,
    line: &'l str,
    fields: &mut Vec<&'l str>,
    rows: &mut Rows,
    layout: &Layout,
    max_rows: usize,
) -> Result<bool> {
    let trimmed = line.trim();
    let Some(&first) = trimmed.as_bytes().first() else {
        return Ok(true);
    };
    // the first byte before the whole prefix: most lines start with a digit, no prefix does
    let comment = |p: &String| {
        p.as_bytes().first().is_none_or(|&c| c == first) && trimmed.starts_with(p.as_str())
    };
    if layout.spec.comment_prefixes.iter().any(comment) {
        return Ok(true);
    }
    split_fields(line, layout.delim, fields);
    let expected = layout.header_fields.len();
    if fields.len() != expected {
        let trailing_empty =
            fields.len() == expected + 1 && fields.last().is_some_and(|f| f.is_empty());
        if !trailing_empty {
            return Ok(false);
        }
    }
    let n = rows.row_lines.len();
    if n >= max_rows {
        return Err(LdhError::TooManySamples {
            path: layout.path.to_path_buf(),
            rows: n as u64 + 1,
            limit: max_rows,
        });
    }
    if n == rows.raw[0].capacity() {
        grow(rows, layout)?;
    }
    if let Some(tc) = layout.cols.time {
        rows.time_raw
            .push(parse_time_cell(fields[tc], lineno, tc, layout)?);
    }
    let signal_cols = layout.cols.acc.iter().chain(layout.cols.gyro.iter());
    for (k, &c) in signal_cols.enumerate() {
        let v = parse_signal_cell(fields[c], lineno, c, layout)?;
        rows.raw[k].push(v);
    }
    rows.row_lines.push(lineno);
    Ok(true)
}

/// Double the room of every column (at least 4096 rows), fallibly: a file too large for the
/// memory is this file's [`LdhError::OutOfMemory`], not an abort.
fn grow(rows: &mut Rows, layout: &Layout) -> Result<()> {
    let more = rows.raw[0].capacity().max(4096);
    if layout.cols.time.is_some() {
        reserve(&mut rows.time_raw, more, layout.path)?;
    }
    for r in &mut rows.raw {
        reserve(r, more, layout.path)?;
    }
    Ok(())
}

/// The [`LdhError::FieldCount`] of row `lineno` (`line`), with a hint when the cause is
/// likely: decimal commas in a comma-separated file, or a truncated last line (the lines left
/// in `lines` are read to know).
fn field_count_error<R: BufRead>(
    lines: &mut Lines<R>,
    lineno: u64,
    line: &str,
    layout: &Layout,
) -> LdhError {
    let expected = layout.header_fields.len();
    let mut fields = Vec::new();
    split_fields(line, layout.delim, &mut fields);
    // Decimal commas in a comma-separated file double the fields; one such cell adds one.
    let numbers = fields.iter().all(|f| f.parse::<f64>().is_ok());
    let hint = if layout.delim == b',' && fields.len() > expected && numbers && !line.contains('.')
    {
        "; the row has no '.' but more commas than the header: decimal commas in a comma-separated file? Export with '.' as decimal separator or ';' as delimiter".to_string()
    } else if layout.delim == b',' && fields.len() > expected && numbers {
        decimal_comma_hint(&fields, fields.len() - expected)
    } else if fields.len() < expected && lines.rest_is_blank().unwrap_or(false) {
        "; it is the last line: the file looks truncated (an interrupted export or copy?)"
            .to_string()
    } else {
        String::new()
    };
    LdhError::FieldCount {
        loc: Location::line(layout.path, lineno),
        found: fields.len(),
        expected,
        hint,
    }
}

/// The hint for a row of numbers with `extra` fields more than the header: a decimal comma is
/// likely, at the first integer cell followed by a cell of digits alone (`1,25` split into `1`
/// and `25`), named with its column.
fn decimal_comma_hint(fields: &[&str], extra: usize) -> String {
    let digits = |c: &str| !c.is_empty() && c.bytes().all(|b| b.is_ascii_digit());
    let at = fields.windows(2).position(|w| {
        let a = w[0].trim_start_matches(['-', '+']);
        digits(a) && digits(w[1])
    });
    let place = match at {
        Some(i) => format!(
            " ('{},{}' at column {} reads as two cells)",
            fields[i],
            fields[i + 1],
            i + 1
        ),
        None => String::new(),
    };
    format!(
        "; the row holds numbers only, {extra} more than the header: a decimal comma in {extra} cell(s) is likely{place}. Write that value with '.' (or export with ';' as delimiter)"
    )
}

/// The time cell of column `tc` (0-based) on line `lineno`, in the format's time unit (an
/// ISO 8601 timestamp as seconds since 1970).
fn parse_time_cell(cell: &str, lineno: u64, tc: usize, layout: &Layout) -> Result<f64> {
    let (path, spec) = (layout.path, layout.spec);
    match spec.time.unit {
        TimeUnit::Iso8601 => parse_iso8601(cell).ok_or_else(|| LdhError::NotANumber {
            loc: Location::cell(path, lineno, tc + 1),
            column: layout.header_fields[tc].clone(),
            value: cell.to_string(),
            hint: "; expected an ISO 8601 timestamp like 2024-03-01T10:15:02.250".into(),
        }),
        _ => {
            let at = CellAt {
                path,
                line: lineno,
                col: tc,
                name: &layout.header_fields[tc],
            };
            parse_number(cell, spec.decimal, layout.delim, &at)
        }
    }
}

/// The signal cell of column `c` (0-based) on line `lineno`, refused beyond
/// [`super::MAX_ABS_SIGNAL`] ([`LdhError::OutOfRange`]).
fn parse_signal_cell(cell: &str, lineno: u64, c: usize, layout: &Layout) -> Result<f64> {
    let at = CellAt {
        path: layout.path,
        line: lineno,
        col: c,
        name: &layout.header_fields[c],
    };
    let v = parse_number(cell, layout.spec.decimal, layout.delim, &at)?;
    if v.abs() > super::MAX_ABS_SIGNAL {
        return Err(LdhError::OutOfRange {
            loc: Location::cell(layout.path, lineno, c + 1),
            column: layout.header_fields[c].clone(),
            value: cell.to_string(),
        });
    }
    Ok(v)
}
