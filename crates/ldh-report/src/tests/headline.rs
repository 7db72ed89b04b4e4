//! The headline and the verdicts made once (issue 36): a walk with a 30 % step-time
//! asymmetry and a normal cadence, the inclusive rounded bounds, and the headline's wording
//! for the usual gaps (no sensor height, no affected side, no quiet standing, two trials).

use super::super::headline::{make, Headline};
use super::super::verdict::{judge, verdicts, Asymmetry, Cell, Judgement, Verdicts};
use super::super::*;
use super::row;
use ldh_core::domain::Parameter;
use ldh_core::pipeline::{Severity, Warning, WarningList, WithheldList};

/// A normal walk of `id`'s `side`: stride 1.05 s (114 steps/min), step time `step_s`, stance
/// 62 %, stride 1.30 m at 1.24 m/s.
pub(super) fn leg(id: &str, side: &str, step_s: f64) -> RecordingRow {
    let mut r = row(id, "ldh", side, 1.24);
    r.parameters[Parameter::StrideTime] = Some(1.05);
    // The run's walk cadence from both legs' strides (the report reads it, never recomputes).
    r.walk_cadence_steps_per_min = Some(120.0 / 1.05);
    r.parameters[Parameter::StepTime] = Some(step_s);
    // The pipeline's per-leg step frequency: 1 / step time (never the page's cadence).
    r.parameters[Parameter::StepFrequency] = Some(1.0 / step_s);
    r.parameters[Parameter::StanceRatio] = Some(0.62);
    r.parameters[Parameter::SwingRatio] = Some(0.38);
    r.parameters[Parameter::StrideLength] = Some(1.30);
    r.parameters[Parameter::StrideTimeCv] = Some(0.02);
    r.parameters[Parameter::StrideLengthCv] = Some(0.03);
    r
}

/// Left step 30 % longer than the right, the stride (and cadence) normal.
fn uneven(id: &str) -> Vec<RecordingRow> {
    // 0.5935 / 0.4565 = 1.300; the two steps make the 1.05 s stride.
    vec![leg(id, "left", 0.5935), leg(id, "right", 0.4565)]
}

pub(super) fn page_parts(recs: Vec<RecordingRow>) -> (String, Verdicts, Headline) {
    let p = ReportParams::default().check().unwrap();
    let reference = Reference::published(&p);
    let s = SubjectReport {
        subject_id: recs[0].subject_id.clone(),
        recordings: recs,
        ..Default::default()
    };
    let html = subject_html(&s, &reference, &p).unwrap();
    let own = super::super::subject::person_sides(&s.recordings);
    let sides: Vec<&RecordingRow> = own.iter().collect();
    let v = verdicts(&sides, &reference, p.0.asymmetry_flag_pct);
    let h = make(&v, &sides, &s.recordings, &reference, &s.context);
    (html, v, h)
}

/// The marks (▲/▼/◆) of a table row of `html` whose first cell starts with `start`.
fn marks(html: &str, start: &str) -> String {
    let at = html.find(start).unwrap_or_else(|| panic!("no row {start}"));
    let row = &html[at..];
    row[..row.find("</tr>").unwrap()]
        .chars()
        .filter(|c| matches!(c, '▲' | '▼' | '◆'))
        .collect()
}

