use ldh_core::domain::Parameter;
use ldh_core::pipeline::*;
use ldh_core::recording::Side;
use ldh_sim::{analyze_simulated, CohortParams};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]
    /// Detected events alternate HS/TO and increase, on any simulated subject, except where a
    /// toe off was not found: that stride is withheld with the reason "no toe off".
    #[test]
    fn events_alternate_and_increase(seed in 0u64..10_000, ldh in any::<bool>()) {
        let c = CohortParams { healthy: usize::from(!ldh), ldh: usize::from(ldh), duration_s: 20.0, seed, ..CohortParams::default() };
        let r = analyze_simulated(&c.simulate(0).unwrap(), &AnalysisParams { compute_sta: false, ..AnalysisParams::default() });
        for (_, leg) in r.legs() {
            let leg = leg.as_ref().unwrap();
            let mut ev: Vec<(f64, u8)> = leg.events.hs_s.iter().map(|&t| (t, 0)).chain(leg.events.to_s.iter().map(|&t| (t, 1))).collect();
            ev.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
            prop_assert!(ev.len() >= 16);
            for w in ev.windows(2) {
                prop_assert!(w[1].0 > w[0].0);
                // A toe off missed (in a turn, seed 8918) leaves two heel strikes in a row: the
                // stride between them is withheld and says so; never two toe offs in a row.
                let missed_to = w[0].1 == 0 && w[1].1 == 0 && leg.strides.iter().any(|s| {
                    s.hs_time_s == w[0].0 && !s.valid && s.reason.contains("no toe off")
                });
                prop_assert!(w[0].1 != w[1].1 || missed_to, "two {} in a row at {} s", if w[0].1 == 0 { "HS" } else { "TO" }, w[1].0);
            }
            for s in &leg.strides {
                prop_assert!(s.hs_time_s < s.to_time_s || !s.to_time_s.is_finite());
                // Invalid strides say why; a valid one may only say why its length is withheld.
                prop_assert!(s.valid || !s.reason.is_empty());
                prop_assert!(!s.valid || s.reason.split("; ").all(|r| r.is_empty() || r.starts_with("stride length")), "{}", s.reason);
                prop_assert!(!s.valid || s.reason.is_empty() == s.stride_length_m.is_finite());
            }
        }
    }
}

#[test]
fn bilateral_sequence_alternates_in_steady_walking() {
    let c = CohortParams {
        healthy: 0,
        ldh: 1,
        duration_s: 30.0,
        seed: 5,
        turn: false,
        ..CohortParams::default()
    };
    let r = analyze_simulated(
        &c.simulate(0).unwrap(),
        &AnalysisParams {
            compute_sta: false,
            ..AnalysisParams::default()
        },
    );
    let seq = r.bilateral_events();
    assert!(seq.len() > 60);
    let breaks: Vec<&BilateralEvent> = seq.iter().filter(|e| !e.order.is_empty()).collect();
    // Only where gait starts (the first leg's TO has no HS before it) may it break.
    assert!(breaks.len() <= 2, "{breaks:?}");
    assert!(
        seq.iter()
            .filter(|e| e.event == EventKind::HeelStrike)
            .count()
            > 30
    );
    // With one leg, every TO lacks the other leg's HS before it.
    let one = bilateral_events(r.left.as_ref().ok().map(|l| &l.events), None);
    assert!(one
        .iter()
        .skip(1)
        .filter(|e| e.event == EventKind::ToeOff)
        .all(|e| e.order.contains("expected right HS")));
}

