//! Manifests (csv crate, columns, refusals), subject ids of files given directly, and trials
//! averaged per person before the statistics and the classifiers.

use super::super::*;
use crate::domain::Parameter;
use crate::output::RecordingRow;
use crate::recording::{Setting, Side};

fn manifest(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let d = tempfile::tempdir().unwrap();
    let m = d.path().join("manifest.csv");
    std::fs::write(&m, text).unwrap();
    (d, m)
}

fn err(text: &str) -> String {
    let (_d, m) = manifest(text);
    read_manifest(&m).unwrap_err().to_string()
}

#[test]
fn manifest_columns_quoting_formats_settings_and_groups() {
    let (d, m) = manifest(
        "# a comment line\n\
         Subject_ID,group,affected_side,left,right,setting,left_format,right_format,format\n\
         S1,ldh,right,\"a, b/l.csv\",a/r.csv,treadmill,hugadb-left-shank,hugadb-right-shank,\n\
         S2,healthy,,b/l.csv,b/r.csv,,,,raw-counts\n\
         S3,stroke,,c/l.csv,c/r.csv,overground,,,\n\
         S4,stroke,none,d/l.csv,,,,,\n",
    );
    std::fs::write(d.path().join("my.toml"), "x").unwrap();
    let v = read_manifest(&m).unwrap();
    assert_eq!(v.len(), 4);
    assert_eq!(v[0].left, Some(Source::Path(d.path().join("a, b/l.csv"))));
    assert_eq!(v[0].setting, Some(Setting::Treadmill));
    assert_eq!(v[0].left_format.as_ref().unwrap().name, "hugadb-left-shank");
    assert_eq!(
        v[0].right_format.as_ref().unwrap().name,
        "hugadb-right-shank"
    );
    assert_eq!(v[0].group, Some(Group::Ldh));
    assert_eq!(v[1].group, Some(Group::Healthy));
    assert!(!v[1].affected_side_unknown, "healthy: empty side is none");
    assert_eq!(v[1].left_format.as_ref().unwrap().name, "raw-counts");
    assert_eq!(v[1].right_format.as_ref().unwrap().name, "raw-counts");
    assert_eq!(v[1].setting, None);
    assert_eq!(v[2].group, Some(Group::Other("stroke".into())));
    assert!(v[2].affected_side_unknown);
    assert!(!v[3].affected_side_unknown);
    assert_eq!(v[3].right, None);
    assert!(is_manifest(&m));
    // The results carry the label, the unknown side (said), and the setting.
    let r = Analysis::new(AnalysisParams::default().check().unwrap()).subject(&v[2]);
    let rows = crate::output::recording_rows(&[r]);
    assert_eq!(rows[0].group, Some(Group::Other("stroke".into())));
    assert_eq!(rows[0].affected_side, None);
    assert_eq!(rows[0].side_role, None);
    assert_eq!(rows[0].setting, Some(Setting::Overground.into()));
    let opts = InputOptions {
        setting: Some(Setting::Treadmill),
        ..InputOptions::default()
    };
    let v = discover_with(std::slice::from_ref(&m), &opts).unwrap();
    assert_eq!(v[0].setting, Some(Setting::Treadmill));
    assert_eq!(v[2].setting, Some(Setting::Overground), "the row wins");
    assert_eq!(v[1].setting, Some(Setting::Treadmill));
}

