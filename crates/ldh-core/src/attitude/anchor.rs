//! Gravity re-acquisition windows: where the accelerometer measures gravity well enough to
//! re-anchor roll and pitch whatever the filter believes.
//!
//! A sample is quasi-static when its specific force is within `anchor_acc_g` of 1 g and the
//! shank turns slower than `anchor_gyro_dps`; a run of such samples lasting at least
//! `anchor_window_s` is a window. In walking these are the foot-flat phases of stance, where
//! the shank rotates over the fixed ankle: the sensor, `h` ≈ 0.05–0.25 m above the ankle, then
//! feels gravity plus a centripetal ω²h along the shank and a tangential α·h across it. At
//! 100–150 deg/s that is ≤ 0.07–0.17 g along the shank (which hardly moves the tilt of a
//! near-vertical shank) and, with the small angular acceleration of mid-stance, a few
//! hundredths of a g across it: a tilt error of 1–3°. The same gating is the zero-velocity
//! detector of foot-mounted inertial navigation (the SHOE statistic, Skog et al., IEEE TBME
//! 2010;57:2657), here with thresholds for a shank instead of a foot, and the quasi-static
//! gravity update of attitude filters (Sabatini, IEEE TBME 2006;53:1346; Valenti et al.,
//! Sensors 2015;15:19302).

/// Samples that belong to a gravity re-acquisition window, and the number of samples of a
/// minimum window (the measurement noise of an anchor is shared over that many samples).
pub(super) fn quasi_static_windows(
    acc_g: &[Vec<f64>; 3],
    gyro_dps: &[Vec<f64>; 3],
    fs_hz: f64,
    max_acc_dev_g: f64,
    max_gyro_dps: f64,
    window_s: f64,
) -> (Vec<bool>, usize) {
    let n = acc_g[0].len();
    let min_len = ((window_s * fs_hz).round() as usize).max(3);
    let quiet: Vec<bool> = (0..n)
        .map(|i| {
            let a = (acc_g[0][i].powi(2) + acc_g[1][i].powi(2) + acc_g[2][i].powi(2)).sqrt();
            let w =
                (gyro_dps[0][i].powi(2) + gyro_dps[1][i].powi(2) + gyro_dps[2][i].powi(2)).sqrt();
            (a - 1.0).abs() <= max_acc_dev_g && w <= max_gyro_dps
        })
        .collect();
    let mut mask = vec![false; n];
    let mut i = 0;
    while i < n {
        if !quiet[i] {
            i += 1;
            continue;
        }
        let s = i;
        while i < n && quiet[i] {
            i += 1;
        }
        if i - s >= min_len {
            mask[s..i].iter_mut().for_each(|x| *x = true);
        }
    }
    (mask, min_len)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_need_gravity_slow_rotation_and_duration() {
        let fs = 100.0;
        let n = 100;
        // 1 g along z; a 20-sample quiet run, a 5-sample quiet run, swing elsewhere.
        let mut acc = [vec![0.0; n], vec![0.0; n], vec![1.0; n]];
        let mut gyro = [vec![0.0; n], vec![300.0; n], vec![0.0; n]];
        for i in 10..30 {
            gyro[1][i] = 80.0;
        }
        for i in 50..55 {
            gyro[1][i] = 10.0;
        }
        // Slow but accelerating: not gravity alone.
        for i in 70..90 {
            gyro[1][i] = 10.0;
            acc[0][i] = 0.5;
        }
        let (m, len) = quasi_static_windows(&acc, &gyro, fs, 0.1, 150.0, 0.1);
        assert_eq!(len, 10);
        assert!(m[10..30].iter().all(|x| *x));
        assert!(m[50..55].iter().all(|x| !*x), "shorter than 0.1 s");
        assert!(m[70..90].iter().all(|x| !*x), "|a| = 1.12 g");
        assert_eq!(m.iter().filter(|x| **x).count(), 20);
    }
}
