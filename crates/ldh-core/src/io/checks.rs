//! The reader's plausibility checks on a read recording (SPEC §2, docs/input.md): magnitudes
//! that contradict the declared units are refused; channels that do not measure (constant, or
//! all six frozen for a second or more) are warned about.

use std::path::Path;

use super::format::{AccUnit, FormatSpec, GyroUnit};
use crate::error::{LdhError, Result};
use crate::recording::{Recording, STANDARD_GRAVITY_MPS2};
use crate::stats::{median, EvenMedian};

/// Refuse data whose magnitudes contradict the declared units.
///
/// Rules (documented in docs/input.md): the median acceleration magnitude must lie in
/// 0.5–2.5 g (a shank sensor spends most of the time near 1 g); the walking gyro must peak above
/// 20 deg/s when the accelerometer shows movement (SD of the magnitude > 0.05 g) — smaller peaks
/// mean rad/s declared as deg/s — and below 3000 deg/s (larger means deg/s declared as rad/s).
pub fn check_units_plausible(rec: &Recording, spec: &FormatSpec, path: &Path) -> Result<()> {
    let n = rec.len();
    let mut mag: Vec<f64> = (0..n)
        .map(|i| {
            (rec.acc_g[0][i].powi(2) + rec.acc_g[1][i].powi(2) + rec.acc_g[2][i].powi(2)).sqrt()
        })
        .collect();
    let mean = mag.iter().sum::<f64>() / n as f64;
    let sd = (mag.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    let median = median(&mut mag, EvenMedian::Upper).unwrap_or(f64::NAN);
    let declared_acc = match spec.acc.unit {
        AccUnit::G => "g",
        AccUnit::Mps2 => "m/s2",
    };
    let declared_gyro = match spec.gyro.unit {
        GyroUnit::Dps => "deg/s",
        GyroUnit::Rps => "rad/s",
    };
    if !(0.5..=2.5).contains(&median) {
        let hint = if (0.5 * STANDARD_GRAVITY_MPS2..=2.5 * STANDARD_GRAVITY_MPS2).contains(&median)
        {
            " — this looks like m/s² declared as g"
        } else if (0.5 / STANDARD_GRAVITY_MPS2..=2.5 / STANDARD_GRAVITY_MPS2).contains(&median) {
            " — this looks like g declared as m/s²"
        } else if median == 0.0 {
            " — the accelerometer reads zero: is it connected?"
        } else {
            ""
        };
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "median acceleration magnitude is {median:.3} g after converting from the declared unit '{declared_acc}' (×{}); a shank sensor reads about 1 g{hint}",
                spec.acc.scale
            ),
        });
    }
    let gyro_peak = rec
        .gyro_dps
        .iter()
        .flat_map(|c| c.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let gyro_constant = rec.gyro_dps.iter().all(|c| c.iter().all(|&v| v == c[0]));
    if sd > 0.05 && gyro_constant {
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "the accelerometer shows movement (SD {sd:.2} g) but the gyroscope reads a constant ({:.2}, {:.2}, {:.2}) deg/s on all three axes over the whole recording: is the gyroscope switched on and connected?",
                rec.gyro_dps[0][0], rec.gyro_dps[1][0], rec.gyro_dps[2][0]
            ),
        });
    }
    if sd > 0.05 && gyro_peak < 20.0 {
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "the accelerometer shows movement (SD {sd:.2} g) but the gyroscope peaks at only {gyro_peak:.2} deg/s after converting from the declared unit '{declared_gyro}'; walking gives 200–500 deg/s at the shank — is the gyroscope in rad/s?"
            ),
        });
    }
    if gyro_peak > 3000.0 {
        return Err(LdhError::Implausible {
            path: path.to_path_buf(),
            reason: format!(
                "the gyroscope peaks at {gyro_peak:.0} deg/s after converting from the declared unit '{declared_gyro}'; walking gives 200–500 deg/s — is it in deg/s declared as rad/s?"
            ),
        });
    }
    Ok(())
}

/// Warnings about channels that do not measure: a channel constant over the whole recording
/// (a dead axis or a disconnected sensor), and runs of at least one second in which all six
/// channels repeat the same values exactly (a sensor that stalled or lost its connection and
/// was padded by the logger). Real sensor noise never repeats six channels bit for bit.
pub fn flat_channel_warnings(
    acc_g: &[Vec<f64>; 3],
    gyro_dps: &[Vec<f64>; 3],
    fs: f64,
    t0: f64,
) -> Vec<String> {
    const NAMES: [&str; 6] = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"];
    let ch: Vec<&Vec<f64>> = acc_g.iter().chain(gyro_dps.iter()).collect();
    let n = ch[0].len();
    let mut out = Vec::new();
    if n < 2 {
        return out;
    }
    let constant: Vec<usize> = (0..6)
        .filter(|&k| ch[k].iter().all(|&v| v == ch[k][0]))
        .collect();
    if constant.len() == 6 {
        out.push(format!(
            "all six channels are constant over the whole recording (acc {:.3}, {:.3}, {:.3} g; gyro {:.2}, {:.2}, {:.2} deg/s): the sensor did not measure — disconnected, switched off, or a placeholder export?",
            ch[0][0], ch[1][0], ch[2][0], ch[3][0], ch[4][0], ch[5][0]
        ));
        return out;
    }
    if !constant.is_empty() {
        out.push(format!(
            "channel(s) {} constant over all {n} samples (at {}): a dead axis or a disconnected sensor?",
            constant.iter().map(|&k| NAMES[k]).collect::<Vec<_>>().join(", "),
            constant
                .iter()
                .map(|&k| format!("{}", ch[k][0]))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let min_run = ((fs.round() as usize).max(10)).min(n);
    let same = |i: usize| (0..6).all(|k| ch[k][i] == ch[k][i - 1]);
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut i = 1;
    while i < n {
        if same(i) {
            let s = i - 1;
            while i < n && same(i) {
                i += 1;
            }
            if i - s >= min_run {
                runs.push((s, i));
            }
        } else {
            i += 1;
        }
    }
    if let Some(&(a, b)) = runs.iter().max_by_key(|(a, b)| b - a) {
        let total: usize = runs.iter().map(|(a, b)| b - a).sum();
        out.push(format!(
            "all six channels frozen at the same values in {} run(s), {:.2} s in all (longest {:.2}–{:.2} s, acc {:.3}, {:.3}, {:.3} g): the sensor stopped measuring (disconnected or stalled) and those samples are not measurements",
            runs.len(),
            total as f64 / fs,
            t0 + a as f64 / fs,
            t0 + (b - 1) as f64 / fs,
            ch[0][a],
            ch[1][a],
            ch[2][a]
        ));
    }
    out
}
