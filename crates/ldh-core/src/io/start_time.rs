//! The date and time a recording started, where the file says it (docs/input.md, "Recording
//! date and time"): a header comment (`// Start Time: 2024-03-05 10:21:33` in an Xsens MT
//! Manager export, `# start: 2024-03-05T10:21:33Z`), Xsens' `UTC_Year` … `UTC_Second` columns
//! in the first data row, the first ISO 8601 timestamp of an `iso8601` time column, or the
//! first value of a Unix-time column (`Shimmer_Timestamp_Unix_CAL`). Files without one have
//! none; nothing is guessed.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::format::TimeUnit;
use super::units::Unit;

/// A calendar date and time of day, to the second, as a file states it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct DateTime {
    /// Year (1970–9999).
    pub year: u16,
    /// Month, 1–12.
    pub month: u8,
    /// Day of the month, 1–31 (checked against the month).
    pub day: u8,
    /// Hour, 0–23.
    pub hour: u8,
    /// Minute, 0–59.
    pub minute: u8,
    /// Second, 0–60 (a leap second kept as written).
    pub second: u8,
    /// The time is UTC (the file said `Z`, an offset that was applied, or UTC columns or Unix
    /// time); `false`: the file's clock, zone not stated.
    pub utc: bool,
}

fn days_in_month(y: i64, m: u8) -> u8 {
    match m {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        _ if (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 => 29,
        _ => 28,
    }
}

/// Days since 1970-01-01 of a civil date (Howard Hinnant's algorithm).
pub(crate) fn days_from_civil(y: i64, m: i64, d: i64) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = if y >= 0 { y } else { y - 399 } / 400;
    let yoe = y - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146097 + doe - 719468
}

/// Parse `YYYY-MM-DD[T ]HH:MM:SS[.fff][Z]` into seconds since 1970-01-01 (UTC assumed).
///
/// Hand-written: the timestamp grammar needed is tiny, and a date crate would be a large
/// dependency for one conversion.
pub fn parse_iso8601(s: &str) -> Option<f64> {
    let s = s.trim().trim_end_matches('Z');
    let (date, time) = s.split_once(['T', ' '])?;
    let mut d = date.split('-');
    let y: i64 = d.next()?.parse().ok()?;
    let m: i64 = d.next()?.parse().ok()?;
    let day: i64 = d.next()?.parse().ok()?;
    // Four-digit years only (ISO 8601 without expansion): a longer year overflowed the day
    // count below (found while fuzzing the reader, fuzz/regressions/read_csv/iso-huge-year).
    if d.next().is_some()
        || !(0..=9999).contains(&y)
        || !(1..=12).contains(&m)
        || !(1..=31).contains(&day)
    {
        return None;
    }
    let mut t = time.split(':');
    let hh: f64 = t.next()?.parse().ok()?;
    let mm: f64 = t.next()?.parse().ok()?;
    let ss: f64 = t.next()?.parse().ok()?;
    if t.next().is_some()
        || !(0.0..24.0).contains(&hh)
        || !(0.0..60.0).contains(&mm)
        || !(0.0..61.0).contains(&ss)
    {
        return None;
    }
    let days = days_from_civil(y, m, day);
    Some(days as f64 * 86400.0 + hh * 3600.0 + mm * 60.0 + ss)
}

