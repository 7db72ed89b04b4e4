//! What the reader made of each column it reads, for `ldh inspect` and the read report: the
//! channel it feeds, the unit understood (and where that unit came from) and the conversion to
//! ldh's internal units (g, deg/s, s) with the format's scale and axis map.

use serde::{Deserialize, Serialize};

use super::format::{FormatSpec, TimeUnit};
use super::header::{Header, UnitsFrom};
use super::infer::Assumed;
use super::units::Unit;

/// One column the reader reads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ColumnInfo {
    /// 1-based position in the row.
    pub column: usize,
    /// The header's text (`column 3` in a file without a header row).
    pub name: String,
    /// The channel it feeds, in ldh's frame: `time`, `acc_x` … `gyro_z`.
    pub channel: String,
    /// The unit understood: `m/s²`, `deg/s`, `ms`, `counter`, `ISO 8601`.
    pub unit: String,
    /// Where the unit comes from: `header` (the name), `units row (line 2)`, `name suffix`,
    /// `format 'xsens-mtmanager'`.
    pub unit_from: String,
    /// The factor from the file's value to the internal unit (scale, unit and the axis map's
    /// sign together); `None` for time given as a counter or ISO 8601.
    pub factor: Option<f64>,
    /// The conversion in words: `÷ 9.80665 (m/s² → g)`, `× 180/π (rad/s → deg/s), sign
    /// flipped (axis map -x)`, `no conversion`.
    pub conversion: String,
}

impl ColumnInfo {
    /// One line for `ldh inspect`: `column 2 'Acc_X [m/s^2]' → acc_x: m/s² (header), ÷ 9.80665
    /// (m/s² → g)`.
    pub fn line(&self) -> String {
        format!(
            "column {} '{}' → {}: {} ({}), {}",
            self.column, self.name, self.channel, self.unit, self.unit_from, self.conversion
        )
    }
}

const AXES: [&str; 3] = ["x", "y", "z"];

fn units_from_text(h: &Header) -> String {
    match h.units_from {
        UnitsFrom::Format => format!("format '{}'", h.spec.name),
        UnitsFrom::NameSuffix => "name suffix".into(),
        UnitsFrom::Labels => "header".into(),
        UnitsFrom::UnitsRow(n) => format!("units row (line {n})"),
        UnitsFrom::Signal => "assumed from the signal".into(),
    }
}

/// The time column's entry, if the format has one.
fn time_info(h: &Header, from: &str) -> Option<ColumnInfo> {
    let i = h.cols.time?;
    let spec = &h.spec;
    let (unit, factor, conversion) = match Unit::from_time(spec.time.unit) {
        Some(u) => (
            u.symbol().to_string(),
            Some(u.to_internal()),
            words(&[u.conversion()]),
        ),
        None => match spec.time.unit {
            TimeUnit::Counter => (
                "counter".to_string(),
                None,
                counter_words(spec.time.rate_hz, spec.time.counter_wrap),
            ),
            _ => (
                "ISO 8601".to_string(),
                None,
                "date and time → s since the first sample".to_string(),
            ),
        },
    };
    Some(ColumnInfo {
        column: i + 1,
        name: h
            .fields
            .get(i)
            .map_or(String::new(), |f| f.trim().to_string()),
        channel: "time".into(),
        unit,
        unit_from: from.to_string(),
        factor,
        conversion,
    })
}

fn counter_words(rate: Option<f64>, wrap: Option<u64>) -> String {
    let mut s = match rate {
        Some(r) => format!("samples at {r} Hz (stated) → s"),
        None => "samples → s".to_string(),
    };
    if let Some(w) = wrap {
        s.push_str(&format!(", wraps at {w}"));
    }
    s
}

/// The parts joined, or `no conversion` (the file's values are ldh's units).
fn words(parts: &[String]) -> String {
    let v: Vec<&str> = parts
        .iter()
        .map(String::as_str)
        .filter(|p| !p.is_empty())
        .collect();
    if v.is_empty() {
        "no conversion".into()
    } else {
        v.join(", ")
    }
}

/// One sensor's three columns: `pos` (file axes x, y, z), `unit`, `scale`, `prefix` of the
/// channel names (`acc`, `gyro`).
fn sensor_info(
    h: &Header,
    spec: &FormatSpec,
    sensor: (&str, [usize; 3], Unit, f64),
    from: &str,
    out: &mut Vec<ColumnInfo>,
) {
    let (prefix, pos, unit, scale) = sensor;
    let Ok(map) = spec.axis_map() else { return };
    for (ldh_axis, ldh_name) in AXES.iter().enumerate() {
        let file_axis = map.index[ldh_axis];
        let sign = map.sign[ldh_axis];
        let i = pos[file_axis];
        let mut parts = Vec::new();
        if scale != 1.0 {
            parts.push(format!("× {scale} (scale: raw → {unit})"));
        }
        parts.push(unit.conversion());
        if sign < 0.0 {
            parts.push(format!("sign flipped (axis map -{})", AXES[file_axis]));
        }
        if file_axis != ldh_axis {
            parts.push(format!(
                "file axis {} → ldh axis {ldh_name}",
                AXES[file_axis]
            ));
        }
        out.push(ColumnInfo {
            column: i + 1,
            name: h
                .fields
                .get(i)
                .map_or(String::new(), |f| f.trim().to_string()),
            channel: format!("{prefix}_{ldh_name}"),
            unit: unit.symbol().to_string(),
            unit_from: from.to_string(),
            factor: Some(sign * scale * unit.to_internal()),
            conversion: words(&parts),
        });
    }
}

/// Every column the header's format reads, time first, then acc x y z and gyro x y z in
/// ldh's frame.
pub(super) fn describe_columns(h: &Header, assumed: &Assumed) -> Vec<ColumnInfo> {
    let from = units_from_text(h);
    let from_of = |a: &Option<String>| a.clone().unwrap_or_else(|| from.clone());
    let spec = &h.spec;
    let mut out: Vec<ColumnInfo> = time_info(h, &from_of(&assumed.time)).into_iter().collect();
    let acc = ("acc", h.cols.acc, Unit::from(spec.acc.unit), spec.acc.scale);
    sensor_info(h, spec, acc, &from_of(&assumed.acc), &mut out);
    let gyro = (
        "gyro",
        h.cols.gyro,
        Unit::from(spec.gyro.unit),
        spec.gyro.scale,
    );
    sensor_info(h, spec, gyro, &from_of(&assumed.gyro), &mut out);
    out
}
