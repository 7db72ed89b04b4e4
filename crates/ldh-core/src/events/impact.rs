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
//! largest change in the [`IMPACT_WINDOW_STRIDE`] of the stride after the zero crossing must be
//! at least [`IMPACT_RATIO`] times that median and at least [`IMPACT_MIN_G`]; the impact is
//! where |Δa|, smoothed by the zero-phase kernel [1 2 1]/4, first reaches half of its own peak
//! in the window (the onset of the step), interpolated linearly between the two changes around
//! it, plus half a sample (each change sits half-way between its two samples, and the kernel
//! leads an ideal one-sample step by half a sample: that step lands where the raw rule puts
//! it). Where the smoothed step is already under way at the window's start, the raw |Δa|'s
//! onset is kept. The smoothing (issue 49, 2026-12-02) was chosen on TRIPOD's first half of
//! each run among five thresholds, three kernels, the axial component, |Δ|a||, peaks and a
//! shrink toward the walk's median delay: the onset's scatter against OptoGait fell from 13.4
//! to 12.2 ms on the second halves (docs/accuracy.md "Heel-strike precision on TRIPOD").
//!
//! **Each strike at its own impact (issue 49).** A walk uses impacts when at least
//! [`IMPACT_SHARE`] of its heel strikes, both legs pooled (and at least
//! [`IMPACT_MIN_STRIKES`]), show one. Each strike with an impact is then placed at it: the heel
//! strike is what happens at the foot, step by step, and the delay from the crossing to the
//! landing is not constant — it grows in short and slow steps, where the shank stops rotating
//! backwards well before the heel lands (up to 120 ms on force plates). A strike without an
//! impact in such a walk keeps its zero crossing plus the walk's median delay and carries
//! a low confidence, [`NO_IMPACT_CONFIDENCE`] (docs/quality.md "Unsure events"). Until 2026-12-01 every strike of such a walk lay at its
//! crossing plus the walk's median delay: stride times then kept the interpolated crossing's
//! sub-millisecond precision on the simulators (family B: 0.6 ms against 3.6 ms with per-strike
//! impacts known to a sample), but on real walks the crossing's own scatter stayed: on TRIPOD
//! (OptoGait per footfall) 14–23 ms SD against 11–17 ms per strike, the OptoGait's own
//! 10–13 ms included (docs/accuracy.md "Event timing per dataset and condition (issue 49)").
//! The linear interpolation of the onset keeps most of the crossing's precision.
//!
//! **A strike at the crossing (2026-12-03).** Where the impact is weak against the swing's
//! own |Δa|, the smoothed change that holds the crossing already reaches half the window's
//! peak, and the onset falls on the crossing itself: the step cannot be told from the swing
//! there (family B's slow hemiparetic walker BP01: a quarter of the right leg's strikes ≈ 37 ms
//! early). The leg's other strikes say where its contact lies. A strike is **at the crossing**
//! when its onset is interpolated from the first two smoothed changes after the crossing (the
//! first of which holds the change across it) or the smoothed step is under way at the
//! window's start ([`Impact::near_crossing`]), *and* its delay is less than half the leg's
//! median delay over all its impacts; it is then placed at its crossing plus the median delay
//! of the leg's other impacts (at least [`IMPACT_MIN_STRIKES`] of them), with confidence
//! [`NO_IMPACT_CONFIDENCE`] (or lower, with two candidate landings). A leg whose strikes all
//! land near the crossing keeps them: its own delay says the contact is there. Tuned on family
//! B seed 36 (the steady-window cases), reported on TRIPOD's OptoGait: 10 of its 570 impacts
//! are at the crossing, and its heel-strike scatter narrows on every shank it touches
//! (docs/accuracy.md "Heel strikes at the crossing").
//!
//! A walk without impacts keeps the gyroscope's landmark and offset (family A: 3–4 % of its
//! strikes exceed the ratio by chance, so no walk qualifies); its strikes carry confidence
//! [`GYRO_ONLY_CONFIDENCE`].
//!
//! **Confidence of a heel strike** (`events.csv` `confidence`): with an impact,
//! 1 − ½·[`IMPACT_RATIO`] / ratio (0.5 at the smallest impact accepted, → 1 for a clear one);
//! [`TWO_CANDIDATES_CONFIDENCE`] when a second step at least as large as the first follows it
//! after a lull, [`SECOND_CANDIDATE_GAP_S`] or more later (two candidate landings: a shuffle,
//! a toe touching before the heel); [`NO_IMPACT_CONFIDENCE`] without an impact in a walk
//! that shows them, or with one at the crossing.
//!
//! The ratio and share are not fitted: they are set between what family A shows without an
//! impact (median ratio 1.7, 95th percentile 3.4) and what an impact is. The window must cover
//! the 120 ms by which the crossing can precede the
//! landing in short steps. The window stays at 0.12 of the stride (180 ms in a slow stride of
//! 1.5 s, 120 ms in a fast one of 1 s): on TRIPOD 0.20 gives the same strikes, but on family
//! A's slow walkers, which model no impact, it finds chance steps in the longer window and took
//! their HS P95 from 23 to 34 ms.

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
/// The impact is searched from the zero crossing to this fraction of the stride after it.
pub const IMPACT_WINDOW_STRIDE: f64 = 0.12;
/// A later step of at least this share of the first burst's largest |Δa|, after |Δa| fell
/// below a quarter of the window's peak, is a second candidate landing (set after TRIPOD: at
/// 0.8, with no gap, the ringing of single impacts made a quarter of its strikes unsure).
pub const SECOND_CANDIDATE_SHARE: f64 = 1.0;
/// A second candidate landing starts at least this long after the first's onset, s (the
/// ringing of one impact lasts 2–4 samples at 100–128 Hz).
pub const SECOND_CANDIDATE_GAP_S: f64 = 0.05;
/// Confidence of a heel strike with two candidate landings.
pub const TWO_CANDIDATES_CONFIDENCE: f64 = 0.2;
/// Confidence of a heel strike of a walk that shows no impacts (the gyroscope's landmark and
/// offset alone).
pub const GYRO_ONLY_CONFIDENCE: f64 = 0.5;
/// Confidence of a heel strike without an impact in a walk that shows them (at its zero
/// crossing plus the walk's median delay): low, but not withheld — on family B's normal
/// walkers such strikes lie where the impacts of the others do, and withholding them took a
/// quarter of their strides (docs/quality.md "Unsure events").
pub const NO_IMPACT_CONFIDENCE: f64 = 0.3;
/// Events whose confidence is below this are unsure: the strides they bound are withheld.
pub const MIN_EVENT_CONFIDENCE: f64 = 0.25;

