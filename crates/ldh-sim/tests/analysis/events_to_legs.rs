//! Toe off per leg (issue 49 item 2): where the simulators' toe-off P95 comes from, and the
//! per-leg consistency checks tried as a confidence for it (docs/accuracy.md "Toe-off
//! consistency checks per leg").
//!
//! For every leg of the conditions of `events_accuracy.rs` it prints the mean and SD of the toe
//! off's error over the truth's steady strides, the bracket fraction k the rule used and the
//! truth's, and what a check can read without the truth (bracket width, ρ and swing arc of both
//! legs, stance, the leg's terminal double support — from the other leg's heel strike to this
//! leg's toe off — and the median stride). Then each candidate check: the legs it would flag as
//! unsure, how many of them the rule placed within 30 ms (flagged for nothing), and the toe-off
//! P95 of the strides it would keep. It asserts what the doc says of the error: a constant per
//! leg (each leg's SD small against the spread of the legs' means).
//!
//! `cargo test --profile ci -p ldh-sim --test analysis events_to_legs -- --nocapture`
//! (seed 4949; `LDH_SEEDS=100,101,102,103,7,2026` for the seeds the checks were chosen on).

use super::events_accuracy::{no_sta, sim_conditions_at, summary};
use ldh_core::events::{landmark_geometry, BRACKET_K0};
use ldh_core::pipeline::LegResult;
use ldh_sim::{analyze_simulated, LegTruth};

