//! Stride length by strapdown integration between two zero-velocity instants of the ankle, and
//! the checks that withhold it when it cannot be vouched for (issue 20).
//!
//! **Zero-velocity instant.** The ankle is at rest only while the foot is flat (after the heel
//! rocker, before heel off). [`ZeroVelocity::FootFlat`] (default) looks for it in the middle
//! of the detected stance (10–65 % of HS→TO, so a late toe off cannot move it into early swing,
//! where the shank also stops rotating at its pitch peak) as the 0.1 s window with the least
//! rotation and an acceleration magnitude closest to 1 g (the SHOE statistic of Skog et al.
//! 2010, IEEE TBME 57:2657, on the shank). The sensor is not at rest there: the shank rotates
//! over the fixed ankle, so its velocity is ω × r (the inverted-pendulum velocity update of
//! Sci Rep 2021, doi 10.1038/s41598-021-81009-w; r = `sensor_height_m` along the shank).
//! [`ZeroVelocity::MinGyro`] keeps the former rule (minimum |ω| anywhere between HS and TO).
//!
//! **Acceleration integrated.** [`crate::align::Aligned::acc_motion_g`]: the paper's
//! preprocessing interpolates every sample whose |a| lies beyond 3 SDs of its mean, which in
//! slow gait (|a| varying little) is 70-110 ms of every heel strike's real deceleration; cut
//! from the integral it made family A's slow walkers' strides up to 29 % short, so the
//! integration reads the acceleration with those samples kept. Samples where the
//! accelerometer clipped are reconstructed on the axis that clipped by a local quadratic
//! ([`crate::preprocess::declip`]; issue 20: a ±2 g shank sensor clips in 2-3 runs per stride,
//! in push-off and swing, and interpolating them left lengths up to 40 % short).
//!
//! **Plausibility** ([`LengthEstimate::implausible`]): a stride length is withheld (the stride is
//! marked invalid with the reason) when the integration is inconsistent — the velocity drift
//! removed by de-drifting is large ([`MAX_DRIFT_MPS`]), the drift left over a stride whose
//! accelerometer clipped could, as a step at a clipped run, move the ankle by more than
//! [`MAX_CLIP_STEP_SHARE`] of the length, or the ankle does not come back to the floor level
//! (within [`MAX_VERTICAL_M`] and [`MAX_VERTICAL_SHARE`] of the length) — or when the length
//! disagrees with a shank-pendulum estimate from the pitch excursion in stance by more than a
//! factor 2 (0.45–2.2). The bout-level checks (a stride far from its bout's median, left and
//! right disagreeing over the walk) are in [`super::mod`] and [`crate::pipeline`].

use serde::{Deserialize, Serialize};

use crate::align::Aligned;
use crate::attitude::{rotation_wf, Attitude};
use crate::error::LdhError;
use crate::recording::STANDARD_GRAVITY_MPS2;

/// How the zero-velocity (mid-stance) instant of each stance is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ZeroVelocity {
    /// The quietest 0.1 s window (low |ω|, |a| ≈ 1 g) in 10–65 % of the stance (default).
    #[default]
    FootFlat,
    /// The minimum |ω| anywhere between HS and TO (before issue 20).
    MinGyro,
}

impl std::str::FromStr for ZeroVelocity {
    type Err = LdhError;
    fn from_str(s: &str) -> crate::error::Result<Self> {
        match s {
            "foot-flat" => Ok(ZeroVelocity::FootFlat),
            "min-gyro" => Ok(ZeroVelocity::MinGyro),
            o => Err(LdhError::param(
                "zero_velocity",
                o,
                "expected foot-flat or min-gyro",
            )),
        }
    }
}

