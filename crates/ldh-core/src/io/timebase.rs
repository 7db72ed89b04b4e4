//! The reader's time base (SPEC §2): timestamps to seconds, their checks (monotonic, a
//! plausible median interval), splitting at gaps, the sampling rate fitted to the kept segment
//! and the channels placed on its uniform grid.
//!
//! Every row of the kept segment gets an integer sample index (each interval rounded to a whole
//! number of median periods), and the period is the least-squares slope of time against index.
//! When every timestamp lies within 10 % of a period of that uniform grid and no row is
//! missing, samples are kept as they are; otherwise the channels are resampled onto the grid by
//! linear interpolation (gaps up to `max_gap_s` are bridged that way).

use serde::{Deserialize, Serialize};
use std::path::Path;

use super::format::{FormatSpec, TimeUnit};
use super::rows::RowLines;
use crate::error::{LdhError, Location, Result};
use crate::stats::{median, EvenMedian};

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

/// The plausible sampling rates, Hz (`ReadParams::min_rate_hz`, `max_rate_hz`).
#[derive(Debug, Clone, Copy)]
pub(super) struct RateBounds {
    /// Lowest plausible rate, Hz.
    pub min_hz: f64,
    /// Highest plausible rate, Hz.
    pub max_hz: f64,
}

impl RateBounds {
    fn contains(&self, rate_hz: f64) -> bool {
        rate_hz >= self.min_hz && rate_hz <= self.max_hz
    }
}

/// The time cells (`time_raw`, in the format's unit; `rows` rows) in seconds of the file
/// clock: ms and µs scaled, a sample counter unwrapped and divided by the stated rate, and
/// without a time column uniform samples at the stated rate. Notes a counter wrap and a missing
/// time column.
pub(super) fn times_in_seconds(
    time_raw: Vec<f64>,
    spec: &FormatSpec,
    rows: usize,
    notes: &mut Vec<String>,
) -> Vec<f64> {
    match spec.time.unit {
        TimeUnit::Seconds | TimeUnit::Iso8601 => time_raw,
        TimeUnit::Milliseconds => time_raw.iter().map(|t| t * 1e-3).collect(),
        TimeUnit::Microseconds => time_raw.iter().map(|t| t * 1e-6).collect(),
        TimeUnit::HundredMicroseconds => time_raw.iter().map(|t| t * 1e-4).collect(),
        TimeUnit::Nanoseconds => time_raw.iter().map(|t| t * 1e-9).collect(),
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
    }
}

/// Refuse a timestamp (s) that repeats or goes backwards, at its line (`row_lines`) and the
/// time column (`time_col`, 0-based; column 1 without one).
pub(super) fn check_monotonic(
    times: &[f64],
    row_lines: &RowLines,
    time_col: Option<usize>,
    path: &Path,
) -> Result<()> {
    for i in 1..times.len() {
        if times[i] <= times[i - 1] {
            return Err(LdhError::NonMonotonicTime {
                loc: Location::cell(path, row_lines.get(i), time_col.map_or(1, |c| c + 1)),
                value: times[i],
                previous: times[i - 1],
            });
        }
    }
    Ok(())
}

/// Refuse a median interval between timestamps (s) outside the plausible rates: a time-unit
/// problem, not a series of gaps (e.g. milliseconds written into a seconds column). Needs at
/// least three timestamps.
pub(super) fn check_median_rate(
    times: &[f64],
    bounds: RateBounds,
    unit: TimeUnit,
    path: &Path,
) -> Result<()> {
    if times.len() >= 3 {
        let mut dts: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
        let median_dt = median(&mut dts, EvenMedian::Upper).unwrap_or(f64::NAN);
        let rate = 1.0 / median_dt;
        if !bounds.contains(rate) {
            return Err(LdhError::SamplingRate {
                path: path.to_path_buf(),
                reason: format!(
                    "the median interval between timestamps is {:.6} s ({rate:.3} Hz), outside the plausible {}–{} Hz; check the time unit ({:?} declared: milliseconds written as seconds?)",
                    median_dt,
                    bounds.min_hz,
                    bounds.max_hz,
                    unit
                ),
            });
        }
    }
    Ok(())
}

/// The recording split at gaps: the kept segment (rows `start..end`) and what was not kept.
#[derive(Debug)]
pub(super) struct Segments {
    /// Gaps longer than `max_gap_s`.
    pub gaps: Vec<GapInfo>,
    /// The segments not kept, as (start_s, end_s) in the file clock.
    pub dropped: Vec<(f64, f64)>,
    /// First row of the kept (longest) segment.
    pub start: usize,
    /// One past its last row.
    pub end: usize,
}

