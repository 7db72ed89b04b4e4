//! The cohort page's people and trials: the header's counts (people apart from trials, people
//! with both legs analysed) and "Trials of one person", a person's trials side by side (grouped
//! by visit) with their difference (docs/reports.md "Cohort report").

use maud::{html, Markup};

use super::html::fmt;
use ldh_core::cohort::{person_row, PARAMETERS};
use ldh_core::output::{rows_by_subject, Parameter, RecordingRow};
use ldh_core::Side;

/// What the cohort page's header counts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Counts {
    /// People (distinct `subject_id`).
    pub people: usize,
    /// Trials: distinct (`subject_id`, `trial_id`) pairs (a person without trial ids has one).
    pub trials: usize,
    /// Recordings (one per leg and trial).
    pub recordings: usize,
    /// Recordings analysed (status ok or no valid strides).
    pub analysed: usize,
    /// People with both legs analysed (in at least one trial each).
    pub both_legs: usize,
}

impl Counts {
    /// The counts of `rows`.
    pub(crate) fn of(rows: &[RecordingRow]) -> Counts {
        let mut trials: Vec<(&str, &str)> = rows
            .iter()
            .map(|r| (r.subject_id.as_str(), r.trial_id.as_str()))
            .collect();
        trials.sort_unstable();
        trials.dedup();
        let people = rows_by_subject(rows);
        let both_legs = people
            .iter()
            .filter(|(_, recs)| {
                [Side::Left, Side::Right]
                    .into_iter()
                    .all(|s| person_row(recs, s).is_some_and(|r| r.is_ok()))
            })
            .count();
        Counts {
            people: people.len(),
            trials: trials.len(),
            recordings: rows.len(),
            analysed: rows.iter().filter(|r| r.is_ok()).count(),
            both_legs,
        }
    }
}

/// One column of a person's comparison: a trial (its visit, its id) and its walk's values.
pub(super) struct Trial<'a> {
    pub(super) visit: &'a str,
    pub(super) id: &'a str,
    legs: Vec<&'a RecordingRow>,
}

impl Trial<'_> {
    /// The walk's value of `p`: the mean of both legs, `None` unless both legs have one. The
    /// cadence (`p` step frequency, steps/s) is the run's walk cadence of both legs' steps
    /// (`walk_cadence_steps_per_min`, the summary's), never the mean of the legs' step
    /// frequencies: with uneven steps that mean is larger than the steps per minute (TRIPOD's
    /// 0.42 / 0.76 s steps read 103 steps/min in a walk of 96).
    pub(super) fn value(&self, p: Parameter) -> Option<f64> {
        if p == Parameter::StepFrequency {
            return self
                .legs
                .iter()
                .filter(|r| r.is_ok())
                .find_map(|r| r.walk(ldh_core::domain::WalkValue::Cadence))
                .map(|per_min| per_min / 60.0);
        }
        let side = |s: Side| {
            self.legs
                .iter()
                .find(|r| r.side == s && r.is_ok())
                .and_then(|r| r.value(p))
        };
        Some((side(Side::Left)? + side(Side::Right)?) / 2.0)
    }
}

/// The analysed trials of a person in column order: visits in time order when every visit is a
/// date (`2024-03-05`, or a date and time), else in order of first appearance; then trials in
/// order of appearance.
pub(super) fn trials_of<'a>(recs: &[&'a RecordingRow]) -> Vec<Trial<'a>> {
    let mut visits: Vec<&str> = Vec::new();
    let mut out: Vec<Trial> = Vec::new();
    for r in recs.iter().filter(|r| r.is_ok()) {
        if !visits.contains(&r.visit.as_str()) {
            visits.push(&r.visit);
        }
        match out.iter_mut().find(|t| t.id == r.trial_id) {
            Some(t) => t.legs.push(r),
            None => out.push(Trial {
                visit: &r.visit,
                id: &r.trial_id,
                legs: vec![r],
            }),
        }
    }
    let dates: Option<Vec<ldh_core::io::DateTime>> = visits.iter().map(|v| visit_date(v)).collect();
    if let Some(d) = dates {
        let mut by_date: Vec<(ldh_core::io::DateTime, &str)> = d.into_iter().zip(visits).collect();
        by_date.sort_by_key(|a| a.0);
        visits = by_date.into_iter().map(|(_, v)| v).collect();
    }
    out.sort_by_key(|t| visits.iter().position(|v| *v == t.visit));
    out
}

