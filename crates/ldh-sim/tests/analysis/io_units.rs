//! Units in headers (`units.rs`, `labelled.rs`): the spellings device exports write, each read
//! into the same recording as ldh's own format; unknown, wrong, missing and mixed units refused
//! with file, line and column; a given map keeps its units; the per-column report.

use ldh_core::error::LdhError;
use ldh_core::io::format::*;
use ldh_core::io::reader::*;
use ldh_core::io::units::{Quantity, Unit, UnitError};
use ldh_core::recording::{Recording, STANDARD_GRAVITY_MPS2};
use ldh_sim::CohortParams;
use std::path::{Path, PathBuf};

/// A simulated walk, made once for all the tests of this file.
pub(crate) fn walking() -> &'static Recording {
    static REC: std::sync::OnceLock<Recording> = std::sync::OnceLock::new();
    REC.get_or_init(|| {
        let c = CohortParams {
            healthy: 3,
            ldh: 0,
            duration_s: 12.0,
            fs_hz: 100.0,
            turn: false,
            ..CohortParams::default()
        };
        c.simulate(0).unwrap().left.recording
    })
}

fn read(p: &Path, f: Option<&FormatSpec>) -> ldh_core::Result<(Recording, ReadReport)> {
    read_recording(p, f, &ReadParams::default().check().unwrap())
}

/// The file of `rec` under `header` (one or more lines), cells cut at `delim`, values × the
/// factors (time, acc, gyro), written with every digit (shortest round trip).
fn file(dir: &Path, name: &str, header: &str, delim: char, k: [f64; 3]) -> PathBuf {
    let rec = walking();
    let mut s = format!("{header}\n");
    for i in 0..rec.len() {
        let mut row = vec![format!("{}", i as f64 / rec.fs_hz * k[0])];
        row.extend((0..3).map(|a| format!("{}", rec.acc_g[a][i] * k[1])));
        row.extend((0..3).map(|a| format!("{}", rec.gyro_dps[a][i] * k[2])));
        s.push_str(&row.join(&delim.to_string()));
        s.push('\n');
    }
    let p = dir.join(name);
    std::fs::write(&p, s).unwrap();
    p
}

/// Largest differences of the channels (acc in g, gyro in deg/s) of two recordings.
fn max_diff(a: &Recording, b: &Recording) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut d = 0.0f64;
    for k in 0..3 {
        for i in 0..a.len() {
            d = d.max((a.acc_g[k][i] - b.acc_g[k][i]).abs());
            d = d.max((a.gyro_dps[k][i] - b.gyro_dps[k][i]).abs());
        }
    }
    d
}

const MPS2: f64 = STANDARD_GRAVITY_MPS2;
const RAD: f64 = std::f64::consts::PI / 180.0;

