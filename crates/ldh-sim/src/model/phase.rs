//! The gait timeline of family A: the left leg's continuous gait phase p(t) and the heading
//! ψ(t) of the optional 180° turn (the "Motion" paragraph of [`super`]).

use rand_chacha::ChaCha8Rng;

use super::super::jet::{smoothstep5, Jet, Quintic};
use super::super::{SubjectParams, RAMP_STRIDE_EXTRA};
use super::std_normal;
use ldh_core::error::{LdhError, Result};

/// A C² gait phase p(t) through knots (t, p, ṗ, p̈).
#[derive(Debug, Clone)]
pub(super) struct PhaseCurve {
    t: Vec<f64>,
    p: Vec<f64>,
    segs: Vec<Quintic>,
}

impl PhaseCurve {
    fn new(knots: &[(f64, f64, f64, f64)]) -> PhaseCurve {
        let segs = knots
            .windows(2)
            .map(|w| {
                let (t0, p0, v0, a0) = w[0];
                let (t1, p1, v1, a1) = w[1];
                Quintic::new(t0, t1, Jet::new(p0, v0, a0), Jet::new(p1, v1, a1))
            })
            .collect();
        PhaseCurve {
            t: knots.iter().map(|k| k.0).collect(),
            p: knots.iter().map(|k| k.1).collect(),
            segs,
        }
    }
    /// The phase (with its first two time derivatives) at time `t`, s; constant outside the
    /// knots.
    pub(super) fn eval(&self, t: f64) -> Jet {
        if t <= self.t[0] {
            return Jet::cst(self.p[0]);
        }
        if t >= *self.t.last().unwrap() {
            return Jet::cst(*self.p.last().unwrap());
        }
        let i = self.t.partition_point(|&x| x <= t) - 1;
        self.segs[i].eval(t)
    }
    /// The time at which the phase equals `p` (bisection; p(t) is monotone).
    pub(super) fn time_of(&self, p: f64) -> Option<f64> {
        if p < self.p[0] || p > *self.p.last().unwrap() {
            return None;
        }
        let i = self.p.partition_point(|&x| x < p).max(1) - 1;
        let seg = &self.segs[i.min(self.segs.len() - 1)];
        let (mut lo, mut hi) = (seg.t0, seg.t1);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if seg.eval(mid).v < p {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }
    fn is_monotone(&self) -> bool {
        self.segs.iter().all(|s| {
            (0..=200).all(|k| {
                let t = s.t0 + (s.t1 - s.t0) * k as f64 / 200.0;
                s.eval(t).d >= -1e-12
            })
        })
    }
}

/// Heading ψ(t): 0, then a C² ramp to π over the turn.
#[derive(Debug, Clone, Copy)]
pub(super) struct Heading {
    /// Start and end of the turn, s (None: a straight walk).
    pub(super) turn: Option<(f64, f64)>,
}

impl Heading {
    /// ψ at time `t`, rad, with its first two time derivatives.
    pub(super) fn eval(&self, t: f64) -> Jet {
        match self.turn {
            None => Jet::cst(0.0),
            Some((t0, t1)) => {
                let x = Jet::time(t).scale(1.0 / (t1 - t0)) - t0 / (t1 - t0);
                let (f, f1, f2) = smoothstep5(x.v);
                x.compose(f, f1, f2).scale(std::f64::consts::PI)
            }
        }
    }
}

/// The subject's gait timeline: how many strides, where the turn is, the left leg's phase and
/// the heading.
#[derive(Debug, Clone)]
pub(super) struct Timeline {
    /// Heel strikes of the left leg (phase 1 … n while walking).
    pub(super) n: usize,
    /// The first of the two turning strides (left phase), when the subject turns.
    pub(super) turn_strides: Option<usize>,
    /// Left gait phase p(t).
    pub(super) phase: PhaseCurve,
    /// Heading ψ(t).
    pub(super) heading: Heading,
    /// End of the belt start-up, s (`standing_s + ramp_s`; None without a ramp): strides that
    /// begin before it are accelerating.
    pub(super) ramp_end_s: Option<f64>,
    /// Start of the slowing down before the end, s (None without one): strides that end after
    /// it are decelerating.
    pub(super) slowdown_start_s: Option<f64>,
}

impl Timeline {
    /// Length of the per-stride tables of a leg (warp coefficients, heel positions, swings):
    /// `n + 3`, enough for the right leg's strides 1 … n + 1 and the ramps.
    pub(super) fn n_idx(&self) -> usize {
        self.n + 3
    }