/// A visit label as a date (`2024-03-05`, `2024/03/05`) or date and time, when it is one.
fn visit_date(v: &str) -> Option<ldh_core::io::DateTime> {
    v.parse()
        .ok()
        .or_else(|| format!("{} 00:00", v.trim()).parse().ok())
}

/// The visits of `trials` in column order, each with its number of trials.
pub(super) fn visits_of<'a>(trials: &[Trial<'a>]) -> Vec<(&'a str, usize)> {
    let mut v: Vec<(&str, usize)> = Vec::new();
    for t in trials {
        match v.last_mut() {
            Some((name, n)) if *name == t.visit => *n += 1,
            _ => v.push((t.visit, 1)),
        }
    }
    v
}

/// The mean of the walk values of `p` over the trials of `visit` (`None` when none has one).
pub(super) fn visit_mean(trials: &[Trial], visit: &str, p: Parameter) -> Option<f64> {
    let v: Vec<f64> = trials
        .iter()
        .filter(|t| t.visit == visit)
        .filter_map(|t| t.value(p))
        .collect();
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// Decimals of a parameter in the comparison.
pub(super) fn decimals(p: Parameter) -> usize {
    if p.is_angle() {
        1
    } else {
        3
    }
}

/// The difference column: with two or more visits, the last visit's mean minus the first's;
/// otherwise the last trial minus the first. Its header and the values.
fn difference(trials: &[Trial], p: Parameter) -> Option<f64> {
    let visits = visits_of(trials);
    let mean_of = |visit: &str| visit_mean(trials, visit, p);
    if visits.len() >= 2 {
        Some(mean_of(visits.last()?.0)? - mean_of(visits[0].0)?)
    } else {
        Some(trials.last()?.value(p)? - trials.first()?.value(p)?)
    }
}

fn difference_header(trials: &[Trial]) -> String {
    let visits = visits_of(trials);
    match (visits.first(), visits.last(), trials.first(), trials.last()) {
        (Some(a), Some(b), _, _) if visits.len() >= 2 => {
            format!("{} − {} (visit means)", b.0, a.0)
        }
        (_, _, Some(a), Some(b)) => format!("{} − {}", b.id, a.id),
        _ => String::new(),
    }
}

/// "Trials of one person": for each person with two or more analysed trials, per parameter
/// the walk's value (mean of both legs) of each trial side by side, grouped by visit, and
/// their difference. No change is marked here: the subject page's "Change between visits"
/// (`visits.rs`) marks those beyond a reliability table's MDC95. `title` makes the numbered heading
/// (called only when the section is shown, so an absent section takes no number).
pub(crate) fn trials_of_people(
    rows: &[RecordingRow],
    links: &std::collections::HashMap<&str, &str>,
    title: impl FnOnce() -> Markup,
) -> Markup {
    let people: Vec<(&str, Vec<Trial>)> = rows_by_subject(rows)
        .into_iter()
        .map(|(id, recs)| (id, trials_of(&recs)))
        .filter(|(_, t)| t.len() >= 2)
        .collect();
    if people.is_empty() {
        return html! {};
    }
    html! {
        (title())
        p.meta { "Each person with two or more analysed trials: per parameter the value of each trial (the mean of both legs; a dash when a leg has none), trials grouped by visit, and their difference (with two visits, the difference of the visits' means). No change is marked here: each person's page (\"Change between visits\") marks the changes beyond the measurement's own noise when a reliability table is given." } "\n"
        @for (id, trials) in &people {
            h3 {
                "Trials of this person: "
                @if let Some(href) = links.get(id) { a href=(href) { (id) } } @else { (id) }
            } "\n"
            @if nothing_measured(trials) {
                p { "No value was measured in any of this person's " (trials.len()) " trials (the reasons are on the person's page)." } "\n"
            } @else {
                (trial_table(trials, &PARAMETERS))
            }
        }
    }
}

/// Whether no trial has a value of any parameter: their table would be dashes only.
fn nothing_measured(trials: &[Trial]) -> bool {
    PARAMETERS
        .into_iter()
        .all(|p| trials.iter().all(|t| t.value(p).is_none()))
}

/// One person's trials side by side: per parameter of `params` the walk value of each trial,
/// grouped by visit, and their difference.
fn trial_table(trials: &[Trial], params: &[Parameter]) -> Markup {
    let visits = visits_of(trials);
    let several_visits = visits.len() >= 2;
    html! {
        table.trials {
            @if several_visits {
                tr { th colspan="2" {} @for (v, n) in &visits { th colspan=(n) { "visit " (v) } } th {} } "\n"
            }
            tr {
                th { "parameter" } th { "unit" }
                @for t in trials { th { "trial " (t.id) } }
                th { (difference_header(trials)) }
            }
            "\n"
            @for &p in params {
                @let (scale, unit, d) = shown(p);
                tr {
                    td { (p.code()) " — " (p.name()) } td { (unit) }
                    @for t in trials { td.num { (fmt(t.value(p).map(|v| v * scale), d)) } }
                    td.num { (signed(difference(trials, p).map(|v| v * scale), d)) }
                }
                "\n"
            }
        }
        "\n"
    }
}

/// How the trials table shows `p`: in the clinical unit of the person's page (stance in % of
/// the gait cycle, variability as CV %, step frequency in steps/min), with the page's decimals
/// (one more for a value the page shows without decimals, so a small difference stays
/// visible): (factor from the table's unit, unit, decimals).
fn shown(p: Parameter) -> (f64, &'static str, usize) {
    let (scale, unit) = p.display();
    // Swing, the complement of stance, with stance's decimals (the cohort page read "36.61").
    let like = match p {
        Parameter::SwingRatio => Parameter::StanceRatio,
        _ => p,
    };
    let d = super::verdict::quantities()
        .iter()
        .find(|q| q.parameter == like)
        .map_or(2, |q| q.decimals.max(1));
    (scale, unit, d)
}

/// `v` with its sign (`+0.012`), an en dash when missing.
pub(super) fn signed(v: Option<f64>, dec: usize) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:+.dec$}"),
        _ => "–".into(),
    }
}

