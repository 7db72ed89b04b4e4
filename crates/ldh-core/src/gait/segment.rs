//! Stride segmentation (paper §3.2; SPEC §3.5): heel strike to heel strike of one leg, the
//! per-stride parameters (time, stance ratio, length, speed, WQK, PBI, BDK, heading change),
//! walking bouts split at pauses and turns, and the per-stride reasons a stride or its length
//! is not used.

use super::times::SortedTimes;
use super::{
    anatomical_roll_deg, pendulum_length_m, stride_lengths, zero_velocity_sample, LengthCheck,
    LengthEstimate, Stride, StrideCode, StrideFinding, StrideParams, ValidStrideParams,
};
use crate::align::Aligned;
use crate::attitude::{Attitude, AttitudeModel};
use crate::error::Result;
use crate::events::Events;
use crate::recording::Side;

/// Segment one leg into strides and compute the per-stride parameters.
pub fn strides(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
) -> Result<Vec<Stride>> {
    let turn_deg = params.0.turn_deg;
    strides_with_turns(side, al, att, ev, params, &|_, _, d| d.abs() > turn_deg)
}

/// Why the ACC-only model never reports a stride length: its attitude is the accelerometer's
/// own tilt, which walking accelerations corrupt, so gravity cannot be removed before the
/// integration. On both simulator families its few lengths that passed the per-stride checks
/// were 86-99 % short (docs/accuracy.md); the paper uses this model for angles only.
pub const ACC_ONLY_LENGTH: &str = "stride length withheld: the ACC-only attitude cannot separate gravity from motion, so the acceleration is not integrated";

/// The turn test of [`strides_with_turns`]: (HS time s, next HS time s, this leg's heading
/// change over the stride deg) → the stride is part of a turn.
pub type TurnTest<'a> = dyn Fn(f64, f64, f64) -> bool + 'a;

/// As [`strides`], with the turn decision made by `is_turn` (e.g. from both legs: a turn
/// rotates both shanks at the same time, yaw drift on one leg does not; none on a treadmill).
pub fn strides_with_turns(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
    is_turn: &TurnTest,
) -> Result<Vec<Stride>> {
    Ok(strides_with_turns_at(side, al, att, ev, params, is_turn, &[])?.0)
}

/// [`strides`], also measuring each stride's length with the sensor at each of `heights_m`
/// (for [`super::height_sensitivity_measured`]): the same integration as the stride's own
/// length, sharing its zero-velocity search and its rotation of the acceleration, so the
/// lengths are [`lengths_at_heights`]' bit for bit at a fraction of its cost.
pub fn strides_at_heights(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
    heights_m: &[f64],
) -> Result<(Vec<Stride>, LengthsAtHeights)> {
    let turn_deg = params.0.turn_deg;
    let is_turn = |_: f64, _: f64, d: f64| d.abs() > turn_deg;
    strides_with_turns_at(side, al, att, ev, params, &is_turn, heights_m)
}

/// [`strides_with_turns`] and [`strides_at_heights`].
fn strides_with_turns_at(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
    is_turn: &TurnTest,
    heights_m: &[f64],
) -> Result<(Vec<Stride>, LengthsAtHeights)> {
    let p = &params.0;
    let leg = Leg::new(side, al, att, ev, params);
    let mut hs = ev.hs_s.clone();
    hs.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    let mut out: Vec<Stride> = Vec::new();
    // Why a stride's length is withheld (the stride stays valid for its timing and angles).
    let mut length_notes: Vec<Option<StrideFinding>> = Vec::new();
    // Whether a stride is part of a turn (a turn ends a walking bout).
    let mut turns: Vec<bool> = Vec::new();
    let mut at_heights = LengthsAtHeights::new(heights_m);
    for (k, w) in hs.windows(2).enumerate() {
        let mut m = leg.measure(k, w[0], w[1], is_turn, heights_m);
        // A stride bounded by an unsure event is not valid (docs/quality.md "Unsure events").
        for why in crate::events::unsure_events(ev, w[0], m.stride.to_time_s, w[1]) {
            m.stride.push(StrideFinding::new(
                StrideCode::UnsureEvent(why),
                why.to_string(),
            ));
        }
        out.push(m.stride);
        length_notes.push(m.length_note);
        turns.push(m.turn);
        at_heights.push(&m.at_heights_m);
    }
    let bouts = assign_bouts(&out, &turns, p.max_stride_s);
    if p.drop_bout_edges {
        flag_bout_edges(&mut out, &bouts);
    }
    for (s, b) in out.iter_mut().zip(&bouts) {
        s.bout = b.unwrap_or(0);
        s.valid = s.findings.is_empty();
    }
    for (s, note) in out.iter_mut().zip(length_notes) {
        if let Some(f) = note {
            s.push(f);
        }
    }
    withhold_length_outliers(&mut out, p.max_length_deviation);
    Ok((out, at_heights))
}

