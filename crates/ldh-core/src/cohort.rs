//! Cohort statistics (paper §3.4 and §4.1, Tables 3–4; SPEC §5): the gait parameters of the
//! LDH subjects' unaffected (LDHH) and affected (LDHE) sides against healthy subjects (H, the
//! mean of both legs), and healthy left vs right (LR).
//!
//! For each parameter: mean ± SD per group; Shapiro–Wilk per group; then
//! * **HE** (LDHH vs LDHE): the two sides of one subject are paired data, so the primary test
//!   is paired — paired t when the differences pass Shapiro–Wilk (p > 0.05), else Wilcoxon
//!   signed-rank — with the paper's independent test beside it;
//! * **H-H** (LDHH vs H) and **E-H** (LDHE vs H): independent — Student's t when both groups
//!   pass Shapiro–Wilk, else Mann–Whitney U (the paper's rule);
//! * **LR** (healthy left vs right): paired, as HE;
//! * one-way ANOVA and Kruskal–Wallis across LDHH, LDHE and H;
//! * Holm-adjusted p-values across the parameters, per comparison, beside the raw ones.
//!
//! A test that is undefined for the data (e.g. constant values) gives no p-value and a note.
//!
//! **Model comparison** (Table 4): every parameter is z-normalised with the healthy group's mean
//! and SD (eq. 18, healthy subjects as the baseline); OFF0 = mean over parameters of the
//! |mean z| of LDHH, OFF1 the same for LDHE (eq. 19). A larger offset separates LDH from
//! healthy gait better.
//!
//! **Test–retest reliability** (`ldh stats --reliability`): the reliability of every parameter
//! from a cohort's repeated trials ([`fn@reliability_table`], `cohort/retest.rs`), the table
//! `reliability.csv` ([`ReliabilityTable`], `cohort/reliability_table.rs`) and its statistics
//! ([`crate::stats::agreement::test_retest`]).

use serde::{Deserialize, Serialize};

use crate::attitude::AttitudeModel;
use crate::error::{LdhError, Result};
use crate::output::{AffectedSide, Label, RecordingRow};
use crate::pipeline::Group;
use crate::Side;

#[cfg(all(test, feature = "dummy-parameter"))]
mod dummy_parameter;
mod offsets;
mod outcome;
pub mod reliability_table;
mod retest;
mod table3;
pub use offsets::{offsets, table4_markdown, ModelOffsets};
pub use outcome::{stats, StatsOutcome};
pub use reliability_table::{ReliabilityRow, ReliabilityTable};
pub use retest::{reliability_table, require_repeated_trials};
pub use table3::{any_partial, fmt_ms_n, fmt_p, PARTIAL_NOTE};
pub use table3::{
    table3, table3_markdown, table3_rows, ParameterStats, Summary, Table3Row, TestResult,
};

pub use crate::output::{Parameter, UnknownParameter};

/// The parameters, in the order of the paper's Table 3 (plus PBI).
pub const PARAMETERS: [Parameter; Parameter::COUNT] = Parameter::ALL;

