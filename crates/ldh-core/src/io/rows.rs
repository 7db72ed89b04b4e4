//! The reader's row stage (SPEC §2): the data rows after the header, parsed into columns of raw
//! numbers (the file's units, before the format's scale), each row remembering its file line.
//! A row with the wrong number of fields, a cell that is not a finite number or a magnitude
//! beyond [`super::MAX_ABS_SIGNAL`] is refused with FILE:LINE[:COL].

use std::path::Path;

use super::columns::Columns;
use super::format::{FormatSpec, TimeUnit};
use super::reader::reserve;
use super::text::{parse_number, split_fields, CellAt};
use super::timebase::parse_iso8601;
use crate::error::{LdhError, Location, Result};

/// The data rows, column by column, as read.
pub(super) struct Rows {
    /// The time cells in the format's time unit (ISO 8601: seconds since 1970); empty when the
    /// format has no time column.
    pub time_raw: Vec<f64>,
    /// acc x, y, z then gyro x, y, z, in the file's units before the format's scale.
    pub raw: [Vec<f64>; 6],
    /// The 1-based file line of each row.
    pub row_lines: Vec<u64>,
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

/// Parse the data rows `lines[first_data..]` (numbered lines, see
/// [`super::text::numbered_lines`]); blank lines and comment lines are skipped. The column
/// buffers are reserved fallibly from the number of lines.
pub(super) fn parse_rows(
    lines: &[(u64, &str)],
    first_data: usize,
    layout: &Layout,
) -> Result<Rows> {
    let (path, spec, delim) = (layout.path, layout.spec, layout.delim);
    let expected = layout.header_fields.len();
    let mut rows = Rows {
        time_raw: Vec::new(),
        raw: Default::default(),
        row_lines: Vec::new(),
    };
    let n_rows = lines.len().saturating_sub(first_data);
    reserve(&mut rows.time_raw, n_rows, path)?;
    reserve(&mut rows.row_lines, n_rows, path)?;
    for r in &mut rows.raw {
        reserve(r, n_rows, path)?;
    }
    let mut fields: Vec<&str> = Vec::with_capacity(expected);
    for &(lineno, line) in lines.iter().skip(first_data) {
        let trimmed = line.trim();
        if trimmed.is_empty()
            || spec
                .comment_prefixes
                .iter()
                .any(|p| trimmed.starts_with(p.as_str()))
        {
            continue;
        }
        split_fields(line, delim, &mut fields);
        if fields.len() != expected {
            // Tolerate one trailing empty field (a trailing delimiter).
            let trailing_empty =
                fields.len() == expected + 1 && fields.last().is_some_and(|f| f.is_empty());
            if !trailing_empty {
                return Err(field_count_error(lines, lineno, line, &fields, layout));
            }
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
    }
    Ok(rows)
}

/// The [`LdhError::FieldCount`] of row `lineno` (its `fields` split from `line`), with a hint
/// when the cause is likely: decimal commas in a comma-separated file, or a truncated last line.
fn field_count_error(
    lines: &[(u64, &str)],
    lineno: u64,
    line: &str,
    fields: &[&str],
    layout: &Layout,
) -> LdhError {
    let expected = layout.header_fields.len();
    // Decimal commas in a comma-separated file double the fields.
    let hint = if layout.delim == b','
        && fields.len() > expected
        && !line.contains('.')
        && fields.iter().all(|f| f.parse::<f64>().is_ok())
    {
        "; the row has no '.' but more commas than the header: decimal commas in a comma-separated file? Export with '.' as decimal separator or ';' as delimiter".to_string()
    } else if fields.len() < expected
        && lines
            .iter()
            .rev()
            .find(|(_, l)| !l.trim().is_empty())
            .is_some_and(|(n, _)| *n == lineno)
    {
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
            value: cell.chars().take(60).collect(),
        });
    }
    Ok(v)
}
