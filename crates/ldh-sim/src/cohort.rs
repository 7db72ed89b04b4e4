//! Family A cohort parameters ([`CohortParams`]): how many subjects, how long, which seed, and
//! the per-subject random stream that makes a cohort byte-identical whatever the thread count.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::{check_size, simulate_subject, Group, SensorModel, SimSubject, SubjectParams};
use ldh_core::error::{LdhError, Result};

/// Parameters of a simulated cohort (`ldh simulate`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CohortParams {
    /// Number of healthy subjects. Default 2.
    pub healthy: usize,
    /// Number of LDH subjects. Default 2.
    pub ldh: usize,
    /// Number of slow, severely affected LDH subjects ([`SubjectParams::draw_slow`]: 0.28–0.75
    /// m/s, strides of 1.35–2.0 s), after the others (ids S01…). Default 0 (then not written
    /// to cohort.json, so earlier cohorts keep their bytes).
    #[serde(skip_serializing_if = "is_zero")]
    pub slow_ldh: usize,
    /// Recording length per subject, s. Default 25.
    pub duration_s: f64,
    /// Sampling rate, Hz. Default 100.
    pub fs_hz: f64,
    /// Seed. Default 1.
    pub seed: u64,
    /// Walk there and back with a turn. Default true.
    pub turn: bool,
    /// Lowest LDH severity: each LDH subject's severity is drawn uniformly in [this, 1] and
    /// scales every LDH effect from a healthy gait (0) to the full LDH gait (1). Default 1 (all
    /// subjects fully affected; nothing extra is drawn, so seeds keep their output).
    pub ldh_severity_min: f64,
    /// Treadmill belt start-up per subject, s ([`SubjectParams::ramp_s`]; `ldh simulate
    /// --ramp-s`). Default 0 (then not written to cohort.json, so earlier cohorts keep their
    /// bytes).
    #[serde(skip_serializing_if = "super::params::is_zero_s")]
    pub ramp_s: f64,
    /// Trials per subject (`ldh simulate --trials`): a retest cohort, each person walking this
    /// many times with their own gait and a day-to-day variation between trials
    /// ([`CohortParams::simulate_trial`]). Default 1 (then not written to cohort.json, so
    /// earlier cohorts keep their bytes).
    #[serde(skip_serializing_if = "is_one")]
    pub trials: usize,
    /// Day-to-day SD between a person's trials of their mean stride time and of their mean
    /// stride length, each as a fraction of the person's own value (independent draws; stride
    /// speed follows as length / time). Only with `trials` ≥ 2; default 0 (then not written).
    #[serde(skip_serializing_if = "super::params::is_zero_s")]
    pub day_to_day_sd_fraction: f64,
    /// Sensor model.
    pub sensor: SensorModel,
}

