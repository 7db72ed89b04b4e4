//! `ldh stats` end to end: Table 3 and Table 4 layouts, figures, known simulated effects.

mod common;
use common::*;

#[test]
fn stats_on_a_simulated_cohort_finds_the_simulated_effects() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("cohort");
    simulate_cohort(&c, 15, 20, 30, 11);
    let out = d.path().join("stats");
    let o = ldh(&[
        "stats",
        c.to_str().unwrap(),
        "--compare",
        "acc",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let md = std::fs::read_to_string(out.join("stats.md")).unwrap();
    assert!(md.contains("| Feature | unit | LDHH | LDHE | H | HE (paired) | HE (indep.) | H-H | E-H | LR | ANOVA | Kruskal |"));
    assert!(md.contains("| Model | OFF0 (LDHH) | OFF1 (LDHE) |"));
    let rows = json(&out.join("table3.json"));
    let row = |model: &str, code: &str| {
        rows.as_array()
            .unwrap()
            .iter()
            .find(|r| r["model"] == model && r["code"] == code)
            .unwrap()
            .clone()
    };
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();
    // 14 parameters (13 and double support, issue 49) for each of the two models.
    assert_eq!(rows.as_array().unwrap().len(), 28);
    // Longer stance on the affected side, paired test significant.
    let stp = row("fusion", "STP");
    assert!(f(&stp, "ldhe_mean") > f(&stp, "ldhh_mean"));
    assert!(f(&stp, "he_paired_p") < 0.01 && f(&stp, "he_paired_p_holm") < 0.05);
    assert!(["paired t", "wilcoxon"].contains(&stp["he_paired_test"].as_str().unwrap()));
    // Slower than healthy.
    let ss = row("fusion", "SS");
    assert!(f(&ss, "ldhe_mean") < f(&ss, "h_mean") && f(&ss, "eh_p") < 0.01);
    assert!(f(&ss, "ldhh_mean") < f(&ss, "h_mean") && f(&ss, "hh_p") < 0.01);
    // Less knee flexion (max shank inclination) on the affected side; more circumduction.
    let wqk = row("fusion", "WQK");
    assert!(f(&wqk, "ldhe_mean") < f(&wqk, "ldhh_mean") && f(&wqk, "he_paired_p") < 0.01);
    let bdk = row("fusion", "BDK");
    assert!(f(&bdk, "ldhe_mean") > f(&bdk, "ldhh_mean") && f(&bdk, "he_paired_p") < 0.01);
    // Healthy left vs right: no stance difference.
    assert!(f(&stp, "lr_p") > 0.01);
    // Holm never lowers a p-value.
    for r in rows.as_array().unwrap() {
        if let (Some(p), Some(h)) = (r["eh_p"].as_f64(), r["eh_p_holm"].as_f64()) {
            assert!(h >= p);
        }
    }
    let t4 = json(&out.join("table4.json"));
    assert_eq!(t4[0]["model"], "fusion");
    assert_eq!(t4[1]["model"], "acc");
    assert!(t4[0]["off1"].as_f64().unwrap() > t4[0]["off0"].as_f64().unwrap());
    for f in [
        "radar_fusion.svg",
        "radar_acc.svg",
        "box_STP.svg",
        "box_SS.svg",
        "table3.csv",
    ] {
        let t = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(t.len() > 200, "{f}");
    }
    let b = std::fs::read_to_string(out.join("box_SS.svg")).unwrap();
    assert!(b.contains("SS (m/s)") && b.contains("LDHE"));
}

#[test]
fn stats_refuses_cohorts_it_cannot_test_and_names_what_is_missing() {
    let d = tempfile::tempdir().unwrap();
    // The demo without its third LDH subject: two in that group.
    ldh_core::demo::write_to(d.path()).unwrap();
    let manifest = d.path().join("manifest.csv");
    let two: String = ldh_core::demo::file("manifest.csv")
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("L03,"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&manifest, two).unwrap();
    let o = ldh(&[
        "stats",
        manifest.to_str().unwrap(),
        "--out",
        d.path().join("s").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("ldh group has 2 usable subject(s) (both legs analysed"),
        "{}",
        text(&o)
    );
    // Without a manifest there are no groups.
    std::fs::remove_file(d.path().join("manifest.csv")).unwrap();
    let o = ldh(&[
        "stats",
        d.path().to_str().unwrap(),
        "--out",
        d.path().join("s2").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("no group (give a manifest with group and affected_side)"),
        "{}",
        text(&o)
    );
    // A subject with one leg is named.
    let c = d.path().join("c");
    assert!(ldh(&[
        "simulate",
        "--out",
        c.to_str().unwrap(),
        "--healthy",
        "3",
        "--ldh",
        "3",
        "--seconds",
        "20",
        "--seed",
        "4"
    ])
    .status
    .success());
    std::fs::remove_file(c.join("L02/right.csv")).unwrap();
    let o = ldh(&[
        "stats",
        c.to_str().unwrap(),
        "--out",
        d.path().join("s3").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("L02: right failed") && text(&o).contains("at least 3"),
        "{}",
        text(&o)
    );
    let o = ldh(&["stats", c.to_str().unwrap(), "--compare", "gyro"]);
    assert_eq!(o.status.code(), Some(2));
}

/// Issue 38 item 2's done-when, end to end: `ldh simulate --trials 3`, `ldh analyze`, then
/// `ldh stats --reliability` writes reliability.csv/.json/.md with one row per parameter
/// (13), readable by `ReliabilityTable::read`, and prints the Markdown table.
#[test]
fn stats_reliability_on_a_simulated_retest_cohort_writes_the_table() {
    let d = tempfile::tempdir().unwrap();
    let (c, a, s) = (d.path().join("c"), d.path().join("a"), d.path().join("s"));
    let p = |x: &std::path::Path| x.to_str().unwrap().to_string();
    ldh_ok(&[
        "simulate",
        "--healthy",
        "4",
        "--ldh",
        "0",
        "--trials",
        "3",
        "--no-turn",
        "--seconds",
        "30",
        "--seed",
        "5",
        "--out",
        &p(&c),
    ]);
    let manifest = std::fs::read_to_string(c.join("manifest.csv")).unwrap();
    assert!(
        manifest.starts_with("subject_id,trial_id,group,affected_side,left,right,sensor_height_m,clocks\nH01,T1,healthy,none,H01/T1/left.csv,H01/T1/right.csv,"),
        "{manifest}"
    );
    assert_eq!(manifest.lines().count(), 1 + 4 * 3);
    ldh_ok(&["analyze", &p(&c), "--out", &p(&a)]);
    let o = ldh(&[
        "stats",
        "--reliability",
        "--results",
        &p(&a),
        "--out",
        &p(&s),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("| stride time (ST, s) | 4 × 3 | "), "{out}");
    let t = ldh_core::cohort::ReliabilityTable::read(&s.join("reliability.csv")).unwrap();
    assert_eq!(t.rows.len(), ldh_core::output::Parameter::ALL.len());
    let st = t.row(ldh_core::output::Parameter::StrideTime).unwrap();
    assert_eq!(
        (st.n_subjects, st.k_trials, st.withheld.as_str()),
        (4, 3, "")
    );
    // 3 % day-to-day SD of a ≈ 1.05 s stride: MDC95 ≈ 1.96·√2·0.03·1.05 ≈ 0.09 s.
    let mdc = t.mdc95(ldh_core::output::Parameter::StrideTime).unwrap();
    assert!((0.03..0.3).contains(&mdc), "{mdc}");
    assert_eq!(
        json(&s.join("reliability.json"))["rows"]
            .as_array()
            .unwrap()
            .len(),
        14
    );
    assert!(std::fs::read_to_string(s.join("reliability.md"))
        .unwrap()
        .contains("MDC95"));
    assert!(
        !s.join("stats.md").exists(),
        "--reliability writes only its own files"
    );
}

#[test]
fn stats_reliability_without_repeated_trials_says_what_is_needed() {
    let d = tempfile::tempdir().unwrap();
    let o = ldh(&[
        "stats",
        "--reliability",
        "--out",
        d.path().join("s").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let t = text(&o);
    assert!(
        t.contains("no person has two or more trials") && t.contains("trial_id"),
        "{t}"
    );
}
