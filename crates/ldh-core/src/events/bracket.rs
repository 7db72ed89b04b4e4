//! Toe off inside the shank's landmark bracket, referenced to the subject's other leg
//! ([`EventDetector::GyroBracket`], the default detector; issue 20 item 4).
//!
//! Toe off leaves no mark of its own on a shank: the literature's landmarks bracket it. The
//! late-stance peak of the sagittal angular velocity t_s (Aminian et al. 2002, J Biomech
//! 35:689; Salarian et al. 2004, IEEE TBME 51:1434) comes before it and the pitch peak t_p (the
//! paper's toe off) after it, on both simulators and on HuGaDB's foot sensors
//! (docs/accuracy.md "Toe off without fitted offsets", "Toe off against the feet of HuGaDB").
//! Where inside the bracket it lies depends on the leg's swing: a stiff-knee leg reaches its
//! pitch peak early in its swing and leaves the ground late in the bracket. That geometry is
//! read as ρ = (t_m − t_p)/(t_p − t_s) (t_m mid-swing), and a population threshold on it does
//! not carry from one simulator to the other (their normal legs differ by 40 % in ρ). The
//! subject's other leg does: the same sensors, walk and speed, so only the difference between
//! the legs is read. A larger ρ alone does not make the stiffer leg (a normal walker's legs
//! differ in ρ too, and a moderately stiff leg with a broad late-stance peak can have the
//! smaller ρ of the two): the stiffer leg also swings its shank through the smaller arc, as
//! stiff-knee and paretic legs do (reduced knee flexion in swing; Kerrigan et al. 1991, Am J
//! Phys Med Rehabil 70:294), so a leg is raised only when both signs say it is the stiffer.
//!
//! TO = t_s + k·(t_p − t_s), k = k₀ + s·max(0, ln(ρ/ρ_other)) + s_arc·ln(arc_other/arc),
//! clamped to [k₀, 1.5], when the leg's swing arc (−∫ω_s dt from t_p to the next heel strike) is
//! shorter than the other leg's; else k = k₀. The arc term (issue 49) raises a paretic leg
//! whose stiff knee flattens its pitch peak: its bracket widens, its ρ can fall below the other
//! leg's, and without the term its toe off came 25–40 ms early on family B; s_arc was fitted on
//! family A alone (docs/accuracy.md "Toe off by the swing arc"). ρ and the arc are the leg's medians over its strides. With no other leg (or
//! fewer than [`MIN_BRACKETS`] strides on either, or a partner whose gyroscope is faulty:
//! `pipeline::subject` does not pass it) k = k₀; with too few arcs on either leg, ρ alone
//! decides. k₀ and s are least squares on family A's tuning cohort (seed 100: 10 healthy, 10 LDH,
//! 10 slow LDH, 756 steady strides; `data-fixtures/scripts/toe_off_landmarks.py`);
//! family B was not fitted on. The arc's sign test fits nothing; it was added after family B's
//! over-raised legs were seen, and it lowers family A's error as well (docs/accuracy.md "The
//! stiffer leg by its swing arc too"). The cap [`BRACKET_MAX`] only guards against a partner
//! whose landmarks are not gait.

use super::{EventDetector, Events, ValidEventParams};

/// k₀: the fraction of the bracket at which a leg no stiffer than its partner leaves the ground
/// (least squares on family A seed 100).
pub const BRACKET_K0: f64 = 0.38855;

/// s: how much k rises per unit of ln(ρ/ρ_other) (least squares on family A seed 100).
pub const BRACKET_SLOPE: f64 = 0.87179;

/// s_arc: how much k rises per unit of ln(arc_other/arc) on the leg whose swing arc is the
/// shorter (issue 49; least squares on family A seeds 100–103 with k₀ and s kept, weighted by
/// the bracket width so that it minimises the error in ms; family B was not fitted on). A
/// paretic leg whose pitch peak is flattened by its stiff knee can have the smaller ρ of the two
/// and still leave the ground late in its bracket; its shorter arc says so.
pub const BRACKET_ARC_SLOPE: f64 = 0.18231;

