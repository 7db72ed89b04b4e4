//! The linear peak finder against the `find_peaks` crate it replaces: the same peaks on random
//! signals with plateaus, ties and NaNs, on repeated identical strides, on the demo cohort's legs
//! (simulated, family A) and on the HuGaDB recordings when present.

use super::peaks;
use crate::events::{midswing_threshold_dps, EventParams};
use crate::recording::Recording;
use find_peaks::PeakFinder;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The crate's peaks with the same three rules (quadratic on repeated strides).
fn reference(y: &[f64], height: f64, prominence: f64, distance: usize) -> Vec<usize> {
    let mut pf = PeakFinder::new(y);
    pf.with_min_height(height)
        .with_min_prominence(prominence)
        .with_min_distance(distance);
    let mut m: Vec<usize> = pf
        .find_peaks()
        .iter()
        .map(|p| p.middle_position())
        .collect();
    m.sort_unstable();
    m
}

/// Both finders on `y` with the mid-swing rules of `events` (default parameters, rate `fs_hz`)
/// and with a few fixed thresholds; the number of mid-swings found with the default rules.
fn same_as_crate(y: &[f64], fs_hz: f64, what: &str) -> usize {
    let p = EventParams::default();
    let thr = midswing_threshold_dps(y, &p);
    let dist = ((p.min_stride_s * 0.8) * fs_hz).max(1.0) as usize;
    let got = peaks(y, thr, thr, dist);
    assert_eq!(got, reference(y, thr, thr, dist), "{what}: default rules");
    for (h, pr, d) in [(0.0, 0.0, 1), (10.0, 50.0, 5), (thr, 0.5 * thr, 2 * dist)] {
        assert_eq!(
            peaks(y, h, pr, d),
            reference(y, h, pr, d),
            "{what}: height {h}, prominence {pr}, distance {d}"
        );
    }
    got.len()
}

#[test]
fn random_signals_with_plateaus_ties_and_nans() {
    let mut rng = ChaCha8Rng::seed_from_u64(19);
    for case in 0..4000 {
        let n = rng.gen_range(0..300);
        let levels = rng.gen_range(2..8);
        let y: Vec<f64> = (0..n)
            .map(|_| match rng.gen_range(0..100) {
                0 => f64::NAN,
                1 => f64::INFINITY,
                2 => -0.0,
                _ => rng.gen_range(0..levels) as f64 - 2.0,
            })
            .collect();
        let h = rng.gen_range(-3..4) as f64;
        let pr = rng.gen_range(0..4) as f64 * 0.5;
        let d = rng.gen_range(1..20);
        assert_eq!(
            peaks(&y, h, pr, d),
            reference(&y, h, pr, d),
            "case {case}: {y:?} height {h} prominence {pr} distance {d}"
        );
    }
}

#[test]
fn identical_repeated_strides() {
    // The worst case of the crate: every prominence walk runs to the ends.
    let stride: Vec<f64> = (0..110)
        .map(|i| {
            let t = i as f64 / 110.0 * std::f64::consts::TAU;
            300.0 * t.sin().max(0.0).powi(3) - 40.0 * (2.0 * t).sin()
        })
        .collect();
    let y: Vec<f64> = stride.iter().copied().cycle().take(110 * 400).collect();
    assert_eq!(same_as_crate(&y, 100.0, "tiled strides"), 400);
}

fn all_channels(rec: &Recording, what: &str) -> usize {
    let mut found = 0;
    for (k, g) in rec.gyro_dps.iter().enumerate() {
        let neg: Vec<f64> = g.iter().map(|w| -w).collect();
        found += same_as_crate(g, rec.fs_hz, &format!("{what} gyro {k}"));
        found += same_as_crate(&neg, rec.fs_hz, &format!("{what} −gyro {k}"));
    }
    found
}

#[test]
fn hugadb_recordings() {
    let Some(dir) = crate::pipeline::quality::tests::hugadb::hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "txt"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for f in &files {
        let (right, left) = crate::pipeline::quality::tests::hugadb::read_hugadb(f);
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        all_channels(&right, &format!("{name} right"));
        all_channels(&left, &format!("{name} left"));
    }
}

/// The embedded demo cohort's legs (thirteen simulated subjects, family A; the simulator itself is
/// `ldh-sim`'s, which `ldh-core` does not depend on).
#[test]
fn demo_legs() {
    let mut found = 0;
    for id in crate::demo::SUBJECTS {
        for side in ["left", "right"] {
            let rec = crate::demo::recording(&format!("{id}/{side}.csv")).unwrap();
            found += all_channels(&rec, &format!("{id} {side}"));
        }
    }
    assert!(found > 4 * 2 * 10, "{found} peaks");
}
