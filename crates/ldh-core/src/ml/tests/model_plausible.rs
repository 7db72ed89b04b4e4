//! Every plausibility rule of [`super::model_plausible`] refuses an edit re-sealed with a
//! recomputed checksum, with the reason in the message (issue 37).

use serde_json::{json, Value};

use super::super::model::ModelFile;
use super::super::model_check::ModelError;
use super::model::{sealed, trained};

/// The edited, re-sealed model is refused as implausible, naming the file and `needle`.
fn implausible(v: Value, needle: &str) {
    let Err(e) = ModelFile::from_json(&sealed(v), "edited.json") else {
        panic!("{needle}: the edited model was accepted");
    };
    let msg = e.to_string();
    assert!(
        matches!(e, ModelError::Implausible { .. }) && msg.contains(needle),
        "{needle}: {msg}"
    );
    assert!(msg.starts_with("edited.json: "), "{msg}");
}

fn edit(kind: &str, f: impl FnOnce(&mut Value)) -> Value {
    let (_, mut v, _) = trained(kind);
    f(&mut v);
    v
}

/// Set feature `j`'s training range, scaler and class means consistently (so that only the
/// rule under test can object).
fn set_feature(v: &mut Value, j: usize, lo: f64, hi: f64) {
    let mid = 0.5 * (lo + hi);
    v["training"]["min"][j] = json!(lo);
    v["training"]["max"][j] = json!(hi);
    v["training"]["mean"][j] = json!(mid);
    v["training"]["sd"][j] = json!(0.0);
    v["scaling"]["min"][j] = json!(lo);
    v["scaling"]["range"][j] = json!(hi - lo);
    for p in v["training"]["probes"].as_array_mut().unwrap() {
        p["x"][j] = json!(mid);
    }
}

fn leaves(n: &mut Value, f: &mut impl FnMut(&mut Vec<Value>)) {
    if let Some(c) = n.get_mut("Leaf") {
        f(c.as_array_mut().unwrap());
    } else {
        let s = &mut n["Split"];
        leaves(&mut s["left"], f);
        leaves(&mut s["right"], f);
    }
}

fn every_leaf(v: &mut Value, mut f: impl FnMut(&mut Vec<Value>)) {
    for t in v["model"]["trees"].as_array_mut().unwrap() {
        leaves(t, &mut f);
    }
}

#[test]
fn a_fresh_model_of_every_kind_is_plausible() {
    for kind in ["rf", "svm", "mlp"] {
        let (m, v, _) = trained(kind);
        assert!(ModelFile::from_json(&sealed(v), "m.json").is_ok(), "{kind}");
        assert_eq!(m.training.probes.len(), 3);
    }
}

#[test]
fn scaling_must_be_the_training_range() {
    implausible(
        edit("rf", |v| v["scaling"]["range"][0] = json!(1e300)),
        "is not the training range",
    );
    implausible(
        edit("rf", |v| v["scaling"]["range"][0] = json!(1e-300)),
        "is not the training range",
    );
    implausible(
        edit("rf", |v| v["scaling"]["min"][2] = json!(-5.0)),
        "scaling of speed_mps",
    );
    // The summary edited along with the scaler: bounded values, a minimum range.
    implausible(edit("rf", |v| set_feature(v, 9, 0.0, 1e300)), "within ±1e9");
    implausible(edit("rf", |v| set_feature(v, 9, 0.0, 1e-300)), "below 1e-9");
}

#[test]
fn the_training_summary_must_hold_together() {
    implausible(
        edit("rf", |v| v["training"]["rows"] = json!(7)),
        "training.rows",
    );
    implausible(
        edit("rf", |v| v["training"]["mean"][0] = json!(100.0)),
        "do not fit together",
    );
    implausible(
        edit("rf", |v| v["training"]["sd"][0] = json!(100.0)),
        "do not fit together",
    );
    implausible(
        edit("rf", |v| {
            v["training"]["mean"].as_array_mut().unwrap().pop();
        }),
        "training.mean has 12 values",
    );
    implausible(
        edit("rf", |v| {
            v["training"]["probes"].as_array_mut().unwrap().pop();
        }),
        "training probes for classes",
    );
    implausible(
        edit("rf", |v| {
            let m = v["training"]["mean"][0].as_f64().unwrap();
            v["training"]["mean"][0] = json!(m * 1.01);
        }),
        "average to",
    );
}