/// The lengths of a leg's strides with the sensor at other heights, as the segmentation
/// measured them ([`strides_at_heights`]): per height, per stride, the length after the
/// stride's own checks (NaN where they withhold it), before its local median check.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthsAtHeights {
    /// The heights, m.
    pub heights_m: Vec<f64>,
    /// Per height, per stride (in the order of the strides), m.
    pub lengths_m: Vec<Vec<f64>>,
}

impl LengthsAtHeights {
    fn new(heights_m: &[f64]) -> LengthsAtHeights {
        LengthsAtHeights {
            heights_m: heights_m.to_vec(),
            lengths_m: vec![Vec::new(); heights_m.len()],
        }
    }

    /// Add the next stride's lengths, one per height.
    fn push(&mut self, lengths_m: &[f64]) {
        for (v, l) in self.lengths_m.iter_mut().zip(lengths_m) {
            v.push(*l);
        }
    }

    /// Per height, the lengths of `strides` (the strides these lengths were measured with,
    /// after any later check) as [`lengths_at_heights`] gives them: each valid stride's length
    /// through its local median check, NaN where withheld and for invalid strides.
    pub fn checked(&self, strides: &[Stride], max_length_deviation: f64) -> Vec<Vec<f64>> {
        self.lengths_m
            .iter()
            .map(|lengths| {
                let mut st = strides.to_vec();
                for (s, l) in st.iter_mut().zip(lengths) {
                    s.stride_length_m = if s.valid { *l } else { f64::NAN };
                }
                withhold_length_outliers(&mut st, max_length_deviation);
                st.iter().map(|s| s.stride_length_m).collect()
            })
            .collect()
    }
}

/// One measured stride, before bouts are known.
struct Measured {
    /// The stride, `bout` 0 and `valid` true for now; `reason` holds the timing and turn reasons.
    stride: Stride,
    /// Why its length is withheld, if it is.
    length_note: Option<StrideFinding>,
    /// Whether it is part of a turn.
    turn: bool,
    /// Its length with the sensor at each of the other heights asked for, m (NaN where the
    /// stride's own checks withhold it).
    at_heights_m: Vec<f64>,
}

/// One leg's signals and the stride parameters: what measuring a stride reads.
struct Leg<'a> {
    side: Side,
    al: &'a Aligned,
    att: &'a Attitude,
    ev: &'a Events,
    p: &'a StrideParams,
    /// The sensor height the stride length uses, m (given or assumed).
    height_m: f64,
    /// Samples of the attitude.
    n: usize,
    /// |ω|, deg/s, per sample (for the zero-velocity instant).
    w_norm: Vec<f64>,
    /// The toe offs by time (the toe offs in a stride without a scan of all: issue 19).
    tos: SortedTimes,
}

impl<'a> Leg<'a> {
    fn new(
        side: Side,
        al: &'a Aligned,
        att: &'a Attitude,
        ev: &'a Events,
        params: &'a ValidStrideParams,
    ) -> Self {
        let p = &params.0;
        let n = att.pitch_deg.len();
        let w_norm: Vec<f64> = (0..n)
            .map(|i| {
                (al.gyro_dps[0][i].powi(2) + al.gyro_dps[1][i].powi(2) + al.gyro_dps[2][i].powi(2))
                    .sqrt()
            })
            .collect();
        Leg {
            side,
            al,
            att,
            ev,
            p,
            height_m: params.sensor_height_m(),
            n,
            w_norm,
            tos: SortedTimes::new(&ev.to_s),
        }
    }