/// One person's row for one side: the row itself when the person has one trial; with several
/// trials (rows sharing `subject_id`), the mean over the trials analysed (`status` ok) of each
/// parameter of [`PARAMETERS`] (and STA per stride) that has a value, so a person counts once in
/// every statistic, classifier and report whatever the number of trials. The aggregate's
/// duration and stride counts are the trials' sums, its `source` and `warnings` each trial's
/// (`t2: ...`), its `trial_mean` names the trials and its `trial_id` says so
/// (`mean of 2 trials (t1, t2)`). When no trial of that side was
/// analysed, the first failed row (its error says why).
pub fn person_row(rows: &[&RecordingRow], side: Side) -> Option<RecordingRow> {
    let all: Vec<&RecordingRow> = rows.iter().copied().filter(|r| r.side == side).collect();
    let ok: Vec<&RecordingRow> = all.iter().copied().filter(|r| r.is_ok()).collect();
    if all.len() <= 1 || ok.is_empty() {
        return all.first().map(|r| (*r).clone());
    }
    if ok.len() == 1 {
        return Some(ok[0].clone());
    }
    let mut out = ok[0].clone();
    let mean = |v: Vec<f64>| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
    for p in PARAMETERS {
        out.set_value(p, mean(ok.iter().filter_map(|r| r.value(p)).collect()));
    }
    out.parameters.sta_per_stride = mean(
        ok.iter()
            .filter_map(|r| r.parameters.sta_per_stride)
            .collect(),
    );
    // The walk's values: the cadence is the trials' mean, like the parameters (the first
    // trial's alone sat beside the mean stride time: 96 against 102 steps/min on TRIPOD's two
    // belt speeds); a mean of trials has no one steady window, so none is given (each trial's
    // is its own row's).
    out.walk_cadence_steps_per_min = mean(
        ok.iter()
            .filter_map(|r| r.walk_cadence_steps_per_min)
            .collect(),
    );
    out.steady_start_s = None;
    out.steady_end_s = None;
    let sum = |f: fn(&RecordingRow) -> Option<usize>| ok.iter().map(|r| f(r)).sum();
    out.steady_excluded_start = sum(|r| r.steady_excluded_start);
    out.steady_excluded_end = sum(|r| r.steady_excluded_end);
    out.strides_total = sum(|r| r.strides_total);
    out.strides_valid = sum(|r| r.strides_valid);
    out.duration_s = ok.iter().map(|r| r.duration_s).sum();
    // Each trial's file, prefixed by its trial.
    out.source = ok
        .iter()
        .map(|r| format!("{}: {}", r.trial_id, r.source))
        .collect::<Vec<_>>()
        .join("; ");
    out.warnings = crate::pipeline::WarningList(
        ok.iter()
            .flat_map(|r| {
                r.warnings.iter().map(|w| {
                    let mut w = w.clone();
                    w.message = format!("{}: {}", r.trial_id, w.message);
                    w
                })
            })
            .collect(),
    );
    // A parameter some trial measured is the person's; one none measured keeps every trial's
    // reason (the first trial's list alone would say "not measured" of a value stats then use).
    let mut withheld = crate::domain::Withheld::default();
    for r in &ok {
        for (p, why) in r.withheld.0.iter() {
            if out.value(p).is_none() {
                let why = format!("{}: {why}", r.trial_id);
                let merged = match withheld.reason(p) {
                    Some(w) => format!("{w}; {why}"),
                    None => why,
                };
                withheld.insert(p, crate::domain::Reason::read(merged));
            }
        }
    }
    out.withheld = crate::pipeline::WithheldList(withheld);
    // A parameter measured by some trials but not all: its mean is of those alone, and says so.
    let partial = PARAMETERS
        .into_iter()
        .filter_map(|p| {
            let ids: Vec<String> = ok
                .iter()
                .filter(|r| r.value(p).is_some())
                .map(|r| r.trial_id.clone())
                .collect();
            (!ids.is_empty() && ids.len() < ok.len()).then_some((p, ids))
        })
        .collect();
    let mean = crate::output::TrialMean {
        trial_ids: ok.iter().map(|r| r.trial_id.clone()).collect(),
        partial,
    };
    out.trial_id = mean.to_string();
    out.trial_mean = Some(mean);
    Some(out)
}

/// One subject's values for the cohort analysis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectValues {
    /// Subject.
    pub subject_id: String,
    /// LDH: unaffected side; healthy: left leg.
    pub a: RecordingRow,
    /// LDH: affected side; healthy: right leg.
    pub b: RecordingRow,
}

/// The cohort split into groups; subjects that cannot be used are listed in `excluded`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cohort {
    /// Attitude model of the rows (empty `Other` when there are none).
    pub model: Label<AttitudeModel>,
    /// LDH subjects with both sides analysed (a = unaffected, b = affected).
    pub ldh: Vec<SubjectValues>,
    /// Healthy subjects with both legs analysed (a = left, b = right).
    pub healthy: Vec<SubjectValues>,
    /// Subjects left out, with the reason.
    pub excluded: Vec<String>,
}

/// Minimum subjects per group for the tests.
pub const MIN_GROUP_SIZE: usize = 3;

