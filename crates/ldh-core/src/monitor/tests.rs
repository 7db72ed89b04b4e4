//! The monitor on synthetic days built from the embedded demo walks (25 s at 100 Hz, 3 s of
//! standing then walking with a turn) between still, sitting, non-wear and cycling
//! segments; bad inputs. Accuracy on simulated free-living days is in ldh-sim's tests.

use super::*;
use crate::domain::Legs;
use crate::pipeline::bare_subject;

const FS: f64 = 100.0;

/// A deterministic noise in [-1, 1).
struct Noise(u64);
impl Noise {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

struct Day {
    s: Vec<Sample>,
    noise: Noise,
}

impl Day {
    fn new(seed: u64) -> Self {
        Day {
            s: Vec::new(),
            noise: Noise(seed),
        }
    }
    fn t(&self) -> f64 {
        self.s.len() as f64 / FS
    }
    /// Still with the shank tilted `tilt` deg; `noise_g` of acceleration noise, `sway_dps`.
    fn still(&mut self, secs: f64, tilt: f64, noise_g: f64, sway_dps: f64) -> &mut Self {
        let (c, s) = (tilt.to_radians().cos(), tilt.to_radians().sin());
        for _ in 0..(secs * FS) as usize {
            let t = self.t();
            let n = [
                self.noise.next(),
                self.noise.next(),
                self.noise.next(),
                self.noise.next(),
            ];
            self.s.push(Sample {
                t_s: t,
                acc_g: [c + noise_g * n[0], s + noise_g * n[1], noise_g * n[2]],
                gyro_dps: [
                    sway_dps * n[3],
                    sway_dps * (t * 0.7).sin(),
                    sway_dps * (t * 1.3).cos(),
                ],
            });
        }
        self
    }
    /// A demo walk (one leg's file).
    fn walk(&mut self, rel: &str) -> &mut Self {
        let r = crate::demo::recording(rel).unwrap();
        for i in 0..r.len() {
            let t = self.t();
            self.s.push(Sample {
                t_s: t,
                acc_g: [r.acc_g[0][i], r.acc_g[1][i], r.acc_g[2][i]],
                gyro_dps: [r.gyro_dps[0][i], r.gyro_dps[1][i], r.gyro_dps[2][i]],
            });
        }
        self
    }
    /// Pedalling: a sinusoidal shank rotation at 1.2 Hz, smooth acceleration, no impact.
    fn cycle(&mut self, secs: f64, phase: f64) -> &mut Self {
        let w = 2.0 * std::f64::consts::PI * 1.2;
        for _ in 0..(secs * FS) as usize {
            let t = self.t();
            let th = (30.0 + 25.0 * (w * t + phase).sin()).to_radians();
            self.s.push(Sample {
                t_s: t,
                acc_g: [
                    th.cos() + 0.05 * (2.0 * w * t).sin(),
                    th.sin(),
                    0.02 * (w * t).cos(),
                ],
                gyro_dps: [
                    5.0 * (w * t).sin(),
                    8.0 * (w * t).cos(),
                    25.0 * 180.0 / std::f64::consts::PI * w * (w * t + phase).cos() / 1.0,
                ],
            });
        }
        self
    }
}

fn day(side: &str, seed: u64) -> Vec<Sample> {
    let mut d = Day::new(seed);
    d.still(120.0, 40.0, 0.004, 0.5) // sitting
        .walk(&format!("H01/{side}.csv"))
        .still(60.0, 5.0, 0.004, 2.0) // standing
        .walk(&format!("L01/{side}.csv"))
        .still(60.0, 40.0, 0.004, 0.5)
        .cycle(
            120.0,
            if side == "left" {
                0.0
            } else {
                std::f64::consts::PI
            },
        )
        .still(60.0, 40.0, 0.004, 0.5)
        .walk(&format!("H02/{side}.csv"))
        .still(120.0, 85.0, 0.004, 0.3); // lying
    d.s
}

fn params() -> ValidMonitorParams {
    MonitorParams::default().check().unwrap()
}

fn run(left: Vec<Sample>, right: Vec<Sample>) -> MonitorResult {
    let l: Box<dyn SampleSource> = Box::new(MemorySamples::new("left", left));
    let r: Box<dyn SampleSource> = Box::new(MemorySamples::new("right", right));
    monitor_sources(&bare_subject("S1"), Ok(l), Ok(r), &params())
}

#[test]
fn the_walks_are_found_and_cycling_sitting_and_lying_are_not() {
    let res = run(day("left", 1), day("right", 2));
    assert!(res.errors.is_empty(), "{:?}", res.errors);
    let b = &res.bouts;
    assert_eq!(b.len(), 3, "{b:#?}\n{:?}", res.notes);
    // Each demo walk lasts 35 s: sitting 120 s, walk, 60 s, walk, 60 + 120 + 60 s, walk.
    let walks = [120.0, 215.0, 490.0];
    for (bout, start) in b.iter().zip(walks) {
        assert_eq!(bout.legs, Legs::Both);
        // The demo walks: 3 s standing, first heel strike at about 4 s, then about 27 s and
        // 54 steps of walking with a turn (H01's truth; the others alike).
        assert!((bout.start_s - start - 4.0).abs() < 1.0, "{bout:?}");
        assert!(bout.duration_s > 22.0 && bout.duration_s < 32.0, "{bout:?}");
        assert!(bout.steps >= 44 && bout.steps <= 64, "{bout:?}");
        assert!(
            bout.cadence_steps_per_min > 90.0 && bout.cadence_steps_per_min < 140.0,
            "{bout:?}"
        );
        assert!(
            bout.stride_time_s > 0.9 && bout.stride_time_s < 1.3,
            "{bout:?}"
        );
        // The envelopes' level: each demo walk starts with the same leg, which biases it by
        // up to half a step (docs/free-living.md).
        assert!(bout.clock_offset_s.abs() < 0.4, "{bout:?}");
    }
    let states: Vec<&str> = res.periods.iter().map(|p| p.state.as_str()).collect();
    assert!(states.contains(&"cycling"), "{states:?}");
    assert!(states.contains(&"lying"), "{states:?}");
    assert!(states.contains(&"sitting"), "{states:?}");
    assert_eq!(res.days.len(), 1);
    // Under 12 h worn: not a valid day, amounts withheld with the reason, bouts kept.
    let d = &res.days[0];
    assert!(!d.valid);
    assert!(
        d.walking_min.is_nan() && d.withheld.contains("walking_min: not a valid day"),
        "{d:?}"
    );
}

#[test]
fn a_clock_offset_between_the_sensors_is_found_and_the_bouts_still_pair() {
    let mut right = day("right", 2);
    for s in &mut right {
        s.t_s += 2.5;
    }
    let res = run(day("left", 1), right);
    assert_eq!(res.bouts.len(), 3, "{:?}", res.notes);
    for b in &res.bouts {
        assert_eq!(b.legs, Legs::Both);
        assert!((b.clock_offset_s - 2.5).abs() < 0.4, "{b:?}");
    }
}

#[test]
fn a_sensor_that_stops_leaves_the_other_legs_bouts() {
    let left = day("left", 1);
    let mut right = day("right", 2);
    right.truncate((300.0 * FS) as usize); // stops before the third walk
    let res = run(left, right);
    assert_eq!(res.bouts.len(), 3, "{:?}", res.notes);
    assert_eq!(res.bouts[2].legs, Legs::Left);
    assert!(res.bouts[2].step_time_asymmetry_pct.is_nan());
    assert!(res.bouts[2]
        .withheld
        .contains("step_time_asymmetry_pct: needs both legs"));
}

#[test]
fn a_gap_and_a_backward_jump_are_said_and_the_rest_is_kept() {
    let mut left = day("left", 1);
    // A 10-min gap before the last walk, and ten samples that go back in time.
    let cut = (400.0 * FS) as usize;
    for s in &mut left[cut..] {
        s.t_s += 600.0;
    }
    let dup: Vec<Sample> = left[1000..1010].to_vec();
    left.splice(2000..2000, dup);
    let mut right = day("right", 2);
    for s in &mut right[cut..] {
        s.t_s += 600.0;
    }
    let res = run(left, right);
    assert_eq!(res.bouts.len(), 3, "{:?}", res.notes);
    assert!(
        res.notes.iter().any(|n| n.contains("no data from")),
        "{:?}",
        res.notes
    );
    assert!(
        res.notes.iter().any(|n| n.contains("clock jumped back")),
        "{:?}",
        res.notes
    );
    assert!(res.periods.iter().any(|p| p.state == "no_data"));
}

#[test]
fn only_non_wear_gives_no_bout_no_valid_day_and_says_why() {
    let mut d = Day::new(3);
    d.still(3.0 * 3600.0, 88.0, 0.0005, 0.05);
    let res = run(d.s.clone(), d.s);
    assert!(res.bouts.is_empty());
    assert!(
        res.periods.iter().all(|p| p.state == "non_wear"),
        "{:?}",
        res.periods
    );
    assert!(res.days.iter().all(|d| !d.valid && d.wear_h == 0.0));
    assert!(
        res.notes.iter().any(|n| n.contains("not worn")),
        "{:?}",
        res.notes
    );
    assert!(!res.summary.valid);
}

#[test]
fn legs_of_different_rates_are_each_read_at_their_own() {
    let left = day("left", 1);
    // The right leg at 50 Hz (every other sample).
    let right: Vec<Sample> = day("right", 2).into_iter().step_by(2).collect();
    let res = run(left, right);
    assert_eq!(res.bouts.len(), 3, "{:?}", res.notes);
    assert!(
        res.bouts.iter().all(|b| b.legs == Legs::Both),
        "{:?}",
        res.bouts
    );
}

fn csv_of(samples: &[Sample]) -> String {
    let mut s = String::from(
        "# start: 2024-03-05T23:58:00\ntime_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n",
    );
    for x in samples {
        s.push_str(&format!(
            "{:.4},{:.5},{:.5},{:.5},{:.3},{:.3},{:.3}\n",
            x.t_s, x.acc_g[0], x.acc_g[1], x.acc_g[2], x.gyro_dps[0], x.gyro_dps[1], x.gyro_dps[2]
        ));
    }
    s
}

fn csv_source(text: String, name: &str) -> Box<dyn SampleSource> {
    Box::new(
        CsvSamples::from_reader(
            Box::new(std::io::Cursor::new(text.into_bytes())),
            std::path::Path::new(name),
        )
        .unwrap(),
    )
}

#[test]
fn csv_with_a_bad_row_and_a_truncated_last_line_is_read_with_notes_and_calendar_days() {
    let mut l = csv_of(&day("left", 1));
    l = l.replacen("\n1.0000,", "\n1.0000,abc,", 1);
    l.push_str("600.01,0.99,0.0");
    let r = csv_of(&day("right", 2));
    let res = monitor_sources(
        &bare_subject("S1"),
        Ok(csv_source(l, "l.csv")),
        Ok(csv_source(r, "r.csv")),
        &params(),
    );
    assert_eq!(res.bouts.len(), 3, "{:?}", res.notes);
    assert!(
        res.notes
            .iter()
            .any(|n| n.contains("last line is incomplete")),
        "{:?}",
        res.notes
    );
    assert!(
        res.notes.iter().any(|n| n.contains("were skipped")),
        "{:?}",
        res.notes
    );
    // Started at 23:58: two calendar days.
    let dates: Vec<&str> = res.days.iter().map(|d| d.date.as_str()).collect();
    assert_eq!(dates, ["2024-03-05", "2024-03-06"]);
}

#[test]
fn a_file_without_the_columns_is_refused_with_what_is_read() {
    let e = CsvSamples::from_reader(
        Box::new(std::io::Cursor::new(b"a,b\n1,2\n".to_vec())),
        std::path::Path::new("x.csv"),
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("no column 'time_s'"), "{e}");
}

#[test]
fn the_tables_have_their_columns() {
    let res = run(day("left", 1), day("right", 2));
    let dir = std::env::temp_dir().join(format!("ldh-monitor-test-{}", std::process::id()));
    let files = write::write_tables(&dir, &[res]).unwrap();
    assert_eq!(files.len(), 4);
    let bouts = std::fs::read_to_string(dir.join("bouts.csv")).unwrap();
    assert!(bouts.starts_with("subject_id,visit,bout,day,start_s,end_s,duration_s,steps"));
    assert_eq!(bouts.lines().count(), 4);
    let days = std::fs::read_to_string(dir.join("days.csv")).unwrap();
    assert!(days.lines().next().unwrap().contains("wear_h") && days.contains("walking_min"));
    std::fs::remove_dir_all(&dir).unwrap();
}
