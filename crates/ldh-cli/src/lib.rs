//! The `ldh` command line: argument parsing, files, parallelism, progress, output and exit
//! codes. No signal processing happens here; every computation is a call into `ldh_core`.
//!
//! Exit codes: 0 all good; 1 some inputs failed (the others' results are written); 2 usage or
//! a failure that stopped the whole command.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use ldh_core::io::{read_recording, FormatSpec, GapPolicy, ReadParams};
use ldh_core::output;
use ldh_core::pipeline::{analyze_subject, discover, AnalysisParams, SubjectResult};
use ldh_core::preprocess::{preprocess, PreprocessParams};
use ldh_core::simulate::{manifest_csv, CohortParams, ManifestRow, SensorModel};

mod demo_cmd;

/// Gait assessment for lumbar disc herniation from two shank-worn IMUs.
///
/// Typical use: `ldh simulate --out demo` to make a cohort, `ldh inspect FILE` to check
/// that a vendor export is read correctly.
#[derive(Debug, Parser)]
#[command(name = "ldh", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Analyse recordings: events, strides and the 12 gait parameters per side.
    ///
    /// INPUT is a manifest CSV, a cohort folder (with manifest.csv or subject folders), a
    /// subject folder with left.csv and right.csv, or a subject's two files. Without INPUT the
    /// embedded demo cohort is analysed. Writes strides.csv/.json, recordings.csv/.json and
    /// events.csv (both legs' HS and TO in one time-ordered sequence) to
    /// --out; a recording that fails is listed with its reason, the others are still written,
    /// and the exit code is 1.
    Analyze(AnalyzeArgs),
    /// Score the pipeline against simulator ground truth: `ldh simulate` output (with
    /// truth.json per subject) is analysed with both attitude models and the event and
    /// stride accuracy is printed as a Markdown table.
    Evaluate(EvaluateArgs),
    /// Cohort statistics like the paper's Tables 3 and 4, with radar charts and box plots.
    ///
    /// Analyses INPUT (a manifest or cohort folder with groups; see `analyze`) — or reads the
    /// per-recording table of an earlier `ldh analyze` with --results — and compares the LDH
    /// subjects' unaffected (LDHH) and affected (LDHE) sides with healthy subjects (H) and
    /// healthy left vs right (LR). With --compare acc the ACC-only model is analysed from the
    /// same recordings and Table 4 (z-normalised offsets OFF0/OFF1) compares the two models.
    Stats(StatsArgs),
    /// Rank features and cross-validate RF, SVM and MLP classifiers; save trained models.
    ///
    /// Subject-grouped cross-validation is the default: both sides of a subject always fall on
    /// the same side of a split (the paper's plain stratified folds let a subject's unaffected
    /// side train the model that tests its affected side). Stratified folds are run beside it
    /// for comparison with the paper, and the report shows the gap.
    Train(TrainArgs),
    /// Predict the class of recordings with a model saved by `ldh train`.
    Predict(PredictArgs),
    /// HTML reports a clinician opens offline: one per subject and one for the cohort.
    ///
    /// Reads the output folder of `ldh analyze` (recordings.json, strides.csv and, when
    /// `analyze --report` kept them, the signal traces in traces/) and writes
    /// <OUT>/index.html (the cohort) and <OUT>/subjects/<subject>.html. With --model the
    /// classifier's output is added to each subject's report as decision support; --stats and
    /// --train add Table 4 and the classifier results to the cohort report.
    Report(ReportArgs),
    /// Simulate a cohort of healthy and LDH subjects with two shank IMUs and exact ground truth.
    ///
    /// Writes <OUT>/<subject>/left.csv, right.csv, truth.json and <OUT>/manifest.csv. The same
    /// seed gives byte-identical files whatever --jobs is.
    Simulate(SimulateArgs),
    /// Read sensor files, say what was detected (format, delimiter, rate, gaps, clipping) and
    /// run the preprocessing; one line per file, or JSON.
    Inspect(InspectArgs),
    /// List the built-in vendor formats, or print one as TOML to adapt for your device.
    Formats {
        /// A format's name; omit to list them all.
        name: Option<String>,
    },
    /// Write the embedded demo cohort (the default data of `ldh analyze`) to a folder.
    Demo {
        /// Output folder.
        #[arg(long, default_value = "ldh-demo")]
        out: PathBuf,
    },
}

#[derive(Debug, Args)]
struct AnalyzeArgs {
    /// Inputs (see above); none: the embedded demo cohort.
    inputs: Vec<PathBuf>,
    /// Output folder.
    #[arg(long, default_value = "ldh-out")]
    out: PathBuf,
    /// Attitude model: fusion (adaptive Kalman; default) or acc (accelerometer tilt only).
    #[arg(long)]
    model: Option<String>,
    /// Event detector: gyro-landmarks (default), gyro-zero-crossing, salarian or pitch-peaks (the
    /// paper's).
    #[arg(long)]
    detector: Option<String>,
    /// Sensor format: a built-in name or a TOML column map; default: detect.
    #[arg(long)]
    format: Option<String>,
    /// Sensor height above the ankle when the manifest has none, m (default 0.10).
    #[arg(long)]
    sensor_height_m: Option<f64>,
    /// All analysis parameters as a TOML file (docs/parameters.md); the flags above, when given,
    /// override it.
    #[arg(long)]
    params: Option<PathBuf>,
    /// Skip the Lyapunov exponent (STA).
    #[arg(long)]
    no_sta: bool,
    /// Also write the HTML reports (as `ldh report`) to <OUT>/reports, and the signal traces
    /// they plot to <OUT>/traces.
    #[arg(long)]
    report: bool,
    /// With --report: a model saved by `ldh train` whose output the subject reports show.
    #[arg(long, requires = "report")]
    classifier: Option<PathBuf>,
    /// Subjects analysed between two writes of the output (default 32 per worker thread).
    /// Memory grows with it, not with the number of subjects; the output does not depend on it.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    batch: Option<u64>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
}

