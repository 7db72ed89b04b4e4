//! Family B kinematics of one leg: shank segment angle, rolling rigid foot, swing, heading, belt.
//!
//! Written independently of family A ([`crate::model`]): no jets (derivatives are
//! central differences of closed-form functions of time, step 1 ms for positions and 0.1 ms for
//! rotations), segment-angle curves instead of joint angles, rolling (not pivoting) heel and
//! forefoot, a C² phase made of quintic Hermite pieces through the heel-strike times.
//!
//! Frames: world X forward at the start, Y left, Z up. The shank frame F has e1 anterior, e2 left,
//! e3 along the shank upwards; `R_wF = Rz(ψ) Ry(θ) Rx(φ)` with θ the sagittal inclination
//! (positive: knee anterior to the ankle), φ = −lat·ρ and ρ the anatomical roll (positive: knee
//! lateral to the ankle).

use nalgebra::{Matrix3, Rotation3, Vector3};

/// Canonical toe-off of the shank curve (fraction of the cycle).
pub const CANON_TO: f64 = 0.62;

/// Shank (leg) segment inclination over the normal cycle at natural cadence, deg, knee anterior
/// positive: key points read approximately from the shank segment angle of normal walking
/// reported by Winter (2009, appendix A, "leg" segment) and the shank-angle curves of Tong & Granat
/// (1999, Med Eng Phys 21:87) and Aminian et al. (2002, J Biomech 35:689, fig. 1): −18° at heel
/// strike, near vertical by 15 %, +45° at toe off (62 %), a +50° peak in early swing, −19° in
/// terminal swing.
pub const SHANK_KEYPOINTS_DEG: [(f64, f64); 15] = [
    (0.00, -18.0),
    (0.05, -12.0),
    (0.10, -5.0),
    (0.20, 2.0),
    (0.30, 8.0),
    (0.40, 15.0),
    (0.50, 25.0),
    (0.58, 38.0),
    (0.62, 45.0),
    (0.67, 50.0),
    (0.72, 47.0),
    (0.80, 28.0),
    (0.87, 5.0),
    (0.93, -14.0),
    (0.97, -19.0),
];

/// Heel arc centre from the ankle joint in the foot frame (forward, up), m, and its radius.
pub const HEEL_ARC: (f64, f64, f64) = (-0.055, -0.045, 0.035);
/// Forefoot (MTP) arc centre from the ankle joint, m, and its radius.
pub const MTP_ARC: (f64, f64, f64) = (0.13, -0.065, 0.015);
/// Ankle joint height at foot flat, m.
pub const ANKLE_HEIGHT_M: f64 = 0.08;

/// A periodic curve: truncated Fourier series of a periodic Catmull–Rom spline through key points.
#[derive(Debug, Clone)]
pub struct Fourier {
    a0: f64,
    ab: Vec<(f64, f64)>,
}

impl Fourier {
    /// Fit `harmonics` harmonics to the key points `(c, y)` (c increasing in [0, 1)).
    pub fn from_keypoints(pts: &[(f64, f64)], harmonics: usize) -> Fourier {
        let n = pts.len();
        let x = |i: isize| -> f64 {
            let k = i.rem_euclid(n as isize) as usize;
            pts[k].0 + i.div_euclid(n as isize) as f64
        };
        let y = |i: isize| pts[i.rem_euclid(n as isize) as usize].1;
        let slope = |i: isize| (y(i + 1) - y(i - 1)) / (x(i + 1) - x(i - 1));
        let spline = |c: f64| -> f64 {
            let c = c.rem_euclid(1.0);
            let mut i = (0..n).rev().find(|&i| pts[i].0 <= c).unwrap_or(0) as isize;
            if c < pts[0].0 {
                i = -1;
            }
            let (x0, x1) = (x(i), x(i + 1));
            let h = x1 - x0;
            let s = (c - x0) / h;
            let (h00, h10) = (
                2.0 * s.powi(3) - 3.0 * s * s + 1.0,
                s.powi(3) - 2.0 * s * s + s,
            );
            let (h01, h11) = (-2.0 * s.powi(3) + 3.0 * s * s, s.powi(3) - s * s);
            h00 * y(i) + h10 * h * slope(i) + h01 * y(i + 1) + h11 * h * slope(i + 1)
        };
        let m = 720;
        let samples: Vec<f64> = (0..m).map(|j| spline(j as f64 / m as f64)).collect();
        let a0 = samples.iter().sum::<f64>() / m as f64;
        let ab = (1..=harmonics)
            .map(|k| {
                let (mut a, mut b) = (0.0, 0.0);
                for (j, v) in samples.iter().enumerate() {
                    let w = std::f64::consts::TAU * k as f64 * j as f64 / m as f64;
                    a += v * w.cos();
                    b += v * w.sin();
                }
                (2.0 * a / m as f64, 2.0 * b / m as f64)
            })
            .collect();
        Fourier { a0, ab }
    }

