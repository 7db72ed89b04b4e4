//! Tampered model files (issue 19): each is refused with a [`ModelError`], never a panic and
//! never a silent prediction.

use crate::domain::Parameter;
use serde_json::{json, Value};

use super::super::dataset::{Dataset, Task};
use super::super::model::{Classifier, ModelFile};
use super::super::model_check::{checksum, ModelError};

const THREE: &str = include_str!("../../../../../data-fixtures/ml/three_class_dataset.csv");

pub(super) fn trained(kind: &str) -> (ModelFile, Value, Dataset) {
    let ds = Dataset::from_csv(THREE, Task::ThreeClass, "t").unwrap();
    let m = ModelFile::train(&ds, &Classifier::from_name(kind, 3).unwrap(), "fusion").unwrap();
    let v: Value = serde_json::from_str(&m.to_json().unwrap()).unwrap();
    (m, v, ds)
}

/// Re-seal an edited file with a matching checksum (what a careful tamperer would do), so the
/// structural checks are tested on their own.
pub(super) fn sealed(mut v: Value) -> String {
    let sum = checksum(&v);
    v["checksum"] = Value::String(sum);
    serde_json::to_string(&v).unwrap()
}

/// Load `text`; it must fail (no panic) with an error of the expected kind naming the file.
fn refused(text: &str, what: &str) -> ModelError {
    let r = std::panic::catch_unwind(|| ModelFile::from_json(text, "tampered.json"));
    let e = r.unwrap_or_else(|_| panic!("{what}: panicked")).err();
    let e = e.unwrap_or_else(|| panic!("{what}: loaded"));
    assert!(e.to_string().contains("tampered.json"), "{what}: {e}");
    e
}

fn inconsistent(text: &str, what: &str, needle: &str) {
    match refused(text, what) {
        ModelError::Inconsistent { what: w, .. } => assert!(w.contains(needle), "{what}: {w}"),
        e => panic!("{what}: {e}"),
    }
}

fn damaged(text: &str, what: &str) {
    let e = refused(text, what);
    assert!(matches!(e, ModelError::Damaged { .. }), "{what}: {e}");
}

#[test]
fn every_model_round_trips_with_its_checksum() {
    for kind in ["rf", "svm", "mlp"] {
        let (m, v, ds) = trained(kind);
        assert!(v["checksum"].as_str().unwrap().starts_with("crc32:"));
        let back = ModelFile::from_json(&m.to_json().unwrap(), "m.json").unwrap();
        assert_eq!(back.predict(&ds.x).unwrap().0, m.predict(&ds.x).unwrap().0);
        // Pretty-printing (same content) keeps the checksum valid.
        let pretty = serde_json::to_string_pretty(&v).unwrap();
        assert!(ModelFile::from_json(&pretty, "m.json").is_ok(), "{kind}");
    }
}

#[test]
fn truncated_or_unsealed_files_are_refused() {
    let (m, v, _) = trained("rf");
    let text = m.to_json().unwrap();
    for cut in [1, 10, text.len() / 2, text.len() - 1] {
        let e = refused(&text[..cut], "truncated text");
        assert!(matches!(e, ModelError::NotJson { .. }), "{e}");
    }
    let mut no_sum = v.clone();
    no_sum.as_object_mut().unwrap().remove("checksum");
    let e = refused(&serde_json::to_string(&no_sum).unwrap(), "no checksum");
    assert!(e.to_string().contains("checksum missing"), "{e}");
    // One weight changed by hand, checksum left as it was.
    let mut edited = v.clone();
    edited["scaling"]["min"][0] = json!(123.0);
    let e = refused(&serde_json::to_string(&edited).unwrap(), "edited");
    assert!(matches!(e, ModelError::Checksum { .. }), "{e}");
    let e = refused(&text.replace("ldh-model/3", "ldh-model/2"), "old schema");
    assert!(e.to_string().contains("retrain"), "{e}");
    assert!(matches!(
        refused("{}", "empty object"),
        ModelError::NoSchema { .. }
    ));
}

