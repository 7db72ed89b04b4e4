//! The recording: one shank IMU, uniformly sampled, in canonical units.
//!
//! This is the first data type of the pipeline (recording → preprocessed → attitude → events →
//! strides → features). Whatever the vendor format, a [`Recording`] holds acceleration in g and
//! angular velocity in deg/s on a uniform time grid whose rate was measured from the data
//! (SPEC §2; paper §2.2 for the sensor axes: x along the shank, y anterior-posterior,
//! z medio-lateral).

use serde::{Deserialize, Serialize};
use std::path::PathBuf;

pub use crate::domain::{Setting, Side};
use crate::error::{LdhError, Result};

/// Standard gravity in m/s² (the conversion factor between g and m/s²).
pub const STANDARD_GRAVITY_MPS2: f64 = 9.80665;

/// One shank IMU recording on a uniform time grid.
///
/// Invariants (checked by [`Recording::new`]): all six channels have the same length ≥ 2, every
/// value is finite, `fs_hz` is finite and positive.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Recording {
    /// The file it was read from, if any.
    pub source: Option<PathBuf>,
    /// The leg, if known.
    pub side: Option<Side>,
    /// Sampling rate in Hz, measured from the timestamps (or stated where the file has none).
    pub fs_hz: f64,
    /// Time of the first sample in seconds, in the file's own clock (0 when the file has no time).
    pub t0_s: f64,
    /// Acceleration (specific force) in g, channels x, y, z of the sensor.
    pub acc_g: [Vec<f64>; 3],
    /// Angular velocity in deg/s, channels x, y, z of the sensor.
    pub gyro_dps: [Vec<f64>; 3],
    /// `true` for samples where any channel was at the sensor's range (clipped). Such samples
    /// are outliers, not data: preprocessing replaces them by interpolation, on the channels of
    /// the sensor that clipped (see `acc_saturated`, `gyro_saturated`).
    pub saturated: Vec<bool>,
    /// `true` for samples where an accelerometer channel was clipped. Empty when the source did
    /// not say which sensor clipped: every `saturated` sample then counts for both sensors.
    /// Set with [`Recording::with_sensor_saturation`].
    #[serde(default)]
    pub acc_saturated: Vec<bool>,
    /// `true` for samples where a gyroscope channel was clipped; empty as `acc_saturated`.
    #[serde(default)]
    pub gyro_saturated: Vec<bool>,
    /// When the recording started, where its file says it (`io::RecordedAt`); `None` when
    /// the file does not, or the recording did not come from a file.
    #[serde(default)]
    pub recorded_at: Option<crate::io::RecordedAt>,
}

impl Recording {
    /// Build a recording from channels, checking the invariants.
    ///
    /// `saturated` may be empty (no sample flagged).
    pub fn new(
        fs_hz: f64,
        acc_g: [Vec<f64>; 3],
        gyro_dps: [Vec<f64>; 3],
        saturated: Vec<bool>,
    ) -> Result<Self> {
        let n = acc_g[0].len();
        let saturated = if saturated.is_empty() {
            vec![false; n]
        } else {
            saturated
        };
        let rec = Recording {
            source: None,
            side: None,
            fs_hz,
            t0_s: 0.0,
            acc_g,
            gyro_dps,
            saturated,
            acc_saturated: Vec::new(),
            gyro_saturated: Vec::new(),
            recorded_at: None,
        };
        rec.validate()?;
        Ok(rec)
    }

    /// Say which sensor clipped where: `acc` and `gyro` (one entry per sample each) replace the
    /// sensor masks, and `saturated` becomes their union. Preprocessing then replaces each
    /// sensor's channels only where that sensor clipped: a heel-strike impact beyond a ±2 g
    /// accelerometer leaves the angular velocity of the same sample valid, and interpolating
    /// the gyroscope over such samples removes rotation from the attitude's integral.
    pub fn with_sensor_saturation(mut self, acc: Vec<bool>, gyro: Vec<bool>) -> Result<Self> {
        self.saturated = acc.iter().zip(&gyro).map(|(a, g)| *a || *g).collect();
        self.acc_saturated = acc;
        self.gyro_saturated = gyro;
        self.validate()?;
        Ok(self)
    }

