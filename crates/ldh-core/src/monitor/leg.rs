//! One leg's recording streamed once: the sampling rate measured from its first seconds, gaps
//! and jumps of the clock found, each window classified (`monitor::windows`), per-minute sums
//! kept for wear and posture (`monitor::days`), and each walking span (candidate windows
//! joined across breaks of at most `max_break_s`, mobgap's rule) captured with a margin and
//! spilled to the span store. Memory: one window, the periodicity context, a margin ring and
//! the open span (at most `max_span_s`).

use std::collections::{BTreeMap, VecDeque};

use serde::{Deserialize, Serialize};

use super::store::{SpanRef, SpanStore};
use super::stream::{Sample, SampleSource};
use super::windows::{classify, periodicity, Activity, WindowAcc, WindowParams, CONTEXT_HZ};
use super::ValidMonitorParams;
use crate::error::{LdhError, Result};
use crate::io::DateTime;
use crate::recording::Side;

/// One minute of one leg: the sums van Hees' non-wear rule needs and the seconds of each class.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct MinuteStats {
    /// Samples.
    pub n: u64,
    /// Sum and sum of squares of each acceleration axis, g and g².
    pub sum: [f64; 3],
    /// See `sum`.
    pub sum_sq: [f64; 3],
    /// Smallest value of each axis, g.
    pub min: [f64; 3],
    /// Largest value of each axis, g.
    pub max: [f64; 3],
    /// Windows of each class ([`Activity::ALL`] order).
    pub windows: [u32; 9],
}

impl MinuteStats {
    /// Add another stretch's sums (its window counts are not added).
    pub fn merge(&mut self, o: &MinuteStats) {
        if o.n == 0 {
            return;
        }
        if self.n == 0 {
            self.min = o.min;
            self.max = o.max;
        }
        self.n += o.n;
        for k in 0..3 {
            self.sum[k] += o.sum[k];
            self.sum_sq[k] += o.sum_sq[k];
            self.min[k] = self.min[k].min(o.min[k]);
            self.max[k] = self.max[k].max(o.max[k]);
        }
    }

    fn push(&mut self, acc: &[f64; 3]) {
        if self.n == 0 {
            self.min = *acc;
            self.max = *acc;
        }
        self.n += 1;
        for k in 0..3 {
            self.sum[k] += acc[k];
            self.sum_sq[k] += acc[k] * acc[k];
            self.min[k] = self.min[k].min(acc[k]);
            self.max[k] = self.max[k].max(acc[k]);
        }
    }
}

/// A captured walking span of one leg.
#[derive(Debug, Clone, PartialEq)]
pub struct LegSpan {
    /// The leg.
    pub side: Side,
    /// Where its samples are.
    pub at: SpanRef,
    /// First and last walking window, s (own clock).
    pub walk_s: (f64, f64),
    /// Activity envelope: mean gyroscope magnitude per 1/[`ENVELOPE_HZ`] s from `at.t0_s`.
    pub envelope: Vec<f32>,
    /// The span was cut at `max_span_s` and the walk goes on in the next span.
    pub continues: bool,
    /// Mid-swing times (peaks of the swing on the most moving gyroscope axis), s own clock.
    pub midswing_s: Vec<f64>,
}

/// Rate of the activity envelope used to pair the legs, Hz.
pub const ENVELOPE_HZ: f64 = 20.0;

/// What one leg's stream gave.
#[derive(Debug, Clone, Default)]
pub struct LegStream {
    /// The file.
    pub label: String,
    /// Sampling rate measured, Hz.
    pub fs_hz: f64,
    /// First and last sample time, s.
    pub span_s: (f64, f64),
    /// Start date and time, where the file gives it.
    pub start: Option<DateTime>,
    /// Per-minute sums, by minute number on the leg's clock (`floor(t / 60)`).
    pub minutes: BTreeMap<i64, MinuteStats>,
    /// Walking spans, in time order.
    pub spans: Vec<LegSpan>,
    /// Gaps in the data, (from, to) s.
    pub gaps: Vec<(f64, f64)>,
    /// What was found (gaps, jumps, skipped rows), one sentence each.
    pub notes: Vec<String>,
    /// Samples read.
    pub samples: u64,
}

