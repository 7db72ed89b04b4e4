//! The steady window on real walks (issue 50): it must not cut steady walking. HuGaDB's
//! overground walks (18 files, 17 healthy young adults) and TRIPOD's treadmill runs (one healthy
//! adult at three belt speeds, steady by design for the first 125 s; then the belt slows to a
//! stop), when `../shared/realdata` is present (one line when skipped). Each walk is analysed
//! with and without the rule; the share of its valid strides the window keeps is printed per
//! leg and asserted. The same walks check the swap warning: none on the files as labelled,
//! and, printed, whether it fires with the two files exchanged.
//!
//! `cargo test --profile ci -p ldh-sim --test analysis real_walks -- --nocapture`

use super::events_accuracy::tripod::TRIPOD_UNTIL_S;
use super::real_data::{real_walks, RealSet};
use ldh_core::gait::STEADY_REASON;
use ldh_core::pipeline::quality::{codes, swapped_mounting};
use ldh_core::pipeline::{Analysis, AnalysisParams, LoadedLeg, SubjectInput, SubjectResult};
use ldh_core::recording::Side;

/// The default analysis without STA, the steady rule on or off.
fn params(steady: bool) -> AnalysisParams {
    let mut p = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    p.steady.enabled = steady;
    p
}

/// Per leg of an analysed walk: (valid strides without the rule, strides the rule excluded).
fn kept(on: &SubjectResult, off: &SubjectResult) -> Vec<(Side, usize, usize, String)> {
    let mut out = Vec::new();
    for (a, b) in [(&on.left, &off.left), (&on.right, &off.right)] {
        let (Ok(a), Ok(b)) = (a.as_ref(), b.as_ref()) else {
            continue;
        };
        let valid = b.strides.iter().filter(|s| s.valid).count();
        let cut = a
            .strides
            .iter()
            .filter(|s| s.reason.contains(STEADY_REASON))
            .count();
        let w = a.steady.map_or("no window".into(), |w| {
            format!(
                "window {:.1}–{:.1} s, excluded {} + {}{}",
                w.start_s,
                w.end_s,
                w.excluded_start,
                w.excluded_end,
                if w.never_steady { ", never steady" } else { "" }
            )
        });
        out.push((a.side, valid, cut, w));
    }
    out
}

/// `leg` given as the other side's file (a manifest with the files exchanged).
fn as_side(leg: LoadedLeg, side: Side) -> LoadedLeg {
    leg.map(|(rec, rep, name)| (rec.with_side(side), rep, name))
}

/// Whether the swap warning fires on a walk's result, and how far each device's face turns
/// toward the other leg (deg; negative: away from it).
fn swap_finding(res: &SubjectResult) -> (bool, String) {
    let fired = res.warnings.iter().any(|w| w.code == codes::POSSIBLE_SWAP);
    let faces = match (res.left.as_ref(), res.right.as_ref()) {
        (Ok(l), Ok(r)) => {
            let face = |a: &ldh_core::align::Alignment| {
                a.r_f_from_device[1][2].clamp(-1.0, 1.0).asin().to_degrees()
            };
            format!(
                "faces {:.0}° / {:.0}° inward{}",
                -face(&l.alignment),
                face(&r.alignment),
                if swapped_mounting(l, r).is_some() {
                    " (swap rule met)"
                } else {
                    ""
                }
            )
        }
        _ => "a leg failed".into(),
    };
    (fired, faces)
}

/// Analyse `input` with the two legs `leg()` gives, with and without the rule; print and return
/// the per-leg kept shares. Also the swap check with the files as given (pushed to `false_swaps`
/// when it fires) and exchanged.
fn shares(
    name: &str,
    input: &SubjectInput,
    leg: impl Fn(Side) -> LoadedLeg,
    false_swaps: &mut Vec<String>,
) -> Vec<f64> {
    let run = |steady: bool| {
        Analysis::new(params(steady).check().unwrap()).pair(
            input,
            leg(Side::Left),
            leg(Side::Right),
        )
    };
    let (on, off) = (run(true), run(false));
    let exchanged = Analysis::new(params(true).check().unwrap()).pair(
        input,
        as_side(leg(Side::Right), Side::Left),
        as_side(leg(Side::Left), Side::Right),
    );
    let ((fired, faces), (fired_x, _)) = (swap_finding(&on), swap_finding(&exchanged));
    println!("{name}: swap warning as labelled {fired}, files exchanged {fired_x}; {faces}");
    if fired {
        false_swaps.push(name.to_string());
    }
    kept(&on, &off)
        .into_iter()
        .map(|(side, valid, cut, w)| {
            let share = 1.0 - cut as f64 / valid.max(1) as f64;
            println!(
                "{name} {side}: {valid} valid strides, {cut} excluded as not steady, {:.1} % kept; {w}",
                100.0 * share
            );
            share
        })
        .collect()
}

#[test]
fn the_steady_window_keeps_steady_real_walking() {
    let Some(walks) = real_walks() else {
        return;
    };
    let mut all = Vec::new();
    let mut false_swaps = Vec::new();
    for walk in walks.iter().filter(|w| w.set == RealSet::HuGaDb) {
        let leg = |side| walk.leg(side, f64::INFINITY);
        all.extend(shares(&walk.name(), &walk.input, leg, &mut false_swaps));
    }
    let hugadb_min = all.iter().fold(1.0_f64, |a, &b| a.min(b));
    let mut tripod = Vec::new();
    let mut full = Vec::new();
    for walk in walks.iter().filter(|w| w.set == RealSet::Tripod) {
        for (until, out) in [(TRIPOD_UNTIL_S, &mut tripod), (f64::INFINITY, &mut full)] {
            let name = format!("{} until {until} s", walk.name());
            let leg = |side| walk.leg(side, until);
            out.extend(shares(&name, &walk.input, leg, &mut false_swaps));
        }
    }
    let min = |v: &[f64]| v.iter().fold(1.0_f64, |a, &b| a.min(b));
    println!(
        "kept (smallest leg): HuGaDB {:.1} %, TRIPOD first 125 s {:.1} %, TRIPOD whole runs {:.1} %",
        100.0 * hugadb_min,
        100.0 * min(&tripod),
        100.0 * min(&full)
    );
    // Measured 2026-12-02 (docs/accuracy.md "One steady window per walk"): HuGaDB 53.1 % (03_01,
    // one leg of 32 strides whose first 15 are slower), TRIPOD 84.9 % (PWS: the first 24 s,
    // strides 1.35 s shortening to 1.25 s, are a real start-up), 83.8 % on whole runs (PWS: its
    // start-up and, since the fit runs at both ends in both directions, the belt's slow-down,
    // which a dip of shorter strides had hidden); the CUSUM rule before it kept 27.8 % of
    // TRIPOD's PWS run.
    assert!(hugadb_min >= 0.5, "HuGaDB {hugadb_min}");
    // Issue 50: no swap warning on a correctly labelled real walk.
    assert!(false_swaps.is_empty(), "{false_swaps:?}");
    assert!(
        min(&tripod) >= 0.8 && min(&full) >= 0.8,
        "{tripod:?} {full:?}"
    );
}
