//! `ldh agree` end to end: an analysed simulated cohort against its exported truth, with the
//! reference clock shifted by 0.75 s, and a bad reference refused before anything is written.

mod common;
use common::html::check_page;
use common::{json, ldh, ldh_ok, simulate_cohort, text};

use std::path::{Path, PathBuf};

use ldh_sim::evaluate::{truth_reference, TruthScope};

/// A simulated cohort (`healthy` + `ldh` subjects of `seconds` s, `seed`) written to `dir/sim`
/// and analysed into `dir/res` with `ldh analyze`: the results folder and every subject's truth.
fn analysed(
    dir: &Path,
    healthy: u32,
    ldh_n: u32,
    seconds: u32,
    seed: u64,
) -> (PathBuf, Vec<ldh_sim::SubjectTruth>) {
    let (sim, res) = (dir.join("sim"), dir.join("res"));
    simulate_cohort(&sim, healthy, ldh_n, seconds, seed);
    ldh_ok(&[
        "analyze",
        sim.to_str().unwrap(),
        "-o",
        res.to_str().unwrap(),
        "-q",
    ]);
    let mut truths = Vec::new();
    for e in std::fs::read_dir(&sim).unwrap() {
        let t = e.unwrap().path().join("truth.json");
        if t.is_file() {
            truths.push(ldh_sim::read_truth(&t).unwrap());
        }
    }
    truths.sort_by(|a, b| a.subject_id.cmp(&b.subject_id));
    (res, truths)
}