/// Family B subject analysed end to end, scored against its truth: (matched HS errors s,
/// reported stride length errors (fraction), strides flagged turning, valid strides) per leg.
fn family_b_case(
    speed: f64,
    setting: ldh_core::Setting,
    seed: u64,
) -> Vec<(Vec<f64>, Vec<f64>, usize, usize)> {
    use ldh_sim::family_b::CohortParamsB;
    let c = CohortParamsB {
        healthy: 0,
        patients: 1,
        seed,
        duration_s: 45.0,
        speed_mps: Some(speed),
        setting: Some(setting),
        ..CohortParamsB::default()
    };
    let s = c.simulate(0).unwrap();
    let r = analyze_simulated(
        &s,
        &AnalysisParams {
            compute_sta: false,
            ..AnalysisParams::default()
        },
    );
    let t = s.truth();
    let mut out = Vec::new();
    for (leg, tr) in [(&r.left, &t.left), (&r.right, &t.right)] {
        let leg = leg.as_ref().unwrap();
        let (mut hs, mut sl) = (vec![], vec![]);
        for ts in tr.strides.iter().filter(|s| !s.turning && !s.bout_edge) {
            if let Some(d) = leg
                .events
                .hs_s
                .iter()
                .find(|d| (*d - ts.hs_time_s).abs() < 0.25)
            {
                hs.push(d - ts.hs_time_s);
            }
            if let Some(st) = leg.strides.iter().find(|x| {
                x.valid
                    && (x.hs_time_s - ts.hs_time_s).abs() < 0.25
                    && x.stride_length_m.is_finite()
            }) {
                sl.push(st.stride_length_m / ts.stride_length_m - 1.0);
            }
        }
        let turning = leg
            .strides
            .iter()
            .filter(|s| s.reason.contains("turning"))
            .count();
        let valid = leg.strides.iter().filter(|s| s.valid).count();
        out.push((hs, sl, turning, valid));
    }
    out
}

/// Slow hemiparetic gait at 0.3 m/s (strides ≈ 2 s, mid-swing well under 100 deg/s): both legs
/// find their strides, heel strikes within 40 ms, no reported stride length more than 15 % off.
/// On this seed 8 of the affected leg's 11 valid strides fail the velocity-drift check, so its
/// 3 survivors are withheld too (`gait::MIN_LENGTH_SHARE`); the other leg reports its lengths.
#[test]
fn slow_gait_at_0_3_mps_against_truth() {
    let legs = family_b_case(0.3, ldh_core::Setting::Overground, 31);
    for (hs, sl, _, valid) in &legs {
        assert!(*valid >= 4, "valid strides {valid}");
        assert!(hs.len() >= 4);
        assert!(hs.iter().all(|e| e.abs() < 0.04), "{hs:?}");
        assert!(sl.iter().all(|e| e.abs() < 0.15), "{sl:?}");
    }
    assert!(
        legs.iter().any(|(_, sl, _, _)| sl.len() >= 4),
        "no leg reports its stride length"
    );
}

/// Treadmill walking: no stride is a turn, lengths on the belt within 15 % when reported, and
/// reported on at least one leg. On this seed the right leg's velocity drift (family B's gyro
/// bias and scale faults) grows to 0.56-0.72 m/s mid-walk: 14 of its 25 valid strides fail the
/// 0.6 m/s check, so its 11 survivors are withheld too (`gait::MIN_LENGTH_SHARE`). Before the
/// stride length integrated the heel-strike decelerations the outlier rule used to interpolate
/// (docs/accuracy.md "Stride length of slow walkers on family A"), 13 of 25 passed, their
/// lengths 1-5 % short where the impact had been cut.
#[test]
fn treadmill_walk_has_no_turns_against_truth() {
    let legs = family_b_case(0.9, ldh_core::Setting::Treadmill, 32);
    for (hs, sl, turning, valid) in &legs {
        assert_eq!(*turning, 0);
        assert!(*valid >= 8, "valid strides {valid}");
        assert!(hs.iter().all(|e| e.abs() < 0.04), "{hs:?}");
        assert!(sl.iter().all(|e| e.abs() < 0.15), "{sl:?}");
    }
    assert!(
        legs.iter().any(|(_, sl, _, _)| sl.len() >= 4),
        "no leg reports its stride length"
    );
}

