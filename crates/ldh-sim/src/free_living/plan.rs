//! The activity plan of a free-living recording: nights, non-wear periods and the day's rest
//! episodes and movements as a list of [`Segment`]s on the left (true) clock. Durations and
//! proportions are stated at each draw; the module docs of [`super`] cite their sources.

use std::str::FromStr;

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, LogNormal};
use serde::{Deserialize, Serialize};

use super::FreeLivingParams;
use crate::draw::{normal_clamped, std_normal};
use crate::SubjectParams;

/// What a subject does in a truth bout (`truth_bouts.csv`'s `activity`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Activity {
    /// Level walking (the gait model).
    Walking,
    /// Stair climbing, up and down in turn: short slow strides, each step one riser up or down
    /// (`SubjectParams::stair_rise_m`), high swing clearance, more hip and knee flexion.
    Stairs,
    /// Running: the fastest strides of the gait model with strong heel impacts.
    Running,
    /// Cycling: the shank rotating with the pedal crank at ≈ 1 Hz, no impacts.
    Cycling,
    /// Sitting: shank near vertical or tilted (−35° to +20°).
    Sitting,
    /// Standing: shank vertical.
    Standing,
    /// Lying: shank horizontal (supine, on a side, prone).
    Lying,
    /// The sensors off the body, still on a table.
    NonWear,
    /// Short irregular leg motion while sitting (2–20 s).
    Fidgeting,
}

impl Activity {
    /// Every activity, in the order of the enum.
    pub const ALL: [Activity; 9] = [
        Activity::Walking,
        Activity::Stairs,
        Activity::Running,
        Activity::Cycling,
        Activity::Sitting,
        Activity::Standing,
        Activity::Lying,
        Activity::NonWear,
        Activity::Fidgeting,
    ];

    /// The name in `truth_bouts.csv`: `walking`, `stairs`, `running`, `cycling`, `sitting`,
    /// `standing`, `lying`, `non_wear`, `fidgeting`.
    pub fn as_str(self) -> &'static str {
        match self {
            Activity::Walking => "walking",
            Activity::Stairs => "stairs",
            Activity::Running => "running",
            Activity::Cycling => "cycling",
            Activity::Sitting => "sitting",
            Activity::Standing => "standing",
            Activity::Lying => "lying",
            Activity::NonWear => "non_wear",
            Activity::Fidgeting => "fidgeting",
        }
    }

    /// Rest, non-wear or cycling: the time in which found walking is false walking (issue 52's
    /// "false walking in rest, non-wear and cycling").
    pub fn counts_against_false_walking(self) -> bool {
        matches!(
            self,
            Activity::Sitting
                | Activity::Standing
                | Activity::Lying
                | Activity::NonWear
                | Activity::Cycling
        )
    }
}

impl std::fmt::Display for Activity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for Activity {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Activity::ALL
            .into_iter()
            .find(|a| a.as_str() == s.trim())
            .ok_or_else(|| format!("'{s}' is not an activity (walking, stairs, running, cycling, sitting, standing, lying, non_wear, fidgeting)"))
    }
}

/// How the legs move in a segment (rendered by [`super::render`]).
#[derive(Debug, Clone)]
pub(super) enum Motion {
    /// Worn rest: the specific-force direction in the shank frame F per leg, with a slow sway.
    Rest { up_f: [[f64; 3]; 2] },
    /// Off the body: the gravity direction in each device's own frame, no motion.
    Table { up_device: [[f64; 3]; 2] },
    /// Pedalling: crank frequency, mean shank pitch and its amplitude.
    Cycling {
        cadence_hz: f64,
        mean_pitch_deg: f64,
        amp_pitch_deg: f64,
    },
    /// Seated leg motion: a windowed sum of three sinusoids of shank pitch per moving leg.
    Fidget {
        up_f: [[f64; 3]; 2],
        moving: [bool; 2],
        freq_hz: [f64; 3],
        amp_deg: [f64; 3],
        phase: [f64; 3],
    },
    /// A gait bout of the family A model; `impact_g` > 0 adds heel impacts (running).
    Gait {
        params: Box<SubjectParams>,
        impact_g: f64,
    },
}

/// One planned segment on the true (left) clock.
#[derive(Debug, Clone)]
pub(super) struct Segment {
    /// The activity (a gait segment also holds standing before and after its walk).
    pub activity: Activity,
    /// Start, s from the first sample.
    pub start_s: f64,
    /// Length, s.
    pub duration_s: f64,
    /// The motion.
    pub motion: Motion,
}

