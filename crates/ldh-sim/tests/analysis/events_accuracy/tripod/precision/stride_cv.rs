//! An honest reference for TRIPOD's stride-time CV (issue 49's "within 0.3 points of
//! OptoGait's"; docs/accuracy.md "Stride-time CV against a reference corrected for its own
//! noise").
//!
//! Every system times footfall k as τ_k = t_k + e_k (plus a constant), so its stride time is
//! S_k + ε_k with ε_k = e_(k+1) − e_k. Two adjacent strides share one footfall error with opposite
//! signs, so Var(ε) = 2σ²(1 − ρ₁) (σ the footfall scatter, ρ₁ its lag-1 autocorrelation), not
//! simply 2σ²; and the mean of the ε telescopes to (e_n − e_0)/n, so the sample variance of the
//! measured strides estimates Var(S) + Var(ε) with no further term. Var(ε) is therefore measured
//! on the stride times themselves, not derived from the footfall scatter: with three systems
//! whose errors are independent of each other and of S — ldh's shank (L), OptoGait (O) and the
//! impact on the heel's own sensor (H, `LH`/`RH`, `RL` in PWS; the same onset rule as
//! `precision.rs`) — the three-cornered hat on the stride-time differences gives each one's
//! Var(ε_X) = ½[Var(S_X − S_Y) + Var(S_X − S_Z) − Var(S_Y − S_Z)], ρ₁ included. Then
//! CV_true² ≈ CV_X² − Var(ε_X)/mean², which by the same sample-moment identities is
//! [Cov(X,Y) + Cov(X,Z) − Cov(Y,Z)]/mean²; and Cov(S_X, S_Y)/mean² alone estimates CV_true² with
//! no hat at all (independent errors cancel in a covariance).
//!
//! Caveat printed with the table: the heel and the shank both feel the same landing, so their
//! errors may share a part c; the hat then gives ldh's Var(ε) too small by c and OptoGait's too
//! large by c (its corrected CV reads too low), while Cov(S_L, S_O) is untouched by c. Only the
//! strides that all three systems bound by consecutive matched footfalls are used (whole runs,
//! first 125 s, as the rest of the harness). Analysis only: ldh's outputs are unchanged.

use super::*;
use std::collections::HashMap;

/// Sample covariance (n − 1).
fn cov(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - ma) * (y - mb))
        .sum::<f64>()
        / (n - 1.0)
}

/// Stride times (s) of ldh, OptoGait and the heel sensor over the strides all three bound with
/// consecutive matched footfalls.
fn common_strides(s: &Shank) -> [Vec<f64>; 3] {
    let by_contact = |hs: &[f64]| -> HashMap<usize, usize> {
        matched(hs, &s.opto).0.iter().map(|d| (d.0, d.1)).collect()
    };
    let (l, h) = (by_contact(&s.hs), by_contact(&s.heel));
    let mut out: [Vec<f64>; 3] = Default::default();
    for k in 1..s.opto.len() {
        let (Some(&l0), Some(&l1), Some(&h0), Some(&h1)) =
            (l.get(&(k - 1)), l.get(&k), h.get(&(k - 1)), h.get(&k))
        else {
            continue;
        };
        if l1 != l0 + 1 || h1 != h0 + 1 {
            continue;
        }
        out[0].push(s.hs[l1] - s.hs[l0]);
        out[1].push(s.opto[k] - s.opto[k - 1]);
        out[2].push(s.heel[h1] - s.heel[h0]);
    }
    out
}

/// One shank's CVs (%): raw, corrected by each system's own stride-time error, and from the
/// covariance of ldh's and OptoGait's strides; the systems' own stride-time error SDs (ms).
pub(super) struct StrideCv {
    pub(super) n: usize,
    pub(super) mean_s: f64,
    /// ldh, OptoGait, heel sensor.
    pub(super) raw_pct: [f64; 3],
    pub(super) own_error_ms: [f64; 3],
    pub(super) corrected_pct: [f64; 3],
    pub(super) cov_lo_pct: f64,
    /// √2 × each system's own footfall scatter (the footfall hat), ms: what Var(ε) = 2σ² would say.
    pub(super) naive_error_ms: [f64; 3],
}

