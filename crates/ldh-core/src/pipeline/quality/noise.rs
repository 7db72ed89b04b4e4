//! Stride length variability (SV) against the measurement's own noise, estimated from the two
//! legs of one walk.
//!
//! SV is the coefficient of variation of a leg's stride lengths; what it measures is the gait's
//! variability plus the per-stride error of the length measurement, added in quadrature:
//! SV² = T² + σ². On real recordings σ is not known, but the two legs give it: over a walk a
//! stride of leg A spans the second half of one stride of leg B and the first half of the next,
//! so its length equals the mean of those two up to the gait's step-to-step variation. The
//! relative residuals e_A = L_A / ((L_B,k + L_B,k+1)/2) − 1 have variance
//! v_A = σ_A² + σ_B²/2 + g (independent per-stride errors; g ≥ 0 the gait's share), and
//! likewise v_B. With the same noise on both legs, σ² ≤ v/1.5 in either direction; the
//! smaller of the two bounds is taken, σ² = min(v_A, v_B)/1.5: a noise both comparisons
//! show (one direction alone can be large for other reasons: family A's truth makes each left
//! stride the exact mean of the right ones around it, but not the reverse). The decision is the
//! walk's: where σ accounts for more than [`SV_MAX_INFLATION`] of the legs' root-mean-square SV
//! (SV − √(SV² − σ²)), both legs' SV is withheld — a clinician reading it would read the
//! sensor, not the gait (one leg's alone cannot be told apart on a short walk: the estimate's
//! own error is ≈ 30 % at 10 pairs). A leg whose SV no other leg can check (the other leg not
//! analysed, or without an SV) has it withheld (`sv_unchecked`), and so do both legs of a walk
//! too short for the check ([`SV_MIN_PAIRS`]): on the real walks that could be checked the
//! noise dominated every SV. docs/quality.md `sv_noise`; docs/accuracy.md "Stride
//! length variability against its noise" has the numbers (families A and B against the truth,
//! and HuGaDB).

use super::warning::{codes, Severity, Warning};
use super::LegResult;
use crate::domain::Parameter;

/// Most the per-stride length error may add to SV, as a CV (0.01 = one percentage point): the
/// normal range is 0–5 % (Hausdorff 2005) and healthy walkers sit at 1.5–3 %, so an SV more than
/// a point above the gait's own would move a walker across it. A resolution, not fitted.
pub const SV_MAX_INFLATION: f64 = 0.01;

/// Fewest paired strides in each direction (5) for the check to run: a residual variance from
/// n pairs has a relative standard error of √(2/(n − 1)), 71 % at 5, so the check then still
/// catches a gross noise (HuGaDB's 3–5 % a stride) but decides near its threshold by chance.
/// With fewer (a walk under ≈ 25 s, or one with many strides left out) SV is withheld
/// (`sv_unchecked`; reported unchecked until 2026-11-26). A resolution, not fitted (8 until
/// 2026-11-26, which left every 25 s demo walk unchecked).
pub const SV_MIN_PAIRS: usize = 5;

/// A leg's reported strides: (start, end) on the left leg's clock and the length, m.
fn reported(leg: &LegResult, shift_s: f64) -> Vec<(f64, f64, f64)> {
    leg.strides
        .iter()
        .filter(|s| s.valid && s.stride_length_m.is_finite())
        .map(|s| {
            (
                s.hs_time_s + shift_s,
                s.next_hs_time_s + shift_s,
                s.stride_length_m,
            )
        })
        .collect()
}

