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
//! Timing: every row of the kept segment gets an integer sample index (each interval rounded to
//! a whole number of median periods), and the period is the least-squares slope of time against
//! index. When every timestamp lies within 10 % of a period of that uniform grid and no row is
//! missing, samples are kept as they are; otherwise the channels are resampled onto the grid by
//! linear interpolation (gaps up to `max_gap_s` are bridged that way).

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

use super::format::{AccUnit, Decimal, Delimiter, FormatSpec, GyroUnit, TimeUnit};
use crate::error::{LdhError, Location, Result};
use crate::recording::{Recording, STANDARD_GRAVITY_MPS2};

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
}

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
        }
    }
}

/// Checked reader parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidReadParams(ReadParams);

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
        Ok(ValidReadParams(self.clone()))
    }
}

impl std::ops::Deref for ValidReadParams {
    type Target = ReadParams;
    fn deref(&self) -> &ReadParams {
        &self.0
    }
}

/// A gap found in the timestamps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GapInfo {
    /// Time before the gap, s (file clock).
    pub from_s: f64,
    /// Length of the gap, s.
    pub gap_s: f64,
    /// Line of the row after the gap.
    pub line: u64,
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
    let bytes = read_limited(path, params.max_file_size_mb)?;
    read_recording_bytes(&bytes, path, format, params)
}

