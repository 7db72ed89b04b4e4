//! Reading one sensor's CSV export into a [`Recording`] (SPEC §2).
//!
//! What is detected, and reported in [`ReadReport::notes`]: a UTF-8 byte-order mark, a
//! `sep=` line, the delimiter (most frequent of `,` `;` tab in the header row), comment lines
//! before the header, the format (the first built-in format whose columns are all in the
//! header), the sampling rate (from the timestamps), jitter, gaps and clipped samples.
//!
//! What is refused, with the file, line and column: empty, binary or non-UTF-8 files, missing
//! columns, rows with a wrong number of fields, text or NaN/Inf in number columns, timestamps
//! that repeat or go backwards, gaps longer than `max_gap_s` (with [`GapPolicy::Reject`]),
//! recordings too short to hold three strides, and units that are physically implausible
//! (e.g. angular velocity in rad/s declared as deg/s).
//!
//! [`read_recording_from`] runs the stages in order, each in its own file, streaming: a byte
//! stream to numbered lines read one at a time (`text.rs`), the header and the format (`columns.rs`), the data rows into columns
//! (`rows.rs`), the time base — seconds, gaps, the fitted rate and the uniform grid
//! (`timebase.rs`) —, the scale, clipping flags, units and axes (`channels.rs`), then the
//! plausibility checks (`checks.rs`); the memory bounds are in `limits.rs`. The file's bytes
//! are never held whole: memory is the seven columns kept (time and six channels, 56 bytes a
//! row) plus what the later stages allocate, and a recording with more rows than
//! `max_samples` is refused while reading.
//!
//! Timing: every row of the kept segment gets an integer sample index (each interval rounded to
//! a whole number of median periods), and the period is the least-squares slope of time against
//! index. When every timestamp lies within 10 % of a period of that uniform grid and no row is
//! missing, samples are kept as they are; otherwise the channels are resampled onto the grid by
//! linear interpolation (gaps up to `max_gap_s` are bridged that way).

use serde::{Deserialize, Serialize};
use std::io::BufRead;
use std::path::{Path, PathBuf};

use super::channels::{scale_and_flag_clipping, to_ldh_frame};
use super::format::{Delimiter, FormatSpec};
use super::infer::infer_units;
use super::limits::{check_headroom, open_limited};
use super::rows::{parse_rows, Layout};
use super::start_time::{start_in_time, start_in_utc_cells, utc_columns, RecordedAt, StartFrom};
use super::text::{split_fields, Lines};
use super::timebase::{
    check_median_rate, check_monotonic, fit_grid, place_on_grid, split_at_gaps, times_in_seconds,
    Grid, RateBounds, Segments,
};
use crate::error::{LdhError, Result};
use crate::recording::Recording;

// The reader's public helpers, at their historical paths (`ldh_core::io::reader::...`).
pub use super::channels::detect_clipping;
pub use super::checks::{check_units_plausible, flat_channel_warnings};
pub use super::start_time::parse_iso8601;
pub use super::timebase::{interp_linear, GapInfo};
// For the unit tests.
#[cfg(test)]
pub(crate) use super::limits::reserve;

/// What to do with a gap in the timestamps longer than `max_gap_s`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum GapPolicy {
    /// Split at the gap and keep the longest segment (the others are listed in the report).
    #[default]
    Split,
    /// Refuse the recording.
    Reject,
}

