//! The one reader of every CSV table that is not a sensor recording (issue 48): the cohort
//! manifest (`pipeline::manifest`), `ldh agree`'s reference files and walkway exports
//! (`reference::long_form`, `reference::walkway`), `reliability.csv`
//! (`cohort::reliability_table`) and ldh's own `strides.csv` / `events.csv` read back
//! (`output::stride_groups`, `output::results`).
//!
//! Built on the `csv` crate (RFC 4180 quoting: a quoted field may hold the delimiter) and serde
//! ([`Row::deserialize`] maps a row onto a `#[derive(Deserialize)]` type by header name). A
//! [`Table`] holds its header (names trimmed, a leading byte-order mark dropped, lower-cased
//! when the [`TableFormat`] says so) and its rows with their 1-based line numbers; a [`Row`]
//! gives each cell by column name with its [`Location`] (file:line:column), so every reader's
//! message names the cell it refuses. What a cell must hold, and the words of the message, stay
//! with each reader: this layer only splits, locates and parses.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use crate::error::{LdhError, Location, Result};

/// How a table is split.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableFormat {
    /// Field delimiter (default `,`).
    pub delimiter: u8,
    /// Trim the spaces around every field (default `false`; cells read by name are trimmed
    /// anyway).
    pub trim: bool,
    /// Lines starting with this byte are comments, skipped (default none).
    pub comment: Option<u8>,
    /// Lower-case the header's names (default `false`).
    pub lowercase_header: bool,
    /// Rows before the header row that are skipped (an export's title lines; default 0).
    pub skip_rows_before_header: usize,
    /// Rows may hold more or fewer fields than the header (default `false`): the reader
    /// checks them itself.
    pub flexible: bool,
}

impl Default for TableFormat {
    fn default() -> Self {
        TableFormat {
            delimiter: b',',
            trim: false,
            comment: None,
            lowercase_header: false,
            skip_rows_before_header: 0,
            flexible: false,
        }
    }
}

/// A row the CSV layer could not split: more or fewer fields than the header (the only fault
/// of text already decoded as UTF-8). Each reader words it its own way.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvFault {
    /// File and line.
    pub loc: Location,
    /// Fields in the row, when the fault is a field count.
    pub found: Option<usize>,
    /// Fields in the header, when the fault is a field count.
    pub expected: Option<usize>,
    /// The `csv` crate's message.
    pub reason: String,
}

impl CsvFault {
    fn of(e: &csv::Error, path: &Path) -> CsvFault {
        let line = e.position().map_or(1, |p| p.line());
        let (found, expected) = match e.kind() {
            csv::ErrorKind::UnequalLengths {
                expected_len, len, ..
            } => (Some(*len as usize), Some(*expected_len as usize)),
            _ => (None, None),
        };
        CsvFault {
            loc: Location::line(path, line),
            found,
            expected,
            reason: e.to_string(),
        }
    }

    /// As [`LdhError::FieldCount`] (with `hint`, empty or starting with "; "), or a signal
    /// naming the file and line for any other fault.
    pub fn into_error(self, hint: &str) -> LdhError {
        match (self.found, self.expected) {
            (Some(found), Some(expected)) => LdhError::FieldCount {
                loc: self.loc,
                found,
                expected,
                hint: hint.to_string(),
            },
            _ => LdhError::signal(self.loc.to_string(), self.reason),
        }
    }
}

/// A CSV table read whole: its header and its rows, each with its line.
#[derive(Debug, Clone)]
pub struct Table {
    /// The file (it names every location).
    pub path: PathBuf,
    /// The header's names as [`TableFormat`] normalises them.
    pub header: Vec<String>,
    /// The header as written (serde maps fields by these names).
    raw_header: csv::StringRecord,
    /// The header's line, 1-based.
    pub header_line: u64,
    /// The rows under the header, with their 1-based lines, up to the first that could not
    /// be split.
    rows: Vec<(u64, csv::StringRecord)>,
    /// The row that could not be split, if any: [`Table::rows`] yields it after the others,
    /// where a reader streaming the file would meet it (after the header's checks).
    fault: Option<CsvFault>,
}

impl Table {
    /// Read the table at `path` (at most [`super::MAX_TABLE_MB`]; `what` names it in the size
    /// message).
    pub fn read(path: &Path, what: &'static str, format: &TableFormat) -> Result<Table> {
        let text = super::read_text_limited(path, super::MAX_TABLE_MB, what)?;
        Table::parse(&text, path, format).map_err(|f| f.into_error(""))
    }

