//! Why a stride is not valid, or which of its values is withheld (issue 48: typed codes, no
//! logic reads a reason's text). A stride's findings are [`StrideFinding`]s: a typed
//! [`StrideCode`] and the text `strides.csv` writes in `reason`. Each code has a stable text
//! ([`StrideCode::as_code`], the `reason_codes` column, read back by [`str::parse`]), says
//! whether it excludes the stride from the means ([`StrideCode::excludes`]) and has one
//! plain-language wording ([`StrideCode::plain`], the report's "Strides excluded" rows).
//! docs/quality.md lists the checks behind them.

use std::borrow::Cow;

use crate::domain::{UnsureEvent, WarningCode};

/// What a stride's own length check found ([`super::LengthEstimate::check`], the segmentation
/// and the checks between strides and legs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LengthCheck {
    /// The ACC-only attitude: the acceleration is not integrated.
    AccOnly,
    /// The accelerometer clipped, and the reconstruction's drift could move the ankle too far.
    Clipped,
    /// Velocity drift over the stride (with or without a tilt to explain it).
    Drift,
    /// The attitude needed too large a tilt correction.
    TiltCorrection,
    /// The ankle ends off the floor level.
    Floor,
    /// The length disagrees with the shank-pendulum estimate.
    Pendulum,
    /// Far from the median length of the strides around it in its bout.
    BoutMedian,
    /// Contradicted by the other leg's strides over the same time.
    OtherLeg,
    /// The integration gave no finite length.
    NotIntegrable,
}

impl LengthCheck {
    /// Every check, in the order of the enum.
    pub const ALL: [LengthCheck; 9] = [
        LengthCheck::AccOnly,
        LengthCheck::Clipped,
        LengthCheck::Drift,
        LengthCheck::TiltCorrection,
        LengthCheck::Floor,
        LengthCheck::Pendulum,
        LengthCheck::BoutMedian,
        LengthCheck::OtherLeg,
        LengthCheck::NotIntegrable,
    ];

    /// The check in the words of a leg's withheld stride length ("… (velocity drift)").
    pub fn words(self) -> &'static str {
        match self {
            LengthCheck::AccOnly => "the ACC-only attitude cannot separate gravity from motion",
            LengthCheck::Clipped => "accelerometer clipped",
            LengthCheck::Drift => "velocity drift",
            LengthCheck::TiltCorrection => "attitude tilt correction too large",
            LengthCheck::Floor => "ankle off the floor level",
            LengthCheck::Pendulum => "disagrees with the shank-pendulum estimate",
            LengthCheck::BoutMedian => "far from the median of the strides around it",
            LengthCheck::OtherLeg => "contradicted by the other leg's strides",
            LengthCheck::NotIntegrable => "not integrable",
        }
    }

    /// The code text after `length_` (`drift` → `length_drift`).
    fn key(self) -> &'static str {
        match self {
            LengthCheck::AccOnly => "acc_only",
            LengthCheck::Clipped => "clipped",
            LengthCheck::Drift => "drift",
            LengthCheck::TiltCorrection => "tilt_correction",
            LengthCheck::Floor => "floor",
            LengthCheck::Pendulum => "pendulum",
            LengthCheck::BoutMedian => "bout_median",
            LengthCheck::OtherLeg => "other_leg",
            LengthCheck::NotIntegrable => "not_integrable",
        }
    }
}

/// What a quality finding does to a stride.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FindingEffect {
    /// The stride is not valid (a fault over it, or a finding that withholds every parameter).
    Excludes,
    /// Its angles (WQK, PBI, BDK) are withheld; it stays valid.
    Angles,
    /// Its stride length (and speed) is withheld; it stays valid.
    Length,
    /// Its angles and its stride length are withheld; it stays valid.
    AnglesAndLength,
}

impl FindingEffect {
    /// Whether the stride's length is withheld.
    pub fn withholds_length(self) -> bool {
        matches!(
            self,
            FindingEffect::Excludes | FindingEffect::Length | FindingEffect::AnglesAndLength
        )
    }

    /// The suffix of the code text (`:angles` …; empty when it excludes the stride).
    fn suffix(self) -> &'static str {
        match self {
            FindingEffect::Excludes => "",
            FindingEffect::Angles => ":angles",
            FindingEffect::Length => ":length",
            FindingEffect::AnglesAndLength => ":angles_and_length",
        }
    }

    /// What is withheld, in words (`None` when the whole stride is).
    fn words(self) -> Option<&'static str> {
        match self {
            FindingEffect::Excludes => None,
            FindingEffect::Angles => Some("angles"),
            FindingEffect::Length => Some("stride length"),
            FindingEffect::AnglesAndLength => Some("angles and stride length"),
        }
    }
}

