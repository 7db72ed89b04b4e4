//! Minutes, periods, days and the period summary.
//!
//! **Non-wear** (van Hees et al., PLoS ONE 2011;6:e22922 and 2013;8:e61691, GGIR): a minute
//! is not worn when the `nonwear_window_min` (60) minutes centred on it have, on each
//! acceleration axis, an SD below `nonwear_sd_g` (13 mg), and on at least two axes a range
//! below `nonwear_range_g` (50 mg). A minute either sensor wore counts as worn (a sensor taken
//! off alone is said in the notes through its own periods).
//!
//! **Valid day** (Mobilise-D / mobgap's daily aggregation; Kirk et al. 2024): at least
//! `min_wear_h` (12) hours of waking wear — worn minutes that are not lying. A **valid
//! period** (week) has at least `min_valid_days` (3) valid days. A day that is not valid keeps
//! its wear and posture hours, and withholds its walking amounts with the reason; its bouts
//! still count in bouts.csv.
//!
//! **Gait in daily life** (Mobilise-D's digital mobility outcomes): over the bouts longer than
//! 30 s, the median and 90th percentile of cadence, speed, stride time, stride length,
//! stride-time variability and step-time asymmetry, withheld with fewer than
//! `min_long_bouts` (3) such bouts measuring the value. Stair bouts (`super::stairs`) count in
//! walking time, steps and bouts, not in these: they describe level walking.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::bouts::BoutRow;
use super::leg::{LegStream, MinuteStats};
use super::pair::ClockDrift;
use super::stairs::BoutKind;
use super::windows::Activity;
use super::MonitorParams;
use crate::io::DateTime;

/// One period of one state: a row of periods.csv.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PeriodRow {
    /// Start, s on the recording's clock.
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// Minutes.
    pub duration_min: f64,
    /// The state (`non_wear`, `lying`, `sitting`, `standing`, `walking`, …, `no_data`).
    pub state: String,
}

/// The bout parameters aggregated per day and period, with their table column stems.
pub const GAIT_AGGREGATES: [&str; 6] = [
    "cadence_steps_per_min",
    "speed_mps",
    "stride_time_s",
    "stride_length_m",
    "stride_time_cv",
    "step_time_asymmetry_pct",
];

/// A bout's values in [`GAIT_AGGREGATES`] order.
pub fn gait_values(b: &BoutRow) -> [f64; 6] {
    [
        b.cadence_steps_per_min,
        b.speed_mps,
        b.stride_time_s,
        b.stride_length_m,
        b.stride_time_cv,
        b.step_time_asymmetry_pct,
    ]
}

/// One day: a row of days.csv. Values withheld are NaN with `column: reason` in `withheld`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct DayRow {
    /// Day number from 1 (the recording's first day).
    pub day: usize,
    /// Calendar date (YYYY-MM-DD) when the file gives a start date; empty otherwise.
    pub date: String,
    /// Start of the day, s on the recording's clock.
    pub start_s: f64,
    /// Hours with data from either sensor.
    pub recorded_h: f64,
    /// Hours worn.
    pub wear_h: f64,
    /// Hours worn and not lying.
    pub waking_wear_h: f64,
    /// Hours of non-wear.
    pub non_wear_h: f64,
    /// Hours lying, sitting, standing.
    pub lying_h: f64,
    /// See `lying_h`.
    pub sitting_h: f64,
    /// See `lying_h`.
    pub standing_h: f64,
    /// Minutes of cycling and running windows.
    pub cycling_min: f64,
    /// See `cycling_min`.
    pub running_min: f64,
    /// The day is valid (≥ `min_wear_h` of waking wear).
    pub valid: bool,
    /// Minutes in walking bouts.
    pub walking_min: f64,
    /// Steps in walking bouts.
    pub steps: f64,
    /// Walking bouts.
    pub bouts: f64,
    /// Bouts of 10–30 s, 30–60 s and > 60 s.
    pub bouts_10_30s: f64,
    /// See `bouts_10_30s`.
    pub bouts_30_60s: f64,
    /// See `bouts_10_30s`.
    pub bouts_over_60s: f64,
    /// Longest bout, s (a walk longer than a span joined).
    pub longest_bout_s: f64,
    /// Level-walking bouts longer than 30 s the gait values are of (stair bouts left out).
    pub long_bouts: usize,
    /// Median and 90th percentile of each of [`GAIT_AGGREGATES`] over the long bouts.
    pub gait_median: [f64; 6],
    /// See `gait_median`.
    pub gait_p90: [f64; 6],
    /// Withheld values and why: `column: reason; …`.
    pub withheld: String,
}

