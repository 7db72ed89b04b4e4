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
//! **Tilt from the zero-velocity update** (issue 20). The attitude's roll and pitch are
//! anchored to the accelerometer's tilt at foot flat, where the sensor is not at rest: it
//! rotates over the ankle, faster and faster through mid-stance, so a sensor h above the ankle
//! feels α h across the shank and the anchor is off by α h / g (HuGaDB's mid-shin sensors:
//! 2.5–15°; docs/accuracy.md "Why HuGaDB strides drift"). The gyroscope carries that error
//! through the stride, where it leaks g sin δ along the walk: a velocity drift of g δ T
//! against the walking direction at the next mid-stance, and an ankle that ends δ × L off
//! the floor. Over one stride the specific force must integrate to the velocity change plus
//! gravity, v₁ − v₀ + g T ẑ; the rotation that takes the integrated specific force onto that
//! vector is the stride's tilt error (a zero-velocity update observes roll and pitch: Foxlin
//! 2005, IEEE CG&A 25(6):38; Skog et al. 2010), and it is removed before integrating. Linear
//! de-drifting already took the constant g δ of such an error out of the horizontal length, so
//! the lengths hardly move (HuGaDB ≤ 4.4 cm, family A ≤ 0.7 mm, family B ≤ 4.4 mm); what
//! changes is what the checks see. The floor-level closure is not used to estimate the tilt, and checks it: a
//! horizontal drift that was not a tilt (a step lost at a clipped run) leaves the ankle |z| =
//! δ × L off the floor after the correction, so the drift such a closure could hide, |z| g T /
//! L, counts as unexplained ([`LengthEstimate::unexplained_mps`], never more than the
//! horizontal drift before the correction, so no check is stricter than without it).
//!
//! **Plausibility** ([`LengthEstimate::implausible`]): a stride length is withheld (the stride is
//! marked invalid with the reason) when the integration is inconsistent — the velocity drift
//! removed by de-drifting or the horizontal drift the tilt does not explain is large
//! ([`MAX_DRIFT_MPS`]), the tilt correction exceeds [`MAX_TILT_DEG`], the unexplained drift
//! over a stride whose accelerometer clipped could, as a step at a clipped run, move the ankle
//! by more than
//! [`MAX_CLIP_STEP_SHARE`] of the length, or the ankle does not come back to the floor level
//! (within [`MAX_VERTICAL_M`] and [`MAX_VERTICAL_SHARE`] of the length) — or when the length
//! disagrees with a shank-pendulum estimate from the pitch excursion in stance by more than a
//! factor 2 (0.45–2.2). The bout-level checks (a stride far from the local median of its bout, left and
//! right disagreeing over the walk) are in [`super::mod`] and [`crate::pipeline`].

use nalgebra::{Matrix3, Rotation3, Vector3};
use serde::{Deserialize, Serialize};

use super::{LengthCheck, StrideCode, StrideFinding};
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
    /// Velocity error removed by de-drifting after the tilt correction (|v_end − ω × r|), m/s.
    pub drift_mps: f64,
    /// Horizontal velocity drift the tilt correction does not explain, m/s: the larger of the
    /// horizontal drift left after it and the drift the floor-level closure could hide (|z| g
    /// T / L), never more than the horizontal drift before the correction.
    pub unexplained_mps: f64,
    /// Tilt of the attitude corrected over the stride (from the velocity at the next
    /// mid-stance), deg.
    pub tilt_deg: f64,
    /// Vertical displacement of the ankle between the two mid-stances, m (0 on level ground).
    pub vertical_m: f64,
    /// Samples between the two mid-stances where the accelerometer clipped (reconstructed,
    /// [`crate::preprocess::declip`]).
    pub clipped_samples: usize,
    /// Horizontal ankle displacement the unexplained drift could leave after linear
    /// de-drifting if it were a step at one of the clipped runs, m: `unexplained_mps` ×
    /// duration × max |½ − φ| over the runs (φ: the run's centre as a share of the
    /// integration); 0 without clipping.
    pub clip_step_m: f64,
}