#[test]
fn a_30_pct_step_asymmetry_with_normal_cadence_is_the_headline_and_one_verdict_everywhere() {
    let (html, v, h) = page_parts(uneven("A1"));
    // The headline names the asymmetry first, in a clinician's words.
    assert_eq!(
        h.findings[0],
        "Steps are uneven: the left step takes 30 % longer than the right (0.59 s against 0.46 s)."
    );
    assert!(html.contains(&h.findings[0]));
    // One cadence per walk, from both legs' strides: 60·2/1.05 = 114, within 96–126.
    let cadence = v.rows.iter().find(|r| r.q.label() == "Cadence").unwrap();
    assert_eq!(cadence.cells.len(), 1);
    assert!(matches!(
        cadence.cells[0],
        Cell::Value { v, judgement: Judgement::Within, .. } if v == 114.0
    ));
    assert!(!h.findings.iter().any(|f| f.contains("Cadence")), "{h:?}");
    // Step frequency is no row of its own, so the step asymmetry is said once.
    assert_eq!(v.asymmetric(), 1);
    assert_eq!(
        html.matches('◆').count() - html.matches("◆ asymmetry").count(),
        2
    );
    // The same marks in the summary and in section 2, quantity by quantity.
    let summary = &html[html.find("<table class=\"summary\"").unwrap()..];
    let summary = &summary[..summary.find("</table>").unwrap()];
    let section2 = &html[html.find("2. Gait parameters").unwrap()..];
    let section2 = &section2[..section2.find("</table>").unwrap()];
    for row in v.rows.iter().filter(|r| r.q.in_summary) {
        let in_summary = marks(summary, &format!("<b>{}</b>", row.q.label()));
        let in_table = marks(
            section2,
            &format!("<td>{} — {}", row.q.parameter.code(), row.q.label()),
        );
        let asym = match &row.asymmetry {
            Some(_) => marks(summary, &format!("<b>{} asymmetry</b>", row.q.label())),
            None => String::new(),
        };
        assert_eq!(format!("{in_summary}{asym}"), in_table, "{}", row.q.label());
    }
    assert!(!marks(summary, "<b>Cadence</b>").contains(['▲', '▼']));
    // The cohort page counts the same verdicts.
    let mut recs = uneven("A1");
    recs.extend(uneven("A2"));
    let c = cohort_html(&CohortReport {
        recordings: recs,
        reference: Some(Reference::published(
            &ReportParams::default().check().unwrap(),
        )),
        ..Default::default()
    })
    .unwrap();
    let expect = format!(
        "<td class=\"num bad\">{} of {}</td><td class=\"num bad\">1</td>",
        v.outside(),
        v.judged()
    );
    assert!(c.contains(&expect), "{expect} not in {c}");
}

#[test]
fn bounds_are_inclusive_and_compared_as_shown() {
    let p = ReportParams::default().check().unwrap();
    let reference = Reference::published(&p);
    let sf = reference.range(ldh_core::output::Parameter::StepFrequency);
    // 96–126 steps/min: 126.3 shows as "126" and is within; 126.6 shows as "127".
    assert_eq!(judge(126.3, sf, 60.0, 0), Judgement::Within);
    assert_eq!(judge(126.6, sf, 60.0, 0), Judgement::Above);
    assert_eq!(judge(95.5, sf, 60.0, 0), Judgement::Within);
    assert_eq!(judge(95.4, sf, 60.0, 0), Judgement::Below);
    // Stance against its published range (issue 49): 70 % is above 57–65 %, and its
    // asymmetry is judged.
    let mut recs = uneven("S");
    recs[0].parameters[Parameter::StanceRatio] = Some(0.70);
    let (_, v, _) = page_parts(recs);
    let stance = v.rows.iter().find(|r| r.q.label() == "Stance").unwrap();
    assert!(matches!(
        stance.cells[0],
        Cell::Value {
            judgement: Judgement::Above,
            ..
        }
    ));
    assert!(matches!(
        stance.asymmetry,
        Some(Asymmetry::Value(_, Some(true)))
    ));
}

pub(super) fn warn(r: &mut RecordingRow, code: &str, cols: &[&str]) {
    let ps: Vec<ldh_core::domain::Parameter> = cols
        .iter()
        .filter_map(|c| ldh_core::domain::Parameter::from_column(c).ok())
        .collect();
    let w = Warning::new(
        code.parse().unwrap(),
        Severity::Warning,
        format!("{code} message"),
    )
    .withholding(&ps);
    for &p in &ps {
        r.set_value(p, None);
    }
    r.withheld = WithheldList(Default::default());
    for &p in &ps {
        r.withheld.0.insert(p, w.withheld_reason());
    }
    r.warnings = WarningList(vec![w]);
}

