//! Output tables written row by row ([`TableSink`]): `<stem>.csv` and, when asked, `<stem>.json`
//! as one array, each through a [`RunWriter`] of the folder's [`OutputRun`] (atomic, never
//! through a link, listed in the run's marker).

use serde::Serialize;
use std::io::Write;

use super::run::{OutputRun, RunWriter};
use crate::error::{LdhError, Result};
use crate::pipeline::quality::flat;

/// A table written row by row to `<stem>.csv` (and `<stem>.json` as one array when asked), each
/// through a [`RunWriter`]: a batch streams its rows out instead of holding them, and an
/// interrupted run leaves the previous files whole.
///
/// Rows can be rendered to bytes anywhere ([`TableSink::render`], e.g. on the thread that
/// analysed them) and only copied in order here ([`TableSink::push_rendered`]), so the one
/// thread that writes does not serialise a whole batch while the others wait.
pub struct TableSink<'a> {
    csv: RunWriter<'a>,
    json: Option<RunWriter<'a>>,
    header: Vec<String>,
    rows: usize,
}

/// Rows of one table rendered to bytes, in order: the CSV header and records, and each row's
/// JSON text as it sits in the array (indented by two spaces).
#[derive(Debug, Default)]
pub struct RenderedRows {
    /// The CSV header line the rows' type produces (empty without rows).
    csv_header: Vec<u8>,
    /// The CSV records, without the header.
    csv: Vec<u8>,
    /// One text per row when JSON was asked for.
    json: Vec<String>,
    rows: usize,
}

/// CSV bytes of `rows` (serde's flat cells), with or without the header line.
fn csv_bytes<T: Serialize>(rows: &[T], header: bool) -> Result<Vec<u8>> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(header)
        .from_writer(Vec::new());
    for r in rows {
        flat(|| w.serialize(r))?;
    }
    w.into_inner()
        .map_err(|e| LdhError::signal("csv", e.to_string()))
}

impl RenderedRows {
    /// Render `rows` (and their JSON texts when `json`).
    pub fn of<T: Serialize>(rows: &[T], json: bool) -> Result<RenderedRows> {
        // The header line is what a header-writing CSV writer puts before the first record
        // (the csv crate writes headers only on a first `serialize`): the first row rendered
        // with it, less the same row rendered without it.
        let csv_header = match rows.first() {
            Some(first) => {
                let mut with = csv_bytes(std::slice::from_ref(first), true)?;
                let record = csv_bytes(std::slice::from_ref(first), false)?.len();
                with.truncate(with.len() - record);
                with
            }
            None => Vec::new(),
        };
        let json = if json {
            rows.iter()
                .map(|r| Ok(serde_json::to_string_pretty(r)?.replace('\n', "\n  ")))
                .collect::<Result<Vec<String>>>()?
        } else {
            Vec::new()
        };
        Ok(RenderedRows {
            csv_header,
            csv: csv_bytes(rows, false)?,
            json,
            rows: rows.len(),
        })
    }
}

fn csv_err(e: std::io::Error) -> LdhError {
    LdhError::signal("csv", e.to_string())
}

fn json_err(e: std::io::Error) -> LdhError {
    LdhError::signal("json", e.to_string())
}

impl<'a> TableSink<'a> {
    /// Start `<stem>.csv` (and `.json`) in the run's folder; `header` is written when no row
    /// comes.
    pub fn create(
        run: &'a OutputRun,
        stem: &str,
        header: &[&str],
        json: bool,
    ) -> Result<TableSink<'a>> {
        let csv = run.create(&format!("{stem}.csv"))?;
        let json = if json {
            let mut j = run.create(&format!("{stem}.json"))?;
            j.write_all(b"[").map_err(json_err)?;
            Some(j)
        } else {
            None
        };
        Ok(TableSink {
            csv,
            json,
            header: header.iter().map(|s| s.to_string()).collect(),
            rows: 0,
        })
    }

    /// Whether the table has a JSON file (what [`RenderedRows::of`] is asked for).
    pub fn has_json(&self) -> bool {
        self.json.is_some()
    }

    /// Append rows rendered by [`RenderedRows::of`] (with JSON texts if [`Self::has_json`]).
    pub fn push_rendered(&mut self, r: &RenderedRows) -> Result<()> {
        if r.rows == 0 {
            return Ok(());
        }
        if self.rows == 0 {
            self.csv.write_all(&r.csv_header).map_err(csv_err)?;
        }
        self.csv.write_all(&r.csv).map_err(csv_err)?;
        if let Some(j) = self.json.as_mut() {
            debug_assert_eq!(r.json.len(), r.rows, "rendered without the JSON texts");
            for (k, text) in r.json.iter().enumerate() {
                let sep = if self.rows + k == 0 { "\n  " } else { ",\n  " };
                j.write_all(sep.as_bytes())
                    .and_then(|_| j.write_all(text.as_bytes()))
                    .map_err(json_err)?;
            }
        }
        self.rows += r.rows;
        Ok(())
    }

    /// Rows written so far.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Close both files and rename them into place (each flushed and fsynced; the two files
    /// side by side).
    pub fn finish(mut self) -> Result<()> {
        if self.rows == 0 {
            let mut w = csv::Writer::from_writer(Vec::new());
            w.write_record(&self.header)?;
            let bytes = w
                .into_inner()
                .map_err(|e| LdhError::signal("csv", e.to_string()))?;
            self.csv.write_all(&bytes).map_err(csv_err)?;
        }
        let json = match self.json.take() {
            Some(mut j) => {
                j.write_all(if self.rows == 0 { b"]" } else { b"\n]" })
                    .map_err(json_err)?;
                Some(j)
            }
            None => None,
        };
        finish_all(std::iter::once(self.csv).chain(json).collect())
    }
}

