//! Plausibility of a saved model's content on its own (issue 37). The checksum
//! ([`super::model_check`]) catches damage, not an edit re-sealed with a recomputed checksum;
//! these rules refuse content that `ldh train` cannot have written, whatever the checksum says:
//!
//! * **Sizes.** At most [`MAX_FEATURES`] features, [`MAX_TRAINING_ROWS`] training rows,
//!   [`MAX_TREES`] trees of at most 2·rows − 1 nodes each (a bootstrap sample of `rows` rows
//!   has at most `rows` leaves), SVM machines of at most `rows` support vectors, MLPs of at most
//!   2 hidden layers of at most [`MAX_HIDDEN_UNITS`] units (and the layers the stored parameters
//!   name). The file itself is read only up to [`MODEL_MAX_MB`] (`read_model`).
//! * **Training summary.** `training` (written by `ldh train` since `ldh-model/3`): rows (= the
//!   rows per class), per feature the mean, SD, minimum and maximum in the feature's units, and
//!   the mean of every class. All finite, |value| ≤ [`VALUE_BOUND`], min ≤ mean ≤ max,
//!   0 ≤ SD ≤ (max − min) / 2, the class means inside [min, max] and averaging (weighted by the
//!   rows per class) to the mean. The scaler must be the one fitted on that summary, bit for bit:
//!   `min` = the minima, `range` = max − min (1 for a constant feature), and a range of at least
//!   [`MIN_RANGE`] (a 1e-300 range would multiply the inputs by 1e300).
//! * **Feature order.** A feature named as one of the 13 parameters must have its minimum and
//!   maximum inside the parameter's physical range ([`physical_range`]) and its mean must keep the
//!   relations the parameters have with each other in walking: stance + swing ratio = 1 with
//!   stance the larger, stride time ≈ 2 × step time, step frequency × stride time ≈ 2, speed ≈
//!   stride length × step frequency / 2. Two features swapped in the names (or in the scaler and
//!   summary together) break one of these. Features of the same unit and range (the three angles,
//!   the two CVs) cannot be told apart this way; the probes below catch a swap of their columns.
//! * **Probes.** The model's output (forest and MLP: class probabilities; SVM: decision values)
//!   at every class mean, recorded at training. On load the model is run on those means and must
//!   give the recorded outputs (within 1e-9). An edit of the fitted model that changes what it
//!   predicts there (permuted leaf counts, swapped scaler columns, a weight changed) is refused.
//! * **Values.** Random forest: as many trees as the stored `n_trees`; leaf counts whole numbers,
//!   every tree's leaves counting `rows` rows (its bootstrap sample), no counts for a class
//!   without training rows, every class's count over the trees within 8 binomial SDs of its
//!   share of the training rows; thresholds inside [0, 1] (midpoints of scaled training values);
//!   no split whose rows were all of one class. SVM: γ between 1/p and 2·rows (scikit-learn's
//!   "scale" on scaled rows; or the stored γ), the kernel width 1/γ, |α| ≤ C, |ρ| ≤ rows·C + 1,
//!   support vectors inside [0, 1] (scaled training rows). MLP: |weight| and |bias| ≤
//!   [`MAX_WEIGHT`] (Adam moves a weight by at most ≈3.2 × the learning rate per step: 200
//!   epochs of default training move it by less than 10 on the cohort's few hundred rows), class
//!   labels increasing and each with training rows, at most `max_iter` epochs.

use ndarray::Array2;

use super::model_types::{FittedModel, ModelError, ModelFile};
pub use super::model_types::{
    Probe, TrainingSummary, MAX_FEATURES, MAX_HIDDEN_UNITS, MAX_TRAINING_ROWS, MAX_TREES,
    MAX_WEIGHT, MIN_RANGE, MODEL_MAX_MB, VALUE_BOUND,
};
use crate::output::Parameter;