/// What the acceleration shows after one heel strike's zero crossing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// Delay from the zero crossing to the impact's onset, s.
    pub delay_s: f64,
    /// The impact's |Δa| over the terminal swing's median |Δa|.
    pub ratio: f64,
    /// A second candidate landing follows ([`SECOND_CANDIDATE_SHARE`]).
    pub second_candidate: bool,
    /// The onset lies in the first two changes after the zero crossing (or the smoothed step
    /// is under way at the window's start), whose interpolation still holds the swing's own
    /// change across the crossing: the step there cannot be told from the swing (module docs,
    /// "A strike at the crossing").
    pub near_crossing: bool,
}

impl Impact {
    /// The heel strike's confidence when placed at this impact (module docs).
    pub fn confidence(&self) -> f64 {
        if self.second_candidate {
            TWO_CANDIDATES_CONFIDENCE
        } else {
            (1.0 - 0.5 * IMPACT_RATIO / self.ratio).clamp(0.5, 1.0)
        }
    }
}

/// The onset of the step in the smoothed changes `sm` ([`smooth121`]) in the window
/// `[w0, w1]`: where `sm` first reaches half its largest value there, interpolated linearly,
/// plus half a sample (the kernel's lead: an ideal one-sample step is placed where the raw
/// rule places it, half-way between its two samples), s, and the index of the first smoothed
/// change reaching the half. `None` when the smoothed step is already under way at the
/// window's start.
fn smoothed_onset_s(sm: &[f64], w0: usize, w1: usize, fs_hz: f64) -> Option<(f64, usize)> {
    let half = 0.5 * sm[w0..=w1].iter().copied().fold(0.0, f64::max);
    let i = w0 + sm[w0..=w1].iter().position(|&d| d >= half)?;
    let prev = sm[i - 1];
    if prev >= half {
        return None;
    }
    let frac = (half - prev) / (sm[i] - prev);
    Some(((i as f64 - 0.5 + frac) / fs_hz, i))
}

