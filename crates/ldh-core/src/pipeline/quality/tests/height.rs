//! The `sensor_height_unknown` rule (issue 20) on a synthetic leg whose ankle rests through the
//! stance while the shank turns over it at 60 deg/s at mid-stance (HuGaDB's shanks: 40–80),
//! the sensor 0.25 m above the ankle: with the height given the length is the true one and
//! nothing is said; without it the assumed 0.10 m gives strides 13 % short, the lengths at the
//! ends of the height range are 0.99 and 1.31 m (a movement of 30 %), and the leg's stride
//! length is withheld. A leg
//! whose shank is almost still at mid-stance (as the simulators') only gets the note.

use super::super::{apply_to_strides, codes, params, sensor_height_warning, withhold, Severity};
use crate::align::{Aligned, Alignment};
use crate::attitude::{Attitude, AttitudeModel};
use crate::domain::Parameter;
use crate::events::Events;
use crate::gait::{
    height_sensitivity, height_sensitivity_measured, heights_to_measure, lengths_at_heights,
    side_parameters, strides, strides_at_heights, HeightSensitivity, Stride, StrideParams,
    ValidStrideParams, SENSOR_HEIGHT_RANGE_M,
};
use crate::recording::{Side, STANDARD_GRAVITY_MPS2};

/// Sampling rate, Hz.
const FS: f64 = 100.0;
/// Stride time, s.
const T: f64 = 1.0;
/// Stance share of the stride.
const STANCE: f64 = 0.6;
/// Stride length, m.
const L: f64 = 1.2;
/// The sensor's true height above the ankle, m.
const H_TRUE: f64 = 0.25;
/// First heel strike, s.
const T0: f64 = 0.5;
/// Strides recorded.
const STRIDES: usize = 12;

/// A periodic walk: the ankle at rest in stance and carried forward by `L` in swing (zero
/// velocity at both ends), the shank pitch turning through 40° of stance at `mid_dps` at
/// mid-stance (faster at heel strike and toe off) and back in swing (a cubic Hermite with the
/// same rates at its ends).
struct Walk {
    mid_dps: f64,
}

impl Walk {
    /// Stance pitch at the stance share `s` ∈ [0, 1], deg, and its rate, deg/s.
    fn stance(&self, s: f64) -> (f64, f64) {
        let ts = STANCE * T;
        let k = 4.0 * (40.0 - self.mid_dps * ts);
        let u = s - 0.5;
        (
            3.0 + self.mid_dps * u * ts + k * u.powi(3),
            self.mid_dps + 3.0 * k * u * u / ts,
        )
    }

    /// Shank pitch, deg, at `t` s.
    fn pitch_deg(&self, t: f64) -> f64 {
        let ph = ((t - T0) / T).rem_euclid(1.0);
        if ph < STANCE {
            return self.stance(ph / STANCE).0;
        }
        let (u, tsw) = ((ph - STANCE) / (1.0 - STANCE), (1.0 - STANCE) * T);
        let ((p0, r), (p1, _)) = (self.stance(1.0), self.stance(0.0));
        let m = r * tsw;
        let (u2, u3) = (u * u, u * u * u);
        (2.0 * u3 - 3.0 * u2 + 1.0) * p0
            + (u3 - 2.0 * u2 + u) * m
            + (-2.0 * u3 + 3.0 * u2) * p1
            + (u3 - u2) * m
    }

    /// Ankle position (forward, up), m, at `t` s.
    fn ankle(&self, t: f64) -> (f64, f64) {
        let k = ((t - T0) / T).floor();
        let ph = (t - T0) / T - k;
        if ph < STANCE {
            return (k * L, 0.0);
        }
        let u = (ph - STANCE) / (1.0 - STANCE);
        let tau = 2.0 * std::f64::consts::PI;
        (
            k * L + L * (u - (tau * u).sin() / tau),
            0.05 * (0.5 * tau * u).sin().powi(2),
        )
    }

