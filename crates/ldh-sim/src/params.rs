//! Family A subject parameters ([`SubjectParams`], [`LegParams`]): the values a subject is
//! simulated with, drawn from population distributions of healthy and LDH gait (SPEC §2,
//! issue 2) or given by hand, and their physical ranges.

use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::draw::normal_clamped;
use super::{check_samples, Group};
use ldh_core::error::{LdhError, Result};
use ldh_core::recording::Side;

/// Per-leg parameters of a subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegParams {
    /// Mean stance ratio (stance time / stride time). Normal 0.60.
    pub stance_ratio: f64,
    /// Fraction of the swing knee flexion removed (0 = normal, 0.2 = peak 60° → 48°).
    pub knee_reduction: f64,
    /// Scale of the hip flexion excursion about its mean (1 = normal).
    pub hip_scale: f64,
    /// Lateral excursion of the ankle in swing (circumduction), m.
    pub circumduction_m: f64,
    /// Anatomical roll change at mid-swing, deg (negative: knee medial to the ankle as the foot
    /// swings out).
    pub roll_swing_deg: f64,
    /// Anatomical roll in stance, deg (positive: knee lateral to the ankle).
    pub roll_stance_deg: f64,
    /// Height of the sensor above the ankle joint along the shank, m.
    pub sensor_height_m: f64,
    /// Distance of the sensor from the shank axis on the lateral side, m.
    pub sensor_lateral_m: f64,
    /// Extra ankle height at mid-swing, m.
    pub swing_clearance_m: f64,
}

impl Default for LegParams {
    fn default() -> Self {
        LegParams {
            stance_ratio: 0.60,
            knee_reduction: 0.0,
            hip_scale: 1.0,
            circumduction_m: 0.01,
            roll_swing_deg: -1.5,
            roll_stance_deg: 2.0,
            sensor_height_m: 0.10,
            sensor_lateral_m: 0.04,
            swing_clearance_m: 0.04,
        }
    }
}

/// The extra stride time at the first step of a belt start-up ([`SubjectParams::ramp_s`]):
/// 25 %, the 1.25 s against ≈ 1.0 s of steady walking seen on real treadmill trials while the
/// belt accelerates (issue 36).
pub const RAMP_STRIDE_EXTRA: f64 = 0.25;

pub(crate) fn is_zero_s(x: &f64) -> bool {
    *x == 0.0
}

/// One subject's gait and recording parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubjectParams {
    /// Identifier (folder name).
    pub subject_id: String,
    /// Group.
    pub group: Group,
    /// Affected side of an LDH subject.
    pub affected_side: Option<Side>,
    /// Sampling rate of both sensors, Hz.
    pub fs_hz: f64,
    /// Recording length, s.
    pub duration_s: f64,
    /// Quiet standing at start and at end, s.
    pub standing_s: f64,
    /// Mean stride time, s.
    pub stride_time_s: f64,
    /// Mean stride length, m.
    pub stride_length_m: f64,
    /// Coefficient of variation of stride time.
    pub stride_time_cv: f64,
    /// Coefficient of variation of stride length.
    pub stride_length_cv: f64,
    /// SD of the stance ratio from stride to stride.
    pub stance_ratio_sd: f64,
    /// Right heel strike at left phase 0.5 + this (step-time asymmetry, fraction of a stride).
    pub step_timing_asymmetry: f64,
    /// Right step = (1 + a) · L/2, left step = (1 − a) · L/2.
    pub step_length_asymmetry: f64,
    /// Foot angle to the ground at heel strike, deg.
    pub heel_strike_foot_angle_deg: f64,
    /// Foot angle to the ground at toe off, deg.
    pub toe_off_foot_angle_deg: f64,
    /// Walk there and back with a 180° turn in the middle (when there are ≥ 8 strides).
    pub turn: bool,
    /// Treadmill belt start-up, s from the first step: strides that begin within it are
    /// longer, by [`RAMP_STRIDE_EXTRA`] at the first step falling linearly to 0 at `ramp_s`
    /// (the belt accelerating to its speed). Default 0: no ramp (then not serialised, so
    /// earlier subjects keep their bytes).
    #[serde(default, skip_serializing_if = "is_zero_s")]
    pub ramp_s: f64,
    /// Slowing down before the walk ends, s before the last step: strides that end within it
    /// are longer, by [`RAMP_STRIDE_EXTRA`] at the last step falling linearly to 0 at
    /// `slowdown_s` before it (the mirror of `ramp_s`). Default 0 (then not serialised).
    #[serde(default, skip_serializing_if = "is_zero_s")]
    pub slowdown_s: f64,
    /// A trend in stride time over the whole walk: the last stride is `1 + trend_share` times
    /// the first, linearly in between (−0.25: a walker who speeds up throughout, 2.0 → 1.5 s).
    /// Default 0 (then not serialised).
    #[serde(default, skip_serializing_if = "is_zero_s")]
    pub trend_share: f64,
    /// Stairs: each step lands this much higher (ascent, > 0) or lower (descent, < 0) than the
    /// other foot, m (a riser is 0.15–0.18 m; each foot rises two risers a stride). Default 0:
    /// level ground (then not serialised).
    #[serde(default, skip_serializing_if = "is_zero_s")]
    pub stair_rise_m: f64,
    /// Left leg.
    pub left: LegParams,
    /// Right leg.
    pub right: LegParams,
}

