//! Units a header does not state, inferred from the signal (docs/input.md, "Exports read
//! without a map"), and said: each assumption is a note of the read report and the column's
//! `unit_from` in `ldh inspect`.
//!
//! - **Time**: the median step between timestamps read in each candidate unit (s, ms, µs, ns;
//!   for Xsens/Movella `SampleTimeFine` µs or 100 µs ticks) gives a rate; the unit whose rate is
//!   within the reader's plausible rates (20–2000 Hz by default) is taken, the one nearest
//!   100 Hz when two are. The candidates are a factor 1000 apart (10 for `SampleTimeFine`, whose
//!   two readings are 1 MHz and 10 kHz clocks), so at most one is usually plausible.
//! - **Acceleration**: a shank sensor's acceleration magnitude has its median near 1 g (the
//!   rule of the unit check, `checks.rs`): a median in 0.5–2.5 reads as g, in 4.9–24.5 as m/s².
//! - **Angular rate**: walking turns the shank at 200–500 deg/s (3.5–9 rad/s). When the
//!   accelerometer shows movement (SD of the magnitude > 0.05 g), a 99th percentile of the
//!   largest axis below 20 reads as rad/s, otherwise deg/s; a sensor at rest cannot tell, and
//!   deg/s is assumed and said.
//!
//! A value that fits no unit keeps the default (s, g, deg/s) and the reader's checks refuse it
//! with their message (rate out of range, magnitude not 1 g).

use super::format::{AccUnit, FormatSpec, GyroUnit, TimeUnit};
use super::rows::Rows;
use super::timebase::RateBounds;
use super::units::Unit;
use crate::recording::STANDARD_GRAVITY_MPS2;

/// Which units of a header's columns are to be inferred from the signal.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Infer {
    /// The time unit, and from which candidates.
    pub time: Option<TimeGuess>,
    /// The acceleration unit (g or m/s²).
    pub acc: bool,
    /// The angular-rate unit (deg/s or rad/s).
    pub gyro: bool,
}

/// The candidate time units of a time column without a unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TimeGuess {
    /// A clock: s, ms, µs or ns.
    Clock,
    /// Xsens/Movella `SampleTimeFine`: µs (Movella DOT) or 100 µs ticks (MTi, MTw).
    SampleTimeFine,
}

/// What was assumed, per quantity, in the words `ldh inspect` shows as the unit's origin
/// (`assumed from the signal: median |acc| 9.79`); `None` where the unit was stated.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Assumed {
    /// Time.
    pub time: Option<String>,
    /// Acceleration.
    pub acc: Option<String>,
    /// Angular rate.
    pub gyro: Option<String>,
}

/// At most this many samples are looked at (evenly spaced): the medians and percentiles of a
/// long recording need no more.
const MAX_LOOKED_AT: usize = 50_000;

fn stride(n: usize) -> usize {
    (n / MAX_LOOKED_AT).max(1)
}

/// Set the units `infer` asks for in `spec` from the rows, noting each assumption.
pub(super) fn infer_units(
    spec: &mut FormatSpec,
    infer: Infer,
    rows: &Rows,
    bounds: &RateBounds,
    notes: &mut Vec<String>,
) -> Assumed {
    let mut out = Assumed::default();
    if let Some(guess) = infer.time {
        if let Some((unit, why, note)) = time_unit(&rows.time_raw, guess, bounds) {
            spec.time.unit = unit;
            out.time = Some(why);
            notes.push(note);
        }
    }
    if infer.acc {
        let (unit, why, note) = acc_unit(&rows.raw, spec.acc.scale);
        spec.acc.unit = unit;
        out.acc = Some(why);
        notes.push(note);
    }
    if infer.gyro {
        let to_g = spec.acc.scale * Unit::from(spec.acc.unit).to_internal();
        let (unit, why, note) = gyro_unit(&rows.raw, to_g, spec.gyro.scale);
        spec.gyro.unit = unit;
        out.gyro = Some(why);
        notes.push(note);
    }
    out
}