impl Cohort {
    /// Split per-recording rows (one model) into groups. Errors when a group has fewer than
    /// [`MIN_GROUP_SIZE`] usable subjects, naming what is missing.
    pub fn from_rows(rows: &[RecordingRow]) -> Result<Cohort> {
        let model = rows
            .first()
            .map_or(Label::Other(String::new()), |r| r.model.clone());
        let mut subjects = crate::output::rows_by_subject(rows);
        subjects.sort_unstable_by(|a, b| a.0.cmp(b.0));
        let mut c = Cohort {
            model,
            ldh: vec![],
            healthy: vec![],
            excluded: vec![],
        };
        for (id, rows) in subjects {
            let (l_own, r_own) = (
                person_row(&rows, Side::Left),
                person_row(&rows, Side::Right),
            );
            let (l, r) = (l_own.as_ref(), r_own.as_ref());
            let group = l.or(r).and_then(|x| x.group.clone());
            let problem = |x: Option<&RecordingRow>, side: &str| -> Option<String> {
                match x {
                    None => Some(format!("{id}: no {side} recording")),
                    Some(x) if !x.is_ok() => Some(format!("{id}: {side} failed ({})", x.error)),
                    _ => None,
                }
            };
            if let Some(p) = problem(l, "left").or_else(|| problem(r, "right")) {
                c.excluded.push(p);
                continue;
            }
            let (l, r) = (l.expect("checked").clone(), r.expect("checked").clone());
            let affected = l.affected_side.as_ref();
            match group {
                Some(Group::Healthy) => c.healthy.push(SubjectValues {
                    subject_id: id.into(),
                    a: l,
                    b: r,
                }),
                Some(Group::Ldh) => match affected.and_then(Label::known) {
                    Some(AffectedSide::Left) => c.ldh.push(SubjectValues {
                        subject_id: id.into(),
                        a: r,
                        b: l,
                    }),
                    Some(AffectedSide::Right) => c.ldh.push(SubjectValues {
                        subject_id: id.into(),
                        a: l,
                        b: r,
                    }),
                    _ => c.excluded.push(format!(
                        "{id}: LDH subject without an affected side ('{}')",
                        affected.map_or("", Label::as_str)
                    )),
                },
                Some(Group::Other(other)) if !other.is_empty() => c.excluded.push(format!(
                    "{id}: group '{other}' is not compared (the statistics compare ldh with healthy)"
                )),
                _ => c.excluded.push(format!(
                    "{id}: no group (give a manifest with group and affected_side)"
                )),
            }
        }
        // Group names as the manifest writes them (`ldh`, `healthy`), never upper-cased; a
        // person is usable with both legs analysed, in one of the two groups (ldh: with an
        // affected side): the count says so, not "with both legs analysed" alone.
        for (group, n) in [(Group::Ldh, c.ldh.len()), (Group::Healthy, c.healthy.len())] {
            let name = group.as_str();
            if n < MIN_GROUP_SIZE {
                let why = if c.excluded.is_empty() {
                    String::new()
                } else {
                    format!("; left out: {}", c.excluded.join("; "))
                };
                return Err(LdhError::signal(
                    "cohort statistics",
                    format!("the {name} group has {n} usable subject(s) (both legs analysed, in group '{name}'{side}); at least {MIN_GROUP_SIZE} are needed{why}", side = if group == Group::Ldh { ", affected side given" } else { "" }),
                ));
            }
        }
        Ok(c)
    }

    /// Values of one parameter: (LDHH, LDHE, H = mean of both legs, healthy left, healthy right),
    /// subjects with a missing value dropped pairwise.
    pub fn groups(&self, p: Parameter) -> Groups {
        let pair = |s: &SubjectValues| Some((s.a.value(p)?, s.b.value(p)?));
        let ldh: Vec<(f64, f64)> = self.ldh.iter().filter_map(pair).collect();
        let h: Vec<(f64, f64)> = self.healthy.iter().filter_map(pair).collect();
        Groups {
            ldhh: ldh.iter().map(|p| p.0).collect(),
            ldhe: ldh.iter().map(|p| p.1).collect(),
            h: h.iter().map(|p| (p.0 + p.1) / 2.0).collect(),
            h_left: h.iter().map(|p| p.0).collect(),
            h_right: h.iter().map(|p| p.1).collect(),
        }
    }
}

/// The groups' values of one parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Groups {
    /// LDH unaffected sides.
    pub ldhh: Vec<f64>,
    /// LDH affected sides (paired with `ldhh`).
    pub ldhe: Vec<f64>,
    /// Healthy subjects, mean of both legs.
    pub h: Vec<f64>,
    /// Healthy left legs.
    pub h_left: Vec<f64>,
    /// Healthy right legs (paired with `h_left`).
    pub h_right: Vec<f64>,
}