/// Relative residuals of the strides of `a` against the mean of the two contiguous strides of
/// `b` that bracket them (the one starting inside the `a` stride and the one before it), each
/// direction's mean removed (a constant left–right bias is not noise).
fn residuals(a: &[(f64, f64, f64)], b: &[(f64, f64, f64)], out: &mut Vec<f64>) {
    let mut e = Vec::new();
    // both in time order: one sweep (linear in the strides, issue 19)
    let mut k = 0;
    for &(t0, t1, len) in a {
        while k < b.len() && b[k].0 <= t0 {
            k += 1;
        }
        // exactly one stride of `b` starts inside (t0, t1), and the one before it is contiguous
        let one = k < b.len() && b[k].0 < t1 && b.get(k + 1).is_none_or(|n| n.0 >= t1);
        if !one || k == 0 {
            continue;
        }
        let (b0, b1) = (b[k - 1], b[k]);
        if (b0.1 - b1.0).abs() < 1e-6 {
            e.push(len / (0.5 * (b0.2 + b1.2)) - 1.0);
        }
    }
    let m = e.iter().sum::<f64>() / e.len().max(1) as f64;
    out.extend(e.iter().map(|x| x - m));
}

/// Residual variances of the two directions, (v_left, n_left) and (v_right, n_right): each
/// Σe²/(n − 1) of the mean-removed residuals, NaN below two residuals.
fn residual_stats(l: &LegResult, r: &LegResult) -> [(f64, usize); 2] {
    let (a, b) = (reported(l, 0.0), reported(r, r.t0_s - l.t0_s));
    let var = |x: &[(f64, f64, f64)], y: &[(f64, f64, f64)]| {
        let mut e = Vec::new();
        residuals(x, y, &mut e);
        let n = e.len();
        let v = if n < 2 {
            f64::NAN
        } else {
            e.iter().map(|v| v * v).sum::<f64>() / (n - 1) as f64
        };
        (v, n)
    };
    [var(&a, &b), var(&b, &a)]
}

/// The per-stride noise variance both legs' comparisons show: min(v_left, v_right)/1.5.
pub fn walk_noise(v: [f64; 2]) -> f64 {
    v[0].min(v[1]) / 1.5
}

/// The noise's share of an SV `sv` given the noise variance `sigma2`: SV − √(SV² − σ²).
pub fn noise_share(sv: f64, sigma2: f64) -> f64 {
    sv - (sv * sv - sigma2).max(0.0).sqrt()
}

/// The warning that withholds both legs' SV (`sv`: left, right) when the walk's noise variance
/// `sigma2` (from [`walk_noise`]; `n` residuals) accounts for more than [`SV_MAX_INFLATION`] of
/// their root-mean-square; `None` otherwise.
pub fn variability_warning(sv: [f64; 2], sigma2: f64, n: usize) -> Option<Warning> {
    let rms = ((sv[0] * sv[0] + sv[1] * sv[1]) / 2.0).sqrt();
    let share = noise_share(rms, sigma2);
    (rms.is_finite() && share > SV_MAX_INFLATION).then(|| {
        Warning::new(codes::SV_NOISE, Severity::Warning, format!(
            "stride length variability (left {:.1} %, right {:.1} %) not measured: compared stride by stride ({n} pairs), the two legs' lengths show a measurement noise of ≈ {:.1} % per stride, which accounts for {:.1} points of the walk's {:.1} %",
            100.0 * sv[0],
            100.0 * sv[1],
            100.0 * sigma2.sqrt(),
            100.0 * share,
            100.0 * rms
        ))
        .withholding(&[crate::domain::Parameter::StrideLengthCv])
    })
}