/// Largest bracket fraction: half a bracket past the pitch peak. A guard against a partner leg
/// whose landmarks are not gait (not fitted): stiff-knee legs of family B leave the ground up to
/// 0.37 of a bracket after their pitch peak, so the pitch peak itself is not a bound.
pub const BRACKET_MAX: f64 = 1.5;

/// Fewest toe-off brackets a leg needs for its landmark geometry ρ to be read.
pub const MIN_BRACKETS: usize = 5;

/// The toe off at fraction `k` of the bracket `[t_s, t_p]` of landmarks `lm` (t_s, t_p, t_m), plus
/// `offset_s`, s.
pub fn bracket_toe_off_s(lm: [f64; 3], k: f64, offset_s: f64) -> f64 {
    let [ts, tp, _] = lm;
    ts + k * (tp - ts) + offset_s
}

/// What the bilateral rule reads of one leg: medians over its strides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegGeometry {
    /// The landmark geometry ρ = (t_m − t_p)/(t_p − t_s) (upper median).
    pub rho: f64,
    /// The swing arc −∫ω_s dt from t_p to the next heel strike, deg (upper median); `None` with
    /// fewer than [`MIN_BRACKETS`] strides that have one.
    pub swing_arc_deg: Option<f64>,
}

/// The upper median of the finite values, `None` with fewer than [`MIN_BRACKETS`].
fn upper_median(values: impl Iterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    if v.len() < MIN_BRACKETS {
        return None;
    }
    crate::stats::median(&mut v, crate::stats::EvenMedian::Upper)
}

/// A leg's landmark geometry and swing arc, medians over its strides whose landmarks are in
/// order; `None` with fewer than [`MIN_BRACKETS`] of them. The arc is `None` with fewer than
/// [`MIN_BRACKETS`] finite arcs, or when the events carry none for some toe offs.
pub fn landmark_geometry(ev: &Events) -> Option<LegGeometry> {
    let in_order = |[ts, tp, tm]: &[f64; 3]| tp > ts && tm > tp;
    let rho = upper_median(
        ev.to_landmarks_s
            .iter()
            .filter(|lm| in_order(lm))
            .map(|[ts, tp, tm]| (tm - tp) / (tp - ts)),
    )?;
    let arcs = &ev.to_swing_arc_deg;
    let swing_arc_deg = (arcs.len() == ev.to_landmarks_s.len())
        .then(|| {
            upper_median(
                ev.to_landmarks_s
                    .iter()
                    .zip(arcs)
                    .filter(|(lm, _)| in_order(lm))
                    .map(|(_, &a)| a),
            )
        })
        .flatten();
    Some(LegGeometry { rho, swing_arc_deg })
}

/// The bracket fraction of a leg of geometry `own` whose other leg's is `other`: raised by ρ
/// only when the leg is the stiffer of the two by both signs, a larger ρ and a shorter swing arc
/// (by ρ alone when either arc is unknown), and raised by the arc whenever its swing arc is the
/// shorter: k = k₀ + s·max(0, ln(ρ/ρ_other)) + s_arc·ln(arc_other/arc), clamped to
/// [k₀, [`BRACKET_MAX`]].
pub fn bracket_fraction(own: Option<LegGeometry>, other: Option<LegGeometry>) -> f64 {
    let (Some(a), Some(b)) = (own, other) else {
        return BRACKET_K0;
    };
    if !(a.rho > 0.0 && b.rho > 0.0) {
        return BRACKET_K0;
    }
    let by_rho = BRACKET_SLOPE * (a.rho / b.rho).ln().max(0.0);
    let k = match (a.swing_arc_deg, b.swing_arc_deg) {
        // A sign, no margin: arcs within a gyroscope's gain tolerance (a few %) of each other
        // decide by chance; a 3 % margin cost family A (docs/accuracy.md).
        (Some(arc), Some(arc_other)) if arc >= arc_other => BRACKET_K0,
        (Some(arc), Some(arc_other)) if arc > 0.0 => {
            BRACKET_K0 + by_rho + BRACKET_ARC_SLOPE * (arc_other / arc).ln()
        }
        _ => BRACKET_K0 + by_rho,
    };
    k.clamp(BRACKET_K0, BRACKET_MAX)
}