#[test]
fn features_out_of_order_are_refused() {
    // Names swapped (step frequency and stride length overlap in range): a relation breaks.
    implausible(
        edit("rf", |v| {
            v["feature_names"].as_array_mut().unwrap().swap(0, 1)
        }),
        "step frequency × stride time",
    );
    implausible(
        edit("rf", |v| {
            v["feature_names"].as_array_mut().unwrap().swap(3, 4)
        }),
        "stride time / step time",
    );
    implausible(
        edit("rf", |v| {
            v["feature_names"].as_array_mut().unwrap().swap(5, 6)
        }),
        "stance ratio",
    );
    implausible(
        edit("rf", |v| {
            v["feature_names"].as_array_mut().unwrap().swap(2, 9)
        }),
        "speed / (stride length",
    );
    // Outside the physical range of the named parameter.
    implausible(
        edit("rf", |v| {
            v["feature_names"].as_array_mut().unwrap().swap(0, 10)
        }),
        "outside its physical range",
    );
    // Two angle columns swapped everywhere (scaler, summary, class means): the model's output
    // at the class means changes.
    for kind in ["rf", "svm", "mlp"] {
        implausible(
            edit(kind, |v| {
                for key in ["min", "max", "mean", "sd"] {
                    v["training"][key].as_array_mut().unwrap().swap(10, 12);
                }
                for key in ["min", "range"] {
                    v["scaling"][key].as_array_mut().unwrap().swap(10, 12);
                }
                for p in v["training"]["probes"].as_array_mut().unwrap() {
                    p["x"].as_array_mut().unwrap().swap(10, 12);
                }
            }),
            "the fitted model was edited",
        );
    }
}

#[test]
fn forest_edits_are_refused() {
    implausible(
        edit("rf", |v| every_leaf(v, |c| c.rotate_right(1))),
        "edited",
    );
    implausible(
        edit("rf", |v| {
            let t = v["model"]["trees"][0].clone();
            v["model"]["trees"].as_array_mut().unwrap().push(t);
        }),
        "101 trees, the parameters say 100",
    );
    implausible(
        edit("rf", |v| {
            let t = v["model"]["trees"][0].clone();
            let trees = v["model"]["trees"].as_array_mut().unwrap();
            trees.extend(std::iter::repeat_n(t, 1000));
            v["classifier"]["n_trees"] = json!(1100);
        }),
        "at most 1000",
    );
    implausible(
        edit("rf", |v| every_leaf(v, |c| c[0] = json!(0.5))),
        "whole numbers",
    );
    implausible(
        edit("rf", |v| {
            let mut first = true;
            every_leaf(v, |c| {
                if std::mem::take(&mut first) {
                    c[0] = json!(c[0].as_f64().unwrap() + 1.0);
                }
            })
        }),
        "bootstrap sample",
    );
    implausible(
        edit("rf", |v| {
            let rows = v["training"]["rows"].as_f64().unwrap();
            v["model"]["trees"][0] = json!({"Split": {"feature": 0, "threshold": 0.5,
                "left": {"Leaf": [rows - 1.0, 0.0, 0.0]}, "right": {"Leaf": [1.0, 0.0, 0.0]}}});
        }),
        "all of one class",
    );
    implausible(
        edit("rf", |v| {
            let mut n = &mut v["model"]["trees"][0];
            while n.get("Split").is_some() {
                n["Split"]["threshold"] = json!(2.5);
                n = &mut n["Split"]["left"];
            }
        }),
        "outside the scaled training range",
    );
    implausible(
        edit("rf", |v| {
            let rows = v["training"]["rows"].as_f64().unwrap();
            for t in v["model"]["trees"].as_array_mut().unwrap() {
                *t = json!({"Leaf": [rows, 0.0, 0.0]});
            }
        }),
        "leaf counts edited",
    );
    // A chain of splits with more nodes than a bootstrap sample of the training rows allows.
    implausible(
        edit("rf", |v| {
            let rows = v["training"]["rows"].as_u64().unwrap();
            let mut t = json!({"Leaf": [1.0, 0.0, 0.0]});
            for k in 0..rows {
                let leaf = json!({"Leaf": [0.0, 1.0, 0.0]});
                t = json!({"Split": {"feature": 0, "threshold": 0.5, "left": if k % 2 == 0 { leaf } else { json!({"Leaf": [1.0, 0.0, 0.0]}) }, "right": t}});
            }
            v["model"]["trees"][0] = t;
        }),
        "nodes",
    );
}

