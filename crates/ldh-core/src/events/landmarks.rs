//! The landmarks of the shank's sagittal angular velocity ω_s the detectors read, one stride
//! at a time (split from `events.rs`; no rule changed): mid-swing (the negative peaks of ω_s),
//! the heel strike after it per detector, the late-stance peak t_s and the pitch peak t_p before
//! it (Aminian et al. 2002, J Biomech 35:689; Salarian et al. 2004, IEEE TBME 51:1434;
//! Trojaniello et al. 2014, J NeuroEng Rehabil 11:152) and the toe off of the detectors other
//! than `gyro-bracket`, and the confidence of the bracket's start (`events/confidence.rs` uses it).

use super::{
    bracket_toe_off_s, midswing_threshold_dps, peaks, EventDetector, EventParams, ValidEventParams,
    BRACKET_K0, TO_LANDMARK_COEFFS,
};

/// Parabolic sub-sample position of an extremum at `i`.
pub(super) fn parabolic(y: &[f64], i: usize) -> f64 {
    if i == 0 || i + 1 >= y.len() {
        return i as f64;
    }
    let (a, b, c) = (y[i - 1], y[i], y[i + 1]);
    let den = a - 2.0 * b + c;
    if den.abs() < 1e-12 {
        return i as f64;
    }
    i as f64 + (0.5 * (a - c) / den).clamp(-0.5, 0.5)
}

/// The late-stance landmarks before the mid-swing at `m`, searched in `[start, m)`: the
/// late-stance peak of ω_s (index `l`, Aminian et al. 2002 and Salarian et al. 2004 take the
/// largest such peak before mid-swing as the toe-off landmark; Trojaniello et al. 2014 likewise
/// take the largest one in the search window) and the first downward zero crossing after it
/// (index `z`, ω_s[z] ≥ 0 > ω_s[z + 1]: the pitch peak).
///
/// The peak is the largest positive local maximum of the window, not the last one: a stiff-knee
/// swing can pause the shank just after toe off, and the small bump of ω_s that pause makes
/// (with a second zero crossing) lies 100–200 ms after the toe off. `None` when the window has
/// no positive local maximum followed by a zero crossing before `m`.
fn late_stance(omega_s_dps: &[f64], start: usize, m: usize) -> Option<(usize, usize)> {
    let start = start.max(1);
    let l = (start..m)
        .filter(|&i| {
            omega_s_dps[i] > 0.0
                && omega_s_dps[i] >= omega_s_dps[i + 1]
                && omega_s_dps[i] > omega_s_dps[i - 1]
        })
        .max_by(|&a, &b| omega_s_dps[a].total_cmp(&omega_s_dps[b]))?;
    let z = (l..m).find(|&i| omega_s_dps[i] >= 0.0 && omega_s_dps[i + 1] < 0.0)?;
    Some((l, z))
}

/// The confidence of the toe off before the mid-swing at `m` (window `[start, m)`): 1 − the
/// largest other positive peak of ω_s over the late-stance peak the bracket starts from, where
/// "other" means separated from it by a dip below half its own height (a wobble on one peak is
/// not a second candidate). Two push-off peaks of nearly one height (a shuffle, a hesitation
/// before the swing) leave the bracket's start, and the toe off with it, unsure.
pub(super) fn late_stance_confidence(omega_s_dps: &[f64], start: usize, m: usize) -> f64 {
    let w = omega_s_dps;
    let (a, b) = (start.max(1), m.min(w.len().saturating_sub(1)));
    let peaks: Vec<usize> = (a..b)
        .filter(|&i| w[i] > 0.0 && w[i] >= w[i + 1] && w[i] > w[i - 1])
        .collect();
    let Some(&l) = peaks.iter().max_by(|&&x, &&y| w[x].total_cmp(&w[y])) else {
        return 0.0;
    };
    let second = peaks
        .iter()
        .filter(|&&i| {
            let (lo, hi) = (i.min(l), i.max(l));
            i != l && w[lo..=hi].iter().copied().fold(f64::INFINITY, f64::min) < 0.5 * w[i]
        })
        .map(|&i| w[i])
        .fold(0.0, f64::max);
    1.0 - second / w[l]
}

/// The signals the event rules read: pitch (deg), ω_s (deg/s), −ω_s and the rate (Hz).
pub(super) struct Signals<'a> {
    pub(super) pitch_deg: &'a [f64],
    pub(super) omega_s_dps: &'a [f64],
    pub(super) neg: &'a [f64],
    pub(super) fs_hz: f64,
}

/// Mid-swing samples: peaks of −ω_s above the threshold (height and prominence), at least 0.8 ×
/// the shortest stride apart, in order (`find_peaks`' peaks, found in linear time: [`peaks`]).
pub(super) fn midswings(neg: &[f64], p: &EventParams, fs_hz: f64) -> Vec<usize> {
    let min_dist = ((p.min_stride_s * 0.8) * fs_hz).max(1.0) as usize;
    let threshold = midswing_threshold_dps(neg, p);
    peaks::peaks(neg, threshold, threshold, min_dist)
}

/// The median interval between mid-swings no longer than `max_stride_s`, s (1.1 s when none).
pub(super) fn median_stride_s(mid: &[usize], fs_hz: f64, max_stride_s: f64) -> f64 {
    let mut iv: Vec<f64> = mid
        .windows(2)
        .map(|w| (w[1] - w[0]) as f64 / fs_hz)
        .filter(|d| *d <= max_stride_s)
        .collect();
    crate::stats::median(&mut iv, crate::stats::EvenMedian::Upper).unwrap_or(1.1)
}