#[derive(Debug, Args)]
struct ReportArgs {
    /// Output folder of `ldh analyze`.
    results: PathBuf,
    /// Where to write the reports (default: <RESULTS>/reports).
    #[arg(long)]
    out: Option<PathBuf>,
    /// A model saved by `ldh train`: its output goes into each subject's report.
    #[arg(long)]
    model: Option<PathBuf>,
    /// Output folder of `ldh stats` (table4.json) for the cohort report.
    #[arg(long)]
    stats: Option<PathBuf>,
    /// Output folder of `ldh train` (cv_results.json) for the cohort report.
    #[arg(long)]
    train: Option<PathBuf>,
    /// Report parameters as TOML (docs/reports.md).
    #[arg(long)]
    params: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
}

#[derive(Debug, Args)]
struct StatsArgs {
    /// Inputs as for `analyze` (they need groups: a manifest or `ldh simulate` output).
    inputs: Vec<PathBuf>,
    /// Read recordings.json from an `ldh analyze` output folder instead of analysing.
    #[arg(long, conflicts_with = "inputs")]
    results: Option<PathBuf>,
    /// Also analyse with this model and compare (Table 4): `acc`.
    #[arg(long)]
    compare: Option<String>,
    /// Output folder.
    #[arg(long, default_value = "ldh-stats")]
    out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
}

#[derive(Debug, Args)]
struct TrainArgs {
    /// Inputs as for `analyze` (they need groups: a manifest or `ldh simulate` output).
    inputs: Vec<PathBuf>,
    /// Read recordings.json from an `ldh analyze` output folder instead of analysing.
    #[arg(long, conflicts_with = "inputs")]
    results: Option<PathBuf>,
    /// Task: three-class (LDHH / LDHE / H) or binary (LDHE vs H).
    #[arg(long, default_value = "three-class")]
    task: String,
    /// Classifiers, comma-separated: rf, svm, mlp.
    #[arg(long, default_value = "rf,svm,mlp")]
    classifiers: String,
    /// Folds.
    #[arg(long, default_value_t = 10)]
    k: usize,
    /// Repeats of the k-fold split.
    #[arg(long, default_value_t = 10)]
    repeats: usize,
    /// Seed of folds and models.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Keep the k features with the largest |Pearson r| inside each training fold.
    #[arg(long)]
    top_k: Option<usize>,
    /// Features (comma-separated columns of recordings.csv); default: the 13 parameters.
    #[arg(long)]
    features: Option<String>,
    /// Output folder.
    #[arg(long, default_value = "ldh-train")]
    out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
}

#[derive(Debug, Args)]
struct PredictArgs {
    /// A model file written by `ldh train`.
    #[arg(long)]
    model: PathBuf,
    /// Inputs as for `analyze`; or --results.
    inputs: Vec<PathBuf>,
    /// Read recordings.json from an `ldh analyze` output folder instead of analysing.
    #[arg(long, conflicts_with = "inputs")]
    results: Option<PathBuf>,
    /// Output folder.
    #[arg(long, default_value = "ldh-predict")]
    out: PathBuf,
}

#[derive(Debug, Args)]
struct EvaluateArgs {
    /// A folder written by `ldh simulate` (manifest.csv and truth.json per subject).
    #[arg(long)]
    truth: PathBuf,
    /// Event detector to score.
    #[arg(long, default_value = "gyro-landmarks")]
    detector: String,
    /// Also write the accuracy as JSON here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
}

#[derive(Debug, Args)]
struct SimulateArgs {
    /// Output folder (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Number of healthy subjects.
    #[arg(long, default_value_t = 2)]
    healthy: usize,
    /// Number of LDH subjects.
    #[arg(long, default_value_t = 2)]
    ldh: usize,
    /// Recording length per subject, seconds.
    #[arg(long, default_value_t = 25.0)]
    seconds: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Sampling rate of the simulated sensors, Hz.
    #[arg(long, default_value_t = 100.0)]
    rate_hz: f64,
    /// Walk straight only (no 180° turn in the middle).
    #[arg(long)]
    no_turn: bool,
    /// Noise-free sensors without bias, quantisation or misalignment.
    #[arg(long)]
    ideal: bool,
    /// Lowest LDH severity (0–1): each LDH subject's effects are scaled by a severity drawn in
    /// [this, 1]; 1 (default) makes every LDH subject fully affected.
    #[arg(long, default_value_t = 1.0)]
    ldh_severity_min: f64,
    /// Output format: a built-in format name or a TOML file.
    #[arg(long, default_value = "ldh")]
    format: String,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
}