    /// Draw the timeline: `standing_s` of quiet standing, then `n` left heel strikes with stride
    /// times drawn around `stride_time_s` (CV `stride_time_cv`, 10 % longer over the turn,
    /// clamped to 0.6–1.6 × the mean; a stride beginning `e` s into a belt start-up of `ramp_s`
    /// is then `1 + RAMP_STRIDE_EXTRA · (1 − e / ramp_s)` times longer), then standing again.
    /// Draws `n − 1` standard normals from `rng`. Errors: fewer than 4 strides fit in `duration_s`, or the drawn phase is not
    /// monotone.
    pub(super) fn draw(params: &SubjectParams, rng: &mut ChaCha8Rng) -> Result<Timeline> {
        let t0 = params.standing_s;
        let big_t = params.stride_time_s;
        // A start-up adds RAMP_STRIDE_EXTRA / 2 of its length on average.
        let walk_s = params.duration_s
            - 2.0 * params.standing_s
            - 1.8 * big_t
            - 0.5 * RAMP_STRIDE_EXTRA * (params.ramp_s + params.slowdown_s);
        // A trend makes the mean stride 1 + trend_share / 2 times the first.
        let n = (walk_s / (big_t * (1.0 + 0.5 * params.trend_share))).floor() as usize + 1; // heel strikes of the left leg
        if n < 4 {
            return Err(LdhError::param(
                "duration_s",
                params.duration_s,
                format!(
                    "too short for 4 strides after {} s of standing at each end",
                    params.standing_s
                ),
            ));
        }
        let turn_strides = if params.turn && n >= 8 {
            Some(n / 2 - 1)
        } else {
            None
        };
        let mut durations = Vec::with_capacity(n);
        for k in 1..n {
            let mut d = big_t * (1.0 + params.stride_time_cv * std_normal(rng));
            if let Some(kt) = turn_strides {
                if k >= kt && k < kt + 2 {
                    d *= 1.1;
                }
            }
            durations.push(d.clamp(0.6 * big_t, 1.6 * big_t));
        }
        if params.trend_share != 0.0 {
            let last = durations.len().saturating_sub(1).max(1) as f64;
            for (k, d) in durations.iter_mut().enumerate() {
                *d *= 1.0 + params.trend_share * k as f64 / last;
            }
        }
        if params.slowdown_s > 0.0 {
            // The walk ends 0.9 strides after the last heel strike (the mirror of the ramp).
            let mut elapsed = 0.9 * big_t;
            for d in durations.iter_mut().rev() {
                let left = (1.0 - elapsed / params.slowdown_s).max(0.0);
                *d *= 1.0 + RAMP_STRIDE_EXTRA * left;
                elapsed += *d;
            }
        }
        if params.ramp_s > 0.0 {
            // The first heel strike comes 0.9 strides after the walk starts.
            let mut elapsed = 0.9 * big_t;
            for d in durations.iter_mut() {
                let left = (1.0 - elapsed / params.ramp_s).max(0.0);
                *d *= 1.0 + RAMP_STRIDE_EXTRA * left;
                elapsed += *d;
            }
        }
        let phase = PhaseCurve::new(&phase_knots(t0, big_t, &durations));
        if !phase.is_monotone() {
            return Err(LdhError::param(
                "stride_time_cv",
                params.stride_time_cv,
                "gives a non-monotone gait phase",
            ));
        }
        let heading = Heading {
            turn: turn_strides.map(|kt| {
                (
                    phase.time_of(kt as f64).unwrap(),
                    phase.time_of(kt as f64 + 2.0).unwrap(),
                )
            }),
        };
        Ok(Timeline {
            n,
            turn_strides,
            phase,
            heading,
            ramp_end_s: (params.ramp_s > 0.0).then_some(t0 + params.ramp_s),
            slowdown_start_s: (params.slowdown_s > 0.0)
                .then(|| t0 + 1.8 * big_t + durations.iter().sum::<f64>() - params.slowdown_s),
        })
    }
}

/// The knots (t s, p, ṗ 1/s, p̈ 1/s²) of the left phase: at rest at phase 0.55 from `t0`, heel
/// strike k at phase k (k = 1 … n, `durations[k − 1]` apart, the rate the inverse of the mean
/// of the neighbouring stride times), at rest at phase n + 0.55 0.9 strides after the last.
fn phase_knots(t0: f64, big_t: f64, durations: &[f64]) -> Vec<(f64, f64, f64, f64)> {
    let n = durations.len() + 1;
    let mut knots = vec![(t0, 0.55, 0.0, 0.0)];
    let mut t = t0 + 0.9 * big_t;
    for k in 1..=n {
        let prev = if k == 1 {
            durations[0]
        } else {
            durations[k - 2]
        };
        let next = if k == n {
            durations[n - 2]
        } else {
            durations[k - 1]
        };
        let v = 2.0 / (prev + next);
        knots.push((t, k as f64, v, 0.0));
        if k < n {
            t += durations[k - 1];
        }
    }
    let t_end = t + 0.9 * big_t;
    knots.push((t_end, n as f64 + 0.55, 0.0, 0.0));
    knots
}
