//! The command line's arguments (clap derive): one struct per command. Choices are the core's
//! enums (`clap::ValueEnum` behind ldh-core's `clap` feature), never strings parsed here.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use ldh_core::attitude::AttitudeModel;
use ldh_core::events::EventDetector;
use ldh_core::ml::{ClassifierKind, Task};
use ldh_core::Setting;
use ldh_sim::family_b::Family;

/// Gait assessment for lumbar disc herniation from two shank-worn IMUs.
///
/// Typical use: `ldh simulate --out demo` to make a cohort, `ldh inspect FILE` to check
/// that a vendor export is read correctly.
#[derive(Debug, Parser)]
#[command(name = "ldh", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    /// How much to print (`-q`, `-v`), for every command.
    #[command(flatten)]
    pub verbosity: Verbosity,
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// `-q` / `-v`, accepted before or after the command.
#[derive(Debug, Clone, Copy, Default, Args)]
pub struct Verbosity {
    /// Print only errors (no progress, no summary, no warnings).
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Also print every recording's warnings and the reader's notes.
    #[arg(short, long, global = true)]
    pub verbose: bool,
}

/// Shells `ldh completions` writes a completion script for.
pub use clap_complete::Shell;

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Analyse recordings: events, strides and the 12 gait parameters per side.
    ///
    /// INPUT is a manifest CSV, a cohort folder (with manifest.csv or subject folders), a
    /// subject folder with left.csv and right.csv, or a subject's two files. Without INPUT the
    /// embedded demo cohort is analysed. Writes strides.csv/.json, recordings.csv/.json and
    /// events.csv (both legs' HS and TO in one time-ordered sequence) to
    /// --out; a recording that fails is listed with its reason, the others are still written,
    /// and the exit code is 1.
    ///
    /// --out holds one run: a re-run replaces the whole earlier result set (reports and traces
    /// included), and ldh-run.json, written last, lists every file of the run (a folder without a
    /// complete ldh-run.json holds no finished run). Files no ldh run wrote, or a symbolic link
    /// inside --out, make the run refuse (exit 2), naming them; nothing is deleted or written
    /// through a link.
    Analyze(AnalyzeArgs),
    /// Walking in daily life from two shank sensors worn for days (docs/free-living.md).
    ///
    /// INPUT as for `analyze`: a subject's two files (left, then right), a subject folder, or
    /// a manifest with one row per person and monitoring period (`visit`). Each recording is
    /// streamed (minutes to weeks, memory does not grow with its length): wear, posture,
    /// cycling and running are found per window, walking bouts are analysed by the same
    /// pipeline as `analyze`, the two sensors' clock drift is estimated. Writes bouts.csv,
    /// days.csv, summary.csv and periods.csv to --out, changes.csv when a person has more
    /// than one period, and each person's page week_<subject>.html. A person whose recordings cannot
    /// be read is a summary row with the error (exit 1); the others are written.
    Monitor(MonitorArgs),
    /// Score the pipeline against simulator ground truth: `ldh simulate` output (with
    /// truth.json per subject) is analysed with both attitude models and the event and
    /// stride accuracy is printed as a Markdown table.
    Evaluate(EvaluateArgs),
    /// Agreement of an `ldh analyze` run with a laboratory's reference system (force plates,
    /// an instrumented walkway, motion capture).
    ///
    /// RESULTS is an `ldh analyze` output folder; each --reference a long CSV of events
    /// (subject_id[,trial_id],side,event,time_s) or of parameters (subject_id[,trial_id],side
    /// and parameter columns such as stride_time_s, per stride with time_s or stride, else per
    /// recording); docs/agreement.md. Events are matched one-to-one within --tolerance-s; each
    /// parameter gets bias, limits of agreement, MAE, ICC and Pearson's r per stride and per
    /// recording. Writes agreement.csv, agreement.json and agreement.md to --out and prints the
    /// Markdown. A bad reference file is refused, naming file, line and column, before anything
    /// is written (exit 2).
    Agree(AgreeArgs),
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
    /// <OUT>/index.html (the cohort) and <OUT>/subjects/<subject>.html (and <OUT>/ldh-run.json,
    /// last). Only files the analysis' ldh-run.json lists are used: a folder whose run did not
    /// finish is refused, and a trace that is not its run's is left out with a warning. <OUT>
    /// holds one report, as --out of `analyze` holds one run. With --model the
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
    /// Explain the output columns (recordings.csv, strides.csv, events.csv): unit and meaning.
    ///
    /// Without NAME the whole dictionary is printed as Markdown (docs/columns.md is the same).
    Columns {
        /// A column's name, e.g. wqk_deg; omit to print them all.
        name: Option<String>,
    },
    /// Write the embedded demo cohort (the default data of `ldh analyze`) to a folder.
    Demo {
        /// Output folder.
        #[arg(short, long, default_value = "ldh-demo")]
        out: PathBuf,
    },
    /// Print a shell completion script: `ldh completions bash > ~/.local/share/bash-completion/completions/ldh`.
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: Shell,
    },
    /// Print a manual page (roff): `ldh man > ldh.1 && man ./ldh.1`, one command's with
    /// `ldh man analyze` (the page `ldh-analyze.1`), or write every page with `--out DIR`.
    Man {
        /// A command whose page to print (`analyze`, `inspect`…); omit for the page of `ldh`.
        command: Option<String>,
        /// Write every page (`ldh.1`, `ldh-analyze.1`, …) into this folder instead (made if
        /// needed); `MANPATH=DIR/.. man ldh-analyze` then finds them when DIR is `…/man1`.
        #[arg(short, long, value_name = "DIR", conflicts_with = "command")]
        out: Option<PathBuf>,
    },
}

