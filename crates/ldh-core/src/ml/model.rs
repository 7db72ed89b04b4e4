//! Classifiers behind one interface, and the saved model file.
//!
//! The model file is JSON with a schema version, a checksum, the task, the feature names (with
//! units in them), the class names, the training-set scaling, the fitted model and training
//! metadata. [`ModelFile::from_json`] refuses another version, a checksum that does not match
//! and arrays whose sizes do not fit together ([`super::model_check`]);
//! [`ModelFile::check_features`] refuses an input whose features differ by name or order.

use ndarray::{Array2, Axis};
use serde::{Deserialize, Serialize};

use super::dataset::{Dataset, MinMax};
use super::forest::{Forest, ForestParams};
use super::mlp::{Mlp, MlpParams};
use super::model_plausible::probe_output;
pub use super::model_types::{Classifier, FittedModel, ModelError, ModelFile, MODEL_SCHEMA};
use super::model_types::{TrainingSummary, MODEL_MAX_MB};
use super::svm::{SvmModel, SvmParams};
use crate::error::{LdhError, Result};
use crate::output::Parameter;
use serde_json::Value;

impl Classifier {
    /// Short name (`rf`, `svm`).
    pub fn name(&self) -> &'static str {
        match self {
            Classifier::RandomForest(_) => "rf",
            Classifier::Svm(_) => "svm",
            Classifier::Mlp(_) => "mlp",
        }
    }
    /// The default classifier of a short name.
    pub fn from_name(name: &str, seed: u64) -> Result<Classifier> {
        match name {
            "rf" | "random-forest" => Ok(Classifier::RandomForest(ForestParams {
                seed,
                ..ForestParams::default()
            })),
            "svm" => Ok(Classifier::Svm(SvmParams::default())),
            "mlp" => Ok(Classifier::Mlp(MlpParams::default().seed(seed))),
            o => Err(LdhError::param("classifier", o, "expected rf, svm or mlp")),
        }
    }
    /// The same classifier with another seed (for repeats and folds).
    pub fn reseeded(&self, seed: u64) -> Classifier {
        match self {
            Classifier::RandomForest(p) => {
                Classifier::RandomForest(ForestParams { seed, ..p.clone() })
            }
            Classifier::Mlp(p) => Classifier::Mlp(p.clone().seed(seed)),
            c => c.clone(),
        }
    }
    /// Fit on (already scaled) rows.
    pub fn fit(&self, x: &Array2<f64>, y: &[usize], n_classes: usize) -> Result<FittedModel> {
        Ok(match self {
            Classifier::RandomForest(p) => {
                FittedModel::RandomForest(Forest::fit(p, x, y, n_classes)?)
            }
            Classifier::Svm(p) => FittedModel::Svm(SvmModel::fit(p, x, y, n_classes)?),
            Classifier::Mlp(p) => {
                let v = p
                    .clone()
                    .check()
                    .map_err(|e| LdhError::param("mlp", "", e.to_string()))?;
                FittedModel::Mlp(Mlp::fit(&v, x.view(), y)?)
            }
        })
    }
}

impl FittedModel {
    /// Predicted classes for (scaled) rows.
    pub fn predict(&self, x: &Array2<f64>) -> Result<Vec<usize>> {
        Ok(match self {
            FittedModel::RandomForest(f) => argmax_rows(&f.predict_proba(x)),
            FittedModel::Svm(s) => s.predict(x),
            FittedModel::Mlp(m) => m.predict(x)?.to_vec(),
        })
    }
    /// Class probabilities where the model has them (forest: vote shares; MLP: softmax; SVM:
    /// none), columns in class order.
    pub fn predict_proba(&self, x: &Array2<f64>, n_classes: usize) -> Result<Option<Array2<f64>>> {
        Ok(match self {
            FittedModel::RandomForest(f) => Some(f.predict_proba(x)),
            FittedModel::Svm(_) => None,
            FittedModel::Mlp(m) => {
                let p = m.predict_proba(x)?;
                // The MLP's columns are the classes it saw in training; map them to all classes.
                let mut full = Array2::<f64>::zeros((x.nrows(), n_classes));
                for (j, &c) in m.classes().iter().enumerate() {
                    if c < n_classes {
                        full.column_mut(c).assign(&p.column(j));
                    }
                }
                Some(full)
            }
        })
    }
}

/// Index of the largest value of every row (first on ties).
pub fn argmax_rows(p: &Array2<f64>) -> Vec<usize> {
    p.axis_iter(Axis(0))
        .map(|r| {
            r.iter()
                .enumerate()
                .fold((0, f64::MIN), |b, (j, &v)| if v > b.1 { (j, v) } else { b })
                .0
        })
        .collect()
}

