//! `ldh monitor` (issue 52) end to end: two files made of the demo walks between still
//! periods, a manifest of two people and two visits, and bad inputs (exit codes, messages,
//! nothing lost).

mod common;
use common::{ldh, ldh_ok, text};
use std::path::Path;

/// One leg: 2 min still, then the demo walks of H01, L01 and H02 each followed by 1 min still.
fn write_leg(path: &Path, side: &str, truncate_last: bool) {
    let mut out = String::from(
        "# start: 2024-03-05T10:00:00\ntime_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n",
    );
    let mut n = 0usize;
    let still = |out: &mut String, n: &mut usize, secs: usize| {
        for i in 0..secs * 100 {
            let w = ((i * 7919) % 13) as f64 * 0.0006;
            out.push_str(&format!(
                "{:.2},{:.5},{:.5},{:.5},0.300,-0.200,{:.3}\n",
                *n as f64 / 100.0,
                0.766 + w,
                0.643 - w,
                w,
                w * 100.0
            ));
            *n += 1;
        }
    };
    still(&mut out, &mut n, 120);
    for s in ["H01", "L01", "H02"] {
        let text = ldh_core::demo::file(&format!("{s}/{side}.csv")).unwrap();
        for line in text.lines().skip(1) {
            let rest = line.split_once(',').unwrap().1;
            out.push_str(&format!("{:.2},{rest}\n", n as f64 / 100.0));
            n += 1;
        }
        still(&mut out, &mut n, 60);
    }
    if truncate_last {
        out.push_str("999.99,0.9");
    }
    std::fs::write(path, out).unwrap();
}

#[test]
fn monitor_writes_the_four_tables_for_two_files() {
    let d = tempfile::tempdir().unwrap();
    let (l, r) = (d.path().join("p1_left.csv"), d.path().join("p1_right.csv"));
    write_leg(&l, "left", true);
    write_leg(&r, "right", false);
    let out = d.path().join("out");
    let o = ldh_ok(&[
        "monitor",
        l.to_str().unwrap(),
        r.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-j",
        "1",
    ]);
    let err = text(&o);
    assert!(err.contains("3 walking bout(s)"), "{err}");
    assert!(err.contains("last line is incomplete"), "{err}");
    for f in ["bouts.csv", "days.csv", "summary.csv", "periods.csv"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let bouts = std::fs::read_to_string(out.join("bouts.csv")).unwrap();
    assert_eq!(bouts.lines().count(), 4, "{bouts}");
    let days = std::fs::read_to_string(out.join("days.csv")).unwrap();
    assert!(days.contains("2024-03-05"), "{days}");
    assert!(days.contains("not a valid day"), "{days}");
}

#[test]
fn monitor_on_a_manifest_of_two_people_and_two_visits() {
    let d = tempfile::tempdir().unwrap();
    let mut manifest = String::from("subject_id,trial_id,visit,left,right\n");
    for (p, v) in [("P1", "pre"), ("P1", "post"), ("P2", "pre")] {
        let (l, r) = (format!("{p}_{v}_l.csv"), format!("{p}_{v}_r.csv"));
        write_leg(&d.path().join(&l), "left", false);
        write_leg(&d.path().join(&r), "right", false);
        manifest.push_str(&format!("{p},{v},{v},{l},{r}\n"));
    }
    // A person whose right file is missing: an error row, the others written, exit 1.
    manifest.push_str("P3,pre,pre,P1_pre_l.csv,missing.csv\n");
    let m = d.path().join("manifest.csv");
    std::fs::write(&m, manifest).unwrap();
    let out = d.path().join("out");
    let o = ldh(&["monitor", m.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = text(&o);
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap_or_default();
    // A file the manifest lists that is missing fails that person only (as in `ldh analyze`).
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("P3"), "{err}");
    assert_eq!(summary.lines().count(), 5, "{summary}");
    assert!(
        summary.contains("P1,pre") && summary.contains("P1,post") && summary.contains("P2,pre"),
        "{summary}"
    );
    let bouts = std::fs::read_to_string(out.join("bouts.csv")).unwrap();
    assert!(
        bouts.lines().filter(|l| l.starts_with("P1,post,")).count() == 3,
        "{bouts}"
    );
    // A week page per person; P1's change between its two periods, withheld without valid
    // days (a few minutes each), with the reason.
    for p in ["P1", "P2", "P3"] {
        assert!(out.join(format!("week_{p}.html")).is_file(), "{p}");
    }
    let changes = std::fs::read_to_string(out.join("changes.csv")).unwrap();
    assert_eq!(changes.lines().count(), 5, "{changes}");
    assert!(
        changes
            .lines()
            .skip(1)
            .all(|l| l.starts_with("P1,pre,post,")),
        "{changes}"
    );
    let page = std::fs::read_to_string(out.join("week_P1.html")).unwrap();
    assert!(page.contains("Change between the periods"), "{page}");
    assert!(page.contains("not judged"), "{page}");
}

#[test]
fn monitor_refuses_a_file_that_is_not_ldh_csv_with_the_column_it_needs() {
    let d = tempfile::tempdir().unwrap();
    let (l, r) = (d.path().join("left.csv"), d.path().join("right.csv"));
    std::fs::write(&l, "a,b\n1,2\n").unwrap();
    write_leg(&r, "right", false);
    let out = d.path().join("out");
    let o = ldh(&[
        "monitor",
        l.to_str().unwrap(),
        r.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = text(&o);
    assert!(err.contains("no column 'time_s'"), "{err}");
    // The right leg's bouts are still there.
    let bouts = std::fs::read_to_string(out.join("bouts.csv")).unwrap();
    assert_eq!(bouts.lines().count(), 4, "{bouts}");
}