/// The bytes of a regular file of at most `max_mb` MB. Folders, FIFOs and devices are refused
/// (a FIFO would block forever, `/dev/zero` never ends); so is a larger file, before it is read.
/// The read itself is bounded too, for files whose stated size is not their content (`/proc`).
fn read_limited(path: &Path, max_mb: f64) -> Result<Vec<u8>> {
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
    let too_large = |size: u64| LdhError::FileTooLarge {
        path: path.to_path_buf(),
        size_mb: size as f64 / 1e6,
        limit_mb: max_mb,
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::new();
    reserve(&mut bytes, meta.len() as usize + 1, path)?;
    std::fs::File::open(path)
        .map_err(io)?
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Memory the reading and the analysis of one leg need at their peak, bytes per sample
/// (measured: a 2-hour pair of 720 000 samples per leg peaks at 1.0 GB, docs/robustness.md),
/// with a margin. Checked with a fallible reservation once the rows are parsed.
const HEADROOM_BYTES_PER_SAMPLE: usize = 1024;

/// Reserve room for `n` more items in `v`, or [`LdhError::OutOfMemory`] naming `path`.
pub(crate) fn reserve<T>(v: &mut Vec<T>, n: usize, path: &Path) -> Result<()> {
    v.try_reserve_exact(n).map_err(|_| LdhError::OutOfMemory {
        path: path.to_path_buf(),
        needed_mb: n as f64 * std::mem::size_of::<T>() as f64 / 1e6,
    })
}

/// Number of lines of `bytes` (newlines, plus one for a last line without one).
fn bytecount_lines(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b == b'\n').count() + usize::from(!bytes.ends_with(b"\n"))
}

/// As [`read_recording`], from bytes in memory; `path` is used in messages.
pub fn read_recording_bytes(
    bytes: &[u8],
    path: &Path,
    format: Option<&FormatSpec>,
    params: &ValidReadParams,
) -> Result<(Recording, ReadReport)> {
    if let Some(f) = format {
        f.validate()?;
    }
    let text = decode_text(bytes, path)?;
    let bom = text.len() + 3 == bytes.len() && bytes.starts_with(&[0xEF, 0xBB, 0xBF]);
    let mut notes = Vec::new();
    let mut warnings = Vec::new();
    if bom {
        notes.push("UTF-8 byte-order mark found and ignored".to_string());
    }

    // Lines with their 1-based numbers (the buffers sized from the input are reserved
    // fallibly: a file too large for the memory is this file's error, not an abort).
    let n_lines = bytecount_lines(bytes);
    let mut lines: Vec<(u64, &str)> = Vec::new();
    reserve(&mut lines, n_lines, path)?;
    lines.extend(
        text.lines()
            .enumerate()
            .map(|(i, l)| (i as u64 + 1, l.strip_suffix('\r').unwrap_or(l))),
    );

    // Find the header row and the format (column resolution: `columns.rs`).
    let found = super::columns::find_header(&lines, format, path, &mut notes)?;
    let (hidx, delim, header_fields) = (found.index, found.delim, found.fields);
    let spec = found.spec;
    let sep_line_delim = found.sep_line;
    let header_line = lines[hidx].0;
    if format.is_none() {
        notes.push(format!("format detected: {}", spec.name));
    }
    if !found.has_row {
        notes.push("no header row: columns taken by number".to_string());
    }
    let delim_name = Delimiter::from_byte(delim).map(|d| d.name()).unwrap_or("?");
    if spec.delimiter == Delimiter::Auto && sep_line_delim.is_none() {
        notes.push(format!("delimiter detected: {delim_name}"));
    }

    // Column indices.
    let time_col = found.cols.time;
    let acc_cols = found.cols.acc;
    let gyro_cols = found.cols.gyro;
    let expected = header_fields.len();

    // Data rows.
    let first_data = hidx + usize::from(found.has_row) + spec.skip_rows_after_header;
    let mut time_raw: Vec<f64> = Vec::new();
    let mut raw: [Vec<f64>; 6] = Default::default();
    let mut row_lines: Vec<u64> = Vec::new();
    let n_rows = lines.len().saturating_sub(first_data);
    reserve(&mut time_raw, n_rows, path)?;
    reserve(&mut row_lines, n_rows, path)?;
    for r in &mut raw {
        reserve(r, n_rows, path)?;
    }
    let mut fields: Vec<&str> = Vec::with_capacity(expected);
    let mut rdr_buf = String::new();
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
        split_fields(line, delim, &mut fields, &mut rdr_buf);
        if fields.len() != expected {
            // Tolerate one trailing empty field (a trailing delimiter).
            let trailing_empty =
                fields.len() == expected + 1 && fields.last().is_some_and(|f| f.is_empty());
            if !trailing_empty {
                // Decimal commas in a comma-separated file double the fields.
                let hint = if delim == b','
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
                    "; it is the last line: the file looks truncated (an interrupted export or copy?)".to_string()
                } else {
                    String::new()
                };
                return Err(LdhError::FieldCount {
                    loc: Location::line(path, lineno),
                    found: fields.len(),
                    expected,
                    hint,
                });
            }
        }
        if let Some(tc) = time_col {
            let cell = fields[tc];
            let v = match spec.time.unit {
                TimeUnit::Iso8601 => parse_iso8601(cell).ok_or_else(|| LdhError::NotANumber {
                    loc: Location::cell(path, lineno, tc + 1),
                    column: header_fields[tc].clone(),
                    value: cell.to_string(),
                    hint: "; expected an ISO 8601 timestamp like 2024-03-01T10:15:02.250".into(),
                })?,
                _ => parse_number(
                    cell,
                    spec.decimal,
                    delim,
                    path,
                    lineno,
                    tc,
                    &header_fields[tc],
                )?,
            };
            time_raw.push(v);
        }
        for (k, &c) in acc_cols.iter().chain(gyro_cols.iter()).enumerate() {
            let v = parse_number(
                fields[c],
                spec.decimal,
                delim,
                path,
                lineno,
                c,
                &header_fields[c],
            )?;
            if v.abs() > super::MAX_ABS_SIGNAL {
                return Err(LdhError::OutOfRange {
                    loc: Location::cell(path, lineno, c + 1),
                    column: header_fields[c].clone(),
                    value: fields[c].chars().take(60).collect(),
                });
            }
            raw[k].push(v);
        }
        row_lines.push(lineno);
    }
    let rows = row_lines.len();
    // The rest of the reading and the analysis of this leg allocate as they go; check once
    // that their peak can be had, so that a leg too large for the memory fails alone.
    let mut probe: Vec<u8> = Vec::new();
    reserve(
        &mut probe,
        rows.saturating_mul(HEADROOM_BYTES_PER_SAMPLE),
        path,
    )?;
    drop(probe);
    if rows == 0 {
        return Err(LdhError::TooShort {
            path: path.to_path_buf(),
            duration_s: 0.0,
            samples: 0,
            min_s: params.min_duration_s,
        });
    }

    // Time in seconds.
    let times: Vec<f64> = match spec.time.unit {
        TimeUnit::Seconds | TimeUnit::Iso8601 => time_raw,
        TimeUnit::Milliseconds => time_raw.iter().map(|t| t * 1e-3).collect(),
        TimeUnit::Microseconds => time_raw.iter().map(|t| t * 1e-6).collect(),
        TimeUnit::Counter => {
            let rate = spec.time.rate_hz.expect("validated");
            let wrap = spec.time.counter_wrap.map(|w| w as f64);
            let mut out = Vec::with_capacity(rows);
            let mut offset = 0.0;
            let mut prev = f64::NEG_INFINITY;
            for &c in &time_raw {
                if let Some(w) = wrap {
                    if c < prev && prev - c > w / 2.0 {
                        offset += w;
                    }
                }
                prev = c;
                out.push((c + offset) / rate);
            }
            if offset > 0.0 {
                notes.push(format!(
                    "sample counter wrapped {} time(s)",
                    (offset / wrap.unwrap_or(1.0)) as u64
                ));
            }
            out
        }
        TimeUnit::None => {
            let rate = spec.time.rate_hz.expect("validated");
            notes.push(format!(
                "no time column: uniform samples at the stated {rate} Hz"
            ));
            (0..rows).map(|i| i as f64 / rate).collect()
        }
    };

    // Monotonic time.
    for i in 1..times.len() {
        if times[i] <= times[i - 1] {
            return Err(LdhError::NonMonotonicTime {
                loc: Location::cell(path, row_lines[i], time_col.map_or(1, |c| c + 1)),
                value: times[i],
                previous: times[i - 1],
            });
        }
    }

    // A median interval outside the plausible rates is a time-unit problem, not a series of
    // gaps (e.g. milliseconds written into a seconds column).
    if times.len() >= 3 {
        let mut dts: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
        dts.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let rate = 1.0 / dts[dts.len() / 2];
        if !(rate >= params.min_rate_hz && rate <= params.max_rate_hz) {
            return Err(LdhError::SamplingRate {
                path: path.to_path_buf(),
                reason: format!(
                    "the median interval between timestamps is {:.6} s ({rate:.3} Hz), outside the plausible {}–{} Hz; check the time unit ({:?} declared: milliseconds written as seconds?)",
                    dts[dts.len() / 2],
                    params.min_rate_hz,
                    params.max_rate_hz,
                    spec.time.unit
                ),
            });
        }
    }

    // Gaps → segments.
    let mut gaps = Vec::new();
    let mut cuts = vec![0usize];
    for i in 1..times.len() {
        let dt = times[i] - times[i - 1];
        if dt > params.max_gap_s {
            if params.gap_policy == GapPolicy::Reject {
                return Err(LdhError::Gap {
                    loc: Location::line(path, row_lines[i]),
                    gap_s: dt,
                    from_s: times[i - 1],
                    max_gap_s: params.max_gap_s,
                });
            }
            gaps.push(GapInfo {
                from_s: times[i - 1],
                gap_s: dt,
                line: row_lines[i],
            });
            cuts.push(i);
        }
    }
    cuts.push(times.len());
    let (seg_start, seg_end) = cuts
        .windows(2)
        .map(|w| (w[0], w[1]))
        .max_by(|a, b| {
            let da = times[a.1 - 1] - times[a.0];
            let db = times[b.1 - 1] - times[b.0];
            da.partial_cmp(&db)
                .unwrap_or(std::cmp::Ordering::Equal)
                .then(b.0.cmp(&a.0))
        })
        .expect("at least one segment");
    let dropped_segments: Vec<(f64, f64)> = cuts
        .windows(2)
        .filter(|w| w[0] != seg_start)
        .map(|w| (times[w[0]], times[w[1] - 1]))
        .collect();
    if !gaps.is_empty() {
        warnings.push(format!(
            "{} gap(s) longer than {} s: kept the longest segment {:.2}–{:.2} s, dropped {}",
            gaps.len(),
            params.max_gap_s,
            times[seg_start],
            times[seg_end - 1],
            dropped_segments.len()
        ));
    }
    let seg_t = &times[seg_start..seg_end];
    let n_seg = seg_t.len();
    let span = seg_t[n_seg - 1] - seg_t[0];
    if n_seg < 2 || span <= 0.0 {
        return Err(LdhError::TooShort {
            path: path.to_path_buf(),
            duration_s: span.max(0.0),
            samples: n_seg,
            min_s: params.min_duration_s,
        });
    }
    // The rate: each row gets an integer sample index (every interval rounded to a whole
    // number of median periods, at least one), then time is fitted against index by least
    // squares. Exact under timestamp rounding and jitter, unbiased by dropped rows, and it
    // follows a device clock that runs slightly fast or slow.
    let (fs, index) = match spec.time.unit {
        TimeUnit::None | TimeUnit::Counter => {
            let fs = spec.time.rate_hz.expect("validated");
            (
                fs,
                seg_t
                    .iter()
                    .map(|t| ((t - seg_t[0]) * fs).round())
                    .collect::<Vec<f64>>(),
            )
        }
        _ => {
            let mut dts: Vec<f64> = seg_t.windows(2).map(|w| w[1] - w[0]).collect();
            dts.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
            let median_dt = dts[dts.len() / 2];
            let mut index = Vec::with_capacity(n_seg);
            let mut k = 0.0;
            index.push(0.0);
            for w in seg_t.windows(2) {
                k += ((w[1] - w[0]) / median_dt).round().max(1.0);
                index.push(k);
            }
            let (km, tm) = (
                index.iter().sum::<f64>() / n_seg as f64,
                seg_t.iter().sum::<f64>() / n_seg as f64,
            );
            let (mut sxy, mut sxx) = (0.0, 0.0);
            for (k, t) in index.iter().zip(seg_t) {
                sxy += (k - km) * (t - tm);
                sxx += (k - km) * (k - km);
            }
            (sxx / sxy, index)
        }
    };
    if !(fs >= params.min_rate_hz && fs <= params.max_rate_hz) {
        return Err(LdhError::SamplingRate {
            path: path.to_path_buf(),
            reason: format!(
                "measured {fs:.3} Hz from the timestamps, outside the plausible {}–{} Hz; check the time unit ({:?})",
                params.min_rate_hz, params.max_rate_hz, spec.time.unit
            ),
        });
    }
    let t0 = seg_t[0];
    let max_jitter = seg_t
        .iter()
        .zip(&index)
        .map(|(&t, &k)| (t - (t0 + k / fs)).abs())
        .fold(0.0f64, f64::max);
    let consecutive = index.last().is_some_and(|&k| k as usize + 1 == n_seg);
    let uniform = consecutive && max_jitter <= 0.1 / fs;
    if max_jitter > 0.5 / fs {
        warnings.push(format!(
            "timestamps deviate from the fitted {fs:.3} Hz grid by up to {:.1} ms ({:.1} sample periods): the jitter is too large to place every row on the grid, so the sampling rate and the resampled signals may be wrong; check the device's timestamps",
            max_jitter * 1e3,
            max_jitter * fs
        ));
    }
    let mut channels: [Vec<f64>; 6] = Default::default();
    let n_out;
    if uniform {
        for k in 0..6 {
            channels[k] = raw[k][seg_start..seg_end].to_vec();
        }
        n_out = n_seg;
    } else {
        // Resample onto the uniform grid t0 + i / fs by linear interpolation.
        n_out = (span * fs + 1e-9).floor() as usize + 1;
        let grid: Vec<f64> = (0..n_out).map(|i| t0 + i as f64 / fs).collect();
        for k in 0..6 {
            channels[k] = interp_linear(seg_t, &raw[k][seg_start..seg_end], &grid);
        }
        notes.push(format!(
            "timestamps not uniform (max deviation {:.2} ms): resampled to {fs:.3} Hz by linear interpolation",
            max_jitter * 1e3
        ));
    }

    // Saturation, on the values in the file's units after scaling.
    let mut sat_per = [0usize; 6];
    // Per sensor (acc, gyro): preprocessing replaces only the channels of the sensor that clipped.
    let mut saturated = [vec![false; n_out], vec![false; n_out]];
    for k in 0..6 {
        let (scale, range, floor) = if k < 3 {
            let floor = match spec.acc.unit {
                AccUnit::G => 1.5,
                AccUnit::Mps2 => 1.5 * STANDARD_GRAVITY_MPS2,
            };
            (spec.acc.scale, spec.acc.range, floor)
        } else {
            let floor = match spec.gyro.unit {
                GyroUnit::Dps => 200.0,
                GyroUnit::Rps => 200f64.to_radians(),
            };
            (spec.gyro.scale, spec.gyro.range, floor)
        };
        let ch = &mut channels[k];
        for v in ch.iter_mut() {
            *v *= scale;
        }
        let flags = detect_clipping(ch, range, floor);
        for (i, f) in flags.iter().enumerate() {
            if *f {
                sat_per[k] += 1;
                saturated[k / 3][i] = true;
            }
        }
    }
    let saturated_samples = (0..n_out)
        .filter(|&i| saturated[0][i] || saturated[1][i])
        .count();
    if saturated_samples > 0 {
        notes.push(format!(
            "{saturated_samples} clipped sample(s) at the sensor range (acc x/y/z, gyro x/y/z: {sat_per:?}); treated as outliers"
        ));
    }

    // Units → g and deg/s, then the axis map.
    let acc_to_g = match spec.acc.unit {
        AccUnit::G => 1.0,
        AccUnit::Mps2 => 1.0 / STANDARD_GRAVITY_MPS2,
    };
    let gyro_to_dps = match spec.gyro.unit {
        GyroUnit::Dps => 1.0,
        GyroUnit::Rps => 180.0 / std::f64::consts::PI,
    };
    let map = spec.axis_map()?;
    let [c0, c1, c2, c3, c4, c5] = channels;
    let acc_in = [c0, c1, c2];
    let gyro_in = [c3, c4, c5];
    let acc_g: [Vec<f64>; 3] = std::array::from_fn(|i| {
        acc_in[map.index[i]]
            .iter()
            .map(|v| v * acc_to_g * map.sign[i])
            .collect()
    });
    let gyro_dps: [Vec<f64>; 3] = std::array::from_fn(|i| {
        gyro_in[map.index[i]]
            .iter()
            .map(|v| v * gyro_to_dps * map.sign[i])
            .collect()
    });
    if map != super::format::AxisMap::IDENTITY {
        notes.push(format!("axes mapped to ldh's frame as {:?}", spec.axes.map));
    }

    let duration_s = (n_out - 1) as f64 / fs;
    if duration_s < params.min_duration_s {
        return Err(LdhError::TooShort {
            path: path.to_path_buf(),
            duration_s,
            samples: n_out,
            min_s: params.min_duration_s,
        });
    }

    warnings.extend(flat_channel_warnings(&acc_g, &gyro_dps, fs, t0));

    let [acc_sat, gyro_sat] = saturated;
    let mut rec = Recording::new(fs, acc_g, gyro_dps, vec![])
        .and_then(|r| r.with_sensor_saturation(acc_sat, gyro_sat))
        .map_err(|e| LdhError::Signal {
            context: path.display().to_string(),
            reason: e.to_string(),
        })?;
    rec.t0_s = t0;
    rec.source = Some(path.to_path_buf());
    if params.check_units {
        check_units_plausible(&rec, &spec, path)?;
    }

    let report = ReadReport {
        file: path.to_path_buf(),
        format: spec.name.clone(),
        format_detected: format.is_none(),
        delimiter: delim_name.to_string(),
        bom,
        header_line,
        rows,
        fs_hz: fs,
        max_jitter_ms: max_jitter * 1e3,
        resampled: !uniform,
        gaps,
        dropped_segments,
        saturated_per_channel: sat_per,
        saturated_samples,
        samples: n_out,
        duration_s,
        notes,
        warnings,
    };
    Ok((rec, report))
}

