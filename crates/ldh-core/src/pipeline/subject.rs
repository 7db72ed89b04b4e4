//! One subject: both legs analysed and paired for step time and frequency.

use super::*;
use serde::{Deserialize, Serialize};

use crate::attitude::AttitudeModel;
use crate::io::{FormatSpec, ReadReport, ValidReadParams};
use crate::recording::{Recording, Side};
use crate::timings::{Stage, StageTimings};

impl SubjectResult {
    /// The bilateral event sequence of this subject (see [`bilateral_events`]).
    pub fn bilateral_events(&self) -> Vec<BilateralEvent> {
        bilateral_events(
            self.left.as_ref().ok().map(|l| &l.events),
            self.right.as_ref().ok().map(|r| &r.events),
        )
    }
}

/// The analysis of one subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectResult {
    /// Identifier.
    pub subject_id: String,
    /// Trial of the person (from the manifest), if several were given.
    #[serde(default)]
    pub trial_id: Option<String>,
    /// Group (from the manifest).
    pub group: Option<Group>,
    /// Affected side (from the manifest).
    pub affected_side: Option<Side>,
    /// The manifest left the affected side empty for a subject outside the healthy group.
    #[serde(default)]
    pub affected_side_unknown: bool,
    /// Where the walk happened, as given (`None`: not said, analysed as overground).
    #[serde(default)]
    pub setting: Option<crate::recording::Setting>,
    /// Treadmill belt speed, m/s, as given (manifest `belt_speed_mps`).
    #[serde(default)]
    pub belt_speed_mps: Option<f64>,
    /// The visit of this recording pair, as given (manifest `visit`).
    #[serde(default)]
    pub visit: Option<String>,
    /// Attitude model used.
    pub model: AttitudeModel,
    /// Left leg, or the error that stopped it.
    pub left: std::result::Result<LegResult, String>,
    /// Right leg, or the error that stopped it.
    pub right: std::result::Result<LegResult, String>,
    /// Problems of the pair (different clocks, rates or lengths; left and right possibly
    /// swapped); see [`pair_warnings`].
    #[serde(default)]
    pub warnings: Vec<Warning>,
    /// Wall time per stage of both legs, reading included (describes the run, not the result:
    /// not serialised, and always compares equal; see [`StageTimings`]).
    #[serde(skip)]
    pub timings: StageTimings,
}

impl SubjectResult {
    /// Both legs' results or errors, left first.
    pub fn legs(&self) -> [(Side, &std::result::Result<LegResult, String>); 2] {
        [(Side::Left, &self.left), (Side::Right, &self.right)]
    }
}

/// Read both legs of `input`, then `pair` them; the read time is added to the result's.
pub(super) fn load_and_pair(
    input: &SubjectInput,
    format: Option<&FormatSpec>,
    read: &ValidReadParams,
    pair: impl FnOnce(LoadedLeg, LoadedLeg) -> SubjectResult,
) -> SubjectResult {
    let load = |src: &Option<Source>,
                own: Option<&FormatSpec>,
                side: Side|
     -> std::result::Result<(Recording, ReadReport, String), String> {
        // Files of a subject folder not taken for a leg are named (issue 37): in a missing
        // leg's error, else among the leg's reader notes.
        let unpaired = input.unpaired.join("; ");
        let src = src.as_ref().ok_or_else(|| {
            if unpaired.is_empty() {
                format!("no {side} recording given")
            } else {
                format!("no {side} recording given ({unpaired})")
            }
        })?;
        let (rec, mut report) = src.read(own.or(format), read).map_err(|e| e.to_string())?;
        report.notes.extend(input.unpaired.iter().cloned());
        Ok((rec, report, src.label()))
    };
    let mut read_time = StageTimings::default();
    let (left, right) = read_time.time(Stage::Read, || {
        (
            load(&input.left, input.left_format.as_ref(), Side::Left),
            load(&input.right, input.right_format.as_ref(), Side::Right),
        )
    });
    let mut out = pair(left, right);
    out.timings.add(&read_time);
    out
}

/// The read outcome of one leg: the recording, what the reader found and a label, or the error.
pub type LoadedLeg = std::result::Result<(Recording, ReadReport, String), String>;

