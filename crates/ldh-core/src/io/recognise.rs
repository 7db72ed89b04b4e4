//! Column names of vendor exports recognised without a map (docs/input.md, "Exports read
//! without a map"): which channel a header cell names, the unit it carries or implies, and how
//! strongly it claims the channel when two cells do.
//!
//! A cell is cut into its name and unit text ([`split_label`]: `Acc_X [m/s^2]`, `ax(g)`,
//! `GyrX/deg/s`), the name into lower-case words at `_`, `-`, `.`, `:` and spaces, and a
//! trailing unit word is taken as the unit (`acc_x_mps2`, `gyro_x_rad_s`, `time_ms`). The
//! shortest run of final words that names a channel wins; the words before it are a sensor
//! label (`Shimmer_8665_`, `RWrist_`, `Right Shank/`). Recognised, case ignored:
//!
//! | channel | names (then the axis `x`, `y` or `z`) |
//! |---|---|
//! | acceleration | `acc`, `accel`, `accl`, `accelerometer`, `acceleration`, `a`, `gF` (in g: Physics Toolbox), Shimmer's `Accel_LN` / `Accel_WR` (low-noise preferred), APDM's `…/Acceleration/X`, SensorLog's `accelerometerAcceleration` |
//! | angular rate | `gyr`, `gyro`, `gyroscope`, `angular_velocity`, `angular_rate`, `angvel`, `rotationRate`, `g`, `w`, `as` (WitMotion), APDM's `…/Angular Velocity/X` |
//! | time | `time`, `timestamp`, `t`, `elapsed`, `elapsed_time`, `seconds_elapsed`, `time_since_start`, Shimmer's `Timestamp_Unix`, `TimestampSync_Unix`, Xsens/Movella `SampleTimeFine` |
//!
//! Names that are not the sensor's specific force are not recognised: `FreeAcc_X` (Movella,
//! gravity removed), `LinearAcc`, `userAcceleration`; nor uncalibrated counts (`…_RAW`,
//! `…_UNCAL`) nor a `PacketCounter` (a counter needs a stated rate).

use super::units::{split_label, Unit};

/// A channel a recognised column feeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Channel {
    /// Time.
    Time,
    /// Acceleration axis 0, 1, 2 (x, y, z).
    Acc(usize),
    /// Angular-rate axis 0, 1, 2.
    Gyro(usize),
}

impl Channel {
    /// Index in the order time, acc x y z, gyro x y z.
    pub fn slot(self) -> usize {
        match self {
            Channel::Time => 0,
            Channel::Acc(k) => 1 + k,
            Channel::Gyro(k) => 4 + k,
        }
    }
}

/// A unit a name implies without writing it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Implied {
    /// A known unit (`gFx`: g).
    Unit(Unit),
    /// Xsens/Movella `SampleTimeFine`: µs (Movella DOT) or 100 µs ticks (MTi, MTw), told apart
    /// by the sampling rate; a 32-bit counter that wraps.
    SampleTimeFine,
}

/// What a header cell names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Recognised {
    /// The channel.
    pub channel: Channel,
    /// The unit text the cell carries, if any (`m/s^2`, `rad/s`).
    pub unit_text: Option<String>,
    /// The unit the name implies, if any.
    pub implied: Option<Implied>,
    /// How strongly the cell claims its channel when another cell names the same one: the
    /// higher wins, equal ranks are a duplicate.
    pub rank: u8,
}

const ACC_STEMS: [&str; 9] = [
    "acc",
    "accel",
    "accl",
    "accelerometer",
    "acceleration",
    "accelerations",
    "accelerometeracceleration",
    "a",
    "gf",
];
const GYRO_STEMS: [&str; 12] = [
    "gyr",
    "gyro",
    "gyroscope",
    "angularvelocity",
    "angularrate",
    "angvel",
    "rotationrate",
    "gyrorotation",
    "gyroscoperotationrate",
    "g",
    "w",
    "as",
];
/// Time names and their rank (a Unix timestamp over a relative one: Shimmer writes both).
const TIME_KEYS: [(&str, u8); 14] = [
    ("time", 2),
    ("timestamp", 2),
    ("timestamps", 2),
    ("t", 2),
    ("elapsed", 2),
    ("elapsedtime", 2),
    ("secondselapsed", 2),
    ("timesincestart", 2),
    ("timestampunix", 3),
    ("timestampsyncunix", 3),
    ("timestampsync", 2),
    ("systemtimestamp", 2),
    ("sampletimefine", 2),
    ("accelerometertimestampsincereboot", 2),
];

