//! `ldh analyze` and `ldh evaluate` end to end.

mod common;
use common::*;

#[test]
fn analyze_without_input_runs_the_embedded_demo() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    let o = ldh(&["analyze", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("embedded demo cohort (13 people)"));
    let strides = std::fs::read_to_string(out.join("strides.csv")).unwrap();
    assert!(strides.starts_with(
        "subject_id,side,model,stride_index,bout,hs_time_s,to_time_s,next_hs_time_s,stride_time_s,stance_ratio,double_support_ratio,stride_length_m,speed_mps,wqk_deg,pbi_deg,bdk_deg,heading_change_deg,valid,reason,reason_codes,trial_id\n"
    ));
    let rec = json(&out.join("recordings.json"));
    let rows = rec.as_array().unwrap();
    assert_eq!(rows.len(), 26);
    for r in rows {
        assert_eq!(r["status"], "ok", "{r}");
        let st = r["stride_time_s"].as_f64().unwrap();
        assert!((0.9..1.4).contains(&st), "{r}");
        assert!(
            (0.55..0.70).contains(&r["stance_ratio"].as_f64().unwrap()),
            "{r}"
        );
        assert!(
            (0.8..1.7).contains(&r["stride_length_m"].as_f64().unwrap()),
            "{r}"
        );
        assert!(
            (35.0..60.0).contains(&r["wqk_deg"].as_f64().unwrap()),
            "{r}"
        );
        assert!(r["sta_per_s"].as_f64().unwrap() > 0.0, "{r}");
        assert!(r["strides_valid"].as_u64().unwrap() >= 10, "{r}");
        let role = r["side_role"].as_str().unwrap();
        assert!(["healthy", "affected", "unaffected"].contains(&role));
    }
    // The affected side of each LDH subject has the longer stance (simulated effect).
    for id in ["L01", "L02", "L03"] {
        let get = |role: &str| {
            rows.iter()
                .find(|r| r["subject_id"] == id && r["side_role"] == role)
                .unwrap()["stance_ratio"]
                .as_f64()
                .unwrap()
        };
        assert!(get("affected") > get("unaffected"), "{id}");
    }
    let strides = json(&out.join("strides.json"));
    let invalid: Vec<&serde_json::Value> = strides
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["valid"] == false)
        .collect();
    assert!(invalid
        .iter()
        .all(|s| !s["reason"].as_str().unwrap().is_empty()));
    assert!(invalid
        .iter()
        .any(|s| s["reason"].as_str().unwrap().contains("turning")));
    assert!(invalid.iter().any(|s| s["reason"]
        .as_str()
        .unwrap()
        .contains("first stride of a walking bout")));
}