/// A value drawn from N(mean, sd) clamped to [lo, hi].
#[derive(Debug, Clone, Copy)]
struct Spread {
    mean: f64,
    sd: f64,
    lo: f64,
    hi: f64,
}

/// A [`Spread`]: mean, SD, lowest, highest.
const fn spread(mean: f64, sd: f64, lo: f64, hi: f64) -> Spread {
    Spread { mean, sd, lo, hi }
}

impl Spread {
    fn draw(self, rng: &mut ChaCha8Rng) -> f64 {
        normal_clamped(rng, self.mean, self.sd, self.lo, self.hi)
    }
}

/// The drawn gait of one leg, in the order drawn.
struct LegSpread {
    stance_ratio: Spread,
    knee_reduction: Spread,
    circumduction_m: Spread,
    roll_swing_deg: Spread,
}

impl LegSpread {
    fn draw_into(&self, leg: &mut LegParams, rng: &mut ChaCha8Rng) {
        leg.stance_ratio = self.stance_ratio.draw(rng);
        leg.knee_reduction = self.knee_reduction.draw(rng);
        leg.circumduction_m = self.circumduction_m.draw(rng);
        leg.roll_swing_deg = self.roll_swing_deg.draw(rng);
    }
}

/// Either leg of a healthy subject.
const HEALTHY_LEG: LegSpread = LegSpread {
    stance_ratio: spread(0.60, 0.008, 0.58, 0.62),
    knee_reduction: spread(0.0, 0.02, -0.04, 0.04),
    circumduction_m: spread(0.01, 0.003, 0.0, 0.02),
    roll_swing_deg: spread(-1.5, 0.5, -3.0, 0.0),
};

/// An LDH population's gait ([`SubjectParams::draw`], [`SubjectParams::draw_slow`]).
struct LdhPopulation {
    stride_time_s: Spread,
    speed_m_per_s: Spread,
    /// Both the stride time's and the stride length's CV (two draws).
    stride_cv: Spread,
    stance_ratio_sd: f64,
    /// Magnitude; its sign puts the affected leg's heel strike late.
    step_timing_asymmetry: Spread,
    /// Magnitude; its sign makes the affected leg's step short.
    step_length_asymmetry: Spread,
    affected: LegSpread,
    unaffected: LegSpread,
}