#[derive(Debug, Args)]
pub struct AnalyzeArgs {
    /// Inputs (see above); none: the embedded demo cohort.
    pub inputs: Vec<PathBuf>,
    /// Output folder: new, empty, or holding an earlier ldh run (replaced whole; see above).
    #[arg(short, long, default_value = "ldh-out")]
    pub out: PathBuf,
    /// Attitude model: fusion (adaptive Kalman; default) or acc (accelerometer tilt only).
    #[arg(long, value_enum)]
    pub model: Option<AttitudeModel>,
    /// Event detector: gyro-bracket (default), gyro-landmarks, gyro-zero-crossing, salarian or
    /// pitch-peaks (the paper's).
    #[arg(long, value_enum)]
    pub detector: Option<EventDetector>,
    /// Input sensor format: a built-in name or a TOML column map (a regular file of at most
    /// 1 MB); default: detect. (`--format` is accepted as an alias for one release.)
    #[arg(long = "input-format", alias = "format", value_name = "FORMAT")]
    pub format: Option<String>,
    /// Sensor height above the ankle joint, m, for subjects whose manifest row has none. Not
    /// given: 0.10 m is assumed and a stride length that depends on it by more than 15 % is
    /// withheld (warning sensor_height_unknown; docs/input.md).
    #[arg(long)]
    pub sensor_height_m: Option<f64>,
    /// The left sensor's height above the ankle joint, m, for subjects whose manifest row gives
    /// none for the left leg (a leg's own height wins over --sensor-height-m; the two may not
    /// differ).
    #[arg(long)]
    pub left_sensor_height_m: Option<f64>,
    /// The right sensor's height above the ankle joint, m (as --left-sensor-height-m).
    #[arg(long)]
    pub right_sensor_height_m: Option<f64>,
    /// Subject id of two files given directly (default: the common stem of their names).
    #[arg(long)]
    pub subject: Option<String>,
    /// Where the walks happened, for subjects whose manifest row does not say: overground
    /// (default; turns are detected) or treadmill (no turns).
    #[arg(long, value_enum)]
    pub setting: Option<ldh_core::Setting>,
    /// All analysis parameters as a TOML file (docs/parameters.md; a regular file of at most
    /// 1 MB); the flags above, when given, override it.
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Skip the Lyapunov exponent (STA); the tables and pages then say "not computed: turned
    /// off for this run".
    #[arg(long)]
    pub no_sta: bool,
    /// Also write the HTML reports (as `ldh report`) to <OUT>/reports, and the signal traces
    /// they plot to <OUT>/traces.
    #[arg(long)]
    pub report: bool,
    /// With --report: a test–retest reliability table (reliability.csv of `ldh stats
    /// --reliability`); a change between visits is marked only beyond its MDC95.
    #[arg(long, value_name = "FILE", requires = "report")]
    pub reliability: Option<PathBuf>,
    /// With --report: a model saved by `ldh train` whose output the subject reports show (a
    /// regular file of at most 256 MB).
    #[arg(long, requires = "report")]
    pub classifier: Option<PathBuf>,
    /// Subjects analysed between two writes of the output (default 32 per worker thread).
    /// Memory grows with it, not with the number of subjects; the output does not depend on it.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub batch: Option<u64>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// Print the end-of-run summary on stdout as JSON (for scripts) instead of a sentence.
    #[arg(long)]
    pub json: bool,
    /// Largest sensor file read, MB (default 256); larger files are refused before reading, and
    /// so is a line longer than 64 KiB.
    #[arg(long, value_name = "MB")]
    pub max_file_size_mb: Option<f64>,
    /// Most samples (data rows) in one sensor file (default 2500000: 6.9 h at 100 Hz); the
    /// analysis keeps about 150 bytes per sample, so longer files are refused while being read.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_samples: Option<u64>,
    /// Print the wall time of each stage (read, preprocess, align, attitude, events, strides,
    /// STA, write), summed over the run, as a table on stderr; with --json also as "timings" in
    /// the summary. The outputs are unchanged.
    #[arg(long)]
    pub timings: bool,
}