/// Every spelling of the brief, read without a map, gives the recording ldh's own format gives,
/// to 1e-12 (the factors undone in floating point), and the per-column report names the unit
/// understood and where it came from.
#[test]
fn headers_with_units_read_into_identical_recordings() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let plain = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z";
    let (reference, _) = read(&file(d, "ref.csv", plain, ',', [1.0, 1.0, 1.0]), None).unwrap();
    // (file, header, delimiter, factors time/acc/gyro, units understood time/acc/gyro, from)
    type Case = (
        &'static str,
        &'static str,
        char,
        [f64; 3],
        [&'static str; 3],
        &'static str,
    );
    let cases: [Case; 8] = [
        (
            "brackets.csv",
            "Time [s],Acc_X [m/s^2],Acc_Y [m/s^2],Acc_Z [m/s^2],Gyr_X [rad/s],Gyr_Y [rad/s],Gyr_Z [rad/s]",
            ',',
            [1.0, MPS2, RAD],
            ["s", "m/s²", "rad/s"],
            "header",
        ),
        (
            "parentheses.csv",
            "time (ms);acc_x (g);acc_y (g);acc_z (g);gyro_x (deg/s);gyro_y (deg/s);gyro_z (deg/s)",
            ';',
            [1e3, 1.0, 1.0],
            ["ms", "g", "deg/s"],
            "header",
        ),
        (
            "slash.tsv",
            "Timestamp/us\tAccX/m/s²\tAccY/m/s²\tAccZ/m/s²\tGyrX/deg/s\tGyrY/deg/s\tGyrZ/deg/s",
            '\t',
            [1e6, MPS2, 1.0],
            ["µs", "m/s²", "deg/s"],
            "header",
        ),
        (
            "slash_spaced.csv",
            "time / s,acc_x / g,acc_y / g,acc_z / g,gyro_x / rad/s,gyro_y / rad/s,gyro_z / rad/s",
            ',',
            [1.0, 1.0, RAD],
            ["s", "g", "rad/s"],
            "header",
        ),
        (
            "degree_sign.csv",
            "Timestamp [us],AccX [m/s²],AccY [m/s²],AccZ [m/s²],Gyr_X (°/s),Gyr_Y (°/s),Gyr_Z (°/s)",
            ',',
            [1e6, MPS2, 1.0],
            ["µs", "m/s²", "deg/s"],
            "header",
        ),
        (
            "units_row.csv",
            "time,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\ns,m/s^2,m/s^2,m/s^2,rad/s,rad/s,rad/s",
            ',',
            [1.0, MPS2, RAD],
            ["s", "m/s²", "rad/s"],
            "units row (line 2)",
        ),
        (
            "units_row_brackets.csv",
            "# exported\ntime,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n\n[ms],[g],[g],[g],[dps],[dps],[dps]",
            ',',
            [1e3, 1.0, 1.0],
            ["ms", "g", "deg/s"],
            "units row (line 4)",
        ),
        (
            "other_columns.csv",
            "Temp [°C],time (s),Acc_X (g),Acc_Y (g),Acc_Z (g),Gyr_X (dps),Gyr_Y (dps),Gyr_Z (dps)",
            ',',
            [1.0, 1.0, 1.0],
            ["s", "g", "deg/s"],
            "header",
        ),
    ];
    for (name, header, delim, k, units, from) in cases {
        let p = if name == "other_columns.csv" {
            // An extra first column (a unit ldh does not read) that must not matter.
            let base = file(d, "tmp.csv", "x", ',', k);
            let text = std::fs::read_to_string(&base).unwrap();
            let body: Vec<String> = text.lines().skip(1).map(|l| format!("21.5,{l}")).collect();
            let p = d.join(name);
            std::fs::write(&p, format!("{header}\n{}\n", body.join("\n"))).unwrap();
            p
        } else {
            file(d, name, header, delim, k)
        };
        let (rec, rep) = read(&p, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            (rec.fs_hz - reference.fs_hz).abs() < 1e-9,
            "{name}: {}",
            rec.fs_hz
        );
        let diff = max_diff(&rec, &reference);
        assert!(diff <= 1e-12, "{name}: channels differ by {diff}");
        assert_eq!(rep.columns.len(), 7, "{name}");
        let got: Vec<&str> = [0, 1, 4]
            .iter()
            .map(|&i| rep.columns[i].unit.as_str())
            .collect();
        assert_eq!(got, units, "{name}");
        assert!(
            rep.columns.iter().all(|c| c.unit_from == from),
            "{name}: {:?}",
            rep.columns
        );
        let chans: Vec<&str> = rep.columns.iter().map(|c| c.channel.as_str()).collect();
        assert_eq!(
            chans,
            ["time", "acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"],
            "{name}"
        );
    }
}

/// The error of reading `header` (+ a data row set) without a map: the unit error.
fn unit_error(d: &Path, name: &str, header: &str) -> (UnitError, String) {
    let p = file(d, name, header, ',', [1.0, 1.0, 1.0]);
    match read(&p, None) {
        Err(LdhError::Unit(e)) => {
            let msg = LdhError::Unit(e.clone()).to_string();
            (*e, msg)
        }
        other => panic!("{name}: unit error expected, got {other:?}"),
    }
}