#[derive(Debug, Args)]
struct InspectArgs {
    /// Sensor CSV files.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Format: a built-in name or a TOML column map; default: detect a built-in format.
    #[arg(long)]
    format: Option<String>,
    /// Longest gap in the timestamps bridged by interpolation, s.
    #[arg(long, default_value_t = 0.2)]
    max_gap_s: f64,
    /// Refuse recordings with longer gaps instead of keeping the longest segment.
    #[arg(long)]
    reject_gaps: bool,
    /// Print JSON instead of one line per file.
    #[arg(long)]
    json: bool,
}

/// Resolve `--format`: a built-in name or a path to a TOML file.
pub fn resolve_format(name: &str) -> Result<FormatSpec> {
    Ok(FormatSpec::resolve(name)?)
}

fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        ProgressBar::new(len)
    } else {
        ProgressBar::hidden()
    };
    pb.set_style(
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {elapsed_precise} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_prefix(what.to_string());
    pb
}

fn thread_pool(jobs: Option<usize>) -> Result<rayon::ThreadPool> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(j) = jobs {
        anyhow::ensure!(j >= 1, "--jobs must be at least 1");
        b = b.num_threads(j);
    }
    Ok(b.build()?)
}

fn simulate(a: SimulateArgs) -> Result<ExitCode> {
    let format = resolve_format(&a.format)?;
    let params = CohortParams {
        healthy: a.healthy,
        ldh: a.ldh,
        duration_s: a.seconds,
        fs_hz: a.rate_hz,
        seed: a.seed,
        turn: !a.no_turn,
        ldh_severity_min: a.ldh_severity_min,
        sensor: if a.ideal {
            SensorModel::ideal()
        } else {
            SensorModel::default()
        },
    };
    params.validate()?;
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let pool = thread_pool(a.jobs)?;
    let pb = progress(params.len() as u64, "simulate");
    let results: Vec<Result<ManifestRow>> = pool.install(|| {
        (0..params.len())
            .into_par_iter()
            .map(|i| {
                let s = params.simulate(i)?;
                s.write(&a.out.join(&s.params.subject_id), &format)?;
                pb.inc(1);
                Ok(ManifestRow::of(&s))
            })
            .collect()
    });
    pb.finish_and_clear();
    let rows: Vec<ManifestRow> = results.into_iter().collect::<Result<_>>()?;
    ldh_core::io::write_atomic(a.out.join("manifest.csv"), manifest_csv(&rows).as_bytes())?;
    let cohort = serde_json::to_string_pretty(&params)?;
    ldh_core::io::write_atomic(a.out.join("cohort.json"), cohort.as_bytes())?;
    eprintln!(
        "wrote {} subjects ({} healthy, {} LDH) to {}",
        rows.len(),
        a.healthy,
        a.ldh,
        a.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

fn inspect(a: InspectArgs) -> Result<ExitCode> {
    let format = a.format.as_deref().map(resolve_format).transpose()?;
    let rp = ReadParams {
        max_gap_s: a.max_gap_s,
        gap_policy: if a.reject_gaps {
            GapPolicy::Reject
        } else {
            GapPolicy::Split
        },
        ..ReadParams::default()
    }
    .check()?;
    let outcomes: Vec<(PathBuf, Result<serde_json::Value, String>)> = a
        .files
        .par_iter()
        .map(|f| {
            let r = read_recording(f, format.as_ref(), &rp).and_then(|(rec, report)| {
                let pp = PreprocessParams::default().check(rec.fs_hz)?;
                let pre = preprocess(&rec, &pp)?;
                Ok(serde_json::json!({
                    "file": f,
                    "read": report,
                    "preprocess": {
                        "outliers_replaced": pre.replaced.len(),
                        "raw_norm_mean_g": pre.raw_norm_mean_g,
                        "raw_norm_sd_g": pre.raw_norm_sd_g,
                    }
                }))
            });
            (f.clone(), r.map_err(|e| e.to_string()))
        })
        .collect();
    let failed = outcomes.iter().filter(|o| o.1.is_err()).count();
    if a.json {
        let v: Vec<serde_json::Value> = outcomes
            .iter()
            .map(|(f, r)| match r {
                Ok(v) => v.clone(),
                Err(e) => serde_json::json!({"file": f, "error": e}),
            })
            .collect();
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        for (f, r) in &outcomes {
            match r {
                Ok(v) => {
                    let rd = &v["read"];
                    println!(
                        "{}: {} format, {} Hz, {:.1} s, {} samples, {} clipped, {} outliers replaced{}",
                        f.display(),
                        rd["format"].as_str().unwrap_or("?"),
                        rd["fs_hz"].as_f64().map(|x| format!("{x:.2}")).unwrap_or_default(),
                        rd["duration_s"].as_f64().unwrap_or(0.0),
                        rd["samples"],
                        rd["saturated_samples"],
                        v["preprocess"]["outliers_replaced"],
                        rd["notes"]
                            .as_array()
                            .filter(|n| !n.is_empty())
                            .map(|n| format!(
                                "; {}",
                                n.iter().filter_map(|x| x.as_str()).collect::<Vec<_>>().join("; ")
                            ))
                            .unwrap_or_default()
                    );
                }
                Err(e) => eprintln!("error: {e}"),
            }
        }
    }
    for (f, r) in &outcomes {
        if let Ok(v) = r {
            for w in v["read"]["warnings"].as_array().into_iter().flatten() {
                eprintln!(
                    "warning: {}: {}",
                    f.display(),
                    w.as_str().unwrap_or_default()
                );
            }
        }
    }
    if failed > 0 {
        eprintln!("{failed} of {} file(s) failed", outcomes.len());
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

fn analysis_params(
    params: Option<&Path>,
    model: Option<&str>,
    detector: Option<&str>,
    sensor_height_m: Option<f64>,
    no_sta: bool,
) -> Result<AnalysisParams> {
    let base = match params {
        Some(f) => {
            let text =
                std::fs::read_to_string(f).with_context(|| format!("reading {}", f.display()))?;
            toml::from_str::<AnalysisParams>(&text)
                .with_context(|| format!("parameters in {}", f.display()))?
        }
        None => AnalysisParams::default(),
    };
    Ok(base.with_options(model, detector, sensor_height_m, no_sta.then_some(false))?)
}

fn analyze(a: AnalyzeArgs) -> Result<ExitCode> {
    let params = analysis_params(
        a.params.as_deref(),
        a.model.as_deref(),
        a.detector.as_deref(),
        a.sensor_height_m,
        a.no_sta,
    )?;
    let format = a.format.as_deref().map(resolve_format).transpose()?;
    let read = ReadParams::default().check()?;
    let subjects = discover(&a.inputs)?;
    anyhow::ensure!(!subjects.is_empty(), "no subjects found in the inputs");
    // One report/trace file per subject id, checked before any work (issue 19).
    output::names::check_unique(subjects.iter().map(|s| s.subject_id.as_str()))?;
    if a.inputs.is_empty() {
        eprintln!(
            "no input given: analysing the embedded demo cohort ({} subjects)",
            subjects.len()
        );
    }
    let pool = thread_pool(a.jobs)?;
    let stale = ldh_core::io::remove_stale_temp_files(&a.out)?;
    if stale > 0 {
        eprintln!(
            "removed {stale} temporary file(s) of an interrupted earlier run in {}",
            a.out.display()
        );
    }
    // Checked before the analysis so a bad model file fails fast.
    let classifier = a.classifier.as_deref().map(read_model).transpose()?;
    let report_params = ldh_core::report::ReportParams::default().check()?;
    let pb = progress(subjects.len() as u64, "analyze");
    // Subjects are analysed a chunk at a time and their rows streamed to the output files, so
    // memory stays flat however many subjects there are; chunks keep the input order, so the
    // files are the same whatever --jobs is.
    let mut strides = output::TableSink::create(&a.out, "strides", &output::STRIDE_COLUMNS, true)?;
    let mut events = output::TableSink::create(
        &a.out,
        "events",
        &["subject_id", "time_s", "side", "event", "order"],
        false,
    )?;
    let mut recordings = output::TableSink::create(&a.out, "recordings", &[], true)?;
    // Only the rows with something to say are kept for the summary.
    let mut flagged: Vec<output::RecordingRow> = Vec::new();
    let (mut n_rows, mut n_failed, mut valid) = (0usize, 0usize, 0usize);
    let chunk = a
        .batch
        .map(|b| b as usize)
        .unwrap_or((pool.current_num_threads() * 32).max(32));
    for part in subjects.chunks(chunk) {
        let done: Vec<ldh_core::Result<output::Tables>> = pool.install(|| {
            part.par_iter()
                .map(|s| {
                    let r = analyze_subject(s, &params, format.as_ref(), &read);
                    if a.report {
                        let t = ldh_core::report::SubjectTraces::of(&r, report_params.trace());
                        ldh_core::io::write_atomic(
                            a.out.join("traces").join(format!(
                                "{}.json",
                                ldh_core::report::file_stem(&r.subject_id)
                            )),
                            serde_json::to_string(&t)
                                .map_err(|e| ldh_core::LdhError::signal("trace", e.to_string()))?
                                .as_bytes(),
                        )?;
                    }
                    pb.inc(1);
                    Ok(output::Tables::of(std::slice::from_ref(&r)))
                })
                .collect()
        });
        for t in done {
            let t = t?;
            valid += t.strides.iter().filter(|s| s.valid).count();
            strides.push(&t.strides)?;
            events.push(&t.events)?;
            recordings.push(&t.recordings)?;
            n_rows += t.recordings.len();
            n_failed += t.recordings.iter().filter(|r| r.status != "ok").count();
            flagged.extend(
                t.recordings
                    .into_iter()
                    .filter(|r| r.status != "ok" || !r.warnings.is_empty()),
            );
        }
    }
    pb.finish_and_clear();
    let n_strides = strides.rows();
    strides.finish()?;
    events.finish()?;
    recordings.finish()?;
    ldh_core::io::write_atomic(
        a.out.join("params.json"),
        serde_json::to_string_pretty(&params)?.as_bytes(),
    )?;
    if a.report {
        let dir = a.out.join("reports");
        let n = build_reports(
            &a.out,
            &dir,
            classifier.as_ref(),
            None,
            None,
            &report_params,
            &pool,
        )?;
        eprintln!(
            "{n} subject reports and the cohort report (index.html) in {}",
            dir.display()
        );
    }
    eprintln!(
        "analysed {} of {n_rows} recordings ({} subjects, model {}): {n_strides} strides, {valid} valid; results in {}",
        n_rows - n_failed,
        subjects.len(),
        params.attitude.model.as_str(),
        a.out.display()
    );
    for r in flagged.iter().filter(|r| !r.warnings.is_empty()) {
        eprintln!("warning: {} {}: {}", r.subject_id, r.side, r.warnings);
    }
    for f in flagged.iter().filter(|r| r.status != "ok") {
        eprintln!("error: {} {}: {}", f.subject_id, f.side, f.error);
    }
    Ok(if n_failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn read_model(path: &Path) -> Result<ldh_core::ml::ModelFile> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    Ok(ldh_core::ml::ModelFile::from_json(
        &text,
        &path.display().to_string(),
    )?)
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path, what: &str) -> Result<T> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{} is not {what}", path.display()))
}

/// Write the subject reports and the cohort report of an `ldh analyze` output folder; returns
/// the number of subject reports.
fn build_reports(
    results: &Path,
    out: &Path,
    model: Option<&ldh_core::ml::ModelFile>,
    stats: Option<&Path>,
    train: Option<&Path>,
    params: &ldh_core::report::ValidReportParams,
    pool: &rayon::ThreadPool,
) -> Result<usize> {
    use ldh_core::report::{
        self, file_stem, CohortReport, Reference, SubjectReport, SubjectTraces,
    };
    let rows = read_results(results)?;
    let reference = Reference::from_rows(&rows, params);
    let predictions = model.map(|m| m.predict_rows(&rows)).transpose()?;
    let model_desc = model.map(|m| m.describe()).unwrap_or_default();
    let mut preds_by: std::collections::HashMap<&str, Vec<ldh_core::ml::Prediction>> =
        std::collections::HashMap::new();
    for p in predictions.iter().flatten() {
        preds_by
            .entry(p.subject_id.as_str())
            .or_default()
            .push(p.clone());
    }
    let subjects = output::rows_by_subject(&rows);
    let ids: Vec<String> = subjects.iter().map(|(id, _)| id.to_string()).collect();
    output::names::check_unique(ids.iter().map(String::as_str))?;
    let mut groups = output::stride_groups(&results.join("strides.csv"))?.peekable();
    let pb = progress(ids.len() as u64, "report");
    let chunk = (pool.current_num_threads() * 32).max(32);
    for part in subjects.chunks(chunk) {
        // Strides of this chunk's subjects (the file has each subject's rows together, in the
        // order of recordings.json).
        let mut jobs: Vec<SubjectReport> = Vec::with_capacity(part.len());
        for (id, recs) in part {
            let mut strides = Vec::new();
            if let Some(Ok((gid, _))) = groups.peek() {
                if gid == id {
                    strides = groups.next().expect("peeked")?.1;
                }
            } else if let Some(Err(_)) = groups.peek() {
                groups.next().expect("peeked")?;
            }
            jobs.push(SubjectReport {
                subject_id: id.to_string(),
                recordings: recs.iter().map(|r| (*r).clone()).collect(),
                strides,
                traces: None,
                predictions: model.map(|m| {
                    (
                        preds_by.remove(*id).unwrap_or_default(),
                        m.class_names.clone(),
                        model_desc.clone(),
                    )
                }),
            });
        }
        let done: Vec<Result<()>> = pool.install(|| {
            jobs.into_par_iter()
                .map(|mut job| {
                    let stem = file_stem(&job.subject_id);
                    let tf = results.join("traces").join(format!("{stem}.json"));
                    if tf.exists() {
                        let text = std::fs::read_to_string(&tf)
                            .with_context(|| format!("reading {}", tf.display()))?;
                        job.traces =
                            Some(SubjectTraces::from_json(&text, &tf.display().to_string())?);
                    }
                    let html = report::subject_html(&job, &reference, params)?;
                    ldh_core::io::write_atomic(
                        out.join("subjects").join(format!("{stem}.html")),
                        html.as_bytes(),
                    )?;
                    pb.inc(1);
                    Ok(())
                })
                .collect()
        });
        for d in done {
            d?;
        }
    }
    pb.finish_and_clear();
    let cohort = CohortReport {
        offsets: match stats {
            Some(d) => read_json(&d.join("table4.json"), "an ldh stats Table 4")?,
            None => Vec::new(),
        },
        cv: match train {
            Some(d) => read_json(&d.join("cv_results.json"), "an ldh train result")?,
            None => Vec::new(),
        },
        subject_links: ids
            .iter()
            .map(|id| (id.clone(), format!("subjects/{}.html", file_stem(id))))
            .collect(),
        recordings: rows,
    };
    ldh_core::io::write_atomic(
        out.join("index.html"),
        report::cohort_html(&cohort)?.as_bytes(),
    )?;
    Ok(ids.len())
}

fn report(a: ReportArgs) -> Result<ExitCode> {
    let params = match &a.params {
        Some(f) => {
            let text =
                std::fs::read_to_string(f).with_context(|| format!("reading {}", f.display()))?;
            toml::from_str::<ldh_core::report::ReportParams>(&text)
                .with_context(|| format!("report parameters in {}", f.display()))?
        }
        None => ldh_core::report::ReportParams::default(),
    }
    .check()?;
    let model = a.model.as_deref().map(read_model).transpose()?;
    let out = a.out.clone().unwrap_or_else(|| a.results.join("reports"));
    let pool = thread_pool(a.jobs)?;
    ldh_core::io::remove_stale_temp_files(&out)?;
    let n = build_reports(
        &a.results,
        &out,
        model.as_ref(),
        a.stats.as_deref(),
        a.train.as_deref(),
        &params,
        &pool,
    )?;
    eprintln!(
        "{n} subject reports in {} and the cohort report {}",
        out.join("subjects").display(),
        out.join("index.html").display()
    );
    Ok(ExitCode::SUCCESS)
}

fn recording_rows_for(
    inputs: &[PathBuf],
    model: &str,
    pool: &rayon::ThreadPool,
) -> Result<Vec<output::RecordingRow>> {
    let params = analysis_params(None, Some(model), None, None, false)?;
    let read = ReadParams::default().check()?;
    let subjects = discover(inputs)?;
    let results: Vec<SubjectResult> = pool.install(|| {
        subjects
            .par_iter()
            .map(|s| analyze_subject(s, &params, None, &read))
            .collect()
    });
    Ok(output::recording_rows(&results))
}

fn read_results(dir: &Path) -> Result<Vec<output::RecordingRow>> {
    let f = dir.join("recordings.json");
    let text = std::fs::read_to_string(&f).with_context(|| format!("reading {}", f.display()))?;
    serde_json::from_str(&text)
        .with_context(|| format!("{} is not an ldh recordings table", f.display()))
}

fn train(a: TrainArgs) -> Result<ExitCode> {
    use ldh_core::ml::{cv, dataset, Classifier, CvKind, CvParams, Dataset, ModelFile};
    let pool = thread_pool(a.jobs)?;
    let rows = match &a.results {
        Some(d) => read_results(d)?,
        None => recording_rows_for(&a.inputs, "fusion", &pool)?,
    };
    let task: ldh_core::ml::Task = a.task.parse()?;
    let features: Vec<String> = match &a.features {
        Some(f) => f.split(',').map(|s| s.trim().to_string()).collect(),
        None => dataset::default_features(),
    };
    let ds = Dataset::from_recordings(&rows, task, &features)?;
    let attitude_model = rows.first().map(|r| r.model.clone()).unwrap_or_default();
    let clfs: Vec<Classifier> = a
        .classifiers
        .split(',')
        .map(|c| Classifier::from_name(c.trim(), a.seed))
        .collect::<ldh_core::Result<_>>()?;
    let w = |name: &str, text: &str| ldh_core::io::write_atomic(a.out.join(name), text.as_bytes());
    let mut reports = Vec::new();
    pool.install(|| -> Result<()> {
        for kind in [CvKind::Grouped, CvKind::Stratified] {
            let p = CvParams {
                k: a.k,
                repeats: a.repeats,
                seed: a.seed,
                kind,
                top_k: a.top_k,
                permutation_importance: true,
            };
            for c in &clfs {
                reports.push(ldh_core::ml::cross_validate(&ds, c, &p)?);
            }
        }
        Ok(())
    })?;
    // Folds as used (for the scikit-learn comparison script) and the dataset.
    let mut folds_csv = String::from("row_id");
    for kind in ["grouped", "stratified"] {
        for r in 0..a.repeats {
            folds_csv.push_str(&format!(",{kind}_r{r}"));
        }
    }
    folds_csv.push('\n');
    let mut cols: Vec<Vec<usize>> = Vec::new();
    for kind in [CvKind::Grouped, CvKind::Stratified] {
        let p = CvParams {
            k: a.k,
            repeats: a.repeats,
            seed: a.seed,
            kind,
            ..CvParams::default()
        };
        for r in 0..a.repeats {
            cols.push(cv::folds(&ds, &p, r)?);
        }
    }
    for i in 0..ds.len() {
        folds_csv.push_str(&ds.row_ids[i]);
        for c in &cols {
            folds_csv.push_str(&format!(",{}", c[i]));
        }
        folds_csv.push('\n');
    }
    w("dataset.csv", &ds.to_csv())?;
    w("folds.csv", &folds_csv)?;
    let mut md = format!(
        "# Classification ({}, {} rows: {})\n\nFeatures from the `{attitude_model}` attitude model. Min–max scaling{} is fitted on each training fold only.\n\n",
        task.as_str(),
        ds.len(),
        ds.class_names.iter().zip(ds.class_counts()).map(|(n, c)| format!("{c} {n}")).collect::<Vec<_>>().join(", "),
        if a.top_k.is_some() { " and the top-k feature selection" } else { "" }
    );
    if !ds.dropped.is_empty() {
        md.push_str(&format!(
            "Rows left out (a feature missing): {}.\n\n",
            ds.dropped.join("; ")
        ));
    }
    md.push_str("## Cross-validation\n\n**Subject-grouped folds are the primary result**: both sides of a subject always fall on the same side of a split. The paper's stratified folds, beside them, let one side of a subject train the model that tests the other side.\n\n");
    md.push_str(&cv::markdown(&reports));
    md.push_str("\n| classifier | grouped − stratified accuracy |\n|---|---:|\n");
    for c in &clfs {
        let g = reports
            .iter()
            .find(|r| r.classifier == c.name() && r.kind == CvKind::Grouped)
            .map(|r| r.accuracy.mean)
            .unwrap_or(f64::NAN);
        let s = reports
            .iter()
            .find(|r| r.classifier == c.name() && r.kind == CvKind::Stratified)
            .map(|r| r.accuracy.mean)
            .unwrap_or(f64::NAN);
        md.push_str(&format!("| {} | {:+.3} |\n", c.name(), g - s));
    }
    md.push_str(
        "\n## Feature ranking (Table 5): Pearson r with the label\n\n| feature | r |\n|---|---:|\n",
    );
    for (f, r) in cv::ranking(&ds) {
        md.push_str(&format!("| {f} | {r:+.3} |\n"));
    }
    md.push_str("\n## Permutation importance (grouped CV, mean accuracy drop)\n\n| feature |");
    let grouped: Vec<&ldh_core::ml::CvReport> = reports
        .iter()
        .filter(|r| r.kind == CvKind::Grouped)
        .collect();
    for r in &grouped {
        md.push_str(&format!(" {} |", r.classifier));
    }
    md.push_str("\n|---|");
    for _ in &grouped {
        md.push_str("---:|");
    }
    md.push('\n');
    for (j, f) in ds.feature_names.iter().enumerate() {
        md.push_str(&format!("| {f} |"));
        for r in &grouped {
            md.push_str(&format!(" {:+.3} |", r.permutation_importance[j].1));
        }
        md.push('\n');
    }
    for r in &reports {
        let kind = r.kind.as_str();
        let svg = ldh_core::plots::confusion_svg(
            &format!("{} — {kind} {}-fold × {}", r.classifier, r.k, r.repeats),
            &r.class_names,
            &r.confusion,
        )?;
        w(&format!("confusion_{}_{kind}.svg", r.classifier), &svg)?;
    }
    for c in &clfs {
        // The saved model is the cross-validated pipeline: with --top-k, the top features
        // ranked on all rows.
        let final_ds = match a.top_k {
            Some(k) => ds.select_top_k(k)?,
            None => ds.clone(),
        };
        let m = ModelFile::train(&final_ds, c, &attitude_model)?;
        w(&format!("model_{}.json", c.name()), &m.to_json()?)?;
    }
    w("cv_results.json", &serde_json::to_string_pretty(&reports)?)?;
    w("report.md", &md)?;
    println!("{md}");
    eprintln!("report, models and figures in {}", a.out.display());
    Ok(ExitCode::SUCCESS)
}

fn predict(a: PredictArgs) -> Result<ExitCode> {
    let model = read_model(&a.model)?;
    let rows = match &a.results {
        Some(d) => read_results(d)?,
        None => {
            let pool = thread_pool(None)?;
            recording_rows_for(&a.inputs, &model.attitude_model, &pool)?
        }
    };
    let predictions = model.predict_rows(&rows)?;
    let mut out = String::from("subject_id,side,status,predicted_class");
    for c in &model.class_names {
        out.push_str(&format!(",p_{c}"));
    }
    out.push_str(",note\n");
    let mut failed = 0;
    for p in &predictions {
        let probs: Vec<String> = match &p.probabilities {
            Some(v) => v.iter().map(|x| format!("{x:.4}")).collect(),
            None => vec![String::new(); model.class_names.len()],
        };
        let status = if p.predicted_class.is_some() {
            "ok"
        } else {
            failed += 1;
            "error"
        };
        out.push_str(&format!(
            "{},{},{status},{},{},{}\n",
            p.subject_id,
            p.side,
            p.predicted_class.as_deref().unwrap_or(""),
            probs.join(","),
            p.note.replace(',', ";")
        ));
    }
    ldh_core::io::write_atomic(a.out.join("predictions.csv"), out.as_bytes())?;
    print!("{out}");
    eprintln!(
        "decision support, not a diagnosis: predictions in {}",
        a.out.join("predictions.csv").display()
    );
    Ok(if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

fn stats(a: StatsArgs) -> Result<ExitCode> {
    use ldh_core::cohort::{
        offsets, table3, table3_markdown, table3_rows, table4_markdown, Cohort, PARAMETERS,
    };
    let pool = thread_pool(a.jobs)?;
    let mut models: Vec<Vec<output::RecordingRow>> = Vec::new();
    match &a.results {
        Some(dir) => {
            let f = dir.join("recordings.json");
            let text =
                std::fs::read_to_string(&f).with_context(|| format!("reading {}", f.display()))?;
            let rows: Vec<output::RecordingRow> = serde_json::from_str(&text)
                .with_context(|| format!("{} is not an ldh recordings table", f.display()))?;
            anyhow::ensure!(
                a.compare.is_none(),
                "--compare needs the recordings (INPUT), not --results"
            );
            models.push(rows);
        }
        None => {
            models.push(recording_rows_for(&a.inputs, "fusion", &pool)?);
            if let Some(m) = &a.compare {
                anyhow::ensure!(
                    m == "acc",
                    "--compare takes 'acc' (the ACC-only model), got '{m}'"
                );
                models.push(recording_rows_for(&a.inputs, "acc", &pool)?);
            }
        }
    }
    let w = |name: &str, text: &str| ldh_core::io::write_atomic(a.out.join(name), text.as_bytes());
    let mut md = String::from("# Cohort statistics (ldh stats)\n\n");
    let mut all_rows = Vec::new();
    let mut offs = Vec::new();
    for rows in &models {
        let cohort = Cohort::from_rows(rows)?;
        let t3 = table3(&cohort);
        md.push_str(&format!(
            "## Table 3 — model {}\n\n{}\n",
            cohort.model,
            table3_markdown(&t3, &cohort)
        ));
        all_rows.extend(table3_rows(&cohort.model, &t3));
        let off = offsets(&cohort);
        let series = [
            ("LDHH".to_string(), off.z_ldhh.clone()),
            ("LDHE".to_string(), off.z_ldhe.clone()),
            ("H".to_string(), off.z_h.clone()),
        ];
        w(
            &format!("radar_{}.svg", cohort.model),
            &ldh_core::plots::radar_svg(
                &format!("Gait parameters, {} model (z vs healthy)", cohort.model),
                &off.codes,
                &series,
            )?,
        )?;
        if cohort.model == "fusion" {
            for p in PARAMETERS {
                let g = cohort.groups(p.column);
                if g.h.is_empty() {
                    continue;
                }
                let svg = ldh_core::plots::boxplot_svg(
                    &format!("{} — {}", p.code, p.name),
                    &format!("{} ({})", p.name, p.unit),
                    &[
                        ("LDHH".into(), g.ldhh),
                        ("LDHE".into(), g.ldhe),
                        ("H".into(), g.h),
                    ],
                )?;
                w(&format!("box_{}.svg", p.code), &svg)?;
            }
        }
        offs.push(off);
    }
    md.push_str(&format!(
        "## Table 4 — model comparison\n\n{}",
        table4_markdown(&offs)
    ));
    w("table3.csv", &output::to_csv(&all_rows, &[])?)?;
    w("table3.json", &serde_json::to_string_pretty(&all_rows)?)?;
    w("table4.json", &serde_json::to_string_pretty(&offs)?)?;
    w("stats.md", &md)?;
    println!("{md}");
    eprintln!("tables and figures in {}", a.out.display());
    Ok(ExitCode::SUCCESS)
}

fn evaluate(a: EvaluateArgs) -> Result<ExitCode> {
    let subjects = discover(std::slice::from_ref(&a.truth))?;
    let truths: Vec<ldh_core::simulate::SubjectTruth> = subjects
        .iter()
        .map(|s| ldh_core::simulate::read_truth(a.truth.join(&s.subject_id).join("truth.json")))
        .collect::<ldh_core::Result<_>>()?;
    let read = ReadParams::default().check()?;
    let pool = thread_pool(a.jobs)?;
    let mut accs = Vec::new();
    for model in ["fusion", "acc"] {
        let params = analysis_params(None, Some(model), Some(&a.detector), None, true)?;
        let results: Vec<SubjectResult> = pool.install(|| {
            subjects
                .par_iter()
                .map(|s| analyze_subject(s, &params, None, &read))
                .collect()
        });
        accs.push(ldh_core::evaluate::evaluate(&results, &truths));
    }
    println!(
        "Accuracy against ground truth: {} subjects in {}, detector {}\n",
        subjects.len(),
        a.truth.display(),
        a.detector
    );
    println!("{}", ldh_core::evaluate::markdown(&accs));
    if let Some(j) = a.json {
        ldh_core::io::write_atomic(&j, serde_json::to_string_pretty(&accs)?.as_bytes())?;
    }
    Ok(ExitCode::SUCCESS)
}

fn formats(name: Option<String>) -> Result<ExitCode> {
    match name {
        None => {
            for f in FormatSpec::builtins() {
                println!("{:<20} {}", f.name, f.description);
            }
        }
        Some(n) => print!("{}", resolve_format(&n)?.to_toml()),
    }
    Ok(ExitCode::SUCCESS)
}

/// Run the command line with these arguments (the first is the program name).
pub fn run<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let r = match cli.command {
        Command::Analyze(a) => analyze(a),
        Command::Report(a) => report(a),
        Command::Evaluate(a) => evaluate(a),
        Command::Stats(a) => stats(a),
        Command::Train(a) => train(a),
        Command::Predict(a) => predict(a),
        Command::Simulate(a) => simulate(a),
        Command::Inspect(a) => inspect(a),
        Command::Formats { name } => formats(name),
        Command::Demo { out } => demo_cmd::write_demo(&out),
    };
    match r {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