/// Zero-velocity sample of the stance from `hs` to `to` (sample indices, `to` > `hs` + 2).
pub fn zero_velocity_sample(
    rule: ZeroVelocity,
    al: &Aligned,
    w_norm: &[f64],
    hs: usize,
    to: usize,
) -> Option<usize> {
    if to <= hs + 2 || to > w_norm.len() {
        return None;
    }
    match rule {
        ZeroVelocity::MinGyro => (hs..to).min_by(|&x, &y| w_norm[x].total_cmp(&w_norm[y])),
        ZeroVelocity::FootFlat => {
            let len = (to - hs) as f64;
            let a = hs + (0.10 * len).round() as usize;
            let b = (hs + (0.65 * len).round() as usize).max(a + 1);
            let half = ((0.05 * al.fs_hz).round() as usize).max(1);
            // SHOE: ‖ω‖²/σω² + (|a| − 1 g)²/σa², σω = 20 deg/s, σa = 0.05 g, mean over the window.
            // Each sample's term once, each window's mean once (summed in the same order as
            // term by term: the same numbers; `min_by` had computed both sides of every
            // comparison, and every term once per window holding it).
            let (lo0, hi0) = (a.saturating_sub(half), (b + half).min(w_norm.len()));
            let term: Vec<f64> = (lo0..hi0)
                .map(|j| {
                    let an =
                        (al.acc_g[0][j].powi(2) + al.acc_g[1][j].powi(2) + al.acc_g[2][j].powi(2))
                            .sqrt();
                    (w_norm[j] / 20.0).powi(2) + ((an - 1.0) / 0.05).powi(2)
                })
                .collect();
            let stat: Vec<f64> = (a..b)
                .map(|i| {
                    let (lo, hi) = (i.saturating_sub(half), (i + half + 1).min(w_norm.len()));
                    let s: f64 = term[lo - lo0..hi - lo0].iter().sum();
                    s / (hi - lo) as f64
                })
                .collect();
            (a..b).min_by(|&x, &y| stat[x - a].total_cmp(&stat[y - a]))
        }
    }
}

/// One integrated stride: the length and what the integration says about its own consistency.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LengthEstimate {
    /// Horizontal displacement of the ankle, m.
    pub length_m: f64,
    /// Velocity error removed by de-drifting (|v_end − ω × r| before correction), m/s.
    pub drift_mps: f64,
    /// Vertical displacement of the ankle between the two mid-stances, m (0 on level ground).
    pub vertical_m: f64,
    /// Samples between the two mid-stances where the accelerometer clipped (reconstructed,
    /// [`crate::preprocess::declip`]).
    pub clipped_samples: usize,
    /// Horizontal ankle displacement the horizontal drift could leave after linear de-drifting
    /// if it were a step at one of the clipped runs, m: |drift| × duration × max |½ − φ| over
    /// the runs (φ: the run's centre as a share of the integration); 0 without clipping.
    pub clip_step_m: f64,
}

/// Largest velocity drift over one stride accepted, m/s.
pub const MAX_DRIFT_MPS: f64 = 0.6;
/// Largest vertical ankle displacement over one stride accepted, m.
pub const MAX_VERTICAL_M: f64 = 0.15;
/// Largest vertical ankle displacement over one stride accepted, as a share of the stride
/// length.
///
/// On level ground the ankle ends a stride where it started, so the vertical displacement the
/// integration finds is its own error, observed; the horizontal error, which cannot be
/// observed, comes from the same integration (attitude, drift, impacts). A stride whose
/// integration misses the floor by more than this share of its length is not vouched for to
/// that share horizontally either: 15 %, the largest per-stride error the team accepts (issue
/// 20). Derived from that tolerance, not fitted (docs/accuracy.md has its effect on both
/// simulator families). A slow stride of 0.6 m is held to 9 cm, where [`MAX_VERTICAL_M`] alone
/// allowed 15 cm.
pub const MAX_VERTICAL_SHARE: f64 = 0.15;

/// Largest horizontal error a step at the clipped samples could leave, as a share of the
/// stride length.
///
/// What a reconstruction of clipped samples misses is a step in velocity at the clipped run
/// (its time known), which linear de-drifting turns into a position error of drift × duration
/// × (½ − φ) for a run at the share φ of the integration; the drift left over the stride is
/// observed, so is that error's worst case. Held to the same 15 % as the floor-level miss
/// ([`MAX_VERTICAL_SHARE`]): the largest per-stride error the team accepts (issue 20); not
/// fitted.
pub const MAX_CLIP_STEP_SHARE: f64 = MAX_VERTICAL_SHARE;

