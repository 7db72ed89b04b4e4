//! Column maps on whole files: unit-suffixed names, alternatives, multi-sensor files (HuGaDB
//! layout), selection by number, duplicates, `#` lines, and the refused maps.

use ldh_core::io::format::*;
use ldh_core::io::reader::*;
use ldh_core::io::writer::*;
use ldh_core::recording::Recording;
use ldh_sim::CohortParams;
use std::path::{Path, PathBuf};

fn walking(fs_hz: f64, seed: usize) -> Recording {
    let c = CohortParams {
        healthy: 3,
        ldh: 0,
        duration_s: 12.0,
        fs_hz,
        turn: false,
        ..CohortParams::default()
    };
    c.simulate(seed).unwrap().left.recording
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn read(p: &Path, f: Option<&FormatSpec>) -> ldh_core::Result<(Recording, ReadReport)> {
    read_recording(p, f, &ReadParams::default().check().unwrap())
}

fn max_diff(a: &Recording, b: &Recording) -> (f64, f64) {
    assert_eq!(a.len(), b.len());
    let mut d = (0.0f64, 0.0f64);
    for k in 0..3 {
        for i in 0..a.len() {
            d.0 = d.0.max((a.acc_g[k][i] - b.acc_g[k][i]).abs());
            d.1 = d.1.max((a.gyro_dps[k][i] - b.gyro_dps[k][i]).abs());
        }
    }
    d
}

/// The ldh CSV of `rec` with its header replaced.
fn with_header(rec: &Recording, header: &str, acc_k: f64, gyro_k: f64, time_k: f64) -> String {
    let mut s = format!("{header}\n");
    for i in 0..rec.len() {
        s.push_str(&format!(
            "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}\n",
            i as f64 / rec.fs_hz * time_k,
            rec.acc_g[0][i] * acc_k,
            rec.acc_g[1][i] * acc_k,
            rec.acc_g[2][i] * acc_k,
            rec.gyro_dps[0][i] * gyro_k,
            rec.gyro_dps[1][i] * gyro_k,
            rec.gyro_dps[2][i] * gyro_k
        ));
    }
    s
}

#[test]
fn unit_suffixed_csv_reads_without_a_map() {
    let rec = walking(100.0, 0);
    let t = tempfile::tempdir().unwrap();
    let g = ldh_core::recording::STANDARD_GRAVITY_MPS2;
    let r2d = std::f64::consts::PI / 180.0;
    for (name, header, ak, gk, tk) in [
        (
            "g_dps.csv",
            "time_s,acc_x_g,acc_y_g,acc_z_g,gyro_x_dps,gyro_y_dps,gyro_z_dps",
            1.0,
            1.0,
            1.0,
        ),
        (
            "mps2_rads_ms.csv",
            "time_ms,acc_x_mps2,acc_y_mps2,acc_z_mps2,gyro_x_rads,gyro_y_rads,gyro_z_rads",
            g,
            r2d,
            1e3,
        ),
        (
            "m_s2_rad_s.csv",
            "time_s,acc_x_m_s2,acc_y_m_s2,acc_z_m_s2,gyro_x_rad_s,gyro_y_rad_s,gyro_z_rad_s",
            g,
            r2d,
            1.0,
        ),
        (
            "deg_s.csv",
            "time_s,acc_x,acc_y,acc_z,gyro_x_deg_s,gyro_y_deg_s,gyro_z_deg_s",
            1.0,
            1.0,
            1.0,
        ),
    ] {
        let p = write(t.path(), name, &with_header(&rec, header, ak, gk, tk));
        let (r, rep) = read(&p, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(rep.format, "ldh", "{name}");
        assert!(
            rep.notes.iter().any(|n| n.contains("unit-suffixed")),
            "{name}: {:?}",
            rep.notes
        );
        let (da, dg) = max_diff(&r, &rec);
        assert!(da < 1e-5 && dg < 1e-3, "{name}: {da} g, {dg} deg/s");
        // The same with the ldh format given explicitly.
        read(&p, Some(&FormatSpec::default())).unwrap();
    }
}

#[test]
fn missing_columns_are_named_with_the_closest_header_names_only() {
    let rec = walking(100.0, 0);
    let t = tempfile::tempdir().unwrap();
    let text = with_header(
        &rec,
        "time_s,acc_x_g,acc_y_g,acc_z_g,gyro_1,gyro_2,gyro_3",
        1.0,
        1.0,
        1.0,
    );
    let p = write(t.path(), "half.csv", &text);
    let e = read(&p, None).unwrap_err().to_string();
    assert!(e.contains("no header row"), "{e}");
    assert!(e.contains("gyro_x → gyro_1"), "{e}");
    // What the names read as, and how to write a map.
    assert!(
        e.contains("acceleration (acc_x_g, acc_y_g, acc_z_g); no angular rate"),
        "{e}"
    );
    assert!(e.contains("ldh formats ldh > my.toml"), "{e}");
    // time_s is there: not called missing.
    assert!(!e.contains("\"time_s\""), "{e}");
    let e = read(&p, Some(&FormatSpec::default()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("half.csv:1"), "{e}");
    assert!(
        e.contains("[\"acc_x\", \"acc_y\", \"acc_z\", \"gyro_x\", \"gyro_y\", \"gyro_z\"]"),
        "{e}"
    );
}

#[test]
fn a_repeated_column_name_is_refused_naming_it() {
    let rec = walking(100.0, 0);
    let t = tempfile::tempdir().unwrap();
    let text = with_header(
        &rec,
        "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z",
        1.0,
        1.0,
        1.0,
    );
    let dup = text
        .lines()
        .map(|l| format!("{l},{}", l.split(',').nth(1).unwrap()))
        .collect::<Vec<_>>()
        .join("\n")
        .replacen(",acc_x\n", ",ACC_X\n", 1);
    let p = write(t.path(), "dup.csv", &dup);
    for f in [None, Some(&FormatSpec::default())] {
        let e = read(&p, f).unwrap_err().to_string();
        assert!(
            e.contains("dup.csv:1") && e.contains("'acc_x' occurs 2 times") && e.contains("[2, 8]"),
            "{e}"
        );
    }
    // Read from one block: allowed (the second acc_x is the 8th column: block 2 of acc_x only
    // exists for acc_x, so the other names are missing).
    let mut b = FormatSpec::default();
    b.sensor.block = Some(2);
    let e = read(&p, Some(&b)).unwrap_err().to_string();
    assert!(e.contains("(block 2)"), "{e}");
}

#[test]
fn a_multi_sensor_file_is_read_per_side_with_either_spelling() {
    // HuGaDB layout: 3 '#' lines, tab, a foot sensor, the right shin as RS_*, the left shin
    // spelled acc_ls_*, an activity column; no time.
    let (rr, rl) = (walking(58.8, 1), walking(58.8, 2));
    let right = FormatSpec::builtin("hugadb-right-shank").unwrap();
    let left = FormatSpec::builtin("hugadb-left-shank").unwrap();
    let body = |rec: &Recording, f: &FormatSpec| -> Vec<String> {
        recording_to_csv(rec, f, &WriteOptions::default())
            .unwrap()
            .lines()
            .map(String::from)
            .collect()
    };
    let (br, bl) = (body(&rr, &right), body(&rl, &left));
    assert_eq!(
        br[0],
        "RS_acc_x\tRS_acc_y\tRS_acc_z\tRS_gyro_x\tRS_gyro_y\tRS_gyro_z"
    );
    let left_header = "acc_ls_x\tacc_ls_y\tacc_ls_z\tgyro_ls_x\tgyro_ls_y\tgyro_ls_z";
    let mut text = String::from("#Activity\twalking \r\n#ActivityID\t1 \r\n#Date 2016-09-23\r\n");
    text.push_str(&format!("RF_acc_x\t{}\t{left_header}\tact\r\n", br[0]));
    for (a, b) in br.iter().zip(&bl).skip(1) {
        text.push_str(&format!("-10856\t{a}\t{b}\t1\r\n"));
    }
    let t = tempfile::tempdir().unwrap();
    let p = write(t.path(), "HuGaDB_v1_walking_99_00.txt", &text);
    for (f, rec) in [(&right, &rr), (&left, &rl)] {
        let (r, rep) = read(&p, Some(f)).unwrap_or_else(|e| panic!("{}: {e}", f.name));
        assert_eq!(rep.header_line, 4);
        assert!((r.fs_hz - 58.8).abs() < 1e-9);
        // One count: 1/16384 g, 1/16.4 deg/s (values beyond the range are written as counts
        // beyond int16 and read back the same).
        let (da, dg) = max_diff(&r, rec);
        assert!(
            da <= 0.6 / 16384.0 && dg <= 0.6 / 16.4,
            "{}: {da} {dg}",
            f.name
        );
    }
    // Not detected without a map: the same file holds both legs.
    let e = read(&p, None).unwrap_err().to_string();
    assert!(e.contains("no header row"), "{e}");
}

#[test]
fn columns_by_number_with_and_without_a_header_row() {
    let rec = walking(100.0, 0);
    let t = tempfile::tempdir().unwrap();
    let text = with_header(&rec, "t,a1,a2,a3,g1,g2,g3", 1.0, 1.0, 1.0);
    let by_number = FormatSpec::from_toml_str(
        "name = \"numbers\"\n[time]\ncolumn = 1\nunit = \"s\"\n[acc]\ncolumns = [2, 3, 4]\nunit = \"g\"\n[gyro]\ncolumns = [5, 6, 7]\nunit = \"deg/s\"\n",
        "numbers.toml",
    )
    .unwrap();
    let p = write(t.path(), "named.csv", &text);
    let (r, rep) = read(&p, Some(&by_number)).unwrap();
    assert_eq!(rep.header_line, 1);
    assert!(max_diff(&r, &rec).0 < 1e-5);
    let headerless = text.split_once('\n').unwrap().1;
    let p = write(t.path(), "headerless.csv", headerless);
    let (r2, rep) = read(&p, Some(&by_number)).unwrap();
    assert_eq!(max_diff(&r2, &r), (0.0, 0.0));
    assert!(rep.notes.iter().any(|n| n.contains("no header row")));
    let mut far = by_number.clone();
    far.gyro.columns[2] = ColumnRef::Index(40);
    let e = read(&p, Some(&far)).unwrap_err().to_string();
    assert!(e.contains("#40"), "{e}");
}

#[test]
fn raw_counts_files_with_hash_lines_read() {
    let rec = walking(100.0, 0);
    let f = FormatSpec::builtin("raw-counts").unwrap();
    let text = format!(
        "# logger v2\n# subject S1\n{}",
        recording_to_csv(&rec, &f, &WriteOptions::default()).unwrap()
    );
    let t = tempfile::tempdir().unwrap();
    let p = write(t.path(), "counts.csv", &text);
    let (r, _) = read(&p, Some(&f)).unwrap();
    assert!(max_diff(&r, &rec).0 < 1e-3);
    let (_, rep) = read(&p, None).unwrap();
    assert_eq!(rep.format, "raw-counts");
}

#[test]
fn column_maps_with_mistakes_are_refused_with_the_reason() {
    let base = |acc: &str| {
        format!("name = \"m\"\n[time]\ncolumn = \"t\"\n[acc]\ncolumns = {acc}\nunit = \"g\"\n[gyro]\ncolumns = [\"gx\", \"gy\", \"gz\"]\nunit = \"deg/s\"\n")
    };
    for (acc, want) in [
        ("[0, 1, 2]", "count from 1"),
        ("[[], \"ay\", \"az\"]", "non-empty names"),
        ("[\"\", \"ay\", \"az\"]", "empty column name"),
        ("[\"ax\", \"ay\"]", "m.toml"),
        ("[1.5, \"ay\", \"az\"]", "m.toml"),
    ] {
        let e = FormatSpec::from_toml_str(&base(acc), "m.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains(want), "{acc}: {e}");
    }
    let e = FormatSpec::from_toml_str(
        &format!("{}[sensor]\nblock = 0\n", base("[\"ax\", \"ay\", \"az\"]")),
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("sensor.block counts from 1"), "{e}");
    let e = FormatSpec::from_toml_str(
        &format!("{}[sensor]\nblok = 2\n", base("[\"ax\", \"ay\", \"az\"]")),
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("blok"), "{e}");
    let numbers = FormatSpec::from_toml_str(&base("[1, 2, 3]"), "m.toml").unwrap();
    let e = recording_to_csv(&walking(100.0, 0), &numbers, &WriteOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("by number"), "{e}");
}
