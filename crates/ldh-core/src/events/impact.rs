//! Heel strike at the impact, where the recording shows one ([`EventParams::hs_impact`]; issue
//! 20 item 4).
//!
//! The gyroscope's heel-strike landmark, the zero crossing of the sagittal angular velocity at
//! the end of swing, comes before the contact by a delay that depends on how the shank ends its
//! swing: 0.016 of the stride on family A, about 0.023 on family B, so any fixed offset is a
//! simulator's. The contact itself shakes the shank: the heel's impact is a step in the
//! acceleration, several g against the tenths of a g of terminal swing (Selles et al. 2005,
//! IEEE TBME 52:1512; Lee et al. 2010, Med Eng Phys 32:545: heel strike from the shank
//! acceleration). On HuGaDB's shins the step is 3–4 g against 0.3 g; on family B, whose
//! soft-tissue transient starts at the true contact, 0.3–1.4 g against 0.04–0.2 g. Family A
//! models no impact.
//!
//! Per heel strike, the sample-to-sample change of the raw acceleration vector |Δa| is compared
//! with its median over terminal swing ([0.15, 0.03] of the stride before the zero crossing): the
//! largest change in the 0.12 of the stride after the zero crossing must be at least
//! [`IMPACT_RATIO`] times that median and at least [`IMPACT_MIN_G`]; the impact is the first
//! sample of the window reaching half of it (the onset of the step), and the contact is placed
//! half a sample before that sample (it lies between the two). A walk uses impacts only when at
//! least [`IMPACT_SHARE`] of its heel strikes, both legs pooled (and at least
//! [`IMPACT_MIN_STRIKES`]), show one. Every strike of both legs then lies at its zero crossing
//! plus the walk's median delay from crossing to impact: the recording's own offset in place of
//! the simulator-fitted one ([`crate::events::place_bilateral`]; a leg analysed alone uses its
//! own). Each strike's own impact is known to a sample only, where the interpolated crossing
//! keeps stride times to a fraction of a millisecond (per-strike impacts took family B's stride
//! time MAE from 0.6 to 3.6 ms); one delay for both legs keeps the step times between them
//! (decided per leg, one leg of a short walk moved and the other did not). A walk without
//! impacts keeps the gyroscope's landmark and offset (family A: 3–4 % of its strikes exceed the
//! ratio by chance, so no walk qualifies).
//!
//! The ratio and share are not fitted: they are set between what family A shows without an
//! impact (median ratio 1.7, 95th percentile 3.4) and what an impact is.

use super::Events;

/// Smallest ratio of the impact's |Δa| to the terminal swing's median |Δa|.
pub const IMPACT_RATIO: f64 = 4.0;
/// Smallest |Δa| of an impact, g (noise floor of a still sensor is ≈ 0.01 g).
pub const IMPACT_MIN_G: f64 = 0.1;
/// Smallest share of a walk's heel strikes (both legs pooled) that must show an impact for the
/// walk to use them.
pub const IMPACT_SHARE: f64 = 0.5;
/// Fewest heel strikes with an impact for a walk to use them.
pub const IMPACT_MIN_STRIKES: usize = 5;

/// The impact after the gyroscope's heel-strike landmark `zc_s` (s), or `None`: the time half a
/// sample before the first large step of the acceleration (`da[i]` = |a_i − a_(i−1)|, g).
fn impact_s(da: &[f64], fs_hz: f64, zc_s: f64, stride_s: f64) -> Option<f64> {
    let idx = |t: f64| (t * fs_hz).round();
    let (b0, b1) = (idx(zc_s - 0.15 * stride_s), idx(zc_s - 0.03 * stride_s));
    // The first change that ends after the crossing.
    let (w0, w1) = ((zc_s * fs_hz).floor() + 1.0, idx(zc_s + 0.12 * stride_s));
    if b0 < 1.0 || w1 >= da.len() as f64 || b1 <= b0 || w1 < w0 {
        return None;
    }
    let mut base: Vec<f64> = da[b0 as usize..b1 as usize].to_vec();
    let base = crate::stats::median(&mut base, crate::stats::EvenMedian::Upper).expect("b1 > b0");
    let window = &da[w0 as usize..=w1 as usize];
    let peak = window.iter().copied().fold(0.0, f64::max);
    if peak < (IMPACT_RATIO * base).max(IMPACT_MIN_G) {
        return None;
    }
    // The onset of the largest step: its first sample above half the peak.
    window
        .iter()
        .position(|&d| d >= 0.5 * peak)
        .map(|i| (w0 + i as f64 - 0.5) / fs_hz)
}

