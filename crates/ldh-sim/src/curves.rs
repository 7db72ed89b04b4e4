//! Normal sagittal joint-angle curves over one gait cycle, as periodic C² cubic splines.
//!
//! Key points follow the normal adult curves at natural cadence in Winter, *Biomechanics and
//! Motor Control of Human Movement* (4th ed., 2009, ch. 4 and appendix A) and Perry & Burnfield,
//! *Gait Analysis* (2nd ed., 2010): hip flexion about +25° at heel strike, maximal extension
//! about −9° in terminal stance; knee flexion about 3° at heel strike, an 18° loading-response
//! peak, about 38° at toe off (60 % of the cycle) and a 60° swing peak near 72 %. The shank's
//! sagittal inclination from vertical (positive when the knee is anterior to the ankle, SPEC §3.3)
//! is knee flexion − hip flexion: about −22° at heel strike and +50° in early swing.
//!
//! Hand-written: a periodic cubic spline with analytic derivatives is ~60 lines, and the
//! interpolation crates do not offer periodic end conditions.

/// A periodic cubic spline on the unit cycle (period 1).
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicSpline {
    x: Vec<f64>,
    y: Vec<f64>,
    m: Vec<f64>,
}

impl PeriodicSpline {
    /// Through points `(x_i, y_i)` with `x` strictly increasing within `[0, 1)`.
    pub fn new(points: &[(f64, f64)]) -> PeriodicSpline {
        let n = points.len();
        assert!(n >= 3, "a periodic spline needs at least 3 points");
        let x: Vec<f64> = points.iter().map(|p| p.0).collect();
        let y: Vec<f64> = points.iter().map(|p| p.1).collect();
        let h: Vec<f64> = (0..n)
            .map(|i| {
                if i + 1 < n {
                    x[i + 1] - x[i]
                } else {
                    x[0] + 1.0 - x[n - 1]
                }
            })
            .collect();
        // Cyclic system for the second derivatives, solved densely (n is small).
        let mut a = vec![vec![0.0; n + 1]; n];
        for i in 0..n {
            let im = (i + n - 1) % n;
            let ip = (i + 1) % n;
            a[i][im] += h[im];
            a[i][i] += 2.0 * (h[im] + h[i]);
            a[i][ip] += h[i];
            a[i][n] = 6.0 * ((y[ip] - y[i]) / h[i] - (y[i] - y[im]) / h[im]);
        }
        for c in 0..n {
            let piv = (c..n)
                .max_by(|&p, &q| a[p][c].abs().partial_cmp(&a[q][c].abs()).unwrap())
                .unwrap();
            a.swap(c, piv);
            for r in 0..n {
                if r != c {
                    let f = a[r][c] / a[c][c];
                    for k in c..=n {
                        a[r][k] -= f * a[c][k];
                    }
                }
            }
        }
        let m = (0..n).map(|i| a[i][n] / a[i][i]).collect();
        PeriodicSpline { x, y, m }
    }

    /// Value, first and second derivative with respect to the phase at `q` (any real; wrapped).
    pub fn eval(&self, q: f64) -> (f64, f64, f64) {
        let n = self.x.len();
        let mut t = (q - self.x[0]).rem_euclid(1.0) + self.x[0];
        if t >= self.x[0] + 1.0 {
            t -= 1.0;
        }
        let i = match self.x.iter().rposition(|&xi| xi <= t) {
            Some(i) => i,
            None => n - 1,
        };
        let (x0, x1) = if i + 1 < n {
            (self.x[i], self.x[i + 1])
        } else {
            (self.x[n - 1], self.x[0] + 1.0)
        };
        let ip = (i + 1) % n;
        let h = x1 - x0;
        let (y0, y1, m0, m1) = (self.y[i], self.y[ip], self.m[i], self.m[ip]);
        let a = (x1 - t) / h;
        let b = (t - x0) / h;
        let v = a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
        let d = (y1 - y0) / h + (-(3.0 * a * a - 1.0) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0;
        let dd = a * m0 + b * m1;
        (v, d, dd)
    }
}

/// Hip flexion in degrees over the cycle (0 = heel strike, toe off at 0.60).
pub fn hip_flexion() -> PeriodicSpline {
    PeriodicSpline::new(&[
        (0.00, 25.0),
        (0.10, 22.0),
        (0.20, 13.0),
        (0.30, 4.0),
        (0.40, -4.0),
        (0.50, -9.0),
        (0.55, -8.0),
        (0.62, -2.0),
        (0.70, 10.0),
        (0.80, 22.0),
        (0.88, 27.0),
        (0.95, 26.0),
    ])
}

/// Knee flexion in degrees over the cycle (0 = heel strike, toe off at 0.60).
pub fn knee_flexion() -> PeriodicSpline {
    PeriodicSpline::new(&[
        (0.00, 3.0),
        (0.07, 12.0),
        (0.15, 18.0),
        (0.25, 12.0),
        (0.35, 5.0),
        (0.42, 5.0),
        (0.50, 14.0),
        (0.60, 38.0),
        (0.67, 55.0),
        (0.72, 60.0),
        (0.78, 55.0),
        (0.85, 38.0),
        (0.92, 14.0),
        (0.97, 3.0),
    ])
}

/// Mean hip flexion over the cycle in degrees (the centre about which hip excursion scales).
pub const HIP_MEAN_DEG: f64 = 10.0;

/// Canonical phase of foot flat (end of the heel rocker).
pub const FOOT_FLAT: f64 = 0.10;
/// Canonical phase of heel off (start of the forefoot rocker).
pub const HEEL_OFF: f64 = 0.42;
/// Canonical phase of toe off.
pub const TOE_OFF: f64 = 0.60;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spline_interpolates_and_is_periodic() {
        let s = knee_flexion();
        assert!((s.eval(0.72).0 - 60.0).abs() < 1e-9);
        assert!((s.eval(1.72).0 - 60.0).abs() < 1e-9);
        let a = s.eval(0.9999999);
        let b = s.eval(0.0);
        assert!((a.0 - b.0).abs() < 1e-4 && (a.1 - b.1).abs() < 1e-2 && (a.2 - b.2).abs() < 1.0);
    }

    #[test]
    fn shank_inclination_has_the_spec_shape() {
        let (h, k) = (hip_flexion(), knee_flexion());
        let th = |q: f64| k.eval(q).0 - h.eval(q).0;
        let (mut max, mut min) = (f64::MIN, f64::MAX);
        for i in 0..1000 {
            let q = i as f64 / 1000.0;
            max = max.max(th(q));
            min = min.min(th(q));
        }
        assert!((45.0..55.0).contains(&max), "max {max}");
        assert!((-26.0..-18.0).contains(&min), "min {min}");
        assert!(th(0.0) < -18.0);
    }
}
