//! Finding the header row of a file while it streams (docs/input.md, "Column maps"): the first
//! header-like row whose columns a given or detected format resolves ([`find_header`]), a file
//! without a header row when a map gives every column by number, and the closest built-in's
//! missing columns when none fits. Column resolution itself is in `columns.rs`.

use std::io::BufRead;
use std::path::Path;

use super::columns::{
    all_by_index, describe_missing, resolve, unit_suffixed, Columns, Missing, Unresolved,
};
use super::format::{Delimiter, FormatSpec};
use super::infer::Infer;
use super::labelled::{
    all_inferred, kinds_row, labelled, partial, stated_unit, with_units_row, without_units, Found,
    Labelled,
};
use super::start_time::{start_in_comment, DateTime};
use super::text::{detect_delimiter, split_header, Lines};
use super::units::Unit;
use crate::error::{LdhError, Location, Result};

/// The header row found in a file and the format that reads it.
#[derive(Debug, Clone)]
pub(crate) struct Header {
    /// 1-based line of the header row; of the first data row when the file has no header row
    /// (`has_row` false).
    pub line: u64,
    /// The format (a detected built-in, the given one, or `ldh` adapted to unit-suffixed names).
    pub spec: FormatSpec,
    /// Field delimiter.
    pub delim: u8,
    /// Column names (`column 1`, ... for a file without a header row).
    pub fields: Vec<String>,
    /// Where the format's columns are.
    pub cols: Columns,
    /// The file has a header row (false only for maps that give every column by number).
    pub has_row: bool,
    /// The first data row when it was read ahead (its line and text), to be read as data: in a
    /// file without a header row, or under recognised names looked under for units.
    pub first_row: Option<(u64, String)>,
    /// Delimiter named by a `sep=` line.
    pub sep_line: Option<u8>,
    /// Where the units of the columns read come from.
    pub units_from: UnitsFrom,
    /// The start date and time a line above the header states (`// Start Time: ...`).
    pub start: Option<DateTime>,
    /// The units the header does not state, to infer from the signal (`infer.rs`).
    pub infer: Infer,
}

/// Where the units of the columns read come from (shown per column by `ldh inspect`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum UnitsFrom {
    /// The format (a built-in or the user's column map).
    Format,
    /// The names' suffixes (`acc_x_mps2`, `time_ms`).
    NameSuffix,
    /// The header's names (`Acc_X [m/s^2]`, `GyrX/deg/s`).
    Labels,
    /// The row of units under the names, at this 1-based line.
    UnitsRow(u64),
    /// Nowhere: every unit is inferred from the signal.
    Signal,
}

fn is_number(f: &str) -> bool {
    f.parse::<f64>().is_ok() || f.replace(',', ".").parse::<f64>().is_ok()
}

/// A row that may be a header: at least three fields, at least three of them not numbers.
fn header_like(fields: &[String]) -> bool {
    fields.len() >= 3 && fields.iter().filter(|f| !is_number(f)).count() >= 3
}

/// Find the header row of `lines`, reading up to it, and the format that reads it:
/// the given format, or the first detected built-in whose columns are all in a row (the `ldh`
/// map also in its unit-suffixed form). Refuses a row with a duplicated column; with a given
/// format, the first header-like row missing columns; otherwise says which columns the closest
/// built-in lacks in the first header-like row.
pub(super) fn find_header<R: BufRead>(
    lines: &mut Lines<R>,
    format: Option<&FormatSpec>,
    path: &Path,
    notes: &mut Vec<String>,
) -> Result<Header> {
    let detected;
    let candidates: Vec<&FormatSpec> = match format {
        Some(f) => vec![f],
        None => {
            detected = FormatSpec::detected();
            detected.iter().collect()
        }
    };
    let mut sep_line: Option<u8> = None;
    let mut first_row = String::new();
    // Detection mode: the closest format for the first header-like row, for the message.
    let mut closest: Option<Closest> = None;
    let mut all_blank = true;
    // A row read ahead (a possible units row that was not one) and read next.
    let mut pending: Option<(u64, String)> = None;
    let mut start: Option<DateTime> = None;
    loop {
        let (lineno, line) = match pending.take() {
            Some(p) => p,
            None => match lines.next_line()? {
                Some((n, l)) => (n, l.to_string()),
                None => break,
            },
        };
        let line = line.as_str();
        let trimmed = line.trim();
        if trimmed.is_empty() {
            continue;
        }
        all_blank = false;
        if start.is_none() {
            start = start_in_comment(trimmed);
        }
        if let Some(sep) = sep_line_delimiter(trimmed) {
            sep_line = sep;
            notes.push(format!(
                "'sep=' line found: delimiter {:?}",
                sep_line.map(|b| b as char)
            ));
            continue;
        }
        if candidates.iter().any(|f| {
            f.comment_prefixes
                .iter()
                .any(|p| trimmed.starts_with(p.as_str()))
        }) {
            continue;
        }
        if first_row.is_empty() {
            first_row = trimmed.to_string();
        }
        for f in &candidates {
            let row = (lineno, line);
            match match_row(f, row, sep_line, format.is_some(), path, notes)? {
                RowMatch::Found(header) => return Ok(Header { start, ..*header }),
                RowMatch::No => {}
                RowMatch::Missing(missing, fields, delim_note) => {
                    // Only the first header-like row is described; among the formats,
                    // the one missing the fewest columns.
                    let replace = match &closest {
                        None => true,
                        Some(c) => c.at == lineno && missing.len() < c.missing.len(),
                    };
                    if replace {
                        closest = Some(Closest {
                            format: f,
                            missing,
                            at: lineno,
                            fields,
                            delim_note,
                        });
                    }
                }
            }
        }
        if format.is_none() {
            match try_labelled(lines, (lineno, line), sep_line, path, notes)? {
                (Some(header), _) => return Ok(Header { start, ..header }),
                (None, next) => pending = next,
            }
        }
    }
    Err(no_header(
        all_blank,
        closest,
        &candidates,
        format.is_some(),
        path,
        first_row,
    ))
}

