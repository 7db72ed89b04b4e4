//! Each paired walking span through the lab pipeline — [`crate::pipeline::Analysis::pair`],
//! the one code path of `ldh analyze` (attitude, events, strides, the parameters, the quality
//! checks and their withholding, turns allowed) — and the bout it gives: its start and end
//! from the first and last heel strike of either leg, its steps (heel strikes of both legs;
//! twice one leg's when only one sensor saw the walk), and its parameters.
//!
//! A span is a walking bout when the pipeline finds at least `min_strides` strides in it
//! (both legs' strides counted, as mobgap's stride list holds both feet's; Kluge et al. 2021,
//! Micó-Amigo et al. 2023: ≥ 4 strides). The bout's cadence, speed, stride time, stride
//! length and stride-time CV are the mean of the legs' values the pipeline vouches for; the
//! step-time asymmetry is |STT_L − STT_R| / mean(STT_L, STT_R) × 100 and needs both legs.

use serde::{Deserialize, Serialize};

use super::leg::LegStream;
use super::pair::Plan;
use super::stairs::BoutKind;
use super::steps::{heel_strike_peak_g, leg_heel_strikes};
use super::store::SpanStore;
use super::stream::Sample;
use super::windows::WindowParams;
use super::MonitorParams;
use crate::domain::{Legs, Parameter};
use crate::pipeline::{Analysis, LegResult, LoadedLeg, SubjectInput};
use crate::recording::{Recording, Side};

/// One walking bout: a row of bouts.csv.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct BoutRow {
    /// Bout number within the subject's period, from 1 (in time order).
    pub bout: usize,
    /// First heel strike, s on the left sensor's clock (the right's when only it was worn).
    pub start_s: f64,
    /// Last heel strike, s.
    pub end_s: f64,
    /// `end_s − start_s`, s.
    pub duration_s: f64,
    /// Heel strikes of both legs (twice one leg's with one sensor).
    pub steps: usize,
    /// Which legs saw the bout: `both`, `left` or `right`.
    pub legs: Legs,
    /// Strides of the left leg.
    pub strides_left: usize,
    /// Strides of the right leg.
    pub strides_right: usize,
    /// Cadence, steps/min (60 × the step frequency, SF).
    pub cadence_steps_per_min: f64,
    /// Walking speed, m/s (SS).
    pub speed_mps: f64,
    /// Stride time, s (ST).
    pub stride_time_s: f64,
    /// Stride length, m (SL).
    pub stride_length_m: f64,
    /// Stride-time variability, SD / mean (STV).
    pub stride_time_cv: f64,
    /// Step-time asymmetry, % of the mean step time.
    pub step_time_asymmetry_pct: f64,
    /// Level walking or stairs (`monitor::stairs`): a stair bout counts in walking time and
    /// steps, not in the gait aggregates of daily life.
    pub kind: BoutKind,
    /// Strides (both legs) whose ankle rose or fell by at least `stairs.min_rise_m`.
    pub stair_strides: usize,
    /// Median vertical displacement of the ankle over a stride, m (+ up, − down; ≈ 0 on
    /// level ground, NaN when no stride's was measured).
    pub stride_rise_m: f64,
    /// Right − left clock at this bout, s.
    pub clock_offset_s: f64,
    /// The walk went on past the longest span held (`max_span_s`): the next bout continues it.
    pub continues: bool,
    /// Values withheld and why: `column: reason; …`.
    pub withheld: String,
}

/// A span the pipeline did not confirm as a walk (kept for the notes).
#[derive(Debug, Clone, PartialEq)]
pub struct Refused {
    /// Start of the span, s.
    pub start_s: f64,
    /// Why.
    pub reason: String,
    /// It was a run (else too few strides).
    pub run: bool,
}

/// Each moment of walking counted once: a bout that another bout already covers for at least
/// half its length (a span of one leg the pairing did not join to the other leg's span of the
/// same walk) is dropped. Bouts seen by both legs are kept first, then longer ones.
/// Returns the bouts kept, in time order, and how many were dropped.
pub fn count_once(mut rows: Vec<BoutRow>) -> (Vec<BoutRow>, usize) {
    rows.sort_by(|a, b| {
        (b.legs == Legs::Both)
            .cmp(&(a.legs == Legs::Both))
            .then(b.duration_s.total_cmp(&a.duration_s))
    });
    let mut kept: Vec<BoutRow> = Vec::with_capacity(rows.len());
    let mut dropped = 0;
    for b in rows {
        let covered: f64 = kept
            .iter()
            .map(|k| (b.end_s.min(k.end_s) - b.start_s.max(k.start_s)).max(0.0))
            .sum();
        if covered >= 0.5 * b.duration_s.max(1e-9) {
            dropped += 1;
        } else {
            kept.push(b);
        }
    }
    kept.sort_by(|a, b| a.start_s.total_cmp(&b.start_s));
    (kept, dropped)
}

