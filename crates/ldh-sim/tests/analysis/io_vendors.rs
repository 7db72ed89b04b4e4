//! Vendor exports read without a map (`recognise.rs`, `labelled.rs`, `infer.rs`): the header
//! lines of real exports, as their vendors' manuals and examples publish them, over a simulated
//! walk written in each vendor's units, each read with no `--input-format` into the recording
//! the walk is (to the precision written), with the format recognised and every unit the
//! header does not state inferred and said.
//!
//! Sources of the header lines: Movella DOT User Manual (exported CSV, "Custom Mode 4" with
//! inertial data: `PacketCounter,SampleTimeFine,…,Acc_X…,Gyr_X…`, µs, m/s², deg/s); Xsens MT
//! Manager User Manual (ASCII export, `//` header lines, tab or comma; SampleTimeFine in 100 µs
//! ticks, m/s², rad/s); Shimmer ConsensysPRO CSV export (`"sep=\t"`, names with the device id,
//! a `CAL` row and a units row); APDM Motion Studio CSV (as OpenSim's `APDMDataReader` reads it:
//! `Test Name:`, `Sample Rate:`, `Time,<label>/Acceleration/X…`, then a units row); Physics
//! Toolbox Sensor Suite (`time,gFx,gFy,gFz,ax,ay,az,wx,wy,wz,…`: g-force in g, linear
//! acceleration in m/s², rad/s); SensorLog for iOS (`accelerometerAccelerationX(G)`,
//! `gyroRotationX(rad/s)`); the generic app exports of issue 51 (`timestamp,ax,ay,az,gx,gy,gz`;
//! `time,accX…,gyroX…`; `Time [s],Acc_X [m/s^2]…`).

use ldh_core::error::LdhError;
use ldh_core::io::reader::*;
use ldh_core::recording::{Recording, STANDARD_GRAVITY_MPS2};
use ldh_sim::CohortParams;
use std::path::Path;

/// A simulated walk at `fs_hz`, made once per rate.
fn walking(fs_hz: f64) -> Recording {
    let c = CohortParams {
        healthy: 3,
        ldh: 0,
        duration_s: 12.0,
        fs_hz,
        turn: false,
        ..CohortParams::default()
    };
    c.simulate(0).unwrap().left.recording
}

/// How a vendor writes a walk: the time cell of sample `i`, the factor of the acceleration (g →
/// the file's unit) and of the angular rate (deg/s → the file's unit), the signs of the file's
/// axes (the inverse of the axis map ldh applies), the cells before, between and after.
struct Vendor {
    /// What the case is.
    name: &'static str,
    /// Lines above the header and the header (and units rows), `\n`-separated, in `delim`.
    head: &'static str,
    delim: char,
    fs_hz: f64,
    /// Time cell of sample i at `fs_hz`.
    time: fn(usize, f64) -> String,
    acc_k: f64,
    gyro_k: f64,
    /// Sign of the file's x, y, z for ldh's x, y, z.
    sign: [f64; 3],
    /// Cells of columns not read, before the time, between time and acc, between acc and gyro,
    /// after the gyro.
    pad: [usize; 4],
    /// The format named in the read report.
    format: &'static str,
    /// Words every note of the report must hold together (what was assumed).
    notes: &'static [&'static str],
}

const G: f64 = STANDARD_GRAVITY_MPS2;
const RAD: f64 = std::f64::consts::PI / 180.0;