/// The civil date of a day count since 1970-01-01 (Hinnant's inverse).
fn civil_from_days(z: i64) -> (i64, i64, i64) {
    let z = z + 719468;
    let era = if z >= 0 { z } else { z - 146096 } / 146097;
    let doe = z - era * 146097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

impl DateTime {
    /// A checked date and time (`None` when a field is out of its range, the day past the
    /// month's end or the year outside 1970–9999).
    pub fn new(ymd: (i64, i64, i64), hms: (i64, i64, i64), utc: bool) -> Option<Self> {
        let (y, m, d) = ymd;
        let (hh, mm, ss) = hms;
        let ok = (1970..=9999).contains(&y)
            && (1..=12).contains(&m)
            && d >= 1
            && d <= i64::from(days_in_month(y, m as u8))
            && (0..24).contains(&hh)
            && (0..60).contains(&mm)
            && (0..=60).contains(&ss);
        ok.then_some(DateTime {
            year: y as u16,
            month: m as u8,
            day: d as u8,
            hour: hh as u8,
            minute: mm as u8,
            second: ss as u8,
            utc,
        })
    }

    /// The UTC date and time of a Unix time in seconds (fractions dropped); `None` before
    /// 1970 or after 9999.
    pub fn from_unix_s(t: f64) -> Option<Self> {
        if !(t.is_finite() && (0.0..253_402_300_800.0).contains(&t)) {
            return None;
        }
        let s = t.floor() as i64;
        let (y, m, d) = civil_from_days(s.div_euclid(86_400));
        let r = s.rem_euclid(86_400);
        DateTime::new((y, m, d), (r / 3600, r / 60 % 60, r % 60), true)
    }

    /// Seconds since 1970-01-01 00:00:00 of this date and time read as UTC.
    pub(crate) fn unix_s(&self) -> i64 {
        days_from_civil(
            i64::from(self.year),
            i64::from(self.month),
            i64::from(self.day),
        ) * 86_400
            + i64::from(self.hour) * 3600
            + i64::from(self.minute) * 60
            + i64::from(self.second)
    }

    /// ISO 8601, as `recordings.csv` writes it: `2024-03-05T10:21:33Z` (UTC) or
    /// `2024-03-05T10:21:33` (zone not stated).
    pub fn iso(&self) -> String {
        format!(
            "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}{}",
            self.year,
            self.month,
            self.day,
            self.hour,
            self.minute,
            self.second,
            if self.utc { "Z" } else { "" }
        )
    }

    /// To the minute, as the report shows it: `2024-03-05 10:21 UTC`, `2024-03-05 10:21`.
    pub fn to_minute(&self) -> String {
        format!(
            "{:04}-{:02}-{:02} {:02}:{:02}{}",
            self.year,
            self.month,
            self.day,
            self.hour,
            self.minute,
            if self.utc { " UTC" } else { "" }
        )
    }
}

impl fmt::Display for DateTime {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.iso())
    }
}

/// A text that is not a date and time ldh reads.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("'{}' is not a date and time (YYYY-MM-DD[T ]HH:MM[:SS[.fff]][Z|±HH:MM])", crate::error::clip(.0))]
pub struct BadDateTime(pub String);

/// Numbers of `text` split at `sep`, all of them, each all digits.
fn numbers(text: &str, sep: &[char]) -> Option<Vec<i64>> {
    text.split(sep)
        .map(|p| {
            (!p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
                .then(|| p.parse().ok())
                .flatten()
        })
        .collect()
}

impl FromStr for DateTime {
    type Err = BadDateTime;

    /// `2024-03-05T10:21:33Z`, `2024-03-05 10:21:33.250`, `2024/03/05 10:21`,
    /// `2024-03-05T10:21:33+01:00` (the offset applied: UTC), Xsens' `2024-03-05 10:21:33:250`
    /// (milliseconds after a colon). Fractions of a second are dropped.
    fn from_str(text: &str) -> Result<Self, BadDateTime> {
        let bad = || BadDateTime(text.trim().to_string());
        let s = text.trim();
        let (date, rest) = s.split_once(['T', ' ']).ok_or_else(bad)?;
        let rest = rest.trim();
        let (time, utc, offset_min) = if let Some(t) = rest.strip_suffix(['Z', 'z']) {
            (t, true, 0)
        } else if let Some(t) = rest.strip_suffix(" UTC") {
            (t, true, 0)
        } else if let Some(i) = rest.rfind(['+', '-']) {
            let o = numbers(&rest[i + 1..], &[':']).ok_or_else(bad)?;
            let mins = match o.as_slice() {
                [h, m] => h * 60 + m,
                [hm] if rest.len() - i - 1 == 4 => hm / 100 * 60 + hm % 100,
                [h] => h * 60,
                _ => return Err(bad()),
            };
            let sign = if rest.as_bytes()[i] == b'-' { -1 } else { 1 };
            (&rest[..i], true, sign * mins)
        } else {
            (rest, false, 0)
        };
        let d = numbers(date, &['-', '/']).ok_or_else(bad)?;
        let [y, m, day] = d[..] else {
            return Err(bad());
        };
        let whole = time.split('.').next().unwrap_or("");
        let t = numbers(whole, &[':']).ok_or_else(bad)?;
        let (hh, mm, ss) = match t[..] {
            [hh, mm] => (hh, mm, 0),
            [hh, mm, ss] | [hh, mm, ss, _] => (hh, mm, ss),
            _ => return Err(bad()),
        };
        let dt = DateTime::new((y, m, day), (hh, mm, ss), utc).ok_or_else(bad)?;
        if offset_min == 0 {
            return Ok(dt);
        }
        DateTime::from_unix_s((dt.unix_s() - offset_min * 60) as f64).ok_or_else(bad)
    }
}

impl Serialize for DateTime {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.iso())
    }
}