/// Why a stride is not valid, or which of its values is withheld.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StrideCode {
    /// Stride time outside the stride range.
    StrideTime,
    /// No toe off, or several.
    ToeOff,
    /// Part of a turn.
    Turn,
    /// First or last stride of a walking bout.
    BoutEdge,
    /// Outside the steady walking ([`super::exclude_unsteady`]).
    NotSteady,
    /// Its length failed a check (the stride stays valid).
    Length(LengthCheck),
    /// Its length passed its own checks, but too few of the leg's did
    /// ([`super::withhold_unvouched_lengths`]; the stride stays valid).
    LengthNotVouched,
    /// Its angles are outside anatomical bounds.
    AnglesOutOfBounds,
    /// Bounded by an event the signals cannot place well (docs/quality.md "Unsure events").
    UnsureEvent(UnsureEvent),
    /// A quality finding (its warning code) about the whole leg or a span of it, and what it
    /// does to the stride.
    Finding {
        /// The warning code.
        code: WarningCode,
        /// Whether it excludes the stride or withholds some of its values.
        effect: FindingEffect,
    },
}

const UNSURE: [UnsureEvent; 3] = [
    UnsureEvent::NoImpact,
    UnsureEvent::TwoLandings,
    UnsureEvent::TwoPushOffs,
];

fn unsure_key(u: UnsureEvent) -> &'static str {
    match u {
        UnsureEvent::NoImpact => "unsure_hs_no_impact",
        UnsureEvent::TwoLandings => "unsure_hs_two_landings",
        UnsureEvent::TwoPushOffs => "unsure_to_two_push_offs",
    }
}

/// The codes without a part (`turn`, `bout_edge` …) with their text.
const SIMPLE: [(StrideCode, &str); 7] = [
    (StrideCode::StrideTime, "stride_time_out_of_range"),
    (StrideCode::ToeOff, "toe_off"),
    (StrideCode::Turn, "turn"),
    (StrideCode::BoutEdge, "bout_edge"),
    (StrideCode::NotSteady, "not_steady"),
    (StrideCode::LengthNotVouched, "length_not_vouched"),
    (StrideCode::AnglesOutOfBounds, "angles_out_of_bounds"),
];

impl StrideCode {
    /// The stable text of the code, as the `reason_codes` column writes it: `turn`,
    /// `bout_edge`, `stride_time_out_of_range`, `toe_off`, `not_steady`,
    /// `angles_out_of_bounds`, `unsure_hs_no_impact` …, `length_drift` … (a length check),
    /// `length_not_vouched`; a quality finding is its warning code (`channel_fault`) when it
    /// excludes the stride, else the code with what it withholds (`no_quiet_standing:angles`,
    /// `lr_disagreement:length`, `…:angles_and_length`).
    pub fn as_code(&self) -> Cow<'static, str> {
        if let Some((_, t)) = SIMPLE.iter().find(|(c, _)| c == self) {
            return Cow::Borrowed(t);
        }
        match *self {
            StrideCode::Length(c) => Cow::Owned(format!("length_{}", c.key())),
            StrideCode::UnsureEvent(u) => Cow::Borrowed(unsure_key(u)),
            StrideCode::Finding { code, effect } => {
                Cow::Owned(format!("{}{}", code.as_str(), effect.suffix()))
            }
            _ => unreachable!("every code without a part is in SIMPLE"),
        }
    }

    /// Whether a stride with this finding is excluded from the means (not valid): the stride
    /// time, toe off, turn, bout edge, steadiness, angle bounds, an unsure event and a finding
    /// that excludes it; a length check or a finding that withholds some values leaves the
    /// stride valid for the rest.
    pub fn excludes(&self) -> bool {
        match self {
            StrideCode::Length(_) | StrideCode::LengthNotVouched => false,
            StrideCode::Finding { effect, .. } => *effect == FindingEffect::Excludes,
            _ => true,
        }
    }

    /// The code in plain words, one wording per code for a clinician (the report's "Strides
    /// excluded" rows): what it means, not the stride's own numbers.
    pub fn plain(&self) -> Cow<'static, str> {
        match *self {
            StrideCode::StrideTime => "stride time outside the plausible range".into(),
            StrideCode::ToeOff => "toe off not found, or more than one".into(),
            StrideCode::Turn => "turning".into(),
            StrideCode::BoutEdge => "first or last stride of a walking bout".into(),
            StrideCode::NotSteady => {
                "not steady walking (speeding up, slowing down or a change of pace)".into()
            }
            StrideCode::Length(c) => format!("stride length withheld ({})", c.words()).into(),
            StrideCode::LengthNotVouched => {
                "stride length withheld (too few of the leg's strides pass the integration checks)"
                    .into()
            }
            StrideCode::AnglesOutOfBounds => "shank angles outside anatomical bounds".into(),
            StrideCode::UnsureEvent(u) => u.as_str().into(),
            StrideCode::Finding { code, effect } => {
                let what = code.plain();
                match effect.words() {
                    None => format!("signal quality: {what}").into(),
                    Some(values) => format!("{values} withheld: {what}").into(),
                }
            }
        }
    }
}

