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
//! The strides are every valid stride of the leg, those of the walk's steady window (the trace
//! file's curve, [`ldh_core::output::cycle::pitch_cycle_of`]; issue 50: a curve of the 5
//! strides of the plotted excerpt said little of 98), and the legend says how many. A leg
//! whose shank angles were withheld by a quality check gets no curve: the reason is written in
//! place of it.

use maud::{html, Markup};
use serde::{Deserialize, Serialize};

use super::html::figure;
use super::measured::not_measured;
use super::{LegTrace, Reference, SubjectReport, ValidReportParams};
use crate::plots;
use ldh_core::error::Result;
use ldh_core::output::{RecordingRow, StrideRow};

pub use ldh_core::output::cycle::{time_normalise, CycleCurve, CYCLE_POINTS};

/// Physical range of a shank angle, deg: values beyond are drawn at the edge and captioned.
pub const SHANK_ANGLE_RANGE_DEG: (f64, f64) = (-90.0, 90.0);

/// The shank-pitch cycle of a leg: the trace's own curve over every valid stride of the leg
/// (those of the walk's steady window, [`LegTrace::cycle`]); for a trace written before it
/// carried one, the valid strides of `strides` (this leg's side) whose heel strike and next
/// heel strike both lie in the trace window. `None` with fewer than 2 strides.
pub fn pitch_cycle(leg: &LegTrace, strides: &[StrideRow]) -> Option<CycleCurve> {
    if let Some(c) = &leg.cycle {
        return Some(c.clone());
    }
    let curves: Vec<Vec<f64>> = strides
        .iter()
        .filter(|s| s.valid && s.side == leg.side)
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
        let leg = t.legs.iter().find(|l| l.side == side);
        let row = sides.iter().find(|r| r.side == side);
        let why = match (no_angles(row), leg) {
            (Some(why), _) => Some(why),
            (None, None) => Some("no signal trace for this leg".into()),
            (None, Some(leg)) => match pitch_cycle(leg, &s.strides) {
                None => Some("fewer than two valid strides".into()),
                Some(c) => {
                    let (lo, hi) = SHANK_ANGLE_RANGE_DEG;
                    let (m, k) = plots::clip_to(&c.mean_deg, lo, hi);
                    clipped += k;
                    series.push((
                        plots::SeriesName::of_side(side, format!("{side} (n = {} strides)", c.n)),
                        m,
                        c.sd_deg,
                    ));
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
            format!("healthy reference (n = {} legs): mean ± SD", b.n).into(),
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
            &format!("Shank pitch (sagittal inclination) from heel strike (0 %) to the next heel strike (100 %) of the same leg: mean (line) ± 1 SD (band) over the leg's valid strides{}, those of the steady window (n in the legend); left blue, right orange. {band_text}{clip}", of_trial(&s.recordings)),
            &[plots::CYCLE_X_LABEL, "shank pitch (deg)"],
            plots::CYCLE_PRINT,
        )
    };
    Ok(html! {
        (head)
        @for r in &reasons { p.note { (r) } "\n" }
        div.beside { (fig) } "\n"
    })
}

/// " of trial PWS (the first of 3 trials; the tables are of all)" when the page has several
/// trials (the figures draw the first one's strides), else "" (issue 50: "n = 88 strides" read
/// as the person's, of 3 trials).
pub(crate) fn of_trial(recordings: &[RecordingRow]) -> String {
    let Some(t) = crate::results::first_trial(recordings).1 else {
        return String::new();
    };
    let mut ids: Vec<&str> = recordings.iter().map(|r| r.trial_id.as_str()).collect();
    ids.sort_unstable();
    ids.dedup();
    format!(
        " of trial {t} (the first of {} trials; the tables are of all)",
        ids.len()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gait-cycle figure of a page of three trials says whose strides it averages.
    #[test]
    fn the_cycle_caption_names_its_trial_of_several() {
        let mut recs = Vec::new();
        for t in ["PWS", "PWS+20", "PWS-20"] {
            for side in ["left", "right"] {
                let mut r = crate::tests::row("FZ", "healthy", side, 1.0);
                r.trial_id = t.into();
                recs.push(r);
            }
        }
        assert_eq!(
            of_trial(&recs),
            " of trial PWS (the first of 3 trials; the tables are of all)"
        );
        assert_eq!(of_trial(&recs[..2]), "");
    }

    #[test]
    fn the_reference_band_needs_enough_legs() {
        let curve = CycleCurve::of(&[vec![1.0, 2.0], vec![3.0, 2.0]]).unwrap();
        let r = CycleReference::from_legs(&[curve.clone(), curve.clone()], 3);
        assert_eq!((r.band.is_none(), r.n_legs), (true, 2));
        let r = CycleReference::from_legs(&[curve.clone(), curve], 2);
        assert_eq!(r.band.unwrap().n, 2);
    }

    #[test]
    fn the_curve_is_the_traces_own_over_every_valid_stride() {
        // Issue 50: a trace's curve over the walk's 98 steady strides, not the excerpt's 5.
        let curve = CycleCurve {
            mean_deg: vec![0.0; CYCLE_POINTS],
            sd_deg: vec![1.0; CYCLE_POINTS],
            n: 98,
        };
        let leg = LegTrace {
            side: ldh_core::Side::Left,
            fs_hz: 100.0,
            start_s: 0.0,
            acc_g: Default::default(),
            gyro_dps: Default::default(),
            roll_deg: vec![],
            pitch_deg: vec![],
            hs_s: vec![],
            to_s: vec![],
            stance_s: vec![],
            read_notes: vec![],
            alignment_notes: vec![],
            gaps_s: vec![],
            cycle: Some(curve),
        };
        assert_eq!(pitch_cycle(&leg, &[]).unwrap().n, 98);
        // A trace without one (written before) pools the excerpt's strides: none here.
        let old = LegTrace { cycle: None, ..leg };
        assert!(pitch_cycle(&old, &[]).is_none());
    }
}
