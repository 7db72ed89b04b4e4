//! Change between visits on the subject page (issue 38 item 3; docs/reports.md "Change between
//! visits").
//!
//! A person recorded at two or more visits (manifest `visit`) sees, per parameter, the value at
//! each visit (the mean over the visit's trials of the walk value, the mean of both legs — the
//! quantity `ldh stats --reliability` measures the noise of) and its change from the first
//! visit. A change is marked (▲ larger, ▼ smaller) **only** when it exceeds the parameter's
//! MDC95 in the reliability table the user gave (`--reliability reliability.csv`): the smallest
//! change a measurement tells from its own trial-to-trial noise with 95 % confidence (Weir 2005,
//! MDC95 = 1.96·√2·SEM). Without a table, or for a parameter the table withholds, no change is
//! marked and the page says why: a difference inside the noise is not a change.
//!
//! The MDC95 is that of one trial against one trial; a visit with several trials has a mean
//! that is less noisy, so the comparison is conservative there (never a mark the noise could
//! make).

use maud::{html, Markup};

use super::html::fmt;
use super::trials::{decimals, signed, trials_of, visit_mean, visits_of};
use super::RunContext;
use ldh_core::cohort::PARAMETERS;
use ldh_core::output::{Parameter, RecordingRow};

/// One parameter's values at the visits and its changes from the first.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct VisitChange {
    pub parameter: Parameter,
    /// The value at each visit, in visit order.
    pub values: Vec<Option<f64>>,
    /// The MDC95 of the reliability table, when it gives one.
    pub mdc95: Option<f64>,
}

impl VisitChange {
    /// The change of visit `i` (≥ 1) from the first.
    pub fn change(&self, i: usize) -> Option<f64> {
        Some((*self.values.get(i)?)? - (*self.values.first()?)?)
    }

    /// Whether the change of visit `i` exceeds the MDC95; `None` without both.
    pub fn beyond(&self, i: usize) -> Option<bool> {
        Some(self.change(i)?.abs() > self.mdc95?)
    }
}

/// A person's visits and the changes of every parameter.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct VisitChanges {
    /// The visits, in order (dates in time order, else as the manifest lists them).
    pub visits: Vec<String>,
    /// One per parameter of [`PARAMETERS`].
    pub rows: Vec<VisitChange>,
    /// Where the MDC95 come from ("reliability.csv: 10 people × 3 trials"), when given.
    pub source: Option<String>,
}

/// The changes of a person whose analysed trials come from two or more visits.
pub(crate) fn visit_changes(recordings: &[RecordingRow], ctx: &RunContext) -> Option<VisitChanges> {
    // Trials without a visit (a manifest that names only some) are not placed in time.
    let recs: Vec<&RecordingRow> = recordings.iter().filter(|r| !r.visit.is_empty()).collect();
    let trials = trials_of(&recs);
    let visits: Vec<&str> = visits_of(&trials).into_iter().map(|(v, _)| v).collect();
    if visits.len() < 2 {
        return None;
    }
    let table = ctx.reliability.as_ref();
    let rows = PARAMETERS
        .iter()
        .map(|&p| VisitChange {
            parameter: p,
            values: visits.iter().map(|v| visit_mean(&trials, v, p)).collect(),
            mdc95: table.and_then(|t| t.mdc95(p)),
        })
        .collect();
    let source = table.map(|t| {
        let (n, k) = t
            .rows
            .iter()
            .filter(|r| r.mdc95.is_some())
            .map(|r| (r.n_subjects, r.k_trials))
            .max()
            .unwrap_or((0, 0));
        format!(
            "{}: {n} people × {k} trials",
            ctx.reliability_source
                .as_deref()
                .unwrap_or("the reliability table")
        )
    });
    Some(VisitChanges {
        visits: visits.into_iter().map(String::from).collect(),
        rows,
        source,
    })
}

