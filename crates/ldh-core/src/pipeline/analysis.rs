//! One analysis object: the checked parameters of a run ([`ValidAnalysisParams`], from
//! [`crate::ParamGuard::check`]) and its options, with one verb per scale — a leg, a pair of
//! legs already read, a subject (read, then paired), many subjects (in memory or streamed into
//! an output folder). The model is linfa's `params → checked params → fit`
//! (`src/param_guard.rs`) and mobgap's one pipeline composing one step after another
//! (`mobgap/pipeline/_mobilised_pipeline.py`).
//!
//! ```
//! use ldh_core::pipeline::{demo_inputs, Analysis, AnalysisParams};
//!
//! let params = AnalysisParams { compute_sta: false, ..AnalysisParams::default() };
//! let analysis = Analysis::new(params.check()?).jobs(1);
//! let subjects = demo_inputs()?;
//! let results = analysis.many(&subjects[..1]).results()?;
//! assert!(results[0].left.is_ok());
//! # Ok::<(), ldh_core::LdhError>(())
//! ```

use super::*;
use crate::error::LdhError;
use crate::io::{FormatSpec, ValidReadParams};
use crate::output::OutputRun;
use crate::recording::{Recording, Side};
use crate::timings::StageTimings;

/// A run's analysis: checked parameters and options (reader limits, a vendor format, worker
/// threads, progress, one-leg mode). Built once, used for any number of legs or subjects; the
/// options change how the work is done or what is said about it, never a result (except
/// [`Analysis::one_leg`], which says what a leg without its partner cannot vouch for).
#[derive(Clone)]
pub struct Analysis<'a> {
    params: ValidAnalysisParams,
    read: ValidReadParams,
    format: Option<FormatSpec>,
    jobs: Option<usize>,
    progress: Option<&'a (dyn Fn() + Sync)>,
    one_leg: bool,
}

impl std::fmt::Debug for Analysis<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Analysis")
            .field("params", &self.params)
            .field("read", &self.read)
            .field("format", &self.format)
            .field("jobs", &self.jobs)
            .field("progress", &self.progress.is_some())
            .field("one_leg", &self.one_leg)
            .finish()
    }
}

impl Analysis<'static> {
    /// An analysis with these checked parameters, the default reader limits
    /// ([`crate::io::ReadParams::default`]), formats detected per file, the current rayon pool,
    /// no progress, and legs analysed as part of a pair.
    pub fn new(params: ValidAnalysisParams) -> Self {
        Analysis {
            params,
            read: ValidReadParams::default(),
            format: None,
            jobs: None,
            progress: None,
            one_leg: false,
        }
    }
}

impl<'a> Analysis<'a> {
    /// With these checked reader limits (file size, samples, gaps, rates).
    pub fn read(mut self, read: ValidReadParams) -> Self {
        self.read = read;
        self
    }
    /// Every file read in this vendor format (`None`: detected per file; a manifest row's own
    /// format wins).
    pub fn format(mut self, format: Option<FormatSpec>) -> Self {
        self.format = format;
        self
    }
    /// Many subjects on a pool of `n_jobs` threads (0 = one per core) instead of the current
    /// rayon pool; results are identical whatever the count.
    pub fn jobs(mut self, n_jobs: usize) -> Self {
        self.jobs = Some(n_jobs);
        self
    }
    /// Call `done()` after each subject of [`Analysis::many`] (progress).
    pub fn progress<'b>(self, done: &'b (dyn Fn() + Sync)) -> Analysis<'b>
    where
        'a: 'b,
    {
        Analysis {
            progress: Some(done),
            ..self
        }
    }
    /// [`Analysis::leg`] on a leg with no other leg to pair it with (Python's
    /// `analyze_recording`): what only the other leg could vouch for is withheld with the
    /// reason — stride length variability (`sv_unchecked`,
    /// [`quality::check_length_variability`]).
    pub fn one_leg(mut self) -> Self {
        self.one_leg = true;
        self
    }
    /// The checked parameters.
    pub fn params(&self) -> &ValidAnalysisParams {
        &self.params
    }

    /// Analyse one recording up to its strides and parameters, with no other leg: its toe offs
    /// placed from its own landmarks ([`crate::events::place_bilateral`] needs both legs for the
    /// default detector), so a leg analysed alone may differ from the same leg in
    /// [`Analysis::pair`]. Only what belongs to the recording (its rate, for preprocessing) and
    /// to the subject (`sensor_height_m`) is checked here.
    pub fn leg(
        &self,
        rec: &Recording,
        side: Side,
        sensor_height_m: Option<f64>,
    ) -> Result<AnalysedLeg> {
        let v = &self.params;
        let t = &mut StageTimings::default();
        let mut front = leg_front(rec, v, t)?;
        // This leg's events by itself (a subject places both legs' together).
        crate::events::place_bilateral(Some(&mut front.events), None, v.events());
        let mut out = leg_back(rec, side, v, sensor_height_m, front, t)?;
        if self.one_leg {
            quality::withhold_unchecked(&mut out.leg, "no other leg was given");
        }
        Ok(out)
    }

    /// Analyse one subject from recordings already read (or their read errors): both legs,
    /// paired for step time and frequency; a treadmill walk (`input.setting`) has no turns.
    /// Errors are per leg and name the file.
    pub fn pair(&self, input: &SubjectInput, left: LoadedLeg, right: LoadedLeg) -> SubjectResult {
        match input.setting {
            Some(crate::recording::Setting::Treadmill) => {
                super::subject::pair_legs(input, left, right, &self.params.for_treadmill())
            }
            _ => super::subject::pair_legs(input, left, right, &self.params),
        }
    }

    /// Analyse one subject: read both legs (the read time is part of the result's timings),
    /// then [`Analysis::pair`].
    pub fn subject(&self, input: &SubjectInput) -> SubjectResult {
        super::subject::load_and_pair(input, self.format.as_ref(), &self.read, |l, r| {
            self.pair(input, l, r)
        })
    }

    /// Many subjects: [`Many::results`] in memory, or [`Many::to_folder`] streamed into an
    /// output folder. In parallel (on [`Analysis::jobs`] threads, or the current pool), in
    /// input order; one failed recording never stops the others.
    pub fn many<'s>(&'s self, subjects: &'s [SubjectInput]) -> Many<'s, 'a> {
        Many {
            analysis: self,
            subjects,
        }
    }

    /// `f` on the pool of [`Analysis::jobs`], or on the current one.
    pub(super) fn on_pool<T: Send>(&self, f: impl FnOnce() -> T + Send) -> Result<T> {
        match self.jobs {
            None => Ok(f()),
            Some(n) => {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .map_err(|e| LdhError::param("n_jobs", n, e.to_string()))?;
                Ok(pool.install(f))
            }
        }
    }

    /// The progress call after a subject of a batch.
    pub(super) fn done(&self) {
        if let Some(done) = self.progress {
            done();
        }
    }
}

