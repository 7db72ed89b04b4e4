//! Output tables written row by row ([`TableSink`]): `<stem>.csv` and, when asked, `<stem>.json`
//! as one array, each through an [`crate::io::AtomicFile`].

use serde::Serialize;
use std::io::Write;

use crate::error::{LdhError, Result};
use crate::pipeline::quality::flat;

/// A table written row by row to `<stem>.csv` (and `<stem>.json` as one array when asked), each
/// through an [`AtomicFile`](crate::io::AtomicFile): a batch streams its rows out instead of holding them, and an
/// interrupted run leaves the previous files whole.
pub struct TableSink {
    csv: csv::Writer<crate::io::AtomicFile>,
    json: Option<crate::io::AtomicFile>,
    header: Vec<String>,
    rows: usize,
}

impl TableSink {
    /// Start `<dir>/<stem>.csv` (and `.json`); `header` is written when no row comes.
    pub fn create(
        dir: &std::path::Path,
        stem: &str,
        header: &[&str],
        json: bool,
    ) -> Result<TableSink> {
        let f = crate::io::AtomicFile::create(dir.join(format!("{stem}.csv")))?;
        let json = if json {
            let mut j = crate::io::AtomicFile::create(dir.join(format!("{stem}.json")))?;
            j.write_all(b"[")
                .map_err(|e| LdhError::signal("json", e.to_string()))?;
            Some(j)
        } else {
            None
        };
        Ok(TableSink {
            csv: csv::WriterBuilder::new().has_headers(true).from_writer(f),
            json,
            header: header.iter().map(|s| s.to_string()).collect(),
            rows: 0,
        })
    }

    /// Append rows.
    pub fn push<T: Serialize>(&mut self, rows: &[T]) -> Result<()> {
        for r in rows {
            flat(|| self.csv.serialize(r))?;
            if let Some(j) = self.json.as_mut() {
                let text = serde_json::to_string_pretty(r)?;
                let sep = if self.rows == 0 { "\n  " } else { ",\n  " };
                j.write_all(sep.as_bytes())
                    .and_then(|_| j.write_all(text.replace('\n', "\n  ").as_bytes()))
                    .map_err(|e| LdhError::signal("json", e.to_string()))?;
            }
            self.rows += 1;
        }
        Ok(())
    }

    /// Rows written so far.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Close both files and rename them into place.
    pub fn finish(mut self) -> Result<()> {
        if self.rows == 0 {
            self.csv.write_record(&self.header)?;
        }
        let f = self
            .csv
            .into_inner()
            .map_err(|e| LdhError::signal("csv", e.to_string()))?;
        f.finish()?;
        if let Some(mut j) = self.json.take() {
            j.write_all(if self.rows == 0 { b"]" } else { b"\n]" })
                .map_err(|e| LdhError::signal("json", e.to_string()))?;
            j.finish()?;
        }
        Ok(())
    }
}
