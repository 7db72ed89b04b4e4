//! `ldh evaluate`: score the pipeline against simulator ground truth
//! ([`ldh_sim::evaluate::evaluate`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::attitude::AttitudeModel;
use ldh_core::io::ReadParams;
use ldh_core::pipeline::{discover, Analysis};

use super::{analysis_params, thread_pool};
use crate::args::EvaluateArgs;

/// Run `ldh evaluate`.
pub fn run(a: EvaluateArgs) -> Result<ExitCode> {
    let mut subjects = discover(std::slice::from_ref(&a.truth))?;
    let truths: Vec<ldh_sim::SubjectTruth> = subjects
        .iter()
        .map(|s| ldh_sim::read_truth(a.truth.join(&s.subject_id).join("truth.json")))
        .collect::<ldh_core::Result<_>>()?;
    // A family B truth knows its setting (treadmill: no turns) when the manifest does not say.
    for (s, t) in subjects.iter_mut().zip(&truths) {
        s.setting = s.setting.or(t.family_b.as_ref().map(|b| b.setting));
    }
    let read = ReadParams::default().check()?;
    let pool = thread_pool(a.jobs)?;
    let mut accs = Vec::new();
    let mut scores = Vec::new();
    for model in [AttitudeModel::Fusion, AttitudeModel::Acc] {
        let params = analysis_params(None, Some(model), Some(a.detector), None, true)?;
        let analysis = Analysis::new(params.check()?).read(read.clone());
        let results = pool.install(|| analysis.many(&subjects).results())?;
        accs.push(ldh_sim::evaluate::evaluate(&results, &truths));
        if a.strides_csv.is_some() {
            scores.extend(ldh_sim::evaluate::stride_scores(&results, &truths));
        }
    }
    println!(
        "Accuracy against ground truth: {} subjects in {}, detector {}\n",
        subjects.len(),
        a.truth.display(),
        a.detector.as_str()
    );
    println!("{}", ldh_sim::evaluate::markdown(&accs));
    if let Some(j) = a.json {
        ldh_core::io::write_atomic(&j, serde_json::to_string_pretty(&accs)?.as_bytes())?;
    }
    if let Some(p) = a.strides_csv {
        ldh_sim::evaluate::write_stride_scores(&p, &scores)?;
    }
    Ok(ExitCode::SUCCESS)
}