struct Tracker<'a> {
    p: &'a ValidMonitorParams,
    w: &'a WindowParams,
    store: &'a SpanStore,
    side: Side,
    fs: f64,
    win_n: usize,
    dec_k: usize,
    last_t: f64,
    win: WindowAcc,
    win_start: f64,
    dec_acc: [f64; 3],
    dec_n: usize,
    hist: VecDeque<[f64; 3]>,
    ctx_max: VecDeque<f64>,
    ring: VecDeque<Sample>,
    open: Option<Open>,
    env_acc: (f64, usize),
    out: LegStream,
    back_jumps: u64,
    /// The minute being summed (its number, its sums).
    minute: (i64, MinuteStats),
}

struct Open {
    samples: Vec<Sample>,
    walk: (f64, f64),
    continued: bool,
}

/// Read one leg to its end.
pub fn stream_leg(
    src: &mut dyn SampleSource,
    side: Side,
    p: &ValidMonitorParams,
    store: &SpanStore,
) -> Result<LegStream> {
    let mut chunk = Vec::with_capacity(p.chunk_samples);
    let mut first = Vec::new();
    // The rate: the median interval of the first samples (up to 2000).
    while first.len() < 2000 {
        if src.next_chunk(2000 - first.len(), &mut chunk)? == 0 {
            break;
        }
        first.extend_from_slice(&chunk);
    }
    let fs = rate_of(&first).ok_or_else(|| {
        LdhError::signal(
            src.label(),
            format!(
                "too few samples with increasing times to measure a sampling rate ({} read)",
                first.len()
            ),
        )
    })?;
    let w = &p.params.windows;
    let mut t = Tracker {
        p,
        w,
        store,
        side,
        fs,
        win_n: (w.window_s * fs).round().max(1.0) as usize,
        dec_k: (fs / CONTEXT_HZ).round().max(1.0) as usize,
        last_t: f64::NEG_INFINITY,
        win: WindowAcc::default(),
        win_start: f64::NAN,
        dec_acc: [0.0; 3],
        dec_n: 0,
        hist: VecDeque::new(),
        ctx_max: VecDeque::new(),
        ring: VecDeque::new(),
        open: None,
        env_acc: (0.0, 0),
        out: LegStream {
            label: src.label(),
            fs_hz: fs,
            span_s: (first.first().map_or(0.0, |s| s.t_s), 0.0),
            start: src.start(),
            ..LegStream::default()
        },
        back_jumps: 0,
        minute: (i64::MIN, MinuteStats::default()),
    };
    for s in &first {
        t.push(*s)?;
    }
    drop(first);
    while src.next_chunk(p.chunk_samples, &mut chunk)? > 0 {
        for s in &chunk {
            t.push(*s)?;
        }
    }
    t.close_span(false)?;
    t.flush_minute();
    if t.back_jumps > 0 {
        t.out.notes.push(format!(
            "{}: {} sample(s) whose time did not increase (the clock jumped back) were dropped",
            t.out.label, t.back_jumps
        ));
    }
    t.out.notes.extend(src.notes());
    t.out.span_s.1 = t.last_t;
    Ok(t.out)
}

/// The median rate of the samples' intervals, Hz (`None` with fewer than 10 increasing steps).
pub fn rate_of(s: &[Sample]) -> Option<f64> {
    let mut dt: Vec<f64> = s
        .windows(2)
        .map(|w| w[1].t_s - w[0].t_s)
        .filter(|d| *d > 0.0 && d.is_finite())
        .collect();
    if dt.len() < 10 {
        return None;
    }
    let m = crate::stats::median(&mut dt, crate::stats::EvenMedian::Mean)?;
    (m > 0.0).then(|| 1.0 / m)
}

