//! Accuracy of the pipeline against the simulator's ground truth (`ldh evaluate`).
//!
//! Scored on the truth's steady strides (not turning, not the first or last of the walk): each
//! true HS and TO is matched to the nearest detected one within 250 ms (otherwise it is
//! missed); a true stride is matched to the detected stride starting at the matched HS.
//! Stride length is scored on the reported lengths only (valid strides with a length); the
//! strides whose length was withheld are counted, and so are reported lengths more than 15 %
//! off (a clinical tool may withhold, never report a wrong number).
//! Each steady stride's scores are also available one by one ([`stride_scores`],
//! `ldh evaluate --strides-csv`); the figures here are aggregated from them.
//! Attitude errors are RMS over the whole recording, pitch against the true shank pitch θ and
//! roll against the true anatomical roll. Like stride length, they are scored on the legs whose
//! angles the pipeline reports: a leg whose angle parameters a quality check withheld (the
//! attitude health checks, a clipped gyroscope) is counted, not scored; the mean over all legs
//! is given beside it, so a runaway that was withheld stays visible.

use serde::{Deserialize, Serialize};

mod strides;
mod truth_reference;
pub use strides::{stride_scores, write_stride_scores, StrideScore, MATCH_WINDOW_S};
pub use truth_reference::{
    truth_reference, write_cohort_reference, write_truth_reference, TruthScope,
};

use crate::SubjectTruth;
use ldh_core::gait::anatomical_roll_deg;
use ldh_core::pipeline::SubjectResult;

/// Accuracy figures for one model over a cohort.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Accuracy {
    /// Attitude model.
    pub model: String,
    /// Recordings scored.
    pub recordings: usize,
    /// Steady true strides scored.
    pub strides: usize,
    /// HS mean absolute error, ms.
    pub hs_mae_ms: f64,
    /// HS 95th percentile of the absolute error, ms.
    pub hs_p95_ms: f64,
    /// HS mean signed error (detected − true), ms.
    pub hs_bias_ms: f64,
    /// TO mean absolute error, ms.
    pub to_mae_ms: f64,
    /// TO 95th percentile, ms.
    pub to_p95_ms: f64,
    /// TO mean signed error, ms.
    pub to_bias_ms: f64,
    /// True steady HS or TO without a detection within 250 ms.
    pub missed_events: usize,
    /// Stride time mean absolute error, ms.
    pub stride_time_mae_ms: f64,
    /// Stance ratio mean absolute error.
    pub stance_ratio_mae: f64,
    /// Stance ratio mean signed error (detected − true).
    pub stance_ratio_bias: f64,
    /// Stride length mean absolute error, % of the true length.
    pub stride_length_mae_pct: f64,
    /// Stride length mean signed error, %.
    pub stride_length_bias_pct: f64,
    /// Stride length SD of the signed error, %.
    pub stride_length_sd_pct: f64,
    /// Largest stride length error of a reported stride, %.
    #[serde(default)]
    pub stride_length_max_pct: f64,
    /// Reported stride lengths more than 15 % off.
    #[serde(default)]
    pub stride_length_over_15pct: usize,
    /// Matched steady strides whose length was withheld (or the stride invalid).
    #[serde(default)]
    pub stride_length_withheld: usize,
    /// Pitch RMSE (mean over the recordings whose angles are reported), deg.
    pub pitch_rmse_deg: f64,
    /// Roll RMSE (mean over the recordings whose angles are reported), deg.
    pub roll_rmse_deg: f64,
    /// Recordings whose angle parameters were withheld (not scored in `pitch_rmse_deg`).
    #[serde(default)]
    pub angles_withheld: usize,
    /// Pitch RMSE (mean over all recordings, withheld angles included), deg.
    #[serde(default)]
    pub pitch_rmse_all_deg: f64,
    /// Roll RMSE (mean over all recordings, withheld angles included), deg.
    #[serde(default)]
    pub roll_rmse_all_deg: f64,
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        f64::NAN
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