/// The LDH group of [`SubjectParams::draw`].
const LDH: LdhPopulation = LdhPopulation {
    stride_time_s: spread(1.18, 0.06, 1.02, 1.35),
    speed_m_per_s: spread(0.98, 0.10, 0.75, 1.25),
    stride_cv: spread(0.04, 0.008, 0.025, 0.06),
    stance_ratio_sd: 0.012,
    step_timing_asymmetry: spread(0.02, 0.008, 0.0, 0.04),
    step_length_asymmetry: spread(0.04, 0.015, 0.0, 0.08),
    affected: LegSpread {
        stance_ratio: spread(0.65, 0.01, 0.62, 0.68),
        knee_reduction: spread(0.18, 0.04, 0.08, 0.28),
        circumduction_m: spread(0.035, 0.008, 0.02, 0.055),
        roll_swing_deg: spread(-5.0, 1.0, -8.0, -3.0),
    },
    unaffected: LegSpread {
        stance_ratio: spread(0.615, 0.01, 0.59, 0.64),
        knee_reduction: spread(0.05, 0.03, -0.02, 0.12),
        circumduction_m: spread(0.012, 0.004, 0.0, 0.025),
        roll_swing_deg: spread(-2.0, 0.6, -3.5, -0.5),
    },
};

/// The slow, severely affected LDH subjects of [`SubjectParams::draw_slow`].
const LDH_SLOW: LdhPopulation = LdhPopulation {
    stride_time_s: spread(1.65, 0.18, 1.35, 2.0),
    speed_m_per_s: spread(0.50, 0.12, 0.28, 0.75),
    stride_cv: spread(0.05, 0.01, 0.03, 0.08),
    stance_ratio_sd: 0.015,
    step_timing_asymmetry: spread(0.03, 0.01, 0.0, 0.045),
    step_length_asymmetry: spread(0.06, 0.02, 0.0, 0.12),
    affected: LegSpread {
        stance_ratio: spread(0.65, 0.015, 0.62, 0.69),
        knee_reduction: spread(0.28, 0.08, 0.10, 0.45),
        circumduction_m: spread(0.04, 0.01, 0.02, 0.07),
        roll_swing_deg: spread(-5.0, 1.0, -8.0, -3.0),
    },
    unaffected: LegSpread {
        stance_ratio: spread(0.67, 0.015, 0.63, 0.70),
        knee_reduction: spread(0.10, 0.04, 0.0, 0.20),
        circumduction_m: spread(0.015, 0.005, 0.0, 0.03),
        roll_swing_deg: spread(-2.0, 0.6, -3.5, -0.5),
    },
};

impl SubjectParams {
    /// A typical healthy adult at 1.3 m/s, 100 Hz, 25 s with a turn.
    pub fn healthy(subject_id: impl Into<String>) -> Self {
        SubjectParams {
            subject_id: subject_id.into(),
            group: Group::Healthy,
            affected_side: None,
            fs_hz: 100.0,
            duration_s: 25.0,
            standing_s: 3.0,
            stride_time_s: 1.05,
            stride_length_m: 1.36,
            stride_time_cv: 0.02,
            stride_length_cv: 0.02,
            stance_ratio_sd: 0.008,
            step_timing_asymmetry: 0.0,
            step_length_asymmetry: 0.0,
            heel_strike_foot_angle_deg: 15.0,
            toe_off_foot_angle_deg: 55.0,
            turn: true,
            ramp_s: 0.0,
            slowdown_s: 0.0,
            trend_share: 0.0,
            stair_rise_m: 0.0,
            left: LegParams::default(),
            right: LegParams::default(),
        }
    }

    /// The parameters of one leg.
    pub fn leg(&self, side: Side) -> &LegParams {
        match side {
            Side::Left => &self.left,
            Side::Right => &self.right,
        }
    }

    /// Mutable parameters of one leg.
    pub fn leg_mut(&mut self, side: Side) -> &mut LegParams {
        match side {
            Side::Left => &mut self.left,
            Side::Right => &mut self.right,
        }
    }