#[derive(Debug, Args)]
pub struct MonitorArgs {
    /// Inputs (see above).
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output folder.
    #[arg(short, long, default_value = "ldh-monitor")]
    pub out: PathBuf,
    /// Subject id of two files given directly (default: the common stem of their names).
    #[arg(long)]
    pub subject: Option<String>,
    /// Monitoring parameters as a TOML file (the fields of `MonitorParams`, docs/free-living.md).
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
}

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Output folder of `ldh analyze`.
    pub results: PathBuf,
    /// Where to write the reports (default: <RESULTS>/reports).
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// A model saved by `ldh train`: its output goes into each subject's report (a regular file
    /// of at most 256 MB).
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Output folder of `ldh stats` (table4.json) for the cohort report.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Output folder of `ldh train` (cv_results.json) for the cohort report.
    #[arg(long)]
    pub train: Option<PathBuf>,
    /// A test–retest reliability table (reliability.csv of `ldh stats --reliability`): the
    /// subject pages mark a change between visits only when it exceeds its MDC95.
    #[arg(long, value_name = "FILE")]
    pub reliability: Option<PathBuf>,
    /// Report parameters as TOML (docs/reports.md; a regular file of at most 1 MB).
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
}

#[derive(Debug, Args)]
pub struct StatsArgs {
    /// Inputs as for `analyze` (they need groups: a manifest or `ldh simulate` output).
    pub inputs: Vec<PathBuf>,
    /// Read recordings.json from an `ldh analyze` output folder instead of analysing.
    #[arg(long, conflicts_with = "inputs")]
    pub results: Option<PathBuf>,
    /// Also analyse with this model and compare (Table 4): `acc`.
    #[arg(long, value_enum, conflicts_with = "results")]
    pub compare: Option<CompareModel>,
    /// Test–retest reliability instead of the group statistics: per parameter ICC(2,1) and
    /// ICC(3,1) with 95 % intervals, SEM, MDC95, within-subject CV and variance components, from
    /// each person's repeated trials (manifest trial_id; the value of a trial is the mean of both
    /// legs). Writes only reliability.csv, reliability.json and reliability.md and prints the
    /// table; groups are not needed (docs/agreement.md, "Reliability table").
    #[arg(long, conflicts_with = "compare")]
    pub reliability: bool,
    /// Output folder.
    #[arg(short, long, default_value = "ldh-stats")]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
}