fn p95(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut a: Vec<f64> = v.iter().map(|x| x.abs()).collect();
    a.sort_by(|x, y| x.partial_cmp(y).unwrap_or(std::cmp::Ordering::Equal));
    a[((a.len() as f64 * 0.95).ceil() as usize).clamp(1, a.len()) - 1]
}

/// Score results against truths (matched by subject id); `results` may hold one model.
pub fn evaluate(results: &[SubjectResult], truths: &[SubjectTruth]) -> Accuracy {
    let mut hs = Vec::new();
    let mut to = Vec::new();
    let mut st = Vec::new();
    let mut stance = Vec::new();
    let mut sl = Vec::new();
    let mut pitch = Vec::new();
    let mut roll = Vec::new();
    let mut pitch_all = Vec::new();
    let mut roll_all = Vec::new();
    let mut angles_withheld = 0;
    let mut missed = 0;
    let mut withheld = 0;
    let mut recs = 0;
    let mut model = String::new();
    for r in results {
        model = r.model.as_str().to_string();
        let Some(t) = truths.iter().find(|t| t.subject_id == r.subject_id) else {
            continue;
        };
        for (leg, truth) in [(&r.left, &t.left), (&r.right, &t.right)] {
            let Ok(leg) = leg else { continue };
            recs += 1;
            for sc in strides::leg_scores(
                leg,
                truth,
                (r.model.as_str(), &t.subject_id, t.group.clone()),
            ) {
                add_score(&sc, &mut hs, &mut to, &mut missed);
                if sc.stride_index.is_some() {
                    st.extend(sc.stride_time_error_ms);
                    stance.extend(sc.stance_ratio_error);
                    match sc.stride_length_error_pct {
                        Some(e) => sl.push(e),
                        None => withheld += 1,
                    }
                }
            }
            if let Some(att) = &leg.attitude {
                let n = att.pitch_deg.len().min(truth.pitch_deg.len());
                let ep: f64 = (0..n)
                    .map(|i| (att.pitch_deg[i] - truth.pitch_deg[i]).powi(2))
                    .sum::<f64>()
                    / n as f64;
                let er: f64 = (0..n)
                    .map(|i| {
                        (anatomical_roll_deg(att.roll_deg[i], leg.side) - truth.roll_deg[i]).powi(2)
                    })
                    .sum::<f64>()
                    / n as f64;
                pitch_all.push(ep.sqrt());
                roll_all.push(er.sqrt());
                let withheld = ldh_core::pipeline::quality::params::ANGLES
                    .iter()
                    .any(|k| leg.parameters.withheld.contains(*k));
                if withheld {
                    angles_withheld += 1;
                } else {
                    pitch.push(ep.sqrt());
                    roll.push(er.sqrt());
                }
            }
        }
    }
    let sl_mean = mean(&sl);
    Accuracy {
        model,
        recordings: recs,
        strides: st.len(),
        hs_mae_ms: mean(&hs.iter().map(|x: &f64| x.abs()).collect::<Vec<_>>()),
        hs_p95_ms: p95(&hs),
        hs_bias_ms: mean(&hs),
        to_mae_ms: mean(&to.iter().map(|x: &f64| x.abs()).collect::<Vec<_>>()),
        to_p95_ms: p95(&to),
        to_bias_ms: mean(&to),
        missed_events: missed,
        stride_time_mae_ms: mean(&st.iter().map(|x: &f64| x.abs()).collect::<Vec<_>>()),
        stance_ratio_mae: mean(&stance.iter().map(|x: &f64| x.abs()).collect::<Vec<_>>()),
        stance_ratio_bias: mean(&stance),
        stride_length_mae_pct: mean(&sl.iter().map(|x: &f64| x.abs()).collect::<Vec<_>>()),
        stride_length_bias_pct: sl_mean,
        stride_length_sd_pct: if sl.len() > 1 {
            (sl.iter().map(|x| (x - sl_mean).powi(2)).sum::<f64>() / (sl.len() - 1) as f64).sqrt()
        } else {
            f64::NAN
        },
        stride_length_max_pct: sl.iter().fold(f64::NAN, |m, x| m.max(x.abs())),
        stride_length_over_15pct: sl.iter().filter(|x| x.abs() > 15.0).count(),
        stride_length_withheld: withheld,
        pitch_rmse_deg: mean(&pitch),
        roll_rmse_deg: mean(&roll),
        angles_withheld,
        pitch_rmse_all_deg: mean(&pitch_all),
        roll_rmse_all_deg: mean(&roll_all),
    }
}