/// Withhold both legs' SV when the walk's measurement noise inflates it (the warning goes to
/// each leg), and a leg's SV that no other leg can check ([`unchecked_warning`]): the other leg
/// not analysed (`None`) or without an SV. With fewer than [`SV_MIN_PAIRS`] strides paired in
/// a direction (a short walk) both legs' SV is withheld as unchecked.
pub fn check_length_variability(l: Option<&mut LegResult>, r: Option<&mut LegResult>) {
    let (l, r) = match (l, r) {
        (Some(l), Some(r)) => (l, r),
        (Some(leg), None) | (None, Some(leg)) => {
            let other = leg.side.other();
            withhold_unchecked(leg, &format!("the {other} leg was not analysed"));
            return;
        }
        (None, None) => return,
    };
    let sv = [
        l.parameters[Parameter::StrideLengthCv],
        r.parameters[Parameter::StrideLengthCv],
    ];
    match sv.map(f64::is_finite) {
        [true, true] => {}
        [true, false] => {
            return withhold_unchecked(l, "the right leg reports no stride length variability")
        }
        [false, true] => {
            return withhold_unchecked(r, "the left leg reports no stride length variability")
        }
        [false, false] => return,
    }
    let [(vl, nl), (vr, nr)] = residual_stats(l, r);
    if nl.min(nr) == 0 {
        // no comparison at all (recordings that do not overlap, strides all lost to turns)
        let why = "no stride of one leg pairs up with two of the other (the walks do not overlap in time, or no stretch of both legs' strides is vouched for)";
        for leg in [l, r] {
            withhold_unchecked(leg, why);
        }
        return;
    }
    let pairs = nl.min(nr);
    if pairs < SV_MIN_PAIRS {
        // a short walk: too few pairs to estimate the noise
        let s = if pairs == 1 { "" } else { "s" };
        let why = format!(
            "only {pairs} stride{s} of one leg pair up with the other leg's ({SV_MIN_PAIRS} needed each way): the walk is too short (record ≥ 30 s of walking), or too many of its strides were left out"
        );
        for leg in [l, r] {
            let sv = leg.parameters[Parameter::StrideLengthCv];
            if sv.is_finite() {
                let w = unchecked(sv, "too few strides to check it against its noise", &why);
                super::withhold(&mut leg.parameters, std::slice::from_ref(&w));
                leg.warnings.push(w);
            }
        }
        return;
    }
    if let Some(w) = variability_warning(sv, walk_noise([vl, vr]), nl + nr) {
        for leg in [l, r] {
            super::withhold(&mut leg.parameters, std::slice::from_ref(&w));
            leg.warnings.push(w.clone());
        }
    }
}

/// The warning that withholds a leg's SV `sv` whose noise cannot be checked, `why` saying
/// what is missing. The two-leg comparison is the only check of SV against the length
/// measurement's noise, and on real walks it found that noise to dominate (HuGaDB: every
/// checked leg), so an unchecked SV is not reported.
/// The reason a page shows names what is missing ("not checked against its noise, as the left
/// leg reports no stride length variability"): "not checked against its noise" alone left a
/// clinician asking why.
pub fn unchecked_warning(sv: f64, why: &str) -> Warning {
    unchecked(
        sv,
        &format!("not checked against its noise, as {why}"),
        "its noise is checked against the other leg's strides",
    )
}

/// The `sv_unchecked` warning: `cause` first (a report's reason for the empty cell), then
/// `why` in full.
fn unchecked(sv: f64, cause: &str, why: &str) -> Warning {
    Warning::new(
        codes::SV_UNCHECKED,
        Severity::Warning,
        format!(
            "{cause}: stride length variability ({:.1} %) not measured, as {why}",
            100.0 * sv
        ),
    )
    .withholding(&[crate::domain::Parameter::StrideLengthCv])
}

