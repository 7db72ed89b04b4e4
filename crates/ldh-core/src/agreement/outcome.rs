//! What `ldh agree` found ([`AgreementReport`], what `agreement.json` holds) and the pieces both
//! of its steps fill: the trials' clock offsets, the event rows, the parameter rows. Below
//! [`super::run`] and its event step (`run_events.rs`), which write into it.

use serde::{Deserialize, Serialize};

use crate::domain::Legs;
use crate::pipeline::EventKind;
use crate::Side;

use super::{AgreementParams, ClockOffset, MatchSummary, ParameterAgreement};

/// The group of the pooled rows (every subject).
pub const ALL_GROUPS: &str = "all";

/// The group of a subject whose manifest gives none.
pub const UNLABELLED: &str = "unlabelled";

/// A closed set of labels of `agreement.json`: each variant written as its lowercase name, read
/// by serde and shown by `Display` as the same word, so code compares variants, never text.
macro_rules! label {
    ($(#[$m:meta])* $name:ident { $($(#[$vm:meta])* $v:ident => $s:literal,)+ }) => {
        $(#[$m])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
        #[serde(rename_all = "lowercase")]
        pub enum $name {
            $($(#[$vm])* $v,)+
        }
        impl $name {
            /// The label as `agreement.json` writes it.
            pub fn as_str(self) -> &'static str {
                match self {
                    $($name::$v => $s,)+
                }
            }
        }
        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.as_str())
            }
        }
    };
}

label! {
    /// Which system an unmatched event came from.
    System {
        /// ldh's event (a false positive).
        Ldh => "ldh",
        /// The reference's event (missed by ldh).
        Reference => "reference",
    }
}

label! {
    /// Where a trial's clock offset came from.
    OffsetSource {
        /// An `offset_s` column of the reference file.
        File => "file",
        /// `--offset-s X`.
        Given => "given",
        /// Estimated from the events.
        Estimated => "estimated",
        /// No offset (0 s).
        None => "none",
    }
}

label! {
    /// The level a parameter is compared at.
    Level {
        /// Per stride.
        Stride => "stride",
        /// Per recording.
        Recording => "recording",
    }
}

/// Detection rates and timing errors of one event kind on one side (or both), in one group
/// (or all).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EventAgreement {
    /// `HS` or `TO`.
    pub event: EventKind,
    /// `left`, `right` or `both`.
    pub side: Legs,
    /// `all`, or the subjects' group (`healthy`, `ldh`, another label, `unlabelled`).
    #[serde(default = "all_groups")]
    pub group: String,
    /// Rates and errors (ldh − reference, s).
    pub summary: MatchSummary,
}

fn all_groups() -> String {
    ALL_GROUPS.into()
}

/// An event without a partner.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnmatchedEvent {
    /// `ldh` (a false positive) or `reference` (a missed event).
    pub system: System,
    /// Subject.
    pub subject_id: String,
    /// Trial.
    pub trial_id: String,
    /// The subject's group (`unlabelled` without one).
    #[serde(default)]
    pub group: String,
    /// Leg.
    pub side: Side,
    /// `HS` or `TO`.
    pub event: EventKind,
    /// Time on the reference clock, s (ldh's with the offset removed).
    pub time_s: f64,
}

/// A matched pair of events.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MatchedEvent {
    /// Subject.
    pub subject_id: String,
    /// Trial.
    pub trial_id: String,
    /// The subject's group.
    pub group: String,
    /// Leg.
    pub side: Side,
    /// `HS` or `TO`.
    pub event: EventKind,
    /// The reference's time, s.
    pub reference_time_s: f64,
    /// ldh − reference, s (ldh's time with the offset removed).
    pub error_s: f64,
}

/// One group of the trials the reference covers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GroupCount {
    /// `healthy`, `ldh`, another label, or `unlabelled`.
    pub group: String,
    /// Subjects of the group the reference covers.
    pub subjects: usize,
    /// Their trials the reference covers.
    pub trials: usize,
}

/// The clock offset used for one trial.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialOffset {
    /// Subject.
    pub subject_id: String,
    /// Trial (empty without one).
    pub trial_id: String,
    /// ldh clock − reference clock, s (subtracted from ldh's times).
    pub offset_s: f64,
    /// `file` (an `offset_s` column), `given` (`--offset-s X`), `estimated` or `none`.
    pub source: OffsetSource,
    /// The estimate, when estimated (`offset_s` is its best offset polished).
    pub estimate: Option<ClockOffset>,
}

/// One pair of values (NaN: missing on that side, dropped from the statistics).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PairedValue {
    /// Subject.
    pub subject_id: String,
    /// Trial.
    pub trial_id: String,
    /// Leg.
    pub side: Side,
    /// ldh's stride number (per-stride pairs).
    pub stride_index: Option<usize>,
    /// ldh's value (`None`: withheld or missing).
    pub ldh: Option<f64>,
    /// The reference value (`None`: empty cell).
    pub reference: Option<f64>,
}

/// The agreement of one parameter at one level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParameterResult {
    /// `stride` or `recording`.
    pub level: Level,
    /// The column, e.g. `stride_time_s`.
    pub parameter: String,
    /// The statistics, when they could be computed.
    pub agreement: Option<ParameterAgreement>,
    /// Why not, otherwise.
    pub not_computed: Option<String>,
    /// The pairs, in the order of the results.
    pub pairs: Vec<PairedValue>,
}

/// Everything `ldh agree` found (what `agreement.json` holds).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AgreementReport {
    /// The parameters used.
    pub params: AgreementParams,
    /// The reference files.
    pub reference_files: Vec<String>,
    /// The clock offset of each trial the reference covers.
    pub offsets: Vec<TrialOffset>,
    /// The groups of the subjects the reference covers (the manifest's `group`), in order of
    /// first appearance.
    #[serde(default)]
    pub groups: Vec<GroupCount>,
    /// Per event kind: left, right, both (every subject: group `all`).
    pub events: Vec<EventAgreement>,
    /// The same per group, when [`Self::groups`] has two or more (else empty: the one group's
    /// rows are [`Self::events`]).
    #[serde(default)]
    pub events_by_group: Vec<EventAgreement>,
    /// Matched events with their timing errors, in the order matched.
    #[serde(default)]
    pub event_pairs: Vec<MatchedEvent>,
    /// Unmatched events (ldh's only inside the span the reference covers).
    pub unmatched_events: Vec<UnmatchedEvent>,
    /// Reference strides (with a time or a number).
    pub reference_strides: usize,
    /// Of those, matched to an ldh stride.
    pub strides_matched: usize,
    /// Per parameter: stride level first, then recording level.
    pub parameters: Vec<ParameterResult>,
}

/// (subject, trial).
pub(crate) type Trial = (String, String);

pub(crate) const KINDS: [EventKind; 2] = [EventKind::HeelStrike, EventKind::ToeOff];
pub(crate) const SIDES: [Side; 2] = [Side::Left, Side::Right];

/// The clock offset of `trial` in `report` (0 when it has none).
pub(crate) fn offset_of(report: &AgreementReport, (s, t): &Trial) -> f64 {
    report
        .offsets
        .iter()
        .find(|o| &o.subject_id == s && &o.trial_id == t)
        .map_or(0.0, |o| o.offset_s)
}
