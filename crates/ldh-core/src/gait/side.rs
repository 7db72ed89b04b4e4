//! Per-side gait parameters (paper Table 2; SPEC §3.6): the means over a leg's valid strides,
//! SV and STV, step time and frequency from the other leg's heel strikes, and the rules of
//! evidence that withhold a leg's stride length when too few of its strides vouch for it.

use super::times::SortedTimes;
use super::{LengthCheck, SideParameters, Stride, StrideCode, StrideFinding};
use crate::domain::{Parameter, PerParameter, Reason, ReasonCode};

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        f64::NAN
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

fn cv(v: &[f64]) -> f64 {
    if v.len() < 2 {
        return f64::NAN;
    }
    let m = mean(v);
    let sd = (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt();
    sd / m
}

/// Per-side parameters from the strides of one leg and, when available, the other leg's HS.
pub fn side_parameters(strides: &[Stride], other_hs_s: Option<&[f64]>) -> SideParameters {
    let valid: Vec<&Stride> = strides.iter().filter(|s| s.valid).collect();
    let col = |f: fn(&Stride) -> f64| -> Vec<f64> {
        valid
            .iter()
            .map(|s| f(s))
            .filter(|v| v.is_finite())
            .collect()
    };
    let st = col(|s| s.stride_time_s);
    let sl = col(|s| s.stride_length_m);
    let mean_st = mean(&st);
    let stt: Vec<f64> = match other_hs_s {
        Some(other) => {
            // The other leg's last heel strike before each one (sorted: linear, issue 19).
            let other = SortedTimes::new(other);
            valid
                .iter()
                .filter_map(|s| {
                    other
                        .last_before(s.hs_time_s, |c| s.hs_time_s - c < 0.75 * mean_st)
                        .map(|c| s.hs_time_s - c)
                })
                .collect()
        }
        None => vec![],
    };
    let mean_stt = mean(&stt);
    let stance = mean(&col(|s| s.stance_ratio));
    // Each parameter's computation, one arm per parameter (a new parameter adds its arm).
    let values = PerParameter::from_fn(|p| match p {
        Parameter::StrideTime => mean_st,
        Parameter::StepTime => mean_stt,
        Parameter::StepFrequency if mean_stt.is_finite() => 1.0 / mean_stt,
        Parameter::StepFrequency => 2.0 / mean_st,
        Parameter::StanceRatio => stance,
        Parameter::SwingRatio => 1.0 - stance,
        Parameter::DoubleSupport => mean(&col(|s| s.double_support_ratio)),
        Parameter::StrideLength => mean(&sl),
        Parameter::Speed => mean(&col(|s| s.speed_mps)),
        Parameter::StrideLengthCv => cv(&sl),
        Parameter::StrideTimeCv => cv(&st),
        // From the leg's angular velocity, later (`crate::nonlinear::gait_sta`).
        Parameter::Sta => f64::NAN,
        Parameter::Wqk => mean(&col(|s| s.wqk_deg)),
        Parameter::Pbi => mean(&col(|s| s.pbi_deg)),
        Parameter::Bdk => mean(&col(|s| s.bdk_deg)),
        #[cfg(feature = "dummy-parameter")]
        Parameter::Dummy => 2.0 * mean_st,
    });
    let mut out = SideParameters {
        strides_total: strides.len(),
        strides_valid: valid.len(),
        values,
        sta_per_stride: f64::NAN,
        sta_status: "not computed".into(),
        withheld: Default::default(),
    };
    withhold_side_length(&mut out, &valid, sl.len());
    out
}

/// Fewest valid strides with a length for the side's stride length, speed and SV (half of
/// them, rounded up, when the side has fewer than 6 valid strides).
pub const MIN_LENGTH_STRIDES: usize = 3;

/// Smallest share of the valid strides that must have a length for the side's stride length,
/// speed and SV. When most strides of a leg fail the per-stride integration checks, the few
/// that pass are survivors of the same faulty integration (their drift happened to be small),
/// not a sample of the leg's walking, so their mean is not vouched for. A rule of evidence,
/// not a fitted value: with HuGaDB 06_00 (right leg: 4 of 127 strides passing) it withheld a
/// mean 10 % off the other leg's.
pub const MIN_LENGTH_SHARE: f64 = 0.5;

/// Whether `with_length` strides with a length among `valid` valid strides vouch for the leg's
/// stride length ([`MIN_LENGTH_STRIDES`], [`MIN_LENGTH_SHARE`]).
fn lengths_vouched(valid: usize, with_length: usize) -> bool {
    with_length >= MIN_LENGTH_STRIDES.min(valid.div_ceil(2)).max(1)
        && with_length as f64 >= MIN_LENGTH_SHARE * valid as f64
}

/// Withholds the per-stride lengths (and speeds) of a leg whose lengths are not vouched for
/// ([`lengths_vouched`]): the few strides that passed their own checks are survivors of the
/// same faulty integration (on simulator family A the ACC-only model's 2 survivors of 616 were
/// 99 % short), so strides.csv does not report them either. Call on the final strides, before
/// [`side_parameters`].
pub fn withhold_unvouched_lengths(strides: &mut [Stride]) {
    let valid = strides.iter().filter(|s| s.valid).count();
    let with_length = strides
        .iter()
        .filter(|s| s.valid && s.stride_length_m.is_finite())
        .count();
    if valid == 0 || with_length == 0 || lengths_vouched(valid, with_length) {
        return;
    }
    for s in strides.iter_mut().filter(|s| s.stride_length_m.is_finite()) {
        s.stride_length_m = f64::NAN;
        s.speed_mps = f64::NAN;
        s.push(StrideFinding::new(
            StrideCode::LengthNotVouched,
            format!("stride length withheld: only {with_length} of the leg's {valid} valid strides pass the integration checks"),
        ));
    }
}

/// Why a valid stride's length is blank, in words: the first of the length checks it failed
/// (in the order of [`LengthCheck`]), else the first quality finding that withheld it, else
/// "not integrable".
fn why_no_length(s: &Stride) -> String {
    let checks = s.findings.iter().filter_map(|f| match f.code {
        StrideCode::Length(c) if c != LengthCheck::NotIntegrable => Some(c),
        _ => None,
    });
    if let Some(c) = checks.min() {
        return c.words().to_string();
    }
    s.findings
        .iter()
        .find_map(|f| match &f.code {
            StrideCode::Finding { code, effect } if effect.withholds_length() => {
                Some(code.plain().to_string())
            }
            _ => None,
        })
        .unwrap_or_else(|| LengthCheck::NotIntegrable.words().to_string())
}

/// Withhold the side's stride length, speed and SV unless at least [`MIN_LENGTH_STRIDES`] (or
/// half, when fewer) and at least [`MIN_LENGTH_SHARE`] of the valid strides have a length: say
/// why (the most common per-stride reason).
fn withhold_side_length(out: &mut SideParameters, valid: &[&Stride], with_length: usize) {
    if valid.is_empty() || lengths_vouched(valid.len(), with_length) {
        return;
    }
    // Survivors withheld by `withhold_unvouched_lengths` passed their own checks.
    let survivor = |s: &Stride| s.has(&StrideCode::LengthNotVouched);
    let survivors = valid.iter().filter(|s| survivor(s)).count();
    let passed = with_length + survivors;
    let mut why: std::collections::BTreeMap<String, usize> = Default::default();
    for s in valid
        .iter()
        .filter(|s| !s.stride_length_m.is_finite() && !survivor(s))
    {
        *why.entry(why_no_length(s)).or_default() += 1;
    }
    let top = why
        .iter()
        .max_by_key(|(_, n)| **n)
        .map(|(r, _)| r.clone())
        .unwrap_or_default();
    // One reason for every stride is that reason alone: "not measured: sensor height not
    // given" on a page, not "passed its checks on only 0 of 99 strides (most often: …)".
    let reason = if passed == 0 && why.len() == 1 {
        top
    } else {
        format!(
            "stride length passed its checks on only {passed} of {} strides (most often: {top})",
            valid.len()
        )
    };
    for p in [
        Parameter::StrideLength,
        Parameter::Speed,
        Parameter::StrideLengthCv,
    ] {
        out.withhold(
            p,
            Reason::new(ReasonCode::LengthNotVouched, reason.clone()),
            true,
        );
    }
}
