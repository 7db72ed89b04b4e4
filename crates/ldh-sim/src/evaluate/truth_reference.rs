//! The simulator's ground truth as `ldh agree` reference files, so that `ldh evaluate` is a
//! case of `ldh agree` (issue 38; this moves to the simulator crate with the simulator).
//!
//! [`TruthScope::Steady`] writes the strides `ldh evaluate` scores: the steady ones (not
//! turning, not the first or last of a walking bout); [`TruthScope::All`] every true stride and
//! event of the walk. The events file holds each stride's heel strike and toe off (with `All`,
//! every true event); the strides file its first and ending heel strikes (`time_s`,
//! `end_time_s`), stride time, stance ratio and stride length. Times are written in full
//! (shortest round-trip decimal), so the files read back to the same numbers.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::{LegTruth, SubjectTruth};
use ldh_core::error::Result;

/// Which true strides and events a truth reference holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TruthScope {
    /// The steady strides, what `ldh evaluate` scores.
    Steady,
    /// Every stride and event of the walk.
    All,
}

/// The reference files' text: (events, strides). `shift_s` is added to every time (a
/// reference clock started `shift_s` s before ldh's reads `t + shift_s`; 0 for the truth).
pub fn truth_reference(
    truths: &[SubjectTruth],
    scope: TruthScope,
    shift_s: f64,
) -> (String, String) {
    let trials: Vec<(&SubjectTruth, Option<&str>)> = truths.iter().map(|t| (t, None)).collect();
    reference_text(&trials, scope, shift_s)
}

/// [`truth_reference`] of truths that may belong to trials: with any trial, both files get a
/// `trial_id` column after `subject_id`.
fn reference_text(
    truths: &[(&SubjectTruth, Option<&str>)],
    scope: TruthScope,
    shift_s: f64,
) -> (String, String) {
    let with_trials = truths.iter().any(|(_, t)| t.is_some());
    let trial_col = if with_trials { "trial_id," } else { "" };
    let mut events = format!("subject_id,{trial_col}side,event,time_s\n");
    let mut strides = format!(
        "subject_id,{trial_col}side,time_s,end_time_s,stride_time_s,stance_ratio,stride_length_m\n"
    );
    for (t, trial) in truths {
        let who = match (with_trials, trial) {
            (true, Some(tr)) => format!("{},{tr}", t.subject_id),
            (true, None) => format!("{},", t.subject_id),
            (false, _) => t.subject_id.clone(),
        };
        for leg in [&t.left, &t.right] {
            let side = leg.side.as_str();
            for (kind, at) in [("HS", 0usize), ("TO", 1)] {
                let times: Vec<f64> = match scope {
                    TruthScope::Steady => strides_of(leg, scope)
                        .map(|s| if at == 0 { s.hs_time_s } else { s.to_time_s })
                        .collect(),
                    TruthScope::All if at == 0 => leg.hs_times_s.clone(),
                    TruthScope::All => leg.to_times_s.clone(),
                };
                for time in times {
                    // writing to a String cannot fail
                    let _ = writeln!(events, "{who},{side},{kind},{}", time + shift_s);
                }
            }
            for s in strides_of(leg, scope) {
                let _ = writeln!(
                    strides,
                    "{who},{side},{},{},{},{},{}",
                    s.hs_time_s + shift_s,
                    s.next_hs_time_s + shift_s,
                    s.stride_time_s,
                    s.stance_ratio,
                    s.stride_length_m
                );
            }
        }
    }
    (events, strides)
}

fn strides_of(leg: &LegTruth, scope: TruthScope) -> impl Iterator<Item = &crate::StrideTruth> {
    let all = scope == TruthScope::All;
    leg.strides
        .iter()
        .filter(move |s| all || (!s.turning && !s.bout_edge))
}

/// Write [`truth_reference`] (unshifted) into `dir` as `reference_events.csv` and
/// `reference_strides.csv`, atomically; returns their paths.
pub fn write_truth_reference(
    dir: &Path,
    truths: &[SubjectTruth],
    scope: TruthScope,
) -> Result<[PathBuf; 2]> {
    let (events, strides) = truth_reference(truths, scope, 0.0);
    let e = dir.join("reference_events.csv");
    let s = dir.join("reference_strides.csv");
    ldh_core::io::write_atomic(&e, events.as_bytes())?;
    ldh_core::io::write_atomic(&s, strides.as_bytes())?;
    Ok([e, s])
}

/// The truth of a simulated cohort folder (`ldh simulate --reference`): every subject and
/// trial of its manifest, each trial's `truth.json` beside its left recording, written into
/// `cohort` as `reference_events.csv` and `reference_strides.csv` (with a `trial_id` column for
/// a retest cohort), the whole walk ([`TruthScope::All`]): the files a lab's force plates would
/// give, for trying `ldh agree` end to end.
pub fn write_cohort_reference(cohort: &Path) -> Result<[PathBuf; 2]> {
    let subjects = ldh_core::pipeline::discover(&[cohort.to_path_buf()])?;
    let mut truths = Vec::with_capacity(subjects.len());
    for s in &subjects {
        let dir = match &s.left {
            Some(ldh_core::pipeline::Source::Path(p)) => p.parent().map(Path::to_path_buf),
            _ => None,
        }
        .unwrap_or_else(|| cohort.join(&s.subject_id));
        truths.push((
            crate::read_truth(dir.join("truth.json"))?,
            s.trial_id.clone(),
        ));
    }
    let refs: Vec<(&SubjectTruth, Option<&str>)> =
        truths.iter().map(|(t, tr)| (t, tr.as_deref())).collect();
    let (events, strides) = reference_text(&refs, TruthScope::All, 0.0);
    let e = cohort.join("reference_events.csv");
    let st = cohort.join("reference_strides.csv");
    ldh_core::io::write_atomic(&e, events.as_bytes())?;
    ldh_core::io::write_atomic(&st, strides.as_bytes())?;
    Ok([e, st])
}
