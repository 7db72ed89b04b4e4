//! The headline's "To do": one action that follows from **why** a value of the summary was not
//! measured (issue 50: a stride length withheld because the two legs disagree asked for the
//! sensor height, which does not change that disagreement).
//!
//! Each quantity of the summary without a value is traced to the findings that withheld it on
//! its leg (`Warning::affects`, written to recordings.csv/JSON with the finding, so a page read
//! back from a folder traces it the same way); each finding's code gives an [`Action`], and the
//! first action in the order of [`Action`] is the page's to-do. A leg that failed comes first.
//! A value withheld by no finding (e.g. too few strides whose length passed its own checks)
//! asks for nothing: no action of the technician changes it short of recording again.

use super::verdict::{Cell, Scope, Verdicts};
use ldh_core::output::{Parameter, RecordingRow};
use ldh_core::pipeline::{Group, Severity, Warning};

/// What the technician can do about a withheld value, in the order the headline prefers them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Action {
    /// The sensor recorded faulty signals (a finding of severity fault).
    CheckSensor,
    /// The two legs disagree, or their files do not belong together (`lr_disagreement`,
    /// `identical_legs`, `possible_swap`, `no_overlap`, `length_mismatch`, `rate_mismatch`).
    CheckFiles,
    /// The two sensors are not on one clock (`clock_offset`), or not known to be and the steps
    /// look uneven (`two_clocks`).
    Synchronise,
    /// The stride length depends on the sensor's height, not given (`sensor_height_unknown`).
    MeasureHeight,
    /// No quiet standing, so no gyroscope bias removed (`no_quiet_standing`).
    StandStill,
    /// Too little steady walking for the variability (`too_little_steady`).
    SteadyWalk,
    /// Too few strides (`few_strides`, `sv_noise`, and `sv_unchecked` when the walk held too
    /// few strides to pair up: [`Action::of_unchecked`]).
    LongerWalk,
}

impl Action {
    /// The action a finding `w` of the leg `row` that withholds a value asks for (`None`: none
    /// helps); `sides` are the walk's legs.
    fn of(w: &Warning, row: &RecordingRow, sides: &[&RecordingRow]) -> Option<Action> {
        if w.code == ldh_core::pipeline::WarningCode::SvUnchecked {
            return Action::of_unchecked(row, sides);
        }
        if w.severity == Severity::Fault {
            return Some(Action::CheckSensor);
        }
        use ldh_core::pipeline::WarningCode as C;
        Some(match w.code {
            C::LrDisagreement
            | C::IdenticalLegs
            | C::PossibleSwap
            | C::NoOverlap
            | C::LengthMismatch
            | C::RateMismatch => Action::CheckFiles,
            C::ClockOffset | C::TwoClocks => Action::Synchronise,
            C::SensorHeightUnknown => Action::MeasureHeight,
            C::NoQuietStanding => Action::StandStill,
            C::TooLittleSteady | C::NeverSteady => Action::SteadyWalk,
            C::FewStrides | C::SvNoise => Action::LongerWalk,
            _ => return None,
        })
    }

    /// A stride length variability withheld as unchecked (`sv_unchecked`) on `row`: it is checked
    /// against the other leg's strides, so a longer walk helps only when that check had too few
    /// strides on both legs (both withheld as unchecked). When the other leg has no stride length
    /// variability of its own (not analysed, or withheld for its own reason), that leg's reason
    /// asks for its own action and this one asks for none: a simulated hemiparetic walk whose
    /// left stride length failed its drift check asked to "record a longer walk" of a 55 s
    /// steady walk.
    fn of_unchecked(row: &RecordingRow, sides: &[&RecordingRow]) -> Option<Action> {
        let other = sides.iter().find(|r| r.side != row.side)?;
        other
            .warnings
            .iter()
            .any(|w| {
                w.code == ldh_core::pipeline::WarningCode::SvUnchecked
                    && w.withholds(Parameter::StrideLengthCv)
            })
            .then_some(Action::LongerWalk)
    }