/// What [`try_labelled`] found: the header, or none and the row it read ahead (to be read
/// next), if any.
type LabelledRow = (Option<Header>, Option<(u64, String)>);

/// The next non-blank line of `lines`, owned.
fn next_nonblank<R: BufRead>(lines: &mut Lines<R>) -> Result<Option<(u64, String)>> {
    loop {
        match lines.next_line()? {
            Some((_, l)) if l.trim().is_empty() => continue,
            Some((n, l)) => return Ok(Some((n, l.to_string()))),
            None => return Ok(None),
        }
    }
}

/// A row no built-in format reads, tried as recognised vendor names (`labelled.rs`): the
/// header found, or none and the row read ahead to look for units under the names, if any, to
/// be read next. Names without units take them from a units row under them (Shimmer's `CAL`
/// row between skipped), else from the signal; the row read ahead is then the first data row.
fn try_labelled<R: BufRead>(
    lines: &mut Lines<R>,
    row: (u64, &str),
    sep_line: Option<u8>,
    path: &Path,
    notes: &mut Vec<String>,
) -> Result<LabelledRow> {
    let (lineno, line) = row;
    let delim = sep_line.unwrap_or_else(|| detect_delimiter(line));
    let fields = split_header(line, delim);
    if !header_like(&fields) {
        return Ok((None, None));
    }
    let base = &FormatSpec::detected()[0];
    let header = |f: Found, units_from, first_row| Header {
        line: lineno,
        spec: f.spec,
        delim,
        fields: fields.clone(),
        cols: f.cols,
        has_row: true,
        first_row,
        sep_line,
        units_from,
        start: None,
        infer: f.infer,
    };
    let pos = match labelled(base, &fields, path, lineno)? {
        Labelled::No => return Ok((None, None)),
        Labelled::Found(b) => {
            notes.push(format!(
                "format recognised from the column names ({}); units read from the names",
                b.spec.name
            ));
            return Ok((Some(header(*b, UnitsFrom::Labels, None)), None));
        }
        Labelled::NeedsUnitsRow(pos) => pos,
    };
    let Some((mut n, mut text)) = next_nonblank(lines)? else {
        return Ok((None, None));
    };
    let mut units = split_header(&text, delim);
    if kinds_row(&pos, &units) {
        match next_nonblank(lines)? {
            Some((m, t)) => (n, text) = (m, t),
            None => return Ok((None, None)),
        }
        units = split_header(&text, delim);
    }
    if let Some(found) = with_units_row(base, &fields, &pos, &units, (lineno, n), path)? {
        notes.push(format!(
            "format recognised from the column names ({}); units read from the row under the names (line {n})",
            found.spec.name
        ));
        return Ok((Some(header(found, UnitsFrom::UnitsRow(n), None)), None));
    }
    let data = pos
        .iter()
        .all(|(i, _)| units.get(*i).is_some_and(|c| is_number(c)));
    if data {
        if let Some(found) = all_inferred(base, &fields, &pos, path, lineno)? {
            notes.push(format!(
                "format recognised from the column names ({}); no units stated",
                found.spec.name
            ));
            return Ok((
                Some(header(found, UnitsFrom::Signal, Some((n, text)))),
                None,
            ));
        }
    }
    Ok((None, Some((n, text))))
}