/// A period's summary: a row of summary.csv.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct SummaryRow {
    /// Days with data.
    pub days: usize,
    /// Valid days.
    pub valid_days: usize,
    /// The period has ≥ `min_valid_days` valid days.
    pub valid: bool,
    /// Means over valid days: wear hours, walking minutes, steps, bouts.
    pub wear_h_per_day: f64,
    /// See `wear_h_per_day`.
    pub walking_min_per_day: f64,
    /// See `wear_h_per_day`.
    pub steps_per_day: f64,
    /// See `wear_h_per_day`.
    pub bouts_per_day: f64,
    /// Longest bout of the valid days, s.
    pub longest_bout_s: f64,
    /// Bouts > 30 s of the valid days.
    pub long_bouts: usize,
    /// Median and P90 of the gait values over those bouts.
    pub gait_median: [f64; 6],
    /// See `gait_median`.
    pub gait_p90: [f64; 6],
    /// Clock drift of the right sensor against the left, ppm and s a day.
    pub drift_ppm: f64,
    /// See `drift_ppm`.
    pub drift_s_per_day: f64,
    /// Withheld values and why.
    pub withheld: String,
}

/// Per-minute state of one leg: `None` no data; non-wear by van Hees' rule.
fn leg_states(leg: &LegStream, p: &MonitorParams, shift_s: f64) -> BTreeMap<i64, Activity> {
    let mut out = BTreeMap::new();
    let (Some(&lo), Some(&hi)) = (leg.minutes.keys().next(), leg.minutes.keys().next_back()) else {
        return out;
    };
    let half = (p.nonwear_window_min / 2.0).round() as i64;
    let empty = MinuteStats::default();
    let get = |m: i64| leg.minutes.get(&m).unwrap_or(&empty);
    for m in lo..=hi {
        let own = get(m);
        if own.n == 0 {
            continue;
        }
        let mut agg = MinuteStats::default();
        for k in m - half..m + half {
            agg.merge(get(k));
        }
        let n = agg.n as f64;
        let sd_low = (0..3).all(|a| {
            let mean = agg.sum[a] / n;
            (agg.sum_sq[a] / n - mean * mean).max(0.0).sqrt() < p.nonwear_sd_g
        });
        let range_low = (0..3)
            .filter(|&a| agg.max[a] - agg.min[a] < p.nonwear_range_g)
            .count()
            >= 2;
        let state = if sd_low && range_low {
            Activity::NonWear
        } else {
            let w = own.windows;
            let moving = w[Activity::Walking.index()]
                + w[Activity::Running.index()]
                + w[Activity::Cycling.index()];
            Activity::ALL
                .iter()
                .copied()
                .filter(|a| *a != Activity::NoData)
                .max_by_key(|a| {
                    if moving >= 20
                        && !matches!(a, Activity::Walking | Activity::Running | Activity::Cycling)
                    {
                        0
                    } else {
                        w[a.index()]
                    }
                })
                .unwrap_or(Activity::Other)
        };
        // On the left leg's clock (whole minutes).
        out.insert(m - (shift_s / 60.0).round() as i64, state);
    }
    out
}