/// Family A's slow walkers (issue 20): long stances (0.67-0.72) and a small spread of |a|, so
/// the paper's 3-SD outlier rule flags 7-11 samples of every heel strike's deceleration. When
/// the stride length integrated the interpolated acceleration, S06 of seed 200 (right leg,
/// stance ≈ 0.70, strides of 0.6 m) reported strides 16-25 % short as valid, S03 18 %
/// (docs/accuracy.md "Stride length of slow walkers on family A"). Every reported steady
/// stride must be within 15 % of the truth, and most must be reported.
#[test]
fn slow_long_stance_walkers_report_no_stride_length_more_than_15_percent_off() {
    for j in [2usize, 5] {
        let c = CohortParams {
            healthy: 0,
            ldh: 0,
            slow_ldh: j + 1,
            duration_s: 30.0,
            seed: 200,
            ..CohortParams::default()
        };
        let s = c.simulate(j).unwrap();
        let r = analyze_simulated(
            &s,
            &AnalysisParams {
                compute_sta: false,
                ..AnalysisParams::default()
            },
        );
        let t = s.truth();
        for (leg, tr) in [(&r.left, &t.left), (&r.right, &t.right)] {
            let leg = leg.as_ref().unwrap();
            let steady: Vec<_> = tr
                .strides
                .iter()
                .filter(|s| !s.turning && !s.bout_edge)
                .collect();
            let errs: Vec<f64> = steady
                .iter()
                .filter_map(|ts| {
                    leg.strides
                        .iter()
                        .find(|x| x.valid && (x.hs_time_s - ts.hs_time_s).abs() < 0.25)
                        .filter(|x| x.stride_length_m.is_finite())
                        .map(|x| x.stride_length_m / ts.stride_length_m - 1.0)
                })
                .collect();
            let id = &s.params.subject_id;
            assert!(
                errs.iter().all(|e| e.abs() < 0.15),
                "{id} {:?}: {errs:?}",
                tr.side
            );
            assert!(
                2 * errs.len() >= steady.len(),
                "{id} {:?}: {} of {} steady strides reported",
                tr.side,
                errs.len(),
                steady.len()
            );
        }
    }
}

/// Stride length variability that no other leg can check is withheld, saying why, in every
/// case of `check_length_variability` (family A, 30 s: its SV is reported when checked).
#[test]
fn stride_length_variability_unchecked_is_withheld_with_its_reason() {
    use ldh_core::pipeline::quality::{check_length_variability, codes};
    let c = CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 30.0,
        seed: 4,
        ..CohortParams::default()
    };
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let r = analyze_simulated(&c.simulate(0).unwrap(), &params);
    let (l0, r0) = (r.left.clone().unwrap(), r.right.clone().unwrap());
    let code = |leg: &LegResult| {
        leg.warnings
            .iter()
            .find(|w| w.code == codes::SV_UNCHECKED)
            .map(|w| w.message.clone())
    };
    // both legs, enough pairs: checked, reported
    assert!(l0.parameters[Parameter::StrideLengthCv].is_finite() && code(&l0).is_none());
    let withheld = |leg: &LegResult, why: &str| {
        assert!(leg.parameters[Parameter::StrideLengthCv].is_nan(), "{why}");
        assert!(leg
            .parameters
            .withheld
            .reason(ldh_core::domain::Parameter::StrideLengthCv)
            .is_some());
        let m = code(leg).unwrap_or_default();
        assert!(m.contains(why), "{m}");
    };
    // the other leg not analysed
    let mut l = l0.clone();
    check_length_variability(Some(&mut l), None);
    withheld(&l, "the right leg was not analysed");
    // the other leg without an SV
    let (mut l, mut r) = (l0.clone(), r0.clone());
    r.parameters[Parameter::StrideLengthCv] = f64::NAN;
    check_length_variability(Some(&mut l), Some(&mut r));
    withheld(&l, "the right leg reports no stride length variability");
    assert!(code(&r).is_none());
    // no stride pairs up: the right leg's walk an hour later
    let (mut l, mut r) = (l0.clone(), r0.clone());
    r.t0_s += 3600.0;
    check_length_variability(Some(&mut l), Some(&mut r));
    withheld(&l, "no stride of one leg pairs up");
    withheld(&r, "no stride of one leg pairs up");
    // a few pairs (a short walk): too few to check the noise, withheld on both legs
    let (mut l, mut r) = (l0.clone(), r0.clone());
    l.strides.truncate(5);
    r.strides.truncate(5);
    check_length_variability(Some(&mut l), Some(&mut r));
    for leg in [&l, &r] {
        withheld(
            leg,
            "of one leg pair up with the other leg's (5 needed each way)",
        );
        let why = leg
            .parameters
            .withheld
            .reason(ldh_core::domain::Parameter::StrideLengthCv)
            .unwrap();
        assert!(why.contains("too few strides"), "{why}");
    }
}

