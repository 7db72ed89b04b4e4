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
//! half a sample before that sample (it lies between the two). A leg uses impacts only when at
//! least [`IMPACT_SHARE`] of its heel strikes (and at least [`IMPACT_MIN_STRIKES`]) show one.
//! Every strike of the leg then lies at its zero crossing plus the leg's median delay from
//! crossing to impact: the recording's own offset in place of the simulator-fitted one. Each
//! strike's own impact is known to a sample only, where the interpolated crossing keeps stride
//! times to a fraction of a millisecond (per-strike impacts took family B's stride time MAE
//! from 0.6 to 3.6 ms). A leg without impacts keeps the gyroscope's landmark and offset (family
//! A: 3–4 % of its strikes exceed the ratio by chance, so no leg qualifies).
//!
//! The ratio and share are not fitted: they are set between what family A shows without an
//! impact (median ratio 1.7, 95th percentile 3.4) and what an impact is.

use super::Events;

/// Smallest ratio of the impact's |Δa| to the terminal swing's median |Δa|.
pub const IMPACT_RATIO: f64 = 4.0;
/// Smallest |Δa| of an impact, g (noise floor of a still sensor is ≈ 0.01 g).
pub const IMPACT_MIN_G: f64 = 0.1;
/// Smallest share of a leg's heel strikes that must show an impact for the leg to use them.
pub const IMPACT_SHARE: f64 = 0.5;
/// Fewest heel strikes with an impact for a leg to use them.
pub const IMPACT_MIN_STRIKES: usize = 5;

/// The impact after the gyroscope's heel-strike landmark `zc_s` (s), or `None`: the time half a
/// sample before the first large step of the acceleration (`da[i]` = |a_i − a_(i−1)|, g).
fn impact_s(da: &[f64], fs_hz: f64, zc_s: f64, stride_s: f64) -> Option<f64> {
    let idx = |t: f64| (t * fs_hz).round();
    let (b0, b1) = (idx(zc_s - 0.15 * stride_s), idx(zc_s - 0.03 * stride_s));
    let (w0, w1) = (idx(zc_s), idx(zc_s + 0.12 * stride_s));
    if b0 < 1.0 || w1 >= da.len() as f64 || b1 <= b0 {
        return None;
    }
    let mut base: Vec<f64> = da[b0 as usize..b1 as usize].to_vec();
    base.sort_by(f64::total_cmp);
    let base = base[base.len() / 2];
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

/// Move a leg's heel strikes to their impacts when the leg shows impacts (see the module docs).
/// `acc_g`: the raw acceleration, g, on the events' clock; `hs_offset_s`: the offset that was
/// added to each zero crossing (s). Returns how many heel strikes moved.
pub fn heel_strikes_at_impacts(
    ev: &mut Events,
    acc_g: [&[f64]; 3],
    fs_hz: f64,
    hs_offset_s: f64,
) -> usize {
    let n = acc_g.iter().map(|c| c.len()).min().unwrap_or(0);
    if n < 2 || ev.hs_s.is_empty() {
        return 0;
    }
    let mut da = vec![0.0; n];
    for (i, d) in da.iter_mut().enumerate().skip(1) {
        *d = (0..3)
            .map(|k| (acc_g[k][i] - acc_g[k][i - 1]).powi(2))
            .sum::<f64>()
            .sqrt();
    }
    let t = ev.median_stride_s;
    // The delay from each zero crossing to its impact, s.
    let delays: Vec<Option<f64>> = ev
        .hs_s
        .iter()
        .map(|&hs| {
            let zc = hs - hs_offset_s;
            impact_s(&da, fs_hz, zc, t).map(|i| i - zc)
        })
        .collect();
    let mut found: Vec<f64> = delays.iter().flatten().copied().collect();
    let k = found.len();
    if k < IMPACT_MIN_STRIKES || (k as f64) < IMPACT_SHARE * delays.len() as f64 {
        return 0;
    }
    found.sort_by(f64::total_cmp);
    let typical = found[k / 2];
    // Every strike at its zero crossing plus the leg's median delay: the recording's own offset
    // in place of a simulator's. Not each strike's own impact: that is known to a sample only
    // (±5 ms at 100 Hz), where the interpolated crossing keeps stride times to a fraction of
    // a millisecond.
    for hs in ev.hs_s.iter_mut() {
        *hs += typical - hs_offset_s;
    }
    k
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

    #[test]
    fn heel_strikes_move_to_the_impacts_of_a_leg_that_shows_them() {
        let (acc, mut ev) = walk(|k| k != 3);
        let moved = heel_strikes_at_impacts(&mut ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016);
        assert_eq!(moved, 9);
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
        heel_strikes_at_impacts(&mut ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016);
        assert!((ev.hs_s[5] - 5.535).abs() < 1e-9, "{}", ev.hs_s[5]);
    }

    #[test]
    fn a_leg_without_impacts_keeps_its_gyroscope_heel_strikes() {
        // Impacts on 4 of 10 strides: fewer than half.
        let (acc, mut ev) = walk(|k| k % 3 == 0);
        let before = ev.hs_s.clone();
        let moved = heel_strikes_at_impacts(&mut ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016);
        assert_eq!(moved, 0);
        assert_eq!(ev.hs_s, before);
        // None at all.
        let (acc, mut ev) = walk(|_| false);
        assert_eq!(
            heel_strikes_at_impacts(&mut ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016),
            0
        );
    }
}