/// The output a probe records: probabilities where the model has them, else decision values.
pub fn probe_output(m: &ModelFile, x: &[f64]) -> Option<Vec<f64>> {
    let row = Array2::from_shape_vec((1, x.len()), x.to_vec()).ok()?;
    let xs = m.scaling.transform(&row);
    match &m.model {
        FittedModel::Svm(s) => Some(s.decision(&xs).row(0).to_vec()),
        f => f
            .predict_proba(&xs, m.class_names.len())
            .ok()
            .flatten()
            .map(|p| p.row(0).to_vec()),
    }
}

/// Physical range of a feature that is a parameter ([`crate::domain::Definition::range`]).
pub fn physical_range(p: Parameter) -> (f64, f64) {
    p.definition().range
}

fn bad(origin: &str, what: impl Into<String>) -> ModelError {
    ModelError::Implausible {
        origin: origin.into(),
        what: what.into(),
    }
}

/// Check the plausibility rules of the module docs on a structurally valid model.
pub fn check(m: &ModelFile, origin: &str) -> Result<(), ModelError> {
    check_summary(m, origin)?;
    check_feature_order(m, origin)?;
    match &m.model {
        FittedModel::RandomForest(f) => super::model_plausible_fit::check_forest(m, f, origin)?,
        FittedModel::Svm(s) => super::model_plausible_fit::check_svm(m, s, origin)?,
        FittedModel::Mlp(p) => super::model_plausible_fit::check_mlp(m, p, origin)?,
    }
    check_probes(m, origin)
}

fn check_summary(m: &ModelFile, origin: &str) -> Result<(), ModelError> {
    let t = &m.training;
    let nf = m.feature_names.len();
    if nf > MAX_FEATURES {
        return Err(bad(
            origin,
            format!("{nf} features, more than {MAX_FEATURES}"),
        ));
    }
    let total: usize = m.trained_rows_per_class.iter().sum();
    if t.rows != total || !(2..=MAX_TRAINING_ROWS).contains(&t.rows) {
        return Err(bad(
            origin,
            format!(
                "training.rows = {} for {total} rows per class (2 to {MAX_TRAINING_ROWS} expected)",
                t.rows
            ),
        ));
    }
    for (name, v) in [
        ("mean", &t.mean),
        ("sd", &t.sd),
        ("min", &t.min),
        ("max", &t.max),
    ] {
        if v.len() != nf {
            return Err(bad(
                origin,
                format!("training.{name} has {} values for {nf} features", v.len()),
            ));
        }
        if let Some(j) = v.iter().position(|x| !(x.abs() <= VALUE_BOUND)) {
            return Err(bad(
                origin,
                format!(
                    "training.{name}[{j}] = {:e} ({}) is not a finite value within ±{VALUE_BOUND:e}",
                    v[j], m.feature_names[j]
                ),
            ));
        }
    }
    for j in 0..nf {
        let (lo, hi, mu, sd) = (t.min[j], t.max[j], t.mean[j], t.sd[j]);
        let f = &m.feature_names[j];
        if !((lo..=hi).contains(&mu)
            && (0.0..=0.5 * (hi - lo) * (1.0 + 1e-9) + 1e-300).contains(&sd))
        {
            return Err(bad(
                origin,
                format!("training summary of {f}: min {lo}, mean {mu}, max {hi}, SD {sd} do not fit together"),
            ));
        }
        let want_range = if hi > lo { hi - lo } else { 1.0 };
        let (smin, srange) = (m.scaling.min[j], m.scaling.range[j]);
        if smin.to_bits() != lo.to_bits() || srange.to_bits() != want_range.to_bits() {
            return Err(bad(
                origin,
                format!(
                    "scaling of {f} (min {smin:e}, range {srange:e}) is not the training range (min {lo:e}, range {want_range:e})"
                ),
            ));
        }
        if srange < MIN_RANGE {
            return Err(bad(
                origin,
                format!("scaling.range of {f} = {srange:e} is below {MIN_RANGE:e}"),
            ));
        }
    }
    // Class means: one per class with rows, inside the range, averaging to the mean.
    let with_rows: Vec<usize> = (0..m.trained_rows_per_class.len())
        .filter(|&c| m.trained_rows_per_class[c] > 0)
        .collect();
    let classes: Vec<usize> = t.probes.iter().map(|p| p.class).collect();
    if classes != with_rows {
        return Err(bad(
            origin,
            format!(
                "training probes for classes {classes:?}, the classes with rows are {with_rows:?}"
            ),
        ));
    }
    for j in 0..nf {
        let mut weighted = 0.0;
        for p in &t.probes {
            let v = p.x.get(j).copied().unwrap_or(f64::NAN);
            if p.x.len() != nf || !(t.min[j]..=t.max[j]).contains(&v) {
                return Err(bad(
                    origin,
                    format!(
                        "the mean of class {} is not {nf} values inside the training range (feature {})",
                        p.class, m.feature_names[j]
                    ),
                ));
            }
            weighted += v * m.trained_rows_per_class[p.class] as f64;
        }
        let mu = weighted / t.rows as f64;
        let scale = t.max[j].abs().max(t.min[j].abs()).max(1e-300);
        if (mu - t.mean[j]).abs() > 1e-9 * scale {
            return Err(bad(
                origin,
                format!(
                    "the class means of {} average to {mu}, the training mean is {}",
                    m.feature_names[j], t.mean[j]
                ),
            ));
        }
    }
    Ok(())
}

