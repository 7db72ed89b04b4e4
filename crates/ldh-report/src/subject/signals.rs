//! Sections 3 and 4 of the per-subject page (on screen only): each leg's signals with its gait
//! events and attitude (paper Figs. 3–4), and the parameters stride by stride.

use maud::{html, Markup};

use crate::html::figure;
use crate::plots::{self, EventMarks, Panel, SeriesName};
use crate::{LegTrace, SubjectReport};
use ldh_core::error::Result;
use ldh_core::output::{Parameter, StrideRow};
use ldh_core::Side;

/// Section 3: the paper's Figs. 3–4 per leg.
pub(super) fn signals(s: &SubjectReport) -> Result<Markup> {
    let head = html! { h2 { "3. Signals" } "\n" };
    let legs = match &s.traces {
        None => {
            return Ok(
                html! { (head) p.note { "No signal traces for this subject (see above)." } "\n" },
            )
        }
        Some(t) if t.legs.is_empty() => {
            return Ok(
                html! { (head) p.note { "No leg of this subject was analysed, so there are no signals to show." } "\n" },
            )
        }
        Some(t) => &t.legs,
    };
    let mut figs: Vec<Markup> = Vec::new();
    for leg in legs {
        figs.push(leg_signals(leg)?);
        figs.push(leg_attitude(leg)?);
    }
    Ok(html! { (head) @for f in &figs { (f) } })
}

fn leg_signals(leg: &LegTrace) -> Result<Markup> {
    let secs = leg.pitch_deg.len() as f64 / leg.fs_hz;
    let mut clipped: Vec<String> = Vec::new();
    let mut named = |names: [SeriesName; 3], v: &[Vec<f64>; 3], range: f64, unit: &str| {
        let mut n = 0;
        let out: Vec<(SeriesName, Vec<f64>)> = names
            .into_iter()
            .zip(v)
            .map(|(a, v)| {
                let (v, k) = plots::clip_to(v, -range, range);
                n += k;
                (a, v)
            })
            .collect();
        if n > 0 {
            clipped.push(format!("{n} samples beyond ±{range:.0} {unit}"));
        }
        out
    };
    let acc = Panel {
        y_label: "acceleration (g)".into(),
        series: named(
            // Axes, not sides: each its own colour by its place (the y axis, pointing left,
            // was once drawn in the left leg's colour, the same blue as x).
            ["anterior (x)".into(), "left (y)".into(), "up (z)".into()],
            &leg.acc_g,
            ACC_RANGE_G,
            "g",
        ),
    };
    let gyro = Panel {
        y_label: "angular velocity (deg/s)".into(),
        series: named(
            [
                "about anterior".into(),
                "about left (sagittal)".into(),
                "about up".into(),
            ],
            &leg.gyro_dps,
            GYRO_RANGE_DPS,
            "deg/s",
        ),
    };
    let svg = plots::signals_svg(
        &format!("{} shank: preprocessed signals ({secs:.0} s)", leg.side),
        leg.start_s,
        leg.fs_hz,
        &[acc, gyro],
        None,
    )?;
    Ok(figure(
        &svg,
        &format!("{} leg: filtered acceleration and angular velocity in the shank frame (after alignment and outlier replacement).{}", leg.side, clip_note(&clipped)),
        &["time (s)", "acceleration (g)", "angular velocity (deg/s)"],
        plots::SIGNALS_PRINT,
    ))
}

