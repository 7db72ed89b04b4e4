//! A simulated subject through the pipeline in memory, as a read pair of files would go (for
//! evaluation and tests): the simulator's side of the analysis, which the analysis does not know.

use super::{SimLeg, SimSubject};
use crate::pipeline::{
    analyze_pair, memory_report, AnalysisParams, LoadedLeg, SubjectInput, SubjectResult,
};

/// Analyse a simulated subject in memory (for evaluation and tests).
pub fn analyze_simulated(s: &SimSubject, params: &AnalysisParams) -> SubjectResult {
    let input = SubjectInput {
        setting: s.family_b.as_ref().map(|p| p.setting),
        subject_id: s.params.subject_id.clone(),
        group: Some(s.params.group.into()),
        affected_side: s.params.affected_side,
        sensor_height_m: Some((s.left.truth.sensor_height_m + s.right.truth.sensor_height_m) / 2.0),
        ..SubjectInput::default()
    };
    let leg = |l: &SimLeg| -> LoadedLeg {
        let rec = l.recording.clone();
        let report = memory_report(&rec);
        Ok((
            rec,
            report,
            format!("{}/{}", s.params.subject_id, l.truth.side),
        ))
    };
    analyze_pair(&input, leg(&s.left), leg(&s.right), params)
}
