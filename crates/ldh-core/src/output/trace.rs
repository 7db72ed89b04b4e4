//! The signal excerpt a per-subject report plots (paper Figs. 3–4): a window of the
//! preprocessed, aligned acceleration and angular velocity and the attitude angles of one leg,
//! with its events and what the reader and the alignment found. `ldh analyze --report` writes
//! one per subject and trial (`traces/<subject>.json`, `traces/<subject>~trial-<trial>.json`;
//! [`crate::output::names`]) so `ldh report` can redraw the report later without the
//! recordings.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::pipeline::LegResult;

/// Schema tag of a trace file.
pub const TRACE_SCHEMA: &str = "ldh-trace/1";

/// Parameters of the plotted window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TraceParams {
    /// Length of the plotted window, s. Default 10 s (about 9 strides at a normal cadence:
    /// enough to see the pattern, short enough to read each stride).
    pub window_s: f64,
    /// Time kept before the first heel strike of the window, s. Default 0.5 s.
    pub lead_s: f64,
}

impl Default for TraceParams {
    fn default() -> Self {
        TraceParams {
            window_s: 10.0,
            lead_s: 0.5,
        }
    }
}

impl TraceParams {
    /// Set [`TraceParams::window_s`].
    pub fn window_s(mut self, v: f64) -> Self {
        self.window_s = v;
        self
    }
    /// Validate: a finite window of 1–600 s and a lead of 0 to the window.
    pub fn check(&self) -> Result<ValidTraceParams> {
        if !(self.window_s.is_finite() && (1.0..=600.0).contains(&self.window_s)) {
            return Err(LdhError::param(
                "window_s",
                self.window_s,
                "must be between 1 and 600 s",
            ));
        }
        if !(self.lead_s.is_finite() && self.lead_s >= 0.0 && self.lead_s < self.window_s) {
            return Err(LdhError::param(
                "lead_s",
                self.lead_s,
                "must be ≥ 0 and shorter than window_s",
            ));
        }
        Ok(ValidTraceParams(self.clone()))
    }
}

/// Checked [`TraceParams`].
#[derive(Debug, Clone, PartialEq)]
pub struct ValidTraceParams(TraceParams);

/// The plotted excerpt of one leg. Times are s from the recording's first sample, like the
/// stride table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LegTrace {
    /// The leg (`left` or `right` in the file).
    pub side: crate::Side,
    /// Sampling rate, Hz.
    pub fs_hz: f64,
    /// Time of the first sample of the window, s.
    pub start_s: f64,
    /// Specific force in the anatomical frame (anterior, left, up), g, 4 decimals.
    pub acc_g: [Vec<f64>; 3],
    /// Angular velocity in the anatomical frame (about anterior, left, up), deg/s, 2 decimals.
    pub gyro_dps: [Vec<f64>; 3],
    /// Shank roll, deg.
    pub roll_deg: Vec<f64>,
    /// Shank pitch (sagittal inclination), deg.
    pub pitch_deg: Vec<f64>,
    /// Heel strikes inside the window, s.
    pub hs_s: Vec<f64>,
    /// Toe offs inside the window, s.
    pub to_s: Vec<f64>,
    /// Stance phases (HS, TO) overlapping the window, s.
    pub stance_s: Vec<(f64, f64)>,
    /// What the reader noticed (BOM, gaps, resampling, …), one sentence each.
    pub read_notes: Vec<String>,
    /// What the alignment found (quiet standing, mounting), one sentence each.
    pub alignment_notes: Vec<String>,
    /// Gaps found in the file, as (time before the gap in the file clock s, length s).
    pub gaps_s: Vec<(f64, f64)>,
    /// The shank-pitch gait cycle over every valid stride of the leg (those of the walk's
    /// steady window), mean ± SD in deg at 2 decimals ([`super::cycle::pitch_cycle_of`]);
    /// absent with fewer than 2 valid strides, and in traces written before 2026-12-02.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycle: Option<super::cycle::CycleCurve>,
}

fn round(v: &[f64], dec: i32) -> Vec<f64> {
    let f = 10f64.powi(dec);
    v.iter().map(|x| (x * f).round() / f).collect()
}

