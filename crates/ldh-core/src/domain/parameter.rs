//! Every gait parameter, defined once (paper Table 2 and Table 3, plus PBI; issue 48): its code,
//! the column of the per-recording table, its plain name, its unit, what it means, and what its
//! per-stride value means when the per-stride table has one. The column dictionary
//! (`ldh columns`, docs/columns.md), the tables' parameter columns, the report's rows and the
//! reliability table all read these definitions, so a parameter has one name and one unit
//! everywhere. A column name given from outside (`ldh train --features`, a model file's feature
//! list) becomes a `Parameter` once, by [`Parameter::from_column`], with a typed
//! [`UnknownParameter`] error.

use crate::error::LdhError;

/// A gait parameter of the cohort tables, the classifiers and the reports.
/// Declared in the order of [`Parameter::ALL`] ([`Parameter::index`] relies on it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Parameter {
    /// SF, steps/s.
    StepFrequency,
    /// SL, m.
    StrideLength,
    /// SS, m/s.
    Speed,
    /// STT, s.
    StepTime,
    /// ST, s.
    StrideTime,
    /// STP, fraction of the gait cycle.
    StanceRatio,
    /// SWP, fraction of the gait cycle.
    SwingRatio,
    /// SV, SD / mean.
    StrideLengthCv,
    /// STV, SD / mean.
    StrideTimeCv,
    /// STA, 1/s (largest Lyapunov exponent).
    Sta,
    /// WQK, deg.
    Wqk,
    /// PBI, deg (ldh's addition).
    Pbi,
    /// BDK, deg.
    Bdk,
    /// DS, fraction of the gait cycle (ldh's addition, issue 49: double support).
    DoubleSupport,
    /// A made-up parameter (twice the stride time, s; per stride too), only with the test-only
    /// feature `dummy-parameter`: the proof that a parameter is its definition and its
    /// computation (per walk and per stride).
    #[cfg(feature = "dummy-parameter")]
    Dummy,
}

/// The definition of one parameter: everything any output says about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Definition {
    /// Code in the paper's Table 2 (`SF`, `SL` …).
    pub code: &'static str,
    /// Column of the per-recording table (units in the name).
    pub column: &'static str,
    /// Plain name, as in a sentence ("walking speed"; a report's row capitalises it).
    pub name: &'static str,
    /// Unit of the value as the tables hold it (its text: [`Unit::as_str`]).
    pub unit: Unit,
    /// How a report shows it: the factor from [`Definition::unit`] and the unit it then has
    /// (the same quantity: a fraction × 100 is a per cent, steps/s × 60 steps/min).
    pub display: (f64, &'static str),
    /// The values it can physically have, in [`Definition::unit`] (a classifier's feature
    /// statistics outside it make a model file implausible, `ml::model_plausible`).
    pub range: (f64, f64),
    /// What the per-side value means (the column dictionary, after the code).
    pub description: &'static str,
    /// What the per-stride value means, when the per-stride table has one (same column name).
    pub per_stride: Option<&'static str>,
}

/// The unit of a parameter's value as the tables hold it: what code decides on (a report's
/// decimals for an angle), its text ([`Unit::as_str`]) what every output shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Unit {
    /// Steps per second.
    StepsPerS,
    /// Metres.
    M,
    /// Metres per second.
    Mps,
    /// Seconds.
    S,
    /// A share of the stride (heel strike to the next heel strike of the same leg, the gait
    /// cycle): [`GAIT_CYCLE_FRACTION`].
    GaitCycleFraction,
    /// The coefficient of variation: [`CV`].
    Cv,
    /// Per second (a Lyapunov exponent).
    PerS,
    /// Degrees (an angle).
    Deg,
}

impl Unit {
    /// The unit's text, as the column dictionary, the reports and the reliability table show it.
    pub const fn as_str(self) -> &'static str {
        match self {
            Unit::StepsPerS => "steps/s",
            Unit::M => "m",
            Unit::Mps => "m/s",
            Unit::S => "s",
            Unit::GaitCycleFraction => GAIT_CYCLE_FRACTION,
            Unit::Cv => CV,
            Unit::PerS => "1/s",
            Unit::Deg => "deg",
        }
    }
}

