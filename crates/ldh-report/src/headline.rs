//! The clinical headline at the top of a subject's page, in a clinician's words: the findings
//! that matter (asymmetry first), what could not be measured, and the one thing to do about
//! it. Rendered from the page's [`Verdicts`], so it never disagrees with the summary or
//! section 2 (docs/reports.md "The headline").

use maud::{html, Markup};

use super::html::plural;
use super::verdict::{Asymmetry, Cell, Judgement, Row, Scope, Verdicts};
use super::Reference;
use ldh_core::output::{Parameter, RecordingRow};
use ldh_core::pipeline::quality::codes;

/// At most this many findings are named; the rest are counted.
pub(crate) const MAX_FINDINGS: usize = 4;

/// What the headline says, as plain sentences (rendered by [`headline`]).
#[derive(Debug, Default, PartialEq)]
pub(crate) struct Headline {
    /// What the values are (e.g. the mean of two trials), when worth saying.
    pub context: Option<String>,
    /// The person's visits, when the recordings come from two or more (manifest `visit`).
    pub visits: Option<String>,
    /// On a treadmill with a given belt speed: the belt's speed is the walking speed.
    pub belt: Option<String>,
    /// The findings, asymmetry first, then the whole walk, then each side (at most
    /// [`MAX_FINDINGS`], then one sentence counting the rest).
    pub findings: Vec<String>,
    /// A walk without enough steady walking: its variability is not reported, and why (said
    /// before the findings).
    pub steady: Option<String>,
    /// What could not be measured, one sentence.
    pub not_measured: Option<String>,
    /// The one thing to do about it.
    pub to_do: Option<String>,
    /// No value of the summary was measured: there is nothing to call normal ("No finding"
    /// would be untrue).
    pub nothing_measured: bool,
}

/// `v` with its decimals and unit.
fn val(row: &Row, v: f64) -> String {
    let d = row.q.decimals;
    match row.q.parameter {
        // "4.4 %", not "4.4 CV %": the sentence names the variability.
        Parameter::StanceRatio | Parameter::StrideTimeCv | Parameter::StrideLengthCv => {
            format!("{v:.d$} %")
        }
        Parameter::Wqk | Parameter::Pbi | Parameter::Bdk => format!("{v:.d$}°"),
        _ => format!("{v:.d$} {}", row.q.unit()),
    }
}

/// The range of a row in clinical units ("96–126 steps/min").
fn range(row: &Row, reference: &Reference) -> String {
    let q = row.q;
    match reference.range(q.parameter) {
        Some(r) => match (r.low, r.high) {
            (Some(l), Some(h)) => {
                let d = q.decimals;
                let (l, h) = (l * q.scale(), h * q.scale());
                format!("normal {l:.d$}–{}", val(row, h))
            }
            _ => String::new(),
        },
        None => String::new(),
    }
}

/// The sentence of an asymmetry beyond the threshold: how much longer one side is, from the
/// symmetry index `si` (L/R = (1 + SI/200)/(1 − SI/200), so the shown values' rounding does
/// not enter), and the two sides' shown values.
fn asymmetry_sentence(row: &Row, si: f64) -> Option<String> {
    let (Cell::Value { v: l, .. }, Cell::Value { v: r, .. }) = (&row.cells[0], &row.cells[1])
    else {
        return None;
    };
    let (big, small, side, other) = if l >= r {
        (*l, *r, "left", "right")
    } else {
        (*r, *l, "right", "left")
    };
    let h = si.abs() / 200.0;
    if small <= 0.0 || h >= 1.0 {
        return None;
    }
    let pct = (100.0 * ((1.0 + h) / (1.0 - h) - 1.0)).round();
    let vs = format!("{} against {}", val(row, big), val(row, small));
    Some(match row.q.parameter {
        Parameter::StepTime => format!(
            "Steps are uneven: the {side} step takes {pct:.0} % longer than the {other} ({vs})."
        ),
        Parameter::StanceRatio => format!(
            "Stance is uneven: the {side} leg stays on the ground {pct:.0} % longer than the {other} ({vs} of the gait cycle; swing {:.1} % against {:.1} %).",
            100.0 - big,
            100.0 - small
        ),
        Parameter::StrideLength => format!(
            "Strides are uneven: the {side} stride is {pct:.0} % longer than the {other} ({vs})."
        ),
        _ => format!(
            "{} is uneven: {pct:.0} % larger on the {side} than on the {other} ({vs}).",
            row.q.label()
        ),
    })
}

