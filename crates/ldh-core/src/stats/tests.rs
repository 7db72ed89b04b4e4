//! Golden tests against scipy.stats (fixtures written by
//! `data-fixtures/scripts/gen_stats_golden.py`). Every case is checked:
//! statistic and p-value to 1e-6 relative (1e-12 absolute below 1e-12),
//! and every case scipy marks undefined must be a `StatsError`.

use std::collections::BTreeMap;

use serde_json::Value;

use super::*;

const SHAPIRO: &str = include_str!("../../../../data-fixtures/golden/stats/shapiro.json");
const MWU: &str = include_str!("../../../../data-fixtures/golden/stats/mannwhitneyu.json");
const TTEST: &str = include_str!("../../../../data-fixtures/golden/stats/ttest.json");
const WILCOXON: &str = include_str!("../../../../data-fixtures/golden/stats/wilcoxon.json");
const ANOVA: &str = include_str!("../../../../data-fixtures/golden/stats/anova.json");
const PEARSONR: &str = include_str!("../../../../data-fixtures/golden/stats/pearsonr.json");
const HOLM_DESC: &str =
    include_str!("../../../../data-fixtures/golden/stats/holm_descriptives.json");

const REL_TOL: f64 = 1e-6;
const ABS_TOL: f64 = 1e-12;

/// Tracks the comparisons of one fixture file.
struct Checker {
    file: &'static str,
    failures: Vec<String>,
    max_rel: BTreeMap<String, f64>,
    compared: usize,
    tiny: usize,
    cases: usize,
}

impl Checker {
    fn new(file: &'static str) -> Self {
        Checker {
            file,
            failures: Vec::new(),
            max_rel: BTreeMap::new(),
            compared: 0,
            tiny: 0,
            cases: 0,
        }
    }

    /// `key` groups the error statistics, e.g. "ttest_rel pvalue".
    fn close_k(&mut self, key: &str, case: &str, what: &str, actual: f64, expected: f64) {
        self.compared += 1;
        let diff = (actual - expected).abs();
        let ok = diff <= REL_TOL * expected.abs() || (expected.abs() < ABS_TOL && diff <= ABS_TOL);
        let entry = self.max_rel.entry(format!("{key} {what}")).or_insert(0.0);
        if expected.abs() >= ABS_TOL {
            *entry = entry.max(diff / expected.abs());
        } else {
            self.tiny += 1;
        }
        if !ok || actual.is_nan() {
            self.failures.push(format!(
                "{case}: {what} = {actual:e}, scipy {expected:e} (diff {diff:e})"
            ));
        }
    }

    fn fail(&mut self, msg: String) {
        self.failures.push(msg);
    }

    fn finish(self) {
        eprintln!(
            "{}: {} cases, {} values compared ({} below 1e-12, compared absolutely)",
            self.file, self.cases, self.compared, self.tiny
        );
        for (k, v) in &self.max_rel {
            eprintln!("    max relative error {k}: {v:.3e}");
        }
        assert!(self.cases > 0, "{}: no cases", self.file);
        assert!(
            self.failures.is_empty(),
            "{}: {} failures:\n{}",
            self.file,
            self.failures.len(),
            self.failures.join("\n")
        );
    }
}

fn cases(json: &str) -> Vec<Value> {
    let v: Value = serde_json::from_str(json).expect("fixture is valid JSON");
    assert!(
        v["meta"]["scipy"].is_string(),
        "fixture records the scipy version"
    );
    v["cases"].as_array().expect("cases array").clone()
}

fn vecf(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array of numbers")
        .iter()
        .map(|x| match x {
            Value::String(s) if s == "nan" => f64::NAN,
            Value::String(s) if s == "inf" => f64::INFINITY,
            Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
            other => other.as_f64().expect("number"),
        })
        .collect()
}