/// The delimiter a `sep=` line names (`Some(None)`: a `sep=` line naming no delimiter ldh
/// knows); `None` when `trimmed` is not a `sep=` line.
fn sep_line_delimiter(trimmed: &str) -> Option<Option<u8>> {
    let rest = trimmed
        .strip_prefix("sep=")
        .or_else(|| trimmed.strip_prefix("\"sep="))?;
    let rest = rest.trim_end_matches('"');
    Some(match rest {
        "\\t" | "\t" | "" => Some(b'\t'),
        r => r
            .bytes()
            .next()
            .filter(|b| Delimiter::from_byte(*b).is_some()),
    })
}

/// What one candidate format makes of one row.
enum RowMatch {
    /// The format reads this row: the header (boxed: the enum stays small).
    Found(Box<Header>),
    /// Not this format's header: a data row, or a row that does not look like a header.
    No,
    /// A header-like row lacking the format's columns (detection mode), with its fields and,
    /// when they were split at another delimiter than the format's, what differs.
    Missing(Vec<Missing>, Vec<String>, Option<String>),
}

/// The format that misses the fewest columns in the first header-like row (detection mode).
struct Closest<'a> {
    /// The format.
    format: &'a FormatSpec,
    /// What it misses.
    missing: Vec<Missing>,
    /// Line of the row.
    at: u64,
    /// The row's fields.
    fields: Vec<String>,
    /// The delimiter that differs, in words.
    delim_note: Option<String>,
}

/// Try format `f` on `row` (1-based line number, text), split at the
/// format's delimiter, else the `sep=` line's, else the detected one. A duplicated column is an
/// error; so is a header-like row missing columns when the format was given (`format_given`).
fn match_row(
    f: &FormatSpec,
    row: (u64, &str),
    sep_line: Option<u8>,
    format_given: bool,
    path: &Path,
    notes: &mut Vec<String>,
) -> Result<RowMatch> {
    let (lineno, line) = row;
    let delim = f
        .delimiter
        .byte()
        .or(sep_line)
        .unwrap_or_else(|| detect_delimiter(line));
    let fields = split_header(line, delim);
    let by_index = all_by_index(f);
    let delim_note = other_delimiter(f, line, delim, &fields);
    if let Some((note, alt)) = delim_note {
        if format_given {
            return Err(LdhError::DelimiterMismatch {
                loc: Location::line(path, lineno),
                detail: format!(
                    "{note}, where it holds the format's columns; set delimiter = \"auto\" in {}",
                    map_command(f)
                ),
            });
        }
        // Detection: what differs is said if no format fits; the map is not used with another
        // delimiter than its own (its other settings, a counter's rate, may not hold either).
        let m = match resolve(f, &alt) {
            Err(Unresolved::Missing(m)) => m,
            _ => Vec::new(),
        };
        return Ok(RowMatch::Missing(m, alt, Some(note)));
    }
    if !by_index && fields.iter().all(|x| x.is_empty() || is_number(x)) {
        // A data row: names cannot match (and suggestions would cost time).
        return Ok(RowMatch::No);
    }
    let attempt = match resolve(f, &fields) {
        Ok(c) => Ok((f.clone(), c, UnitsFrom::Format)),
        Err(e) => match unit_suffixed(f, &fields) {
            Some(g) => resolve(&g, &fields).map(|c| (g, c, UnitsFrom::NameSuffix)),
            None => match without_units(&fields).filter(|_| format_given) {
                // A given map keeps its units; its names may be written without the units
                // the header adds (`Acc_X` for `Acc_X [m/s^2]`).
                Some(cut) => resolve(f, &cut).map(|c| (f.clone(), c, UnitsFrom::Format)),
                None => Err(e),
            },
        },
    };
    match attempt {
        Ok((spec, cols, units_from)) => {
            if units_from == UnitsFrom::Format && format_given {
                map_units_notes(&spec, &cols, &fields, notes);
            }
            let has_row = !(by_index && fields.iter().all(|x| is_number(x)));
            let fields = if has_row {
                fields
            } else {
                (1..=fields.len()).map(|i| format!("column {i}")).collect()
            };
            if spec.acc.columns != f.acc.columns || spec.gyro.columns != f.gyro.columns {
                notes.push(format!(
                    "unit-suffixed column names: acceleration in {:?}, angular velocity in {:?}, time in {:?}",
                    spec.acc.unit, spec.gyro.unit, spec.time.unit
                ));
            }
            let first_row = (!has_row).then(|| (lineno, line.to_string()));
            Ok(RowMatch::Found(Box::new(Header {
                line: lineno,
                spec,
                delim,
                fields,
                cols,
                has_row,
                sep_line,
                first_row,
                units_from,
                start: None,
                infer: Infer::default(),
            })))
        }
        Err(Unresolved::Duplicate { column, positions }) => Err(LdhError::DuplicateColumn {
            loc: Location::line(path, lineno),
            column,
            positions,
        }),
        Err(Unresolved::Missing(m)) => {
            if !header_like(&fields) {
                return Ok(RowMatch::No);
            }
            if format_given {
                let (missing, hint) = describe_missing(&m, &fields, f);
                return Err(LdhError::MissingColumn {
                    loc: Location::line(path, lineno),
                    missing,
                    by: format!("format '{}'{hint}", f.name),
                });
            }
            Ok(RowMatch::Missing(m, fields, None))
        }
    }
}

