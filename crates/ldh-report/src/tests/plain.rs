//! Plain language on the clinical page (issue 50 item 9): the warning codes, the tool's own
//! words ("vouched for", "mirrored (y axis backwards)", "samples replaced as outliers") and the
//! reading notes are in the technical appendix (on screen only); the printed page says what was
//! found in plain words, from the typed codes ([`ldh_core::domain::WarningCode::plain`]).

use super::super::*;
use super::row;
use ldh_core::domain::{Parameter, WarningCode};
use ldh_core::output::StrideRow;
use ldh_core::pipeline::{codes, Severity, Warning, WarningList};

/// A stride of `side`, not valid for `codes` (strides.csv's `reason_codes`).
fn stride(side: &str, i: usize, codes: &str) -> StrideRow {
    serde_json::from_value(serde_json::json!({
        "subject_id": "J", "side": side, "model": "fusion", "stride_index": i, "bout": 0,
        "hs_time_s": i as f64, "to_time_s": null, "next_hs_time_s": null, "stride_time_s": 1.0,
        "stance_ratio": null, "double_support_ratio": null, "stride_length_m": null,
        "speed_mps": null, "wqk_deg": null, "pbi_deg": null, "bdk_deg": null,
        "heading_change_deg": null, "valid": false, "reason": "the tool's own text",
        "reason_codes": codes, "trial_id": ""
    }))
    .unwrap()
}

#[test]
fn the_clinical_page_says_in_plain_words_what_the_appendix_says_with_codes() {
    let p = ReportParams::default().check().unwrap();
    let mut recs = vec![row("J", "ldh", "left", 1.2), row("J", "ldh", "right", 1.2)];
    let lr = Warning::new(
        codes::LR_DISAGREEMENT,
        Severity::Warning,
        "left and right median stride lengths differ by 31 % (left 1.20 m, right 0.88 m): over a walk both ankles cover the same distance",
    )
    .withholding(&[Parameter::StrideLength, Parameter::Speed]);
    let gyro = Warning::new(
        codes::GYRO_SCALE_FAULT,
        Severity::Fault,
        "gyroscope sensor fault: 12.0 % of the samples exceed 1000 deg/s",
    )
    .withholding(&[Parameter::Wqk]);
    for r in recs.iter_mut() {
        r.mirrored = Some(true);
        r.outliers_replaced = Some(350);
        for w in [&lr, &gyro] {
            for &p in &w.affects {
                r.set_value(p, None);
                r.withheld.0.insert(p, w.withheld_reason());
            }
        }
        r.warnings = WarningList(vec![lr.clone(), gyro.clone()]);
        // One value measured, so the tables (and their reasons under them) stay.
        r.parameters[Parameter::StrideTime] = Some(1.1);
    }
    let s = SubjectReport {
        subject_id: "J".into(),
        recordings: recs,
        strides: vec![
            stride("left", 1, "lr_disagreement"),
            stride("left", 2, "gyro_scale_fault"),
            stride("right", 3, "not_steady"),
        ],
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    let at = html.find("<h2 id=\"appendix\">").expect("an appendix");
    let (clinical, appendix) = html.split_at(at);
    for code in WarningCode::ALL {
        for text in [code.as_str().to_string(), code.as_str().replace('_', " ")] {
            if text.contains(['_', ' ']) {
                assert!(!clinical.contains(&text), "'{text}' on the clinical page");
            }
        }
    }
    for jargon in [
        "vouched for",
        "mirrored",
        "y axis",
        "replaced as outliers",
        "350",
        "the tool's own text",
    ] {
        assert!(
            !clinical.contains(jargon),
            "'{jargon}' on the clinical page"
        );
    }
    // In plain words: the withheld values' reasons (one for both legs: their asymmetry's
    // too, not "left leg: …"), the excluded strides' reasons.
    assert!(
        clinical.contains("] not measured: left and right median stride lengths differ by 31 % (left 1.20 m, right 0.88 m)</div>")
            && !clinical.contains("left leg: left and right"),
        "{clinical}"
    );
    assert!(
        clinical.contains("] not measured: gyroscope sensor fault</div>"),
        "{clinical}"
    );
    assert!(
        clinical.contains("<td>signal quality: the two legs disagree</td>"),
        "{clinical}"
    );
    assert!(
        clinical.contains("<td>signal quality: gyroscope fault</td>"),
        "{clinical}"
    );
    // The technical appendix keeps the codes and the counts.
    for tech in [
        "lr_disagreement [warning]",
        "gyro_scale_fault [fault]",
        "mirrored (y axis backwards)",
        "samples replaced as outliers",
    ] {
        assert!(appendix.contains(tech), "'{tech}' not in the appendix");
    }
}

/// A walk whose two sensors are faulty (HuGaDB 14_00: both gyroscopes amplified): nothing is
/// measured, so the headline does not say "No finding … within its normal range"; the to-do
/// names both sensors, not the left one.
#[test]
fn a_walk_with_nothing_measured_is_not_called_normal_and_both_sensors_are_named() {
    use ldh_core::pipeline::quality::params;
    let p = ReportParams::default().check().unwrap();
    let mut recs = vec![row("K", "ldh", "left", 1.2), row("K", "ldh", "right", 1.2)];
    for r in recs.iter_mut() {
        let w = Warning::new(
            codes::GYRO_SCALE_FAULT,
            Severity::Fault,
            "gyroscope sensor fault: 43.4 % of the samples exceed 1200 deg/s",
        )
        .withholding(&params::ALL);
        for &p in &w.affects {
            r.set_value(p, None);
            r.withheld.0.insert(p, w.withheld_reason());
        }
        r.warnings = WarningList(vec![w]);
    }
    let s = SubjectReport {
        subject_id: "K".into(),
        recordings: recs,
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    assert!(!html.contains("No finding"), "{html}");
    assert!(html.contains(
        "<b>Nothing could be judged: </b>no value of this walk was measured (the reasons follow)."
    ));
    assert!(html.contains(
        "<b>To do: </b>Check both sensors (they recorded faulty signals) and record the walk again."
    ));
    // Every value withheld: one sentence per table, the reason for both legs' values and
    // their asymmetry said once in it, no table of "not measured" cells.
    assert_eq!(html.matches("] not measured: ").count(), 0, "{html}");
    assert!(html.contains(
        "No value of this summary was measured on either leg, so its table is left out: gyroscope sensor fault."
    ), "{html}");
}

#[test]
fn sta_turned_off_is_said_once_and_names_no_switch() {
    let p = ReportParams::default().check().unwrap();
    let mut recs = vec![row("K", "ldh", "left", 1.2), row("K", "ldh", "right", 1.2)];
    for r in recs.iter_mut() {
        r.parameters[Parameter::Sta] = None;
        r.parameters.sta_status = ldh_core::pipeline::STA_TURNED_OFF.into();
    }
    let s = SubjectReport {
        subject_id: "K".into(),
        recordings: recs,
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    assert!(
        html.contains("not computed: turned off for this run"),
        "{html}"
    );
    assert!(!html.contains("not computed: not computed"), "{html}");
    for switch in ["--no-sta", "compute_sta"] {
        assert!(!html.contains(switch), "'{switch}' on the page");
    }
}