/// The sentence of a quantity outside its range (the walk's, or a side's or both sides').
fn outside_sentence(row: &Row, reference: &Reference) -> Option<String> {
    let rng = range(row, reference);
    let out: Vec<(usize, f64, Judgement)> = row
        .cells
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match c {
            Cell::Value { v, judgement, .. } if judgement.mark().is_some() => {
                Some((i, *v, *judgement))
            }
            _ => None,
        })
        .collect();
    let first = out.first()?;
    let label = row.q.label();
    Some(match row.q.scope {
        Scope::Walk => format!(
            "{label} is {}: {} ({rng}).",
            first.2.words(),
            val(row, first.1)
        ),
        Scope::Side if out.len() == 2 && out[0].2 == out[1].2 => format!(
            "{label} is {} on both legs: {} left, {} right ({rng}).",
            first.2.words(),
            val(row, out[0].1),
            val(row, out[1].1)
        ),
        Scope::Side => {
            let parts: Vec<String> = out
                .iter()
                .map(|(i, v, j)| {
                    let side = if *i == 0 { "left" } else { "right" };
                    format!("{} on the {side}: {}", j.words(), val(row, *v))
                })
                .collect();
            format!("{label} is {} ({rng}).", parts.join("; "))
        }
    })
}

/// A finding's sentence with the trials its values come from, when a mean of trials has them
/// from some trials only ("…, from trial PWS-20 only."; [`Row::from_trials`]).
fn with_trials(sentence: String, row: &Row) -> String {
    match &row.from_trials {
        Some(f) => format!("{}, {f}.", sentence.trim_end_matches('.')),
        None => sentence,
    }
}

/// The number of values of a row marked ▲/▼ in the tables.
fn value_marks(row: &Row) -> usize {
    row.cells
        .iter()
        .filter(|c| c.judgement().and_then(Judgement::mark).is_some())
        .count()
}

/// The findings: flagged asymmetries (largest first), then the walk's and each side's values
/// outside their range, at most [`MAX_FINDINGS`] and a count of the rest — counted as the
/// tables mark them (one mark per value and per asymmetry), so "N more" is what a reader finds
/// marked there besides the findings named.
fn findings(v: &Verdicts, reference: &Reference) -> Vec<String> {
    // (sentence, the marks it stands for)
    let mut asym: Vec<(f64, String)> = v
        .rows
        .iter()
        .filter_map(|r| match r.asymmetry {
            Some(Asymmetry::Value(si, Some(true))) => {
                Some((si.abs(), with_trials(asymmetry_sentence(r, si)?, r)))
            }
            _ => None,
        })
        .collect();
    asym.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut all: Vec<(String, usize)> = asym.into_iter().map(|x| (x.1, 1)).collect();
    for scope in [Scope::Walk, Scope::Side] {
        all.extend(
            v.rows
                .iter()
                .filter(|r| r.q.scope == scope)
                .filter_map(|r| {
                    Some((
                        with_trials(outside_sentence(r, reference)?, r),
                        value_marks(r),
                    ))
                }),
        );
    }
    if all.len() > MAX_FINDINGS + 1 {
        let rest: usize = all[MAX_FINDINGS..].iter().map(|x| x.1).sum();
        all.truncate(MAX_FINDINGS);
        all.push((
            format!(
                "{rest} more {} marked in the tables below (▲/▼ outside the normal range, ◆ asymmetric).",
                plural(rest, "value is", "values are")
            ),
            0,
        ));
    }
    all.into_iter().map(|x| x.0).collect()
}

