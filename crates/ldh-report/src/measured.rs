//! Why a side has no value of a parameter, in the words every section of a page uses (below the
//! sections that say it: the summary, the verdicts, the gait-cycle figure).

use ldh_core::output::{Parameter, RecordingRow};

/// Why a side has no value of `p` (the quality check's reason first), or `None` when it has
/// one.
pub(crate) fn not_measured(r: &RecordingRow, p: Parameter) -> Option<String> {
    if !r.is_ok() {
        return Some("not analysed (see above)".into());
    }
    if let Some(why) = r.withheld.reason(p) {
        let why = why.to_string();
        return Some(match &r.trial_mean {
            Some(m) => same_in_every_trial(&why, &m.trial_ids).unwrap_or(why),
            None => why,
        });
    }
    if r.value(p).is_some() {
        return None;
    }
    if p == Parameter::Sta && !r.parameters.sta_status.is_empty() {
        return Some(sta_reason(&r.parameters.sta_status).to_string());
    }
    Some(match (r.strides_valid, p) {
        (Some(0), _) => "no valid stride".into(),
        // From one leg's heel strike to the other's: the other leg's events were not lent (a
        // gyroscope fault, no recording) or none fell inside this leg's strides.
        (_, Parameter::StepTime | Parameter::StepFrequency | Parameter::DoubleSupport) => {
            "needs the other leg's heel strikes in the same strides, and there were none to use"
                .into()
        }
        _ => "not computable from these strides".into(),
    })
}

/// Why STA is missing, from the run's `sta_status`, without its own "not computed: " or
/// "not measured: " (the page's cell already says "not measured: "; a HuGaDB page read "not
/// measured: not computed: turned off for this run (…)").
pub(crate) fn sta_reason(status: &str) -> &str {
    status
        .strip_prefix("not computed: ")
        .or_else(|| status.strip_prefix("not measured: "))
        .unwrap_or(status)
}

/// A mean of trials' reason (`t1: A; t2: A`, as `ldh_core::cohort::person_row` joins them)
/// said once when every trial gives the same words: "A (trials t1, t2)". `None` when there is
/// one trial's reason, or the trials' words differ (each keeps its own, with its numbers).
fn same_in_every_trial(why: &str, trials: &[String]) -> Option<String> {
    // Each trial's reason starts at "<id>: " (the first) or "; <id>: " (the others), in order.
    let mut starts: Vec<(usize, usize, &str)> = Vec::new();
    let mut from = 0;
    for id in trials {
        let at = if starts.is_empty() {
            why.starts_with(&format!("{id}: ")).then_some(0)
        } else {
            why[from..].find(&format!("; {id}: ")).map(|i| from + i)
        };
        if let Some(at) = at {
            let text = at + if starts.is_empty() { 0 } else { 2 } + id.len() + 2;
            starts.push((at, text, id));
            from = text;
        }
    }
    let texts: Vec<&str> = (0..starts.len())
        .map(|k| &why[starts[k].1..starts.get(k + 1).map_or(why.len(), |n| n.0)])
        .collect();
    if texts.len() < 2 || texts.iter().any(|t| *t != texts[0]) {
        return None;
    }
    let ids: Vec<&str> = starts.iter().map(|s| s.2).collect();
    Some(format!("{} (trials {})", texts[0], ids.join(", ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two trials withheld for the same reason say it once (HuGaDB 03's right leg read "t1:
    /// gyroscope sensor fault; t2: gyroscope sensor fault"); different words keep both.
    #[test]
    fn one_reason_of_every_trial_is_said_once() {
        let ids = ["t1".to_string(), "t2".to_string()];
        assert_eq!(
            same_in_every_trial(
                "t1: gyroscope sensor fault; t2: gyroscope sensor fault",
                &ids
            )
            .as_deref(),
            Some("gyroscope sensor fault (trials t1, t2)")
        );
        assert_eq!(
            same_in_every_trial("t1: only 0 of 28 strides; t2: only 0 of 17 strides", &ids),
            None
        );
        assert_eq!(
            same_in_every_trial("t2: gyroscope sensor fault", &ids),
            None
        );
        let mut r = crate::tests::row("P", "ldh", "right", 1.2);
        r.parameters[Parameter::Wqk] = None;
        r.withheld.0.insert(
            Parameter::Wqk,
            ldh_core::domain::Reason::read("t1: a fault; t2: a fault"),
        );
        r.trial_mean = Some(ldh_core::output::TrialMean {
            trial_ids: ids.to_vec(),
            ..Default::default()
        });
        assert_eq!(
            not_measured(&r, Parameter::Wqk).as_deref(),
            Some("a fault (trials t1, t2)")
        );
    }

    /// A leg's step time without a value and without a withheld reason says it needs the other
    /// leg (HuGaDB 03: the right gyroscope is faulty, so the left step time read "not
    /// computable from these strides").
    #[test]
    fn a_between_legs_value_without_the_other_leg_says_so() {
        let mut r = crate::tests::row("P", "ldh", "left", 1.2);
        r.parameters[Parameter::StepTime] = None;
        r.parameters[Parameter::StrideLength] = None;
        r.strides_valid = Some(28);
        assert_eq!(
            not_measured(&r, Parameter::StepTime).as_deref(),
            Some("needs the other leg's heel strikes in the same strides, and there were none to use")
        );
        assert_eq!(
            not_measured(&r, Parameter::StrideLength).as_deref(),
            Some("not computable from these strides")
        );
    }
}