/// The combined state of each minute: a worn leg wins over a leg not worn or without data.
pub fn minute_states(
    left: Option<&LegStream>,
    right: Option<&LegStream>,
    p: &MonitorParams,
    drift: &ClockDrift,
) -> BTreeMap<i64, Activity> {
    let l = left.map(|l| leg_states(l, p, 0.0)).unwrap_or_default();
    let r = right
        .map(|r| leg_states(r, p, drift.at(r.span_s.0)))
        .unwrap_or_default();
    let mut out = l.clone();
    for (m, s) in r {
        let e = out.entry(m).or_insert(s);
        if *e == Activity::NonWear && s != Activity::NonWear {
            *e = s;
        }
    }
    out
}

/// Consecutive minutes of one state joined into periods.
pub fn periods(states: &BTreeMap<i64, Activity>) -> Vec<PeriodRow> {
    let mut out: Vec<PeriodRow> = Vec::new();
    let mut prev: Option<(i64, Activity)> = None;
    for (&m, &s) in states {
        let (start, end) = (m as f64 * 60.0, (m + 1) as f64 * 60.0);
        match (prev, out.last_mut()) {
            (Some((pm, ps)), Some(last)) if pm + 1 == m && ps == s => last.end_s = end,
            (Some((pm, _)), _) if pm + 1 < m => {
                out.push(period(pm as f64 * 60.0 + 60.0, start, Activity::NoData));
                out.push(period(start, end, s));
            }
            _ => out.push(period(start, end, s)),
        }
        prev = Some((m, s));
    }
    for p in &mut out {
        p.duration_min = (p.end_s - p.start_s) / 60.0;
    }
    out
}

fn period(start_s: f64, end_s: f64, s: Activity) -> PeriodRow {
    PeriodRow {
        start_s,
        end_s,
        duration_min: 0.0,
        state: s.name().into(),
    }
}

/// The day of a time on the recording's clock: seconds from the first day's start, and
/// the day's start and calendar date when the file gives one.
pub struct DayClock {
    /// Unix seconds at recording time 0 (`None`: days are 24 h from the first sample).
    unix_at_zero: Option<i64>,
    first_s: f64,
}

impl DayClock {
    /// `start`: the file's start date (at its first sample `first_s`).
    pub fn new(start: Option<DateTime>, first_s: f64) -> Self {
        DayClock {
            unix_at_zero: start.map(|d| d.unix_s() - first_s.round() as i64),
            first_s,
        }
    }
    /// The day index (0 = the first day) of a time.
    pub fn day_of(&self, t_s: f64) -> i64 {
        match self.unix_at_zero {
            Some(u) => ((u as f64 + t_s) / 86_400.0).floor() as i64 - self.first_day(),
            None => ((t_s - self.first_s) / 86_400.0).floor() as i64,
        }
    }
    fn first_day(&self) -> i64 {
        self.unix_at_zero
            .map_or(0, |u| ((u as f64 + self.first_s) / 86_400.0).floor() as i64)
    }
    /// The start of day `d` on the recording's clock, and its date.
    pub fn start_of(&self, d: i64) -> (f64, String) {
        match self.unix_at_zero {
            Some(u) => {
                let unix = (self.first_day() + d) * 86_400;
                let date = DateTime::from_unix_s(unix as f64)
                    .map(|x| format!("{:04}-{:02}-{:02}", x.year, x.month, x.day))
                    .unwrap_or_default();
                ((unix - u) as f64, date)
            }
            None => (self.first_s + d as f64 * 86_400.0, String::new()),
        }
    }
}

/// Nearest-rank percentile `q` (0–1) of finite values.
pub fn percentile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    if (q - 0.5).abs() < 1e-12 {
        return crate::stats::median(v, crate::stats::EvenMedian::Mean).unwrap_or(f64::NAN);
    }
    let rank = (q * v.len() as f64).ceil().max(1.0) as usize;
    v[rank - 1]
}