/// Both legs of an even walk of `id` (`make`: [`leg`] or [`leg_of`]), each with the warning
/// `code` withholding `cols`.
fn both_warned(
    make: fn(&str, &str, f64) -> RecordingRow,
    id: &str,
    code: &str,
    cols: &[&str],
) -> Vec<RecordingRow> {
    ["left", "right"]
        .into_iter()
        .map(|side| {
            let mut r = make(id, side, 0.525);
            warn(&mut r, code, cols);
            r
        })
        .collect()
}

/// The stride length's columns a withholding check takes.
const LENGTH_COLUMNS: [&str; 3] = ["stride_length_m", "speed_mps", "stride_length_cv"];

#[test]
fn headline_without_the_sensor_height() {
    let recs = both_warned(leg, "H", "sensor_height_unknown", &LENGTH_COLUMNS);
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h,
        Headline {
            context: None,
            visits: None,
            belt: None,
            findings: vec![],
            steady: None,
            not_measured: Some(
                "Could not be measured: walking speed, stride length, stride length variability."
                    .into()
            ),
            to_do: Some(
                "Measure the sensor's height above the ankle and re-run the analysis with it."
                    .into()
            ),
            nothing_measured: false,
        }
    );
    // Only withholding: not a reason to distrust the other numbers.
    assert!(!html.contains("Check before reading"));
    assert_eq!(html.matches("sensor_height_unknown [warning]").count(), 1);
}

#[test]
fn headline_without_the_affected_side() {
    let (_, _, h) = page_parts(vec![leg("U", "left", 0.525), leg("U", "right", 0.525)]);
    assert_eq!(h.findings, Vec::<String>::new());
    assert_eq!(h.not_measured, None);
    assert_eq!(
        h.to_do.as_deref(),
        Some("The affected side is not given: add it to the manifest so the legs are compared as affected and unaffected.")
    );
}

#[test]
fn headline_when_the_gyroscope_bias_was_not_removed() {
    let recs = both_warned(leg_of, "B", "no_quiet_standing", &["wqk_deg", "pbi_deg"]);
    let (html, _, h) = page_parts(recs);
    assert_eq!(h.findings, Vec::<String>::new());
    // WQK and PBI are not in the summary: nothing of the summary is missing.
    assert_eq!(h.not_measured, None);
    assert_eq!(h.to_do, None);
    // It only withholds the two angles, each "not measured" with its reason as the table's
    // note: no "Check before reading" box saying it again (issue 50's HuGaDB page).
    let clinical = &html[..html.find("<h2 id=\"appendix\">").unwrap()];
    assert!(!clinical.contains("Check before reading"), "{clinical}");
    assert!(clinical.contains("not measured"), "{clinical}");
}

#[test]
fn headline_of_two_trials_of_one_person() {
    let mut recs = uneven("T");
    for r in recs.iter_mut() {
        r.trial_id = "t1".into();
    }
    for mut r in uneven("T") {
        r.trial_id = "t2".into();
        recs.push(r);
    }
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h.context.as_deref(),
        Some("The values are the mean of 2 trials (t1, t2) of this person.")
    );
    assert_eq!(
        h.findings,
        vec![
            "Steps are uneven: the left step takes 30 % longer than the right (0.59 s against 0.46 s).",
            "Step time is below normal on the right: 0.46 s (normal 0.48–0.63 s).",
        ]
    );
    assert!(html.contains(h.context.as_deref().unwrap()));
}

/// `id`'s uneven walk as trial `trial` of visit `visit`.
fn visit(id: &str, trial: &str, visit: &str) -> Vec<RecordingRow> {
    let mut recs = uneven(id);
    for r in recs.iter_mut() {
        r.trial_id = trial.into();
        r.visit = visit.into();
    }
    recs
}

