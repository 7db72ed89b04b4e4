//! Sensor-to-segment alignment (SPEC §3.3): express both legs' signals in the same anatomical
//! frame F, whatever the mounting.
//!
//! F: e1 anterior, e2 left, e3 along the shank upwards (right-handed, the same on both legs).
//!
//! 1. **Quiet standing**: the longest run of 0.5 s windows whose angular velocity norm stays
//!    below `still_gyro_dps` and whose acceleration magnitude varies by less than
//!    `still_acc_sd_g`. Its mean angular velocity is the gyroscope bias; its mean acceleration
//!    is gravity, which gives the shank axis e3 (the shank is assumed vertical when standing).
//! 2. **Sagittal (medio-lateral) axis**: the principal axis of the bias-corrected angular velocity
//!    while walking (|ω| > `walking_gyro_dps`) — the shank rotates mostly about it — made
//!    orthogonal to e3.
//! 3. **Sign**: e2 must point to the subject's left on both legs. At mid-swing the foot swings
//!    forward, so the shank inclination θ falls fast: the largest angular-velocity excursions
//!    about +e2 are negative (≈ −300 to −450 deg/s) and larger than the positive stance ones.
//!    The sign of e2 is chosen so that this holds.
//! 4. e1 = e2 × e3.
//!
//! The result reports the axes found, whether the device is mounted mirrored (its y axis
//! pointing backwards) and its rotation about the shank axis.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::preprocess::Preprocessed;

/// Alignment parameters (unchecked).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AlignParams {
    /// Largest angular velocity norm of a still window, deg/s. Default 15.
    pub still_gyro_dps: f64,
    /// Largest SD of the acceleration magnitude in a still window, g. Default 0.02.
    pub still_acc_sd_g: f64,
    /// Length of a still window, s. Default 0.5.
    pub still_window_s: f64,
    /// Shortest usable quiet standing, s. Default 1.0.
    pub min_still_s: f64,
    /// Angular velocity norm above which a sample counts as walking for the axis search, deg/s.
    /// Default 50.
    pub walking_gyro_dps: f64,
}

impl Default for AlignParams {
    fn default() -> Self {
        AlignParams {
            still_gyro_dps: 15.0,
            still_acc_sd_g: 0.02,
            still_window_s: 0.5,
            min_still_s: 1.0,
            walking_gyro_dps: 50.0,
        }
    }
}

impl AlignParams {
    /// Validate against physical bounds (docs/parameters.md "Bounds"): a still window of
    /// 0.1–5 s (a window is a run of samples judged still together: below 0.1 s a mid-stance
    /// pause looks still, beyond 5 s no standing of a walking recording fills it), a shortest
    /// quiet standing of one window to 60 s, a still angular velocity up to 60 deg/s and
    /// acceleration SD up to 0.2 g (a walking shank exceeds both within every stride), and a
    /// walking threshold of 10–300 deg/s (below the swing peaks of 300–500 deg/s). A value
    /// outside these finds no standing or no walking and silently moves every angle (issue 37).
    pub fn check(&self) -> Result<ValidAlignParams> {
        for (n, v) in [
            ("still_gyro_dps", self.still_gyro_dps),
            ("still_acc_sd_g", self.still_acc_sd_g),
            ("still_window_s", self.still_window_s),
            ("min_still_s", self.min_still_s),
            ("walking_gyro_dps", self.walking_gyro_dps),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(LdhError::param(n, v, "must be > 0"));
            }
        }
        within("align.still_window_s", self.still_window_s, 0.1, 5.0, "s")?;
        within(
            "align.min_still_s",
            self.min_still_s,
            self.still_window_s,
            60.0,
            "s (at least align.still_window_s)",
        )?;
        within(
            "align.still_gyro_dps",
            self.still_gyro_dps,
            0.0,
            60.0,
            "deg/s",
        )?;
        within("align.still_acc_sd_g", self.still_acc_sd_g, 0.0, 0.2, "g")?;
        within(
            "align.walking_gyro_dps",
            self.walking_gyro_dps,
            10.0,
            300.0,
            "deg/s",
        )?;
        Ok(ValidAlignParams(self.clone()))
    }
}

