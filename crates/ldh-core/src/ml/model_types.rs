//! The types of the saved model file, defined below the code that reads, writes and checks
//! them ([`super::model`], [`super::model_check`], [`super::model_plausible`]) so that none of
//! those files needs another's: the schema tag, the classifier and fitted-model enums, the file
//! itself, its error type, the plausibility limits and the training summary.

use ndarray::Array2;
use serde::{Deserialize, Serialize};

use super::dataset::{MinMax, Task};
use super::forest::{Forest, ForestParams};
use super::mlp::{Mlp, MlpParams};
use super::svm::{SvmModel, SvmParams};

/// Version tag of the model file (2: with a checksum, validated on load; 3: with the training
/// summary and probes of [`super::model_plausible`], an exact checksum). Files of an older schema
/// are refused with a request to retrain: without a training summary their content cannot be
/// checked for plausibility.
pub const MODEL_SCHEMA: &str = "ldh-model/3";

/// A classifier and its parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Classifier {
    /// Random forest.
    RandomForest(ForestParams),
    /// RBF SVM.
    Svm(SvmParams),
    /// Multi-layer perceptron.
    Mlp(MlpParams),
}

/// A fitted classifier.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum FittedModel {
    /// Random forest.
    RandomForest(Forest),
    /// SVM.
    Svm(SvmModel),
    /// MLP.
    Mlp(Mlp),
}

/// A saved, trained model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelFile {
    /// [`MODEL_SCHEMA`].
    pub schema: String,
    /// ldh version that trained it.
    pub ldh_version: String,
    /// Task.
    pub task: Task,
    /// Feature names (columns of the per-recording table, units in the names).
    pub feature_names: Vec<String>,
    /// Class names in label order.
    pub class_names: Vec<String>,
    /// Scaling fitted on the training rows.
    pub scaling: MinMax,
    /// The classifier's parameters.
    pub classifier: Classifier,
    /// The fitted model.
    pub model: FittedModel,
    /// Training rows per class.
    pub trained_rows_per_class: Vec<usize>,
    /// Attitude model of the features (`fusion` or `acc`).
    pub attitude_model: String,
    /// What the training rows looked like, and the model's output at every class mean
    /// (checked on load, [`super::model_plausible`]).
    pub training: TrainingSummary,
    /// Where the model was read from (named in every error; not saved). Empty: `<model>`.
    #[serde(skip)]
    pub origin: String,
}

/// What is wrong with a model file. Every message starts with where the model came from.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// Not JSON at all (or truncated).
    #[error("{origin}: not a model file: not JSON: {reason}")]
    NotJson {
        /// The file (or `<model>`).
        origin: String,
        /// The parser's message (with line and column).
        reason: String,
    },
    /// A file larger than a model file may be ([`super::model_plausible::MODEL_MAX_MB`]).
    #[error("{origin}: not a model file: {size_mb:.1} MB, more than the {limit_mb} MB a model file may have")]
    TooLarge {
        /// The file.
        origin: String,
        /// Its size, MB (at least this much when it was not known in advance).
        size_mb: f64,
        /// The limit, MB.
        limit_mb: f64,
    },
    /// JSON without a `schema` field.
    #[error("{origin}: not an ldh model file (no schema field)")]
    NoSchema {
        /// The file.
        origin: String,
    },
    /// Another schema version.
    #[error("{origin}: model schema '{found}' is not supported by this ldh (expects '{MODEL_SCHEMA}'): retrain with ldh train")]
    Schema {
        /// The file.
        origin: String,
        /// The version found.
        found: String,
    },
    /// The checksum is missing or does not match the content.
    #[error("{origin}: checksum {found} does not match the content ({computed}): the model file was damaged or edited; restore it or retrain with ldh train")]
    Checksum {
        /// The file.
        origin: String,
        /// The checksum in the file (`missing` when absent).
        found: String,
        /// The checksum of the content.
        computed: String,
    },
    /// A field is missing or has the wrong type.
    #[error("{origin}: damaged model file: {reason}")]
    Damaged {
        /// The file.
        origin: String,
        /// The deserialiser's message.
        reason: String,
    },
    /// Arrays whose sizes do not fit together, or values that cannot be.
    #[error("{origin}: inconsistent model: {what}")]
    Inconsistent {
        /// The file.
        origin: String,
        /// Which array or value, and what was expected.
        what: String,
    },
    /// Content that `ldh train` cannot have written, though the file is sealed and consistent
    /// (an edit re-sealed with a recomputed checksum; [`super::model_plausible`]).
    #[error("{origin}: implausible model: {what}; retrain with ldh train")]
    Implausible {
        /// The file.
        origin: String,
        /// Which value, and what `ldh train` writes.
        what: String,
    },
    /// A feature of the model is not a column of the per-recording table (a model trained on
    /// arrays from Python under names of its own cannot classify recordings).
    #[error("{origin}: unknown feature '{feature}' in the model: not a column of the per-recording table (known: {known}); use a model trained by ldh train on recordings")]
    UnknownFeature {
        /// The file.
        origin: String,
        /// The feature.
        feature: String,
        /// The known columns.
        known: String,
    },
    /// The input's features differ from the model's by name or order.
    #[error("{origin}: the input's features do not match the model's: {detail} (the model was trained on {expected:?})")]
    Features {
        /// The model file.
        origin: String,
        /// What differs.
        detail: String,
        /// The model's features, in order.
        expected: Vec<String>,
    },
}

