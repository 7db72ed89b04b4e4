//! One file per command: each reads its arguments, calls into `ldh_core` and writes what the
//! core returned. Shared here: thread pool, progress bar, parameter files, reading inputs.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};

use ldh_core::attitude::AttitudeModel;
use ldh_core::events::EventDetector;
use ldh_core::io::{FormatSpec, ReadParams};
use ldh_core::output::RecordingRow;
use ldh_core::pipeline::{discover, Analysis, AnalysisParams};

use crate::args::Verbosity;

/// Print an informational line on stderr, unless `-q` was given.
macro_rules! note {
    ($($t:tt)*) => {
        if !$crate::commands::verbosity().quiet {
            eprintln!($($t)*);
        }
    };
}
pub(crate) use note;

pub mod agree;
pub mod analyze;
pub mod columns;
pub mod completions;
pub mod demo;
pub mod evaluate;
pub mod formats;
pub mod inspect;
pub mod monitor;
pub mod predict;
pub mod report;
pub mod simulate;
pub mod stats;
pub mod train;

/// Resolve `--format`: a built-in name or a path to a TOML file.
pub fn resolve_format(name: &str) -> Result<FormatSpec> {
    Ok(FormatSpec::resolve(name)?)
}

static VERBOSITY: OnceLock<Verbosity> = OnceLock::new();

/// Set `-q` / `-v` for the run (once, before the command runs).
pub fn set_verbosity(v: Verbosity) {
    let _ = VERBOSITY.set(v);
}

/// `-q` / `-v` of this run.
pub fn verbosity() -> Verbosity {
    VERBOSITY.get().copied().unwrap_or_default()
}

/// Refuse an output folder that is an existing file, before any work (exit 2).
pub fn check_out_dir(out: &Path) -> Result<()> {
    anyhow::ensure!(
        !out.exists() || out.is_dir(),
        "--out {}: exists and is not a folder",
        out.display()
    );
    Ok(())
}

/// A progress bar on stderr when it is a terminal (and not `-q`), hidden otherwise.
pub fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = if std::io::IsTerminal::is_terminal(&std::io::stderr()) && !verbosity().quiet {
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

/// `n` and the word, plural unless `n` is 1: "1 subject", "2 subjects", "0 strides".
pub fn count(n: usize, word: &str) -> String {
    if n == 1 {
        format!("1 {word}")
    } else {
        format!("{n} {word}s")
    }
}

/// The worker pool of `--jobs` (default: all cores).
pub fn thread_pool(jobs: Option<usize>) -> Result<rayon::ThreadPool> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(j) = jobs {
        anyhow::ensure!(j >= 1, "--jobs must be at least 1");
        let (j, warning) = ldh_core::pipeline::bounded_jobs(j);
        if let Some(w) = warning {
            eprintln!("warning: {w}");
        }
        b = b.num_threads(j);
    }
    Ok(b.build()?)
}

/// Build the HTML reports of `results` into `out` on `pool` with a progress bar, and print the
/// builder's warnings (`ldh analyze --report`, `ldh report`).
pub fn build_reports(
    pool: &rayon::ThreadPool,
    results: &ldh_report::RunResults,
    out: &Path,
    src: ldh_report::BuildSources<'_>,
    params: &ldh_report::ValidReportParams,
) -> Result<ldh_report::BuildSummary> {
    let pb = progress(0, "report");
    let built = pool.install(|| {
        ldh_report::build(results, out, src, params, &|n| {
            pb.set_length(n as u64);
            pb.inc(1)
        })
    })?;
    pb.finish_and_clear();
    for w in &built.warnings {
        eprintln!("warning: {w}");
    }
    Ok(built)
}

/// Read a TOML parameter file into `T`: a regular file of at most
/// [`ldh_core::io::MAX_PARAMS_MB`] MB (a FIFO or device is refused without blocking); the
/// parser's message, which quotes the file, cut to a few lines.
pub fn read_toml<T: serde::de::DeserializeOwned>(f: &Path, what: &str) -> Result<T> {
    let text = ldh_core::io::read_text_limited(f, ldh_core::io::MAX_PARAMS_MB, "a parameter file")?;
    toml::from_str::<T>(&text).map_err(|e| {
        let reason = e.to_string();
        let reason = ldh_core::error::clip_to(&reason, ldh_core::error::REASON_CHARS);
        anyhow::anyhow!("{what} in {}: {reason}", f.display())
    })
}

/// Analysis parameters: the `--params` file (or the defaults) with the flags on top.
pub fn analysis_params(
    params: Option<&Path>,
    model: Option<AttitudeModel>,
    detector: Option<EventDetector>,
    sensor_height_m: Option<f64>,
    no_sta: bool,
) -> Result<AnalysisParams> {
    let base = match params {
        Some(f) => read_toml::<AnalysisParams>(f, "parameters")?,
        None => AnalysisParams::default(),
    };
    Ok(base.with_options(
        model.map(|m| m.as_str()),
        detector.map(|d| d.as_str()),
        sensor_height_m,
        no_sta.then_some(false),
    )?)
}

/// Per-recording rows of `inputs` analysed with `model` (default parameters otherwise).
pub fn rows_for(
    inputs: &[PathBuf],
    model: AttitudeModel,
    pool: &rayon::ThreadPool,
) -> Result<Vec<RecordingRow>> {
    let params = analysis_params(None, Some(model), None, None, false)?;
    let read = ReadParams::default().check()?;
    let subjects = discover(inputs)?;
    let pb = progress(
        subjects.len() as u64,
        &format!("analyze ({})", model.as_str()),
    );
    let done = || pb.inc(1);
    let analysis = Analysis::new(params.check()?).read(read).progress(&done);
    let results = pool.install(|| analysis.many(&subjects).results())?;
    pb.finish_and_clear();
    Ok(ldh_core::output::recording_rows(&results))
}

/// Per-recording rows from `--results` (an `ldh analyze` folder) or else from the inputs.
pub fn rows_from(
    results: Option<&Path>,
    inputs: &[PathBuf],
    model: AttitudeModel,
    pool: &rayon::ThreadPool,
) -> Result<Vec<RecordingRow>> {
    match results {
        Some(d) => Ok(ldh_core::output::read_recordings(d)?),
        None => rows_for(inputs, model, pool),
    }
}

/// Write `(name, content)` files into `dir`.
pub fn write_files(dir: &Path, files: &[(String, String)]) -> Result<()> {
    for (name, text) in files {
        ldh_core::io::write_atomic(dir.join(name), text.as_bytes())?;
    }
    Ok(())
}