#[test]
fn manifest_mistakes_are_refused_naming_the_column() {
    let e = err("subject_id,group,left,right,notes\nS1,ldh,a,b,x\n");
    assert!(
        e.contains("manifest.csv:1:5: unknown column 'notes'") && e.contains("affected_side"),
        "{e}"
    );
    let e = err("subject_id,left,right,Left\nS1,a,b,c\n");
    assert!(
        e.contains("'left' occurs 2 times") && e.contains("[2, 4]"),
        "{e}"
    );
    let e = err("subject_id,group,affected_side\nS1,ldh,left\n");
    assert!(e.contains("[\"left\", \"right\"]"), "{e}");
    let e = err("subject_id,left,right\nS1,a,b\nS1,c,d\n");
    assert!(
        e.contains("manifest.csv:3:1") && e.contains("trial_id"),
        "{e}"
    );
    let e = err("subject_id,trial_id,left,right\nS1,1,a,b\nS1,1,c,d\n");
    assert!(
        e.contains("manifest.csv:3:1") && e.contains("line 2"),
        "{e}"
    );
    let e = err("subject_id,trial_id,trial,left,right\nS1,1,1,a,b\n");
    assert!(e.contains("one trial column"), "{e}");
    let e = err("subject_id,trial,group,left,right\nS1,1,ldh,a,b\nS1,2,healthy,c,d\n");
    assert!(
        e.contains("manifest.csv:3:3") && e.contains("earlier trials"),
        "{e}"
    );
    let e = err("subject_id,affected_side,left,right\nS1,both,a,b\n");
    assert!(
        e.contains("manifest.csv:2:2") && e.contains("'both'"),
        "{e}"
    );
    let e = err("subject_id,setting,left,right\nS1,stairs,a,b\n");
    assert!(
        e.contains("manifest.csv:2:2") && e.contains("treadmill"),
        "{e}"
    );
    let e = err("subject_id,format,left,right\nS1,nosuch,a,b\n");
    assert!(
        e.contains("manifest.csv:2:2") && e.contains("no such built-in format"),
        "{e}"
    );
    let e = err("subject_id,left_format,left,right\nS1,maps/none.toml,a,b\n");
    assert!(
        e.contains("manifest.csv:2:2") && e.contains("none.toml"),
        "{e}"
    );
    let e = err("subject_id,left,right\nS1,a,b,c\n");
    assert!(
        e.contains("manifest.csv:2") && e.contains("double quotes"),
        "{e}"
    );
    let e = err("subject_id,sensor_height_m,left,right\nS1,-1,a,b\n");
    assert!(e.contains("manifest.csv:2:2"), "{e}");
    let e = err("subject_id,left,right\n,a,b\n");
    assert!(e.contains("non-empty subject id"), "{e}");
    // Not a manifest: a recording, or a CSV without subject_id.
    let (d, m) = manifest("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n0,1,0,0,0,0,0\n");
    assert!(!is_manifest(&m));
    std::fs::write(
        d.path().join("m2.csv"),
        "\"subject_id\" , \"right\"\nS1,x\n",
    )
    .unwrap();
    assert!(is_manifest(&d.path().join("m2.csv")));
}

/// Rows of a cohort: `n` persons per group, `trials` trials each; every parameter of trial t
/// is `base + t`, so a person's mean is `base + (trials − 1) / 2`.
fn cohort_rows(n: usize, trials: usize) -> Vec<RecordingRow> {
    let mut out = Vec::new();
    for (g, group) in ["healthy", "ldh"].iter().enumerate() {
        for i in 0..n {
            for t in 0..trials {
                for side in ["left", "right"] {
                    let base = 1.0
                        + g as f64 * 0.5
                        + i as f64 * 0.05
                        + (side == "right") as u8 as f64 * 0.1;
                    let v = base + t as f64;
                    let mut r: RecordingRow = serde_json::from_value(serde_json::json!({
                        "subject_id": format!("{group}{i}"), "side": side, "model": "fusion",
                        "group": group, "affected_side": if g == 1 { "right" } else { "none" },
                        "side_role": "", "source": "", "status": "ok", "error": "",
                        "fs_hz": 100.0, "duration_s": 60.0, "strides_total": 40,
                        "strides_valid": 40, "stride_time_s": null, "step_time_s": null,
                        "step_frequency_steps_per_s": null, "stance_ratio": null,
                        "swing_ratio": null, "stride_length_m": null, "speed_mps": null,
                        "stride_length_cv": null, "stride_time_cv": null, "sta_per_s": null,
                        "sta_per_stride": null, "sta_status": "", "wqk_deg": null,
                        "pbi_deg": null, "bdk_deg": null, "mirrored": false,
                        "axial_rotation_deg": 0.0, "outliers_replaced": 0,
                        "clipped_samples": 0, "trial_id": format!("t{t}")
                    }))
                    .unwrap();
                    for (k, p) in crate::cohort::PARAMETERS.into_iter().enumerate() {
                        let x = v * (1.0 + k as f64 * 0.1) + ((i * 7 + k) % 5) as f64 * 0.01;
                        r.set_value(p, Some(x));
                    }
                    out.push(r);
                }
            }
        }
    }
    out
}

