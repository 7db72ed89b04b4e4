//! Input and output of recordings: vendor formats ([`format`]), the CSV reader ([`reader`],
//! whose stages live in `text`, `columns`, `rows`, `timebase`, `channels`, `checks` and
//! `limits`) and the writer ([`writer`]).

mod channels;
mod checks;
mod column_info;
mod columns;
pub mod cwa;
pub mod format;
mod header;
mod infer;
mod inspect;
mod labelled;
pub(crate) mod limits;
pub(crate) mod number;
pub mod reader;
mod recognise;
mod rows;
pub(crate) mod start_time;
pub mod table;
pub(crate) mod text;
mod timebase;
pub mod units;
pub mod writer;

pub use column_info::ColumnInfo;
pub use format::{ColumnRef, FormatSpec, SensorSelect, BUILTIN_FORMATS, DETECTED_FORMATS};
pub use inspect::{inspect, Inspection, PreprocessSummary};
pub use limits::{
    open_regular, read_text_limited, require_existing, MAX_FORMAT_MB, MAX_MANIFEST_MB,
    MAX_MODEL_MB, MAX_PARAMS_MB, MAX_TABLE_MB,
};
pub use reader::{
    flat_channel_warnings, read_recording, read_recording_bytes, read_recording_from, GapPolicy,
    ReadParams, ReadReport, ValidReadParams, DEFAULT_MAX_SAMPLES,
};
pub use start_time::{BadDateTime, DateTime, RecordedAt, StartFrom};
pub use units::{Quantity, Unit, UnitError, UnknownUnit};
pub use writer::{
    recording_to_csv, remove_stale_temp_files, write_atomic, write_recording, AtomicFile,
    OutputLock, WriteOptions,
};

/// The largest magnitude a signal cell may hold (raw, before the format's scale): 1e12, far
/// beyond any sensor's range in physical units or raw counts. A larger finite value (`1e308`)
/// is a corrupted cell, refused with its line and column (it would overflow the filters'
/// arithmetic and silently void the recording).
pub const MAX_ABS_SIGNAL: f64 = 1e12;

/// The longest line a recording may hold, bytes, line ending included: 65 536 (64 KiB). A row
/// of a sensor export holds a few hundred bytes, a header row of a wide multi-sensor export a
/// few kB. A longer line (a file without line ends, a runaway cell) is refused with its file
/// and line ([`crate::LdhError::LineTooLong`]) while it streams: no more than this is ever
/// held of it.
pub const MAX_LINE_BYTES: usize = 1 << 16;

#[cfg(test)]
mod tests;