/// Warnings about channels that do not measure: a channel constant over the whole recording
/// (a dead axis or a disconnected sensor), and runs of at least one second in which all six
/// channels repeat the same values exactly (a sensor that stalled or lost its connection and
/// was padded by the logger). Real sensor noise never repeats six channels bit for bit.
pub fn flat_channel_warnings(
    acc_g: &[Vec<f64>; 3],
    gyro_dps: &[Vec<f64>; 3],
    fs: f64,
    t0: f64,
) -> Vec<String> {
    const NAMES: [&str; 6] = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"];
    let ch: Vec<&Vec<f64>> = acc_g.iter().chain(gyro_dps.iter()).collect();
    let n = ch[0].len();
    let mut out = Vec::new();
    if n < 2 {
        return out;
    }
    let constant: Vec<usize> = (0..6)
        .filter(|&k| ch[k].iter().all(|&v| v == ch[k][0]))
        .collect();
    if constant.len() == 6 {
        out.push(format!(
            "all six channels are constant over the whole recording (acc {:.3}, {:.3}, {:.3} g; gyro {:.2}, {:.2}, {:.2} deg/s): the sensor did not measure — disconnected, switched off, or a placeholder export?",
            ch[0][0], ch[1][0], ch[2][0], ch[3][0], ch[4][0], ch[5][0]
        ));
        return out;
    }
    if !constant.is_empty() {
        out.push(format!(
            "channel(s) {} constant over all {n} samples (at {}): a dead axis or a disconnected sensor?",
            constant.iter().map(|&k| NAMES[k]).collect::<Vec<_>>().join(", "),
            constant
                .iter()
                .map(|&k| format!("{}", ch[k][0]))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let min_run = ((fs.round() as usize).max(10)).min(n);
    let same = |i: usize| (0..6).all(|k| ch[k][i] == ch[k][i - 1]);
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut i = 1;
    while i < n {
        if same(i) {
            let s = i - 1;
            while i < n && same(i) {
                i += 1;
            }
            if i - s >= min_run {
                runs.push((s, i));
            }
        } else {
            i += 1;
        }
    }
    if let Some(&(a, b)) = runs.iter().max_by_key(|(a, b)| b - a) {
        let total: usize = runs.iter().map(|(a, b)| b - a).sum();
        out.push(format!(
            "all six channels frozen at the same values in {} run(s), {:.2} s in all (longest {:.2}–{:.2} s, acc {:.3}, {:.3}, {:.3} g): the sensor stopped measuring (disconnected or stalled) and those samples are not measurements",
            runs.len(),
            total as f64 / fs,
            t0 + a as f64 / fs,
            t0 + (b - 1) as f64 / fs,
            ch[0][a],
            ch[1][a],
            ch[2][a]
        ));
    }
    out
}

/// Refuse empty, binary and non-UTF-8 content; strip a BOM.
fn decode_text<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str> {
    if bytes.is_empty() {
        return Err(LdhError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    let body = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    // UTF-16 (byte-order mark, or every other byte zero in the first line's ASCII text): a
    // common export mistake, named as such rather than as a binary file.
    if let Some(big_endian) = utf16_order(bytes) {
        return Err(LdhError::Utf16 {
            path: path.to_path_buf(),
            big_endian,
        });
    }
    if let Some(off) = body
        .iter()
        .take(1 << 16)
        .position(|&b| b == 0 || (b < 0x09) || (0x0E..0x20).contains(&b) && b != 0x1B)
    {
        return Err(LdhError::Binary {
            path: path.to_path_buf(),
            offset: off as u64 + (bytes.len() - body.len()) as u64,
            byte: body[off],
        });
    }
    std::str::from_utf8(body).map_err(|e| {
        let off = e.valid_up_to();
        let line = body[..off].iter().filter(|&&b| b == b'\n').count() as u64 + 1;
        LdhError::NotUtf8 {
            loc: Location::line(path, line),
            offset: off as u64 + (bytes.len() - body.len()) as u64,
        }
    })
}

/// `Some(big_endian)` when `bytes` look like UTF-16: a byte-order mark, or (without one) the
/// first up to 64 bytes alternate ASCII characters and zero bytes.
fn utf16_order(bytes: &[u8]) -> Option<bool> {
    if bytes.starts_with(&[0xFF, 0xFE]) {
        return Some(false);
    }
    if bytes.starts_with(&[0xFE, 0xFF]) {
        return Some(true);
    }
    let head = &bytes[..bytes.len().min(64) & !1];
    if head.len() < 4 {
        return None;
    }
    let ascii = |b: &u8| (0x09..0x7F).contains(b);
    let pairs = || head.chunks_exact(2);
    if pairs().all(|p| ascii(&p[0]) && p[1] == 0) {
        Some(false)
    } else if pairs().all(|p| p[0] == 0 && ascii(&p[1])) {
        Some(true)
    } else {
        None
    }
}

/// The most frequent of `,` `;` tab in a header line (ties: tab, `;`, `,`).
pub(super) fn detect_delimiter(line: &str) -> u8 {
    let count = |c: char| line.chars().filter(|&x| x == c).count();
    let (t, s, c) = (count('\t'), count(';'), count(','));
    if t >= s && t >= c && t > 0 {
        b'\t'
    } else if s >= c && s > 0 {
        b';'
    } else {
        b','
    }
}

pub(super) fn split_header(line: &str, delim: u8) -> Vec<String> {
    let mut v = Vec::new();
    let mut buf = String::new();
    split_fields(line, delim, &mut v, &mut buf);
    v.into_iter().map(|s| s.to_string()).collect()
}

/// Split one line into trimmed fields, removing surrounding double quotes.
///
/// Hand-written rather than the `csv` crate: rows are numeric, and per-line splitting keeps the
/// exact file line numbers for messages while skipping comment lines anywhere in the file.
fn split_fields<'a>(line: &'a str, delim: u8, out: &mut Vec<&'a str>, _buf: &mut String) {
    out.clear();
    for f in line.split(delim as char) {
        let f = f.trim();
        let f = f
            .strip_prefix('"')
            .and_then(|x| x.strip_suffix('"'))
            .unwrap_or(f)
            .trim();
        out.push(f);
    }
}

fn parse_number(
    cell: &str,
    decimal: Decimal,
    delim: u8,
    path: &Path,
    line: u64,
    col: usize,
    col_name: &str,
) -> Result<f64> {
    let owned;
    let s = if decimal == Decimal::Comma {
        owned = cell.replace(',', ".");
        owned.as_str()
    } else {
        cell
    };
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(LdhError::NonFinite {
            loc: Location::cell(path, line, col + 1),
            column: col_name.to_string(),
            value: cell.to_string(),
        }),
        Err(_) => {
            let hint = if cell.is_empty() {
                "; the cell is empty".to_string()
            } else if decimal == Decimal::Point
                && delim != b','
                && cell.contains(',')
                && cell.replace(',', ".").parse::<f64>().is_ok()
            {
                "; this looks like a decimal comma: set decimal = \",\" in the format".to_string()
            } else {
                String::new()
            };
            Err(LdhError::NotANumber {
                loc: Location::cell(path, line, col + 1),
                column: col_name.to_string(),
                value: cell.chars().take(60).collect(),
                hint,
            })
        }
    }
}

/// Parse `YYYY-MM-DD[T ]HH:MM:SS[.fff][Z]` into seconds since 1970-01-01 (UTC assumed).
///
/// Hand-written: the timestamp grammar needed is tiny, and a date crate would be a large
/// dependency for one conversion.
pub fn parse_iso8601(s: &str) -> Option<f64> {
    let s = s.trim().trim_end_matches('Z');
    let (date, time) = s.split_once(['T', ' '])?;
    let mut d = date.split('-');
    let y: i64 = d.next()?.parse().ok()?;
    let m: i64 = d.next()?.parse().ok()?;
    let day: i64 = d.next()?.parse().ok()?;
    // Four-digit years only (ISO 8601 without expansion): a longer year overflowed the day
    // count below (found while fuzzing the reader, fuzz/regressions/read_csv/iso-huge-year).
    if d.next().is_some()
        || !(0..=9999).contains(&y)
        || !(1..=12).contains(&m)
        || !(1..=31).contains(&day)
    {
        return None;
    }
    let mut t = time.split(':');
    let hh: f64 = t.next()?.parse().ok()?;
    let mm: f64 = t.next()?.parse().ok()?;
    let ss: f64 = t.next()?.parse().ok()?;
    if t.next().is_some()
        || !(0.0..24.0).contains(&hh)
        || !(0.0..60.0).contains(&mm)
        || !(0.0..61.0).contains(&ss)
    {
        return None;
    }
    // Days from civil (Howard Hinnant's algorithm).
    let y2 = if m <= 2 { y - 1 } else { y };
    let era = if y2 >= 0 { y2 } else { y2 - 399 } / 400;
    let yoe = y2 - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + day - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146097 + doe - 719468;
    Some(days as f64 * 86400.0 + hh * 3600.0 + mm * 60.0 + ss)
}

/// Linear interpolation of `(x, y)` at increasing `at` (clamped at the ends).
pub fn interp_linear(x: &[f64], y: &[f64], at: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(at.len());
    let mut j = 0usize;
    for &t in at {
        while j + 2 < x.len() && x[j + 1] < t {
            j += 1;
        }
        let (x0, x1) = (x[j], x[(j + 1).min(x.len() - 1)]);
        let (y0, y1) = (y[j], y[(j + 1).min(y.len() - 1)]);
        let v = if x1 > x0 {
            let w = ((t - x0) / (x1 - x0)).clamp(0.0, 1.0);
            y0 + w * (y1 - y0)
        } else {
            y0
        };
        out.push(v);
    }
    out
}

/// Flag clipped samples of one channel.
///
/// With a known `range`: every sample with |v| ≥ 99.9 % of it. Without: samples at the channel's
/// extreme value (within 0.1 %) that sit in a flat run of ≥ 3 equal values, provided that
/// extreme is at least `floor` (so a sensor lying still is not called clipped).
pub fn detect_clipping(ch: &[f64], range: Option<f64>, floor: f64) -> Vec<bool> {
    let n = ch.len();
    let mut flags = vec![false; n];
    if let Some(r) = range {
        for (f, v) in flags.iter_mut().zip(ch) {
            *f = v.abs() >= 0.999 * r;
        }
        return flags;
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in ch {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    for ext in [hi, lo] {
        if ext.abs() < floor {
            continue;
        }
        let near = |v: f64| (v - ext).abs() <= 1e-3 * ext.abs();
        let mut i = 0;
        while i < n {
            if near(ch[i]) {
                let mut j = i;
                while j + 1 < n && ch[j + 1] == ch[i] {
                    j += 1;
                }
                if j + 1 - i >= 3 {
                    for f in &mut flags[i..=j] {
                        *f = true;
                    }
                }
                i = j + 1;
            } else {
                i += 1;
            }
        }
    }
    flags
}

/// Refuse data whose magnitudes contradict the declared units.
///
/// Rules (documented in docs/input.md): the median acceleration magnitude must lie in
/// 0.5–2.5 g (a shank sensor spends most of the time near 1 g); the walking gyro must peak above
/// 20 deg/s when the accelerometer shows movement (SD of the magnitude > 0.05 g) — smaller peaks
/// mean rad/s declared as deg/s — and below 3000 deg/s (larger means deg/s declared as rad/s).
pub fn check_units_plausible(rec: &Recording, spec: &FormatSpec, path: &Path) -> Result<()> {
    let n = rec.len();
    let mut mag: Vec<f64> = (0..n)
        .map(|i| {
            (rec.acc_g[0][i].powi(2) + rec.acc_g[1][i].powi(2) + rec.acc_g[2][i].powi(2)).sqrt()
        })
        .collect();
    let mean = mag.iter().sum::<f64>() / n as f64;
    let sd = (mag.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    mag.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    let median = mag[n / 2];
    let declared_acc = match spec.acc.unit {
        AccUnit::G => "g",
        AccUnit::Mps2 => "m/s2",
    };
    let declared_gyro = match spec.gyro.unit {
        GyroUnit::Dps => "deg/s",
        GyroUnit::Rps => "rad/s",
    };
    if !(0.5..=2.5).contains(&median) {
        let hint = if (0.5 * STANDARD_GRAVITY_MPS2..=2.5 * STANDARD_GRAVITY_MPS2).contains(&median)
        {
            " — this looks like m/s² declared as g"
        } else if (0.5 / STANDARD_GRAVITY_MPS2..=2.5 / STANDARD_GRAVITY_MPS2).contains(&median) {
            " — this looks like g declared as m/s²"
        } else if median == 0.0 {
            " — the accelerometer reads zero: is it connected?"
        } else {
            ""
        };
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "median acceleration magnitude is {median:.3} g after converting from the declared unit '{declared_acc}' (×{}); a shank sensor reads about 1 g{hint}",
                spec.acc.scale
            ),
        });
    }
    let gyro_peak = rec
        .gyro_dps
        .iter()
        .flat_map(|c| c.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let gyro_constant = rec.gyro_dps.iter().all(|c| c.iter().all(|&v| v == c[0]));
    if sd > 0.05 && gyro_constant {
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "the accelerometer shows movement (SD {sd:.2} g) but the gyroscope reads a constant ({:.2}, {:.2}, {:.2}) deg/s on all three axes over the whole recording: is the gyroscope switched on and connected?",
                rec.gyro_dps[0][0], rec.gyro_dps[1][0], rec.gyro_dps[2][0]
            ),
        });
    }
    if sd > 0.05 && gyro_peak < 20.0 {
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "the accelerometer shows movement (SD {sd:.2} g) but the gyroscope peaks at only {gyro_peak:.2} deg/s after converting from the declared unit '{declared_gyro}'; walking gives 200–500 deg/s at the shank — is the gyroscope in rad/s?"
            ),
        });
    }
    if gyro_peak > 3000.0 {
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "the gyroscope peaks at {gyro_peak:.0} deg/s after converting from the declared unit '{declared_gyro}'; walking gives 200–500 deg/s — is it in deg/s declared as rad/s?"
            ),
        });
    }
    Ok(())
}
