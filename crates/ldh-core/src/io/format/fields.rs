//! The vocabulary of a vendor column map (the TOML fields of [`super::FormatSpec`]): delimiter,
//! decimal separator, time unit, column references, sensor selection, channel units and the
//! axis map as written.

use serde::{Deserialize, Serialize};

/// Field delimiter of a CSV file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Delimiter {
    /// Detect from the header row (the most frequent of `,` `;` tab).
    #[default]
    #[serde(rename = "auto")]
    Auto,
    /// `,`
    #[serde(rename = ",")]
    Comma,
    /// `;`
    #[serde(rename = ";")]
    Semicolon,
    /// tab
    #[serde(rename = "\t")]
    Tab,
}

impl Delimiter {
    /// The byte, or `None` for [`Delimiter::Auto`].
    pub fn byte(self) -> Option<u8> {
        match self {
            Delimiter::Auto => None,
            Delimiter::Comma => Some(b','),
            Delimiter::Semicolon => Some(b';'),
            Delimiter::Tab => Some(b'\t'),
        }
    }
    /// From a byte (`,` `;` tab).
    pub fn from_byte(b: u8) -> Option<Self> {
        match b {
            b',' => Some(Delimiter::Comma),
            b';' => Some(Delimiter::Semicolon),
            b'\t' => Some(Delimiter::Tab),
            _ => None,
        }
    }
    /// A readable name for reports.
    pub fn name(self) -> &'static str {
        match self {
            Delimiter::Auto => "auto",
            Delimiter::Comma => "comma",
            Delimiter::Semicolon => "semicolon",
            Delimiter::Tab => "tab",
        }
    }
}

/// Decimal separator of numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Decimal {
    /// `1.25`
    #[default]
    #[serde(rename = ".")]
    Point,
    /// `1,25` (only with `;` or tab as delimiter)
    #[serde(rename = ",")]
    Comma,
}

/// How time is given in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum TimeUnit {
    /// Seconds.
    #[default]
    #[serde(rename = "s")]
    Seconds,
    /// Milliseconds.
    #[serde(rename = "ms")]
    Milliseconds,
    /// Microseconds.
    #[serde(rename = "us")]
    Microseconds,
    /// Ticks of 100 µs (Xsens MTi/MTw `SampleTimeFine`, a 10 kHz clock).
    #[serde(rename = "100us")]
    HundredMicroseconds,
    /// Nanoseconds (Android's sensor timestamps).
    #[serde(rename = "ns")]
    Nanoseconds,
    /// A sample counter (needs `rate_hz`), possibly wrapping at `counter_wrap`.
    #[serde(rename = "counter")]
    Counter,
    /// ISO 8601 timestamps such as `2024-03-01T10:15:02.250` (a trailing `Z` is accepted;
    /// other time-zone offsets are not).
    #[serde(rename = "iso8601")]
    Iso8601,
    /// No time column: samples are uniform at `rate_hz`.
    #[serde(rename = "none")]
    None,
}

/// Which column of the file holds a value: a name (case-insensitive), alternative names (the
/// first one present in the header is used: exports that spell a column two ways), or a
/// 1-based column number.
///
/// In TOML: `"Acc_X"`, `["RS_acc_x", "acc_rs_x"]` or `7`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ColumnRef {
    /// A 1-based column number.
    Index(usize),
    /// A column name.
    Name(String),
    /// Alternative names, in order of preference.
    AnyOf(Vec<String>),
}

impl From<&str> for ColumnRef {
    fn from(s: &str) -> Self {
        ColumnRef::Name(s.to_string())
    }
}

impl From<String> for ColumnRef {
    fn from(s: String) -> Self {
        ColumnRef::Name(s)
    }
}

impl ColumnRef {
    /// The names this reference accepts (empty for a column number).
    pub fn names(&self) -> &[String] {
        match self {
            ColumnRef::Index(_) => &[],
            ColumnRef::Name(n) => std::slice::from_ref(n),
            ColumnRef::AnyOf(v) => v,
        }
    }

    /// How the reference reads in messages: `acc_x`, `RS_acc_x|acc_rs_x` or `#7`.
    pub fn describe(&self, prefix: &str) -> String {
        match self {
            ColumnRef::Index(i) => format!("#{i}"),
            _ => self
                .names()
                .iter()
                .map(|n| format!("{prefix}{n}"))
                .collect::<Vec<_>>()
                .join("|"),
        }
    }
}

/// Where one sensor's columns are in a file that holds several sensors.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SensorSelect {
    /// Prefix put before every column name of the map (e.g. `"RS_"` with `columns =
    /// ["acc_x", ...]`); default none.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub prefix: String,
    /// For headers that repeat the same column names once per sensor: the 1-based block to
    /// read (the `block`-th occurrence of each name). Without it a repeated name is refused.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub block: Option<usize>,
}

impl SensorSelect {
    /// Whether this is the default (one sensor per file), for serialisation.
    pub(crate) fn is_default(&self) -> bool {
        self == &SensorSelect::default()
    }
}

/// Time column description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// The time column; `None` when the file has no time column.
    #[serde(default)]
    pub column: Option<ColumnRef>,
    /// Unit of the column.
    #[serde(default)]
    pub unit: TimeUnit,
    /// The stated sampling rate in Hz, required for `counter` and `none`.
    #[serde(default)]
    pub rate_hz: Option<f64>,
    /// Counter modulus for counters that wrap (e.g. 65536).
    #[serde(default)]
    pub counter_wrap: Option<u64>,
}

/// Acceleration units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum AccUnit {
    /// Standard gravity.
    #[serde(rename = "g")]
    G,
    /// m/s².
    #[serde(rename = "m/s2", alias = "m/s^2", alias = "mps2")]
    Mps2,
}

/// Angular velocity units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum GyroUnit {
    /// Degrees per second.
    #[serde(rename = "deg/s", alias = "dps")]
    Dps,
    /// Radians per second.
    #[serde(rename = "rad/s", alias = "rps")]
    Rps,
}

/// A three-axis sensor's columns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChannelSpec<U> {
    /// Columns of the x, y, z axes: names (case-insensitive), alternatives or 1-based numbers.
    pub columns: [ColumnRef; 3],
    /// Unit after scaling.
    pub unit: U,
    /// Multiplier from the raw value to `unit` (1 unless the file holds integer counts).
    #[serde(default = "one")]
    pub scale: f64,
    /// Full-scale range in `unit` (e.g. 8 for a ±8 g accelerometer); samples at the range are
    /// counted as saturated. When absent, clipping is detected from flat runs at the extremes.
    #[serde(default)]
    pub range: Option<f64>,
}

/// The default scale, 1.
fn one() -> f64 {
    1.0
}

/// Axis mapping from the file's axes to ldh's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxesSpec {
    /// For ldh x, y, z: which input axis with which sign, e.g. `["+x", "-z", "+y"]`.
    pub map: [String; 3],
}

impl Default for AxesSpec {
    fn default() -> Self {
        AxesSpec {
            map: ["+x".into(), "+y".into(), "+z".into()],
        }
    }
}
