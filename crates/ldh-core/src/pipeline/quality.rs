//! Warnings about one leg and about a pair of legs that do not stop the analysis.

use super::*;

use crate::align::Alignment;
use crate::gait::{SideParameters, Stride};

/// Shortest mean stride time of walking, s: below it (a cadence above 150 steps/min) the gait
/// looks like running.
pub const RUNNING_STRIDE_TIME_S: f64 = 0.8;

/// Warnings about one leg's analysis: a device mounted upside down (corrected by the
/// alignment, but worth checking), gait that looks like running (the median time of all detected
/// strides below [`RUNNING_STRIDE_TIME_S`], or their median stance below half the stride, i.e. a
/// flight phase — running strides are usually refused as too short, so all strides are used),
/// and fewer than three valid strides.
pub fn leg_warnings(al: &Alignment, st: &[Stride], p: &SideParameters) -> Vec<String> {
    let mut w = Vec::new();
    if al.shank_axis_tilt_deg > 90.0 {
        w.push(format!(
            "device mounted upside down: its x axis points down the shank ({:.0} deg from the shank axis found from gravity at rest); the alignment corrected for it — check the mounting if this is unexpected",
            al.shank_axis_tilt_deg
        ));
    }
    let median = |mut v: Vec<f64>| -> Option<f64> {
        v.retain(|x| x.is_finite());
        v.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        (v.len() >= 3).then(|| v[v.len() / 2])
    };
    let stride_time = median(st.iter().map(|s| s.stride_time_s).collect());
    let stance = median(st.iter().map(|s| s.stance_ratio).collect());
    if let Some(t) = stride_time {
        let stance = stance.unwrap_or(f64::NAN);
        if t < RUNNING_STRIDE_TIME_S || stance < 0.5 {
            w.push(format!(
                "this looks like running, not walking: median stride time {t:.2} s ({:.0} steps/min) over {} detected strides, median stance {:.0} % of the stride; the gait parameters and their reference values are defined for walking",
                120.0 / t,
                st.len(),
                stance * 100.0
            ));
        }
    }
    if p.strides_valid < 3 {
        w.push(format!(
            "only {} valid stride(s) of {}: the per-side parameters are unreliable or missing",
            p.strides_valid, p.strides_total
        ));
    }
    w
}

/// Warnings about a pair of legs read from two files: sampling rates that differ by more than
/// 0.5 % (different settings, or a clock running fast), recordings that do not overlap in time
/// (different clocks: step time is then not computed), different lengths or starts (more than
/// 1 s and 5 %), and the left sensor mounted mirrored while the right one is not — the opposite
/// of identical devices worn on the lateral side of both shanks, so the files may be swapped.
/// Returns the warnings and whether the legs share a time span (to pair their heel strikes).
pub fn pair_warnings(l: &LegResult, r: &LegResult) -> (Vec<String>, bool) {
    let mut w = Vec::new();
    let (lf, rf) = (l.read.fs_hz, r.read.fs_hz);
    if (lf - rf).abs() > 0.005 * lf.max(rf) {
        w.push(format!(
            "the two sensors' sampling rates differ: left {lf:.3} Hz, right {rf:.3} Hz ({:+.1} %): different device settings, or a clock that runs fast or slow; each leg is analysed at its own rate",
            (rf / lf - 1.0) * 100.0
        ));
    }
    let (ld, rd) = (l.read.duration_s, r.read.duration_s);
    let (la, lb, ra, rb) = (l.t0_s, l.t0_s + ld, r.t0_s, r.t0_s + rd);
    let overlap = lb.min(rb) - la.max(ra);
    let overlapping = overlap > 0.0;
    if !overlapping {
        w.push(format!(
            "the two recordings do not overlap in time (left {la:.2}–{lb:.2} s, right {ra:.2}–{rb:.2} s, each on its file's clock): different clocks or different sessions? Step time and step frequency, which pair the legs, are not computed"
        ));
    } else {
        let tol = |a: f64, b: f64| (a - b).abs() > 1.0_f64.max(0.05 * a.abs().max(b.abs()));
        if tol(ld, rd) || (la - ra).abs() > 1.0_f64.max(0.05 * ld.max(rd)) {
            w.push(format!(
                "the two recordings differ in length or start: left {la:.2}–{lb:.2} s ({ld:.1} s), right {ra:.2}–{rb:.2} s ({rd:.1} s), overlap {overlap:.1} s: the sensors were not started and stopped together, or a file is cut; the legs are paired only where they overlap"
            ));
        }
    }
    if l.alignment.mirrored && !r.alignment.mirrored {
        w.push(
            "the left sensor is mounted mirrored (its y axis points backwards) and the right one is not — the opposite of identical devices worn on the lateral side of both shanks: are the left and right files swapped? (This check assumes identical devices worn laterally; the results keep the sides as given.)".to_string(),
        );
    }
    (w, overlapping)
}
