//! The reader's memory bounds (docs/robustness.md): a file is read only up to a size limit
//! (and streamed: its bytes are never held whole), and buffers sized from the input are
//! reserved fallibly, so that a file too large for the
//! memory fails alone with a message ([`LdhError::FileTooLarge`], [`LdhError::OutOfMemory`])
//! instead of aborting the process and the batch with it.

use std::path::Path;

use crate::error::{LdhError, Result};

/// A regular file of at most `max_mb` MB, opened for buffered reading. Folders, FIFOs and
/// devices are refused (a FIFO would block forever, `/dev/zero` never ends); so is a larger
/// file, before it is read. The read itself is bounded too (one byte past the limit), for files
/// whose stated size is not their content (`/proc`): [`super::text::Lines`] refuses the content
/// once it passes the limit.
pub(crate) fn open_limited(
    path: &Path,
    max_mb: f64,
) -> Result<std::io::BufReader<std::io::Take<std::fs::File>>> {
    use std::io::Read;
    let io = |source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a folder, FIFO or device)",
        )));
    }
    let limit = (max_mb * 1e6) as u64;
    if meta.len() > limit {
        return Err(LdhError::FileTooLarge {
            path: path.to_path_buf(),
            size_mb: meta.len() as f64 / 1e6,
            limit_mb: max_mb,
        });
    }
    let file = std::fs::File::open(path).map_err(io)?;
    Ok(std::io::BufReader::with_capacity(
        1 << 16,
        file.take(limit.saturating_add(1)),
    ))
}

/// Memory the reading and the analysis of one leg need at their peak, bytes per sample, with a
/// wide margin (measured when this was set: a 2-hour pair of 720 000 samples per leg peaked at
/// 1.0 GB; since the attitude smoother keeps less per sample, 0.23 GB, docs/robustness.md).
/// Checked with a fallible reservation once the rows are parsed.
const HEADROOM_BYTES_PER_SAMPLE: usize = 1024;

/// Reserve room for `n` more items in `v`, or [`LdhError::OutOfMemory`] naming `path`.
pub(crate) fn reserve<T>(v: &mut Vec<T>, n: usize, path: &Path) -> Result<()> {
    v.try_reserve_exact(n).map_err(|_| LdhError::OutOfMemory {
        path: path.to_path_buf(),
        needed_mb: n as f64 * std::mem::size_of::<T>() as f64 / 1e6,
    })
}

/// Check that the peak memory of reading and analysing a leg of `rows` samples can be had
/// (`HEADROOM_BYTES_PER_SAMPLE` each, reserved and released at once): the rest of the reading
/// and the analysis allocate as they go, and a leg too large must fail alone.
pub(super) fn check_headroom(rows: usize, path: &Path) -> Result<()> {
    let mut probe: Vec<u8> = Vec::new();
    reserve(
        &mut probe,
        rows.saturating_mul(HEADROOM_BYTES_PER_SAMPLE),
        path,
    )?;
    drop(probe);
    Ok(())
}
