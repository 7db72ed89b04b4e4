//! `ldh monitor`: walking in daily life from two shank sensors worn for days (issue 52).
//!
//! A stage above the pipeline: each leg's recording is streamed once, in chunks
//! (`stream`: ldh's CSV; [`SampleSource`] for other readers), each 1-s window classified
//! (`windows`: non-wear, lying, sitting, standing, walking, running, cycling, other), walking
//! spans captured and spilled to a temporary file (`leg`, `store`: memory does not grow with
//! the recording's length), the two legs' spans paired and the drift between their clocks
//! fitted (`pair`), every paired span analysed by the lab pipeline itself
//! ([`crate::pipeline::Analysis::pair`], `bouts`: one code path with `ldh analyze`), and the
//! bouts, minutes and days aggregated (`days`) into bouts.csv, days.csv, summary.csv and
//! periods.csv (`write`).
//!
//! Rules and sources (docs/free-living.md): bouts of ≥ 4 strides with breaks ≤ 3 s (mobgap's
//! gait sequence detection and walking-bout assembly: Micó-Amigo et al., J NeuroEng Rehabil
//! 2023;20:78; Kluge et al., Sensors 2021;21:7356); non-wear when each acceleration axis has an
//! SD below 13 mg (and two a range below 50 mg) over 60 min (van Hees et al., PLoS ONE 2011 and
//! 2013); a valid day has ≥ 12 h of waking wear and a valid week ≥ 3 valid days (Mobilise-D).

pub mod bouts;
pub mod change;
pub mod days;
pub mod leg;
pub mod pair;
pub mod stairs;
pub mod steps;
pub mod store;
pub mod stream;
pub mod windows;
pub mod write;

#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};

pub use bouts::BoutRow;
pub use change::{visit_changes, VisitChange};
pub use days::{DayRow, PeriodRow, SummaryRow};
pub use pair::ClockDrift;
pub use stairs::{BoutKind, StairParams};
pub use stream::{CsvSamples, MemorySamples, Sample, SampleSource};
pub use windows::{Activity, WindowParams};

use crate::error::{LdhError, Result};
use crate::pipeline::{Analysis, AnalysisParams, Source, SubjectInput, ValidAnalysisParams};
use crate::recording::Side;

/// The monitor's parameters (defaults in brackets; docs/free-living.md).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MonitorParams {
    /// Window classes.
    pub windows: WindowParams,
    /// A longer interval between samples is a gap, s [1].
    pub max_gap_s: f64,
    /// Longest break inside a bout, s [3] (mobgap).
    pub max_break_s: f64,
    /// Samples kept before and after a walking span, s [2].
    pub margin_s: f64,
    /// Shortest walking span passed to the pipeline, s [3].
    pub min_candidate_s: f64,
    /// Longest span held at once, s [1200]: a longer walk is analysed in consecutive bouts
    /// marked `continues` (memory stays bounded; the day's longest bout joins them).
    pub max_span_s: f64,
    /// Least strides of a bout, both legs counted [4] (mobgap).
    pub min_strides: usize,
    /// Largest clock offset searched between the legs, s [60].
    pub max_offset_s: f64,
    /// A pair further than this from the drift line is an outlier, s [1].
    pub offset_outlier_s: f64,
    /// Least envelope correlation of a pair [0.6].
    pub min_pair_corr: f64,
    /// Samples read at a time [65536].
    pub chunk_samples: usize,
    /// Non-wear: window, min [60]; SD below, g [0.013]; range below, g [0.05].
    pub nonwear_window_min: f64,
    /// See `nonwear_window_min`.
    pub nonwear_sd_g: f64,
    /// See `nonwear_window_min`.
    pub nonwear_range_g: f64,
    /// A valid day has this much waking wear, h [12].
    pub min_wear_h: f64,
    /// A valid period has this many valid days [3].
    pub min_valid_days: usize,
    /// Gait aggregates need this many bouts > 30 s [3].
    pub min_long_bouts: usize,
    /// The stair rule (`stairs`).
    pub stairs: StairParams,
    /// The per-bout analysis (STA off: a bout is too short for it and it is not aggregated).
    pub analysis: AnalysisParams,
}

impl Default for MonitorParams {
    fn default() -> Self {
        MonitorParams {
            windows: WindowParams::default(),
            max_gap_s: 1.0,
            max_break_s: 3.0,
            margin_s: 2.0,
            min_candidate_s: 3.0,
            max_span_s: 1200.0,
            min_strides: 4,
            max_offset_s: 60.0,
            offset_outlier_s: 1.0,
            min_pair_corr: 0.6,
            chunk_samples: 1 << 16,
            nonwear_window_min: 60.0,
            nonwear_sd_g: 0.013,
            nonwear_range_g: 0.05,
            min_wear_h: 12.0,
            min_valid_days: 3,
            min_long_bouts: 3,
            stairs: StairParams::default(),
            analysis: AnalysisParams {
                compute_sta: false,
                ..AnalysisParams::default()
            },
        }
    }
}

