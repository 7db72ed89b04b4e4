//! `ldh analyze`: analyse inputs into an output folder ([`ldh_core::pipeline::Many::to_folder`])
//! and, with `--report`, write the reports from the run's results in memory
//! ([`ldh_report::RunResults::of_run`], [`ldh_report::build`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::io::ReadParams;
use ldh_core::output::{OutputRun, RecordingRow, RunKind};
use ldh_core::pipeline::{
    discover_with, Analysis, FolderOptions, FolderSummary, InputOptions, SensorHeights, Severity,
};
use ldh_report::{BuildSources, ReportParams, RunResults};

use super::{analysis_params, progress, resolve_format, thread_pool};
use crate::args::AnalyzeArgs;

/// Run `ldh analyze`.
pub fn run(a: AnalyzeArgs) -> Result<ExitCode> {
    let started = std::time::Instant::now();
    super::check_out_dir(&a.out)?;
    let params = analysis_params(
        a.params.as_deref(),
        a.model,
        a.detector,
        a.sensor_height_m,
        a.no_sta,
    )?;
    let format = a.format.as_deref().map(resolve_format).transpose()?;
    // The report's reliability table is read now, so a bad one stops the run before the analysis.
    if let Some(f) = &a.reliability {
        ldh_core::cohort::ReliabilityTable::read(f)?;
    }
    let defaults = ReadParams::default();
    let read = ReadParams {
        max_file_size_mb: a.max_file_size_mb.unwrap_or(defaults.max_file_size_mb),
        max_samples: a.max_samples.map_or(defaults.max_samples, |n| n as usize),
        ..defaults
    }
    .check()?;
    let heights = SensorHeights {
        both_m: a.sensor_height_m,
        left_m: a.left_sensor_height_m,
        right_m: a.right_sensor_height_m,
    }
    .check()?;
    let subjects = discover_with(
        &a.inputs,
        &InputOptions {
            subject_id: a.subject.clone(),
            setting: a.setting,
            left_sensor_height_m: heights.left_m,
            right_sensor_height_m: heights.right_m,
        },
    )?;
    anyhow::ensure!(!subjects.is_empty(), "no subjects found in the inputs");
    // Before anything is said or done: a bad --jobs is a usage error.
    let pool = thread_pool(a.jobs)?;
    if a.inputs.is_empty() {
        super::note!(
            "no input given: analysing the embedded demo cohort ({})",
            ldh_core::pipeline::PeopleTrials::of(&subjects).describe()
        );
    }
    // Names checked before the folder is touched: an id clash leaves an earlier run whole.
    ldh_core::pipeline::check_output_names(&subjects)?;
    let stale = ldh_core::io::remove_stale_temp_files(&a.out)?;
    if stale > 0 {
        super::note!(
            "removed {stale} temporary file(s) of an interrupted earlier run in {}",
            a.out.display()
        );
    }
    // Checked before the analysis so a bad model file fails fast.
    let classifier = a
        .classifier
        .as_deref()
        .map(ldh_core::ml::read_model)
        .transpose()?;
    let report_params = ReportParams::default().check()?;
    let pb = progress(subjects.len() as u64, "analyze");
    let opts = FolderOptions {
        chunk: a
            .batch
            .map(|b| b as usize)
            .unwrap_or((pool.current_num_threads() * 32).max(32)),
        traces: a.report.then(|| report_params.trace()),
        keep: a.report,
    };
    // One run per folder: an earlier run's outputs are removed (its marker first), other files
    // or a link inside --out refuse the run; the marker is written last (docs/robustness.md).
    let run = OutputRun::begin(&a.out, RunKind::Analyze)?;
    let done = || pb.inc(1);
    let analysis = Analysis::new(params.check()?)
        .read(read)
        .format(format)
        .progress(&done);
    let mut sum = pool.install(|| analysis.many(&subjects).to_folder(&run, opts))?;
    pb.finish_and_clear();
    run.write(
        "params.json",
        serde_json::to_string_pretty(&params)?.as_bytes(),
    )?;
    let marker = run.finish()?;
    if let Some(kept) = sum.kept.take() {
        // The reports from this run's own results, in memory (nothing read back).
        let results = RunResults::of_run(&a.out, kept, &marker, &params);
        let dir = a.out.join("reports");
        let src = BuildSources {
            model: classifier.as_ref(),
            reliability: a.reliability.as_deref(),
            ..BuildSources::default()
        };
        let n = super::build_reports(&pool, &results, &dir, src, &report_params)?.subjects;
        super::note!(
            "{n} subject reports and the cohort report (index.html) in {}",
            dir.display()
        );
    }
    let wall_s = started.elapsed().as_secs_f64();
    if a.timings {
        eprint!("{}", sum.timings.table(Some(wall_s)));
    }
    summary(
        &a,
        &sum,
        ldh_core::pipeline::PeopleTrials::of(&subjects),
        params.attitude.model.as_str(),
        wall_s,
    )?;
    Ok(if sum.failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// The end of a run: failures (always) and warnings (with `-v`) on stderr, then one summary on
/// stdout — a sentence, or JSON with `--json` — unless `-q`.
fn summary(
    a: &AnalyzeArgs,
    sum: &FolderSummary,
    who: ldh_core::pipeline::PeopleTrials,
    model: &str,
    wall_s: f64,
) -> Result<()> {
    let v = super::verbosity();
    let warned: Vec<_> = sum.warned().collect();
    let failures: Vec<_> = sum.failures().collect();
    for f in &failures {
        eprintln!("error: {} {}: {}", f.subject_id, f.side, f.error);
    }
    if v.verbose {
        for r in &warned {
            for w in r.warnings.iter() {
                let (sev, code) = (w.severity.as_str(), &w.code);
                eprintln!("{sev}: {} {}: {code}: {}", r.subject_id, r.side, w.message);
            }
        }
    }
    if a.json {
        let failure = |r: &&RecordingRow| serde_json::json!({"subject_id": r.subject_id, "side": r.side, "error": r.error});
        let warning = |r: &&RecordingRow| serde_json::json!({"subject_id": r.subject_id, "side": r.side, "warnings": r.warnings});
        let mut j = serde_json::json!({
            "subjects": who.trials,
            "people": who.people,
            "trials": who.trials,
            "recordings": sum.recordings,
            "ok": sum.recordings - sum.failed,
            "failed": sum.failed,
            "with_warnings": warned.len(),
            "strides": sum.strides,
            "valid_strides": sum.valid_strides,
            "model": model,
            "out": a.out,
            "failures": failures.iter().map(failure).collect::<Vec<_>>(),
            "warnings": warned.iter().map(warning).collect::<Vec<_>>(),
        });
        if a.timings {
            j["timings"] = sum.timings.to_json(Some(wall_s));
        }
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !v.quiet {
        let line = format!(
            "{} ({}, model {model}): {} ok, {} failed; {}, {} valid; outputs in {}",
            super::count(sum.recordings, "recording"),
            who.describe(),
            sum.recordings - sum.failed,
            sum.failed,
            super::count(sum.strides, "stride"),
            sum.valid_strides,
            a.out.display()
        );
        println!("{line}");
        // Notes (what the pipeline did, e.g. the steady window it chose) are not counted: the
        // line is for what a technician should look at (`-v` lists notes too).
        let to_see = warned
            .iter()
            .filter(|r| r.warnings.at_least(Severity::Warning).next().is_some())
            .count();
        if to_see > 0 && !v.verbose {
            eprintln!(
                "{to_see} recording(s) with warnings: see recordings.csv, or -v to list them"
            );
        }
    }
    Ok(())
}
