//! Shank attitude by adaptive Kalman fusion of gyroscope and accelerometer (paper §3.2,
//! eq. 4–15; SPEC §3.3), and the accelerometer-only baseline (SPEC §3.7).
//!
//! State: ZYX Euler angles (roll φ, pitch θ, yaw ψ) of the anatomical frame F ([`crate::align`]).
//! θ is the sagittal inclination of the shank from vertical, positive when the knee is anterior
//! to the ankle; φ the frontal inclination; ψ the heading, which no accelerometer observes: it
//! is propagated only and never used for a clinical feature (only to find turns).
//!
//! **Predict** with the Euler-rate kinematics of eq. 7 driven by the bias-corrected angular
//! velocity (mid-point of consecutive samples), linearised for the covariance (an extended
//! Kalman filter; the paper's A = I is its small-step limit).
//!
//! **Update** with roll and pitch from the accelerometer's gravity direction,
//! φ_acc = atan2(f₂, f₃), θ_acc = atan2(−f₁, √(f₂² + f₃²)), covariance update in Joseph form
//! (eq. 14).
//!
//! **Adaptive** (eq. 15): a bank of filters that differ in their innovation gate (a filter skips
//! the update when the normalised innovation exceeds its gate). Each filter adapts its
//! measurement noise R from its innovations (Sage & Husa 1969, forgetting factor b, during
//! quasi-static samples only) and inflates it by 1 + (|‖a‖ − 1 g| / `dynamic_scale_g`)² +
//! (|ω| / `rotation_scale_dps`)² when the sensor accelerates or rotates (swing, heel strike).
//! A filter that has rejected every measurement for `reacquire_s` accepts the next one. The output is Σ βᵢ x̂ᵢ with βᵢ proportional to each
//! filter's accumulated innovation likelihood (floored so no filter is ever shut out for good).
//!
//! **Smoother** (optional): Rauch–Tung–Striebel backward pass per filter, fused with the forward
//! weights (offline analysis only).
//!
//! **ACC-only** baseline: roll and pitch from the tilt of the acceleration low-passed at
//! `acc_only_cutoff_hz` (the unfiltered tilt in swing is dominated by linear acceleration);
//! yaw propagated from the angular velocity with those angles, for turn detection only. In the
//! pipeline only the attitude is replaced: events still come from the sagittal angular
//! velocity, so fusion vs ACC-only (Table 4) compares attitude models, not event detectors.

use nalgebra::{Matrix2, Matrix2x3, Matrix3, Matrix3x2, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::align::Aligned;
use crate::error::{LdhError, Result};
use crate::preprocess::butter_filtfilt;

/// Which attitude model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum AttitudeModel {
    /// Adaptive Kalman fusion of gyroscope and accelerometer (the paper's model).
    #[default]
    Fusion,
    /// Accelerometer tilt alone (the paper's comparison model).
    #[cfg_attr(feature = "clap", value(alias = "acc-only"))]
    Acc,
}

impl std::str::FromStr for AttitudeModel {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "fusion" => Ok(AttitudeModel::Fusion),
            "acc" | "acc-only" => Ok(AttitudeModel::Acc),
            o => Err(LdhError::param("model", o, "expected 'fusion' or 'acc'")),
        }
    }
}

impl AttitudeModel {
    /// `"fusion"` or `"acc"`.
    pub fn as_str(self) -> &'static str {
        match self {
            AttitudeModel::Fusion => "fusion",
            AttitudeModel::Acc => "acc",
        }
    }
}