/// Checked [`MonitorParams`].
#[derive(Debug, Clone)]
pub struct ValidMonitorParams {
    /// The parameters.
    pub params: MonitorParams,
    /// The per-bout analysis, checked.
    pub analysis: ValidAnalysisParams,
    /// Spans read at a time (≥ 1000).
    pub chunk_samples: usize,
}

impl MonitorParams {
    /// Check the parameters once.
    pub fn check(&self) -> Result<ValidMonitorParams> {
        let pos = |name: &'static str, v: f64| -> Result<()> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(LdhError::param(name, v, "must be finite and > 0"))
            }
        };
        let w = &self.windows;
        for (n, v) in [
            ("windows.window_s", w.window_s),
            ("windows.context_s", w.context_s),
            ("windows.min_stride_s", w.min_stride_s),
            ("max_gap_s", self.max_gap_s),
            ("max_break_s", self.max_break_s),
            ("margin_s", self.margin_s),
            ("min_candidate_s", self.min_candidate_s),
            ("max_offset_s", self.max_offset_s),
            ("offset_outlier_s", self.offset_outlier_s),
            ("nonwear_window_min", self.nonwear_window_min),
            ("nonwear_sd_g", self.nonwear_sd_g),
            ("nonwear_range_g", self.nonwear_range_g),
            ("min_wear_h", self.min_wear_h),
        ] {
            pos(n, v)?;
        }
        if w.max_stride_s <= w.min_stride_s {
            return Err(LdhError::param(
                "windows.max_stride_s",
                w.max_stride_s,
                "must exceed min_stride_s",
            ));
        }
        self.stairs.check()?;
        if !(self.max_span_s >= 60.0 && self.max_span_s <= 7200.0) {
            return Err(LdhError::param(
                "max_span_s",
                self.max_span_s,
                "must be 60–7200 s",
            ));
        }
        Ok(ValidMonitorParams {
            params: self.clone(),
            analysis: self.analysis.check()?,
            chunk_samples: self.chunk_samples.max(1000),
        })
    }
}

/// One person's monitoring period analysed.
#[derive(Debug, Clone, Default)]
pub struct MonitorResult {
    /// The person.
    pub subject_id: String,
    /// The visit (monitoring period), as the manifest gives it.
    pub visit: Option<String>,
    /// Walking bouts.
    pub bouts: Vec<BoutRow>,
    /// Days.
    pub days: Vec<DayRow>,
    /// The period.
    pub summary: SummaryRow,
    /// Wear and rest periods.
    pub periods: Vec<PeriodRow>,
    /// The right sensor's clock against the left's.
    pub drift: ClockDrift,
    /// What the readers and the pairing found, one sentence each.
    pub notes: Vec<String>,
    /// Errors that lost a leg (the other leg is still analysed).
    pub errors: Vec<String>,
}

/// Open a source as a stream of samples.
pub fn open_source(src: &Source) -> Result<Box<dyn SampleSource>> {
    match src {
        Source::Path(p) => Ok(Box::new(CsvSamples::open(p)?)),
        Source::Embedded(rel) => {
            let text = crate::demo::file(rel)
                .ok_or_else(|| LdhError::signal("demo", format!("no embedded file {rel}")))?;
            Ok(Box::new(CsvSamples::from_reader(
                Box::new(std::io::Cursor::new(text.as_bytes().to_vec())),
                std::path::Path::new(&src.label()),
            )?))
        }
    }
}

/// Analyse one person's period from its input (two recordings; either may fail alone).
pub fn monitor_subject(input: &SubjectInput, p: &ValidMonitorParams) -> MonitorResult {
    let open = |s: &Option<Source>, side: Side| -> Result<Box<dyn SampleSource>> {
        let s = s.as_ref().ok_or_else(|| {
            LdhError::signal(side.to_string(), format!("no {side} recording given"))
        })?;
        open_source(s)
    };
    let l = open(&input.left, Side::Left);
    let r = open(&input.right, Side::Right);
    monitor_sources(input, l, r, p)
}