#[test]
fn svm_edits_are_refused() {
    implausible(
        edit("svm", |v| v["model"]["gamma"] = json!(1e300)),
        "SVM gamma",
    );
    implausible(
        edit("svm", |v| {
            v["model"]["gamma"] = json!(2.0);
        }),
        "kernel width",
    );
    implausible(
        edit("svm", |v| v["classifier"]["c"] = json!(1e300)),
        "SVM C",
    );
    implausible(
        edit("svm", |v| {
            let a = v["model"]["machines"][0]["alpha"].as_array_mut().unwrap();
            let i = a
                .iter()
                .position(|x| x.as_f64().unwrap().abs() > 1e-6)
                .unwrap();
            a[i] = json!(a[i].as_f64().unwrap().signum() * 5.0);
        }),
        "beyond C",
    );
    implausible(
        edit("svm", |v| v["model"]["machines"][0]["rho"] = json!(1e9)),
        "offset rho",
    );
    implausible(
        edit("svm", |v| {
            v["model"]["machines"][0]["sep_hyperplane"]["WeightedCombination"]["data"][0] =
                json!(7.5)
        }),
        "support vector value",
    );
}

#[test]
fn mlp_edits_are_refused() {
    implausible(
        edit("mlp", |v| v["model"]["coefs"][0]["data"][0] = json!(1e200)),
        "beyond ±1e3",
    );
    implausible(
        edit("mlp", |v| {
            v["model"]["intercepts"][1]["data"][0] = json!(-2e3)
        }),
        "beyond ±1e3",
    );
    implausible(
        edit("mlp", |v| {
            v["classifier"]["hidden_layer_sizes"] = json!([50])
        }),
        "hidden layers",
    );
    implausible(
        edit("mlp", |v| v["model"]["n_epochs"] = json!(100_000)),
        "epochs",
    );
    implausible(
        edit("mlp", |v| v["model"]["classes"] = json!([0, 2, 1])),
        "MLP classes",
    );
    implausible(
        edit("mlp", |v| {
            let w = v["model"]["intercepts"][1]["data"][0].as_f64().unwrap();
            v["model"]["intercepts"][1]["data"][0] = json!(w + 0.5);
        }),
        "the fitted model was edited",
    );
}

#[test]
fn read_model_refuses_large_files_fifos_and_devices_before_parsing() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.json");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(100_000_000)
        .unwrap(); // sparse: 100 MB stated, nothing written
    let e = super::super::read_model(&big).unwrap_err().to_string();
    assert!(
        e.contains("big.json") && e.contains("100.0 MB") && e.contains("16 MB"),
        "{e}"
    );
    #[cfg(unix)]
    {
        let e = super::super::read_model(std::path::Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("/dev/zero") && e.contains("not a regular file"),
            "{e}"
        );
    }
    let (m, _, _) = trained("svm");
    let ok = dir.path().join("m.json");
    std::fs::write(&ok, m.to_json().unwrap()).unwrap();
    let back = super::super::read_model(&ok).unwrap();
    assert_eq!(back.origin(), ok.display().to_string());
    let e = back
        .check_features(&["x".to_string()])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with(&format!("{}: ", ok.display())), "{e}");
}