/// The delay from each heel strike's zero crossing to its impact, s (`None`: no impact found),
/// in the order of `ev.hs_s`. `acc_g`: the raw acceleration, g, on the events' clock;
/// `hs_offset_s`: the offset that was added to each zero crossing, s.
pub fn impact_delays_s(
    ev: &Events,
    acc_g: [&[f64]; 3],
    fs_hz: f64,
    hs_offset_s: f64,
) -> Vec<Option<f64>> {
    let n = acc_g.iter().map(|c| c.len()).min().unwrap_or(0);
    if n < 2 {
        return vec![None; ev.hs_s.len()];
    }
    let mut da = vec![0.0; n];
    for (i, d) in da.iter_mut().enumerate().skip(1) {
        *d = (0..3)
            .map(|k| (acc_g[k][i] - acc_g[k][i - 1]).powi(2))
            .sum::<f64>()
            .sqrt();
    }
    let t = ev.median_stride_s;
    ev.hs_s
        .iter()
        .map(|&hs| {
            let zc = hs - hs_offset_s;
            impact_s(&da, fs_hz, zc, t).map(|i| i - zc)
        })
        .collect()
}

/// Move the heel strikes of the legs of one walk (one or both) to their zero crossings plus the
/// median delay to the impact over all their strikes, when at least [`IMPACT_SHARE`] of them
/// (and [`IMPACT_MIN_STRIKES`]) show one (`ev.hs_impact_delays_s`); both legs get the same
/// delay, so the step times between them keep what the crossings measure. `hs_offset_stride`:
/// the offset that was added to each crossing, fraction of the leg's median stride. Returns
/// the delay used, s.
pub fn shift_to_impacts(legs: &mut [&mut Events], hs_offset_stride: f64) -> Option<f64> {
    let all: usize = legs.iter().map(|e| e.hs_impact_delays_s.len()).sum();
    let mut found: Vec<f64> = legs
        .iter()
        .flat_map(|e| e.hs_impact_delays_s.iter().flatten().copied())
        .collect();
    let k = found.len();
    if k < IMPACT_MIN_STRIKES || (k as f64) < IMPACT_SHARE * all as f64 {
        return None;
    }
    let typical = crate::stats::median(&mut found, crate::stats::EvenMedian::Upper).expect("k > 0");
    // Every strike at its zero crossing plus the median delay: the recording's own offset in
    // place of a simulator's. Not each strike's own impact: that is known to a sample only
    // (±5 ms at 100 Hz), where the interpolated crossing keeps stride times to a fraction of a
    // millisecond.
    for ev in legs.iter_mut() {
        let shift = typical - hs_offset_stride * ev.median_stride_s;
        for hs in ev.hs_s.iter_mut() {
            *hs += shift;
        }
    }
    Some(typical)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 10 strides of 1 s at 100 Hz: smooth swing acceleration with a step of 1 g at the
    /// contacts, 30 ms after each zero crossing at k + 0.5 s (`impacts`: which strides have one).
    fn walk(impacts: impl Fn(usize) -> bool) -> ([Vec<f64>; 3], Events) {
        let n = 1100;
        let mut acc: [Vec<f64>; 3] = Default::default();
        for i in 0..n {
            let t = i as f64 / 100.0;
            acc[0].push(0.3 * (std::f64::consts::TAU * t).sin());
            acc[1].push(0.0);
            acc[2].push(1.0);
        }
        for k in 0..10 {
            if impacts(k) {
                // Contact at k + 0.535 s: samples from 54 on ring.
                for (j, v) in [1.0, -0.8, 0.5, -0.2].iter().enumerate() {
                    acc[0][100 * k + 54 + j] += v;
                }
            }
        }
        let ev = Events {
            hs_s: (0..10).map(|k| k as f64 + 0.5 + 0.016).collect(),
            median_stride_s: 1.0,
            ..Events::default()
        };
        (acc, ev)
    }

    /// Find the impacts of one leg and place its heel strikes by them alone.
    fn place(ev: &mut Events, acc: &[Vec<f64>; 3]) -> Option<f64> {
        ev.hs_impact_delays_s = impact_delays_s(ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016);
        shift_to_impacts(&mut [ev], 0.016)
    }

    #[test]
    fn both_legs_of_a_walk_get_the_delay_of_their_pooled_impacts() {
        // Left: impacts on 4 of 10 strikes (too few alone); right: on all 10.
        let (acc_l, mut l) = walk(|k| k % 3 == 0);
        let (acc_r, mut r) = walk(|_| true);
        l.hs_impact_delays_s = impact_delays_s(&l, [&acc_l[0], &acc_l[1], &acc_l[2]], 100.0, 0.016);
        r.hs_impact_delays_s = impact_delays_s(&r, [&acc_r[0], &acc_r[1], &acc_r[2]], 100.0, 0.016);
        let d = shift_to_impacts(&mut [&mut l, &mut r], 0.016).unwrap();
        assert!((d - 0.035).abs() < 1e-9, "{d}");
        assert!((l.hs_s[1] - 1.535).abs() < 1e-9 && (r.hs_s[1] - 1.535).abs() < 1e-9);
        // Placed once: the pipeline's placement clears the delays, so a second one is a no-op.
        let p = crate::events::EventParams::default().check().unwrap();
        for e in [&mut l, &mut r] {
            e.to_landmarks_s = vec![[0.1, 0.2, 0.3]; e.to_s.len()];
        }
        crate::events::place_bilateral(Some(&mut l), Some(&mut r), &p);
        let before = l.hs_s.clone();
        crate::events::place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert_eq!(l.hs_s, before);
    }

    #[test]
    fn heel_strikes_move_to_the_impacts_of_a_leg_that_shows_them() {
        let (acc, mut ev) = walk(|k| k != 3);
        let moved = place(&mut ev, &acc);
        assert!(moved.is_some());
        // Every strike at its crossing plus the median delay (35 ms), stride 3 too.
        for (k, hs) in ev.hs_s.iter().enumerate() {
            assert!((hs - (k as f64 + 0.535)).abs() < 1e-9, "stride {k}: {hs}");
        }
    }

    #[test]
    fn a_step_far_from_the_legs_typical_delay_is_not_taken_for_the_contact() {
        let (mut acc, mut ev) = walk(|k| k != 5);
        // Stride 5: a step 100 ms after its crossing instead of 35 ms.
        for (j, v) in [1.0, -0.8, 0.5, -0.2].iter().enumerate() {
            acc[0][560 + j] += v;
        }
        place(&mut ev, &acc);
        assert!((ev.hs_s[5] - 5.535).abs() < 1e-9, "{}", ev.hs_s[5]);
    }

    #[test]
    fn an_explicit_offset_or_another_detector_turns_the_impacts_off() {
        use crate::events::{find_impacts, EventDetector, EventParams};
        let (acc, ev) = walk(|_| true);
        let a = [&acc[0][..], &acc[1][..], &acc[2][..]];
        let on = EventParams::default().check().unwrap();
        assert_eq!(find_impacts(&mut ev.clone(), a, 100.0, &on), 10);
        for p in [
            EventParams {
                hs_offset_stride: Some(0.016),
                ..EventParams::default()
            },
            EventParams {
                hs_impact: false,
                ..EventParams::default()
            },
            EventParams::default().detector(EventDetector::GyroLandmarks),
        ] {
            let mut e = ev.clone();
            assert_eq!(find_impacts(&mut e, a, 100.0, &p.check().unwrap()), 0);
            assert!(e.hs_impact_delays_s.is_empty());
        }
    }

    #[test]
    fn a_leg_without_impacts_keeps_its_gyroscope_heel_strikes() {
        // Impacts on 4 of 10 strides: fewer than half.
        let (acc, mut ev) = walk(|k| k % 3 == 0);
        let before = ev.hs_s.clone();
        assert_eq!(place(&mut ev, &acc), None);
        assert_eq!(ev.hs_s, before);
        // None at all.
        let (acc, mut ev) = walk(|_| false);
        assert_eq!(place(&mut ev, &acc), None);
    }
}
