//! Reconstruction of clipped accelerometer samples for the strapdown integration (issue 20).
//!
//! An accelerometer at its range reads the range, not the acceleration: a ±2 g shank sensor
//! (HuGaDB; family B's and family A's ±2 g subjects) clips in 2-3 runs of 50-150 ms per stride,
//! at push-off, in early swing and in terminal swing up to the heel strike. Interpolating a
//! clipped run linearly between its ends (what the attitude's signals get, paper §3.1) removes
//! the area above the range and more: the other axes of those samples were measured and are
//! replaced too. Integrated, the lost area is a velocity error at the clipped samples that
//! linear de-drifting spreads over the stride, leaving stride lengths up to 40 % short.
//!
//! Declipping (restoring a clipped signal from its unclipped neighbourhood: Abel & Smith 1991,
//! ICASSP, "Restoring a clipped signal") here is local and per axis: only the axis that reads
//! the clip level is replaced, each clipped run by the least-squares quadratic through the two
//! unclipped samples on each side of it, never smaller in magnitude than the clipped reading
//! (the true value lies beyond the range). Smooth bumps (the swing's decelerations) are
//! restored; an impact's shape is not, and the stride-length checks judge what is left
//! ([`crate::gait::LengthEstimate::implausible`]). On family A at ±2 g (tuning seed 100) it
//! takes the velocity lost per clipped run from 0.215 m/s (linear interpolation) to 0.021 m/s
//! (median; docs/accuracy.md). A quadratic through four points is hand-written (normal
//! equations, solved with nalgebra): no crate offers local declipping.

use nalgebra::{Matrix3, Vector3};

/// Good samples used on each side of a clipped run.
pub const DECLIP_NEIGHBOURS: usize = 2;

/// How far (samples) from a clipped run its good neighbours may lie; beyond, the run keeps its
/// clipped reading.
const MAX_REACH: usize = 8;

/// Relative tolerance of "at the clip level" (HuGaDB's int16 counts read +1.99994 and −2.0 g).
const LEVEL_TOL: f64 = 1e-3;

/// Per axis, the samples (sorted) where that axis clipped, and the flagged samples where no
/// axis reads the clip level (to be interpolated on all three axes, as before declipping).
///
/// `flagged` (sorted) are the samples the reader marked as clipped on the accelerometer; the
/// clip level is the largest magnitude any axis reads at a flagged sample (all axes of one
/// accelerometer share a range), and an axis clipped at a flagged sample when its magnitude
/// lies within 0.1 % of that level.
pub fn clipped_axes(acc: &[Vec<f64>; 3], flagged: &[usize]) -> ([Vec<usize>; 3], Vec<usize>) {
    let level = flagged
        .iter()
        .flat_map(|&i| acc.iter().map(move |ch| ch[i].abs()))
        .fold(0.0, f64::max);
    let at_level = |x: f64| level > 0.0 && x.abs() >= level * (1.0 - LEVEL_TOL);
    let mut axes: [Vec<usize>; 3] = Default::default();
    let mut unknown = Vec::new();
    for &i in flagged {
        let mut any = false;
        for (k, ch) in acc.iter().enumerate() {
            if at_level(ch[i]) {
                axes[k].push(i);
                any = true;
            }
        }
        if !any {
            unknown.push(i);
        }
    }
    (axes, unknown)
}

/// Replace the clipped samples `bad` (sorted) of one axis `v` by the least-squares quadratic
/// through the [`DECLIP_NEIGHBOURS`] good samples on each side of each run, never smaller in
/// magnitude than the clipped reading. A run without them within 8 samples (at the recording's
/// ends) keeps its clipped reading, the best lower bound of the truth.
pub fn declip(v: &mut [f64], bad: &[usize]) {
    let mut is_bad = vec![false; v.len()];
    for &i in bad {
        is_bad[i] = true;
    }
    let orig = v.to_vec();
    for (start, end) in runs(&is_bad) {
        let (Some(l), Some(r)) = (
            neighbours_left(&is_bad, start),
            neighbours_right(&is_bad, end),
        ) else {
            continue;
        };
        let pts: Vec<usize> = l.into_iter().chain(r).collect();
        let Some(c) = fit_quadratic(&orig, &pts, start) else {
            continue;
        };
        for k in start..end {
            let t = (k - start) as f64;
            let p = c[0] + c[1] * t + c[2] * t * t;
            v[k] = if orig[k] >= 0.0 {
                p.max(orig[k])
            } else {
                p.min(orig[k])
            };
        }
    }
}

