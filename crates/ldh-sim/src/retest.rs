//! Retest cohorts (`ldh simulate --trials N`): each person walks N times. The person's own
//! gait — every parameter [`CohortParams::draw`] draws, from the person's stream, exactly as
//! for a single trial — is fixed; each trial then varies the person's mean stride time and
//! mean stride length from day to day, T·(1 + f·z_T) and L·(1 + f·z_L) with z_T, z_L
//! independent standard normals cut at ±4 SD and f = `day_to_day_sd_fraction` (the hip
//! excursion follows the stride length as [`SubjectParams::draw`] ties them), and is simulated
//! with a fresh random stream of its own: stride-to-stride variability, sensor noise, bias and
//! mounting are new for every trial. The within-person variance of the trial means is thus
//! known: f²·T² for stride time and f²·L² for stride length, plus what the stride-to-stride
//! variability adds to a trial's mean. This is the test bed of the test–retest statistics
//! (`docs/agreement.md`; Weir 2005): their variance components must recover these.
//!
//! One trial (N = 1) is the plain cohort, byte for byte: [`CohortParams::simulate`].

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::model::normal_clamped;
use super::{simulate_subject, CohortParams, SimSubject, SubjectParams};
use ldh_core::error::{LdhError, Result};

/// The most trials per simulated person: 100.
pub const MAX_TRIALS: usize = 100;

/// The largest day-to-day SD fraction: 0.1 (10 % of a person's stride time and length).
pub const MAX_DAY_TO_DAY_SD_FRACTION: f64 = 0.1;

/// The day-to-day SD fraction `ldh simulate --trials N` uses when none is given: 0.03 (a
/// between-day CV of about 3 % of stride time and stride length, the order reported for
/// healthy adults' repeated walks on instrumented walkways).
pub const DEFAULT_DAY_TO_DAY_SD_FRACTION: f64 = 0.03;

/// The day-to-day SD fraction of a cohort of `trials` trials per person when `given` is
/// not given: [`DEFAULT_DAY_TO_DAY_SD_FRACTION`] with two or more trials, else 0 (`ldh
/// simulate` and `ldh.simulate_cohort` share this rule).
pub fn day_to_day_sd_fraction_or_default(trials: usize, given: Option<f64>) -> f64 {
    given.unwrap_or(if trials > 1 {
        DEFAULT_DAY_TO_DAY_SD_FRACTION
    } else {
        0.0
    })
}

/// The standard normal draws of the day-to-day variation are cut at this many SDs (the SD of
/// the cut normal is 0.99943 of the uncut one's; no stride time or length leaves its range).
const CUT_SD: f64 = 4.0;

/// Trial `t` (0-based) of `n` as the manifest's `trial_id` names it: `T1`…`T9`, zero-padded
/// to the width of `n` (`T01`…`T12`).
pub fn trial_id(t: usize, n: usize) -> String {
    let width = n.to_string().len();
    format!("T{:0width$}", t + 1)
}

impl SubjectParams {
    /// This person's parameters on one day: mean stride time and mean stride length each
    /// multiplied by (1 + `sd_fraction`·z), z a standard normal from `rng` cut at ±4 (time
    /// first, then length), kept in the simulator's ranges; the hip excursion scales with the
    /// stride length.
    pub fn on_another_day(&self, sd_fraction: f64, rng: &mut ChaCha8Rng) -> SubjectParams {
        let z_time = normal_clamped(rng, 0.0, 1.0, -CUT_SD, CUT_SD);
        let z_length = normal_clamped(rng, 0.0, 1.0, -CUT_SD, CUT_SD);
        let mut p = self.clone();
        p.stride_time_s = (self.stride_time_s * (1.0 + sd_fraction * z_time)).clamp(0.7, 2.0);
        p.stride_length_m = (self.stride_length_m * (1.0 + sd_fraction * z_length)).clamp(0.3, 2.2);
        let ratio = p.stride_length_m / self.stride_length_m;
        p.left.hip_scale = (self.left.hip_scale * ratio).clamp(0.5, 1.5);
        p.right.hip_scale = (self.right.hip_scale * ratio).clamp(0.5, 1.5);
        p
    }
}

