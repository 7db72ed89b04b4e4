//! `ldh agree`: one `ldh analyze` run against a laboratory's reference files
//! (`docs/agreement.md`, "Command line and Python").
//!
//! 1. **Clock offset** per trial (ldh clock − reference clock): the reference file's
//!    `offset_s`, else [`OffsetMode`] (none, one given for all trials, or estimated by
//!    [`super::estimate_clock_offset`] from the trial's event trains — or, without reference
//!    events, its stride start times; an ambiguous estimate is refused — and polished by
//!    [`super::polish_offset`]). Subtracted from ldh's
//!    times before anything is matched.
//! 2. **Events** per subject, trial, side and event kind: ldh's events inside the span the
//!    reference covers (its first event − tolerance to its last + tolerance: a walkway sees a
//!    few strides of a long walk) matched one-to-one ([`super::match_events`]); rates and
//!    timing errors per event kind and side, and pooled over both sides; per group too when
//!    the subjects the reference covers are in two groups or more (`run_events.rs`).
//! 3. **Strides**: a reference stride with `time_s` is matched to the ldh stride whose first
//!    heel strike is its mutual nearest within the tolerance (and, when the reference gives
//!    `end_time_s`, whose ending heel strike lies within the tolerance of it); with only a
//!    `stride` number, to ldh's stride of that number. ldh's value of a matched stride is used
//!    for the event-timing parameters (`stride_time_s`, `stance_ratio`) whether or not the
//!    stride is valid, and for the others only when it is valid (an invalid stride's length or
//!    angles are not reported) — the rule of `ldh evaluate`.
//! 4. **Recordings** (one leg of one trial): the reference's per-recording row, else the mean
//!    of its strides of that leg, against `recordings.csv`.
//! 5. Each parameter's [`super::agreement`] per stride and per recording; one that cannot be
//!    computed (too few pairs, constant values) is reported with the reason.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::output::Parameter;
use crate::Side;

pub(crate) use super::outcome::{offset_of, Trial, KINDS, SIDES};
pub use super::outcome::{
    AgreementReport, EventAgreement, GroupCount, Level, MatchedEvent, OffsetSource, PairedValue,
    ParameterResult, System, TrialOffset, UnmatchedEvent, ALL_GROUPS, UNLABELLED,
};
use super::run_events::{event_train, group_counts};
use super::{
    agreement, estimate_clock_offset, match_events, polish_offset, ReferenceError,
    ValidAgreementParams,
};
use crate::output::results::{LdhResults, LdhStride, STRIDE_PARAMETERS};
use crate::reference::boxed;
use crate::reference::{Reference, ReferenceValues};

/// The clock offset of the trials whose reference file gives none.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OffsetMode {
    /// The clocks agree (offset 0).
    #[default]
    None,
    /// This offset, s (ldh clock − reference clock), for every trial.
    Fixed(f64),
    /// Estimated per trial from the events ([`super::estimate_clock_offset`]); note that an
    /// estimated offset absorbs a constant bias of the event times.
    Estimate,
}

impl OffsetMode {
    /// A given offset, s: refused unless finite (`what` names the argument in the error).
    pub fn fixed(offset_s: f64, what: &'static str) -> Result<Self, LdhError> {
        if offset_s.is_finite() {
            Ok(OffsetMode::Fixed(offset_s))
        } else {
            Err(LdhError::param(
                what,
                offset_s.to_string(),
                "expected a finite number of seconds or 'estimate'",
            ))
        }
    }
}

/// `estimate` (any case) or a finite number of seconds: the one reading of `--offset-s` and of
/// Python's `offset_s=` string.
impl std::str::FromStr for OffsetMode {
    type Err = LdhError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("estimate") {
            return Ok(OffsetMode::Estimate);
        }
        match t.parse::<f64>() {
            Ok(v) => OffsetMode::fixed(v, "offset_s"),
            Err(_) => Err(LdhError::param(
                "offset_s",
                s,
                "expected a number of seconds or 'estimate'",
            )),
        }
    }
}

/// Compare `results` with `reference` (see the module docs).
///
/// Errors: a trial's offset that cannot be estimated or is ambiguous
/// ([`ReferenceError::Offset`]); an event train that is not finite.
pub fn run(
    results: &LdhResults,
    reference: &Reference,
    params: &ValidAgreementParams,
    mode: OffsetMode,
) -> Result<AgreementReport> {
    let trials = reference_trials(results, reference);
    let offsets = trials
        .iter()
        .map(|t| trial_offset(results, reference, t, params, mode))
        .collect::<Result<Vec<_>>>()?;
    let mut report = AgreementReport {
        params: params.params().clone(),
        reference_files: reference
            .files
            .iter()
            .map(|f| f.display().to_string())
            .collect(),
        offsets,
        groups: group_counts(results, &trials),
        events: Vec::new(),
        events_by_group: Vec::new(),
        event_pairs: Vec::new(),
        unmatched_events: Vec::new(),
        reference_strides: reference.strides.len(),
        strides_matched: 0,
        parameters: Vec::new(),
    };
    super::run_events::events(results, reference, params, &trials, &mut report)?;
    strides(results, reference, params, &trials, &mut report)?;
    recordings(results, reference, params, &trials, &mut report);
    Ok(report)
}

