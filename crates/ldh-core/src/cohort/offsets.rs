//! Table 4 (paper §4.1, eqs. 18–19): every parameter z-normalised against the healthy group,
//! the offsets OFF0 (LDHH) and OFF1 (LDHE) per attitude model.

use serde::{Deserialize, Serialize};

use super::{Cohort, PARAMETERS};
use crate::stats;

/// Table 4 for one model: z-normalised group means and the offsets OFF0 / OFF1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelOffsets {
    /// Model.
    pub model: String,
    /// Parameters used (those with a healthy SD > 0).
    pub codes: Vec<String>,
    /// Mean z of LDHH per parameter.
    pub z_ldhh: Vec<f64>,
    /// Mean z of LDHE per parameter.
    pub z_ldhe: Vec<f64>,
    /// Mean z of H per parameter (0 by construction).
    pub z_h: Vec<f64>,
    /// OFF0: mean |z| of LDHH.
    pub off0: f64,
    /// OFF1: mean |z| of LDHE.
    pub off1: f64,
}

/// z-normalisation against the healthy baseline (eq. 18) and the offsets (eq. 19).
pub fn offsets(c: &Cohort) -> ModelOffsets {
    let mut out = ModelOffsets {
        model: c.model.to_string(),
        codes: vec![],
        z_ldhh: vec![],
        z_ldhe: vec![],
        z_h: vec![],
        off0: f64::NAN,
        off1: f64::NAN,
    };
    for p in PARAMETERS {
        let g = c.groups(p);
        let (Ok(mu), Ok(sd)) = (stats::mean(&g.h), stats::std_dev(&g.h)) else {
            continue;
        };
        if !(sd > 0.0) || g.ldhh.is_empty() {
            continue;
        }
        let z = |v: &[f64]| v.iter().map(|x| (x - mu) / sd).sum::<f64>() / v.len() as f64;
        out.codes.push(p.code().into());
        out.z_ldhh.push(z(&g.ldhh));
        out.z_ldhe.push(z(&g.ldhe));
        out.z_h.push(z(&g.h));
    }
    // No usable parameter (e.g. every healthy SD is 0): no offset, not 0.
    let m = |v: &[f64]| {
        if v.is_empty() {
            f64::NAN
        } else {
            v.iter().map(|x| x.abs()).sum::<f64>() / v.len() as f64
        }
    };
    out.off0 = m(&out.z_ldhh);
    out.off1 = m(&out.z_ldhe);
    out
}

/// Table 4 as Markdown.
pub fn table4_markdown(models: &[ModelOffsets]) -> String {
    let mut s = String::from("| Model | OFF0 (LDHH) | OFF1 (LDHE) |\n|---|---:|---:|\n");
    for m in models {
        s.push_str(&format!(
            "| {} | {:.2} | {:.2} |\n",
            m.model, m.off0, m.off1
        ));
    }
    s
}