/// Analyse both legs and pair them ([`Analysis::pair`]).
pub(super) fn pair_legs(
    input: &SubjectInput,
    left: LoadedLeg,
    right: LoadedLeg,
    v: &ValidAnalysisParams,
) -> SubjectResult {
    let params = v.params();
    let mut timings = StageTimings::default();
    let (hl, hr) = (
        input.sensor_height_m_of(Side::Left),
        input.sensor_height_m_of(Side::Right),
    );
    let mut lf = front(left, v, &mut timings);
    let mut rf = front(right, v, &mut timings);
    // Each leg's toe offs from both legs' landmarks (the default detector); a faulty
    // gyroscope's landmarks are not lent to the other leg.
    crate::events::place_bilateral(sound(&mut lf), sound(&mut rf), v.events());
    let (mut l, mut r) = (
        back(lf, Side::Left, v, hl, &mut timings),
        back(rf, Side::Right, v, hr, &mut timings),
    );
    // The pairing below (turns from both legs, step times, the pair's checks) counts as strides.
    let clock = std::time::Instant::now();
    bilateral_turns(&mut l, &mut r, input, v);
    // The other leg's heel strikes on this leg's clock: event times count from each file's own
    // first sample, and the two files may start at different times.
    let t0 = |x: &LegRun| x.as_ref().ok().map(|a| a.leg.t0_s);
    let shifted =
        |x: &LegRun, to: Option<f64>| x.as_ref().ok().map(|a| a.lent.on_clock(a.leg.t0_s, to));
    let (lt0, rt0) = (t0(&l), t0(&r));
    let (warnings, overlapping) = match (&l, &r) {
        (Ok(ll), Ok(rl)) => pair_warnings(&ll.leg, &rl.leg),
        _ => (Vec::new(), true),
    };
    let (lhs, rhs) = if overlapping {
        (shifted(&l, rt0), shifted(&r, lt0))
    } else {
        (None, None)
    };
    // Issue 49: the other leg's toe offs on this leg's clock, for its double support.
    let shifted_to =
        |x: &LegRun, to: Option<f64>| x.as_ref().ok().map(|a| a.lent.to_on_clock(a.leg.t0_s, to));
    let (lto, rto) = (shifted_to(&l, rt0), shifted_to(&r, lt0));
    // Not when the pair's checks doubt they are one walk (what withholds the step time).
    let one_walk = overlapping
        && !warnings
            .iter()
            .any(|w| w.withholds(crate::domain::Parameter::StepTime));
    // One steady window for both legs of one walk (issue 50); else each leg its own.
    let walk = one_walk && l.is_ok() && r.is_ok();
    // Every finding applied once, in the order of `finalize` (the leg's own findings again:
    // the strides may have been re-segmented for turns since the leg checks ran).
    for a in [l.as_mut(), r.as_mut()].into_iter().flatten() {
        finalize::finalize_strides(&mut a.leg, &warnings, (!walk).then(|| v.steady()));
    }
    if let (Ok(AnalysedLeg { leg: ll, .. }), Ok(AnalysedLeg { leg: rl, .. }), true) =
        (l.as_mut(), r.as_mut(), walk)
    {
        quality::apply_steady_walk(ll, rl, v.steady());
        let shift_s = rl.t0_s - ll.t0_s;
        quality::withhold_disagreeing_lengths(&mut ll.strides, &mut rl.strides, shift_s);
    }
    // Two sensors not on one clock (`quality::clocks`): from the steady strides of both legs.
    let mut warnings = warnings;
    if let (Ok(ll), Ok(rl), Some(rh), Some(rt), Some(lh), Some(lt), true) =
        (&l, &r, &rhs, &rto, &lhs, &lto, walk)
    {
        let b = quality::clock_balance(&ll.leg.strides, &rl.leg.strides, (rh, rt), (lh, lt));
        // A split no walker shows, else (two files) a step asymmetry no swing backs.
        let found = b.as_ref().and_then(quality::clock_warning).or_else(|| {
            b.as_ref()
                .and_then(|b| quality::two_clocks_warning(b, input.clocks()))
        });
        warnings.extend(found);
    }
    let one_clock = !warnings
        .iter()
        .any(|w| [quality::codes::CLOCK_OFFSET, quality::codes::TWO_CLOCKS].contains(&w.code));
    // The parameters from the final strides, then what the findings withhold (`finalize`).
    // Double support (issue 49) from the other leg's events, when the two are one walk on one
    // clock.
    let finish = |x: LegRun, other: Option<Vec<f64>>, other_to: Option<Vec<f64>>| {
        x.map(|AnalysedLeg { mut leg, .. }| {
            if let (Some(hs), Some(to), true) = (&other, &other_to, one_walk && one_clock) {
                crate::gait::double_support(&mut leg.strides, hs, to);
            }
            finalize::finalize_parameters(&mut leg, &warnings, other.as_deref());
            leg
        })
    };
    let (mut left, mut right) = (finish(l, rhs, rto), finish(r, lhs, lto));
    quality::check_length_variability(left.as_mut().ok(), right.as_mut().ok());
    if input.affected_side_unknown {
        warnings.push(Warning::new(
            crate::domain::codes::AFFECTED_SIDE_UNKNOWN,
            Severity::Note,
            format!(
                "affected side unknown (empty in the manifest for group '{}'): no affected/unaffected comparison for this subject",
                input.group.as_ref().map_or("", |g| g.as_str())
            ),
        ));
    }
    timings.strides_s += clock.elapsed().as_secs_f64();
    SubjectResult {
        subject_id: input.subject_id.clone(),
        trial_id: input.trial_id.clone(),
        group: input.group.clone(),
        affected_side: input.affected_side,
        affected_side_unknown: input.affected_side_unknown,
        setting: input.setting,
        belt_speed_mps: input.belt_speed_mps,
        visit: input.visit.clone(),
        model: params.attitude.model,
        left,
        right,
        warnings,
        timings,
    }
}