/// The parameters whose disagreement between a person's trials is said in words: the
/// clinical summary's per-walk quantities (cadence is their stride time).
const SAID: [Parameter; 7] = [
    Parameter::StrideTime,
    Parameter::StepTime,
    Parameter::StanceRatio,
    Parameter::StrideLength,
    Parameter::Speed,
    Parameter::StrideTimeCv,
    Parameter::StrideLengthCv,
];

/// Without a reliability table, a difference between two trials is named when it exceeds this
/// share of their mean (the report's asymmetry threshold, `asymmetry_flag_pct`, read the same
/// way): named, never called beyond the noise.
pub(crate) const NAMED_DIFFERENCE_SHARE: f64 = 0.10;

/// `v` (the table's unit) in clinical units with its decimals ("1.03 s", "13.0 %").
fn clinical(p: Parameter, v: f64) -> String {
    let (scale, unit) = p.display();
    let d = super::verdict::quantities()
        .iter()
        .find(|q| q.parameter == p)
        .map_or(2, |q| q.decimals);
    let unit = if scale == 100.0 { "%" } else { unit };
    format!("{:.d$} {unit}", v * scale)
}

/// What a person's trials disagree on: per parameter of [`SAID`] whose first and last trial
/// differ beyond the reliability table's MDC95 (or, without one, by more than
/// [`NAMED_DIFFERENCE_SHARE`] of their mean), its name and the two values in words.
pub(crate) struct Disagreement {
    /// (parameter name, "1.03 s in trial t1 against 1.18 s in trial t2[, MDC95 0.08 s]").
    parts: Vec<(&'static str, String)>,
    /// Judged against a reliability table's MDC95 (else the 10 % rule).
    by_mdc: bool,
    /// The trials' belt speeds ("PWS 1.03, PWS+20 1.22 m/s") when they were walked on a
    /// treadmill at different speeds: their timing and speed differ by design.
    belts: Option<String>,
}

impl Disagreement {
    /// The disagreement of a person's first and last analysed trial; `None` with fewer than
    /// two analysed trials or when they agree.
    pub(crate) fn of(recordings: &[RecordingRow], ctx: &super::RunContext) -> Option<Self> {
        let recs: Vec<&RecordingRow> = recordings.iter().collect();
        let trials = trials_of(&recs);
        let (first, last) = (trials.first()?, trials.last()?);
        if trials.len() < 2 {
            return None;
        }
        let table = ctx.reliability.as_ref();
        let mut parts: Vec<(&'static str, String)> = Vec::new();
        for p in SAID {
            let (Some(a), Some(b)) = (first.value(p), last.value(p)) else {
                continue;
            };
            let mdc = table.and_then(|t| t.mdc95(p));
            let beyond = match (table, mdc) {
                (Some(_), Some(m)) => (a - b).abs() > m,
                (Some(_), None) => false,
                (None, _) => (a - b).abs() > NAMED_DIFFERENCE_SHARE * 0.5 * (a + b).abs(),
            };
            if beyond {
                let noise = mdc.map_or(String::new(), |m| format!(", MDC95 {}", clinical(p, m)));
                parts.push((
                    p.name(),
                    format!(
                        "{} in trial {} against {} in trial {}{noise}",
                        clinical(p, a),
                        first.id,
                        clinical(p, b),
                        last.id
                    ),
                ));
            }
        }
        let belt = |t: &Trial| t.legs.iter().find_map(|r| r.belt_speed_mps);
        let belts = trials
            .iter()
            .map(|t| Some(format!("{} {:.2}", t.id, belt(t)?)))
            .collect::<Option<Vec<String>>>()
            .filter(|_| trials.iter().any(|t| belt(t) != belt(first)))
            .map(|b| format!("{} m/s", b.join(", ")));
        (!parts.is_empty()).then_some(Disagreement {
            parts,
            by_mdc: table.is_some(),
            belts,
        })
    }

    /// By how much, in words; `noise`: with what that means without a reliability table.
    fn by(&self, noise: bool) -> &'static str {
        match (self.by_mdc, noise) {
            (true, _) => "by more than the measurement's own noise (MDC95 of the reliability table)",
            (false, true) => "by more than 10 % (without a reliability table, whether this is beyond the measurement's noise is not known)",
            (false, false) => "by more than 10 %",
        }
    }