/// `rose by 0.120 m (MDC95 0.080 m)` / `fell by …`.
fn change_text(r: &VisitChange, i: usize) -> String {
    let d = decimals(r.parameter);
    let unit = r.parameter.unit();
    let x = r.change(i).unwrap_or(f64::NAN);
    let verb = if x > 0.0 { "rose" } else { "fell" };
    format!(
        "{verb} by {} {unit} (MDC95 {} {unit})",
        fmt(Some(x.abs()), d),
        fmt(r.mdc95, d)
    )
}

/// The headline's sentence on the visits: which they are and, from the first to the last, the
/// changes beyond the measurement's noise — or why none is judged.
pub(crate) fn headline_sentence(c: &VisitChanges) -> String {
    let (first, last) = (&c.visits[0], &c.visits[c.visits.len() - 1]);
    let i = c.visits.len() - 1;
    let opening = format!(
        "Recorded at {} visits ({}): the values on this page are the mean of all of them.",
        c.visits.len(),
        c.visits.join(", ")
    );
    let Some(source) = &c.source else {
        return format!(
            "{opening} The changes between the visits are listed under \"Change between visits\" and none is judged: without a reliability table the measurement's own noise is not known, so no change can be told apart from it."
        );
    };
    let beyond: Vec<String> = c
        .rows
        .iter()
        .filter(|r| r.beyond(i) == Some(true))
        .map(|r| format!("{} {}", r.parameter.name(), change_text(r, i)))
        .collect();
    let unjudged = c
        .rows
        .iter()
        .filter(|r| r.change(i).is_some() && r.mdc95.is_none())
        .count();
    let rest = match unjudged {
        0 => String::new(),
        1 => " One parameter has no MDC95 in the table and is not judged.".to_string(),
        n => format!(" {n} parameters have no MDC95 in the table and are not judged."),
    };
    if beyond.is_empty() {
        format!(
            "{opening} From {first} to {last} no parameter changed by more than the measurement's own noise (MDC95, {source}).{rest}"
        )
    } else {
        format!(
            "{opening} From {first} to {last}, changed by more than the measurement's own noise (MDC95, {source}): {}; every other change lies within the noise.{rest}",
            beyond.join("; ")
        )
    }
}