    /// The sample at time `t` s, clamped to the recording.
    fn idx(&self, t: f64) -> usize {
        ((t * self.al.fs_hz).round().max(0.0) as usize).min(self.n.saturating_sub(1))
    }

    /// Mid-stance (zero-velocity) sample after the heel strike at `h` s.
    fn zero_velocity_after(&self, h: f64) -> Option<usize> {
        let (to, _) = self.tos.after(h, |t| t - h < 0.75 * self.p.max_stride_s);
        let end = to.unwrap_or(h + 0.6 * self.ev.median_stride_s.max(0.5));
        zero_velocity_sample(
            self.p.zero_velocity,
            self.al,
            &self.w_norm,
            self.idx(h),
            self.idx(end),
        )
    }

    /// Stride `k` from the heel strike at `h0` s to the next at `h1` s.
    fn measure(
        &self,
        k: usize,
        h0: f64,
        h1: f64,
        is_turn: &TurnTest,
        heights_m: &[f64],
    ) -> Measured {
        let (p, att, n) = (self.p, self.att, self.n);
        let st = h1 - h0;
        let mut reasons: Vec<StrideFinding> = Vec::new();
        if st < p.min_stride_s || st > p.max_stride_s {
            reasons.push(StrideFinding::new(
                StrideCode::StrideTime,
                format!(
                    "stride time {st:.2} s outside [{}, {}] s",
                    p.min_stride_s, p.max_stride_s
                ),
            ));
        }
        let to = self.toe_off(h0, h1, &mut reasons);
        let (a, b) = (self.idx(h0), self.idx(h1));
        let (mut mx, mut mn) = (f64::MIN, f64::MAX);
        for i in a..b.max(a + 1).min(n) {
            mx = mx.max(att.pitch_deg[i]);
            mn = mn.min(att.pitch_deg[i]);
        }
        let bdk = self.roll_excursion(to, b);
        let mut dpsi = att.yaw_deg[b.min(n - 1)] - att.yaw_deg[a];
        dpsi = (dpsi + 180.0).rem_euclid(360.0) - 180.0;
        let turn = is_turn(h0, h1, dpsi);
        if turn {
            reasons.push(StrideFinding::new(
                StrideCode::Turn,
                format!("turning ({dpsi:.0} deg heading change)"),
            ));
        }
        let span = self.span(h0, h1, to, a);
        let mut heights = Vec::with_capacity(heights_m.len() + 1);
        heights.push(self.height_m);
        heights.extend_from_slice(heights_m);
        let mut lengths = self.lengths(&span, &heights).into_iter();
        let (length, length_note, vertical_m) =
            lengths.next().unwrap_or((f64::NAN, None, f64::NAN));
        let mut stride = Stride {
            stride_index: k,
            hs_time_s: h0,
            to_time_s: to,
            next_hs_time_s: h1,
            stride_time_s: st,
            stance_ratio: (to - h0) / st,
            double_support_ratio: f64::NAN,
            stride_length_m: length,
            speed_mps: length / st,
            wqk_deg: mx,
            pbi_deg: -mn,
            bdk_deg: bdk,
            heading_change_deg: dpsi,
            bout: 0,
            valid: true,
            reason: String::new(),
            findings: Vec::new(),
            vertical_m,
        };
        for f in reasons {
            stride.push(f);
        }
        Measured {
            stride,
            length_note,
            turn,
            at_heights_m: lengths.map(|(l, _, _)| l).collect(),
        }
    }

    /// The toe off between the heel strikes at `h0` and `h1` s (the first when several, NaN
    /// when none), adding the reason to `reasons` unless there is exactly one.
    fn toe_off(&self, h0: f64, h1: f64, reasons: &mut Vec<StrideFinding>) -> f64 {
        match self.tos.after(h0, |t| t < h1) {
            (None, _) => {
                reasons.push(StrideFinding::new(StrideCode::ToeOff, "no toe off"));
                f64::NAN
            }
            (Some(t), 1) => t,
            (Some(t), n) => {
                reasons.push(StrideFinding::new(
                    StrideCode::ToeOff,
                    format!("{n} toe offs"),
                ));
                t
            }
        }
    }