impl CohortParams {
    /// The random stream of trial `t` of subject `i` in a retest cohort: independent of every
    /// other trial, subject and of the single-trial streams (streams from 2⁴¹ on).
    pub fn trial_rng(&self, i: usize, t: usize) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(((t as u64 + 2) << 40) + i as u64 + 1);
        rng
    }

    /// Trial `t` (0-based) of subject `i`: with one trial the plain [`CohortParams::simulate`];
    /// else the person's parameters ([`CohortParams::draw`]) on another day
    /// ([`SubjectParams::on_another_day`]), simulated from the trial's own stream.
    pub fn simulate_trial(&self, i: usize, t: usize) -> Result<SimSubject> {
        if self.trials <= 1 {
            return self.simulate(i);
        }
        let (person, _) = self.draw(i);
        let mut rng = self.trial_rng(i, t);
        let p = person.on_another_day(self.day_to_day_sd_fraction, &mut rng);
        simulate_subject(&p, &self.sensor, &mut rng)
    }

    /// `trials` in 1..=[`MAX_TRIALS`], `trials × subjects` within the cohort's limit,
    /// `day_to_day_sd_fraction` in [0, [`MAX_DAY_TO_DAY_SD_FRACTION`]] and 0 with one trial.
    pub(super) fn validate_trials(&self) -> Result<()> {
        if !(1..=MAX_TRIALS).contains(&self.trials) {
            return Err(LdhError::param(
                "trials",
                self.trials,
                format!("must lie in [1, {MAX_TRIALS}]"),
            ));
        }
        if self.len().saturating_mul(self.trials) as u64 > super::MAX_SUBJECTS {
            return Err(LdhError::param(
                "trials",
                self.trials,
                format!(
                    "a simulated cohort holds at most {} recordings (subjects × trials)",
                    super::MAX_SUBJECTS
                ),
            ));
        }
        let f = self.day_to_day_sd_fraction;
        if !(0.0..=MAX_DAY_TO_DAY_SD_FRACTION).contains(&f) {
            return Err(LdhError::param(
                "day_to_day_sd_fraction",
                f,
                format!("must lie in [0, {MAX_DAY_TO_DAY_SD_FRACTION}]"),
            ));
        }
        if f > 0.0 && self.trials == 1 {
            return Err(LdhError::param(
                "day_to_day_sd_fraction",
                f,
                "varies a person's trials: it needs trials ≥ 2",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trial_ids_are_padded_to_the_count() {
        assert_eq!(trial_id(0, 3), "T1");
        assert_eq!(trial_id(2, 12), "T03");
        assert_eq!(trial_id(99, 100), "T100");
        assert_eq!(day_to_day_sd_fraction_or_default(1, None), 0.0);
        assert_eq!(day_to_day_sd_fraction_or_default(3, None), 0.03);
        assert_eq!(day_to_day_sd_fraction_or_default(3, Some(0.01)), 0.01);
    }

    #[test]
    fn each_trial_keeps_the_person_and_varies_time_and_length_only() {
        let c = CohortParams {
            healthy: 1,
            ldh: 1,
            trials: 3,
            day_to_day_sd_fraction: 0.05,
            ..CohortParams::default()
        };
        c.validate().unwrap();
        for i in 0..2 {
            let (person, _) = c.draw(i);
            let days: Vec<SubjectParams> = (0..3)
                .map(|t| person.on_another_day(0.05, &mut c.trial_rng(i, t)))
                .collect();
            for d in &days {
                let mut same = d.clone();
                same.stride_time_s = person.stride_time_s;
                same.stride_length_m = person.stride_length_m;
                same.left.hip_scale = person.left.hip_scale;
                same.right.hip_scale = person.right.hip_scale;
                assert_eq!(same, person, "only time, length and hip excursion change");
                let rel = d.stride_time_s / person.stride_time_s - 1.0;
                assert!(rel.abs() <= 0.05 * 4.0 + 1e-12 && rel != 0.0, "{rel}");
                assert!(
                    (d.left.hip_scale / person.left.hip_scale
                        - d.stride_length_m / person.stride_length_m)
                        .abs()
                        < 1e-12
                );
            }
            assert_ne!(
                days[0].stride_time_s, days[1].stride_time_s,
                "fresh stream per trial"
            );
        }
        // The streams differ from every single-trial stream and between trials.
        use rand::RngCore;
        let firsts: Vec<u64> = [
            c.rng(0),
            c.rng(1),
            c.trial_rng(0, 0),
            c.trial_rng(0, 1),
            c.trial_rng(1, 0),
        ]
        .into_iter()
        .map(|mut r| r.next_u64())
        .collect();
        let mut unique = firsts.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), firsts.len());
    }

    #[test]
    fn the_draws_have_the_declared_sd() {
        // 4000 days: the sample SD of z has a standard error of 1/√(2·4000) = 1.1 %; 4 SE.
        let c = CohortParams::default();
        let p = SubjectParams::healthy("x");
        let zs: Vec<f64> = (0..4000)
            .map(|t| {
                p.on_another_day(0.03, &mut c.trial_rng(0, t)).stride_time_s / p.stride_time_s - 1.0
            })
            .collect();
        let sd = ldh_core::stats::std_dev(&zs).unwrap() / 0.03;
        assert!((sd - 1.0).abs() < 0.045, "{sd}");
    }

    #[test]
    fn bad_trial_parameters_are_refused() {
        let ok = CohortParams {
            trials: 2,
            day_to_day_sd_fraction: 0.03,
            ..CohortParams::default()
        };
        ok.validate().unwrap();
        for (trials, f, msg) in [
            (0, 0.0, "trials = 0: must lie in [1, 100]"),
            (101, 0.0, "trials = 101"),
            (2, 0.2, "day_to_day_sd_fraction = 0.2: must lie in [0, 0.1]"),
            (2, f64::NAN, "day_to_day_sd_fraction = NaN"),
            (1, 0.03, "it needs trials ≥ 2"),
        ] {
            let c = CohortParams {
                trials,
                day_to_day_sd_fraction: f,
                ..CohortParams::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains(msg), "{e}");
        }
        let big = CohortParams {
            healthy: 50_000,
            ldh: 0,
            trials: 3,
            ..CohortParams::default()
        };
        assert!(big
            .validate()
            .unwrap_err()
            .to_string()
            .contains("subjects × trials"));
    }
}
