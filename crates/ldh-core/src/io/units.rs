//! Units written in column headers (docs/input.md, "Units in the header"): `Acc_X [m/s^2]`,
//! `acc_x (g)`, `GyrX/deg/s`, `Gyr_X (°/s)`, `time (ms)`, or a second header row of units.
//!
//! [`Unit`] is the typed unit (parsed by [`FromStr`] from the spellings device exports write)
//! with its factor to ldh's internal units: g for accelerations, deg/s for angular rates, s for
//! time. [`split_label`] cuts a header cell into its name and its unit text. A unit ldh does not
//! know, or a unit of the wrong quantity, on a column ldh reads is a [`UnitError`] naming the
//! file, line, column and the unit text: it is never silently ignored.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::format::{AccUnit, GyroUnit, TimeUnit};
use crate::error::{clip, Location};
use crate::recording::STANDARD_GRAVITY_MPS2;

/// What a unit measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Acceleration (specific force): internal unit g.
    Acceleration,
    /// Angular rate: internal unit deg/s.
    AngularRate,
    /// Time: internal unit s.
    Time,
}

impl Quantity {
    /// The spellings accepted for this quantity, for messages.
    pub fn accepted(self) -> &'static str {
        match self {
            Quantity::Acceleration => "g, m/s^2 (m/s2, m/s², m s^-2, m/s/s)",
            Quantity::AngularRate => "deg/s (°/s, dps, deg/sec, degrees/s), rad/s (rad/sec)",
            Quantity::Time => "s (sec, seconds), ms (msec), us (µs, usec), ns (nsec)",
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Quantity::Acceleration => "an acceleration",
            Quantity::AngularRate => "an angular rate",
            Quantity::Time => "a time",
        })
    }
}

/// A unit of a recording's column: the units ldh converts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    /// Standard gravity, g (internal).
    G,
    /// Metres per second squared.
    MetresPerSecond2,
    /// Degrees per second (internal).
    DegreesPerSecond,
    /// Radians per second.
    RadiansPerSecond,
    /// Seconds (internal).
    Seconds,
    /// Milliseconds.
    Milliseconds,
    /// Microseconds.
    Microseconds,
    /// Ticks of 100 µs (Xsens `SampleTimeFine`).
    HundredMicroseconds,
    /// Nanoseconds.
    Nanoseconds,
}

impl Unit {
    /// What the unit measures.
    pub fn quantity(self) -> Quantity {
        match self {
            Unit::G | Unit::MetresPerSecond2 => Quantity::Acceleration,
            Unit::DegreesPerSecond | Unit::RadiansPerSecond => Quantity::AngularRate,
            Unit::Seconds
            | Unit::Milliseconds
            | Unit::Microseconds
            | Unit::HundredMicroseconds
            | Unit::Nanoseconds => Quantity::Time,
        }
    }

    /// The internal unit of the same quantity (g, deg/s, s).
    pub fn internal(self) -> Unit {
        match self.quantity() {
            Quantity::Acceleration => Unit::G,
            Quantity::AngularRate => Unit::DegreesPerSecond,
            Quantity::Time => Unit::Seconds,
        }
    }

    /// The factor from this unit to the internal one: a value in `self` × factor = the value
    /// in [`Unit::internal`] (1/9.80665 for m/s², 180/π for rad/s, 10⁻³ for ms).
    pub fn to_internal(self) -> f64 {
        match self {
            Unit::G | Unit::DegreesPerSecond | Unit::Seconds => 1.0,
            Unit::MetresPerSecond2 => 1.0 / STANDARD_GRAVITY_MPS2,
            Unit::RadiansPerSecond => 180.0 / std::f64::consts::PI,
            Unit::Milliseconds => 1e-3,
            Unit::Microseconds => 1e-6,
            Unit::HundredMicroseconds => 1e-4,
            Unit::Nanoseconds => 1e-9,
        }
    }

