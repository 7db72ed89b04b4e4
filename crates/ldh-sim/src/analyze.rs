//! A simulated subject through the pipeline in memory, as a read pair of files would go (for
//! evaluation and tests): the simulator's side of the analysis, which the analysis does not know.

use super::{SimLeg, SimSubject};
use ldh_core::pipeline::{
    memory_report, Analysis, AnalysisParams, LoadedLeg, SubjectInput, SubjectResult,
};

/// Analyse a simulated subject in memory (for evaluation and tests), with its manifest row
/// ([`simulated_input`]: the sensor height the mean of its legs').
///
/// # Panics
/// When `params` fail their check (a test's parameters are valid).
pub fn analyze_simulated(s: &SimSubject, params: &AnalysisParams) -> SubjectResult {
    analyze_simulated_with(s, params, &simulated_input(s))
}

/// What a manifest row says of a simulated subject: setting, id, group, affected side, and the
/// sensor height (the mean of its legs', as `ldh simulate` writes it); and that its legs share
/// one clock.
pub fn simulated_input(s: &SimSubject) -> SubjectInput {
    SubjectInput {
        setting: s.family_b.as_ref().map(|p| p.setting),
        subject_id: s.params.subject_id.clone(),
        group: Some(s.params.group.clone()),
        affected_side: s.params.affected_side,
        sensor_height_m: Some((s.left.truth.sensor_height_m + s.right.truth.sensor_height_m) / 2.0),
        // Both legs are simulated on one clock.
        clocks: Some(ldh_core::pipeline::Clocks::One),
        ..SubjectInput::default()
    }
}

/// [`analyze_simulated`] with another manifest row (`input`, e.g. other sensor heights).
///
/// # Panics
/// When `params` fail their check (a test's parameters are valid).
pub fn analyze_simulated_with(
    s: &SimSubject,
    params: &AnalysisParams,
    input: &SubjectInput,
) -> SubjectResult {
    let leg = |l: &SimLeg| -> LoadedLeg {
        let rec = l.recording.clone();
        let report = memory_report(&rec);
        Ok((
            rec,
            report,
            format!("{}/{}", s.params.subject_id, l.truth.side),
        ))
    };
    let analysis = Analysis::new(params.check().expect("valid analysis parameters"));
    analysis.pair(input, leg(&s.left), leg(&s.right))
}

/// Write the cohort `c` into `dir` as `ldh simulate` does, analyse the files as `ldh analyze`
/// does (every subject of the folder, default reading) with `params`, and read each subject's
/// truth: `(results, truths)` in the same subject order. For evaluation and tests of what needs
/// a whole analysed cohort (agreement, reports).
pub fn analyze_cohort(
    c: &crate::CohortParams,
    dir: &std::path::Path,
    params: &AnalysisParams,
) -> ldh_core::Result<(Vec<SubjectResult>, Vec<crate::SubjectTruth>)> {
    use ldh_core::io::{FormatSpec, ReadParams};
    crate::write_cohort(c, dir, &FormatSpec::default(), &|| {})?;
    let subjects = ldh_core::pipeline::discover(&[dir.to_path_buf()])?;
    let truths = subjects
        .iter()
        .map(|s| crate::read_truth(dir.join(&s.subject_id).join("truth.json")))
        .collect::<ldh_core::Result<Vec<_>>>()?;
    let read = ReadParams::default().check()?;
    let analysis = Analysis::new(params.check()?).read(read);
    let results = analysis.many(&subjects).results()?;
    Ok((results, truths))
}