impl LengthEstimate {
    /// Why this length cannot be vouched for, if so. `pendulum_m`: the shank-pendulum estimate
    /// ([`pendulum_length_m`]), NaN when unknown.
    pub fn implausible(&self, pendulum_m: f64) -> Option<String> {
        if !self.length_m.is_finite() {
            return Some("stride length not integrable".into());
        }
        if self.drift_mps > MAX_DRIFT_MPS {
            return Some(format!(
                "stride length withheld: velocity drift {:.2} m/s over the stride",
                self.drift_mps
            ));
        }
        if self.clipped_samples > 0 && self.clip_step_m > MAX_CLIP_STEP_SHARE * self.length_m {
            return Some(format!(
                "stride length withheld: the accelerometer clipped on {} sample{} of the stride, and the drift left after reconstructing them could move the ankle by {:.0} cm ({:.0} % of the {:.2} m stride)",
                self.clipped_samples,
                if self.clipped_samples == 1 { "" } else { "s" },
                self.clip_step_m * 100.0,
                100.0 * self.clip_step_m / self.length_m,
                self.length_m
            ));
        }
        if self.vertical_m.abs() > MAX_VERTICAL_M.min(MAX_VERTICAL_SHARE * self.length_m) {
            return Some(format!(
                "stride length withheld: the ankle ends {:.0} cm off the floor level ({:.0} % of the {:.2} m stride)",
                self.vertical_m * 100.0,
                100.0 * self.vertical_m.abs() / self.length_m,
                self.length_m
            ));
        }
        if pendulum_m.is_finite()
            && pendulum_m > 0.05
            && !(0.45..=2.2).contains(&(self.length_m / pendulum_m))
        {
            return Some(format!(
                "stride length withheld: {:.2} m disagrees with the shank-pendulum estimate {:.2} m",
                self.length_m, pendulum_m
            ));
        }
        None
    }
}

/// Typical shank length (knee to ankle joint) of an adult, m (Winter 2009: 0.246 × height).
pub const SHANK_LENGTH_M: f64 = 0.43;
/// Ratio of the integrated stride length to the bare pendulum term, median over the family A
/// tuning cohort (seed 100; 1.69, range 0.82–2.19): the foot's roll and the swing leg add to
/// the stance leg's rotation.
pub const PENDULUM_GAIN: f64 = 1.7;

/// Shank-pendulum stride length: over the stance the shank turns over the fixed foot from
/// θ_HS to θ_TO, moving the knee by ℓ (sin θ_TO − sin θ_HS); the body covers that during the
/// stance fraction `stance` of the stride, so L ≈ g ℓ (sin θ_TO − sin θ_HS) / stance, g =
/// [`PENDULUM_GAIN`]. Coarse (ℓ varies between people, the foot rolls): used only as a
/// factor-2 sanity check (a length outside 0.45–2.2 × this is withheld).
pub fn pendulum_length_m(theta_hs_deg: f64, theta_to_deg: f64, stance: f64) -> f64 {
    if !(stance > 0.3 && stance < 0.95) {
        return f64::NAN;
    }
    PENDULUM_GAIN
        * SHANK_LENGTH_M
        * (theta_to_deg.to_radians().sin() - theta_hs_deg.to_radians().sin())
        / stance
}

/// Horizontal displacement of the ankle between two mid-stance samples (see the module doc).
pub fn stride_length(al: &Aligned, att: &Attitude, z0: usize, z1: usize, h: f64) -> LengthEstimate {
    let fs = al.fs_hz;
    let dt = 1.0 / fs;
    let rot = |i: usize| {
        rotation_wf(
            att.roll_deg[i].to_radians(),
            att.pitch_deg[i].to_radians(),
            att.yaw_deg[i].to_radians(),
        )
    };
    let mv = |r: &[[f64; 3]; 3], v: [f64; 3]| -> [f64; 3] {
        std::array::from_fn(|k| r[k][0] * v[0] + r[k][1] * v[1] + r[k][2] * v[2])
    };
    let acc = al.acc_motion_g();
    let acc_w = |i: usize| -> [f64; 3] {
        let f = [acc[0][i], acc[1][i], acc[2][i]];
        let mut a = mv(&rot(i), f);
        for x in a.iter_mut() {
            *x *= STANDARD_GRAVITY_MPS2;
        }
        a[2] -= STANDARD_GRAVITY_MPS2;
        a
    };
    // Sensor position from the ankle and its velocity when the ankle is at rest.
    let lever = |i: usize| -> ([f64; 3], [f64; 3]) {
        let r = rot(i);
        let rw = mv(&r, [0.0, 0.0, h]);
        let w = mv(
            &r,
            [
                al.gyro_dps[0][i].to_radians(),
                al.gyro_dps[1][i].to_radians(),
                al.gyro_dps[2][i].to_radians(),
            ],
        );
        let v = [
            w[1] * rw[2] - w[2] * rw[1],
            w[2] * rw[0] - w[0] * rw[2],
            w[0] * rw[1] - w[1] * rw[0],
        ];
        (rw, v)
    };
    let (r0, v0) = lever(z0);
    let (r1, v1) = lever(z1);
    let m = z1 - z0;
    let mut v = vec![[0.0f64; 3]; m + 1];
    v[0] = v0;
    let mut prev = acc_w(z0);
    for j in 1..=m {
        let a = acc_w(z0 + j);
        for k in 0..3 {
            v[j][k] = v[j - 1][k] + 0.5 * dt * (prev[k] + a[k]);
        }
        prev = a;
    }
    // Linear de-drifting so the velocity ends at the known v1.
    let drift: [f64; 3] = std::array::from_fn(|k| v[m][k] - v1[k]);
    for (j, vj) in v.iter_mut().enumerate() {
        let f = j as f64 / m as f64;
        for k in 0..3 {
            vj[k] -= f * drift[k];
        }
    }
    let mut d = [0.0f64; 3];
    for j in 1..=m {
        for k in 0..3 {
            d[k] += 0.5 * dt * (v[j - 1][k] + v[j][k]);
        }
    }
    let ankle = [d[0] - (r1[0] - r0[0]), d[1] - (r1[1] - r0[1])];
    let clipped = clipped_between(&al.acc_clipped, z0, z1);
    LengthEstimate {
        length_m: (ankle[0] * ankle[0] + ankle[1] * ankle[1]).sqrt(),
        drift_mps: (drift[0].powi(2) + drift[1].powi(2) + drift[2].powi(2)).sqrt(),
        vertical_m: d[2] - (r1[2] - r0[2]),
        clipped_samples: clipped.len(),
        clip_step_m: drift[0].hypot(drift[1]) * m as f64 * dt * worst_step_share(clipped, z0, z1),
    }
}