/// The changes `da` smoothed by the zero-phase kernel [1 2 1]/4 (the ends kept).
fn smooth121(da: &[f64]) -> Vec<f64> {
    let n = da.len();
    (0..n)
        .map(|i| {
            if i == 0 || i + 1 == n {
                da[i]
            } else {
                0.25 * da[i - 1] + 0.5 * da[i] + 0.25 * da[i + 1]
            }
        })
        .collect()
}

/// The impact after the gyroscope's heel-strike landmark `zc_s` (s), or `None` (`da[i]` =
/// |a_i − a_(i−1)|, g; `sm`: the same smoothed, [`smooth121`]).
fn impact_at(da: &[f64], sm: &[f64], fs_hz: f64, zc_s: f64, stride_s: f64) -> Option<Impact> {
    let idx = |t: f64| (t * fs_hz).round();
    let (b0, b1) = (idx(zc_s - 0.15 * stride_s), idx(zc_s - 0.03 * stride_s));
    // The first change that ends after the crossing.
    let (w0, w1) = (
        (zc_s * fs_hz).floor() + 1.0,
        idx(zc_s + IMPACT_WINDOW_STRIDE * stride_s),
    );
    if b0 < 1.0 || w1 >= da.len() as f64 || b1 <= b0 || w1 < w0 {
        return None;
    }
    let mut base: Vec<f64> = da[b0 as usize..b1 as usize].to_vec();
    let base = crate::stats::median(&mut base, crate::stats::EvenMedian::Upper).expect("b1 > b0");
    let (w0, w1) = (w0 as usize, w1 as usize);
    let window = &da[w0..=w1];
    let peak = window.iter().copied().fold(0.0, f64::max);
    if peak < (IMPACT_RATIO * base).max(IMPACT_MIN_G) {
        return None;
    }
    // The onset of the largest step: the first change reaching half the peak is the one from
    // sample i − 1 to i, so the contact lies between them; the larger that change already is,
    // the earlier in the interval (half the peak: at i; the whole peak: at i − ½).
    let half = 0.5 * peak;
    let j = window.iter().position(|&d| d >= half)?;
    let i = w0 + j;
    // A step already under way before the crossing is the swing's own deceleration, not a
    // landing (family A, which models no impact, shows it on slow walkers).
    if da[i - 1] >= half {
        return None;
    }
    let smoothed = smoothed_onset_s(sm, w0, w1, fs_hz);
    // sm[w0] holds the change across the crossing and the one before it: an onset interpolated
    // from it (index w0 + 1 or earlier), or a step already under way, is the swing's as much
    // as the contact's.
    let near_crossing = smoothed.is_none_or(|(_, i)| i <= w0 + 1);
    let onset_s = smoothed.map(|(t, _)| t).unwrap_or_else(|| {
        let prev = da[i - 1];
        let frac = if da[i] > prev {
            (half - prev) / (da[i] - prev)
        } else {
            1.0
        };
        (i as f64 - 1.0 + frac) / fs_hz
    });
    // A second candidate: after the first burst (from the onset until |Δa| falls below a
    // quarter of the burst's own largest change) and at least SECOND_CANDIDATE_GAP_S after the
    // onset, a change of at least the share of that largest one.
    let lull = window[j..].iter().position(|&d| d < 0.25 * peak);
    let second_candidate = lull.is_some_and(|l| {
        let first = window[j..j + l].iter().copied().fold(0.0, f64::max);
        let gap = j + ((SECOND_CANDIDATE_GAP_S * fs_hz).ceil() as usize).max(l);
        window
            .get(gap..)
            .is_some_and(|rest| rest.iter().any(|&d| d >= SECOND_CANDIDATE_SHARE * first))
    });
    Some(Impact {
        delay_s: onset_s - zc_s,
        ratio: peak / base.max(1e-12),
        second_candidate,
        near_crossing,
    })
}