/// Attitude parameters (unchecked).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AttitudeParams {
    /// Model. Default fusion.
    pub model: AttitudeModel,
    /// Innovation gates of the filter bank, in standard deviations (one filter per gate;
    /// ≥ 1e6 means no gate). Default [2.5, 4, 8, 1e6].
    pub gates_sigma: Vec<f64>,
    /// Process noise on the angular rates, deg/s. Default 2.
    pub gyro_noise_dps: f64,
    /// Initial accelerometer tilt noise (SD), deg. Default 3.
    pub acc_tilt_noise_deg: f64,
    /// Lower and upper bound of the adapted tilt noise SD, deg. Default [3, 30]: the tilt of a
    /// walking shank's accelerometer is never better than ~3° (tuned on simulated cohort seed
    /// 100, docs/accuracy.md), however quiet the standing it adapted on.
    pub acc_tilt_noise_bounds_deg: [f64; 2],
    /// Acceleration deviation from 1 g at which R is doubled, g. Default 0.02.
    pub dynamic_scale_g: f64,
    /// Angular velocity at which R is doubled (rotation of the shank means tangential and
    /// centripetal acceleration at the sensor), deg/s. Default 100.
    pub rotation_scale_dps: f64,
    /// A filter that has rejected every measurement for this long accepts the next one (so a
    /// filter cannot lock itself out after a transient), s. Default 0.5.
    pub reacquire_s: f64,
    /// Sage–Husa forgetting factor b (0–1). Default 0.995.
    pub forgetting: f64,
    /// Floor of a filter's weight, so it can recover. Default 1e-3.
    pub min_weight: f64,
    /// Run the RTS smoother (offline). Default true.
    pub smoother: bool,
    /// Low-pass cut-off of the ACC-only tilt, Hz. Default 2.
    pub acc_only_cutoff_hz: f64,
}

impl Default for AttitudeParams {
    fn default() -> Self {
        AttitudeParams {
            model: AttitudeModel::Fusion,
            gates_sigma: vec![2.5, 4.0, 8.0, 1e6],
            gyro_noise_dps: 2.0,
            acc_tilt_noise_deg: 3.0,
            acc_tilt_noise_bounds_deg: [3.0, 30.0],
            dynamic_scale_g: 0.02,
            rotation_scale_dps: 100.0,
            reacquire_s: 0.5,
            forgetting: 0.995,
            min_weight: 1e-3,
            smoother: true,
            acc_only_cutoff_hz: 2.0,
        }
    }
}

impl AttitudeParams {
    /// Set the model.
    pub fn model(mut self, m: AttitudeModel) -> Self {
        self.model = m;
        self
    }
    /// Switch the RTS smoother.
    pub fn smoother(mut self, on: bool) -> Self {
        self.smoother = on;
        self
    }
    /// Set the gates.
    pub fn gates_sigma(mut self, g: Vec<f64>) -> Self {
        self.gates_sigma = g;
        self
    }
    /// Validate.
    pub fn check(&self) -> Result<ValidAttitudeParams> {
        if self.gates_sigma.is_empty()
            || self
                .gates_sigma
                .iter()
                .any(|g| !(g.is_finite() && *g > 0.0))
        {
            return Err(LdhError::param(
                "gates_sigma",
                format!("{:?}", self.gates_sigma),
                "need at least one gate, each > 0",
            ));
        }
        for (n, v) in [
            ("gyro_noise_dps", self.gyro_noise_dps),
            ("acc_tilt_noise_deg", self.acc_tilt_noise_deg),
            ("dynamic_scale_g", self.dynamic_scale_g),
            ("rotation_scale_dps", self.rotation_scale_dps),
            ("reacquire_s", self.reacquire_s),
            ("acc_only_cutoff_hz", self.acc_only_cutoff_hz),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(LdhError::param(n, v, "must be > 0"));
            }
        }
        let [lo, hi] = self.acc_tilt_noise_bounds_deg;
        if !(lo > 0.0 && hi > lo) {
            return Err(LdhError::param(
                "acc_tilt_noise_bounds_deg",
                format!("{lo}, {hi}"),
                "need 0 < low < high",
            ));
        }
        if !(self.forgetting > 0.0 && self.forgetting < 1.0) {
            return Err(LdhError::param(
                "forgetting",
                self.forgetting,
                "must lie in (0, 1)",
            ));
        }
        if !(self.min_weight >= 0.0 && self.min_weight < 1.0 / self.gates_sigma.len() as f64) {
            return Err(LdhError::param(
                "min_weight",
                self.min_weight,
                "must lie in [0, 1/number of filters)",
            ));
        }
        Ok(ValidAttitudeParams(self.clone()))
    }
}

/// Checked attitude parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidAttitudeParams(AttitudeParams);

impl ValidAttitudeParams {
    /// The parameters.
    pub fn params(&self) -> &AttitudeParams {
        &self.0
    }
}