    /// Draw a subject of `group` (LDH: affected side drawn too). Population values: healthy
    /// 1.30 ± 0.10 m/s, stride time 1.05 ± 0.05 s, CV 2 %; LDH slower (0.98 ± 0.10 m/s), longer
    /// strides in time (1.18 ± 0.06 s), CV 4 %, affected side stance 0.65, swing knee flexion
    /// −18 %, circumduction 3.5 cm.
    pub fn draw(
        subject_id: impl Into<String>,
        group: Group,
        fs_hz: f64,
        duration_s: f64,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        let mut p = SubjectParams::placed(subject_id, group.clone(), fs_hz, duration_s, rng);
        match group {
            // Any other label walks as the healthy group (the simulator models two groups).
            Group::Healthy | Group::Other(_) => {
                p.stride_time_s = normal_clamped(rng, 1.05, 0.05, 0.92, 1.2);
                let speed = normal_clamped(rng, 1.30, 0.10, 1.05, 1.6);
                p.stride_length_m = speed * p.stride_time_s;
                p.stride_time_cv = normal_clamped(rng, 0.02, 0.004, 0.01, 0.03);
                p.stride_length_cv = normal_clamped(rng, 0.02, 0.004, 0.01, 0.03);
                p.step_timing_asymmetry = normal_clamped(rng, 0.0, 0.005, -0.015, 0.015);
                p.step_length_asymmetry = normal_clamped(rng, 0.0, 0.01, -0.03, 0.03);
                for side in [Side::Left, Side::Right] {
                    HEALTHY_LEG.draw_into(p.leg_mut(side), rng);
                }
            }
            Group::Ldh => p.draw_ldh_gait(&LDH, rng),
        }
        p.tie_hip_to_stride(0.75);
        p
    }

    /// Draw a slow, severely affected LDH subject (`ldh simulate --slow-ldh`): 0.28–0.75 m/s
    /// (0.50 ± 0.12), stride time 1.35–2.0 s (1.65 ± 0.18), CV 5 %, stance 0.65 on the affected
    /// side and 0.67 on the other (stance lengthens as gait slows), swing knee flexion −28 %
    /// (affected) and −10 %, hip excursion scaled to the short strides. Slow gait in LDH
    /// (and in the elderly) is reported at 0.4–0.8 m/s with stance ratios of 0.63–0.70; these
    /// subjects widen family A's stride times beyond the 0.9–1.35 s of [`SubjectParams::draw`].
    pub fn draw_slow(
        subject_id: impl Into<String>,
        fs_hz: f64,
        duration_s: f64,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        let mut p = SubjectParams::placed(subject_id, Group::Ldh, fs_hz, duration_s, rng);
        p.draw_ldh_gait(&LDH_SLOW, rng);
        p.tie_hip_to_stride(0.55);
        p
    }

    /// The healthy defaults with this group, rate and length, and the sensors' placement drawn
    /// (height on the shank, near the same on both legs, and the stance roll): the first draws
    /// of every family A subject.
    fn placed(
        subject_id: impl Into<String>,
        group: Group,
        fs_hz: f64,
        duration_s: f64,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        let mut p = SubjectParams::healthy(subject_id);
        p.group = group;
        p.fs_hz = fs_hz;
        p.duration_s = duration_s;
        let h = normal_clamped(rng, 0.10, 0.015, 0.06, 0.16);
        for side in [Side::Left, Side::Right] {
            let l = p.leg_mut(side);
            l.sensor_height_m =
                (h + normal_clamped(rng, 0.0, 0.005, -0.015, 0.015)).clamp(0.06, 0.16);
            l.roll_stance_deg = normal_clamped(rng, 2.0, 1.0, -1.0, 5.0);
        }
        p
    }

