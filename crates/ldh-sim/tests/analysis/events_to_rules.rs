//! Toe-off rules from the literature scored per simulated condition (issue 49 item 1; the table
//! "Toe-off rules tried" of docs/accuracy.md). Each rule places a toe off from what the default
//! detector already found in the same stride (its landmarks t_s, t_p, t_m and the aligned
//! signals), so only the rule differs; errors are against the truth's steady strides, detected −
//! true, with **no bias fitted** to either family.
//!
//! * the default (`gyro-bracket`): t_s + k·(t_p − t_s), k raised on the stiffer leg;
//! * t_s, the late-stance peak of ω_s: Aminian et al. 2002 (J Biomech 35:689; "the minimum of
//!   the shank's angular velocity before swing" in their sign), Salarian et al. 2004 (IEEE TBME
//!   51:1434) and Trojaniello et al. 2014 (J NeuroEng Rehabil 11:152; "the negative peak before
//!   the swing peak");
//! * t_p, the pitch peak (the paper's toe off, ω_s = 0);
//! * k₀ of the bracket on every leg (the default without the other leg);
//! * the steepest fall of ω_s between t_s and mid-swing (the shank's largest forward angular
//!   acceleration as the swing begins);
//! * acceleration features at push-off (the kind issue 49 names after Lee et al. 2010 and
//!   Catalfamo et al. 2010; their exact definitions were not checked): the largest anterior
//!   acceleration and the largest change of the acceleration vector between t_s and the middle
//!   of [t_p, t_m];
//! * a level of the pitch (2026-12-03, `events_to_pitch.rs`): where ∫ω_s from t_s reaches
//!   [`PITCH_SHARE`] of its rise to t_p.
//!
//! `cargo test --profile ci -p ldh-sim --test analysis events_to_rules -- --nocapture`

use super::events_accuracy::{fmt, no_sta, sim_conditions, summary};
use super::events_to_pitch::{at, cumulative, reach, PITCH_SHARE};
use ldh_core::events::BRACKET_K0;
use ldh_core::pipeline::LegResult;
use ldh_sim::analyze_simulated;
use ldh_sim::LegTruth;

/// The rules, in table order.
pub(crate) const RULES: [&str; 8] = [
    "default (bracket, stiffer leg raised)",
    "t_s (Aminian 2002, Salarian 2004, Trojaniello 2014)",
    "t_p, the pitch peak (the paper)",
    "bracket k0 on every leg",
    "steepest fall of w_s in [t_s, t_m]",
    "largest anterior acceleration in [t_s, (t_p + t_m)/2]",
    "largest |da| in [t_s, (t_p + t_m)/2]",
    "pitch level: f of the pitch rise from t_s to t_p (2026-12-03)",
];

/// Time (s) of the largest value of `y` between `a_s` and `b_s`, on the sample grid (these
/// rules miss by tens of ms: a sample's ±5 ms does not change their rank).
fn argmax_s(y: &[f64], fs: f64, a_s: f64, b_s: f64) -> Option<f64> {
    let (a, b) = (
        (a_s * fs).ceil() as usize,
        ((b_s * fs).floor() as usize).min(y.len() - 1),
    );
    let i = (a..=b).max_by(|&i, &j| y[i].total_cmp(&y[j]))?;
    Some(i as f64 / fs)
}

/// Each rule's toe off for each detected toe off of `leg` (rows in [`RULES`] order).
pub(crate) fn rule_toe_offs(leg: &LegResult) -> Vec<Vec<f64>> {
    let ev = &leg.events;
    let al = leg.signals.as_ref().expect("signals kept");
    let fs = al.fs_hz;
    let w = &al.gyro_dps[1];
    let n = w.len();
    // dω/dt (deg/s per sample), negated: its maximum is the steepest fall.
    let fall: Vec<f64> = (0..n)
        .map(|i| {
            if i == 0 || i + 1 >= n {
                0.0
            } else {
                -(w[i + 1] - w[i - 1]) / 2.0
            }
        })
        .collect();
    let a = &al.acc_g;
    let da: Vec<f64> = (0..n)
        .map(|i| {
            if i == 0 {
                return 0.0;
            }
            (0..3)
                .map(|k| (a[k][i] - a[k][i - 1]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let cum = cumulative(w, fs);
    let mut rows = vec![Vec::new(); RULES.len()];
    for (j, &[ts, tp, tm]) in ev.to_landmarks_s.iter().enumerate() {
        let mid = 0.5 * (tp + tm);
        let cand = [
            ev.to_s[j],
            ts,
            tp,
            ts + BRACKET_K0 * (tp - ts),
            argmax_s(&fall, fs, ts, tm).unwrap_or(f64::NAN),
            argmax_s(&a[0], fs, ts, mid).unwrap_or(f64::NAN),
            argmax_s(&da, fs, ts, mid).map_or(f64::NAN, |t| t - 0.5 / fs),
            {
                let (cs, cp) = (at(&cum, fs, ts), at(&cum, fs, tp));
                reach(&cum, fs, ts, tp, cs + PITCH_SHARE * (cp - cs))
            },
        ];
        for (r, c) in rows.iter_mut().zip(cand) {
            r.push(c);
        }
    }
    rows
}

/// Each rule's errors (ms) on the steady true strides of one leg: the toe off nearest the true
/// one (within 250 ms) of the default gives the stride whose landmarks the rules read.
fn leg_errors(leg: &LegResult, truth: &LegTruth, out: &mut [Vec<f64>]) {
    if leg.events.to_landmarks_s.len() != leg.events.to_s.len() {
        return;
    }
    let rows = rule_toe_offs(leg);
    for ts in truth.strides.iter().filter(|s| !s.turning && !s.bout_edge) {
        let to = &leg.events.to_s;
        let Some(j) = (0..to.len())
            .min_by(|&a, &b| {
                (to[a] - ts.to_time_s)
                    .abs()
                    .total_cmp(&(to[b] - ts.to_time_s).abs())
            })
            .filter(|&j| (to[j] - ts.to_time_s).abs() < 0.25)
        else {
            continue;
        };
        for (o, r) in out.iter_mut().zip(&rows) {
            if r[j].is_finite() {
                o.push(1e3 * (r[j] - ts.to_time_s));
            }
        }
    }
}

/// Per simulated condition and rule: TO bias / SD / P95 (ms).
#[test]
fn events_to_rules_on_the_simulators() {
    let mut lines = vec![
        "| condition | rule | n | TO bias / SD / P95 (ms) |".to_string(),
        "|---|---|---:|---|".to_string(),
    ];
    for (name, subjects) in sim_conditions() {
        let mut errs = vec![Vec::new(); RULES.len()];
        for s in &subjects {
            let r = analyze_simulated(s, &no_sta());
            for (leg, truth) in [(&r.left, &s.left.truth), (&r.right, &s.right.truth)] {
                if let Ok(leg) = leg {
                    leg_errors(leg, truth, &mut errs);
                }
            }
        }
        for (rule, e) in RULES.iter().zip(&errs) {
            let s = summary(e);
            lines.push(format!("| {name} | {rule} | {} | {} |", s.n, fmt(s)));
        }
        // The default's row is the harness's own TO row (same matching within 250 ms).
        assert!(!errs[0].is_empty(), "{name}: no toe off scored");
    }
    println!("{}", lines.join("\n"));
}
