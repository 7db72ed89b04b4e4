//! The cohort page's facts (issue 36 item 4): people apart from trials, people with both legs
//! analysed, group labels as given, sections numbered in order without the paper's table
//! numbers, shading only for what is wrong, a person's trials side by side (by visit), file
//! names without folders; and the subject page's identification (item 5).

use super::super::trials::Counts;
use super::super::*;
use super::row;
use ldh_core::domain::Parameter;

/// `id`'s two legs of trial `trial` at visit `visit`, speed `speed` m/s, from machine paths.
fn trial(id: &str, group: &str, trial: &str, visit: &str, speed: f64) -> Vec<RecordingRow> {
    ["left", "right"]
        .into_iter()
        .map(|side| {
            let mut r = row(id, group, side, speed);
            r.trial_id = trial.into();
            r.visit = visit.into();
            r.source = format!("/home/someone/study/{id}/{trial}_{side}.csv");
            r
        })
        .collect()
}

fn cohort(recs: Vec<RecordingRow>) -> String {
    cohort_html(&CohortReport {
        subject_links: vec![("P1".into(), "subjects/P1.html".into())],
        recordings: recs,
        ..Default::default()
    })
    .unwrap()
}

#[test]
fn the_cohort_page_counts_people_trials_and_both_legs_and_keeps_labels_as_given() {
    let mut recs = trial("P1", "Stroke", "t1", "pre", 1.0);
    recs.extend(trial("P1", "Stroke", "t2", "post", 1.2));
    recs.extend(trial("P2", "Stroke", "t1", "", 1.1));
    let mut failed = trial("P3", "Stroke", "t1", "", 1.1);
    failed[1].status = ldh_core::output::Status::Error.into();
    failed[1].error = "unreadable".into();
    recs.extend(failed);
    assert_eq!(
        Counts::of(&recs),
        Counts {
            people: 3,
            trials: 4,
            recordings: 8,
            analysed: 7,
            both_legs: 2
        }
    );
    let c = cohort(recs);
    assert!(
        c.contains("3 people, 4 trials, 8 recordings (7 analysed, 1 failed); 2 of the 3 with both legs analysed"),
        "{c}"
    );
    // The free label as written, nowhere upper-cased; no group statistic for it.
    assert!(c.contains("<td>Stroke</td>") && !c.contains("STROKE"));
    assert!(
        c.contains("No group statistics: they compare the ldh group (affected side given) with the healthy group, each with at least 3 people with both legs analysed; this cohort has 0 and 0. Left out: "),
        "{c}"
    );
    // One message for the cohort, people counted by why they are left out (issue 50).
    assert!(
        c.contains("2 people in group 'Stroke', which the statistics do not compare")
            && c.contains("1 person with a leg missing or not analysed"),
        "{c}"
    );
    // Sections 1–4 in order, without the paper's table or figure numbers.
    let at = |h: &str| c.find(h).unwrap_or_else(|| panic!("no {h}"));
    assert!(at("1. Group statistics") < at("2. Classifiers"));
    assert!(at("2. Classifiers") < at("3. Trials of one person"));
    assert!(at("3. Trials of one person") < at("4. Recordings"));
    for paper in ["Table 3", "Table 4", "Fig. 7", "Tables 6"] {
        assert!(!c.contains(paper), "{paper}");
    }
    // Only the person with a failed recording has a shaded status.
    let triage = &c[at("Subjects, most findings first")..];
    let triage = &triage[..triage.find("</table>").unwrap()];
    assert_eq!(triage.matches("<td class=\"bad\">").count(), 1, "{triage}");
    assert!(triage.contains("<td class=\"bad\">right side failed</td>"));
    // File names without the machine's folders; the trial and visit of each row.
    assert!(c.contains("<td>t2</td><td>post</td><td>Stroke</td><td>left</td><td>t2_left.csv</td>"));
    assert!(!c.contains("/home/someone"));
}

#[test]
fn a_persons_trials_stand_side_by_side_grouped_by_visit_with_their_difference() {
    let mut recs = trial("P1", "healthy", "t1", "pre", 1.0);
    recs.extend(trial("P1", "healthy", "t2", "pre", 1.1));
    recs.extend(trial("P1", "healthy", "t3", "post", 1.3));
    recs.extend(trial("P2", "healthy", "t1", "", 1.0));
    let c = cohort(recs);
    let s = &c[c.find("Trials of this person").unwrap()..];
    let s = &s[..s.find("</table>").unwrap()];
    assert!(s.contains("<a href=\"subjects/P1.html\">P1</a>"), "{s}");
    assert!(
        s.contains("<th colspan=\"2\">visit pre</th><th colspan=\"1\">visit post</th>"),
        "{s}"
    );
    assert!(
        s.contains(
            "<th>trial t1</th><th>trial t2</th><th>trial t3</th><th>post − pre (visit means)</th>"
        ),
        "{s}"
    );
    // Speed: 1.0 and 1.1 at the first visit (mean 1.05), 1.3 at the second: +0.25 (the
    // page's units and decimals).
    assert!(s.contains("<td class=\"num\">1.00</td><td class=\"num\">1.10</td><td class=\"num\">1.30</td><td class=\"num\">+0.25</td>"), "{s}");
    // No change is marked; P2 (one trial) has no comparison.
    assert!(!s.contains('▲') && !s.contains('▼'));
    assert_eq!(c.matches("Trials of this person").count(), 1);
    // One visit: the last trial minus the first.
    let mut recs = trial("P1", "healthy", "a", "", 1.0);
    recs.extend(trial("P1", "healthy", "b", "", 0.9));
    // Without a person of several trials the section is left out and takes no number.
    let one = cohort(trial("P2", "healthy", "t1", "", 1.0));
    assert!(one.contains("3. Recordings") && !one.contains("Trials of one person"));
    let c = cohort(recs);
    assert!(
        c.contains("<th>b − a</th>") && c.contains("<td class=\"num\">-0.10</td>"),
        "{c}"
    );
}