#[test]
fn headline_of_two_visits_of_one_person() {
    let mut recs = visit("V", "1", "pre");
    recs.extend(visit("V", "2", "post"));
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h.context.as_deref(),
        Some("The values are the mean of 2 trials (1, 2) of this person.")
    );
    assert_eq!(
        h.visits.as_deref(),
        Some(
            "Recorded at 2 visits (pre, post): the values on this page are the mean of all of \
             them. The changes between the visits are listed under \"Change between visits\" \
             and none is judged: without a reliability table the measurement's own noise is \
             not known, so no change can be told apart from it."
        )
    );
    assert!(html.contains("<h2 id=\"visits\">Change between visits</h2>"));
    let section = &html[html.find("id=\"visits\"").unwrap()..];
    let section = &section[..section.find("</table>").unwrap()];
    assert!(
        !section.contains('▲') && !section.contains('▼'),
        "{section}"
    );
    // The page is read by a clinician: it names no switch of the tool's.
    assert!(
        section.contains("no reliability table (made from repeated trials of the same people)")
            && !html.contains("--reliability"),
        "{section}"
    );
    // Two trials of one visit say no visits.
    let mut recs = visit("W", "1", "pre");
    recs.extend(visit("W", "2", "pre"));
    assert_eq!(page_parts(recs).2.visits, None);
}

#[test]
fn headline_on_a_treadmill_with_a_belt_speed() {
    let mut recs = uneven("B");
    for r in recs.iter_mut() {
        r.setting = Some(ldh_core::Setting::Treadmill.into());
        r.belt_speed_mps = Some(1.1);
    }
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h.belt.as_deref(),
        Some("On a treadmill, belt at 1.10 m/s: the walking speed is the belt's, within normal (normal 1.00–1.60 m/s); the speed the sensors estimate is 1.24 m/s.")
    );
    assert!(html.contains("treadmill, belt 1.10 m/s"));
    assert_eq!(page_parts(uneven("C")).2.belt, None);
}

/// Issue 36 item 7, done when: the wording of a frozen gyroscope segment. The fault is named
/// with its span once, in "Check before reading"; its strides are left out but every parameter
/// is still measured (from the other strides), so the headline itself has nothing to add.
#[test]
fn headline_with_a_frozen_gyroscope_segment() {
    use ldh_core::pipeline::quality::{fault_warning, ChannelFault, FaultKind};
    let mut recs = vec![leg("F", "left", 0.525), leg("F", "right", 0.525)];
    let fault = ChannelFault {
        channel: 5,
        kind: FaultKind::Frozen,
        start_s: 12.3,
        end_s: 15.8,
        samples: 351,
    };
    let w = fault_warning(&fault);
    for &p in &w.affects {
        recs[0].set_value(p, None);
        recs[0].withheld.0.insert(p, w.withheld_reason());
    }
    recs[0].warnings = WarningList(vec![w]);
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h,
        Headline {
            context: None,
            visits: None,
            belt: None,
            findings: vec![],
            steady: None,
            not_measured: Some(
                "Could not be measured: stride length (left), stride length variability (left)."
                    .into()
            ),
            to_do: Some("The affected side is not given: add it to the manifest so the legs are compared as affected and unaffected.".into()),
            nothing_measured: false,
        }
    );
    let at = html
        .find("<div class=\"missing\"><b>Check before reading")
        .unwrap();
    let bx = &html[at..];
    let bx = &bx[..bx.find("</div>").unwrap() + 6];
    assert_eq!(
        bx,
        "<div class=\"missing\"><b>Check before reading the numbers.</b><ul><li>left: shank gyroscope z frozen from 12.3 s to 15.8 s: it repeated one value for 3.5 s while the other channels moved, so the strides in this span are left out and, as the attitude carries the lost rotation on, the shank angles and stride length of this leg are not measured</li></ul></div>"
    );
    // Once in the box, once (with its code) in the technical appendix; the withheld cells
    // give it as their reason.
    assert_eq!(bx.matches("frozen from 12.3 s to 15.8 s").count(), 1);
    assert_eq!(html.matches("channel_fault [warning]").count(), 1);
}

/// `leg` with the affected side given (so the to-do is about the recording alone).
pub(super) fn leg_of(id: &str, side: &str, step_s: f64) -> RecordingRow {
    let mut r = leg(id, side, step_s);
    r.affected_side = Some(ldh_core::output::AffectedSide::from(ldh_core::Side::Left).into());
    r
}

