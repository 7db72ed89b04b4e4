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
//! **Anchored to gravity** (issue 20; [`fusion`], [`anchor`]): the state carries the bias of the
//! two tilting gyroscope axes, and in quasi-static windows (foot flat) the tilt update is never
//! gated and its noise is capped, so a bias left after alignment (a recording without quiet
//! standing) or an adapted R grown by drift cannot let the attitude run away.
//!
//! **Smoother** (optional): Rauch–Tung–Striebel backward pass per filter, fused with the forward
//! weights (offline analysis only).
//!
//! **ACC-only** baseline: roll and pitch from the tilt of the acceleration low-passed at
//! `acc_only_cutoff_hz` (the unfiltered tilt in swing is dominated by linear acceleration);
//! yaw propagated from the angular velocity with those angles, for turn detection only. In the
//! pipeline only the attitude is replaced: events still come from the sagittal angular
//! velocity, so fusion vs ACC-only (Table 4) compares attitude models, not event detectors.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::align::Aligned;
use crate::error::{LdhError, Result};
use crate::preprocess::butter_filtfilt;

mod anchor;
mod fusion;

use fusion::{euler_rates, fusion};

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
    /// Prior SD of the gyroscope bias states (anterior and medio-lateral axes), deg/s. Default
    /// 5: consumer MEMS gyroscopes keep 1–5 deg/s of bias after power-up (an MPU-6050's
    /// data sheet allows ±20), and `align` removes it only when the recording has quiet
    /// standing.
    pub gyro_bias_sd_dps: f64,
    /// Random walk of the gyroscope bias, deg/s per √s. Default 0.01 (0.3 deg/s over 15
    /// minutes; the in-run bias instability of MEMS gyroscopes is 0.002–0.01 deg/s, thermal
    /// drift after warm-up is slower than that). Tuned on simulator family A (seed 100: pitch
    /// RMSE 0.39° at 0.01, 0.44° at 0.05, 0.70° at 0.2 deg/s per √s).
    pub gyro_bias_walk_dps: f64,
    /// Re-anchor roll and pitch to gravity in quasi-static windows (foot flat): the tilt
    /// update is never gated there and its noise is capped at `anchor_tilt_noise_deg`. Default
    /// true.
    pub reacquire_gravity: bool,
    /// Largest deviation of |a| from 1 g in a gravity window, g. Default 0.1.
    pub anchor_acc_g: f64,
    /// Largest |ω| in a gravity window, deg/s. Default 150 (the shank rotates over the ankle
    /// through stance at 50–140 deg/s on real recordings; swing peaks at 300–500).
    pub anchor_gyro_dps: f64,
    /// Shortest gravity window, s. Default 0.1.
    pub anchor_window_s: f64,
    /// Tilt noise of one gravity window, deg (the cap of R, shared over the window's minimum
    /// length). Default 3.
    pub anchor_tilt_noise_deg: f64,
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
            gyro_bias_sd_dps: 5.0,
            gyro_bias_walk_dps: 0.01,
            reacquire_gravity: true,
            anchor_acc_g: 0.1,
            anchor_gyro_dps: 150.0,
            anchor_window_s: 0.1,
            anchor_tilt_noise_deg: 3.0,
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
            ("gyro_bias_sd_dps", self.gyro_bias_sd_dps),
            ("gyro_bias_walk_dps", self.gyro_bias_walk_dps),
            ("anchor_acc_g", self.anchor_acc_g),
            ("anchor_gyro_dps", self.anchor_gyro_dps),
            ("anchor_window_s", self.anchor_window_s),
            ("anchor_tilt_noise_deg", self.anchor_tilt_noise_deg),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(LdhError::param(n, v, "must be > 0"));
            }
        }
        // Physical bounds of the windows and the cut-off (docs/parameters.md "Bounds"): a
        // reacquisition after up to 10 s of rejected updates (longer is gyroscope integration
        // across several strides), gravity windows of 0.02–1 s (foot flat lasts 0.1–0.4 s of a
        // stride: a longer window finds none), a tilt low-pass of 0.1–10 Hz.
        crate::align::within("attitude.reacquire_s", self.reacquire_s, 0.0, 10.0, "s")?;
        crate::align::within(
            "attitude.anchor_window_s",
            self.anchor_window_s,
            0.02,
            1.0,
            "s",
        )?;
        crate::align::within(
            "attitude.acc_only_cutoff_hz",
            self.acc_only_cutoff_hz,
            0.1,
            10.0,
            "Hz",
        )?;
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
    /// Estimated gyroscope bias at the end (anterior, medio-lateral axes of F), deg/s, on top
    /// of what `align` removed (fusion only; zero otherwise).
    #[serde(default)]
    pub gyro_bias_dps: [f64; 2],
    /// Number of gravity re-acquisition windows (fusion only).
    #[serde(default)]
    pub gravity_windows: usize,
}

/// The angle `a` (rad) wrapped into [−π, π): a − 2π ⌊(a + π) / 2π⌋.
fn wrap(a: f64) -> f64 {
    // |a| < 3 puts (a + π) / 2π in (0.02, 0.98), where the floor is 0 and a − 2π·0 is a bit
    // for bit: the common case, without the call to floor (no SSE4.1 in baseline x86-64)
    if a.abs() < 3.0 {
        return a;
    }
    let t = std::f64::consts::TAU;
    a - t * ((a + std::f64::consts::PI) / t).floor()
}

#[cfg(test)]
#[test]
fn wraps_fast_path_is_the_formula_bit_for_bit() {
    let t = std::f64::consts::TAU;
    let formula = |a: f64| a - t * ((a + std::f64::consts::PI) / t).floor();
    let mut a = -3.0f64;
    while a < 3.0 {
        assert_eq!(wrap(a).to_bits(), formula(a).to_bits(), "{a}");
        assert_eq!(wrap(-a).to_bits(), formula(-a).to_bits(), "{a}");
        a = a.next_up() + 1e-4;
    }
    for a in [
        0.0,
        -0.0,
        1e-300,
        -1e-300,
        2.999_999_999_999_999_6,
        -2.999_999_999_999_999_6,
    ] {
        assert_eq!(wrap(a).to_bits(), formula(a).to_bits(), "{a}");
    }
    for a in [
        3.0,
        -3.0,
        3.5,
        -4.0,
        10.0,
        std::f64::consts::PI,
        -std::f64::consts::PI,
    ] {
        assert_eq!(wrap(a).to_bits(), formula(a).to_bits(), "{a}");
    }
    assert!(wrap(f64::NAN).is_nan());
}

fn acc_tilt(f: [f64; 3]) -> (f64, f64) {
    let phi = f[1].atan2(f[2]);
    let theta = (-f[0]).atan2((f[1] * f[1] + f[2] * f[2]).sqrt());
    (phi, theta)
}

/// Estimate the attitude of one aligned recording.
pub fn estimate(al: &Aligned, params: &ValidAttitudeParams) -> Result<Attitude> {
    let p = &params.0;
    match p.model {
        AttitudeModel::Fusion => fusion(al, p),
        AttitudeModel::Acc => acc_only(al, p),
    }
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
        gyro_bias_dps: [0.0; 2],
        gravity_windows: 0,
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
