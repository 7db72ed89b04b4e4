//! Calibration of the gait events against a laboratory's own reference (issue 38 item 4).
//!
//! Every detector places heel strikes and toe offs at a fixed phase of the shank's motion; a
//! force plate, instrumented treadmill or pressure walkway places them where the foot loads and
//! unloads. The two differ by a systematic delay that depends on the reference system and its
//! threshold (docs/accuracy.md: the two simulator families alone disagree by 25–40 ms on toe
//! off). `ldh agree --write-params` measures that delay on a lab's recordings (the mean of
//! ldh − reference over the matched events, [`crate::agreement`]) and writes it, negated, as
//! [`EventCalibration`] into a parameter file; `ldh analyze --params` then adds it to every
//! event, so the lab's later recordings are timed like its reference. The shift is one constant
//! per event kind, the same for both legs and for every walk: the correction a validation paper
//! would apply as "bias removal", and nothing more (the spread of the errors is not reduced).
//!
//! A calibration is measured with one detector and applies only to it: parameters whose
//! detector differs from the calibration's are refused at their check.

use serde::{Deserialize, Serialize};

use super::{EventDetector, Events};
use crate::error::{LdhError, Result};

/// Largest shift a calibration may apply, s. A delay of a fifth of a second between two systems
/// timing the same footfall is not a detector's bias but a wrong clock, a wrong reference
/// threshold or a mismatched file; it is refused rather than applied.
pub const MAX_CALIBRATION_SHIFT_S: f64 = 0.15;

/// Event times shifted to agree with a reference system on average (no default: absent unless
/// a parameter file gives it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventCalibration {
    /// Added to every heel strike, s: minus the mean heel-strike error (ldh − reference) that
    /// was measured. |value| ≤ [`MAX_CALIBRATION_SHIFT_S`].
    pub hs_shift_s: f64,
    /// Added to every toe off, s: minus the mean toe-off error that was measured.
    /// |value| ≤ [`MAX_CALIBRATION_SHIFT_S`].
    pub to_shift_s: f64,
    /// The detector the errors were measured with; the calibration applies to it only.
    pub detector: EventDetector,
    /// Against what, in words for the report: the reference file and the events matched
    /// ("force plates in ref.csv: 812 heel strikes, 806 toe offs matched").
    pub against: String,
}

impl EventCalibration {
    /// Check the shifts (finite, within ±[`MAX_CALIBRATION_SHIFT_S`]), the description (not
    /// empty) and that `detector`, the run's detector, is the calibration's.
    pub fn check(&self, detector: EventDetector) -> Result<()> {
        for (name, v) in [
            ("events.calibration.hs_shift_s", self.hs_shift_s),
            ("events.calibration.to_shift_s", self.to_shift_s),
        ] {
            if !(v.is_finite() && v.abs() <= MAX_CALIBRATION_SHIFT_S) {
                return Err(LdhError::param(
                    name,
                    v,
                    format!(
                        "must lie in [−{MAX_CALIBRATION_SHIFT_S}, {MAX_CALIBRATION_SHIFT_S}] s"
                    ),
                ));
            }
        }
        if self.against.trim().is_empty() {
            return Err(LdhError::param(
                "events.calibration.against",
                "\"\"",
                "must say what the events were calibrated against",
            ));
        }
        if self.detector != detector {
            return Err(LdhError::param(
                "events.calibration.detector",
                self.detector.as_str(),
                format!(
                    "the calibration was measured with the {} detector, and this run uses {}: measure it again with ldh agree on results of this detector, or remove [events.calibration]",
                    self.detector.as_str(),
                    detector.as_str()
                ),
            ));
        }
        Ok(())
    }

    /// Shift the heel strikes and toe offs of `ev` (a recording of `duration_s` seconds). An
    /// event shifted outside [0, `duration_s`] is dropped with what belongs to it (a toe off's
    /// landmarks and swing arc, a heel strike's impact delay), so no stride starts or ends
    /// outside the signal. Mid-swings are not events of a reference system and stay.
    pub fn apply(&self, ev: &mut Events, duration_s: f64) {
        let inside = |t: f64| (0.0..=duration_s).contains(&t);
        let hs_keep: Vec<bool> = ev
            .hs_s
            .iter()
            .map(|t| inside(t + self.hs_shift_s))
            .collect();
        let to_keep: Vec<bool> = ev
            .to_s
            .iter()
            .map(|t| inside(t + self.to_shift_s))
            .collect();
        retain_by(&mut ev.hs_s, &hs_keep);
        retain_by(&mut ev.hs_impacts, &hs_keep);
        retain_by(&mut ev.hs_confidence, &hs_keep);
        retain_by(&mut ev.to_confidence, &to_keep);
        retain_by(&mut ev.to_s, &to_keep);
        retain_by(&mut ev.to_landmarks_s, &to_keep);
        retain_by(&mut ev.to_swing_arc_deg, &to_keep);
        ev.hs_s.iter_mut().for_each(|t| *t += self.hs_shift_s);
        ev.to_s.iter_mut().for_each(|t| *t += self.to_shift_s);
    }

