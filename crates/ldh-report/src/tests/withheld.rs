//! A page where every value was withheld (HuGaDB participant 17: both shanks' gyroscopes faulty
//! in both trials) says so in one sentence per table, never a grid of "not measured" or dashes;
//! and the subject page's layout rule for print: the charts kept whole stand before the table
//! that can break, with their captions beside them.

use super::super::*;
use super::row;
use ldh_core::domain::Parameter;
use ldh_core::output::RecordingRow;

/// Both legs of `trial` with nothing measured (the fixture's speed removed too).
fn nothing(trial: &str) -> Vec<RecordingRow> {
    ["left", "right"]
        .iter()
        .map(|side| {
            let mut r = row("P", "healthy", side, 1.2);
            r.parameters[Parameter::Speed] = None;
            r.trial_id = trial.into();
            r
        })
        .collect()
}

fn page(recordings: Vec<RecordingRow>) -> String {
    let p = ReportParams::default().check().unwrap();
    let s = SubjectReport {
        subject_id: "P".into(),
        recordings,
        ..Default::default()
    };
    subject_html(&s, &Reference::published(&p), &p).unwrap()
}

/// Every value withheld: the summary, section 2 and the trials each say it in one sentence
/// with the reason, and draw no table of "not measured" cells.
#[test]
fn a_table_with_every_value_withheld_is_one_sentence() {
    let mut recs = nothing("t1");
    recs.extend(nothing("t2"));
    let html = page(recs);
    for gone in [
        "<table class=\"summary\">",
        "<table class=\"params\">",
        "<table class=\"trials\">",
        "not measured [",
    ] {
        assert!(!html.contains(gone), "'{gone}' in {html}");
    }
    for said in [
        "No value of this summary was measured on either leg, so its table is left out: not computable from these strides;",
        "No gait parameter was measured on either leg, so the table is left out: not computable from these strides;",
        "No value was measured in any of the 2 trials (t1, t2), so there is nothing to compare",
    ] {
        assert!(html.contains(said), "no '{said}' in {html}");
    }
}

/// One value measured (the walking speed of one trial): every table stays, the withheld cells
/// say "not measured [n]" with the reason under the table.
#[test]
fn one_value_measured_keeps_the_tables() {
    let mut recs = nothing("t1");
    recs.extend(nothing("t2"));
    for r in recs.iter_mut().filter(|r| r.trial_id == "t1") {
        r.parameters[Parameter::Speed] = Some(1.1);
    }
    let html = page(recs);
    for kept in [
        "<table class=\"summary\">",
        "<table class=\"params\">",
        "<table class=\"trials\">",
        "not measured [",
    ] {
        assert!(html.contains(kept), "no '{kept}' in {html}");
    }
    assert!(!html.contains("so its table is left out"), "{html}");
    assert!(!html.contains("so the table is left out"), "{html}");
}

/// The layout rule of a printed subject page: the radar (kept whole) comes before section 2's
/// table, whose rows may break across pages, so the table fills the page where the chart did
/// not fit (the demo's L01 page 2 ended 44 % blank when the radar came after the table); both
/// charts print with their captions beside them (`div.beside`, the chart at its print width).
#[test]
fn the_charts_come_before_the_table_that_can_break_with_their_captions_beside() {
    let mut l = row("S1", "ldh", "left", 0.6);
    let mut r = row("S1", "ldh", "right", 1.2);
    for (x, stance) in [(&mut l, 0.62), (&mut r, 0.70)] {
        x.parameters[Parameter::StrideTime] = Some(4.0 / 3.0);
        x.parameters[Parameter::StepTime] = Some(0.6);
        x.parameters[Parameter::StanceRatio] = Some(stance);
        x.walk_cadence_steps_per_min = Some(90.0);
    }
    let html = page(vec![l, r]);
    let radar = html.find("Radar chart of the values").expect("a radar");
    let table = html.find("<table class=\"params\">").unwrap();
    let section = html.find("2. Gait parameters").unwrap();
    assert!(
        section < radar && radar < table,
        "radar not between the heading and the table"
    );
    let div = html[..radar].rfind("<div class=\"beside\">").unwrap();
    assert!(
        !html[div..radar].contains("</div>"),
        "the radar is not in div.beside"
    );
    let w = plots::PrintWidth::Chart;
    let rule = format!(
        "div.beside > figure.{} > svg {{ width: {}pt; flex: 0 0 {}pt; }}",
        w.class(),
        w.pt(),
        w.pt()
    );
    assert!(html.contains(&rule), "no '{rule}' in the page's CSS");
}

/// HuGaDB 07_03 read as a clinician would (2026-12-03): the right leg, its gyroscope faulty,
/// had no stride used, and its steady window (the walk's, 4.7–95.0 s of 96.6 s) read "the
/// whole walk"; one stride is "1 stride", not "1 stride(s)"; the "Check before reading" box
/// printed the fault's measurement (percentages of samples beyond a limit) on the clinical
/// part, where plain words and a pointer to the appendix do.
#[test]
fn a_faulty_legs_window_fault_and_counts_in_plain_words() {
    use ldh_core::pipeline::{codes, Severity, Warning, WarningList};
    let mut recs: Vec<RecordingRow> = ["left", "right"]
        .iter()
        .map(|side| {
            let mut r = row("P", "healthy", side, 1.2);
            r.parameters[Parameter::StrideTime] = Some(0.91);
            r.steady_start_s = Some(4.7);
            r.steady_end_s = Some(95.0);
            r
        })
        .collect();
    recs[0].steady_excluded_start = Some(1);
    recs[1].strides_valid = Some(0);
    recs[1].warnings = WarningList(vec![Warning::new(
        codes::GYRO_SCALE_FAULT,
        Severity::Fault,
        "gyroscope sensor fault: 55.5 % of the samples exceed 1200 deg/s",
    )]);
    let html = page(recs);
    let clinical = &html[..html.find("<h2 id=\"appendix\">").unwrap()];
    for said in [
        "<td>4.7–95.0 s (1 stride at the start excluded)</td>",
        "<td>4.7–95.0 s (no stride of this leg could be used)</td>",
        "<li>right: gyroscope fault (what the sensor recorded is in the technical appendix)</li>",
        "1 value lies outside the reference range; 0 asymmetries beyond the threshold.",
    ] {
        assert!(clinical.contains(said), "no '{said}' in {clinical}");
    }
    for gone in ["the whole walk", "stride(s)", "55.5 %", "value(s)"] {
        assert!(!clinical.contains(gone), "'{gone}' on the clinical page");
    }
    assert!(
        html[clinical.len()..].contains("55.5 %"),
        "the appendix keeps the numbers"
    );
}