#[test]
fn statistics_and_cv_count_each_person_once_whatever_the_trials() {
    use crate::cohort::{table3, Cohort, Parameter};
    use crate::ml::{cross_validate, Classifier, CvParams, Dataset, Task};
    let one = cohort_rows(6, 1);
    let two = cohort_rows(6, 2);
    assert_eq!(two.len(), 2 * one.len());
    let (c1, c2) = (
        Cohort::from_rows(&one).unwrap(),
        Cohort::from_rows(&two).unwrap(),
    );
    assert_eq!((c2.healthy.len(), c2.ldh.len()), (6, 6));
    assert!(c2.excluded.is_empty(), "{:?}", c2.excluded);
    // The person's value is the mean of the two trials.
    for (a, b) in c1.healthy.iter().zip(&c2.healthy) {
        let (x1, x2) = (
            a.a.value(Parameter::StrideTime).unwrap(),
            b.a.value(Parameter::StrideTime).unwrap(),
        );
        let step = 1.0 + 4.0 * 0.1; // stride_time_s is the 5th parameter: trial t adds t × 1.4
        assert!((x2 - (x1 + 0.5 * step)).abs() < 1e-9, "{x1} {x2}");
        let mean = b.a.trial_mean.as_ref().expect("a mean of trials");
        assert_eq!(mean.trial_ids.len(), 2);
        assert_eq!(b.a.trial_id, mean.to_string());
    }
    for p in table3(&c2) {
        assert_eq!((p.h.n, p.ldhh.n, p.ldhe.n), (6, 6, 6), "{}", p.code);
    }
    for task in [Task::Binary, Task::ThreeClass] {
        let ds =
            Dataset::from_recordings(&two, task, &crate::ml::dataset::default_features()).unwrap();
        let per_person = if task == Task::Binary { 12 } else { 18 };
        assert_eq!(ds.len(), per_person);
        let mut g = ds.groups.clone();
        g.sort();
        g.dedup();
        assert_eq!(g.len(), 12, "one subject per person");
        let p = CvParams {
            k: 3,
            repeats: 1,
            permutation_importance: false,
            ..CvParams::default()
        };
        let rep = cross_validate(&ds, &Classifier::from_name("svm", 1).unwrap(), &p).unwrap();
        let n: usize = rep.confusion.iter().flatten().sum();
        assert_eq!(n, per_person, "each person's row predicted once");
    }
}

/// A person with two trials whose first trial's SV is withheld and whose second's is measured
/// has the second's SV and nothing withheld for it; a parameter neither trial measured keeps
/// both trials' reasons.
#[test]
fn a_persons_withheld_values_are_those_no_trial_measured() {
    let rows = cohort_rows(1, 2);
    let mut legs: Vec<RecordingRow> = rows
        .into_iter()
        .filter(|r| r.subject_id == "healthy0" && r.side == crate::Side::Left)
        .collect();
    assert_eq!(legs.len(), 2);
    let sv2 = legs[1].parameters[Parameter::StrideLengthCv].unwrap();
    legs[0].parameters[Parameter::StrideLengthCv] = None;
    legs[0].withheld.0.insert(
        crate::domain::Parameter::StrideLengthCv,
        crate::domain::Reason::read("sv unchecked (short)"),
    );
    for (t, leg) in legs.iter_mut().enumerate() {
        leg.parameters[Parameter::Sta] = None;
        leg.withheld.0.insert(
            crate::domain::Parameter::Sta,
            crate::domain::Reason::read(format!("sta not computed {t}")),
        );
    }
    let refs: Vec<&RecordingRow> = legs.iter().collect();
    let p = crate::cohort::person_row(&refs, crate::Side::Left).unwrap();
    assert_eq!(p.parameters[Parameter::StrideLengthCv], Some(sv2));
    assert!(
        p.withheld
            .reason(crate::domain::Parameter::StrideLengthCv)
            .is_none(),
        "{}",
        p.withheld
    );
    assert_eq!(
        p.withheld.reason(crate::domain::Parameter::Sta).unwrap(),
        "t0: sta not computed 0; t1: sta not computed 1"
    );
    // The SV "mean" is trial t1's alone, and the mean says so; a parameter both trials (or
    // neither) measured is no partial one.
    let mean = p.trial_mean.as_ref().unwrap();
    assert_eq!(
        mean.only_from(Parameter::StrideLengthCv),
        Some(&[legs[1].trial_id.clone()][..])
    );
    assert_eq!(mean.only_from(Parameter::StrideTime), None);
    assert_eq!(mean.only_from(Parameter::Sta), None);
}

