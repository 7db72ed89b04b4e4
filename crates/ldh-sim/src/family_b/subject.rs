//! Simulate one family B subject: timeline, foot placements, both legs, sensors, truth.

use nalgebra::{Matrix3, Rotation3, Vector3};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::kin::{FootRoll, Fourier, Phase, SHANK_KEYPOINTS_DEG};
use super::leg::{LegModelB, Walk, HALF_STEP_WIDTH_M};
use super::sensor::{measure, SensorModelB};
use super::SubjectParamsB;
use crate::{
    DenseTruth, LegTruth, SensorTruth, SimLeg, SimSubject, StrideTruth, SubjectParams,
    RAMP_STRIDE_EXTRA,
};
use ldh_core::error::{LdhError, Result};
use ldh_core::recording::{Recording, Setting, Side};

/// Timeline: left heel strikes k = −1..=n+1, the turn window and its strides, and the pace.
struct Timeline {
    n: i64,
    t_left: Vec<f64>,
    turn: Option<(f64, f64)>,
    turn_strides: Option<i64>,
    /// How much longer than drawn each left stride k = −1..=n is (index k + 1), in time and
    /// length: the start-up, slow-down and trend of [`SubjectParamsB`] (1 without them).
    pace: Vec<f64>,
    /// End of the start-up, s (strides that begin before it are accelerating).
    ramp_end_s: Option<f64>,
    /// Start of the slow-down, s (strides that end after it are decelerating).
    slowdown_start_s: Option<f64>,
}

fn timeline(p: &SubjectParamsB, z: &mut impl FnMut() -> f64) -> Result<Timeline> {
    let d = p.stride_time_s;
    // A start-up or slow-down adds RAMP_STRIDE_EXTRA / 2 of its length; a trend makes the mean
    // stride 1 + trend_share / 2 times the first.
    let walk_s = p.duration_s
        - 2.0 * p.standing_s
        - 1.5 * d
        - 0.5 * RAMP_STRIDE_EXTRA * (p.ramp_s + p.slowdown_s);
    let n = (walk_s / (d * (1.0 + 0.5 * p.trend_share))).floor() as i64;
    if n < 4 {
        return Err(LdhError::param(
            "duration_s",
            p.duration_s,
            format!("too short for 4 strides of {d:.2} s after the standing"),
        ));
    }
    let kt = (p.turn && p.setting == Setting::Overground && n >= 8).then_some(n / 2 - 1);
    let mut dur = Vec::with_capacity(n as usize + 2);
    for k in -1..=n {
        let mut dk = d * (1.0 + p.stride_time_cv * z()).clamp(0.8, 1.2);
        if kt.is_some_and(|kt| k >= kt && k < kt + 2) {
            dk *= 1.1;
        }
        dur.push(dk);
    }
    let pace = pace(p, &mut dur);
    let mut t_left = vec![p.standing_s];
    for dk in &dur {
        t_left.push(t_left.last().expect("non-empty") + dk);
    }
    let turn = kt.map(|kt| (t_left[(kt + 1) as usize], t_left[(kt + 3) as usize]));
    let end = *t_left.last().expect("non-empty");
    Ok(Timeline {
        n,
        turn,
        turn_strides: kt,
        pace,
        ramp_end_s: (p.ramp_s > 0.0).then_some(p.standing_s + p.ramp_s),
        slowdown_start_s: (p.slowdown_s > 0.0).then_some(end - p.slowdown_s),
        t_left,
    })
}

/// Stretch the drawn stride times `dur` by the pace of [`SubjectParamsB`] (a trend over the
/// walk, then the slow-down measured back from its end and the start-up from its start, each
/// `1 + RAMP_STRIDE_EXTRA · (1 − e / length)` at `e` s into it) and return the factors.
fn pace(p: &SubjectParamsB, dur: &mut [f64]) -> Vec<f64> {
    let mut f = vec![1.0; dur.len()];
    let last = dur.len().saturating_sub(1).max(1) as f64;
    for (j, x) in f.iter_mut().enumerate() {
        *x *= 1.0 + p.trend_share * j as f64 / last;
    }
    let stretch = |length_s: f64, order: &mut dyn Iterator<Item = usize>, f: &mut [f64]| {
        if length_s <= 0.0 {
            return;
        }
        let mut elapsed = 0.0;
        for j in order {
            f[j] *= 1.0 + RAMP_STRIDE_EXTRA * (1.0 - elapsed / length_s).max(0.0);
            elapsed += dur[j] * f[j];
        }
    };
    stretch(p.slowdown_s, &mut (0..dur.len()).rev(), &mut f);
    stretch(p.ramp_s, &mut (0..dur.len()), &mut f);
    for (x, k) in dur.iter_mut().zip(&f) {
        *x *= k;
    }
    f
}