/// `v` must lie in [lo, hi] (`unit` and any rule after it in the message); the error names the
/// parameter, its value and the range.
pub(crate) fn within(name: &'static str, v: f64, lo: f64, hi: f64, unit: &str) -> Result<()> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(LdhError::param(
            name,
            v,
            format!("outside its physical range [{lo}, {hi}] {unit}"),
        ))
    }
}

/// Checked alignment parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidAlignParams(AlignParams);

/// What the alignment found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Alignment {
    /// Rows e1 (anterior), e2 (left), e3 (shank, up) in device coordinates: v_F = R · v_device.
    pub r_f_from_device: [[f64; 3]; 3],
    /// Gyroscope bias in device axes, deg/s (zero when no quiet standing was found).
    pub gyro_bias_dps: [f64; 3],
    /// Quiet standing used, (start, end) in s; `None` when there was none.
    pub quiet_standing_s: Option<(f64, f64)>,
    /// All still periods found, s.
    pub still_periods_s: Vec<(f64, f64)>,
    /// The device's y axis points backwards (mirrored mounting, e.g. the right leg of a pair of
    /// identical devices worn laterally).
    pub mirrored: bool,
    /// Rotation of the device about the shank axis relative to y anterior (or posterior when
    /// mirrored), deg.
    pub axial_rotation_deg: f64,
    /// Angle between the device x axis and the shank axis, deg.
    pub shank_axis_tilt_deg: f64,
    /// Share of the walking angular-velocity variance about the sagittal axis (0–1).
    pub sagittal_variance_share: f64,
    /// Assumptions and findings, one sentence each.
    pub notes: Vec<String>,
}

impl Alignment {
    /// The alignment's note when it found no quiet standing (so no gyroscope bias was removed
    /// and the shank axis came from the mean acceleration of the whole recording); `None`
    /// when it found one. The quiet-standing step writes the first note ([`align`]), so it is
    /// found by its place, not by its text.
    pub fn no_standing_note(&self) -> Option<&str> {
        if self.quiet_standing_s.is_some() {
            return None;
        }
        self.notes.first().map(String::as_str)
    }
}

impl Alignment {
    /// The device frame is F: no rotation, no bias, nothing found (a recording already in the
    /// shank frame, as the simulator's truth and the tests build them).
    pub fn identity() -> Self {
        Alignment {
            r_f_from_device: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            gyro_bias_dps: [0.0; 3],
            quiet_standing_s: None,
            still_periods_s: vec![],
            mirrored: false,
            axial_rotation_deg: 0.0,
            shank_axis_tilt_deg: 0.0,
            sagittal_variance_share: 1.0,
            notes: vec![],
        }
    }
}

/// Signals in the anatomical frame F, gyroscope bias-corrected.
#[derive(Debug, Clone, PartialEq)]
pub struct Aligned {
    /// Sampling rate, Hz.
    pub fs_hz: f64,
    /// Specific force in F, g.
    pub acc_g: [Vec<f64>; 3],
    /// Angular velocity in F, deg/s (bias removed).
    pub gyro_dps: [Vec<f64>; 3],
    /// Samples where the accelerometer clipped (sorted indices, from
    /// [`Preprocessed::acc_clipped`]).
    pub acc_clipped: Vec<usize>,
    /// Specific force in F with the magnitude outliers kept, g, when it differs from `acc_g`
    /// ([`Preprocessed::acc_motion_g`]); read through [`Aligned::acc_motion_g`].
    pub acc_motion_g: Option<[Vec<f64>; 3]>,
    /// The alignment.
    pub alignment: Alignment,
}

