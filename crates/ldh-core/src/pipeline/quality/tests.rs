//! The quality layer on real recordings (HuGaDB, when present) and on the simulator.

use super::*;
use crate::pipeline::{analyze_pair, memory_report, AnalysisParams, LoadedLeg, SubjectInput};
use crate::recording::Side;
use std::path::{Path, PathBuf};

/// `LDH_REALDATA/hugadb`, or `../shared/realdata/hugadb` / `../../shared/realdata/hugadb` from
/// the workspace root (a worktree sits one level deeper than the main checkout).
pub(crate) fn hugadb_dir() -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut c: Vec<PathBuf> = Vec::new();
    if let Ok(d) = std::env::var("LDH_REALDATA") {
        c.push(Path::new(&d).join("hugadb"));
        c.push(PathBuf::from(d));
    }
    c.push(root.join("../shared/realdata/hugadb"));
    c.push(root.join("../../shared/realdata/hugadb"));
    c.into_iter().find(|d| {
        d.join("PROVENANCE.md").is_file() || d.join("HuGaDB_v1_walking_01_00.txt").is_file()
    })
}

/// The HuGaDB files whose two shank gyroscopes are clean (PROVENANCE.md).
pub(crate) const HUGADB_CLEAN: [&str; 5] =
    ["01_00", "06_00", "08_02-Test", "10_00-Test", "11_03-Test"];

/// One clean HuGaDB file's shank (`side`: "left" or "right") through the built-in format map
/// (the CLI's path: axis map, declared ranges, clipped samples flagged per sensor).
pub(crate) fn read_hugadb_map(dir: &Path, file: &str, side: &str) -> crate::recording::Recording {
    use crate::io::{read_recording, FormatSpec, ReadParams};
    let path = dir.join(format!("HuGaDB_v1_walking_{file}.txt"));
    let spec = FormatSpec::builtin(&format!("hugadb-{side}-shank")).unwrap();
    let rp = ReadParams::default().check().unwrap();
    read_recording(&path, Some(&spec), &rp).unwrap().0
}

/// HuGaDB's shank columns (0-based): right shin 6-11, left shin 24-29 (acc x,y,z, gyro x,y,z).
const FS_HUGADB: f64 = 58.8;

/// One HuGaDB file's two shanks as recordings: acc counts / 16384 g, gyro counts / 16.4 deg/s.
pub(crate) fn read_hugadb(
    path: &Path,
) -> (crate::recording::Recording, crate::recording::Recording) {
    let mut r = csv::ReaderBuilder::new()
        .delimiter(b'\t')
        .comment(Some(b'#'))
        .has_headers(true)
        .flexible(true)
        .from_path(path)
        .unwrap();
    let mut ch: [Vec<f64>; 12] = Default::default();
    for rec in r.records() {
        let rec = rec.unwrap();
        for (k, col) in (6..12).chain(24..30).enumerate() {
            let v: f64 = rec[col].trim().parse().unwrap();
            let unit = if k % 6 < 3 { 16384.0 } else { 16.4 };
            ch[k].push(v / unit);
        }
    }
    let make = |o: usize| {
        let mut rec = crate::recording::Recording::new(
            FS_HUGADB,
            [ch[o].clone(), ch[o + 1].clone(), ch[o + 2].clone()],
            [ch[o + 3].clone(), ch[o + 4].clone(), ch[o + 5].clone()],
            vec![],
        )
        .unwrap();
        rec.source = Some(path.to_path_buf());
        rec
    };
    (make(0), make(6))
}

/// Files whose shank gyroscopes HuGaDB's README lists as corrupted (PROVENANCE.md): (file
/// fragment, right corrupted, left corrupted).
const HUGADB: [(&str, bool, bool); 18] = [
    ("01_00", false, false),
    ("03_00", true, false),
    ("03_01", true, false),
    ("04_00", true, true),
    ("05_00", true, false),
    ("06_00", false, false),
    ("07_03", true, false),
    ("08_02", false, false),
    ("10_00", false, false),
    ("11_03", false, false),
    ("12_02", true, true),
    ("13_03", true, true),
    ("14_00", true, true),
    ("15_00", true, true),
    ("16_00", true, true),
    ("17_00", true, true),
    ("17_02", true, true),
    ("18_03", true, true),
];

