//! A person at two visits (issue 38 item 3): the subject page lists each parameter's change from
//! the first visit and marks it only when it exceeds the MDC95 of the reliability table given
//! with `--reliability`; without one, none is marked.

mod common;
use common::{ldh, ldh_ok, text};

/// A file of the embedded demo cohort, written under `dir` (once per test).
fn fixture(dir: &std::path::Path, name: &str) -> String {
    if !dir.join("manifest.csv").exists() {
        ldh_core::demo::write_to(dir).unwrap();
    }
    dir.join(name).display().to_string()
}

/// The rows of the visits table of `html`, by parameter code, with their marks.
fn marks(html: &str, code: &str) -> usize {
    let at = html.find("id=\"visits\"").expect("a visits section");
    let section = &html[at..];
    let section = &section[..section.find("</table>").unwrap()];
    let row = &section[section.find(&format!("<td>{code} — ")).unwrap()..];
    row[..row.find("</tr>").unwrap()]
        .matches(['▲', '▼'])
        .count()
}

#[test]
fn a_two_visit_report_marks_only_changes_beyond_the_mdc95() {
    let d = tempfile::tempdir().unwrap();
    let demo = d.path().join("demo");
    // Person P: visit "pre" walks like H01, visit "post" like L01 (slower, shorter strides).
    let manifest = d.path().join("manifest.csv");
    std::fs::write(
        &manifest,
        format!(
            "subject_id,trial_id,visit,group,affected_side,left,right,sensor_height_m\n\
             P,1,pre,ldh,left,{},{},0.08\nP,2,post,ldh,left,{},{},0.08\n",
            fixture(&demo, "H01/left.csv"),
            fixture(&demo, "H01/right.csv"),
            fixture(&demo, "L01/left.csv"),
            fixture(&demo, "L01/right.csv"),
        ),
    )
    .unwrap();
    // Stride time: an MDC95 of 1 ms (any change beyond it); speed: 5 m/s (no change beyond).
    let rel = d.path().join("reliability.csv");
    let header = "parameter,code,unit,n_subjects,k_trials,icc_2_1,icc_2_1_ci_low,icc_2_1_ci_high,icc_3_1,icc_3_1_ci_low,icc_3_1_ci_high,sd_all,sem,sem_from_mse,mdc95,within_subject_cv,between_subject_var,within_subject_var,withheld";
    std::fs::write(
        &rel,
        format!(
            "{header}\nstride_time_s,ST,s,10,3,0.9,0.8,0.95,0.9,0.8,0.95,0.1,0.00036,0.00036,0.001,0.01,0.01,0.0001,\n\
             speed_mps,SS,m/s,10,3,0.9,0.8,0.95,0.9,0.8,0.95,2,1.8,1.8,5,0.01,1,0.1,\n"
        ),
    )
    .unwrap();
    let res = d.path().join("res");
    ldh_ok(&[
        "analyze",
        manifest.to_str().unwrap(),
        "-o",
        res.to_str().unwrap(),
        "--report",
        "--reliability",
        rel.to_str().unwrap(),
        "-q",
    ]);
    let html = std::fs::read_to_string(res.join("reports/subjects/P.html")).unwrap();
    assert_eq!(
        marks(&html, "ST"),
        1,
        "stride time changed beyond its 1 ms MDC95"
    );
    assert_eq!(
        marks(&html, "SS"),
        0,
        "a speed change inside a 5 m/s MDC95 is not marked"
    );
    assert_eq!(
        marks(&html, "SL"),
        0,
        "no MDC95 for stride length: not judged"
    );
    assert!(html.contains("From pre to post, changed by more than the measurement's own noise (MDC95, reliability.csv: 10 people × 3 trials): stride time "));
    let said = &html[html.find("From pre to post").unwrap()..];
    let said = &said[..said.find("</p>").unwrap()];
    assert!(!said.contains("walking speed"), "{said}");
    assert!(
        said.contains("every other change lies within the noise"),
        "{said}"
    );

    // Without a table: the changes are listed, none marked, and the page says why.
    let rep = d.path().join("rep");
    ldh_ok(&[
        "report",
        res.to_str().unwrap(),
        "-o",
        rep.to_str().unwrap(),
        "-q",
    ]);
    let html = std::fs::read_to_string(rep.join("subjects/P.html")).unwrap();
    for code in ["ST", "SS", "SL"] {
        assert_eq!(marks(&html, code), 0, "{code}");
    }
    assert!(html.contains("none is judged: without a reliability table"));

    // A table that does not read stops the report with its file and line.
    std::fs::write(
        &rel,
        format!("{header}\nstride_time_s,ST,s,10,3,,,,,,,,,,-1,,,,\n"),
    )
    .unwrap();
    let o = ldh(&[
        "report",
        res.to_str().unwrap(),
        "-o",
        d.path().join("rep2").to_str().unwrap(),
        "--reliability",
        rel.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("reliability.csv:2"), "{}", text(&o));
}
