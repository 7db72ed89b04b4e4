//! `ldh train` and `ldh predict` end to end.

mod common;
use common::*;
use std::path::Path;

#[test]
fn train_reports_grouped_and_stratified_cv_and_predict_uses_the_model() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("cohort");
    let o = ldh(&[
        "simulate",
        "--out",
        c.to_str().unwrap(),
        "--healthy",
        "8",
        "--ldh",
        "8",
        "--seconds",
        "30",
        "--seed",
        "21",
        "--ldh-severity-min",
        "0.5",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let out = d.path().join("train");
    train_reports_both_cvs_reproducibly(d.path(), &c, &out);
    let pred = d.path().join("pred");
    predict_labels_every_recording(&c, &out, &pred);
    predict_refuses_models_that_do_not_fit(d.path(), &c, &out, &pred);
}

/// `train` into `out`: the report, 6 CV results above chance, the figures and models, and the
/// same CV results and model again with the same seed.
fn train_reports_both_cvs_reproducibly(d: &Path, c: &Path, out: &Path) {
    let args = [
        "train",
        c.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--k",
        "4",
        "--repeats",
        "2",
        "--task",
        "binary",
    ];
    let o = ldh(&args);
    assert!(o.status.success(), "{}", text(&o));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("Subject-grouped folds are the primary result"));
    assert!(
        md.contains("| rf | subject-grouped 4-fold × 2 |")
            && md.contains("| mlp | stratified 4-fold × 2 |")
    );
    assert!(md.contains("grouped − stratified accuracy") && md.contains("Pearson r"));
    let cv = json(&out.join("cv_results.json"));
    assert_eq!(cv.as_array().unwrap().len(), 6);
    for r in cv.as_array().unwrap() {
        let acc = r["accuracy"]["mean"].as_f64().unwrap();
        assert!(acc > 0.6, "{r}");
    }
    for f in [
        "confusion_rf_grouped.svg",
        "confusion_svm_stratified.svg",
        "model_rf.json",
        "model_svm.json",
        "model_mlp.json",
        "dataset.csv",
        "folds.csv",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    // Same seed: byte-identical CV results.
    let out2 = d.join("train2");
    let mut args2 = args.to_vec();
    args2[3] = out2.to_str().unwrap();
    assert!(ldh(&args2).status.success());
    assert_eq!(
        std::fs::read(out.join("cv_results.json")).unwrap(),
        std::fs::read(out2.join("cv_results.json")).unwrap()
    );
    assert_eq!(
        std::fs::read(out.join("model_rf.json")).unwrap(),
        std::fs::read(out2.join("model_rf.json")).unwrap()
    );
}

/// `predict` with the forest: labels and probabilities for every recording into `pred`.
fn predict_labels_every_recording(c: &Path, out: &Path, pred: &Path) {
    let o = ldh(&[
        "predict",
        "--model",
        out.join("model_rf.json").to_str().unwrap(),
        c.to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("decision support, not a diagnosis"));
    let p = std::fs::read_to_string(pred.join("predictions.csv")).unwrap();
    assert!(
        p.starts_with("subject_id,side,status,predicted_class,p_H,p_LDHE,note\n"),
        "{p}"
    );
    assert_eq!(p.lines().count(), 1 + 32);
    let healthy_right = p
        .lines()
        .filter(|l| l.starts_with('H') && l.contains(",ok,H,"))
        .count();
    assert!(healthy_right >= 12, "{p}");
    let affected_found = p
        .lines()
        .filter(|l| l.starts_with('L') && l.contains(",ok,LDHE,"))
        .count();
    assert!(affected_found >= 6, "{p}");
}

/// A model from another schema, or with features the input lacks, is refused.
fn predict_refuses_models_that_do_not_fit(d: &Path, c: &Path, out: &Path, pred: &Path) {
    let m = std::fs::read_to_string(out.join("model_rf.json")).unwrap();
    let old = d.join("old.json");
    std::fs::write(&old, m.replace("ldh-model/3", "ldh-model/0")).unwrap();
    let o = ldh(&[
        "predict",
        "--model",
        old.to_str().unwrap(),
        c.to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("ldh-model/0") && text(&o).contains("retrain"),
        "{}",
        text(&o)
    );
    // Features from the ACC-only model do not fit a model trained on fusion features.
    let acc = d.join("acc");
    assert!(ldh(&[
        "analyze",
        c.to_str().unwrap(),
        "--model",
        "acc",
        "--no-sta",
        "--out",
        acc.to_str().unwrap()
    ])
    .status
    .success());
    let o = ldh(&[
        "predict",
        "--model",
        out.join("model_svm.json").to_str().unwrap(),
        "--results",
        acc.to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("'fusion' attitude model but the input has 'acc'"),
        "{}",
        text(&o)
    );
}

#[test]
fn train_refuses_what_it_cannot_do() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("cohort");
    assert!(ldh(&[
        "simulate",
        "--out",
        c.to_str().unwrap(),
        "--healthy",
        "3",
        "--ldh",
        "3",
        // 30 s: at 15 s some legs have too few strides, and on such short walks stride
        // length variability cannot be checked against its noise and is withheld
        // (`sv_unchecked`): the refusal would be about missing features, not the folds
        "--seconds",
        "30",
        "--seed",
        "2"
    ])
    .status
    .success());
    let out = d.path().join("t");
    // Fewer subjects than folds: k is lowered to the smallest class, with a note.
    let o = ldh(&[
        "train",
        c.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--k",
        "10",
        "--repeats",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(
        text(&o).contains("note: k lowered from 10 to"),
        "{}",
        text(&o)
    );
    let o = ldh(&[
        "train",
        c.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--classifiers",
        "rf,knn",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("possible values: rf, svm, mlp"),
        "{}",
        text(&o)
    );
    let o = ldh(&[
        "train",
        c.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--features",
        "stride_time_s,height_cm",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("height_cm") && text(&o).contains("unknown feature"));
    // 15 s walks: five sides have no valid stride (every parameter withheld), and stride
    // length variability is unchecked (too short a walk) everywhere; what is left has one row
    // in a class: one refusal naming the class, the rows per class and what was left out
    let short = d.path().join("short");
    assert!(ldh(&[
        "simulate",
        "--out",
        short.to_str().unwrap(),
        "--healthy",
        "3",
        "--ldh",
        "3",
        "--seconds",
        "15",
        "--seed",
        "2"
    ])
    .status
    .success());
    let o = ldh(&[
        "train",
        short.to_str().unwrap(),
        "--out",
        d.path().join("t15").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    for want in [
        "nothing to train on",
        "the smallest class (LDHH) has 1 row",
        "rows per class: 1 LDHH, 1 LDHE, 2 H",
        "5 row(s) left out with nothing measured (no valid stride)",
        "stride_length_cv (measured in 0 of 4 rows)",
    ] {
        assert!(text(&o).contains(want), "{want}: {}", text(&o));
    }
    assert_eq!(text(&o).trim().lines().count(), 1, "{}", text(&o));
    // Features named by the user are used as named: rows lacking one are dropped, and the
    // refusal says which and how to choose others.
    let o = ldh(&[
        "train",
        short.to_str().unwrap(),
        "--out",
        d.path().join("t15f").to_str().unwrap(),
        "--features",
        "stride_time_s,stride_length_cv",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    for want in ["stride_length_cv on", "--features"] {
        assert!(text(&o).contains(want), "{want}: {}", text(&o));
    }
}

/// Issue 39's done-when: `ldh train` on a short-walk cohort (`ldh simulate --healthy 6 --ldh 6
/// --seconds 20`) trains on what was measured and says what it left out; sides without a valid
/// stride say so in `status`; an analysis folder given as input points to `--results`.
#[test]
fn train_on_short_walks_uses_what_was_measured_with_notes() {
    let d = tempfile::tempdir().unwrap();
    let p = |n: &str| d.path().join(n).to_str().unwrap().to_string();
    let sim = [
        "simulate",
        "--out",
        &p("s"),
        "--healthy",
        "6",
        "--ldh",
        "6",
        "--seconds",
        "20",
    ];
    ldh_ok(&sim);
    let o = ldh(&["train", &p("s"), "--out", &p("t")]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        // 20 s walks: fewer than 10 steady strides, so both CVs are withheld (issue 36).
        err.contains("note: 3 feature(s) left out, measured in fewer than 90 % of the rows: stride_length_cv (measured in 0 of 18 rows), stride_time_cv (measured in 0 of 18 rows)"),
        "{err}"
    );
    assert!(
        err.contains("note: k lowered from 10 to 6: the smallest class (LDHH) has 6 rows"),
        "{err}"
    );
    let report = std::fs::read_to_string(d.path().join("t/report.md")).unwrap();
    assert!(
        report.contains("Notes:") && report.contains("- k lowered from 10 to 6"),
        "{report}"
    );
    assert!(d.path().join("t/model_rf.json").is_file());
    // Seed 3: five sides without a valid stride; their rows say so and training sets them aside.
    let (s3, a3) = (p("s3"), p("a3"));
    ldh_ok(&[
        "simulate",
        "--out",
        &s3,
        "--healthy",
        "6",
        "--ldh",
        "6",
        "--seconds",
        "20",
        "--seed",
        "3",
    ]);
    ldh_ok(&["analyze", &s3, "-o", &a3, "-q"]);
    let rows = json(&d.path().join("a3/recordings.json"));
    let rows = rows.as_array().unwrap();
    for r in rows {
        let want = if r["strides_valid"] == 0 {
            "no_valid_strides"
        } else {
            "ok"
        };
        assert_eq!(r["status"], want, "{r}");
    }
    assert_eq!(
        rows.iter()
            .filter(|r| r["status"] == "no_valid_strides")
            .count(),
        5
    );
    let o = ldh(&["train", "--results", &a3, "--out", &p("t3")]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(
        text(&o).contains("note: 5 row(s) left out with nothing measured (no valid stride)"),
        "{}",
        text(&o)
    );
    // The analysis folder given where recordings go: the way to pass it.
    let model = p("t3/model_rf.json");
    for cmd in [
        &["stats", &a3, "--out", &p("x")][..],
        &["train", &a3, "--out", &p("x")],
        &["predict", "--model", &model, &a3, "--out", &p("x")],
        &[
            "predict",
            "--model",
            &model,
            &format!("{a3}/recordings.csv"),
            "--out",
            &p("x"),
        ],
    ] {
        let o = ldh(cmd);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(
            text(&o).contains(&format!("--results {a3}")),
            "{cmd:?}: {}",
            text(&o)
        );
    }
}