    /// Draw an LDH subject's gait from `population`: the affected side, then stride time,
    /// speed and variability, the asymmetries (the affected leg's step comes late and short),
    /// and each leg (affected or not).
    fn draw_ldh_gait(&mut self, population: &LdhPopulation, rng: &mut ChaCha8Rng) {
        use rand::Rng;
        let affected = if rng.gen_bool(0.5) {
            Side::Left
        } else {
            Side::Right
        };
        self.affected_side = Some(affected);
        self.stride_time_s = population.stride_time_s.draw(rng);
        let speed = population.speed_m_per_s.draw(rng);
        self.stride_length_m = speed * self.stride_time_s;
        self.stride_time_cv = population.stride_cv.draw(rng);
        self.stride_length_cv = population.stride_cv.draw(rng);
        self.stance_ratio_sd = population.stance_ratio_sd;
        // The affected leg's step (its heel strike after the other's) comes late and short.
        let sign = if affected == Side::Right { 1.0 } else { -1.0 };
        self.step_timing_asymmetry = sign * population.step_timing_asymmetry.draw(rng);
        self.step_length_asymmetry = -sign * population.step_length_asymmetry.draw(rng);
        for side in [Side::Left, Side::Right] {
            let leg = if side == affected {
                &population.affected
            } else {
                &population.unaffected
            };
            leg.draw_into(self.leg_mut(side), rng);
        }
    }

    /// Scale both legs' hip excursion with the stride length (1 at 1.36 m), within
    /// [`min`, 1.15].
    fn tie_hip_to_stride(&mut self, min: f64) {
        let hip_scale = (self.stride_length_m / 1.36).clamp(min, 1.15);
        self.left.hip_scale = hip_scale;
        self.right.hip_scale = hip_scale;
    }

    /// This (LDH) subject's gait moved towards `healthy`: every gait parameter becomes
    /// healthy + severity · (self − healthy). Group, affected side and sensor placement stay.
    pub fn blend_towards(&self, healthy: &SubjectParams, severity: f64) -> SubjectParams {
        let b = |l: f64, h: f64| h + severity * (l - h);
        let mut p = self.clone();
        p.stride_time_s = b(self.stride_time_s, healthy.stride_time_s);
        p.stride_length_m = b(self.stride_length_m, healthy.stride_length_m);
        p.stride_time_cv = b(self.stride_time_cv, healthy.stride_time_cv);
        p.stride_length_cv = b(self.stride_length_cv, healthy.stride_length_cv);
        p.stance_ratio_sd = b(self.stance_ratio_sd, healthy.stance_ratio_sd);
        p.step_timing_asymmetry = b(self.step_timing_asymmetry, healthy.step_timing_asymmetry);
        p.step_length_asymmetry = b(self.step_length_asymmetry, healthy.step_length_asymmetry);
        for side in [Side::Left, Side::Right] {
            let (l, h) = (self.leg(side).clone(), healthy.leg(side).clone());
            let t = p.leg_mut(side);
            t.stance_ratio = b(l.stance_ratio, h.stance_ratio);
            t.knee_reduction = b(l.knee_reduction, h.knee_reduction);
            t.hip_scale = b(l.hip_scale, h.hip_scale);
            t.circumduction_m = b(l.circumduction_m, h.circumduction_m);
            t.roll_swing_deg = b(l.roll_swing_deg, h.roll_swing_deg);
        }
        p
    }

