//! Healthy reference ranges for the per-subject report.
//!
//! From the cohort's healthy subjects when there are at least
//! [`ReportParams::min_healthy_subjects`] (each healthy subject counts once, the mean of both
//! legs, as in the paper's Table 3), as mean ± `reference_z`·SD; otherwise from published
//! normal values of healthy adults walking at a comfortable speed, cited in the report. The
//! published ranges are approximate (they pool ages and studies, and sensors differ): the
//! cohort's own healthy subjects, measured with the same devices and protocol, are always
//! preferred. STA and the shank angles (WQK, PBI, BDK) depend on the method and the sensor
//! placement, so no published range is used for them ([`NO_PUBLISHED`]). Stance, swing and
//! double support are judged against Perry & Burnfield's normal gait cycle again since issue 49
//! (docs/reports.md "Reference ranges"): the default toe off puts healthy walkers' stance at
//! 0.58–0.63 on HuGaDB's real walks, inside 0.57–0.65.

use serde::{Deserialize, Serialize};

use super::ValidReportParams;
use ldh_core::cohort::{Parameter, PARAMETERS};
use ldh_core::output::RecordingRow;

/// Where a reference range comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ReferenceSource {
    /// The cohort's healthy subjects.
    Cohort {
        /// Healthy subjects with this parameter.
        n_subjects: usize,
    },
    /// Published normal values (the citation).
    Published(String),
    /// None available.
    None,
}

/// The reference of one parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceRange {
    /// Parameter code (Table 3).
    pub code: String,
    /// Column of the per-recording table.
    pub column: String,
    /// Name.
    pub name: String,
    /// Unit.
    pub unit: String,
    /// Lower bound, in the parameter's unit.
    pub low: Option<f64>,
    /// Upper bound.
    pub high: Option<f64>,
    /// Centre for z-scores.
    pub mean: Option<f64>,
    /// Spread for z-scores (SD; for a published range, its width / (2 · z)).
    pub sd: Option<f64>,
    /// Where it comes from.
    pub source: ReferenceSource,
    /// Healthy subjects of the cohort with a value of this parameter from legs that pass every
    /// quality check (0 for a reference made without a cohort): the range is the cohort's own
    /// when this reaches [`super::ReportParams::min_healthy_subjects`]; below it the report says
    /// "no reference (n = …)" or names the published range it fell back to.
    #[serde(default)]
    pub n_reference: usize,
}

impl ReferenceRange {
    /// The z-score of `v` against this reference, when it has a spread.
    pub fn z(&self, v: f64) -> Option<f64> {
        match (self.mean, self.sd) {
            (Some(m), Some(s)) if s > 0.0 && v.is_finite() => Some((v - m) / s),
            _ => None,
        }
    }
    /// Whether `v` lies outside [low, high] (`None` without a range).
    pub fn outside(&self, v: f64) -> Option<bool> {
        match (self.low, self.high) {
            (Some(l), Some(h)) => Some(v < l || v > h),
            _ => None,
        }
    }
}

/// Reference ranges for all parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reference {
    /// One per parameter of [`PARAMETERS`], in that order.
    pub ranges: Vec<ReferenceRange>,
    /// One sentence on how the ranges were made, for the report.
    pub description: String,
    /// The healthy band of the shank-pitch gait cycle (from the legs' traces; empty when the
    /// reference was made from the tables alone).
    #[serde(default)]
    pub cycle: super::cycle::CycleReference,
}

/// Whether a leg passes every quality check: no warning or fault, nothing withheld
/// (docs/quality.md). Only such legs make a healthy reference. A warning about stride length
/// variability alone (`sv_noise`, `sv_unchecked`: a noisy or unchecked spread of the lengths, on
/// every walk under ≈ 25 s) says nothing of the leg's other parameters and leaves it in: its SV,
/// withheld, gives the SV range no value.
pub(crate) fn passes_every_check(x: &RecordingRow) -> bool {
    use ldh_core::pipeline::Severity;
    const SV: Parameter = Parameter::StrideLengthCv;
    let sv_only = |w: &ldh_core::pipeline::Warning| {
        w.severity == Severity::Warning
            && !w.affects.is_empty()
            && w.affects.iter().all(|a| *a == SV)
    };
    x.withheld.0.iter().all(|(p, _)| p == SV) && x.warnings.at_least(Severity::Warning).all(sv_only)
}