/// Reader parameters (unchecked). See [`ReadParams::check`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReadParams {
    /// Longest gap between two timestamps that is bridged by interpolation, in s. Default 0.2.
    pub max_gap_s: f64,
    /// What to do with longer gaps. Default [`GapPolicy::Split`].
    pub gap_policy: GapPolicy,
    /// Shortest usable recording, in s: three strides of slow walking. Default 4.0.
    pub min_duration_s: f64,
    /// Lowest plausible sampling rate in Hz. Default 20.
    pub min_rate_hz: f64,
    /// Highest plausible sampling rate in Hz. Default 2000.
    pub max_rate_hz: f64,
    /// Refuse data whose magnitudes do not fit the declared units. Default true.
    pub check_units: bool,
    /// Largest file read, in MB (10^6 bytes). Default 256: 14 h of 7 columns at 100 Hz, 1.4 h
    /// at 1000 Hz. A larger file is refused with a message before it is read, so that `/dev/zero`
    /// or a mistaken multi-gigabyte export cannot exhaust the memory.
    pub max_file_size_mb: f64,
    /// Most data rows (samples) in one recording. Default 2 500 000: 6.9 h at 100 Hz, 42 min at
    /// 1000 Hz. The analysis keeps per-sample state, about 150 bytes per sample of a pair at
    /// its peak (measured: a pair of 720 000-sample legs 0.23 GB, of 2 000 000-sample legs
    /// 0.62 GB, `--jobs 1`), so the default keeps one subject under 1 GB. A longer recording
    /// is refused while it is read, naming its row count, before the rows past the limit are
    /// stored: a 10-million-row file costs no more memory than the limit.
    pub max_samples: usize,
}

/// Default [`ReadParams::max_samples`].
pub const DEFAULT_MAX_SAMPLES: usize = 2_500_000;

impl Default for ReadParams {
    fn default() -> Self {
        ReadParams {
            max_gap_s: 0.2,
            gap_policy: GapPolicy::Split,
            min_duration_s: 4.0,
            min_rate_hz: 20.0,
            max_rate_hz: 2000.0,
            check_units: true,
            max_file_size_mb: 256.0,
            max_samples: DEFAULT_MAX_SAMPLES,
        }
    }
}

/// Checked reader parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidReadParams(ReadParams);

impl Default for ValidReadParams {
    /// [`ReadParams::default`], which passes its check (a test says so).
    fn default() -> Self {
        ValidReadParams(ReadParams::default())
    }
}

impl ReadParams {
    /// Set `max_gap_s`.
    pub fn max_gap_s(mut self, v: f64) -> Self {
        self.max_gap_s = v;
        self
    }
    /// Set `gap_policy`.
    pub fn gap_policy(mut self, v: GapPolicy) -> Self {
        self.gap_policy = v;
        self
    }
    /// Set `min_duration_s`.
    pub fn min_duration_s(mut self, v: f64) -> Self {
        self.min_duration_s = v;
        self
    }
    /// Set `check_units`.
    pub fn check_units(mut self, v: bool) -> Self {
        self.check_units = v;
        self
    }
    /// Validate once into the type the reader accepts.
    pub fn check(&self) -> Result<ValidReadParams> {
        let p = self;
        if !(p.max_gap_s.is_finite() && p.max_gap_s > 0.0) {
            return Err(LdhError::param("max_gap_s", p.max_gap_s, "must be > 0"));
        }
        if !(p.min_duration_s.is_finite() && p.min_duration_s >= 0.0) {
            return Err(LdhError::param(
                "min_duration_s",
                p.min_duration_s,
                "must be ≥ 0",
            ));
        }
        if !(p.min_rate_hz > 0.0 && p.max_rate_hz > p.min_rate_hz && p.max_rate_hz.is_finite()) {
            return Err(LdhError::param(
                "min_rate_hz/max_rate_hz",
                format!("{}/{}", p.min_rate_hz, p.max_rate_hz),
                "need 0 < min_rate_hz < max_rate_hz",
            ));
        }
        if !(p.max_file_size_mb.is_finite() && p.max_file_size_mb > 0.0) {
            return Err(LdhError::param(
                "max_file_size_mb",
                p.max_file_size_mb,
                "must be > 0",
            ));
        }
        if p.max_samples == 0 {
            return Err(LdhError::param("max_samples", p.max_samples, "must be ≥ 1"));
        }
        Ok(ValidReadParams(self.clone()))
    }
}

impl std::ops::Deref for ValidReadParams {
    type Target = ReadParams;
    fn deref(&self) -> &ReadParams {
        &self.0
    }
}