/// The median of the finite values (upper for an even count; NaN when none).
pub(crate) fn med(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One leg: its toe-off errors (ms) and what a check can read without the truth.
struct Leg {
    name: String,
    errors_ms: Vec<f64>,
    k_used: f64,
    k_true: f64,
    width_ms: f64,
    ln_rho: f64,
    ln_arc: f64,
    stance: f64,
    other_stance: f64,
    terminal_ds: f64,
    other_terminal_ds: f64,
    stride_s: f64,
}

/// The last value of `v` (sorted) at or before `t` and within `max` of it.
fn before(v: &[f64], t: f64, max: f64) -> Option<f64> {
    v.iter().copied().rev().find(|&x| x <= t && t - x < max)
}

/// The leg's median stance (ldh's events) and terminal double support, fractions of the stride.
fn stance_and_ds(ev: &ldh_core::events::Events, other_hs: &[f64]) -> (f64, f64) {
    let t = ev.median_stride_s;
    let (mut st, mut ds) = (Vec::new(), Vec::new());
    for &to in &ev.to_s {
        if let Some(h) = before(&ev.hs_s, to, t) {
            st.push((to - h) / t);
        }
        if let Some(oh) = before(other_hs, to, 0.5 * t) {
            ds.push((to - oh) / t);
        }
    }
    (med(st), med(ds))
}

fn leg(name: String, leg: &LegResult, other: &LegResult, truth: &LegTruth) -> Leg {
    let ev = &leg.events;
    let (mut errors_ms, mut k_used, mut k_true, mut width) = (vec![], vec![], vec![], vec![]);
    for s in truth.strides.iter().filter(|s| !s.turning && !s.bout_edge) {
        let to = &ev.to_s;
        let nearest = (0..to.len())
            .min_by(|&a, &b| {
                (to[a] - s.to_time_s)
                    .abs()
                    .total_cmp(&(to[b] - s.to_time_s).abs())
            })
            .filter(|&j| (to[j] - s.to_time_s).abs() < 0.25);
        let Some(j) = nearest else { continue };
        errors_ms.push(1e3 * (to[j] - s.to_time_s));
        if let Some(&[ts, tp, _]) = ev.to_landmarks_s.get(j) {
            k_used.push((to[j] - ts) / (tp - ts));
            k_true.push((s.to_time_s - ts) / (tp - ts));
            width.push(1e3 * (tp - ts));
        }
    }
    let (g, og) = (landmark_geometry(ev), landmark_geometry(&other.events));
    let ratio = |f: fn(&ldh_core::events::LegGeometry) -> Option<f64>| match (g, og) {
        (Some(a), Some(b)) => match (f(&a), f(&b)) {
            (Some(x), Some(y)) => (x / y).ln(),
            _ => f64::NAN,
        },
        _ => f64::NAN,
    };
    let (stance, terminal_ds) = stance_and_ds(ev, &other.events.hs_s);
    let (other_stance, other_terminal_ds) = stance_and_ds(&other.events, &ev.hs_s);
    Leg {
        name,
        errors_ms,
        k_used: med(k_used),
        k_true: med(k_true),
        width_ms: med(width),
        ln_rho: ratio(|g| Some(g.rho)),
        ln_arc: -ratio(|g| g.swing_arc_deg),
        stance,
        other_stance,
        terminal_ds,
        other_terminal_ds,
        stride_s: ev.median_stride_s,
    }
}

/// A candidate check: its name and whether it flags a leg's toe offs as unsure.
type Check = (&'static str, fn(&Leg) -> bool);

/// The checks tried (docs/accuracy.md), each chosen on family A seeds 7, 100–103 and 2026 but
/// the last, chosen on family B's same seeds; reported on the other family and on seed 4949.
const CHECKS: [Check; 8] = [
    // Double-support asymmetry between the legs (the one precise check; it needs the two
    // sensors on one clock, which TRIPOD's are not, so it was not adopted).
    ("terminal DS > 1.5 x the other leg's", |l| {
        l.terminal_ds > 1.5 * l.other_terminal_ds
    }),
    ("terminal DS > 1.8 x the other leg's", |l| {
        l.terminal_ds > 1.8 * l.other_terminal_ds
    }),
    ("the two DS differ > 1.5 x", |l| {
        l.terminal_ds.max(l.other_terminal_ds) > 1.5 * l.terminal_ds.min(l.other_terminal_ds)
    }),
    ("the two DS differ > 1.8 x", |l| {
        l.terminal_ds.max(l.other_terminal_ds) > 1.8 * l.terminal_ds.min(l.other_terminal_ds)
    }),
    // The leg's own double support (the best single threshold on family A but slowness).
    ("terminal double support > 0.164 of the stride", |l| {
        l.terminal_ds > 0.164
    }),
    // Slowness itself.
    ("median stride > 1.35 s", |l| l.stride_s > 1.35),
    // The bracket-width rule of 2026-11-26 (chosen then on family A seed 100).
    ("bracket wider than 160 ms", |l| l.width_ms > 160.0),
    // Family B: a leg the rule raised whose stance then comes out the longer of the two
    // (every over-raised normal leg at 0.5 m/s of those seeds; a paretic leg's is the shorter).
    ("raised, and its stance the longer", |l| {
        l.k_used > BRACKET_K0 + 0.05 && l.stance > l.other_stance
    }),
];

#[test]
fn events_to_legs_on_the_simulators() {
    let seeds: Vec<u64> = std::env::var("LDH_SEEDS")
        .unwrap_or_else(|_| "4949".into())
        .split(',')
        .filter_map(|s| s.trim().parse().ok())
        .collect();
    let mut table = vec![
        "| seed | condition | leg | n | TO error mean / SD (ms) | k used / true | bracket (ms) | ln ρ/ρ_other | ln arc_other/arc | stance / other's | terminal DS | stride (s) |".to_string(),
        "|---|---|---|---:|---|---|---:|---:|---:|---|---:|---:|".to_string(),
    ];
    let mut checks = vec![
        "| seed | condition | check | legs flagged | of them within 30 ms | TO P95 of the kept strides (ms), before → after |".to_string(),
        "|---|---|---|---|---:|---|".to_string(),
    ];
    let mut scattered = Vec::new();
    for &seed in &seeds {
        for (cond, subjects) in sim_conditions_at(seed) {
            let mut legs = Vec::new();
            for s in &subjects {
                let r = analyze_simulated(s, &no_sta());
                let (Ok(l), Ok(rr)) = (&r.left, &r.right) else {
                    continue;
                };
                let id = &s.params.subject_id;
                legs.push(leg(format!("{id} L"), l, rr, &s.left.truth));
                legs.push(leg(format!("{id} R"), rr, l, &s.right.truth));
            }
            for l in &legs {
                let e = summary(&l.errors_ms);
                table.push(format!(
                    "| {seed} | {cond} | {} | {} | {:.1} / {:.1} | {:.2} / {:.2} | {:.0} | {:.3} | {:.3} | {:.3} / {:.3} | {:.3} | {:.2} |",
                    l.name, e.n, e.bias, e.sd, l.k_used, l.k_true, l.width_ms, l.ln_rho, l.ln_arc,
                    l.stance, l.other_stance, l.terminal_ds, l.stride_s
                ));
                if e.n >= 2 && e.sd >= 25.0 {
                    scattered.push(format!("{seed} {cond} {}: {e:?}", l.name));
                }
            }
            let all: Vec<f64> = legs.iter().flat_map(|l| l.errors_ms.clone()).collect();
            for (name, flags) in CHECKS {
                let flagged: Vec<&Leg> = legs.iter().filter(|l| flags(l)).collect();
                let right = flagged
                    .iter()
                    .filter(|l| l.errors_ms.iter().all(|e| e.abs() <= 30.0))
                    .count();
                let kept: Vec<f64> = legs
                    .iter()
                    .filter(|l| !flags(l))
                    .flat_map(|l| l.errors_ms.clone())
                    .collect();
                checks.push(format!(
                    "| {seed} | {cond} | {name} | {} / {} | {right} | {:.1} → {:.1} |",
                    flagged.len(),
                    legs.len(),
                    summary(&all).p95,
                    summary(&kept).p95
                ));
            }
        }
    }
    println!("{}\n\n{}", table.join("\n"), checks.join("\n"));
    // The error is a constant per leg on seed 4949: its steps scatter little about their leg's
    // mean (on the other seeds one slow hemiparetic leg of seed 100 scatters, SD 35 ms).
    if seeds == [4949] {
        assert!(scattered.is_empty(), "{scattered:?}");
    }
    println!("legs whose steps scatter (SD >= 25 ms): {scattered:?}");
}
