//! `ldh stats --reliability`: the test–retest reliability of every parameter from a cohort's
//! repeated trials ([`reliability_table`]), rendered as Markdown like the reliability tables of
//! gait papers ([`ReliabilityTable::to_markdown`]) and written as `reliability.csv`, `.json` and
//! `.md` ([`ReliabilityTable::files`]).
//!
//! The value of a trial is the walk's value the reports use for a person's trials
//! (`report/trials.rs`): the mean of the left and right legs, both analysed (status ok or no
//! valid strides) and both with a value; else the trial is missing. Each person's trials are
//! those of their first visit (the visit of their first row): a change between visits is what
//! the MDC95 is for, so it must not enter the trial-to-trial noise. k is the most common number
//! of trials among the people with two or more (ties: the smaller); a person with more trials uses the first k, in the
//! order of the results; a person with fewer, or with a missing value in the first k, is left
//! out by [`test_retest`]'s listwise rule. The statistics are Weir (2005)'s SEM and
//! MDC95 and Shrout & Fleiss (1979)'s ICCs; `docs/agreement.md`, "Reliability table".

use std::collections::BTreeMap;

use super::reliability_table::{ReliabilityRow, ReliabilityTable};
use crate::error::{LdhError, Result};
use crate::output::{Parameter, RecordingRow};
use crate::stats::agreement::{test_retest, AgreementError, ValidAgreementParams};
use crate::Side;

/// The legs of one trial of a person.
struct Trial<'a> {
    id: &'a str,
    legs: Vec<&'a RecordingRow>,
}

impl Trial<'_> {
    /// The walk's value of `p`: the mean of both legs, NaN unless both legs have one.
    fn value(&self, p: Parameter) -> f64 {
        let side = |s: Side| {
            self.legs
                .iter()
                .find(|r| r.side == s && r.is_ok())
                .and_then(|r| r.value(p))
        };
        match (side(Side::Left), side(Side::Right)) {
            (Some(l), Some(r)) => (l + r) / 2.0,
            _ => f64::NAN,
        }
    }
}

/// Each person's trials of their first visit, people and trials in order of first appearance.
fn trials_by_person(rows: &[RecordingRow]) -> Vec<Vec<Trial<'_>>> {
    let mut people: Vec<(&str, &str, Vec<Trial>)> = Vec::new();
    for r in rows {
        let i = match people.iter().position(|p| p.0 == r.subject_id) {
            Some(i) => i,
            None => {
                people.push((&r.subject_id, &r.visit, Vec::new()));
                people.len() - 1
            }
        };
        let (_, visit, trials) = &mut people[i];
        if r.visit != *visit {
            continue;
        }
        match trials.iter_mut().find(|t| t.id == r.trial_id) {
            Some(t) => t.legs.push(r),
            None => trials.push(Trial {
                id: &r.trial_id,
                legs: vec![r],
            }),
        }
    }
    people.into_iter().map(|p| p.2).collect()
}

/// The most common number of trials among the people with two or more (ties: the smaller); 0
/// when nobody has two. People with one trial say nothing of the trial-to-trial noise, so a
/// cohort of mostly single walks with a few repeated ones is judged on the repeated ones.
fn common_trial_count(people: &[Vec<Trial>]) -> usize {
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    for p in people.iter().filter(|p| p.len() >= 2) {
        *counts.entry(p.len()).or_default() += 1;
    }
    // max_by_key keeps the last of equal keys: iterate from the largest count down.
    counts
        .iter()
        .rev()
        .max_by_key(|(_, people)| **people)
        .map_or(0, |(k, _)| *k)
}

/// The reliability of every parameter of [`Parameter::ALL`] from the repeated trials in `rows`
/// (module docs: which value, which trials). A parameter that cannot be computed is a row with
/// its reason in `withheld`, never an error.
pub fn reliability_table(rows: &[RecordingRow], params: &ValidAgreementParams) -> ReliabilityTable {
    let people = trials_by_person(rows);
    let k = common_trial_count(&people);
    let mut out = ReliabilityTable::default();
    for p in Parameter::ALL {
        if k < 2 {
            out.rows.push(ReliabilityRow::withheld(
                p,
                0,
                k,
                "no repeated trials: no person has two or more trials (manifest column trial_id)"
                    .into(),
            ));
            continue;
        }
        let table: Vec<Vec<f64>> = people
            .iter()
            .filter(|t| t.len() >= k)
            .map(|t| t[..k].iter().map(|t| t.value(p)).collect())
            .collect();
        let complete = table
            .iter()
            .filter(|r| r.iter().all(|v| v.is_finite()))
            .count();
        out.rows.push(match test_retest(&table, params) {
            Ok(r) => ReliabilityRow::computed(p, &r),
            Err(e) => ReliabilityRow::withheld(p, complete, k, reason(&e, k)),
        });
    }
    out
}