/// The sorted sample indices of `clipped` that lie in `[a, b]`.
fn clipped_between(clipped: &[usize], a: usize, b: usize) -> &[usize] {
    &clipped[clipped.partition_point(|&i| i < a)..clipped.partition_point(|&i| i <= b)]
}

/// max |½ − φ| over the runs of consecutive samples in `clipped` (sorted, within `[z0, z1]`),
/// φ = (run centre − z0) / (z1 − z0): the share of a step's size that linear de-drifting over
/// the duration leaves as position error (0 without clipping).
fn worst_step_share(clipped: &[usize], z0: usize, z1: usize) -> f64 {
    let m = (z1 - z0) as f64;
    let mut worst = 0.0f64;
    let mut k = 0;
    while k < clipped.len() {
        let start = clipped[k];
        while k + 1 < clipped.len() && clipped[k + 1] == clipped[k] + 1 {
            k += 1;
        }
        let centre = 0.5 * (start + clipped[k]) as f64;
        worst = worst.max((0.5 - (centre - z0 as f64) / m).abs());
        k += 1;
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::align::Alignment;
    use crate::attitude::AttitudeModel;

    /// A level 1 s stride at 100 Hz, shank upright and not rotating (the sensor moves with the
    /// ankle): forward velocity 2 sin²(π t) m/s (1.00 m), with `lost` m/s of forward
    /// acceleration missing, evenly over the samples `run`, which are marked clipped.
    fn stride(run: std::ops::Range<usize>, lost: f64) -> (Aligned, Attitude) {
        let (fs, n) = (100.0, 101);
        let ax: Vec<f64> = (0..n)
            .map(|i| {
                let t = i as f64 / fs;
                let a = 2.0 * std::f64::consts::PI * (2.0 * std::f64::consts::PI * t).sin();
                let cut = if run.contains(&i) {
                    lost * fs / run.len() as f64
                } else {
                    0.0
                };
                (a - cut) / STANDARD_GRAVITY_MPS2
            })
            .collect();
        let al = Aligned {
            fs_hz: fs,
            acc_g: [ax, vec![0.0; n], vec![1.0; n]],
            gyro_dps: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            acc_clipped: run.collect(),
            acc_motion_g: None,
            alignment: Alignment::identity(),
        };
        let att = Attitude {
            model: AttitudeModel::Fusion,
            fs_hz: fs,
            roll_deg: vec![0.0; n],
            pitch_deg: vec![0.0; n],
            yaw_deg: vec![0.0; n],
            final_weights: vec![],
            final_tilt_noise_deg: vec![],
            gyro_bias_dps: [0.0; 2],
            gravity_windows: 0,
        };
        (al, att)
    }

    /// What a reconstruction of clipped samples misses is a step in velocity at a known time:
    /// linear de-drifting leaves drift × duration × (φ − ½) of it in the length, which is
    /// exactly what `clip_step_m` bounds, and the stride is withheld when that exceeds 15 %.
    #[test]
    fn a_step_left_at_the_clipped_samples_is_bounded_and_withheld_when_large() {
        let est = |run, lost| {
            let (al, att) = stride(run, lost);
            stride_length(&al, &att, 0, 100, 0.1)
        };
        // Fully reconstructed (nothing lost): the length, no drift, no bound.
        let e = est(88..97, 0.0);
        assert!((e.length_m - 1.0).abs() < 2e-3, "{}", e.length_m);
        assert!(e.clip_step_m < 1e-3 && e.clipped_samples == 9);
        assert_eq!(e.implausible(f64::NAN), None);
        // 0.5 m/s lost in terminal swing (φ = 0.92): 0.21 m too long, the drift (0.5 m/s)
        // passes its own check, the step bound says 0.21 m = 17 %: withheld.
        let e = est(88..97, 0.5);
        let expected = 0.5 * 1.0 * (0.92 - 0.5);
        assert!((e.length_m - 1.0 - expected).abs() < 3e-3, "{}", e.length_m);
        assert!((e.clip_step_m - expected).abs() < 3e-3, "{}", e.clip_step_m);
        assert!((e.drift_mps - 0.5).abs() < 1e-9);
        let r = e.implausible(f64::NAN).unwrap();
        assert!(
            r.contains("clipped on 9 samples") && r.contains("21 cm (17 % of the 1.21 m stride)"),
            "{r}"
        );
        // The same loss in early swing (φ = 0.66): 0.08 m (7 %), reported.
        let e = est(62..71, 0.5);
        assert!(
            (e.length_m - 1.0 - 0.5 * 0.16).abs() < 3e-3,
            "{}",
            e.length_m
        );
        assert_eq!(e.implausible(f64::NAN), None);
    }

    #[test]
    fn pendulum_estimate_of_a_normal_stride() {
        // θ from −20° at HS to +40° at TO over 60 % of the stride: ≈ 1.0 m.
        let l = pendulum_length_m(-20.0, 40.0, 0.6);
        assert!(
            (l - 1.7 * 0.43 * (0.6428 + 0.3420) / 0.6).abs() < 1e-3,
            "{l}"
        );
        assert!(pendulum_length_m(0.0, 10.0, 0.1).is_nan());
    }

    #[test]
    fn implausible_lengths_say_why() {
        let ok = LengthEstimate {
            length_m: 1.3,
            drift_mps: 0.1,
            vertical_m: 0.01,
            clipped_samples: 0,
            clip_step_m: 0.0,
        };
        assert_eq!(ok.implausible(1.1), None);
        assert_eq!(ok.implausible(f64::NAN), None);
        let r = ok.implausible(0.4).unwrap();
        assert!(r.contains("shank-pendulum"), "{r}");
        let drift = LengthEstimate {
            drift_mps: 1.5,
            ..ok
        };
        assert!(drift.implausible(1.1).unwrap().contains("drift"));
        // 11 cm off the floor: withheld on a 0.59 m stride (19 %), not on a 1.3 m one (8 %).
        let slow = LengthEstimate {
            length_m: 0.59,
            vertical_m: 0.11,
            ..ok
        };
        let r = slow.implausible(0.6).unwrap();
        assert!(
            r.contains("11 cm off the floor level (19 % of the 0.59 m stride)"),
            "{r}"
        );
        let brisk = LengthEstimate {
            vertical_m: -0.11,
            ..ok
        };
        assert_eq!(brisk.implausible(1.1), None);
        let up = LengthEstimate {
            vertical_m: 0.3,
            ..ok
        };
        assert!(up.implausible(1.1).unwrap().contains("floor"));
        // Clipped and reconstructed: reported unless the drift left, as a step at a clipped
        // run, could move the ankle by more than 15 % of the length.
        let clipped = LengthEstimate {
            clipped_samples: 3,
            clip_step_m: 0.15,
            ..ok
        };
        assert_eq!(clipped.implausible(1.1), None);
        let step = LengthEstimate {
            clip_step_m: 0.21,
            ..clipped
        };
        let r = step.implausible(1.1).unwrap();
        assert!(
            r.contains("clipped on 3 samples") && r.contains("21 cm (16 % of the 1.30 m stride)"),
            "{r}"
        );
        assert_eq!(clipped_between(&[2, 5, 9, 12], 5, 9), &[5, 9]);
        assert!(clipped_between(&[2, 5, 9, 12], 6, 8).is_empty());
        assert!(clipped_between(&[], 0, 100).is_empty());
        // runs centred at 20 % and 85 % of a 100-sample integration: the later one is worse
        assert!((worst_step_share(&[29, 30, 31, 94, 95, 96], 10, 110) - 0.35).abs() < 1e-12);
        assert_eq!(worst_step_share(&[], 10, 110), 0.0);
        assert_eq!(
            "min-gyro".parse::<ZeroVelocity>().unwrap(),
            ZeroVelocity::MinGyro
        );
        assert!("x".parse::<ZeroVelocity>().is_err());
    }
}