#[test]
fn agree_reads_an_analyze_folder_estimates_the_offset_and_refuses_a_bad_reference() {
    let d = tempfile::tempdir().unwrap();
    let (res, truths) = analysed(d.path(), 2, 2, 25, 38);
    let (ev, st) = truth_reference(&truths, TruthScope::All, 0.75);
    let (evp, stp) = (d.path().join("ev.csv"), d.path().join("st.csv"));
    std::fs::write(&evp, ev).unwrap();
    std::fs::write(&stp, st).unwrap();
    let out = d.path().join("agree");
    let o = ldh_ok(&[
        "agree",
        res.to_str().unwrap(),
        "--reference",
        evp.to_str().unwrap(),
        "--reference",
        stp.to_str().unwrap(),
        "--offset-s",
        "estimate",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(text(&o).contains("| HS | both |"), "{}", text(&o));
    let j = json(&out.join("agreement.json"));
    for o in j["offsets"].as_array().unwrap() {
        let off = o["offset_s"].as_f64().unwrap();
        assert!((off + 0.75).abs() <= 0.01, "{o}");
        assert_eq!(o["source"], "estimated");
    }
    let hs = j["events"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["event"] == "HS" && e["side"] == "both")
        .unwrap();
    assert!(hs["summary"]["recall"].as_f64().unwrap() > 0.9, "{hs}");
    let csv = std::fs::read_to_string(out.join("agreement.csv")).unwrap();
    assert!(
        csv.lines()
            .any(|l| l.starts_with("stride,stride_time_s,both,")),
        "{csv}"
    );
    assert!(std::fs::read_to_string(out.join("agreement.md"))
        .unwrap()
        .contains("stride_length_m"));
    // The page: well-formed and self-contained, figures numbered, axis labels with units,
    // text ≥ 8 pt in print; two timing histograms and a Bland–Altman plot per computed
    // parameter (per stride and per recording).
    let computed = j["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| !p["agreement"].is_null())
        .count();
    assert!(computed >= 6, "{computed}");
    assert_eq!(check_page(&out.join("agreement.html")), 2 + computed);
    let page = std::fs::read_to_string(out.join("agreement.html")).unwrap();
    assert!(
        page.contains("Bland–Altman plot of the stride time"),
        "{page}"
    );
    assert!(text(&o).contains("agreement.html"), "{}", text(&o));

    let bad = d.path().join("bad.csv");
    std::fs::write(
        &bad,
        "subject_id,side,event,time_s\nH01,left,HS,2\nX9,left,HS,3\n",
    )
    .unwrap();
    let out2 = d.path().join("agree2");
    let o = ldh(&[
        "agree",
        res.to_str().unwrap(),
        "--reference",
        bad.to_str().unwrap(),
        "-o",
        out2.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("bad.csv:3:1") && text(&o).contains("X9"),
        "{}",
        text(&o)
    );
    assert!(!out2.exists(), "nothing written");
}

/// A GAITRite-like per-footfall export read through its column map (the shipped example, its
/// subject renamed to one of the analysed cohort): its 8 heel strikes, 7 toe offs and 6 strides
/// are the reference; a foot the map does not list is refused naming the export's line and
/// column, before anything is written.
#[test]
fn agree_reads_a_walkway_export_through_its_column_map() {
    let d = tempfile::tempdir().unwrap();
    let (res, _) = analysed(d.path(), 1, 1, 20, 7);
    let fixtures =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data-fixtures/agreement");
    let export = std::fs::read_to_string(fixtures.join("gaitrite-footfalls.csv"))
        .unwrap()
        .replace("S01,", "H01,");
    let exp = d.path().join("export.csv");
    std::fs::write(&exp, &export).unwrap();
    let map = fixtures.join("gaitrite-footfalls.toml");
    let out = d.path().join("agree");
    ldh_ok(&[
        "agree",
        res.to_str().unwrap(),
        "--walkway",
        exp.to_str().unwrap(),
        "--walkway-map",
        map.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let j = json(&out.join("agreement.json"));
    let n_ref = |ev: &str| {
        j["events"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["event"] == ev && e["side"] == "both")
            .unwrap()["summary"]["n_reference"]
            .as_u64()
            .unwrap()
    };
    assert_eq!((n_ref("HS"), n_ref("TO")), (8, 7));
    assert_eq!(j["reference_strides"], 6);
    assert!(out.join("agreement.html").is_file());

    let bad = d.path().join("bad.csv");
    std::fs::write(&bad, export.replacen("H01,L,", "H01,X,", 1)).unwrap();
    let out2 = d.path().join("agree2");
    let o = ldh(&[
        "agree",
        res.to_str().unwrap(),
        "--walkway",
        bad.to_str().unwrap(),
        "--walkway-map",
        map.to_str().unwrap(),
        "-o",
        out2.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("bad.csv:4:2"), "{}", text(&o));
    assert!(!out2.exists());
}

/// `ldh agree --write-params` (issue 38 item 4): a lab whose reference times heel strikes 40 ms
/// later and toe offs 25 ms earlier than the simulator's truth. The calibration it writes,
/// given to `ldh analyze --params`, takes the mean error of both event kinds to within 2 ms
/// of zero, and every report page says against what the events were calibrated.
#[test]
fn a_calibration_written_by_agree_removes_the_bias_and_the_report_says_so() {
    let d = tempfile::tempdir().unwrap();
    let (res, truths) = analysed(d.path(), 2, 2, 25, 38);
    let (ev, _) = truth_reference(&truths, TruthScope::All, 0.0);
    // The lab's reference: heel strikes 40 ms later, toe offs 25 ms earlier than the truth.
    let mut lines = ev.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let (ce, ct) = (col("event"), col("time_s"));
    let mut lab = header.join(",") + "\n";
    for l in lines {
        let mut f: Vec<String> = l.split(',').map(String::from).collect();
        let t: f64 = f[ct].parse().unwrap();
        let shift = if f[ce] == "HS" { 0.040 } else { -0.025 };
        f[ct] = format!("{:.4}", t + shift);
        lab += &(f.join(",") + "\n");
    }
    let evp = d.path().join("plates.csv");
    std::fs::write(&evp, lab).unwrap();
    let bias = |out: &std::path::Path, event: &str| {
        json(&out.join("agreement.json"))["events"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["event"] == event && e["side"] == "both")
            .unwrap()["summary"]["bias_s"]
            .as_f64()
            .unwrap()
    };
    let (a1, cal) = (d.path().join("a1"), d.path().join("calibration.toml"));
    let o = ldh_ok(&[
        "agree",
        res.to_str().unwrap(),
        "--reference",
        evp.to_str().unwrap(),
        "-o",
        a1.to_str().unwrap(),
        "--write-params",
        cal.to_str().unwrap(),
        "--reference-system",
        "force plates",
    ]);
    assert!(text(&o).contains("calibration.toml"), "{}", text(&o));
    let (hs1, to1) = (bias(&a1, "HS"), bias(&a1, "TO"));
    let toml = std::fs::read_to_string(&cal).unwrap();
    assert!(toml.contains("[events.calibration]"), "{toml}");
    assert!(
        toml.contains("against = \"force plates (plates.csv; "),
        "{toml}"
    );

    let res2 = d.path().join("res2");
    ldh_ok(&[
        "analyze",
        d.path().join("sim").to_str().unwrap(),
        "-o",
        res2.to_str().unwrap(),
        "--params",
        cal.to_str().unwrap(),
        "--report",
        "-q",
    ]);
    let a2 = d.path().join("a2");
    ldh_ok(&[
        "agree",
        res2.to_str().unwrap(),
        "--reference",
        evp.to_str().unwrap(),
        "-o",
        a2.to_str().unwrap(),
        "-q",
    ]);
    let (hs2, to2) = (bias(&a2, "HS"), bias(&a2, "TO"));
    eprintln!("bias before: HS {hs1:.4} s, TO {to1:.4} s; after: HS {hs2:.5} s, TO {to2:.5} s");
    assert!(hs1.abs() > 0.02 && hs2.abs() < 0.002, "HS {hs1} → {hs2}");
    assert!(to2.abs() < 0.002, "TO {to1} → {to2}");
    for page in ["reports/index.html", "reports/subjects/H01.html"] {
        let html = std::fs::read_to_string(res2.join(page)).unwrap();
        assert!(
            html.contains("Gait events calibrated against force plates (plates.csv; "),
            "{page}"
        );
    }
    // An uncalibrated run's pages say nothing of it.
    ldh_ok(&[
        "report",
        res.to_str().unwrap(),
        "-o",
        d.path().join("rep").to_str().unwrap(),
        "-q",
    ]);
    let html = std::fs::read_to_string(d.path().join("rep/index.html")).unwrap();
    assert!(!html.contains("calibrated against"));
}
