//! What one window of one shank's signal is: the activity classes of the monitor and the
//! rules that give them (docs/free-living.md, "Windows").
//!
//! Features per window (default 1 s) with a context of the last seconds (default 4 s):
//! the standard deviation of the gyroscope axis that moves most (the sagittal axis of a shank
//! while walking or pedalling, whatever the mounting), its autocorrelation peak at a stride
//! period of 0.45–2.2 s (a dominant frequency of 0.45–2.2 Hz, the stride frequencies of
//! walking, running and pedalling), the skewness of that axis (the shank's swing is one short
//! fast burst and stance a slow return: skewed; pedalling is close to a sine), the largest
//! acceleration magnitude (heel-strike impacts), and the shank's tilt from gravity (the angle
//! between the mean acceleration and the sensor's long x axis).
//!
//! - periodic rotation with impacts and a skewed waveform: **walking** candidate (confirmed or
//!   refused by the gait pipeline on the bout, `monitor::bouts`);
//! - a stride period under `running_max_stride_s` with impacts over `running_min_acc_g`:
//!   **running**; periodic rotation without impacts, or with a near-sinusoidal waveform:
//!   **cycling** (sustained shank rotation with no stance phase and no heel strike);
//! - moving but not periodic: **other** (fidgeting, shuffling, transfers);
//! - still: **lying** (shank within `lying_min_tilt_deg` of horizontal), **sitting** (shank
//!   tilted more than `sitting_min_tilt_deg`, or upright with no postural sway at all),
//!   **standing** (upright with sway). The sitting/standing split from a shank alone is a
//!   heuristic (a thigh sensor would settle it: Bourke et al., J Biomech 2017;
//!   ActivPAL-style posture needs the thigh); it is reported, never used to withhold gait.
//!
//! Non-wear is decided per minute over longer spans (`monitor::days`, van Hees 2011/2013).
//! Sources: mobgap's gait sequence detection (Micó-Amigo et al., J NeuroEng Rehabil 2023;
//! Paraschiv-Ionescu et al. 2019: a periodic signal with a dominant frequency in the stride
//! band, here on the shank's angular velocity); Kluge et al. (Sensors 2021) for the stride
//! band on shank gyroscopes.

use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// The activity of a window (or a minute: its most frequent window class).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Activity {
    /// No sample in the window (a gap, or before/after the recording).
    NoData,
    /// The sensor was not worn (van Hees: still on every axis for 60 min).
    NonWear,
    /// Lying: shank near horizontal.
    Lying,
    /// Sitting.
    Sitting,
    /// Standing.
    Standing,
    /// Walking (a candidate window; bouts are confirmed by the gait pipeline).
    Walking,
    /// Running.
    Running,
    /// Cycling (periodic rotation without impacts or stance).
    Cycling,
    /// Other movement.
    Other,
}

impl Activity {
    /// Every class, in table order.
    pub const ALL: [Activity; 9] = [
        Activity::NoData,
        Activity::NonWear,
        Activity::Lying,
        Activity::Sitting,
        Activity::Standing,
        Activity::Walking,
        Activity::Running,
        Activity::Cycling,
        Activity::Other,
    ];
    /// The name in the tables (`non_wear`, `walking` …).
    pub fn name(self) -> &'static str {
        match self {
            Activity::NoData => "no_data",
            Activity::NonWear => "non_wear",
            Activity::Lying => "lying",
            Activity::Sitting => "sitting",
            Activity::Standing => "standing",
            Activity::Walking => "walking",
            Activity::Running => "running",
            Activity::Cycling => "cycling",
            Activity::Other => "other",
        }
    }
    /// Position in [`Activity::ALL`].
    pub fn index(self) -> usize {
        Activity::ALL.iter().position(|a| *a == self).unwrap_or(0)
    }
}