    /// Split `text` (`path` names it in locations). A text without rows has an empty header.
    /// Errors: a header row that cannot be split (a row under it is [`Table::rows`]' fault).
    pub fn parse(text: &str, path: &Path, format: &TableFormat) -> Result<Table, CsvFault> {
        let text = text.trim_start_matches('\u{feff}');
        let skip = format.skip_rows_before_header;
        let mut rdr = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(format.flexible)
            .trim(if format.trim {
                csv::Trim::All
            } else {
                csv::Trim::None
            })
            .comment(format.comment)
            .delimiter(format.delimiter)
            .from_reader(text.as_bytes());
        let mut records = rdr.records();
        let mut raw_header = csv::StringRecord::new();
        for _ in 0..=skip {
            match records.next() {
                Some(r) => raw_header = r.map_err(|e| CsvFault::of(&e, path))?,
                None => {
                    raw_header = csv::StringRecord::new();
                    break;
                }
            }
        }
        // With comments, csv's position of a record is where its read began (before the
        // comment lines skipped): the header's line is then the first other line.
        let header_line = match format.comment {
            Some(c) => text
                .lines()
                .position(|l| !l.trim().is_empty() && !l.trim_start().starts_with(c as char))
                .map_or(1, |i| i as u64 + 1),
            None => raw_header.position().map_or(1, |p| p.line()),
        };
        let header = raw_header
            .iter()
            .map(|h| {
                let h = h.trim().trim_start_matches('\u{feff}');
                if format.lowercase_header {
                    h.to_ascii_lowercase()
                } else {
                    h.to_string()
                }
            })
            .collect();
        let (mut rows, mut fault) = (Vec::new(), None);
        for rec in records {
            match rec {
                Ok(rec) => rows.push((rec.position().map_or(0, |p| p.line()), rec)),
                Err(e) => {
                    fault = Some(CsvFault::of(&e, path));
                    break;
                }
            }
        }
        Ok(Table {
            path: path.to_path_buf(),
            header,
            raw_header,
            header_line,
            rows,
            fault,
        })
    }

    /// The 0-based position of column `name` in the header.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// The rows, each able to name its cells, then the row that could not be split (more or
    /// fewer fields than the header), if any.
    pub fn rows(&self) -> impl Iterator<Item = Result<Row<'_>, CsvFault>> {
        let rows = self.rows.iter().map(move |(line, record)| {
            Ok(Row {
                table: self,
                line: *line,
                record,
            })
        });
        rows.chain(self.fault.clone().map(Err))
    }

    /// The location of the header's column `i` (0-based).
    pub fn header_cell(&self, i: usize) -> Location {
        Location::cell(&self.path, self.header_line, i + 1)
    }
}

/// One row of a [`Table`].
#[derive(Debug, Clone, Copy)]
pub struct Row<'t> {
    /// The table.
    pub table: &'t Table,
    /// The row's line, 1-based.
    pub line: u64,
    /// Its fields.
    pub record: &'t csv::StringRecord,
}

impl<'t> Row<'t> {
    /// The trimmed cell of column `i` (0-based; empty when the row is shorter).
    pub fn at(&self, i: usize) -> &'t str {
        self.record.get(i).unwrap_or("").trim()
    }

    /// The trimmed cell of column `name` (empty when the table has no such column).
    pub fn get(&self, name: &str) -> &'t str {
        self.table.column(name).map_or("", |i| self.at(i))
    }

    /// The location of column `i`'s cell (0-based).
    pub fn loc_at(&self, i: usize) -> Location {
        Location::cell(&self.table.path, self.line, i + 1)
    }

    /// The location of column `name`'s cell (column 1 when the table has none).
    pub fn loc(&self, name: &str) -> Location {
        self.loc_at(self.table.column(name).unwrap_or(0))
    }

    /// The row's location (file and line).
    pub fn loc_line(&self) -> Location {
        Location::line(&self.table.path, self.line)
    }

    /// [`LdhError::InvalidValue`] for column `name`'s cell.
    pub fn invalid(&self, name: &str, expected: impl Into<String>) -> LdhError {
        self.invalid_value(name, self.get(name), expected)
    }

    /// [`LdhError::InvalidValue`] for column `name` holding `value`.
    pub fn invalid_value(&self, name: &str, value: &str, expected: impl Into<String>) -> LdhError {
        LdhError::InvalidValue {
            loc: self.loc(name),
            column: name.into(),
            value: value.into(),
            expected: expected.into(),
        }
    }

    /// Column `name` as a finite number; `None` for an empty cell. Errors:
    /// [`LdhError::NotANumber`], [`LdhError::NonFinite`].
    pub fn number(&self, name: &str) -> Result<Option<f64>> {
        match self.table.column(name) {
            Some(i) => self.number_at(i, name),
            None => Ok(None),
        }
    }

    /// Column `i`'s cell (0-based; errors name it `column`) as a finite number; `None` for an
    /// empty cell. Errors: [`LdhError::NotANumber`], [`LdhError::NonFinite`].
    pub fn number_at(&self, i: usize, column: &str) -> Result<Option<f64>> {
        let s = self.at(i);
        if s.is_empty() {
            return Ok(None);
        }
        let v = s.parse::<f64>().map_err(|_| LdhError::NotANumber {
            loc: self.loc_at(i),
            column: column.to_string(),
            value: s.to_string(),
            hint: String::new(),
        })?;
        if !v.is_finite() {
            return Err(LdhError::NonFinite {
                loc: self.loc_at(i),
                column: column.to_string(),
                value: s.to_string(),
            });
        }
        Ok(Some(v))
    }

    /// The row as a `T`, its fields matched to the header's names as written.
    pub fn deserialize<T: DeserializeOwned>(&self) -> std::result::Result<T, csv::Error> {
        self.record.deserialize(Some(&self.table.raw_header))
    }
}