    /// BDK: range of anatomical roll from the toe off at `to` s to the sample `b` of the next
    /// heel strike, deg (NaN without a toe off).
    fn roll_excursion(&self, to: f64, b: usize) -> f64 {
        if !to.is_finite() {
            return f64::NAN;
        }
        let (mut rmx, mut rmn) = (f64::MIN, f64::MAX);
        for i in self.idx(to)..b.max(self.idx(to) + 1).min(self.n) {
            let r = anatomical_roll_deg(self.att.roll_deg[i], self.side);
            rmx = rmx.max(r);
            rmn = rmn.min(r);
        }
        rmx - rmn
    }

    /// What the length integration of the stride from the heel strike at `h0` s (sample `a`)
    /// to the next at `h1` s, toe off at `to` s, reads whatever the sensor height.
    fn span(&self, h0: f64, h1: f64, to: f64, a: usize) -> Span {
        let att = self.att;
        let zv = match (self.zero_velocity_after(h0), self.zero_velocity_after(h1)) {
            (Some(z0), Some(z1)) if z1 > z0 + 1 => Some((z0, z1)),
            _ => None,
        };
        let pendulum_m = if to.is_finite() {
            pendulum_length_m(
                att.pitch_deg[a],
                att.pitch_deg[self.idx(to)],
                (to - h0) / (h1 - h0),
            )
        } else {
            f64::NAN
        };
        Span { zv, pendulum_m }
    }

    /// The stride length over `span`, m, with the sensor at each of `heights_m` above the
    /// ankle, NaN with the reason where it is withheld; and the ankle's vertical displacement,
    /// m, NaN where the integration is not consistent (no zero-velocity span, an
    /// accelerometer-only attitude, drift, tilt or clipping beyond the checks).
    fn lengths(&self, span: &Span, heights_m: &[f64]) -> Vec<(f64, Option<StrideFinding>, f64)> {
        let ests = match span.zv {
            Some((z0, z1)) => stride_lengths(self.al, self.att, z0, z1, heights_m),
            None => vec![
                LengthEstimate {
                    length_m: f64::NAN,
                    drift_mps: f64::NAN,
                    unexplained_mps: f64::NAN,
                    tilt_deg: f64::NAN,
                    vertical_m: f64::NAN,
                    clipped_samples: 0,
                    clip_step_m: 0.0,
                };
                heights_m.len()
            ],
        };
        ests.into_iter()
            .map(|est| {
                let note = if self.att.model == AttitudeModel::Acc {
                    Some(StrideFinding::new(
                        StrideCode::Length(LengthCheck::AccOnly),
                        ACC_ONLY_LENGTH,
                    ))
                } else {
                    est.check(span.pendulum_m)
                };
                let length = if note.is_some() {
                    f64::NAN
                } else {
                    est.length_m
                };
                // The rise is vouched for when the integration is consistent: only the
                // checks a stair stride fails by its rise (off the floor level, and a length
                // unlike a level stride's pendulum) may have withheld the length.
                let consistent = note.as_ref().is_none_or(|f| {
                    matches!(
                        f.code,
                        StrideCode::Length(LengthCheck::Floor | LengthCheck::Pendulum)
                    )
                });
                let vertical = if consistent { est.vertical_m } else { f64::NAN };
                (length, note, vertical)
            })
            .collect()
    }
}

/// What a stride's length integration reads besides the sensor height.
struct Span {
    /// Its two zero-velocity samples (`None` when not found).
    zv: Option<(usize, usize)>,
    /// The shank-pendulum estimate, m (NaN when unknown).
    pendulum_m: f64,
}

/// The lengths of `strides` (segmented from these signals by [`strides`] or
/// [`strides_with_turns`] with `params`) recomputed with the sensor at each of `heights_m`
/// instead, m: per height, each valid stride's length through the same per-stride checks (the
/// integration's, then the local median of its bout), NaN where withheld and for invalid strides. The
/// zero-velocity spans are found once more per stride here and the acceleration rotated once
/// more, for all heights (they do not depend on the height); the attitude, the bouts and which
/// strides are valid are the strides' own. The pipeline does not call this: it measures the
/// heights during the segmentation ([`strides_at_heights`], the same numbers without the
/// repetition).
pub fn lengths_at_heights(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
    strides: &[Stride],
    heights_m: &[f64],
) -> Vec<Vec<f64>> {
    let leg = Leg::new(side, al, att, ev, params);
    let mut measured = LengthsAtHeights::new(heights_m);
    for s in strides {
        let lengths: Vec<f64> = if s.valid {
            let a = leg.idx(s.hs_time_s);
            let span = leg.span(s.hs_time_s, s.next_hs_time_s, s.to_time_s, a);
            leg.lengths(&span, heights_m)
                .into_iter()
                .map(|(l, _, _)| l)
                .collect()
        } else {
            vec![f64::NAN; heights_m.len()]
        };
        measured.push(&lengths);
    }
    measured.checked(strides, params.0.max_length_deviation)
}