#[derive(Debug, Args)]
pub struct TrainArgs {
    /// Inputs as for `analyze` (they need groups: a manifest or `ldh simulate` output).
    pub inputs: Vec<PathBuf>,
    /// Read recordings.json from an `ldh analyze` output folder instead of analysing.
    #[arg(long, conflicts_with = "inputs")]
    pub results: Option<PathBuf>,
    /// Task: three-class (LDHH / LDHE / H) or binary (LDHE vs H).
    #[arg(long, value_enum, default_value = "three-class")]
    pub task: Task,
    /// Classifiers, comma-separated: rf, svm, mlp.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "rf,svm,mlp")]
    pub classifiers: Vec<ClassifierKind>,
    /// Folds (lowered, with a note, to the rows of the smallest class when it has fewer).
    #[arg(long, default_value_t = 10)]
    pub k: usize,
    /// Repeats of the k-fold split.
    #[arg(long, default_value_t = 10)]
    pub repeats: usize,
    /// Seed of folds and models.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Keep the k features with the largest |Pearson r| inside each training fold.
    #[arg(long)]
    pub top_k: Option<usize>,
    /// Features (comma-separated columns of recordings.csv); default: those of the 13
    /// parameters measured in enough rows (--min-feature-coverage), with a note naming the rest.
    #[arg(long, value_delimiter = ',')]
    pub features: Option<Vec<String>>,
    /// Share of the rows a default feature must be measured in to be kept, in (0, 1].
    #[arg(long, default_value_t = 0.9, conflicts_with = "features")]
    pub min_feature_coverage: f64,
    /// Output folder.
    #[arg(short, long, default_value = "ldh-train")]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
}

#[derive(Debug, Args)]
pub struct PredictArgs {
    /// A model file written by `ldh train` (a regular file of at most 256 MB).
    #[arg(long)]
    pub model: PathBuf,
    /// Inputs as for `analyze`; or --results.
    pub inputs: Vec<PathBuf>,
    /// Read recordings.json from an `ldh analyze` output folder instead of analysing.
    #[arg(long, conflicts_with = "inputs")]
    pub results: Option<PathBuf>,
    /// Output folder.
    #[arg(short, long, default_value = "ldh-predict")]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct EvaluateArgs {
    /// A folder written by `ldh simulate` (manifest.csv and truth.json per subject).
    #[arg(long)]
    pub truth: PathBuf,
    /// Event detector to score.
    #[arg(long, value_enum, default_value = "gyro-bracket")]
    pub detector: EventDetector,
    /// Also write the accuracy as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Also write every steady stride's errors as CSV here (one row per true stride and model:
    /// HS, TO, stride time, stance and stride length errors, the reported length, valid and
    /// reason; empty cells where nothing was matched or a value was withheld).
    #[arg(long)]
    pub strides_csv: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
}

