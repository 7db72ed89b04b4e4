//! Per-stride scoring (`ldh evaluate --strides-csv`): every steady true stride of every leg with
//! what the pipeline reported for it. [`super::evaluate`]'s cohort figures are aggregated from
//! these records, so the table and the file always agree.

use std::path::Path;

use serde::Serialize;

use crate::{Group, LegTruth, StrideTruth, SubjectTruth};
use ldh_core::gait::Stride;
use ldh_core::pipeline::{LegResult, SubjectResult};

/// Largest distance between a true and a detected event (or stride start) that still matches, s.
pub const MATCH_WINDOW_S: f64 = 0.25;

/// One steady true stride (not turning, not the first or last of a walking bout) and what the
/// pipeline reported for it. Errors are detected − true; empty (`None`) when nothing was
/// detected within [`MATCH_WINDOW_S`] or the value was withheld.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrideScore {
    /// Attitude model of the analysis (`fusion`, `acc`).
    pub model: String,
    /// Subject.
    pub subject_id: String,
    /// The subject's group in the truth.
    pub group: String,
    /// Leg (`left`, `right`).
    pub side: String,
    /// The true stride's number within the leg.
    pub true_index: usize,
    /// True heel strike, s from the recording's first sample.
    pub true_hs_time_s: f64,
    /// Detected − true heel strike, ms (empty: missed).
    pub hs_error_ms: Option<f64>,
    /// Detected − true toe off, ms (empty: missed).
    pub to_error_ms: Option<f64>,
    /// The detected stride's number, when a detected stride starts and ends at this one's
    /// heel strikes (within [`MATCH_WINDOW_S`]).
    pub stride_index: Option<usize>,
    /// True stride time, s.
    pub true_stride_time_s: f64,
    /// Detected − true stride time, ms.
    pub stride_time_error_ms: Option<f64>,
    /// True stance ratio.
    pub true_stance_ratio: f64,
    /// Detected − true stance ratio (a ratio, not %).
    pub stance_ratio_error: Option<f64>,
    /// True stride length, m.
    pub true_stride_length_m: f64,
    /// Reported stride length, m (empty: withheld, or the stride not valid or not matched).
    pub stride_length_m: Option<f64>,
    /// (reported − true) / true stride length, %.
    pub stride_length_error_pct: Option<f64>,
    /// Whether the matched stride is valid (empty: no stride matched).
    pub valid: Option<bool>,
    /// The matched stride's reasons (why it is not valid, why a value is withheld).
    pub reason: String,
}

/// The detected time nearest `t` within [`MATCH_WINDOW_S`].
fn nearest(v: &[f64], t: f64) -> Option<f64> {
    v.iter()
        .copied()
        .min_by(|a, b| {
            (a - t)
                .abs()
                .partial_cmp(&(b - t).abs())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .filter(|x| (x - t).abs() < MATCH_WINDOW_S)
}

/// The per-stride scores of every leg of `results` that was analysed, matched to `truths` by
/// subject id, legs in the order left, right, strides in the truth's order.
pub fn stride_scores(results: &[SubjectResult], truths: &[SubjectTruth]) -> Vec<StrideScore> {
    let mut out = Vec::new();
    for r in results {
        let Some(t) = truths.iter().find(|t| t.subject_id == r.subject_id) else {
            continue;
        };
        for (leg, truth) in [(&r.left, &t.left), (&r.right, &t.right)] {
            if let Ok(leg) = leg {
                let who = (r.model.as_str(), t.subject_id.as_str(), t.group.clone());
                out.extend(leg_scores(leg, truth, who));
            }
        }
    }
    out
}

/// The steady true strides of one leg, scored.
pub(super) fn leg_scores<'a>(
    leg: &'a LegResult,
    truth: &'a LegTruth,
    (model, subject_id, group): (&'a str, &'a str, Group),
) -> impl Iterator<Item = StrideScore> + 'a {
    let steady = truth.strides.iter().filter(|s| !s.turning && !s.bout_edge);
    steady.map(move |ts| {
        let matched = leg.strides.iter().find(|s| {
            (s.hs_time_s - ts.hs_time_s).abs() < MATCH_WINDOW_S
                && (s.next_hs_time_s - ts.next_hs_time_s).abs() < MATCH_WINDOW_S
        });
        let mut score = StrideScore {
            model: model.to_string(),
            subject_id: subject_id.to_string(),
            group: group.as_str().to_string(),
            side: truth.side.as_str().to_string(),
            true_index: ts.index,
            true_hs_time_s: ts.hs_time_s,
            hs_error_ms: nearest(&leg.events.hs_s, ts.hs_time_s).map(|d| (d - ts.hs_time_s) * 1e3),
            to_error_ms: nearest(&leg.events.to_s, ts.to_time_s).map(|d| (d - ts.to_time_s) * 1e3),
            stride_index: None,
            true_stride_time_s: ts.stride_time_s,
            stride_time_error_ms: None,
            true_stance_ratio: ts.stance_ratio,
            stance_ratio_error: None,
            true_stride_length_m: ts.stride_length_m,
            stride_length_m: None,
            stride_length_error_pct: None,
            valid: None,
            reason: String::new(),
        };
        if let Some(s) = matched {
            fill_matched(&mut score, s, ts);
        }
        score
    })
}

/// The values of the detected stride `s` matched to the true stride `ts`.
fn fill_matched(score: &mut StrideScore, s: &Stride, ts: &StrideTruth) {
    score.stride_index = Some(s.stride_index);
    score.stride_time_error_ms = Some((s.stride_time_s - ts.stride_time_s) * 1e3);
    score.stance_ratio_error = s
        .stance_ratio
        .is_finite()
        .then_some(s.stance_ratio - ts.stance_ratio);
    if s.valid && s.stride_length_m.is_finite() && ts.stride_length_m.is_finite() {
        score.stride_length_m = Some(s.stride_length_m);
        score.stride_length_error_pct =
            Some((s.stride_length_m - ts.stride_length_m) / ts.stride_length_m * 100.0);
    }
    score.valid = Some(s.valid);
    score.reason = s.reason.clone();
}

/// Write the scores as CSV to `path` (a header row, one row per score, empty cells for `None`),
/// atomically.
pub fn write_stride_scores(path: &Path, scores: &[StrideScore]) -> ldh_core::Result<()> {
    let failed = |e: &dyn std::fmt::Display| ldh_core::LdhError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    for s in scores {
        w.serialize(s).map_err(|e| failed(&e))?;
    }
    let bytes = w.into_inner().map_err(|e| failed(&e))?;
    ldh_core::io::write_atomic(path, &bytes)
}