impl Aligned {
    /// The specific force a strapdown integration reads, g: the magnitude outliers kept (only
    /// clipped samples replaced), see [`Preprocessed::acc_motion_g`].
    pub fn acc_motion_g(&self) -> &[Vec<f64>; 3] {
        self.acc_motion_g.as_ref().unwrap_or(&self.acc_g)
    }
}

fn still_mask(pre: &Preprocessed, p: &AlignParams) -> Vec<bool> {
    let n = pre.acc_norm_g.len();
    let w = ((p.still_window_s * pre.fs_hz).round() as usize).clamp(3, n.max(3));
    let mut mask = vec![false; n];
    if n < w {
        return mask;
    }
    let gn: Vec<f64> = (0..n)
        .map(|i| {
            (pre.gyro_dps[0][i].powi(2) + pre.gyro_dps[1][i].powi(2) + pre.gyro_dps[2][i].powi(2))
                .sqrt()
        })
        .collect();
    let mut i = 0;
    while i + w <= n {
        let win = &pre.acc_norm_g[i..i + w];
        let m = win.iter().sum::<f64>() / w as f64;
        let sd = (win.iter().map(|x| (x - m).powi(2)).sum::<f64>() / w as f64).sqrt();
        let gmax = gn[i..i + w].iter().cloned().fold(0.0, f64::max);
        if sd < p.still_acc_sd_g && gmax < p.still_gyro_dps && (0.7..1.3).contains(&m) {
            mask[i..i + w].iter_mut().for_each(|x| *x = true);
        }
        i += w / 2;
    }
    mask
}

/// Find the alignment of one sensor from its preprocessed signals.
pub fn align(pre: &Preprocessed, params: &ValidAlignParams) -> Result<Aligned> {
    let p = &params.0;
    let fs = pre.fs_hz;
    let mut notes = Vec::new();
    let still = crate::preprocess::runs(&still_mask(pre, p));
    // First: its note is the first (`Alignment::no_standing_note`).
    let quiet = quiet_standing(pre, p, &still, &mut notes);
    let e3 = shank_axis(quiet.gravity)?;
    let (e2, share) = sagittal_axis(pre, p, quiet.bias, e3)?;
    let e1 = e2.cross(&e3).normalize();
    let e2 = e3.cross(&e1);
    let r = [[e1.x, e1.y, e1.z], [e2.x, e2.y, e2.z], [e3.x, e3.y, e3.z]];
    let mirrored = e1.y < 0.0;
    // Axial rotation: angle of e1 in the device's y–z plane from ±y.
    let axial = if mirrored {
        (-e1.z).atan2(-e1.y)
    } else {
        e1.z.atan2(e1.y)
    };
    let tilt = e3.x.clamp(-1.0, 1.0).acos().to_degrees();
    notes.push(format!(
        "shank axis at {tilt:.1} deg from the device x axis; sagittal rotation axis explains {:.0} % of walking rotation; device {} about the shank by {:.1} deg",
        share * 100.0,
        if mirrored { "mirrored (y backwards), rotated" } else { "rotated" },
        axial.to_degrees()
    ));
    let (acc_f, gyro_f) = rotate(pre, &r, quiet.bias);
    Ok(Aligned {
        fs_hz: fs,
        acc_g: acc_f,
        gyro_dps: gyro_f,
        acc_clipped: pre.acc_clipped.clone(),
        acc_motion_g: pre.acc_motion_g.as_ref().map(|a| rotate_acc(a, &r)),
        alignment: Alignment {
            r_f_from_device: r,
            gyro_bias_dps: quiet.bias,
            quiet_standing_s: quiet.first_s,
            still_periods_s: still
                .iter()
                .map(|&(a, b)| (a as f64 / fs, b as f64 / fs))
                .collect(),
            mirrored,
            axial_rotation_deg: axial.to_degrees(),
            shank_axis_tilt_deg: tilt,
            sagittal_variance_share: share,
            notes,
        },
    })
}

