//! Reader tests: every supported variation reads back what was written, and every bad input
//! gives an error that names the file and the problem (and line and column where there is one).

use ldh_core::io::format::*;
use ldh_core::io::reader::*;
use ldh_core::io::writer::*;
use ldh_core::recording::Recording;
use ldh_sim::{CohortParams, SensorModel};
use ldh_test_support::TempFolder;
use std::path::Path;

fn walking(fs_hz: f64) -> Recording {
    let c = CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 12.0,
        fs_hz,
        turn: false,
        ..CohortParams::default()
    };
    c.simulate(0).unwrap().left.recording
}

fn params() -> ValidReadParams {
    ReadParams::default().check().unwrap()
}

fn csv(rec: &Recording, spec: &FormatSpec) -> String {
    recording_to_csv(rec, spec, &WriteOptions::default()).unwrap()
}

fn read(path: &Path, spec: Option<&FormatSpec>) -> ldh_core::Result<(Recording, ReadReport)> {
    read_recording(path, spec, &params())
}

fn assert_close(a: &Recording, b: &Recording, acc_tol_g: f64, gyro_tol_dps: f64) {
    assert_eq!(a.len(), b.len());
    assert!(
        (a.fs_hz - b.fs_hz).abs() < 1e-6 * a.fs_hz,
        "{} vs {}",
        a.fs_hz,
        b.fs_hz
    );
    for k in 0..3 {
        for i in 0..a.len() {
            assert!(
                (a.acc_g[k][i] - b.acc_g[k][i]).abs() <= acc_tol_g,
                "acc {k} {i}"
            );
            assert!(
                (a.gyro_dps[k][i] - b.gyro_dps[k][i]).abs() <= gyro_tol_dps,
                "gyro {k} {i}"
            );
        }
    }
}

fn err_of(path: &Path, spec: Option<&FormatSpec>) -> String {
    let e = read(path, spec).expect_err("should fail");
    let msg = e.to_string();
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    assert!(msg.contains(&name), "message does not name the file: {msg}");
    msg
}