impl LegTrace {
    /// The excerpt of an analysed leg: from `lead_s` before a heel strike in the middle of the
    /// longest run of valid strides (inside the walk's steady window, whose edges are a
    /// transient's end; issue 50: an excerpt of the belt's start-up), at the run's first heel
    /// strike when the run is shorter than the window; the start of the recording when there
    /// is no valid stride.
    /// `None` when the leg kept no signals (a result read back from JSON).
    pub fn of(leg: &LegResult, p: &ValidTraceParams) -> Option<LegTrace> {
        let p = &p.0;
        let (sig, att) = (leg.signals.as_ref()?, leg.attitude.as_ref()?);
        let fs = sig.fs_hz;
        let n = sig.acc_g[0].len().min(att.pitch_deg.len());
        if n == 0 || !(fs > 0.0) {
            return None;
        }
        // Longest run of valid strides.
        let mut best: Option<(usize, usize)> = None;
        let mut cur: Option<(usize, usize)> = None;
        for (i, s) in leg.strides.iter().enumerate() {
            cur = if s.valid {
                Some(cur.map_or((i, i), |(a, _)| (a, i)))
            } else {
                None
            };
            if let Some(c) = cur {
                if best.is_none_or(|b| c.1 - c.0 > b.1 - b.0) {
                    best = Some(c);
                }
            }
        }
        let start_s = best
            .map(|(a, b)| {
                let run = &leg.strides[a..=b];
                let (first, end) = (run[0].hs_time_s, run[run.len() - 1].next_hs_time_s);
                let want = 0.5 * (first + end - p.window_s);
                let hs = run
                    .iter()
                    .map(|s| s.hs_time_s)
                    .find(|&t| t >= want)
                    .unwrap_or(first);
                (hs - p.lead_s).max(0.0)
            })
            .unwrap_or(0.0);
        let i0 = ((start_s * fs).round() as usize).min(n - 1);
        let i1 = (i0 + (p.window_s * fs).round() as usize).min(n);
        let (t0, t1) = (i0 as f64 / fs, (i1 - 1) as f64 / fs);
        let inside = |t: &f64| (t0..=t1).contains(t);
        let stance_s = leg
            .strides
            .iter()
            .filter(|s| s.to_time_s >= t0 && s.hs_time_s <= t1)
            .map(|s| (s.hs_time_s, s.to_time_s))
            .collect();
        let ch = |v: &[f64], d: i32| round(&v[i0..i1], d);
        Some(LegTrace {
            side: leg.side,
            fs_hz: fs,
            start_s: t0,
            acc_g: [
                ch(&sig.acc_g[0], 4),
                ch(&sig.acc_g[1], 4),
                ch(&sig.acc_g[2], 4),
            ],
            gyro_dps: [
                ch(&sig.gyro_dps[0], 2),
                ch(&sig.gyro_dps[1], 2),
                ch(&sig.gyro_dps[2], 2),
            ],
            roll_deg: ch(&att.roll_deg, 2),
            pitch_deg: ch(&att.pitch_deg, 2),
            hs_s: round(
                &leg.events
                    .hs_s
                    .iter()
                    .copied()
                    .filter(inside)
                    .collect::<Vec<_>>(),
                4,
            ),
            to_s: round(
                &leg.events
                    .to_s
                    .iter()
                    .copied()
                    .filter(inside)
                    .collect::<Vec<_>>(),
                4,
            ),
            stance_s,
            read_notes: leg.read.notes.clone(),
            alignment_notes: leg.alignment.notes.clone(),
            gaps_s: leg.read.gaps.iter().map(|g| (g.from_s, g.gap_s)).collect(),
            cycle: super::cycle::pitch_cycle_of(leg).map(|c| c.rounded(2)),
        })
    }
}

/// The traces of one subject as written to `traces/<subject>.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectTraces {
    /// [`TRACE_SCHEMA`].
    pub schema: String,
    /// Subject.
    pub subject_id: String,
    /// The trial (manifest `trial_id`) for one of a person's several trials; absent otherwise.
    /// With the subject id it names the recording, which `ldh report` checks against the file
    /// it expected.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trial_id: Option<String>,
    /// One per leg that was analysed.
    pub legs: Vec<LegTrace>,
}

impl SubjectTraces {
    /// The traces of a subject's result (legs that failed have none).
    pub fn of(r: &crate::pipeline::SubjectResult, p: &ValidTraceParams) -> SubjectTraces {
        SubjectTraces {
            schema: TRACE_SCHEMA.into(),
            subject_id: r.subject_id.clone(),
            trial_id: r.trial_id.clone(),
            legs: r
                .legs()
                .into_iter()
                .filter_map(|(_, l)| l.as_ref().ok().and_then(|l| LegTrace::of(l, p)))
                .collect(),
        }
    }

    /// Parse a trace file; `origin` names it in errors.
    pub fn from_json(text: &str, origin: &str) -> Result<SubjectTraces> {
        let t: SubjectTraces = serde_json::from_str(text)
            .map_err(|e| LdhError::signal(origin, format!("not an ldh trace file: {e}")))?;
        if t.schema != TRACE_SCHEMA {
            return Err(LdhError::signal(
                origin,
                format!("trace schema '{}', expected '{TRACE_SCHEMA}'", t.schema),
            ));
        }
        Ok(t)
    }
}
