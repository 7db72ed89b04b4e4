//! The two legs' walking spans paired, and the drift between the two sensors' clocks.
//!
//! Each sensor keeps its own clock; over days two clocks part by tens of ppm (up to half a
//! minute a week). A span of one leg is paired with the span of the other leg whose activity
//! envelope (the gyroscope magnitude smoothed over 1 s, `monitor::leg::envelope`) it matches
//! best: the cross-correlation of the envelopes over offsets within `max_offset_s`, first on a
//! 0.5 s grid, then refined at 0.05 s with a parabola through the peak. The offsets of all
//! pairs (right clock − left clock at the left time) are fitted by a line — Theil–Sen (robust
//! to a mispaired span), then least squares on the pairs within `offset_outlier_s` of it — whose
//! slope is the drift (ppm; s a day) and whose value at each bout places the right leg on the
//! left leg's clock for the gait pipeline: step time and its asymmetry need the two legs'
//! heel strikes on one clock.

use serde::{Deserialize, Serialize};

use super::leg::{LegSpan, ENVELOPE_HZ};

/// The clock of the right sensor against the left: `right_s = left_s + offset_s + slope · left_s`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct ClockDrift {
    /// Offset at left time 0, s.
    pub offset_s: f64,
    /// Drift, s per s (× 10⁶: ppm).
    pub slope: f64,
    /// Pairs the line was fitted on.
    pub pairs: usize,
}

impl ClockDrift {
    /// The offset (right − left) at left time `t_s`.
    pub fn at(&self, t_s: f64) -> f64 {
        self.offset_s + self.slope * t_s
    }
    /// Drift in ppm.
    pub fn ppm(&self) -> f64 {
        self.slope * 1e6
    }
    /// Drift in s per day.
    pub fn s_per_day(&self) -> f64 {
        self.slope * 86_400.0
    }
}

/// One bout to analyse: a left span, a right span, or both, and the offset between them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plan {
    /// Index into the left spans.
    pub left: Option<usize>,
    /// Index into the right spans.
    pub right: Option<usize>,
    /// Right − left clock at this bout, s.
    pub offset_s: f64,
}

