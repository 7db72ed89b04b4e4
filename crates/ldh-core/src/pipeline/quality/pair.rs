//! Checks on a pair of legs: clocks, rates and lengths, identical signals, legs that cannot
//! come from one walk, stride lengths that disagree, and a possible left/right swap.

use super::warning::{codes, params, Severity, Warning};
use super::{finite_median, LegResult};

/// Largest relative difference of the two legs' median stride times in one walk (0.05): both
/// legs take the same number of strides, so their stride times agree within event-timing noise
/// (a few %) unless the files come from different walks or subjects, or a clock is wrong.
pub const LR_STRIDE_TIME_TOL: f64 = 0.05;

/// Largest relative difference of the two legs' median stride lengths (0.10): over a walk both
/// ankles cover the same distance, so their stride lengths agree (healthy asymmetry 1-3 %, and
/// even hemiparetic gait keeps equal stride lengths: only the steps differ), and a larger gap is
/// a measurement error on at least one leg.
pub const LR_STRIDE_LENGTH_TOL: f64 = 0.10;

/// Largest angle between a device axis (x, z) on one leg and the mirror image (in the sagittal
/// plane) of the same axis on the other leg for the two devices to count as strapped the same
/// way on each leg, deg (30).
pub const MIRROR_TOL_DEG: f64 = 30.0;

/// Smallest angle by which both devices' faces (their +z axes) must turn toward the other leg,
/// away from straight ahead, for the swap check, deg (30): a strap turned a little round the
/// front of the shin says nothing.
pub const MEDIAL_FACE_DEG: f64 = 30.0;

/// Warnings about a pair of legs read from two files: sampling rates that differ by more than
/// 0.5 %, recordings that do not overlap in time (step time is then not computed), different
/// lengths or starts (more than 1 s and 5 %), the same signals in both files, stride times or
/// stride lengths that one walk cannot give, and two devices strapped the same way on
/// each leg whose faces both point at the other leg (the files swapped, [`swapped_mounting`]). Returns the
/// warnings and whether the legs share a time span (to pair their heel strikes).
pub fn pair_warnings(l: &LegResult, r: &LegResult) -> (Vec<Warning>, bool) {
    let mut w = Vec::new();
    let (lf, rf) = (l.read.fs_hz, r.read.fs_hz);
    if (lf - rf).abs() > 0.005 * lf.max(rf) {
        w.push(Warning::new(codes::RATE_MISMATCH, Severity::Warning, format!(
            "the two sensors' sampling rates differ: left {lf:.3} Hz, right {rf:.3} Hz ({:+.1} %): different device settings, or a clock that runs fast or slow; each leg is analysed at its own rate",
            (rf / lf - 1.0) * 100.0
        )));
    }
    let (ld, rd) = (l.read.duration_s, r.read.duration_s);
    let (la, lb, ra, rb) = (l.t0_s, l.t0_s + ld, r.t0_s, r.t0_s + rd);
    let overlap = lb.min(rb) - la.max(ra);
    let overlapping = overlap > 0.0;
    if !overlapping {
        w.push(Warning::new(codes::NO_OVERLAP, Severity::Warning, format!(
            "the two recordings do not overlap in time (left {la:.2}–{lb:.2} s, right {ra:.2}–{rb:.2} s, each on its file's clock): different clocks or different sessions? Step time and step frequency, which pair the legs, are not computed"
        )));
    } else {
        let tol = |a: f64, b: f64| (a - b).abs() > 1.0_f64.max(0.05 * a.abs().max(b.abs()));
        if tol(ld, rd) || (la - ra).abs() > 1.0_f64.max(0.05 * ld.max(rd)) {
            w.push(Warning::new(codes::LENGTH_MISMATCH, Severity::Warning, format!(
                "the two recordings differ in length or start: left {la:.2}–{lb:.2} s ({ld:.1} s), right {ra:.2}–{rb:.2} s ({rd:.1} s), overlap {overlap:.1} s: the sensors were not started and stopped together, or a file is cut; the legs are paired only where they overlap"
            )));
        }
    }
    if let Some(x) = identical(l, r) {
        w.push(x);
    } else {
        w.extend(disagreement(l, r));
    }
    if let Some((fl, fr)) = swapped_mounting(l, r) {
        w.push(Warning::new(codes::POSSIBLE_SWAP, Severity::Warning, format!(
            "the left and right files may be swapped: the two devices are strapped the same way on each leg (mirror images), but each faces the other leg (the left one {fl:.0}° toward the right, the right one {fr:.0}° toward the left), as the files of devices worn facing outwards do when they are exchanged. Check which file is which leg's; the results keep the sides as given"
        )));
    }
    (w, overlapping)
}

