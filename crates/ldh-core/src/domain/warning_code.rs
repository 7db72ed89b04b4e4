//! The stable codes of the quality findings (docs/quality.md lists each with its threshold,
//! its source and its consequence): a typed [`WarningCode`], written as its text (`gyro_scale_fault`)
//! in the tables, and read back from it. Code decides on the variant, never on text.

/// Declares [`WarningCode`] with its text, and a constant of the same name in `codes`.
macro_rules! warning_codes {
    ($($(#[$doc:meta])* $variant:ident = $text:literal, $constant:ident;)*) => {
        /// A stable warning code (docs/quality.md).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum WarningCode {
            $($(#[$doc])* $variant,)*
        }

        impl WarningCode {
            /// Every code, in the order of docs/quality.md's list.
            pub const ALL: &'static [WarningCode] = &[$(WarningCode::$variant,)*];

            /// The code as the tables write it (`gyro_scale_fault`).
            pub const fn as_str(self) -> &'static str {
                match self {
                    $(WarningCode::$variant => $text,)*
                }
            }
        }

        /// The codes as constants (`codes::GYRO_SCALE_FAULT`), for the checks that raise them.
        pub mod codes {
            use super::WarningCode;
            $($(#[$doc])* pub const $constant: WarningCode = WarningCode::$variant;)*
        }
    };
}

warning_codes! {
    /// A reader finding (gap, constant or frozen channel, jitter …).
    Input = "input", INPUT;
    /// Gyroscope rates beyond any walking human shank (e.g. amplified ×10).
    GyroScaleFault = "gyro_scale_fault", GYRO_SCALE_FAULT;
    /// Gyroscope samples at the sensor's range.
    GyroClipping = "gyro_clipping", GYRO_CLIPPING;
    /// Accelerometer samples at the sensor's range.
    AccClipping = "acc_clipping", ACC_CLIPPING;
    /// Cadence and stance that no human gait has at the declared sampling rate.
    ImplausibleCadenceForRate = "implausible_cadence_for_rate", IMPLAUSIBLE_CADENCE_FOR_RATE;
    /// Shank angles outside anatomical bounds.
    ImplausibleAngle = "implausible_angle", IMPLAUSIBLE_ANGLE;
    /// The attitude drifts: stance pitch inconsistent from stride to stride.
    AttitudeDivergence = "attitude_divergence", ATTITUDE_DIVERGENCE;
    /// Left and right disagree beyond what one walk allows.
    LrDisagreement = "lr_disagreement", LR_DISAGREEMENT;
    /// Left and right files carry the same signals.
    IdenticalLegs = "identical_legs", IDENTICAL_LEGS;
    /// Left and right may be swapped.
    PossibleSwap = "possible_swap", POSSIBLE_SWAP;
    /// The gait looks like running.
    Running = "running", RUNNING;
    /// The device is mounted upside down relative to its usual orientation.
    UpsideDown = "upside_down", UPSIDE_DOWN;
    /// Too few valid strides.
    FewStrides = "few_strides", FEW_STRIDES;
    /// The sensor height was not given: the stride length used an assumed one (a note), or
    /// depends on it too much to be reported (a warning).
    SensorHeightUnknown = "sensor_height_unknown", SENSOR_HEIGHT_UNKNOWN;
    /// The two sensors' sampling rates differ.
    RateMismatch = "rate_mismatch", RATE_MISMATCH;
    /// The two recordings do not overlap in time.
    NoOverlap = "no_overlap", NO_OVERLAP;
    /// The two recordings differ in length or start.
    LengthMismatch = "length_mismatch", LENGTH_MISMATCH;
    /// The two sensors are not on one clock: the walk's two double supports split as no
    /// walker's do (`pipeline::quality::clocks`); the timings between the legs are withheld.
    ClockOffset = "clock_offset", CLOCK_OFFSET;
    /// Two files whose clocks nothing synchronised, and a step-time asymmetry that the legs'
    /// own swing times do not back: a clock offset could have made it
    /// (`pipeline::quality::clocks`); the timings between the legs are withheld.
    TwoClocks = "two_clocks", TWO_CLOCKS;
    /// Stride length variability mostly the measurement's own noise (from the two legs).
    SvNoise = "sv_noise", SV_NOISE;
    /// Stride length variability whose noise cannot be checked (no other leg to compare with,
    /// or too few strides pairing up with the other leg's: a short walk).
    SvUnchecked = "sv_unchecked", SV_UNCHECKED;
    /// No quiet standing: the shank axis came from the mean acceleration of the walk and no
    /// gyroscope bias was removed at rest; WQK and PBI are withheld (off by ≈ 10°).
    NoQuietStanding = "no_quiet_standing", NO_QUIET_STANDING;
    /// The heel strikes were placed at their own impacts (a note: which rule placed them, and
    /// the walk's median delay from the gyroscope's landmark to the impact).
    HsAtImpact = "hs_at_impact", HS_AT_IMPACT;
    /// Strides at the start or end of the walk excluded as not steady (a note with the window).
    SteadyWindow = "steady_window", STEADY_WINDOW;
    /// Too little steady walking for the variability (CVs withheld).
    TooLittleSteady = "too_little_steady", TOO_LITTLE_STEADY;
    /// The walk never becomes steady: its stride time changes throughout (a trend, or more than
    /// one change of pace), so its variability is withheld (CVs withheld, means of the whole
    /// walk).
    NeverSteady = "never_steady", NEVER_STEADY;
    /// One channel frozen, dropped to zero or spiking for part of the walk, named with its
    /// span; the strides overlapping it are withheld (`pipeline::quality::detect_faults`).
    ChannelFault = "channel_fault", CHANNEL_FAULT;
    /// No stride was found in the leg (why: too slow for the mid-swing threshold, too short …).
    NoStrides = "no_strides", NO_STRIDES;
    /// The manifest gives a group but no affected side: no affected/unaffected comparison.
    AffectedSideUnknown = "affected_side_unknown", AFFECTED_SIDE_UNKNOWN;
}

impl WarningCode {
    /// The finding in a clinician's words, for the pages ("the two legs disagree"), never the
    /// code: the code is the tables' and the technical appendix's (issue 50).
    pub const fn plain(self) -> &'static str {
        use WarningCode as W;
        match self {
            W::Input => "a problem in the recording file",
            W::GyroScaleFault => "gyroscope fault",
            W::GyroClipping => "gyroscope over its range",
            W::AccClipping => "accelerometer over its range",
            W::ImplausibleCadenceForRate => "a cadence no walk has at this sampling rate",
            W::ImplausibleAngle => "shank angles beyond what a leg can do",
            W::AttitudeDivergence => "the sensor's tilt estimate drifts",
            W::LrDisagreement => "the two legs disagree",
            W::IdenticalLegs => "the same recording given for both legs",
            W::PossibleSwap => "left and right may be swapped",
            W::Running => "running, not walking",
            // The note says a device convention or an upside-down mounting, corrected either
            // way: "worn upside down" claimed more than the data show (TRIPOD's Physilog units).
            W::UpsideDown => "sensor axis pointing down the shank (corrected)",
            W::FewStrides => "too few strides",
            W::SensorHeightUnknown => "sensor height not given",
            W::RateMismatch => "the two sensors record at different rates",
            W::NoOverlap => "the two recordings do not overlap in time",
            W::LengthMismatch => "the two recordings differ in length",
            W::ClockOffset => "the two sensors' clocks do not agree",
            W::TwoClocks => "two sensors not known to share a clock",
            W::SvNoise => "variability within the measurement's own noise",
            W::SvUnchecked => "variability that cannot be checked against noise",
            W::NoQuietStanding => "no quiet standing at the start",
            W::HsAtImpact => "heel strikes placed at their impacts",
            W::SteadyWindow => "start or end of the walk not steady",
            W::TooLittleSteady => "too little steady walking",
            W::NeverSteady => "the walk never becomes steady",
            W::ChannelFault => "a sensor channel failed for part of the walk",
            W::NoStrides => "no stride found",
            W::AffectedSideUnknown => "affected side not given",
        }
    }
}

/// A text that is no [`WarningCode`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown warning code '{0}'")]
pub struct UnknownWarningCode(pub String);

impl std::str::FromStr for WarningCode {
    type Err = UnknownWarningCode;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        WarningCode::ALL
            .iter()
            .copied()
            .find(|c| c.as_str() == s)
            .ok_or_else(|| UnknownWarningCode(s.to_string()))
    }
}

impl std::fmt::Display for WarningCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<str> for WarningCode {
    fn eq(&self, other: &str) -> bool {
        self.as_str() == other
    }
}

impl PartialEq<&str> for WarningCode {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

impl serde::Serialize for WarningCode {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl<'de> serde::Deserialize<'de> for WarningCode {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = std::borrow::Cow::<str>::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_reads_back_from_its_text() {
        for c in WarningCode::ALL {
            assert_eq!(c.as_str().parse::<WarningCode>(), Ok(*c));
            let j = serde_json::to_string(c).unwrap();
            assert_eq!(j, format!("\"{}\"", c.as_str()));
            assert_eq!(serde_json::from_str::<WarningCode>(&j).unwrap(), *c);
        }
        assert_eq!(codes::GYRO_SCALE_FAULT.as_str(), "gyro_scale_fault");
        assert!(codes::CHANNEL_FAULT == "channel_fault");
        assert!("frozen".parse::<WarningCode>().is_err());
    }
}
