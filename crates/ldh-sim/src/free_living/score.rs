//! Scoring what a free-living analysis found against the simulator's truth, with the targets
//! of issue 52's "done when": walking bouts ≥ 10 s found with recall ≥ 0.95, walking time and
//! steps within 5 %, false walking in rest, non-wear and cycling ≤ 2 % of their time, clock
//! drift within 0.5 s a day.
//!
//! Matching rule: a true walking bout counts as found when found bouts cover at least half of
//! it (the overlap criterion of bout-level evaluation in Mobilise-D, Micó-Amigo et al.,
//! J NeuroEng Rehabil 2023, there as IoU; coverage here so a bout found in two pieces
//! counts). Walking time and steps compare totals over the recording (level walking only:
//! stairs and running are not walking; found bouts labelled stairs are left out of the found
//! side too). Stairs: a true flight counts as found when found stair bouts cover ≥ 50 % of it
//! (recall), a found stair bout as right when ≥ 50 % of it lies in true stairs (precision).

use serde::{Deserialize, Serialize};

use super::plan::Activity;
use super::truth::TruthBout;

/// A walking bout an analysis found, on the left sensor's clock.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FoundBout {
    /// Start, s.
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// Steps of both legs counted in it.
    pub steps: f64,
    /// The analysis labelled it stairs (not level walking). Default false.
    #[serde(default)]
    pub stairs: bool,
}

/// The shortest true walking bout scored for recall, s: 10.
pub const RECALL_MIN_BOUT_S: f64 = 10.0;
/// Share of a true bout that found bouts must cover for it to count as found: 0.5.
pub const MIN_COVERAGE: f64 = 0.5;

/// The targets a [`Score`] is judged against (defaults: issue 52's).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ScoreTargets {
    /// Lowest recall of walking bouts ≥ 10 s. Default 0.95.
    pub recall_min: f64,
    /// Largest |walking time error|, %. Default 5.
    pub walking_time_error_pct_max: f64,
    /// Largest |steps error|, %. Default 5.
    pub steps_error_pct_max: f64,
    /// Largest false walking, % of rest, non-wear and cycling time. Default 2.
    pub false_walking_pct_max: f64,
    /// Largest drift error, s a day. Default 0.5.
    pub drift_error_s_per_day_max: f64,
}

impl Default for ScoreTargets {
    fn default() -> Self {
        ScoreTargets {
            recall_min: 0.95,
            walking_time_error_pct_max: 5.0,
            steps_error_pct_max: 5.0,
            false_walking_pct_max: 2.0,
            drift_error_s_per_day_max: 0.5,
        }
    }
}

/// How found walking bouts compare with the truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Score {
    /// True walking bouts ≥ 10 s.
    pub true_bouts_10s: usize,
    /// Of them, found (covered ≥ 50 %).
    pub found_bouts_10s: usize,
    /// `found_bouts_10s / true_bouts_10s` (`None` without true bouts ≥ 10 s).
    pub recall_10s: Option<f64>,
    /// True walking time, s.
    pub true_walking_s: f64,
    /// Found walking time, s.
    pub found_walking_s: f64,
    /// (found − true) / true walking time, % (`None` without true walking).
    pub walking_time_error_pct: Option<f64>,
    /// True steps in walking bouts (both legs).
    pub true_steps: f64,
    /// Found steps.
    pub found_steps: f64,
    /// (found − true) / true steps, %.
    pub steps_error_pct: Option<f64>,
    /// Found walking time inside rest, non-wear and cycling, % of their time.
    pub false_walking_pct: Option<f64>,
    /// The same per activity (sitting, standing, lying, non_wear, cycling), % of its time.
    pub false_walking_pct_by_activity: Vec<(Activity, f64)>,
    /// True stairs time, s.
    pub stairs_s: f64,
    /// Found walking time inside stairs, s (stairs are not level walking).
    pub found_in_stairs_s: f64,
    /// True stair bouts (flights).
    pub true_stair_bouts: usize,
    /// Of them, covered ≥ 50 % by found bouts labelled stairs.
    pub found_stair_bouts: usize,
    /// `found_stair_bouts / true_stair_bouts` (`None` without true stairs).
    pub stairs_recall: Option<f64>,
    /// Found bouts labelled stairs.
    pub labelled_stair_bouts: usize,
    /// Of them, lying ≥ 50 % in true stairs.
    pub right_stair_bouts: usize,
    /// `right_stair_bouts / labelled_stair_bouts` (`None` without a found stair bout).
    pub stairs_precision: Option<f64>,
    /// Found stair time inside true level walking, % of the level walking time.
    pub false_stairs_in_walking_pct: Option<f64>,
}

fn overlap(a0: f64, a1: f64, b0: f64, b1: f64) -> f64 {
    (a1.min(b1) - a0.max(b0)).max(0.0)
}

/// Seconds of `[t0, t1)` covered by `found` (sorted by start, not overlapping each other).
fn covered(found: &[FoundBout], t0: f64, t1: f64) -> f64 {
    let from = found.partition_point(|f| f.end_s <= t0);
    found[from..]
        .iter()
        .take_while(|f| f.start_s < t1)
        .map(|f| overlap(f.start_s, f.end_s, t0, t1))
        .sum()
}