impl ModelFile {
    /// Train on the whole dataset.
    pub fn train(ds: &Dataset, classifier: &Classifier, attitude_model: &str) -> Result<ModelFile> {
        ds.validate()?;
        let scaling = MinMax::fit(&ds.x);
        let model = classifier.fit(&scaling.transform(&ds.x), &ds.y, ds.class_names.len())?;
        let mut m = ModelFile {
            schema: MODEL_SCHEMA.into(),
            ldh_version: env!("CARGO_PKG_VERSION").into(),
            task: ds.task,
            feature_names: ds.feature_names.clone(),
            class_names: ds.class_names.clone(),
            scaling,
            classifier: classifier.clone(),
            model,
            trained_rows_per_class: ds.class_counts(),
            attitude_model: attitude_model.into(),
            training: TrainingSummary::of(&ds.x, &ds.y, ds.class_names.len()),
            origin: String::new(),
        };
        let outputs: Vec<Vec<f64>> = m
            .training
            .probes
            .iter()
            .map(|p| probe_output(&m, &p.x).unwrap_or_default())
            .collect();
        for (p, o) in m.training.probes.iter_mut().zip(outputs) {
            p.output = o;
        }
        Ok(m)
    }

    /// Where the model came from, for messages (`<model>` when it was not read from a file).
    pub fn origin(&self) -> &str {
        if self.origin.is_empty() {
            "<model>"
        } else {
            &self.origin
        }
    }

    /// The model file's JSON text, with its checksum. A model larger than the
    /// [`MODEL_MAX_MB`] that `ldh predict` reads is an error (train fewer trees or on fewer rows).
    pub fn to_json(&self) -> Result<String> {
        let mut v =
            serde_json::to_value(self).map_err(|e| LdhError::signal("model", e.to_string()))?;
        let sum = super::model_check::checksum(&v);
        if let Value::Object(m) = &mut v {
            m.insert("checksum".into(), Value::String(sum));
        }
        let text =
            serde_json::to_string(&v).map_err(|e| LdhError::signal("model", e.to_string()))?;
        if text.len() as f64 > MODEL_MAX_MB * 1e6 {
            return Err(LdhError::signal(
                "model",
                format!(
                    "the model file would be {:.1} MB, more than the {MODEL_MAX_MB} MB a model file may have: train fewer trees or on fewer rows",
                    text.len() as f64 / 1e6
                ),
            ));
        }
        Ok(text)
    }

    /// Parse a model file: the schema version, the checksum, then every array's size against
    /// the declared features and classes ([`super::model_check::validate`]). `origin` names the
    /// file in the messages.
    pub fn from_json(text: &str, origin: &str) -> std::result::Result<ModelFile, ModelError> {
        let v: Value = serde_json::from_str(text).map_err(|e| ModelError::NotJson {
            origin: origin.into(),
            reason: e.to_string(),
        })?;
        match v.get("schema").and_then(|s| s.as_str()) {
            Some(MODEL_SCHEMA) => {}
            Some(other) => {
                return Err(ModelError::Schema {
                    origin: origin.into(),
                    found: other.into(),
                })
            }
            None => {
                return Err(ModelError::NoSchema {
                    origin: origin.into(),
                })
            }
        }
        let computed = super::model_check::checksum(&v);
        let found = v
            .get("checksum")
            .and_then(|c| c.as_str())
            .unwrap_or("missing");
        if found != computed {
            return Err(ModelError::Checksum {
                origin: origin.into(),
                found: found.into(),
                computed,
            });
        }
        let mut m: ModelFile = serde_json::from_value(v).map_err(|e| ModelError::Damaged {
            origin: origin.into(),
            reason: e.to_string(),
        })?;
        super::model_check::validate(&m, origin)?;
        super::model_plausible::check(&m, origin)?;
        m.origin = origin.into();
        Ok(m)
    }

    /// Check an input's features against the model's, by name and order.
    pub fn check_features(&self, names: &[String]) -> std::result::Result<(), ModelError> {
        if names == self.feature_names.as_slice() {
            return Ok(());
        }
        let missing: Vec<&String> = self
            .feature_names
            .iter()
            .filter(|f| !names.contains(f))
            .collect();
        let extra: Vec<&String> = names
            .iter()
            .filter(|f| !self.feature_names.contains(f))
            .collect();
        let detail =
            if missing.is_empty() && extra.is_empty() && names.len() == self.feature_names.len() {
                let i = names
                    .iter()
                    .zip(&self.feature_names)
                    .position(|(a, b)| a != b)
                    .unwrap_or(0);
                format!(
                "the same features in another order (column {} is {:?}, the model expects {:?})",
                i + 1,
                names[i],
                self.feature_names[i]
            )
            } else {
                format!("missing {missing:?}, unexpected {extra:?}")
            };
        Err(ModelError::Features {
            origin: self.origin().into(),
            detail,
            expected: self.feature_names.clone(),
        })
    }

