//! Unsure events (issue 49): which heel strikes and toe offs the signals cannot place well, and
//! the typed reason a stride bounded by one is withheld (docs/quality.md "Unsure events").
//!
//! Each event carries a confidence, 0–1 ([`Events::hs_confidence`], [`Events::to_confidence`];
//! `events.csv` `confidence`). A heel strike is unsure without an impact in a walk that shows
//! them, or with two candidate landings (`events/impact.rs`); a toe off is unsure when the
//! late-stance peak of ω_s that starts its bracket has a rival of nearly its height
//! (`late_stance_confidence` in `events.rs`). Below [`MIN_EVENT_CONFIDENCE`] the stride is not
//! valid: its stride time, stance and length would add the event's error to the means and CVs
//! instead of measuring the walk. Walks without impacts (every strike at the gyroscope's
//! landmark, confidence 0.5) withhold nothing on that account.

use super::{Events, MIN_EVENT_CONFIDENCE, TWO_CANDIDATES_CONFIDENCE};
pub use crate::domain::UnsureEvent;

/// The confidence of the event at exactly `t` in `times` (NaN when it is not one of them or
/// the detector gives none).
fn confidence_at(times: &[f64], conf: &[f64], t: f64) -> f64 {
    if times.len() != conf.len() {
        return f64::NAN;
    }
    times
        .iter()
        .position(|&x| x == t)
        .map_or(f64::NAN, |i| conf[i])
}

/// The confidence of the heel strike at `t_s` (NaN: unknown).
pub fn hs_confidence_at(ev: &Events, t_s: f64) -> f64 {
    confidence_at(&ev.hs_s, &ev.hs_confidence, t_s)
}

/// The confidence of the toe off at `t_s` (NaN: unknown).
pub fn to_confidence_at(ev: &Events, t_s: f64) -> f64 {
    confidence_at(&ev.to_s, &ev.to_confidence, t_s)
}

/// Why the stride from the heel strike at `hs_s` to the one at `next_hs_s`, with its toe off at
/// `to_s` (NaN: none), depends on an unsure event; empty when it does not.
pub fn unsure_events(ev: &Events, hs_s: f64, to_s: f64, next_hs_s: f64) -> Vec<UnsureEvent> {
    let mut out = Vec::new();
    for t in [hs_s, next_hs_s] {
        let c = hs_confidence_at(ev, t);
        if c < MIN_EVENT_CONFIDENCE {
            let why = if c == TWO_CANDIDATES_CONFIDENCE {
                UnsureEvent::TwoLandings
            } else {
                UnsureEvent::NoImpact
            };
            if !out.contains(&why) {
                out.push(why);
            }
        }
    }
    if to_confidence_at(ev, to_s) < MIN_EVENT_CONFIDENCE {
        out.push(UnsureEvent::TwoPushOffs);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stride_is_unsure_when_one_of_its_events_is() {
        let ev = Events {
            hs_s: vec![1.0, 2.0, 3.0],
            hs_confidence: vec![0.9, 0.0, TWO_CANDIDATES_CONFIDENCE],
            to_s: vec![1.6, 2.6],
            to_confidence: vec![0.8, 0.1],
            ..Events::default()
        };
        assert!(unsure_events(&ev, 1.0, 1.6, 2.0) == vec![UnsureEvent::NoImpact]);
        assert_eq!(
            unsure_events(&ev, 2.0, 2.6, 3.0),
            vec![
                UnsureEvent::NoImpact,
                UnsureEvent::TwoLandings,
                UnsureEvent::TwoPushOffs
            ]
        );
        // Without confidences (another detector), nothing is unsure.
        let bare = Events {
            hs_s: vec![1.0, 2.0],
            to_s: vec![1.6],
            ..Events::default()
        };
        assert!(unsure_events(&bare, 1.0, 1.6, 2.0).is_empty());
        assert_eq!(
            UnsureEvent::NoImpact.to_string(),
            "heel strike unsure (no impact)"
        );
    }
}
