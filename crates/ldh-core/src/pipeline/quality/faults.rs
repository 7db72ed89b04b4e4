//! Partial sensor faults, per channel, named with their time span (issue 36 item 7,
//! docs/quality.md `channel_fault`): one channel frozen (stuck at one value), dropped to zero,
//! or spiking, for part of the walk, while the sensor's other channels go on measuring. The
//! strides whose span overlaps a fault are withheld with the reason; the others keep their
//! numbers and their values.
//!
//! The rules are those of data-quality screening of inertial recordings (a stuck or zeroed
//! channel is a repeated value that real sensor noise never produces; a spike is a sample far
//! outside the channel's own robust range, e.g. Ganguli et al., "Data quality in wearable
//! sensing", and the flat-line and out-of-range tests of the PhysioNet signal quality indices,
//! Li et al., Physiol Meas 2008;29:15–32). The thresholds below are physical or were checked
//! against real walks, never fitted: every constant says why.
//!
//! What this module does not cover, because other checks do: a channel constant over the whole
//! recording and all six channels frozen together (the reader's `input` warnings,
//! [`crate::io::flat_channel_warnings`]), flat runs at a channel's extreme (clipping,
//! `gyro_clipping` / `acc_clipping`), and a gyroscope amplified throughout (`gyro_scale_fault`).

use super::warning::{codes, params, Severity, Warning};
use crate::gait::Stride;
use crate::gait::{StrideCode, StrideFinding};
use crate::recording::Recording;

/// Shortest run of one repeated value that makes a channel frozen, s. A walking shank never
/// holds any axis still to the last bit for half a second (stance lasts 0.6–0.7 s but the shank
/// rotates through all of it), and the repeat must be bit for bit: a change smaller than one
/// quantisation step cannot be seen, so "constant within the quantisation" is a repeated value.
/// Measured: the longest repeat on 36 real HuGaDB shank legs and the 8 demo legs is 0.03 s.
pub const MIN_FROZEN_S: f64 = 0.5;

/// Shortest run of exact zeros that makes a channel dropped to zero, s (a lost packet padded
/// with zeros by the logger): 0.1 s is ten samples at 100 Hz, and a moving channel's noise
/// never returns exactly 0.0 ten times in a row.
pub const MIN_ZERO_S: f64 = 0.1;

/// Range over a run above which another accelerometer channel is moving, g (a sensor at rest
/// varies by < 0.05 g peak to peak; walking moves every axis by ≥ 0.5 g).
pub const MOVING_ACC_G: f64 = 0.1;

/// Range over a run above which another gyroscope channel is moving, deg/s (a sensor at rest
/// varies by < 5 deg/s peak to peak; walking turns every axis by ≥ 50 deg/s).
pub const MOVING_GYRO_DPS: f64 = 20.0;

/// How far outside the channel's robust band [P1, P99] a sample must lie to be a spike, in
/// units of the band's width (P99 − P1). The largest excursion measured on real and simulated
/// walks (36 HuGaDB shank legs, 8 demo legs) is 1.34 band widths (a heel strike on a lateral
/// gyroscope axis), so 2 keeps a margin of 1.5; the 10·MAD-from-a-running-median rule was
/// measured at 15 MAD on clean real walks and is not used.
pub const SPIKE_BAND_WIDTHS: f64 = 2.0;

/// Longest run of samples beyond the spike threshold that is still a spike, s: a spike is
/// isolated; anything longer is a movement or a scale fault (`gyro_scale_fault`).
pub const MAX_SPIKE_S: f64 = 0.05;

/// Spikes closer than this are one spiking span, s.
pub const SPIKE_MERGE_S: f64 = 1.0;

/// The six channels of a recording, in order, in plain words.
pub const CHANNEL_NAMES: [&str; 6] = [
    "accelerometer x",
    "accelerometer y",
    "accelerometer z",
    "gyroscope x",
    "gyroscope y",
    "gyroscope z",
];

/// What went wrong on a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaultKind {
    /// One value repeated for at least [`MIN_FROZEN_S`] while other channels move.
    Frozen,
    /// Exactly zero for at least [`MIN_ZERO_S`] while other channels move.
    Zero,
    /// Isolated samples more than [`SPIKE_BAND_WIDTHS`] beyond the channel's robust band.
    Spikes,
}

impl FaultKind {
    /// In plain words, as the warning says it.
    pub fn words(self) -> &'static str {
        match self {
            FaultKind::Frozen => "frozen",
            FaultKind::Zero => "dropped to zero",
            FaultKind::Spikes => "spiking",
        }
    }
}