/// What the reader found and assumed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReadReport {
    /// The file.
    pub file: PathBuf,
    /// The format used.
    pub format: String,
    /// Whether the format was detected (true) or given (false).
    pub format_detected: bool,
    /// The delimiter used.
    pub delimiter: String,
    /// A UTF-8 byte-order mark was present.
    pub bom: bool,
    /// 1-based line of the header row.
    pub header_line: u64,
    /// Data rows read.
    pub rows: usize,
    /// Sampling rate measured (or stated), Hz.
    pub fs_hz: f64,
    /// Largest deviation of a timestamp from the uniform grid, ms.
    pub max_jitter_ms: f64,
    /// Channels were resampled onto a uniform grid.
    pub resampled: bool,
    /// Gaps longer than `max_gap_s`.
    pub gaps: Vec<GapInfo>,
    /// Segments (split at gaps) that were dropped, as (start_s, end_s) in the file clock.
    pub dropped_segments: Vec<(f64, f64)>,
    /// Clipped samples per channel: acc x, y, z, gyro x, y, z.
    pub saturated_per_channel: [usize; 6],
    /// Samples with any channel clipped.
    pub saturated_samples: usize,
    /// Samples kept.
    pub samples: usize,
    /// Duration kept, s.
    pub duration_s: f64,
    /// Each column read: the channel it feeds, the unit understood and the conversion applied
    /// (`ldh inspect` shows them).
    #[serde(default)]
    pub columns: Vec<super::ColumnInfo>,
    /// When the recording started, where the file says it (a header line, UTC columns, the
    /// first ISO or Unix timestamp); `None` when it does not.
    #[serde(default)]
    pub recorded_at: Option<RecordedAt>,
    /// Assumptions and findings, one sentence each.
    pub notes: Vec<String>,
    /// Problems that did not stop the reading but need the user's attention (data dropped at a
    /// gap, a constant channel, a sensor that froze), one sentence each.
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// Read a sensor CSV with a known format (`Some`) or by detecting a built-in one (`None`).
///
/// Returns the recording (its `source` set to `path`) and what was found.
pub fn read_recording(
    path: impl AsRef<Path>,
    format: Option<&FormatSpec>,
    params: &ValidReadParams,
) -> Result<(Recording, ReadReport)> {
    let path = path.as_ref();
    let file = open_limited(path, params.max_file_size_mb)?;
    read_from(file, Some(params.max_file_size_mb), path, format, params)
}

/// As [`read_recording`], from bytes in memory (no size limit); `path` is used in messages.
pub fn read_recording_bytes(
    bytes: &[u8],
    path: &Path,
    format: Option<&FormatSpec>,
    params: &ValidReadParams,
) -> Result<(Recording, ReadReport)> {
    read_from(bytes, None, path, format, params)
}

/// As [`read_recording`], from any buffered byte stream (read once, line by line; no size
/// limit); `path` is used in messages.
pub fn read_recording_from(
    src: impl BufRead,
    path: &Path,
    format: Option<&FormatSpec>,
    params: &ValidReadParams,
) -> Result<(Recording, ReadReport)> {
    read_from(src, None, path, format, params)
}