    /// Sensor position (forward, up), m, at `t` s, `h` m up the shank from the ankle.
    fn sensor(&self, t: f64, h: f64) -> (f64, f64) {
        let (x, z) = self.ankle(t);
        let th = self.pitch_deg(t).to_radians();
        (x + h * th.sin(), z + h * th.cos())
    }

    /// The leg's aligned signals, attitude and events (the sensor at `H_TRUE`).
    fn leg(&self) -> (Aligned, Attitude, Events) {
        let n = ((T0 + STRIDES as f64 * T + 0.7) * FS) as usize;
        let e = 1e-4;
        let (mut ax, mut az, mut gy, mut pitch) = (vec![], vec![], vec![], vec![]);
        for i in 0..n {
            let t = i as f64 / FS;
            let (p, q, r) = (
                self.sensor(t - e, H_TRUE),
                self.sensor(t, H_TRUE),
                self.sensor(t + e, H_TRUE),
            );
            // Specific force in the world, m/s², then in the shank frame (pitch about y).
            let fx = (p.0 - 2.0 * q.0 + r.0) / (e * e);
            let fz = (p.1 - 2.0 * q.1 + r.1) / (e * e) + STANDARD_GRAVITY_MPS2;
            let th = self.pitch_deg(t).to_radians();
            let (s, c) = th.sin_cos();
            ax.push((c * fx - s * fz) / STANDARD_GRAVITY_MPS2);
            az.push((s * fx + c * fz) / STANDARD_GRAVITY_MPS2);
            gy.push((self.pitch_deg(t + e) - self.pitch_deg(t - e)) / (2.0 * e));
            pitch.push(self.pitch_deg(t));
        }
        let al = Aligned {
            fs_hz: FS,
            acc_g: [ax, vec![0.0; n], az],
            gyro_dps: [vec![0.0; n], gy, vec![0.0; n]],
            acc_clipped: vec![],
            acc_motion_g: None,
            alignment: Alignment::identity(),
        };
        let att = Attitude {
            model: AttitudeModel::Fusion,
            fs_hz: FS,
            roll_deg: vec![0.0; n],
            pitch_deg: pitch,
            yaw_deg: vec![0.0; n],
            final_weights: vec![],
            final_tilt_noise_deg: vec![],
            gyro_bias_dps: [0.0; 2],
            gravity_windows: 0,
        };
        let hs: Vec<f64> = (0..=STRIDES).map(|k| T0 + k as f64 * T).collect();
        let ev = Events {
            to_s: hs.iter().map(|h| h + STANCE * T).collect(),
            midswing_s: hs.iter().map(|h| h + 0.8 * T).collect(),
            hs_s: hs,
            median_stride_s: T,
            ..Events::default()
        };
        (al, att, ev)
    }

    /// The leg's strides and their height sensitivity with `params`.
    fn analyse(&self, params: &ValidStrideParams) -> (Vec<Stride>, Option<HeightSensitivity>) {
        let (al, att, ev) = self.leg();
        let st = strides(Side::Left, &al, &att, &ev, params).unwrap();
        let h = height_sensitivity(Side::Left, &al, &att, &ev, params, &st);
        (st, h)
    }
}