/// What the still periods give: gravity (g) and the gyroscope bias (deg/s) in device axes, and
/// the first quiet-standing period (s), if any.
struct QuietStanding {
    gravity: [f64; 3],
    bias: [f64; 3],
    first_s: Option<(f64, f64)>,
}

/// The mean of `ch` over the sample ranges `idx`.
fn mean_over(ch: &[f64], idx: &[(usize, usize)]) -> f64 {
    let (mut s, mut c) = (0.0, 0usize);
    for &(a, b) in idx {
        s += ch[a..b].iter().sum::<f64>();
        c += b - a;
    }
    s / c.max(1) as f64
}

/// Step 1: gravity and the gyroscope bias from all still periods of at least `min_still_s`
/// (standing at the start and at the end); without any, gravity from the whole recording and
/// no bias removed. Says which in `notes`.
fn quiet_standing(
    pre: &Preprocessed,
    p: &AlignParams,
    still: &[(usize, usize)],
    notes: &mut Vec<String>,
) -> QuietStanding {
    let fs = pre.fs_hz;
    let min_len = (p.min_still_s * fs) as usize;
    let long: Vec<(usize, usize)> = still
        .iter()
        .copied()
        .filter(|(a, b)| b - a >= min_len)
        .collect();
    let means = |ch: &[Vec<f64>; 3], idx: &[(usize, usize)]| {
        [
            mean_over(&ch[0], idx),
            mean_over(&ch[1], idx),
            mean_over(&ch[2], idx),
        ]
    };
    if long.is_empty() {
        // A window longer than the recording cannot find standing: say which (issue 37).
        let dur = pre.acc_norm_g.len() as f64 / fs;
        let long_window = [
            ("align.min_still_s", p.min_still_s),
            ("align.still_window_s", p.still_window_s),
        ]
        .into_iter()
        .find(|&(_, v)| v > dur)
        .map(|(n, v)| format!(" ({n} = {v} s is longer than the {dur:.1} s recording)"))
        .unwrap_or_default();
        notes.push(format!(
            "no quiet standing of {} s found{long_window}: gyroscope bias not removed, shank axis from the mean acceleration of the whole recording",
            p.min_still_s
        ));
        return QuietStanding {
            gravity: means(&pre.acc_g, &[(0, pre.acc_norm_g.len())]),
            bias: [0.0; 3],
            first_s: None,
        };
    }
    let g = means(&pre.acc_g, &long);
    let b = means(&pre.gyro_dps, &long);
    let total: usize = long.iter().map(|(a, b)| b - a).sum();
    notes.push(format!(
        "quiet standing: {:.1} s in {} period(s); gyroscope bias ({:.2}, {:.2}, {:.2}) deg/s removed",
        total as f64 / fs,
        long.len(),
        b[0],
        b[1],
        b[2]
    ));
    let first = long[0];
    QuietStanding {
        gravity: g,
        bias: b,
        first_s: Some((first.0 as f64 / fs, first.1 as f64 / fs)),
    }
}

/// The shank axis e3: the unit gravity direction (refused when the accelerometer reads almost
/// nothing at rest).
fn shank_axis(gravity: [f64; 3]) -> Result<Vector3<f64>> {
    let e3 = Vector3::from(gravity);
    if e3.norm() < 0.3 {
        return Err(LdhError::signal(
            "alignment",
            format!(
                "the accelerometer reads {:.3} g at rest: no gravity direction",
                e3.norm()
            ),
        ));
    }
    Ok(e3.normalize())
}

/// The bias-corrected angular velocity at sample `i`, deg/s, device axes.
fn gyro_at(pre: &Preprocessed, bias: [f64; 3], i: usize) -> Vector3<f64> {
    Vector3::new(
        pre.gyro_dps[0][i] - bias[0],
        pre.gyro_dps[1][i] - bias[1],
        pre.gyro_dps[2][i] - bias[2],
    )
}

