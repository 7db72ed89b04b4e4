//! The reader's channel values (SPEC §2): the format's scale applied, clipped samples flagged
//! at the sensor range (or, without a stated range, as flat runs at the channel's extreme), then
//! the units converted to g and deg/s and the axes mapped to ldh's frame.

use super::format::{AccUnit, AxisMap, FormatSpec, GyroUnit};
use super::units::Unit;
use crate::error::Result;
use crate::recording::STANDARD_GRAVITY_MPS2;

/// Three axes of one sensor (x, y, z), one value per sample each.
pub(super) type Axes = [Vec<f64>; 3];

/// Clipped samples found by [`scale_and_flag_clipping`].
pub(super) struct Clipping {
    /// Clipped samples per channel: acc x, y, z, gyro x, y, z.
    pub per_channel: [usize; 6],
    /// Per sample: an accelerometer channel clipped.
    pub acc: Vec<bool>,
    /// Per sample: a gyroscope channel clipped (kept apart from `acc`: preprocessing replaces
    /// only the channels of the sensor that clipped).
    pub gyro: Vec<bool>,
    /// Samples with any channel clipped.
    pub samples: usize,
}

/// Multiply the six channels (acc x, y, z, gyro x, y, z; `n_out` samples each) in place by the
/// format's scale, then flag clipped samples on the scaled values, in the file's units (the
/// range as the format states it; without one, an extreme of at least 1.5 g or 200 deg/s).
/// Notes how many samples were clipped.
pub(super) fn scale_and_flag_clipping(
    channels: &mut [Vec<f64>; 6],
    spec: &FormatSpec,
    n_out: usize,
    notes: &mut Vec<String>,
) -> Clipping {
    let mut sat_per = [0usize; 6];
    let mut saturated = [vec![false; n_out], vec![false; n_out]];
    for k in 0..6 {
        let (scale, range, floor) = if k < 3 {
            let floor = match spec.acc.unit {
                AccUnit::G => 1.5,
                AccUnit::Mps2 => 1.5 * STANDARD_GRAVITY_MPS2,
            };
            (spec.acc.scale, spec.acc.range, floor)
        } else {
            let floor = match spec.gyro.unit {
                GyroUnit::Dps => 200.0,
                GyroUnit::Rps => 200f64.to_radians(),
            };
            (spec.gyro.scale, spec.gyro.range, floor)
        };
        let ch = &mut channels[k];
        for v in ch.iter_mut() {
            *v *= scale;
        }
        let flags = detect_clipping(ch, range, floor);
        for (i, f) in flags.iter().enumerate() {
            if *f {
                sat_per[k] += 1;
                saturated[k / 3][i] = true;
            }
        }
    }
    let saturated_samples = (0..n_out)
        .filter(|&i| saturated[0][i] || saturated[1][i])
        .count();
    if saturated_samples > 0 {
        notes.push(format!(
            "{saturated_samples} clipped sample(s) at the sensor range (acc x/y/z, gyro x/y/z: {sat_per:?}); treated as outliers"
        ));
    }
    let [acc, gyro] = saturated;
    Clipping {
        per_channel: sat_per,
        acc,
        gyro,
        samples: saturated_samples,
    }
}

/// The six scaled channels (file units, consumed) as acceleration in g and angular velocity in
/// deg/s, in ldh's frame (the format's axis map; noted when it is not the identity).
pub(super) fn to_ldh_frame(
    channels: [Vec<f64>; 6],
    spec: &FormatSpec,
    notes: &mut Vec<String>,
) -> Result<(Axes, Axes)> {
    // The factors `ldh inspect` shows (`units.rs`).
    let acc_to_g = Unit::from(spec.acc.unit).to_internal();
    let gyro_to_dps = Unit::from(spec.gyro.unit).to_internal();
    let map = spec.axis_map()?;
    let [c0, c1, c2, c3, c4, c5] = channels;
    // In place: the map is a permutation (checked by `axis_map`), each input taken once.
    let convert = |mut input: Axes, to: f64| -> Axes {
        std::array::from_fn(|i| {
            let mut ch = std::mem::take(&mut input[map.index[i]]);
            for v in &mut ch {
                *v = *v * to * map.sign[i];
            }
            ch
        })
    };
    let acc_g = convert([c0, c1, c2], acc_to_g);
    let gyro_dps = convert([c3, c4, c5], gyro_to_dps);
    if map != AxisMap::IDENTITY {
        notes.push(format!("axes mapped to ldh's frame as {:?}", spec.axes.map));
    }
    Ok((acc_g, gyro_dps))
}

/// Samples [`detect_clipping`] tests at once for a run near an extreme.
const CLIP_BLOCK: usize = 16;

/// Flag clipped samples of one channel.
///
/// With a known `range`: every sample with |v| ≥ 99.9 % of it. Without: samples at the channel's
/// extreme value (within 0.1 %) that sit in a flat run of ≥ 3 equal values, provided that
/// extreme is at least `floor` (so a sensor lying still is not called clipped).
pub fn detect_clipping(ch: &[f64], range: Option<f64>, floor: f64) -> Vec<bool> {
    let n = ch.len();
    let mut flags = vec![false; n];
    if let Some(r) = range {
        for (f, v) in flags.iter_mut().zip(ch) {
            *f = v.abs() >= 0.999 * r;
        }
        return flags;
    }
    let (lo, hi) = extremes(ch);
    for ext in [hi, lo] {
        if ext.abs() < floor {
            continue;
        }
        let near = |v: f64| (v - ext).abs() <= 1e-3 * ext.abs();
        let mut i = 0;
        while i < n {
            // a block with no sample near the extreme, where the walk below would only step
            // on, is passed in one test that vectorises (issue 17: this was a branch per
            // sample, run on six channels by the reader and again by the sensor checks)
            if let Some(block) = ch.get(i..i + CLIP_BLOCK) {
                if !block.iter().fold(false, |any, &v| any | near(v)) {
                    i += CLIP_BLOCK;
                    continue;
                }
            }
            i = if near(ch[i]) {
                flag_flat_run(ch, i, &mut flags)
            } else {
                i + 1
            };
        }
    }
    flags
}