#[derive(Debug, Args)]
pub struct AgreeArgs {
    /// The output folder of `ldh analyze` (recordings.json, strides.csv, events.csv).
    pub results: PathBuf,
    /// A reference file (CSV); repeat for events and parameters in separate files.
    #[arg(long, required_unless_present = "walkway")]
    pub reference: Vec<PathBuf>,
    /// A per-step walkway export (GAITRite / Zeno style, one row per footfall), read through
    /// --walkway-map; repeatable.
    #[arg(long, requires = "walkway_map")]
    pub walkway: Vec<PathBuf>,
    /// The column map (TOML) of the --walkway exports: which column is the foot, the heel
    /// strike, the toe off and each stride parameter, in which unit (docs/agreement.md).
    #[arg(long)]
    pub walkway_map: Option<PathBuf>,
    /// The subject of the --walkway exports, when their map names no subject column.
    #[arg(long)]
    pub subject_id: Option<String>,
    /// The trial of the --walkway exports, when their map names no trial column.
    #[arg(long)]
    pub trial_id: Option<String>,
    /// Output folder (created if missing).
    #[arg(short, long, default_value = "ldh-agree")]
    pub out: PathBuf,
    /// Largest |ldh − reference| time of two matched events, s [default: 0.2, or --params].
    #[arg(long)]
    pub tolerance_s: Option<f64>,
    /// Clock offset ldh − reference, s, for the trials whose reference gives no offset_s; or
    /// `estimate` to estimate it per trial from the events (refused when ambiguous). Default:
    /// the clocks agree.
    #[arg(long)]
    pub offset_s: Option<ldh_core::agreement::OffsetMode>,
    /// Agreement parameters as TOML (loa_sd_multiplier, confidence_level, tolerance_s,
    /// max_clock_offset_s, clock_offset_step_s).
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Also write the analysis parameters of the compared run with its events calibrated to
    /// this reference (each event kind shifted by minus its mean error; at least 20 matched
    /// events of each kind): `ldh analyze --params FILE` then times events like the reference.
    #[arg(long, value_name = "FILE")]
    pub write_params: Option<PathBuf>,
    /// What the reference system is, for the calibration's description in reports (e.g.
    /// "force plates"); the reference files are named beside it.
    #[arg(long, value_name = "TEXT", requires = "write_params")]
    pub reference_system: Option<String>,
}

#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Output folder (created if missing).
    #[arg(short, long)]
    pub out: PathBuf,
    /// Number of healthy subjects (default 2; with --free-living 1).
    #[arg(long)]
    pub healthy: Option<usize>,
    /// Number of LDH subjects (default 2; with --free-living 0).
    #[arg(long)]
    pub ldh: Option<usize>,
    /// Free-living days instead of lab walks: per subject a day (or --days N, --hours H) of
    /// two shank sensors at home — nights, non-wear, sitting, standing, walking bouts, stairs,
    /// running, cycling, fidgeting — streamed to <OUT>/<subject>/left.csv, right.csv with
    /// truth_bouts.csv and truth.json; the right sensor's clock drifts (--drift-ppm).
    /// docs/free-living.md.
    #[arg(long)]
    pub free_living: bool,
    /// With --free-living: days per subject (default 1).
    #[arg(long, requires = "free_living", conflicts_with = "hours")]
    pub days: Option<f64>,
    /// With --free-living: hours per subject.
    #[arg(long, requires = "free_living")]
    pub hours: Option<f64>,
    /// With --free-living: the right clock's drift, ppm (default: drawn per subject in
    /// ±20–50 ppm).
    #[arg(long, requires = "free_living", allow_hyphen_values = true)]
    pub drift_ppm: Option<f64>,
    /// Family a: number of slow, severely affected LDH subjects (0.28–0.75 m/s, strides of
    /// 1.35–2.0 s), written after the others as S01…; they count in the `ldh` group.
    #[arg(long, default_value_t = 0)]
    pub slow_ldh: usize,
    /// Recording length per subject, seconds.
    #[arg(long, default_value_t = 25.0)]
    pub seconds: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Sampling rate of the simulated sensors, Hz.
    #[arg(long, default_value_t = 100.0)]
    pub rate_hz: f64,
    /// Walk straight only (no 180° turn in the middle).
    #[arg(long)]
    pub no_turn: bool,
    /// Family a: a treadmill walk whose belt starts up over this many seconds (strides 25 %
    /// longer at the first step, steady at the end; needs --no-turn). Default 0: no start-up.
    #[arg(long, default_value_t = 0.0)]
    pub ramp_s: f64,
    /// Noise-free sensors without bias, quantisation or misalignment.
    #[arg(long)]
    pub ideal: bool,
    /// Family a: the accelerometer's range (±), g (default 8, the paper's; 2 clips the shank's
    /// heel-strike decelerations as HuGaDB's and family b's ±2 g devices do).
    #[arg(long)]
    pub acc_range_g: Option<f64>,
    /// Lowest LDH severity (0–1): each LDH subject's effects are scaled by a severity drawn in
    /// [this, 1]; 1 (default) makes every LDH subject fully affected.
    #[arg(long, default_value_t = 1.0)]
    pub ldh_severity_min: f64,
    /// Output format: a built-in format name or a TOML file (with --free-living: `ldh`, ldh's
    /// CSV).
    #[arg(long, default_value = "ldh")]
    pub format: String,
    /// Simulator family: a (default, the original model) or b (the independently written family:
    /// other published curves, rolling foot, slow hemiparetic gait as the `ldh` group, treadmill
    /// walks, any sensor rotation, scale faults, clipping; docs/simulator.md).
    #[arg(long, value_enum, default_value_t = Family::A)]
    pub family: Family,
    /// Family a: trials per subject, a retest cohort: each person walks N times with their own
    /// gait and a day-to-day variation (--day-to-day-sd-fraction), written to
    /// <OUT>/<subject>/T1/… with a trial_id column in the manifest. Default 1.
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub trials: usize,
    /// Family a, with --trials ≥ 2: day-to-day SD of each person's mean stride time and mean
    /// stride length between trials, as a fraction of the person's own value (default 0.03).
    #[arg(long, value_name = "FRACTION")]
    pub day_to_day_sd_fraction: Option<f64>,
    /// Also write the cohort's true events and strides as reference files
    /// (<OUT>/reference_events.csv, reference_strides.csv, with trial_id for --trials ≥ 2), the
    /// files a lab's force plates would give, to try `ldh agree` end to end.
    #[arg(long)]
    pub reference: bool,
    /// Family b: every subject's mean walking speed, m/s (default: drawn per subject).
    #[arg(long)]
    pub speed_mps: Option<f64>,
    /// Family b: overground or treadmill for every subject (default: about 30 % on a treadmill).
    #[arg(long)]
    pub setting: Option<Setting>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
}