fn no_false_alarm(w: &[Warning]) -> Result<(), String> {
    for x in w {
        if [codes::POSSIBLE_SWAP, codes::RUNNING, codes::UPSIDE_DOWN].contains(&x.code.as_str())
            && x.severity > Severity::Note
        {
            return Err(format!("false {}: {}", x.code, x.message));
        }
    }
    Ok(())
}

#[test]
fn hugadb_faulty_gyroscopes_are_flagged_and_clean_legs_analysed() {
    let Some(dir) = hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "txt"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 18);
    let mut failures = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        let &(_, r_bad, l_bad) = HUGADB.iter().find(|(k, _, _)| name.contains(k)).unwrap();
        let (right, left) = read_hugadb(f);
        let leg = |rec: crate::recording::Recording, s: &str| -> LoadedLeg {
            let rep = memory_report(&rec);
            Ok((rec, rep, format!("{name}/{s}")))
        };
        let input = SubjectInput {
            subject_id: name.clone(),
            ..SubjectInput::default()
        };
        let res = analyze_pair(&input, leg(left, "left"), leg(right, "right"), &params);
        let mut line = format!("{name}:");
        for (side, bad) in [(Side::Left, l_bad), (Side::Right, r_bad)] {
            let l = match if side == Side::Left {
                &res.left
            } else {
                &res.right
            } {
                Ok(l) => l,
                Err(e) => {
                    failures.push(format!("{name} {side}: failed: {e}"));
                    continue;
                }
            };
            let p = &l.parameters;
            let codes_: Vec<String> = l
                .warnings
                .iter()
                .map(|w| format!("{}[{}]", w.code, w.severity.as_str()))
                .collect();
            line.push_str(&format!(
                " {side}: valid {}/{} ST {:.3} SL {:.3} WQK {:.1} withheld {} {:?};",
                p.strides_valid,
                p.strides_total,
                p.stride_time_s,
                p.stride_length_m,
                p.wqk_deg,
                p.withheld.len(),
                codes_
            ));
            let fault = l
                .warnings
                .iter()
                .any(|w| w.code == codes::GYRO_SCALE_FAULT && w.severity == Severity::Fault);
            let values = [
                p.stride_time_s,
                p.step_time_s,
                p.step_frequency_hz,
                p.stance_ratio,
                p.swing_ratio,
                p.stride_length_m,
                p.speed_mps,
                p.stride_length_cv,
                p.stride_time_cv,
                p.sta_per_s,
                p.sta_per_stride,
                p.wqk_deg,
                p.pbi_deg,
                p.bdk_deg,
            ];
            if bad {
                if !fault {
                    failures.push(format!("{name} {side}: corrupted gyroscope not flagged"));
                }
                if values.iter().any(|v| v.is_finite()) || p.withheld.len() != params::ALL.len() {
                    failures.push(format!(
                        "{name} {side}: a parameter of a faulty leg is a number: {p:?}"
                    ));
                }
            } else {
                if fault {
                    failures.push(format!("{name} {side}: clean gyroscope flagged"));
                }
                if !p.stride_time_s.is_finite() || p.strides_valid < 3 {
                    failures.push(format!("{name} {side}: clean leg not analysed: {p:?}"));
                }
                if let Err(e) = no_false_alarm(&l.warnings) {
                    failures.push(format!("{name} {side}: {e}"));
                }
            }
        }
        if let Err(e) = no_false_alarm(&res.warnings) {
            failures.push(format!("{name} pair: {e}"));
        }
        let pc: Vec<&str> = res.warnings.iter().map(|w| w.code.as_str()).collect();
        println!("{line} pair {pc:?}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Both devices turned by `deg` about the shank axis (the device x axis): the mounting of real
/// sensors strapped on at any angle (stroke trials: 50-70°).
fn rotated_about_shank(rec: &crate::recording::Recording, deg: f64) -> crate::recording::Recording {
    let (s, c) = deg.to_radians().sin_cos();
    let rot = |v: &[Vec<f64>; 3]| -> [Vec<f64>; 3] {
        let y = v[1].iter().zip(&v[2]).map(|(y, z)| c * y - s * z).collect();
        let z = v[1].iter().zip(&v[2]).map(|(y, z)| s * y + c * z).collect();
        [v[0].clone(), y, z]
    };
    let mut out = rec.clone();
    out.acc_g = rot(&rec.acc_g);
    out.gyro_dps = rot(&rec.gyro_dps);
    out
}

#[test]
fn sensors_rotated_about_the_shank_never_look_swapped() {
    let c = crate::simulate::CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 25.0,
        seed: 11,
        ..crate::simulate::CohortParams::default()
    };
    let mut sub = c.simulate(0).unwrap();
    let (l0, r0) = (sub.left.recording.clone(), sub.right.recording.clone());
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let mut failures = Vec::new();
    for k in 0..12 {
        let deg = 30.0 * k as f64;
        sub.left.recording = rotated_about_shank(&l0, deg);
        sub.right.recording = rotated_about_shank(&r0, deg);
        let res = crate::pipeline::analyze_simulated(&sub, &params);
        let mut all: Vec<Warning> = res.warnings.clone();
        for (side, leg) in res.legs() {
            let Ok(leg) = leg else {
                failures.push(format!("{deg} deg {side}: failed"));
                continue;
            };
            if leg.parameters.strides_valid < 5 || !leg.parameters.wqk_deg.is_finite() {
                failures.push(format!(
                    "{deg} deg {side}: not analysed: {:?}",
                    leg.warnings
                ));
            }
            all.extend(leg.warnings.iter().cloned());
        }
        for w in &all {
            // A turn of 180° makes identical lateral devices look exchanged: only then may the
            // mounting note appear, and nothing is ever more than a note.
            let near_180 = (deg - 180.0).abs() <= CANONICAL_MOUNT_DEG + 15.0;
            let swap_ok =
                w.code == codes::POSSIBLE_SWAP && near_180 && w.severity == Severity::Note;
            if [codes::POSSIBLE_SWAP, codes::RUNNING, codes::UPSIDE_DOWN].contains(&w.code.as_str())
                && !swap_ok
            {
                failures.push(format!("{deg} deg: false {}: {}", w.code, w.message));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn stride(i: usize, t: f64, stance: f64) -> crate::gait::Stride {
    crate::gait::Stride {
        stride_index: i,
        hs_time_s: i as f64 * t,
        to_time_s: i as f64 * t + stance * t,
        next_hs_time_s: (i + 1) as f64 * t,
        stride_time_s: t,
        stance_ratio: stance,
        stride_length_m: 1.4,
        speed_mps: 1.4 / t,
        wqk_deg: 40.0,
        pbi_deg: 20.0,
        bdk_deg: 8.0,
        heading_change_deg: 0.0,
        bout: 0,
        valid: true,
        reason: String::new(),
    }
}

fn codes_of(t: f64, stance: f64) -> Vec<String> {
    let st: Vec<crate::gait::Stride> = (0..20).map(|i| stride(i, t, stance)).collect();
    let p = crate::gait::side_parameters(&st, None);
    let al = crate::align::Alignment {
        shank_axis_tilt_deg: 3.0,
        sagittal_variance_share: 0.9,
        ..crate::align::Alignment::identity()
    };
    leg_warnings(&al, &st, &p, 100.0)
        .into_iter()
        .map(|w| w.code)
        .collect()
}

#[test]
fn running_needs_a_flight_phase_and_brisk_walking_is_walking() {
    // Brisk walking: 0.79-0.8 s strides (150 steps/min), 60 % stance.
    assert!(codes_of(0.8, 0.60).is_empty(), "{:?}", codes_of(0.8, 0.60));
    assert!(codes_of(0.79, 0.60).is_empty());
    assert!(codes_of(0.72, 0.58).is_empty());
    // Running: a flight phase (35 % stance), at any cadence.
    assert_eq!(codes_of(0.7, 0.35), vec![codes::RUNNING]);
    assert_eq!(codes_of(0.9, 0.40), vec![codes::RUNNING]);
    // 0.6 s strides with 60 % stance: no gait; the time base is wrong.
    assert_eq!(
        codes_of(0.6, 0.60),
        vec![codes::IMPLAUSIBLE_CADENCE_FOR_RATE]
    );
}

/// A leg-level finding that withholds the angles and stride length blanks them per stride and
/// says why in the stride's reason; one that withholds everything invalidates the stride.
#[test]
fn blanked_stride_cells_carry_the_findings_reason() {
    let mut st: Vec<crate::gait::Stride> = (0..3).map(|i| stride(i, 1.0, 0.6)).collect();
    st[1].stride_length_m = f64::NAN;
    st[1].reason = "stride length withheld: velocity drift 1.00 m/s over the stride".into();
    let w = Warning::new(
        codes::ATTITUDE_DIVERGENCE,
        Severity::Warning,
        "the shank attitude drifts",
    )
    .withholding(&[
        "wqk_deg",
        "pbi_deg",
        "bdk_deg",
        "stride_length_m",
        "speed_mps",
    ]);
    apply_to_strides(&mut st, std::slice::from_ref(&w));
    assert!(st.iter().all(|s| s.valid && s.wqk_deg.is_nan()));
    assert!(st.iter().all(|s| s.stride_length_m.is_nan()));
    assert_eq!(
        st[0].reason,
        "angles and stride length withheld: attitude divergence"
    );
    assert_eq!(
        st[1].reason,
        "stride length withheld: velocity drift 1.00 m/s over the stride; angles withheld: attitude divergence"
    );
    // applied twice (leg, then pair): one reason
    apply_to_strides(&mut st, &[w]);
    assert_eq!(
        st[0].reason,
        "angles and stride length withheld: attitude divergence"
    );
    let all = Warning::new(
        codes::GYRO_SCALE_FAULT,
        Severity::Fault,
        "gyroscope scale fault",
    )
    .withholding(&params::ALL);
    apply_to_strides(&mut st, &[all]);
    assert!(st
        .iter()
        .all(|s| !s.valid && s.reason == "gyro scale fault"));
}

/// Pitch at mid-stance (middle fifth of HS–TO, as the attitude health check) of the valid
/// strides, with their HS times.
fn mid_stance_pitch(l: &crate::pipeline::LegResult) -> Vec<(f64, f64)> {
    let att = l.attitude.as_ref().expect("attitude kept");
    let n = att.pitch_deg.len();
    let idx = |t: f64| ((t * att.fs_hz).round().max(0.0) as usize).min(n - 1);
    l.strides
        .iter()
        .filter(|s| s.valid && s.to_time_s.is_finite() && s.to_time_s > s.hs_time_s)
        .map(|s| {
            let d = s.to_time_s - s.hs_time_s;
            let (a, b) = (idx(s.hs_time_s + 0.4 * d), idx(s.hs_time_s + 0.6 * d));
            let w = &att.pitch_deg[a..=b.max(a)];
            (s.hs_time_s, w.iter().sum::<f64>() / w.len() as f64)
        })
        .collect()
}

/// 10th-to-90th percentile spread.
fn spread(v: &[f64]) -> f64 {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    s.sort_by(|a, b| a.total_cmp(b));
    if s.is_empty() {
        return f64::NAN;
    }
    let q = |p: f64| s[((s.len() - 1) as f64 * p).round() as usize];
    q(0.9) - q(0.1)
}

/// The same HuGaDB file read through the built-in format maps (the CLI's path: axis map,
/// declared ranges, clipped samples flagged per sensor) and through the raw reader above (no
/// map, nothing flagged) gives the same attitude outcome on the five files with clean shank
/// gyroscopes. The accelerometers clip at ±2 g at heel strike in 3-21 % of the samples; the
/// accelerometer's own tilt at mid-stance spreads over only 2-6° per leg, so the shank really
/// is steady there, and the fused attitude must be too. (When clipped accelerometer samples
/// also replaced the gyroscope, the CLI path's mid-stance pitch spread over 23-27° on 01_00
/// and 08_02 and their angles were withheld as a divergence, while the raw path kept them.)
#[test]
fn hugadb_format_maps_and_raw_reading_agree_on_the_attitude() {
    use crate::attitude::AttitudeModel;
    let Some(dir) = hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let mut failures = Vec::new();
    for f in HUGADB_CLEAN {
        let path = dir.join(format!("HuGaDB_v1_walking_{f}.txt"));
        let (raw_r, raw_l) = read_hugadb(&path);
        let (map_l, map_r) = (
            read_hugadb_map(&dir, f, "left"),
            read_hugadb_map(&dir, f, "right"),
        );
        assert!(map_l.saturated_count() > 0 && map_l.gyro_saturated.iter().all(|g| !g));
        let run =
            |l: &crate::recording::Recording, r: &crate::recording::Recording, m: AttitudeModel| {
                let leg = |rec: crate::recording::Recording, s: &str| -> LoadedLeg {
                    let rep = memory_report(&rec);
                    Ok((rec, rep, format!("{f}/{s}")))
                };
                let input = SubjectInput {
                    subject_id: f.into(),
                    ..SubjectInput::default()
                };
                let p = params.clone().model(m);
                analyze_pair(&input, leg(l.clone(), "left"), leg(r.clone(), "right"), &p)
            };
        let raw = run(&raw_l, &raw_r, AttitudeModel::Fusion);
        let map = run(&map_l, &map_r, AttitudeModel::Fusion);
        let acc = run(&map_l, &map_r, AttitudeModel::Acc);
        for (((side, a), (_, b)), (_, c)) in raw.legs().into_iter().zip(map.legs()).zip(acc.legs())
        {
            let (a, b, c) = (
                a.as_ref().unwrap(),
                b.as_ref().unwrap(),
                c.as_ref().unwrap(),
            );
            let codes_of = |l: &crate::pipeline::LegResult| -> Vec<String> {
                l.warnings
                    .iter()
                    .filter(|w| w.severity > Severity::Note)
                    .map(|w| w.code.clone())
                    .collect()
            };
            let pitch = |l| -> Vec<f64> { mid_stance_pitch(l).iter().map(|x| x.1).collect() };
            let (pa, pb, pc) = (a.parameters.clone(), &b.parameters, &c.parameters);
            println!(
                "{f} {side}: raw WQK {:.1} PBI {:.1} mid-stance spread {:.1} {:?} | format map WQK {:.1} PBI {:.1} spread {:.1} {:?} ({} acc samples replaced) | acc tilt spread {:.1}",
                pa.wqk_deg,
                pa.pbi_deg,
                spread(&pitch(a)),
                codes_of(a),
                pb.wqk_deg,
                pb.pbi_deg,
                spread(&pitch(b)),
                codes_of(b),
                b.outliers_replaced,
                spread(&pitch(c)),
            );
            if codes_of(a) != codes_of(b) || !codes_of(b).is_empty() {
                failures.push(format!(
                    "{f} {side}: warnings {:?} vs {:?}",
                    codes_of(a),
                    codes_of(b)
                ));
            }
            for (name, x, y) in [
                ("WQK", pa.wqk_deg, pb.wqk_deg),
                ("PBI", pa.pbi_deg, pb.pbi_deg),
            ] {
                // the paths differ only in the interpolated clipped accelerations
                if !((x - y).abs() <= 4.0) {
                    failures.push(format!("{f} {side}: {name} {x:.1} raw vs {y:.1} mapped"));
                }
            }
            let s = spread(&pitch(b));
            if !(s <= 12.0) || pc.wqk_deg.is_nan() {
                failures.push(format!("{f} {side}: mid-stance pitch spread {s:.1} deg"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