/// The smallest and largest value of `ch`, NaN skipped (±∞ when there is none). `v < lo` keeps
/// what `f64::min` keeps (an equal value changes nothing but the sign of a zero extreme, which
/// is below any clipping floor) and vectorises.
fn extremes(ch: &[f64]) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in ch {
        lo = if v < lo { v } else { lo };
        hi = if v > hi { v } else { hi };
    }
    (lo, hi)
}

/// Flag the run of values equal to `ch[i]` that starts at `i` when it is 3 or more long; the
/// index after the run.
fn flag_flat_run(ch: &[f64], i: usize, flags: &mut [bool]) -> usize {
    let mut j = i;
    while j + 1 < ch.len() && ch[j + 1] == ch[i] {
        j += 1;
    }
    if j + 1 - i >= 3 {
        for f in &mut flags[i..=j] {
            *f = true;
        }
    }
    j + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: &str = r#"
name = "t"
[time]
column = "t"
unit = "s"
[acc]
columns = ["ax", "ay", "az"]
unit = "g"
scale = 0.5
range = 16.0
[gyro]
columns = ["gx", "gy", "gz"]
unit = "rad/s"
[axes]
map = ["-y", "+x", "+z"]
"#;

    #[test]
    fn scaled_values_at_the_stated_range_are_clipped() {
        let spec = FormatSpec::from_toml_str(SPEC, "test").unwrap();
        let mut ch: [Vec<f64>; 6] = std::array::from_fn(|_| vec![0.0; 3]);
        ch[0] = vec![32.0, 2.0, -40.0];
        let mut notes = Vec::new();
        let c = scale_and_flag_clipping(&mut ch, &spec, 3, &mut notes);
        assert_eq!(ch[0], vec![16.0, 1.0, -20.0]);
        assert_eq!(c.per_channel, [2, 0, 0, 0, 0, 0]);
        assert_eq!(c.acc, vec![true, false, true]);
        assert_eq!(c.gyro, vec![false; 3]);
        assert_eq!(c.samples, 2);
        assert_eq!(notes.len(), 1);
    }

    #[test]
    fn units_and_the_axis_map_give_ldh_frame() {
        let spec = FormatSpec::from_toml_str(SPEC, "test").unwrap();
        let ch = [
            vec![1.0],
            vec![2.0],
            vec![3.0],
            vec![std::f64::consts::PI],
            vec![0.5 * std::f64::consts::PI],
            vec![0.0],
        ];
        let mut notes = Vec::new();
        let (acc, gyro) = to_ldh_frame(ch, &spec, &mut notes).unwrap();
        assert_eq!(acc, [vec![-2.0], vec![1.0], vec![3.0]]);
        assert!((gyro[0][0] + 90.0).abs() < 1e-12 && (gyro[1][0] - 180.0).abs() < 1e-12);
        assert_eq!(gyro[2][0], 0.0);
        assert!(
            notes[0].starts_with("axes mapped to ldh's frame"),
            "{notes:?}"
        );
    }

    /// The block skip flags what the sample-by-sample walk flagged: runs of 1-5 equal values
    /// at and near both extremes, anywhere relative to the blocks, NaN among them.
    #[test]
    fn clipping_by_blocks_is_the_walk_sample_by_sample() {
        let walk = |ch: &[f64], floor: f64| -> Vec<bool> {
            let mut flags = vec![false; ch.len()];
            let (lo, hi) = extremes(ch);
            for ext in [hi, lo] {
                if ext.abs() < floor {
                    continue;
                }
                let near = |v: f64| (v - ext).abs() <= 1e-3 * ext.abs();
                let mut i = 0;
                while i < ch.len() {
                    i = if near(ch[i]) {
                        flag_flat_run(ch, i, &mut flags)
                    } else {
                        i + 1
                    };
                }
            }
            flags
        };
        let mut seed = 12345u64;
        let mut next = |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        for case in 0..3000 {
            let n = 1 + next(200) as usize;
            let mut ch: Vec<f64> = (0..n).map(|_| next(1000) as f64 - 500.0).collect();
            for _ in 0..next(6) {
                let (at, len) = (next(n as u64) as usize, 1 + next(5) as usize);
                let v = [500.0, -500.0, 499.9, -499.8, 250.0][next(5) as usize];
                for x in ch.iter_mut().skip(at).take(len) {
                    *x = v;
                }
            }
            if case % 17 == 0 {
                ch[next(n as u64) as usize] = f64::NAN;
            }
            for floor in [0.0, 200.0, 499.95, 600.0] {
                assert_eq!(
                    detect_clipping(&ch, None, floor),
                    walk(&ch, floor),
                    "case {case}"
                );
            }
        }
    }

    #[test]
    fn a_flat_run_at_a_large_extreme_is_clipping_a_still_sensor_is_not() {
        let flags = detect_clipping(&[0.0, 250.0, 250.0, 250.0, 10.0], None, 200.0);
        assert_eq!(flags, vec![false, true, true, true, false]);
        assert!(!detect_clipping(&[1.0, 1.0, 1.0], None, 1.5).contains(&true));
    }
}