/// Median and P90 of each gait value over level-walking bouts longer than 30 s (stair bouts
/// are not level gait: `monitor::stairs`); withheld with too few.
fn gait_of(
    bouts: &[&BoutRow],
    min: usize,
    withheld: &mut Vec<String>,
) -> (usize, [f64; 6], [f64; 6]) {
    let long: Vec<&&BoutRow> = bouts
        .iter()
        .filter(|b| b.duration_s > 30.0 && b.kind == BoutKind::Walking)
        .collect();
    let mut med = [f64::NAN; 6];
    let mut p90 = [f64::NAN; 6];
    for (k, col) in GAIT_AGGREGATES.iter().enumerate() {
        let mut v: Vec<f64> = long
            .iter()
            .map(|b| gait_values(b)[k])
            .filter(|x| x.is_finite())
            .collect();
        if v.len() < min {
            withheld.push(format!(
                "{col}: {} level bout(s) over 30 s measure it, {min} needed",
                v.len()
            ));
            continue;
        }
        med[k] = percentile(&mut v, 0.5);
        p90[k] = percentile(&mut v, 0.9);
    }
    (long.len(), med, p90)
}

/// The longest walk: bouts chained by `continues` joined.
fn longest(bouts: &[&BoutRow]) -> f64 {
    let mut best: f64 = 0.0;
    let mut run = 0.0;
    for b in bouts {
        run += b.duration_s;
        best = best.max(run);
        if !b.continues {
            run = 0.0;
        }
    }
    best
}

/// The day rows.
pub fn days(
    states: &BTreeMap<i64, Activity>,
    bouts: &[BoutRow],
    clock: &DayClock,
    p: &MonitorParams,
) -> Vec<DayRow> {
    let mut rows: BTreeMap<i64, DayRow> = BTreeMap::new();
    fn row<'r>(rows: &'r mut BTreeMap<i64, DayRow>, clock: &DayClock, d: i64) -> &'r mut DayRow {
        rows.entry(d).or_insert_with(|| {
            let (start_s, date) = clock.start_of(d);
            DayRow {
                day: (d + 1).max(1) as usize,
                date,
                start_s,
                ..DayRow::default()
            }
        })
    }
    for (&m, &s) in states {
        let r = row(&mut rows, clock, clock.day_of(m as f64 * 60.0 + 30.0));
        let h = 1.0 / 60.0;
        if s != Activity::NoData {
            r.recorded_h += h;
        }
        match s {
            Activity::NoData => {}
            Activity::NonWear => r.non_wear_h += h,
            Activity::Lying => r.lying_h += h,
            Activity::Sitting => r.sitting_h += h,
            Activity::Standing => r.standing_h += h,
            Activity::Cycling => r.cycling_min += 1.0,
            Activity::Running => r.running_min += 1.0,
            _ => {}
        }
        if !matches!(s, Activity::NoData | Activity::NonWear) {
            r.wear_h += h;
            if s != Activity::Lying {
                r.waking_wear_h += h;
            }
        }
    }
    for b in bouts {
        row(&mut rows, clock, clock.day_of(b.start_s));
    }
    rows.into_iter()
        .map(|(d, mut r)| {
            let mine: Vec<&BoutRow> = bouts
                .iter()
                .filter(|b| clock.day_of(b.start_s) == d)
                .collect();
            fill_day(&mut r, &mine, p);
            r
        })
        .collect()
}