/// Score found walking bouts against the truth of one recording.
pub fn score(truth: &[TruthBout], found: &[FoundBout]) -> Score {
    let mut found: Vec<FoundBout> = found.to_vec();
    found.sort_by(|a, b| a.start_s.total_cmp(&b.start_s));
    let (found_stairs, level): (Vec<FoundBout>, Vec<FoundBout>) =
        found.iter().cloned().partition(|f| f.stairs);
    let walking: Vec<&TruthBout> = truth
        .iter()
        .filter(|b| b.activity == Activity::Walking)
        .collect();
    let long: Vec<&&TruthBout> = walking
        .iter()
        .filter(|b| b.duration_s() >= RECALL_MIN_BOUT_S)
        .collect();
    let hit = long
        .iter()
        .filter(|b| covered(&found, b.start_s, b.end_s) >= MIN_COVERAGE * b.duration_s())
        .count();
    let true_walking_s: f64 = walking.iter().map(|b| b.duration_s()).sum();
    let found_walking_s: f64 = level.iter().map(|f| (f.end_s - f.start_s).max(0.0)).sum();
    let true_steps: f64 = walking.iter().map(|b| b.steps() as f64).sum();
    let found_steps: f64 = level.iter().map(|f| f.steps).sum();
    let pct = |f: f64, t: f64| (t > 0.0).then(|| 100.0 * (f - t) / t);
    let mut by = Vec::new();
    let (mut false_s, mut against_s) = (0.0, 0.0);
    for a in Activity::ALL
        .into_iter()
        .filter(|a| a.counts_against_false_walking())
    {
        let (mut f, mut t) = (0.0, 0.0);
        for b in truth.iter().filter(|b| b.activity == a) {
            f += covered(&found, b.start_s, b.end_s);
            t += b.duration_s();
        }
        if t > 0.0 {
            by.push((a, 100.0 * f / t));
        }
        false_s += f;
        against_s += t;
    }
    let stairs: Vec<&TruthBout> = truth
        .iter()
        .filter(|b| b.activity == Activity::Stairs)
        .collect();
    let stairs_hit = stairs
        .iter()
        .filter(|b| covered(&found_stairs, b.start_s, b.end_s) >= MIN_COVERAGE * b.duration_s())
        .count();
    let true_stairs: Vec<FoundBout> = stairs
        .iter()
        .map(|b| FoundBout {
            start_s: b.start_s,
            end_s: b.end_s,
            steps: 0.0,
            stairs: true,
        })
        .collect();
    let right = found_stairs
        .iter()
        .filter(|f| {
            covered(&true_stairs, f.start_s, f.end_s) >= MIN_COVERAGE * (f.end_s - f.start_s)
        })
        .count();
    let stairs_in_walking: f64 = walking
        .iter()
        .map(|b| covered(&found_stairs, b.start_s, b.end_s))
        .sum();
    Score {
        true_stair_bouts: stairs.len(),
        found_stair_bouts: stairs_hit,
        stairs_recall: (!stairs.is_empty()).then(|| stairs_hit as f64 / stairs.len() as f64),
        labelled_stair_bouts: found_stairs.len(),
        right_stair_bouts: right,
        stairs_precision: (!found_stairs.is_empty())
            .then(|| right as f64 / found_stairs.len() as f64),
        false_stairs_in_walking_pct: (true_walking_s > 0.0)
            .then(|| 100.0 * stairs_in_walking / true_walking_s),
        stairs_s: stairs.iter().map(|b| b.duration_s()).sum(),
        found_in_stairs_s: stairs
            .iter()
            .map(|b| covered(&found, b.start_s, b.end_s))
            .sum(),
        true_bouts_10s: long.len(),
        found_bouts_10s: hit,
        recall_10s: (!long.is_empty()).then(|| hit as f64 / long.len() as f64),
        true_walking_s,
        found_walking_s,
        walking_time_error_pct: pct(found_walking_s, true_walking_s),
        true_steps,
        found_steps,
        steps_error_pct: pct(found_steps, true_steps),
        false_walking_pct: (against_s > 0.0).then(|| 100.0 * false_s / against_s),
        false_walking_pct_by_activity: by,
    }
}

/// The drift error, s a day: |found − true| ppm × 86 400 s × 10⁻⁶.
pub fn drift_error_s_per_day(true_ppm: f64, found_ppm: f64) -> f64 {
    (found_ppm - true_ppm).abs() * 86_400.0 * 1e-6
}

impl Score {
    /// The targets this score misses, in words (empty: all met). A value that cannot be
    /// computed (no true walking) is not a miss.
    pub fn misses(&self, t: &ScoreTargets) -> Vec<String> {
        let mut m = Vec::new();
        if let Some(r) = self.recall_10s.filter(|&r| r < t.recall_min) {
            m.push(format!(
                "recall of walking bouts ≥ 10 s {r:.3} < {}",
                t.recall_min
            ));
        }
        if let Some(e) = self
            .walking_time_error_pct
            .filter(|e| e.abs() > t.walking_time_error_pct_max)
        {
            m.push(format!(
                "walking time error {e:+.1} % beyond ±{} %",
                t.walking_time_error_pct_max
            ));
        }
        if let Some(e) = self
            .steps_error_pct
            .filter(|e| e.abs() > t.steps_error_pct_max)
        {
            m.push(format!(
                "steps error {e:+.1} % beyond ±{} %",
                t.steps_error_pct_max
            ));
        }
        if let Some(f) = self
            .false_walking_pct
            .filter(|&f| f > t.false_walking_pct_max)
        {
            m.push(format!(
                "false walking {f:.2} % of rest, non-wear and cycling > {} %",
                t.false_walking_pct_max
            ));
        }
        m
    }
}