/// The shank's swing arc from the pitch peak at `tp_s` (s) to the heel strike's zero crossing at
/// sub-sample `hs` of ω_s, deg: −∫ω_s dt by the rectangle rule over the samples between them
/// (gyroscope only, so both attitude models read the same); NaN when they are not in order.
pub(super) fn swing_arc_deg(omega_s_dps: &[f64], fs_hz: f64, tp_s: f64, hs: f64) -> f64 {
    let (a, b) = ((tp_s * fs_hz).ceil(), hs.floor());
    if !(a >= 0.0 && b >= a && (b as usize) < omega_s_dps.len()) {
        return f64::NAN;
    }
    -omega_s_dps[a as usize..=b as usize].iter().sum::<f64>() / fs_hz
}

/// Place both legs' events of one subject ([`EventDetector::GyroBracket`] only; the other
/// detectors are left as they are; one leg alone: the other `None`). Heel strikes: each at its
/// own impact, when the walk shows impacts (a strike without one at its zero crossing plus the
/// walk's median delay; [`super::shift_to_impacts`]; each leg alone when the two are not one
/// walk). Toe
/// offs: each leg's at its fraction of its brackets, from its own
/// and the other leg's landmark geometry, and never after its mid-swing. A leg not given (not
/// read, failed, or faulty) is `None`; the other then keeps k₀, as do both legs when their
/// median stride times differ by more than [`SAME_WALK_STRIDE_TOLERANCE`] (not one walk).
pub fn place_bilateral(
    left: Option<&mut Events>,
    right: Option<&mut Events>,
    params: &ValidEventParams,
) {
    if params.p.detector != EventDetector::GyroBracket {
        return;
    }
    // Events of another detector (or deserialised, without their landmarks) are left alone.
    let usable = |e: &&mut Events| e.to_landmarks_s.len() == e.to_s.len();
    let (mut left, mut right) = (left.filter(usable), right.filter(usable));
    // Both legs of one walk share its stride time: a partner that does not is another walk.
    let one_walk = match (left.as_deref(), right.as_deref()) {
        (Some(l), Some(r)) => same_walk(l.median_stride_s, r.median_stride_s),
        _ => false,
    };
    // Heel strikes: at their impacts, the walk's median delay for those without (each leg
    // alone if not one walk).
    let hs_offset = params.hs_offset;
    let place_hs = |legs: &mut [&mut Events]| {
        // Impacts not searched (`hs_impact` off) or already used: nothing to place.
        if legs.iter().all(|e| e.hs_impacts.is_empty()) {
            return;
        }
        let d = super::shift_to_impacts(legs, hs_offset);
        for ev in legs.iter_mut() {
            ev.hs_impact_delay_s = d;
            // Used once: a second placement must not shift the heel strikes again.
            ev.hs_impacts.clear();
        }
    };
    match (left.as_deref_mut(), right.as_deref_mut()) {
        (Some(l), Some(r)) if one_walk => place_hs(&mut [l, r]),
        (l, r) => {
            for ev in [l, r].into_iter().flatten() {
                place_hs(&mut [ev]);
            }
        }
    }
    let mut rho_l = left.as_deref().and_then(landmark_geometry);
    let mut rho_r = right.as_deref().and_then(landmark_geometry);
    if !one_walk {
        (rho_l, rho_r) = (None, None);
    }
    for (ev, own, other) in [(left, rho_l, rho_r), (right, rho_r, rho_l)] {
        let Some(ev) = ev else { continue };
        let k = bracket_fraction(own, other);
        let offset = params.to_offset * ev.median_stride_s;
        // Never past mid-swing, whatever the fraction.
        ev.to_s = ev
            .to_landmarks_s
            .iter()
            .map(|&lm| bracket_toe_off_s(lm, k, offset).min(lm[2]))
            .collect();
    }
}