impl std::fmt::Display for Unit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The unit of stance and swing: a share of the stride (heel strike to the next heel strike
/// of the same leg, the gait cycle).
pub const GAIT_CYCLE_FRACTION: &str = "fraction of the gait cycle";

/// The unit of the variability parameters: the coefficient of variation.
pub const CV: &str = "SD / mean";

const fn d(
    (code, column, name, unit): (&'static str, &'static str, &'static str, Unit),
    display: (f64, &'static str),
    range: (f64, f64),
    description: &'static str,
    per_stride: Option<&'static str>,
) -> Definition {
    Definition {
        code,
        column,
        name,
        unit,
        display,
        range,
        description,
        per_stride,
    }
}

const AS_IS_S: (f64, &str) = (1.0, "s");
const AS_IS_M: (f64, &str) = (1.0, "m");
const AS_IS_DEG: (f64, &str) = (1.0, "deg");
const PER_CENT_OF_CYCLE: (f64, &str) = (100.0, "% of the gait cycle");
const CV_PER_CENT: (f64, &str) = (100.0, "CV %");
/// The range of a share of the gait cycle.
const UNIT: (f64, f64) = (0.0, 1.0);
/// The range of a shank angle, deg.
const ANGLE: (f64, f64) = (-360.0, 360.0);

/// A column name that is not a parameter of [`Parameter::ALL`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown feature '{0}'; known: {known}", known = Parameter::columns().join(", "))]
pub struct UnknownParameter(pub String);

impl From<UnknownParameter> for LdhError {
    fn from(e: UnknownParameter) -> Self {
        LdhError::param(
            "features",
            &e.0,
            format!(
                "unknown feature; known: {}",
                Parameter::columns().join(", ")
            ),
        )
    }
}

impl Parameter {
    /// Every parameter, in the order of the paper's Table 3 (plus PBI, then double support).
    pub const ALL: [Parameter; Parameter::COUNT] = [
        Parameter::StepFrequency,
        Parameter::StrideLength,
        Parameter::Speed,
        Parameter::StepTime,
        Parameter::StrideTime,
        Parameter::StanceRatio,
        Parameter::SwingRatio,
        Parameter::StrideLengthCv,
        Parameter::StrideTimeCv,
        Parameter::Sta,
        Parameter::Wqk,
        Parameter::Pbi,
        Parameter::Bdk,
        Parameter::DoubleSupport, // issue 49
        #[cfg(feature = "dummy-parameter")]
        Parameter::Dummy,
    ];

    /// How many parameters there are.
    pub const COUNT: usize = 14 + cfg!(feature = "dummy-parameter") as usize;

    /// Every parameter in the column order of the per-recording table (recordings.csv).
    pub const TABLE_ORDER: [Parameter; Parameter::COUNT] = [
        Parameter::StrideTime,
        Parameter::StepTime,
        Parameter::StepFrequency,
        Parameter::StanceRatio,
        Parameter::SwingRatio,
        Parameter::DoubleSupport, // issue 49
        Parameter::StrideLength,
        Parameter::Speed,
        Parameter::StrideLengthCv,
        Parameter::StrideTimeCv,
        Parameter::Sta,
        Parameter::Wqk,
        Parameter::Pbi,
        Parameter::Bdk,
        #[cfg(feature = "dummy-parameter")]
        Parameter::Dummy,
    ];

    /// How many parameters have a per-stride value ([`Definition::per_stride`]).
    pub const PER_STRIDE_COUNT: usize = {
        let mut n = 0;
        let mut i = 0;
        while i < Parameter::COUNT {
            n += Parameter::TABLE_ORDER[i].definition().per_stride.is_some() as usize;
            i += 1;
        }
        n
    };

    /// The parameters with a per-stride value ([`Definition::per_stride`]), in the order of
    /// [`Parameter::TABLE_ORDER`]: the parameter columns of strides.csv, in this order.
    pub const PER_STRIDE: [Parameter; Parameter::PER_STRIDE_COUNT] = {
        let mut out = [Parameter::StrideTime; Parameter::PER_STRIDE_COUNT];
        let (mut i, mut k) = (0, 0);
        while i < Parameter::COUNT {
            let p = Parameter::TABLE_ORDER[i];
            if p.definition().per_stride.is_some() {
                out[k] = p;
                k += 1;
            }
            i += 1;
        }
        out
    };

    /// The parameter's definition.
    pub const fn definition(self) -> Definition {
        use Parameter::*;
        match self {
            StepFrequency => d(
                ("SF", "step_frequency_steps_per_s", "cadence", Unit::StepsPerS),
                (60.0, "steps/min"),
                (0.1, 6.0),
                "1 / mean step time (× 60 = steps/min of this side; the report's cadence is one value per walk from both legs).",
                None,
            ),
            StrideLength => d(
                ("SL", "stride_length_m", "stride length", Unit::M),
                AS_IS_M,
                (0.0, 4.0),
                "mean distance the foot travels over a stride (both feet travel the same distance on a straight walk).",
                Some("Stride length; empty when withheld (`reason` says why)."),
            ),
            Speed => d(
                ("SS", "speed_mps", "walking speed", Unit::Mps),
                (1.0, "m/s"),
                (0.0, 6.0),
                "mean walking speed, stride length / stride time.",
                Some("Stride length / stride time."),
            ),
            StepTime => d(
                ("STT", "step_time_s", "step time", Unit::S),
                AS_IS_S,
                (0.05, 10.0),
                "mean step time (the other leg's heel strike to this leg's); empty with one leg.",
                None,
            ),
            StrideTime => d(
                ("ST", "stride_time_s", "stride time", Unit::S),
                AS_IS_S,
                (0.1, 20.0),
                "mean stride time (heel strike to the next heel strike of the same leg).",
                Some("Stride time."),
            ),
            StanceRatio => d(
                ("STP", "stance_ratio", "stance", Unit::GaitCycleFraction),
                PER_CENT_OF_CYCLE,
                UNIT,
                "mean share of the stride the foot is on the ground (toe off − heel strike) / stride time; normal ≈ 0.60.",
                Some("(toe off − heel strike) / stride time."),
            ),
            SwingRatio => d(
                ("SWP", "swing_ratio", "swing", Unit::GaitCycleFraction),
                PER_CENT_OF_CYCLE,
                UNIT,
                "1 − stance ratio: the share of the stride the foot is in the air.",
                None,
            ),
            StrideLengthCv => d(
                ("SV", "stride_length_cv", "stride length variability", Unit::Cv),
                CV_PER_CENT,
                (0.0, 5.0),
                "stride-to-stride variability of stride length (× 100 = %).",
                None,
            ),
            StrideTimeCv => d(
                ("STV", "stride_time_cv", "stride time variability", Unit::Cv),
                CV_PER_CENT,
                (0.0, 5.0),
                "stride-to-stride variability of stride time (× 100 = %); healthy ≈ 0.01–0.03.",
                None,
            ),
            Sta => d(
                ("STA", "sta_per_s", "gait stability (Lyapunov exponent)", Unit::PerS),
                (1.0, "1/s"),
                (-50.0, 50.0),
                "short-term largest Lyapunov exponent of the shank's sagittal angular velocity (Rosenstein): how fast nearby gait states diverge; higher = less stable.",
                None,
            ),
            Wqk => d(
                ("WQK", "wqk_deg", "shank swing (peak forward pitch)", Unit::Deg),
                AS_IS_DEG,
                ANGLE,
                "mean largest forward inclination of the shank in a stride (sagittal pitch maximum, the knee ahead of the ankle, late swing).",
                Some("Largest forward shank inclination in the stride (WQK)."),
            ),
            Pbi => d(
                ("PBI", "pbi_deg", "shank pitch back", Unit::Deg),
                AS_IS_DEG,
                ANGLE,
                "mean largest backward inclination of the shank in a stride (−pitch minimum, at push-off).",
                Some("Largest backward shank inclination in the stride (PBI)."),
            ),
            Bdk => d(
                ("BDK", "bdk_deg", "shank roll in swing", Unit::Deg),
                AS_IS_DEG,
                ANGLE,
                "mean range of the shank's frontal-plane roll in swing (toe off to heel strike): sideways swing of the leg, e.g. circumduction.",
                Some("Range of frontal-plane shank roll from toe off to the next heel strike (BDK)."),
            ),
            // Issue 49: double support (docs/quality.md "Stance, swing and double support").
            DoubleSupport => d(
                ("DS", "double_support_ratio", "double support", Unit::GaitCycleFraction),
                PER_CENT_OF_CYCLE,
                UNIT,
                "mean share of the stride both feet are on the ground: the initial (heel strike to the other leg's toe off) plus the terminal (the other leg's heel strike to this leg's toe off) double support, / stride time (× stride time = s); normal ≈ 0.20; empty with one leg.",
                Some("(initial + terminal double support) / stride time, from the other leg's toe off and heel strike inside the stride; empty without them."),
            ),
            #[cfg(feature = "dummy-parameter")]
            Dummy => d(
                ("DUM", "dummy_s", "dummy", Unit::S),
                AS_IS_S,
                (0.0, 40.0),
                "twice the mean stride time (a test-only parameter).",
                Some("Twice the stride time (a test-only parameter)."),
            ),
        }
    }

    /// The position in [`Parameter::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Code in the paper's Table 2 (`SF`, `SL` …; PBI is ldh's addition).
    pub const fn code(self) -> &'static str {
        self.definition().code
    }

    /// Column of the per-recording table (units in the name).
    pub const fn column(self) -> &'static str {
        self.definition().column
    }

    /// Plain name.
    pub const fn name(self) -> &'static str {
        self.definition().name
    }

    /// Unit, as text ([`Unit::as_str`]).
    pub const fn unit(self) -> &'static str {
        self.definition().unit.as_str()
    }

    /// Whether the parameter is an angle (its unit is [`Unit::Deg`]).
    pub const fn is_angle(self) -> bool {
        matches!(self.definition().unit, Unit::Deg)
    }

    /// How a report shows it: `(factor from the unit, unit)`.
    pub const fn display(self) -> (f64, &'static str) {
        self.definition().display
    }

    /// The name as a report's row label (capitalised: "Walking speed").
    pub fn label(self) -> String {
        let name = self.name();
        let mut c = name.chars();
        c.next().map_or(String::new(), |f| {
            f.to_uppercase().collect::<String>() + c.as_str()
        })
    }

    /// The decimals the tables round a value to: 3 for an angle (deg), 4 for the rest.
    pub fn decimals(self) -> i32 {
        if self.is_angle() {
            3
        } else {
            4
        }
    }

    /// What the per-side value means.
    pub const fn description(self) -> &'static str {
        self.definition().description
    }

    /// The columns a withheld value of this parameter empties in the per-recording table: its
    /// own, and for STA also `sta_per_stride` (the same exponent per stride).
    pub fn withheld_columns(self) -> Vec<&'static str> {
        match self {
            Parameter::Sta => vec!["sta_per_s", "sta_per_stride"],
            _ => vec![self.column()],
        }
    }

    /// The columns of [`Parameter::ALL`].
    pub fn columns() -> Vec<&'static str> {
        Parameter::ALL.iter().map(|p| p.column()).collect()
    }

    /// The parameter whose column is `column`.
    pub fn from_column(column: &str) -> Result<Parameter, UnknownParameter> {
        Parameter::ALL
            .into_iter()
            .find(|p| p.column() == column)
            .ok_or_else(|| UnknownParameter(column.to_string()))
    }

    /// The parameter one of whose [`withheld_columns`](Parameter::withheld_columns) is `column`.
    pub fn from_withheld_column(column: &str) -> Option<Parameter> {
        Parameter::ALL
            .into_iter()
            .find(|p| p.withheld_columns().contains(&column))
    }
}

impl std::str::FromStr for Parameter {
    type Err = UnknownParameter;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Parameter::from_column(s)
    }
}

impl std::fmt::Display for Parameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.column())
    }
}