/// Withhold `leg`'s SV, if it has one, with [`unchecked_warning`] (`why`: what is missing, e.g.
/// "no other leg was given").
pub fn withhold_unchecked(leg: &mut LegResult, why: &str) {
    let sv = leg.parameters[Parameter::StrideLengthCv];
    if sv.is_finite() {
        let w = unchecked_warning(sv, why);
        super::withhold(&mut leg.parameters, std::slice::from_ref(&w));
        leg.warnings.push(w);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lengths built from steps with per-stride errors: the noise is recovered from the two
    /// legs, the rule withholds a noisy walk's SV and keeps an exact one's, and a residual that
    /// only one direction shows is not taken for noise.
    #[test]
    fn the_walks_noise_from_the_two_legs_and_the_rule() {
        let mut rng = 12345u64;
        let mut unif = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut gauss = || {
            let (u, v) = (unif().max(1e-12), unif());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        };
        // Steps alternate legs; step i lands at t = 0.5 i s; stride k of a leg spans the two
        // steps after its heel strike j (left: even j, right: odd j).
        let n = 800;
        let steps: Vec<f64> = (0..n).map(|_| 0.7 + 0.014 * gauss()).collect();
        let noise: Vec<f64> = (0..n).map(|_| gauss()).collect();
        let strides = |first: usize, err: f64| -> Vec<(f64, f64, f64)> {
            (first..n - 4)
                .step_by(2)
                .map(|j| {
                    let len = steps[j + 1] + steps[j + 2];
                    (
                        0.5 * j as f64,
                        0.5 * (j + 2) as f64,
                        len * (1.0 + err * noise[j]),
                    )
                })
                .collect()
        };
        let cv = |v: &[(f64, f64, f64)]| {
            let m = v.iter().map(|x| x.2).sum::<f64>() / v.len() as f64;
            (v.iter().map(|x| (x.2 - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt() / m
        };
        let var = |x: &[(f64, f64, f64)], y: &[(f64, f64, f64)]| {
            let mut e = Vec::new();
            residuals(x, y, &mut e);
            (
                e.iter().map(|v| v * v).sum::<f64>() / (e.len() - 1) as f64,
                e.len(),
            )
        };
        // the gait's SV: √2·0.014/1.4 = 1.41 %; left leg 0.3 % error per stride, right 3 %
        let (l, r) = (strides(0, 0.003), strides(1, 0.03));
        let truth = cv(&strides(0, 0.0));
        let ((vl, nl), (vr, nr)) = (var(&l, &r), var(&r, &l));
        assert!(nl > 380 && nr > 380, "{nl} {nr}");
        let sv = [cv(&l), cv(&r)];
        let s2 = walk_noise([vl, vr]);
        // the smaller direction (the left leg's strides against the noisy right ones) holds
        // σ_left² + σ_right²/2 + g: its bound on a common σ sees the right leg's 3 % at ≈ 1/√3
        // (1.7 %, plus the gait's share)
        assert!(s2.sqrt() > 0.015 && s2.sqrt() < 0.022, "{}", s2.sqrt());
        assert!(nl + nr > 700 && sv[1] > sv[0]);
        // 3 % on both legs: σ recovered within 15 %, and both SVs withheld
        let (l3, r3) = (strides(0, 0.03), strides(1, 0.03));
        let ((v3l, n3), (v3r, _)) = (var(&l3, &r3), var(&r3, &l3));
        let s3 = walk_noise([v3l, v3r]);
        assert!((s3.sqrt() - 0.03).abs() < 0.0045, "{}", s3.sqrt());
        let w = variability_warning([cv(&l3), cv(&r3)], s3, n3).unwrap();
        assert_eq!(w.affects, [crate::domain::Parameter::StrideLengthCv]);
        assert!(w.message.contains("not measured"), "{}", w.message);
        // no noise anywhere: nothing withheld (the gait's own share alone stays below the rule)
        let (l0, r0) = (strides(0, 0.0), strides(1, 0.0));
        let s0 = walk_noise([var(&l0, &r0).0, var(&r0, &l0).0]);
        assert!(
            variability_warning([cv(&l0), cv(&r0)], s0, 2).is_none(),
            "{s0}"
        );
        assert!(noise_share(truth, s0) < 0.005, "{}", noise_share(truth, s0));
        // one direction alone large (family A's truth: left strides the exact means of the
        // right ones, not the reverse): not noise
        assert!(walk_noise([0.0, 4e-4]) == 0.0);
        assert!(variability_warning([0.02, 0.03], walk_noise([0.0, 4e-4]), 20).is_none());
        // no SV, no warning
        assert!(variability_warning([f64::NAN, 0.02], 1e-3, 10).is_none());
    }
}
