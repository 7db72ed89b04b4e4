//! Attitude health (docs/quality.md): the shank's pitch at mid-stance is nearly the same from
//! stride to stride (the foot is flat and the shank near vertical), and the shank angles stay
//! within anatomical bounds. A leg that fails loses its angle parameters and its stride length
//! (which rotates the acceleration with the same attitude).
//!
//! Bounds: in walking the shank inclines about 20-30° backward before heel strike and 40-55°
//! forward at toe off (Perry, Gait Analysis, 1992; Winter, Biomechanics and Motor Control of
//! Human Movement, 2009); its frontal excursion in swing is 5-15°. No walking shank passes
//! ±90° in the sagittal plane or 45° of frontal excursion within a stride.

use super::finite_median;
use super::warning::{codes, params, Severity, Warning};
use crate::align::Aligned;
use crate::attitude::Attitude;
use crate::gait::Stride;
use crate::gait::{StrideCode, StrideFinding};

/// Largest sagittal shank angle of walking, either way, deg (WQK and PBI bounds).
pub const MAX_PITCH_DEG: f64 = 90.0;

/// Smallest WQK and PBI, deg: the shank passes the vertical in every stride, forward at toe off
/// and backward before heel strike; −10° leaves room for a mounting offset.
pub const MIN_PITCH_EXCURSION_DEG: f64 = -10.0;

/// Largest frontal (roll) excursion in swing, deg (BDK bound).
pub const MAX_BDK_DEG: f64 = 45.0;

/// Share of valid strides with an angle out of bounds above which the leg's angles are withheld.
pub const OUT_OF_BOUNDS_SHARE: f64 = 0.10;

/// Largest spread (10th to 90th percentile) of the mid-stance pitch over valid strides, deg:
/// the shank is near vertical at mid-stance in every stride (stride-to-stride SD of sagittal
/// segment angles in steady walking is 1-3°; Winter, Biomechanics and Motor Control of Human
/// Movement, 2009), so a 10-90 % spread of 20° (≈ 8 SD) means the attitude drifts.
pub const STANCE_PITCH_SPREAD_DEG: f64 = 20.0;

/// Largest |median mid-stance pitch|, deg: the shank at foot flat leans 0-15° forward.
pub const STANCE_PITCH_MAX_DEG: f64 = 30.0;

/// Pitch at mid-stance of the valid strides: the mean over the middle fifth of HS–TO (the
/// shank passes the vertical there, at a phase that does not depend on where |ω| happens to be
/// least: the shank rotates over the ankle through all of stance).
fn stance_pitch(al: &Aligned, att: &Attitude, st: &[Stride]) -> Vec<f64> {
    let n = att.pitch_deg.len();
    let fs = al.fs_hz;
    let idx = |t: f64| ((t * fs).round().max(0.0) as usize).min(n.saturating_sub(1));
    st.iter()
        .filter(|s| s.valid && s.to_time_s.is_finite() && s.to_time_s > s.hs_time_s)
        .filter_map(|s| {
            let d = s.to_time_s - s.hs_time_s;
            let (a, b) = (idx(s.hs_time_s + 0.4 * d), idx(s.hs_time_s + 0.6 * d));
            let w = &att.pitch_deg[a..=b.max(a)];
            let m = w.iter().sum::<f64>() / w.len() as f64;
            m.is_finite().then_some(m)
        })
        .collect()
}

fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    s.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    if s.is_empty() {
        return f64::NAN;
    }
    s[((s.len() - 1) as f64 * q).round() as usize]
}