    /// Whether the accelerometer clipped at sample `i` (any clipped sample when the recording
    /// does not say which sensor clipped).
    pub fn acc_saturated_at(&self, i: usize) -> bool {
        if self.acc_saturated.is_empty() {
            self.saturated[i]
        } else {
            self.acc_saturated[i]
        }
    }

    /// Whether the gyroscope clipped at sample `i` (any clipped sample when the recording does
    /// not say which sensor clipped).
    pub fn gyro_saturated_at(&self, i: usize) -> bool {
        if self.gyro_saturated.is_empty() {
            self.saturated[i]
        } else {
            self.gyro_saturated[i]
        }
    }

    /// Check the invariants of [`Recording::new`] on a recording whose public fields may have
    /// been set directly: `fs_hz` finite and > 0, `t0_s` finite, six channels of one length ≥ 2,
    /// every value finite, and a saturation mask of the same length.
    ///
    /// The pipeline ([`crate::pipeline::Analysis::leg`]) calls this first, so a hand-built
    /// recording that breaks them is refused with an error rather than reaching the algorithms.
    pub fn validate(&self) -> Result<()> {
        let fs_hz = self.fs_hz;
        if !(fs_hz.is_finite() && fs_hz > 0.0) {
            return Err(LdhError::param("fs_hz", fs_hz, "must be finite and > 0"));
        }
        if !self.t0_s.is_finite() {
            return Err(LdhError::param("t0_s", self.t0_s, "must be finite"));
        }
        let n = self.acc_g[0].len();
        let names = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"];
        for (name, ch) in names
            .iter()
            .zip(self.acc_g.iter().chain(self.gyro_dps.iter()))
        {
            if ch.len() != n {
                return Err(LdhError::signal(
                    "recording",
                    format!("channel {name} has {} samples, acc_x has {n}", ch.len()),
                ));
            }
            if let Some(i) = first_non_finite(ch) {
                return Err(LdhError::signal(
                    "recording",
                    format!("channel {name} has a non-finite value at sample {i}"),
                ));
            }
        }
        if n < 2 {
            return Err(LdhError::signal(
                "recording",
                format!("{n} samples: at least 2 are needed"),
            ));
        }
        if self.saturated.len() != n {
            return Err(LdhError::signal(
                "recording",
                format!(
                    "saturation mask has {} entries for {n} samples",
                    self.saturated.len()
                ),
            ));
        }
        for (name, mask) in [("acc", &self.acc_saturated), ("gyro", &self.gyro_saturated)] {
            if !mask.is_empty() && mask.len() != n {
                return Err(LdhError::signal(
                    "recording",
                    format!(
                        "{name} saturation mask has {} entries for {n} samples",
                        mask.len()
                    ),
                ));
            }
            if let Some(i) = first_unflagged(mask, &self.saturated) {
                return Err(LdhError::signal(
                    "recording",
                    format!(
                        "{name} saturated at sample {i}, which the saturation mask does not flag"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.acc_g[0].len()
    }

    /// Never true for a valid recording (kept for API completeness).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Duration in seconds, `(n - 1) / fs_hz`.
    pub fn duration_s(&self) -> f64 {
        (self.len().saturating_sub(1)) as f64 / self.fs_hz
    }

    /// Sample period in seconds.
    pub fn dt_s(&self) -> f64 {
        1.0 / self.fs_hz
    }

    /// Time of sample `i` in seconds from the first sample.
    pub fn time_s(&self, i: usize) -> f64 {
        i as f64 / self.fs_hz
    }

    /// Times of all samples in seconds from the first sample.
    pub fn times_s(&self) -> Vec<f64> {
        (0..self.len()).map(|i| self.time_s(i)).collect()
    }

    /// Number of samples flagged as saturated.
    pub fn saturated_count(&self) -> usize {
        self.saturated.iter().filter(|&&s| s).count()
    }

    /// Acceleration in m/s² (a converted copy).
    pub fn acc_mps2(&self) -> [Vec<f64>; 3] {
        self.acc_g
            .clone()
            .map(|c| c.into_iter().map(|v| v * STANDARD_GRAVITY_MPS2).collect())
    }

    /// A label for messages: the file name, or `<memory>`.
    pub fn label(&self) -> String {
        self.source
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_else(|| "<memory>".to_string())
    }

    /// With the source file set.
    pub fn with_source(mut self, path: impl Into<PathBuf>) -> Self {
        self.source = Some(path.into());
        self
    }

    /// With the side set.
    pub fn with_side(mut self, side: Side) -> Self {
        self.side = Some(side);
        self
    }
}

/// Samples per block of [`first_non_finite`] and [`first_unflagged`].
const BLOCK: usize = 64;

/// The index of the first value of `x` that is not finite. Checked a block at a time without
/// an exit per value, which the compiler vectorises (a pipeline run checks every channel of a
/// leg three times, and `position` compared one value at a time); the block that holds one is
/// then searched.
pub(crate) fn first_non_finite(x: &[f64]) -> Option<usize> {
    x.chunks(BLOCK).enumerate().find_map(|(b, c)| {
        let all = c.iter().fold(true, |ok, v| ok & v.is_finite());
        (!all).then(|| b * BLOCK + c.iter().position(|v| !v.is_finite()).unwrap_or(0))
    })
}

/// The first sample flagged in `mask` and not in `flags` (`flags` at least as long), as
/// [`first_non_finite`] a block at a time.
fn first_unflagged(mask: &[bool], flags: &[bool]) -> Option<usize> {
    let flags = &flags[..mask.len()];
    mask.chunks(BLOCK)
        .zip(flags.chunks(BLOCK))
        .enumerate()
        .find_map(|(b, (m, f))| {
            let any = m.iter().zip(f).fold(false, |a, (m, f)| a | (*m & !*f));
            any.then(|| b * BLOCK + m.iter().zip(f).position(|(m, f)| *m && !*f).unwrap_or(0))
        })
}

#[cfg(test)]
mod tests {

    #[test]
    fn blockwise_searches_find_the_first_offending_sample() {
        use super::{first_non_finite, first_unflagged};
        for n in [0, 1, 63, 64, 65, 200] {
            let x = vec![1.0; n];
            assert_eq!(first_non_finite(&x), None);
            let m = vec![false; n];
            assert_eq!(first_unflagged(&m, &m), None);
            for i in [0, n / 2, n.saturating_sub(1)]
                .into_iter()
                .filter(|&i| i < n)
            {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let mut y = x.clone();
                    y[i] = bad;
                    if i + 1 < n {
                        y[n - 1] = bad;
                    }
                    assert_eq!(first_non_finite(&y), Some(i), "n {n} at {i}");
                }
                let (mut mask, mut flags) = (m.clone(), m.clone());
                mask[i] = true;
                assert_eq!(first_unflagged(&mask, &flags), Some(i));
                flags[i] = true;
                assert_eq!(first_unflagged(&mask, &flags), None);
            }
        }
    }
    use super::*;
    use crate::pipeline::{Analysis, AnalysisParams};

    fn ok() -> Recording {
        let n = 500;
        let acc = [vec![1.0; n], vec![0.0; n], vec![0.0; n]];
        let gyro = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        Recording::new(100.0, acc, gyro, vec![]).unwrap()
    }

    /// The public fields can break the invariants; `validate` and the pipeline refuse that.
    #[test]
    fn hand_built_recordings_are_refused() {
        let mut bad = Vec::new();
        let mut r = ok();
        r.gyro_dps[2].pop();
        bad.push((r, "gyro_z has 499 samples"));
        let mut r = ok();
        r.saturated.truncate(10);
        bad.push((r, "saturation mask has 10 entries"));
        let mut r = ok();
        r.acc_g[1][7] = f64::NAN;
        bad.push((r, "acc_y has a non-finite value at sample 7"));
        let mut r = ok();
        r.fs_hz = f64::INFINITY;
        bad.push((r, "fs_hz"));
        let mut r = ok();
        r.t0_s = f64::NAN;
        bad.push((r, "t0_s"));
        for (r, msg) in bad {
            let e = r.validate().unwrap_err().to_string();
            assert!(e.contains(msg), "{e}");
            let analysis = Analysis::new(AnalysisParams::default().check().unwrap());
            let e = analysis.leg(&r, Side::Left, None).unwrap_err().to_string();
            assert!(e.contains(msg), "{e}");
        }
        assert!(ok().validate().is_ok());
    }

    /// A clipped accelerometer sample is replaced on the accelerometer only: the angular
    /// velocity of the same sample is data (heel strike beyond ±2 g). A clipped gyroscope
    /// sample is replaced on the gyroscope only. A recording that does not say which sensor
    /// clipped has both replaced, as before.
    #[test]
    fn clipped_samples_are_replaced_on_the_sensor_that_clipped() {
        let n = 200;
        let fs = 100.0;
        let wave = |f: f64, a: f64| -> Vec<f64> {
            (0..n)
                .map(|i| a * (2.0 * std::f64::consts::PI * f * i as f64 / fs).sin())
                .collect()
        };
        let acc = [wave(1.0, 0.3), wave(1.3, 0.2), wave(0.7, 0.1)]
            .map(|v| v.into_iter().map(|x| x + 1.0).collect::<Vec<f64>>());
        let gyro = [wave(1.0, 300.0), wave(0.9, 40.0), wave(1.1, 20.0)];
        let acc_sat: Vec<bool> = (0..n).map(|i| (23..28).contains(&i)).collect();
        let gyro_sat: Vec<bool> = (0..n).map(|i| (74..78).contains(&i)).collect();
        let clean = Recording::new(fs, acc.clone(), gyro.clone(), vec![]).unwrap();
        let split = clean
            .clone()
            .with_sensor_saturation(acc_sat.clone(), gyro_sat.clone())
            .unwrap();
        let any: Vec<bool> = split.saturated.clone();
        assert_eq!(split.saturated_count(), 9);
        let merged = Recording::new(fs, acc, gyro, any).unwrap();
        let p = crate::preprocess::PreprocessParams::default()
            .outlier_sd(100.0)
            .check(fs)
            .unwrap();
        let (c, s, m) = (
            crate::preprocess::preprocess(&clean, &p).unwrap(),
            crate::preprocess::preprocess(&split, &p).unwrap(),
            crate::preprocess::preprocess(&merged, &p).unwrap(),
        );
        assert!(c.replaced.is_empty());
        assert_eq!(s.replaced, vec![23, 24, 25, 26, 27]);
        // gyro: untouched at the accelerometer's clipped samples, replaced at its own
        let at = |x: &[Vec<f64>; 3], i: usize| x[0][i];
        assert!((at(&s.gyro_dps, 25) - at(&c.gyro_dps, 25)).abs() < 1e-3);
        assert!((at(&s.gyro_dps, 76) - at(&c.gyro_dps, 76)).abs() > 0.1);
        // acc: replaced at its own clipped samples, untouched at the gyroscope's
        assert!((at(&s.acc_g, 25) - at(&c.acc_g, 25)).abs() > 1e-4);
        assert!((at(&s.acc_g, 76) - at(&c.acc_g, 76)).abs() < 1e-6);
        // without the per-sensor masks both sensors are replaced at every clipped sample
        assert_eq!(m.replaced.len(), 9);
        assert!((at(&m.gyro_dps, 25) - at(&c.gyro_dps, 25)).abs() > 0.1);
        // a sensor mask must agree with the mask of any clipped sample
        let mut bad = split.clone();
        bad.saturated[76] = false;
        assert!(bad.validate().is_err());
        assert!(clean
            .with_sensor_saturation(vec![true], vec![true])
            .is_err());
    }
}