/// Largest relative difference of the two legs' median stride times for them to be one walk.
pub const SAME_WALK_STRIDE_TOLERANCE: f64 = 0.1;

/// Whether two median stride times (s) can be the two legs of one walk.
fn same_walk(a: f64, b: f64) -> bool {
    a > 0.0 && b > 0.0 && (a / b - 1.0).abs() <= SAME_WALK_STRIDE_TOLERANCE
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::events::EventParams;

    fn events(rho: f64, n: usize) -> Events {
        // Brackets of 0.1 s at 1 s strides; mid-swing ρ·0.1 s after the pitch peak.
        let lm: Vec<[f64; 3]> = (0..n)
            .map(|i| {
                let ts = i as f64 + 0.5;
                [ts, ts + 0.1, ts + 0.1 + rho * 0.1]
            })
            .collect();
        Events {
            to_s: lm
                .iter()
                .map(|&l| bracket_toe_off_s(l, BRACKET_K0, 0.0))
                .collect(),
            to_landmarks_s: lm,
            median_stride_s: 1.0,
            ..Events::default()
        }
    }

    #[test]
    fn the_stiffer_leg_leaves_the_ground_later_in_its_bracket() {
        let p = EventParams::default().check().unwrap();
        let (mut l, mut r) = (events(2.0, 8), events(1.0, 8));
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        // ln 2 · 0.87179 + 0.38855 = 0.99282 of the 0.1 s bracket for the left leg.
        let k = BRACKET_K0 + BRACKET_SLOPE * 2f64.ln();
        assert!((l.to_s[0] - (0.5 + 0.1 * k)).abs() < 1e-12, "{}", l.to_s[0]);
        // The less stiff leg keeps k₀.
        assert!((r.to_s[0] - (0.5 + 0.1 * BRACKET_K0)).abs() < 1e-12);
        // A much stiffer leg is capped half a bracket past the pitch peak.
        let (mut l, mut r) = (events(5.0, 8), events(1.0, 8));
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert!((l.to_s[3] - 3.65).abs() < 1e-12, "{}", l.to_s[3]);
    }

    #[test]
    fn a_leg_with_the_larger_rho_but_the_longer_swing_arc_is_not_raised() {
        let p = EventParams::default().check().unwrap();
        let with_arc = |rho: f64, arc: f64| {
            let mut e = events(rho, 8);
            e.to_swing_arc_deg = vec![arc; 8];
            e
        };
        // The larger ρ swings the shank through more: not the stiffer leg, not raised; the
        // other leg, with the shorter arc, is raised by its arc alone.
        let (mut l, mut r) = (with_arc(2.0, 70.0), with_arc(1.0, 60.0));
        let before = l.to_s.clone();
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert_eq!(l.to_s, before);
        let k_r = BRACKET_K0 + BRACKET_ARC_SLOPE * (70.0f64 / 60.0).ln();
        assert!(
            (r.to_s[0] - (0.5 + 0.1 * k_r)).abs() < 1e-12,
            "{}",
            r.to_s[0]
        );
        // Both signs agree: raised by ρ and by the arc.
        let (mut l, mut r) = (with_arc(2.0, 50.0), with_arc(1.0, 60.0));
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        let k_arc = BRACKET_ARC_SLOPE * 1.2f64.ln();
        let k = BRACKET_K0 + BRACKET_SLOPE * 2f64.ln();
        assert!(
            (l.to_s[0] - (0.5 + 0.1 * (k + k_arc))).abs() < 1e-12,
            "{}",
            l.to_s[0]
        );
        // The shorter arc with the smaller ρ (a stiff knee's flattened pitch peak): raised by
        // the arc alone; the other leg keeps k₀.
        let (mut l, mut r) = (with_arc(1.0, 50.0), with_arc(2.0, 60.0));
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        let want = 0.5 + 0.1 * (BRACKET_K0 + k_arc);
        assert!((l.to_s[0] - want).abs() < 1e-12, "{}", l.to_s[0]);
        assert!((r.to_s[0] - (0.5 + 0.1 * BRACKET_K0)).abs() < 1e-12);
        // Too few arcs on one leg (NaN: its heel strikes not found): ρ alone decides.
        let k = BRACKET_K0 + BRACKET_SLOPE * 2f64.ln();
        let (mut l, mut r) = (with_arc(2.0, 70.0), with_arc(1.0, f64::NAN));
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert!((l.to_s[0] - (0.5 + 0.1 * k)).abs() < 1e-12, "{}", l.to_s[0]);
        assert_eq!(landmark_geometry(&r).unwrap().swing_arc_deg, None);
        // Equal arcs: neither is the shorter, neither leg is raised.
        let (mut l, mut r) = (with_arc(2.0, 60.0), with_arc(1.0, 60.0));
        let before = l.to_s.clone();
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert_eq!(l.to_s, before);
        // Five finite arcs are enough to read a leg's arc, four are not.
        let mut e = with_arc(1.0, 60.0);
        e.to_swing_arc_deg[..3].fill(f64::NAN);
        assert_eq!(landmark_geometry(&e).unwrap().swing_arc_deg, Some(60.0));
        e.to_swing_arc_deg[3] = f64::NAN;
        assert_eq!(landmark_geometry(&e).unwrap().swing_arc_deg, None);
        // Arcs for some toe offs only (events built by hand): not read.
        let mut e = with_arc(1.0, 60.0);
        e.to_swing_arc_deg.pop();
        assert_eq!(landmark_geometry(&e).unwrap().swing_arc_deg, None);
    }

    #[test]
    fn without_a_usable_other_leg_every_leg_keeps_k0() {
        let p = EventParams::default().check().unwrap();
        let mut l = events(2.0, 8);
        let before = l.to_s.clone();
        place_bilateral(Some(&mut l), None, &p);
        assert_eq!(l.to_s, before);
        // Too few strides on the other leg to read its geometry.
        let mut r = events(1.0, MIN_BRACKETS - 1);
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert_eq!(l.to_s, before);
        assert_eq!(landmark_geometry(&r), None);
        assert!((landmark_geometry(&l).unwrap().rho - 2.0).abs() < 1e-9);
    }

    #[test]
    fn legs_of_different_walks_keep_k0() {
        let p = EventParams::default().check().unwrap();
        let (mut l, mut r) = (events(2.0, 8), events(1.0, 8));
        r.median_stride_s = 1.2;
        let before = l.to_s.clone();
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert_eq!(l.to_s, before);
        // A user's toe-off offset is added once, in stride times.
        let p = EventParams {
            to_offset_stride: Some(0.05),
            ..EventParams::default()
        }
        .check()
        .unwrap();
        let (mut l, mut r) = (events(1.0, 8), events(1.0, 8));
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert!((l.to_s[2] - (2.5 + 0.1 * BRACKET_K0 + 0.05)).abs() < 1e-12);
    }

    #[test]
    fn other_detectors_are_left_alone() {
        let p = EventParams::default()
            .detector(EventDetector::GyroLandmarks)
            .check()
            .unwrap();
        let (mut l, mut r) = (events(2.0, 8), events(1.0, 8));
        let before = l.to_s.clone();
        place_bilateral(Some(&mut l), Some(&mut r), &p);
        assert_eq!(l.to_s, before);
    }

    #[test]
    fn the_swing_arc_sums_the_backward_rotation_between_the_pitch_peak_and_the_heel_strike() {
        // −100 deg/s from sample 10 to 29 at 100 Hz: 20 samples, 20 degrees.
        let w: Vec<f64> = (0..40)
            .map(|i| if (10..30).contains(&i) { -100.0 } else { 5.0 })
            .collect();
        assert!((swing_arc_deg(&w, 100.0, 0.095, 29.5) - 20.0).abs() < 1e-12);
        // Out of order or past the end: unknown.
        assert!(swing_arc_deg(&w, 100.0, 0.3, 20.0).is_nan());
        assert!(swing_arc_deg(&w, 100.0, 0.1, 45.0).is_nan());
    }
}