impl Tracker<'_> {
    fn push(&mut self, s: Sample) -> Result<()> {
        if s.t_s <= self.last_t {
            self.back_jumps += 1;
            return Ok(());
        }
        let gap = s.t_s - self.last_t;
        if self.last_t.is_finite() && gap > self.p.params.max_gap_s {
            self.out.gaps.push((self.last_t, s.t_s));
            self.out.notes.push(format!(
                "{}: no data from {:.1} s to {:.1} s ({:.1} s; a gap or a jump of the clock): windows restart after it",
                self.out.label, self.last_t, s.t_s, gap
            ));
            self.close_span(false)?;
            self.reset_context();
        }
        self.last_t = s.t_s;
        self.out.samples += 1;
        let minute = (s.t_s / 60.0).floor() as i64;
        if self.minute.0 != minute {
            self.flush_minute();
            self.minute.0 = minute;
        }
        self.minute.1.push(&s.acc_g);
        if self.win.n == 0 {
            self.win_start = s.t_s;
        }
        self.win.push(&s.acc_g, &s.gyro_dps);
        for k in 0..3 {
            self.dec_acc[k] += s.gyro_dps[k];
        }
        self.dec_n += 1;
        if self.dec_n == self.dec_k {
            let ctx = (self.w.context_s * CONTEXT_HZ).round() as usize;
            self.hist
                .push_back(self.dec_acc.map(|v| v / self.dec_n as f64));
            while self.hist.len() > ctx {
                self.hist.pop_front();
            }
            self.dec_acc = [0.0; 3];
            self.dec_n = 0;
        }
        self.ring.push_back(s);
        let ring_n = ((self.w.context_s + self.p.params.margin_s) * self.fs) as usize;
        while self.ring.len() > ring_n {
            self.ring.pop_front();
        }
        if let Some(o) = &mut self.open {
            o.samples.push(s);
        }
        if self.win.n >= self.win_n {
            self.end_window(s.t_s)?;
        }
        Ok(())
    }

    /// Add the current minute's sums to the table.
    fn flush_minute(&mut self) {
        let (m, stats) = std::mem::take(&mut self.minute);
        if stats.n == 0 {
            return;
        }
        self.out.minutes.entry(m).or_default().merge(&stats);
    }

    fn reset_context(&mut self) {
        self.win = WindowAcc::default();
        self.hist.clear();
        self.ctx_max.clear();
        self.ring.clear();
        self.dec_n = 0;
        self.dec_acc = [0.0; 3];
    }

    fn end_window(&mut self, t_end: f64) -> Result<()> {
        let win = std::mem::take(&mut self.win);
        let n_ctx = (self.w.context_s / self.w.window_s).round().max(1.0) as usize;
        self.ctx_max.push_back(win.acc_max_g);
        while self.ctx_max.len() > n_ctx {
            self.ctx_max.pop_front();
        }
        let per = periodicity(&self.hist, self.w);
        let ctx_max = self.ctx_max.iter().copied().fold(0.0, f64::max);
        let class = classify(&win, &per, ctx_max, self.w);
        let minute = (self.win_start / 60.0).floor() as i64;
        self.out.minutes.entry(minute).or_default().windows[class.index()] += 1;
        let walking = class == Activity::Walking;
        match &mut self.open {
            None if walking => {
                let from = t_end - self.w.context_s;
                self.open = Some(Open {
                    samples: self.ring.iter().copied().collect(),
                    walk: (from, t_end),
                    continued: false,
                });
            }
            Some(o) if walking => o.walk.1 = t_end,
            Some(o) if t_end - o.walk.1 >= self.p.params.max_break_s + self.p.params.margin_s => {
                self.close_span(false)?;
            }
            _ => {}
        }
        if let Some(o) = &self.open {
            let first = o.samples.first().map_or(t_end, |s| s.t_s);
            if t_end - first >= self.p.params.max_span_s {
                self.close_span(true)?;
            }
        }
        Ok(())
    }

    /// Close the open span (`cut`: at the length limit, the walk goes on in a new span).
    fn close_span(&mut self, cut: bool) -> Result<()> {
        let Some(o) = self.open.take() else {
            return Ok(());
        };
        if o.walk.1 - o.walk.0 >= self.p.params.min_candidate_s && o.samples.len() > 1 {
            let at = self.store.put(&o.samples)?;
            let envelope = envelope(&o.samples, at.t0_s);
            let midswing_s = midswings(&o.samples, self.fs);
            self.out.spans.push(LegSpan {
                side: self.side,
                at,
                walk_s: o.walk,
                envelope,
                continues: cut,
                midswing_s,
            });
        }
        let _ = o.continued;
        if cut {
            let t = o.samples.last().map_or(0.0, |s| s.t_s);
            self.open = Some(Open {
                samples: Vec::new(),
                walk: (t, t),
                continued: true,
            });
        }
        self.env_acc = (0.0, 0);
        Ok(())
    }
}