fn fill_day(r: &mut DayRow, mine: &[&BoutRow], p: &MonitorParams) {
    let mut withheld = Vec::new();
    r.valid = r.waking_wear_h >= p.min_wear_h;
    let count = |lo: f64, hi: f64| {
        mine.iter()
            .filter(|b| b.duration_s >= lo && b.duration_s < hi)
            .count() as f64
    };
    r.walking_min = mine.iter().map(|b| b.duration_s).sum::<f64>() / 60.0;
    r.steps = mine.iter().map(|b| b.steps as f64).sum();
    r.bouts = mine.len() as f64;
    r.bouts_10_30s = count(10.0, 30.0);
    r.bouts_30_60s = count(30.0, 60.0);
    r.bouts_over_60s = count(60.0, f64::INFINITY);
    r.longest_bout_s = longest(mine);
    if !r.valid {
        let why = format!(
            "not a valid day: {:.1} h of waking wear, {} h needed",
            r.waking_wear_h, p.min_wear_h
        );
        for (col, v) in [
            ("walking_min", &mut r.walking_min),
            ("steps", &mut r.steps),
            ("bouts", &mut r.bouts),
            ("bouts_10_30s", &mut r.bouts_10_30s),
            ("bouts_30_60s", &mut r.bouts_30_60s),
            ("bouts_over_60s", &mut r.bouts_over_60s),
            ("longest_bout_s", &mut r.longest_bout_s),
        ] {
            *v = f64::NAN;
            withheld.push(format!("{col}: {why}"));
        }
    }
    let (n, med, p90) = gait_of(mine, p.min_long_bouts, &mut withheld);
    r.long_bouts = n;
    r.gait_median = med;
    r.gait_p90 = p90;
    r.withheld = withheld.join("; ");
}

/// The period's summary over its valid days.
pub fn summary(
    days: &[DayRow],
    bouts: &[BoutRow],
    clock: &DayClock,
    drift: &ClockDrift,
    p: &MonitorParams,
) -> SummaryRow {
    let valid: Vec<&DayRow> = days.iter().filter(|d| d.valid).collect();
    let mut withheld = Vec::new();
    let mean = |f: &dyn Fn(&DayRow) -> f64| -> f64 {
        if valid.is_empty() {
            f64::NAN
        } else {
            valid.iter().map(|d| f(d)).sum::<f64>() / valid.len() as f64
        }
    };
    let ok = valid.len() >= p.min_valid_days;
    let mut s = SummaryRow {
        days: days.len(),
        valid_days: valid.len(),
        valid: ok,
        wear_h_per_day: mean(&|d| d.wear_h),
        walking_min_per_day: mean(&|d| d.walking_min),
        steps_per_day: mean(&|d| d.steps),
        bouts_per_day: mean(&|d| d.bouts),
        longest_bout_s: valid
            .iter()
            .map(|d| d.longest_bout_s)
            .fold(f64::NAN, f64::max),
        drift_ppm: drift.ppm(),
        drift_s_per_day: drift.s_per_day(),
        ..SummaryRow::default()
    };
    if !ok {
        let why = format!("{} valid day(s), {} needed", valid.len(), p.min_valid_days);
        for (col, v) in [
            ("wear_h_per_day", &mut s.wear_h_per_day),
            ("walking_min_per_day", &mut s.walking_min_per_day),
            ("steps_per_day", &mut s.steps_per_day),
            ("bouts_per_day", &mut s.bouts_per_day),
            ("longest_bout_s", &mut s.longest_bout_s),
        ] {
            *v = f64::NAN;
            withheld.push(format!("{col}: {why}"));
        }
    }
    let valid_days: Vec<usize> = valid.iter().map(|d| d.day).collect();
    let mine: Vec<&BoutRow> = bouts
        .iter()
        .filter(|b| valid_days.contains(&((clock.day_of(b.start_s) + 1).max(1) as usize)))
        .collect();
    let (n, med, p90) = gait_of(&mine, p.min_long_bouts, &mut withheld);
    s.long_bouts = n;
    s.gait_median = med;
    s.gait_p90 = p90;
    if drift.pairs < 2 {
        s.drift_ppm = f64::NAN;
        s.drift_s_per_day = f64::NAN;
        withheld.push(format!(
            "drift_ppm: {} bout(s) paired between the legs, 2 needed over at least an hour",
            drift.pairs
        ));
    }
    s.withheld = withheld.join("; ");
    s
}