impl std::fmt::Display for StrideCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.as_code())
    }
}

/// A text that is no [`StrideCode`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown stride reason code '{0}'")]
pub struct UnknownStrideCode(pub String);

impl std::str::FromStr for StrideCode {
    type Err = UnknownStrideCode;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let unknown = || UnknownStrideCode(s.to_string());
        if let Some((c, _)) = SIMPLE.iter().find(|(_, t)| *t == s) {
            return Ok(*c);
        }
        if let Some(u) = UNSURE.into_iter().find(|u| unsure_key(*u) == s) {
            return Ok(StrideCode::UnsureEvent(u));
        }
        if let Some(k) = s.strip_prefix("length_") {
            if let Some(c) = LengthCheck::ALL.into_iter().find(|c| c.key() == k) {
                return Ok(StrideCode::Length(c));
            }
        }
        let (code, suffix) = match s.find(':') {
            Some(i) => s.split_at(i),
            None => (s, ""),
        };
        let effect = [
            FindingEffect::Excludes,
            FindingEffect::Angles,
            FindingEffect::Length,
            FindingEffect::AnglesAndLength,
        ]
        .into_iter()
        .find(|e| e.suffix() == suffix)
        .ok_or_else(unknown)?;
        let code = code.parse::<WarningCode>().map_err(|_| unknown())?;
        Ok(StrideCode::Finding { code, effect })
    }
}

/// One reason of a stride: a typed code and its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StrideFinding {
    /// What it is.
    pub code: StrideCode,
    /// The text, as `strides.csv` writes it.
    pub message: String,
}

impl StrideFinding {
    /// A finding of `code` with `message`.
    pub fn new(code: StrideCode, message: impl Into<String>) -> StrideFinding {
        StrideFinding {
            code,
            message: message.into(),
        }
    }
}

/// The codes of a stride's findings, in the order of its `reason`'s reasons: the
/// `reason_codes` column, written as the codes' texts joined by `; ` (an empty cell when
/// valid with every value reported) and read back from it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct StrideCodes(pub Vec<StrideCode>);

impl StrideCodes {
    /// The codes that exclude the stride from the means ([`StrideCode::excludes`]).
    pub fn excluding(&self) -> impl Iterator<Item = &StrideCode> {
        self.0.iter().filter(|c| c.excludes())
    }
}

impl std::fmt::Display for StrideCodes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, c) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            f.write_str(&c.as_code())?;
        }
        Ok(())
    }
}

impl std::str::FromStr for StrideCodes {
    type Err = UnknownStrideCode;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        s.split(';')
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .map(str::parse)
            .collect::<Result<Vec<_>, _>>()
            .map(StrideCodes)
    }
}

impl serde::Serialize for StrideCodes {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> serde::Deserialize<'de> for StrideCodes {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = Cow::<str>::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_reads_back_from_its_text() {
        let mut all: Vec<StrideCode> = SIMPLE.iter().map(|(c, _)| *c).collect();
        all.extend(LengthCheck::ALL.map(StrideCode::Length));
        all.extend(UNSURE.map(StrideCode::UnsureEvent));
        for code in WarningCode::ALL.iter().copied() {
            for effect in [
                FindingEffect::Excludes,
                FindingEffect::Angles,
                FindingEffect::Length,
                FindingEffect::AnglesAndLength,
            ] {
                all.push(StrideCode::Finding { code, effect });
            }
        }
        let mut texts = std::collections::HashSet::new();
        for c in &all {
            let t = c.as_code();
            assert!(texts.insert(t.to_string()), "{t} twice");
            assert_eq!(t.parse::<StrideCode>(), Ok(*c));
            assert!(!c.plain().is_empty());
        }
        let list = StrideCodes(vec![
            StrideCode::Turn,
            StrideCode::Length(LengthCheck::Drift),
        ]);
        assert_eq!(list.to_string(), "turn; length_drift");
        assert_eq!(
            "turn; length_drift".parse::<StrideCodes>(),
            Ok(list.clone())
        );
        assert_eq!(list.excluding().collect::<Vec<_>>(), [&StrideCode::Turn]);
        assert_eq!("".parse::<StrideCodes>(), Ok(StrideCodes::default()));
        assert!("turning".parse::<StrideCode>().is_err());
        assert!("channel_fault:legs".parse::<StrideCode>().is_err());
    }
}
