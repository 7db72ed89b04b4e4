//! Double support per stride (issue 49): the time both feet are on the ground, as a share of
//! the stride. A stride of one leg, heel strike HS to the next, has two double-support
//! periods inside its stance (Perry & Burnfield 2010, *Gait Analysis: Normal and Pathological
//! Function*, 2nd ed., ch. 2; Kirtley 2006, *Clinical Gait Analysis*, ch. 1): the **initial**
//! one from its heel strike to the other leg's toe off (loading response), and the **terminal**
//! one from the other leg's heel strike to its own toe off (pre-swing). Between them the other
//! leg swings (single support):
//!
//! DS = [(TO_other − HS) + (TO − HS_other)] / stride time = stance − the other leg's swing.
//!
//! Normal walking: ≈ 0.10 + 0.10 of the cycle, 2 × stance − 1 when the legs are symmetric.
//! A stride gets a value only when its stance holds exactly one toe off and then one heel
//! strike of the other leg, in that order (the bilateral order of `pipeline::bilateral`): a
//! missed or extra event of either leg leaves it NaN rather than a wrong period.

use super::Stride;

/// Sorted copy of the finite times.
fn sorted(v: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = v.iter().copied().filter(|t| t.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    v
}

/// The times of sorted `v` strictly inside `(lo, hi)`.
fn inside(v: &[f64], lo: f64, hi: f64) -> &[f64] {
    let a = v.partition_point(|&t| t <= lo);
    let b = v.partition_point(|&t| t < hi);
    &v[a..b.max(a)]
}

/// The double support ratio of one stride from its heel strike `hs`, toe off `to` and stride
/// time `t_s`, given the other leg's sorted toe offs and heel strikes (same clock); NaN unless
/// the stance holds exactly one toe off and then one heel strike of the other leg.
fn ratio(hs: f64, to: f64, t_s: f64, other_to: &[f64], other_hs: &[f64]) -> f64 {
    if !(hs.is_finite() && to > hs && t_s > 0.0) {
        return f64::NAN;
    }
    match (inside(other_to, hs, to), inside(other_hs, hs, to)) {
        ([o_to], [o_hs]) if o_to < o_hs => ((o_to - hs) + (to - o_hs)) / t_s,
        _ => f64::NAN,
    }
}

/// Set each stride's `double_support_ratio` from the other leg's toe offs `other_to_s` and heel
/// strikes `other_hs_s` (s, on this leg's clock); NaN where they do not bound it.
pub fn double_support(strides: &mut [Stride], other_hs_s: &[f64], other_to_s: &[f64]) {
    let (o_hs, o_to) = (sorted(other_hs_s), sorted(other_to_s));
    for s in strides.iter_mut() {
        s.double_support_ratio = ratio(s.hs_time_s, s.to_time_s, s.stride_time_s, &o_to, &o_hs);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initial_plus_terminal_over_the_stride() {
        // HS 0, other TO 0.1, other HS 0.5, TO 0.62, stride 1.0: 0.1 + 0.12.
        let r = ratio(0.0, 0.62, 1.0, &[0.1, 1.1], &[-0.5, 0.5, 1.5]);
        assert!((r - 0.22).abs() < 1e-12, "{r}");
        // Symmetric gait: 2 × stance − 1.
        let r = ratio(0.0, 0.6, 1.0, &[0.1], &[0.5]);
        assert!((r - (2.0 * 0.6 - 1.0)).abs() < 1e-12, "{r}");
    }

    #[test]
    fn a_missing_or_extra_event_leaves_it_empty() {
        // No other toe off in the stance.
        assert!(ratio(0.0, 0.6, 1.0, &[], &[0.5]).is_nan());
        // Two other heel strikes (an extra one).
        assert!(ratio(0.0, 0.6, 1.0, &[0.1], &[0.3, 0.5]).is_nan());
        // The other leg lands before it leaves the ground: the order is broken.
        assert!(ratio(0.0, 0.6, 1.0, &[0.4], &[0.2]).is_nan());
        // No toe off of this stride.
        assert!(ratio(0.0, f64::NAN, 1.0, &[0.1], &[0.5]).is_nan());
    }
}