    /// The symbol in messages and `ldh inspect`: `g`, `m/s²`, `deg/s`, `rad/s`, `s`, `ms`, `µs`.
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::G => "g",
            Unit::MetresPerSecond2 => "m/s²",
            Unit::DegreesPerSecond => "deg/s",
            Unit::RadiansPerSecond => "rad/s",
            Unit::Seconds => "s",
            Unit::Milliseconds => "ms",
            Unit::Microseconds => "µs",
            Unit::HundredMicroseconds => "100 µs",
            Unit::Nanoseconds => "ns",
        }
    }

    /// The conversion as `ldh inspect` shows it: `÷ 9.80665 (m/s² → g)`, `× 57.2958 (rad/s →
    /// deg/s)`, `× 0.001 (ms → s)`; empty for an internal unit.
    pub fn conversion(self) -> String {
        let to = self.internal().symbol();
        match self {
            Unit::G | Unit::DegreesPerSecond | Unit::Seconds => String::new(),
            Unit::MetresPerSecond2 => format!("÷ {STANDARD_GRAVITY_MPS2} (m/s² → {to})"),
            Unit::RadiansPerSecond => format!("× 180/π (rad/s → {to})"),
            Unit::Milliseconds => format!("× 0.001 (ms → {to})"),
            Unit::Microseconds => format!("× 0.000001 (µs → {to})"),
            Unit::HundredMicroseconds => format!("× 0.0001 (100 µs ticks → {to})"),
            Unit::Nanoseconds => format!("× 0.000000001 (ns → {to})"),
        }
    }

    /// As a column map's acceleration unit (`None` for another quantity).
    pub fn acc(self) -> Option<AccUnit> {
        match self {
            Unit::G => Some(AccUnit::G),
            Unit::MetresPerSecond2 => Some(AccUnit::Mps2),
            _ => None,
        }
    }

    /// As a column map's angular-rate unit (`None` for another quantity).
    pub fn gyro(self) -> Option<GyroUnit> {
        match self {
            Unit::DegreesPerSecond => Some(GyroUnit::Dps),
            Unit::RadiansPerSecond => Some(GyroUnit::Rps),
            _ => None,
        }
    }

    /// As a column map's time unit (`None` for another quantity).
    pub fn time(self) -> Option<TimeUnit> {
        match self {
            Unit::Seconds => Some(TimeUnit::Seconds),
            Unit::Milliseconds => Some(TimeUnit::Milliseconds),
            Unit::Microseconds => Some(TimeUnit::Microseconds),
            Unit::HundredMicroseconds => Some(TimeUnit::HundredMicroseconds),
            Unit::Nanoseconds => Some(TimeUnit::Nanoseconds),
            _ => None,
        }
    }
}

impl Unit {
    /// A column map's time unit as a [`Unit`] (`None` for a counter, ISO 8601 or no time).
    pub fn from_time(u: TimeUnit) -> Option<Unit> {
        match u {
            TimeUnit::Seconds => Some(Unit::Seconds),
            TimeUnit::Milliseconds => Some(Unit::Milliseconds),
            TimeUnit::Microseconds => Some(Unit::Microseconds),
            TimeUnit::HundredMicroseconds => Some(Unit::HundredMicroseconds),
            TimeUnit::Nanoseconds => Some(Unit::Nanoseconds),
            TimeUnit::Counter | TimeUnit::Iso8601 | TimeUnit::None => None,
        }
    }
}

impl From<AccUnit> for Unit {
    fn from(u: AccUnit) -> Self {
        match u {
            AccUnit::G => Unit::G,
            AccUnit::Mps2 => Unit::MetresPerSecond2,
        }
    }
}

impl From<GyroUnit> for Unit {
    fn from(u: GyroUnit) -> Self {
        match u {
            GyroUnit::Dps => Unit::DegreesPerSecond,
            GyroUnit::Rps => Unit::RadiansPerSecond,
        }
    }
}

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

/// A unit text ldh does not know (from [`Unit::from_str`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown unit '{}'", clip(.0))]
pub struct UnknownUnit(pub String);

