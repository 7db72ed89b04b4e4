//! Property tests of the model file (issue 37): every float written reads back bit-identical,
//! and 10^5 random small models (forests, SVMs, MLPs) are written, read back (checksum,
//! structure and plausibility all accepted) and predict bit-identically.

use ndarray::Array2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::super::dataset::{Dataset, Task};
use super::super::forest::ForestParams;
use super::super::mlp::MlpParams;
use super::super::model::{Classifier, ModelFile};
use super::super::svm::SvmParams;

/// Models of each kind in [`random_models_round_trip_bit_identically`]: 10^5 in all by default
/// (about 10 s of CPU); `LDH_MODEL_ROUNDTRIPS_PER_KIND=100000` runs 10^5 of each (about 80 s of
/// CPU, 32 s on 2 cores), which `.ci/run` sets.
fn models_per_kind() -> u64 {
    std::env::var("LDH_MODEL_ROUNDTRIPS_PER_KIND")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(33_334)
}

/// A value of any magnitude from 1e-6 to 1e8, with all 53 bits of mantissa random.
fn value(rng: &mut ChaCha8Rng) -> f64 {
    let k = rng.gen_range(-6..=8);
    (rng.gen::<f64>() - 0.5) * 10f64.powi(k)
}

/// A small random dataset: 2-3 classes (every class present), 1-3 features (one constant now
/// and then), 2-4 rows per class.
fn dataset(rng: &mut ChaCha8Rng) -> Dataset {
    let task = if rng.gen_bool(0.5) {
        Task::Binary
    } else {
        Task::ThreeClass
    };
    let nc = task.class_names().len();
    let nf = rng.gen_range(1..=3);
    let mut y: Vec<usize> = (0..nc)
        .flat_map(|c| std::iter::repeat_n(c, rng.gen_range(2..=4)))
        .collect();
    y.sort_unstable();
    let n = y.len();
    let mut x = Array2::<f64>::zeros((n, nf));
    for mut col in x.columns_mut() {
        if rng.gen_bool(0.1) {
            col.fill(value(rng));
        } else {
            let (centre, scale) = (value(rng), value(rng).abs().max(1e-6));
            col.mapv_inplace(|_| centre + scale * (rng.gen::<f64>() - 0.5));
        }
    }
    Dataset {
        task,
        feature_names: (0..nf).map(|j| format!("f{j}")).collect(),
        class_names: task.class_names().iter().map(|s| s.to_string()).collect(),
        x,
        y,
        groups: (0..n).map(|i| format!("s{i}")).collect(),
        row_ids: (0..n).map(|i| format!("r{i}")).collect(),
        dropped: vec![],
    }
}

fn classifier(kind: usize, rng: &mut ChaCha8Rng) -> Classifier {
    let seed = rng.gen();
    match kind {
        0 => Classifier::RandomForest(ForestParams {
            n_trees: rng.gen_range(1..=3),
            seed,
            ..ForestParams::default()
        }),
        1 => Classifier::Svm(SvmParams::default()),
        _ => Classifier::Mlp(
            MlpParams::default()
                .hidden_layer_sizes([rng.gen_range(1..=3)])
                .max_iter(rng.gen_range(1..=3))
                .seed(seed),
        ),
    }
}

fn bits(a: &Array2<f64>) -> Vec<u64> {
    a.iter().map(|v| v.to_bits()).collect()
}

/// Train, write, read back and compare predictions on the training rows and on random rows.
fn round_trip(kind: usize, seed: u64) -> Result<(), String> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let ds = dataset(&mut rng);
    let m = ModelFile::train(&ds, &classifier(kind, &mut rng), "fusion")
        .map_err(|e| format!("train: {e}"))?;
    let text = m.to_json().map_err(|e| e.to_string())?;
    let back = ModelFile::from_json(&text, "m.json").map_err(|e| e.to_string())?;
    let mut probe = ds.x.clone();
    probe.mapv_inplace(|v| v + value(&mut rng) * 1e-3);
    for x in [&ds.x, &probe] {
        let (a, pa) = m.predict(x).map_err(|e| e.to_string())?;
        let (b, pb) = back.predict(x).map_err(|e| e.to_string())?;
        if a != b || pa.as_ref().map(bits) != pb.as_ref().map(bits) {
            return Err("predictions differ after the round trip".into());
        }
    }
    if back.to_json().map_err(|e| e.to_string())? != text {
        return Err("the re-written file differs".into());
    }
    Ok(())
}

#[test]
fn every_float_reads_back_bit_identical() {
    let mut rng = ChaCha8Rng::seed_from_u64(37);
    for i in 0..1_000_000u64 {
        let x = match i % 3 {
            0 => f64::from_bits(rng.gen()),
            1 => value(&mut rng),
            _ => rng.gen::<f64>(),
        };
        if !x.is_finite() {
            continue;
        }
        let text = serde_json::to_string(&x).unwrap();
        let back: f64 = serde_json::from_str(&text).unwrap();
        assert_eq!(back.to_bits(), x.to_bits(), "{x:e} written as {text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(
            v.as_f64().unwrap().to_bits(),
            x.to_bits(),
            "{text} as a Value"
        );
    }
}

/// 10^5 random models (a third of each kind: forest, SVM, MLP; see [`models_per_kind`]):
/// accepted on reading, identical predictions, the same text when written again.
#[test]
fn random_models_round_trip_bit_identically() {
    let per_kind = models_per_kind();
    for kind in 0..3 {
        let failures: Vec<String> = (0..per_kind)
            .into_par_iter()
            .filter_map(|i| {
                let seed = kind as u64 * per_kind + i;
                round_trip(kind, seed)
                    .err()
                    .map(|e| format!("kind {kind} seed {seed}: {e}"))
            })
            .collect();
        assert!(
            failures.is_empty(),
            "{} failures, first: {:?}",
            failures.len(),
            &failures[..failures.len().min(5)]
        );
    }
}