/// One partial fault of one channel: which, what, and when (s from the recording's first
/// sample, the clock of the strides; `end_s` is the last faulty sample).
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelFault {
    /// Channel index, 0–5: accelerometer x, y, z, gyroscope x, y, z ([`CHANNEL_NAMES`]).
    pub channel: usize,
    /// What went wrong.
    pub kind: FaultKind,
    /// First faulty sample, s.
    pub start_s: f64,
    /// Last faulty sample, s.
    pub end_s: f64,
    /// Faulty samples in the span (for spikes, the spiking samples only).
    pub samples: usize,
}

impl ChannelFault {
    /// The channel's name ("gyroscope z").
    pub fn channel_name(&self) -> &'static str {
        CHANNEL_NAMES[self.channel]
    }
    /// "shank gyroscope z frozen from 12.3 s to 15.8 s"; a span shorter than the 0.1 s shown
    /// is said at its time ("shank gyroscope x spiking at 24.0 s", not "from 24.0 s to 24.0 s").
    pub fn describe(&self) -> String {
        let (a, b) = (format!("{:.1}", self.start_s), format!("{:.1}", self.end_s));
        let when = if a == b {
            format!("at {a} s")
        } else {
            format!("from {a} s to {b} s")
        };
        format!("shank {} {} {when}", self.channel_name(), self.kind.words())
    }
}

/// The channels of a recording as six slices.
fn channels(rec: &Recording) -> [&[f64]; 6] {
    let (a, g) = (&rec.acc_g, &rec.gyro_dps);
    [&a[0], &a[1], &a[2], &g[0], &g[1], &g[2]]
}

/// Whether a channel other than `k` moves within samples `a..b`.
fn others_move(ch: &[&[f64]; 6], k: usize, a: usize, b: usize) -> bool {
    (0..6).filter(|&j| j != k).any(|j| {
        let (lo, hi) = ch[j][a..b]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                (l.min(v), h.max(v))
            });
        hi - lo > if j < 3 { MOVING_ACC_G } else { MOVING_GYRO_DPS }
    })
}

/// Frozen and zero runs of channel `k`.
fn stuck_runs(ch: &[&[f64]; 6], k: usize, fs: f64, out: &mut Vec<ChannelFault>) {
    let x = ch[k];
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    if lo == hi {
        // Constant throughout: the reader's warning.
        return;
    }
    let n = x.len();
    let mut s = 0;
    while s < n {
        let mut e = s + 1;
        while e < n && x[e] == x[s] {
            e += 1;
        }
        let v = x[s];
        let kind = if v == 0.0 {
            FaultKind::Zero
        } else {
            FaultKind::Frozen
        };
        let min_s = match kind {
            FaultKind::Zero => MIN_ZERO_S,
            _ => MIN_FROZEN_S,
        };
        // At the channel's extreme it is clipping, not a frozen channel.
        let clipped = v != 0.0 && (v == lo || v == hi);
        if (e - s) as f64 >= min_s * fs && !clipped && others_move(ch, k, s, e) {
            out.push(ChannelFault {
                channel: k,
                kind,
                start_s: s as f64 / fs,
                end_s: (e - 1) as f64 / fs,
                samples: e - s,
            });
        }
        s = e;
    }
}

/// The `q` quantile of the sorted `v` (nearest rank).
fn quantile(v: &[f64], q: f64) -> f64 {
    v[((v.len() - 1) as f64 * q).round() as usize]
}

/// Spiking spans of channel `k`: isolated runs (≤ [`MAX_SPIKE_S`]) more than
/// [`SPIKE_BAND_WIDTHS`] outside [P1, P99], merged when closer than [`SPIKE_MERGE_S`].
fn spikes(x: &[f64], k: usize, fs: f64, out: &mut Vec<ChannelFault>) {
    let mut sorted = x.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (p1, p99) = (quantile(&sorted, 0.01), quantile(&sorted, 0.99));
    let w = p99 - p1;
    if w <= 0.0 {
        return;
    }
    let (lo, hi) = (p1 - SPIKE_BAND_WIDTHS * w, p99 + SPIKE_BAND_WIDTHS * w);
    let max_run = ((MAX_SPIKE_S * fs).floor() as usize).max(1);
    let mut found: Vec<ChannelFault> = Vec::new();
    let mut i = 0;
    while i < x.len() {
        if x[i] >= lo && x[i] <= hi {
            i += 1;
            continue;
        }
        let s = i;
        while i < x.len() && !(x[i] >= lo && x[i] <= hi) {
            i += 1;
        }
        if i - s > max_run {
            continue;
        }
        let (a, b) = (s as f64 / fs, (i - 1) as f64 / fs);
        match found.last_mut() {
            Some(f) if a - f.end_s < SPIKE_MERGE_S => {
                f.end_s = b;
                f.samples += i - s;
            }
            _ => found.push(ChannelFault {
                channel: k,
                kind: FaultKind::Spikes,
                start_s: a,
                end_s: b,
                samples: i - s,
            }),
        }
    }
    out.extend(found);
}

