//! Gait-cycle-normalised curves (the plot every clinical gait report has): each valid stride's
//! shank pitch from its heel strike to the next heel strike of the same leg, resampled by linear
//! interpolation onto 0–100 % of the cycle, then mean ± SD across strides per leg (time
//! normalisation as in Winter, *Biomechanics and Motor Control of Human Movement*, 4th ed.,
//! Wiley 2009, ch. 1). [`pitch_cycle_of`] pools every valid stride of a leg — those of the
//! walk's steady window, the others being invalid (`gait::steady`) — so the curve is of steady
//! walking and of all of it, not of the few strides a plotted excerpt holds (issue 50: "5 of
//! 98"). The trace file carries it ([`super::trace::LegTrace::cycle`]) for `ldh report`.

use serde::{Deserialize, Serialize};

use crate::pipeline::LegResult;

/// Points of a normalised cycle: 0, 1, …, 100 % of the cycle.
pub const CYCLE_POINTS: usize = 101;

/// Resample `signal` (sampled at `fs_hz`, first sample at `t0_s`) over `[a_s, b_s]` onto `points`
/// equally spaced instants (linear interpolation between samples). `None` when the interval is
/// not inside the signal, is empty, or touches a non-finite sample, or `points < 2`.
pub fn time_normalise(
    signal: &[f64],
    t0_s: f64,
    fs_hz: f64,
    a_s: f64,
    b_s: f64,
    points: usize,
) -> Option<Vec<f64>> {
    if points < 2 || !(fs_hz > 0.0) || signal.len() < 2 || !(b_s > a_s) {
        return None;
    }
    let (ia, ib) = ((a_s - t0_s) * fs_hz, (b_s - t0_s) * fs_hz);
    let last = (signal.len() - 1) as f64;
    if !(ia >= -1e-9 && ib <= last + 1e-9) {
        return None;
    }
    (0..points)
        .map(|k| {
            let x = (ia + (ib - ia) * k as f64 / (points - 1) as f64).clamp(0.0, last);
            let i = (x.floor() as usize).min(signal.len() - 2);
            let f = x - i as f64;
            let v = signal[i] * (1.0 - f) + signal[i + 1] * f;
            v.is_finite().then_some(v)
        })
        .collect()
}

/// Mean ± SD of curves over the gait cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CycleCurve {
    /// Mean at 0, 1, …, 100 % of the cycle, deg.
    pub mean_deg: Vec<f64>,
    /// Sample SD (n − 1) at the same points, deg.
    pub sd_deg: Vec<f64>,
    /// Curves pooled (strides of one leg, or legs of a reference).
    pub n: usize,
}

impl CycleCurve {
    /// Mean ± SD of equally long curves; `None` with fewer than 2 (an SD needs two).
    pub fn of(curves: &[Vec<f64>]) -> Option<CycleCurve> {
        let n = curves.len();
        let len = curves.first()?.len();
        if n < 2 || curves.iter().any(|c| c.len() != len) {
            return None;
        }
        let mean: Vec<f64> = (0..len)
            .map(|k| curves.iter().map(|c| c[k]).sum::<f64>() / n as f64)
            .collect();
        let sd = (0..len)
            .map(|k| {
                let ss: f64 = curves.iter().map(|c| (c[k] - mean[k]).powi(2)).sum();
                (ss / (n - 1) as f64).sqrt()
            })
            .collect();
        Some(CycleCurve {
            mean_deg: mean,
            sd_deg: sd,
            n,
        })
    }

    /// Rounded to `decimals` (what a trace file stores).
    pub fn rounded(mut self, decimals: i32) -> CycleCurve {
        let f = 10f64.powi(decimals);
        for v in self.mean_deg.iter_mut().chain(self.sd_deg.iter_mut()) {
            *v = (*v * f).round() / f;
        }
        self
    }
}

/// The shank-pitch cycle of an analysed leg over all its valid strides (its attitude's pitch,
/// on the recording's clock from its first sample). `None` without the attitude (a result read
/// back from JSON) or with fewer than 2 valid strides.
pub fn pitch_cycle_of(leg: &LegResult) -> Option<CycleCurve> {
    let (sig, att) = (leg.signals.as_ref()?, leg.attitude.as_ref()?);
    let curves: Vec<Vec<f64>> = leg
        .strides
        .iter()
        .filter(|s| s.valid)
        .filter_map(|s| {
            time_normalise(
                &att.pitch_deg,
                0.0,
                sig.fs_hz,
                s.hs_time_s,
                s.next_hs_time_s,
                CYCLE_POINTS,
            )
        })
        .collect();
    CycleCurve::of(&curves)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strides_are_normalised_to_the_cycle() {
        // A ramp sampled at 10 Hz from t = 1 s: value = t.
        let sig: Vec<f64> = (0..50).map(|i| 1.0 + i as f64 / 10.0).collect();
        let c = time_normalise(&sig, 1.0, 10.0, 2.0, 3.0, 11).unwrap();
        for (k, v) in c.iter().enumerate() {
            assert!((v - (2.0 + k as f64 / 10.0)).abs() < 1e-12);
        }
        // Between samples: linear interpolation.
        let c = time_normalise(&sig, 1.0, 10.0, 2.05, 2.15, 3).unwrap();
        assert!((c[1] - 2.1).abs() < 1e-12);
        assert!(time_normalise(&sig, 1.0, 10.0, 0.5, 2.0, 11).is_none());
        assert!(time_normalise(&sig, 1.0, 10.0, 3.0, 2.0, 11).is_none());
        let curve = CycleCurve::of(&[vec![1.0, 2.0], vec![3.0, 2.0]]).unwrap();
        assert_eq!(curve.mean_deg, vec![2.0, 2.0]);
        assert!((curve.sd_deg[0] - 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(curve.sd_deg[1], 0.0);
        assert!(CycleCurve::of(&[vec![1.0]]).is_none());
        assert_eq!(
            CycleCurve::of(&[vec![1.04, 2.0], vec![1.0, 2.0]])
                .unwrap()
                .rounded(1)
                .mean_deg,
            vec![1.0, 2.0]
        );
    }
}