/// Heel-strike and toe-off errors (s) of the steady strides of a family B cohort of normal
/// walkers analysed with `detector`.
fn family_b_event_errors(
    healthy: usize,
    seed: u64,
    detector: ldh_core::events::EventDetector,
) -> (Vec<f64>, Vec<f64>) {
    use ldh_sim::family_b::CohortParamsB;
    let c = CohortParamsB {
        healthy,
        patients: 0,
        seed,
        ..CohortParamsB::default()
    };
    let mut params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    params.events.detector = detector;
    let nearest = |v: &[f64], t: f64| v.iter().copied().find(|d| (d - t).abs() < 0.25);
    let (mut hs, mut to) = (Vec::new(), Vec::new());
    for i in 0..healthy {
        let s = c.simulate(i).unwrap();
        let r = analyze_simulated(&s, &params);
        let t = s.truth();
        for (leg, tr) in [(&r.left, &t.left), (&r.right, &t.right)] {
            let leg = leg.as_ref().unwrap();
            for ts in tr.strides.iter().filter(|s| !s.turning && !s.bout_edge) {
                hs.extend(nearest(&leg.events.hs_s, ts.hs_time_s).map(|d| d - ts.hs_time_s));
                to.extend(nearest(&leg.events.to_s, ts.to_time_s).map(|d| d - ts.to_time_s));
            }
        }
    }
    (hs, to)
}

/// Family B's normal walkers (not tuned on): the default toe off (`gyro-bracket`, placed from
/// both legs) is within 12 ms on average (8.0 ms, bias −4.5, on this seed), where the
/// three-landmark model fitted on family A is late by more than 10 ms on every such cohort
/// measured (+13.8 ms here); the default heel strike, at the delay this recording shows from
/// the gyroscope's landmark to the impact, is within 5 ms (the family-A offset: more than 5 ms
/// early on average). docs/accuracy.md "The bracket rule becomes the default", "Heel strike at
/// the impact".
#[test]
fn family_b_normal_events_are_not_off_like_the_family_a_models() {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let mae = |v: &[f64]| v.iter().map(|e| e.abs()).sum::<f64>() / v.len() as f64;
    let (hs, to) = family_b_event_errors(3, 41, ldh_core::events::EventDetector::GyroBracket);
    let (hs_a, to_a) = family_b_event_errors(3, 41, ldh_core::events::EventDetector::GyroLandmarks);
    assert!(to.len() >= 40 && to.len() == to_a.len() && hs.len() == hs_a.len());
    assert!(mae(&to) < 0.012, "{to:?}");
    assert!(mean(&to_a) > 0.010, "{to_a:?}");
    assert!(mae(&hs) < 0.005, "{hs:?}");
    assert!(mean(&hs_a) < -0.005, "{hs_a:?}");
}

