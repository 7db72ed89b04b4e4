//! "A week at home": the page `ldh monitor` writes per person (`week_<subject>.html`;
//! docs/free-living.md "The week page"): per monitoring period a sentence in plain words
//! (valid days, walking per day, the longest walk, the cadence of the long walks), the daily
//! table (wear, walking minutes, steps, bouts, bouts over a minute, longest bout, median cadence
//! in bouts over 30 s), and with two periods (`visit`) the change of each daily measure judged
//! against the day-to-day noise ([`ldh_core::monitor::change`]). Values the monitor withholds
//! show as an en dash with the reason below the table. The frame and CSS are the reports'
//! (`html.rs`); every spliced value is escaped by maud.

use maud::{html, Markup};

use crate::html::{fmt, page};
use ldh_core::monitor::{MonitorResult, VisitChange};

fn opt(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

fn period_title(r: &MonitorResult) -> String {
    match &r.visit {
        Some(v) if !v.is_empty() => format!("Period “{v}”"),
        _ => "Monitoring period".into(),
    }
}

/// The period in plain words.
fn headline(r: &MonitorResult) -> String {
    let s = &r.summary;
    let mut t = format!(
        "{} day(s) recorded, {} valid (≥ 12 h of waking wear).",
        s.days, s.valid_days
    );
    if s.walking_min_per_day.is_finite() {
        t.push_str(&format!(
            " On a valid day the person walked {} min in {} bouts, {} steps; the longest walk lasted {} s.",
            fmt(opt(s.walking_min_per_day), 0),
            fmt(opt(s.bouts_per_day), 0),
            fmt(opt(s.steps_per_day), 0),
            fmt(opt(s.longest_bout_s), 0)
        ));
    } else {
        t.push_str(" Walking per day is withheld: too few valid days for a period.");
    }
    if s.gait_median[0].is_finite() {
        t.push_str(&format!(
            " In walks over 30 s the median cadence was {} steps/min and the median step-time asymmetry {} %.",
            fmt(opt(s.gait_median[0]), 0),
            fmt(opt(s.gait_median[5]), 1)
        ));
    }
    t
}

fn day_table(r: &MonitorResult) -> Markup {
    let reasons: Vec<String> = r
        .days
        .iter()
        .filter(|d| !d.withheld.is_empty())
        .map(|d| format!("day {}: {}", d.day, d.withheld))
        .collect();
    html! {
        table {
            tr {
                th { "day" } th { "date" } th { "valid" } th { "wear (h)" } th { "walking (min)" }
                th { "steps" } th { "bouts" } th { "bouts > 60 s" } th { "longest (s)" }
                th { "cadence, walks > 30 s (steps/min)" }
            }
            @for d in &r.days {
                tr {
                    td { (d.day) } td { (d.date) } td { (if d.valid { "yes" } else { "no" }) }
                    td { (fmt(opt(d.wear_h), 1)) } td { (fmt(opt(d.walking_min), 1)) }
                    td { (fmt(opt(d.steps), 0)) } td { (fmt(opt(d.bouts), 0)) }
                    td { (fmt(opt(d.bouts_over_60s), 0)) } td { (fmt(opt(d.longest_bout_s), 0)) }
                    td { (fmt(opt(d.gait_median[0]), 0)) }
                }
            }
        }
        @if !reasons.is_empty() {
            p.note { "Withheld: " (reasons.join("; ")) }
        }
    }
}

fn change_table(changes: &[&VisitChange]) -> Markup {
    html! {
        table {
            tr {
                th { "measure (per valid day)" } th { (changes[0].from_visit) } th { (changes[0].to_visit) }
                th { "change" } th { "noise limit (95 %)" } th { "judgement" }
            }
            @for c in changes {
                tr {
                    td { (c.measure) " (" (c.unit) ")" }
                    td { (fmt(opt(c.mean_from), 1)) " (" (c.days_from) " d)" }
                    td { (fmt(opt(c.mean_to), 1)) " (" (c.days_to) " d)" }
                    td { (fmt(opt(c.change), 1)) }
                    td { (fmt(opt(c.noise), 1)) }
                    td {
                        @match c.beyond_noise {
                            Some(true) => "beyond the day-to-day noise",
                            Some(false) => "within the day-to-day noise: not a change",
                            None => (format!("not judged: {}", c.withheld)),
                        }
                    }
                }
            }
        }
    }
}

/// Write one week page per person of `results` into `dir` (`week_<subject>.html`, the subject's
/// file-safe stem), each with that person's periods in the order given and the `changes` between
/// them; how many pages were written. What `ldh monitor` writes beside its tables.
pub fn write_week_pages(
    dir: &std::path::Path,
    results: &[MonitorResult],
    changes: &[VisitChange],
) -> ldh_core::Result<usize> {
    let mut people: Vec<&str> = Vec::new();
    for r in results {
        if !people.contains(&r.subject_id.as_str()) {
            people.push(&r.subject_id);
        }
    }
    for who in &people {
        let mine: Vec<&MonitorResult> = results.iter().filter(|r| r.subject_id == *who).collect();
        let stem = ldh_core::output::names::file_stem(who);
        let path = dir.join(format!("week_{stem}.html"));
        ldh_core::io::write_atomic(&path, week_html(&mine, changes).as_bytes())?;
    }
    Ok(people.len())
}

/// The week page of one person: `periods` are that person's monitoring periods (in visit
/// order), `changes` the changes between them ([`ldh_core::monitor::visit_changes`]; others'
/// rows are ignored).
pub fn week_html(periods: &[&MonitorResult], changes: &[VisitChange]) -> String {
    let who = periods.first().map_or("", |r| r.subject_id.as_str());
    let mine: Vec<&VisitChange> = changes.iter().filter(|c| c.subject_id == who).collect();
    let body = html! {
        h1 { "A week at home: " (who) }
        @for r in periods {
            h2 { (period_title(r)) }
            p { (headline(r)) }
            (day_table(r))
            @if !r.errors.is_empty() {
                p.note { "Errors: " (r.errors.join("; ")) }
            }
        }
        @if !mine.is_empty() {
            h2 { "Change between the periods" }
            p {
                "A change is beyond the noise when it exceeds 1.96·√(s₁²/n₁ + s₂²/n₂), the 95 % "
                "limit of a difference of two means of days that vary as this person's days do."
            }
            @for pair in mine.chunk_by(|a, b| a.to_visit == b.to_visit) {
                (change_table(pair))
            }
        }
    };
    page(&format!("A week at home: {who}"), body)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ldh_core::monitor::visit_changes;
    use ldh_test_support::monitor_period;

    #[test]
    fn the_page_has_each_period_its_days_and_the_judged_change() {
        let a = monitor_period("P<1>", "pre", &[4000.0, 4400.0, 3600.0]);
        let b = monitor_period("P<1>", "post", &[6000.0, 6400.0, 5600.0]);
        let changes = visit_changes(&[a.clone(), b.clone()]);
        let h = week_html(&[&a, &b], &changes);
        assert!(h.contains("A week at home: P&lt;1&gt;"), "escaped name");
        assert!(h.contains("Period “pre”") && h.contains("Period “post”"));
        assert!(h.contains("<td>6400</td>"));
        assert!(h.contains("beyond the day-to-day noise"));
        assert!(h.contains("not judged: 0 and 0 valid day(s)"));
    }
}