#[test]
fn shuffled_feature_names_are_refused() {
    let (m, v, ds) = trained("rf");
    let mut shuffled = v.clone();
    shuffled["feature_names"].as_array_mut().unwrap().swap(0, 1);
    // Without re-sealing: the checksum catches the edit.
    let e = refused(&serde_json::to_string(&shuffled).unwrap(), "shuffled");
    assert!(matches!(e, ModelError::Checksum { .. }), "{e}");
    // An input table in another order is refused by name and order.
    let mut names = ds.feature_names.clone();
    names.swap(0, 1);
    let e = m.check_features(&names).unwrap_err().to_string();
    assert!(e.contains("another order") && e.contains("column 1"), "{e}");
    // A repeated name (even re-sealed) is refused on load.
    let mut rep = v.clone();
    rep["feature_names"][1] = rep["feature_names"][0].clone();
    inconsistent(&sealed(rep), "repeated name", "repeated");
}

#[test]
fn forest_tampering_is_refused() {
    let (_, v, _) = trained("rf");
    let leaf_path = |v: &mut Value| -> Value {
        // The first leaf of the first tree.
        let mut n = &mut v["model"]["trees"][0];
        while n.get("Split").is_some() {
            n = &mut n["Split"]["left"];
        }
        n.clone()
    };
    let mut t = v.clone();
    let leaf = leaf_path(&mut t);
    let mut short = leaf.clone();
    short["Leaf"].as_array_mut().unwrap().pop();
    let s = serde_json::to_string(&t).unwrap().replacen(
        &serde_json::to_string(&leaf).unwrap(),
        &serde_json::to_string(&short).unwrap(),
        1,
    );
    inconsistent(
        &sealed(serde_json::from_str(&s).unwrap()),
        "short leaf",
        "class counts",
    );
    let mut t = v.clone();
    if t["model"]["trees"][0].get("Split").is_some() {
        t["model"]["trees"][0]["Split"]["feature"] = json!(99);
        inconsistent(&sealed(t), "feature 99", "feature 99");
    }
    let mut t = v.clone();
    t["model"]["trees"] = json!([]);
    inconsistent(&sealed(t), "no trees", "0 trees");
    let mut t = v.clone();
    t["model"]["n_classes"] = json!(4);
    inconsistent(&sealed(t), "4 classes", "classes");
    let mut t = v.clone();
    t["model"]["trees"][0] = json!({"Leaf": [0.0, 0.0, 0.0]});
    inconsistent(&sealed(t), "empty leaf", "counts");
}

#[test]
fn svm_tampering_is_refused() {
    let (_, v, _) = trained("svm");
    let sv = |v: &mut Value| -> Value {
        v["model"]["machines"][0]["sep_hyperplane"]["WeightedCombination"].clone()
    };
    // Support vectors one column short (shape and data consistent, width wrong).
    let mut t = v.clone();
    let w = sv(&mut t);
    let (r, c) = (
        w["dim"][0].as_u64().unwrap() as usize,
        w["dim"][1].as_u64().unwrap() as usize,
    );
    let data: Vec<Value> = w["data"]
        .as_array()
        .unwrap()
        .chunks(c)
        .flat_map(|row| row[..c - 1].to_vec())
        .collect();
    t["model"]["machines"][0]["sep_hyperplane"]["WeightedCombination"] =
        json!({"v": 1, "dim": [r, c - 1], "data": data});
    inconsistent(&sealed(t), "narrow support vectors", "features");
    // A multiplier dropped: support vectors and multipliers no longer pair up.
    let mut t = v.clone();
    let a = t["model"]["machines"][0]["alpha"].as_array_mut().unwrap();
    let i = a
        .iter()
        .position(|x| x.as_f64().unwrap().abs() > 1e-10)
        .unwrap();
    a[i] = json!(0.0);
    inconsistent(&sealed(t), "alpha zeroed", "multipliers");
    // Truncated support-vector data (shape says more): refused by ndarray's reader.
    let mut t = v.clone();
    t["model"]["machines"][0]["sep_hyperplane"]["WeightedCombination"]["data"]
        .as_array_mut()
        .unwrap()
        .pop();
    damaged(&sealed(t), "truncated support vectors");
    let mut t = v.clone();
    t["model"]["machines"].as_array_mut().unwrap().pop();
    inconsistent(&sealed(t), "machine missing", "machines");
    let mut t = v.clone();
    t["model"]["gamma"] = json!(null);
    damaged(&sealed(t), "gamma null");
}