/// The reader. The stages, in order: check the first bytes and stream numbered lines, find the
/// header and the format, parse the rows, put the time in seconds and check it, split at gaps,
/// fit the grid and place the channels on it, scale and flag clipping, convert to g and deg/s
/// in ldh's frame, then the duration, flat-channel and unit checks. `limit_mb`: the content's
/// size limit.
fn read_from(
    src: impl BufRead,
    limit_mb: Option<f64>,
    path: &Path,
    format: Option<&FormatSpec>,
    params: &ValidReadParams,
) -> Result<(Recording, ReadReport)> {
    if let Some(f) = format {
        f.validate()?;
    }
    let mut lines = Lines::new(src, path, limit_mb)?;
    let bom = lines.bom;
    let mut notes = Vec::new();
    let mut warnings = Vec::new();
    if bom {
        notes.push("UTF-8 byte-order mark found and ignored".to_string());
    }

    // The header row and the format (column resolution: `columns.rs`).
    let mut found = super::header::find_header(&mut lines, format, path, &mut notes)?;
    let delim_name = header_notes(&found, format.is_none(), &mut notes);

    // Data rows into columns, from the first after the header (the start read on the way).
    let (first_row, mut recorded_at) = first_row_and_start(&mut lines, &mut found)?;
    let layout = Layout {
        path,
        spec: &found.spec,
        delim: found.delim,
        header_fields: &found.fields,
        cols: found.cols,
    };
    let rows = parse_rows(&mut lines, first_row, &layout, params.max_samples)?;
    drop(lines);
    let n_rows = rows.row_lines.len();
    check_headroom(n_rows, path)?;
    if n_rows == 0 {
        return Err(too_short(path, 0.0, 0, params));
    }
    let bounds = RateBounds {
        min_hz: params.min_rate_hz,
        max_hz: params.max_rate_hz,
    };
    // Units the header does not state, from the signal (`infer.rs`).
    let assumed = infer_units(&mut found.spec, found.infer, &rows, &bounds, &mut notes);
    let columns = super::column_info::describe_columns(&found, &assumed);
    let spec = &found.spec;

    // The time base: seconds, checks, the longest segment between gaps, the grid.
    if let (None, Some(&t), Some(i)) = (recorded_at, rows.time_raw.first(), found.cols.time) {
        recorded_at = start_in_time(t, spec.time.unit, &found.fields[i]);
    }
    if let Some(r) = recorded_at {
        notes.push(format!(
            "recording start {} (from the {})",
            r.at.iso(),
            r.from.words()
        ));
    }
    let (grid, segments, mut channels) = time_base(
        rows,
        (spec, found.cols.time),
        path,
        params,
        bounds,
        &mut notes,
        &mut warnings,
    )?;

    // Channel values: scale, clipping, units and axes.
    let clipping = scale_and_flag_clipping(&mut channels, spec, grid.n_out, &mut notes);
    let (acc_g, gyro_dps) = to_ldh_frame(channels, spec, &mut notes)?;

    let duration_s = (grid.n_out - 1) as f64 / grid.fs;
    if duration_s < params.min_duration_s {
        return Err(too_short(path, duration_s, grid.n_out, params));
    }
    warnings.extend(flat_channel_warnings(&acc_g, &gyro_dps, grid.fs, grid.t0));
    let mut rec = Recording::new(grid.fs, acc_g, gyro_dps, vec![])
        .and_then(|r| r.with_sensor_saturation(clipping.acc, clipping.gyro))
        .map_err(|e| LdhError::Signal {
            context: path.display().to_string(),
            reason: e.to_string(),
        })?;
    rec.t0_s = grid.t0;
    rec.source = Some(path.to_path_buf());
    rec.recorded_at = recorded_at;
    if params.check_units {
        check_units_plausible(&rec, spec, path)?;
    }

    let report = ReadReport {
        file: path.to_path_buf(),
        format: spec.name.clone(),
        format_detected: format.is_none(),
        delimiter: delim_name.to_string(),
        bom,
        header_line: found.line,
        rows: n_rows,
        fs_hz: grid.fs,
        max_jitter_ms: grid.max_jitter_s * 1e3,
        resampled: !grid.uniform,
        gaps: segments.gaps,
        dropped_segments: segments.dropped,
        saturated_per_channel: clipping.per_channel,
        saturated_samples: clipping.samples,
        samples: grid.n_out,
        duration_s,
        columns,
        recorded_at,
        notes,
        warnings,
    };
    Ok((rec, report))
}

