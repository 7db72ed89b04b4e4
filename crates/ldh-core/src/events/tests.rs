//! Event matching and the clock-offset search: hand-made cases (ties, the tolerance's edge,
//! one-to-many candidates, empty trains) and property tests (every match within the
//! tolerance, one-to-one, mutual nearest, counts add up, a common shift changes nothing, a
//! known 0.75 s offset is found to within one sample at 100 Hz).

use proptest::prelude::*;

use super::matching::*;
use super::offset::*;
use crate::stats::agreement::{AgreementError, AgreementParams, ValidAgreementParams};

fn params(tolerance_s: f64) -> ValidAgreementParams {
    AgreementParams {
        tolerance_s,
        ..Default::default()
    }
    .check()
    .unwrap()
}

fn m(ldh: &[f64], reference: &[f64], tol: f64) -> EventMatch {
    match_events(ldh, reference, &params(tol)).unwrap()
}

#[test]
fn empty_trains_match_nothing_and_rates_are_undefined_only_where_they_divide_by_zero() {
    let e = m(&[], &[], 0.2);
    assert!(e.pairs.is_empty());
    let s = e.summary();
    assert_eq!(
        (s.recall, s.precision, s.f1, s.bias_s),
        (None, None, None, None)
    );
    let e = m(&[], &[1.0, 2.0], 0.2);
    assert_eq!(e.unmatched_reference, vec![0, 1]);
    let s = e.summary();
    assert_eq!((s.recall, s.precision, s.f1), (Some(0.0), None, Some(0.0)));
    let e = m(&[1.0], &[], 0.2);
    assert_eq!(e.unmatched_ldh, vec![0]);
    assert_eq!(e.summary().precision, Some(0.0));
}

#[test]
fn ties_go_to_the_earlier_event() {
    // equidistant (exact binary fractions): the earlier reference event wins
    let e = m(&[1.0], &[0.875, 1.125], 0.2);
    assert_eq!(e.pairs, vec![(0, 0)]);
    assert_eq!(e.unmatched_reference, vec![1]);
    // and the earlier ldh event
    let e = m(&[0.875, 1.125], &[1.0], 0.2);
    assert_eq!(e.pairs, vec![(0, 0)]);
    assert_eq!(e.unmatched_ldh, vec![1]);
    // equal times: the lower index
    let e = m(&[1.0], &[1.0, 1.0], 0.2);
    assert_eq!(e.pairs, vec![(0, 0)]);
    // two equal ldh times both have the first equal reference time nearest, and it has the
    // first ldh time nearest: one match, the duplicates stay unmatched
    let e = m(&[1.0, 1.0], &[0.5, 1.0, 1.0], 0.2);
    assert_eq!(e.pairs, vec![(0, 1)]);
    assert_eq!(e.unmatched_ldh, vec![1]);
    assert_eq!(e.unmatched_reference, vec![0, 2]);
}

#[test]
fn the_tolerance_is_inclusive_and_nothing_beyond_it_matches() {
    assert_eq!(m(&[1.0], &[1.25], 0.25).pairs, vec![(0, 0)]);
    assert!(m(&[1.0], &[1.25], 0.2).pairs.is_empty());
    assert!(m(&[1.0], &[1.2500001], 0.25).pairs.is_empty());
}

#[test]
fn of_several_candidates_only_the_mutual_nearest_pair_matches() {
    // three ldh events near one reference event: the nearest takes it, the others are false
    // positives
    let e = m(&[1.0, 1.05, 1.1], &[1.06], 0.2);
    assert_eq!(e.pairs, vec![(1, 0)]);
    assert_eq!(e.unmatched_ldh, vec![0, 2]);
    // reference 0.625 lies within the tolerance of ldh 0.5, but ldh 0.5 is taken by the
    // (tie-winning, earlier) reference 0.375; ldh 0.0 is too far from both (gaitmap's rule)
    let e = m(&[0.0, 0.5], &[0.375, 0.625], 0.2);
    assert_eq!(e.pairs, vec![(1, 0)]);
    assert_eq!(e.unmatched_ldh, vec![0]);
    assert_eq!(e.unmatched_reference, vec![1]);
}