/// Steps 2–3: the sagittal axis e2 (the principal axis of the walking angular velocity made
/// orthogonal to `e3`, pointing left) and the share of the walking rotation about it.
fn sagittal_axis(
    pre: &Preprocessed,
    p: &AlignParams,
    bias: [f64; 3],
    e3: Vector3<f64>,
) -> Result<(Vector3<f64>, f64)> {
    let (n, fs) = (pre.acc_norm_g.len(), pre.fs_hz);
    let mut c = Matrix3::<f64>::zeros();
    let mut count = 0usize;
    for i in 0..n {
        let w = gyro_at(pre, bias, i);
        if w.norm() > p.walking_gyro_dps {
            c += w * w.transpose();
            count += 1;
        }
    }
    if count < (fs as usize).max(10) {
        return Err(LdhError::signal(
            "alignment",
            format!(
                "only {count} samples with angular velocity above {} deg/s: no walking found to locate the sagittal axis",
                p.walking_gyro_dps
            ),
        ));
    }
    let eig = SymmetricEigen::new(c);
    let (imax, _) = eig
        .eigenvalues
        .iter()
        .enumerate()
        .fold((0, f64::MIN), |m, (i, &v)| if v > m.1 { (i, v) } else { m });
    let share = eig.eigenvalues[imax] / eig.eigenvalues.iter().sum::<f64>().max(1e-12);
    let axis: Vector3<f64> = eig.eigenvectors.column(imax).into();
    let mut e2 = axis - e3 * axis.dot(&e3);
    if e2.norm() < 0.3 {
        return Err(LdhError::signal(
            "alignment",
            "the main rotation axis of walking is along the shank: cannot find the sagittal plane",
        ));
    }
    e2 = e2.normalize();
    // Sign: the mid-swing excursions about +e2 are negative.
    let mut proj: Vec<f64> = (0..n).map(|i| gyro_at(pre, bias, i).dot(&e2)).collect();
    let k = (n / 100).max(1);
    // The k lowest and the k highest, summed in ascending order as after a full sort (only
    // they are sorted: a select instead of sorting all n, issue 17).
    let cmp = |a: &f64, b: &f64| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal);
    proj.select_nth_unstable_by(k - 1, cmp);
    proj[..k].sort_by(cmp);
    let low = -proj[..k].iter().sum::<f64>() / k as f64;
    if n - k >= k {
        proj[k..].select_nth_unstable_by(n - 2 * k, cmp);
    }
    proj[n - k..].sort_by(cmp);
    let high = proj[n - k..].iter().sum::<f64>() / k as f64;
    if high > low {
        e2 = -e2;
    }
    Ok((e2, share))
}

/// The acceleration (g) and bias-corrected angular velocity (deg/s) rotated into frame F by
/// `r` (rows e1, e2, e3 in device axes).
/// Device-frame acceleration `a` rotated into F by `r`.
fn rotate_acc(a: &[Vec<f64>; 3], r: &[[f64; 3]; 3]) -> [Vec<f64>; 3] {
    std::array::from_fn(|row| {
        (0..a[0].len())
            .map(|i| r[row][0] * a[0][i] + r[row][1] * a[1][i] + r[row][2] * a[2][i])
            .collect()
    })
}

fn rotate(pre: &Preprocessed, r: &[[f64; 3]; 3], bias: [f64; 3]) -> ([Vec<f64>; 3], [Vec<f64>; 3]) {
    let n = pre.acc_norm_g.len();
    let acc_f = rotate_acc(&pre.acc_g, r);
    let gyro_f: [Vec<f64>; 3] = std::array::from_fn(|row| {
        (0..n)
            .map(|i| {
                let w = gyro_at(pre, bias, i);
                r[row][0] * w.x + r[row][1] * w.y + r[row][2] * w.z
            })
            .collect()
    });
    (acc_f, gyro_f)
}