    /// The sentence; `sides` are the legs concerned (the sensors to check).
    fn sentence(self, sides: &[&str]) -> String {
        match self {
            Action::CheckSensor if sides.len() > 1 => {
                "Check both sensors (they recorded faulty signals) and record the walk again."
                    .into()
            }
            Action::CheckSensor => format!(
                "Check the {} sensor (it recorded faulty signals) and record the walk again.",
                sides.first().copied().unwrap_or("")
            ),
            Action::CheckFiles => "Check that the two files come from the same walk and that each is named for the leg it was worn on (the legs disagree, which no setting of the analysis explains), then analyse them again.".into(),
            Action::Synchronise => "Synchronise the two sensors' clocks before the next recording (the device's own synchronisation, or both started together), so the timings between the legs can be measured.".into(),
            Action::MeasureHeight => {
                "Measure the sensor's height above the ankle and re-run the analysis with it.".into()
            }
            Action::StandStill => {
                "Next time, have the person stand still for 2 s before walking, then re-run.".into()
            }
            Action::SteadyWalk => "Record a longer walk at the person's own steady pace (at least 30 s after the start-up), so its variability can be measured.".into(),
            Action::LongerWalk => "Record a longer walk (at least 30 s of straight walking).".into(),
        }
    }
}

/// The parameter whose withholding leaves a summary row without a value (the cadence comes
/// from the stride times).
fn source(p: Parameter) -> Parameter {
    if p == Parameter::StepFrequency {
        Parameter::StrideTime
    } else {
        p
    }
}

/// The actions the missing values of the summary ask for, with the leg each is about.
pub(crate) fn actions<'a>(v: &Verdicts, sides: &[&'a RecordingRow]) -> Vec<(Action, &'a str)> {
    let mut out: Vec<(Action, &str)> = Vec::new();
    for row in v.rows.iter().filter(|r| r.q.in_summary) {
        let p = source(row.q.parameter);
        let missing_sides: Vec<&&RecordingRow> = match row.q.scope {
            Scope::Walk if matches!(row.cells.first(), Some(Cell::NotMeasured(_))) => {
                sides.iter().collect()
            }
            Scope::Walk => Vec::new(),
            Scope::Side => sides
                .iter()
                .filter(|r| {
                    let i = usize::from(r.side == ldh_core::Side::Right);
                    matches!(row.cells.get(i), Some(Cell::NotMeasured(_)))
                })
                .collect(),
        };
        for r in missing_sides {
            for w in r.warnings.iter().filter(|w| w.withholds(p)) {
                if let Some(a) = Action::of(w, r, sides) {
                    if !out.contains(&(a, r.side.as_str())) {
                        out.push((a, r.side.as_str()));
                    }
                }
            }
        }
    }
    out.sort();
    out
}

/// The one thing to do, the first that applies: a leg that failed, then the action of the
/// findings that withheld the summary's missing values ([`Action`] order), then, for an LDH
/// subject, the affected side when it is not given.
pub(crate) fn to_do(v: &Verdicts, sides: &[&RecordingRow]) -> Option<String> {
    if let Some(r) = sides.iter().find(|r| !r.is_ok()) {
        return Some(format!(
            "Check the {} recording (the reason is in the box below) and analyse it again.",
            r.side
        ));
    }
    let acts = actions(v, sides);
    if let Some((a, _)) = acts.first() {
        // Every leg the first action is about (a fault on both legs names both sensors).
        let legs: Vec<&str> = acts.iter().filter(|x| x.0 == *a).map(|x| x.1).collect();
        return Some(a.sentence(&legs));
    }
    let ldh = sides.iter().any(|r| matches!(r.group, Some(Group::Ldh)));
    if ldh && sides.iter().all(|r| r.affected_side.is_none()) {
        return Some(
            "The affected side is not given: add it to the manifest so the legs are compared as affected and unaffected."
                .into(),
        );
    }
    None
}
