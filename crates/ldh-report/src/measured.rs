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
        return Some(why.to_string());
    }
    if r.value(p).is_some() {
        return None;
    }
    if p == Parameter::Sta && !r.parameters.sta_status.is_empty() {
        return Some(r.parameters.sta_status.clone());
    }
    Some(match r.strides_valid {
        Some(0) => "no valid stride".into(),
        _ => "not computable from these strides".into(),
    })
}