    /// Check the parameters are physically sensible.
    pub fn validate(&self) -> Result<()> {
        let range = |name: &'static str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(LdhError::param(
                    name,
                    v,
                    format!("must lie in [{lo}, {hi}]"),
                ))
            }
        };
        range("fs_hz", self.fs_hz, 20.0, 2000.0)?;
        range("duration_s", self.duration_s, 5.0, 24.0 * 3600.0)?;
        check_samples(self.duration_s, self.fs_hz)?;
        range("standing_s", self.standing_s, 0.0, 60.0)?;
        range(
            "ramp_s",
            self.ramp_s,
            0.0,
            (0.5 * (self.duration_s - 2.0 * self.standing_s)).max(0.0),
        )?;
        range(
            "slowdown_s",
            self.slowdown_s,
            0.0,
            (0.5 * (self.duration_s - 2.0 * self.standing_s)).max(0.0),
        )?;
        range("trend_share", self.trend_share, -0.5, 0.5)?;
        range("stair_rise_m", self.stair_rise_m, -0.25, 0.25)?;
        range("stride_time_s", self.stride_time_s, 0.7, 2.0)?;
        range("stride_length_m", self.stride_length_m, 0.3, 2.2)?;
        range("stride_time_cv", self.stride_time_cv, 0.0, 0.1)?;
        range("stride_length_cv", self.stride_length_cv, 0.0, 0.1)?;
        range("stance_ratio_sd", self.stance_ratio_sd, 0.0, 0.03)?;
        range(
            "step_timing_asymmetry",
            self.step_timing_asymmetry,
            -0.045,
            0.045,
        )?;
        range(
            "step_length_asymmetry",
            self.step_length_asymmetry,
            -0.3,
            0.3,
        )?;
        range(
            "heel_strike_foot_angle_deg",
            self.heel_strike_foot_angle_deg,
            0.0,
            35.0,
        )?;
        range(
            "toe_off_foot_angle_deg",
            self.toe_off_foot_angle_deg,
            10.0,
            80.0,
        )?;
        for l in [&self.left, &self.right] {
            range("stance_ratio", l.stance_ratio, 0.55, 0.70)?;
            range("knee_reduction", l.knee_reduction, -0.3, 0.6)?;
            range("hip_scale", l.hip_scale, 0.5, 1.5)?;
            range("circumduction_m", l.circumduction_m, 0.0, 0.15)?;
            range("roll_swing_deg", l.roll_swing_deg, -20.0, 20.0)?;
            range("roll_stance_deg", l.roll_stance_deg, -15.0, 15.0)?;
            range("sensor_height_m", l.sensor_height_m, 0.0, 0.4)?;
            range("sensor_lateral_m", l.sensor_lateral_m, 0.0, 0.1)?;
            range("swing_clearance_m", l.swing_clearance_m, 0.0, 0.2)?;
        }
        if self.group == Group::Ldh && self.affected_side.is_none() {
            return Err(LdhError::param(
                "affected_side",
                "none",
                "an LDH subject needs an affected side",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn legs(p: &LdhPopulation) -> [&LegSpread; 2] {
        [&p.affected, &p.unaffected]
    }

    /// Every population spread is a distribution that can be drawn: SD > 0 and the mean within
    /// its clamp (a typo that swaps two numbers fails here).
    #[test]
    fn every_spread_has_its_mean_within_its_range() {
        let leg = |l: &LegSpread| {
            [
                l.stance_ratio,
                l.knee_reduction,
                l.circumduction_m,
                l.roll_swing_deg,
            ]
        };
        let mut all = leg(&HEALTHY_LEG).to_vec();
        for p in [&LDH, &LDH_SLOW] {
            all.extend([
                p.stride_time_s,
                p.speed_m_per_s,
                p.stride_cv,
                p.step_timing_asymmetry,
                p.step_length_asymmetry,
            ]);
            for l in legs(p) {
                all.extend(leg(l));
            }
        }
        for s in all {
            assert!(s.sd > 0.0 && s.lo <= s.mean && s.mean <= s.hi, "{s:?}");
        }
    }

    /// A drawn LDH subject lies within its population's ranges, the affected leg within the
    /// affected spreads.
    #[test]
    fn slow_ldh_subjects_are_drawn_within_their_ranges() {
        use rand::SeedableRng;
        let within = |v: f64, s: Spread| s.lo - 1e-9 <= v && v <= s.hi + 1e-9;
        for seed in 0..20 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let p = SubjectParams::draw_slow("s", 100.0, 30.0, &mut rng);
            assert_eq!(p.group, Group::Ldh);
            assert!(within(p.stride_time_s, LDH_SLOW.stride_time_s));
            let speed = p.stride_length_m / p.stride_time_s;
            assert!(within(speed, LDH_SLOW.speed_m_per_s), "{speed}");
            let affected = p.leg(p.affected_side.unwrap());
            assert!(within(
                affected.knee_reduction,
                LDH_SLOW.affected.knee_reduction
            ));
            assert!(p.left.hip_scale >= 0.55 && p.left.hip_scale == p.right.hip_scale);
        }
    }
}