/// The words of a name: lower case, cut at `_`, `-`, `.`, `:`, `/` and white space.
fn words(name: &str) -> Vec<String> {
    name.split(|c: char| matches!(c, '_' | '-' | '.' | ':' | '/') || c.is_whitespace())
        .filter(|w| !w.is_empty())
        .map(|w| w.to_lowercase())
        .collect()
}

/// APDM's `Sensor label/Acceleration/X` and `…/Angular Velocity/Y`.
fn apdm_path(cell: &str) -> Option<Channel> {
    let parts: Vec<&str> = cell.trim().split('/').map(str::trim).collect();
    if parts.len() < 3 {
        return None;
    }
    let axis = axis_of(parts[parts.len() - 1])?;
    let mut what = parts[parts.len() - 2].to_lowercase();
    what.retain(|c| !c.is_whitespace() && c != '_');
    match what.as_str() {
        "acceleration" | "accelerometer" => Some(Channel::Acc(axis)),
        "angularvelocity" | "gyroscope" => Some(Channel::Gyro(axis)),
        _ => None,
    }
}

fn axis_of(s: &str) -> Option<usize> {
    match s.to_ascii_lowercase().as_str() {
        "x" => Some(0),
        "y" => Some(1),
        "z" => Some(2),
        _ => None,
    }
}

/// The unit written as the last word or two of a name (`time_ms`, `acc_x_mps2`,
/// `gyro_x_rad_s`): the unit text and the words left.
fn trailing_unit(mut w: Vec<String>) -> (Vec<String>, Option<String>) {
    if w.len() >= 3 {
        let two = format!("{}/{}", w[w.len() - 2], w[w.len() - 1]);
        if two.parse::<Unit>().is_ok() {
            w.truncate(w.len() - 2);
            return (w, Some(two));
        }
    }
    if w.len() >= 2 && axis_of(&w[w.len() - 1]).is_none() {
        let one = w[w.len() - 1].clone();
        if one.parse::<Unit>().is_ok() {
            w.pop();
            return (w, Some(one));
        }
    }
    (w, None)
}

/// What one header cell names, if a channel ldh reads.
pub(super) fn recognise(cell: &str) -> Option<Recognised> {
    if let Some(channel) = apdm_path(cell) {
        return Some(Recognised {
            channel,
            unit_text: None,
            implied: None,
            rank: 2,
        });
    }
    let (name, unit) = split_label(cell);
    let (mut w, suffix_unit) = trailing_unit(words(name));
    let unit_text = unit.map(str::to_string).or(suffix_unit);
    // Calibrated values only (Shimmer's `_CAL`); raw counts need a map with their scale.
    match w.last().map(String::as_str) {
        Some("cal") => {
            w.pop();
        }
        Some("raw" | "uncal") => return None,
        _ => {}
    }
    // Shimmer's low-noise (preferred) and wide-range accelerometers.
    let mut rank = 2;
    if let Some(i) = w.iter().position(|x| x == "ln" || x == "wr") {
        rank = if w[i] == "ln" { 3 } else { 2 };
        w.remove(i);
    }
    let n = w.len();
    for k in 1..=n {
        let key: String = w[n - k..].concat();
        // A whole-name match claims the channel over one after a sensor label.
        let whole = u8::from(k == n);
        if let Some((t, r)) = TIME_KEYS
            .iter()
            .find(|(t, _)| *t == key && (t.len() > 2 || k == n))
        {
            let implied = (*t == "sampletimefine").then_some(Implied::SampleTimeFine);
            return Some(Recognised {
                channel: Channel::Time,
                unit_text,
                implied,
                rank: 2 * r + whole,
            });
        }
        let Some(axis) = key.chars().last().and_then(|c| axis_of(&c.to_string())) else {
            continue;
        };
        let stem = &key[..key.len() - 1];
        if stem.is_empty() || (stem.len() <= 2 && k != n) {
            continue;
        }
        let channel = if ACC_STEMS.contains(&stem) {
            Channel::Acc(axis)
        } else if GYRO_STEMS.contains(&stem) {
            Channel::Gyro(axis)
        } else {
            continue;
        };
        // g-force (Physics Toolbox) over the linear acceleration (`ax`) beside it.
        let (implied, rank) = if stem == "gf" {
            (Some(Implied::Unit(Unit::G)), 3)
        } else {
            (None, rank)
        };
        return Some(Recognised {
            channel,
            unit_text,
            implied,
            rank: 2 * rank + whole,
        });
    }
    None
}

