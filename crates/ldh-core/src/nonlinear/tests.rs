//! Tests of the nonlinear module: parity with nolds 0.6.2 (goldens written by
//! `data-fixtures/scripts/gen_lyapunov_golden.py`), exactness of the
//! neighbour search, known exponents of textbook systems, and error paths;
//! one file per concern, sharing the helpers below.

mod blocks;
mod errors;
mod gait;
mod known;
mod neighbours;
mod nolds;

use super::*;

/// Validate-then-run, so the tests below read like the nolds calls (local
/// items shadow the glob import of `super::lyap_r` / `super::lyap_e`).
fn lyap_r(x: &[f64], p: &RosensteinParams) -> Result<RosensteinResult, NonlinearError> {
    super::lyap_r(x, &p.check()?)
}

/// See [`lyap_r`] above.
fn lyap_e(x: &[f64], p: &EckmannParams) -> Result<EckmannResult, NonlinearError> {
    super::lyap_e(x, &p.check()?)
}

fn logistic(n: usize) -> Vec<f64> {
    let mut x = 0.1f64;
    let mut out = Vec::with_capacity(n);
    for i in 0..n + 100 {
        x = 4.0 * x * (1.0 - x);
        if i >= 100 {
            out.push(x);
        }
    }
    out
}

/// Standard normal by Box-Muller (keeps the test free of rand_distr).
mod rand_distr_free {
    use rand::Rng;
    pub fn normal<R: Rng>(rng: &mut R) -> f64 {
        let u1: f64 = rng.gen::<f64>().max(f64::MIN_POSITIVE);
        let u2: f64 = rng.gen();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}