/// The impact after each heel strike's zero crossing (`None`: no impact found), in the order
/// of `ev.hs_s`. `acc_g`: the raw acceleration, g, on the events' clock; `hs_offset_s`: the
/// offset that was added to each zero crossing, s.
pub fn impacts(
    ev: &Events,
    acc_g: [&[f64]; 3],
    fs_hz: f64,
    hs_offset_s: f64,
) -> Vec<Option<Impact>> {
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
    let sm = smooth121(&da);
    let t = ev.median_stride_s;
    ev.hs_s
        .iter()
        .map(|&hs| impact_at(&da, &sm, fs_hz, hs - hs_offset_s, t))
        .collect()
}

/// Which of one leg's impacts lie at the zero crossing rather than at the contact, and the
/// leg's delay from its other strikes, s (module docs, "A strike at the crossing"): an impact
/// [`Impact::near_crossing`] whose delay is less than half the leg's median delay (over all its
/// impacts), when at least [`IMPACT_MIN_STRIKES`] of its other impacts give that delay (their
/// median). `None` when nothing is at the crossing or too few others are left.
fn at_the_crossing(impacts: &[Option<Impact>]) -> Option<(Vec<bool>, f64)> {
    let mut all: Vec<f64> = impacts.iter().flatten().map(|i| i.delay_s).collect();
    let median = crate::stats::median(&mut all, crate::stats::EvenMedian::Upper)?;
    let at: Vec<bool> = impacts
        .iter()
        .map(|i| i.is_some_and(|i| i.near_crossing && i.delay_s < 0.5 * median))
        .collect();
    let mut others: Vec<f64> = impacts
        .iter()
        .zip(&at)
        .filter(|(_, &a)| !a)
        .filter_map(|(i, _)| i.map(|i| i.delay_s))
        .collect();
    if !at.contains(&true) || others.len() < IMPACT_MIN_STRIKES {
        return None;
    }
    let delay = crate::stats::median(&mut others, crate::stats::EvenMedian::Upper)?;
    Some((at, delay))
}