/// The exporter a header's names suggest, for the format's name and messages: `movella-xsens`
/// (`SampleTimeFine` or `PacketCounter`), `shimmer` (`…_CAL`), `apdm` (`…/Acceleration/X`),
/// else `generic`.
pub(super) fn exporter(fields: &[String]) -> &'static str {
    let has = |p: &dyn Fn(&str) -> bool| fields.iter().any(|f| p(&f.to_ascii_lowercase()));
    if has(&|f| f.trim() == "sampletimefine" || f.trim() == "packetcounter") {
        "movella-xsens"
    } else if has(&|f| f.ends_with("_cal") && (f.contains("accel") || f.contains("gyro"))) {
        "shimmer"
    } else if has(&|f| f.contains("/acceleration/") || f.contains("/angular velocity/")) {
        "apdm"
    } else {
        "generic"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ch(cell: &str) -> Option<Channel> {
        recognise(cell).map(|r| r.channel)
    }

    #[test]
    fn vendor_names_name_their_channels() {
        let cases: [(&str, Channel); 22] = [
            ("Acc_X", Channel::Acc(0)),
            ("accY", Channel::Acc(1)),
            ("az", Channel::Acc(2)),
            ("Accelerometer X", Channel::Acc(0)),
            ("Acc_X [m/s^2]", Channel::Acc(0)),
            ("Shimmer_8665_Accel_LN_Z_CAL", Channel::Acc(2)),
            ("Right Shank/Acceleration/Y", Channel::Acc(1)),
            ("Right Shank/Angular Velocity/Z", Channel::Gyro(2)),
            ("gFx", Channel::Acc(0)),
            ("Gyr_Z", Channel::Gyro(2)),
            ("gx", Channel::Gyro(0)),
            ("wy", Channel::Gyro(1)),
            ("AsX(°/s)", Channel::Gyro(0)),
            ("rotationRateX", Channel::Gyro(0)),
            ("Shimmer_8665_Gyro_Y_CAL", Channel::Gyro(1)),
            ("gyro_z_rad_s", Channel::Gyro(2)),
            ("SampleTimeFine", Channel::Time),
            ("timestamp", Channel::Time),
            ("Time (s)", Channel::Time),
            ("Shimmer_8665_Timestamp_Unix_CAL", Channel::Time),
            ("seconds_elapsed", Channel::Time),
            ("time_ms", Channel::Time),
        ];
        for (cell, want) in cases {
            assert_eq!(ch(cell), Some(want), "{cell}");
        }
        for not in [
            "FreeAcc_X",
            "PacketCounter",
            "Euler_X",
            "Mag_X",
            "Shimmer_8665_Accel_LN_X_RAW",
            "Quat_W",
            "Status",
            "acc_rs_x",
            "x",
            "linearAccX",
        ] {
            assert_eq!(ch(not), None, "{not}");
        }
    }

    #[test]
    fn units_written_or_implied_and_ranks() {
        let r = recognise("gyro_x_rad_s").unwrap();
        assert_eq!(r.unit_text.as_deref(), Some("rad/s"));
        let r = recognise("acc_x_g").unwrap();
        assert_eq!(r.unit_text.as_deref(), Some("g"));
        assert_eq!(
            recognise("gFz").unwrap().implied,
            Some(Implied::Unit(Unit::G))
        );
        assert_eq!(
            recognise("SampleTimeFine").unwrap().implied,
            Some(Implied::SampleTimeFine)
        );
        let ln = recognise("Shimmer_1_Accel_LN_X_CAL").unwrap().rank;
        let wr = recognise("Shimmer_1_Accel_WR_X_CAL").unwrap().rank;
        assert!(ln > wr);
        let unix = recognise("Shimmer_1_Timestamp_Unix_CAL").unwrap().rank;
        let rel = recognise("Shimmer_1_Timestamp_CAL").unwrap().rank;
        assert!(unix > rel);
        assert!(recognise("timestamp").unwrap().rank > recognise("UTC time").unwrap().rank);
    }
}
