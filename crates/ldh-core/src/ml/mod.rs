//! Feature ranking and classifiers with honest cross-validation (paper §3.5, §4.2, Tables 5–7;
//! SPEC §5).
//!
//! * **Datasets** from the per-recording table: three-class (LDHH / LDHE / H, H being the mean of
//!   a healthy subject's two legs, as in the paper) and binary (LDHE vs H); subject ids are kept
//!   as groups.
//! * **Scaling**: min–max, fitted on the training fold only.
//! * **Classifiers**: a random forest of CART trees with ⌈√p⌉ features per split (scikit-learn's
//!   algorithm; hand-written because linfa-trees is not deterministic for a seed and
//!   linfa-ensemble's forest can neither be serialised nor give probabilities), an RBF SVM
//!   (linfa-svm, one-vs-rest on the decision values for three classes, γ = 1 / (p · Var X) as
//!   scikit-learn's "scale", C = 1), and a small MLP ([`mlp`]; linfa has none).
//! * **Cross-validation**: stratified k-fold (shuffled by seed) and subject-grouped k-fold (both
//!   sides of a subject always on the same side of the split — the paper's stratified design
//!   lets a subject's unaffected side train the model that tests its affected side), repeated.
//!   Folds run in parallel; results do not depend on the thread count.
//! * **Ranking**: Pearson r of each feature with the label (Table 5), permutation importance on
//!   the test folds; optional top-k selection by |r| inside each training fold.

mod arrays;
pub mod cv;
pub mod dataset;
pub mod forest;
pub mod measured;
pub mod mlp;
pub mod model;
pub mod model_check;
pub mod model_plausible;
mod model_plausible_fit;
mod model_types;
mod predict;
pub mod svm;
mod task;
mod train;
pub mod tree;

pub use cv::{cross_validate, cross_validate_with_folds, CvKind, CvParams, CvReport};
pub use dataset::{Dataset, Task};
pub use measured::TrainNote;
pub use model::{Classifier, FittedModel, ModelError, ModelFile, Prediction};
pub use predict::{predict, read_model, PredictOutcome};
pub use train::{train, train_with_progress, ClassifierKind, TrainOutcome, TrainParams};

#[cfg(test)]
mod tests;
