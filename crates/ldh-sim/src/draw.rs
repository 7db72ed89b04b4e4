//! The normal draws of both simulator families, below the modules that use them (a ChaCha8
//! stream per subject; `rand_distr`'s `Normal` sampling, so a seed gives the same cohort).

use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// A standard normal draw from `rng` (N(0, 1), as `Normal::new(0, 1)` samples it).
pub(crate) fn std_normal(rng: &mut ChaCha8Rng) -> f64 {
    Normal::new(0.0, 1.0).expect("valid").sample(rng)
}

/// Draw a value from N(mean, sd) clamped to [lo, hi].
pub(crate) fn normal_clamped(rng: &mut ChaCha8Rng, mean: f64, sd: f64, lo: f64, hi: f64) -> f64 {
    let v = Normal::new(mean, sd.max(1e-12)).expect("valid").sample(rng);
    v.clamp(lo, hi)
}