#[test]
fn mlp_tampering_is_refused() {
    let (_, v, _) = trained("mlp");
    // A truncated weight array.
    let mut t = v.clone();
    t["model"]["coefs"][0]["data"].as_array_mut().unwrap().pop();
    damaged(&sealed(t), "truncated weights");
    // Layers that do not fit together.
    let mut t = v.clone();
    let d = t["model"]["coefs"][1]["dim"].clone();
    let (r, c) = (d[0].as_u64().unwrap(), d[1].as_u64().unwrap());
    t["model"]["coefs"][1]["dim"] = json!([r - 1, c]);
    t["model"]["coefs"][1]["data"]
        .as_array_mut()
        .unwrap()
        .truncate(((r - 1) * c) as usize);
    damaged(&sealed(t), "layer shapes");
    // NaN (null in JSON) and overflowing weights.
    let mut t = v.clone();
    t["model"]["coefs"][0]["data"][0] = Value::Null;
    damaged(&sealed(t), "null weight");
    let text = sealed(v.clone());
    let first = serde_json::to_string(&v["model"]["coefs"][0]["data"][0]).unwrap();
    let e = refused(
        &text.replacen(&format!("[{first}"), "[NaN", 1),
        "NaN literal",
    );
    assert!(matches!(e, ModelError::NotJson { .. }), "{e}");
    let e = refused(&text.replacen(&format!("[{first}"), "[1e999", 1), "1e999");
    assert!(matches!(e, ModelError::NotJson { .. }), "{e}");
    // A class label outside the class list.
    let mut t = v.clone();
    t["model"]["classes"][2] = json!(7);
    inconsistent(&sealed(t), "class 7", "class label 7");
}

#[test]
fn class_and_scaler_tampering_is_refused() {
    let (_, v, _) = trained("rf");
    let mut t = v.clone();
    t["class_names"].as_array_mut().unwrap().push(json!("X"));
    inconsistent(&sealed(t), "extra class", "class names");
    let mut t = v.clone();
    t["class_names"].as_array_mut().unwrap().swap(0, 2);
    inconsistent(&sealed(t), "swapped classes", "class names");
    let mut t = v.clone();
    t["trained_rows_per_class"].as_array_mut().unwrap().pop();
    inconsistent(&sealed(t), "counts", "rows-per-class");
    let mut t = v.clone();
    t["scaling"]["min"].as_array_mut().unwrap().pop();
    inconsistent(&sealed(t), "short scaler", "scaler");
    let mut t = v.clone();
    t["scaling"]["range"][0] = json!(0.0);
    inconsistent(&sealed(t), "zero range", "not positive");
    let mut t = v.clone();
    t["scaling"]["range"][0] = json!(1e308);
    t["scaling"]["min"][0] = json!(-1e308);
    // Consistent in shape, but not the training range (issue 37: tests/model_plausible.rs).
    let e = ModelFile::from_json(&sealed(t), "big.json").unwrap_err();
    assert!(matches!(e, ModelError::Implausible { .. }), "{e}");
    // Non-finite values in memory (a file cannot hold them) are caught by validation too.
    let (mut m, _, _) = trained("rf");
    m.scaling.min[0] = f64::NAN;
    assert!(super::super::model_check::validate(&m, "mem").is_err());
}

#[test]
fn feature_names_become_parameters_once_with_a_typed_error() {
    let (mut m, _, _) = trained("rf");
    assert!(m.predict_rows(&[]).unwrap().is_empty(), "the 13 columns");
    m.feature_names[3] = "height_cm".into();
    let e = m.predict_rows(&[]).unwrap_err().to_string();
    assert!(
        e.contains("height_cm") && e.contains("unknown feature") && e.starts_with("<model>: "),
        "{e}"
    );
}

#[test]
fn a_missing_feature_is_named_with_the_reason_it_was_withheld() {
    let (m, _, _) = trained("rf");
    let mut r = crate::output::test_rows::row("S1", "", "left", 1.0);
    for name in &m.feature_names {
        let p = crate::output::Parameter::from_column(name).unwrap();
        r.set_value(p, Some(1.0));
    }
    r.parameters[Parameter::StrideLengthCv] = None;
    r.withheld.0.insert(
        crate::domain::Parameter::StrideLengthCv,
        crate::domain::Reason::read("sv unchecked (too few strides to check it against its noise)"),
    );
    let p = m.predict_rows(&[r]).unwrap();
    assert_eq!(p[0].predicted_class, None);
    assert_eq!(
        p[0].note,
        "missing stride_length_cv (sv unchecked (too few strides to check it against its noise))"
    );
}
