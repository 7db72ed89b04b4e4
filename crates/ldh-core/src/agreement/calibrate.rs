//! `ldh agree --write-params`: the event timing bias that `ldh agree` measured, written as an
//! [`EventCalibration`] into the analysis parameters of the run it compared (issue 38 item 4;
//! docs/agreement.md "Calibrating the events to a reference").
//!
//! The shift of each event kind is minus its mean error (ldh − reference) over both legs'
//! matched events, added to the run's own calibration if it had one (a calibrated run compared
//! again measures the residual bias). A calibration from a few events would move every later
//! recording by a chance value, so at least [`MIN_CALIBRATION_EVENTS`] matched events of each
//! kind are required; the standard error of the mean error is then at most SD/√20 (≈ 4 ms for
//! the 15–20 ms SD of good detectors, docs/accuracy.md).

use super::{AgreementError, AgreementReport};
use crate::domain::{EventKind, Legs};
use crate::error::Result;
use crate::events::EventCalibration;
use crate::pipeline::AnalysisParams;

/// Fewest matched events of each kind (heel strike, toe off; both legs) a calibration is
/// measured from.
pub const MIN_CALIBRATION_EVENTS: usize = 20;

/// The mean error (ldh − reference, s) of `event` (`HS` or `TO`) over both legs, with at least
/// [`MIN_CALIBRATION_EVENTS`] matches.
fn bias_s(report: &AgreementReport, event: EventKind, what: &'static str) -> Result<(f64, usize)> {
    let summary = report
        .events
        .iter()
        .find(|e| e.event == event && e.side == Legs::Both)
        .map(|e| &e.summary);
    let n = summary.map_or(0, |s| s.n_matched);
    match summary.and_then(|s| s.bias_s) {
        Some(b) if n >= MIN_CALIBRATION_EVENTS => Ok((b, n)),
        _ => Err(AgreementError::TooFewPairs {
            what,
            needed: MIN_CALIBRATION_EVENTS,
            got: n,
            dropped: 0,
            unit: "matched events",
        }
        .into()),
    }
}

/// `base` (the compared run's parameters; `None`: not known, the defaults) with its events
/// calibrated to the reference of `report`: each event kind's shift is the run's earlier shift
/// minus the bias measured. `system` names the reference system for the report ("force
/// plates"); the reference files are named after it (or alone, without it).
///
/// Errors: fewer than [`MIN_CALIBRATION_EVENTS`] matched heel strikes or toe offs; a shift
/// beyond ±[`crate::events::MAX_CALIBRATION_SHIFT_S`] (the check of [`EventCalibration`]).
pub fn calibrated_params(
    report: &AgreementReport,
    base: Option<&AnalysisParams>,
    system: Option<&str>,
) -> Result<AnalysisParams> {
    let default = AnalysisParams::default();
    let base = base.unwrap_or(&default);
    let files = report
        .reference_files
        .iter()
        .map(|f| {
            std::path::Path::new(f)
                .file_name()
                .map_or(f.clone(), |n| n.to_string_lossy().into_owned())
        })
        .collect::<Vec<_>>()
        .join(", ");
    let reference = match system.map(str::trim).filter(|s| !s.is_empty()) {
        Some(s) => format!("{s} ({files}"),
        None => format!("{files} ("),
    };
    let (hs_bias, n_hs) = bias_s(
        report,
        EventKind::HeelStrike,
        "event calibration (heel strikes)",
    )?;
    let (to_bias, n_to) = bias_s(report, EventKind::ToeOff, "event calibration (toe offs)")?;
    let earlier = base.events.calibration.as_ref();
    let calibration = EventCalibration {
        hs_shift_s: earlier.map_or(0.0, |c| c.hs_shift_s) - hs_bias,
        to_shift_s: earlier.map_or(0.0, |c| c.to_shift_s) - to_bias,
        detector: base.events.detector,
        against: if system.is_some_and(|s| !s.trim().is_empty()) {
            format!("{reference}; {n_hs} heel strikes, {n_to} toe offs matched)")
        } else {
            format!("{reference}{n_hs} heel strikes, {n_to} toe offs matched)")
        },
    };
    calibration.check(base.events.detector)?;
    let mut out = base.clone();
    out.events.calibration = Some(calibration);
    Ok(out)
}

