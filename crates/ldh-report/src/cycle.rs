//! Gait-cycle-normalised curves (the plot every clinical gait report has): each valid stride's
//! shank pitch from its heel strike to the next heel strike of the same leg, resampled by linear
//! interpolation onto 0–100 % of the cycle, then mean ± SD across strides per leg (time
//! normalisation as in Winter, *Biomechanics and Motor Control of Human Movement*, 4th ed.,
//! Wiley 2009, ch. 1). The reference band is the mean ± SD over the per-leg mean curves of the
//! cohort's healthy legs that pass every quality check (the same legs as the parameters'
//! reference, [`super::reference`]), drawn only when there are at least
//! [`super::ReportParams::min_healthy_subjects`] of them; otherwise the caption says
//! "no reference band (n = …)".
//!
//! The strides come from the plotted trace window ([`super::LegTrace`], 10 s by default), so a
//! curve pools the valid strides that window holds, and says how many. A leg whose shank angles
//! were withheld by a quality check gets no curve: the reason is written in place of it.

use maud::{html, Markup};
use serde::{Deserialize, Serialize};

use super::html::figure;
use super::measured::not_measured;
use super::{LegTrace, Reference, SubjectReport, ValidReportParams};
use crate::plots;
use ldh_core::error::Result;
use ldh_core::output::{RecordingRow, StrideRow};

/// Points of a normalised cycle: 0, 1, …, 100 % of the cycle.
pub const CYCLE_POINTS: usize = 101;

/// Physical range of a shank angle, deg: values beyond are drawn at the edge and captioned.
pub const SHANK_ANGLE_RANGE_DEG: (f64, f64) = (-90.0, 90.0);

/// Resample `signal` (sampled at `fs_hz`, first sample at `t0_s`) over `[a_s, b_s]` onto `points`
/// equally spaced instants (linear interpolation between samples). `None` when the interval is
/// not inside the signal, is empty, or touches a non-finite sample, or `points < 2`.
pub fn time_normalise(
    signal: &[f64],
    t0_s: f64,
    fs_hz: f64,
    a_s: f64,
    b_s: f64,
    points: usize,
) -> Option<Vec<f64>> {
    if points < 2 || !(fs_hz > 0.0) || signal.len() < 2 || !(b_s > a_s) {
        return None;
    }
    let (ia, ib) = ((a_s - t0_s) * fs_hz, (b_s - t0_s) * fs_hz);
    let last = (signal.len() - 1) as f64;
    if !(ia >= -1e-9 && ib <= last + 1e-9) {
        return None;
    }
    (0..points)
        .map(|k| {
            let x = (ia + (ib - ia) * k as f64 / (points - 1) as f64).clamp(0.0, last);
            let i = (x.floor() as usize).min(signal.len() - 2);
            let f = x - i as f64;
            let v = signal[i] * (1.0 - f) + signal[i + 1] * f;
            v.is_finite().then_some(v)
        })
        .collect()
}

/// Mean ± SD of curves over the gait cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CycleCurve {
    /// Mean at 0, 1, …, 100 % of the cycle, deg.
    pub mean_deg: Vec<f64>,
    /// Sample SD (n − 1) at the same points, deg.
    pub sd_deg: Vec<f64>,
    /// Curves pooled (strides of one leg, or legs of a reference).
    pub n: usize,
}

impl CycleCurve {
    /// Mean ± SD of equally long curves; `None` with fewer than 2 (an SD needs two).
    pub fn of(curves: &[Vec<f64>]) -> Option<CycleCurve> {
        let n = curves.len();
        let len = curves.first()?.len();
        if n < 2 || curves.iter().any(|c| c.len() != len) {
            return None;
        }
        let mean: Vec<f64> = (0..len)
            .map(|k| curves.iter().map(|c| c[k]).sum::<f64>() / n as f64)
            .collect();
        let sd = (0..len)
            .map(|k| {
                let ss: f64 = curves.iter().map(|c| (c[k] - mean[k]).powi(2)).sum();
                (ss / (n - 1) as f64).sqrt()
            })
            .collect();
        Some(CycleCurve {
            mean_deg: mean,
            sd_deg: sd,
            n,
        })
    }
}

/// The shank-pitch cycle of a leg: the valid strides of `strides` (this leg's side) whose heel
/// strike and next heel strike both lie in the trace window. `None` with fewer than 2 strides.
pub fn pitch_cycle(leg: &LegTrace, strides: &[StrideRow]) -> Option<CycleCurve> {
    let curves: Vec<Vec<f64>> = strides
        .iter()
        .filter(|s| s.valid && s.side.as_str() == leg.side)
        .filter_map(|s| {
            time_normalise(
                &leg.pitch_deg,
                leg.start_s,
                leg.fs_hz,
                s.hs_time_s?,
                s.next_hs_time_s?,
                CYCLE_POINTS,
            )
        })
        .collect();
    CycleCurve::of(&curves)
}

/// The healthy reference band of the shank-pitch cycle.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CycleReference {
    /// Mean ± SD over the legs' mean curves, when there were enough legs.
    pub band: Option<CycleCurve>,
    /// Healthy legs passing every check that had a curve.
    pub n_legs: usize,
}

impl CycleReference {
    /// From the per-leg mean curves of the reference legs; a band with at least `min_legs`.
    pub fn from_legs(legs: &[CycleCurve], min_legs: usize) -> CycleReference {
        let means: Vec<Vec<f64>> = legs.iter().map(|c| c.mean_deg.clone()).collect();
        CycleReference {
            band: (legs.len() >= min_legs)
                .then(|| CycleCurve::of(&means))
                .flatten(),
            n_legs: legs.len(),
        }
    }
}