/// Issue 50 item 4: a 30 % stance asymmetry is named (71.6 % against 52.7 %, SI +30.4), with
/// the swing it leaves, and each leg's stance is judged against its published range (issue 49).
#[test]
fn headline_of_a_30_pct_stance_asymmetry() {
    let mut recs = vec![leg_of("S", "left", 0.525), leg_of("S", "right", 0.525)];
    recs[0].parameters[Parameter::StanceRatio] = Some(0.716);
    recs[0].parameters[Parameter::SwingRatio] = Some(0.284);
    recs[1].parameters[Parameter::StanceRatio] = Some(0.527);
    recs[1].parameters[Parameter::SwingRatio] = Some(0.473);
    let (html, v, h) = page_parts(recs);
    assert_eq!(
        h,
        Headline {
            findings: vec![
                "Stance is uneven: the left leg stays on the ground 36 % longer than the right (71.6 % against 52.7 % of the gait cycle; swing 28.4 % against 47.3 %).".into(),
                "Stance is above normal on the left: 71.6 %; below normal on the right: 52.7 % (normal 57.0–65.0 %).".into(),
            ],
            ..Default::default()
        }
    );
    assert!(html.contains(&h.findings[0]));
    // One verdict: marked ◆ in the tables and counted as the page's one asymmetry.
    assert_eq!(v.asymmetric(), 1);
    assert!(
        html.contains("+30.4 ◆ <span class=\"flagword\">asymmetric</span>"),
        "{html}"
    );
}

/// Issue 50 item 5: two trials of one person that disagree say so, in the headline and beside
/// each other on the page.
#[test]
fn headline_of_two_disagreeing_trials() {
    let trial = |t: &str, stride_s: f64, cv: f64| {
        let mut recs = vec![
            leg_of("D", "left", stride_s / 2.0),
            leg_of("D", "right", stride_s / 2.0),
        ];
        for r in recs.iter_mut() {
            r.trial_id = t.into();
            r.parameters[Parameter::StrideTime] = Some(stride_s);
            r.walk_cadence_steps_per_min = Some(120.0 / stride_s);
            r.parameters[Parameter::StrideTimeCv] = Some(cv);
        }
        recs
    };
    let mut recs = trial("t1", 1.03, 0.05);
    recs.extend(trial("t2", 1.18, 0.13));
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h.context.as_deref(),
        Some(
            "The values are the mean of 2 trials (t1, t2) of this person. The trials disagree \
             in stride time, step time and stride time variability by more than 10 % (without \
             a reliability table, whether this is beyond the measurement's noise is not known): the page shows their mean; look at each trial \
             under \"Trials side by side\" before relying on it."
        )
    );
    // The values are said once, beside each other under the summary, not again in the
    // headline.
    assert!(html.contains(
        "stride time 1.03 s in trial t1 against 1.18 s in trial t2; step time 0.52 s in trial \
         t1 against 0.59 s in trial t2; stride time variability 5.0 % in trial t1 against 13.0 % \
         in trial t2."
    ));
    assert_eq!(html.matches("1.03 s in trial t1").count(), 1);
    // Side by side on the page, under the summary.
    let at = html
        .find("<h2 id=\"trials\">Trials side by side</h2>")
        .expect("trials section");
    assert!(at < html.find("1. Recordings").unwrap());
    assert!(html[at..].contains("<th>trial t1</th><th>trial t2</th>"));
}