/// The unit text without white space, brackets, powers written as `^`/`**`/`²`, degree signs
/// and micro signs: `[m/s^2]` → `m/s2`, `(°/s)` → `deg/s`, `µs` → `us`.
fn normalise(text: &str) -> String {
    let mut s = strip_brackets(text.trim()).to_lowercase();
    for (from, to) in [
        ("²", "2"),
        ("**", ""),
        ("^", ""),
        ("°", "deg"),
        ("º", "deg"),
        ("µ", "u"),
        ("μ", "u"),
        ("·", ""),
    ] {
        s = s.replace(from, to);
    }
    s.retain(|c| !c.is_whitespace());
    s
}

/// `text` without brackets around the whole of it: `[g]`, `(ms)`, `{s}` → `g`, `ms`, `s`.
fn strip_brackets(mut text: &str) -> &str {
    loop {
        let t = text.trim();
        let inner = t
            .strip_prefix('[')
            .and_then(|r| r.strip_suffix(']'))
            .or_else(|| t.strip_prefix('(').and_then(|r| r.strip_suffix(')')))
            .or_else(|| t.strip_prefix('{').and_then(|r| r.strip_suffix('}')));
        match inner {
            Some(i) => text = i,
            None => return t,
        }
    }
}

impl FromStr for Unit {
    type Err = UnknownUnit;

    /// The spellings device exports write, case-insensitive, brackets and white space ignored:
    /// `g`; `m/s^2`, `m/s2`, `m/s²`, `m s^-2`, `ms-2`, `m/s/s`, `m/(s^2)`, `mps2`; `deg/s`,
    /// `°/s`, `dps`, `deg/sec`, `degrees/s`, `deg s^-1`; `rad/s`, `rad/sec`, `rad s^-1`;
    /// `s`, `sec`, `seconds`; `ms`, `msec`, `milliseconds`; `us`, `µs`, `usec`,
    /// `microseconds`.
    fn from_str(text: &str) -> Result<Self, UnknownUnit> {
        let s = normalise(text);
        let u = match s.as_str() {
            "g" => Unit::G,
            "m/s2" | "ms-2" | "m/s/s" | "m/(s2)" | "mps2" | "m.s-2" | "m/sec2" => {
                Unit::MetresPerSecond2
            }
            "deg/s" | "deg/sec" | "degs-1" | "deg.s-1" | "dps" | "degree/s" | "degrees/s"
            | "degree/sec" | "degrees/sec" | "degpersec" => Unit::DegreesPerSecond,
            "rad/s" | "rad/sec" | "rads-1" | "rad.s-1" | "radians/s" | "radian/s" => {
                Unit::RadiansPerSecond
            }
            "s" | "sec" | "secs" | "second" | "seconds" => Unit::Seconds,
            "ms" | "msec" | "msecs" | "millisecond" | "milliseconds" => Unit::Milliseconds,
            "us" | "usec" | "usecs" | "microsecond" | "microseconds" => Unit::Microseconds,
            "100us" => Unit::HundredMicroseconds,
            "ns" | "nsec" | "nanosecond" | "nanoseconds" => Unit::Nanoseconds,
            _ => return Err(UnknownUnit(text.trim().to_string())),
        };
        Ok(u)
    }
}

/// Find the bracket that opens the one closing `t` (`t` ends with `close`), nesting counted:
/// `acc (m/(s^2))` → the index of the first `(`.
fn opening(t: &str, open: char, close: char) -> Option<usize> {
    let mut depth = 0usize;
    for (i, c) in t.char_indices().rev() {
        if c == close {
            depth += 1;
        } else if c == open {
            depth -= 1;
            if depth == 0 {
                return Some(i);
            }
        }
    }
    None
}