/// The attitude of one shank over time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Attitude {
    /// Model used.
    pub model: AttitudeModel,
    /// Sampling rate, Hz.
    pub fs_hz: f64,
    /// Roll φ (frontal inclination, ZYX convention), deg.
    pub roll_deg: Vec<f64>,
    /// Pitch θ (sagittal inclination, knee anterior positive), deg.
    pub pitch_deg: Vec<f64>,
    /// Yaw ψ (heading, propagated only), deg.
    pub yaw_deg: Vec<f64>,
    /// Final weight of each filter of the bank (fusion only).
    pub final_weights: Vec<f64>,
    /// Adapted tilt noise SD of each filter at the end, deg (fusion only).
    pub final_tilt_noise_deg: Vec<f64>,
}

fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    a - t * ((a + std::f64::consts::PI) / t).floor()
}

fn acc_tilt(f: [f64; 3]) -> (f64, f64) {
    let phi = f[1].atan2(f[2]);
    let theta = (-f[0]).atan2((f[1] * f[1] + f[2] * f[2]).sqrt());
    (phi, theta)
}

/// Euler-angle rates (eq. 7) and their Jacobian with respect to (φ, θ, ψ).
fn euler_rates(x: &Vector3<f64>, w: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let (sp, cp) = x[0].sin_cos();
    let (st, ct) = x[1].sin_cos();
    let ct = if ct.abs() < 1e-6 {
        1e-6f64.copysign(ct)
    } else {
        ct
    };
    let tt = st / ct;
    let a = sp * w[1] + cp * w[2];
    let b = cp * w[1] - sp * w[2];
    let rates = Vector3::new(w[0] + a * tt, b, a / ct);
    let j = Matrix3::new(
        b * tt,
        a / (ct * ct),
        0.0,
        -a,
        0.0,
        0.0,
        b / ct,
        a * st / (ct * ct),
        0.0,
    );
    (rates, j)
}

struct Filter {
    x: Vector3<f64>,
    p: Matrix3<f64>,
    r: Matrix2<f64>,
    gate2: f64,
    logw: f64,
    rejected: usize,
    // For the smoother.
    xs_pred: Vec<Vector3<f64>>,
    ps_pred: Vec<Matrix3<f64>>,
    xs: Vec<Vector3<f64>>,
    ps: Vec<Matrix3<f64>>,
    fs: Vec<Matrix3<f64>>,
}

/// Estimate the attitude of one aligned recording.
pub fn estimate(al: &Aligned, params: &ValidAttitudeParams) -> Result<Attitude> {
    let p = &params.0;
    match p.model {
        AttitudeModel::Fusion => fusion(al, p),
        AttitudeModel::Acc => acc_only(al, p),
    }
}

