//! The change of a person's daily walking between two monitoring periods (`visit`: before and
//! after surgery), judged against the day-to-day noise.
//!
//! Per daily measure (walking minutes, steps, bouts, and the day's median cadence in bouts
//! over 30 s) over each period's **valid days**: the mean per day of each period, the change
//! (second − first), and the noise limit 1.96 · √(s₁²/n₁ + s₂²/n₂), the 95 % limit of a
//! difference of two means whose days vary as the periods' own days do (the standard error of
//! Welch's difference of means; days of one person vary by 20–30 % in steps: Tudor-Locke et
//! al., Med Sci Sports Exerc 2005). The change is *beyond the noise* when larger than that
//! limit. Each is withheld with the reason when a period has fewer than
//! [`MIN_DAYS_FOR_NOISE`] valid days measuring the value (one day has no day-to-day spread).
//! Tests: `crates/ldh-core/tests/monitor_change.rs` (their fixture is shared with the week
//! page's tests in ldh-test-support).

use serde::{Deserialize, Serialize};

use super::days::DayRow;
use super::MonitorResult;

/// Valid days each period needs for the change to be judged: 2.
pub const MIN_DAYS_FOR_NOISE: usize = 2;

/// The daily measures compared, with their units.
pub const DAILY_MEASURES: [(&str, &str); 4] = [
    ("walking_min", "min/day"),
    ("steps", "steps/day"),
    ("bouts", "bouts/day"),
    ("cadence_steps_per_min", "steps/min"),
];

/// One measure of a day (`DAILY_MEASURES` index `k`).
pub fn daily_value(d: &DayRow, k: usize) -> f64 {
    match k {
        0 => d.walking_min,
        1 => d.steps,
        2 => d.bouts,
        _ => d.gait_median[0],
    }
}

/// The change of one daily measure between two periods of one person.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VisitChange {
    /// The person.
    pub subject_id: String,
    /// The first period's visit.
    pub from_visit: String,
    /// The second period's visit.
    pub to_visit: String,
    /// The measure ([`DAILY_MEASURES`]).
    pub measure: String,
    /// Its unit.
    pub unit: String,
    /// Valid days measuring it in each period.
    pub days_from: usize,
    /// See `days_from`.
    pub days_to: usize,
    /// Mean per valid day in each period.
    pub mean_from: f64,
    /// See `mean_from`.
    pub mean_to: f64,
    /// `mean_to − mean_from`.
    pub change: f64,
    /// The 95 % noise limit of the change (module docs); NaN when withheld.
    pub noise: f64,
    /// The change is larger than the noise limit (`None`: withheld).
    pub beyond_noise: Option<bool>,
    /// Why the noise (and the judgement) is withheld; empty otherwise.
    pub withheld: String,
}

fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, var.sqrt())
}

/// The changes between two periods of one person, one per [`DAILY_MEASURES`].
pub fn visit_change(from: &MonitorResult, to: &MonitorResult) -> Vec<VisitChange> {
    let vals = |r: &MonitorResult, k: usize| -> Vec<f64> {
        r.days
            .iter()
            .filter(|d| d.valid)
            .map(|d| daily_value(d, k))
            .filter(|v| v.is_finite())
            .collect()
    };
    DAILY_MEASURES
        .iter()
        .enumerate()
        .map(|(k, (measure, unit))| {
            let (a, b) = (vals(from, k), vals(to, k));
            let (ma, sa) = if a.is_empty() { (f64::NAN, f64::NAN) } else { mean_sd(&a) };
            let (mb, sb) = if b.is_empty() { (f64::NAN, f64::NAN) } else { mean_sd(&b) };
            let enough = a.len() >= MIN_DAYS_FOR_NOISE && b.len() >= MIN_DAYS_FOR_NOISE;
            let noise = if enough {
                1.96 * (sa * sa / a.len() as f64 + sb * sb / b.len() as f64).sqrt()
            } else {
                f64::NAN
            };
            let change = mb - ma;
            VisitChange {
                subject_id: from.subject_id.clone(),
                from_visit: from.visit.clone().unwrap_or_default(),
                to_visit: to.visit.clone().unwrap_or_default(),
                measure: (*measure).into(),
                unit: (*unit).into(),
                days_from: a.len(),
                days_to: b.len(),
                mean_from: ma,
                mean_to: mb,
                change,
                noise,
                beyond_noise: enough.then(|| change.abs() > noise),
                withheld: if enough {
                    String::new()
                } else {
                    format!(
                        "{} and {} valid day(s) measure it, {MIN_DAYS_FOR_NOISE} needed in each period for the day-to-day noise",
                        a.len(),
                        b.len()
                    )
                },
            }
        })
        .collect()
}

/// Every person's change from their first period to each later one, in input order (periods
/// of one person in the order given: the manifest's visit order).
pub fn visit_changes(results: &[MonitorResult]) -> Vec<VisitChange> {
    let mut out = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for r in results {
        if seen.contains(&r.subject_id.as_str()) {
            continue;
        }
        seen.push(&r.subject_id);
        let mine: Vec<&MonitorResult> = results
            .iter()
            .filter(|x| x.subject_id == r.subject_id)
            .collect();
        for later in &mine[1..] {
            out.extend(visit_change(mine[0], later));
        }
    }
    out
}