fn check_feature_order(m: &ModelFile, origin: &str) -> Result<(), ModelError> {
    let t = &m.training;
    let mut known = std::collections::HashMap::new();
    for (j, f) in m.feature_names.iter().enumerate() {
        if let Ok(p) = Parameter::from_column(f) {
            let (lo, hi) = physical_range(p);
            if t.min[j] < lo || t.max[j] > hi {
                return Err(bad(
                    origin,
                    format!(
                        "feature {f} spans {} to {} in training, outside its physical range {lo} to {hi}: are the features in another order?",
                        t.min[j], t.max[j]
                    ),
                ));
            }
            known.insert(p, t.mean[j]);
        }
    }
    use Parameter::*;
    let g = |p| known.get(&p).copied();
    let mut rules: Vec<(String, bool)> = vec![];
    if let (Some(st), Some(sw)) = (g(StanceRatio), g(SwingRatio)) {
        rules.push((
            format!("mean stance ratio {st} + swing ratio {sw} = 1, stance the larger"),
            (st + sw - 1.0).abs() <= 0.05 && st >= sw,
        ));
    }
    if let (Some(step), Some(stride)) = (g(StepTime), g(StrideTime)) {
        let r = stride / step;
        rules.push((
            format!("mean stride time / step time = {r:.3} ≈ 2"),
            (1.6..=2.4).contains(&r),
        ));
    }
    if let (Some(sf), Some(stride)) = (g(StepFrequency), g(StrideTime)) {
        let r = sf * stride;
        rules.push((
            format!("mean step frequency × stride time = {r:.3} ≈ 2"),
            (1.5..=2.5).contains(&r),
        ));
    }
    if let (Some(sf), Some(sl), Some(v)) = (g(StepFrequency), g(StrideLength), g(Speed)) {
        let r = v / (sl * sf / 2.0);
        rules.push((
            format!("mean speed / (stride length × step frequency / 2) = {r:.3} ≈ 1"),
            (0.6..=1.4).contains(&r),
        ));
    }
    match rules.into_iter().find(|(_, ok)| !ok) {
        Some((rule, _)) => Err(bad(
            origin,
            format!("the training means break a relation of walking: {rule}: are the features in another order?"),
        )),
        None => Ok(()),
    }
}

fn check_probes(m: &ModelFile, origin: &str) -> Result<(), ModelError> {
    for p in &m.training.probes {
        let name = &m.class_names[p.class];
        let got = probe_output(m, &p.x).unwrap_or_default();
        let same = got.len() == p.output.len()
            && got
                .iter()
                .zip(&p.output)
                .all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + b.abs()));
        if !same {
            return Err(bad(
                origin,
                format!(
                    "at the mean of the {name} training rows the model gives {got:?}, ldh train recorded {:?}: the fitted model was edited",
                    p.output
                ),
            ));
        }
    }
    Ok(())
}