    /// The full sentence, each parameter with its two values (issue 50 item 5): under "Trials
    /// side by side" (`noise` false: the headline above says what 10 % means without a
    /// reliability table), or in the headline when the page has no such section (two visits).
    pub(crate) fn sentence(&self, noise: bool) -> String {
        let parts: Vec<String> = self
            .parts
            .iter()
            .map(|(name, vs)| format!("{name} {vs}"))
            .collect();
        let differ = match &self.belts {
            Some(b) => format!("were walked at different belt speeds ({b}) and differ"),
            None => "disagree".into(),
        };
        format!(
            "The trials {differ} {}: {}. The page shows their mean; look at each trial before relying on it.",
            self.by(noise),
            parts.join("; ")
        )
    }

    /// The headline's short sentence: the parameters named, their values left to "Trials side
    /// by side" (the page said them twice, a third of a printed page on a real person's trials).
    pub(crate) fn headline(&self) -> String {
        let names: Vec<&str> = self.parts.iter().map(|p| p.0).collect();
        let list = match names.as_slice() {
            [one] => one.to_string(),
            [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
            [] => String::new(),
        };
        match &self.belts {
            Some(b) => format!(
                "The trials were walked at different belt speeds ({b}), and they differ in {list} {}: the page shows the mean of different speeds; look at each trial under \"Trials side by side\" before relying on it.",
                self.by(true)
            ),
            None => format!(
                "The trials disagree in {list} {}: the page shows their mean; look at each trial under \"Trials side by side\" before relying on it.",
                self.by(true)
            ),
        }
    }
}

/// The person's own trials side by side on their page (two or more analysed trials), with
/// their disagreement in words; `title` makes the heading.
pub(crate) fn person_trials(
    recordings: &[RecordingRow],
    ctx: &super::RunContext,
    title: impl FnOnce() -> Markup,
) -> Markup {
    let recs: Vec<&RecordingRow> = recordings.iter().collect();
    if trials_of(&recs).len() < 2 {
        return html! {};
    }
    let trials = trials_of(&recs);
    // Only the parameters some trial measured (a leg that failed in every trial leaves the
    // walk values empty: a table of dashes says nothing and lengthens the printed page; with
    // none, one sentence says so), and
    // not swing, the complement of stance (the page shows it beside stance, never alone).
    let params: Vec<Parameter> = PARAMETERS
        .into_iter()
        .filter(|&p| p != Parameter::SwingRatio)
        .filter(|&p| trials.iter().any(|t| t.value(p).is_some()))
        .collect();
    if params.is_empty() {
        // A table of dashes says nothing: one sentence says so (why: under the summary).
        let ids: Vec<&str> = trials.iter().map(|t| t.id).collect();
        return html! {
            (title())
            p { "No value was measured in any of the " (trials.len()) " trials (" (ids.join(", ")) "), so there is nothing to compare; why is said under the clinical summary." } "\n"
        };
    }
    let agree = match ctx.reliability {
        Some(_) => "The trials agree: no parameter of the summary differs between the first and the last trial by more than its MDC95 (reliability table).",
        None => "The trials agree: no parameter of the summary differs between the first and the last trial by more than 10 %.",
    };
    html! {
        (title())
        p { (Disagreement::of(recordings, ctx).map_or(agree.to_string(), |d| d.sentence(false))) } "\n"
        (trial_table(&trials, &params))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ldh_core::cohort::{ReliabilityRow, ReliabilityTable};

    fn walk(trial: &str, stride_s: f64, cv: f64) -> Vec<RecordingRow> {
        ["left", "right"]
            .iter()
            .map(|side| {
                let mut r = crate::tests::row("P", "ldh", side, 1.2);
                r.trial_id = trial.into();
                r.parameters[Parameter::StrideTime] = Some(stride_s);
                r.parameters[Parameter::StrideTimeCv] = Some(cv);
                r
            })
            .collect()
    }

    /// With a reliability table, only a difference beyond the MDC95 is named, with it; a
    /// parameter the table has no MDC95 for is not named (issue 50 item 2).
    #[test]
    fn trials_are_said_to_disagree_only_beyond_the_mdc95() {
        let mut recs = walk("t1", 1.03, 0.05);
        recs.extend(walk("t2", 1.18, 0.13));
        let mut row = ReliabilityRow::withheld(Parameter::StrideTime, 10, 3, String::new());
        row.withheld.clear();
        row.mdc95 = Some(0.08);
        let ctx = crate::RunContext {
            reliability: Some(ReliabilityTable { rows: vec![row] }),
            ..Default::default()
        };
        assert_eq!(
            Disagreement::of(&recs, &ctx)
                .map(|d| d.sentence(true))
                .as_deref(),
            Some(
                "The trials disagree by more than the measurement's own noise (MDC95 of the \
                 reliability table): stride time 1.03 s in trial t1 against 1.18 s in trial t2, \
                 MDC95 0.08 s. The page shows their mean; look at each trial before relying \
                 on it."
            )
        );
        // 0.15 s inside an MDC95 of 0.20 s: the trials agree.
        let mut ctx = ctx;
        ctx.reliability.as_mut().unwrap().rows[0].mdc95 = Some(0.20);
        assert!(Disagreement::of(&recs, &ctx).is_none());
        // Without a table the 10 % rule names both; the headline names them without values.
        let named = Disagreement::of(&recs, &Default::default()).unwrap();
        let sentence = named.sentence(false);
        assert!(sentence.starts_with("The trials disagree by more than 10 %: stride time"));
        assert!(sentence.contains("stride time 1.03 s") && sentence.contains("5.0 % in trial t1"));
        assert_eq!(
            named.headline(),
            "The trials disagree in stride time and stride time variability by more than 10 % \
             (without a reliability table, whether this is beyond the measurement's noise is \
             not known): the page shows their mean; look at each trial under \"Trials side by \
             side\" before relying on it."
        );
    }

    /// Trials walked at different belt speeds (TRIPOD's runs) differ by design, and the page
    /// says so instead of only calling them in disagreement.
    #[test]
    fn trials_at_different_belt_speeds_are_said_to_be_at_different_speeds() {
        let mut recs = walk("PWS", 1.25, 0.07);
        recs.extend(walk("PWS-20", 1.45, 0.03));
        for (r, belt) in recs.iter_mut().zip([1.028, 1.028, 0.833, 0.833]) {
            r.belt_speed_mps = Some(belt);
        }
        let d = Disagreement::of(&recs, &Default::default()).unwrap();
        assert_eq!(
            d.headline(),
            "The trials were walked at different belt speeds (PWS 1.03, PWS-20 0.83 m/s), and \
             they differ in stride time and stride time variability by more than 10 % (without a \
             reliability table, whether this is beyond the measurement's noise is not known): \
             the page shows the mean of different speeds; look at each trial under \"Trials \
             side by side\" before relying on it."
        );
        assert!(d.sentence(false).starts_with(
            "The trials were walked at different belt speeds (PWS 1.03, PWS-20 0.83 m/s) and \
             differ by more than 10 %: stride time 1.25 s in trial PWS against 1.45 s in trial \
             PWS-20;"
        ));
    }

    /// The trials table's cadence is each trial's walk cadence of both legs' steps (the
    /// summary's), not the mean of the legs' step frequencies, which uneven steps inflate.
    #[test]
    fn a_trials_cadence_is_its_walk_cadence() {
        let mut recs = walk("t1", 1.25, 0.05);
        for (r, step_frequency) in recs.iter_mut().zip([2.1657, 1.2752]) {
            r.parameters[Parameter::StepFrequency] = Some(step_frequency);
            r.walk_cadence_steps_per_min = Some(95.71);
        }
        let rows: Vec<&RecordingRow> = recs.iter().collect();
        let trials = trials_of(&rows);
        let cadence = trials[0].value(Parameter::StepFrequency).unwrap() * 60.0;
        assert!((cadence - 95.71).abs() < 1e-9, "{cadence}");
    }

    /// The cohort page's trials of one person: a person none of whose trials measured
    /// anything gets one sentence, not a table of dashes; another person keeps the table.
    #[test]
    fn a_person_with_nothing_measured_gets_a_sentence_on_the_cohort_page() {
        let mut rows = walk("t1", 1.03, 0.05);
        rows.extend(walk("t2", 1.05, 0.05));
        for t in ["t1", "t2"] {
            for mut r in walk(t, 1.0, 0.05) {
                r.subject_id = "Q".into();
                r.parameters = Default::default();
                r.walk_cadence_steps_per_min = None;
                rows.push(r);
            }
        }
        let html = trials_of_people(&rows, &Default::default(), || html! {}).into_string();
        assert_eq!(
            html.matches("<table class=\"trials\">").count(),
            1,
            "{html}"
        );
        assert!(
            html.contains("No value was measured in any of this person's 2 trials"),
            "{html}"
        );
    }
}
