//! What the steady-state rule ([`crate::gait::exclude_unsteady_walk`]) says about a walk's legs:
//! the window it kept when it excluded strides (a note), too little steady walking for the
//! variability, or a walk that never becomes steady (warnings that withhold the CVs).
//!
//! A subject's two legs are one walk: they get one window, from both legs' strides on the left
//! recording's clock ([`apply_steady_walk`]); a leg alone, or legs the pair's checks doubt
//! are one walk, get their own ([`apply_steady`]).

use super::warning::{codes, params, Severity, Warning};
use super::LegResult;
use crate::gait::{exclude_unsteady_walk, SteadySpan, Stride, ValidSteadyParams};

/// Apply the steady-state rule to one leg's strides, the leg being the walk (idempotent), and
/// put its finding among the leg's `warnings` in place of an earlier one (most severe first).
pub fn apply_steady(
    strides: &mut [Stride],
    warnings: &mut Vec<Warning>,
    p: &ValidSteadyParams,
) -> Option<SteadySpan> {
    let span = exclude_unsteady_walk(&mut [(strides, 0.0)], p)
        .pop()
        .flatten();
    set_warning(warnings, span.as_ref(), p);
    span
}

/// Apply the steady-state rule to both legs of one walk: one window from both legs' strides
/// (the right leg's times shifted onto the left recording's clock by the difference of the
/// files' first samples, `t0_s`), each leg's strides outside it excluded, each leg's `steady`
/// and finding set. Idempotent.
pub fn apply_steady_walk(left: &mut LegResult, right: &mut LegResult, p: &ValidSteadyParams) {
    let shift_s = right.t0_s - left.t0_s;
    let mut spans = exclude_unsteady_walk(
        &mut [(&mut left.strides, 0.0), (&mut right.strides, shift_s)],
        p,
    );
    let (r, l) = (spans.pop().flatten(), spans.pop().flatten());
    for (leg, span) in [(left, l), (right, r)] {
        set_warning(&mut leg.warnings, span.as_ref(), p);
        leg.steady = span;
    }
}

/// Put the rule's finding about a leg among its warnings in place of an earlier one.
fn set_warning(warnings: &mut Vec<Warning>, span: Option<&SteadySpan>, p: &ValidSteadyParams) {
    warnings.retain(|w| {
        ![
            codes::STEADY_WINDOW,
            codes::TOO_LITTLE_STEADY,
            codes::NEVER_STEADY,
        ]
        .contains(&w.code)
    });
    if let Some(w) = span.and_then(|s| steady_warning(s, p.0.min_steady_share)) {
        warnings.push(w);
        warnings.sort_by_key(|x| std::cmp::Reverse(x.severity));
    }
}