/// The attitude checks of one leg; out-of-bounds strides lose their angles (with a reason).
pub fn attitude_checks(al: &Aligned, att: &Attitude, st: &mut [Stride]) -> Vec<Warning> {
    let mut w = Vec::new();
    let mut affects: Vec<crate::domain::Parameter> = params::ANGLES.to_vec();
    affects.extend(params::LENGTH);
    let sp = stance_pitch(al, att, st);
    if sp.len() >= 3 {
        let spread = quantile(&sp, 0.9) - quantile(&sp, 0.1);
        let med = finite_median(sp.clone()).unwrap_or(f64::NAN);
        if spread > STANCE_PITCH_SPREAD_DEG || med.abs() > STANCE_PITCH_MAX_DEG {
            w.push(
                Warning::new(
                    codes::ATTITUDE_DIVERGENCE,
                    Severity::Warning,
                    format!(
                        "the shank attitude drifts: its pitch at mid-stance, near vertical in every stride, spreads over {spread:.0} deg (10th-90th percentile over {} strides, median {med:.0} deg; at most {STANCE_PITCH_SPREAD_DEG:.0} and ±{STANCE_PITCH_MAX_DEG:.0} deg expected), so the shank angles and stride length are not measured",
                        sp.len()
                    ),
                )
                .withholding(&affects),
            );
        }
    }
    let out = |s: &Stride| {
        let pitch_ok =
            |x: f64| x.is_finite() && (MIN_PITCH_EXCURSION_DEG..=MAX_PITCH_DEG).contains(&x);
        !pitch_ok(s.wqk_deg)
            || !pitch_ok(s.pbi_deg)
            || (s.bdk_deg.is_finite() && !(0.0..=MAX_BDK_DEG).contains(&s.bdk_deg))
    };
    let valid = st.iter().filter(|s| s.valid).count();
    let bad: Vec<usize> = (0..st.len())
        .filter(|&i| st[i].valid && out(&st[i]))
        .collect();
    if valid > 0 && bad.len() as f64 > OUT_OF_BOUNDS_SHARE * valid as f64 {
        let ext = |f: fn(&Stride) -> f64| {
            bad.iter()
                .map(|&i| f(&st[i]))
                .filter(|x| x.is_finite())
                .fold(f64::NAN, |m, x| {
                    if x.abs() > m.abs() || m.is_nan() {
                        x
                    } else {
                        m
                    }
                })
        };
        w.push(
            Warning::new(
                codes::IMPLAUSIBLE_ANGLE,
                Severity::Warning,
                format!(
                    "shank angles outside anatomical bounds in {} of {valid} valid strides (most extreme: WQK {:.0}, PBI {:.0}, BDK {:.0} deg; walking stays within {MIN_PITCH_EXCURSION_DEG:.0} to {MAX_PITCH_DEG:.0} deg forward and backward, and {MAX_BDK_DEG:.0} deg of frontal excursion): the attitude is wrong, so the shank angles and stride length are not measured",
                    bad.len(),
                    ext(|s| s.wqk_deg),
                    ext(|s| s.pbi_deg),
                    ext(|s| s.bdk_deg)
                ),
            )
            .withholding(&affects),
        );
    } else {
        for &i in &bad {
            let s = &mut st[i];
            s.wqk_deg = f64::NAN;
            s.pbi_deg = f64::NAN;
            s.bdk_deg = f64::NAN;
            s.push_once(StrideFinding::new(
                StrideCode::AnglesOutOfBounds,
                "angles withheld: outside anatomical bounds",
            ));
            s.valid = false;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    //! The attitude health checks on synthetic legs: 1 s strides at 100 Hz, stance over the
    //! first 60 %, the mid-stance pitch set per stride (the divergence fixture: an attitude
    //! that drifts by a few degrees per stride, as a gyro-only integration with an unremoved
    //! bias does).
    use super::*;
    use crate::align::Alignment;
    use crate::attitude::AttitudeModel;
    use crate::domain::WarningCode;

    const FS: f64 = 100.0;

    fn aligned() -> Aligned {
        Aligned {
            fs_hz: FS,
            acc_g: Default::default(),
            gyro_dps: Default::default(),
            acc_clipped: vec![],
            acc_motion_g: None,
            alignment: Alignment::identity(),
        }
    }

    /// A leg whose mid-stance pitch in stride k is `stance_pitch(k)` and whose stride angles are
    /// `angles(k)` = (WQK, PBI, BDK).
    fn leg(
        n: usize,
        stance_pitch: impl Fn(usize) -> f64,
        angles: impl Fn(usize) -> (f64, f64, f64),
    ) -> (Attitude, Vec<Stride>) {
        let len = (n + 1) * FS as usize;
        let pitch: Vec<f64> = (0..len)
            .map(|i| stance_pitch((i / FS as usize).min(n - 1)))
            .collect();
        let att = Attitude {
            model: AttitudeModel::Fusion,
            fs_hz: FS,
            roll_deg: vec![0.0; len],
            pitch_deg: pitch,
            yaw_deg: vec![0.0; len],
            final_weights: vec![],
            final_tilt_noise_deg: vec![],
            gyro_bias_dps: [0.0; 2],
            gravity_windows: 0,
        };
        let strides = (0..n)
            .map(|k| {
                let (wqk, pbi, bdk) = angles(k);
                Stride {
                    stride_index: k,
                    hs_time_s: k as f64,
                    to_time_s: k as f64 + 0.6,
                    next_hs_time_s: k as f64 + 1.0,
                    stride_time_s: 1.0,
                    stance_ratio: 0.6,
                    double_support_ratio: f64::NAN,
                    stride_length_m: 1.3,
                    speed_mps: 1.3,
                    wqk_deg: wqk,
                    pbi_deg: pbi,
                    bdk_deg: bdk,
                    heading_change_deg: 0.0,
                    bout: 0,
                    valid: true,
                    reason: String::new(),
                    findings: Vec::new(),
                    vertical_m: f64::NAN,
                }
            })
            .collect();
        (att, strides)
    }

    fn normal(_: usize) -> (f64, f64, f64) {
        (30.0, 45.0, 8.0)
    }

    fn codes_of(w: &[Warning]) -> Vec<WarningCode> {
        w.iter().map(|w| w.code).collect()
    }

    #[test]
    fn a_steady_stance_pitch_passes() {
        // ±1.5° stride to stride around 5° forward: what a walking shank does
        let (att, mut st) = leg(12, |k| 5.0 + 1.5 * ((k % 3) as f64 - 1.0), normal);
        let w = attitude_checks(&aligned(), &att, &mut st);
        assert!(w.is_empty(), "{w:?}");
        assert!(st.iter().all(|s| s.valid && s.wqk_deg == 30.0));
    }

    #[test]
    fn a_drifting_attitude_withholds_angles_and_stride_length() {
        // 2.5° more per stride: 12 strides spread over 25° at mid-stance
        let (att, mut st) = leg(12, |k| 2.5 * k as f64, normal);
        let w = attitude_checks(&aligned(), &att, &mut st);
        assert_eq!(codes_of(&w), [codes::ATTITUDE_DIVERGENCE]);
        assert_eq!(w[0].severity, Severity::Warning);
        for p in params::ANGLES.iter().chain(&params::LENGTH) {
            assert!(w[0].affects.iter().any(|a| a == p), "{p} not withheld");
        }
        assert!(w[0].message.contains("spreads over"), "{}", w[0].message);
        // a constant lean far from vertical is the same failure
        let (att, mut st) = leg(12, |_| 40.0, normal);
        let w = attitude_checks(&aligned(), &att, &mut st);
        assert_eq!(codes_of(&w), [codes::ATTITUDE_DIVERGENCE]);
    }

    #[test]
    fn angles_out_of_bounds_in_many_strides_withhold_the_leg() {
        let (att, mut st) = leg(
            10,
            |_| 5.0,
            |k| {
                if k < 3 {
                    (250.0, 45.0, 8.0)
                } else {
                    normal(k)
                }
            },
        );
        let w = attitude_checks(&aligned(), &att, &mut st);
        assert_eq!(codes_of(&w), [codes::IMPLAUSIBLE_ANGLE]);
        assert!(w[0].message.contains("WQK 250"), "{}", w[0].message);
        assert!(w[0].withholds(crate::domain::Parameter::Wqk));
    }

    #[test]
    fn one_stride_out_of_bounds_loses_only_its_angles() {
        let (att, mut st) = leg(
            20,
            |_| 5.0,
            |k| {
                if k == 7 {
                    (30.0, 45.0, 60.0)
                } else {
                    normal(k)
                }
            },
        );
        let w = attitude_checks(&aligned(), &att, &mut st);
        assert!(w.is_empty(), "{w:?}");
        assert!(!st[7].valid && st[7].bdk_deg.is_nan() && st[7].wqk_deg.is_nan());
        assert!(
            st[7].has(&crate::gait::StrideCode::AnglesOutOfBounds),
            "{:?}",
            st[7].findings
        );
        assert_eq!(st.iter().filter(|s| s.valid).count(), 19);
    }
}
