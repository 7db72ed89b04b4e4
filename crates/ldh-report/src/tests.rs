//! Report building blocks: escaping by construction, file names, symmetry index, reference ranges, params.

mod agreement_page;
mod cohort;
#[cfg(feature = "dummy-parameter")]
mod dummy_parameter;
mod headline;
mod plain;
mod reread;
mod two_trials;
mod vocabulary;
mod withheld;

use super::*;
use ldh_core::domain::Parameter;
use ldh_core::output::RecordingRow;

/// A recording row of `id` with only its speed (m/s) measured (`ldh-core`'s ML tests have the same row, output/test_rows.rs).
pub(crate) fn row(id: &str, group: &str, side: &str, speed: f64) -> RecordingRow {
    let mut r: RecordingRow = serde_json::from_value(serde_json::json!({
        "subject_id": id, "side": side, "model": "fusion", "group": group, "affected_side": "",
        "side_role": "", "source": "", "status": "ok", "error": "", "fs_hz": 100.0,
        "duration_s": 20.0, "strides_total": 10, "strides_valid": 8, "stride_time_s": null,
        "step_time_s": null, "step_frequency_steps_per_s": null, "stance_ratio": null,
        "swing_ratio": null, "stride_length_m": null, "speed_mps": null,
        "stride_length_cv": null, "stride_time_cv": null, "sta_per_s": null,
        "sta_per_stride": null, "sta_status": "", "wqk_deg": null, "pbi_deg": null,
        "bdk_deg": null, "mirrored": false, "axial_rotation_deg": 0.0,
        "outliers_replaced": 0, "clipped_samples": 0
    }))
    .unwrap();
    r.parameters[Parameter::Speed] = Some(speed);
    r
}

#[test]
fn escaping_file_names_and_symmetry() {
    assert_eq!(file_stem("S 01/../x"), "S%2001%2F%2E%2E%2Fx");
    assert_eq!(file_stem(".hidden"), "%2Ehidden");
    assert_eq!(file_stem(""), "%");
    assert!((symmetry_index_pct(1.1, 0.9).unwrap() - 20.0).abs() < 1e-12);
    assert_eq!(symmetry_index_pct(1.0, -1.0), None);
    assert_eq!(symmetry_index_pct(f64::NAN, 1.0), None);
}

#[test]
fn reference_from_the_cohort_needs_enough_healthy_subjects() {
    let p = ReportParams::default()
        .min_healthy_subjects(4)
        .check()
        .unwrap();
    // Four healthy subjects, speeds (mean of both legs) 1.0, 1.1, 1.2, 1.3 m/s.
    let mut rows = Vec::new();
    for (i, v) in [1.0, 1.1, 1.2, 1.3].iter().enumerate() {
        rows.push(row(&format!("H{i}"), "healthy", "left", v - 0.05));
        rows.push(row(&format!("H{i}"), "healthy", "right", v + 0.05));
    }
    rows.push(row("L1", "ldh", "left", 0.3));
    let r = Reference::from_rows(&rows, &p);
    let s = r.ranges.iter().find(|x| x.column == "speed_mps").unwrap();
    assert_eq!(s.source, ReferenceSource::Cohort { n_subjects: 4 });
    let sd = (0.05f64 * 0.05 * 2.0 + 0.15 * 0.15 * 2.0) / 3.0;
    assert!((s.mean.unwrap() - 1.15).abs() < 1e-12);
    assert!((s.sd.unwrap() - sd.sqrt()).abs() < 1e-12);
    assert!((s.low.unwrap() - (1.15 - 1.96 * sd.sqrt())).abs() < 1e-12);
    assert_eq!(s.outside(0.3), Some(true));
    assert_eq!(s.outside(1.15), Some(false));
    // Parameters the cohort lacks fall back to the published ranges.
    let st = r
        .ranges
        .iter()
        .find(|x| x.column == "stride_time_s")
        .unwrap();
    assert!(matches!(st.source, ReferenceSource::Published(_)));
    // Too few healthy subjects: published everywhere, and STA has no range at all.
    let r = Reference::from_rows(&rows[..6], &p);
    let s = r.ranges.iter().find(|x| x.column == "speed_mps").unwrap();
    assert_eq!((s.low, s.high), (Some(1.0), Some(1.6)));
    let sta = r.ranges.iter().find(|x| x.code == "STA").unwrap();
    assert_eq!(sta.source, ReferenceSource::None);
    assert_eq!(sta.z(1.0), None);
    // A parameter is either published or says why it is not, never both.
    for (col, _) in super::reference::NO_PUBLISHED {
        assert!(
            super::reference::PUBLISHED.iter().all(|p| p.0 != col),
            "{col}"
        );
    }
    // Stance, swing and double support: Perry & Burnfield's normal cycle (issue 49).
    for (col, lo, hi) in [
        ("stance_ratio", 0.57, 0.65),
        ("swing_ratio", 0.35, 0.43),
        ("double_support_ratio", 0.14, 0.30),
    ] {
        let x = r.ranges.iter().find(|x| x.column == col).unwrap();
        assert_eq!(
            (x.source.clone(), x.low, x.high),
            (
                ReferenceSource::Published(super::reference::PERRY.into()),
                Some(lo),
                Some(hi)
            )
        );
        assert!(super::reference::no_published_reason(col).is_none());
    }
    // With enough healthy subjects the cohort's own range is used for them as for the rest.
    let mut rows = rows.clone();
    for (i, x) in rows.iter_mut().enumerate() {
        x.parameters[Parameter::StanceRatio] = Some(0.60 + 0.01 * i as f64);
    }
    let r = Reference::from_rows(&rows, &p);
    let x = r
        .ranges
        .iter()
        .find(|x| x.column == "stance_ratio")
        .unwrap();
    assert_eq!(x.source, ReferenceSource::Cohort { n_subjects: 4 });
}