/// One leg's analysis up to its strides (the leg and the heel strikes it lends), or its error.
type LegRun = std::result::Result<AnalysedLeg, String>;

/// One leg read and analysed up to its events ([`leg_front`]), or its error naming the file.
type FrontRun = std::result::Result<(Recording, ReadReport, String, LegFront), String>;

/// [`leg_front`] of a leg read (or its read error).
fn front(loaded: LoadedLeg, v: &ValidAnalysisParams, t: &mut StageTimings) -> FrontRun {
    let (rec, report, label) = loaded?;
    let f = leg_front(&rec, v, t).map_err(|e| format!("{label}: {e}"))?;
    Ok((rec, report, label, f))
}

/// The events of a leg whose gyroscope is sound (`None`: not read, failed, or faulty).
fn sound(f: &mut FrontRun) -> Option<&mut crate::events::Events> {
    match f {
        Ok((.., front)) if !front.sensor.gyro_fault => Some(&mut front.events),
        _ => None,
    }
}

/// [`leg_back`] of a leg's front (or its error), with the reader's report and label.
fn back(
    f: FrontRun,
    side: Side,
    v: &ValidAnalysisParams,
    h: Option<f64>,
    t: &mut StageTimings,
) -> LegRun {
    let (rec, report, label, f) = f?;
    let mut a = leg_back(&rec, side, v, h, f, t).map_err(|e| format!("{label}: {e}"))?;
    a.leg.read = report;
    a.leg.source = label;
    Ok(a)
}

/// Heading change of a leg between two times on its own clock, deg (wrapped to ±180).
fn heading_change(leg: &LegResult, t0: f64, t1: f64) -> Option<f64> {
    let att = leg.attitude.as_ref()?;
    let fs = leg.signals.as_ref()?.fs_hz;
    let n = att.yaw_deg.len();
    let idx = |t: f64| ((t * fs).round().max(0.0) as usize).min(n.saturating_sub(1));
    if n == 0 || t1 < 0.0 || t0 * fs > n as f64 {
        return None;
    }
    let d = att.yaw_deg[idx(t1)] - att.yaw_deg[idx(t0)];
    Some((d + 180.0).rem_euclid(360.0) - 180.0)
}

/// Re-segment both legs' strides with the turn decided from both legs (issue 20): a turn
/// rotates both shanks at the same time, so a stride is a turn only when the other leg's
/// heading also changes by more than half of `turn_deg` over the same interval (yaw drift on
/// one leg is not a turn); on a treadmill (`input.setting`) no stride is a turn. With one leg,
/// its own heading decides (as before). A heading from an attitude the checks do not vouch for
/// ([`quality::discredits_attitude`]) decides nothing: the other leg's then decides alone (by
/// `turn_deg`), and with neither no stride is taken for a turn.
fn bilateral_turns(
    l: &mut LegRun,
    r: &mut LegRun,
    input: &SubjectInput,
    params: &ValidAnalysisParams,
) {
    let treadmill = input.setting == Some(crate::recording::Setting::Treadmill);
    let vouched = |leg: &LegResult| !leg.warnings.iter().any(quality::discredits_attitude);
    let (Ok(ll), Ok(rl)) = (&*l, &*r) else {
        for a in [l, r].into_iter().flatten() {
            if treadmill || !vouched(&a.leg) {
                resegment(&mut a.leg, input, params, &|_, _, _| false);
            }
        }
        return;
    };
    let (ll, rl) = (ll.leg.clone(), rl.leg.clone());
    let turn_deg = params.params().strides.turn_deg;
    for (x, other) in [(l, &rl), (r, &ll)] {
        let Ok(AnalysedLeg { leg, .. }) = x else {
            continue;
        };
        let shift = leg.t0_s - other.t0_s;
        let (own_ok, other_ok) = (vouched(leg), vouched(other));
        let other_turns = |h0: f64, h1: f64, by: f64| {
            heading_change(other, h0 + shift, h1 + shift).is_none_or(|o| o.abs() > by)
        };
        let test = |h0: f64, h1: f64, d: f64| match (treadmill, own_ok, other_ok) {
            (true, _, _) | (false, false, false) => false,
            (false, true, true) => d.abs() > turn_deg && other_turns(h0, h1, 0.5 * turn_deg),
            (false, true, false) => d.abs() > turn_deg,
            (false, false, true) => {
                heading_change(other, h0 + shift, h1 + shift).is_some_and(|o| o.abs() > turn_deg)
            }
        };
        resegment(leg, input, params, &test);
    }
}

/// Recompute a leg's strides with another turn test (the leg keeps its events and attitude).
fn resegment(
    leg: &mut LegResult,
    input: &SubjectInput,
    params: &ValidAnalysisParams,
    test: &crate::gait::TurnTest,
) {
    let (Some(al), Some(att)) = (&leg.signals, &leg.attitude) else {
        return;
    };
    let Ok(sp) = params.strides(input.sensor_height_m_of(leg.side)) else {
        return;
    };
    if let Ok(st) = crate::gait::strides_with_turns(leg.side, al, att, &leg.events, &sp, test) {
        leg.strides = st;
    }
}