fn num(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

fn alt(c: &Value) -> Alternative {
    c["args"]["alternative"]
        .as_str()
        .unwrap_or("two-sided")
        .parse()
        .expect("valid alternative")
}

/// Compares an Ok result, or checks that an expected error is an error.
fn check(ck: &mut Checker, key: &str, c: &Value, res: Result<(f64, f64, Option<f64>), StatsError>) {
    ck.cases += 1;
    let name = c["name"].as_str().unwrap_or("?").to_string();
    let expect_error = c["expect_error"].as_bool().expect("expect_error flag");
    match (expect_error, res) {
        (true, Err(e)) => {
            // the message must be non-empty and name the problem
            assert!(!e.to_string().is_empty());
        }
        (true, Ok(r)) => ck.fail(format!(
            "{name}: expected an error (scipy: {}), got {r:?}",
            c["scipy_behaviour"]
        )),
        (false, Err(e)) => ck.fail(format!("{name}: unexpected error {e}")),
        (false, Ok((stat, p, df))) => {
            ck.close_k(key, &name, "statistic", stat, num(&c["statistic"]));
            ck.close_k(key, &name, "pvalue", p, num(&c["pvalue"]));
            if let (Some(df), Some(e)) = (df, c["df"].as_f64()) {
                ck.close_k(key, &name, "df", df, e);
            }
        }
    }
}

#[test]
fn golden_shapiro() {
    let mut ck = Checker::new("shapiro.json");
    for c in cases(SHAPIRO) {
        let x = vecf(&c["args"]["x"]);
        let res = shapiro(&x);
        if let Ok(r) = &res {
            assert_eq!(r.large_sample, x.len() > 5000);
        }
        check(
            &mut ck,
            "shapiro",
            &c,
            res.map(|r| (r.statistic, r.pvalue, None)),
        );
    }
    ck.finish();
}

/// The p-value path the case name promises (`exact_`, `perm_`, `asymp_`).
fn expected_method(name: &str) -> Option<PValueMethod> {
    if name.starts_with("exact_") {
        Some(PValueMethod::Exact)
    } else if name.starts_with("perm_") {
        Some(PValueMethod::ExactPermutation)
    } else if name.starts_with("asymp_") {
        Some(PValueMethod::Asymptotic)
    } else {
        None
    }
}

#[test]
fn golden_mannwhitneyu() {
    let mut ck = Checker::new("mannwhitneyu.json");
    for c in cases(MWU) {
        let x = vecf(&c["args"]["x"]);
        let y = vecf(&c["args"]["y"]);
        let res = mannwhitneyu(&x, &y, alt(&c));
        if let (Ok(r), Some(m)) = (&res, expected_method(c["name"].as_str().unwrap_or(""))) {
            assert_eq!(r.method, m, "{}", c["name"]);
        }
        let key = match &res {
            Ok(r) if r.method == PValueMethod::Exact => "mannwhitneyu(exact)",
            _ => "mannwhitneyu(asymptotic)",
        };
        check(&mut ck, key, &c, res.map(|r| (r.statistic, r.pvalue, None)));
    }
    ck.finish();
}

#[test]
fn golden_ttest() {
    let mut ck = Checker::new("ttest.json");
    for c in cases(TTEST) {
        let a = &c["args"];
        let x = vecf(&a["x"]);
        let key = match (a["kind"].as_str().expect("kind"), a["equal_var"].as_bool()) {
            ("ind", Some(true)) => "ttest_ind(student)",
            ("ind", _) => "ttest_ind(welch)",
            ("rel", _) => "ttest_rel",
            _ => "ttest_1samp",
        };
        let res = match a["kind"].as_str().expect("kind") {
            "ind" => ttest_ind(
                &x,
                &vecf(&a["y"]),
                a["equal_var"].as_bool().expect("equal_var"),
                alt(&c),
            ),
            "rel" => ttest_rel(&x, &vecf(&a["y"]), alt(&c)),
            "1samp" => ttest_1samp(&x, num(&a["popmean"]), alt(&c)),
            k => panic!("unknown kind {k}"),
        };
        check(
            &mut ck,
            key,
            &c,
            res.map(|r| (r.statistic, r.pvalue, Some(r.df))),
        );
    }
    ck.finish();
}

#[test]
fn golden_wilcoxon() {
    let mut ck = Checker::new("wilcoxon.json");
    for c in cases(WILCOXON) {
        let a = &c["args"];
        let x = vecf(&a["x"]);
        let res = if a["y"].is_array() {
            wilcoxon_paired(&x, &vecf(&a["y"]), alt(&c))
        } else {
            wilcoxon(&x, alt(&c))
        };
        if let (Ok(r), Some(m)) = (&res, expected_method(c["name"].as_str().unwrap_or(""))) {
            assert_eq!(r.method, m, "{}", c["name"]);
        }
        let key = match &res {
            Ok(r) if r.method == PValueMethod::Exact => "wilcoxon(exact)",
            Ok(r) if r.method == PValueMethod::ExactPermutation => "wilcoxon(permutation)",
            _ => "wilcoxon(asymptotic)",
        };
        check(&mut ck, key, &c, res.map(|r| (r.statistic, r.pvalue, None)));
    }
    ck.finish();
}

#[test]
fn golden_anova_kruskal() {
    let mut ck = Checker::new("anova.json");
    for c in cases(ANOVA) {
        let a = &c["args"];
        let groups: Vec<Vec<f64>> = a["groups"]
            .as_array()
            .expect("groups")
            .iter()
            .map(vecf)
            .collect();
        let refs: Vec<&[f64]> = groups.iter().map(|g| g.as_slice()).collect();
        let key = if a["test"] == "f_oneway" {
            "f_oneway"
        } else {
            "kruskal"
        };
        let res = match a["test"].as_str().expect("test") {
            "f_oneway" => f_oneway(&refs).map(|r| {
                if let Some(df) = c["df"].as_array() {
                    assert_eq!(r.df_between, num(&df[0]));
                    assert_eq!(r.df_within, num(&df[1]));
                }
                (r.statistic, r.pvalue, None)
            }),
            "kruskal" => kruskal(&refs).map(|r| (r.statistic, r.pvalue, Some(r.df))),
            t => panic!("unknown test {t}"),
        };
        check(&mut ck, key, &c, res);
    }
    ck.finish();
}

#[test]
fn golden_pearsonr() {
    let mut ck = Checker::new("pearsonr.json");
    for c in cases(PEARSONR) {
        let x = vecf(&c["args"]["x"]);
        let y = vecf(&c["args"]["y"]);
        let res = pearsonr(&x, &y, alt(&c));
        if let Ok(r) = &res {
            assert_eq!(r.n, x.len());
        }
        check(
            &mut ck,
            "pearsonr",
            &c,
            res.map(|r| (r.statistic, r.pvalue, None)),
        );
    }
    ck.finish();
}

#[test]
fn golden_holm_and_descriptives() {
    let v: Value = serde_json::from_str(HOLM_DESC).expect("valid JSON");
    let mut ck = Checker::new("holm_descriptives.json");
    for c in v["holm"].as_array().expect("holm cases") {
        ck.cases += 1;
        let name = c["name"].as_str().expect("name");
        let got = holm(&vecf(&c["p"])).expect("valid p-values");
        let want = vecf(&c["adjusted"]);
        assert_eq!(got.len(), want.len());
        for (i, (g, w)) in got.iter().zip(&want).enumerate() {
            ck.close_k("holm", &format!("{name}[{i}]"), "adjusted", *g, *w);
        }
    }
    for c in v["descriptives"].as_array().expect("descriptive cases") {
        ck.cases += 1;
        let name = c["name"].as_str().expect("name");
        let x = vecf(&c["x"]);
        ck.close_k(
            "mean",
            name,
            "value",
            mean(&x).expect("non-empty"),
            num(&c["mean"]),
        );
        match c.get("std") {
            Some(s) => ck.close_k(
                "std_dev",
                name,
                "value",
                std_dev(&x).expect("n >= 2"),
                num(s),
            ),
            None => assert!(std_dev(&x).is_err()),
        }
    }
    ck.finish();
}

#[test]
fn error_messages_are_specific() {
    let e = shapiro(&[1.0, 2.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shapiro needs at least 3 observations, got 2"
    );
    let x: Vec<f64> = (0..12).map(f64::from).collect();
    let e = ttest_rel(&x, &x[..11], Alternative::TwoSided).unwrap_err();
    assert_eq!(
        e.to_string(),
        "ttest_rel: the two samples have different lengths (12 vs 11)"
    );
    let e = ttest_1samp(&[1.0; 5], 0.0, Alternative::TwoSided).unwrap_err();
    assert_eq!(
        e.to_string(),
        "ttest_1samp: constant input: the statistic is undefined (all 5 values equal 1.0)"
    );
    let e = f_oneway(&[&[1.0, 2.0], &[], &[3.0]]).unwrap_err();
    assert_eq!(e.to_string(), "group 1 of f_oneway is empty");
    let e = mannwhitneyu(&[1.0, 2.0, 3.0, 4.0, f64::NAN], &[1.0], Alternative::Less).unwrap_err();
    assert_eq!(e.to_string(), "mannwhitneyu: NaN in sample x at index 4");
    assert!(matches!(
        holm(&[0.5, 1.5]).unwrap_err(),
        StatsError::InvalidArgument { .. }
    ));
    assert!(matches!(
        mean(&[]).unwrap_err(),
        StatsError::TooFewObservations { .. }
    ));
    assert_eq!(holm(&[]).unwrap(), Vec::<f64>::new());
}

#[test]
fn mannwhitneyu_exact_path_with_one_small_sample_is_fast_and_symmetric() {
    // n1 = 8, n2 = 400, no ties: scipy's "auto" picks the exact distribution.
    let x: Vec<f64> = (0..8).map(|i| f64::from(i) * 50.0 + 0.5).collect();
    let y: Vec<f64> = (0..400).map(f64::from).collect();
    let a = mannwhitneyu(&x, &y, Alternative::TwoSided).unwrap();
    let b = mannwhitneyu(&y, &x, Alternative::TwoSided).unwrap();
    assert_eq!(a.method, PValueMethod::Exact);
    assert!((a.pvalue - b.pvalue).abs() <= 1e-15);
    assert!((a.statistic + b.statistic - 3200.0).abs() < 1e-9);
    let forced =
        mannwhitneyu_with(&x, &y, Alternative::TwoSided, MwuMethod::Asymptotic, true).unwrap();
    assert_eq!(forced.method, PValueMethod::Asymptotic);
    assert!((forced.pvalue - a.pvalue).abs() < 0.05);
}