/// Every partial fault of a recording's six channels, by channel then time.
pub fn detect_faults(rec: &Recording) -> Vec<ChannelFault> {
    let ch = channels(rec);
    let mut out = Vec::new();
    if rec.len() < 3 || !(rec.fs_hz > 0.0) {
        return out;
    }
    for k in 0..6 {
        stuck_runs(&ch, k, rec.fs_hz, &mut out);
        spikes(ch[k], k, rec.fs_hz, &mut out);
    }
    out.sort_by(|a, b| {
        (a.channel, a.start_s)
            .partial_cmp(&(b.channel, b.start_s))
            .unwrap()
    });
    out
}

/// The warning of one fault: a plain sentence with its span. The strides over the span are
/// withheld ([`withhold_faulty_strides`], and [`super::apply_to_strides`] again after the
/// strides are re-segmented); the others are measurements. A gyroscope fault also withholds the
/// shank angles and the stride length of the whole leg: the attitude integrates the rotation
/// the fault lost and carries the error on (measured on a simulated walk with gyroscope x frozen
/// for 3 s: 3–9 deg off in the next stride and still 1–1.5 deg ten seconds later, while the
/// stride times and stance stay identical to 1e-6 s; docs/quality.md `channel_fault`).
pub fn fault_warning(f: &ChannelFault) -> Warning {
    let what = match f.kind {
        FaultKind::Frozen => format!(
            "it repeated one value for {:.1} s while the other channels moved",
            f.end_s - f.start_s
        ),
        FaultKind::Zero => format!(
            "it read exactly 0 for {:.2} s while the other channels moved (lost samples?)",
            f.end_s - f.start_s
        ),
        FaultKind::Spikes => format!(
            "{} isolated sample(s) far outside the channel's range",
            f.samples
        ),
    };
    let gyro = f.channel >= 3;
    let then = if gyro {
        "so the strides in this span are left out and, as the attitude carries the lost rotation on, the shank angles and stride length of this leg are not measured"
    } else {
        "so the strides in this span are left out (the others are kept)"
    };
    let w = Warning::new(
        codes::CHANNEL_FAULT,
        Severity::Warning,
        format!("{}: {what}, {then}", f.describe()),
    );
    let mut affects: Vec<crate::domain::Parameter> = params::ANGLES.to_vec();
    affects.extend(params::LENGTH);
    let w = if gyro { w.withholding(&affects) } else { w };
    w.over_span(f.start_s, f.end_s)
}

/// Withhold the strides that overlap the span of `w` (a finding about part of the walk): not
/// valid, with the finding added ([`Warning::reason`] its text). The other strides keep their
/// numbers and values. Returns how many overlap.
pub(crate) fn withhold_span(st: &mut [Stride], w: &Warning) -> usize {
    let Some([start_s, end_s]) = w.span_s else {
        return 0;
    };
    let f = StrideFinding::new(
        StrideCode::Finding {
            code: w.code,
            effect: crate::gait::FindingEffect::Excludes,
        },
        w.reason(),
    );
    let mut n = 0;
    for s in st
        .iter_mut()
        .filter(|s| s.hs_time_s <= end_s && s.next_hs_time_s >= start_s)
    {
        s.valid = false;
        s.push_once(f.clone());
        n += 1;
    }
    n
}

/// Withhold the strides that overlap a fault: not valid, with the fault named in the reason
/// ("shank gyroscope z frozen from 12.3 s to 15.8 s", as
/// [`Warning::reason`] of its [`fault_warning`]). Returns how many strides were withheld.
pub fn withhold_faulty_strides(st: &mut [Stride], faults: &[ChannelFault]) -> usize {
    faults
        .iter()
        .map(|f| withhold_span(st, &fault_warning(f)))
        .sum()
}