#[test]
fn rates_and_errors_of_a_small_case() {
    let e = m(&[1.0, 2.0, 3.0, 5.0], &[1.0625, 1.9375, 3.125, 4.0], 0.2);
    assert_eq!(e.pairs, vec![(0, 0), (1, 1), (2, 2)]);
    assert_eq!(e.errors_s, vec![-0.0625, 0.0625, -0.125]);
    let s = e.summary();
    assert_eq!((s.n_ldh, s.n_reference, s.n_matched), (4, 4, 3));
    assert_eq!(
        (s.recall, s.precision, s.f1),
        (Some(0.75), Some(0.75), Some(0.75))
    );
    assert_eq!(s.bias_s, Some(-0.125 / 3.0));
    assert_eq!(s.mae_s, Some(0.25 / 3.0));
    // np.percentile([0.0625, 0.0625, 0.125], 95) = 0.11875
    assert!((s.p95_abs_s.unwrap() - 0.11875).abs() < 1e-15);
    let sd = s.sd_s.unwrap();
    let b: f64 = -0.125 / 3.0;
    let want = (((-0.0625 - b).powi(2) + (0.0625 - b).powi(2) + (-0.125 - b).powi(2)) / 2.0).sqrt();
    assert!((sd - want).abs() < 1e-15);
    // pooled over groups: every event counts once
    let groups = match_groups(
        [
            ("L", &[1.0, 2.0][..], &[1.0][..]),
            ("R", &[][..], &[4.0][..]),
        ],
        &params(0.2),
    )
    .unwrap();
    let pooled = summarize(&groups.iter().map(|g| g.1.clone()).collect::<Vec<_>>());
    assert_eq!(
        (pooled.n_ldh, pooled.n_reference, pooled.n_matched),
        (2, 2, 1)
    );
    assert_eq!(groups[0].0, "L");
}

#[test]
fn unsorted_or_non_finite_times_are_errors() {
    let p = params(0.2);
    let e = match_events(&[1.0, 0.5], &[], &p).unwrap_err();
    assert!(
        matches!(
            e,
            AgreementError::UnsortedEvents {
                index: 1,
                input: "ldh",
                ..
            }
        ),
        "{e}"
    );
    let e = match_events(&[], &[f64::NAN], &p).unwrap_err();
    assert!(matches!(e, AgreementError::NonFinite { .. }), "{e}");
    let e = estimate_clock_offset(&[(&[1.0][..], &[9.0][..])], &p).unwrap_err();
    assert!(matches!(e, AgreementError::NoOffset { .. }), "{e}");
}

#[test]
fn a_stride_periodic_train_with_extra_strides_is_flagged_ambiguous() {
    // exactly periodic reference (1 s strides), ldh sees strides 5..35 only, 0.25 s late:
    // offsets 0.25 ± whole strides match all 30 ldh events
    let reference: Vec<f64> = (0..40).map(|i| i as f64).collect();
    let ldh: Vec<f64> = (5..35).map(|i| i as f64 + 0.25).collect();
    let o = estimate_clock_offset(&[(&ldh, &reference)], &params(0.2)).unwrap();
    assert!(o.ambiguous, "{o:?}");
    assert_eq!(o.best.n_matched, 30);
    assert!((o.best.offset_s - 0.25).abs() < 1e-12, "{o:?}");
    let r = o.runner_up.unwrap();
    assert!((r.offset_s + 0.75).abs() < 1e-12, "{o:?}");
    assert_eq!(o.separation_s, 0.5);
}