/// The time unit whose rate is plausible: (unit, short reason, note); `None` without steps.
fn time_unit(
    raw: &[f64],
    guess: TimeGuess,
    bounds: &RateBounds,
) -> Option<(TimeUnit, String, String)> {
    let k = stride(raw.len());
    let mut steps: Vec<f64> = raw
        .windows(2)
        .step_by(k)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0 && d.is_finite())
        .collect();
    if steps.is_empty() {
        return None;
    }
    let step = upper_median(&mut steps);
    let candidates: &[(TimeUnit, &str)] = match guess {
        TimeGuess::Clock => &[
            (TimeUnit::Seconds, "s"),
            (TimeUnit::Milliseconds, "ms"),
            (TimeUnit::Microseconds, "µs"),
            (TimeUnit::Nanoseconds, "ns"),
        ],
        TimeGuess::SampleTimeFine => &[
            (TimeUnit::Microseconds, "µs (Movella DOT)"),
            (
                TimeUnit::HundredMicroseconds,
                "100 µs ticks (Xsens MTi/MTw)",
            ),
        ],
    };
    let rate = |u: TimeUnit| 1.0 / (step * Unit::from_time(u).map_or(1.0, Unit::to_internal));
    let far = |u: TimeUnit| (rate(u) / 100.0).ln().abs();
    let plausible: Vec<&(TimeUnit, &str)> = candidates
        .iter()
        .filter(|(u, _)| (bounds.min_hz..=bounds.max_hz).contains(&rate(*u)))
        .collect();
    let pool: Vec<&(TimeUnit, &str)> = if plausible.is_empty() {
        candidates.iter().collect()
    } else {
        plausible.clone()
    };
    let &&(unit, name) = pool
        .iter()
        .min_by(|a, b| far(a.0).total_cmp(&far(b.0)))
        .expect("candidates");
    let others: Vec<String> = plausible
        .iter()
        .filter(|(u, _)| *u != unit)
        .map(|(u, n)| format!("{n}: {:.1} Hz", rate(*u)))
        .collect();
    let also = if others.is_empty() {
        String::new()
    } else {
        format!("; also plausible: {}", others.join(", "))
    };
    let fits = if plausible.is_empty() {
        format!(
            " — no unit gives a rate within {}–{} Hz",
            bounds.min_hz, bounds.max_hz
        )
    } else {
        String::new()
    };
    let why = format!("assumed from the time steps ({:.1} Hz)", rate(unit));
    let note = format!(
        "time unit not stated: the median step {step} reads as {:.1} Hz in {name}, assumed{also}{fits}",
        rate(unit)
    );
    Some((unit, why, note))
}