/// The parameter file `ldh agree --write-params` writes: a comment saying what was measured
/// and how to use it, then `params` as TOML (the whole run's parameters, so the calibrated
/// analysis differs from the compared one by the calibration alone).
pub fn params_toml(params: &AnalysisParams) -> Result<String> {
    let body = toml::to_string(params).map_err(|e| crate::LdhError::Format {
        name: "calibration parameters".into(),
        reason: e.to_string(),
    })?;
    let c = params.events.calibration.as_ref();
    let said = c.map(EventCalibration::sentence).unwrap_or_default();
    Ok(format!(
        "# Written by `ldh agree --write-params`. {said}\n\
         # Use it with `ldh analyze --params <this file>`: every event is shifted by\n\
         # [events.calibration], the rest are the parameters of the run that was compared.\n\n{body}"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agreement::run::EventAgreement;
    use crate::agreement::{AgreementParams, MatchSummary};

    fn report(n: usize, hs_bias: f64, to_bias: f64) -> AgreementReport {
        let ev = |event: EventKind, side: Legs, bias: f64| EventAgreement {
            event,
            side,
            group: "all".into(),
            summary: MatchSummary {
                n_ldh: n,
                n_reference: n,
                n_matched: n,
                recall: Some(1.0),
                precision: Some(1.0),
                f1: Some(1.0),
                bias_s: Some(bias),
                sd_s: Some(0.01),
                mae_s: Some(bias.abs()),
                p95_abs_s: Some(bias.abs()),
            },
        };
        AgreementReport {
            params: AgreementParams::default(),
            reference_files: vec!["ref.csv".into()],
            offsets: vec![],
            events: vec![
                ev(EventKind::HeelStrike, Legs::Left, 0.5),
                ev(EventKind::HeelStrike, Legs::Both, hs_bias),
                ev(EventKind::ToeOff, Legs::Both, to_bias),
            ],
            unmatched_events: vec![],
            reference_strides: 0,
            strides_matched: 0,
            parameters: vec![],
            groups: vec![],
            events_by_group: vec![],
            event_pairs: vec![],
        }
    }

    #[test]
    fn the_shift_is_minus_the_bias_of_both_legs_added_to_an_earlier_one() {
        let p = calibrated_params(&report(40, 0.012, -0.031), None, Some("force plates")).unwrap();
        let c = p.events.calibration.clone().unwrap();
        assert!((c.hs_shift_s + 0.012).abs() < 1e-15 && (c.to_shift_s - 0.031).abs() < 1e-15);
        assert_eq!(
            c.against,
            "force plates (ref.csv; 40 heel strikes, 40 toe offs matched)"
        );
        // Compared again after calibration: the residual bias is taken off the earlier shift.
        let again = calibrated_params(&report(40, 0.002, 0.001), Some(&p), None).unwrap();
        assert_eq!(
            again.events.calibration.as_ref().unwrap().against,
            "ref.csv (40 heel strikes, 40 toe offs matched)"
        );
        let c2 = again.events.calibration.clone().unwrap();
        assert!((c2.hs_shift_s + 0.014).abs() < 1e-15 && (c2.to_shift_s - 0.030).abs() < 1e-15);
        // Everything else is the compared run's.
        let mut rest = again.clone();
        rest.events.calibration = None;
        assert_eq!(rest, AnalysisParams::default());
    }

    #[test]
    fn too_few_events_or_too_large_a_bias_is_refused() {
        let e = calibrated_params(&report(19, 0.01, 0.01), None, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("needs at least 20 matched events") && e.contains("got 19"),
            "{e}"
        );
        let e = calibrated_params(&report(50, 0.3, 0.0), None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("hs_shift_s"), "{e}");
    }

    #[test]
    fn the_file_reads_back_as_the_same_parameters() {
        let p = calibrated_params(&report(40, 0.012, -0.031), None, Some("plates")).unwrap();
        let text = params_toml(&p).unwrap();
        assert!(text.starts_with(
            "# Written by `ldh agree --write-params`. Gait events calibrated against plates"
        ));
        let back: AnalysisParams = toml::from_str(&text).unwrap();
        assert_eq!(back, p);
        back.check().unwrap();
    }
}