/// Median of the valid strides' lengths, m.
fn median_length(st: &[Stride]) -> f64 {
    let mut v: Vec<f64> = st
        .iter()
        .filter(|s| s.valid && s.stride_length_m.is_finite())
        .map(|s| s.stride_length_m)
        .collect();
    assert!(v.len() >= 8, "{} lengths", v.len());
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[test]
fn a_shank_turning_at_mid_stance_withholds_the_length_without_a_height_and_not_with_it() {
    let walk = Walk { mid_dps: 60.0 };
    // Given: the true length, and no check (nothing assumed).
    let given = StrideParams::default()
        .sensor_height_m(H_TRUE)
        .check()
        .unwrap();
    let (st, h) = walk.analyse(&given);
    assert!(h.is_none());
    let m = median_length(&st);
    assert!((m - L).abs() < 0.01 * L, "{m}");
    // Assumed 0.10 m: each stride is short by ω Δh T (a constant velocity error that
    // de-drifting cannot see, and no per-stride check does).
    let assumed = StrideParams::default().check().unwrap();
    let (mut st, h) = walk.analyse(&assumed);
    let h = h.expect("the height was assumed");
    println!("turning shank, 0.10 m assumed: {h:?}");
    let short = 60f64.to_radians() * (H_TRUE - 0.10) * T;
    assert!((h.median_m - (L - short)).abs() < 0.02, "{h:?}");
    assert_eq!((h.assumed_m, h.range_m), (0.10, [0.05, 0.35]));
    // ≈ L + ω (h − H_TRUE) T at either end: 0.99 and 1.31 m.
    let [lo, hi] = h.at_ends_m.map(Option::unwrap);
    let per_m = 60f64.to_radians() * T;
    assert!((lo - (L - per_m * 0.20)).abs() < 0.02, "{lo}");
    assert!((hi - (L + per_m * 0.10)).abs() < 0.02, "{hi}");
    // The median moves by (1.31 − 0.99) / 1.04 ≈ 30 % across the range: more than 15 %.
    let spread = h.spread_share().unwrap();
    assert!(
        (spread - (hi - lo) / h.median_m).abs() < 1e-12 && spread > 0.25,
        "{spread}"
    );
    assert!(!h.vouched());
    let w = sensor_height_warning(&h);
    assert_eq!(
        (w.code, w.severity),
        (codes::SENSOR_HEIGHT_UNKNOWN, Severity::Warning)
    );
    assert_eq!(w.affects, params::LENGTH);
    let text = format!("would be {lo:.2} and {hi:.2} m with the sensor 0.05 and 0.35 m above the ankle, {:.2} m at the assumed 0.10 m", h.median_m);
    assert!(w.message.contains(&text), "{}", w.message);
    assert!(w.message.contains(&format!(
        "a movement of {:.0} % (more than 15 %)",
        spread * 100.0
    )));
    assert!(
        w.message
            .contains("give it (manifest column sensor_height_m"),
        "{}",
        w.message
    );
    // Per stride and per leg: the lengths are withheld with the reason.
    apply_to_strides(&mut st, std::slice::from_ref(&w));
    assert!(st
        .iter()
        .all(|s| s.stride_length_m.is_nan() && s.speed_mps.is_nan()));
    assert!(st.iter().filter(|s| s.valid).all(|s| s
        .reason
        .contains("stride length withheld: sensor height not given")));
    let mut p = side_parameters(&st, None);
    withhold(&mut p, std::slice::from_ref(&w));
    assert!(
        p[Parameter::StrideLength].is_nan()
            && p[Parameter::Speed].is_nan()
            && p[Parameter::StrideLengthCv].is_nan()
    );
    // The leg's reason names the finding (its message, with the lengths, is the warning's).
    assert_eq!(
        p.withheld
            .reason(crate::domain::Parameter::StrideLength)
            .unwrap(),
        "sensor height not given"
    );
    assert!(w
        .reason()
        .starts_with("the sensor height was not given and the stride length depends on it"));
    assert!(p[Parameter::StrideTime].is_finite() && p[Parameter::Wqk].is_finite());
}

#[test]
fn a_shank_almost_still_at_mid_stance_reports_the_length_with_a_note() {
    let walk = Walk { mid_dps: 5.0 };
    let (st, h) = walk.analyse(&StrideParams::default().check().unwrap());
    let h = h.expect("the height was assumed");
    println!("still shank, 0.10 m assumed: {h:?}");
    let spread = h.spread_share().unwrap();
    assert!(spread < 0.03 && h.vouched(), "{h:?}");
    assert!((median_length(&st) - L).abs() < 0.02 * L);
    let w = sensor_height_warning(&h);
    assert_eq!(w.severity, Severity::Note);
    assert!(w.affects.is_empty());
    assert!(
        w.message
            .starts_with("the sensor height was not given, so 0.10 m above the ankle was assumed"),
        "{}",
        w.message
    );
    assert!(
        w.message.contains(&format!(
            "a movement of {:.1} % (at most 15 %), so it is reported",
            spread * 100.0
        )),
        "{}",
        w.message
    );
    // An end where no stride passes cannot bound the error: withheld.
    let unbounded = HeightSensitivity {
        at_ends_m: [h.at_ends_m[0], None],
        ..h
    };
    assert!(!unbounded.vouched());
    let w = sensor_height_warning(&unbounded);
    assert_eq!(w.severity, Severity::Warning);
    assert!(
        w.message
            .contains("m at 0.05 m and none (no stride passes the integration checks) at 0.35 m"),
        "{}",
        w.message
    );
    assert!(
        w.message.contains("a movement that cannot be bounded"),
        "{}",
        w.message
    );
}

/// The pipeline measures the lengths at the ends of the height range during the segmentation
/// (`strides_at_heights`) instead of integrating the final strides again: the same bits, on the
/// synthetic walks and on a demo leg (simulated) with some strides invalidated after the
/// segmentation (as the leg's checks do), and nothing measured with a height given.
#[test]
fn lengths_measured_during_the_segmentation_are_those_recomputed_bit_for_bit() {
    use crate::align::{align, AlignParams};
    use crate::attitude::{estimate, AttitudeParams};
    use crate::events::{detect, EventParams};
    use crate::preprocess::{preprocess, PreprocessParams};
    let assumed = StrideParams::default().check().unwrap();
    // An LDH walker's leg of the embedded demo cohort (simulated, family A).
    let rec = &crate::demo::recording("L01/left.csv").unwrap();
    let pre = preprocess(rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
    let al = align(&pre, &AlignParams::default().check().unwrap()).unwrap();
    let att = estimate(&al, &AttitudeParams::default().check().unwrap()).unwrap();
    let ev = detect(
        &att.pitch_deg,
        &al.gyro_dps[1],
        rec.fs_hz,
        &EventParams::default().check().unwrap(),
    )
    .unwrap();
    let mut legs = vec![(al, att, ev)];
    legs.extend([5.0, 60.0].map(|mid_dps| Walk { mid_dps }.leg()));
    let bits = |v: &[Vec<f64>]| -> Vec<Vec<u64>> {
        v.iter()
            .map(|l| l.iter().map(|x| x.to_bits()).collect())
            .collect()
    };
    for (al, att, ev) in &legs {
        let heights = heights_to_measure(&assumed, att.model);
        assert_eq!(heights, SENSOR_HEIGHT_RANGE_M);
        let (mut st, measured) =
            strides_at_heights(Side::Left, al, att, ev, &assumed, heights).unwrap();
        // Compared as printed: the double support is NaN until the pair sets it, and NaN ≠ NaN.
        assert_eq!(
            format!("{st:?}"),
            format!("{:?}", strides(Side::Left, al, att, ev, &assumed).unwrap())
        );
        for k in [1, st.len() / 2] {
            st[k].valid = false;
        }
        let again = lengths_at_heights(Side::Left, al, att, ev, &assumed, &st, heights);
        let checked = measured.checked(&st, assumed.params().max_length_deviation);
        assert_eq!(bits(&checked), bits(&again));
        assert!(checked[0].iter().filter(|l| l.is_finite()).count() >= 5);
        let h = height_sensitivity(Side::Left, al, att, ev, &assumed, &st);
        assert!(h.is_some());
        assert_eq!(
            height_sensitivity_measured(&assumed, att.model, &st, &measured),
            h
        );
    }
    let given = StrideParams::default()
        .sensor_height_m(0.2)
        .check()
        .unwrap();
    let (al, att, ev) = &legs[0];
    assert!(heights_to_measure(&given, att.model).is_empty());
    let (_, none) = strides_at_heights(Side::Left, al, att, ev, &given, &[]).unwrap();
    assert!(none.lengths_m.is_empty());
    assert_eq!(
        height_sensitivity_measured(&given, att.model, &[], &none),
        None
    );
}
