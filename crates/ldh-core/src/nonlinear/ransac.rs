//! RANSAC straight-line fit of Rosenstein's divergence curve, as nolds' default
//! `lyap_r(..., fit="RANSAC")` does it: scikit-learn's
//! `RANSACRegressor(LinearRegression(fit_intercept=False))` on the features `[1, k]`
//! (Fischler & Bolles 1981, "Random sample consensus", Commun. ACM 24(6)).
//!
//! scikit-learn's rules: a candidate line goes through a least-squares fit of 3 random points; a
//! point is an inlier when its absolute residual is at most the median absolute deviation of
//! `y`; the candidate with the most inliers wins, ties going to the higher R² on its inliers; the
//! search stops after `ceil(log(0.01) / log(1 − w³))` trials (w: the best inlier fraction so far;
//! at most 100); the result is the least-squares line of the winner's inliers. Because the search
//! is random and stops early, nolds' value varies from run to run. Here the same search is run
//! [`RUNS`] times with fixed seeds and the line found most often is returned: deterministic, and
//! the value a nolds user sees most often.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::linalg::line_fit;
use crate::stats::{median, EvenMedian};

/// Seeded repetitions of scikit-learn's random search; the most frequent line wins.
pub const RUNS: u64 = 101;
/// scikit-learn's `max_trials` default.
const MAX_TRIALS: usize = 100;
/// scikit-learn's `stop_probability` default.
const STOP_PROBABILITY: f64 = 0.99;

/// R² of the line on the points (`sklearn.metrics.r2_score`: 1 for a perfect fit of a constant,
/// 0 for an imperfect one).
fn r2(x: &[f64], y: &[f64], idx: &[usize], (slope, intercept): (f64, f64)) -> f64 {
    let n = idx.len() as f64;
    let mean = idx.iter().map(|&i| y[i]).sum::<f64>() / n;
    let (mut ss_res, mut ss_tot) = (0.0, 0.0);
    for &i in idx {
        ss_res += (y[i] - (slope * x[i] + intercept)).powi(2);
        ss_tot += (y[i] - mean).powi(2);
    }
    if ss_tot == 0.0 {
        return if ss_res == 0.0 { 1.0 } else { 0.0 };
    }
    1.0 - ss_res / ss_tot
}

/// The best consensus so far: inlier count, R², inlier indices.
struct Best {
    count: usize,
    score: f64,
    inliers: Vec<usize>,
}

impl Best {
    /// Try the line through the least-squares fit of the points `t`; true when it became the
    /// best.
    fn consider(&mut self, x: &[f64], y: &[f64], t: [usize; 3], threshold: f64) -> bool {
        let (tx, ty) = (t.map(|i| x[i]), t.map(|i| y[i]));
        let line = line_fit(&tx, &ty);
        if !(line.0.is_finite() && line.1.is_finite()) {
            return false;
        }
        let inliers: Vec<usize> = (0..x.len())
            .filter(|&i| (y[i] - (line.0 * x[i] + line.1)).abs() <= threshold)
            .collect();
        if inliers.len() < self.count {
            return false;
        }
        let score = r2(x, y, &inliers, line);
        if inliers.len() == self.count && score < self.score {
            return false;
        }
        *self = Best {
            count: inliers.len(),
            score,
            inliers,
        };
        true
    }
}

/// scikit-learn's `_dynamic_max_trials` for 3-point samples.
fn dynamic_max_trials(n_inliers: usize, n: usize) -> f64 {
    let ratio = n_inliers as f64 / n as f64;
    let nom = (1.0 - STOP_PROBABILITY).max(f64::EPSILON);
    let denom = (1.0 - ratio.powi(3)).max(f64::EPSILON);
    if denom == 1.0 {
        return f64::INFINITY;
    }
    (nom.ln() / denom.ln()).ceil().abs()
}

/// One run of scikit-learn's random search (seed `seed`): the winner's inliers.
fn one_search(x: &[f64], y: &[f64], threshold: f64, seed: u64) -> Vec<usize> {
    let n = x.len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // scikit-learn starts from one inlier and -inf score.
    let mut best = Best {
        count: 1,
        score: f64::NEG_INFINITY,
        inliers: vec![],
    };
    let (mut trials, mut max_trials) = (0usize, MAX_TRIALS as f64);
    while (trials as f64) < max_trials {
        trials += 1;
        let t = rand::seq::index::sample(&mut rng, n, 3);
        if best.consider(x, y, [t.index(0), t.index(1), t.index(2)], threshold) {
            max_trials = max_trials.min(dynamic_max_trials(best.count, n));
        }
    }
    best.inliers
}

/// RANSAC line `y ≈ slope·x + intercept` (see the module docs); the least-squares line when
/// there are fewer than 4 points or no consensus of at least 2 points (nolds falls back to
/// `np.polyfit` there too).
pub(crate) fn ransac_line_fit(x: &[f64], y: &[f64]) -> (f64, f64) {
    if x.len() < 4 {
        return line_fit(x, y);
    }
    // As `np.median`: the mean of the two middle values for an even count.
    let med = median(&mut y.to_vec(), EvenMedian::Mean).expect("4 points or more");
    let mut dev: Vec<f64> = y.iter().map(|v| (v - med).abs()).collect();
    let threshold = median(&mut dev, EvenMedian::Mean).expect("4 points or more");
    // The most frequent winning inlier set over the seeded runs (first found on a tie).
    let mut found: Vec<(Vec<usize>, usize)> = Vec::new();
    for seed in 0..RUNS {
        let inl = one_search(x, y, threshold, seed);
        match found.iter_mut().find(|(s, _)| *s == inl) {
            Some((_, c)) => *c += 1,
            None => found.push((inl, 1)),
        }
    }
    let mut best: Option<&(Vec<usize>, usize)> = None;
    for f in &found {
        if best.is_none_or(|b| f.1 > b.1) {
            best = Some(f);
        }
    }
    let inliers = best.map(|b| b.0.as_slice()).unwrap_or(&[]);
    if inliers.len() < 2 {
        return line_fit(x, y);
    }
    let (ix, iy): (Vec<f64>, Vec<f64>) = inliers.iter().map(|&i| (x[i], y[i])).unzip();
    line_fit(&ix, &iy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outliers_do_not_move_the_line() {
        let x: Vec<f64> = (0..20).map(f64::from).collect();
        let mut y: Vec<f64> = x.iter().map(|v| 0.5 * v + 1.0).collect();
        y[3] += 40.0;
        y[17] -= 25.0;
        let (s, b) = ransac_line_fit(&x, &y);
        assert!(
            (s - 0.5).abs() < 1e-12 && (b - 1.0).abs() < 1e-12,
            "{s} {b}"
        );
        let (ls, _) = line_fit(&x, &y);
        assert!(
            (ls - 0.5).abs() > 0.1,
            "least squares is pulled by the outliers: {ls}"
        );
    }

    #[test]
    fn a_clean_line_is_found_and_the_fit_is_deterministic() {
        let x: Vec<f64> = (0..200).map(f64::from).collect();
        let y: Vec<f64> = x
            .iter()
            .map(|v| -0.01 * v + 3.0 + 1e-3 * (v * 0.7).sin())
            .collect();
        let a = ransac_line_fit(&x, &y);
        assert_eq!(a, ransac_line_fit(&x, &y));
        assert!((a.0 + 0.01).abs() < 1e-4, "{a:?}");
        assert_eq!(
            ransac_line_fit(&x[..3], &y[..3]),
            line_fit(&x[..3], &y[..3])
        );
    }
}