#[test]
fn params_are_checked() {
    assert!(ReportParams::default().check().is_ok());
    assert!(ReportParams::default()
        .min_healthy_subjects(2)
        .check()
        .is_err());
    let mut p = ReportParams::default();
    p.reference_z = 0.0;
    assert!(p.check().is_err());
    let mut p = ReportParams::default();
    p.trace = TraceParams::default().window_s(0.5);
    assert!(p.check().is_err());
}

#[test]
fn a_subject_without_anything_still_renders() {
    let p = ReportParams::default().check().unwrap();
    let s = SubjectReport {
        subject_id: "X<1>".into(),
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    assert!(html.contains("Gait report: subject X&lt;1&gt;"));
    assert!(html.contains("<title>Gait report — X&lt;1&gt;</title>"));
    assert!(html.contains("No left recording was given."));
    assert!(html.contains("No strides were detected."));
    assert!(html.contains("without signal traces.") && !html.contains("ldh analyze"));
    let c = cohort_html(&CohortReport::default()).unwrap();
    assert!(c.contains("No group statistics"));
}

#[test]
fn text_from_files_is_escaped_and_control_characters_dropped() {
    let p = ReportParams::default().check().unwrap();
    let mut bad = row("S<1>&\"x\"", "ldh", "left", 1.0);
    bad.status = ldh_core::output::Status::Error.into();
    bad.error = "bad value \u{1}<script>alert('x')</script> at line 3".into();
    let s = SubjectReport {
        subject_id: bad.subject_id.clone(),
        recordings: vec![bad.clone()],
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    assert!(!html.contains("<script>"), "{html}");
    assert!(html.contains("&lt;script&gt;alert('x')&lt;/script&gt;"));
    assert!(html.contains("subject S&lt;1&gt;&amp;&quot;x&quot;"));
    assert!(!html.contains('\u{1}'));
    let c = cohort_html(&CohortReport {
        recordings: vec![bad],
        subject_links: vec![("S<1>&\"x\"".into(), "subjects/a\"b.html".into())],
        ..Default::default()
    })
    .unwrap();
    assert!(c.contains("<a href=\"subjects/a&quot;b.html\">"), "{c}");
    assert!(!c.contains("<script>") && !c.contains('\u{1}'));
}

/// A leg whose gyroscope is amplified ×10 and clips at ±2000 deg/s (HuGaDB's fault), analysed
/// and rendered: none of its parameters shows a number or a ▲/▼ mark, each says "not measured".
#[test]
fn a_faulty_gyroscope_leg_shows_no_number_in_the_report() {
    let c = ldh_sim::CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 25.0,
        seed: 4,
        ..ldh_sim::CohortParams::default()
    };
    let mut sub = c.simulate(0).unwrap();
    for ch in sub.left.recording.gyro_dps.iter_mut() {
        for x in ch.iter_mut() {
            *x = (*x * 10.0).clamp(-2000.0, 2000.0);
        }
    }
    let params = ldh_core::pipeline::AnalysisParams {
        compute_sta: false,
        ..Default::default()
    };
    let res = ldh_sim::analyze_simulated(&sub, &params);
    let tables = ldh_core::output::Tables::of(std::slice::from_ref(&res));
    let left = tables
        .recordings
        .iter()
        .find(|r| r.side == ldh_core::Side::Left)
        .unwrap();
    assert!(
        left.warnings
            .iter()
            .any(|w| w.code == "gyro_scale_fault"
                && w.severity == ldh_core::pipeline::Severity::Fault)
    );
    // The rows go through JSON, as `ldh report --results` reads them.
    let rows: Vec<RecordingRow> =
        serde_json::from_str(&serde_json::to_string(&tables.recordings).unwrap()).unwrap();
    // A reference whose every range is narrow, so any number shown would get a mark.
    let p = ReportParams::default()
        .min_healthy_subjects(4)
        .check()
        .unwrap();
    let mut reference = Reference::published(&p);
    for r in reference.ranges.iter_mut() {
        (r.low, r.high) = (Some(1e6), Some(2e6));
    }
    let s = SubjectReport {
        subject_id: res.subject_id.clone(),
        recordings: rows,
        strides: tables.strides.clone(),
        ..Default::default()
    };
    let html = subject_html(&s, &reference, &p).unwrap();
    let table = &html[html.find("2. Gait parameters").unwrap()..];
    let table = &table[..table.find("</table>").unwrap()];
    let mut checked = 0;
    for q in super::verdict::QUANTITIES.iter() {
        let start = table
            .find(&format!("<td>{} — {}", q.parameter.code(), q.label()))
            .unwrap_or_else(|| panic!("{} not in the table", q.label()));
        let row = &table[start..];
        let row = &row[..row.find("</tr>").unwrap()];
        // Cells: parameter, unit, left (or the walk's), right, range, SI.
        let cells: Vec<&str> = row.split("<td").collect();
        let left_cell = cells[3];
        if q.scope == super::verdict::Scope::Walk {
            // One value per walk: the right leg's alone, and said so.
            assert!(
                left_cell.contains("from the right leg only") || left_cell.contains("not measured"),
                "{}: {left_cell}",
                q.label()
            );
            checked += 1;
            continue;
        }
        assert!(
            left_cell.contains("not measured ["),
            "{}: {left_cell}",
            q.label()
        );
        assert!(
            !left_cell.contains('▲') && !left_cell.contains('▼'),
            "{left_cell}"
        );
        assert!(
            !left_cell
                .split('>')
                .nth(1)
                .unwrap_or("")
                .chars()
                .next()
                .is_some_and(|ch| ch.is_ascii_digit() || ch == '-'),
            "{}: a number: {left_cell}",
            q.label()
        );
        // No symmetry index from a withheld value.
        assert!(
            cells[6].contains(">–<") || cells[6].contains("not measured ["),
            "{}: SI {}",
            q.label(),
            cells[6]
        );
        checked += 1;
    }
    assert_eq!(checked, super::verdict::QUANTITIES.len());
    // The clinical summary: every left measure says "not measured", with no number or mark.
    let summary = &html[html.find("Clinical summary").unwrap()..];
    let summary = &summary[summary.find("<table").unwrap()..];
    let summary = &summary[..summary.find("</table>").unwrap()];
    for q in super::verdict::QUANTITIES
        .iter()
        .filter(|q| q.in_summary && q.scope == super::verdict::Scope::Side)
    {
        let row = &summary[summary.find(&format!("<b>{}</b>", q.label())).unwrap()..];
        let row = &row[..row.find("</tr>").unwrap()];
        let cells: Vec<&str> = row.split("<td").collect();
        assert!(
            cells[1].contains("not measured ["),
            "{}: {}",
            q.label(),
            cells[1]
        );
        assert!(!cells[1].contains('▲') && !cells[1].contains('▼'));
        // No number but the note's: "not measured [n]".
        let text = cells[1].split(" [").next().unwrap_or("");
        assert!(!text.chars().any(|c| c.is_ascii_digit()), "{}", cells[1]);
    }
    // Each reason once on the page, numbered, under the first table that cites it.
    assert_eq!(
        html.matches("] not measured: gyroscope sensor fault</div>")
            .count(),
        1,
        "{html}"
    );
    assert_eq!(
        html.matches("] not measured: left leg: gyroscope sensor fault</div>")
            .count(),
        1
    );
    // The warning box: one bullet for the fault, naming the leg.
    assert!(html.contains("left: gyro_scale_fault [fault]: gyroscope sensor fault"));
    // Every left stride is excluded, grouped under one kind.
    assert!(
        html.contains(
            "<tr><td>signal quality: gyroscope fault</td><td class=\"num\">15</td><td class=\"num\">0</td></tr>"
        ),
        "{}",
        &html[html.find("Strides excluded").unwrap_or(0)..][..600]
    );
}

/// Healthy legs with a warning or a withheld value stay out of the cohort's reference range,
/// and the description says how many legs were used.
#[test]
fn the_reference_uses_only_legs_that_pass_every_check() {
    let p = ReportParams::default()
        .min_healthy_subjects(4)
        .check()
        .unwrap();
    let mut rows = Vec::new();
    for (i, v) in [1.0, 1.1, 1.2, 1.3].iter().enumerate() {
        rows.push(row(&format!("H{i}"), "healthy", "left", *v));
        rows.push(row(&format!("H{i}"), "healthy", "right", *v));
    }
    // A fifth healthy subject with a faulty sensor reading 9 m/s on one leg.
    let mut bad = row("H9", "healthy", "left", 9.0);
    bad.warnings = ldh_core::pipeline::WarningList(vec![ldh_core::pipeline::Warning::new(
        ldh_core::pipeline::codes::GYRO_SCALE_FAULT,
        ldh_core::pipeline::Severity::Fault,
        "x",
    )]);
    rows.push(bad);
    let r = Reference::from_rows(&rows, &p);
    let s = r.ranges.iter().find(|x| x.column == "speed_mps").unwrap();
    assert_eq!(s.source, ReferenceSource::Cohort { n_subjects: 4 });
    assert!((s.mean.unwrap() - 1.15).abs() < 1e-12);
    assert!(
        r.description.contains("8 of 9 analysed healthy legs used"),
        "{}",
        r.description
    );
}

/// A healthy leg whose only finding is about its stride length variability (a short walk's
/// `sv_unchecked`) stays in the reference for its other parameters; its SV, withheld, is not
/// counted in the SV range.
#[test]
fn a_finding_about_sv_alone_keeps_the_leg_in_the_reference() {
    let p = ReportParams::default()
        .min_healthy_subjects(4)
        .check()
        .unwrap();
    let mut rows = Vec::new();
    for (i, v) in [1.0, 1.1, 1.2, 1.3].iter().enumerate() {
        for side in ["left", "right"] {
            let mut r = row(&format!("H{i}"), "healthy", side, *v);
            r.parameters[Parameter::StrideLengthCv] = Some(0.02 + 0.005 * i as f64);
            if i == 3 {
                let w = ldh_core::pipeline::quality::unchecked_warning(0.03, "too few strides");
                r.parameters[Parameter::StrideLengthCv] = None;
                r.withheld.0.insert(
                    ldh_core::domain::Parameter::StrideLengthCv,
                    w.withheld_reason(),
                );
                r.warnings = ldh_core::pipeline::WarningList(vec![w]);
            }
            rows.push(r);
        }
    }
    let r = Reference::from_rows(&rows, &p);
    let range = |c: &str| r.ranges.iter().find(|x| x.column == c).unwrap().clone();
    assert_eq!(
        range("speed_mps").source,
        ReferenceSource::Cohort { n_subjects: 4 }
    );
    assert_eq!(range("stride_length_cv").n_reference, 3);
    assert!(r.description.contains("8 of 8"), "{}", r.description);
    // Any other warning still keeps the leg out.
    rows[7].warnings.0[0]
        .affects
        .push(ldh_core::domain::Parameter::Speed);
    let r = Reference::from_rows(&rows, &p);
    assert!(r.description.contains("7 of 8"), "{}", r.description);
}

/// The summary speaks in clinical units, judges each value against its range in plain words,
/// and a parameter without enough healthy subjects says "no reference (n = …)".
#[test]
fn the_summary_uses_clinical_units_and_plain_flags() {
    let p = ReportParams::default()
        .min_healthy_subjects(4)
        .check()
        .unwrap();
    let mut l = row("S1", "ldh", "left", 0.6);
    l.parameters[Parameter::StepFrequency] = Some(1.5);
    // 2 / (4/3 s) = 1.5 steps/s: 90 steps/min from both legs' stride times.
    l.parameters[Parameter::StrideTime] = Some(4.0 / 3.0);
    l.walk_cadence_steps_per_min = Some(90.0);
    l.parameters[Parameter::StanceRatio] = Some(0.62);
    // Step time within its range on both legs (not the point here).
    l.parameters[Parameter::StepTime] = Some(0.6);
    let mut r = row("S1", "ldh", "right", 1.2);
    r.parameters[Parameter::StepTime] = Some(0.6);
    r.parameters[Parameter::StepFrequency] = Some(1.5);
    r.parameters[Parameter::StrideTime] = Some(4.0 / 3.0);
    r.walk_cadence_steps_per_min = Some(90.0);
    r.parameters[Parameter::StanceRatio] = Some(0.70);
    let s = SubjectReport {
        subject_id: "S1".into(),
        recordings: vec![l, r],
        ..Default::default()
    };
    let reference = Reference::from_rows(&s.recordings, &p);
    let html = subject_html(&s, &reference, &p).unwrap();
    let at = html.find("Clinical summary").unwrap();
    assert!(at < html.find("1. Recordings").unwrap(), "summary first");
    let summary = &html[at..];
    let summary = &summary[..summary.find("</table>").unwrap()];
    let summary = summary.replace(" colspan=\"2\"", "");
    for must in [
        "<b>Cadence</b> (steps/min)",
        "<b>Walking speed</b> (m/s)",
        "<b>Stride length</b> (m)",
        "<b>Stance</b> (% of the gait cycle)",
        "(CV %)",
        "<b>Stance asymmetry</b> (SI %)",
        // 1.5 steps/s = 90 steps/min, below the published 96–126.
        ">90 ▼ <span class=\"flagword\">below normal</span>",
        "96–126",
        // One walking speed per walk: the mean of both legs.
        ">0.90 ▼ <span class=\"flagword\">below normal</span>",
        // Stance against Perry & Burnfield's 57–65 % (issue 49).
        "62.0 <span class=\"flagword\">within normal</span>",
        "70.0 ▲ <span class=\"flagword\">above normal</span>",
        // and its asymmetry is judged too (the legs against each other, issue 50):
        // stance SI = 100·(0.62 − 0.70)/0.66.
        "-12.1 ◆ <span class=\"flagword\">asymmetric</span>",
        "published [",
    ] {
        assert!(summary.contains(must), "no '{must}' in {summary}");
    }
    // Stride length is not in the rows: "not measured", never a number.
    // Said once for both legs when their reason is the same, the reason once under the table.
    assert!(
        summary.contains("not measured (both legs) [1]"),
        "{summary}"
    );
    assert!(html.contains("<div>[1] not measured: not computable from these strides</div>"));
    assert!(
        html.contains("Cadence is below normal: 90 steps/min (normal 96–126 steps/min)."),
        "{html}"
    );
    assert!(html.contains("Walking speed is below normal: 0.90 m/s (normal 1.00–1.60 m/s)."));
    // The stance asymmetry, the only one.
    assert_eq!(summary.matches('◆').count(), 1, "{summary}");
    // No cohort: the shank angles have no reference and say how many healthy subjects there
    // were, and why no published range stands in.
    assert!(html.contains("no reference (n = 0 of 4 needed)"), "{html}");
    assert!(
        !html.contains("No published range stands in for STP"),
        "{html}"
    );
}

/// A left leg's trace at 100 Hz with these signals.
fn trace_leg(acc_g: [Vec<f64>; 3], gyro_dps: [Vec<f64>; 3], pitch_deg: Vec<f64>) -> LegTrace {
    LegTrace {
        side: ldh_core::Side::Left,
        fs_hz: 100.0,
        start_s: 0.0,
        roll_deg: pitch_deg.iter().map(|x| x / 30.0).collect(),
        acc_g,
        gyro_dps,
        pitch_deg,
        hs_s: vec![],
        to_s: vec![],
        stance_s: vec![],
        read_notes: vec![],
        alignment_notes: vec![],
        gaps_s: vec![],
        cycle: None,
    }
}

/// Subject C's page with one leg's trace, against the published ranges.
fn page_with_trace(leg: LegTrace) -> String {
    let p = ReportParams::default().check().unwrap();
    let s = SubjectReport {
        subject_id: "C".into(),
        recordings: vec![row("C", "ldh", "left", 1.0)],
        traces: Some(SubjectTraces {
            schema: trace::TRACE_SCHEMA.into(),
            subject_id: "C".into(),
            trial_id: None,
            legs: vec![leg],
        }),
        ..Default::default()
    };
    subject_html(&s, &Reference::published(&p), &p).unwrap()
}

/// 300 samples of a sine of amplitude `a`.
fn wave(a: f64) -> Vec<f64> {
    (0..300)
        .map(|i| a * (i as f64 / 100.0 * 6.0).sin())
        .collect()
}

/// The three axes of the acceleration panel are three colours (the y axis was once drawn in
/// the left leg's colour, the x axis's too).
#[test]
fn each_axis_of_a_signal_panel_has_its_own_colour() {
    let leg = trace_leg(
        [wave(1.0), wave(0.5), wave(0.8)],
        [wave(100.0), wave(200.0), wave(50.0)],
        wave(30.0),
    );
    let html = page_with_trace(leg);
    let fig3 = &html[html.find("shank: preprocessed signals").unwrap()..];
    let fig3 = &fig3[..fig3.find("</svg>").unwrap()];
    // The legend's keys are the only lines 3 px wide; the first three are the acceleration's.
    let keys: Vec<&str> = fig3
        .match_indices("stroke-width=\"3\"")
        .map(|(i, _)| {
            let before = &fig3[..i];
            let at = before.rfind("stroke=\"").expect("a stroke colour") + 8;
            &fig3[at..at + 7]
        })
        .take(3)
        .collect();
    assert_eq!(keys.len(), 3, "{fig3}");
    assert!(
        keys[0] != keys[1] && keys[1] != keys[2] && keys[0] != keys[2],
        "{keys:?}"
    );
}

/// A trace beyond the physical ranges is drawn clipped, and the captions say so.
#[test]
fn clipped_figures_say_so_in_their_caption() {
    let html = page_with_trace(trace_leg(
        [wave(1.0), wave(0.5), wave(30.0)],
        [wave(100.0), wave(2500.0), wave(50.0)],
        wave(300.0),
    ));
    assert!(
        html.contains("samples beyond ±16 g") && html.contains("samples beyond ±2000 deg/s"),
        "Fig. 3 caption"
    );
    assert!(
        html.contains("samples beyond ±90° (a shank angle's physical range) are drawn at the edge"),
        "Fig. 4 caption"
    );
    // Axes stop at the physical range: no tick label beyond ±90 on the attitude plot.
    let fig4 = &html[html.find("shank: attitude with gait events").unwrap()..];
    let fig4 = &fig4[..fig4.find("</figure>").unwrap()];
    assert!(!fig4.contains(">200<") && !fig4.contains(">-200<"));
}