/// A walk that never became steady (`never_steady`, walk-level) or was not steady long enough
/// on a leg (`too_little_steady`): its variability is not reported, and why (the start-up and
/// changes of pace are not variability). Said before the findings, whose means it qualifies.
fn steady(sides: &[&RecordingRow]) -> Option<String> {
    // A leg with a sensor fault says so itself: its steadiness is not a finding.
    let sound: Vec<&&RecordingRow> = sides
        .iter()
        .filter(|r| {
            r.warnings
                .at_least(ldh_core::pipeline::Severity::Fault)
                .next()
                .is_none()
        })
        .collect();
    let has = |r: &RecordingRow, code| r.warnings.iter().any(|w| w.code == code);
    if sound.iter().any(|r| has(r, codes::NEVER_STEADY)) {
        return Some(
            "The walk never became steady: its stride time kept changing (speeding up, slowing down or changing pace), so the values below are of the whole walk and its stride time and stride length variability are not reported.".into(),
        );
    }
    let legs: Vec<&str> = sound
        .iter()
        .filter(|r| has(r, codes::TOO_LITTLE_STEADY))
        .map(|r| r.side.as_str())
        .collect();
    let who = match legs.as_slice() {
        [] => return None,
        [one] => format!("the {one} leg"),
        _ => "both legs".into(),
    };
    Some(format!(
        "The walk never settled into a steady pace long enough ({who}: fewer than 10 strides at a steady pace), so its stride time and stride length variability are not reported: the start-up and changes of pace would be read as variability."
    ))
}

/// What was not measured: the summary's quantities, named once each with the legs concerned.
/// With a belt speed given (`belt`) the walking speed is the belt's, said above, so the sensors'
/// missing estimate is not listed (the belt sentence says the sensors could not estimate it).
fn not_measured(v: &Verdicts, sides: &[&RecordingRow], belt: bool) -> Option<String> {
    let failed: Vec<&str> = sides
        .iter()
        .filter(|r| !r.is_ok())
        .map(|r| r.side.as_str())
        .collect();
    let mut parts: Vec<String> = failed
        .iter()
        .map(|s| format!("anything of the {s} leg (its recording could not be analysed)"))
        .collect();
    for row in v
        .rows
        .iter()
        .filter(|r| r.q.in_summary)
        .filter(|r| !(belt && r.q.parameter == Parameter::Speed))
    {
        let missing: Vec<usize> = (0..row.cells.len())
            .filter(|i| matches!(row.cells[*i], Cell::NotMeasured(_)))
            .filter(|i| row.q.scope == Scope::Walk || !failed.contains(&["left", "right"][*i]))
            .collect();
        let name = row.q.label().to_lowercase();
        match (row.q.scope, missing.len()) {
            (_, 0) => {}
            (Scope::Walk, _) if failed.len() < 2 => parts.push(name),
            (Scope::Side, 1) => parts.push(format!("{name} ({})", ["left", "right"][missing[0]])),
            (Scope::Side, _) => parts.push(name),
            _ => {}
        }
    }
    (!parts.is_empty()).then(|| format!("Could not be measured: {}.", parts.join(", ")))
}

