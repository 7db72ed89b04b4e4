//! What the steady-state rule ([`crate::gait::exclude_unsteady`]) says about a leg: the window
//! it kept when it excluded strides (a note), or too little steady walking for the variability
//! (a warning that withholds the CVs).

use super::warning::{codes, params, Severity, Warning};
use crate::gait::{exclude_unsteady, SteadySpan, Stride, ValidSteadyParams};

/// Apply the steady-state rule to a leg's strides ([`exclude_unsteady`], idempotent) and put
/// its finding among the leg's `warnings` in place of an earlier one (most severe first).
pub fn apply_steady(
    strides: &mut [Stride],
    warnings: &mut Vec<Warning>,
    p: &ValidSteadyParams,
) -> Option<SteadySpan> {
    let span = exclude_unsteady(strides, p);
    warnings.retain(|w| w.code != codes::STEADY_WINDOW && w.code != codes::TOO_LITTLE_STEADY);
    if let Some(w) = span.as_ref().and_then(steady_warning) {
        warnings.push(w);
        warnings.sort_by_key(|x| std::cmp::Reverse(x.severity));
    }
    span
}

/// The finding of the steady-state rule on one leg (`None`: every stride steady and enough of
/// them).
pub fn steady_warning(s: &SteadySpan) -> Option<Warning> {
    if s.steady_strides == 0 {
        return Some(
            Warning::new(
                codes::TOO_LITTLE_STEADY,
                Severity::Warning,
                "no steady walking found (no three consecutive strides within the walk's own band of stride times): stride-time and stride-length variability withheld; the means are of the whole walk",
            )
            .withholding(&params::VARIABILITY),
        );
    }
    if !s.enough {
        return Some(
            Warning::new(
                codes::TOO_LITTLE_STEADY,
                Severity::Warning,
                match excluded(s) {
                    Some(e) => format!(
                        "fewer than 10 steady strides: {} (steady walking from {:.1} s to {:.1} s; {e}), so stride-time and stride-length variability (CV) are withheld",
                        s.steady_strides, s.start_s, s.end_s
                    ),
                    None => format!(
                        "fewer than 10 steady strides: {} valid (walking from {:.1} s to {:.1} s), so stride-time and stride-length variability (CV) are withheld; a longer straight walk gives more",
                        s.steady_strides, s.start_s, s.end_s
                    ),
                },
            )
            .withholding(&params::VARIABILITY),
        );
    }
    excluded(s).map(|e| {
        Warning::new(
            codes::STEADY_WINDOW,
            Severity::Note,
            format!(
                "steady walking from {:.1} s to {:.1} s ({} strides): {e}",
                s.start_s, s.end_s, s.steady_strides
            ),
        )
    })
}

/// "N stride(s) excluded at the start (speeding up) and M at the end (slowing down)", or
/// `None` when none was excluded.
fn excluded(s: &SteadySpan) -> Option<String> {
    match (s.excluded_start, s.excluded_end) {
        (0, 0) => None,
        (a, 0) => Some(format!("{a} stride(s) at the start excluded (speeding up)")),
        (0, b) => Some(format!("{b} stride(s) at the end excluded (slowing down)")),
        (a, b) => Some(format!(
            "{a} stride(s) at the start (speeding up) and {b} at the end (slowing down) excluded"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span(steady: usize, a: usize, b: usize) -> SteadySpan {
        SteadySpan {
            start_s: 12.04,
            end_s: 80.0,
            excluded_start: a,
            excluded_end: b,
            steady_strides: steady,
            enough: steady >= 10,
        }
    }

    #[test]
    fn what_the_rule_says() {
        assert_eq!(steady_warning(&span(60, 0, 0)), None);
        let w = steady_warning(&span(60, 7, 0)).unwrap();
        assert_eq!(w.severity, Severity::Note);
        assert_eq!(
            w.message,
            "steady walking from 12.0 s to 80.0 s (60 strides): 7 stride(s) at the start excluded (speeding up)"
        );
        assert!(w.affects.is_empty());
        let w = steady_warning(&span(6, 2, 1)).unwrap();
        assert_eq!(w.code, codes::TOO_LITTLE_STEADY);
        assert_eq!(w.message, "fewer than 10 steady strides: 6 (steady walking from 12.0 s to 80.0 s; 2 stride(s) at the start (speeding up) and 1 at the end (slowing down) excluded), so stride-time and stride-length variability (CV) are withheld");
        assert_eq!(
            w.reason(),
            "too little steady (fewer than 10 steady strides)"
        );
        assert_eq!(w.affects, params::VARIABILITY);
        assert_eq!(
            steady_warning(&span(7, 0, 0)).unwrap().message,
            "fewer than 10 steady strides: 7 valid (walking from 12.0 s to 80.0 s), so stride-time and stride-length variability (CV) are withheld; a longer straight walk gives more"
        );
        let none = SteadySpan {
            start_s: f64::NAN,
            end_s: f64::NAN,
            ..span(0, 0, 0)
        };
        assert!(steady_warning(&none)
            .unwrap()
            .message
            .starts_with("no steady walking found"));
    }
}
