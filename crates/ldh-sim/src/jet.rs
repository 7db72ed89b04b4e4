//! Second-order forward-mode differentiation: a value with its first and second time
//! derivatives. The simulator evaluates every kinematic quantity as a [`Jet`] of time, so the
//! accelerometer signal is the exact second derivative of the sensor's position and the
//! gyroscope the exact angular velocity, not finite differences.
//!
//! Hand-written (about 100 lines): the dual-number crates either lack second derivatives or
//! bring a large generic-numerics stack for what is a handful of operators here.

use std::ops::{Add, Mul, Neg, Sub};

/// A quantity with its first (`d`) and second (`dd`) derivative with respect to time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    /// Value.
    pub v: f64,
    /// First derivative.
    pub d: f64,
    /// Second derivative.
    pub dd: f64,
}

impl Jet {
    /// A constant.
    pub const fn cst(v: f64) -> Jet {
        Jet { v, d: 0.0, dd: 0.0 }
    }
    /// Time itself: value `t`, derivative 1.
    pub const fn time(t: f64) -> Jet {
        Jet {
            v: t,
            d: 1.0,
            dd: 0.0,
        }
    }
    /// A jet from its parts.
    pub const fn new(v: f64, d: f64, dd: f64) -> Jet {
        Jet { v, d, dd }
    }
    /// `f(self)` given `f`, `f'` and `f''` at `self.v` (chain rule).
    pub fn compose(self, f: f64, f1: f64, f2: f64) -> Jet {
        Jet {
            v: f,
            d: f1 * self.d,
            dd: f2 * self.d * self.d + f1 * self.dd,
        }
    }
    /// Sine.
    pub fn sin(self) -> Jet {
        let (s, c) = self.v.sin_cos();
        self.compose(s, c, -s)
    }
    /// Cosine.
    pub fn cos(self) -> Jet {
        let (s, c) = self.v.sin_cos();
        self.compose(c, -s, -c)
    }
    /// Scale by a constant.
    pub fn scale(self, k: f64) -> Jet {
        Jet {
            v: self.v * k,
            d: self.d * k,
            dd: self.dd * k,
        }
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, o: Jet) -> Jet {
        Jet::new(self.v + o.v, self.d + o.d, self.dd + o.dd)
    }
}

impl Sub for Jet {
    type Output = Jet;
    fn sub(self, o: Jet) -> Jet {
        Jet::new(self.v - o.v, self.d - o.d, self.dd - o.dd)
    }
}

impl Neg for Jet {
    type Output = Jet;
    fn neg(self) -> Jet {
        Jet::new(-self.v, -self.d, -self.dd)
    }
}

impl Mul for Jet {
    type Output = Jet;
    fn mul(self, o: Jet) -> Jet {
        Jet::new(
            self.v * o.v,
            self.d * o.v + self.v * o.d,
            self.dd * o.v + 2.0 * self.d * o.d + self.v * o.dd,
        )
    }
}

impl Add<f64> for Jet {
    type Output = Jet;
    fn add(self, o: f64) -> Jet {
        Jet::new(self.v + o, self.d, self.dd)
    }
}

impl Sub<f64> for Jet {
    type Output = Jet;
    fn sub(self, o: f64) -> Jet {
        Jet::new(self.v - o, self.d, self.dd)
    }
}

impl Mul<f64> for Jet {
    type Output = Jet;
    fn mul(self, o: f64) -> Jet {
        self.scale(o)
    }
}

/// A 3-vector of jets.
pub type JetVec3 = [Jet; 3];

/// A 3×3 matrix of jets (row-major).
pub type JetMat3 = [[Jet; 3]; 3];

/// Matrix product of jet matrices.
pub fn mat_mul(a: &JetMat3, b: &JetMat3) -> JetMat3 {
    let mut out = [[Jet::default(); 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    out
}

/// Matrix × vector.
pub fn mat_vec(a: &JetMat3, v: &JetVec3) -> JetVec3 {
    std::array::from_fn(|i| a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2])
}

/// Rotation about z by `psi`.
pub fn rot_z(psi: Jet) -> JetMat3 {
    let (c, s) = (psi.cos(), psi.sin());
    let (o, l) = (Jet::cst(0.0), Jet::cst(1.0));
    [[c, -s, o], [s, c, o], [o, o, l]]
}

/// Rotation about y by `theta`.
pub fn rot_y(theta: Jet) -> JetMat3 {
    let (c, s) = (theta.cos(), theta.sin());
    let (o, l) = (Jet::cst(0.0), Jet::cst(1.0));
    [[c, o, s], [o, l, o], [-s, o, c]]
}

/// Rotation about x by `phi`.
pub fn rot_x(phi: Jet) -> JetMat3 {
    let (c, s) = (phi.cos(), phi.sin());
    let (o, l) = (Jet::cst(0.0), Jet::cst(1.0));
    [[l, o, o], [o, c, -s], [o, s, c]]
}

/// Body-frame angular velocity of a rotation matrix jet `R` (world ← body):
/// `[ω]× = Rᵀ Ṙ`.
pub fn body_rate(r: &JetMat3) -> [f64; 3] {
    let mut w = [[0.0; 3]; 3];
    for (i, row) in w.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = (0..3).map(|k| r[k][i].v * r[k][j].d).sum();
        }
    }
    [w[2][1], w[0][2], w[1][0]]
}