fn is_one(n: &usize) -> bool {
    *n == 1
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Default for CohortParams {
    fn default() -> Self {
        CohortParams {
            healthy: 2,
            ldh: 2,
            slow_ldh: 0,
            duration_s: 25.0,
            fs_hz: 100.0,
            seed: 1,
            turn: true,
            ldh_severity_min: 1.0,
            ramp_s: 0.0,
            trials: 1,
            day_to_day_sd_fraction: 0.0,
            sensor: SensorModel::default(),
        }
    }
}

impl CohortParams {
    /// Total number of subjects (saturating: [`CohortParams::validate`] refuses a sum that
    /// overflows).
    pub fn len(&self) -> usize {
        self.healthy
            .saturating_add(self.ldh)
            .saturating_add(self.slow_ldh)
    }
    /// No subjects.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Identifier of subject `i` (healthy first: H01…, then L01…, then the slow LDH S01…).
    pub fn subject_id(&self, i: usize) -> String {
        let width = (self.len().max(1) as f64).log10().floor() as usize + 1;
        let width = width.max(2);
        if i < self.healthy {
            format!("H{:0width$}", i + 1)
        } else if i < self.healthy + self.ldh {
            format!("L{:0width$}", i - self.healthy + 1)
        } else {
            format!("S{:0width$}", i - self.healthy - self.ldh + 1)
        }
    }
    /// Check the cohort parameters.
    pub fn validate(&self) -> Result<()> {
        if self.is_empty() {
            return Err(LdhError::param(
                "healthy + ldh",
                0,
                "at least one subject is needed",
            ));
        }
        check_size(
            self.healthy,
            self.ldh.saturating_add(self.slow_ldh),
            self.duration_s,
            self.fs_hz,
        )?;
        if !(0.0..=1.0).contains(&self.ldh_severity_min) {
            return Err(LdhError::param(
                "ldh_severity_min",
                self.ldh_severity_min,
                "must lie in [0, 1]",
            ));
        }
        self.sensor.validate()?;
        self.validate_trials()?;
        if self.ramp_s != 0.0 && self.turn {
            return Err(LdhError::param(
                "ramp_s",
                self.ramp_s,
                "a belt start-up is a treadmill walk, which has no turn: simulate it without the turn (--no-turn)",
            ));
        }
        // 3 s of standing at each end and four strides of the slowest drawn gait (1.35 s each,
        // plus the ramps in and out).
        if !(self.duration_s >= 14.0) {
            return Err(LdhError::param(
                "duration_s",
                self.duration_s,
                "a simulated cohort needs at least 14 s per subject (3 s standing at each end and four strides of slow gait)",
            ));
        }
        // Slow subjects: four strides of up to 2.0 s.
        if self.slow_ldh > 0 && !(self.duration_s >= 20.0) {
            return Err(LdhError::param(
                "duration_s",
                self.duration_s,
                "a cohort with slow LDH subjects needs at least 20 s per subject (3 s standing at each end and four strides of up to 2 s)",
            ));
        }
        SubjectParams {
            fs_hz: self.fs_hz,
            duration_s: self.duration_s,
            ramp_s: self.ramp_s,
            ..SubjectParams::healthy("check")
        }
        .validate()
    }
    /// The random stream of subject `i`: independent of the other subjects and of threads.
    pub fn rng(&self, i: usize) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(i as u64 + 1);
        rng
    }
    /// Draw and simulate subject `i` (its only trial).
    pub fn simulate(&self, i: usize) -> Result<SimSubject> {
        let (p, mut rng) = self.draw(i);
        simulate_subject(&p, &self.sensor, &mut rng)
    }
    /// Draw subject `i`'s parameters (the person's own gait) from its stream, and the stream
    /// in the state the single-trial simulation continues from.
    pub fn draw(&self, i: usize) -> (SubjectParams, ChaCha8Rng) {
        let others = self.healthy.saturating_add(self.ldh);
        if i >= others {
            // Slow subject j draws from its own stream family, so S01… are the same subjects
            // whatever the number of healthy and LDH subjects beside them.
            let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
            rng.set_stream((1u64 << 32) + (i - others) as u64 + 1);
            let mut p =
                SubjectParams::draw_slow(self.subject_id(i), self.fs_hz, self.duration_s, &mut rng);
            p.turn = self.turn;
            p.ramp_s = self.ramp_s;
            return (p, rng);
        }
        let mut rng = self.rng(i);
        let group = if i < self.healthy {
            Group::Healthy
        } else {
            Group::Ldh
        };
        let mut p = SubjectParams::draw(
            self.subject_id(i),
            group.clone(),
            self.fs_hz,
            self.duration_s,
            &mut rng,
        );
        if group == Group::Ldh && self.ldh_severity_min < 1.0 {
            use rand::Rng;
            let severity = rng.gen_range(self.ldh_severity_min..=1.0);
            let h = SubjectParams::draw(
                self.subject_id(i),
                Group::Healthy,
                self.fs_hz,
                self.duration_s,
                &mut rng,
            );
            p = p.blend_towards(&h, severity);
        }
        p.turn = self.turn;
        p.ramp_s = self.ramp_s;
        (p, rng)
    }
}
