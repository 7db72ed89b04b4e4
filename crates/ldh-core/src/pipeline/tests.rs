mod inputs;

use super::*;
use crate::recording::Side;

#[test]
fn manifests_are_parsed_and_bad_rows_named() {
    let d = tempfile::tempdir().unwrap();
    let m = d.path().join("manifest.csv");
    std::fs::write(&m, "subject_id,group,affected_side,left,right,sensor_height_m\nS1,ldh,right,a/l.csv,a/r.csv,0.12\nS2,healthy,none,b/l.csv,b/r.csv,\n").unwrap();
    let v = read_manifest(&m).unwrap();
    assert_eq!(v.len(), 2);
    assert_eq!(v[0].affected_side, Some(Side::Right));
    assert_eq!(v[0].sensor_height_m, Some(0.12));
    assert_eq!(v[0].left, Some(Source::Path(d.path().join("a/l.csv"))));
    assert_eq!(v[1].group, Some(Group::Healthy));
    std::fs::write(
        &m,
        "subject_id,group,affected_side,left,right\nS1,sick,up,a,b\n",
    )
    .unwrap();
    let e = read_manifest(&m).unwrap_err().to_string();
    assert!(e.contains("manifest.csv:2:3") && e.contains("'up'"), "{e}");
    assert_eq!(discover(&[]).unwrap().len(), crate::demo::SUBJECTS.len());
    // A misspelt input is refused before any work, as "not found" (FileNotFoundError in
    // Python, exit 2 on the command line); a file a manifest lists fails per recording.
    let e = discover(&[d.path().join("nothing-here.csv")]).unwrap_err();
    assert_eq!(e.kind(), crate::error::ErrorKind::NotFound);
    assert!(
        e.to_string()
            .contains("nothing-here.csv: cannot read: no such file"),
        "{e}"
    );
    std::fs::create_dir(d.path().join("empty")).unwrap();
    let e = discover(&[d.path().join("empty")]).unwrap_err().to_string();
    assert!(e.contains("empty") && e.contains("no manifest.csv"), "{e}");
}

/// A bad STA parameter is refused once, by `AnalysisParams::check`, naming the parameter, not
/// reported as every leg's STA status; with STA off it is not looked at.
#[test]
fn bad_sta_parameters_are_refused_up_front() {
    let mut p = AnalysisParams::default();
    p.sta.theiler_strides = 0.0;
    let e = p.check().unwrap_err().to_string();
    assert!(e.contains("theiler_strides"), "{e}");
    p.sta.theiler_strides = 1.0;
    p.sta.fit_strides = f64::NAN;
    let e = p.check().unwrap_err().to_string();
    assert!(e.contains("fit_strides"), "{e}");
    p.compute_sta = false;
    assert!(p.check().is_ok());
}
