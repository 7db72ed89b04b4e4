//! The recording's start date and time (`start_time.rs`): the spellings parsed, and files that
//! give it in a header comment (ldh `#`, Xsens `//`), in Xsens' UTC columns, as ISO 8601 or
//! Unix timestamps, read onto the recording and the read report; a file without one has none.

use crate::io_units::walking;
use ldh_core::io::format::FormatSpec;
use ldh_core::io::reader::{read_recording, ReadParams, ReadReport};
use ldh_core::io::writer::format_iso8601;
use ldh_core::io::{DateTime, RecordedAt, StartFrom};
use ldh_core::recording::Recording;
use std::path::Path;

fn dt(ymd: (i64, i64, i64), hms: (i64, i64, i64), utc: bool) -> DateTime {
    DateTime::new(ymd, hms, utc).unwrap()
}

/// `rec` as rows: `time` of each sample, then the six channels × the factors, tab separated.
fn rows(rec: &Recording, time: impl Fn(usize) -> String, acc_k: f64, gyro_k: f64) -> String {
    let mut s = String::new();
    for i in 0..rec.len() {
        let mut row = vec![time(i)];
        row.extend((0..3).map(|a| format!("{}", rec.acc_g[a][i] * acc_k)));
        row.extend((0..3).map(|a| format!("{}", rec.gyro_dps[a][i] * gyro_k)));
        s.push_str(&row.join("\t"));
        s.push('\n');
    }
    s
}

fn read(dir: &Path, name: &str, text: &str, f: Option<&FormatSpec>) -> (Recording, ReadReport) {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    read_recording(&p, f, &ReadParams::default().check().unwrap())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The start of 2024-03-05 10:21:33 in each place a file can give it is read onto the
/// recording and the read report (and noted); a file without one gives none.
#[test]
fn files_give_their_start_where_they_have_one() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let rec = walking();
    let at = dt((2024, 3, 5), (10, 21, 33), true);
    let unix = 1_709_634_093.0;
    let g = ldh_core::recording::STANDARD_GRAVITY_MPS2;
    let rad = std::f64::consts::PI / 180.0;
    let secs = |i: usize| format!("{}", i as f64 / rec.fs_hz);
    let ldh_header = "time_s\tacc_x\tacc_y\tacc_z\tgyro_x\tgyro_y\tgyro_z\n";
    let xsens_header = "PacketCounter\tAcc_X\tAcc_Y\tAcc_Z\tGyr_X\tGyr_Y\tGyr_Z\n";
    let counter = |i: usize| format!("{}", i % 65536);

    let text = format!(
        "# ldh export\n# start: 2024-03-05T10:21:33Z\n{ldh_header}{}",
        rows(rec, secs, 1.0, 1.0)
    );
    let hash = read(d, "hash.csv", &text, None);

    let text = format!(
        "// General information:\n//  MT Manager version: 2022.0.0\n// Start Time: 2024-03-05 10:21:33:125\n{xsens_header}{}",
        rows(rec, counter, g, rad)
    );
    let xsens = read(d, "xsens.txt", &text, None);

    // Xsens with UTC columns between the counter and the channels.
    let utc_header = xsens_header.replacen(
        "PacketCounter\t",
        "PacketCounter\tUTC_Nano\tUTC_Year\tUTC_Month\tUTC_Day\tUTC_Hour\tUTC_Minute\tUTC_Second\tUTC_Valid\t",
        1,
    );
    let utc = |i: usize| {
        let s = DateTime::from_unix_s(unix + i as f64 / rec.fs_hz).unwrap();
        format!(
            "{}\t0\t{}\t{}\t{}\t{}\t{}\t{}\t7",
            i % 65536,
            s.year,
            s.month,
            s.day,
            s.hour,
            s.minute,
            s.second
        )
    };
    let text = format!("{utc_header}{}", rows(rec, utc, g, rad));
    let utc_cols = read(d, "utc.txt", &text, None);

    let mut iso_map = FormatSpec::default();
    iso_map.time.unit = ldh_core::io::format::TimeUnit::Iso8601;
    let iso_time = |i: usize| format_iso8601(unix + i as f64 / rec.fs_hz);
    let text = format!("{ldh_header}{}", rows(rec, iso_time, 1.0, 1.0));
    let iso = read(d, "iso.csv", &text, Some(&iso_map));

    let shimmer = FormatSpec::builtin("shimmer-consensys").unwrap();
    let names = shimmer.column_names_for_writing().unwrap().join("\t");
    let ms = |i: usize| format!("{}", unix * 1e3 + i as f64 * 1e3 / rec.fs_hz);
    let text = format!(
        "sep=\\t\n{names}\nms\tm/(s^2)\tm/(s^2)\tm/(s^2)\tdeg/s\tdeg/s\tdeg/s\n{}",
        rows(rec, ms, g, 1.0)
    );
    let shim = read(d, "shimmer.csv", &text, None);

    let local = DateTime { utc: false, ..at };
    for (name, (r, rep), want) in [
        ("hash", &hash, (at, StartFrom::Header)),
        ("xsens", &xsens, (local, StartFrom::Header)),
        ("utc columns", &utc_cols, (at, StartFrom::UtcColumns)),
        ("iso", &iso, (local, StartFrom::IsoTime)),
        ("shimmer", &shim, (at, StartFrom::UnixTime)),
    ] {
        let want = RecordedAt {
            at: want.0,
            from: want.1,
        };
        assert_eq!(r.recorded_at, Some(want), "{name}");
        assert_eq!(rep.recorded_at, Some(want), "{name}");
        let note = format!("recording start {} (from the ", want.at.iso());
        assert!(
            rep.notes.iter().any(|n| n.starts_with(&note)),
            "{name}: {:?}",
            rep.notes
        );
    }
    // The channels of the UTC-column file are the Xsens file's: the read-ahead row was read.
    assert_eq!(utc_cols.0.len(), xsens.0.len());
    assert_eq!(utc_cols.0.acc_g, xsens.0.acc_g);

    let text = format!("{ldh_header}{}", rows(rec, secs, 1.0, 1.0));
    let (none, rep) = read(d, "none.csv", &text, None);
    assert_eq!(none.recorded_at, None);
    assert_eq!(rep.recorded_at, None);
    assert!(!rep.notes.iter().any(|n| n.contains("recording start")));
}
