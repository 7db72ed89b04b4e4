//! `ldh inspect`: what the reader detected in a sensor file and what preprocessing did to it.

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::{read_recording, FormatSpec, ReadReport, ValidReadParams};
use crate::error::Result;
use crate::preprocess::{outlier_summary, PreprocessParams};

/// Preprocessing facts of an inspected file.
#[derive(Debug, Clone, Serialize)]
pub struct PreprocessSummary {
    /// Samples replaced as outliers.
    pub outliers_replaced: usize,
    /// Mean of the raw acceleration norm, g.
    pub raw_norm_mean_g: f64,
    /// SD of the raw acceleration norm, g.
    pub raw_norm_sd_g: f64,
}

/// One inspected file.
#[derive(Debug, Clone, Serialize)]
pub struct Inspection {
    /// The file.
    pub file: PathBuf,
    /// What the reader detected.
    pub read: ReadReport,
    /// What preprocessing did.
    pub preprocess: PreprocessSummary,
}

/// Read `file` (with `format`, or a detected built-in one) and preprocess it with the default
/// parameters (the outlier search only: the filtered channels are not reported, and not
/// keeping them holds the memory to the recording's).
pub fn inspect(
    file: &Path,
    format: Option<&FormatSpec>,
    rp: &ValidReadParams,
) -> Result<Inspection> {
    let (rec, read) = read_recording(file, format, rp)?;
    let pp = PreprocessParams::default().check(rec.fs_hz)?;
    let pre = outlier_summary(&rec, &pp)?;
    Ok(Inspection {
        file: file.to_path_buf(),
        read,
        preprocess: PreprocessSummary {
            outliers_replaced: pre.replaced.len(),
            raw_norm_mean_g: pre.raw_norm_mean_g,
            raw_norm_sd_g: pre.raw_norm_sd_g,
        },
    })
}

impl Inspection {
    /// One line: format, rate, duration, samples, clipping, outliers and the reader's notes.
    pub fn line(&self) -> String {
        let rd = &self.read;
        let notes = if rd.notes.is_empty() {
            String::new()
        } else {
            format!("; {}", rd.notes.join("; "))
        };
        format!(
            "{}: {} format, {:.2} Hz, {:.1} s, {} samples, {} clipped, {} outliers replaced{notes}",
            self.file.display(),
            rd.format,
            rd.fs_hz,
            rd.duration_s,
            rd.samples,
            rd.saturated_samples,
            self.preprocess.outliers_replaced,
        )
    }

    /// One line per column read: the channel it feeds, the unit understood and where it came
    /// from, the conversion applied (`column 2 'Acc_X [m/s^2]' → acc_x: m/s² (header), ÷ 9.80665
    /// (m/s² → g)`).
    pub fn column_lines(&self) -> Vec<String> {
        self.read.columns.iter().map(|c| c.line()).collect()
    }

    /// As JSON with the keys sorted (the `ldh inspect --json` layout).
    pub fn to_json(&self) -> Result<serde_json::Value> {
        Ok(serde_json::to_value(self)?)
    }
}