/// The subjects of [`Analysis::many`], to analyse in memory or into a folder.
#[derive(Debug, Clone, Copy)]
pub struct Many<'s, 'a> {
    pub(super) analysis: &'s Analysis<'a>,
    pub(super) subjects: &'s [SubjectInput],
}

impl Many<'_, '_> {
    /// Every subject's result, in input order.
    ///
    /// # Errors
    /// Only a thread pool that cannot be built ([`Analysis::jobs`]).
    pub fn results(self) -> Result<Vec<SubjectResult>> {
        use rayon::prelude::*;
        let a = self.analysis;
        a.on_pool(|| {
            self.subjects
                .par_iter()
                .map(|s| {
                    let r = a.subject(s);
                    a.done();
                    r
                })
                .collect()
        })
    }

    /// Analyse the subjects into the folder of `run`: `strides.csv/.json`, `events.csv` and
    /// `recordings.csv/.json` (and traces, see [`FolderOptions`]), streamed a chunk at a time
    /// so memory stays flat. A recording that fails is a row with its error; only a write
    /// failure stops the run. The caller begins the run ([`OutputRun::begin`], which clears an
    /// earlier run's outputs) after [`check_output_names`], and finishes it (the marker) after
    /// its own files.
    pub fn to_folder(self, run: &OutputRun, opts: FolderOptions<'_>) -> Result<FolderSummary> {
        self.analysis
            .on_pool(|| super::many::to_folder(self, run, opts))?
    }
}

/// The events one leg lends to the other leg's step time and frequency and double support,
/// s on the lending leg's own clock (empty when its gyroscope is faulty: its events are not
/// lent).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LentHeelStrikes {
    /// Heel strike times, s from the lending recording's first sample.
    pub hs_s: Vec<f64>,
    /// Toe off times, s (issue 49: the other leg's double support).
    pub to_s: Vec<f64>,
}

impl LentHeelStrikes {
    /// The heel strikes on the other leg's clock: `own_t0_s` is the lending file's first sample
    /// and `other_t0_s` the other file's (`None`: the same clock).
    pub fn on_clock(&self, own_t0_s: f64, other_t0_s: Option<f64>) -> Vec<f64> {
        shift(&self.hs_s, own_t0_s - other_t0_s.unwrap_or(own_t0_s))
    }

    /// The toe offs on the other leg's clock, as [`LentHeelStrikes::on_clock`].
    pub fn to_on_clock(&self, own_t0_s: f64, other_t0_s: Option<f64>) -> Vec<f64> {
        shift(&self.to_s, own_t0_s - other_t0_s.unwrap_or(own_t0_s))
    }
}

/// Times shifted by `d_s`.
fn shift(v: &[f64], d_s: f64) -> Vec<f64> {
    v.iter().map(|t| t + d_s).collect()
}

/// One leg analysed: its result and the heel strikes it lends to the other leg.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysedLeg {
    /// The leg's analysis.
    pub leg: LegResult,
    /// Its heel strikes for the other leg.
    pub lent: LentHeelStrikes,
}