    /// Predict (labels and probabilities where the model has them) for unscaled rows.
    pub fn predict(&self, x: &Array2<f64>) -> Result<(Vec<usize>, Option<Array2<f64>>)> {
        if x.ncols() != self.feature_names.len() {
            return Err(LdhError::signal(
                "model",
                format!(
                    "{}: {} features given, the model needs {}",
                    self.origin(),
                    x.ncols(),
                    self.feature_names.len()
                ),
            ));
        }
        let xs = self.scaling.transform(x);
        Ok((
            self.model.predict(&xs)?,
            self.model.predict_proba(&xs, self.class_names.len())?,
        ))
    }
}

/// The prediction for one per-recording row (what `ldh predict` writes and the report shows).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Prediction {
    /// Subject.
    pub subject_id: String,
    /// `left` or `right`.
    pub side: String,
    /// The predicted class, or `None` when the row could not be classified (see `note`).
    pub predicted_class: Option<String>,
    /// Probability per class (in [`ModelFile::class_names`] order), when the model has them.
    pub probabilities: Option<Vec<f64>>,
    /// Why there is no prediction, or that the model gives no probabilities; else empty.
    pub note: String,
}

impl ModelFile {
    /// One line for reports: classifier, task and training rows per class.
    pub fn describe(&self) -> String {
        format!(
            "{} classifier, task {}, trained on {} rows",
            self.classifier.name(),
            self.task.as_str(),
            self.trained_rows_per_class
                .iter()
                .zip(&self.class_names)
                .map(|(n, c)| format!("{n} {c}"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }

    /// Classify per-recording rows one by one. A row that failed or lacks a feature gets no
    /// class and a note naming what is missing (the STA status when STA is the missing one);
    /// rows of another attitude model are an error for the whole call.
    pub fn predict_rows(&self, rows: &[crate::output::RecordingRow]) -> Result<Vec<Prediction>> {
        if let Some(r) = rows
            .iter()
            .find(|r| r.model.as_str() != self.attitude_model)
        {
            return Err(LdhError::param(
                "model",
                &r.model,
                format!(
                    "{}: the model was trained on features of the '{}' attitude model but the input has '{}' (subject {}): analyse with --model {}",
                    self.origin(), self.attitude_model, r.model, r.subject_id, self.attitude_model
                ),
            ));
        }
        // The model file's feature names become parameters here, once: a model trained on
        // other columns (arrays from Python) cannot classify per-recording rows.
        let features: Vec<Parameter> = self
            .feature_names
            .iter()
            .map(|f| Parameter::from_column(f))
            .collect::<std::result::Result<_, _>>()
            .map_err(|e| ModelError::UnknownFeature {
                origin: self.origin().into(),
                feature: e.0,
                known: Parameter::columns().join(", "),
            })?;
        let mut out = Vec::with_capacity(rows.len());
        for r in rows {
            let vals: Option<Vec<f64>> = features.iter().map(|&f| r.value(f)).collect();
            let mut p = Prediction {
                subject_id: r.subject_id.clone(),
                side: r.side.to_string(),
                predicted_class: None,
                probabilities: None,
                note: String::new(),
            };
            match (r.status.as_str(), vals) {
                ("ok", Some(v)) => {
                    let x = Array2::from_shape_vec((1, v.len()), v)
                        .map_err(|e| LdhError::signal("model", e.to_string()))?;
                    let (label, proba) = self.predict(&x)?;
                    p.predicted_class = Some(self.class_names[label[0]].clone());
                    p.probabilities = proba.map(|a| a.row(0).to_vec());
                    if p.probabilities.is_none() {
                        p.note = "no probabilities for this model".into();
                    }
                }
                _ if !r.is_ok() => p.note = r.error.clone(),
                _ => {
                    // Each missing feature with the reason it was withheld, when it was.
                    let missing: Vec<String> = features
                        .iter()
                        .filter(|&&f| r.value(f).is_none())
                        .map(|f| match r.withheld.reason(*f) {
                            Some(why) => format!("{} ({why})", f.column()),
                            None => f.column().to_string(),
                        })
                        .collect();
                    let sta = if r.parameters.sta_status.is_empty() {
                        String::new()
                    } else {
                        format!(" (STA: {})", r.parameters.sta_status)
                    };
                    p.note = format!("missing {}{sta}", missing.join(", "));
                }
            }
            out.push(p);
        }
        Ok(out)
    }
}