/// Build one leg's model (phase, placements, swings).
fn build_leg(
    p: &SubjectParamsB,
    side: Side,
    tl: &Timeline,
    place: Vec<f64>,
    z: &mut impl FnMut() -> f64,
) -> Result<LegModelB> {
    let lp = p.leg(side).clone();
    let n = tl.n;
    let knots: Vec<f64> = match side {
        Side::Left => tl.t_left.clone(),
        Side::Right => tl
            .t_left
            .iter()
            .enumerate()
            .map(|(i, &t)| {
                let dk = if i + 1 < tl.t_left.len() {
                    tl.t_left[i + 1] - t
                } else {
                    t - tl.t_left[i - 1]
                };
                t + (0.5 + p.step_timing_asymmetry) * dk
            })
            .collect(),
    };
    let phase = Phase::new(-1, knots);
    if !phase.is_monotone() {
        return Err(LdhError::param(
            "stride_time_cv",
            p.stride_time_cv,
            "gives a non-monotone gait phase",
        ));
    }
    let stance: Vec<f64> = (-1..=n + 1)
        .map(|_| (lp.stance_ratio + p.stance_ratio_sd * z()).clamp(0.52, 0.8))
        .collect();
    let mount = Rotation3::from_axis_angle(&Vector3::x_axis(), lp.axial_deg.to_radians())
        * Rotation3::from_axis_angle(&Vector3::y_axis(), lp.tilt_deg[0].to_radians())
        * Rotation3::from_axis_angle(&Vector3::z_axis(), lp.tilt_deg[1].to_radians());
    let nominal = Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0);
    let hs = (0..=n).map(|k| phase.time_of(k as f64)).collect();
    let mut leg = LegModelB {
        lat: if side == Side::Left { 1.0 } else { -1.0 },
        phase,
        n,
        stance,
        place,
        swing: vec![None; (n + 3) as usize],
        foot: FootRoll {
            hs_rad: lp.foot_hs_deg.to_radians(),
            to_rad: lp.foot_to_deg.to_radians(),
            flat: lp.foot_flat,
            heel_off: lp.heel_off,
        },
        curve: Fourier::from_keypoints(&SHANK_KEYPOINTS_DEG, 8),
        hs,
        mount: nominal * mount.into_inner(),
        p: lp,
    };
    for k in -1..n {
        leg.build_swing(k);
    }
    Ok(leg)
}

/// Flat-foot positions along progression per stride k = −1..=n+1 of both legs.
fn placements(p: &SubjectParamsB, tl: &Timeline, z: &mut impl FnMut() -> f64) -> [Vec<f64>; 2] {
    let n = tl.n;
    let mut left = vec![0.0; (n + 3) as usize];
    let mut right = vec![0.0; (n + 3) as usize];
    let a = p.step_length_asymmetry;
    for k in 0..=n {
        let factor = match tl.turn_strides {
            Some(kt) if k >= kt && k < kt + 3 => 0.6,
            _ => 1.0,
        };
        let l = p.stride_length_m()
            * (1.0 + p.stride_length_cv * z())
            * factor
            * tl.pace[k as usize + 1];
        let i = (k + 1) as usize;
        left[i] = right[i - 1] + 0.5 * l * (1.0 - a);
        right[i] = if k < n {
            left[i] + 0.5 * l * (1.0 + a)
        } else {
            left[i]
        };
    }
    left[(n + 2) as usize] = left[(n + 1) as usize];
    right[(n + 2) as usize] = right[(n + 1) as usize];
    [left, right]
}

/// Simulate one family B subject.
pub fn simulate_subject_b(
    p: &SubjectParamsB,
    sensor: &SensorModelB,
    rng: &mut ChaCha8Rng,
) -> Result<SimSubject> {
    sensor.validate()?;
    let normal = Normal::new(0.0, 1.0).expect("valid");
    let mut draws: Vec<f64> = (0..4096).map(|_| normal.sample(rng)).collect();
    let mut z = move || draws.pop().unwrap_or(0.0);
    let tl = timeline(p, &mut z)?;
    let [pl, pr] = placements(p, &tl, &mut z);
    let left = build_leg(p, Side::Left, &tl, pl, &mut z)?;
    let right = build_leg(p, Side::Right, &tl, pr, &mut z)?;
    let belt = (p.setting == Setting::Treadmill).then(|| {
        let end = right.phase.time_of(tl.n as f64 + right.s(tl.n));
        (
            p.speed_mps,
            tl.t_left[0],
            end,
            p.stride_time_s,
            p.belt_ripple,
        )
    });
    let walk = Walk {
        turn: tl.turn,
        belt,
    };
    let mut legs = Vec::with_capacity(2);
    for (side, leg) in [(Side::Left, &left), (Side::Right, &right)] {
        legs.push(simulate_leg(p, sensor, side, leg, &walk, &tl, rng)?);
    }
    let r = legs.pop().expect("two");
    let l = legs.pop().expect("two");
    Ok(SimSubject {
        params: summary(p),
        left: l,
        right: r,
        family_b: Some(p.clone()),
    })
}