fn recording(samples: &[Sample], fs: f64, t0_s: f64, side: Side, label: &str) -> LoadedLeg {
    let first = samples.first().ok_or("empty span")?.t_s;
    let last = samples.last().ok_or("empty span")?.t_s;
    let n = ((last - first) * fs).floor() as usize + 1;
    let mut acc: [Vec<f64>; 3] = Default::default();
    let mut gyro: [Vec<f64>; 3] = Default::default();
    let mut j = 0;
    // Linear interpolation onto the uniform grid of the leg's rate.
    for i in 0..n {
        let t = first + i as f64 / fs;
        while j + 2 < samples.len() && samples[j + 1].t_s <= t {
            j += 1;
        }
        let (a, b) = (&samples[j], &samples[(j + 1).min(samples.len() - 1)]);
        let f = if b.t_s > a.t_s {
            ((t - a.t_s) / (b.t_s - a.t_s)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        for k in 0..3 {
            acc[k].push(a.acc_g[k] + f * (b.acc_g[k] - a.acc_g[k]));
            gyro[k].push(a.gyro_dps[k] + f * (b.gyro_dps[k] - a.gyro_dps[k]));
        }
    }
    let mut rec = Recording::new(fs, acc, gyro, vec![])
        .map_err(|e| e.to_string())?
        .with_side(side);
    rec.t0_s = t0_s;
    rec.source = Some(label.into());
    let report = crate::pipeline::memory_report(&rec);
    Ok((rec, report, label.to_string()))
}

/// Analyse one plan; `Err` when the span is not a walking bout (with why).
pub fn analyse(
    plan: &Plan,
    legs: [&LegStream; 2],
    store: &SpanStore,
    input: &SubjectInput,
    analysis: &Analysis<'_>,
    mp: &MonitorParams,
) -> Result<BoutRow, Refused> {
    let min_strides = mp.min_strides;
    let mut acc_norm: [Vec<f64>; 2] = Default::default();
    let mut load = |k: usize, idx: Option<usize>, side: Side| -> (LoadedLeg, Option<f64>) {
        let Some(i) = idx else {
            return (Err(format!("no {side} walk at this time")), None);
        };
        let span = &legs[k].spans[i];
        let samples = match store.get(&span.at) {
            Ok(s) => s,
            Err(e) => return (Err(e.to_string()), None),
        };
        let rec = recording(&samples, legs[k].fs_hz, 0.0, side, &legs[k].label);
        if let Ok((r, _, _)) = &rec {
            let a = &r.acc_g;
            acc_norm[k] = (0..a[0].len())
                .map(|i| (a[0][i] * a[0][i] + a[1][i] * a[1][i] + a[2][i] * a[2][i]).sqrt())
                .collect();
        }
        // The right leg placed on the left leg's clock.
        let t0 = if k == 1 {
            span.at.t0_s - plan.offset_s
        } else {
            span.at.t0_s
        };
        (
            rec.map(|(mut r, rep, label)| {
                r.t0_s = t0;
                (r, rep, label)
            }),
            Some(span.walk_s.0),
        )
    };
    let (l, lt) = load(0, plan.left, Side::Left);
    let (r, rt) = load(1, plan.right, Side::Right);
    let at = lt.or(rt.map(|t| t - plan.offset_s)).unwrap_or(0.0);
    let res = analysis.pair(input, l, r);
    let legs_ok: Vec<&LegResult> = [&res.left, &res.right]
        .into_iter()
        .filter_map(|x| x.as_ref().ok())
        .collect();
    let strides: [usize; 2] =
        [&res.left, &res.right].map(|x| x.as_ref().map_or(0, |l| l.parameters.strides_total));
    if strides[0] + strides[1] < min_strides || legs_ok.is_empty() {
        let why = [&res.left, &res.right]
            .iter()
            .filter_map(|x| x.as_ref().err().cloned())
            .collect::<Vec<_>>()
            .join("; ");
        return Err(Refused {
            start_s: at,
            reason: format!(
                "{} stride(s) found, {min_strides} needed{}",
                strides[0] + strides[1],
                if why.is_empty() {
                    String::new()
                } else {
                    format!(" ({why})")
                }
            ),
            run: false,
        });
    }
    let mut row = bout_row(&res.left, &res.right, strides, plan);
    let verdict = mp
        .stairs
        .classify(legs_ok.iter().flat_map(|l| l.strides.iter()));
    row.kind = verdict.kind;
    row.stair_strides = verdict.stair_strides;
    row.stride_rise_m = verdict.stride_rise_m;
    if let Some(why) = running(&res.left, &res.right, &acc_norm, &mp.windows) {
        return Err(Refused {
            start_s: at,
            reason: why,
            run: true,
        });
    }
    Ok(row)
}

/// Why the bout is a run (`steps` module docs), or `None`.
fn running(
    left: &Result<LegResult, String>,
    right: &Result<LegResult, String>,
    acc_norm: &[Vec<f64>; 2],
    w: &WindowParams,
) -> Option<String> {
    let legs = [left, right];
    // The events' median stride time (between mid-swings): the stride-time parameter may
    // be withheld by checks made for walking.
    let st: Vec<f64> = legs
        .iter()
        .filter_map(|x| x.as_ref().ok())
        .map(|l| l.events.median_stride_s)
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    let stride_s = st.iter().sum::<f64>() / st.len().max(1) as f64;
    if st.is_empty() || stride_s >= w.running_max_stride_s {
        return None;
    }
    let peaks: Vec<f64> = legs
        .iter()
        .zip(acc_norm)
        .filter_map(|(x, a)| {
            let l = x.as_ref().ok()?;
            heel_strike_peak_g(&l.events.hs_s, a, l.signals.as_ref()?.fs_hz)
        })
        .collect();
    let peak = peaks.iter().copied().fold(f64::NAN, f64::max);
    (peak >= w.running_min_acc_g).then(|| {
        format!(
            "a run: stride time {stride_s:.2} s < {} s and heel strikes of {peak:.1} g ≥ {} g",
            w.running_max_stride_s, w.running_min_acc_g
        )
    })
}

fn bout_row(
    left: &Result<LegResult, String>,
    right: &Result<LegResult, String>,
    strides: [usize; 2],
    plan: &Plan,
) -> BoutRow {
    let legs: Vec<&LegResult> = [left, right]
        .into_iter()
        .filter_map(|x| x.as_ref().ok())
        .collect();
    let hs: Vec<f64> = legs
        .iter()
        .flat_map(|l| leg_heel_strikes(l).into_iter().map(move |h| h + l.t0_s))
        .collect();
    let start = hs.iter().copied().fold(f64::INFINITY, f64::min);
    let end = hs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let steps = if legs.len() == 2 {
        hs.len()
    } else {
        2 * hs.len()
    };
    let mut withheld: Vec<String> = Vec::new();
    let mut mean_of = |p: Parameter, column: &str, factor: f64| -> f64 {
        let vals: Vec<f64> = legs
            .iter()
            .map(|l| l.parameters.value(p))
            .filter(|v| v.is_finite())
            .collect();
        if vals.is_empty() {
            let why: Vec<String> = legs
                .iter()
                .filter_map(|l| {
                    l.parameters
                        .withheld
                        .reason(p)
                        .map(|r| format!("{}: {r}", l.side))
                })
                .collect();
            let why = if why.is_empty() {
                "not measured in this bout".to_string()
            } else {
                why.join(", ")
            };
            withheld.push(format!("{column}: {why}"));
            return f64::NAN;
        }
        factor * vals.iter().sum::<f64>() / vals.len() as f64
    };
    let speed = mean_of(Parameter::Speed, "speed_mps", 1.0);
    let stride_time = mean_of(Parameter::StrideTime, "stride_time_s", 1.0);
    let stride_length = mean_of(Parameter::StrideLength, "stride_length_m", 1.0);
    let stv = mean_of(Parameter::StrideTimeCv, "stride_time_cv", 1.0);
    // One cadence per bout from both legs' stride times (the walk cadence of `ldh analyze`),
    // not the per-leg step frequency: that needs the two clocks aligned to a fraction of a step,
    // which the envelope offset is not (docs/free-living.md).
    let st = |x: &Result<LegResult, _>| {
        x.as_ref()
            .ok()
            .map(|l| l.parameters.value(Parameter::StrideTime))
    };
    let cadence =
        crate::domain::walk_cadence_steps_per_min(st(left), st(right)).unwrap_or_else(|| {
            withheld.push("cadence_steps_per_min: no leg's stride time in this bout".into());
            f64::NAN
        });
    let stt = [left, right].map(|x| {
        x.as_ref()
            .map_or(f64::NAN, |l| l.parameters[Parameter::StepTime])
    });
    let asym = if stt.iter().all(|v| v.is_finite() && *v > 0.0) {
        (stt[0] - stt[1]).abs() / (0.5 * (stt[0] + stt[1])) * 100.0
    } else {
        withheld.push(if legs.len() < 2 {
            "step_time_asymmetry_pct: needs both legs; one sensor saw this bout".into()
        } else {
            "step_time_asymmetry_pct: a leg's step time is not measured".into()
        });
        f64::NAN
    };
    BoutRow {
        bout: 0,
        start_s: start,
        end_s: end,
        duration_s: end - start,
        steps,
        legs: match (left.is_ok(), right.is_ok()) {
            (true, true) => Legs::Both,
            (true, false) => Legs::Left,
            _ => Legs::Right,
        },
        strides_left: strides[0],
        strides_right: strides[1],
        cadence_steps_per_min: cadence,
        speed_mps: speed,
        stride_time_s: stride_time,
        stride_length_m: stride_length,
        stride_time_cv: stv,
        step_time_asymmetry_pct: asym,
        kind: BoutKind::Walking,
        stair_strides: 0,
        stride_rise_m: f64::NAN,
        clock_offset_s: plan.offset_s,
        continues: false,
        withheld: withheld.join("; "),
    }
}