fn vendors() -> Vec<Vendor> {
    vec![
        Vendor {
            name: "Movella DOT CSV",
            head: "DeviceTag:,Left shank\nFirmwareVersion:,2.4.0\nAppVersion:,2023.6.0\nSyncStatus:,Synced\nOutputRate:,60Hz\nFilterProfile:,General\nMeasurement Mode:,Custom Mode 4\nPacketCounter,SampleTimeFine,Quat_W,Quat_X,Quat_Y,Quat_Z,FreeAcc_X,FreeAcc_Y,FreeAcc_Z,Acc_X,Acc_Y,Acc_Z,Gyr_X,Gyr_Y,Gyr_Z,Status",
            delim: ',',
            fs_hz: 60.0,
            time: |i, fs| format!("{}", 3_000_000_000u64 + (i as f64 * 1e6 / fs).round() as u64),
            acc_k: G,
            gyro_k: 1.0,
            sign: [1.0; 3],
            pad: [1, 7, 0, 1],
            format: "movella-xsens",
            notes: &["µs (Movella DOT)", "m/s²", "deg/s"],
        },
        Vendor {
            name: "Xsens MT Manager txt",
            head: "// Start Time: 2024-03-05 10:21:33:125\n// Update Rate: 100.0Hz\n// Filter Profile: human (46.1)\n// Option Flags: AHS Disabled, ICC Disabled\n// Firmware Version: 4.6.0\nPacketCounter\tSampleTimeFine\tAcc_X\tAcc_Y\tAcc_Z\tGyr_X\tGyr_Y\tGyr_Z\tMag_X\tMag_Y\tMag_Z\tRoll\tPitch\tYaw",
            delim: '\t',
            fs_hz: 100.0,
            time: |i, _| format!("{}", i % 65536),
            acc_k: G,
            gyro_k: RAD,
            sign: [1.0; 3],
            pad: [0, 1, 0, 6],
            format: "xsens-mtmanager",
            notes: &[],
        },
        Vendor {
            name: "Xsens MT Manager CSV",
            head: "// Start Time: 2024-03-05 10:21:33:125\n// Update Rate: 60.0Hz\nPacketCounter,SampleTimeFine,Acc_X,Acc_Y,Acc_Z,Gyr_X,Gyr_Y,Gyr_Z,Mag_X,Mag_Y,Mag_Z",
            delim: ',',
            fs_hz: 60.0,
            time: |i, fs| format!("{}", 123_456 + (i as f64 * 1e4 / fs).round() as u64),
            acc_k: G,
            gyro_k: RAD,
            sign: [1.0; 3],
            pad: [1, 0, 0, 3],
            format: "movella-xsens",
            notes: &["100 µs ticks", "m/s²", "rad/s"],
        },
        Vendor {
            name: "Shimmer ConsensysPRO CSV",
            head: "\"sep=\t\"\nShimmer_8665_Timestamp_Unix_CAL\tShimmer_8665_Accel_LN_X_CAL\tShimmer_8665_Accel_LN_Y_CAL\tShimmer_8665_Accel_LN_Z_CAL\tShimmer_8665_Gyro_X_CAL\tShimmer_8665_Gyro_Y_CAL\tShimmer_8665_Gyro_Z_CAL\tShimmer_8665_Accel_WR_X_CAL\tShimmer_8665_Accel_WR_Y_CAL\tShimmer_8665_Accel_WR_Z_CAL\nCAL\tCAL\tCAL\tCAL\tCAL\tCAL\tCAL\tCAL\tCAL\tCAL\nms\tm/(s^2)\tm/(s^2)\tm/(s^2)\tdeg/s\tdeg/s\tdeg/s\tm/(s^2)\tm/(s^2)\tm/(s^2)",
            delim: '\t',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", 1_700_000_000_000.0 + i as f64 * 1e3 / fs),
            acc_k: G,
            gyro_k: 1.0,
            sign: [-1.0, 1.0, -1.0],
            pad: [0, 0, 0, 3],
            format: "shimmer",
            notes: &["units read from the row under the names (line 4)"],
        },
        Vendor {
            name: "APDM Motion Studio CSV",
            head: "Test Name:,walk_01,,,,,,,,\nSample Rate:,100.000000,Hz,,,,,,,\nTime,Right Shank/Acceleration/X,Right Shank/Acceleration/Y,Right Shank/Acceleration/Z,Right Shank/Angular Velocity/X,Right Shank/Angular Velocity/Y,Right Shank/Angular Velocity/Z,Right Shank/Magnetic Field/X,Right Shank/Magnetic Field/Y,Right Shank/Magnetic Field/Z\ns,m/s^2,m/s^2,m/s^2,rad/s,rad/s,rad/s,uT,uT,uT",
            delim: ',',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", i as f64 / fs),
            acc_k: G,
            gyro_k: RAD,
            sign: [1.0; 3],
            pad: [0, 0, 0, 3],
            format: "apdm",
            notes: &["units read from the row under the names"],
        },
        Vendor {
            name: "generic phone app (timestamp,ax…gz), Android units",
            head: "timestamp,ax,ay,az,gx,gy,gz",
            delim: ',',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", 1_700_000_000_000u64 + (i as f64 * 1e3 / fs) as u64),
            acc_k: G,
            gyro_k: RAD,
            sign: [1.0; 3],
            pad: [0, 0, 0, 0],
            format: "generic",
            notes: &["in ms, assumed", "m/s²", "rad/s"],
        },
        Vendor {
            name: "Physics Toolbox Sensor Suite",
            head: "time,gFx,gFy,gFz,ax,ay,az,wx,wy,wz,p,Bx,By,Bz",
            delim: ',',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", i as f64 / fs),
            acc_k: 1.0,
            gyro_k: RAD,
            sign: [1.0; 3],
            pad: [0, 0, 3, 4],
            format: "generic",
            notes: &["in s, assumed", "rad/s"],
        },
        Vendor {
            name: "SensorLog (iOS)",
            head: "accelerometerTimestamp_sinceReboot(s),accelerometerAccelerationX(G),accelerometerAccelerationY(G),accelerometerAccelerationZ(G),gyroRotationX(rad/s),gyroRotationY(rad/s),gyroRotationZ(rad/s)",
            delim: ',',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", 5000.0 + i as f64 / fs),
            acc_k: 1.0,
            gyro_k: RAD,
            sign: [1.0; 3],
            pad: [0, 0, 0, 0],
            format: "generic",
            notes: &["units read from the names"],
        },
        Vendor {
            name: "app export accX…gyroZ (ms, g, deg/s)",
            head: "time;accX;accY;accZ;gyroX;gyroY;gyroZ",
            delim: ';',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", (i as f64 * 1e3 / fs) as u64),
            acc_k: 1.0,
            gyro_k: 1.0,
            sign: [1.0; 3],
            pad: [0, 0, 0, 0],
            format: "generic",
            notes: &["in ms, assumed", "reads as g", "deg/s"],
        },
        Vendor {
            name: "Acc_X [m/s^2] style units",
            head: "Time [s],Acc_X [m/s^2],Acc_Y [m/s^2],Acc_Z [m/s^2],Gyr_X [deg/s],Gyr_Y [deg/s],Gyr_Z [deg/s]",
            delim: ',',
            fs_hz: 100.0,
            time: |i, fs| format!("{}", i as f64 / fs),
            acc_k: G,
            gyro_k: 1.0,
            sign: [1.0; 3],
            pad: [0, 0, 0, 0],
            format: "generic",
            notes: &["units read from the names"],
        },
    ]
}