/// Issue 51: the README's first command (`ldh analyze --report`, the embedded demo) shows the
/// product working: no warning a technician would act on (notes, what the pipeline did, may
/// remain), nothing withheld, every parameter measured and judged against the cohort's own
/// healthy reference on every subject page, and group statistics on the cohort page.
#[test]
fn the_demo_shows_every_parameter_measured_and_judged() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("ldh-out");
    let o = ldh(&["analyze", "--report", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.contains("warning") && !stderr.contains("error"),
        "{stderr}"
    );
    let rec = json(&out.join("recordings.json"));
    for r in rec.as_array().unwrap() {
        let who = format!("{} {}", r["subject_id"], r["side"]);
        let warnings = r["warnings"].as_array().unwrap();
        assert!(
            warnings.iter().all(|w| w["severity"] == "note"),
            "{who}: {warnings:?}"
        );
        assert!(r["withheld"].as_object().unwrap().is_empty(), "{who}");
        assert!(r["strides_valid"].as_u64().unwrap() >= 10, "{who}");
    }
    let codes: Vec<&str> = ldh_core::cohort::PARAMETERS
        .iter()
        .map(|p| p.code())
        .collect();
    assert!(codes.len() >= 12 && codes.contains(&"SWP"), "{codes:?}");
    let reports = out.join("reports");
    for id in ldh_core::demo::SUBJECTS {
        let page = std::fs::read_to_string(reports.join(format!("subjects/{id}.html"))).unwrap();
        // The parameter table of section 2: one row per parameter, its code first.
        // Swing is the complement of stance: shown and judged in the stance row ("with SWP").
        for code in codes.iter().map(|c| if *c == "SWP" { "STP" } else { *c }) {
            let start = format!("<tr><td>{code} — ");
            let at = page
                .find(&start)
                .unwrap_or_else(|| panic!("{id}: no row for {code}"));
            let row = &page[at..at + page[at..].find("</tr>").unwrap()];
            for missing in ["not measured", "no reference", "not judged", "withheld"] {
                assert!(!row.contains(missing), "{id} {code}: {row}");
            }
            assert!(
                row.contains("(cohort healthy, n = 10)"),
                "{id} {code}: {row}"
            );
            let judged = ["within normal", "above normal", "below normal"];
            let sides = judged.iter().map(|j| row.matches(j).count()).sum::<usize>();
            let one_value_per_walk = ["SF", "SS", "ST", "DS"].contains(&code);
            assert_eq!(
                sides,
                if one_value_per_walk { 1 } else { 2 },
                "{id} {code}: {row}"
            );
        }
        assert!(page.contains("with SWP: "), "{id}");
        assert!(!page.contains("Record a longer walk"), "{id}");
    }
    let cohort = std::fs::read_to_string(reports.join("index.html")).unwrap();
    assert!(!cohort.contains("No group statistics"));
    let stats = &cohort[cohort
        .find("1. Group statistics")
        .expect("group statistics")..];
    assert!(
        stats.contains("Group ldh: n = 3 people, group healthy: n = 10 people"),
        "{}",
        &stats[..400]
    );
    for code in &codes {
        assert!(stats.contains(&format!("<tr><td>{code}</td>")), "{code}");
    }
}

#[test]
fn a_bad_recording_is_reported_and_the_rest_is_written() {
    let d = tempfile::tempdir().unwrap();
    ldh_core::demo::write_to(d.path()).unwrap();
    std::fs::write(d.path().join("H02/right.csv"), "time_s,acc_x\n0,1\n").unwrap();
    std::fs::remove_file(d.path().join("L01/left.csv")).unwrap();
    let out = d.path().join("out");
    let o = ldh(&[
        "analyze",
        d.path().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let t = text(&o);
    assert!(
        t.contains("26 recordings (13 people, model fusion): 24 ok, 2 failed"),
        "{t}"
    );
    assert!(
        t.contains("H02 right") && t.contains("H02/right.csv"),
        "{t}"
    );
    assert!(
        t.contains("L01 left") && t.contains("L01/left.csv: cannot read"),
        "{t}"
    );
    let rec = json(&out.join("recordings.json"));
    let errors: Vec<&serde_json::Value> = rec
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["status"] == "error")
        .collect();
    assert_eq!(errors.len(), 2);
    // The other side of a subject with a failed leg is still analysed (without step time).
    let h02l = rec
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["subject_id"] == "H02" && r["side"] == "left")
        .unwrap();
    assert_eq!(h02l["status"], "ok");
    assert!(h02l["step_time_s"].is_null());
}