fn fusion(al: &Aligned, p: &AttitudeParams) -> Result<Attitude> {
    let n = al.acc_g[0].len();
    if n < 2 {
        return Err(LdhError::signal("attitude", "fewer than 2 samples"));
    }
    let dt = 1.0 / al.fs_hz;
    let h = Matrix2x3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0);
    let f_at = |i: usize| [al.acc_g[0][i], al.acc_g[1][i], al.acc_g[2][i]];
    let w_at = |i: usize| {
        Vector3::new(al.gyro_dps[0][i], al.gyro_dps[1][i], al.gyro_dps[2][i])
            * (std::f64::consts::PI / 180.0)
    };
    let q = Matrix3::from_diagonal_element((p.gyro_noise_dps.to_radians() * dt).powi(2));
    let r0 = p.acc_tilt_noise_deg.to_radians().powi(2);
    let (rlo, rhi) = (
        p.acc_tilt_noise_bounds_deg[0].to_radians().powi(2),
        p.acc_tilt_noise_bounds_deg[1].to_radians().powi(2),
    );
    let (phi0, th0) = acc_tilt(f_at(0));
    let x0 = Vector3::new(phi0, th0, 0.0);
    let keep = p.smoother;
    let mut bank: Vec<Filter> = p
        .gates_sigma
        .iter()
        .map(|g| Filter {
            x: x0,
            p: Matrix3::from_diagonal(&Vector3::new(r0, r0, 1e-6)),
            r: Matrix2::from_diagonal_element(r0),
            gate2: g * g,
            logw: 0.0,
            rejected: 0,
            xs_pred: Vec::with_capacity(if keep { n } else { 0 }),
            ps_pred: Vec::with_capacity(if keep { n } else { 0 }),
            xs: Vec::with_capacity(if keep { n } else { 0 }),
            ps: Vec::with_capacity(if keep { n } else { 0 }),
            fs: Vec::with_capacity(if keep { n } else { 0 }),
        })
        .collect();
    let m = bank.len();
    let mut weights_t: Vec<Vec<f64>> = Vec::with_capacity(n);
    let mut fused: Vec<Vector3<f64>> = Vec::with_capacity(n);
    let b = p.forgetting;
    let mut bpow = 1.0;
    for k in 0..n {
        let f = f_at(k);
        let norm = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let dyn_dev = (norm - 1.0).abs();
        let w_norm_dps =
            (al.gyro_dps[0][k].powi(2) + al.gyro_dps[1][k].powi(2) + al.gyro_dps[2][k].powi(2))
                .sqrt();
        let infl = 1.0
            + (dyn_dev / p.dynamic_scale_g).powi(2)
            + (w_norm_dps / p.rotation_scale_dps).powi(2);
        let (zphi, zth) = acc_tilt(f);
        let z = Vector2::new(zphi, zth);
        let w_mid = if k == 0 {
            w_at(0)
        } else {
            (w_at(k - 1) + w_at(k)) * 0.5
        };
        bpow *= b;
        let d_k = (1.0 - b) / (1.0 - bpow);
        for flt in bank.iter_mut() {
            // Predict.
            let (xp, pp, fj) = if k == 0 {
                (flt.x, flt.p, Matrix3::identity())
            } else {
                let (rates, j) = euler_rates(&flt.x, &w_mid);
                let fj = Matrix3::identity() + j * dt;
                let mut xp = flt.x + rates * dt;
                xp[2] = wrap(xp[2]);
                (xp, fj * flt.p * fj.transpose() + q, fj)
            };
            // Update.
            let mut nu = z - h * xp;
            nu[0] = wrap(nu[0]);
            nu[1] = wrap(nu[1]);
            let hph = h * pp * h.transpose();
            let rk = flt.r * infl;
            let s = hph + rk;
            let s_inv = s
                .try_inverse()
                .unwrap_or_else(|| Matrix2::from_diagonal_element(1.0 / r0));
            let d2 = (nu.transpose() * s_inv * nu)[0];
            let det = s.determinant().max(1e-300);
            flt.logw += -0.5 * d2 - 0.5 * (det * (std::f64::consts::TAU).powi(2)).ln();
            let reacquire = flt.rejected as f64 * dt >= p.reacquire_s;
            let (xu, pu) = if d2 <= flt.gate2 || reacquire {
                flt.rejected = 0;
                let kg: Matrix3x2<f64> = pp * h.transpose() * s_inv;
                let ikh = Matrix3::identity() - kg * h;
                let xu = xp + kg * nu;
                let pu = ikh * pp * ikh.transpose() + kg * rk * kg.transpose();
                // Sage–Husa adaptation of R from quasi-static innovations.
                if dyn_dev < 2.0 * p.dynamic_scale_g {
                    for i in 0..2 {
                        let est = nu[i] * nu[i] - hph[(i, i)];
                        let v = ((1.0 - d_k) * flt.r[(i, i)] + d_k * est).clamp(rlo, rhi);
                        flt.r[(i, i)] = v;
                    }
                }
                (xu, pu)
            } else {
                flt.rejected += 1;
                (xp, pp)
            };
            flt.x = xu;
            flt.x[2] = wrap(flt.x[2]);
            flt.p = pu;
            if keep {
                flt.xs_pred.push(xp);
                flt.ps_pred.push(pp);
                flt.xs.push(flt.x);
                flt.ps.push(flt.p);
                flt.fs.push(fj);
            }
        }
        // Weights: normalised likelihoods with a floor (eq. 15).
        let mx = bank.iter().map(|f| f.logw).fold(f64::MIN, f64::max);
        let mut w: Vec<f64> = bank.iter().map(|f| (f.logw - mx).exp()).collect();
        let sum: f64 = w.iter().sum();
        w.iter_mut().for_each(|x| *x /= sum);
        let floor = p.min_weight;
        w.iter_mut().for_each(|x| *x = x.max(floor));
        let sum: f64 = w.iter().sum();
        w.iter_mut().for_each(|x| *x /= sum);
        for (f, wi) in bank.iter_mut().zip(&w) {
            f.logw = wi.ln();
        }
        fused.push(weighted(&bank.iter().map(|f| f.x).collect::<Vec<_>>(), &w));
        weights_t.push(w);
    }
    if keep {
        // RTS per filter, fused with the forward weights.
        let mut smoothed: Vec<Vec<Vector3<f64>>> = Vec::with_capacity(m);
        for flt in &bank {
            let mut xs = flt.xs.clone();
            for k in (0..n - 1).rev() {
                let pp_next = flt.ps_pred[k + 1];
                let Some(inv) = pp_next.try_inverse() else {
                    continue;
                };
                let c = flt.ps[k] * flt.fs[k + 1].transpose() * inv;
                let mut diff = xs[k + 1] - flt.xs_pred[k + 1];
                diff[2] = wrap(diff[2]);
                xs[k] = flt.xs[k] + c * diff;
            }
            smoothed.push(xs);
        }
        for (k, fk) in fused.iter_mut().enumerate() {
            let xs: Vec<Vector3<f64>> = smoothed.iter().map(|s| s[k]).collect();
            *fk = weighted(&xs, &weights_t[k]);
        }
    }
    Ok(Attitude {
        model: AttitudeModel::Fusion,
        fs_hz: al.fs_hz,
        roll_deg: fused.iter().map(|x| x[0].to_degrees()).collect(),
        pitch_deg: fused.iter().map(|x| x[1].to_degrees()).collect(),
        yaw_deg: fused.iter().map(|x| x[2].to_degrees()).collect(),
        final_weights: weights_t.last().cloned().unwrap_or_default(),
        final_tilt_noise_deg: bank
            .iter()
            .map(|f| ((f.r[(0, 0)] + f.r[(1, 1)]) / 2.0).sqrt().to_degrees())
            .collect(),
    })
}