/// The file of `rec` as vendor `v` writes it.
fn vendor_file(dir: &Path, v: &Vendor, rec: &Recording) -> std::path::PathBuf {
    let mut s = format!("{}\n", v.head);
    let zeros = |n: usize| vec!["0".to_string(); n];
    for i in 0..rec.len() {
        let mut row = zeros(v.pad[0]);
        row.push((v.time)(i, v.fs_hz));
        row.extend(zeros(v.pad[1]));
        row.extend((0..3).map(|a| format!("{}", v.sign[a] * rec.acc_g[a][i] * v.acc_k)));
        row.extend(zeros(v.pad[2]));
        row.extend((0..3).map(|a| format!("{}", v.sign[a] * rec.gyro_dps[a][i] * v.gyro_k)));
        row.extend(zeros(v.pad[3]));
        s.push_str(&row.join(&v.delim.to_string()));
        s.push('\n');
    }
    let p = dir.join(format!("{}.csv", v.format));
    std::fs::write(&p, s).unwrap();
    p
}

#[test]
fn vendor_exports_read_without_a_map_into_the_walk() {
    let t = tempfile::tempdir().unwrap();
    let params = ReadParams::default().check().unwrap();
    let vendors = vendors();
    assert!(vendors.len() >= 8);
    for v in &vendors {
        let rec = walking(v.fs_hz);
        let p = vendor_file(t.path(), v, &rec);
        let (r, rep) = read_recording(&p, None, &params)
            .unwrap_or_else(|e| panic!("{}: not read without a map: {e}", v.name));
        assert_eq!(rep.format, v.format, "{}: {:?}", v.name, rep.notes);
        assert!(
            (r.fs_hz - v.fs_hz).abs() < 1e-3,
            "{}: {} Hz; {:?}",
            v.name,
            r.fs_hz,
            rep.notes
        );
        assert_eq!(r.len(), rec.len(), "{}", v.name);
        let notes = rep.notes.join(" | ");
        for w in v.notes {
            assert!(notes.contains(w), "{}: '{w}' not in {notes}", v.name);
        }
        let mut d = (0.0f64, 0.0f64);
        for k in 0..3 {
            for i in 0..r.len() {
                d.0 = d.0.max((r.acc_g[k][i] - rec.acc_g[k][i]).abs());
                d.1 = d.1.max((r.gyro_dps[k][i] - rec.gyro_dps[k][i]).abs());
            }
        }
        assert!(d.0 < 1e-9 && d.1 < 1e-7, "{}: {d:?}", v.name);
    }
}