#[test]
fn inputs_as_pair_subject_folder_and_manifest() {
    let d = tempfile::tempdir().unwrap();
    ldh_core::demo::write_to(d.path()).unwrap();
    let out = d.path().join("o1");
    let l = d.path().join("L02/left.csv");
    let r = d.path().join("L02/right.csv");
    let o = ldh(&[
        "analyze",
        l.to_str().unwrap(),
        r.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-sta",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let rec = json(&out.join("recordings.json"));
    assert_eq!(rec[0]["subject_id"], "L02");
    assert!(rec[0]["sta_per_s"].is_null());
    let out2 = d.path().join("o2");
    let o = ldh(&[
        "analyze",
        d.path().join("L02").to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
        "--no-sta",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(
        std::fs::read(out.join("strides.csv")).unwrap(),
        std::fs::read(out2.join("strides.csv")).unwrap()
    );
    let o = ldh(&[
        "analyze",
        d.path().join("manifest.csv").to_str().unwrap(),
        "--out",
        d.path().join("o3").to_str().unwrap(),
        "--model",
        "acc",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("model acc"));
    let o = ldh(&["analyze", "--model", "kalman"]);
    assert_eq!(o.status.code(), Some(2));
    // clap refuses it (ValueEnum), listing the choices.
    assert!(
        text(&o).contains("possible values: fusion, acc"),
        "{}",
        text(&o)
    );
}

/// The outputs do not depend on the thread count, nor on `--timings` (issue 17), which prints
/// the stage table on stderr and adds "timings" to the JSON summary.
#[test]
fn results_are_byte_identical_whatever_the_jobs() {
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("a"), d.path().join("b"));
    assert!(
        ldh(&["analyze", "--out", a.to_str().unwrap(), "--jobs", "1"])
            .status
            .success()
    );
    let o = ldh(&[
        "analyze",
        "--out",
        b.to_str().unwrap(),
        "--jobs",
        "2",
        "--timings",
        "--json",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    for stage in [
        "read",
        "preprocess",
        "align",
        "attitude",
        "events",
        "strides",
        "sta",
        "write",
    ] {
        assert!(
            err.lines().any(|l| l.starts_with(stage)),
            "{stage} in {err}"
        );
    }
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let t = &j["timings"];
    assert_eq!(t["recordings"], 26, "{t}");
    assert!(t["sta_s"].as_f64().unwrap() > 0.0, "{t}");
    assert!(t["attitude_s"].as_f64().unwrap() > 0.0, "{t}");
    let total = t["total_s"].as_f64().unwrap();
    assert!(
        total > 0.0 && total <= 2.0 * t["wall_s"].as_f64().unwrap() + 1e-3,
        "{t}"
    );
    for f in [
        "strides.csv",
        "recordings.csv",
        "strides.json",
        "recordings.json",
        "events.csv",
        "params.json",
    ] {
        assert_eq!(
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
            "{f}"
        );
    }
}

/// Accuracy against the simulator's truth on a fixed cohort (seed 300, not used for tuning):
/// bounds tighter than trivial, looser than the measured values in docs/accuracy.md.
#[test]
fn evaluate_reports_accuracy_within_the_issue_targets() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("cohort");
    simulate_cohort(&c, 3, 3, 30, 300);
    let j = d.path().join("acc.json");
    let per_stride = d.path().join("strides.csv");
    let o = ldh(&[
        "evaluate",
        "--truth",
        c.to_str().unwrap(),
        "--json",
        j.to_str().unwrap(),
        "--strides-csv",
        per_stride.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("| HS MAE / P95 (ms) |"));
    let acc = json(&j);
    let f = &acc[0];
    assert_eq!(f["model"], "fusion");
    let v = |k: &str| f[k].as_f64().unwrap();
    assert!(f["strides"].as_u64().unwrap() >= 150);
    assert_eq!(f["missed_events"], 0);
    assert!(v("hs_mae_ms") < 8.0 && v("hs_p95_ms") < 20.0, "{f}");
    assert!(v("to_mae_ms") < 10.0 && v("to_p95_ms") < 25.0, "{f}");
    assert!(v("stride_time_mae_ms") < 3.0, "{f}");
    assert!(v("stance_ratio_mae") < 0.01, "{f}");
    assert!(v("stride_length_mae_pct") < 2.0, "{f}");
    assert!(v("pitch_rmse_deg") < 1.5 && v("roll_rmse_deg") < 1.0, "{f}");
    // No leg's angles withheld on family A: the all-legs figures are the same.
    assert_eq!(f["angles_withheld"], 0, "{f}");
    assert_eq!(v("pitch_rmse_all_deg"), v("pitch_rmse_deg"));
    assert!(text(&o).contains("| legs with angles withheld (of recordings) | 0 / 12 |"));
    // The ACC-only baseline is worse where only the attitude differs.
    let a = &acc[1];
    assert_eq!(a["model"], "acc");
    assert!(a["pitch_rmse_deg"].as_f64().unwrap() > 5.0 * v("pitch_rmse_deg"));
    // Its stride lengths (≈ 97 % short) are withheld by the plausibility checks, not reported.
    assert!(a["stride_length_mae_pct"].as_f64().is_none_or(|x| x > 10.0));
    assert!(a["stride_length_withheld"].as_u64().unwrap() * 2 > a["strides"].as_u64().unwrap());
    assert_eq!(f["stride_length_over_15pct"], 0);
    per_stride_scores_agree_with_the_table(&per_stride, f);
}

/// `--strides-csv`: one row per steady true stride and model, and the fusion rows give the
/// table's stride count, withheld lengths and stride-length MAE.
fn per_stride_scores_agree_with_the_table(path: &std::path::Path, f: &serde_json::Value) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().clone();
    let col = |name: &str| h.iter().position(|c| c == name).unwrap();
    let (model, err, valid) = (col("model"), col("stride_length_error_pct"), col("valid"));
    let rows: Vec<csv::StringRecord> = r.records().map(|x| x.unwrap()).collect();
    let fusion: Vec<_> = rows.iter().filter(|x| &x[model] == "fusion").collect();
    assert_eq!(fusion.len() as u64, f["strides"].as_u64().unwrap());
    assert_eq!(rows.len(), 2 * fusion.len(), "fusion and acc rows");
    let errs: Vec<f64> = fusion
        .iter()
        .filter(|x| !x[err].is_empty())
        .map(|x| x[err].parse::<f64>().unwrap())
        .collect();
    assert_eq!(
        (fusion.len() - errs.len()) as u64,
        f["stride_length_withheld"].as_u64().unwrap()
    );
    let mae = errs.iter().map(|e| e.abs()).sum::<f64>() / errs.len() as f64;
    let want = f["stride_length_mae_pct"].as_f64().unwrap();
    assert!((mae - want).abs() < 1e-9 * want.max(1.0), "{mae} vs {want}");
    // a reported length belongs to a valid stride
    assert!(fusion
        .iter()
        .filter(|x| !x[err].is_empty())
        .all(|x| &x[valid] == "true"));
}

/// Issue 20, `sensor_height_unknown`: a family-b walker (its shank turns over the ankle at
/// mid-stance, so its stride length depends on the sensor height) analysed from a manifest
/// without the `sensor_height_m` column gets, on every leg that reports a length with the
/// height, the warning and empty stride-length, speed and SV cells with the reason, per leg and
/// per stride; the same walker with its height (the column, or `--sensor-height-m` on the
/// manifest without it) gets no such finding and its lengths, and everything not derived from
/// the length is the same either way.
#[test]
fn a_recording_without_a_sensor_height_withholds_a_length_that_depends_on_it() {
    let d = tempfile::tempdir().unwrap();
    let sim = d.path().join("sim");
    ldh_ok(&[
        "simulate",
        "--family",
        "b",
        "--out",
        sim.to_str().unwrap(),
        "--healthy",
        "1",
        "--ldh",
        "0",
        "--seed",
        "2026",
    ]);
    // The same recordings, listed by a manifest without the height column.
    let manifest = std::fs::read_to_string(sim.join("manifest.csv")).unwrap();
    let rows: Vec<Vec<&str>> = manifest.lines().map(|l| l.split(',').collect()).collect();
    let col = rows[0]
        .iter()
        .position(|c| *c == "sensor_height_m")
        .unwrap();
    let height = rows[1][col].to_string();
    let without: String = rows
        .iter()
        .map(|r| {
            let mut r = r.clone();
            r.remove(col);
            r.join(",") + "\n"
        })
        .collect();
    std::fs::write(sim.join("no_height.csv"), without).unwrap();
    let analyze = |name: &str, manifest: &str, extra: &[&str]| {
        let out = d.path().join(name);
        let mut args = vec![
            "analyze",
            manifest,
            "--out",
            out.to_str().unwrap(),
            "--no-sta",
        ];
        args.extend_from_slice(extra);
        ldh_ok(&args);
        (
            json(&out.join("recordings.json")),
            json(&out.join("strides.json")),
        )
    };
    let given = analyze("given", sim.join("manifest.csv").to_str().unwrap(), &[]);
    let none = analyze("none", sim.join("no_height.csv").to_str().unwrap(), &[]);
    let flag = analyze(
        "flag",
        sim.join("no_height.csv").to_str().unwrap(),
        &["--sensor-height-m", &height],
    );
    // The height given by the column or by the flag: the same results, nothing about the height.
    assert_eq!(given, flag);
    let fusion = |v: &serde_json::Value| -> Vec<serde_json::Value> {
        let a = v.as_array().unwrap().iter();
        a.filter(|r| r["model"] == "fusion").cloned().collect()
    };
    let (rg, rn) = (fusion(&given.0), fusion(&none.0));
    assert_eq!(rg.len(), 2);
    let mut withheld = 0;
    for (g, n) in rg.iter().zip(&rn) {
        let codes = |r: &serde_json::Value| -> Vec<String> {
            let w = r["warnings"].as_array().unwrap().iter();
            w.map(|w| w["code"].as_str().unwrap().to_string()).collect()
        };
        assert!(
            !codes(g).iter().any(|c| c == "sensor_height_unknown"),
            "{g}"
        );
        let sl = g["stride_length_m"].as_f64().unwrap();
        assert!((0.8..1.9).contains(&sl), "{g}");
        let mut w = n["warnings"].as_array().unwrap().iter();
        let w = w
            .find(|w| w["code"] == "sensor_height_unknown")
            .expect("the finding");
        let message = w["message"].as_str().unwrap();
        if w["severity"] == "warning" {
            withheld += 1;
            assert!(message.contains("(more than 15 %)"), "{message}");
            assert!(
                message.contains("manifest column sensor_height_m"),
                "{message}"
            );
            for p in ["stride_length_m", "speed_mps", "stride_length_cv"] {
                assert!(n[p].is_null(), "{p}: {n}");
                let why = n["withheld"][p].as_str().unwrap();
                assert!(why.contains("sensor height"), "{why}");
            }
        }
        // What does not come from the length is the same.
        for p in [
            "strides_valid",
            "stride_time_s",
            "stance_ratio",
            "wqk_deg",
            "pbi_deg",
        ] {
            assert_eq!(g[p], n[p], "{p}");
        }
    }
    assert_eq!(withheld, 2, "{rn:?}");
    // Per stride: every length empty; a stride that had one with its height says why (the
    // height, or a per-stride check the length at the assumed height failed), and most say
    // it is the height.
    let (sg, sn) = (fusion(&given.1), fusion(&none.1));
    assert_eq!(sg.len(), sn.len());
    assert!(sn
        .iter()
        .all(|s| s["stride_length_m"].is_null() && s["speed_mps"].is_null()));
    let (mut had, mut height) = (0, 0);
    for (g, n) in sg.iter().zip(&sn) {
        assert_eq!(g["stride_time_s"], n["stride_time_s"]);
        if g["stride_length_m"].is_number() {
            let why = n["reason"].as_str().unwrap();
            assert!(why.contains("stride length withheld: "), "{why}");
            had += 1;
            height += usize::from(why.contains("stride length withheld: sensor height not given"));
        }
    }
    assert!(had >= 10 && 2 * height > had, "{height} of {had}");
}