/// Why a parameter's reliability was withheld, in plain words.
fn reason(e: &AgreementError, k: usize) -> String {
    match e {
        AgreementError::TooFewPairs { got, .. } => format!(
            "fewer than 2 people with a value in each of {k} trials (both legs analysed): {got}"
        ),
        AgreementError::ConstantData { .. } => {
            "no trial-to-trial variation (the error mean square is 0)".into()
        }
        other => other.to_string(),
    }
}

/// The refusal of `ldh stats --reliability` (and `ldh.reliability`) when no person has two or
/// more trials in their first visit: every row would be withheld.
pub fn require_repeated_trials(rows: &[RecordingRow]) -> Result<()> {
    let people = trials_by_person(rows);
    if people.iter().any(|t| t.len() >= 2) {
        return Ok(());
    }
    Err(LdhError::signal(
        "test-retest reliability",
        format!(
            "no person has two or more trials ({} people, one trial each): reliability needs \
             repeated trials of each person, given by the manifest column trial_id (`ldh simulate \
             --trials 3` makes such a cohort)",
            people.len()
        ),
    ))
}

/// `x` with 3 significant digits (at least 0 decimals, at most 6).
fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let dec = (2 - x.abs().log10().floor() as i64).clamp(0, 6) as usize;
    format!("{x:.dec$}")
}

impl ReliabilityTable {
    /// The table as Markdown, as gait papers print reliability: per parameter the people × trials
    /// used, ICC(2,1) [CI at `confidence_level`], SEM, MDC95 and the within-subject CV (%).
    pub fn to_markdown(&self, confidence_level: f64) -> String {
        let ci = format!("{:.0} % CI", confidence_level * 100.0);
        let mut md = format!(
            "# Test–retest reliability (ldh stats --reliability)\n\n\
             Value of a trial: the mean of both legs. SEM = SD·√(1 − ICC(2,1)), MDC95 = \
             1.96·√2·SEM (Weir 2005); CVw: root-mean-square within-subject CV.\n\n\
             | parameter | people × trials | ICC(2,1) [{ci}] | SEM | MDC95 | CVw |\n\
             |---|---|---|---|---|---|\n"
        );
        for r in &self.rows {
            let name =
                Parameter::from_column(&r.parameter).map_or(r.parameter.as_str(), |p| p.name());
            let label = format!("{name} ({}, {})", r.code, r.unit);
            let size = format!("{} × {}", r.n_subjects, r.k_trials);
            if !r.withheld.is_empty() {
                md.push_str(&format!(
                    "| {label} | {size} | withheld: {} | | | |\n",
                    r.withheld
                ));
                continue;
            }
            let f =
                |x: Option<f64>, dec: usize| x.map_or("—".to_string(), |v| format!("{v:.dec$}"));
            let s = |x: Option<f64>| x.map_or("—".to_string(), sig3);
            md.push_str(&format!(
                "| {label} | {size} | {} [{}, {}] | {} | {} | {} |\n",
                f(r.icc_2_1, 2),
                f(r.icc_2_1_ci_low, 2),
                f(r.icc_2_1_ci_high, 2),
                s(r.sem),
                s(r.mdc95),
                r.within_subject_cv
                    .map_or("—".to_string(), |v| format!("{:.1} %", v * 100.0)),
            ));
        }
        md
    }