/// The acceleration magnitudes of every `stride`-th row, × `scale`.
fn magnitudes(raw: &[Vec<f64>; 6], first: usize, scale: f64) -> Vec<f64> {
    let n = raw[first].len();
    (0..n)
        .step_by(stride(n))
        .map(|i| {
            (0..3)
                .map(|a| (raw[first + a][i] * scale).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}

/// g or m/s² from the median magnitude: (unit, short reason, note).
fn acc_unit(raw: &[Vec<f64>; 6], scale: f64) -> (AccUnit, String, String) {
    let mut mag = magnitudes(raw, 0, scale);
    if mag.is_empty() {
        return (
            AccUnit::G,
            "assumed".into(),
            "acceleration unit not stated and no rows: g assumed".into(),
        );
    }
    let med = upper_median(&mut mag);
    let g = STANDARD_GRAVITY_MPS2;
    let (unit, how) = if (0.5..=2.5).contains(&med) {
        (AccUnit::G, "g")
    } else if (0.5 * g..=2.5 * g).contains(&med) {
        (AccUnit::Mps2, "m/s²")
    } else {
        (
            AccUnit::G,
            "neither g nor m/s² (a shank sensor reads about 1 g): g",
        )
    };
    let why = format!("assumed from the signal: median |acc| {med:.3}");
    let note = format!(
        "acceleration unit not stated: the median magnitude {med:.3} reads as {how}, assumed"
    );
    (unit, why, note)
}

/// deg/s or rad/s from the walking rotation: (unit, short reason, note). `to_g`: the factor
/// from the raw acceleration to g.
fn gyro_unit(raw: &[Vec<f64>; 6], to_g: f64, scale: f64) -> (GyroUnit, String, String) {
    let mag = magnitudes(raw, 0, to_g);
    let n = mag.len().max(1) as f64;
    let mean = mag.iter().sum::<f64>() / n;
    let sd = (mag.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / n).sqrt();
    let len = raw[3].len();
    let mut peak: Vec<f64> = (0..len)
        .step_by(stride(len))
        .map(|i| {
            (3..6)
                .map(|k| (raw[k][i] * scale).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    if peak.is_empty() {
        return (
            GyroUnit::Dps,
            "assumed".into(),
            "angular-rate unit not stated and no rows: deg/s assumed".into(),
        );
    }
    let k = ((peak.len() as f64 * 0.99) as usize).min(peak.len() - 1);
    let p99 = *peak.select_nth_unstable_by(k, |a, b| a.total_cmp(b)).1;
    let why = format!("assumed from the signal: 99th percentile |gyro| {p99:.2}");
    if sd <= 0.05 {
        let note = format!(
            "angular-rate unit not stated and the sensor barely moves (SD of |acc| {sd:.3} g): deg/s assumed, not checked"
        );
        return (GyroUnit::Dps, why, note);
    }
    let (unit, how) = if p99 < 20.0 {
        (
            GyroUnit::Rps,
            "rad/s (deg/s would be far too slow for walking)",
        )
    } else {
        (GyroUnit::Dps, "deg/s")
    };
    let note = format!(
        "angular-rate unit not stated: a 99th percentile of {p99:.2} while the shank moves reads as {how}, assumed"
    );
    (unit, why, note)
}

/// The upper median of a non-empty slice (`stats::median`, the crate's one median).
fn upper_median(v: &mut [f64]) -> f64 {
    crate::stats::median(v, crate::stats::EvenMedian::Upper).unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOUNDS: RateBounds = RateBounds {
        min_hz: 20.0,
        max_hz: 2000.0,
    };

    fn times(step: f64, n: usize) -> Vec<f64> {
        (0..n).map(|i| 1000.0 + i as f64 * step).collect()
    }

    #[test]
    fn the_time_unit_is_the_one_with_a_plausible_rate() {
        for (step, want) in [
            (0.01, TimeUnit::Seconds),
            (10.0, TimeUnit::Milliseconds),
            (16_667.0, TimeUnit::Microseconds),
            (5_000_000.0, TimeUnit::Nanoseconds),
        ] {
            let (u, _, note) = time_unit(&times(step, 50), TimeGuess::Clock, &BOUNDS).unwrap();
            assert_eq!(u, want, "{note}");
        }
        let (u, _, _) = time_unit(&times(100.0, 50), TimeGuess::SampleTimeFine, &BOUNDS).unwrap();
        assert_eq!(u, TimeUnit::HundredMicroseconds);
        let (u, _, _) =
            time_unit(&times(16_667.0, 50), TimeGuess::SampleTimeFine, &BOUNDS).unwrap();
        assert_eq!(u, TimeUnit::Microseconds);
        let (_, _, note) = time_unit(&times(1e-6, 50), TimeGuess::Clock, &BOUNDS).unwrap();
        assert!(note.contains("no unit gives a rate"), "{note}");
    }

    fn walk(acc_k: f64, gyro_k: f64, moving: bool) -> [Vec<f64>; 6] {
        let n = 1000;
        let s = |i: usize, f: f64| (i as f64 * f).sin();
        let m = if moving { 1.0 } else { 0.0 };
        [
            (0..n)
                .map(|i| acc_k * (1.0 + 0.3 * m * s(i, 0.06)))
                .collect(),
            (0..n).map(|i| acc_k * 0.1 * m * s(i, 0.05)).collect(),
            vec![0.0; n],
            (0..n).map(|i| gyro_k * 40.0 * s(i, 0.06)).collect(),
            vec![0.0; n],
            (0..n).map(|i| gyro_k * 300.0 * m * s(i, 0.06)).collect(),
        ]
    }

    #[test]
    fn acceleration_and_angular_rate_units_from_a_walk() {
        let g = STANDARD_GRAVITY_MPS2;
        let rad = std::f64::consts::PI / 180.0;
        assert_eq!(acc_unit(&walk(1.0, 1.0, true), 1.0).0, AccUnit::G);
        assert_eq!(acc_unit(&walk(g, 1.0, true), 1.0).0, AccUnit::Mps2);
        assert_eq!(gyro_unit(&walk(1.0, 1.0, true), 1.0, 1.0).0, GyroUnit::Dps);
        assert_eq!(gyro_unit(&walk(1.0, rad, true), 1.0, 1.0).0, GyroUnit::Rps);
        assert_eq!(
            gyro_unit(&walk(g, rad, true), 1.0 / g, 1.0).0,
            GyroUnit::Rps
        );
        let (u, _, note) = gyro_unit(&walk(1.0, rad, false), 1.0, 1.0);
        assert_eq!(u, GyroUnit::Dps);
        assert!(note.contains("barely moves"), "{note}");
    }
}