/// Pearson correlation of the envelopes at offset `o` (right = left + o), every `step`-th bin.
fn corr_at(l: &LegSpan, r: &LegSpan, o: f64, step: usize) -> Option<f64> {
    let (le, re) = (&l.envelope, &r.envelope);
    let shift = (l.at.t0_s + o - r.at.t0_s) * ENVELOPE_HZ;
    let (mut sx, mut sy, mut sxx, mut syy, mut sxy, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let mut i = 0;
    while i < le.len() {
        let j = i as f64 + shift;
        if j >= 0.0 && (j as usize) + 1 < re.len() {
            let j0 = j.floor() as usize;
            let f = j - j0 as f64;
            let y = f64::from(re[j0]) * (1.0 - f) + f64::from(re[j0 + 1]) * f;
            let x = f64::from(le[i]);
            sx += x;
            sy += y;
            sxx += x * x;
            syy += y * y;
            sxy += x * y;
            n += 1.0;
        }
        i += step;
    }
    // At least 3 s of overlap.
    if n * step as f64 / ENVELOPE_HZ < 3.0 {
        return None;
    }
    let cov = sxy / n - sx / n * sy / n;
    let vx = sxx / n - (sx / n).powi(2);
    let vy = syy / n - (sy / n).powi(2);
    (vx > 0.0 && vy > 0.0).then(|| cov / (vx * vy).sqrt())
}

/// The best offset of `r` against `l` within `centre ± radius`, and its correlation.
pub fn best_offset(l: &LegSpan, r: &LegSpan, centre: f64, radius: f64) -> Option<(f64, f64)> {
    let coarse = 0.5;
    let k = (radius / coarse).ceil() as i64;
    let mut best: Option<(f64, f64)> = None;
    for m in -k..=k {
        let o = centre + m as f64 * coarse;
        if let Some(c) = corr_at(l, r, o, 5) {
            if best.is_none_or(|b| c > b.1) {
                best = Some((o, c));
            }
        }
    }
    let (o0, _) = best?;
    let fine = 1.0 / ENVELOPE_HZ;
    let mut fb: Option<(f64, f64)> = None;
    let mut vals = Vec::new();
    for m in -12i64..=12 {
        let o = o0 + m as f64 * fine;
        let c = corr_at(l, r, o, 1);
        vals.push(c);
        if let Some(c) = c {
            if fb.is_none_or(|b| c > b.1) {
                fb = Some((o, c));
            }
        }
    }
    let (o, c) = fb?;
    // Parabolic refinement through the neighbours of the peak.
    let i = ((o - o0) / fine).round() as i64 + 12;
    if i > 0 && (i as usize) + 1 < vals.len() {
        if let (Some(a), Some(b)) = (vals[i as usize - 1], vals[i as usize + 1]) {
            let d = a - 2.0 * c + b;
            if d < 0.0 {
                let shift = 0.5 * (a - b) / d;
                return Some((o + shift.clamp(-0.5, 0.5) * fine, c));
            }
        }
    }
    Some((o, c))
}

fn overlaps(l: &LegSpan, r: &LegSpan, o: f64, slack: f64) -> bool {
    r.walk_s.0 - o < l.walk_s.1 + slack && r.walk_s.1 - o > l.walk_s.0 - slack
}

/// Pair the spans and fit the drift (`min_corr`: least envelope correlation of a pair).
pub fn pair_spans(
    left: &[LegSpan],
    right: &[LegSpan],
    max_offset_s: f64,
    outlier_s: f64,
    min_corr: f64,
) -> (Vec<Plan>, ClockDrift) {
    // First pass: each left span's best right span anywhere within the search range.
    let search = |centre: &dyn Fn(f64) -> f64, radius: f64| -> Vec<Option<(usize, f64, f64)>> {
        left.iter()
            .map(|l| {
                let c = centre(l.walk_s.0);
                right
                    .iter()
                    .enumerate()
                    .filter(|(_, r)| overlaps(l, r, c, radius))
                    .filter_map(|(j, r)| best_offset(l, r, c, radius).map(|(o, s)| (j, o, s)))
                    .filter(|m| m.2 >= min_corr)
                    .max_by(|a, b| a.2.total_cmp(&b.2))
            })
            .collect()
    };
    let first = search(&|_| 0.0, max_offset_s);
    let pts: Vec<(f64, f64)> = first
        .iter()
        .zip(left)
        .filter_map(|(m, l)| m.map(|(_, o, _)| (l.walk_s.0, o)))
        .collect();
    let drift = fit_line(&pts, outlier_s);
    // Second pass: around the line, so a mispaired span is searched again near it.
    let second = search(&|t| drift.at(t), outlier_s.max(1.0));
    let pts: Vec<(f64, f64)> = second
        .iter()
        .zip(left)
        .filter_map(|(m, l)| m.map(|(_, o, _)| (l.walk_s.0, o)))
        .collect();
    let drift = if pts.len() >= 2 {
        fit_line(&pts, outlier_s)
    } else {
        drift
    };
    let drift = refine_by_phase(left, right, &second, drift, outlier_s);
    let mut used = vec![false; right.len()];
    let mut plans = Vec::new();
    for (i, (m, l)) in second.iter().zip(left).enumerate() {
        let right_j = m.and_then(|(j, _, _)| (!used[j]).then_some(j));
        if let Some(j) = right_j {
            used[j] = true;
        }
        plans.push(Plan {
            left: Some(i),
            right: right_j,
            offset_s: drift.at(l.walk_s.0),
        });
    }
    for (j, r) in right.iter().enumerate().filter(|(j, _)| !used[*j]) {
        let t_left = r.walk_s.0 - drift.at(r.walk_s.0);
        plans.push(Plan {
            left: None,
            right: Some(j),
            offset_s: drift.at(t_left),
        });
    }
    (plans, drift)
}

/// The phase of the right leg's mid-swings against the left's in a pair: the median of
/// (right mid-swing − left mid-swing) for each left mid-swing's right mid-swing nearest half
/// a stride later at the rough offset `o` — the offset plus half a stride plus the walk's own
/// step asymmetry, measured to a few ms.
fn phase(l: &LegSpan, r: &LegSpan, o: f64) -> Option<f64> {
    let ml = &l.midswing_s;
    let mr = &r.midswing_s;
    if ml.len() < 4 || mr.len() < 4 {
        return None;
    }
    let mut periods: Vec<f64> = ml.windows(2).map(|w| w[1] - w[0]).collect();
    let t = crate::stats::median(&mut periods, crate::stats::EvenMedian::Mean)?;
    let mut d: Vec<f64> = ml
        .iter()
        .filter_map(|&a| {
            let want = a + o + 0.5 * t;
            let j = mr.partition_point(|&b| b < want);
            let c = [j.checked_sub(1).map(|k| mr[k]), mr.get(j).copied()];
            c.into_iter()
                .flatten()
                .min_by(|x, y| (x - want).abs().total_cmp(&(y - want).abs()))
                .filter(|b| (b - want).abs() < 0.25 * t)
                .map(|b| b - a - 0.5 * t)
        })
        .collect();
    if d.len() < 3 {
        return None;
    }
    crate::stats::median(&mut d, crate::stats::EvenMedian::Mean)
}

/// The drift's slope from the pairs' mid-swing phases (precise, but carrying the walker's
/// step asymmetry, constant over the days), its level from the envelopes (free of that
/// asymmetry): the line through the median of `envelope offset − slope · t`.
fn refine_by_phase(
    left: &[LegSpan],
    right: &[LegSpan],
    pairs: &[Option<(usize, f64, f64)>],
    drift: ClockDrift,
    outlier_s: f64,
) -> ClockDrift {
    let mut ph = Vec::new();
    let mut env = Vec::new();
    for (l, m) in left.iter().zip(pairs) {
        let Some((j, o_env, _)) = *m else { continue };
        env.push((l.walk_s.0, o_env));
        if let Some(x) = phase(l, &right[j], drift.at(l.walk_s.0)) {
            // Phase offsets are unwrapped near the envelope's line.
            if (x - drift.at(l.walk_s.0)).abs() < 0.6 {
                ph.push((l.walk_s.0, x));
            }
        }
    }
    if ph.len() < 2 {
        return drift;
    }
    let slope_fit = fit_line(&ph, outlier_s.min(0.2));
    let mut level: Vec<f64> = env.iter().map(|(t, o)| o - slope_fit.slope * t).collect();
    let offset_s =
        crate::stats::median(&mut level, crate::stats::EvenMedian::Mean).unwrap_or(drift.offset_s);
    ClockDrift {
        offset_s,
        slope: slope_fit.slope,
        pairs: slope_fit.pairs,
    }
}

/// Theil–Sen, then least squares on the points within `outlier_s` of it.
pub fn fit_line(pts: &[(f64, f64)], outlier_s: f64) -> ClockDrift {
    use crate::stats::{median, EvenMedian};
    match pts.len() {
        0 => return ClockDrift::default(),
        1 => {
            return ClockDrift {
                offset_s: pts[0].1,
                slope: 0.0,
                pairs: 1,
            }
        }
        _ => {}
    }
    // At most 600 points (every k-th) keep the pairwise slopes cheap.
    let k = pts.len().div_ceil(600);
    let sub: Vec<(f64, f64)> = pts.iter().step_by(k).copied().collect();
    let mut slopes = Vec::new();
    for a in 0..sub.len() {
        for b in a + 1..sub.len() {
            let dt = sub[b].0 - sub[a].0;
            if dt.abs() > 60.0 {
                slopes.push((sub[b].1 - sub[a].1) / dt);
            }
        }
    }
    let slope = median(&mut slopes, EvenMedian::Mean).unwrap_or(0.0);
    let mut res: Vec<f64> = pts.iter().map(|(t, o)| o - slope * t).collect();
    let icpt = median(&mut res, EvenMedian::Mean).unwrap_or(0.0);
    let inl: Vec<&(f64, f64)> = pts
        .iter()
        .filter(|(t, o)| (o - icpt - slope * t).abs() <= outlier_s)
        .collect();
    let n = inl.len() as f64;
    if inl.len() < 3 {
        return ClockDrift {
            offset_s: icpt,
            slope,
            pairs: inl.len(),
        };
    }
    let mt = inl.iter().map(|p| p.0).sum::<f64>() / n;
    let mo = inl.iter().map(|p| p.1).sum::<f64>() / n;
    let stt: f64 = inl.iter().map(|p| (p.0 - mt).powi(2)).sum();
    let sto: f64 = inl.iter().map(|p| (p.0 - mt) * (p.1 - mo)).sum();
    let slope = if stt > 3600.0 * 3600.0 {
        sto / stt
    } else {
        0.0
    };
    ClockDrift {
        offset_s: mo - slope * mt,
        slope,
        pairs: inl.len(),
    }
}