/// Largest velocity drift over one stride accepted, m/s: what de-drifting removes after the
/// tilt correction, and the horizontal drift the tilt does not explain.
pub const MAX_DRIFT_MPS: f64 = 0.6;
/// Largest tilt correction of the attitude over one stride accepted, deg.
///
/// The tilt the zero-velocity update finds is the error of the foot-flat anchor: the sensor's
/// own acceleration there, α h across the shank, read as gravity. With the shank's angular
/// acceleration through mid-stance at most ~10 rad/s² and the sensor at most 0.35 m above the
/// ankle (a shank is ~0.43 m long), α h / g stays below 0.36 rad ≈ 20°; a larger correction
/// means the attitude is not that of a shank pivoting over a resting foot. A physical bound,
/// not fitted.
pub const MAX_TILT_DEG: f64 = 20.0;
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
    /// Why this length cannot be vouched for, if so: the check it fails, with its text. `pendulum_m`: the shank-pendulum estimate
    /// ([`pendulum_length_m`]), NaN when unknown.
    pub fn check(&self, pendulum_m: f64) -> Option<StrideFinding> {
        use LengthCheck::*;
        let f = |c: LengthCheck, m: String| StrideFinding::new(StrideCode::Length(c), m);
        if !self.length_m.is_finite() {
            return Some(f(NotIntegrable, "stride length not integrable".into()));
        }
        if self.drift_mps > MAX_DRIFT_MPS {
            return Some(f(
                Drift,
                format!(
                    "stride length withheld: velocity drift {:.2} m/s over the stride",
                    self.drift_mps
                ),
            ));
        }
        if self.tilt_deg > MAX_TILT_DEG {
            return Some(f(
                TiltCorrection,
                format!(
                "stride length withheld: the attitude needed a {:.0} deg tilt correction over the stride (more than {MAX_TILT_DEG:.0})",
                self.tilt_deg
            )));
        }
        if self.unexplained_mps > MAX_DRIFT_MPS {
            return Some(f(
                Drift,
                format!(
                "stride length withheld: velocity drift {:.2} m/s over the stride that a tilt of the attitude does not explain",
                self.unexplained_mps
            )));
        }
        if self.clipped_samples > 0 && self.clip_step_m > MAX_CLIP_STEP_SHARE * self.length_m {
            return Some(f(
                Clipped,
                format!(
                "stride length withheld: the accelerometer clipped on {} sample{} of the stride, and the drift left after reconstructing them could move the ankle by {:.0} cm ({:.0} % of the {:.2} m stride)",
                self.clipped_samples,
                if self.clipped_samples == 1 { "" } else { "s" },
                self.clip_step_m * 100.0,
                100.0 * self.clip_step_m / self.length_m,
                self.length_m
            )));
        }
        if self.vertical_m.abs() > MAX_VERTICAL_M.min(MAX_VERTICAL_SHARE * self.length_m) {
            return Some(f(
                Floor,
                format!(
                "stride length withheld: the ankle ends {:.0} cm off the floor level ({:.0} % of the {:.2} m stride)",
                self.vertical_m * 100.0,
                100.0 * self.vertical_m.abs() / self.length_m,
                self.length_m
            )));
        }
        if pendulum_m.is_finite()
            && pendulum_m > 0.05
            && !(0.45..=2.2).contains(&(self.length_m / pendulum_m))
        {
            return Some(f(
                Pendulum,
                format!(
                "stride length withheld: {:.2} m disagrees with the shank-pendulum estimate {:.2} m",
                self.length_m, pendulum_m
            )));
        }
        None
    }

    /// [`LengthEstimate::check`]'s text.
    pub fn implausible(&self, pendulum_m: f64) -> Option<String> {
        self.check(pendulum_m).map(|f| f.message)
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

/// The rotation matrix of the attitude at sample `i` (frame F to the world).
fn attitude_at(att: &Attitude, i: usize) -> Matrix3<f64> {
    let r = rotation_wf(
        att.roll_deg[i].to_radians(),
        att.pitch_deg[i].to_radians(),
        att.yaw_deg[i].to_radians(),
    );
    Matrix3::from_fn(|k, l| r[k][l])
}

/// The tilt error of the attitude over one stride, as the rotation that takes the integrated
/// specific force `sum` (m/s, world frame, gravity included) onto what it must be,
/// `target` = v₁ − v₀ + g T ẑ (see the module doc); the identity when either is zero.
fn tilt_correction(sum: &Vector3<f64>, target: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(sum, target).unwrap_or_else(Rotation3::identity)
}

/// Horizontal displacement of the ankle between two mid-stance samples (see the module doc).
pub fn stride_length(al: &Aligned, att: &Attitude, z0: usize, z1: usize, h: f64) -> LengthEstimate {
    integrate(al, att, &world_force(al, att, z0, z1), z0, z1, h)
}

/// [`stride_length`] with the sensor at each of `heights_m` above the ankle, in that order: the
/// specific force in the world frame, which does not depend on the height, is computed once
/// (its rotations are most of the integration's cost), so each estimate is the one
/// [`stride_length`] gives, bit for bit.
pub fn stride_lengths(
    al: &Aligned,
    att: &Attitude,
    z0: usize,
    z1: usize,
    heights_m: &[f64],
) -> Vec<LengthEstimate> {
    let force = world_force(al, att, z0, z1);
    heights_m
        .iter()
        .map(|&h| integrate(al, att, &force, z0, z1, h))
        .collect()
}

/// Specific force in the world frame, m/s², gravity included, at samples `z0..=z1`.
fn world_force(al: &Aligned, att: &Attitude, z0: usize, z1: usize) -> Vec<Vector3<f64>> {
    let acc = al.acc_motion_g();
    (z0..=z1)
        .map(|i| {
            attitude_at(att, i)
                * Vector3::new(acc[0][i], acc[1][i], acc[2][i])
                * STANDARD_GRAVITY_MPS2
        })
        .collect()
}

/// [`stride_length`] from the specific force of its samples ([`world_force`]), the sensor `h`
/// above the ankle.
fn integrate(
    al: &Aligned,
    att: &Attitude,
    force: &[Vector3<f64>],
    z0: usize,
    z1: usize,
    h: f64,
) -> LengthEstimate {
    let dt = 1.0 / al.fs_hz;
    let up = Vector3::z();
    // Sensor position from the ankle and its velocity when the ankle is at rest.
    let lever = |i: usize| -> (Vector3<f64>, Vector3<f64>) {
        let r = attitude_at(att, i);
        let rw = r * Vector3::new(0.0, 0.0, h);
        let g = &al.gyro_dps;
        let w = r * Vector3::new(g[0][i], g[1][i], g[2][i]).map(f64::to_radians);
        (rw, w.cross(&rw))
    };
    let (r0, v0) = lever(z0);
    let (r1, v1) = lever(z1);
    let m = z1 - z0;
    let duration = m as f64 * dt;
    // Tilt: over the stride the specific force integrates to v₁ − v₀ + g T ẑ.
    let sum: Vector3<f64> = force.windows(2).map(|p| (p[0] + p[1]) * (0.5 * dt)).sum();
    let target = v1 - v0 + up * (STANDARD_GRAVITY_MPS2 * duration);
    let tilt = tilt_correction(&sum, &target);
    let raw_drift = sum - target;
    let mut v = Vec::with_capacity(m + 1);
    v.push(v0);
    for j in 1..=m {
        let a = tilt * ((force[j - 1] + force[j]) * 0.5) - up * STANDARD_GRAVITY_MPS2;
        v.push(v[j - 1] + a * dt);
    }
    // Linear de-drifting of what the tilt leaves, so the velocity ends at the known v1.
    let drift = v[m] - v1;
    let dedrifted = |j: usize| v[j] - drift * (j as f64 / m as f64);
    let d: Vector3<f64> = (1..=m)
        .map(|j| (dedrifted(j - 1) + dedrifted(j)) * (0.5 * dt))
        .sum();
    let ankle = d - tilt * (r1 - r0);
    let length = ankle.x.hypot(ankle.y);
    // A horizontal drift that was not a tilt leaves the ankle |z| = δ·L off the floor after
    // the correction, δ = drift / (g T): the drift such a closure could hide.
    let hidden = ankle.z.abs() * STANDARD_GRAVITY_MPS2 * duration / length.max(0.05);
    let unexplained = drift.xy().norm().max(hidden.min(raw_drift.xy().norm()));
    let clipped = clipped_between(&al.acc_clipped, z0, z1);
    LengthEstimate {
        length_m: length,
        drift_mps: drift.norm(),
        unexplained_mps: unexplained,
        tilt_deg: tilt.angle().to_degrees(),
        vertical_m: ankle.z,
        clipped_samples: clipped.len(),
        clip_step_m: unexplained * duration * worst_step_share(clipped, z0, z1),
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
mod tests;