/// The finding of the steady-state rule on one leg (`None`: every stride steady and enough of
/// them); `min_steady_share` is the rule's (`ValidSteadyParams::min_steady_share`). A walk that
/// never becomes steady says which of the rule's two causes it is: its longest stretch at one
/// pace holds fewer strides than that share, or that stretch itself still drifts (a simulated
/// walker speeding up from 1.95 to 1.55 s read "holds 70 % of the strides, fewer than half").
pub fn steady_warning(s: &SteadySpan, min_steady_share: f64) -> Option<Warning> {
    if s.never_steady {
        let why = if s.longest_share < min_steady_share {
            format!(
                "its stride time changes throughout (speeding up, slowing down or changing pace; the longest stretch at one pace holds {:.0} % of the strides, fewer than the {:.0} % a steady walk needs)",
                100.0 * s.longest_share,
                100.0 * min_steady_share
            )
        } else {
            format!(
                "its stride time keeps drifting (speeding up or slowing down) even across its longest stretch at one pace ({:.0} % of the strides)",
                100.0 * s.longest_share
            )
        };
        return Some(
            Warning::new(
                codes::NEVER_STEADY,
                Severity::Warning,
                format!(
                    "the walk never becomes steady: {why}, so stride-time and stride-length variability are withheld; the means are of the whole walk"
                ),
            )
            .withholding(&params::VARIABILITY),
        );
    }
    if !s.enough {
        let message = match excluded(s) {
            _ if !s.start_s.is_finite() => "fewer than 10 steady strides: no valid stride, so stride-time and stride-length variability (CV) are withheld".to_string(),
            Some(e) => format!(
                "fewer than 10 steady strides: {} (steady walking from {:.1} s to {:.1} s; {e}), so stride-time and stride-length variability (CV) are withheld",
                s.steady_strides, s.start_s, s.end_s
            ),
            None => format!(
                "fewer than 10 steady strides: {} valid (walking from {:.1} s to {:.1} s), so stride-time and stride-length variability (CV) are withheld; a longer straight walk gives more",
                s.steady_strides, s.start_s, s.end_s
            ),
        };
        return Some(
            Warning::new(codes::TOO_LITTLE_STEADY, Severity::Warning, message)
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
        (0, b) => Some(format!(
            "{b} stride(s) at the end excluded (slowing down or a change of pace)"
        )),
        (a, b) => Some(format!(
            "{a} stride(s) at the start (speeding up) and {b} at the end (slowing down or a change of pace) excluded"
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
            never_steady: false,
            longest_share: 0.8,
        }
    }

    #[test]
    fn what_the_rule_says() {
        assert_eq!(steady_warning(&span(60, 0, 0), 0.5), None);
        let w = steady_warning(&span(60, 7, 0), 0.5).unwrap();
        assert_eq!(w.severity, Severity::Note);
        assert_eq!(
            w.message,
            "steady walking from 12.0 s to 80.0 s (60 strides): 7 stride(s) at the start excluded (speeding up)"
        );
        assert!(w.affects.is_empty());
        let w = steady_warning(&span(6, 2, 1), 0.5).unwrap();
        assert_eq!(w.code, codes::TOO_LITTLE_STEADY);
        assert_eq!(w.message, "fewer than 10 steady strides: 6 (steady walking from 12.0 s to 80.0 s; 2 stride(s) at the start (speeding up) and 1 at the end (slowing down or a change of pace) excluded), so stride-time and stride-length variability (CV) are withheld");
        assert_eq!(w.reason(), "fewer than 10 steady strides");
        assert_eq!(w.affects, params::VARIABILITY);
        assert_eq!(
            steady_warning(&span(7, 0, 0), 0.5).unwrap().message,
            "fewer than 10 steady strides: 7 valid (walking from 12.0 s to 80.0 s), so stride-time and stride-length variability (CV) are withheld; a longer straight walk gives more"
        );
        let none = SteadySpan {
            start_s: f64::NAN,
            end_s: f64::NAN,
            never_steady: true,
            longest_share: 0.31,
            ..span(0, 0, 0)
        };
        let w = steady_warning(&none, 0.5).unwrap();
        assert_eq!(w.code, codes::NEVER_STEADY);
        assert!(
            w.message
                .contains("holds 31 % of the strides, fewer than the 50 % a steady walk needs"),
            "{}",
            w.message
        );
        // A longest stretch of 70 % that still drifts is never called "fewer than half".
        let drifting = SteadySpan {
            longest_share: 0.7,
            ..none
        };
        let d = steady_warning(&drifting, 0.5).unwrap();
        assert_eq!(d.code, codes::NEVER_STEADY);
        assert!(!d.message.contains("fewer than"), "{}", d.message);
        assert!(
            d.message.contains("keeps drifting (speeding up or slowing down) even across its longest stretch at one pace (70 % of the strides)"),
            "{}",
            d.message
        );
        assert_eq!(d.reason(), "the walk never becomes steady");
        assert_eq!(w.reason(), "the walk never becomes steady");
        assert_eq!(w.affects, params::VARIABILITY);
        let empty = SteadySpan {
            never_steady: false,
            ..none
        };
        assert_eq!(
            steady_warning(&empty, 0.5).unwrap().code,
            codes::TOO_LITTLE_STEADY
        );
    }
}
