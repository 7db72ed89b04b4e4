//! Self-contained HTML reports a clinician opens offline (SPEC §6): one per subject and one
//! per cohort.
//!
//! A report is one HTML file: inline CSS and inline SVG figures (drawn by [`crate::plots`]),
//! no scripts, no network, no fonts to fetch; A4 print CSS (`@page`, figures kept whole). The
//! markup is also well-formed XML (every element closed, only the five XML entities), so it can
//! be checked by any XML parser.
//!
//! The **per-subject report** shows the recording facts (duration, rate, alignment, outlier
//! replacement, clipping, gaps), the strides used and excluded with their reasons, the 12
//! parameters (+PBI) per side beside a healthy reference range ([`reference`]), values outside
//! it marked, the side-to-side symmetry index (Robinson et al. 1987), the signal figures of the
//! paper (Fig. 3: preprocessed acceleration and angular velocity; Fig. 4: attitude with HS/TO
//! marks and stance shading) from a [`trace::SubjectTraces`], stride-by-stride parameters, a
//! radar chart of the subject's z-scores, and — given a model — the classifier's output worded
//! as decision support. A side that failed is named with its error; the rest still renders.
//!
//! The **cohort report** has Table 3 (group statistics), Table 4 (model comparison) when an
//! `ldh stats --compare acc` output is given, the radar and box plots (Figs. 5–7), the
//! cross-validation results (Tables 6–7) and confusion matrices when an `ldh train` output is
//! given, and the list of recordings with their status.
//!
//! The HTML is written by hand with `format!`: the pages are a few fixed sections, and a
//! template engine would add a build dependency without removing any logic. All text from
//! files (ids, paths, error messages) goes through [`esc`].

pub mod reference;
pub mod trace;

use serde::{Deserialize, Serialize};

use crate::cohort::{self, value, ModelOffsets, PARAMETERS};
use crate::error::{LdhError, Result};
use crate::ml::{CvKind, CvReport, Prediction};
use crate::output::{RecordingRow, StrideRow};
use crate::plots::{self, EventMarks, Panel};
pub use reference::{Reference, ReferenceRange, ReferenceSource};
pub use trace::{LegTrace, SubjectTraces, TraceParams, ValidTraceParams};

/// Parameters of the reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReportParams {
    /// Healthy subjects a cohort needs before its own reference range is used (else published
    /// values). Default 10.
    pub min_healthy_subjects: usize,
    /// Half-width of the reference range in SDs (mean ± z·SD). Default 1.96 (95 % of a normal
    /// healthy population).
    pub reference_z: f64,
    /// |symmetry index| above which a parameter is flagged, %. Default 10 %.
    pub asymmetry_flag_pct: f64,
    /// The plotted signal window.
    pub trace: TraceParams,
}

impl Default for ReportParams {
    fn default() -> Self {
        ReportParams {
            min_healthy_subjects: 10,
            reference_z: 1.96,
            asymmetry_flag_pct: 10.0,
            trace: TraceParams::default(),
        }
    }
}

impl ReportParams {
    /// Set [`ReportParams::min_healthy_subjects`].
    pub fn min_healthy_subjects(mut self, v: usize) -> Self {
        self.min_healthy_subjects = v;
        self
    }
    /// Validate.
    pub fn check(&self) -> Result<ValidReportParams> {
        if self.min_healthy_subjects < 3 {
            return Err(LdhError::param(
                "min_healthy_subjects",
                self.min_healthy_subjects,
                "must be at least 3 (an SD from fewer subjects is meaningless)",
            ));
        }
        if !(self.reference_z.is_finite() && self.reference_z > 0.0) {
            return Err(LdhError::param(
                "reference_z",
                self.reference_z,
                "must be > 0",
            ));
        }
        if !(self.asymmetry_flag_pct.is_finite() && self.asymmetry_flag_pct > 0.0) {
            return Err(LdhError::param(
                "asymmetry_flag_pct",
                self.asymmetry_flag_pct,
                "must be > 0",
            ));
        }
        Ok(ValidReportParams(self.clone(), self.trace.check()?))
    }
}

/// Checked [`ReportParams`] (with the checked trace window).
#[derive(Debug, Clone, PartialEq)]
pub struct ValidReportParams(pub(crate) ReportParams, pub(crate) ValidTraceParams);

impl ValidReportParams {
    /// The checked trace window.
    pub fn trace(&self) -> &ValidTraceParams {
        &self.1
    }
}