#[derive(Debug, Args)]
pub struct InspectArgs {
    /// Sensor CSV files.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Input sensor format: a built-in name or a TOML column map (a regular file of at most
    /// 1 MB); default: detect a built-in format. (`--format` is accepted as an alias for one
    /// release.)
    #[arg(long = "input-format", alias = "format", value_name = "FORMAT")]
    pub format: Option<String>,
    /// Longest gap in the timestamps bridged by interpolation, s.
    #[arg(long, default_value_t = 0.2)]
    pub max_gap_s: f64,
    /// Refuse recordings with longer gaps instead of keeping the longest segment.
    #[arg(long)]
    pub reject_gaps: bool,
    /// Largest sensor file read, MB (default 256); larger files are refused before reading, and
    /// so is a line longer than 64 KiB.
    #[arg(long, value_name = "MB")]
    pub max_file_size_mb: Option<f64>,
    /// Most samples (data rows) in one sensor file (default 2500000: 6.9 h at 100 Hz); the
    /// analysis keeps about 150 bytes per sample, so longer files are refused while being read.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_samples: Option<u64>,
    /// Print JSON instead of one line per file.
    #[arg(long)]
    pub json: bool,
}

/// The model `ldh stats --compare` analyses beside fusion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CompareModel {
    /// The accelerometer-only attitude model.
    Acc,
}

impl From<CompareModel> for AttitudeModel {
    fn from(c: CompareModel) -> AttitudeModel {
        match c {
            CompareModel::Acc => AttitudeModel::Acc,
        }
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    /// `-o` is `--out` and `-j` is `--jobs` in every command that has them (the README says so).
    #[test]
    fn out_and_jobs_have_their_short_flag_in_every_command() {
        let mut checked = Vec::new();
        for sub in super::Cli::command().get_subcommands() {
            for arg in sub.get_arguments() {
                let short = match arg.get_long() {
                    Some("out") => 'o',
                    Some("jobs") => 'j',
                    _ => continue,
                };
                assert_eq!(arg.get_short(), Some(short), "ldh {}", sub.get_name());
                checked.push(format!("{} -{short}", sub.get_name()));
            }
        }
        assert!(checked.iter().any(|c| c == "man -o"), "{checked:?}");
    }
}