/// The swap rule (docs/quality.md "Pair checks"): the two devices are mirror images of each
/// other — each one's x and z axes within [`MIRROR_TOL_DEG`] of the other's reflected in the
/// sagittal plane, as identical devices strapped at the same place on each shank are — and
/// both faces (+z, the axis out of a device's face) point at the other leg by more than
/// [`MEDIAL_FACE_DEG`]: the left device toward the right, the right one toward the left. A
/// device is worn on the outside or the front of the shank, facing out, so two faces turned
/// inward are the two files exchanged (or two devices worn face in, which the message names).
/// Devices strapped differently on the two legs, or facing forward, give nothing. Returns how
/// far each face turns inward, deg (left, right).
pub fn swapped_mounting(l: &LegResult, r: &LegResult) -> Option<(f64, f64)> {
    let axis = |a: &crate::align::Alignment, k: usize| {
        let m = &a.r_f_from_device;
        [m[0][k], m[1][k], m[2][k]]
    };
    let (la, ra) = (&l.alignment, &r.alignment);
    let cos_tol = MIRROR_TOL_DEG.to_radians().cos();
    let mirrored = [0, 2].into_iter().all(|k| {
        let (u, v) = (axis(la, k), axis(ra, k));
        u[0] * v[0] - u[1] * v[1] + u[2] * v[2] >= cos_tol
    });
    // How far a face turns to the left (+) or right (−), deg.
    let leftward = |a| axis(a, 2)[1].clamp(-1.0, 1.0).asin().to_degrees();
    let (fl, fr) = (-leftward(la), leftward(ra));
    (mirrored && fl > MEDIAL_FACE_DEG && fr > MEDIAL_FACE_DEG).then_some((fl, fr))
}

/// The same signals in both files (the same file given twice, or a copy): every stride time
/// equal to the microsecond and every event at the same time.
fn identical(l: &LegResult, r: &LegResult) -> Option<Warning> {
    let (le, re) = (&l.events, &r.events);
    let same = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && !a.is_empty() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
    };
    (same(&le.hs_s, &re.hs_s) && same(&le.to_s, &re.to_s) && (l.t0_s - r.t0_s).abs() < 1e-9).then(
        || {
            Warning::new(
                codes::IDENTICAL_LEGS,
                Severity::Fault,
                format!(
                    "the left and right recordings give identical events ({} heel strikes at the same times): the same file given for both legs, or a copy. Nothing is measured for either leg",
                    le.hs_s.len()
                ),
            )
            .withholding(&params::ALL)
        },
    )
}

/// Stride times or stride lengths that one walk cannot give.
fn disagreement(l: &LegResult, r: &LegResult) -> Vec<Warning> {
    let mut w = Vec::new();
    let med = |leg: &LegResult, f: fn(&crate::gait::Stride) -> f64| {
        finite_median(leg.strides.iter().filter(|s| s.valid).map(f).collect())
    };
    let rel = |a: f64, b: f64| (a - b).abs() / a.max(b);
    if let (Some(a), Some(b)) = (med(l, |s| s.stride_time_s), med(r, |s| s.stride_time_s)) {
        // A clock that runs fast shows in the rates, and is its own warning.
        if rel(a, b) > LR_STRIDE_TIME_TOL {
            w.push(
                Warning::new(codes::LR_DISAGREEMENT, Severity::Warning, format!(
                    "left and right median stride times differ by {:.0} % (left {a:.3} s, right {b:.3} s): in one walk both legs take the same strides, so the files may come from different walks or subjects, or one leg's events are wrong; step time and step frequency, which pair the legs, are not measured",
                    rel(a, b) * 100.0
                ))
                .withholding(&params::PAIRED),
            );
        }
    }
    if let (Some(a), Some(b)) = (med(l, |s| s.stride_length_m), med(r, |s| s.stride_length_m)) {
        if rel(a, b) > LR_STRIDE_LENGTH_TOL {
            w.push(
                Warning::new(codes::LR_DISAGREEMENT, Severity::Warning, format!(
                    "left and right median stride lengths differ by {:.0} % (left {a:.2} m, right {b:.2} m): over a walk both ankles cover the same distance, so at least one leg's stride length is wrong; stride length, speed and their variability are not measured on either leg",
                    rel(a, b) * 100.0
                ))
                .withholding(&params::LENGTH),
            );
        }
    }
    w
}