/// Stream the rows of a large table of ldh's own as `T`s (no size limit: `strides.csv` of a
/// cohort), opened as every input is (a FIFO or device is refused). Errors name the file.
pub fn deserialize_stream<T: DeserializeOwned>(
    path: &Path,
    what: &str,
) -> Result<impl Iterator<Item = Result<T>>> {
    let (file, _) = super::open_regular(path, what)?;
    let rdr = csv::Reader::from_reader(std::io::BufReader::new(file));
    let origin = path.display().to_string();
    Ok(rdr
        .into_deserialize::<T>()
        .map(move |r| r.map_err(|e| LdhError::signal(origin.clone(), e.to_string()))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_know_their_lines_and_cells_their_columns() {
        let text = "\u{feff}# a comment\n Subject_ID , Left\n\n# another\nS1,\"a,b.csv\"\nS2 , x\n";
        let f = TableFormat {
            trim: true,
            comment: Some(b'#'),
            lowercase_header: true,
            ..TableFormat::default()
        };
        let t = Table::parse(text, Path::new("m.csv"), &f).unwrap();
        assert_eq!(t.header, ["subject_id", "left"]);
        assert_eq!(t.header_line, 2);
        let rows: Vec<Row> = t.rows().map(Result::unwrap).collect();
        assert_eq!(rows[0].get("left"), "a,b.csv");
        assert_eq!(rows[1].get("missing"), "");
        let t = Table::parse("a,b\n1,2\n3,4\n", Path::new("t.csv"), &f).unwrap();
        let row = t.rows().nth(1).unwrap().unwrap();
        assert_eq!(
            (row.line, row.loc("b").to_string()),
            (3, "t.csv:3:2".into())
        );
        let t = Table::parse("a,b\n1,2\n3\n", Path::new("t.csv"), &f).unwrap();
        let mut rows = t.rows();
        assert!(rows.next().unwrap().is_ok(), "the rows before the fault");
        let e = rows.next().unwrap().unwrap_err();
        assert_eq!((e.found, e.expected), (Some(1), Some(2)));
        assert_eq!(
            e.into_error("").to_string(),
            "t.csv:3: row has 1 fields, the header has 2"
        );
    }

    #[test]
    fn numbers_and_serde_rows() {
        #[derive(serde::Deserialize)]
        struct R {
            b: Option<f64>,
            a: String,
        }
        let t = Table::parse(
            "a,b\nx,1.5\ny,\nz,zero\nw,inf\n",
            Path::new("t.csv"),
            &TableFormat::default(),
        )
        .unwrap();
        let rows: Vec<Row> = t.rows().map(Result::unwrap).collect();
        assert_eq!(rows[0].number("b").unwrap(), Some(1.5));
        assert_eq!(rows[1].number("b").unwrap(), None);
        let m = rows[2].number("b").unwrap_err().to_string();
        assert_eq!(m, "t.csv:4:2: column 'b': 'zero' is not a number");
        let m = rows[3].number("b").unwrap_err().to_string();
        assert_eq!(m, "t.csv:5:2: column 'b': non-finite value 'inf'");
        let r: R = rows[0].deserialize().unwrap();
        assert_eq!((r.a.as_str(), r.b), ("x", Some(1.5)));
        assert!(rows[2].deserialize::<R>().is_err());
    }
}