/// The first data row and the start of the recording as the header gives it. Skips the rows
/// the format skips after the header row (counted from the first data row when the file has
/// none); the start date and time is a header line's, else that of Xsens' UTC columns of the
/// first data row (read ahead here and handed on to the row parser), else `None` (the caller
/// then tries the time column's first value).
#[allow(clippy::type_complexity)]
fn first_row_and_start<R: BufRead>(
    lines: &mut Lines<R>,
    found: &mut super::header::Header,
) -> Result<(Option<(u64, String)>, Option<RecordedAt>)> {
    let mut first_row = found.first_row.take();
    for _ in 0..found.spec.skip_rows_after_header {
        if first_row.take().is_none() && lines.next_line()?.is_none() {
            break;
        }
    }
    let mut recorded_at = found.start.map(|at| RecordedAt {
        at,
        from: StartFrom::Header,
    });
    if let (None, Some(at)) = (recorded_at, utc_columns(&found.fields)) {
        if first_row.is_none() {
            first_row = lines.next_line()?.map(|(n, l)| (n, l.to_string()));
        }
        if let Some((_, row)) = &first_row {
            let mut cells = Vec::new();
            split_fields(row, found.delim, &mut cells);
            recorded_at = start_in_utc_cells(&cells, at).map(|at| RecordedAt {
                at,
                from: StartFrom::UtcColumns,
            });
        }
    }
    Ok((first_row, recorded_at))
}

/// The time base of the parsed rows: the times in seconds (`spec`'s unit; `time_col`, the time
/// column, for messages), checked to rise at a plausible rate, the longest segment between
/// gaps, the grid fitted to it and the six channels placed on the grid.
fn time_base(
    rows: super::rows::Rows,
    (spec, time_col): (&FormatSpec, Option<usize>),
    path: &Path,
    params: &ValidReadParams,
    bounds: RateBounds,
    notes: &mut Vec<String>,
    warnings: &mut Vec<String>,
) -> Result<(Grid, Segments, [Vec<f64>; 6])> {
    let n_rows = rows.row_lines.len();
    let times = times_in_seconds(rows.time_raw, spec, n_rows, notes);
    check_monotonic(&times, &rows.row_lines, time_col, path)?;
    check_median_rate(&times, bounds, spec.time.unit, path)?;
    let reject_gaps = params.gap_policy == GapPolicy::Reject;
    let segments = split_at_gaps(
        &times,
        &rows.row_lines,
        params.max_gap_s,
        reject_gaps,
        path,
        warnings,
    )?;
    let seg = segments.start..segments.end;
    let seg_t = &times[seg.clone()];
    let span = seg_t[seg_t.len() - 1] - seg_t[0];
    if seg_t.len() < 2 || span <= 0.0 {
        return Err(too_short(path, span.max(0.0), seg_t.len(), params));
    }
    let grid = fit_grid(seg_t, spec, bounds, path, warnings)?;
    let channels = place_on_grid(rows.raw, seg, seg_t, &grid, notes);
    Ok((grid, segments, channels))
}

/// The notes about the header found (`detected`: the format was detected, not given): the
/// format, a file without a header row, a detected delimiter. Returns the delimiter's name.
fn header_notes(
    found: &super::header::Header,
    detected: bool,
    notes: &mut Vec<String>,
) -> &'static str {
    if detected {
        notes.push(format!("format detected: {}", found.spec.name));
    }
    if !found.has_row {
        notes.push("no header row: columns taken by number".to_string());
    }
    let delim_name = Delimiter::from_byte(found.delim)
        .map(|d| d.name())
        .unwrap_or("?");
    if found.spec.delimiter == Delimiter::Auto && found.sep_line.is_none() {
        notes.push(format!("delimiter detected: {delim_name}"));
    }
    delim_name
}

/// [`LdhError::TooShort`] for `path`: `duration_s` s in `samples` samples, below the minimum.
fn too_short(path: &Path, duration_s: f64, samples: usize, params: &ReadParams) -> LdhError {
    LdhError::TooShort {
        path: path.to_path_buf(),
        duration_s,
        samples,
        min_s: params.min_duration_s,
    }
}