fn leg_attitude(leg: &LegTrace) -> Result<Markup> {
    let marks = EventMarks {
        hs_s: leg.hs_s.clone(),
        to_s: leg.to_s.clone(),
        stance_s: leg.stance_s.clone(),
    };
    let (lo, hi) = crate::cycle::SHANK_ANGLE_RANGE_DEG;
    let (pitch, a) = plots::clip_to(&leg.pitch_deg, lo, hi);
    let (roll, b) = plots::clip_to(&leg.roll_deg, lo, hi);
    let clipped: Vec<String> = (a + b > 0)
        .then(|| {
            format!(
                "{} samples beyond ±{hi:.0}° (a shank angle's physical range)",
                a + b
            )
        })
        .into_iter()
        .collect();
    let att = Panel {
        y_label: "angle (deg)".into(),
        series: vec![("pitch (sagittal)".into(), pitch), ("roll".into(), roll)],
    };
    let svg = plots::signals_svg(
        &format!("{} shank: attitude with gait events", leg.side),
        leg.start_s,
        leg.fs_hz,
        &[att],
        Some(&marks),
    )?;
    Ok(figure(
        &svg,
        &format!("{} leg: shank attitude; red lines heel strikes (HS), blue lines toe offs (TO), grey bands stance (HS to TO).{}", leg.side, clip_note(&clipped)),
        &["time (s)", "angle (deg)"],
        plots::SIGNALS_PRINT,
    ))
}

/// Physical range of the plotted acceleration, g (± the range of common shank IMUs).
const ACC_RANGE_G: f64 = 16.0;
/// Physical range of the plotted angular rate, deg/s (± the range of common shank IMUs).
const GYRO_RANGE_DPS: f64 = 2000.0;

/// " Clipped: …, drawn at the edge of the range." when something was clipped, else nothing.
fn clip_note(clipped: &[String]) -> String {
    if clipped.is_empty() {
        String::new()
    } else {
        format!(
            " Clipped: {} are drawn at the edge of the physical range.",
            clipped.join("; ")
        )
    }
}

/// A per-stride quantity: title, y label with unit, the parameter (its per-stride value,
/// [`StrideRow::value`]), physical range (values beyond are drawn at its edge and captioned).
type PerStride = (&'static str, &'static str, Parameter, (f64, f64));

const PER_STRIDE: [PerStride; 4] = [
    (
        "stride time",
        "stride time (s)",
        Parameter::StrideTime,
        (0.0, 4.0),
    ),
    (
        "stance phase",
        "stance ratio (fraction of stride)",
        Parameter::StanceRatio,
        (0.0, 1.0),
    ),
    (
        "stride length",
        "stride length (m)",
        Parameter::StrideLength,
        (0.0, 3.0),
    ),
    (
        "shank swing angle (WQK)",
        "WQK (deg)",
        Parameter::Wqk,
        (-180.0, 180.0),
    ),
];

/// Section 4: parameters stride by stride, left and right.
pub(super) fn stride_by_stride(strides: &[StrideRow]) -> Result<Markup> {
    if strides.is_empty() {
        return Ok(html! {
            h2 { "4. Stride by stride" } "\n"
            p.note { "No strides were detected." } "\n"
        });
    }
    let mut figs: Vec<Markup> = Vec::new();
    for (title, ylab, p, (lo, hi)) in PER_STRIDE {
        let mut clipped = 0usize;
        let series: Vec<crate::plots::Series> = [Side::Left, Side::Right]
            .into_iter()
            .map(|side| {
                (
                    SeriesName::of_side(side, side.to_string()),
                    strides
                        .iter()
                        .filter(|r| r.side == side)
                        .filter_map(|r| Some((r.hs_time_s?, r.value(p)?, r.valid)))
                        .filter(|p| p.1.is_finite())
                        .map(|(t, v, ok)| {
                            clipped += usize::from(!(lo..=hi).contains(&v));
                            (t, v.clamp(lo, hi), ok)
                        })
                        .collect(),
                )
            })
            .collect();
        if series.iter().all(|x| x.1.is_empty()) {
            continue;
        }
        let svg = plots::stride_series_svg(title, ylab, &series)?;
        figs.push(figure(
            &svg,
            &format!(
                "{title} per stride; filled circles strides used, hollow circles strides excluded; left blue, right orange.{}",
                clip_note(&if clipped > 0 {
                    vec![format!("{clipped} stride(s) outside {lo}–{hi}")]
                } else {
                    vec![]
                })
            ),
            &["heel-strike time (s)", ylab],
            plots::STRIDE_SERIES_PRINT,
        ));
    }
    Ok(html! { h2 { "4. Stride by stride" } "\n" @for f in &figs { (f) } })
}