/// Why a leg has no curve because of its row: failed, or its shank angles withheld.
fn no_angles(row: Option<&&RecordingRow>) -> Option<String> {
    let r = row?;
    let wqk = ldh_core::output::Parameter::Wqk;
    not_measured(r, wqk)
        .filter(|_| !r.is_ok() || r.withheld.reason(wqk).is_some())
        .map(|why| format!("shank angles not measured: {why}"))
}

/// The section: one figure with both legs over the reference band, and, for a leg without a
/// curve, the reason in place of it.
pub(crate) fn cycle_section(
    s: &SubjectReport,
    sides: &[&RecordingRow],
    reference: &Reference,
    p: &ValidReportParams,
) -> Result<Markup> {
    let head = html! { h2 { "Gait cycle: shank pitch" } "\n" };
    let Some(t) = &s.traces else {
        return Ok(
            html! { (head) p.note { "No gait-cycle curves: this report has no signal traces (see above)." } "\n" },
        );
    };
    let mut series: Vec<plots::CycleSeries> = Vec::new();
    let mut reasons: Vec<String> = Vec::new();
    let mut clipped = 0usize;
    for side in [ldh_core::Side::Left, ldh_core::Side::Right] {
        let leg = t.legs.iter().find(|l| l.side == side.as_str());
        let row = sides.iter().find(|r| r.side == side);
        let why = match (no_angles(row), leg) {
            (Some(why), _) => Some(why),
            (None, None) => Some("no signal trace for this leg".into()),
            (None, Some(leg)) => match pitch_cycle(leg, &s.strides) {
                None => Some("fewer than two valid strides in the plotted window".into()),
                Some(c) => {
                    let (lo, hi) = SHANK_ANGLE_RANGE_DEG;
                    let (m, k) = plots::clip_to(&c.mean_deg, lo, hi);
                    clipped += k;
                    series.push((format!("{side} (n = {} strides)", c.n), m, c.sd_deg));
                    None
                }
            },
        };
        if let Some(why) = why {
            reasons.push(format!("{side} leg: no gait-cycle curve — {why}."));
        }
    }
    let cr = &reference.cycle;
    let band = cr.band.as_ref().map(|b| {
        (
            format!("healthy reference (n = {} legs): mean ± SD", b.n),
            b.mean_deg.clone(),
            b.sd_deg.clone(),
        )
    });
    let band_text = match &cr.band {
        Some(b) => format!("Grey band: mean ± 1 SD of the mean curves of {} healthy legs of this cohort that pass every quality check.", b.n),
        None => format!(
            "No reference band (n = {} healthy legs passing every check; {} needed).",
            cr.n_legs, p.0.min_healthy_subjects
        ),
    };
    let fig = if series.is_empty() {
        html! {}
    } else {
        let svg = plots::cycle_svg(
            &format!("Subject {}: shank pitch over the gait cycle", s.subject_id),
            "shank pitch (deg)",
            &series,
            band.as_ref(),
        )?;
        let clip = if clipped > 0 {
            format!(" Clipped: {clipped} point(s) of a mean curve beyond the physical range of a shank angle (±90°) are drawn at its edge.")
        } else {
            String::new()
        };
        figure(
            &svg,
            &format!("Shank pitch (sagittal inclination) from heel strike (0 %) to the next heel strike (100 %) of the same leg: mean (line) ± 1 SD (band) over the valid strides of the plotted window; left blue, right orange. {band_text}{clip}"),
            &[plots::CYCLE_X_LABEL, "shank pitch (deg)"],
            plots::CYCLE_PRINT,
        )
    };
    Ok(html! {
        (head)
        @for r in &reasons { p.note { (r) } "\n" }
        (fig)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strides_are_normalised_to_the_cycle() {
        // A ramp sampled at 10 Hz from t = 1 s: value = t.
        let sig: Vec<f64> = (0..50).map(|i| 1.0 + i as f64 / 10.0).collect();
        let c = time_normalise(&sig, 1.0, 10.0, 2.0, 3.0, 11).unwrap();
        for (k, v) in c.iter().enumerate() {
            assert!((v - (2.0 + k as f64 / 10.0)).abs() < 1e-12);
        }
        // Between samples: linear interpolation.
        let c = time_normalise(&sig, 1.0, 10.0, 2.05, 2.15, 3).unwrap();
        assert!((c[1] - 2.1).abs() < 1e-12);
        assert!(time_normalise(&sig, 1.0, 10.0, 0.5, 2.0, 11).is_none());
        assert!(time_normalise(&sig, 1.0, 10.0, 3.0, 2.0, 11).is_none());
        let curve = CycleCurve::of(&[vec![1.0, 2.0], vec![3.0, 2.0]]).unwrap();
        assert_eq!(curve.mean_deg, vec![2.0, 2.0]);
        assert!((curve.sd_deg[0] - 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(curve.sd_deg[1], 0.0);
        assert!(CycleCurve::of(&[vec![1.0]]).is_none());
        let r = CycleReference::from_legs(&[curve.clone(), curve.clone()], 3);
        assert_eq!((r.band.is_none(), r.n_legs), (true, 2));
        let r = CycleReference::from_legs(&[curve.clone(), curve], 2);
        assert_eq!(r.band.unwrap().n, 2);
    }
}
