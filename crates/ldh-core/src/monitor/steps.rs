//! The steps of a walking bout and whether it was a run.
//!
//! **Steps.** A step is a foot placed forward: its heel strike (initial contact). The lab
//! pipeline's heel strikes follow mid-swings above an adaptive threshold (35 % of the walk's
//! 99th percentile of −ω_s, at most 100 deg/s; `events`), set for stride parameters; the first
//! step from standing and the last step that brings the feet together are half-swings
//! (≈ 20–30 % of a full swing's peak) and fall below it. Mobilise-D's walking bout runs from
//! the first initial contact to the last (Kluge et al., Sensors 2021; Micó-Amigo et al.,
//! J NeuroEng Rehabil 2023), and a step counter counts those steps too, so the monitor looks
//! for them: a swing of the leg (a peak of −ω_s) 0.6–1.4 stride times before its first
//! mid-swing, or after its last, at least [`EDGE_SWING_SHARE`] of the bout's median mid-swing
//! peak and [`EDGE_SWING_MIN_DPS`]. Its heel strike is the peak plus the bout's median delay
//! from mid-swing to heel strike. These steps count in `steps`, `start_s` and `end_s`, never in
//! the stride parameters (a half-step is not a stride).
//!
//! **Running.** A bout whose median stride time (between mid-swings) is under `running_max_stride_s` (0.8 s: a cadence
//! above 150 steps/min, beyond the walk-to-run transition; Tudor-Locke et al., Br J Sports Med
//! 2018 for cadence bands) and whose heel strikes land with a median peak acceleration of at
//! least `running_min_acc_g` (3 g: tibial shock of running, Lafortune et al., J Biomech 1996)
//! is a run, not walking (the windows' rule at the bout's scale).

use crate::pipeline::LegResult;
use crate::stats::{median, EvenMedian};

/// Least peak of an initiation or termination swing, share of the bout's median mid-swing
/// peak: 0.15.
pub const EDGE_SWING_SHARE: f64 = 0.15;
/// Least peak of an initiation or termination swing, deg/s: 30 (postural sway and weight
/// shifts stay well below).
pub const EDGE_SWING_MIN_DPS: f64 = 30.0;

/// The heel strikes of one leg in a bout, s from the leg's first sample: the pipeline's, plus
/// the initiation step before its first mid-swing and the termination step after its last
/// where the leg shows them (module docs).
pub fn leg_heel_strikes(l: &LegResult) -> Vec<f64> {
    let ev = &l.events;
    let mut hs = ev.hs_s.clone();
    let (Some(sig), true) = (l.signals.as_ref(), ev.midswing_s.len() >= 2) else {
        return hs;
    };
    let (w, fs) = (&sig.gyro_dps[1], sig.fs_hz);
    let n = w.len();
    let at = |t: f64| ((t * fs).round().max(0.0) as usize).min(n.saturating_sub(1));
    let t_med = ev.median_stride_s;
    let mut heights: Vec<f64> = ev.midswing_s.iter().map(|&m| -w[at(m)]).collect();
    let Some(height) = median(&mut heights, EvenMedian::Mean) else {
        return hs;
    };
    let mut delays: Vec<f64> = ev
        .midswing_s
        .iter()
        .filter_map(|&m| {
            let j = hs.partition_point(|&h| h <= m);
            hs.get(j).map(|h| h - m).filter(|d| *d < 0.5 * t_med)
        })
        .collect();
    let Some(delay) = median(&mut delays, EvenMedian::Mean) else {
        return hs;
    };
    let thr = EDGE_SWING_MIN_DPS.max(EDGE_SWING_SHARE * height);
    // The largest swing peak strictly inside [t0, t1] s, when it passes the threshold.
    let swing = |t0: f64, t1: f64| -> Option<f64> {
        let (i0, i1) = (at(t0.max(0.0)), at(t1));
        if i1 <= i0 + 2 {
            return None;
        }
        let i = (i0..=i1).max_by(|&a, &b| (-w[a]).total_cmp(&(-w[b])))?;
        (i > i0 && i < i1 && -w[i] >= thr).then(|| i as f64 / fs)
    };
    let (first, last) = (ev.midswing_s[0], ev.midswing_s[ev.midswing_s.len() - 1]);
    let end_s = n as f64 / fs;
    if let Some(p) = swing(first - 1.4 * t_med, first - 0.6 * t_med) {
        let h = p + delay;
        if h >= 0.0 && hs.first().is_none_or(|&f| h < f - 0.3 * t_med) {
            hs.insert(0, h);
        }
    }
    if let Some(p) = swing(last + 0.6 * t_med, last + 1.4 * t_med) {
        let h = p + delay;
        if h < end_s && hs.last().is_none_or(|&l| h > l + 0.3 * t_med) {
            hs.push(h);
        }
    }
    hs
}

/// The median over heel strikes `hs_s` (s from the first sample) of the largest acceleration
/// magnitude from 50 ms before to 150 ms after each, g; `acc_norm_g` sampled at `fs_hz` from
/// the same first sample.
pub fn heel_strike_peak_g(hs_s: &[f64], acc_norm_g: &[f64], fs_hz: f64) -> Option<f64> {
    let n = acc_norm_g.len();
    let mut peaks: Vec<f64> = hs_s
        .iter()
        .filter_map(|&h| {
            let i0 = (((h - 0.05) * fs_hz).floor().max(0.0) as usize).min(n);
            let i1 = (((h + 0.15) * fs_hz).ceil().max(0.0) as usize).min(n);
            (i1 > i0).then(|| acc_norm_g[i0..i1].iter().copied().fold(0.0, f64::max))
        })
        .collect();
    median(&mut peaks, EvenMedian::Mean)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heel_strike_peaks_are_the_median_of_each_strikes_window() {
        let fs = 100.0;
        let mut a = vec![1.0; 500];
        for (k, &i) in [100usize, 200, 300].iter().enumerate() {
            a[i + 5] = 3.0 + k as f64;
        }
        let m = heel_strike_peak_g(&[1.0, 2.0, 3.0], &a, fs).unwrap();
        assert!((m - 4.0).abs() < 1e-12, "{m}");
        assert_eq!(heel_strike_peak_g(&[], &a, fs), None);
    }
}