/// Units inferred are named as such per column (`ldh inspect`), and a header with no channel
/// names ldh knows is refused naming the closest format, what differs and the command that
/// writes an editable map.
#[test]
fn assumptions_are_shown_and_a_failed_detection_says_how_to_write_a_map() {
    let t = tempfile::tempdir().unwrap();
    let params = ReadParams::default().check().unwrap();
    let generic = vendors()
        .into_iter()
        .find(|v| v.format == "generic")
        .unwrap();
    let rec = walking(100.0);
    let p = vendor_file(t.path(), &generic, &rec);
    let (_, rep) = read_recording(&p, None, &params).unwrap();
    assert!(rep.columns[0]
        .unit_from
        .contains("assumed from the time steps"));
    assert!(rep.columns[1]
        .unit_from
        .starts_with("assumed from the signal: median |acc|"));
    assert!(rep.columns[4]
        .unit_from
        .starts_with("assumed from the signal: 99th"));

    // A Movella DOT export with the built-in Xsens map (tab): the delimiter is named.
    let dot = &vendors()[0];
    let rec60 = walking(60.0);
    let p = vendor_file(t.path(), dot, &rec60);
    let xsens = ldh_core::io::FormatSpec::builtin("xsens-mtmanager").unwrap();
    let e = read_recording(&p, Some(&xsens), &params).unwrap_err();
    assert!(matches!(e, LdhError::DelimiterMismatch { .. }), "{e}");
    let m = e.to_string();
    assert!(
        m.contains("splits rows at tab") && m.contains("comma"),
        "{m}"
    );
    assert!(m.contains("ldh formats xsens-mtmanager > my.toml"), "{m}");

    // Accelerometer only: no format fits; the message names the closest format, what the
    // names read as and the command.
    let text = "time,AccX,AccY,AccZ,Pressure\n0,1,0,0,1000\n0.01,1,0,0,1000\n";
    let p = t.path().join("acc_only.csv");
    std::fs::write(&p, text).unwrap();
    let m = read_recording(&p, None, &params).unwrap_err().to_string();
    assert!(m.contains("no header row"), "{m}");
    assert!(m.contains("closest of"), "{m}");
    assert!(m.contains("no angular rate"), "{m}");
    assert!(m.contains("ldh formats ldh > my.toml"), "{m}");
    assert!(m.contains("--input-format my.toml"), "{m}");
}