/// Weighted mean of states, angles averaged as offsets from the first (no wrap artefacts).
fn weighted(xs: &[Vector3<f64>], w: &[f64]) -> Vector3<f64> {
    let base = xs[0];
    let mut acc = Vector3::zeros();
    for (x, wi) in xs.iter().zip(w) {
        let mut d = x - base;
        for i in 0..3 {
            d[i] = wrap(d[i]);
        }
        acc += d * *wi;
    }
    let mut out = base + acc;
    out[2] = wrap(out[2]);
    out
}

fn acc_only(al: &Aligned, p: &AttitudeParams) -> Result<Attitude> {
    let n = al.acc_g[0].len();
    let fs = al.fs_hz;
    let cutoff = p.acc_only_cutoff_hz.min(0.45 * fs);
    let lp: Vec<Vec<f64>> = al
        .acc_g
        .iter()
        .map(|c| butter_filtfilt(c, 2, cutoff, fs))
        .collect::<Result<_>>()?;
    let mut roll = Vec::with_capacity(n);
    let mut pitch = Vec::with_capacity(n);
    let mut yaw = Vec::with_capacity(n);
    let mut psi = 0.0;
    for k in 0..n {
        let (phi, th) = acc_tilt([lp[0][k], lp[1][k], lp[2][k]]);
        if k > 0 {
            let w = Vector3::new(al.gyro_dps[0][k], al.gyro_dps[1][k], al.gyro_dps[2][k])
                * (std::f64::consts::PI / 180.0);
            let (rates, _) = euler_rates(&Vector3::new(phi, th, psi), &w);
            psi = wrap(psi + rates[2] / fs);
        }
        roll.push(phi.to_degrees());
        pitch.push(th.to_degrees());
        yaw.push(psi.to_degrees());
    }
    Ok(Attitude {
        model: AttitudeModel::Acc,
        fs_hz: fs,
        roll_deg: roll,
        pitch_deg: pitch,
        yaw_deg: yaw,
        final_weights: vec![],
        final_tilt_noise_deg: vec![],
    })
}

/// Rotation world ← F of ZYX angles (rad), row-major.
pub fn rotation_wf(phi: f64, theta: f64, psi: f64) -> [[f64; 3]; 3] {
    let (sf, cf) = phi.sin_cos();
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    [
        [cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf],
        [sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf],
        [-st, ct * sf, ct * cf],
    ]
}