    /// Value at cycle fraction `c`.
    pub fn eval(&self, c: f64) -> f64 {
        self.a0
            + self
                .ab
                .iter()
                .enumerate()
                .map(|(k, (a, b))| {
                    let w = std::f64::consts::TAU * (k + 1) as f64 * c;
                    a * w.cos() + b * w.sin()
                })
                .sum::<f64>()
    }

    /// Mean over the cycle.
    pub fn mean(&self) -> f64 {
        self.a0
    }
}

/// Quintic smoothstep clamped to [0, 1] (C² at both ends).
pub fn s5(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * x * (10.0 - 15.0 * x + 6.0 * x * x)
}

/// A C² bump on [0, 1]: 64 s³ (1 − s)³, 1 at s = 0.5, 0 outside.
pub fn bump3(s: f64) -> f64 {
    if !(0.0..=1.0).contains(&s) {
        return 0.0;
    }
    64.0 * (s * (1.0 - s)).powi(3)
}

/// Quintic Hermite on [t0, t1] through (value, d/dt, d²/dt²) at both ends.
#[derive(Debug, Clone, Copy)]
pub struct Hermite5 {
    t0: f64,
    t1: f64,
    c: [f64; 6],
}

impl Hermite5 {
    /// Through `a = (p, v, acc)` at `t0` and `b` at `t1`.
    pub fn new(t0: f64, t1: f64, a: [f64; 3], b: [f64; 3]) -> Hermite5 {
        let h = t1 - t0;
        let (p0, v0, a0) = (a[0], a[1] * h, a[2] * h * h);
        let (p1, v1, a1) = (b[0], b[1] * h, b[2] * h * h);
        let c3 = 10.0 * (p1 - p0) - 6.0 * v0 - 4.0 * v1 - 1.5 * a0 + 0.5 * a1;
        let c4 = -15.0 * (p1 - p0) + 8.0 * v0 + 7.0 * v1 + 1.5 * a0 - a1;
        let c5 = 6.0 * (p1 - p0) - 3.0 * (v0 + v1) - 0.5 * a0 + 0.5 * a1;
        Hermite5 {
            t0,
            t1,
            c: [p0, v0, 0.5 * a0, c3, c4, c5],
        }
    }
    /// Value at `t` (extrapolated outside).
    pub fn eval(&self, t: f64) -> f64 {
        let s = (t - self.t0) / (self.t1 - self.t0);
        self.c.iter().rev().fold(0.0, |acc, c| acc * s + c)
    }
}

/// Central first and second differences of `f` at `t` with step `h`.
pub fn diff2<const N: usize>(f: impl Fn(f64) -> [f64; N], t: f64, h: f64) -> [[f64; N]; 3] {
    let (a, b, c) = (f(t - h), f(t), f(t + h));
    [
        b,
        std::array::from_fn(|k| (c[k] - a[k]) / (2.0 * h)),
        std::array::from_fn(|k| (c[k] - 2.0 * b[k] + a[k]) / (h * h)),
    ]
}

/// The gait phase of one leg: k at its k-th heel strike, C² (quintic pieces, zero second
/// derivative at the knots), clamped outside the knots.
#[derive(Debug, Clone)]
pub struct Phase {
    /// Phase of the first knot (an integer).
    pub k0: i64,
    /// Knot times.
    pub t: Vec<f64>,
    seg: Vec<Hermite5>,
}