/// The thresholds of the window classes (defaults in brackets; see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WindowParams {
    /// Window length, s [1].
    pub window_s: f64,
    /// Context over which periodicity is judged, s [4].
    pub context_s: f64,
    /// Least SD of the most moving gyroscope axis for periodic rotation, deg/s [40].
    pub min_gyro_sd_dps: f64,
    /// Least autocorrelation at the stride period [0.5].
    pub min_autocorr: f64,
    /// Shortest stride period, s [0.45]; longest [2.2].
    pub min_stride_s: f64,
    /// Longest stride period, s [2.2].
    pub max_stride_s: f64,
    /// Least peak acceleration magnitude of a heel-strike impact, g [1.4].
    pub impact_acc_g: f64,
    /// Least |skewness| of the sagittal angular velocity for a stance and swing [0.35].
    pub min_walk_skew: f64,
    /// Running: stride period below this, s [0.8] …
    pub running_max_stride_s: f64,
    /// … and peak acceleration above this, g [3.0].
    pub running_min_acc_g: f64,
    /// Moving: gyroscope SD above this, deg/s [10], or acceleration-magnitude SD above
    /// `moving_acc_sd_g` [0.03].
    pub moving_gyro_sd_dps: f64,
    /// See `moving_gyro_sd_dps`, g.
    pub moving_acc_sd_g: f64,
    /// Lying: shank tilted at least this from vertical, deg [60].
    pub lying_min_tilt_deg: f64,
    /// Sitting: shank tilted at least this, deg [20].
    pub sitting_min_tilt_deg: f64,
    /// Upright with a gyroscope RMS below this (no postural sway): sitting, deg/s [0.8].
    pub sway_min_dps: f64,
}

impl Default for WindowParams {
    fn default() -> Self {
        WindowParams {
            window_s: 1.0,
            context_s: 4.0,
            min_gyro_sd_dps: 40.0,
            min_autocorr: 0.5,
            min_stride_s: 0.45,
            max_stride_s: 2.2,
            impact_acc_g: 1.4,
            min_walk_skew: 0.35,
            running_max_stride_s: 0.8,
            running_min_acc_g: 3.0,
            moving_gyro_sd_dps: 10.0,
            moving_acc_sd_g: 0.03,
            lying_min_tilt_deg: 60.0,
            sitting_min_tilt_deg: 20.0,
            sway_min_dps: 0.8,
        }
    }
}

/// A shorter lag's autocorrelation peak of at least this share of the highest is taken as the
/// period (its multiples correlate almost as well): 0.9.
pub const HARMONIC_SHARE: f64 = 0.9;

/// The decimated rate of the periodicity context, Hz.
pub const CONTEXT_HZ: f64 = 25.0;

/// One window's sums (filled sample by sample).
#[derive(Debug, Clone, Default)]
pub struct WindowAcc {
    /// Samples.
    pub n: usize,
    acc_sum: [f64; 3],
    acc_norm_sum: f64,
    acc_norm_sq: f64,
    gyro_sq: f64,
    /// Largest acceleration magnitude, g.
    pub acc_max_g: f64,
}

impl WindowAcc {
    /// Add one sample.
    pub fn push(&mut self, acc: &[f64; 3], gyro: &[f64; 3]) {
        self.n += 1;
        for k in 0..3 {
            self.acc_sum[k] += acc[k];
        }
        let a = (acc[0] * acc[0] + acc[1] * acc[1] + acc[2] * acc[2]).sqrt();
        self.acc_norm_sum += a;
        self.acc_norm_sq += a * a;
        self.gyro_sq += gyro[0] * gyro[0] + gyro[1] * gyro[1] + gyro[2] * gyro[2];
        self.acc_max_g = self.acc_max_g.max(a);
    }
    fn tilt_deg(&self) -> f64 {
        let m = self.acc_sum.map(|s| s / self.n.max(1) as f64);
        let norm = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        if norm < 1e-6 {
            return f64::NAN;
        }
        (m[0].abs() / norm).clamp(0.0, 1.0).acos().to_degrees()
    }
    fn acc_sd_g(&self) -> f64 {
        let n = self.n.max(1) as f64;
        let m = self.acc_norm_sum / n;
        (self.acc_norm_sq / n - m * m).max(0.0).sqrt()
    }
    fn gyro_rms_dps(&self) -> f64 {
        (self.gyro_sq / self.n.max(1) as f64).sqrt()
    }
}