/// When `f` has a fixed delimiter (`delim`) that leaves `fields` no header, but the row split
/// at the delimiter it holds is header-like and holds some of `f`'s columns: what differs, in
/// words, and that split.
fn other_delimiter(
    f: &FormatSpec,
    line: &str,
    delim: u8,
    fields: &[String],
) -> Option<(String, Vec<String>)> {
    if f.delimiter == Delimiter::Auto || header_like(fields) {
        return None;
    }
    let other = detect_delimiter(line);
    if other == delim || !line.as_bytes().contains(&other) {
        return None;
    }
    let alt = split_header(line, other);
    if !header_like(&alt) {
        return None;
    }
    let wanted = f.required_columns().len();
    if let Err(Unresolved::Missing(m)) = resolve(f, &alt) {
        if m.len() >= wanted {
            return None;
        }
    }
    let name = |b: u8| Delimiter::from_byte(b).map_or("?", |d| d.name());
    Some((
        format!(
            "format '{}' splits rows at {}, but this row is separated by {}",
            f.name,
            name(delim),
            name(other)
        ),
        alt,
    ))
}

/// Where to change a map: a copy of a built-in one (`ldh formats NAME > my.toml`, then
/// `--input-format my.toml`), else the map given.
pub(super) fn map_command(f: &FormatSpec) -> String {
    if FormatSpec::builtin(&f.name).is_ok_and(|b| b == *f) {
        format!(
            "a copy of the map: `ldh formats {} > my.toml`, edit it, then `--input-format my.toml`",
            f.name
        )
    } else {
        format!("the map '{}' given with --input-format", f.name)
    }
}

/// Notes for a given map's columns whose header states another unit than the map's: the map
/// wins (it was given), and the note says so.
fn map_units_notes(spec: &FormatSpec, cols: &Columns, fields: &[String], notes: &mut Vec<String>) {
    let mut read: Vec<(usize, Unit)> = Vec::new();
    if let (Some(t), Some(u)) = (cols.time, Unit::from_time(spec.time.unit)) {
        read.push((t, u));
    }
    read.extend(cols.acc.iter().map(|&i| (i, Unit::from(spec.acc.unit))));
    read.extend(cols.gyro.iter().map(|&i| (i, Unit::from(spec.gyro.unit))));
    for (i, unit) in read {
        if let Some(stated) = fields.get(i).and_then(|c| stated_unit(c)) {
            if stated != unit {
                notes.push(format!(
                    "column '{}' states {stated}, the format '{}' says {unit}: the format's unit is used",
                    fields[i].trim(),
                    spec.name
                ));
            }
        }
    }
}

/// The error when no row is a header: [`LdhError::EmptyFile`] for blank content (`all_blank`), otherwise
/// [`LdhError::NoHeader`] naming the closest format's missing columns (or the only
/// candidate's required ones) and the first row.
fn no_header(
    all_blank: bool,
    closest: Option<Closest>,
    candidates: &[&FormatSpec],
    format_given: bool,
    path: &Path,
    first_row: String,
) -> LdhError {
    if all_blank {
        return LdhError::EmptyFile {
            path: path.to_path_buf(),
        };
    }
    let (fmt, missing, mut hint) = match closest {
        Some(c) => {
            let (missing, mut hint) = describe_missing(&c.missing, &c.fields, c.format);
            if let Some(d) = c.delim_note {
                hint.push_str(&format!("; {d}"));
            }
            if let Some(p) = partial(&c.fields).filter(|_| !format_given) {
                hint.push_str(&format!("; {p}"));
            }
            (c.format, missing, hint)
        }
        None => (
            candidates[0],
            candidates[0].required_columns(),
            String::new(),
        ),
    };
    hint.push_str(&format!(
        "; to read the file, set its column names and units in {}",
        map_command(fmt)
    ));
    let fmt = fmt.name.clone();
    LdhError::NoHeader {
        path: path.to_path_buf(),
        format: if format_given || candidates.len() == 1 {
            fmt
        } else {
            format!(
                "closest of {}: {fmt}",
                candidates
                    .iter()
                    .map(|f| f.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        },
        missing,
        hint,
        first_row,
    }
}

#[cfg(test)]
mod tests;