/// Analyse one person's period from two sample sources.
pub fn monitor_sources(
    input: &SubjectInput,
    left: Result<Box<dyn SampleSource>>,
    right: Result<Box<dyn SampleSource>>,
    p: &ValidMonitorParams,
) -> MonitorResult {
    let mut out = MonitorResult {
        subject_id: input.subject_id.clone(),
        visit: input.visit.clone(),
        ..MonitorResult::default()
    };
    let store = match store::SpanStore::new() {
        Ok(s) => s,
        Err(e) => {
            out.errors.push(e.to_string());
            return out;
        }
    };
    let run = |src: Result<Box<dyn SampleSource>>, side: Side| {
        src.and_then(|mut s| leg::stream_leg(s.as_mut(), side, p, &store))
    };
    let (l, r) = rayon::join(|| run(left, Side::Left), || run(right, Side::Right));
    let mut legs = [None, None];
    for (k, (side, res)) in [(Side::Left, l), (Side::Right, r)].into_iter().enumerate() {
        match res {
            Ok(s) => {
                out.notes.extend(s.notes.iter().cloned());
                legs[k] = Some(s);
            }
            Err(e) => out.errors.push(format!("{side}: {e}")),
        }
    }
    aggregate(&mut out, input, legs, &store, p);
    out
}

fn aggregate(
    out: &mut MonitorResult,
    input: &SubjectInput,
    legs: [Option<leg::LegStream>; 2],
    store: &store::SpanStore,
    p: &ValidMonitorParams,
) {
    use rayon::prelude::*;
    let mp = &p.params;
    let empty = leg::LegStream::default();
    let [l, r] = &legs;
    let (lspans, rspans) = (
        l.as_ref().map_or(&[][..], |x| &x.spans[..]),
        r.as_ref().map_or(&[][..], |x| &x.spans[..]),
    );
    let (plans, drift) = pair::pair_spans(
        lspans,
        rspans,
        mp.max_offset_s,
        mp.offset_outlier_s,
        mp.min_pair_corr,
    );
    out.drift = drift;
    let analysis = Analysis::new(p.analysis.clone());
    let both = [l.as_ref().unwrap_or(&empty), r.as_ref().unwrap_or(&empty)];
    let results: Vec<_> = plans
        .par_iter()
        .map(|plan| {
            bouts::analyse(plan, both, store, input, &analysis, mp).map(|mut b| {
                b.continues = plan
                    .left
                    .map(|i| lspans[i].continues)
                    .or(plan.right.map(|j| rspans[j].continues))
                    .unwrap_or(false);
                b
            })
        })
        .collect();
    let mut rows: Vec<BoutRow> = Vec::new();
    let (mut refused, mut runs) = (0, 0);
    for res in results {
        match res {
            Ok(b) => rows.push(b),
            Err(r) if r.run => runs += 1,
            Err(_) => refused += 1,
        }
    }
    if refused > 0 {
        out.notes.push(format!(
            "{refused} candidate span(s) were not walking bouts (fewer than {} strides found by the gait pipeline)",
            mp.min_strides
        ));
    }
    if runs > 0 {
        out.notes.push(format!(
            "{runs} candidate span(s) were runs (short strides with running impacts), not counted as walking"
        ));
    }
    let (mut rows, twice) = bouts::count_once(rows);
    if twice > 0 {
        out.notes.push(format!(
            "{twice} bout(s) of one leg lay inside a bout of both legs (the same walk) and were counted once"
        ));
    }
    for (i, b) in rows.iter_mut().enumerate() {
        b.bout = i + 1;
    }
    let first = l.as_ref().or(r.as_ref());
    let clock = days::DayClock::new(
        first.and_then(|x| x.start),
        first.map_or(0.0, |x| x.span_s.0),
    );
    let states = days::minute_states(l.as_ref(), r.as_ref(), mp, &drift);
    out.periods = days::periods(&states);
    out.days = days::days(&states, &rows, &clock, mp);
    out.summary = days::summary(&out.days, &rows, &clock, &drift, mp);
    if out.days.is_empty() && out.errors.is_empty() {
        out.notes.push("no sample was read".into());
    }
    if !out.days.is_empty() && out.days.iter().all(|d| d.wear_h == 0.0) {
        out.notes.push("the sensors were not worn at any time of the recording (non-wear throughout): no day is valid".into());
    }
    out.bouts = rows;
}

/// Many people's periods, each on its own (one bad input never stops the others), in input
/// order, on a pool of `jobs` threads (0: one per core).
pub fn monitor_many(
    inputs: &[SubjectInput],
    p: &ValidMonitorParams,
    jobs: usize,
) -> Result<Vec<MonitorResult>> {
    use rayon::prelude::*;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| LdhError::param("n_jobs", jobs, e.to_string()))?;
    Ok(pool.install(|| inputs.par_iter().map(|i| monitor_subject(i, p)).collect()))
}