/// A leg's toe offs come from both legs' landmarks, unless the other leg's gyroscope is faulty
/// (×10, `gyro_scale_fault`): then they are the leg's own, as if it had been given alone.
#[test]
fn a_faulty_gyroscope_lends_no_landmarks_to_the_other_leg() {
    let c = CohortParams {
        healthy: 0,
        ldh: 1,
        duration_s: 20.0,
        seed: 7,
        ..CohortParams::default()
    };
    let s = c.simulate(0).unwrap();
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let analysis = Analysis::new(params.check().unwrap());
    let alone = |l: &ldh_sim::SimLeg, side| {
        analysis
            .leg(&l.recording, side, None)
            .unwrap()
            .leg
            .events
            .to_s
    };
    let (left_alone, right_alone) = (alone(&s.left, Side::Left), alone(&s.right, Side::Right));
    let both = analyze_simulated(&s, &params);
    let to = |r: &std::result::Result<LegResult, String>| r.as_ref().unwrap().events.to_s.clone();
    // With a sound partner the stiffer leg's toe offs move later in their bracket.
    let (l, r) = (to(&both.left), to(&both.right));
    assert_eq!(l.len(), left_alone.len());
    assert_eq!(r.len(), right_alone.len());
    let later = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x >= y);
    assert!(
        (l != left_alone) ^ (r != right_alone),
        "exactly one leg moves"
    );
    assert!(later(&l, &left_alone) && later(&r, &right_alone));
    // A ×10 gyroscope on the moved leg's partner: the moved leg keeps its own.
    let mut faulty = s.clone();
    let (sound_side, bad) = if l != left_alone {
        (Side::Left, &mut faulty.right)
    } else {
        (Side::Right, &mut faulty.left)
    };
    for ch in bad.recording.gyro_dps.iter_mut() {
        ch.iter_mut().for_each(|x| *x *= 10.0);
    }
    let r = analyze_simulated(&faulty, &params);
    let (got, own) = match sound_side {
        Side::Left => (to(&r.left), left_alone),
        Side::Right => (to(&r.right), right_alone),
    };
    assert_eq!(got, own);
}

/// The events of `gyro-bracket` carry each toe off's swing arc (the shank's backward rotation
/// from the pitch peak to the next heel strike), and an LDH leg swings through the smaller arc
/// and has the larger landmark geometry: the leg the bilateral rule raises.
#[test]
fn each_toe_off_carries_its_swing_arc_and_the_affected_leg_swings_less() {
    let c = CohortParams {
        healthy: 0,
        ldh: 1,
        duration_s: 30.0,
        seed: 5,
        ..CohortParams::default()
    };
    let s = c.simulate(0).unwrap();
    let v = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    }
    .check()
    .unwrap();
    let front = |rec| leg_front(rec, &v, &mut ldh_core::timings::StageTimings::default()).unwrap();
    let (l, r) = (front(&s.left.recording), front(&s.right.recording));
    let geometry = |f: &LegFront| {
        let ev = &f.events;
        assert_eq!(ev.to_swing_arc_deg.len(), ev.to_s.len());
        let finite = ev.to_swing_arc_deg.iter().filter(|a| a.is_finite()).count();
        assert!(finite + 2 >= ev.to_s.len(), "{:?}", ev.to_swing_arc_deg);
        ldh_core::events::landmark_geometry(ev).unwrap()
    };
    let (gl, gr) = (geometry(&l), geometry(&r));
    let (aff, other) = match s.params.affected_side.unwrap() {
        Side::Left => (gl, gr),
        Side::Right => (gr, gl),
    };
    let (arc_a, arc_o) = (aff.swing_arc_deg.unwrap(), other.swing_arc_deg.unwrap());
    // A shank swings through tens of degrees, forward of the pitch peak back to heel strike.
    assert!(arc_o > 40.0 && arc_o < 120.0, "{arc_o}");
    assert!(arc_a < arc_o && aff.rho > other.rho, "{aff:?} {other:?}");
    let k = ldh_core::events::bracket_fraction(Some(aff), Some(other));
    assert!(k > ldh_core::events::BRACKET_K0, "{k}");
    assert_eq!(
        ldh_core::events::bracket_fraction(Some(other), Some(aff)),
        ldh_core::events::BRACKET_K0
    );
}
