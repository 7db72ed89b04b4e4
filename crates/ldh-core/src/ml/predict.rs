//! `ldh predict` as one call: classify per-recording rows with a saved model and render the
//! predictions table.

use super::model_plausible::MODEL_MAX_MB;
use super::ModelError;
use super::{ModelFile, Prediction};
use crate::error::{LdhError, Result};
use crate::output::RecordingRow;

/// Predictions of a model for per-recording rows, and their CSV.
#[derive(Debug, Clone)]
pub struct PredictOutcome {
    /// One per row, in row order.
    pub predictions: Vec<Prediction>,
    /// Rows that got no class (see each prediction's note).
    pub failed: usize,
    /// `predictions.csv`: subject_id, side, status (`ok` or `error`), predicted_class, one
    /// `p_<class>` column per class (4 decimals, empty without probabilities), note (commas
    /// replaced by semicolons).
    pub csv: String,
}

/// Classify `rows` with `model` (see [`ModelFile::predict_rows`]).
pub fn predict(model: &ModelFile, rows: &[RecordingRow]) -> Result<PredictOutcome> {
    let predictions = model.predict_rows(rows)?;
    let mut csv = String::from("subject_id,side,status,predicted_class");
    for c in &model.class_names {
        csv.push_str(&format!(",p_{c}"));
    }
    csv.push_str(",note\n");
    let mut failed = 0;
    for p in &predictions {
        let probs: Vec<String> = match &p.probabilities {
            Some(v) => v.iter().map(|x| format!("{x:.4}")).collect(),
            None => vec![String::new(); model.class_names.len()],
        };
        let status = if p.predicted_class.is_some() {
            "ok"
        } else {
            failed += 1;
            "error"
        };
        csv.push_str(&format!(
            "{},{},{status},{},{},{}\n",
            p.subject_id,
            p.side,
            p.predicted_class.as_deref().unwrap_or(""),
            probs.join(","),
            p.note.replace(',', ";")
        ));
    }
    Ok(PredictOutcome {
        predictions,
        failed,
        csv,
    })
}

/// Read a model file written by `ldh train` (see [`ModelFile::from_json`]): a regular file of
/// at most [`MODEL_MAX_MB`] (a folder, FIFO or device, or a larger file, is refused before
/// anything is parsed).
pub fn read_model(path: &std::path::Path) -> Result<ModelFile> {
    let origin = path.display().to_string();
    // The one opening of a model file (issue 37): a regular file, read up to the limit.
    let text = match crate::io::read_text_limited(path, MODEL_MAX_MB, "a model file") {
        Err(LdhError::TextTooLarge { size_mb, .. }) => {
            return Err(ModelError::TooLarge {
                origin,
                size_mb,
                limit_mb: MODEL_MAX_MB,
            }
            .into())
        }
        r => r?,
    };
    Ok(ModelFile::from_json(&text, &origin)?)
}
