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

use crate::error::Result;
use crate::simulate::{LegTruth, SubjectTruth};

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
    let mut events = String::from("subject_id,side,event,time_s\n");
    let mut strides = String::from(
        "subject_id,side,time_s,end_time_s,stride_time_s,stance_ratio,stride_length_m\n",
    );
    for t in truths {
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
                    let _ = writeln!(events, "{},{side},{kind},{}", t.subject_id, time + shift_s);
                }
            }
            for s in strides_of(leg, scope) {
                let _ = writeln!(
                    strides,
                    "{},{side},{},{},{},{},{}",
                    t.subject_id,
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

fn strides_of(
    leg: &LegTruth,
    scope: TruthScope,
) -> impl Iterator<Item = &crate::simulate::StrideTruth> {
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
    crate::io::write_atomic(&e, events.as_bytes())?;
    crate::io::write_atomic(&s, strides.as_bytes())?;
    Ok([e, s])
}