impl<'de> Deserialize<'de> for DateTime {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// Where in the file the start date and time was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StartFrom {
    /// A comment line above the column names (`// Start Time: ...`, `# start: ...`).
    Header,
    /// The `UTC_Year` … `UTC_Second` columns of the first data row (Xsens).
    UtcColumns,
    /// The first timestamp of an ISO 8601 time column.
    IsoTime,
    /// The first value of a Unix-time column (`Shimmer_Timestamp_Unix_CAL`).
    UnixTime,
}

impl StartFrom {
    /// In words: `header`, `UTC columns`, `first timestamp`, `Unix time column`.
    pub fn words(self) -> &'static str {
        match self {
            StartFrom::Header => "header",
            StartFrom::UtcColumns => "UTC columns",
            StartFrom::IsoTime => "first timestamp",
            StartFrom::UnixTime => "Unix time column",
        }
    }
}

/// When a recording started, as its file says, and where the file says it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct RecordedAt {
    /// The date and time of the file's first sample (or of its header's start).
    pub at: DateTime,
    /// Where it was found.
    pub from: StartFrom,
}

/// Keys of a header comment that gives the start: `Start Time`, `start`, `recorded`, `date`...
const START_KEYS: [&str; 9] = [
    "start time",
    "starttime",
    "start_time",
    "start",
    "recording start",
    "recorded",
    "recorded at",
    "date",
    "start date",
];

/// The start a comment line states (`// Start Time: 2024-03-05 10:21:33`, `# start:
/// 2024-03-05T10:21:33Z`, `% date = 2024-03-05 10:21`), if any.
pub(crate) fn start_in_comment(line: &str) -> Option<DateTime> {
    let body = line
        .trim()
        .trim_start_matches(['#', '/', '%', ';', '!', '*'])
        .trim();
    let (key, value) = body.split_once([':', '='])?;
    let key = key.trim().to_ascii_lowercase();
    if !START_KEYS.contains(&key.as_str()) {
        return None;
    }
    value.trim().trim_matches('"').parse().ok()
}

/// Names of Xsens' UTC columns, year to second.
const UTC_COLUMNS: [&str; 6] = [
    "utc_year",
    "utc_month",
    "utc_day",
    "utc_hour",
    "utc_minute",
    "utc_second",
];

/// Positions of the `UTC_Year` … `UTC_Second` columns, when the header has all six.
pub(crate) fn utc_columns(fields: &[String]) -> Option<[usize; 6]> {
    let mut at = [0usize; 6];
    for (k, name) in UTC_COLUMNS.iter().enumerate() {
        at[k] = fields
            .iter()
            .position(|f| f.trim().eq_ignore_ascii_case(name))?;
    }
    Some(at)
}

/// The UTC date and time of a first data row's UTC columns (`cells`, split at the delimiter).
pub(crate) fn start_in_utc_cells(cells: &[&str], at: [usize; 6]) -> Option<DateTime> {
    let v: Vec<i64> = at
        .iter()
        .map(|&i| cells.get(i)?.trim().parse::<f64>().ok().map(|x| x as i64))
        .collect::<Option<_>>()?;
    DateTime::new((v[0], v[1], v[2]), (v[3], v[4], v[5]), true)
}

/// The start a time column's first raw value gives: the date of an ISO 8601 timestamp (read
/// as seconds since 1970 by the reader), or of a column whose name says Unix time
/// (`Shimmer_Timestamp_Unix_CAL`) in s, ms or µs.
pub(crate) fn start_in_time(first: f64, unit: TimeUnit, column: &str) -> Option<RecordedAt> {
    if unit == TimeUnit::Iso8601 {
        let at = DateTime::from_unix_s(first)?;
        // The reader reads ISO timestamps as UTC only when they end in `Z`; the zone is not
        // known here, so the date is kept as the file's clock.
        return Some(RecordedAt {
            at: DateTime { utc: false, ..at },
            from: StartFrom::IsoTime,
        });
    }
    if !column.to_ascii_lowercase().contains("unix") {
        return None;
    }
    let s = first * Unit::from_time(unit)?.to_internal();
    Some(RecordedAt {
        at: DateTime::from_unix_s(s)?,
        from: StartFrom::UnixTime,
    })
}