/// Issue 50 item 1: a walk that never becomes steady (`too_little_steady` on both legs) says
/// so instead of reporting variability, and asks for a longer steady walk.
#[test]
fn headline_of_a_walk_that_never_becomes_steady() {
    let cvs = ["stride_time_cv", "stride_length_cv"];
    let (_, _, h) = page_parts(both_warned(leg_of, "N", "too_little_steady", &cvs));
    assert_eq!(
        h,
        Headline {
            steady: Some(
                "The walk never settled into a steady pace long enough (both legs: fewer than 10 strides at a steady pace), so its stride time and stride length variability are not reported: the start-up and changes of pace would be read as variability.".into()
            ),
            not_measured: Some(
                "Could not be measured: stride time variability, stride length variability."
                    .into()
            ),
            to_do: Some("Record a longer walk at the person's own steady pace (at least 30 s after the start-up), so its variability can be measured.".into()),
            ..Default::default()
        }
    );
}

/// Issue 50 item 1: a walk whose pace keeps changing (`never_steady`, e.g. a walker speeding
/// up from 1.95 to 1.55 s) says so before the findings, whose means are of the whole walk, and
/// the rule's numbers stay out of "Check before reading" (a simulated hemiparetic walker's page
/// named its whole-walk stride time as a finding before the box said the walk was not steady).
#[test]
fn a_walk_whose_pace_keeps_changing_says_so_before_its_findings() {
    let cvs = ["stride_time_cv", "stride_length_cv"];
    let recs = both_warned(leg_of, "N", "never_steady", &cvs);
    let (html, _, h) = page_parts(recs);
    assert_eq!(
        h.steady.as_deref(),
        Some("The walk never became steady: its stride time kept changing (speeding up, slowing down or changing pace), so the values below are of the whole walk and its stride time and stride length variability are not reported.")
    );
    let said = html.find("The walk never became steady").expect("said");
    let headline = &html[html.find("class=\"headline\"").expect("headline")..];
    for later in ["No finding", "<b>Findings</b>", "Could not be measured"] {
        assert!(headline
            .find(later)
            .is_none_or(|at| html.len() - headline.len() + at > said));
    }
    // Its only finding is said in the headline: no "Check before reading" box.
    assert!(!html.contains("Check before reading the numbers"), "{html}");
}

/// Issue 50 item 6: a stride length withheld because left and right disagree does not ask
/// for the sensor height (given or not, it does not change the disagreement).
#[test]
fn a_stride_length_withheld_for_a_left_right_disagreement_does_not_ask_for_the_height() {
    let mut recs = both_warned(leg_of, "L", "lr_disagreement", &LENGTH_COLUMNS);
    for r in recs.iter_mut() {
        // The height was assumed and moves the length little: a note, withholding nothing.
        r.warnings.0.push(Warning::new(
            ldh_core::pipeline::quality::codes::SENSOR_HEIGHT_UNKNOWN,
            Severity::Note,
            "the sensor height was not given, so 0.10 m above the ankle was assumed",
        ));
    }
    let (_, _, h) = page_parts(recs);
    assert_eq!(
        h,
        Headline {
            not_measured: Some(
                "Could not be measured: walking speed, stride length, stride length variability."
                    .into()
            ),
            to_do: Some("Check that the two files come from the same walk and that each is named for the leg it was worn on (the legs disagree, which no setting of the analysis explains), then analyse them again.".into()),
            ..Default::default()
        }
    );
    assert!(!h.to_do.unwrap().contains("height"));
}

/// Two sensors not on one clock (`clock_offset`, TRIPOD), or two files not known to share one
/// with a step asymmetry no swing asymmetry backs (`two_clocks`, TRIPOD at 3.0 km/h): the
/// timings between the legs are withheld, so the headline names no step-time asymmetry however
/// uneven the offset made the steps look, and the to-do asks to synchronise the sensors.
#[test]
fn steps_made_uneven_by_two_clocks_are_not_named() {
    for code in ["clock_offset", "two_clocks"] {
        let mut recs = uneven("C");
        for r in recs.iter_mut() {
            warn(
                r,
                code,
                &[
                    "step_time_s",
                    "step_frequency_steps_per_s",
                    "double_support_ratio",
                ],
            );
        }
        let (html, v, h) = page_parts(recs);
        assert!(
            !h.findings.iter().any(|f| f.contains("Steps are uneven")),
            "{code}: {h:?}"
        );
        assert_eq!(v.asymmetric(), 0);
        assert!(!html.contains("Steps are uneven"));
        assert_eq!(
            h.not_measured.as_deref(),
            Some("Could not be measured: step time."),
            "{code}: {h:?}"
        );
        assert_eq!(
            h.to_do.as_deref(),
            Some("Synchronise the two sensors' clocks before the next recording (the device's own synchronisation, or both started together), so the timings between the legs can be measured."),
            "{code}"
        );
        // The headline says it; the clinical page's box does not repeat the measurement.
        assert!(!html.contains("Check before reading"), "{code}");
        assert!(
            html.contains(&format!("{code} message")),
            "{code}: in the appendix"
        );
        // The walk's cadence is from each leg's own strides, still measured.
        let cadence = v.rows.iter().find(|r| r.q.label() == "Cadence").unwrap();
        assert!(matches!(cadence.cells[0], Cell::Value { .. }));
    }
}