/// A header cell cut into its name and the unit text it carries, if any: `Acc_X [m/s^2]` →
/// (`Acc_X`, `m/s^2`); `acc_x (g)` → (`acc_x`, `g`); `GyrX/deg/s` → (`GyrX`, `deg/s`);
/// `gyro_x / rad/s` → (`gyro_x`, `rad/s`); `acc_x` → (`acc_x`, none). A trailing bracket
/// wins over a slash; a cell that would leave an empty name or unit is a name.
pub fn split_label(cell: &str) -> (&str, Option<&str>) {
    let t = cell.trim();
    for (open, close) in [('[', ']'), ('(', ')'), ('{', '}')] {
        if t.ends_with(close) {
            if let Some(i) = opening(t, open, close) {
                let (name, unit) = (t[..i].trim(), &t[i + 1..t.len() - 1]);
                if !name.is_empty() && !unit.trim().is_empty() {
                    return (name.trim_end_matches(['_', '-', ' ']), Some(unit.trim()));
                }
            }
            return (t, None);
        }
    }
    if let Some((name, unit)) = t.split_once('/') {
        let (name, unit) = (name.trim(), unit.trim());
        if !name.is_empty() && !unit.is_empty() {
            return (name, Some(unit));
        }
    }
    (t, None)
}

/// A unit in a header that ldh cannot use, with the file, line and column (1-based field) it
/// is in. Never silently ignored: the reader refuses the file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    /// A unit text ldh does not know on a column it reads.
    #[error(
        "{loc}: column '{}' holds {quantity}, but its unit '{}' is not known; accepted: {}",
        clip(column),
        clip(unit),
        quantity.accepted()
    )]
    Unknown {
        /// File, line and column.
        loc: Location,
        /// The column's header text.
        column: String,
        /// The unit text as written.
        unit: String,
        /// What the column holds.
        quantity: Quantity,
    },
    /// A known unit of another quantity (`acc_x [deg/s]`).
    #[error(
        "{loc}: column '{}' holds {expected}, but its unit '{}' is {}; accepted: {}",
        clip(column),
        clip(unit),
        found.quantity(),
        expected.accepted()
    )]
    WrongQuantity {
        /// File, line and column.
        loc: Location,
        /// The column's header text.
        column: String,
        /// The unit text as written.
        unit: String,
        /// The unit it was read as.
        found: Unit,
        /// What the column holds.
        expected: Quantity,
    },
    /// A column ldh reads has no unit while the others of the header have one.
    #[error(
        "{loc}: column '{}' holds {quantity} but gives no unit while the other columns do; write it as '{} [unit]' ({})",
        clip(column),
        clip(column),
        quantity.accepted()
    )]
    Missing {
        /// File, line and column.
        loc: Location,
        /// The column's header text.
        column: String,
        /// What the column holds.
        quantity: Quantity,
    },
    /// The three axes of one sensor in different units.
    #[error(
        "{loc}: column '{}' is in {unit} but '{}' is in {first_unit}: the three axes of a sensor must share one unit",
        clip(column),
        clip(first)
    )]
    Mixed {
        /// File, line and column.
        loc: Location,
        /// The column's header text.
        column: String,
        /// Its unit.
        unit: Unit,
        /// The sensor's first axis column.
        first: String,
        /// That column's unit.
        first_unit: Unit,
    },
}

/// Parse the unit text of a column that holds `quantity`: the [`Unit`], or the [`UnitError`]
/// at `loc` naming `column` and the text.
pub(crate) fn parse_for(
    text: &str,
    quantity: Quantity,
    column: &str,
    loc: Location,
) -> Result<Unit, UnitError> {
    match text.parse::<Unit>() {
        Ok(u) if u.quantity() == quantity => Ok(u),
        Ok(found) => Err(UnitError::WrongQuantity {
            loc,
            column: column.to_string(),
            unit: text.to_string(),
            found,
            expected: quantity,
        }),
        Err(_) => Err(UnitError::Unknown {
            loc,
            column: column.to_string(),
            unit: text.to_string(),
            quantity,
        }),
    }
}

/// Whether a cell of a possible units row reads as a unit (`[g]`, `m/s^2`, `s`).
pub(crate) fn is_unit(cell: &str) -> bool {
    cell.parse::<Unit>().is_ok()
}