/// Published ranges: (column, low, high, citation). Approximate ranges for healthy adults
/// (about 20–79 years) walking at a self-selected speed. Stance, swing and double support
/// (issue 49): Perry & Burnfield's normal cycle, 60 % stance and 40 % swing at a customary
/// speed with two double-support periods of ≈ 10 % each, stance longer as walking slows; the
/// range 0.57–0.65 of stance, its complement for swing, and for double support 2 × stance − 1
/// (its value for two symmetric legs), 0.14–0.30.
pub const PUBLISHED: [(&str, f64, f64, &str); 10] = [
    ("step_frequency_steps_per_s", 1.6, 2.1, HOLLMAN),
    ("stride_length_m", 1.1, 1.6, OBERG),
    ("speed_mps", 1.0, 1.6, BOHANNON),
    ("step_time_s", 0.48, 0.63, HOLLMAN),
    ("stride_time_s", 0.95, 1.25, HOLLMAN),
    ("stride_length_cv", 0.0, 0.05, HAUSDORFF),
    ("stride_time_cv", 0.0, 0.04, HAUSDORFF),
    ("stance_ratio", 0.57, 0.65, PERRY),
    ("swing_ratio", 0.35, 0.43, PERRY),
    ("double_support_ratio", 0.14, 0.30, PERRY),
];

/// Why STA and the shank angles get no published range.
const SENSOR_METHOD: &str = "depends on the method and on where the sensor sits";

/// Parameters judged only against the cohort's own healthy subjects (same sensors, protocol and
/// pipeline), never against a published range: (column, why). Stance and swing were among them
/// from 2026-11-25 to issue 49, when ldh's toe off lay 31–54 ms after the foot's push-off peak
/// on HuGaDB's healthy walks and their stance read "above normal" against Perry's 0.57–0.65
/// (docs/accuracy.md "Toe off against the feet of HuGaDB"); with the bracket rule it lies
/// 13–41 ms after it and their stance is 0.58–0.63.
pub const NO_PUBLISHED: [(&str, &str); 4] = [
    ("sta_per_s", SENSOR_METHOD),
    ("wqk_deg", SENSOR_METHOD),
    ("pbi_deg", SENSOR_METHOD),
    ("bdk_deg", SENSOR_METHOD),
];

/// Why the parameter of `column` has no published range ([`NO_PUBLISHED`]), if it is one of
/// those.
pub fn no_published_reason(column: &str) -> Option<&'static str> {
    NO_PUBLISHED
        .iter()
        .find(|(c, _)| *c == column)
        .map(|(_, why)| *why)
}

/// Citation.
pub const HOLLMAN: &str = "Hollman JH, McDade EM, Petersen RC. Normative spatiotemporal gait parameters in older people. Gait Posture 2011;34(1):111–118";
/// Citation.
pub const OBERG: &str = "Öberg T, Karsznia A, Öberg K. Basic gait parameters: reference data for normal subjects, 10–79 years of age. J Rehabil Res Dev 1993;30(2):210–223";
/// Citation.
pub const BOHANNON: &str = "Bohannon RW, Williams Andrews A. Normal walking speed: a descriptive meta-analysis. Physiotherapy 2011;97(3):182–189";
/// Citation (stance, swing and double support; issue 49).
pub const PERRY: &str = "Perry J, Burnfield JM. Gait Analysis: Normal and Pathological Function. 2nd ed. Thorndike (NJ): SLACK; 2010 (ch. 1–2: the gait cycle)";
/// Citation.
pub const HAUSDORFF: &str =
    "Hausdorff JM. Gait variability: methods, modeling and meaning. J NeuroEng Rehabil 2005;2:19";

impl Reference {
    /// The range of `p`, when the reference has one.
    pub fn range(&self, p: Parameter) -> Option<&ReferenceRange> {
        self.ranges.iter().find(|r| r.column == p.column())
    }

    /// Published ranges only (see [`PUBLISHED`]); parameters without one have no range.
    pub fn published(p: &ValidReportParams) -> Reference {
        let z = p.0.reference_z;
        let ranges = PARAMETERS
            .iter()
            .map(|par| {
                let mut r = ReferenceRange {
                    code: par.code().into(),
                    column: par.column().into(),
                    name: par.name().into(),
                    unit: par.unit().into(),
                    low: None,
                    high: None,
                    mean: None,
                    sd: None,
                    source: ReferenceSource::None,
                    n_reference: 0,
                };
                if let Some(&(_, lo, hi, cite)) = PUBLISHED.iter().find(|x| x.0 == par.column()) {
                    r.low = Some(lo);
                    r.high = Some(hi);
                    r.mean = Some(0.5 * (lo + hi));
                    r.sd = Some((hi - lo) / (2.0 * z));
                    r.source = ReferenceSource::Published(cite.into());
                }
                r
            })
            .collect();
        Reference {
            ranges,
            description: "Published normal values for healthy adults (approximate; see the references): the cohort has too few healthy subjects for its own range.".into(),
            cycle: Default::default(),
        }
    }