/// A stride's event errors into the cohort's lists (a missed event counted).
fn add_score(sc: &strides::StrideScore, hs: &mut Vec<f64>, to: &mut Vec<f64>, missed: &mut usize) {
    for (e, list) in [(sc.hs_error_ms, hs), (sc.to_error_ms, to)] {
        match e {
            Some(e) => list.push(e),
            None => *missed += 1,
        }
    }
}

/// A Markdown table of accuracies side by side (one column per model).
pub fn markdown(acc: &[Accuracy]) -> String {
    let mut s = String::from("| metric |");
    for a in acc {
        s.push_str(&format!(" {} |", a.model));
    }
    s.push_str("\n|---|");
    for _ in acc {
        s.push_str("---:|");
    }
    s.push('\n');
    let rows: [AccuracyRow; 17] = [
        ("recordings / steady strides", |a| {
            format!("{} / {}", a.recordings, a.strides)
        }),
        ("HS MAE / P95 (ms)", |a| {
            format!("{:.1} / {:.1}", a.hs_mae_ms, a.hs_p95_ms)
        }),
        ("HS bias (ms)", |a| format!("{:+.1}", a.hs_bias_ms)),
        ("TO MAE / P95 (ms)", |a| {
            format!("{:.1} / {:.1}", a.to_mae_ms, a.to_p95_ms)
        }),
        ("TO bias (ms)", |a| format!("{:+.1}", a.to_bias_ms)),
        ("missed steady events", |a| a.missed_events.to_string()),
        ("stride time MAE (ms)", |a| {
            format!("{:.2}", a.stride_time_mae_ms)
        }),
        ("stance ratio MAE", |a| format!("{:.4}", a.stance_ratio_mae)),
        ("stance ratio bias", |a| {
            format!("{:+.4}", a.stance_ratio_bias)
        }),
        ("stride length MAE (%)", |a| {
            format!("{:.2}", a.stride_length_mae_pct)
        }),
        ("stride length bias ± SD (%)", |a| {
            format!(
                "{:+.2} ± {:.2}",
                a.stride_length_bias_pct, a.stride_length_sd_pct
            )
        }),
        ("stride length worst reported (%) / > 15 %", |a| {
            format!(
                "{:.1} / {}",
                a.stride_length_max_pct, a.stride_length_over_15pct
            )
        }),
        ("stride lengths withheld (of steady strides)", |a| {
            format!("{} / {}", a.stride_length_withheld, a.strides)
        }),
        ("pitch RMSE (deg), legs with angles reported", |a| {
            format!("{:.2}", a.pitch_rmse_deg)
        }),
        ("roll RMSE (deg), legs with angles reported", |a| {
            format!("{:.2}", a.roll_rmse_deg)
        }),
        ("legs with angles withheld (of recordings)", |a| {
            format!("{} / {}", a.angles_withheld, a.recordings)
        }),
        ("pitch / roll RMSE (deg), all legs", |a| {
            format!("{:.2} / {:.2}", a.pitch_rmse_all_deg, a.roll_rmse_all_deg)
        }),
    ];
    for (name, f) in rows.iter() {
        s.push_str(&format!("| {name} |"));
        for a in acc {
            // A metric over no reported value (e.g. ACC-only stride length, never reported).
            let cell = f(a);
            let cell = if cell.contains("NaN") {
                "— (none reported)".to_string()
            } else {
                cell
            };
            s.push_str(&format!(" {cell} |"));
        }
        s.push('\n');
    }
    s
}

/// A row of the accuracy table: its label and how to print it from an [`Accuracy`].
type AccuracyRow = (&'static str, fn(&Accuracy) -> String);