/// Walking bouts: numbered from 0, split at pauses (a stride longer than `max_stride_s`) and at
/// turns; a stride that breaks a bout belongs to none (`None`).
fn assign_bouts(out: &[Stride], turns: &[bool], max_stride_s: f64) -> Vec<Option<usize>> {
    let mut bout = 0usize;
    let mut prev_break = true;
    out.iter()
        .zip(turns)
        .map(|(s, &turn)| {
            if s.stride_time_s > max_stride_s || turn {
                if !prev_break {
                    bout += 1;
                }
                prev_break = true;
                None
            } else {
                prev_break = false;
                Some(bout)
            }
        })
        .collect()
}

/// Flag the first and last stride of every bout (strides in no bout are left alone).
fn flag_bout_edges(out: &mut [Stride], bouts: &[Option<usize>]) {
    let m = out.len();
    for i in 0..m {
        if bouts[i].is_none() {
            continue;
        }
        let first = i == 0 || bouts[i - 1] != bouts[i];
        let last = i + 1 == m || bouts[i + 1] != bouts[i];
        if first || last {
            let r = if first {
                "first stride of a walking bout"
            } else {
                "last stride of a walking bout"
            };
            out[i].push(StrideFinding::new(StrideCode::BoutEdge, r));
        }
    }
}

/// Valid strides of a bout on each side of a stride whose lengths give the median it is judged
/// against (10: the local median follows a walker who speeds up or slows down, so a trend in
/// stride length does not withhold both ends of the walk; issue 50).
pub const LOCAL_LENGTH_STRIDES: usize = 10;

/// Valid strides whose length differs from the median length of the valid strides around them
/// in their bout (up to [`LOCAL_LENGTH_STRIDES`] on each side) by more than `max_dev`
/// (fraction): the length (and speed) is withheld with the reason; the stride stays valid for
/// its timing and angles. Neighbourhoods with fewer than 3 lengths are left alone (no median
/// to trust).
fn withhold_length_outliers(out: &mut [Stride], max_dev: f64) {
    // The valid strides of each bout, in order (one pass: linear in the strides).
    let mut bouts: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for (k, s) in out.iter().enumerate().filter(|(_, s)| s.valid) {
        bouts.entry(s.bout).or_default().push(k);
    }
    let mut l = Vec::with_capacity(2 * LOCAL_LENGTH_STRIDES + 1);
    for members in bouts.values() {
        // Judged against the lengths as measured (none withheld by a neighbour's verdict).
        let lengths: Vec<f64> = members.iter().map(|&k| out[k].stride_length_m).collect();
        for (j, &k) in members.iter().enumerate() {
            let around = j.saturating_sub(LOCAL_LENGTH_STRIDES)
                ..(j + LOCAL_LENGTH_STRIDES + 1).min(members.len());
            l.clear();
            l.extend(lengths[around].iter().copied().filter(|x| x.is_finite()));
            if l.len() < 3 {
                continue;
            }
            let med =
                crate::stats::median(&mut l, crate::stats::EvenMedian::Upper).expect("3 or more");
            let s = &mut out[k];
            let dev = (s.stride_length_m - med) / med;
            if s.stride_length_m.is_finite() && dev.abs() > max_dev {
                let r = format!(
                    "stride length withheld: {:.2} m is {:+.0} % from the median {med:.2} m of the strides around it",
                    s.stride_length_m,
                    dev * 100.0
                );
                s.push(StrideFinding::new(
                    StrideCode::Length(LengthCheck::BoutMedian),
                    r,
                ));
                s.stride_length_m = f64::NAN;
                s.speed_mps = f64::NAN;
            }
        }
    }
}
