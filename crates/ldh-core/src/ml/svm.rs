//! RBF support vector machine on linfa-svm: C-SVC with a Gaussian kernel, γ = 1 / (p · Var X)
//! (scikit-learn's `gamma="scale"`) and C = 1 by default; one-vs-rest on the decision values for
//! more than two classes (linfa has no one-vs-one; the winning class is the largest decision
//! value). No probabilities: the decision values are not calibrated.

use linfa::prelude::*;
use linfa_svm::Svm;
use ndarray::{Array1, Array2};
use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};

/// SVM parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SvmParams {
    /// Regularisation C. Default 1.
    pub c: f64,
    /// Kernel γ; `None`: 1 / (p · Var X) of the training rows ("scale"). Default None.
    pub gamma: Option<f64>,
}

impl Default for SvmParams {
    fn default() -> Self {
        SvmParams {
            c: 1.0,
            gamma: None,
        }
    }
}

/// A fitted SVM: one binary machine per class (one only for two classes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SvmModel {
    /// Number of classes.
    pub n_classes: usize,
    /// γ used.
    pub gamma: f64,
    /// Machines: for two classes one (positive = class 1), else one per class (that class vs rest).
    pub machines: Vec<Svm<f64, bool>>,
}

impl SvmModel {
    /// Fit on (scaled) rows.
    pub fn fit(p: &SvmParams, x: &Array2<f64>, y: &[usize], n_classes: usize) -> Result<SvmModel> {
        if !(p.c.is_finite() && p.c > 0.0) {
            return Err(LdhError::param("c", p.c, "must be > 0"));
        }
        let var = {
            let n = x.len() as f64;
            let m = x.sum() / n;
            x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n
        };
        let gamma = p
            .gamma
            .unwrap_or(1.0 / (x.ncols() as f64 * if var > 0.0 { var } else { 1.0 }));
        let targets: Vec<usize> = if n_classes == 2 {
            vec![1]
        } else {
            (0..n_classes).collect()
        };
        let mut machines = Vec::new();
        for t in targets {
            let yb = Array1::from(y.iter().map(|&c| c == t).collect::<Vec<bool>>());
            if yb.iter().all(|&b| b) || yb.iter().all(|&b| !b) {
                return Err(LdhError::signal(
                    "svm",
                    format!("class {t} is absent or alone in the training rows"),
                ));
            }
            let ds = Dataset::new(x.clone(), yb);
            let m = Svm::<f64, bool>::params()
                .pos_neg_weights(p.c, p.c)
                .gaussian_kernel(1.0 / gamma)
                .fit(&ds)
                .map_err(|e| LdhError::signal("svm", e.to_string()))?;
            machines.push(m);
        }
        Ok(SvmModel {
            n_classes,
            gamma,
            machines,
        })
    }

    /// Decision values (rows × machines).
    pub fn decision(&self, x: &Array2<f64>) -> Array2<f64> {
        let mut d = Array2::<f64>::zeros((x.nrows(), self.machines.len()));
        for (j, m) in self.machines.iter().enumerate() {
            for (i, row) in x.rows().into_iter().enumerate() {
                d[[i, j]] = m.weighted_sum(&row) - m.rho;
            }
        }
        d
    }

    /// Predicted classes.
    pub fn predict(&self, x: &Array2<f64>) -> Vec<usize> {
        let d = self.decision(x);
        d.rows()
            .into_iter()
            .map(|r| {
                if self.n_classes == 2 {
                    usize::from(r[0] >= 0.0)
                } else {
                    r.iter()
                        .enumerate()
                        .fold((0, f64::MIN), |b, (j, &v)| if v > b.1 { (j, v) } else { b })
                        .0
                }
            })
            .collect()
    }
}