/// A gait-like reference train at 100 Hz: `n` strides of period × (1 ± 3 %).
fn gait_train(seed: u64, n: usize, period: f64, start: f64) -> Vec<f64> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut t = start;
    (0..n)
        .map(|_| {
            t += period * (1.0 + rng.gen_range(-0.03..0.03));
            (t * 100.0).round() / 100.0
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn matches_are_one_to_one_mutual_nearest_within_tolerance_and_shift_invariant(
        mut a in prop::collection::vec(0i64..2000, 0..30),
        mut b in prop::collection::vec(0i64..2000, 0..30),
        shift in -1000i64..1000,
    ) {
        // times on a 1/128 s grid: every difference and shift is exact in f64
        a.sort_unstable();
        b.sort_unstable();
        let t = |v: &[i64], s: i64| v.iter().map(|x| (x + s) as f64 / 128.0).collect::<Vec<_>>();
        let (la, rb) = (t(&a, 0), t(&b, 0));
        let e = m(&la, &rb, 0.2);
        let mut used_a = vec![false; la.len()];
        let mut used_b = vec![false; rb.len()];
        for (k, &(i, j)) in e.pairs.iter().enumerate() {
            prop_assert!((la[i] - rb[j]).abs() <= 0.2);
            prop_assert_eq!(e.errors_s[k], la[i] - rb[j]);
            prop_assert!(!used_a[i] && !used_b[j], "one-to-one");
            used_a[i] = true;
            used_b[j] = true;
            // mutual nearest: nothing strictly nearer on either side
            prop_assert!(rb.iter().all(|y| (la[i] - y).abs() >= (la[i] - rb[j]).abs()));
            prop_assert!(la.iter().all(|x| (x - rb[j]).abs() >= (la[i] - rb[j]).abs()));
        }
        prop_assert_eq!(e.pairs.len() + e.unmatched_ldh.len(), la.len());
        prop_assert_eq!(e.pairs.len() + e.unmatched_reference.len(), rb.len());
        prop_assert!(e.unmatched_ldh.iter().all(|&i| !used_a[i]));
        prop_assert!(e.unmatched_reference.iter().all(|&j| !used_b[j]));
        let shifted = m(&t(&a, shift), &t(&b, shift), 0.2);
        prop_assert_eq!(&shifted.pairs, &e.pairs);
        prop_assert_eq!(&shifted.unmatched_ldh, &e.unmatched_ldh);
        prop_assert_eq!(&shifted.unmatched_reference, &e.unmatched_reference);
        let s = e.summary();
        if let Some(r) = s.recall {
            prop_assert!((0.0..=1.0).contains(&r));
        }
    }

    #[test]
    fn a_clock_offset_of_0_75_s_is_found_within_one_sample_at_100_hz(
        seed in 0u64..10_000,
        n in 15usize..60,
        period in 0.9f64..1.4,
        jitter in prop::collection::vec(-1i32..=1, 60),
    ) {
        // two legs half a stride apart; ldh events 0.75 s late, each off by up to one sample
        let left = gait_train(seed, n, period, 0.3);
        let right: Vec<f64> = left.iter().map(|t| ((t + period / 2.0) * 100.0).round() / 100.0).collect();
        let late = |v: &[f64]| -> Vec<f64> {
            v.iter().zip(&jitter).map(|(t, j)| t + 0.75 + *j as f64 * 0.01).collect()
        };
        let (l_ldh, r_ldh) = (late(&left), late(&right));
        let p = ValidAgreementParams::default();
        let o = estimate_clock_offset(&[(&l_ldh, &left), (&r_ldh, &right)], &p).unwrap();
        prop_assert!((o.best.offset_s - 0.75).abs() <= 0.01 + 1e-9, "{:?}", o);
        prop_assert!(!o.ambiguous, "{:?}", o);
        prop_assert_eq!(o.best.n_matched, 2 * n);
        // removing it matches every event
        let fixed: Vec<f64> = l_ldh.iter().map(|t| t - o.best.offset_s).collect();
        let e = match_events(&fixed, &left, &p).unwrap();
        prop_assert_eq!(e.pairs.len(), n);
    }
}
