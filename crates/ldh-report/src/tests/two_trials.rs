//! A person's page of two trials (issue 50: TRIPOD's treadmill runs printed on 4 A4 pages): the
//! tables count every trial's strides, a finding every trial gives is one line, one kind of
//! finding given at several times is one line in plain words, and the recordings table says
//! its counts are of all trials.

use super::super::*;
use super::row;
use ldh_core::output::{RecordingRow, StrideRow};
use ldh_core::pipeline::{codes, Severity, Warning, WarningList};

/// A stride of `side` in `trial`, excluded for `codes` (or valid when `codes` is empty).
fn stride(trial: &str, side: &str, i: usize, codes: &str) -> StrideRow {
    serde_json::from_value(serde_json::json!({
        "subject_id": "T", "side": side, "model": "fusion", "stride_index": i, "bout": 0,
        "hs_time_s": i as f64, "to_time_s": null, "next_hs_time_s": null, "stride_time_s": 1.0,
        "stance_ratio": null, "double_support_ratio": null, "stride_length_m": null,
        "speed_mps": null, "wqk_deg": null, "pbi_deg": null, "bdk_deg": null,
        "heading_change_deg": null, "valid": codes.is_empty(), "reason": "",
        "reason_codes": codes, "trial_id": trial
    }))
    .unwrap()
}

fn trial(id: &str, spike_s: f64) -> Vec<RecordingRow> {
    let mut legs = vec![
        row("T", "healthy", "left", 1.2),
        row("T", "healthy", "right", 1.2),
    ];
    for r in legs.iter_mut() {
        r.trial_id = id.into();
        r.strides_total = Some(10);
        r.strides_valid = Some(7);
    }
    legs[0].warnings = WarningList(vec![
        Warning::new(
            codes::ACC_CLIPPING,
            Severity::Warning,
            "accelerometer at its range in 3 strides: their lengths are left out",
        ),
        Warning::new(
            codes::NO_QUIET_STANDING,
            Severity::Warning,
            "no quiet standing of 1 s found: no gyroscope bias was removed at rest",
        ),
    ]);
    legs[1].warnings = WarningList(vec![Warning::new(
        codes::CHANNEL_FAULT,
        Severity::Warning,
        format!(
            "shank accelerometer z spiking at {spike_s:.1} s: 1 isolated sample(s) far outside the channel's range, so the strides in this span are left out (the others are kept)"
        ),
    )]);
    legs
}

#[test]
fn a_page_of_two_trials_counts_and_says_every_trial_once() {
    let p = ReportParams::default().check().unwrap();
    let mut recordings = trial("t1", 6.0);
    recordings.extend(trial("t2", 6.3));
    let mut strides = Vec::new();
    for (t, n) in [("t1", 2), ("t2", 3)] {
        for i in 0..n {
            strides.push(stride(t, "left", i, "not_steady"));
            strides.push(stride(t, "right", i, "not_steady"));
        }
        strides.push(stride(t, "left", 9, ""));
    }
    let s = SubjectReport {
        subject_id: "T".into(),
        recordings,
        strides,
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    let clinical = &html[..html.find("<h2 id=\"appendix\">").unwrap()];
    // Both trials' excluded strides (2 + 3 a leg), not the first trial's alone.
    assert!(
        clinical.contains(
            "<td><b>excluded for any reason</b></td><td class=\"num\"><b>5</b></td><td class=\"num\"><b>5</b></td>"
        ),
        "{clinical}"
    );
    // No file gives its date and time: said once, not once per trial.
    assert!(clinical.contains("<p class=\"meta\">Recorded (date and time: not in the files):</p>"));
    assert!(!clinical.contains("Recording date and time"), "{clinical}");
    // The recordings table's sums say they are of all trials.
    assert!(
        clinical.contains("<td>20 / 14 (all trials)</td>"),
        "{clinical}"
    );
    // One message of both trials: one line naming them.
    assert!(
        clinical.contains(
            "<li>left (trials t1, t2): accelerometer at its range in 3 strides: their lengths are left out</li>"
        ),
        "{clinical}"
    );
    // No quiet standing only withholds the shank angles (said where they are not measured):
    // its reasoning is the appendix's, not the clinical box's.
    assert!(!clinical.contains("no quiet standing of 1 s"), "{clinical}");
    assert!(html.contains("no quiet standing of 1 s found"), "{html}");
    // A channel spiking at another time in each trial: one line in plain words, the times in
    // the appendix.
    assert!(
        clinical.contains(
            "<li>right: a sensor channel failed for part of the walk (2 times, in trials t1, t2; each in the technical appendix)</li>"
        ),
        "{clinical}"
    );
    assert!(!clinical.contains("spiking at 6.0 s"), "{clinical}");
    let appendix = &html[html.find("<h2 id=\"appendix\">").unwrap()..];
    assert!(appendix.contains("t1: shank accelerometer z spiking at 6.0 s"));
    assert!(appendix.contains("t2: shank accelerometer z spiking at 6.3 s"));
}