/// "Change between visits": per parameter the value at each visit, the change of each later
/// visit from the first, the MDC95, marked only beyond it. `title` is the numbered heading.
pub(crate) fn visits_section(c: &VisitChanges, title: Markup) -> Markup {
    let first = &c.visits[0];
    html! {
        (title)
        p.meta {
            "The value of each visit is the mean of its trials (each the mean of both legs). "
            @if let Some(s) = &c.source {
                "A change is marked (▲ larger, ▼ smaller) only when it exceeds the MDC95, the smallest change this measurement tells from its own trial-to-trial noise with 95 % confidence (" (s) "); unmarked changes lie within the noise."
            } @else {
                "No change is marked: no reliability table (made from repeated trials of the same people) was given, so the measurement's own noise is not known here."
            }
        } "\n"
        table.visits {
            tr {
                th { "parameter" } th { "unit" }
                @for v in &c.visits { th { "visit " (v) } }
                @for v in &c.visits[1..] { th { (v) " − " (first) } }
                th { "MDC95" }
            }
            "\n"
            @for r in &c.rows {
                @let d = decimals(r.parameter);
                tr {
                    td { (r.parameter.code()) " — " (r.parameter.name()) } td { (r.parameter.unit()) }
                    @for v in &r.values { td.num { (fmt(*v, d)) } }
                    @for i in 1..c.visits.len() {
                        td.num {
                            (signed(r.change(i), d))
                            @match (r.beyond(i), r.change(i)) {
                                (Some(true), Some(x)) if x > 0.0 => " ▲",
                                (Some(true), Some(_)) => " ▼",
                                _ => "",
                            }
                        }
                    }
                    td.num { (fmt(r.mdc95, d)) }
                }
                "\n"
            }
        }
        "\n"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ldh_core::cohort::{ReliabilityRow, ReliabilityTable};

    fn walk(id: &str, trial: &str, visit: &str, speed: f64, length: f64) -> Vec<RecordingRow> {
        ["left", "right"]
            .iter()
            .map(|side| {
                let mut r = crate::tests::row(id, "ldh", side, speed);
                r.trial_id = trial.into();
                r.visit = visit.into();
                r.parameters[Parameter::StrideLength] = Some(length);
                r
            })
            .collect()
    }

    fn table(mdc: &[(Parameter, f64)]) -> ReliabilityTable {
        let mut rows = Vec::new();
        for (p, m) in mdc {
            let mut r = ReliabilityRow::withheld(*p, 10, 3, String::new());
            r.withheld.clear();
            r.mdc95 = Some(*m);
            rows.push(r);
        }
        ReliabilityTable { rows }
    }

    #[test]
    fn only_a_change_beyond_the_mdc95_is_marked() {
        // Speed +0.15 m/s (MDC95 0.10: beyond), stride length +0.05 m (MDC95 0.08: within).
        let mut recs = walk("P", "1", "pre", 1.00, 1.20);
        recs.extend(walk("P", "2", "post", 1.15, 1.25));
        let ctx = RunContext {
            reliability: Some(table(&[
                (Parameter::Speed, 0.10),
                (Parameter::StrideLength, 0.08),
            ])),
            reliability_source: Some("reliability.csv".into()),
            ..Default::default()
        };
        let c = visit_changes(&recs, &ctx).unwrap();
        assert_eq!(c.visits, vec!["pre", "post"]);
        let row = |p| c.rows.iter().find(|r| r.parameter == p).unwrap();
        assert_eq!(row(Parameter::Speed).beyond(1), Some(true));
        assert_eq!(row(Parameter::StrideLength).beyond(1), Some(false));
        assert_eq!(row(Parameter::StrideTime).beyond(1), None);
        let s = headline_sentence(&c);
        assert!(
            s.contains("From pre to post, changed by more than the measurement's own noise (MDC95, reliability.csv: 10 people × 3 trials): walking speed rose by 0.150 m/s (MDC95 0.100 m/s); every other change lies within the noise."),
            "{s}"
        );
        assert!(!s.contains("stride length"), "{s}");
        let html = visits_section(&c, html! {}).into_string();
        let marks = |code: &str| {
            let at = html.find(&format!("<td>{code} — ")).unwrap();
            let row = &html[at..];
            row[..row.find("</tr>").unwrap()]
                .matches(['▲', '▼'])
                .count()
        };
        assert_eq!(marks("SS"), 1);
        assert_eq!(marks("SL"), 0, "a change inside the noise is never marked");
        assert_eq!(marks("ST"), 0);
    }

    #[test]
    fn without_a_table_nothing_is_marked_and_the_page_says_why() {
        let mut recs = walk("P", "1", "pre", 1.00, 1.20);
        recs.extend(walk("P", "2", "post", 1.50, 1.60));
        let c = visit_changes(&recs, &RunContext::default()).unwrap();
        assert!(c.rows.iter().all(|r| r.beyond(1).is_none()));
        assert!(headline_sentence(&c).contains("none is judged: without a reliability table"));
        let html = visits_section(&c, html! {}).into_string();
        assert!(!html.contains('▲') && !html.contains('▼'));
        // One visit (or none named): no section.
        let mut one = walk("Q", "1", "pre", 1.0, 1.2);
        one.extend(walk("Q", "2", "pre", 1.1, 1.2));
        assert!(visit_changes(&one, &RunContext::default()).is_none());
    }

    #[test]
    fn dated_visits_are_in_time_order() {
        let mut recs = walk("P", "1", "2024-06-01", 1.2, 1.3);
        recs.extend(walk("P", "2", "2024-01-15", 1.0, 1.2));
        let c = visit_changes(&recs, &RunContext::default()).unwrap();
        assert_eq!(c.visits, vec!["2024-01-15", "2024-06-01"]);
        let speed = c
            .rows
            .iter()
            .find(|r| r.parameter == Parameter::Speed)
            .unwrap();
        assert!((speed.change(1).unwrap() - 0.2).abs() < 1e-12);
    }
}