/// The trials the reference covers, in the order of the results.
fn reference_trials(results: &LdhResults, reference: &Reference) -> Vec<Trial> {
    let covered = |s: &str, t: &str| {
        reference
            .events
            .iter()
            .any(|e| e.subject_id == s && e.trial_id == t)
            || reference
                .strides
                .iter()
                .chain(&reference.recordings)
                .any(|v| v.subject_id == s && v.trial_id == t)
    };
    results
        .trials()
        .into_iter()
        .filter(|(s, t)| covered(s, t))
        .map(|(s, t)| (s.to_string(), t.to_string()))
        .collect()
}

/// ldh's strides (sorted by start) and the reference's timed strides of one trial and side.
fn stride_train<'a>(
    results: &'a LdhResults,
    reference: &'a Reference,
    (s, t): (&str, &str),
    side: Side,
) -> (Vec<&'a LdhStride>, Vec<&'a ReferenceValues>) {
    let mut l: Vec<&LdhStride> = results
        .strides
        .iter()
        .filter(|x| x.subject_id == s && x.trial_id == t && x.side == side)
        .filter(|x| x.hs_time_s.is_finite())
        .collect();
    l.sort_by(|a, b| a.hs_time_s.total_cmp(&b.hs_time_s));
    let mut r: Vec<&ReferenceValues> = reference
        .strides
        .iter()
        .filter(|x| x.subject_id == s && x.trial_id == t && x.side == side)
        .collect();
    r.sort_by(|a, b| {
        let k = |v: &ReferenceValues| v.time_s.unwrap_or(f64::NEG_INFINITY);
        k(a).total_cmp(&k(b))
    });
    (l, r)
}

/// The offset of one trial: the file's, else by `mode`.
fn trial_offset(
    results: &LdhResults,
    reference: &Reference,
    (s, t): &Trial,
    params: &ValidAgreementParams,
    mode: OffsetMode,
) -> Result<TrialOffset> {
    let mut out = TrialOffset {
        subject_id: s.clone(),
        trial_id: t.clone(),
        offset_s: 0.0,
        source: OffsetSource::None,
        estimate: None,
    };
    if let Some(o) = reference
        .offsets
        .iter()
        .find(|o| &o.subject_id == s && &o.trial_id == t)
    {
        out.offset_s = o.offset_s;
        out.source = OffsetSource::File;
        return Ok(out);
    }
    match mode {
        OffsetMode::None => return Ok(out),
        OffsetMode::Fixed(x) => {
            out.offset_s = x;
            out.source = OffsetSource::Given;
            return Ok(out);
        }
        OffsetMode::Estimate => {}
    }
    let mut trains: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    for side in SIDES {
        for kind in KINDS {
            let tr = event_train(results, reference, (s, t), side, kind);
            if !tr.1.is_empty() {
                trains.push(tr);
            }
        }
    }
    if trains.is_empty() {
        for side in SIDES {
            let (l, r) = stride_train(results, reference, (s, t), side);
            let r: Vec<f64> = r.iter().filter_map(|v| v.time_s).collect();
            if !r.is_empty() {
                trains.push((l.iter().map(|x| x.hs_time_s).collect(), r));
            }
        }
    }
    let refuse = |reason: String| {
        boxed(ReferenceError::Offset {
            subject_id: s.clone(),
            trial_id: t.clone(),
            reason,
        })
    };
    if trains.is_empty() {
        // Per-recording values only: no times to align, none needed.
        return Ok(out);
    }
    let views: Vec<(&[f64], &[f64])> = trains.iter().map(|(l, r)| (&l[..], &r[..])).collect();
    let est = estimate_clock_offset(&views, params).map_err(|e| refuse(e.to_string()))?;
    if est.ambiguous {
        let r = est.runner_up.expect("ambiguous has a runner-up");
        return Err(refuse(format!(
            "ambiguous: {:.3} s and {:.3} s both match {} events",
            est.best.offset_s, r.offset_s, est.best.n_matched
        )));
    }
    out.offset_s = polish_offset(&views, est.best.offset_s, params).offset_s;
    out.source = OffsetSource::Estimated;
    out.estimate = Some(est);
    Ok(out)
}

/// The pairs of one level, per parameter, in first-seen order of the parameters.
#[derive(Default)]
struct Pairs(Vec<(Parameter, Vec<PairedValue>)>);

impl Pairs {
    fn push(&mut self, p: Parameter, v: PairedValue) {
        match self.0.iter_mut().find(|(q, _)| *q == p) {
            Some((_, list)) => list.push(v),
            None => self.0.push((p, vec![v])),
        }
    }

