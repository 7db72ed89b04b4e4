//! `ldh monitor` (issue 52) end to end: two files made of the demo walks between still
//! periods, a manifest of two people and two visits, and bad inputs (exit codes, messages,
//! nothing lost).

mod common;
use common::{ldh, ldh_ok, read_csv, text};
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

/// One monitoring period of person `who` simulated by ldh-sim's free-living generator: a day
/// per seed of `days`, each one hour (11:00–12:00, between the simulator's morning and
/// afternoon non-wear) at 50 Hz, the days' files joined into one recording per leg (a device
/// recording an hour a day: 23 h without data between the days). `stride_time_factor` > 1 is
/// slower walking. Returns the left and right files' names in `dir`.
fn simulated_period(
    dir: &Path,
    name: &str,
    who: u64,
    days: &[u64],
    stride_time_factor: f64,
) -> (String, String) {
    use ldh_sim::free_living::{simulate_free_living, FreeLivingParams};
    let mut legs = [String::new(), String::new()];
    for (d, &seed) in days.iter().enumerate() {
        let params = FreeLivingParams {
            duration_h: 1.0,
            fs_hz: 50.0,
            seed,
            subject_seed: Some(who),
            start: ldh_core::io::DateTime::new((2026, 3, 2 + d as i64), (11, 0, 0), false).unwrap(),
            drift_ppm: Some(0.0),
            stride_time_factor,
            ..FreeLivingParams::default()
        };
        let sim = dir.join(format!("sim_{name}_{d}"));
        let subjects = simulate_free_living(&params, &sim, &|| {}).unwrap();
        for (leg, side) in legs.iter_mut().zip(["left", "right"]) {
            let text =
                std::fs::read_to_string(subjects[0].dir.join(format!("{side}.csv"))).unwrap();
            for line in text.lines() {
                let header = line.starts_with('#') || line.starts_with("time_s");
                if header && d > 0 {
                    continue;
                }
                match line.split_once(',') {
                    Some((t, rest)) if !header => {
                        let t: f64 = t.parse().unwrap();
                        leg.push_str(&format!("{:.2},{rest}\n", t + d as f64 * 86_400.0));
                    }
                    _ => {
                        leg.push_str(line);
                        leg.push('\n');
                    }
                }
            }
        }
        std::fs::remove_dir_all(&sim).unwrap();
    }
    let names = [format!("{name}_left.csv"), format!("{name}_right.csv")];
    for (n, leg) in names.iter().zip(&legs) {
        std::fs::write(dir.join(n), leg).unwrap();
    }
    let [l, r] = names;
    (l, r)
}

#[test]
fn monitor_finds_the_slower_walking_a_simulated_second_visit_put_in() {
    let d = tempfile::tempdir().unwrap();
    // P1 and P2: two days at each visit, walking 25 % slower (stride time × 1.25) at "post",
    // on other days. P3: one day at each visit. The days' seeds have at least three walks over
    // 36 s in their hour (the daily cadence is of walks over 30 s).
    let mut manifest = String::from("subject_id,trial_id,visit,left,right\n");
    let plan: [(&str, u64, [&[u64]; 2]); 3] = [
        ("P1", 101, [&[40, 41], &[57, 58]]),
        ("P2", 102, [&[30, 31], &[44, 35]]),
        ("P3", 103, [&[75], &[66]]),
    ];
    for (p, who, days) in plan {
        for ((v, factor), days) in [("pre", 1.0), ("post", 1.25)].into_iter().zip(days) {
            let (l, r) = simulated_period(d.path(), &format!("{p}_{v}"), who, days, factor);
            manifest.push_str(&format!("{p},{v},{v},{l},{r}\n"));
        }
    }
    let m = d.path().join("manifest.csv");
    std::fs::write(&m, manifest).unwrap();
    // An hour a day: valid days from 30 min of waking wear, a period from two valid days, the
    // daily cadence from one bout over 30 s.
    let params = d.path().join("monitor.toml");
    std::fs::write(
        &params,
        "min_wear_h = 0.5\nmin_valid_days = 2\nmin_long_bouts = 1\n",
    )
    .unwrap();
    let out = d.path().join("out");
    let o = ldh_ok(&[
        "monitor",
        m.to_str().unwrap(),
        "--params",
        params.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = text(&o);
    assert!(err.contains("changes.csv"), "{err}");

    let summary = read_csv(&out.join("summary.csv"));
    assert_eq!(summary.len(), 6, "{summary:?}");
    for s in &summary {
        let two = !s["subject_id"].starts_with("P3");
        assert_eq!(s["valid_days"], if two { "2" } else { "1" }, "{s:?}");
        assert_eq!(s["valid"], two.to_string(), "{s:?}");
        assert!(s["bouts_total"].parse::<usize>().unwrap() >= 10, "{s:?}");
    }
    let days = read_csv(&out.join("days.csv"));
    assert_eq!(days.len(), 10, "{days:?}");
    assert!(days.iter().all(|r| r["valid"] == "true"), "{days:?}");
    assert!(days.iter().any(|r| r["date"] == "2026-03-03"), "{days:?}");
    let bouts = read_csv(&out.join("bouts.csv"));
    let people: std::collections::BTreeSet<(&str, &str)> = bouts
        .iter()
        .map(|b| (b["subject_id"].as_str(), b["visit"].as_str()))
        .collect();
    assert_eq!(people.len(), 6, "{people:?}");
    for p in ["P1", "P2", "P3"] {
        let page = std::fs::read_to_string(out.join(format!("week_{p}.html"))).unwrap();
        assert!(page.contains("Period “post”"), "{p}");
        assert!(page.contains("Change between the periods"), "{p}");
    }

    // changes.csv: four daily measures per person. The cadence fell at "post" (the simulation
    // made each stride 25 % longer: ≈ −20 %), beyond the day-to-day noise for P1 and P2; P3's
    // change is withheld with the reason (one valid day a period).
    let changes = read_csv(&out.join("changes.csv"));
    assert_eq!(changes.len(), 12, "{changes:?}");
    for c in changes
        .iter()
        .filter(|c| c["measure"] == "cadence_steps_per_min")
    {
        let (from, change): (f64, f64) = (
            c["mean_from"].parse().unwrap(),
            c["change"].parse().unwrap(),
        );
        println!(
            "{} cadence {from:.1} → change {change:.1} (noise {})",
            c["subject_id"], c["noise"]
        );
        assert!(change < -0.12 * from && change > -0.28 * from, "{c:?}");
        if c["subject_id"] == "P3" {
            assert_eq!(c["beyond_noise"], "", "{c:?}");
            assert!(c["withheld"].contains("1 and 1 valid day(s)"), "{c:?}");
        } else {
            assert_eq!(c["beyond_noise"], "true", "{c:?}");
            assert_eq!((c["days_from"].as_str(), c["days_to"].as_str()), ("2", "2"));
        }
    }
    let page = std::fs::read_to_string(out.join("week_P3.html")).unwrap();
    assert!(page.contains("not judged: 1 and 1 valid day(s)"), "{page}");
}
