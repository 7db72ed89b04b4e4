//! Sensor checks on the raw recording: gyroscope scale faults and clipping, accelerometer
//! clipping (docs/quality.md).
//!
//! Thresholds come from physiology, not from one data set: a healthy shank peaks at about
//! 300–500 deg/s in mid-swing (Aminian et al., J Biomech 2002;35:689–699; Salarian et al., IEEE
//! TBME 2004;51:1434–1443) and stays well below 1000–1200 deg/s even in fast walking, so a
//! gyroscope that spends more than [`SCALE_FAULT_SHARE`] of the recording above
//! [`SHANK_MAX_DPS`] is not measuring a walking shank.

use super::warning::{codes, params, Severity, Warning};
use crate::recording::Recording;

/// Highest angular velocity of a walking human shank, deg/s (healthy mid-swing peaks
/// 300–500 deg/s; a hard maximum well below 1000–1200 deg/s).
pub const SHANK_MAX_DPS: f64 = 1200.0;

/// Share of the samples above [`SHANK_MAX_DPS`] that makes a gyroscope scale fault (2 %: a few
/// artefact spikes are tolerated; a gyroscope amplified ×10 spends half the recording there).
pub const SCALE_FAULT_SHARE: f64 = 0.02;

/// Share of gyroscope samples clipped (flat runs at the channel's extreme) above which the
/// attitude and stride length are not vouched for, 0.5 %.
pub const GYRO_CLIP_SHARE: f64 = 0.005;

/// What the sensor checks found.
#[derive(Debug, Clone, Default)]
pub struct SensorFindings {
    /// Structured warnings.
    pub warnings: Vec<Warning>,
    /// Per sample: an accelerometer channel is clipped (for the per-stride stride-length check).
    pub acc_clipped: Vec<bool>,
    /// The gyroscope is faulty: nothing derived from it is vouched for.
    pub gyro_fault: bool,
    /// Partial faults of single channels, with their spans ([`super::faults`]); each has its
    /// warning in `warnings`.
    pub faults: Vec<super::faults::ChannelFault>,
}

/// Clipped samples of three channels: flat runs (≥ 3 equal values) at a channel's extreme, the
/// extreme at least `floor` (the reader's rule, [`crate::io::reader::detect_clipping`] without a known
/// range, so recordings built in memory are checked the same way).
fn clipped(ch: &[Vec<f64>; 3], floor: f64) -> Vec<bool> {
    let n = ch[0].len();
    let mut m = vec![false; n];
    for c in ch {
        for (f, x) in m
            .iter_mut()
            .zip(crate::io::reader::detect_clipping(c, None, floor))
        {
            *f |= x;
        }
    }
    m
}

/// Run the sensor checks on a recording.
pub fn sensor_checks(rec: &Recording) -> SensorFindings {
    let n = rec.len().max(1);
    let mut out = SensorFindings::default();
    let g = &rec.gyro_dps;
    let above = (0..rec.len())
        .filter(|&i| {
            (g[0][i] * g[0][i] + g[1][i] * g[1][i] + g[2][i] * g[2][i]).sqrt() > SHANK_MAX_DPS
        })
        .count();
    let share = above as f64 / n as f64;
    let gyro_clip = clipped(g, 200.0);
    let n_gclip = gyro_clip.iter().filter(|&&c| c).count();
    let gclip_share = n_gclip as f64 / n as f64;
    if share > SCALE_FAULT_SHARE {
        out.gyro_fault = true;
        out.warnings.push(
            Warning::new(
                codes::GYRO_SCALE_FAULT,
                Severity::Fault,
                format!(
                    "gyroscope sensor fault: {:.1} % of the samples exceed {SHANK_MAX_DPS:.0} deg/s (a walking shank peaks at 300-500 deg/s){}; the gyroscope is probably amplified (e.g. ×10) or mis-scaled, so no parameter of this leg is measured",
                    share * 100.0,
                    if n_gclip > 0 {
                        format!(", and {:.1} % are clipped at the range", gclip_share * 100.0)
                    } else {
                        String::new()
                    }
                ),
            )
            .withholding(&params::ALL),
        );
    } else if gclip_share > GYRO_CLIP_SHARE {
        let mut affects: Vec<crate::domain::Parameter> = params::ANGLES.to_vec();
        affects.extend(params::LENGTH);
        out.warnings.push(
            Warning::new(
                codes::GYRO_CLIPPING,
                Severity::Warning,
                format!(
                    "gyroscope clipped at its range in {:.1} % of the samples: the rotation in the clipped peaks is lost, so the shank angles and stride length are not measured",
                    gclip_share * 100.0
                ),
            )
            .withholding(&affects),
        );
    }
    out.faults = super::faults::detect_faults(rec);
    out.warnings
        .extend(out.faults.iter().map(super::faults::fault_warning));
    out.acc_clipped = clipped(&rec.acc_g, 1.5);
    let n_aclip = out.acc_clipped.iter().filter(|&&c| c).count();
    if n_aclip > 0 {
        out.warnings.push(Warning::new(
            codes::ACC_CLIPPING,
            Severity::Note,
            format!(
                "accelerometer clipped at its range in {:.1} % of the samples (common at ±2 g: push-off, swing and heel strike go beyond it); the stride length reconstructs the clipped samples and withholds strides it cannot vouch for",
                n_aclip as f64 / n as f64 * 100.0
            ),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn walk(fs: f64, secs: f64, gain: f64, clip: f64) -> Recording {
        let n = (fs * secs) as usize;
        let t = |i: usize| i as f64 / fs;
        let w = |i: usize| {
            (gain * 400.0 * (2.0 * std::f64::consts::PI * t(i)).sin()).clamp(-clip, clip)
        };
        Recording::new(
            fs,
            [
                (0..n).map(|i| 1.0 + 0.3 * (7.0 * t(i)).sin()).collect(),
                vec![0.0; n],
                (0..n).map(|i| 0.2 * (3.0 * t(i)).cos()).collect(),
            ],
            [vec![1.0; n], (0..n).map(w).collect(), vec![-2.0; n]],
            vec![],
        )
        .unwrap()
    }

    #[test]
    fn an_amplified_gyroscope_is_a_fault_and_a_clipped_one_a_warning() {
        let ok = sensor_checks(&walk(100.0, 20.0, 1.0, 1e9));
        assert!(
            ok.warnings.is_empty() && !ok.gyro_fault,
            "{:?}",
            ok.warnings
        );
        let x10 = sensor_checks(&walk(100.0, 20.0, 10.0, 2000.0));
        assert!(x10.gyro_fault);
        assert_eq!(x10.warnings[0].code, codes::GYRO_SCALE_FAULT);
        assert_eq!(x10.warnings[0].affects.len(), params::ALL.len());
        assert!(
            x10.warnings[0].message.contains("clipped"),
            "{}",
            x10.warnings[0].message
        );
        let cl = sensor_checks(&walk(100.0, 20.0, 1.0, 250.0));
        assert!(!cl.gyro_fault);
        assert_eq!(cl.warnings[0].code, codes::GYRO_CLIPPING);
        assert!(cl.warnings[0].withholds(crate::domain::Parameter::Wqk));
    }
}