    /// From the healthy subjects among `rows` (one attitude model) when at least
    /// `min_healthy_subjects` have the parameter; published values for the other parameters.
    pub fn from_rows(rows: &[RecordingRow], p: &ValidReportParams) -> Reference {
        let z = p.0.reference_z;
        let mut out = Reference::published(p);
        // One value per healthy subject: the mean of its analysed legs that pass every quality
        // check (no warning or fault, nothing withheld: docs/quality.md), so a faulty sensor
        // never widens the healthy range.
        let passes = passes_every_check;
        let healthy_legs = rows
            .iter()
            .filter(|x| matches!(x.group, Some(ldh_core::pipeline::Group::Healthy)) && x.is_ok())
            .count();
        let healthy: Vec<Vec<&RecordingRow>> = ldh_core::output::rows_by_subject(rows)
            .into_iter()
            .map(|(_, v)| {
                v.into_iter()
                    .filter(|x| {
                        matches!(x.group, Some(ldh_core::pipeline::Group::Healthy))
                            && x.is_ok()
                            && passes(x)
                    })
                    .collect::<Vec<_>>()
            })
            .filter(|v| !v.is_empty())
            .collect();
        let used_legs: usize = healthy.iter().map(Vec::len).sum();
        let mut any_cohort = 0usize;
        // `published` made one range per parameter, in `PARAMETERS` order.
        for (r, par) in out.ranges.iter_mut().zip(PARAMETERS) {
            let vals: Vec<f64> = healthy
                .iter()
                .filter_map(|legs| {
                    let v: Vec<f64> = legs.iter().filter_map(|x| x.value(par)).collect();
                    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
                })
                .collect();
            r.n_reference = vals.len();
            if vals.len() < p.0.min_healthy_subjects {
                continue;
            }
            let (Ok(m), Ok(sd)) = (
                ldh_core::stats::mean(&vals),
                ldh_core::stats::std_dev(&vals),
            ) else {
                continue;
            };
            if !(sd > 0.0) {
                continue;
            }
            r.mean = Some(m);
            r.sd = Some(sd);
            r.low = Some(m - z * sd);
            r.high = Some(m + z * sd);
            r.source = ReferenceSource::Cohort {
                n_subjects: vals.len(),
            };
            any_cohort = any_cohort.max(vals.len());
        }
        if any_cohort > 0 {
            out.description = format!(
                "Healthy subjects of this cohort (n = {any_cohort}, mean of both legs; {used_legs} of {healthy_legs} analysed healthy legs used: only legs that pass every quality check): mean ± {z:.2} SD; parameters where the cohort has too few values fall back to published normal values."
            );
        } else {
            let have = match healthy_legs {
                0 => "it has no analysed healthy leg".to_string(),
                n => format!("{used_legs} of {n} analysed healthy legs pass every quality check"),
            };
            out.description = format!(
                "Published normal values for healthy adults (approximate; see the references). The cohort's own healthy subjects are not used: it needs at least {} whose legs pass every quality check, and {have}.",
                p.0.min_healthy_subjects
            );
        }
        out
    }
}

/// The published sources cited by the parameter table, numbered in table order.
pub(crate) struct Citations(pub(crate) Vec<String>);

impl Citations {
    pub(crate) fn of(reference: &Reference) -> Citations {
        let mut v: Vec<String> = Vec::new();
        for par in PARAMETERS.iter() {
            if let Some(ReferenceRange {
                low: Some(_),
                high: Some(_),
                source: ReferenceSource::Published(c),
                ..
            }) = reference.range(*par)
            {
                if !v.contains(c) {
                    v.push(c.clone());
                }
            }
        }
        Citations(v)
    }
    /// The number `[k]` of a citation.
    pub(crate) fn number(&self, c: &str) -> usize {
        self.0.iter().position(|x| x == c).unwrap_or(0) + 1
    }
}