/// Split `times` (s, increasing; lines in `row_lines`) at intervals longer than `max_gap_s`
/// and keep the longest segment (the earliest among equals), with a warning naming what was
/// dropped. With `reject_gaps`, the first such gap is an [`LdhError::Gap`] instead.
pub(super) fn split_at_gaps(
    times: &[f64],
    row_lines: &RowLines,
    max_gap_s: f64,
    reject_gaps: bool,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<Segments> {
    let mut gaps = Vec::new();
    let mut cuts = vec![0usize];
    for i in 1..times.len() {
        let dt = times[i] - times[i - 1];
        if dt > max_gap_s {
            if reject_gaps {
                return Err(LdhError::Gap {
                    loc: Location::line(path, row_lines.get(i)),
                    gap_s: dt,
                    from_s: times[i - 1],
                    max_gap_s,
                });
            }
            gaps.push(GapInfo {
                from_s: times[i - 1],
                gap_s: dt,
                line: row_lines.get(i),
            });
            cuts.push(i);
        }
    }
    cuts.push(times.len());
    let (start, end) = cuts
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
    let dropped: Vec<(f64, f64)> = cuts
        .windows(2)
        .filter(|w| w[0] != start)
        .map(|w| (times[w[0]], times[w[1] - 1]))
        .collect();
    if !gaps.is_empty() {
        warnings.push(format!(
            "{} gap(s) longer than {} s: kept the longest segment {:.2}–{:.2} s, dropped {}",
            gaps.len(),
            max_gap_s,
            times[start],
            times[end - 1],
            dropped.len()
        ));
    }
    Ok(Segments {
        gaps,
        dropped,
        start,
        end,
    })
}

/// The uniform sampling grid fitted to the kept segment.
#[derive(Debug)]
pub(super) struct Grid {
    /// Sampling rate, Hz.
    pub fs: f64,
    /// Time of the first sample, s (file clock).
    pub t0: f64,
    /// Largest deviation of a timestamp from the grid, s.
    pub max_jitter_s: f64,
    /// Every row is on the grid (within 10 % of a period) and none is missing: the samples are
    /// kept as they are.
    pub uniform: bool,
    /// Samples on the grid.
    pub n_out: usize,
}

/// The rate and each row's integer sample index for the segment's timestamps `seg_t` (s): the
/// stated rate for a counter or no time column; otherwise every interval rounded to a whole
/// number of median periods (at least one), and the rate from the least-squares fit of time
/// against index. Exact under timestamp rounding and jitter, unbiased by dropped rows, and it
/// follows a device clock that runs slightly fast or slow.
fn rate_and_index(seg_t: &[f64], spec: &FormatSpec) -> (f64, Vec<f64>) {
    let n_seg = seg_t.len();
    match spec.time.unit {
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
            let median_dt = median(&mut dts, EvenMedian::Upper).unwrap_or(f64::NAN);
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
    }
}

/// Fit the grid to the segment's timestamps `seg_t` (s, at least two, spanning > 0 s). A rate
/// outside `bounds` is an [`LdhError::SamplingRate`]; a timestamp off the grid by more than half
/// a period is a warning (the rate and the resampled signals may be wrong).
pub(super) fn fit_grid(
    seg_t: &[f64],
    spec: &FormatSpec,
    bounds: RateBounds,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<Grid> {
    let n_seg = seg_t.len();
    let (fs, index) = rate_and_index(seg_t, spec);
    if !bounds.contains(fs) {
        return Err(LdhError::SamplingRate {
            path: path.to_path_buf(),
            reason: format!(
                "measured {fs:.3} Hz from the timestamps, outside the plausible {}–{} Hz; check the time unit ({:?})",
                bounds.min_hz, bounds.max_hz, spec.time.unit
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
    let span = seg_t[n_seg - 1] - seg_t[0];
    let n_out = if uniform {
        n_seg
    } else {
        (span * fs + 1e-9).floor() as usize + 1
    };
    Ok(Grid {
        fs,
        t0,
        max_jitter_s: max_jitter,
        uniform,
        n_out,
    })
}

/// The six channels' segment (`raw[k][seg]`, timestamps `seg_t`; `raw` consumed) on the grid:
/// kept in place when the grid is uniform, otherwise resampled at `t0 + i / fs` by linear
/// interpolation (noted), one channel at a time (memory: one channel more than `raw`).
pub(super) fn place_on_grid(
    raw: [Vec<f64>; 6],
    seg: std::ops::Range<usize>,
    seg_t: &[f64],
    grid: &Grid,
    notes: &mut Vec<String>,
) -> [Vec<f64>; 6] {
    let mut channels = raw;
    if grid.uniform {
        for ch in &mut channels {
            ch.truncate(seg.end);
            ch.drain(..seg.start);
        }
    } else {
        let grid_t: Vec<f64> = (0..grid.n_out)
            .map(|i| grid.t0 + i as f64 / grid.fs)
            .collect();
        for ch in &mut channels {
            let placed = interp_linear(seg_t, &ch[seg.clone()], &grid_t);
            *ch = placed;
        }
        notes.push(format!(
            "timestamps not uniform (max deviation {:.2} ms): resampled to {:.3} Hz by linear interpolation",
            grid.max_jitter_s * 1e3,
            grid.fs
        ));
    }
    channels
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

#[cfg(test)]
mod tests {
    use super::*;

    const BOUNDS: RateBounds = RateBounds {
        min_hz: 20.0,
        max_hz: 2000.0,
    };

    fn seconds() -> FormatSpec {
        FormatSpec::builtin("ldh").expect("built-in")
    }

    fn path() -> &'static Path {
        Path::new("t.csv")
    }

    #[test]
    fn a_wrapping_counter_is_unwrapped_and_noted() {
        let spec = FormatSpec::builtin("xsens-mtmanager")
            .expect("built-in")
            .with_rate_hz(100.0);
        let mut notes = Vec::new();
        let t = times_in_seconds(vec![65534.0, 65535.0, 0.0, 1.0], &spec, 4, &mut notes);
        assert_eq!(t, vec![655.34, 655.35, 655.36, 655.37]);
        assert_eq!(notes, ["sample counter wrapped 1 time(s)"]);
    }

    #[test]
    fn repeated_time_and_a_millisecond_clock_are_refused() {
        let e = check_monotonic(
            &[0.0, 0.01, 0.01],
            &[2, 3, 5].into_iter().collect(),
            Some(0),
            path(),
        )
        .unwrap_err();
        assert!(matches!(e, LdhError::NonMonotonicTime { .. }), "{e}");
        assert!(e.to_string().starts_with("t.csv:5:1"), "{e}");
        let ms: Vec<f64> = (0..10).map(|i| i as f64 * 10.0).collect();
        let e = check_median_rate(&ms, BOUNDS, TimeUnit::Seconds, path()).unwrap_err();
        assert!(
            e.to_string().contains("milliseconds written as seconds?"),
            "{e}"
        );
        let s: Vec<f64> = ms.iter().map(|t| t * 1e-3).collect();
        assert!(check_median_rate(&s, BOUNDS, TimeUnit::Seconds, path()).is_ok());
    }

    #[test]
    fn the_longest_segment_between_gaps_is_kept_or_the_gap_refused() {
        // 0–1 s, a 0.5 s gap, 1.5–3.5 s, a 0.3 s gap, 3.8–4.3 s; 100 Hz.
        let mut t: Vec<f64> = (0..=100).map(|i| i as f64 / 100.0).collect();
        t.extend((0..=200).map(|i| 1.5 + i as f64 / 100.0));
        t.extend((0..=50).map(|i| 3.8 + i as f64 / 100.0));
        let lines: RowLines = (2..).take(t.len()).collect();
        let mut warnings = Vec::new();
        let s = split_at_gaps(&t, &lines, 0.2, false, path(), &mut warnings).unwrap();
        assert_eq!((s.start, s.end), (101, 302));
        assert_eq!(s.gaps.len(), 2);
        assert_eq!(s.gaps[0].line, 103);
        assert_eq!(s.dropped, vec![(0.0, 1.0), (3.8, t[t.len() - 1])]);
        assert_eq!(
            warnings,
            ["2 gap(s) longer than 0.2 s: kept the longest segment 1.50–3.50 s, dropped 2"]
        );
        let e = split_at_gaps(&t, &lines, 0.2, true, path(), &mut Vec::new()).unwrap_err();
        assert!(matches!(e, LdhError::Gap { .. }), "{e}");
    }

    #[test]
    fn the_rate_is_fitted_through_jitter_and_a_missing_row_is_resampled() {
        let fs = 100.2;
        // ±0.25 ms of jitter (5 % of a period): the rows stay as they are.
        let jittered: Vec<f64> = (0..500)
            .map(|i| i as f64 / fs + if i % 2 == 0 { 2.5e-4 } else { -2.5e-4 })
            .collect();
        let mut warnings = Vec::new();
        let g = fit_grid(&jittered, &seconds(), BOUNDS, path(), &mut warnings).unwrap();
        assert!((g.fs - fs).abs() < 1e-3, "{}", g.fs);
        assert!(g.uniform && g.n_out == 500 && warnings.is_empty());

        // One row missing: resampled onto the grid, which has the missing sample back.
        let mut t: Vec<f64> = (0..500).map(|i| i as f64 / fs).collect();
        t.remove(250);
        let g = fit_grid(&t, &seconds(), BOUNDS, path(), &mut warnings).unwrap();
        assert!((g.fs - fs).abs() < 1e-9 && !g.uniform && g.n_out == 500);
        let raw: [Vec<f64>; 6] = std::array::from_fn(|k| t.iter().map(|x| k as f64 * x).collect());
        let mut notes = Vec::new();
        let ch = place_on_grid(raw, 0..t.len(), &t, &g, &mut notes);
        assert_eq!(ch[3].len(), 500);
        for (i, v) in ch[3].iter().enumerate() {
            let ti = g.t0 + i as f64 / g.fs;
            assert!(
                (v - 3.0 * ti).abs() < 1e-9,
                "sample {i}: {v} vs {}",
                3.0 * ti
            );
        }
        assert!(notes[0].starts_with("timestamps not uniform"), "{notes:?}");

        // Seconds that are really milliseconds: an implausible rate.
        let slow: Vec<f64> = (0..10).map(|i| i as f64 * 10.0).collect();
        let e = fit_grid(&slow, &seconds(), BOUNDS, path(), &mut warnings).unwrap_err();
        assert!(matches!(e, LdhError::SamplingRate { .. }), "{e}");
    }
}