    fn finish(
        mut self,
        level: Level,
        params: &ValidAgreementParams,
        out: &mut Vec<ParameterResult>,
    ) {
        self.0
            .sort_by_key(|(p, _)| Parameter::ALL.iter().position(|q| q == p));
        for (p, pairs) in self.0 {
            let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
            let l: Vec<f64> = pairs.iter().map(|v| nan(v.ldh)).collect();
            let r: Vec<f64> = pairs.iter().map(|v| nan(v.reference)).collect();
            let (agreement, not_computed) = match agreement(&l, &r, params) {
                Ok(a) => (Some(a), None),
                Err(e) => (None, Some(e.to_string())),
            };
            out.push(ParameterResult {
                level,
                parameter: p.column().into(),
                agreement,
                not_computed,
                pairs,
            });
        }
    }
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// ldh's reported value of parameter `p` for a matched stride (see the module docs).
fn stride_value(s: &LdhStride, p: Parameter) -> Option<f64> {
    let i = STRIDE_PARAMETERS.iter().position(|q| *q == p)?;
    let timing = matches!(p, Parameter::StrideTime | Parameter::StanceRatio);
    if timing || s.valid {
        finite(s.values[i])
    } else {
        None
    }
}

/// Match the reference strides to ldh's and pair their values.
fn strides(
    results: &LdhResults,
    reference: &Reference,
    params: &ValidAgreementParams,
    trials: &[Trial],
    report: &mut AgreementReport,
) -> Result<()> {
    let tol = params.params().tolerance_s;
    let mut pairs = Pairs::default();
    for trial in trials {
        let offset = offset_of(report, trial);
        for side in SIDES {
            let (l, r) = stride_train(results, reference, (&trial.0, &trial.1), side);
            let timed: Vec<&ReferenceValues> =
                r.iter().copied().filter(|v| v.time_s.is_some()).collect();
            let starts: Vec<f64> = l.iter().map(|s| s.hs_time_s - offset).collect();
            let ref_starts: Vec<f64> = timed.iter().filter_map(|v| v.time_s).collect();
            let m = match_events(&starts, &ref_starts, params)?;
            let mut matched: Vec<(&LdhStride, &ReferenceValues)> = Vec::new();
            for &(i, j) in &m.pairs {
                let ends_ok = timed[j]
                    .end_time_s
                    .is_none_or(|e| (l[i].next_hs_time_s - offset - e).abs() <= tol);
                if ends_ok {
                    matched.push((l[i], timed[j]));
                }
            }
            for v in r.iter().filter(|v| v.time_s.is_none()) {
                if let Some(s) = l.iter().find(|s| Some(s.stride_index) == v.stride) {
                    matched.push((s, v));
                }
            }
            report.strides_matched += matched.len();
            for (s, v) in matched {
                for &(p, x) in &v.values {
                    pairs.push(
                        p,
                        PairedValue {
                            subject_id: trial.0.clone(),
                            trial_id: trial.1.clone(),
                            side,
                            stride_index: Some(s.stride_index),
                            ldh: stride_value(s, p),
                            reference: finite(x),
                        },
                    );
                }
            }
        }
    }
    pairs.finish(Level::Stride, params, &mut report.parameters);
    Ok(())
}

/// Pair each leg's reference value (given, or the mean of its strides) with recordings.csv.
fn recordings(
    results: &LdhResults,
    reference: &Reference,
    params: &ValidAgreementParams,
    trials: &[Trial],
    report: &mut AgreementReport,
) {
    let mut pairs = Pairs::default();
    for (s, t) in trials {
        for side in SIDES {
            let of_leg =
                |v: &&ReferenceValues| &v.subject_id == s && &v.trial_id == t && v.side == side;
            let values: Vec<(Parameter, f64)> = match reference.recordings.iter().find(of_leg) {
                Some(v) => v.values.clone(),
                None => leg_means(reference.strides.iter().filter(of_leg)),
            };
            let row = results
                .recordings
                .iter()
                .find(|r| &r.subject_id == s && &r.trial_id == t && r.side == side);
            for (p, x) in values {
                pairs.push(
                    p,
                    PairedValue {
                        subject_id: s.clone(),
                        trial_id: t.clone(),
                        side,
                        stride_index: None,
                        ldh: row.and_then(|r| r.value(p)).and_then(finite),
                        reference: finite(x),
                    },
                );
            }
        }
    }
    pairs.finish(Level::Recording, params, &mut report.parameters);
}

/// Mean of each parameter over a leg's reference strides (empty cells skipped; NaN when none).
fn leg_means<'a>(rows: impl Iterator<Item = &'a ReferenceValues>) -> Vec<(Parameter, f64)> {
    let mut acc: Vec<(Parameter, f64, usize)> = Vec::new();
    for v in rows {
        for &(p, x) in &v.values {
            let i = match acc.iter().position(|a| a.0 == p) {
                Some(i) => i,
                None => {
                    acc.push((p, 0.0, 0));
                    acc.len() - 1
                }
            };
            if x.is_finite() {
                acc[i].1 += x;
                acc[i].2 += 1;
            }
        }
    }
    acc.into_iter()
        .map(|(p, sum, n)| (p, if n > 0 { sum / n as f64 } else { f64::NAN }))
        .collect()
}