/// On a treadmill with a belt speed given (manifest `belt_speed_mps`, the same for every
/// recording of the page): the belt speed is the walking speed, judged against the walking
/// speed's published range as the summary judges a value (bounds included, compared as shown),
/// the sensors' estimate beside it. TRIPOD's PWS−20 page said "the walking speed is the
/// belt's" and then "Could not be measured: walking speed" without judging the belt's 0.83 m/s
/// (below 1.00–1.60).
fn belt_sentence(
    v: &Verdicts,
    recordings: &[RecordingRow],
    reference: &Reference,
) -> Option<String> {
    let belt = recordings.first()?.belt_speed_mps?;
    if recordings.iter().any(|r| r.belt_speed_mps != Some(belt)) {
        return None;
    }
    let row = v
        .rows
        .iter()
        .find(|r| r.q.parameter == ldh_core::output::Parameter::Speed);
    let imu = row.and_then(|r| match r.cells.first() {
        Some(Cell::Value { v, .. }) => Some(val(r, *v)),
        _ => None,
    });
    let judged = row
        .and_then(|r| belt_judgement(r, belt, reference))
        .unwrap_or_default();
    Some(match imu {
        Some(x) => format!(
            "On a treadmill, belt at {belt:.2} m/s: the walking speed is the belt's{judged}; the speed the sensors estimate is {x}."
        ),
        None => format!(
            "On a treadmill, belt at {belt:.2} m/s: the walking speed is the belt's{judged}; the sensors could not estimate it."
        ),
    })
}

/// ", below normal (normal 1.00–1.60 m/s)" (or above, or within) for a belt speed `belt`, m/s,
/// against the walking speed row's range ([`super::verdict::judge`]: compared as shown, bounds
/// included); `None` without a range.
fn belt_judgement(row: &Row, belt: f64, reference: &Reference) -> Option<String> {
    let q = row.q;
    let j = super::verdict::judge(
        belt * q.scale(),
        reference.range(q.parameter),
        q.scale(),
        q.decimals,
    );
    j.judged()
        .then(|| format!(", {} ({})", j.words(), range(row, reference)))
}

/// The headline of a subject's page; `recordings` are the page's own rows (every trial).
pub(crate) fn make(
    v: &Verdicts,
    sides: &[&RecordingRow],
    recordings: &[RecordingRow],
    reference: &Reference,
    ctx: &super::RunContext,
) -> Headline {
    let belt = belt_sentence(v, recordings, reference);
    let not_measured = not_measured(v, sides, belt.is_some());
    let visits = super::visits::visit_changes(recordings, ctx);
    Headline {
        belt,
        context: {
            let mean = sides
                .iter()
                .find_map(|r| r.trial_mean.as_ref())
                .map(|t| format!("The values are the {t} of this person."));
            // The values of the disagreement are said under "Trials side by side"; a page of
            // two or more visits has no such section (its visits table stands there instead).
            let d = super::trials::Disagreement::of(recordings, ctx).map(|d| match visits {
                Some(_) => d.sentence(true),
                None => d.headline(),
            });
            match (mean, d) {
                (Some(m), Some(d)) => Some(format!("{m} {d}")),
                (m, d) => m.or(d),
            }
        },
        visits: visits.map(|c| super::visits::headline_sentence(&c)),
        findings: findings(v, reference),
        steady: steady(sides),
        to_do: super::todo::to_do(v, sides),
        nothing_measured: v
            .rows
            .iter()
            .filter(|r| r.q.in_summary)
            .all(|r| r.cells.iter().all(|c| matches!(c, Cell::NotMeasured(_)))),
        not_measured,
    }
}

/// The headline as HTML.
pub(crate) fn headline(h: &Headline) -> Markup {
    html! {
        div.headline {
            "\n"
            @if let Some(c) = &h.context { p { (c) } "\n" }
            @if let Some(c) = &h.visits { p { (c) } "\n" }
            @if let Some(c) = &h.belt { p { (c) } "\n" }
            @if let Some(n) = &h.steady { p { (n) } "\n" }
            @if h.nothing_measured {
                p { b { "Nothing could be judged: " } "no value of this walk was measured (the reasons follow)." } "\n"
            } @else if h.findings.is_empty() {
                p { b { "No finding: " } "every measured value lies within its normal range and left and right are even." } "\n"
            } @else {
                b { "Findings" } "\n"
                ul { @for f in &h.findings { li { (f) } "\n" } } "\n"
            }
            @if let Some(n) = &h.not_measured { p { (n) } "\n" }
            @if let Some(t) = &h.to_do { p { b { "To do: " } (t) } "\n" }
        }
        "\n"
    }
}
