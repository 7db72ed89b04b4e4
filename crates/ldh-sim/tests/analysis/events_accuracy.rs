//! The event-timing harness of issue 49: heel strike (HS) and toe off (TO) scored per dataset and
//! per condition, printed as the tables of docs/accuracy.md "Event timing per dataset and
//! condition (issue 49)".
//!
//! * The simulators, per condition (family A normal, LDH, slow LDH; family B normal, slow
//!   hemiparetic, normal walkers forced to 0.5 m/s): HS and TO bias, SD, P95 of |error| against
//!   the truth's steady strides ([`ldh_sim::evaluate::stride_scores`]). No bias is fitted to
//!   either family (they disagree by 25–40 ms on where HS and TO lie).
//! * TRIPOD (`../shared/realdata/tripod`, when present; PROVENANCE.md there): one person on a
//!   treadmill at three belt speeds, OptoGait per footfall. Each shank is aligned to OptoGait with
//!   one constant offset per shank and run (the median of ldh's HS − OptoGait's contact start),
//!   and the HS scatter is the SD of what remains; stride times per stride and the stride-time CV
//!   against OptoGait's; stride length against belt speed × stride time. First 125 s only.
//!
//! `cargo test --profile ci -p ldh-sim --test analysis events_accuracy -- --nocapture`
//! prints the tables.

use ldh_core::pipeline::{memory_report, Analysis, AnalysisParams, LegResult, SubjectInput};
use ldh_core::recording::{Recording, Side};
use ldh_sim::evaluate::stride_scores;
use ldh_sim::family_b::CohortParamsB;
use ldh_sim::{analyze_simulated, CohortParams, SimSubject};
use std::path::{Path, PathBuf};

/// Summary of signed errors (ms): n, bias, SD, P95 of |error|.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Summary {
    pub(crate) n: usize,
    pub(crate) bias: f64,
    pub(crate) sd: f64,
    pub(crate) p95: f64,
}

pub(crate) fn summary(v: &[f64]) -> Summary {
    let n = v.len();
    if n == 0 {
        return Summary {
            n,
            bias: f64::NAN,
            sd: f64::NAN,
            p95: f64::NAN,
        };
    }
    let bias = v.iter().sum::<f64>() / n as f64;
    let sd = (v.iter().map(|x| (x - bias).powi(2)).sum::<f64>() / (n.max(2) - 1) as f64).sqrt();
    let mut a: Vec<f64> = v.iter().map(|x| x.abs()).collect();
    a.sort_by(f64::total_cmp);
    let p95 = a[((n as f64 * 0.95).ceil() as usize).clamp(1, n) - 1];
    Summary { n, bias, sd, p95 }
}

pub(crate) fn fmt(s: Summary) -> String {
    format!("{:.1} / {:.1} / {:.1}", s.bias, s.sd, s.p95)
}

pub(crate) fn no_sta() -> AnalysisParams {
    AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    }
}

/// HS and TO errors (ms) of the steady strides of `subjects`.
fn sim_errors(subjects: &[SimSubject]) -> (Vec<f64>, Vec<f64>, usize, (usize, usize)) {
    let (mut hs, mut to, mut missed, mut unsure) = (Vec::new(), Vec::new(), 0, (0, 0));
    for s in subjects {
        let r = analyze_simulated(s, &no_sta());
        for leg in [&r.left, &r.right].into_iter().flatten() {
            print_unsure(leg);
            unsure.0 += leg
                .strides
                .iter()
                .filter(|s| s.reason.contains("unsure"))
                .count();
            unsure.1 += leg.strides.len();
        }
        for sc in stride_scores(&[r], &[s.truth()]) {
            match sc.hs_error_ms {
                Some(e) => hs.push(e),
                None => missed += 1,
            }
            match sc.to_error_ms {
                Some(e) => to.push(e),
                None => missed += 1,
            }
        }
    }
    (hs, to, missed, unsure)
}

/// The simulated conditions: (name, subjects). Seeds 4949 (nothing was tuned on them).
pub(crate) fn sim_conditions() -> Vec<(&'static str, Vec<SimSubject>)> {
    sim_conditions_at(4949)
}

/// The simulated conditions of [`sim_conditions`] drawn with `seed`.
pub(crate) fn sim_conditions_at(seed: u64) -> Vec<(&'static str, Vec<SimSubject>)> {
    let a = |healthy, ldh, slow_ldh| {
        let c = CohortParams {
            healthy,
            ldh,
            slow_ldh,
            duration_s: 30.0,
            seed,
            ..CohortParams::default()
        };
        (0..c.len()).map(|i| c.simulate(i).unwrap()).collect()
    };
    let b = |healthy, patients, speed_mps| {
        let c = CohortParamsB {
            healthy,
            patients,
            speed_mps,
            duration_s: 30.0,
            seed,
            ..CohortParamsB::default()
        };
        (0..c.len()).map(|i| c.simulate(i).unwrap()).collect()
    };
    vec![
        ("A normal", a(5, 0, 0)),
        ("A LDH", a(0, 5, 0)),
        ("A slow LDH", a(0, 0, 4)),
        ("B normal", b(5, 0, None)),
        ("B slow hemiparetic", b(0, 5, None)),
        (
            "B normal at 0.5 m/s (short, slow steps)",
            b(4, 0, Some(0.5)),
        ),
    ]
}

/// The unsure reasons of a leg, counted (diagnostics).
fn print_unsure(leg: &LegResult) {
    let mut c = std::collections::BTreeMap::new();
    for s in &leg.strides {
        for r in s.reason.split("; ").filter(|r| r.contains("unsure")) {
            *c.entry(r.to_string()).or_insert(0) += 1;
        }
    }
    if !c.is_empty() {
        println!("{} {:?} {c:?}", leg.source, leg.events.hs_impact_delay_s);
    }
}

/// Per simulated condition: HS and TO bias / SD / P95 (ms) and the missed events.
#[test]
fn events_accuracy_on_the_simulators() {
    let mut lines = vec![
        "| condition | HS n | HS bias / SD / P95 (ms) | TO n | TO bias / SD / P95 (ms) | missed | strides withheld as unsure |"
            .to_string(),
        "|---|---:|---|---:|---|---:|---:|".to_string(),
    ];
    let (mut worst, mut worst_hs): (f64, f64) = (0.0, 0.0);
    for (name, subjects) in sim_conditions() {
        let (hs, to, missed, unsure) = sim_errors(&subjects);
        let (h, t) = (summary(&hs), summary(&to));
        worst = worst.max(h.p95).max(t.p95);
        worst_hs = worst_hs.max(h.p95);
        assert_eq!(missed, 0, "{name}: steady events missed");
        lines.push(format!(
            "| {name} | {} | {} | {} | {} | {missed} | {} / {} |",
            h.n,
            fmt(h),
            t.n,
            fmt(t),
            unsure.0,
            unsure.1
        ));
    }
    println!("{}\nworst P95 {worst:.1} ms", lines.join("\n"));
    // Issue 49: no condition's heel-strike P95 above 30 ms (15.7 ms when written; toe off
    // is not there yet: docs/accuracy.md).
    assert!(worst_hs <= 30.0, "{}", lines.join("\n"));
}

pub(crate) mod tripod;