impl Phase {
    /// Through heel strikes `t[i]` at phase `k0 + i`.
    pub fn new(k0: i64, t: Vec<f64>) -> Phase {
        let n = t.len();
        let slope = |i: usize| {
            let prev = if i == 0 { t[1] - t[0] } else { t[i] - t[i - 1] };
            let next = if i + 1 == n {
                t[n - 1] - t[n - 2]
            } else {
                t[i + 1] - t[i]
            };
            2.0 / (prev + next)
        };
        let seg = (0..n - 1)
            .map(|i| {
                let p = (k0 + i as i64) as f64;
                Hermite5::new(
                    t[i],
                    t[i + 1],
                    [p, slope(i), 0.0],
                    [p + 1.0, slope(i + 1), 0.0],
                )
            })
            .collect();
        Phase { k0, t, seg }
    }
    /// Phase at time `t`.
    pub fn eval(&self, t: f64) -> f64 {
        let n = self.t.len();
        if t <= self.t[0] {
            return self.k0 as f64;
        }
        if t >= self.t[n - 1] {
            return (self.k0 + n as i64 - 1) as f64;
        }
        let i = self.t.partition_point(|&x| x <= t) - 1;
        self.seg[i].eval(t)
    }
    /// Time at which the phase equals `p` (bisection).
    pub fn time_of(&self, p: f64) -> f64 {
        let i = ((p.floor() as i64 - self.k0).max(0) as usize).min(self.seg.len() - 1);
        let (mut lo, mut hi) = (self.t[i], self.t[i + 1]);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if self.seg[i].eval(mid) < p {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
    /// The phase is non-decreasing (checked on a grid).
    pub fn is_monotone(&self) -> bool {
        self.seg.iter().all(|s| {
            (0..200).all(|j| {
                let a = s.t0 + (s.t1 - s.t0) * j as f64 / 200.0;
                s.eval(a + (s.t1 - s.t0) / 200.0) >= s.eval(a)
            })
        })
    }
}

/// Foot angle to the floor (rad, toes up positive) at stance fraction `v` (0 = HS, 1 = TO).
#[derive(Debug, Clone, Copy)]
pub struct FootRoll {
    /// Angle at heel strike, rad.
    pub hs_rad: f64,
    /// Angle at toe off (plantar, given positive), rad.
    pub to_rad: f64,
    /// Foot flat from this stance fraction.
    pub flat: f64,
    /// Heel off at this stance fraction.
    pub heel_off: f64,
}

impl FootRoll {
    /// γ(v): heel rocker (quintic), foot flat, forefoot rocker 2w³ − w⁴ (extrapolated after TO).
    pub fn angle(&self, v: f64) -> f64 {
        if v < self.flat {
            self.hs_rad * (1.0 - s5(v / self.flat))
        } else if v <= self.heel_off {
            0.0
        } else {
            let w = (v - self.heel_off) / (1.0 - self.heel_off);
            -self.to_rad * (2.0 * w.powi(3) - w.powi(4))
        }
    }
}

/// Ankle (x, z) in the progression frame for a foot placed with its flat-foot ankle at `x_flat`
/// and at angle γ: rolling without slip over the heel arc (γ > 0) or the forefoot arc (γ < 0).
pub fn rolling_ankle(x_flat: f64, gamma: f64) -> [f64; 2] {
    let (cx, cz, r) = if gamma >= 0.0 { HEEL_ARC } else { MTP_ARC };
    let centre = [x_flat + cx - r * gamma, r];
    let (c, s) = (gamma.cos(), gamma.sin());
    [centre[0] - (c * cx - s * cz), centre[1] - (s * cx + c * cz)]
}

/// `R_wF = Rz(ψ) Ry(θ) Rx(φ)`.
pub fn r_wf(psi: f64, theta: f64, phi: f64) -> Matrix3<f64> {
    (Rotation3::from_axis_angle(&Vector3::z_axis(), psi)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), theta)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), phi))
    .into_inner()
}

/// Body angular velocity of `r(t)` in its own frame (rad/s), central difference with step `h`.
pub fn body_rate(r: impl Fn(f64) -> Matrix3<f64>, t: f64, h: f64) -> Vector3<f64> {
    let om = r(t).transpose() * (r(t + h) - r(t - h)) / (2.0 * h);
    Vector3::new(
        0.5 * (om[(2, 1)] - om[(1, 2)]),
        0.5 * (om[(0, 2)] - om[(2, 0)]),
        0.5 * (om[(1, 0)] - om[(0, 1)]),
    )
}

/// Heel-strike soft-tissue transient: sin(2πfτ)·e^(−τ/T)·(1 − e^(−τ/3 ms))², τ ≥ 0 (C² at τ = 0).
pub fn hs_transient(tau: f64, f_hz: f64, decay_s: f64) -> f64 {
    if tau <= 0.0 {
        return 0.0;
    }
    let onset = 1.0 - (-tau / 0.003).exp();
    (std::f64::consts::TAU * f_hz * tau).sin() * (-tau / decay_s).exp() * onset * onset
}