/// Largest model file read, MB: [`crate::io::MAX_MODEL_MB`] (its measurement is there).
pub const MODEL_MAX_MB: f64 = crate::io::MAX_MODEL_MB;
/// Most features of a model.
pub const MAX_FEATURES: usize = 256;
/// Most training rows of a model.
pub const MAX_TRAINING_ROWS: usize = 100_000;
/// Most trees of a forest.
pub const MAX_TREES: usize = 1000;
/// Most units of an MLP hidden layer.
pub const MAX_HIDDEN_UNITS: usize = 1024;
/// Largest |weight| or |bias| of an MLP.
pub const MAX_WEIGHT: f64 = 1e3;
/// Largest |value| of a feature in the training summary (any feature; the 13 parameters have
/// narrower ranges, [`super::model_plausible::physical_range`]).
pub const VALUE_BOUND: f64 = 1e9;
/// Smallest range of a non-constant feature.
pub const MIN_RANGE: f64 = 1e-9;

/// What the training rows looked like, stored in the model file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainingSummary {
    /// Training rows (the sum of the rows per class).
    pub rows: usize,
    /// Mean of every feature, in its units.
    pub mean: Vec<f64>,
    /// Standard deviation (population) of every feature.
    pub sd: Vec<f64>,
    /// Smallest value of every feature.
    pub min: Vec<f64>,
    /// Largest value of every feature.
    pub max: Vec<f64>,
    /// The mean of every class with training rows, and the model's output there.
    pub probes: Vec<Probe>,
}

/// A class mean and the fitted model's output at it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Probe {
    /// Class label.
    pub class: usize,
    /// Mean of the class's training rows, per feature, unscaled.
    pub x: Vec<f64>,
    /// The model's output there: class probabilities (forest, MLP) or decision values (SVM).
    pub output: Vec<f64>,
}

impl TrainingSummary {
    /// The summary of training rows `x` (unscaled) with labels `y`; probes without outputs.
    pub fn of(x: &Array2<f64>, y: &[usize], n_classes: usize) -> TrainingSummary {
        let n = x.nrows().max(1) as f64;
        let (mut mean, mut sd, mut min, mut max) = (vec![], vec![], vec![], vec![]);
        for col in x.columns() {
            let lo = col.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = col.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            // Rounding can put the mean of equal values an ulp outside them: clamped, so the
            // summary's own rules hold exactly.
            let m = (col.sum() / n).clamp(lo, hi);
            mean.push(m);
            let var = col.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / n;
            sd.push(var.sqrt().min(0.5 * (hi - lo)));
            min.push(lo);
            max.push(hi);
        }
        let probes = (0..n_classes)
            .filter_map(|c| {
                let rows: Vec<usize> = (0..y.len()).filter(|&i| y[i] == c).collect();
                (!rows.is_empty()).then(|| Probe {
                    class: c,
                    x: x.columns()
                        .into_iter()
                        .zip(min.iter().zip(&max))
                        .map(|(col, (&lo, &hi))| {
                            let s: f64 = rows.iter().map(|&i| col[i]).sum();
                            (s / rows.len() as f64).clamp(lo, hi)
                        })
                        .collect(),
                    output: vec![],
                })
            })
            .collect();
        TrainingSummary {
            rows: x.nrows(),
            mean,
            sd,
            min,
            max,
            probes,
        }
    }
}