/// Quiet standing before and after each gait bout inside its gait segment, s.
pub(super) const GAIT_STANDING_S: f64 = 1.0;

fn lognormal(rng: &mut ChaCha8Rng, median: f64, sigma: f64, lo: f64, hi: f64) -> f64 {
    let d = LogNormal::new(median.ln(), sigma).expect("valid");
    d.sample(rng).clamp(lo, hi)
}

/// A unit vector near `v`: each component perturbed by N(0, `sd`), renormalised.
fn jitter(rng: &mut ChaCha8Rng, v: [f64; 3], sd: f64) -> [f64; 3] {
    let w: [f64; 3] = std::array::from_fn(|k| v[k] + sd * std_normal(rng));
    let n = w.iter().map(|x| x * x).sum::<f64>().sqrt();
    w.map(|x| x / n)
}

/// The specific-force direction in F of a shank at pitch θ and frame roll φ (ZYX, ψ = 0):
/// (−sin θ, sin φ cos θ, cos φ cos θ).
pub(super) fn up_from_angles(pitch_deg: f64, roll_deg: f64) -> [f64; 3] {
    let (t, p) = (pitch_deg.to_radians(), roll_deg.to_radians());
    [-t.sin(), p.sin() * t.cos(), p.cos() * t.cos()]
}

/// A worn rest posture of both legs.
fn rest_motion(rng: &mut ChaCha8Rng, activity: Activity) -> Motion {
    let up_f = match activity {
        Activity::Standing => std::array::from_fn(|_| {
            up_from_angles(
                normal_clamped(rng, 2.0, 2.0, -4.0, 8.0),
                normal_clamped(rng, 0.0, 2.0, -5.0, 5.0),
            )
        }),
        Activity::Lying => {
            let u: f64 = rng.gen();
            let base = if u < 0.45 {
                [1.0, 0.0, 0.0] // supine: anterior up
            } else if u < 0.70 {
                [0.0, 1.0, 0.0] // on the right side: left up
            } else if u < 0.95 {
                [0.0, -1.0, 0.0]
            } else {
                [-1.0, 0.0, 0.0] // prone
            };
            std::array::from_fn(|_| jitter(rng, base, 0.15))
        }
        _ => {
            let pitch = rng.gen_range(-35.0..20.0);
            std::array::from_fn(|_| {
                up_from_angles(
                    pitch + normal_clamped(rng, 0.0, 5.0, -12.0, 12.0),
                    normal_clamped(rng, 0.0, 4.0, -10.0, 10.0),
                )
            })
        }
    };
    Motion::Rest { up_f }
}