#[test]
fn default_format_round_trips_with_every_delimiter_bom_crlf_and_comments() {
    let rec = walking(100.0);
    let t = TempFolder::new();
    let base = csv(&rec, &FormatSpec::default());
    let variants = [
        ("comma.csv", base.clone()),
        ("semicolon.csv", base.replace(',', ";")),
        ("tab.csv", base.replace(',', "\t")),
        ("bom.csv", format!("\u{feff}{base}")),
        ("crlf.csv", base.replace('\n', "\r\n")),
        (
            "comments.csv",
            format!("# exported by a logger\n# subject 7\n\n{base}"),
        ),
    ];
    for (name, text) in variants {
        let p = t.write(name, text);
        let (r, rep) = read(&p, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_close(&r, &rec, 1e-5, 1e-3);
        assert_eq!(rep.format, "ldh");
        assert!(!rep.resampled, "{name}");
        if name == "bom.csv" {
            assert!(rep.bom);
        }
        if name == "tab.csv" {
            assert_eq!(rep.delimiter, "tab");
        }
    }
}

#[test]
fn vendor_formats_round_trip() {
    let rec = walking(100.0);
    let t = TempFolder::new();
    for name in DETECTED_FORMATS {
        let spec = FormatSpec::builtin(name).unwrap();
        let opts = WriteOptions {
            preamble: if name == "xsens-mtmanager" {
                vec!["General information:".into(), "Update Rate: 100.0Hz".into()]
            } else {
                vec![]
            },
            ..WriteOptions::default()
        };
        let mut text = recording_to_csv(&rec, &spec, &opts).unwrap();
        if name == "shimmer-consensys" {
            text = format!("\"sep=,\"\n{text}");
        }
        let p = t.write(&format!("{name}.csv"), &text);
        let (r, rep) = read(&p, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(rep.format, name, "detected format");
        // Counts quantise to one LSB (≤ 0.25 mg, 0.03 deg/s), rad/s keeps 5 decimals.
        assert_close(&r, &rec, 3e-4, 0.05);
        let (r2, _) = read(&p, Some(&spec)).unwrap();
        assert_eq!(r, r2);
    }
}

#[test]
fn time_in_ms_iso8601_and_counters_with_wrap() {
    let rec = walking(100.0);
    let t = TempFolder::new();
    let mut ms = FormatSpec::default();
    ms.time = TimeSpec {
        column: Some("t_ms".into()),
        unit: TimeUnit::Milliseconds,
        ..TimeSpec::default()
    };
    let p = t.write("ms.csv", csv(&rec, &ms));
    let (r, _) = read(&p, Some(&ms)).unwrap();
    assert!((r.fs_hz - 100.0).abs() < 1e-6);

    let mut iso = FormatSpec::default();
    iso.time = TimeSpec {
        column: Some("timestamp".into()),
        unit: TimeUnit::Iso8601,
        ..TimeSpec::default()
    };
    let mut shifted = rec.clone();
    shifted.t0_s = 1_709_288_102.0; // 2024-03-01T10:15:02
    let text = csv(&shifted, &iso);
    assert!(text
        .lines()
        .nth(1)
        .unwrap()
        .starts_with("2024-03-01T10:15:02.000"));
    let p = t.write("iso.csv", text);
    let (r, _) = read(&p, Some(&iso)).unwrap();
    assert!((r.fs_hz - 100.0).abs() < 1e-6);
    assert_eq!(r.t0_s, 1_709_288_102.0);

    // A counter that wraps at 1000 (every 10 s at 100 Hz).
    let mut ctr = FormatSpec::builtin("xsens-mtmanager").unwrap();
    ctr.time.counter_wrap = Some(1000);
    let p = t.write("wrap.txt", csv(&rec, &ctr));
    let (r, rep) = read(&p, Some(&ctr)).unwrap();
    assert_eq!(r.len(), rec.len());
    assert!(
        rep.notes.iter().any(|n| n.contains("wrapped")),
        "{:?}",
        rep.notes
    );
}

#[test]
fn rate_is_measured_for_50_60_and_200_hz_devices() {
    let t = TempFolder::new();
    for fs in [50.0, 60.0, 200.0] {
        let rec = walking(fs);
        let p = t.write(&format!("r{fs}.csv"), csv(&rec, &FormatSpec::default()));
        let (r, rep) = read(&p, None).unwrap();
        assert!((r.fs_hz - fs).abs() < 1e-3 * fs, "{} vs {fs}", r.fs_hz);
        assert!(!rep.resampled);
    }
}

#[test]
fn jittered_timestamps_are_resampled_and_small_gaps_bridged() {
    let rec = walking(100.0);
    let text = csv(&rec, &FormatSpec::default());
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    // Jitter: shift every 7th timestamp by 3 ms; drop 5 consecutive rows (a 60 ms gap).
    for (i, l) in lines.iter_mut().enumerate().skip(1) {
        if i % 7 == 0 {
            let (t, rest) = l.split_once(',').unwrap();
            let t: f64 = t.parse().unwrap();
            *l = format!("{:.4},{rest}", t + 0.003);
        }
    }
    lines.drain(300..305);
    let t = TempFolder::new();
    let p = t.write("jitter.csv", lines.join("\n"));
    let (r, rep) = read(&p, None).unwrap();
    assert!(rep.resampled);
    assert!(rep.gaps.is_empty());
    assert!((r.fs_hz - 100.0).abs() < 0.1, "{}", r.fs_hz);
    assert!(rep.notes.iter().any(|n| n.contains("resampled")));
}

#[test]
fn long_gaps_split_or_reject() {
    let rec = walking(100.0);
    let text = csv(&rec, &FormatSpec::default());
    let mut lines: Vec<&str> = text.lines().collect();
    lines.drain(200..260); // 0.6 s missing
    let t = TempFolder::new();
    let p = t.write("gap.csv", lines.join("\n"));
    let (r, rep) = read(&p, None).unwrap();
    assert_eq!(rep.gaps.len(), 1);
    assert_eq!(rep.gaps[0].line, 201);
    assert_eq!(rep.dropped_segments.len(), 1);
    assert!(r.duration_s() > 9.0);
    let reject = ReadParams::default()
        .gap_policy(GapPolicy::Reject)
        .check()
        .unwrap();
    let e = read_recording(&p, None, &reject).unwrap_err().to_string();
    assert!(e.contains("gap.csv:201") && e.contains("gap of 0.6"), "{e}");
}

#[test]
fn saturation_is_counted_by_range_and_by_flat_extremes() {
    let mut rec = walking(100.0);
    // Clip gyro z at 300 deg/s without a declared range: flat runs at the extreme.
    for v in rec.gyro_dps[2].iter_mut() {
        *v = v.clamp(-300.0, 300.0);
    }
    let t = TempFolder::new();
    let p = t.write("clip.csv", csv(&rec, &FormatSpec::default()));
    let (r, rep) = read(&p, None).unwrap();
    assert!(
        rep.saturated_per_channel[5] > 10,
        "{:?}",
        rep.saturated_per_channel
    );
    assert_eq!(r.saturated_count(), rep.saturated_samples);
    assert!(rep.notes.iter().any(|n| n.contains("clipped")));
    // With a declared range of ±300 deg/s the same samples count.
    let mut spec = FormatSpec::default();
    spec.gyro.range = Some(300.0);
    let (_, rep2) = read(&p, Some(&spec)).unwrap();
    assert!(rep2.saturated_per_channel[5] >= rep.saturated_per_channel[5]);
    // A still sensor reading exactly 1 g for a while is not clipping.
    let mut still = walking(100.0);
    for v in still.acc_g[0].iter_mut().take(200) {
        *v = 1.0;
    }
    let p = t.write("still.csv", csv(&still, &FormatSpec::default()));
    let (_, rep3) = read(&p, None).unwrap();
    assert_eq!(rep3.saturated_per_channel[0], 0);
}

#[test]
fn bad_files_are_refused_with_the_file_and_the_problem() {
    let rec = walking(100.0);
    let good = csv(&rec, &FormatSpec::default());
    let lines: Vec<&str> = good.lines().collect();
    let with_line = |i: usize, new: &str| {
        let mut v = lines.clone();
        v[i] = new;
        v.join("\n")
    };
    let t = TempFolder::new();

    let p = t.write("empty.csv", "");
    assert!(err_of(&p, None).contains("empty"));
    let p = t.write("blank.csv", "\n\n  \n");
    assert!(err_of(&p, None).contains("empty"));
    let p = t.write("binary.csv", [0x50u8, 0x4b, 0x03, 0x04, 0x00, 0x00, 0x14]);
    assert!(err_of(&p, None).contains("not a text file"));
    let mut latin1 = b"time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n".to_vec();
    latin1.extend_from_slice(b"0.0,1.0,0.0,0.0,0.0,0.0,0.0 \xe9\n");
    let p = t.write("latin1.csv", &latin1);
    let m = err_of(&p, None);
    assert!(m.contains("UTF-8") && m.contains("latin1.csv:2"), "{m}");

    let p = t.write("nohead.csv", "a,b,c\n1,2,3\n");
    let m = err_of(&p, None);
    assert!(m.contains("no header row") && m.contains("time_s"), "{m}");
    let p = t.write("missing.csv", good.replacen("gyro_z", "gyro_q", 1));
    let m = err_of(&p, Some(&FormatSpec::default()));
    assert!(
        m.contains("[\"gyro_z\"]") && m.contains("missing.csv:1") && m.ends_with("gyro_z → gyro_q"),
        "{m}"
    );

    let p = t.write("text.csv", with_line(40, "0.39,1.0,abc,0.0,0.0,0.0,0.0"));
    let m = err_of(&p, None);
    assert!(
        m.contains("text.csv:41:3") && m.contains("'abc' is not a number") && m.contains("acc_y"),
        "{m}"
    );
    let p = t.write("emptycell.csv", with_line(40, "0.39,1.0,,0.0,0.0,0.0,0.0"));
    assert!(err_of(&p, None).contains("the cell is empty"));
    let p = t.write("nan.csv", with_line(40, "0.39,1.0,NaN,0.0,0.0,0.0,0.0"));
    let m = err_of(&p, None);
    assert!(
        m.contains("nan.csv:41:3") && m.contains("non-finite"),
        "{m}"
    );
    let p = t.write("inf.csv", with_line(40, "0.39,1.0,0.0,0.0,0.0,inf,0.0"));
    assert!(err_of(&p, None).contains("inf.csv:41:6"));
    // Finite but beyond any sensor (it would overflow the filters): refused where it is.
    let p = t.write("e308.csv", with_line(40, "0.39,1.0,0.0,-1e308,0.0,0.0,0.0"));
    let m = err_of(&p, None);
    assert!(
        m.contains("e308.csv:41:4") && m.contains("'-1e308' is beyond any sensor's range"),
        "{m}"
    );
    let p = t.write("e12.csv", with_line(40, "0.39,1.0,0.0,1e12,0.0,0.0,0.0"));
    assert!(
        read(&p, None).is_ok(),
        "1e12 is allowed (an outlier, replaced later)"
    );
    let p = t.write("fields.csv", with_line(40, "0.39,1.0,0.0,0.0,0.0,0.0"));
    let m = err_of(&p, None);
    assert!(
        m.contains("fields.csv:41") && m.contains("6 fields") && m.contains("has 7"),
        "{m}"
    );
    let p = t.write(
        "toomany.csv",
        with_line(40, "0.39,1.0,0.0,0.0,0.0,0.0,0.0,9.9"),
    );
    assert!(err_of(&p, None).contains("8 fields"));

    let dup = lines[40].replacen(
        lines[40].split(',').next().unwrap(),
        lines[39].split(',').next().unwrap(),
        1,
    );
    let p = t.write("dup.csv", with_line(40, &dup));
    let m = err_of(&p, None);
    assert!(
        m.contains("dup.csv:41:1") && m.contains("must increase"),
        "{m}"
    );
    let back = lines[40].replacen(lines[40].split(',').next().unwrap(), "0.1", 1);
    let p = t.write("back.csv", with_line(40, &back));
    assert!(err_of(&p, None).contains("back.csv:41:1"));

    let short: String = lines[..150].join("\n");
    let p = t.write("short.csv", short);
    let m = err_of(&p, None);
    assert!(
        m.contains("too short") && m.contains("three strides"),
        "{m}"
    );

    // Decimal commas with a ';' delimiter: a hint, then a format that reads them.
    let euro = good.replace(',', ";").replace('.', ",");
    let p = t.write("euro.csv", &euro);
    let m = err_of(&p, None);
    assert!(m.contains("decimal comma"), "{m}");
    let mut spec = FormatSpec::default();
    spec.decimal = Decimal::Comma;
    spec.delimiter = Delimiter::Semicolon;
    let (r, _) = read(&p, Some(&spec)).unwrap();
    assert_close(&r, &rec, 1e-5, 1e-3);

    // One cell with a decimal comma among '.' cells: the likely cause, with its column.
    let mut rows: Vec<String> = good.lines().map(String::from).collect();
    let mut cells: Vec<String> = rows[3].split(',').map(String::from).collect();
    cells[1] = format!("{:.0},{}", 0.0, 5);
    rows[3] = cells.join(",");
    let p = t.write("one_comma.csv", rows.join("\n"));
    let m = err_of(&p, None);
    assert!(
        m.contains("one_comma.csv:4")
            && m.contains("a decimal comma in 1 cell(s) is likely")
            && m.contains("'0,5' at column 2"),
        "{m}"
    );
}

#[test]
fn implausible_units_are_named() {
    let rec = walking(100.0);
    let t = TempFolder::new();
    // Gyro written in rad/s but declared deg/s.
    let mut radians = rec.clone();
    for ch in radians.gyro_dps.iter_mut() {
        for v in ch.iter_mut() {
            *v = v.to_radians();
        }
    }
    let p = t.write("rad.csv", csv(&radians, &FormatSpec::default()));
    let m = err_of(&p, None);
    assert!(m.contains("rad/s"), "{m}");
    // Acceleration in m/s² declared as g.
    let mut mps2 = rec.clone();
    for ch in mps2.acc_g.iter_mut() {
        for v in ch.iter_mut() {
            *v *= 9.80665;
        }
    }
    let p = t.write("mps2.csv", csv(&mps2, &FormatSpec::default()));
    assert!(err_of(&p, None).contains("m/s² declared as g"));
    // Switched off, the file is read.
    let lax = ReadParams::default().check_units(false).check().unwrap();
    assert!(read_recording(&p, None, &lax).is_ok());
}

#[test]
fn axis_maps_are_applied_and_reflections_refused() {
    let rec = walking(100.0);
    let t = TempFolder::new();
    // A device whose x points down the shank and z the other way: ldh x = −x, z = −z.
    let spec = FormatSpec::default().with_axes(["-x", "+y", "-z"]);
    let p = t.write("flipped.csv", csv(&rec, &spec));
    let (r, rep) = read(&p, Some(&spec)).unwrap();
    assert_close(&r, &rec, 1e-5, 1e-3);
    assert!(rep.notes.iter().any(|n| n.contains("axes mapped")));
    // Read with the plain format the x axis is upside down.
    let (plain, _) = read(&p, None).unwrap();
    assert!((plain.acc_g[0][10] + rec.acc_g[0][10]).abs() < 1e-4);
    let bad = FormatSpec::default().with_axes(["-x", "+y", "+z"]);
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.contains("reflection"), "{e}");
    let bad = FormatSpec::default().with_axes(["+x", "+x", "+z"]);
    assert!(bad.validate().unwrap_err().to_string().contains("twice"));
}

#[test]
fn the_sensor_model_of_the_simulator_reads_without_unit_complaints() {
    // Regression guard: the walking fixture used above must pass the plausibility checks.
    let rec = walking(100.0);
    let spec = FormatSpec::default();
    assert!(check_units_plausible(&rec, &spec, Path::new("x.csv")).is_ok());
    let _ = SensorModel::default();
}