    /// The files of `ldh stats --reliability`: `reliability.csv`, `reliability.json` (the same
    /// rows) and `reliability.md` ([`ReliabilityTable::to_markdown`]).
    pub fn files(&self, confidence_level: f64) -> Result<Vec<(String, String)>> {
        Ok(vec![
            ("reliability.csv".into(), self.to_csv()?),
            (
                "reliability.json".into(),
                serde_json::to_string_pretty(self)? + "\n",
            ),
            ("reliability.md".into(), self.to_markdown(confidence_level)),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row of `person`'s `trial` on `side` with stride time `st` (None: failed leg).
    fn row(person: &str, visit: &str, trial: &str, side: Side, st: Option<f64>) -> RecordingRow {
        let mut r: RecordingRow = serde_json::from_value(serde_json::json!({
            "subject_id": person, "trial_id": trial, "visit": visit, "side": side.as_str(),
            "model": "fusion", "group": "", "affected_side": "", "side_role": "", "source": "",
            "status": if st.is_some() { "ok" } else { "error" }, "error": "", "sta_status": "",
        }))
        .unwrap();
        r.set_value(Parameter::StrideTime, st);
        r
    }

    /// Both legs of a trial, left = v − 0.01 and right = v + 0.01 (their mean is v).
    fn trial(rows: &mut Vec<RecordingRow>, person: &str, visit: &str, t: &str, v: f64) {
        rows.push(row(person, visit, t, Side::Left, Some(v - 0.01)));
        rows.push(row(person, visit, t, Side::Right, Some(v + 0.01)));
    }

    #[test]
    fn the_walk_value_of_the_first_visit_and_first_k_trials_is_used() {
        let mut rows = Vec::new();
        // Three people × 2 trials; P1 has a third trial (ignored) and a second visit (ignored).
        let table = [[1.0, 1.1], [1.2, 1.25], [0.9, 1.05]];
        for (i, v) in table.iter().enumerate() {
            let id = format!("P{i}");
            trial(&mut rows, &id, "pre", "a", v[0]);
            trial(&mut rows, &id, "pre", "b", v[1]);
        }
        trial(&mut rows, "P0", "pre", "c", 9.0);
        trial(&mut rows, "P0", "post", "d", 5.0);
        // A fourth person with one trial (fewer than k = 2) is left out.
        trial(&mut rows, "P3", "pre", "a", 3.0);
        let p = ValidAgreementParams::default();
        let t = reliability_table(&rows, &p);
        assert_eq!(t.rows.len(), Parameter::ALL.len());
        let want = test_retest(&table.map(|r| r.to_vec()), &p).unwrap();
        let st = t.row(Parameter::StrideTime).unwrap();
        assert_eq!((st.n_subjects, st.k_trials), (3, 2));
        assert!((st.mdc95.unwrap() - want.mdc95).abs() < 1e-12, "{st:?}");
        assert!((st.icc_2_1.unwrap() - want.icc.icc_2_1.value).abs() < 1e-12);
        assert_eq!(st.withheld, "");
        // Parameters without values: withheld with the reason, counts kept.
        let sl = t.row(Parameter::StrideLength).unwrap();
        assert_eq!((sl.n_subjects, sl.k_trials, sl.mdc95), (0, 2, None));
        assert!(
            sl.withheld.contains("fewer than 2 people"),
            "{}",
            sl.withheld
        );
        let md = t.to_markdown(0.95);
        assert!(md.contains("| stride time (ST, s) | 3 × 2 | "), "{md}");
        assert!(md.contains("ICC(2,1) [95 % CI]"), "{md}");
        assert!(
            md.contains("| stride length (SL, m) | 0 × 2 | withheld: fewer"),
            "{md}"
        );
        let files = t.files(0.95).unwrap();
        assert_eq!(files[0].0, "reliability.csv");
        assert_eq!(files[0].1.lines().count(), 15);
    }

    #[test]
    fn a_trial_with_one_leg_missing_drops_its_person() {
        let mut rows = Vec::new();
        for (i, v) in [[1.0, 1.1], [1.2, 1.25], [0.9, 1.05]].iter().enumerate() {
            trial(&mut rows, &format!("P{i}"), "", "a", v[0]);
            trial(&mut rows, &format!("P{i}"), "", "b", v[1]);
        }
        rows[2 * 2 + 1] = row("P1", "", "a", Side::Right, None);
        let t = reliability_table(&rows, &ValidAgreementParams::default());
        assert_eq!(t.row(Parameter::StrideTime).unwrap().n_subjects, 2);
        rows[0] = row("P0", "", "a", Side::Left, None);
        let t = reliability_table(&rows, &ValidAgreementParams::default());
        let st = t.row(Parameter::StrideTime).unwrap();
        assert_eq!((st.n_subjects, st.mdc95), (1, None));
        assert!(
            st.withheld.contains("2 trials (both legs analysed): 1"),
            "{}",
            st.withheld
        );
    }

    #[test]
    fn without_repeated_trials_every_row_is_withheld_and_the_command_refuses() {
        let mut rows = Vec::new();
        trial(&mut rows, "P0", "", "", 1.0);
        trial(&mut rows, "P1", "", "", 1.1);
        let t = reliability_table(&rows, &ValidAgreementParams::default());
        assert!(t
            .rows
            .iter()
            .all(|r| r.withheld.starts_with("no repeated trials")));
        let e = require_repeated_trials(&rows).unwrap_err().to_string();
        assert!(
            e.contains("no person has two or more trials (2 people"),
            "{e}"
        );
        trial(&mut rows, "P1", "", "b", 1.1);
        assert!(require_repeated_trials(&rows).is_ok());
    }

    #[test]
    fn k_is_the_most_common_trial_count_ties_taking_the_smaller() {
        let mut rows = Vec::new();
        for (person, n) in [("A", 2), ("B", 3), ("C", 3), ("D", 2)] {
            for t in 0..n {
                trial(&mut rows, person, "", &t.to_string(), 1.0 + t as f64);
            }
        }
        assert_eq!(common_trial_count(&trials_by_person(&rows)), 2);
        trial(&mut rows, "E", "", "0", 1.0);
        trial(&mut rows, "E", "", "1", 1.0);
        trial(&mut rows, "E", "", "2", 1.0);
        assert_eq!(common_trial_count(&trials_by_person(&rows)), 3);
        // Single walks say nothing of the noise: ten of them do not make k = 1.
        for person in ["F", "G", "H", "I", "J", "K", "L", "M", "N", "O"] {
            trial(&mut rows, person, "", "0", 1.0);
        }
        assert_eq!(common_trial_count(&trials_by_person(&rows)), 3);
        assert_eq!(sig3(0.012345), "0.0123");
        assert_eq!(sig3(123.45), "123");
        assert_eq!(sig3(1.5), "1.50");
    }
}