#[test]
fn file_names_lose_their_folders() {
    use super::super::html::base_name;
    assert_eq!(base_name("/home/a/b/left.csv"), "left.csv");
    assert_eq!(base_name("C:\\data\\S1\\right.csv"), "right.csv");
    assert_eq!(
        base_name("t1: /x/l.csv; t2: /y/l2.csv"),
        "t1: l.csv; t2: l2.csv"
    );
    assert_eq!(base_name(""), "");
}

#[test]
fn the_subject_page_names_trial_visit_setting_belt_speed_and_files() {
    let p = ReportParams::default().check().unwrap();
    let mut recs = trial("P1", "healthy", "t1", "pre", 1.2);
    for r in recs.iter_mut() {
        r.setting = Some(ldh_core::Setting::Treadmill.into());
        r.belt_speed_mps = Some(1.1);
    }
    let s = SubjectReport {
        subject_id: "P1".into(),
        recordings: recs,
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    assert!(
        html.contains(" Recorded: trial t1, visit pre, treadmill, belt 1.10 m/s: files t1_left.csv (left leg), t1_right.csv (right leg)."),
        "{html}"
    );
    assert!(!html.contains("/home/someone"));
}

/// The recording's start as the file gave it (`recorded_at`, the left file's here) is on the
/// page to the minute; without one the page says the files do not give it.
#[test]
fn the_subject_page_says_when_the_files_were_recorded_or_that_they_do_not_say() {
    let p = ReportParams::default().check().unwrap();
    let page = |at: &str| {
        let mut recs = trial("P1", "healthy", "t1", "", 1.2);
        recs[0].recorded_at = at.into();
        let s = SubjectReport {
            subject_id: "P1".into(),
            recordings: recs,
            ..Default::default()
        };
        subject_html(&s, &Reference::published(&p), &p).unwrap()
    };
    let html = page("2024-03-05T10:21:33Z");
    assert!(
        html.contains(
            "t1_right.csv (right leg). Recorded 2024-03-05 10:21 UTC (from the left file)."
        ),
        "{html}"
    );
    let html = page("");
    assert!(
        html.contains("t1_right.csv (right leg). Recording date and time: not in the files."),
        "{html}"
    );
    assert!(!html.contains("not yet parsed"));
}

/// The triage order (issue 50 item 8): most findings first; among equal findings the person
/// with fewer values measured first (a missing value never moves a person down); people with
/// nothing measured last, their status saying why. The sentence on the order says only that;
/// the reference is its own sentence, with no "(0 of 0 …)" count.
#[test]
fn the_triage_ranks_findings_first_and_never_rewards_a_value_not_measured() {
    let mut recs = trial("Pnormal", "ldh", "t1", "", 1.2);
    // More measured than Pnormal, none outside: after Pnormal.
    let mut more = trial("Pmore", "ldh", "t1", "", 1.2);
    for r in more.iter_mut() {
        r.parameters[Parameter::StrideTime] = Some(1.1);
    }
    recs.extend(more);
    // One value measured, below normal: first, though it has least measured of the analysed.
    recs.extend(trial("Pslow", "ldh", "t1", "", 0.3));
    let mut failed = trial("Pfailed", "ldh", "t1", "", 1.2);
    for r in failed.iter_mut() {
        r.status = ldh_core::output::Status::Error.into();
        r.error = "unreadable".into();
    }
    recs.extend(failed);
    let c = cohort(recs);
    let triage = &c[c.find("Subjects, most findings first").unwrap()..];
    let triage = &triage[..triage.find("</table>").unwrap()];
    let at = |id: &str| {
        triage
            .find(&format!("<td>{id}</td>"))
            .unwrap_or_else(|| panic!("no {id} in {triage}"))
    };
    assert!(at("Pslow") < at("Pnormal"), "{triage}");
    assert!(at("Pnormal") < at("Pmore"), "{triage}");
    assert!(at("Pmore") < at("Pfailed"), "{triage}");
    assert!(
        triage.contains("<td class=\"bad\">not analysed (see above)</td><td class=\"num\">–</td><td class=\"num\">–</td><td class=\"num\">0 of "),
        "{triage}"
    );
    let order = &triage[..triage.find("</p>").unwrap()];
    assert!(
        order.contains("a missing value is never counted as normal")
            && !order.contains("healthy legs"),
        "{order}"
    );
    assert!(
        triage.contains("<p class=\"meta\">Reference: Published normal values")
            && triage.contains("and it has no analysed healthy leg.</p>")
            && !triage.contains("0 of 0"),
        "{triage}"
    );
}