/// The CVs of one shank ([`StrideCv`]).
pub(super) fn stride_cv(s: &Shank) -> StrideCv {
    let [l, o, h] = common_strides(s);
    let mean_s = o.iter().sum::<f64>() / o.len() as f64;
    let var = |a: &[f64], b: &[f64]| {
        let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
        cov(&d, &d)
    };
    let (v_lo, v_lh, v_oh) = (var(&l, &o), var(&l, &h), var(&o, &h));
    let own = [
        0.5 * (v_lo + v_lh - v_oh),
        0.5 * (v_lo + v_oh - v_lh),
        0.5 * (v_lh + v_oh - v_lo),
    ];
    let series = [&l, &o, &h];
    let pct = |v: f64| 100.0 * v.max(0.0).sqrt() / mean_s;
    let raw_pct = series.map(|x| pct(cov(x, x)));
    let mut corrected_pct = [0.0; 3];
    for k in 0..3 {
        corrected_pct[k] = pct(cov(series[k], series[k]) - own[k]);
    }
    // The footfall hat (as precision.rs), scaled by √2.
    let f_lo = score_hs(&s.hs, &s.opto).hs.sd.powi(2);
    let f_lh = score_hs(&s.hs, &s.heel).hs.sd.powi(2);
    let f_ho = score_hs(&s.heel, &s.opto).hs.sd.powi(2);
    let foot = |a: f64, b: f64, c: f64| (2.0 * 0.5 * (a + b - c)).max(0.0).sqrt();
    StrideCv {
        n: l.len(),
        mean_s,
        raw_pct,
        own_error_ms: own.map(|v| 1e3 * v.max(0.0).sqrt()),
        corrected_pct,
        cov_lo_pct: pct(cov(&l, &o)),
        naive_error_ms: [
            foot(f_lo, f_lh, f_ho),
            foot(f_lo, f_ho, f_lh),
            foot(f_lh, f_ho, f_lo),
        ],
    }
}

/// The table of docs/accuracy.md "Stride-time CV against a reference corrected for its own
/// noise".
#[test]
fn stride_cv_against_corrected_references_on_tripod() {
    let Some(dir) = tripod_dir() else {
        println!("skipped: ../shared/realdata/tripod not found (set LDH_REALDATA)");
        return;
    };
    println!("\n| run shank | strides | mean (s) | CV ldh / OptoGait / heel (%) | own stride-time error SD, hat: ldh / OptoGait / heel (ms) | √2·footfall scatter (ms) | corrected CV ldh / OptoGait / heel (%) | √Cov(ldh, OptoGait) CV (%) | ldh − OptoGait / − heel / − corrected OptoGait / corrected ldh − corrected OptoGait (points) |");
    println!("|---|---:|---:|---|---|---|---|---:|---|");
    for s in &shanks(&dir) {
        let c = stride_cv(s);
        let [l, o, h] = c.raw_pct;
        let [lc, oc, hc] = c.corrected_pct;
        println!(
            "| {} | {} | {:.3} | {l:.2} / {o:.2} / {h:.2} | {:.1} / {:.1} / {:.1} | {:.1} / {:.1} / {:.1} | {lc:.2} / {oc:.2} / {hc:.2} | {:.2} | {:+.2} / {:+.2} / {:+.2} / {:+.2} |",
            s.name,
            c.n,
            c.mean_s,
            c.own_error_ms[0],
            c.own_error_ms[1],
            c.own_error_ms[2],
            c.naive_error_ms[0],
            c.naive_error_ms[1],
            c.naive_error_ms[2],
            c.cov_lo_pct,
            l - o,
            l - h,
            l - oc,
            lc - oc,
        );
        // Most of each run's strides are bound by three matched footfalls; OptoGait's own
        // stride-time error is real (its corrected CV is below its raw one).
        assert!(c.n >= 60, "{}: {} strides", s.name, c.n);
        assert!(c.own_error_ms[1] > 5.0 && oc < o, "{}", s.name);
    }
}