/// Finish several tables at once (their fsyncs overlap instead of queueing one after another).
pub fn finish_tables(tables: Vec<TableSink<'_>>) -> Result<()> {
    each_on_a_thread(tables, TableSink::finish)
}

/// Flush, fsync and rename `files`.
fn finish_all(files: Vec<RunWriter<'_>>) -> Result<()> {
    each_on_a_thread(files, RunWriter::finish)
}

/// `f` on every item, each on its own scoped thread (for fsync, which waits on the disk, not
/// the CPU, so the waits overlap whatever the rayon pool); the first error is returned, a panic
/// is passed on as it was.
fn each_on_a_thread<T: Send>(items: Vec<T>, f: fn(T) -> Result<()>) -> Result<()> {
    if items.len() <= 1 {
        return items.into_iter().try_for_each(f);
    }
    std::thread::scope(|s| {
        let handles: Vec<_> = items.into_iter().map(|x| s.spawn(move || f(x))).collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect::<Result<Vec<()>>>()
    })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Row {
        id: String,
        x: f64,
        note: Option<String>,
    }

    /// What the sink wrote before rows were rendered off its thread: one header-writing CSV
    /// writer over every row, each row's pretty JSON indented into the array.
    fn one_go(rows: &[Row], header: &[&str]) -> (Vec<u8>, String) {
        let mut w = csv::WriterBuilder::new()
            .has_headers(true)
            .from_writer(Vec::new());
        for r in rows {
            w.serialize(r).unwrap();
        }
        if rows.is_empty() {
            w.write_record(header).unwrap();
        }
        let mut j = String::from("[");
        for (k, r) in rows.iter().enumerate() {
            j += if k == 0 { "\n  " } else { ",\n  " };
            j += &serde_json::to_string_pretty(r)
                .unwrap()
                .replace('\n', "\n  ");
        }
        j += if rows.is_empty() { "]" } else { "\n]" };
        (w.into_inner().unwrap(), j)
    }

    /// Rows pushed in pieces of any size (empty ones too), rendered elsewhere, give the bytes
    /// of one writer over all of them, also with no row at all (the given header).
    #[test]
    fn rendered_pieces_write_the_same_bytes_as_one_writer() {
        let rows: Vec<Row> = (0..7)
            .map(|i| Row {
                id: format!("S{i}, \"quoted\""),
                x: i as f64 / 3.0,
                note: (i % 2 == 0).then(|| "a\nb".into()),
            })
            .collect();
        let dir = tempfile::tempdir().unwrap();
        for cuts in [vec![], vec![0, 0, 3], vec![1, 2, 2, 6], vec![7]] {
            for n in [0, 1, 7] {
                let run = OutputRun::begin(dir.path(), super::super::RunKind::Analyze).unwrap();
                let mut sink = TableSink::create(&run, "t", &["id", "x", "note"], true).unwrap();
                let mut at = 0;
                for c in cuts.iter().map(|&c| c.min(n)).chain([n]) {
                    let piece = RenderedRows::of(&rows[at..c.max(at)], sink.has_json()).unwrap();
                    sink.push_rendered(&piece).unwrap();
                    at = c.max(at);
                }
                assert_eq!(sink.rows(), n);
                finish_tables(vec![sink]).unwrap();
                let listed = run.finish().unwrap();
                let (csv, json) = one_go(&rows[..n], &["id", "x", "note"]);
                assert_eq!(std::fs::read(dir.path().join("t.csv")).unwrap(), csv);
                let got = std::fs::read_to_string(dir.path().join("t.json")).unwrap();
                assert_eq!(got, json, "cuts {cuts:?}, {n} rows");
                assert!(listed.lists("t.json", json.as_bytes()) && listed.lists("t.csv", &csv));
            }
        }
    }
}