    /// The sentence a report gives: "Gait events calibrated against …: heel strikes +12 ms,
    /// toe offs −31 ms (ldh agree)."
    pub fn sentence(&self) -> String {
        format!(
            "Gait events calibrated against {}: heel strikes shifted {}, toe offs {} (measured by ldh agree with the {} detector).",
            self.against.trim().trim_end_matches('.'),
            signed_ms(self.hs_shift_s),
            signed_ms(self.to_shift_s),
            self.detector.as_str()
        )
    }
}

impl super::ValidEventParams {
    /// Add the calibration's shifts, if any, to the events of a recording of `duration_s`
    /// seconds ([`EventCalibration::apply`]).
    pub fn calibrate(&self, ev: &mut Events, duration_s: f64) {
        if let Some(c) = &self.p.calibration {
            c.apply(ev, duration_s);
        }
    }
}

/// `+12 ms` / `−31 ms` / `0 ms` (a shift that rounds to zero has no sign: never `+-0 ms`).
fn signed_ms(s: f64) -> String {
    let ms = (s * 1000.0).round();
    if ms == 0.0 {
        "0 ms".to_string()
    } else if ms < 0.0 {
        format!("−{} ms", -ms)
    } else {
        format!("+{ms} ms")
    }
}

/// Keep the items of `v` whose `keep` is true; a `v` of another length than `keep` (an array
/// the detector does not fill) is left alone.
fn retain_by<T>(v: &mut Vec<T>, keep: &[bool]) {
    if v.len() != keep.len() {
        return;
    }
    let mut i = 0;
    v.retain(|_| {
        i += 1;
        keep[i - 1]
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cal(hs: f64, to: f64) -> EventCalibration {
        EventCalibration {
            hs_shift_s: hs,
            to_shift_s: to,
            detector: EventDetector::GyroBracket,
            against: "force plates (ref.csv)".into(),
        }
    }

    #[test]
    fn shifts_every_event_and_drops_those_outside_the_recording() {
        let mut ev = Events {
            hs_s: vec![0.01, 1.0, 2.0, 2.99],
            to_s: vec![0.6, 1.6, 2.6],
            midswing_s: vec![0.8, 1.8],
            median_stride_s: 1.0,
            to_landmarks_s: vec![[0.5, 0.7, 0.8], [1.5, 1.7, 1.8], [2.5, 2.7, 2.8]],
            to_swing_arc_deg: vec![40.0, 41.0, 42.0],
            hs_confidence: vec![1.0, 0.0, 0.5, 0.7],
            ..Events::default()
        };
        cal(-0.02, 0.03).apply(&mut ev, 3.0);
        let close = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
        };
        assert!(close(&ev.hs_s, &[0.98, 1.98, 2.97]), "{:?}", ev.hs_s);
        assert!(close(&ev.to_s, &[0.63, 1.63, 2.63]), "{:?}", ev.to_s);
        assert_eq!(ev.hs_confidence, vec![0.0, 0.5, 0.7]);
        assert_eq!(ev.to_landmarks_s.len(), 3);
        assert_eq!(ev.midswing_s, vec![0.8, 1.8]);
        // A toe off pushed past the end goes with its landmarks.
        cal(0.0, 0.15).apply(&mut ev, 2.7);
        assert!(close(&ev.to_s, &[0.78, 1.78]), "{:?}", ev.to_s);
        assert_eq!(ev.to_swing_arc_deg, vec![40.0, 41.0]);
    }

    #[test]
    fn refuses_large_shifts_another_detector_and_no_source() {
        assert!(cal(0.012, -0.031).check(EventDetector::GyroBracket).is_ok());
        let e = cal(0.2, 0.0).check(EventDetector::GyroBracket).unwrap_err();
        assert!(e.to_string().contains("hs_shift_s"), "{e}");
        let e = cal(0.0, f64::NAN)
            .check(EventDetector::GyroBracket)
            .unwrap_err();
        assert!(e.to_string().contains("to_shift_s"), "{e}");
        let e = cal(0.0, 0.0).check(EventDetector::Salarian).unwrap_err();
        assert!(
            e.to_string()
                .contains("measured with the gyro-bracket detector"),
            "{e}"
        );
        let mut c = cal(0.0, 0.0);
        c.against = " ".into();
        assert!(c.check(EventDetector::GyroBracket).is_err());
    }

    #[test]
    fn the_report_sentence_gives_both_shifts_in_ms() {
        assert_eq!(
            cal(0.012, -0.031).sentence(),
            "Gait events calibrated against force plates (ref.csv): heel strikes shifted +12 ms, toe offs −31 ms (measured by ldh agree with the gyro-bracket detector)."
        );
        // A shift that rounds to zero (also from below) has no sign.
        assert!(cal(-0.0004, 0.0)
            .sentence()
            .contains("heel strikes shifted 0 ms, toe offs 0 ms"));
    }
}