/// Place the heel strikes of the legs of one walk (one or both) by their impacts
/// (`ev.hs_impacts`), when at least [`IMPACT_SHARE`] of them (and [`IMPACT_MIN_STRIKES`]) show
/// one: each strike with an impact at it, each without at its zero crossing plus the median
/// delay over all the walk's impacts, each whose impact lies at the crossing (module docs,
/// "A strike at the crossing") at its crossing plus the leg's delay from its other strikes
/// (both with [`NO_IMPACT_CONFIDENCE`]). `hs_offset_stride`: the offset that was
/// added to each crossing, fraction of the leg's median stride. Sets each strike's confidence
/// ([`Events::hs_confidence`]). Returns the median delay, s, or `None` when the walk does not
/// use impacts (every strike then keeps its crossing and offset, with
/// [`GYRO_ONLY_CONFIDENCE`]).
pub fn shift_to_impacts(legs: &mut [&mut Events], hs_offset_stride: f64) -> Option<f64> {
    let all: usize = legs.iter().map(|e| e.hs_impacts.len()).sum();
    let mut found: Vec<f64> = legs
        .iter()
        .flat_map(|e| e.hs_impacts.iter().flatten().map(|i| i.delay_s))
        .collect();
    let k = found.len();
    if k < IMPACT_MIN_STRIKES || (k as f64) < IMPACT_SHARE * all as f64 {
        for ev in legs.iter_mut() {
            ev.hs_confidence = vec![GYRO_ONLY_CONFIDENCE; ev.hs_s.len()];
        }
        return None;
    }
    let typical = crate::stats::median(&mut found, crate::stats::EvenMedian::Upper).expect("k > 0");
    for ev in legs.iter_mut() {
        let offset = hs_offset_stride * ev.median_stride_s;
        let impacts = std::mem::take(&mut ev.hs_impacts);
        let crossing = at_the_crossing(&impacts);
        let mut conf = Vec::with_capacity(ev.hs_s.len());
        for (k, hs) in ev.hs_s.iter_mut().enumerate() {
            let zc = *hs - offset;
            let leg_delay = crossing
                .as_ref()
                .and_then(|(at, d)| at.get(k).is_some_and(|&a| a).then_some(*d));
            match (impacts.get(k).copied().flatten(), leg_delay) {
                (Some(i), Some(d)) => {
                    *hs = zc + d;
                    // Two candidate landings stay unsure.
                    conf.push(NO_IMPACT_CONFIDENCE.min(i.confidence()));
                }
                (Some(i), None) => {
                    *hs = zc + i.delay_s;
                    conf.push(i.confidence());
                }
                (None, _) => {
                    *hs = zc + typical;
                    conf.push(NO_IMPACT_CONFIDENCE);
                }
            }
        }
        ev.hs_impacts = impacts;
        ev.hs_confidence = conf;
    }
    Some(typical)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 10 strides of 1 s at 100 Hz: smooth swing acceleration with a step of 1 g at the
    /// contacts, the first change at sample 54 (35 ms after each zero crossing at k + 0.5 s;
    /// `impacts`: which strides have one).
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
                ring(&mut acc, 100 * k + 54);
            }
        }
        let ev = Events {
            hs_s: (0..10).map(|k| k as f64 + 0.5 + 0.016).collect(),
            median_stride_s: 1.0,
            ..Events::default()
        };
        (acc, ev)
    }

    /// A contact ringing from sample `at` on.
    fn ring(acc: &mut [Vec<f64>; 3], at: usize) {
        for (j, v) in [1.0, -0.8, 0.5, -0.2].iter().enumerate() {
            acc[0][at + j] += v;
        }
    }

    /// The onset of the step at sample 54: the changes 53→54 (≈ 1 g) and 54→55 (≈ 1.8 g),
    /// smoothed by [1 2 1]/4, first reach half their peak late in [53, 54] (raw: ≈ 53.9
    /// samples; smoothed, with its half-sample lead put back, ≈ 54.2).
    const ONSET_DELAY_S: f64 = 0.5419 - 0.5;

    /// Find the impacts of one leg and place its heel strikes by them alone.
    fn place(ev: &mut Events, acc: &[Vec<f64>; 3]) -> Option<f64> {
        ev.hs_impacts = impacts(ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016);
        shift_to_impacts(&mut [ev], 0.016)
    }

    #[test]
    fn each_strike_lies_at_its_own_impact_and_the_others_at_the_walks_delay() {
        // Left: impacts on 4 of 10 strikes (too few alone); right: on all 10.
        let (acc_l, mut l) = walk(|k| k % 3 == 0);
        let (acc_r, mut r) = walk(|_| true);
        l.hs_impacts = impacts(&l, [&acc_l[0], &acc_l[1], &acc_l[2]], 100.0, 0.016);
        r.hs_impacts = impacts(&r, [&acc_r[0], &acc_r[1], &acc_r[2]], 100.0, 0.016);
        let d = shift_to_impacts(&mut [&mut l, &mut r], 0.016).unwrap();
        assert!((d - ONSET_DELAY_S).abs() < 2e-3, "{d}");
        // Every strike 0.5 + the delay after its second; the left's without an impact at the
        // walk's delay with confidence 0, the others at their own with a high one.
        for ev in [&l, &r] {
            for (k, hs) in ev.hs_s.iter().enumerate() {
                assert!((hs - (k as f64 + 0.5 + d)).abs() < 2e-3, "{k}: {hs}");
            }
        }
        assert_eq!(l.hs_confidence[1], NO_IMPACT_CONFIDENCE);
        assert_eq!(l.hs_s[1], 1.5 + d);
        assert!(l.hs_confidence[0] > 0.9 && r.hs_confidence[1] > 0.9);
        // Placed once: the pipeline's placement clears the impacts, so a second one is a no-op.
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
    fn a_late_landing_is_placed_at_its_own_impact() {
        // Stride 5 (a short step): the heel lands 100 ms after its crossing instead of 35 ms.
        let (mut acc, mut ev) = walk(|k| k != 5);
        ring(&mut acc, 560);
        place(&mut ev, &acc);
        assert!((ev.hs_s[5] - 5.5 - 0.102).abs() < 2e-3, "{}", ev.hs_s[5]);
        assert!(
            (ev.hs_s[4] - 4.5 - ONSET_DELAY_S).abs() < 2e-3,
            "{}",
            ev.hs_s[4]
        );
    }

    #[test]
    fn a_strike_at_the_crossing_takes_the_legs_delay_from_its_other_strikes() {
        // Stride 3: its step starts at the first change after its crossing (sample 351, the
        // crossing at 350), where the onset cannot be told from the swing; the others' 3
        // samples later (354).
        let (mut acc, mut ev) = walk(|k| k != 3);
        ring(&mut acc, 351);
        let found = impacts(&ev, [&acc[0], &acc[1], &acc[2]], 100.0, 0.016);
        let i3 = found[3].unwrap();
        assert!(
            i3.near_crossing && i3.delay_s < 0.5 * ONSET_DELAY_S,
            "{i3:?}"
        );
        assert!(!found[4].unwrap().near_crossing);
        place(&mut ev, &acc);
        // At its crossing plus the delay of the leg's other strikes, unsure but kept.
        assert!(
            (ev.hs_s[3] - 3.5 - ONSET_DELAY_S).abs() < 2e-3,
            "{}",
            ev.hs_s[3]
        );
        assert_eq!(ev.hs_confidence[3], NO_IMPACT_CONFIDENCE);
        assert!(ev.hs_confidence[3] >= MIN_EVENT_CONFIDENCE);
        // The strikes with a clear delay keep their own impacts.
        assert!((ev.hs_s[4] - 4.5 - ONSET_DELAY_S).abs() < 2e-3);
        assert!(ev.hs_confidence[4] > 0.9);
    }

    #[test]
    fn a_leg_whose_strikes_all_land_at_the_crossing_keeps_them() {
        // Every step starts at the first change after its crossing: the leg's own delay says
        // the contact is there, so each strike stays at its impact.
        let (mut acc, mut ev) = walk(|_| false);
        for k in 0..10 {
            ring(&mut acc, 100 * k + 51);
        }
        place(&mut ev, &acc);
        for (k, hs) in ev.hs_s.iter().enumerate() {
            assert!((hs - (k as f64 + 0.5)).abs() < 0.02, "{k}: {hs}");
        }
        assert!(ev.hs_confidence.iter().all(|&c| c > 0.9));
    }

    #[test]
    fn two_candidate_landings_make_a_strike_unsure() {
        let (mut acc, mut ev) = walk(|_| true);
        // Stride 2: a second step larger than the first, 60 ms later.
        for (j, v) in [1.2, -1.0, 0.6, -0.2].iter().enumerate() {
            acc[0][260 + j] += v;
        }
        place(&mut ev, &acc);
        assert_eq!(ev.hs_confidence[2], TWO_CANDIDATES_CONFIDENCE);
        assert!(ev.hs_confidence[2] < MIN_EVENT_CONFIDENCE);
        assert!(ev.hs_confidence[3] > MIN_EVENT_CONFIDENCE);
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
            assert!(e.hs_impacts.is_empty());
        }
    }

    #[test]
    fn a_leg_without_impacts_keeps_its_gyroscope_heel_strikes() {
        // Impacts on 4 of 10 strides: fewer than half.
        let (acc, mut ev) = walk(|k| k % 3 == 0);
        let before = ev.hs_s.clone();
        assert_eq!(place(&mut ev, &acc), None);
        assert_eq!(ev.hs_s, before);
        assert!(ev.hs_confidence.iter().all(|&c| c == GYRO_ONLY_CONFIDENCE));
        // None at all.
        let (acc, mut ev) = walk(|_| false);
        assert_eq!(place(&mut ev, &acc), None);
    }
}