/// Table 3 gives a cell's own n when some subjects of its group have the value withheld, and
/// says why under the table; with every value present it is as before.
#[test]
fn table3_says_when_a_cell_has_fewer_subjects_than_its_group() {
    use crate::cohort::{table3, table3_markdown, Cohort};
    let mut rows = cohort_rows(6, 1);
    let full = Cohort::from_rows(&rows).unwrap();
    let md = table3_markdown(&table3(&full), &full);
    assert!(!md.contains("(n = ") && !md.contains("withheld"), "{md}");
    for r in rows
        .iter_mut()
        .filter(|r| r.subject_id == "ldh0" || r.subject_id == "ldh1")
    {
        r.parameters[Parameter::StrideLengthCv] = None;
    }
    let c = Cohort::from_rows(&rows).unwrap();
    let md = table3_markdown(&table3(&c), &c);
    let line = md.lines().find(|l| l.starts_with("| SV ")).unwrap();
    assert_eq!(line.matches("(n = 4)").count(), 2, "{line}");
    assert!(md.contains("the others' values were not measured"), "{md}");
}

#[test]
fn a_manifest_line_longer_than_the_line_bound_is_refused_with_its_line() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("manifest.csv");
    let label = "x".repeat(crate::io::MAX_LINE_BYTES);
    let text = format!("subject_id,group,left,right\nA,{label},a.csv,b.csv\n");
    std::fs::write(&p, text).unwrap();
    let e = read_manifest(&p).unwrap_err().to_string();
    assert!(
        e.contains("manifest.csv:2: the line is longer than 65536 bytes"),
        "{e}"
    );
    assert!(e.len() < 400, "{e}");
}

#[test]
fn per_side_sensor_heights_are_read_filled_and_checked() {
    let (d, m) = manifest(
        "subject_id,left,right,sensor_height_m,left_sensor_height_m,Right_Sensor_Height_m\n\
         S1,a/l.csv,a/r.csv,,0.08,0.14\n\
         S2,b/l.csv,b/r.csv,0.1,,\n\
         S3,c/l.csv,c/r.csv,0.1,0.1,\n\
         S4,d/l.csv,d/r.csv,,0.09,\n",
    );
    let v = read_manifest(&m).unwrap();
    let of = |s: &SubjectInput| {
        (
            s.sensor_height_m_of(Side::Left),
            s.sensor_height_m_of(Side::Right),
        )
    };
    assert_eq!(of(&v[0]), (Some(0.08), Some(0.14)));
    assert_eq!(
        of(&v[1]),
        (Some(0.1), Some(0.1)),
        "one height for both legs"
    );
    assert_eq!(
        of(&v[2]),
        (Some(0.1), Some(0.1)),
        "the same value twice is no conflict"
    );
    assert_eq!(of(&v[3]), (Some(0.09), None));
    // The run's per-side heights fill only the legs a row gives nothing for.
    let opts = InputOptions {
        left_sensor_height_m: Some(0.2),
        right_sensor_height_m: Some(0.3),
        ..InputOptions::default()
    };
    let v = discover_with(std::slice::from_ref(&m), &opts).unwrap();
    assert_eq!(of(&v[0]), (Some(0.08), Some(0.14)), "the row wins");
    assert_eq!(
        of(&v[1]),
        (Some(0.1), Some(0.1)),
        "the row's height for both legs wins"
    );
    assert_eq!(of(&v[3]), (Some(0.09), Some(0.3)));
    drop(d);
    let e = err("subject_id,left,right,sensor_height_m,right_sensor_height_m\nS1,a,b,0.1,0.14\n");
    assert!(
        e.contains("manifest.csv:2:5: column 'right_sensor_height_m': '0.14' is not valid")
            && e.contains("sensor_height_m (0.1)"),
        "{e}"
    );
    let e = err("subject_id,left,right,left_sensor_height_m\nS1,a,b,-1\n");
    assert!(e.contains("'left_sensor_height_m': '-1'"), "{e}");
}

