//! Parity with nolds 0.6.2: `lyap_r` and `lyap_e` against the goldens of
//! `data-fixtures/scripts/gen_lyapunov_golden.py`.

use super::*;
use serde_json::Value;

const GOLDENS: [(&str, &str); 4] = [
    (
        "lorenz",
        include_str!("../../../../../data-fixtures/golden/lyapunov/lorenz.json"),
    ),
    (
        "logistic",
        include_str!("../../../../../data-fixtures/golden/lyapunov/logistic.json"),
    ),
    (
        "noise",
        include_str!("../../../../../data-fixtures/golden/lyapunov/noise.json"),
    ),
    (
        "gait",
        include_str!("../../../../../data-fixtures/golden/lyapunov/gait.json"),
    ),
];

/// Parity tolerance against nolds (relative, with a tiny absolute floor for
/// values that are zero in nolds).
const REL_TOL: f64 = 1e-6;

fn close(a: f64, b: f64, rel: f64) -> bool {
    if a.is_infinite() || b.is_infinite() {
        return a == b;
    }
    (a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-12
}

/// The series of a golden file, from the exact IEEE-754 bits.
fn series(doc: &Value) -> Vec<f64> {
    doc["series_bits"]
        .as_array()
        .expect("series_bits")
        .iter()
        .map(|h| {
            f64::from_bits(u64::from_str_radix(h.as_str().expect("hex"), 16).expect("hex bits"))
        })
        .collect()
}

fn opt_usize(p: &Value, key: &str) -> Option<Option<usize>> {
    match p.get(key) {
        None => None,
        Some(Value::Null) => Some(None),
        Some(v) => Some(Some(v.as_u64().expect("integer") as usize)),
    }
}

fn rosenstein_params(p: &Value) -> RosensteinParams {
    let mut r = RosensteinParams::default();
    if let Some(v) = opt_usize(p, "emb_dim") {
        r = r.emb_dim(v.expect("emb_dim"));
    }
    if let Some(v) = opt_usize(p, "lag") {
        r = r.lag(v);
    }
    if let Some(v) = opt_usize(p, "min_tsep") {
        r = r.min_tsep(v);
    }
    if let Some(v) = opt_usize(p, "trajectory_len") {
        r = r.trajectory_len(v.expect("trajectory_len"));
    }
    if let Some(v) = opt_usize(p, "fit_offset") {
        r = r.fit_offset(v.expect("fit_offset"));
    }
    if let Some(t) = p.get("tau") {
        r = r.tau(t.as_f64().expect("tau"));
    }
    r
}

fn eckmann_params(p: &Value) -> EckmannParams {
    let mut e = EckmannParams::default();
    if let Some(v) = opt_usize(p, "emb_dim") {
        e = e.emb_dim(v.expect("emb_dim"));
    }
    if let Some(v) = opt_usize(p, "matrix_dim") {
        e = e.matrix_dim(v.expect("matrix_dim"));
    }
    if let Some(v) = opt_usize(p, "min_nb") {
        e = e.min_nb(v);
    }
    if let Some(v) = opt_usize(p, "min_tsep") {
        e = e.min_tsep(v.expect("min_tsep"));
    }
    if let Some(t) = p.get("tau") {
        e = e.tau(t.as_f64().expect("tau"));
    }
    e
}

#[test]
fn golden_series_bits_match_decimal() {
    for (name, text) in GOLDENS {
        let doc: Value = serde_json::from_str(text).expect("golden JSON");
        let bits = series(&doc);
        let dec: Vec<f64> = doc["series"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(bits.len(), dec.len(), "{name}");
        assert!(bits.len() <= 3000, "{name}: golden series must stay small");
        for (a, b) in bits.iter().zip(&dec) {
            assert!(close(*a, *b, 1e-15), "{name}: {a} vs {b}");
        }
        assert_eq!(doc["versions"]["nolds"], "0.6.2", "{name}");
    }
}

#[test]
fn golden_lyap_r_matches_nolds() {
    let mut checked = 0;
    for (name, text) in GOLDENS {
        let doc: Value = serde_json::from_str(text).expect("golden JSON");
        let x = series(&doc);
        for case in doc["lyap_r"].as_array().unwrap() {
            let p = rosenstein_params(&case["params"]);
            let res = lyap_r(&x, &p).unwrap_or_else(|e| panic!("{name} {p:?}: {e}"));
            let want = case["lyap"].as_f64().unwrap();
            assert!(
                close(res.exponent, want, REL_TOL),
                "{name} {:?}: exponent {} vs nolds {want} (lag {:?}, min_tsep {})",
                case["params"],
                res.exponent,
                res.lag,
                res.min_tsep
            );
            let ks: Vec<usize> = case["ks"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_u64().unwrap() as usize)
                .collect();
            assert_eq!(res.ks, ks, "{name} {:?}", case["params"]);
            for (a, b) in res
                .divergence
                .iter()
                .zip(case["div_traj"].as_array().unwrap())
            {
                let b = b.as_f64().unwrap();
                assert!(
                    close(*a, b, REL_TOL),
                    "{name} {:?}: div {a} vs {b}",
                    case["params"]
                );
            }
            let poly = case["poly"].as_array().unwrap();
            assert!(close(res.slope, poly[0].as_f64().unwrap(), REL_TOL));
            assert!(close(res.intercept, poly[1].as_f64().unwrap(), REL_TOL));
            checked += 1;
        }
    }
    assert_eq!(checked, 15);
}

#[test]
fn golden_lyap_e_matches_nolds() {
    let mut checked = 0;
    for (name, text) in GOLDENS {
        let doc: Value = serde_json::from_str(text).expect("golden JSON");
        let x = series(&doc);
        for case in doc["lyap_e"].as_array().unwrap() {
            let p = eckmann_params(&case["params"]);
            let res = lyap_e(&x, &p).unwrap_or_else(|e| panic!("{name} {p:?}: {e}"));
            let want: Vec<f64> = case["lyap"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            assert_eq!(res.exponents.len(), want.len());
            for (k, (a, b)) in res.exponents.iter().zip(&want).enumerate() {
                // The one documented exception (docs/lyapunov.md): the logistic
                // map (a 1-D map) embedded in 10 dimensions gives local
                // least-squares systems with condition numbers up to 3e9 and
                // Jacobian rows of size ~1e8, so the *smallest* exponent is set
                // by rounding inside LAPACK: nolds itself moves by up to 5e-4
                // relative when the input is perturbed by 1e-15 relative.
                // The three larger exponents still agree to 1e-6.
                let ill_conditioned = name == "logistic" && p.emb_dim == 10 && k == 3;
                let tol = if ill_conditioned { 1e-3 } else { REL_TOL };
                assert!(
                    close(*a, *b, tol),
                    "{name} {:?} exponent {k}: {a} vs nolds {b} (all: {:?} vs {want:?})",
                    case["params"],
                    res.exponents
                );
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 9);
}