/// The runs of `true` in `mask`, as half-open index ranges (start, end).
pub(crate) fn runs(mask: &[bool]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < mask.len() {
        if mask[i] {
            let s = i;
            while i < mask.len() && mask[i] {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

/// The [`DECLIP_NEIGHBOURS`] nearest good samples before `start`, within reach.
fn neighbours_left(is_bad: &[bool], start: usize) -> Option<Vec<usize>> {
    let lo = start.saturating_sub(MAX_REACH);
    let v: Vec<usize> = (lo..start)
        .rev()
        .filter(|&k| !is_bad[k])
        .take(DECLIP_NEIGHBOURS)
        .collect();
    (v.len() == DECLIP_NEIGHBOURS).then_some(v)
}

/// The [`DECLIP_NEIGHBOURS`] nearest good samples from `end` on, within reach.
fn neighbours_right(is_bad: &[bool], end: usize) -> Option<Vec<usize>> {
    let hi = (end + MAX_REACH).min(is_bad.len());
    let v: Vec<usize> = (end..hi)
        .filter(|&k| !is_bad[k])
        .take(DECLIP_NEIGHBOURS)
        .collect();
    (v.len() == DECLIP_NEIGHBOURS).then_some(v)
}

/// Least-squares c0 + c1·t + c2·t² through `v` at the samples `pts`, t = sample − `origin`.
fn fit_quadratic(v: &[f64], pts: &[usize], origin: usize) -> Option<[f64; 3]> {
    let mut ata = Matrix3::<f64>::zeros();
    let mut atb = Vector3::<f64>::zeros();
    for &k in pts {
        let t = k as f64 - origin as f64;
        let row = Vector3::new(1.0, t, t * t);
        ata += row * row.transpose();
        atb += row * v[k];
    }
    let c = ata.lu().solve(&atb)?;
    c.iter().all(|x| x.is_finite()).then(|| [c[0], c[1], c[2]])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2.6 g Gaussian bump (SD 6 samples) clipped at 2 g for 9 samples: declipping restores
    /// most of the area above the range, linear interpolation none of it.
    #[test]
    fn a_clipped_bump_gets_most_of_its_area_back() {
        let truth: Vec<f64> = (0..60)
            .map(|i| 2.6 * (-((i as f64 - 30.0) / 6.0).powi(2) / 2.0).exp())
            .collect();
        let mut v: Vec<f64> = truth.iter().map(|x| x.min(2.0)).collect();
        let bad: Vec<usize> = (0..60).filter(|&i| v[i] >= 2.0).collect();
        assert!(bad.len() >= 7, "{bad:?}");
        let above = |w: &[f64]| w.iter().map(|x| x - 2.0).filter(|x| *x > 0.0).sum::<f64>();
        let lost = above(&truth);
        let mut lin = v.clone();
        crate::preprocess::interpolate_over(&mut lin, &bad);
        assert!(above(&lin) < 1e-9);
        declip(&mut v, &bad);
        // A quadratic through the shoulders of a 9-sample run: 72 % of the area back.
        let back = above(&v);
        assert!(back > 0.6 * lost && back < 1.2 * lost, "{back} of {lost}");
        // never inside the range where it clipped, and untouched elsewhere
        assert!(bad.iter().all(|&i| v[i] >= 2.0));
        assert!((0..60)
            .filter(|i| !bad.contains(i))
            .all(|i| v[i] == truth[i].min(2.0)));
    }

    #[test]
    fn clipped_axes_are_told_apart_and_runs_at_the_edges_keep_their_reading() {
        // x clips at +2 on samples 3-4, z at −2 on sample 4; sample 8 flagged with no axis at
        // the level (a reader's flag without a range).
        let x = vec![0.0, 1.0, 1.8, 2.0, 2.0, 1.7, 1.0, 0.5, 1.2, 0.2];
        let y = vec![0.1; 10];
        let z = vec![0.0, -1.0, -1.9, -1.99, -2.0, -1.5, -1.0, 0.0, 0.0, 0.0];
        let (axes, unknown) = clipped_axes(&[x, y, z], &[3, 4, 8]);
        assert_eq!(axes, [vec![3, 4], vec![], vec![4]]);
        assert_eq!(unknown, vec![8]);
        // A run at the start has no left neighbours: it keeps its clipped reading.
        let mut v = vec![2.0, 2.0, 1.5, 1.0, 0.5];
        declip(&mut v, &[0, 1]);
        assert_eq!(v, vec![2.0, 2.0, 1.5, 1.0, 0.5]);
        // A run inside: a parabola through 1, 1.75 | 1.75, 1 peaks above 2.
        let mut v = vec![1.0, 1.75, 2.0, 2.0, 1.75, 1.0];
        declip(&mut v, &[2, 3]);
        assert!(v[2] > 2.0 && (v[2] - v[3]).abs() < 1e-12, "{v:?}");
    }
}
