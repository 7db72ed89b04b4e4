//! The true gait events of one family A leg (heel strikes at integer leg phase, toe offs at
//! canonical phase stride + 0.60) and the swing trajectories between them.

use super::super::curves::TOE_OFF;
use super::super::jet::{JetVec3, Quintic};
use super::leg::{LegModel, Shared, Swing};

/// The true events of one leg, s from the first sample.
#[derive(Debug, Clone)]
pub(super) struct LegEvents {
    /// Heel strikes.
    pub(super) hs: Vec<f64>,
    /// Toe offs.
    pub(super) to: Vec<f64>,
}

/// Find the heel strikes and toe offs of `leg` over its strides `first_stride … first_stride +
/// n` (`n`: left heel strikes of the timeline) and fit each swing: a quintic in the ankle's x
/// and z from the stance ankle at toe off of stride j to the stance ankle at heel strike j + 1,
/// matching position, velocity and acceleration at both ends (stored in `leg.swing[j]`).
pub(super) fn leg_events(leg: &mut LegModel, sh: &Shared, n: usize) -> LegEvents {
    let j_first = leg.first_stride();
    let j_last = j_first + n;
    let mut hs = Vec::new();
    let mut to = Vec::new();
    for j in j_first..=j_last {
        if let Some(t) = sh.phase.time_of(j as f64 - leg.offset) {
            if j > j_first {
                hs.push((j, t));
            }
        }
        if j < j_last {
            let pq = leg.phase_of_q(j as f64 + TOE_OFF);
            if let Some(t) = sh.phase.time_of(pq - leg.offset) {
                to.push((j, t));
            }
        }
    }
    // Swing quintics from TO_j to HS_{j+1}.
    for &(j, t_to) in &to {
        let Some(&(_, t_hs)) = hs.iter().find(|(jj, _)| *jj == j + 1) else {
            continue;
        };
        let at = |t: f64, jj: usize, leg: &LegModel| -> JetVec3 {
            let pj = leg.leg_phase(sh, t);
            let q = leg.warp(pj);
            let alpha = leg.alpha(pj);
            leg.stance_ankle(q, jj, alpha)
        };
        let a = at(t_to, j, leg);
        let b = at(t_hs, j + 1, leg);
        leg.swing[j] = Some(Swing {
            x: Quintic::new(t_to, t_hs, a[0], b[0]),
            z: Quintic::new(t_to, t_hs, a[2], b[2]),
        });
    }
    LegEvents {
        hs: hs.iter().map(|e| e.1).collect(),
        to: to.iter().map(|e| e.1).collect(),
    }
}
