//! The ground truth of each stride of one family A leg: times, stance ratio, the heel-to-heel
//! displacement in the world, the pitch extremes and the roll excursion in swing.

use super::super::StrideTruth;
use super::events::LegEvents;
use super::kinematics::FineTrack;
use super::leg::LegModel;
use super::phase::Heading;

/// One [`StrideTruth`] per pair of consecutive heel strikes of `leg` with a toe off between
/// them: pitch extremes over the stride and the roll range from toe off to the next heel strike
/// from the integration grid (`fine`), the stride length from the two heel contact points
/// (NaN when one is missing), `turning` when the stride overlaps the turn, `bout_edge` for the
/// first and last stride, `accelerating` when it begins before `ramp_end_s` (belt start-up),
/// `decelerating` when it ends after `slowdown_start_s`.
pub(super) fn stride_truth(
    leg: &LegModel,
    events: &LegEvents,
    fine: &FineTrack,
    heading: &Heading,
    ramp_end_s: Option<f64>,
    slowdown_start_s: Option<f64>,
) -> Vec<StrideTruth> {
    let (hs_times, to_times) = (&events.hs, &events.to);
    let j_first = leg.first_stride();
    let mut strides = Vec::new();
    for (si, w) in hs_times.windows(2).enumerate() {
        let j = j_first + 1 + si;
        let (t_hs, t_next) = (w[0], w[1]);
        let Some(&t_to) = to_times.iter().find(|&&x| x > t_hs && x < t_next) else {
            continue;
        };
        let (mut mx, mut mn) = (f64::MIN, f64::MAX);
        let (mut rmx, mut rmn) = (f64::MIN, f64::MAX);
        // `fine.t` increases: the stride's samples are one index range (found by bisection,
        // so the truth is linear in the recording's length, not quadratic).
        let at = |t: f64| fine.t.partition_point(|&ft| ft < t);
        for k in at(t_hs)..at(t_next) {
            mx = mx.max(fine.theta_deg[k]);
            mn = mn.min(fine.theta_deg[k]);
        }
        for k in at(t_to)..at(t_next) {
            rmx = rmx.max(fine.rho_deg[k]);
            rmn = rmn.min(fine.rho_deg[k]);
        }
        let length = match (
            fine.heel_pos.get(j).copied().flatten(),
            fine.heel_pos.get(j + 1).copied().flatten(),
        ) {
            (Some(a), Some(b)) => ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt(),
            _ => f64::NAN,
        };
        let turning = heading
            .turn
            .map(|(a, b)| t_next > a && t_hs < b)
            .unwrap_or(false);
        let bout_edge = si == 0 || si + 2 == hs_times.len();
        strides.push(StrideTruth {
            index: j,
            hs_time_s: t_hs,
            to_time_s: t_to,
            next_hs_time_s: t_next,
            stride_time_s: t_next - t_hs,
            stance_ratio: (t_to - t_hs) / (t_next - t_hs),
            stride_length_m: length,
            max_pitch_deg: mx,
            min_pitch_deg: mn,
            roll_swing_excursion_deg: rmx - rmn,
            turning,
            bout_edge,
            accelerating: ramp_end_s.is_some_and(|e| t_hs < e),
            decelerating: slowdown_start_s.is_some_and(|s| t_next > s),
        });
    }
    strides
}