#[test]
fn unusable_units_are_refused_with_file_line_column_and_text() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let (e, msg) = unit_error(
        d,
        "unknown.csv",
        "time [s],acc_x [furlongs/fortnight],acc_y [g],acc_z [g],gyro_x [dps],gyro_y [dps],gyro_z [dps]",
    );
    assert!(
        matches!(
            e,
            UnitError::Unknown {
                quantity: Quantity::Acceleration,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(msg.contains("unknown.csv:1:2"), "{msg}");
    assert!(msg.contains("'furlongs/fortnight'"), "{msg}");
    assert!(msg.contains("accepted: g, m/s^2"), "{msg}");

    let (e, msg) = unit_error(
        d,
        "wrong.csv",
        "time [s],acc_x [g],acc_y [g],acc_z [g],gyro_x [g],gyro_y [g],gyro_z [g]",
    );
    assert!(
        matches!(e, UnitError::WrongQuantity { found: Unit::G, .. }),
        "{e:?}"
    );
    assert!(
        msg.contains("wrong.csv:1:5") && msg.contains("is an acceleration"),
        "{msg}"
    );

    let (e, msg) = unit_error(
        d,
        "row.csv",
        "time,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\ns,g,g,g,deg/s,deg/s,turns/min",
    );
    assert!(
        matches!(
            e,
            UnitError::Unknown {
                quantity: Quantity::AngularRate,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        msg.contains("row.csv:2:7") && msg.contains("'turns/min'"),
        "{msg}"
    );

    let (e, msg) = unit_error(
        d,
        "mixed.csv",
        "time [s],acc_x [g],acc_y [m/s^2],acc_z [g],gyro_x [dps],gyro_y [dps],gyro_z [dps]",
    );
    assert!(
        matches!(
            e,
            UnitError::Mixed {
                unit: Unit::MetresPerSecond2,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        msg.contains("mixed.csv:1:3") && msg.contains("share one unit"),
        "{msg}"
    );
}

/// Names without units, with no units row: the units are inferred from the signal and said;
/// a time column without a unit beside units in the other names is inferred too.
#[test]
fn names_without_units_take_them_from_the_signal() {
    let t = tempfile::tempdir().unwrap();
    let p = file(
        t.path(),
        "nounits.csv",
        "time,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z",
        ',',
        [1e3, MPS2, 1.0],
    );
    let (r, rep) = read(&p, None).unwrap();
    assert!(max_diff(&r, walking()) < 1e-12);
    let notes = rep.notes.join(" | ");
    assert!(notes.contains("in ms, assumed"), "{notes}");
    assert!(notes.contains("reads as m/s², assumed"), "{notes}");
    assert!(notes.contains("reads as deg/s, assumed"), "{notes}");
    assert_eq!(rep.format, "generic");
    let p = file(
        t.path(),
        "time_only.csv",
        "time,acc_x [g],acc_y [g],acc_z [g],gyro_x [dps],gyro_y [dps],gyro_z [dps]",
        ',',
        [1.0, 1.0, 1.0],
    );
    let (r, rep) = read(&p, None).unwrap();
    assert!(max_diff(&r, walking()) < 1e-12);
    assert!(
        rep.columns[0].unit_from.contains("assumed"),
        "{:?}",
        rep.columns[0]
    );
    assert_eq!(rep.columns[1].unit_from, "header");
}

/// A given map keeps its units: the header's `[g]` is noted, not used, and the map's names
/// need not repeat the units.
#[test]
fn a_given_map_keeps_priority_over_header_units() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let map = FormatSpec::from_toml_str(
        r#"
name = "mine"
[time]
column = "time"
unit = "s"
[acc]
columns = ["acc_x", "acc_y", "acc_z"]
unit = "m/s2"
[gyro]
columns = ["gyro_x", "gyro_y", "gyro_z"]
unit = "deg/s"
"#,
        "mine.toml",
    )
    .unwrap();
    let header = "time [s],acc_x [g],acc_y [g],acc_z [g],gyro_x,gyro_y,gyro_z";
    let p = file(d, "given.csv", header, ',', [1.0, MPS2, 1.0]);
    let (rec, rep) = read(&p, Some(&map)).unwrap();
    let (reference, _) = read(
        &file(
            d,
            "ref.csv",
            "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z",
            ',',
            [1.0; 3],
        ),
        None,
    )
    .unwrap();
    assert!(max_diff(&rec, &reference) <= 1e-12);
    assert!(
        rep.notes
            .iter()
            .any(|n| n.contains("column 'acc_x [g]' states g, the format 'mine' says m/s²")),
        "{:?}",
        rep.notes
    );
    assert_eq!(rep.columns[1].unit, "m/s²");
    assert_eq!(rep.columns[1].unit_from, "format 'mine'");
}

/// The per-column report of a built-in with an axis map and units to convert (Shimmer: m/s²,
/// x down the shank).
#[test]
fn the_column_report_gives_channel_unit_and_conversion() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let shimmer = FormatSpec::builtin("shimmer-consensys").unwrap();
    let names = shimmer.column_names_for_writing().unwrap().join(",");
    let header = format!("{names}\nms,m/s^2,m/s^2,m/s^2,deg/s,deg/s,deg/s");
    // Values as ldh's frame would give them back: x and z flipped by the map.
    let p = file(d, "shimmer.csv", &header, ',', [1e3, MPS2, 1.0]);
    let (_, rep) = read(&p, None).unwrap();
    let c = &rep.columns;
    assert_eq!(c[0].channel, "time");
    assert_eq!(c[0].factor, Some(1e-3));
    assert_eq!(c[1].name, "Shimmer_Accel_LN_X_CAL");
    assert_eq!(c[1].channel, "acc_x");
    assert_eq!(c[1].factor, Some(-1.0 / MPS2));
    assert_eq!(
        c[1].conversion,
        format!("÷ {MPS2} (m/s² → g), sign flipped (axis map -x)")
    );
    assert_eq!(c[5].conversion, "no conversion");
    assert_eq!(c[1].unit_from, "format 'shimmer-consensys'");
    assert_eq!(
        c[1].line(),
        format!(
            "column 2 'Shimmer_Accel_LN_X_CAL' → acc_x: m/s² (format 'shimmer-consensys'), ÷ {MPS2} (m/s² → g), sign flipped (axis map -x)"
        )
    );
}