/// The smoothstep polynomial 10x³ − 15x⁴ + 6x⁵ on [0, 1] (0 and 1 outside), with its first
/// and second derivatives zero at both ends.
pub fn smoothstep5(x: f64) -> (f64, f64, f64) {
    if x <= 0.0 {
        (0.0, 0.0, 0.0)
    } else if x >= 1.0 {
        (1.0, 0.0, 0.0)
    } else {
        let x2 = x * x;
        let x3 = x2 * x;
        (
            x3 * (10.0 - 15.0 * x + 6.0 * x2),
            30.0 * x2 * (1.0 - 2.0 * x + x2),
            60.0 * x * (1.0 - 3.0 * x + 2.0 * x2),
        )
    }
}

/// A C² bump (1 − u²)³ with u = (x − centre) / half_width, zero outside; peak 1.
pub fn bump(x: f64, centre: f64, half_width: f64) -> (f64, f64, f64) {
    let u = (x - centre) / half_width;
    if u.abs() >= 1.0 {
        return (0.0, 0.0, 0.0);
    }
    let a = 1.0 - u * u;
    let f = a * a * a;
    let f1 = -6.0 * u * a * a / half_width;
    let f2 = (-6.0 * a * a + 24.0 * u * u * a) / (half_width * half_width);
    (f, f1, f2)
}

/// A quintic polynomial in time on `[t0, t1]` matching position, velocity and acceleration at
/// both ends (C² joins).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quintic {
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t1: f64,
    c: [f64; 6],
}

impl Quintic {
    /// The quintic with `start` = (p, v, a) at `t0` and `end` at `t1`.
    pub fn new(t0: f64, t1: f64, start: Jet, end: Jet) -> Quintic {
        let h = t1 - t0;
        let (p0, v0, a0) = (start.v, start.d, start.dd);
        let dp = end.v - p0 - v0 * h - 0.5 * a0 * h * h;
        let dv = end.d - v0 - a0 * h;
        let da = end.dd - a0;
        let c3 = (10.0 * dp - 4.0 * dv * h + 0.5 * da * h * h) / h.powi(3);
        let c4 = (-15.0 * dp + 7.0 * dv * h - da * h * h) / h.powi(4);
        let c5 = (6.0 * dp - 3.0 * dv * h + 0.5 * da * h * h) / h.powi(5);
        Quintic {
            t0,
            t1,
            c: [p0, v0, 0.5 * a0, c3, c4, c5],
        }
    }
    /// Value and derivatives at time `t`.
    pub fn eval(&self, t: f64) -> Jet {
        let x = t - self.t0;
        let c = &self.c;
        let v = c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * (c[4] + x * c[5]))));
        let d = c[1] + x * (2.0 * c[2] + x * (3.0 * c[3] + x * (4.0 * c[4] + x * 5.0 * c[5])));
        let dd = 2.0 * c[2] + x * (6.0 * c[3] + x * (12.0 * c[4] + x * 20.0 * c[5]));
        Jet::new(v, d, dd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd(f: impl Fn(f64) -> f64, t: f64) -> (f64, f64) {
        let h = 1e-4;
        (
            (f(t + h) - f(t - h)) / (2.0 * h),
            (f(t + h) - 2.0 * f(t) + f(t - h)) / (h * h),
        )
    }

    #[test]
    fn jet_chain_rule_matches_finite_differences() {
        let f = |t: Jet| (t * t).sin() * t.cos() + t * 3.0;
        let t = 0.7;
        let j = f(Jet::time(t));
        let (d, dd) = fd(|x| f(Jet::cst(x)).v, t);
        assert!((j.d - d).abs() < 1e-6, "{} vs {d}", j.d);
        assert!((j.dd - dd).abs() < 1e-4, "{} vs {dd}", j.dd);
    }

    #[test]
    fn quintic_matches_its_end_conditions() {
        let q = Quintic::new(1.0, 1.5, Jet::new(0.2, -1.0, 3.0), Jet::new(1.1, 0.5, -2.0));
        let a = q.eval(1.0);
        let b = q.eval(1.5);
        for (x, y) in [
            (a.v, 0.2),
            (a.d, -1.0),
            (a.dd, 3.0),
            (b.v, 1.1),
            (b.d, 0.5),
            (b.dd, -2.0),
        ] {
            assert!((x - y).abs() < 1e-9, "{x} vs {y}");
        }
    }

    #[test]
    fn body_rate_of_a_pure_yaw_is_the_yaw_rate() {
        let psi = Jet::new(0.3, 2.0, 0.0);
        let w = body_rate(&rot_z(psi));
        assert!((w[2] - 2.0).abs() < 1e-12 && w[0].abs() < 1e-12 && w[1].abs() < 1e-12);
    }

    #[test]
    fn bump_and_smoothstep_derivatives() {
        for x in [0.1, 0.35, 0.6, 0.9] {
            let (_, d, dd) = smoothstep5(x);
            let (fd1, fd2) = fd(|y| smoothstep5(y).0, x);
            assert!((d - fd1).abs() < 1e-6 && (dd - fd2).abs() < 1e-3);
            let (_, d, dd) = bump(x, 0.5, 0.45);
            let (fd1, fd2) = fd(|y| bump(y, 0.5, 0.45).0, x);
            assert!((d - fd1).abs() < 1e-6 && (dd - fd2).abs() < 1e-3);
        }
    }
}
