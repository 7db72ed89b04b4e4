//! The captured walking spans of a recording, spilled to a temporary file as they close, so
//! a week's walking is never held in memory: each span's samples as little-endian `f32`
//! (time relative to the span's start, then the six channels; 28 bytes a sample), read back
//! one span at a time when its bout is analysed. The file is removed when the store is
//! dropped.

use std::fs::File;
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use super::stream::Sample;
use crate::error::{LdhError, Result};

const SAMPLE_BYTES: usize = 28;

/// Where one span lies in the store.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpanRef {
    offset: u64,
    /// Samples.
    pub n: usize,
    /// Time of the first sample, s (the leg's own clock).
    pub t0_s: f64,
}

/// A temporary spill file of spans.
#[derive(Debug)]
pub struct SpanStore {
    path: PathBuf,
    writer: Mutex<Option<BufWriter<File>>>,
    reader: Mutex<Option<File>>,
    len: Mutex<u64>,
}

static COUNTER: AtomicU64 = AtomicU64::new(0);

fn io_err(path: &std::path::Path, source: std::io::Error) -> LdhError {
    LdhError::Io {
        path: path.to_path_buf(),
        source,
    }
}

impl SpanStore {
    /// A new store in the system's temporary folder.
    pub fn new() -> Result<Self> {
        let path = std::env::temp_dir().join(format!(
            "ldh-monitor-{}-{}.spans",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let file = File::create(&path).map_err(|e| io_err(&path, e))?;
        Ok(SpanStore {
            writer: Mutex::new(Some(BufWriter::with_capacity(1 << 16, file))),
            reader: Mutex::new(None),
            len: Mutex::new(0),
            path,
        })
    }

    /// Append a span (times relative to its first sample).
    pub fn put(&self, samples: &[Sample]) -> Result<SpanRef> {
        let t0 = samples.first().map_or(0.0, |s| s.t_s);
        let mut guard = self.writer.lock().unwrap_or_else(|e| e.into_inner());
        let w = guard
            .as_mut()
            .ok_or_else(|| LdhError::signal("monitor", "span store already closed for writing"))?;
        let mut len = self.len.lock().unwrap_or_else(|e| e.into_inner());
        let offset = *len;
        let mut buf = Vec::with_capacity(samples.len() * SAMPLE_BYTES);
        for s in samples {
            buf.extend_from_slice(&((s.t_s - t0) as f32).to_le_bytes());
            for v in s.acc_g.iter().chain(&s.gyro_dps) {
                buf.extend_from_slice(&(*v as f32).to_le_bytes());
            }
        }
        w.write_all(&buf).map_err(|e| io_err(&self.path, e))?;
        *len += buf.len() as u64;
        Ok(SpanRef {
            offset,
            n: samples.len(),
            t0_s: t0,
        })
    }

    /// Read a span back.
    pub fn get(&self, r: &SpanRef) -> Result<Vec<Sample>> {
        {
            let mut w = self.writer.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(mut w) = w.take() {
                w.flush().map_err(|e| io_err(&self.path, e))?;
            }
        }
        let mut guard = self.reader.lock().unwrap_or_else(|e| e.into_inner());
        if guard.is_none() {
            *guard = Some(File::open(&self.path).map_err(|e| io_err(&self.path, e))?);
        }
        let f = guard.as_mut().expect("opened above");
        let mut buf = vec![0u8; r.n * SAMPLE_BYTES];
        f.seek(SeekFrom::Start(r.offset))
            .and_then(|_| f.read_exact(&mut buf))
            .map_err(|e| io_err(&self.path, e))?;
        let v = |i: usize| {
            f64::from(f32::from_le_bytes(
                buf[i..i + 4].try_into().expect("4 bytes"),
            ))
        };
        Ok((0..r.n)
            .map(|k| {
                let b = k * SAMPLE_BYTES;
                Sample {
                    t_s: r.t0_s + v(b),
                    acc_g: [v(b + 4), v(b + 8), v(b + 12)],
                    gyro_dps: [v(b + 16), v(b + 20), v(b + 24)],
                }
            })
            .collect())
    }
}

impl Drop for SpanStore {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}