/// Each leg's stride length uses its own sensor's height: raising the left sensor's height
/// changes the left leg's stride lengths and leaves the right leg's bit for bit.
#[test]
fn each_leg_uses_its_own_sensor_height() {
    let subject = demo_inputs().unwrap().swap_remove(0);
    let p = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let read = crate::io::ReadParams::default().check().unwrap();
    let lengths = |s: &SubjectInput| {
        let r = Analysis::new(p.check().unwrap())
            .read(read.clone())
            .subject(s);
        let leg = |l: &std::result::Result<LegResult, String>| -> Vec<f64> {
            l.as_ref()
                .unwrap()
                .strides
                .iter()
                .map(|s| s.stride_length_m)
                .collect()
        };
        (leg(&r.left), leg(&r.right))
    };
    let same = SubjectInput {
        sensor_height_m: Some(0.1),
        ..subject.clone()
    };
    let left_higher = SubjectInput {
        sensor_height_m: None,
        left_sensor_height_m: Some(0.2),
        right_sensor_height_m: Some(0.1),
        ..subject
    };
    let (l0, r0) = lengths(&same);
    let (l1, r1) = lengths(&left_higher);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&r0), bits(&r1), "the right leg keeps its lengths");
    assert_eq!(l0.len(), l1.len());
    let moved = l0
        .iter()
        .zip(&l1)
        .filter(|(a, b)| a.is_finite() && b.is_finite() && (*a - *b).abs() > 1e-6)
        .count();
    assert!(
        moved > 0,
        "the left leg's lengths move with its height: {l0:?} {l1:?}"
    );
}

#[test]
fn belt_speed_and_visit_are_read_checked_and_carried_to_the_rows() {
    let (_d, m) = manifest(
        "subject_id,trial_id,visit,left,right,setting,belt_speed_mps\n\
         P1,1,pre,a/l.csv,a/r.csv,treadmill,1.10\n\
         P1,2,post,b/l.csv,b/r.csv,treadmill,\n\
         P2,1,,c/l.csv,c/r.csv,,\n",
    );
    let v = read_manifest(&m).unwrap();
    assert_eq!(v[0].belt_speed_mps, Some(1.10));
    assert_eq!(v[0].visit.as_deref(), Some("pre"));
    assert_eq!(v[1].belt_speed_mps, None);
    assert_eq!(v[1].visit.as_deref(), Some("post"));
    assert_eq!((v[2].belt_speed_mps, v[2].visit.as_deref()), (None, None));
    // The rows carry both (trailing columns of the recordings table).
    let r = Analysis::new(AnalysisParams::default().check().unwrap()).subject(&v[0]);
    let rows = crate::output::recording_rows(&[r]);
    assert_eq!(rows[0].belt_speed_mps, Some(1.10));
    assert_eq!(rows[0].visit, "pre");
    // A bad speed is refused with its file, line and column.
    let head = "subject_id,left,right,setting,belt_speed_mps\n";
    for bad in ["0", "-1", "5.5", "NaN", "inf", "fast"] {
        let e = err(&format!("{head}S1,a,b,treadmill,{bad}\n"));
        assert!(
            e.contains(&format!(
                "manifest.csv:2:5: column 'belt_speed_mps': '{bad}' is not valid"
            )) && e.contains("at most 5"),
            "{bad}: {e}"
        );
    }
    let (_d5, m5) = manifest(&format!("{head}S1,a,b,treadmill,5\n"));
    assert_eq!(read_manifest(&m5).unwrap()[0].belt_speed_mps, Some(5.0));
    // A belt speed off a treadmill contradicts the setting.
    let e = err(&format!("{head}S1,a,b,overground,1.2\n"));
    assert!(
        e.contains("manifest.csv:2:5: column 'belt_speed_mps'") && e.contains("treadmill"),
        "{e}"
    );
    let e = err(&format!("{head}S1,a,b,,1.2\n"));
    assert!(e.contains("treadmill"), "{e}");
}

#[test]
fn clocks_are_stated_in_the_manifest_or_read_from_the_files() {
    let (_d, m) = manifest(
        "subject_id,trial_id,left,right,clocks\n\
         P1,1,a/l.csv,a/r.csv,one\n\
         P1,2,b/l.csv,b/r.csv,TWO\n\
         P1,3,c/l.csv,c/r.csv,\n\
         P2,1,both.txt,both.txt,\n",
    );
    let v = read_manifest(&m).unwrap();
    // Synchronised sensors, stated: one clock although two files.
    assert_eq!(v[0].clocks(), Some(Clocks::One));
    assert_eq!(v[1].clocks(), Some(Clocks::Two));
    // Not stated: two files are two clocks, one file holding both legs one.
    assert_eq!(v[2].clocks(), Some(Clocks::Two));
    assert_eq!(v[3].clocks(), Some(Clocks::One));
    let e = err("subject_id,left,right,clocks\nS1,a,b,synced\n");
    assert!(
        e.contains("manifest.csv:2:4: column 'clocks': 'synced' is not valid")
            && e.contains("'one' (synchronised sensors)"),
        "{e}"
    );
}