/// A file name for a subject's report and trace: see [`crate::output::names`] (sanitised and,
/// when the id had to change, disambiguated by a stable suffix).
pub use crate::output::names::file_stem;

/// Escape text for HTML and XML (the five predefined entities).
pub fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            c if (c as u32) < 0x20 && c != '\n' && c != '\t' => o.push(' '),
            c => o.push(c),
        }
    }
    o
}

const CSS: &str = r#"
body { font-family: "DejaVu Sans", Arial, Helvetica, sans-serif; color: #111; margin: 24px auto; max-width: 860px; line-height: 1.35; font-size: 14px; }
h1 { font-size: 22px; margin: 0 0 4px 0; } h2 { font-size: 17px; border-bottom: 1px solid #999; margin-top: 22px; padding-bottom: 2px; } h3 { font-size: 15px; margin: 14px 0 6px; }
table { border-collapse: collapse; margin: 6px 0 10px; width: 100%; font-size: 12.5px; }
th, td { border: 1px solid #bbb; padding: 3px 5px; text-align: left; vertical-align: top; }
th { background: #eee; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
.out { background: #fde2e2; font-weight: bold; } .flag { background: #fff1c2; }
.note { background: #f3f3f3; border-left: 4px solid #888; padding: 6px 10px; margin: 8px 0; }
.missing { background: #fde2e2; border-left: 4px solid #c00; padding: 6px 10px; margin: 8px 0; }
.support { background: #e8f0fe; border-left: 4px solid #1a56c4; padding: 6px 10px; margin: 8px 0; }
.meta { color: #444; font-size: 12.5px; }
figure { margin: 10px 0; page-break-inside: avoid; break-inside: avoid; }
figure svg { width: 100%; height: auto; display: block; }
figcaption { font-size: 12px; color: #333; margin-top: 3px; }
ol.refs { font-size: 11.5px; }
@page { size: A4; margin: 14mm; }
@media print { body { margin: 0; max-width: none; font-size: 11pt; } h2 { page-break-after: avoid; break-after: avoid; } table, .note, .missing, .support { page-break-inside: avoid; break-inside: avoid; } .out, .flag, th { -webkit-print-color-adjust: exact; print-color-adjust: exact; } }
"#;

fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<meta name=\"generator\" content=\"ldh {}\"/>\n<title>{}</title>\n<style>{CSS}</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        env!("CARGO_PKG_VERSION"),
        esc(title)
    )
}

/// A figure: the SVG inline, its caption, and the axis labels it draws (each with its unit), so
/// a checker can verify them (`data-axis-labels`, separated by `|`).
fn figure(svg: &str, caption: &str, axis_labels: &[&str]) -> String {
    let svg = svg
        .trim_start_matches("<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        .trim();
    format!(
        "<figure class=\"plot\" data-axis-labels=\"{}\">\n{svg}\n<figcaption>{}</figcaption>\n</figure>\n",
        esc(&axis_labels.join("|")),
        esc(caption)
    )
}

fn fmt(v: Option<f64>, dec: usize) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:.dec$}"),
        _ => "–".into(),
    }
}

fn decimals(unit: &str) -> usize {
    match unit {
        "deg" => 1,
        "1/s" => 3,
        _ => 3,
    }
}

/// Everything the per-subject report shows.
#[derive(Debug, Clone, Default)]
pub struct SubjectReport {
    /// Subject.
    pub subject_id: String,
    /// The subject's per-recording rows (left and right, failed ones with their error).
    pub recordings: Vec<RecordingRow>,
    /// The subject's strides.
    pub strides: Vec<StrideRow>,
    /// Signal excerpts, when `ldh analyze --report` kept them.
    pub traces: Option<SubjectTraces>,
    /// Classifier output per side, with the model's class names and a description.
    pub predictions: Option<(Vec<Prediction>, Vec<String>, String)>,
}

/// The symmetry index of two values, % (Robinson et al. 1987): 100·(L − R) / ((L + R) / 2).
pub fn symmetry_index_pct(left: f64, right: f64) -> Option<f64> {
    let m = 0.5 * (left + right);
    (left.is_finite() && right.is_finite() && m.abs() > 1e-12).then(|| 100.0 * (left - right) / m)
}

fn side_label(r: &RecordingRow) -> String {
    match r.side_role.as_str() {
        "" | "healthy" => r.side.clone(),
        role => format!("{} ({role})", r.side),
    }
}

/// The per-subject report as an HTML page.
pub fn subject_html(
    s: &SubjectReport,
    reference: &Reference,
    p: &ValidReportParams,
) -> Result<String> {
    let mut b = String::new();
    let mut refs_used: Vec<String> = Vec::new();
    let sides: Vec<&RecordingRow> = ["left", "right"]
        .iter()
        .filter_map(|side| s.recordings.iter().find(|r| r.side == *side))
        .collect();
    let group = sides
        .iter()
        .map(|r| r.group.as_str())
        .find(|g| !g.is_empty())
        .unwrap_or("");
    let model = sides.first().map(|r| r.model.as_str()).unwrap_or("");
    b.push_str(&format!(
        "<h1>Gait report: subject {}</h1>\n<p class=\"meta\">Two shank-worn IMUs; attitude model <b>{}</b>{}. Generated by ldh {}. Times are seconds from each recording's first sample.</p>\n",
        esc(&s.subject_id),
        esc(model),
        if group.is_empty() {
            String::new()
        } else {
            format!(
                "; group in the manifest: <b>{}</b>{}",
                esc(group),
                sides
                    .iter()
                    .map(|r| r.affected_side.as_str())
                    .find(|a| !a.is_empty() && *a != "none")
                    .map(|a| format!(", affected side <b>{}</b>", esc(a)))
                    .unwrap_or_default()
            )
        },
        env!("CARGO_PKG_VERSION")
    ));
    // What is missing.
    let mut missing: Vec<String> = Vec::new();
    for side in ["left", "right"] {
        match s.recordings.iter().find(|r| r.side == side) {
            None => missing.push(format!("No {side} recording was given.")),
            Some(r) if r.status != "ok" => missing.push(format!(
                "The {side} recording could not be analysed: {}",
                r.error
            )),
            _ => {}
        }
    }
    if s.traces.is_none() {
        missing.push("Signal plots are not available: this report was built from result tables without signal traces (run `ldh analyze --report` to include them).".into());
    }
    let warned: Vec<&&RecordingRow> = sides.iter().filter(|r| !r.warnings.is_empty()).collect();
    if !warned.is_empty() {
        b.push_str("<div class=\"missing\"><b>Check before reading the numbers.</b><ul>");
        for r in warned {
            for w in r.warnings.split("; ") {
                b.push_str(&format!("<li>{}: {}</li>", esc(&r.side), esc(w)));
            }
        }
        b.push_str("</ul></div>\n");
    }
    if !missing.is_empty() {
        b.push_str("<div class=\"missing\"><b>Missing from this report.</b><ul>");
        for m in &missing {
            b.push_str(&format!("<li>{}</li>", esc(m)));
        }
        b.push_str("</ul></div>\n");
    }

    // 1. Recordings.
    b.push_str("<h2>1. Recordings</h2>\n<table>\n<tr><th>fact</th>");
    for r in &sides {
        b.push_str(&format!("<th>{}</th>", esc(&side_label(r))));
    }
    b.push_str("</tr>\n");
    let fact = |name: &str, f: &dyn Fn(&RecordingRow) -> String| {
        let mut row = format!("<tr><td>{}</td>", esc(name));
        for r in &sides {
            row.push_str(&format!("<td>{}</td>", esc(&f(r))));
        }
        row.push_str("</tr>\n");
        row
    };
    b.push_str(&fact("file", &|r| r.source.clone()));
    b.push_str(&fact("status", &|r| {
        if r.status == "ok" {
            "analysed".into()
        } else {
            format!("failed: {}", r.error)
        }
    }));
    b.push_str(&fact("warnings", &|r| {
        if r.warnings.is_empty() {
            "none".into()
        } else {
            r.warnings.clone()
        }
    }));
    b.push_str(&fact("duration (s)", &|r| fmt(r.duration_s, 1)));
    b.push_str(&fact("sampling rate (Hz)", &|r| fmt(r.fs_hz, 2)));
    b.push_str(&fact("samples replaced as outliers (3 SD of |a|)", &|r| {
        r.outliers_replaced
            .map(|v| v.to_string())
            .unwrap_or("–".into())
    }));
    b.push_str(&fact("clipped samples", &|r| {
        r.clipped_samples
            .map(|v| v.to_string())
            .unwrap_or("–".into())
    }));
    b.push_str(&fact(
        "mounting",
        &|r| match (r.mirrored, r.axial_rotation_deg) {
            (Some(m), Some(a)) => format!(
                "{}; rotated {a:.0}° about the shank",
                if m {
                    "mirrored (y axis backwards)"
                } else {
                    "y axis forwards"
                }
            ),
            _ => "–".into(),
        },
    ));
    b.push_str(&fact(
        "strides detected / used",
        &|r| match (r.strides_total, r.strides_valid) {
            (Some(t), Some(v)) => format!("{t} / {v}"),
            _ => "–".into(),
        },
    ));
    b.push_str(&fact("STA", &|r| {
        if r.sta_status.is_empty() {
            "computed".into()
        } else {
            format!("not computed: {}", r.sta_status)
        }
    }));
    b.push_str("</table>\n");
    if let Some(t) = &s.traces {
        for leg in &t.legs {
            let mut notes: Vec<String> = leg.alignment_notes.clone();
            notes.extend(leg.read_notes.iter().cloned());
            for (from, len) in &leg.gaps_s {
                notes.push(format!(
                    "gap of {len:.2} s after t = {from:.2} s (file clock)"
                ));
            }
            if !notes.is_empty() {
                b.push_str(&format!(
                    "<p class=\"note\"><b>{} — what reading and alignment found:</b> {}</p>\n",
                    esc(&leg.side),
                    notes.iter().map(|n| esc(n)).collect::<Vec<_>>().join(" · ")
                ));
            }
        }
    }
    // Strides excluded, with reasons.
    let mut excl: Vec<(String, String, usize)> = Vec::new();
    for st in s.strides.iter().filter(|st| !st.valid) {
        let reason = if st.reason.is_empty() {
            "excluded".to_string()
        } else {
            st.reason.clone()
        };
        match excl.iter_mut().find(|e| e.0 == st.side && e.1 == reason) {
            Some(e) => e.2 += 1,
            None => excl.push((st.side.clone(), reason, 1)),
        }
    }
    if excl.is_empty() {
        b.push_str("<p>No stride was excluded.</p>\n");
    } else {
        b.push_str("<h3>Strides excluded from the parameters</h3>\n<table><tr><th>side</th><th>reason</th><th>strides</th></tr>\n");
        for (side, reason, n) in &excl {
            b.push_str(&format!(
                "<tr><td>{}</td><td>{}</td><td class=\"num\">{n}</td></tr>\n",
                esc(side),
                esc(reason)
            ));
        }
        b.push_str("</table>\n");
    }

    // 2. Parameters.
    b.push_str("<h2>2. Gait parameters</h2>\n");
    b.push_str(&format!(
        "<p class=\"meta\">Reference: {} Values outside the reference range are marked ▲ (above) or ▼ (below) and shaded. Symmetry index SI = 100·(L − R)/((L + R)/2) %; |SI| &gt; {:.0} % is shaded.</p>\n",
        esc(&reference.description),
        p.0.asymmetry_flag_pct
    ));
    b.push_str("<table>\n<tr><th>parameter</th><th>unit</th>");
    for r in &sides {
        b.push_str(&format!("<th>{}</th>", esc(&side_label(r))));
    }
    b.push_str("<th>reference range</th><th>SI (%)</th></tr>\n");
    let left = sides.iter().find(|r| r.side == "left" && r.status == "ok");
    let right = sides.iter().find(|r| r.side == "right" && r.status == "ok");
    let mut out_of_range = 0usize;
    for par in PARAMETERS.iter() {
        let rr = reference.ranges.iter().find(|r| r.column == par.column);
        let dec = decimals(par.unit);
        b.push_str(&format!(
            "<tr><td>{} — {}</td><td>{}</td>",
            par.code,
            esc(par.name),
            esc(par.unit)
        ));
        for r in &sides {
            let v = if r.status == "ok" {
                value(r, par.column)
            } else {
                None
            };
            let out = match (v, rr) {
                (Some(v), Some(rr)) => rr.outside(v).filter(|o| *o).map(|_| {
                    if rr.low.is_some_and(|l| v < l) {
                        "▼"
                    } else {
                        "▲"
                    }
                }),
                _ => None,
            };
            if out.is_some() {
                out_of_range += 1;
            }
            b.push_str(&format!(
                "<td class=\"num{}\">{}{}</td>",
                if out.is_some() { " out" } else { "" },
                fmt(v, dec),
                out.map(|m| format!(" {m}")).unwrap_or_default()
            ));
        }
        let range = match rr {
            Some(ReferenceRange {
                low: Some(l),
                high: Some(h),
                source,
                ..
            }) => {
                let src = match source {
                    ReferenceSource::Cohort { n_subjects } => {
                        format!("cohort healthy, n = {n_subjects}")
                    }
                    ReferenceSource::Published(c) => {
                        if !refs_used.contains(c) {
                            refs_used.push(c.clone());
                        }
                        let k = refs_used.iter().position(|x| x == c).unwrap_or(0) + 1;
                        format!("published [{k}]")
                    }
                    ReferenceSource::None => String::new(),
                };
                format!("{}–{} ({src})", fmt(Some(*l), dec), fmt(Some(*h), dec))
            }
            _ => "no reference".into(),
        };
        b.push_str(&format!("<td>{}</td>", esc(&range)));
        let si = match (left, right) {
            (Some(l), Some(r)) => match (value(l, par.column), value(r, par.column)) {
                (Some(a), Some(c)) => symmetry_index_pct(a, c),
                _ => None,
            },
            _ => None,
        };
        let flag = si.is_some_and(|v| v.abs() > p.0.asymmetry_flag_pct);
        b.push_str(&format!(
            "<td class=\"num{}\">{}</td></tr>\n",
            if flag { " flag" } else { "" },
            si.map(|v| format!("{v:+.1}")).unwrap_or("–".into())
        ));
    }
    b.push_str("</table>\n");
    b.push_str(&format!(
        "<p>{out_of_range} value(s) lie outside the reference range.</p>\n"
    ));
    // Radar of z-scores.
    let codes: Vec<(String, &ReferenceRange)> = reference
        .ranges
        .iter()
        .filter(|r| r.sd.is_some())
        .map(|r| (r.code.clone(), r))
        .collect();
    let series: Vec<(String, Vec<f64>)> = sides
        .iter()
        .filter(|r| r.status == "ok")
        .map(|r| {
            (
                side_label(r),
                codes
                    .iter()
                    .map(|(_, rr)| value(r, &rr.column).and_then(|v| rr.z(v)).unwrap_or(0.0))
                    .collect(),
            )
        })
        .collect();
    if !series.is_empty() && codes.len() >= 3 {
        let names: Vec<String> = codes.iter().map(|c| c.0.clone()).collect();
        let svg = plots::radar_svg(
            &format!(
                "Subject {}: z-scores against the healthy reference",
                s.subject_id
            ),
            &names,
            &series,
        )?;
        b.push_str(&figure(
            &svg,
            "Radar chart of the subject's parameters as z-scores against the healthy reference (0 = the healthy mean, the black ring). A missing value is drawn at 0.",
            &[plots::RADAR_SCALE_LABEL],
        ));
    }

    // 3. Signals.
    b.push_str("<h2>3. Signals</h2>\n");
    match &s.traces {
        None => b.push_str("<p class=\"note\">No signal traces for this subject (see above).</p>\n"),
        Some(t) if t.legs.is_empty() => b.push_str(
            "<p class=\"note\">No leg of this subject was analysed, so there are no signals to show.</p>\n",
        ),
        Some(t) => {
            for leg in &t.legs {
                let n = leg.pitch_deg.len();
                let secs = n as f64 / leg.fs_hz;
                let axes = ["anterior (x)", "left (y)", "up (z)"];
                let acc = Panel {
                    y_label: "acceleration (g)".into(),
                    series: axes
                        .iter()
                        .zip(&leg.acc_g)
                        .map(|(a, v)| (a.to_string(), v.clone()))
                        .collect(),
                };
                let gyro = Panel {
                    y_label: "angular velocity (deg/s)".into(),
                    series: ["about anterior", "about left (sagittal)", "about up"]
                        .iter()
                        .zip(&leg.gyro_dps)
                        .map(|(a, v)| (a.to_string(), v.clone()))
                        .collect(),
                };
                let svg = plots::signals_svg(
                    &format!("{} shank: preprocessed signals ({secs:.0} s)", leg.side),
                    leg.start_s,
                    leg.fs_hz,
                    &[acc, gyro],
                    None,
                )?;
                b.push_str(&figure(
                    &svg,
                    &format!("Fig. 3 — {} leg: filtered acceleration and angular velocity in the shank frame (after alignment and outlier replacement).", leg.side),
                    &["time (s)", "acceleration (g)", "angular velocity (deg/s)"],
                ));
                let marks = EventMarks {
                    hs_s: leg.hs_s.clone(),
                    to_s: leg.to_s.clone(),
                    stance_s: leg.stance_s.clone(),
                };
                let att = Panel {
                    y_label: "angle (deg)".into(),
                    series: vec![
                        ("pitch (sagittal)".into(), leg.pitch_deg.clone()),
                        ("roll".into(), leg.roll_deg.clone()),
                    ],
                };
                let svg = plots::signals_svg(
                    &format!("{} shank: attitude with gait events", leg.side),
                    leg.start_s,
                    leg.fs_hz,
                    &[att],
                    Some(&marks),
                )?;
                b.push_str(&figure(
                    &svg,
                    &format!("Fig. 4 — {} leg: shank attitude; red lines heel strikes (HS), blue lines toe offs (TO), grey bands stance (HS to TO).", leg.side),
                    &["time (s)", "angle (deg)"],
                ));
            }
        }
    }

    // 4. Stride by stride.
    b.push_str("<h2>4. Stride by stride</h2>\n");
    if s.strides.is_empty() {
        b.push_str("<p class=\"note\">No strides were detected.</p>\n");
    } else {
        let per: [(&str, &str, fn(&StrideRow) -> Option<f64>); 4] = [
            ("stride time", "stride time (s)", |r| r.stride_time_s),
            ("stance phase", "stance ratio (fraction of stride)", |r| {
                r.stance_ratio
            }),
            ("stride length", "stride length (m)", |r| r.stride_length_m),
            ("shank swing angle (WQK)", "WQK (deg)", |r| r.wqk_deg),
        ];
        for (title, ylab, get) in per {
            let series: Vec<(String, Vec<(f64, f64, bool)>)> = ["left", "right"]
                .iter()
                .map(|side| {
                    (
                        side.to_string(),
                        s.strides
                            .iter()
                            .filter(|r| r.side == *side)
                            .filter_map(|r| Some((r.hs_time_s?, get(r)?, r.valid)))
                            .collect(),
                    )
                })
                .collect();
            if series.iter().all(|x| x.1.is_empty()) {
                continue;
            }
            let svg = plots::stride_series_svg(title, ylab, &series)?;
            b.push_str(&figure(
                &svg,
                &format!("{title} per stride; filled circles strides used, hollow circles strides excluded."),
                &["heel-strike time (s)", ylab],
            ));
        }
    }

    // 5. Classifier.
    if let Some((preds, classes, desc)) = &s.predictions {
        b.push_str("<h2>5. Classifier output (decision support)</h2>\n");
        b.push_str(&format!(
            "<p class=\"support\"><b>Decision support, not a diagnosis.</b> A statistical model ({}) compares this subject's gait parameters with those of the people it was trained on. Its output is one piece of evidence for the clinician, who weighs it with the examination and imaging; it can be wrong, especially for people unlike the training cohort.</p>\n",
            esc(desc)
        ));
        b.push_str("<table><tr><th>side</th><th>most similar class</th>");
        for c in classes {
            b.push_str(&format!("<th>p({})</th>", esc(c)));
        }
        b.push_str("<th>note</th></tr>\n");
        for pr in preds {
            b.push_str(&format!(
                "<tr><td>{}</td><td>{}</td>",
                esc(&pr.side),
                esc(pr.predicted_class.as_deref().unwrap_or("no output"))
            ));
            for k in 0..classes.len() {
                b.push_str(&format!(
                    "<td class=\"num\">{}</td>",
                    pr.probabilities
                        .as_ref()
                        .and_then(|v| v.get(k))
                        .map(|x| format!("{x:.2}"))
                        .unwrap_or("–".into())
                ));
            }
            b.push_str(&format!("<td>{}</td></tr>\n", esc(&pr.note)));
        }
        b.push_str("</table>\n");
    }

    // Methods and references.
    b.push_str("<h2>Methods</h2>\n<p class=\"meta\">Accelerometer and gyroscope are low-pass filtered (4th-order Butterworth, zero phase) after 3-SD outliers of |a| are replaced; the attitude is estimated with an adaptive Kalman filter bank with smoothing (Wang et al.); heel strikes and toe offs come from the sagittal angular velocity; stride length from the integrated shank motion with an ankle lever-arm correction; STA is the largest Lyapunov exponent of the sagittal angular velocity (Rosenstein). Parameters are means over the valid strides.</p>\n");
    if !refs_used.is_empty() {
        b.push_str("<h3>References for the published ranges</h3>\n<ol class=\"refs\">");
        for r in &refs_used {
            b.push_str(&format!("<li>{}</li>", esc(r)));
        }
        b.push_str("</ol>\n");
    }
    Ok(page(&format!("Gait report — {}", s.subject_id), &b))
}

/// What the cohort report shows.
#[derive(Debug, Clone, Default)]
pub struct CohortReport {
    /// Per-recording rows of the analysis (one attitude model).
    pub recordings: Vec<RecordingRow>,
    /// Table 4 offsets per model, from `ldh stats --compare acc` (`table4.json`).
    pub offsets: Vec<ModelOffsets>,
    /// Cross-validation results from `ldh train` (`cv_results.json`).
    pub cv: Vec<CvReport>,
    /// Links to the per-subject reports (subject, relative href).
    pub subject_links: Vec<(String, String)>,
}

/// The cohort report as an HTML page.
pub fn cohort_html(c: &CohortReport) -> Result<String> {
    let mut b = String::new();
    let mut subjects: Vec<&str> = c.recordings.iter().map(|r| r.subject_id.as_str()).collect();
    subjects.sort_unstable();
    subjects.dedup();
    let failed: Vec<&RecordingRow> = c.recordings.iter().filter(|r| r.status != "ok").collect();
    let model = c.recordings.first().map(|r| r.model.as_str()).unwrap_or("");
    b.push_str(&format!(
        "<h1>Cohort gait report</h1>\n<p class=\"meta\">{} subjects, {} recordings ({} analysed, {} failed); attitude model <b>{}</b>. Generated by ldh {}.</p>\n",
        subjects.len(),
        c.recordings.len(),
        c.recordings.len() - failed.len(),
        failed.len(),
        esc(model),
        env!("CARGO_PKG_VERSION")
    ));
    if !failed.is_empty() {
        b.push_str("<div class=\"missing\"><b>Recordings that could not be analysed</b> (their subjects are left out of the group statistics):<ul>");
        for f in &failed {
            b.push_str(&format!(
                "<li>{} {}: {}</li>",
                esc(&f.subject_id),
                esc(&f.side),
                esc(&f.error)
            ));
        }
        b.push_str("</ul></div>\n");
    }
    // Table 3.
    b.push_str("<h2>1. Group statistics (Table 3)</h2>\n");
    match cohort::Cohort::from_rows(&c.recordings) {
        Err(e) => b.push_str(&format!(
            "<p class=\"note\">No group statistics: {}</p>\n",
            esc(&e.to_string())
        )),
        Ok(co) => {
            let t3 = cohort::table3(&co);
            b.push_str(&format!(
                "<p class=\"meta\">LDH n = {}, healthy n = {}. Mean (± SD). p-values with the Holm-adjusted value in brackets. LDHH: unaffected side, LDHE: affected side, H: healthy (mean of both legs). HE is the paired comparison of the two LDH sides (the paper's independent test beside it), H-H is LDHH vs H, E-H is LDHE vs H, LR is healthy left vs right.</p>\n",
                co.ldh.len(),
                co.healthy.len()
            ));
            b.push_str("<table><tr><th>feature</th><th>unit</th><th>LDHH</th><th>LDHE</th><th>H</th><th>HE (paired)</th><th>HE (indep.)</th><th>H-H</th><th>E-H</th><th>LR</th><th>ANOVA</th></tr>\n");
            for r in &t3 {
                let t = |x: &cohort::TestResult| {
                    format!("{} ({})", cohort::fmt_p(x.p), cohort::fmt_p(x.p_holm))
                };
                b.push_str(&format!(
                    "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
                    esc(&r.code),
                    esc(&r.unit),
                    esc(&cohort::fmt_ms(&r.ldhh)),
                    esc(&cohort::fmt_ms(&r.ldhe)),
                    esc(&cohort::fmt_ms(&r.h)),
                    esc(&t(&r.he_paired)),
                    esc(&t(&r.he_independent)),
                    esc(&t(&r.hh)),
                    esc(&t(&r.eh)),
                    esc(&t(&r.lr)),
                    esc(&t(&r.anova)),
                ));
            }
            b.push_str("</table>\n");
            if !co.excluded.is_empty() {
                b.push_str(&format!(
                    "<p class=\"meta\">Left out: {}.</p>\n",
                    esc(&co.excluded.join("; "))
                ));
            }
            // Table 4 and radar.
            let mut offs = c.offsets.clone();
            if offs.is_empty() {
                offs.push(cohort::offsets(&co));
            }
            b.push_str("<h2>2. Offsets from the healthy baseline (Table 4)</h2>\n<table><tr><th>model</th><th>OFF0 (LDHH)</th><th>OFF1 (LDHE)</th></tr>\n");
            for o in &offs {
                b.push_str(&format!(
                    "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
                    esc(&o.model),
                    fmt(Some(o.off0), 2),
                    fmt(Some(o.off1), 2)
                ));
            }
            b.push_str("</table>\n");
            if c.offsets.len() < 2 {
                b.push_str("<p class=\"meta\">The ACC-only comparison appears here when the report is given the output of <code>ldh stats --compare acc</code>.</p>\n");
            }
            for o in &offs {
                if o.codes.len() < 3 {
                    continue;
                }
                let svg = plots::radar_svg(
                    &format!("Gait parameters, {} model (z vs healthy)", o.model),
                    &o.codes,
                    &[
                        ("LDHH".to_string(), o.z_ldhh.clone()),
                        ("LDHE".to_string(), o.z_ldhe.clone()),
                        ("H".to_string(), o.z_h.clone()),
                    ],
                )?;
                b.push_str(&figure(
                    &svg,
                    &format!("Figs. 5–6 — mean z-scores per group, {} model: LDHH unaffected side, LDHE affected side, H healthy baseline.", o.model),
                    &[plots::RADAR_SCALE_LABEL],
                ));
            }
            // Box plots.
            b.push_str("<h2>3. Distributions (Fig. 7)</h2>\n");
            for par in PARAMETERS {
                let g = co.groups(par.column);
                if g.h.is_empty() {
                    continue;
                }
                let ylab = format!("{} ({})", par.name, par.unit);
                let svg = plots::boxplot_svg(
                    &format!("{} — {}", par.code, par.name),
                    &ylab,
                    &[
                        ("LDHH".into(), g.ldhh),
                        ("LDHE".into(), g.ldhe),
                        ("H".into(), g.h),
                    ],
                )?;
                b.push_str(&figure(
                    &svg,
                    &format!("{}: box = quartiles, whiskers 1.5 IQR.", par.name),
                    &[plots::BOX_GROUP_LABEL, &ylab],
                ));
            }
        }
    }
    // Classifiers.
    b.push_str("<h2>4. Classifiers (Tables 6–7)</h2>\n");
    if c.cv.is_empty() {
        b.push_str("<p class=\"note\">No classifier results: give the output folder of <code>ldh train</code> to include them.</p>\n");
    } else {
        b.push_str("<p class=\"meta\">Cross-validated accuracy, macro precision, recall and F1 (mean ± SD over repeats). Subject-grouped folds are the honest estimate; stratified folds (the paper's) let one side of a subject train the model that tests the other.</p>\n<table><tr><th>classifier</th><th>folds</th><th>accuracy</th><th>precision</th><th>recall</th><th>F1</th></tr>\n");
        for r in &c.cv {
            let ms = |m: &crate::ml::cv::MeanSd| format!("{:.3} ± {:.3}", m.mean, m.sd);
            b.push_str(&format!(
                "<tr><td>{}</td><td>{} {}-fold × {}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
                esc(&r.classifier),
                r.kind.as_str(),
                r.k,
                r.repeats,
                ms(&r.accuracy),
                ms(&r.precision_macro),
                ms(&r.recall_macro),
                ms(&r.f1_macro)
            ));
        }
        b.push_str("</table>\n");
        for r in c.cv.iter().filter(|r| r.kind == CvKind::Grouped) {
            let svg = plots::confusion_svg(
                &format!("{} — grouped {}-fold × {}", r.classifier, r.k, r.repeats),
                &r.class_names,
                &r.confusion,
            )?;
            b.push_str(&figure(
                &svg,
                &format!(
                    "Confusion matrix of {} (subject-grouped CV, summed over repeats).",
                    r.classifier
                ),
                &plots::CONFUSION_LABELS,
            ));
        }
    }
    // Recordings.
    b.push_str("<h2>5. Recordings</h2>\n<table><tr><th>subject</th><th>group</th><th>side</th><th>status</th><th>strides used</th><th>duration (s)</th><th>warnings</th></tr>\n");
    let links: std::collections::HashMap<&str, &str> = c
        .subject_links
        .iter()
        .map(|(id, href)| (id.as_str(), href.as_str()))
        .collect();
    for r in &c.recordings {
        let link = links
            .get(r.subject_id.as_str())
            .map(|href| (r.subject_id.as_str(), *href))
            .map(|l| format!("<a href=\"{}\">{}</a>", esc(&l.1), esc(&r.subject_id)))
            .unwrap_or_else(|| esc(&r.subject_id));
        b.push_str(&format!(
            "<tr><td>{link}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td></tr>\n",
            esc(&r.group),
            esc(&side_label(r)),
            esc(if r.status == "ok" { "analysed" } else { &r.error }),
            r.strides_valid.map(|v| v.to_string()).unwrap_or("–".into()),
            fmt(r.duration_s, 1),
            esc(&r.warnings)
        ));
    }
    b.push_str("</table>\n");
    Ok(page("Cohort gait report", &b))
}

#[cfg(test)]
mod tests;