/// The sensors on a table: mostly flat (device z up or down), sometimes on an edge.
fn table_motion(rng: &mut ChaCha8Rng) -> Motion {
    let mut face = || {
        let faces = [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let i = if rng.gen_bool(0.8) {
            rng.gen_range(0..2)
        } else {
            rng.gen_range(2..4)
        };
        jitter(rng, faces[i], 0.01)
    };
    Motion::Table {
        up_device: [face(), face()],
    }
}

fn fidget_motion(rng: &mut ChaCha8Rng) -> Motion {
    let Motion::Rest { up_f } = rest_motion(rng, Activity::Sitting) else {
        unreachable!("sitting is rest")
    };
    let which = rng.gen_range(0..3);
    Motion::Fidget {
        up_f,
        moving: [which != 1, which != 0],
        freq_hz: std::array::from_fn(|_| rng.gen_range(0.8..5.0)),
        amp_deg: std::array::from_fn(|_| rng.gen_range(1.0..8.0)),
        phase: std::array::from_fn(|_| rng.gen_range(0.0..std::f64::consts::TAU)),
    }
}

/// A gait bout of `walk_s` of gait from the subject's `base` gait: stride time and length
/// varied by N(0, 4 %) from bout to bout; stairs and running change the gait as
/// [`Activity`] says (`up`: a flight of stairs climbed, else descended). Returns the segment
/// length too (walk plus standing at both ends).
fn gait_motion(
    rng: &mut ChaCha8Rng,
    base: &SubjectParams,
    activity: Activity,
    walk_s: f64,
    up: bool,
) -> (Motion, f64) {
    let mut p = base.clone();
    let f = normal_clamped(rng, 1.0, 0.04, 0.9, 1.1);
    p.stride_time_s = (p.stride_time_s * f).clamp(0.75, 1.95);
    p.stride_length_m =
        (p.stride_length_m * normal_clamped(rng, 1.0, 0.04, 0.9, 1.1)).clamp(0.35, 2.1);
    p.standing_s = GAIT_STANDING_S;
    p.turn = walk_s > 20.0 && rng.gen_bool(0.5);
    let mut impact_g = 0.0;
    match activity {
        Activity::Stairs => {
            p.stride_time_s = normal_clamped(rng, 1.25, 0.06, 1.1, 1.45);
            p.stride_length_m = normal_clamped(rng, 0.6, 0.04, 0.5, 0.7);
            // Two treads a stride (0.25–0.35 m each) and a riser of 0.17 m at 0.30 m treads
            // (a tread/riser ratio kept: steeper stairs, shorter treads); descent a little
            // quicker than ascent (Riener et al. 2002: cadence in descent ≈ 5–10 % higher).
            let rise = 0.17 * p.stride_length_m / 0.6;
            p.stair_rise_m = if up { rise } else { -rise };
            if !up {
                p.stride_time_s *= 0.92;
            }
            for l in [&mut p.left, &mut p.right] {
                l.hip_scale = 1.35;
                l.knee_reduction = -0.25;
                l.swing_clearance_m = 0.18;
                l.stance_ratio = l.stance_ratio.max(0.64);
            }
            p.turn = false;
        }
        Activity::Running => {
            p.stride_time_s = normal_clamped(rng, 0.72, 0.02, 0.7, 0.78);
            p.stride_length_m = normal_clamped(rng, 2.05, 0.08, 1.8, 2.2);
            for l in [&mut p.left, &mut p.right] {
                l.stance_ratio = 0.55;
                l.hip_scale = 1.4;
                l.knee_reduction = -0.3;
                l.swing_clearance_m = 0.12;
            }
            p.turn = false;
            impact_g = rng.gen_range(4.0..7.0);
        }
        _ => {}
    }
    let min_s = 5.6 * p.stride_time_s + 0.5;
    let walk_s = walk_s.max(min_s);
    p.duration_s = walk_s + 2.0 * GAIT_STANDING_S;
    let d = p.duration_s;
    (
        Motion::Gait {
            params: Box::new(p),
            impact_g,
        },
        d,
    )
}

/// Fixed blocks: nights (lying) and non-wear, as (start, end, is_night) on the true clock.
fn fixed_blocks(params: &FreeLivingParams, rng: &mut ChaCha8Rng) -> Vec<(f64, f64, bool)> {
    let st = &params.start;
    let tod0 = f64::from(st.hour) * 3600.0 + f64::from(st.minute) * 60.0 + f64::from(st.second);
    let total = params.duration_h * 3600.0;
    let days = (total + tod0) / 86400.0;
    let mut blocks = Vec::new();
    let mut bed_prev = -tod0 - 86400.0 + 23.0 * 3600.0;
    for d in 0..=(days.ceil() as i64) {
        let midnight = d as f64 * 86400.0 - tod0;
        let wake = midnight + 7.0 * 3600.0 + normal_clamped(rng, 0.0, 2400.0, -5400.0, 5400.0);
        let bed = midnight + 23.0 * 3600.0 + normal_clamped(rng, 0.0, 2400.0, -5400.0, 5400.0);
        blocks.push((bed_prev, wake, true));
        // Shower or dressing after waking: 15–45 min off.
        let s = wake + rng.gen_range(600.0..3600.0);
        blocks.push((s, s + rng.gen_range(900.0..2700.0), false));
        if rng.gen_bool(0.5) {
            let s = midnight + rng.gen_range(13.0..19.0) * 3600.0;
            blocks.push((s, s + rng.gen_range(1200.0..7200.0), false));
        }
        bed_prev = bed;
    }
    blocks.retain(|b| b.1 > 0.0 && b.0 < total);
    blocks
}

/// Plan the whole recording: the fixed blocks, with the day's episodes between them.
/// Segments are contiguous from 0 to `duration_h`.
pub(super) fn plan(
    params: &FreeLivingParams,
    base: &SubjectParams,
    rng: &mut ChaCha8Rng,
) -> Vec<Segment> {
    let total = params.duration_h * 3600.0;
    let blocks = fixed_blocks(params, rng);
    let mut segs: Vec<Segment> = Vec::new();
    let mut t = 0.0;
    for (b0, b1, night) in blocks.into_iter().chain([(total, total, false)]) {
        fill_day(rng, base, &mut segs, &mut t, b0.min(total));
        let end = b1.min(total);
        while t < end {
            let (activity, motion, d) = if night {
                let d = rng.gen_range(1800.0..7200.0);
                (Activity::Lying, rest_motion(rng, Activity::Lying), d)
            } else {
                (Activity::NonWear, table_motion(rng), f64::INFINITY)
            };
            let d = d.min(end - t);
            push(&mut segs, &mut t, activity, motion, d);
        }
    }
    segs
}

fn push(segs: &mut Vec<Segment>, t: &mut f64, activity: Activity, motion: Motion, d: f64) {
    segs.push(Segment {
        activity,
        start_s: *t,
        duration_s: d,
        motion,
    });
    *t += d;
}

/// Fill [t, end) with daytime episodes: a rest episode (sitting 60 %, median 5 min; standing
/// 35 %, median 45 s; lying 5 %, median 10 min), fidgeting in 40 % of sittings, then a
/// movement: walking 90 % (log-normal, median 15 s, 35 % followed by a 2–10 s stop and another
/// bout), stairs 8 % (8–25 s), cycling 1 % (5–30 min), running 1 % (1–10 min).
fn fill_day(
    rng: &mut ChaCha8Rng,
    base: &SubjectParams,
    segs: &mut Vec<Segment>,
    t: &mut f64,
    end: f64,
) {
    while end - *t > 1e-9 {
        let u: f64 = rng.gen();
        let (activity, d) = if u < 0.60 {
            (Activity::Sitting, lognormal(rng, 300.0, 1.0, 20.0, 5400.0))
        } else if u < 0.95 {
            (Activity::Standing, lognormal(rng, 45.0, 0.9, 3.0, 1200.0))
        } else {
            (Activity::Lying, lognormal(rng, 600.0, 0.6, 120.0, 3600.0))
        };
        let d = d.min(end - *t);
        if activity == Activity::Sitting && d > 60.0 && rng.gen_bool(0.4) {
            let f = rng.gen_range(2.0..20.0);
            let first = rng.gen_range(0.2..0.8) * (d - f);
            let m = rest_motion(rng, Activity::Sitting);
            push(segs, t, activity, m.clone(), first);
            push(segs, t, Activity::Fidgeting, fidget_motion(rng), f);
            push(segs, t, activity, m, d - f - first);
        } else {
            push(segs, t, activity, rest_motion(rng, activity), d);
        }
        let u: f64 = rng.gen();
        let (activity, want_s) = if u < 0.90 {
            (Activity::Walking, lognormal(rng, 15.0, 1.0, 5.0, 600.0))
        } else if u < 0.98 {
            (Activity::Stairs, rng.gen_range(8.0..25.0))
        } else if u < 0.99 {
            (Activity::Cycling, rng.gen_range(300.0..1800.0))
        } else {
            (Activity::Running, rng.gen_range(60.0..600.0))
        };
        movement(rng, base, segs, t, end, activity, want_s);
        while activity == Activity::Walking && rng.gen_bool(0.35) && end - *t > 30.0 {
            let stop = rng.gen_range(2.0..10.0);
            push(
                segs,
                t,
                Activity::Standing,
                rest_motion(rng, Activity::Standing),
                stop,
            );
            let w = lognormal(rng, 15.0, 1.0, 5.0, 600.0);
            movement(rng, base, segs, t, end, Activity::Walking, w);
        }
    }
}

/// One movement of about `want_s` s ending before `end`; standing when it does not fit.
fn movement(
    rng: &mut ChaCha8Rng,
    base: &SubjectParams,
    segs: &mut Vec<Segment>,
    t: &mut f64,
    end: f64,
    activity: Activity,
    want_s: f64,
) {
    let left = end - *t;
    if left <= 1e-9 {
        return;
    }
    if activity == Activity::Cycling {
        let m = Motion::Cycling {
            cadence_hz: rng.gen_range(0.85..1.3),
            mean_pitch_deg: rng.gen_range(10.0..25.0),
            amp_pitch_deg: rng.gen_range(15.0..25.0),
        };
        push(segs, t, activity, m, want_s.min(left));
        return;
    }
    // Flights of stairs go up and down in turn (what goes up comes down): no draw, so the
    // plan's random stream is that of the level stairs before them.
    let up = segs
        .iter()
        .filter(|s| s.activity == Activity::Stairs)
        .count()
        % 2
        == 0;
    let (motion, d) = gait_motion(rng, base, activity, want_s, up);
    if d <= left {
        push(segs, t, activity, motion, d);
    } else {
        push(
            segs,
            t,
            Activity::Standing,
            rest_motion(rng, Activity::Standing),
            left,
        );
    }
}