/// The periodicity of the context: SD, autocorrelation peak and its lag, skewness of the
/// gyroscope axis that moves most.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Periodicity {
    /// SD of the axis, deg/s.
    pub sd_dps: f64,
    /// Normalised autocorrelation at the peak.
    pub r: f64,
    /// Its lag, s (the stride period).
    pub period_s: f64,
    /// Skewness of the axis.
    pub skew: f64,
}

/// The periodicity of `hist` (decimated gyroscope, [`CONTEXT_HZ`]) in the stride band.
pub fn periodicity(hist: &VecDeque<[f64; 3]>, p: &WindowParams) -> Periodicity {
    let n = hist.len();
    let none = Periodicity {
        sd_dps: 0.0,
        r: 0.0,
        period_s: f64::NAN,
        skew: 0.0,
    };
    if n < 8 {
        return none;
    }
    let mut mean = [0.0; 3];
    for s in hist {
        for k in 0..3 {
            mean[k] += s[k];
        }
    }
    mean = mean.map(|m| m / n as f64);
    let mut var = [0.0; 3];
    for s in hist {
        for k in 0..3 {
            var[k] += (s[k] - mean[k]).powi(2);
        }
    }
    let ax = (0..3)
        .max_by(|&a, &b| var[a].total_cmp(&var[b]))
        .unwrap_or(2);
    let x: Vec<f64> = hist.iter().map(|s| s[ax] - mean[ax]).collect();
    let v = var[ax];
    let sd = (v / n as f64).sqrt();
    if v <= 0.0 {
        return none;
    }
    let skew = x.iter().map(|d| d * d * d).sum::<f64>() / n as f64 / sd.powi(3);
    let lo = (p.min_stride_s * CONTEXT_HZ).floor().max(1.0) as usize;
    let hi = ((p.max_stride_s * CONTEXT_HZ).ceil() as usize).min(n - 2);
    let ac = |lag: usize| -> f64 {
        let s: f64 = (0..n - lag).map(|i| x[i] * x[i + lag]).sum();
        // Normalised by the overlap so a long lag is not penalised.
        s / v * n as f64 / (n - lag) as f64
    };
    let mut best = (0.0, f64::NAN);
    if lo < hi {
        let r: Vec<f64> = (lo - 1..=hi + 1).map(ac).collect();
        let peaks: Vec<usize> = (1..r.len() - 1)
            .filter(|&i| r[i] >= r[i - 1] && r[i] >= r[i + 1])
            .collect();
        let top = peaks.iter().map(|&i| r[i]).fold(0.0, f64::max);
        // The shortest lag whose peak is nearly the highest: the fundamental period, not one
        // of its multiples (a running stride of 0.7 s correlates as well at 1.4 and 2.1 s).
        if let Some(&i) = peaks.iter().find(|&&i| r[i] >= HARMONIC_SHARE * top) {
            best = (r[i], (lo - 1 + i) as f64 / CONTEXT_HZ);
        }
    }
    Periodicity {
        sd_dps: sd,
        r: best.0,
        period_s: best.1,
        skew,
    }
}

/// The class of a window from its sums, the context's periodicity and the context's largest
/// acceleration magnitude.
pub fn classify(
    w: &WindowAcc,
    per: &Periodicity,
    ctx_acc_max_g: f64,
    p: &WindowParams,
) -> Activity {
    let periodic = per.r >= p.min_autocorr && per.sd_dps >= p.min_gyro_sd_dps;
    if periodic {
        let impact = ctx_acc_max_g >= p.impact_acc_g;
        if per.period_s < p.running_max_stride_s && ctx_acc_max_g >= p.running_min_acc_g {
            return Activity::Running;
        }
        if !impact || per.skew.abs() < p.min_walk_skew {
            return Activity::Cycling;
        }
        return Activity::Walking;
    }
    let gyro = w.gyro_rms_dps();
    if gyro > p.moving_gyro_sd_dps
        || w.acc_sd_g() > p.moving_acc_sd_g
        || per.sd_dps >= p.min_gyro_sd_dps
    {
        return Activity::Other;
    }
    let tilt = w.tilt_deg();
    if tilt >= p.lying_min_tilt_deg {
        Activity::Lying
    } else if tilt >= p.sitting_min_tilt_deg || gyro < p.sway_min_dps {
        Activity::Sitting
    } else {
        Activity::Standing
    }
}