/// Family A-shaped summary of the subject (identifier, group, rate, mean stride).
fn summary(p: &SubjectParamsB) -> SubjectParams {
    let mut s = SubjectParams::healthy(p.subject_id.clone());
    s.group = p.group.clone();
    s.affected_side = p.affected_side;
    s.fs_hz = p.fs_hz;
    s.duration_s = p.duration_s;
    s.standing_s = p.standing_s;
    s.stride_time_s = p.stride_time_s;
    s.stride_length_m = p.stride_length_m();
    s.turn = p.turn && p.setting == Setting::Overground;
    (s.ramp_s, s.slowdown_s, s.trend_share) = (p.ramp_s, p.slowdown_s, p.trend_share);
    for side in [Side::Left, Side::Right] {
        let (src, dst) = (p.leg(side), s.leg_mut(side));
        dst.stance_ratio = src.stance_ratio;
        dst.sensor_height_m = src.sensor_height_m;
        dst.sensor_lateral_m = src.sensor_lateral_m;
        dst.circumduction_m = src.circumduction_m;
    }
    s
}

#[allow(clippy::too_many_arguments)]
fn simulate_leg(
    p: &SubjectParamsB,
    sensor: &SensorModelB,
    side: Side,
    leg: &LegModelB,
    walk: &Walk,
    tl: &Timeline,
    rng: &mut ChaCha8Rng,
) -> Result<SimLeg> {
    let fs = p.fs_hz;
    let n_out = (p.duration_s * fs).round() as usize + 1;
    let mut acc: [Vec<f64>; 3] = Default::default();
    let mut gyro: [Vec<f64>; 3] = Default::default();
    let mut pos: [Vec<f64>; 3] = Default::default();
    let mut vel: [Vec<f64>; 3] = Default::default();
    let mut rwd = Vec::with_capacity(n_out);
    let mut euler: [Vec<f64>; 3] = Default::default();
    let (mut pitch, mut roll, mut yaw) = (Vec::new(), Vec::new(), Vec::new());
    let a0 = leg.ankle(0.0);
    let mut world = Vector3::new(a0[0], a0[1], a0[2]);
    let mut prev_v = leg.ankle_vel_world(walk, 0.0);
    for i in 0..n_out {
        let t = i as f64 / fs;
        let v = leg.ankle_vel_world(walk, t);
        if i > 0 {
            // Simpson on the half step.
            let vm = leg.ankle_vel_world(walk, t - 0.5 / fs);
            world += (prev_v + 4.0 * vm + v) / (6.0 * fs);
        }
        prev_v = v;
        let (f, w, r) = leg.measure(walk, t);
        let lever = leg.lever(walk, t);
        let h = 1e-3;
        let lever_v = (leg.lever(walk, t + h) - leg.lever(walk, t - h)) / (2.0 * h);
        for k in 0..3 {
            acc[k].push(f[k]);
            gyro[k].push(w[k]);
            pos[k].push(world[k] + lever[k]);
            vel[k].push(v[k] + lever_v[k]);
        }
        rwd.push(std::array::from_fn(|a| std::array::from_fn(|b| r[(a, b)])));
        let (theta, rho) = leg.angles(t);
        let psi = walk.psi(t);
        euler[0].push(-leg.lat * rho);
        euler[1].push(theta);
        euler[2].push(psi);
        pitch.push(theta.to_degrees());
        roll.push(rho.to_degrees());
        yaw.push(psi.to_degrees());
    }
    let strides = stride_truth(leg, walk, tl, &pitch, &roll, fs);
    // One mask per sensor (as the reader gives): preprocessing replaces a clipped sample only
    // on the sensor that clipped.
    let (mut acc_sat, mut gyro_sat) = (vec![false; n_out], vec![false; n_out]);
    let (acc_m, acc_e) = measure(&acc, fs, sensor, false, p.acc_range_g, rng, &mut acc_sat);
    let (gyro_m, gyro_e) = measure(
        &gyro,
        fs,
        sensor,
        true,
        p.gyro_range_dps,
        rng,
        &mut gyro_sat,
    );
    let sat: Vec<bool> = acc_sat
        .iter()
        .zip(&gyro_sat)
        .map(|(a, g)| *a || *g)
        .collect();
    let saturated_samples = sat.iter().filter(|&&s| s).count();
    let recording = Recording::new(fs, acc_m, gyro_m, sat)?
        .with_sensor_saturation(acc_sat, gyro_sat)?
        .with_side(side);
    let lp = &leg.p;
    let axial = lp.axial_deg.rem_euclid(360.0);
    let truth = LegTruth {
        side,
        sensor_height_m: lp.sensor_height_m,
        sensor: SensorTruth {
            axial_misalignment_deg: if axial > 180.0 { axial - 360.0 } else { axial },
            tilt_misalignment_deg: lp.tilt_deg,
            mirrored: axial.to_radians().cos() < 0.0,
            device_axes_in_f: std::array::from_fn(|a| std::array::from_fn(|b| leg.mount[(a, b)])),
            gyro_bias_dps: gyro_e.bias0,
            acc_bias_g: acc_e.bias0,
            saturated_samples,
        },
        hs_times_s: leg.hs.clone(),
        to_times_s: (-1..tl.n)
            .map(|k| leg.phase.time_of(k as f64 + leg.s(k)))
            .collect(),
        strides,
        pitch_deg: pitch,
        roll_deg: roll,
        yaw_deg: yaw,
    };
    Ok(SimLeg {
        recording,
        truth,
        dense: DenseTruth {
            acc_clean_g: acc,
            gyro_clean_dps: gyro,
            sensor_pos_m: pos,
            sensor_vel_mps: vel,
            r_world_device: rwd,
            euler_rad: euler,
        },
    })
}

