//! The reader's memory bounds (docs/robustness.md, "Size limits"): every file ldh opens is
//! opened by [`open_regular`] (a regular file, or refused without blocking), a file read whole
//! by [`read_text_limited`] up to its kind's size limit, a recording streamed up to its own
//! ([`open_limited`]: its bytes are never held whole, nor a line longer than
//! [`super::MAX_LINE_BYTES`]), and buffers sized from the input are reserved fallibly, so that a
//! file too large for the memory fails alone with a message ([`LdhError::FileTooLarge`],
//! [`LdhError::TextTooLarge`], [`LdhError::OutOfMemory`]) instead of aborting the process and
//! the batch with it.

use std::io::Read;
use std::path::Path;

use crate::error::{LdhError, Result};

/// Default size limit of a parameter file (`--params`, `--report-params`), MB: 1. A parameter
/// file holds a few dozen lines (a few kB).
pub const MAX_PARAMS_MB: f64 = 1.0;
/// Default size limit of a column map (format TOML, `--format`), MB: 1. The built-in maps hold
/// 1-3 kB, comments included.
pub const MAX_FORMAT_MB: f64 = 1.0;
/// Default size limit of a cohort manifest, MB: 64, a million rows of subjects (a row holds
/// an id, two paths and a few labels, ≈ 60 bytes).
pub const MAX_MANIFEST_MB: f64 = 64.0;
/// Default size limit of a model file (`--model`, `ldh train`'s `model_*.json`), MB: 16.
/// Parsing takes about 23 times the file's size in memory (a 31 MB forest peaked at 0.72 GB),
/// so a model stays well under 1 GB. A default 100-tree forest takes ≈ 0.6 kB per training row
/// (28 kB for 48 rows): about 25 000 rows fit, a hundred times the largest cohort ldh has met.
pub const MAX_MODEL_MB: f64 = 16.0;
/// Default size limit of a table ldh wrote and reads back (`recordings.json`, `table4.json`,
/// `cv_results.json`, `truth.json`, `strides.csv`), MB: 256, as for a recording.
pub const MAX_TABLE_MB: f64 = 256.0;

/// Open `path` for reading, refusing anything but a regular file without ever blocking: the
/// file is opened non-blocking (a FIFO without a writer opens at once instead of waiting), then
/// the opened handle, not the name, is checked, so that a FIFO or device swapped in between a
/// check and the open is refused too. `what` names the file's role in the message (`a model
/// file`). Returns the file and its size in bytes.
///
/// On a regular file `O_NONBLOCK` changes nothing (reads of regular files never block).
pub fn open_regular(path: &Path, what: &str) -> Result<(std::fs::File, u64)> {
    let io = |source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "not a regular file but {}; {what} must be a regular file",
                file_type_name(&meta.file_type())
            ),
        )));
    }
    Ok((file, meta.len()))
}

/// Refuse, before any work, a path that does not exist: the first one, as
/// [`LdhError::Io`] of kind not found (`X: cannot read: no such file or folder`), the wording
/// and the error every command gives for a misspelt path.
pub fn require_existing(paths: &[std::path::PathBuf]) -> Result<()> {
    // The path itself, not what a symbolic link points to: a dangling link or a loop is the
    // file's own error when it is read ("too many levels of symbolic links"), not a misspelling.
    match paths.iter().find(|p| std::fs::symlink_metadata(p).is_err()) {
        Some(p) => Err(LdhError::Io {
            path: p.clone(),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file or folder"),
        }),
        None => Ok(()),
    }
}

/// What a file that is not a regular file is, for messages.
fn file_type_name(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a folder"
    } else {
        "not a file"
    }
}

/// The whole text of a regular file of at most `max_mb` MB (10^6 bytes), read by every part of
/// ldh that reads a file whole (parameter files, column maps, manifests, models, tables read
/// back), with the default limits [`MAX_PARAMS_MB`], [`MAX_FORMAT_MB`], [`MAX_MANIFEST_MB`],
/// [`MAX_MODEL_MB`] and [`MAX_TABLE_MB`] (docs/robustness.md, "Size limits"). `what` names the
/// file's role in messages (`a model file`).
///
/// Refused: a folder, FIFO or device ([`LdhError::Io`], without blocking: see
/// [`open_regular`]), a larger file ([`LdhError::TextTooLarge`], before it is read; a file
/// whose content outgrows its stated size, as in `/proc`, once it passes the limit) and text
/// that is not UTF-8 ([`LdhError::Io`]). The memory taken is at most the limit.
pub fn read_text_limited(path: &Path, max_mb: f64, what: &'static str) -> Result<String> {
    let (file, len) = open_regular(path, what)?;
    let limit = (max_mb.max(0.0) * 1e6) as u64;
    let too_large = |size: u64| LdhError::TextTooLarge {
        path: path.to_path_buf(),
        what,
        size_mb: size as f64 / 1e6,
        limit_mb: max_mb,
    };
    if len > limit {
        return Err(too_large(len));
    }
    let mut text = String::new();
    reserve_text(&mut text, len, path)?;
    file.take(limit.saturating_add(1))
        .read_to_string(&mut text)
        .map_err(|source| LdhError::Io {
            path: path.to_path_buf(),
            source,
        })?;
    if text.len() as u64 > limit {
        return Err(too_large(text.len() as u64));
    }
    Ok(text)
}

/// Reserve `len` bytes in `text`, fallibly ([`LdhError::OutOfMemory`]).
fn reserve_text(text: &mut String, len: u64, path: &Path) -> Result<()> {
    let n = usize::try_from(len).unwrap_or(usize::MAX);
    text.try_reserve_exact(n)
        .map_err(|_| LdhError::OutOfMemory {
            path: path.to_path_buf(),
            needed_mb: len as f64 / 1e6,
        })
}

/// A regular file of at most `max_mb` MB, opened for buffered reading. Folders, FIFOs and
/// devices are refused without blocking ([`open_regular`]: a FIFO would block forever,
/// `/dev/zero` never ends); so is a larger file, before it is read. The read itself is bounded
/// too (one byte past the limit), for files whose stated size is not their content (`/proc`):
/// [`super::text::Lines`] refuses the content once it passes the limit.
pub(super) fn open_limited(
    path: &Path,
    max_mb: f64,
) -> Result<std::io::BufReader<std::io::Take<std::fs::File>>> {
    let (file, len) = open_regular(path, "a recording")?;
    let limit = (max_mb * 1e6) as u64;
    if len > limit {
        return Err(LdhError::FileTooLarge {
            path: path.to_path_buf(),
            size_mb: len as f64 / 1e6,
            limit_mb: max_mb,
        });
    }
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