/// The mean gyroscope magnitude per 1/[`ENVELOPE_HZ`] s from `t0`, smoothed over 1 s.
pub fn envelope(samples: &[Sample], t0: f64) -> Vec<f32> {
    let Some(last) = samples.last() else {
        return Vec::new();
    };
    let bins = ((last.t_s - t0) * ENVELOPE_HZ).floor() as usize + 1;
    let mut sum = vec![0.0f64; bins];
    let mut n = vec![0u32; bins];
    for s in samples {
        let b = (((s.t_s - t0) * ENVELOPE_HZ).floor() as usize).min(bins - 1);
        let g = s.gyro_dps;
        sum[b] += (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        n[b] += 1;
    }
    let raw: Vec<f64> = sum
        .iter()
        .zip(&n)
        .map(|(s, &k)| if k > 0 { s / f64::from(k) } else { 0.0 })
        .collect();
    let half = (ENVELOPE_HZ / 2.0) as usize;
    let mut out = Vec::with_capacity(bins);
    let mut acc = 0.0;
    let mut cnt = 0usize;
    // Centred moving average over 1 s by a running sum.
    for i in 0..bins + half {
        if i < bins {
            acc += raw[i];
            cnt += 1;
        }
        if i > 2 * half {
            acc -= raw[i - 2 * half - 1];
            cnt -= 1;
        }
        if i >= half {
            out.push((acc / cnt.max(1) as f64) as f32);
        }
    }
    out
}

/// Mid-swing times: the peaks, in the swing's direction (the sign of the skewness), of the
/// gyroscope axis that moves most, at least half the largest and 0.5 s apart.
pub fn midswings(samples: &[Sample], fs: f64) -> Vec<f64> {
    let n = samples.len();
    if n < 3 {
        return Vec::new();
    }
    let mut mean = [0.0; 3];
    for s in samples {
        for k in 0..3 {
            mean[k] += s.gyro_dps[k] / n as f64;
        }
    }
    let mut m2 = [0.0; 3];
    let mut m3 = [0.0; 3];
    for s in samples {
        for k in 0..3 {
            let d = s.gyro_dps[k] - mean[k];
            m2[k] += d * d;
            m3[k] += d * d * d;
        }
    }
    let ax = (0..3).max_by(|&a, &b| m2[a].total_cmp(&m2[b])).unwrap_or(2);
    let sign = if m3[ax] < 0.0 { -1.0 } else { 1.0 };
    let x: Vec<f64> = samples
        .iter()
        .map(|s| sign * (s.gyro_dps[ax] - mean[ax]))
        .collect();
    let top = x.iter().copied().fold(0.0, f64::max);
    let half = ((0.25 * fs) as usize).max(1);
    let mut out = Vec::new();
    let mut i = 0;
    while i < n {
        if x[i] >= 0.5 * top {
            let (lo, hi) = (i.saturating_sub(half), (i + half + 1).min(n));
            if x[lo..hi].iter().all(|v| *v <= x[i]) {
                // Parabolic refinement of the peak time.
                let f = if i > 0 && i + 1 < n {
                    let (a, b, c) = (x[i - 1], x[i], x[i + 1]);
                    let d = a - 2.0 * b + c;
                    if d < 0.0 {
                        (0.5 * (a - c) / d).clamp(-0.5, 0.5)
                    } else {
                        0.0
                    }
                } else {
                    0.0
                };
                let t0 = samples[i].t_s;
                let dt = if i + 1 < n {
                    samples[i + 1].t_s - t0
                } else {
                    1.0 / fs
                };
                out.push(t0 + f * dt);
                i += half;
                continue;
            }
        }
        i += 1;
    }
    out
}