/// Issue 50 (re-read on TRIPOD's three belt speeds): a value that only some trials measured is
/// the mean of those alone, and the page says which, in the finding and in the summary's
/// cell — not "the mean of 2 trials" of a value one trial gave.
#[test]
fn a_value_from_one_trial_of_two_says_which_trial() {
    let mut recs = uneven("T");
    for r in recs.iter_mut() {
        r.trial_id = "t1".into();
        // The clocks disagreed in t1: no step time (nor its step frequency) on either leg.
        r.parameters[Parameter::StepTime] = None;
        r.parameters[Parameter::StepFrequency] = None;
    }
    for mut r in uneven("T") {
        r.trial_id = "t2".into();
        recs.push(r);
    }
    let (html, v, h) = page_parts(recs);
    assert_eq!(
        h.findings,
        vec![
            "Steps are uneven: the left step takes 30 % longer than the right (0.59 s against 0.46 s), from trial t2 only.",
            "Step time is below normal on the right: 0.46 s (normal 0.48–0.63 s), from trial t2 only.",
        ]
    );
    let step = v
        .rows
        .iter()
        .find(|r| r.q.parameter == Parameter::StepTime)
        .unwrap();
    for c in &step.cells {
        assert!(
            matches!(c, Cell::Value { note: Some(n), .. } if n == "from trial t2 only"),
            "{c:?}"
        );
    }
    // Both trials measured the stride time (and so the cadence): no note there.
    let stride = v
        .rows
        .iter()
        .find(|r| r.q.parameter == Parameter::StrideTime)
        .unwrap();
    assert!(matches!(&stride.cells[0], Cell::Value { note: None, .. }));
    assert!(
        html.contains("below normal; from trial t2 only"),
        "summary cell"
    );
}

/// Issue 50 item 7 (re-read): the radar draws the table's values — its cadence axis is the
/// walk's cadence, one value on both legs' polygons (it drew each leg's step frequency, 101
/// and 131 steps/min here, beside a table whose cadence was 114 and within normal), and swing,
/// the complement of stance, is no axis of its own.
#[test]
fn the_radar_draws_the_tables_walk_cadence_on_both_legs() {
    let recs = uneven("T");
    let p = ReportParams::default().check().unwrap();
    let reference = Reference::published(&p);
    let sides: Vec<&RecordingRow> = recs.iter().collect();
    let v = verdicts(&sides, &reference, p.0.asymmetry_flag_pct);
    let (codes, series) = super::super::subject::radar_series(&v, &sides, &reference);
    let sf = codes
        .iter()
        .position(|c| c == "SF")
        .expect("a cadence axis");
    let rr = reference.range(Parameter::StepFrequency).unwrap();
    // The table shows 114 steps/min (0 decimals); its z, on both legs.
    let z = rr.z(114.0 / 60.0).unwrap();
    assert_eq!(series.len(), 2);
    for (name, zs) in &series {
        assert!(
            (zs[sf] - z).abs() < 1e-9,
            "{}: {} against {z}",
            name.text,
            zs[sf]
        );
    }
    assert!(!codes.iter().any(|c| c == "SWP"), "{codes:?}");
}