/// Flat-foot ankle position in the world (belt frame on a treadmill) of each stance k = 0..=n.
fn foot_flat_positions(leg: &LegModelB, walk: &Walk, n: i64) -> Vec<[f64; 2]> {
    let t_ff = |k: i64| {
        leg.phase
            .time_of(k as f64 + leg.s(k) * 0.5 * (leg.foot.flat + leg.foot.heel_off))
    };
    let no_belt = Walk {
        turn: walk.turn,
        belt: None,
    };
    let mut out = Vec::with_capacity(n as usize + 1);
    let a = leg.ankle(t_ff(0));
    let mut w = [a[0], a[1]];
    out.push(w);
    for k in 1..=n {
        let (t0, t1) = (t_ff(k - 1), t_ff(k));
        let m = ((t1 - t0) / 5e-4).ceil().max(2.0) as usize;
        let dt = (t1 - t0) / m as f64;
        for j in 0..m {
            let ta = t0 + j as f64 * dt;
            let (va, vm, vb) = (
                leg.ankle_vel_world(&no_belt, ta),
                leg.ankle_vel_world(&no_belt, ta + 0.5 * dt),
                leg.ankle_vel_world(&no_belt, ta + dt),
            );
            for c in 0..2 {
                w[c] += dt * (va[c] + 4.0 * vm[c] + vb[c]) / 6.0;
            }
        }
        out.push(w);
    }
    out
}

fn stride_truth(
    leg: &LegModelB,
    walk: &Walk,
    tl: &Timeline,
    pitch: &[f64],
    roll: &[f64],
    fs: f64,
) -> Vec<StrideTruth> {
    let n = tl.n;
    let ff = foot_flat_positions(leg, walk, n);
    let _ = HALF_STEP_WIDTH_M;
    (0..n)
        .map(|k| {
            let hs = leg.hs[k as usize];
            let next = leg.hs[k as usize + 1];
            let to = leg.phase.time_of(k as f64 + leg.s(k));
            let range = |a: f64, b: f64, v: &[f64]| {
                let (i, j) = (
                    (a * fs).ceil() as usize,
                    ((b * fs).ceil() as usize).min(v.len()),
                );
                let s = &v[i.min(j)..j];
                (
                    s.iter().copied().fold(f64::MIN, f64::max),
                    s.iter().copied().fold(f64::MAX, f64::min),
                )
            };
            let (mx, mn) = range(hs, next, pitch);
            let (rmx, rmn) = range(to, next, roll);
            let (a, b) = (ff[k as usize], ff[k as usize + 1]);
            StrideTruth {
                index: k as usize,
                hs_time_s: hs,
                to_time_s: to,
                next_hs_time_s: next,
                stride_time_s: next - hs,
                stance_ratio: (to - hs) / (next - hs),
                stride_length_m: ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt(),
                max_pitch_deg: mx,
                min_pitch_deg: mn,
                roll_swing_excursion_deg: rmx - rmn,
                turning: walk.turn.is_some_and(|(a, b)| next > a && hs < b),
                bout_edge: k == 0 || k == n - 1,
                accelerating: tl.ramp_end_s.is_some_and(|e| hs < e),
                decelerating: tl.slowdown_start_s.is_some_and(|s| next > s),
            }
        })
        .collect()
}
