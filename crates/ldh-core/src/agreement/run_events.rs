//! The event step of [`super::run`]: each trial's events matched to the reference's, per
//! subject, trial, side and event kind ([`super::match_events`], the rule of gaitmap's
//! `match_stride_lists`), summarised ([`super::summarize`]) per event kind and side, pooled
//! over both sides, and — when the trials the reference covers span two groups or more — per
//! group (the manifest's `group` of each subject: `healthy`, `ldh`, another label, or
//! `unlabelled`). ldh's events are taken inside the span the reference covers (its first event
//! − tolerance to its last + tolerance).

use crate::domain::Legs;
use crate::error::Result;
use crate::pipeline::EventKind;
use crate::Side;

use super::outcome::{
    offset_of, AgreementReport, EventAgreement, GroupCount, MatchedEvent, System, Trial,
    UnmatchedEvent, ALL_GROUPS, KINDS, SIDES, UNLABELLED,
};
use super::{match_events, summarize, EventMatch, ValidAgreementParams};
use crate::output::results::LdhResults;
use crate::reference::Reference;

/// The group of a trial: its recordings' `group` (the manifest's), else `unlabelled`.
pub(crate) fn trial_group(results: &LdhResults, (s, t): &Trial) -> String {
    results
        .recordings
        .iter()
        .find(|r| &r.subject_id == s && &r.trial_id == t)
        .and_then(|r| r.group.as_ref())
        .map_or_else(|| UNLABELLED.to_string(), |g| g.as_str().to_string())
}

/// The groups of `trials`, in order of first appearance, with their subjects and trials.
pub(crate) fn group_counts(results: &LdhResults, trials: &[Trial]) -> Vec<GroupCount> {
    let mut out: Vec<(GroupCount, Vec<&str>)> = Vec::new();
    for trial in trials {
        let g = trial_group(results, trial);
        let i = match out.iter().position(|(c, _)| c.group == g) {
            Some(i) => i,
            None => {
                out.push((
                    GroupCount {
                        group: g,
                        subjects: 0,
                        trials: 0,
                    },
                    Vec::new(),
                ));
                out.len() - 1
            }
        };
        let (c, subjects) = &mut out[i];
        c.trials += 1;
        if !subjects.contains(&trial.0.as_str()) {
            subjects.push(&trial.0);
            c.subjects += 1;
        }
    }
    out.into_iter().map(|(c, _)| c).collect()
}

/// ldh's and the reference's sorted times of one trial, side and event kind.
pub(crate) fn event_train(
    results: &LdhResults,
    reference: &Reference,
    (s, t): (&str, &str),
    side: Side,
    kind: EventKind,
) -> (Vec<f64>, Vec<f64>) {
    let of_trial = |subject: &str, trial: &str| subject == s && trial == t;
    let mut l: Vec<f64> = results
        .events
        .iter()
        .filter(|e| of_trial(&e.subject_id, &e.trial_id) && e.side == side && e.event == kind)
        .map(|e| e.time_s)
        .collect();
    let mut r: Vec<f64> = reference
        .events
        .iter()
        .filter(|e| of_trial(&e.subject_id, &e.trial_id) && e.side == side && e.event == kind)
        .map(|e| e.time_s)
        .collect();
    l.sort_by(f64::total_cmp);
    r.sort_by(f64::total_cmp);
    (l, r)
}

/// The matchings of one event kind: per trial (with its group) and side.
struct KindMatches {
    /// (group, side index, matching), in the order of the trials, left before right.
    all: Vec<(String, usize, EventMatch)>,
}

impl KindMatches {
    /// The summaries of the matchings that `keep` (by group), per side and pooled.
    fn summaries(&self, kind: EventKind, group: &str, out: &mut Vec<EventAgreement>) {
        let of_group = |g: &String| group == ALL_GROUPS || g == group;
        for (k, side) in SIDES.into_iter().enumerate() {
            let m: Vec<EventMatch> = self
                .all
                .iter()
                .filter(|(g, s, _)| of_group(g) && *s == k)
                .map(|x| x.2.clone())
                .collect();
            out.push(EventAgreement {
                event: kind,
                side: side.into(),
                group: group.to_string(),
                summary: summarize(&m),
            });
        }
        // Pooled: each trial's left then right, as `ldh evaluate` pools them.
        let both: Vec<EventMatch> = self
            .all
            .iter()
            .filter(|(g, _, _)| of_group(g))
            .map(|x| x.2.clone())
            .collect();
        out.push(EventAgreement {
            event: kind,
            side: Legs::Both,
            group: group.to_string(),
            summary: summarize(&both),
        });
    }
}

/// Match every trial's events and summarise per event kind and side (and per group).
pub(crate) fn events(
    results: &LdhResults,
    reference: &Reference,
    params: &ValidAgreementParams,
    trials: &[Trial],
    report: &mut AgreementReport,
) -> Result<()> {
    if reference.events.is_empty() {
        return Ok(());
    }
    let tol = params.params().tolerance_s;
    let groups: Vec<String> = trials.iter().map(|t| trial_group(results, t)).collect();
    for kind in KINDS {
        let mut matches = KindMatches { all: Vec::new() };
        for (trial, group) in trials.iter().zip(&groups) {
            let offset = offset_of(report, trial);
            for (k, side) in SIDES.into_iter().enumerate() {
                let (l, r) = event_train(results, reference, (&trial.0, &trial.1), side, kind);
                let (Some(first), Some(last)) = (r.first(), r.last()) else {
                    continue;
                };
                let l: Vec<f64> = l
                    .iter()
                    .map(|x| x - offset)
                    .filter(|x| *x >= first - tol && *x <= last + tol)
                    .collect();
                let m = match_events(&l, &r, params)?;
                let mut miss = |system: System, time_s: f64| {
                    report.unmatched_events.push(UnmatchedEvent {
                        system,
                        subject_id: trial.0.clone(),
                        trial_id: trial.1.clone(),
                        group: group.clone(),
                        side,
                        event: kind,
                        time_s,
                    })
                };
                m.unmatched_ldh
                    .iter()
                    .for_each(|&i| miss(System::Ldh, l[i]));
                for (&(_, j), &error_s) in m.pairs.iter().zip(&m.errors_s) {
                    report.event_pairs.push(MatchedEvent {
                        subject_id: trial.0.clone(),
                        trial_id: trial.1.clone(),
                        group: group.clone(),
                        side,
                        event: kind,
                        reference_time_s: r[j],
                        error_s,
                    });
                }
                m.unmatched_reference
                    .iter()
                    .for_each(|&j| miss(System::Reference, r[j]));
                matches.all.push((group.clone(), k, m));
            }
        }
        matches.summaries(kind, ALL_GROUPS, &mut report.events);
        if report.groups.len() >= 2 {
            for g in &report.groups {
                matches.summaries(kind, &g.group, &mut report.events_by_group);
            }
        }
    }
    Ok(())
}