/// The heel strike after the mid-swing at sample `m` and before `end`, as a fractional sample.
pub(super) fn heel_strike(
    sig: &Signals,
    detector: EventDetector,
    m: usize,
    end: usize,
) -> Option<f64> {
    let (pitch_deg, omega_s_dps) = (sig.pitch_deg, sig.omega_s_dps);
    match detector {
        EventDetector::PitchPeaks => (m..=end)
            .min_by(|&a, &b| {
                pitch_deg[a]
                    .partial_cmp(&pitch_deg[b])
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .filter(|&i| i > m && i < end)
            .map(|i| i as f64),
        EventDetector::GyroZeroCrossing
        | EventDetector::GyroLandmarks
        | EventDetector::GyroBracket => (m..end)
            .find(|&i| omega_s_dps[i] < 0.0 && omega_s_dps[i + 1] >= 0.0)
            .map(|i| i as f64 + (-omega_s_dps[i]) / (omega_s_dps[i + 1] - omega_s_dps[i])),
        EventDetector::Salarian => {
            let zc = (m..end).find(|&i| omega_s_dps[i] < 0.0 && omega_s_dps[i + 1] >= 0.0);
            zc.and_then(|z| {
                (z + 1..end).find(|&i| {
                    omega_s_dps[i] >= omega_s_dps[i - 1] && omega_s_dps[i] > omega_s_dps[i + 1]
                })
            })
            .map(|i| parabolic(omega_s_dps, i))
        }
    }
}

/// The toe-off landmarks before the mid-swing at `m` (searched from `start`), s: the late-stance
/// peak of ω_s t_s (parabolic), the pitch peak t_p (the zero crossing after it, linear) and
/// mid-swing t_m (parabolic).
pub(super) fn landmarks_s(sig: &Signals, start: usize, m: usize) -> Option<[f64; 3]> {
    let (w, fs_hz) = (sig.omega_s_dps, sig.fs_hz);
    let (l, z) = late_stance(w, start, m)?;
    let tp = (z as f64 + w[z] / (w[z] - w[z + 1])) / fs_hz;
    let ts = parabolic(w, l) / fs_hz;
    let tm = parabolic(sig.neg, m) / fs_hz;
    Some([ts, tp, tm])
}

/// The toe off between sample `start` and the mid-swing at sample `m`, s, offsets applied
/// (`t_med`: the median stride time, s).
pub(super) fn toe_off_s(
    sig: &Signals,
    params: &ValidEventParams,
    t_med: f64,
    start: usize,
    m: usize,
) -> Option<f64> {
    let (pitch_deg, omega_s_dps, fs_hz) = (sig.pitch_deg, sig.omega_s_dps, sig.fs_hz);
    let to_idx: Option<f64> = match params.p.detector {
        EventDetector::GyroLandmarks => {
            let [ts, tp, tm] = landmarks_s(sig, start, m)?;
            let [_, b, c] = TO_LANDMARK_COEFFS;
            return Some(tp + params.to_offset * t_med + b * (tm - tp) + c * (tp - ts));
        }
        // `detect` places these itself (it keeps their landmarks); the same toe off.
        EventDetector::GyroBracket => {
            let lm = landmarks_s(sig, start, m)?;
            return Some(bracket_toe_off_s(lm, BRACKET_K0, params.to_offset * t_med).min(lm[2]));
        }
        EventDetector::PitchPeaks => (start..=m)
            .max_by(|&a, &b| {
                pitch_deg[a]
                    .partial_cmp(&pitch_deg[b])
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .filter(|&i| i > start && i < m)
            .map(|i| i as f64),
        EventDetector::GyroZeroCrossing => late_stance(omega_s_dps, start, m)
            .map(|(_, z)| z as f64 + omega_s_dps[z] / (omega_s_dps[z] - omega_s_dps[z + 1])),
        EventDetector::Salarian => {
            late_stance(omega_s_dps, start, m).map(|(l, _)| parabolic(omega_s_dps, l))
        }
    };
    to_idx.map(|i| i / fs_hz + params.to_offset * t_med)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One stride of ω_s at 100 Hz around a mid-swing at sample 100: a late-stance peak of
    /// 80 deg/s at 60, its zero crossing at 70, then (stiff-knee swing) a 9 deg/s bump at 85
    /// with a second zero crossing at 90 before the −300 deg/s mid-swing.
    fn stiff_knee_swing() -> Vec<f64> {
        let bump = |i: f64, c: f64, w: f64, a: f64| a * (-((i - c) / w).powi(2)).exp();
        (0..140)
            .map(|i| {
                let i = i as f64;
                bump(i, 60.0, 6.0, 80.0) - bump(i, 76.0, 3.0, 40.0) + bump(i, 85.0, 2.5, 25.0)
                    - bump(i, 100.0, 6.0, 300.0)
            })
            .collect()
    }

    #[test]
    fn late_stance_takes_the_largest_peak_and_its_own_zero_crossing() {
        let w = stiff_knee_swing();
        // The swing bump is a positive local maximum followed by a zero crossing.
        assert!(w[85] > 0.0 && w[85] > w[84] && w[85] >= w[86], "{}", w[85]);
        let (l, z) = late_stance(&w, 30, 100).expect("landmarks");
        assert_eq!(l, 60);
        assert!((66..76).contains(&z), "zero crossing at {z}");
        assert!(w[z] >= 0.0 && w[z + 1] < 0.0);
        // No positive peak in the window: no landmark.
        let neg: Vec<f64> = w.iter().map(|x| -x.abs() - 1.0).collect();
        assert_eq!(late_stance(&neg, 30, 100), None);
    }
}
