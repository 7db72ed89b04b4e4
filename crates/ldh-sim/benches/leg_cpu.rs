//! CPU time (not wall time) per call of the per-leg stages of issue 17 on one simulated 30 s leg
//! at 100 Hz, for a shared, loaded machine where criterion's wall-clock medians mostly measure
//! the other processes: the time the process's threads spent on a CPU (Linux
//! `/proc/self/task/*/schedstat`; wall time elsewhere), median over rounds of a fixed number of
//! calls. Same leg and functions as the `leg_30s` group of `benches/pipeline.rs`.
//!
//! Run: `RAYON_NUM_THREADS=1 cargo bench -p ldh-sim --bench leg_cpu [-- ROUNDS CALLS [NAME]]`
//! (NAME: only the cases whose name starts with it, e.g. `attitude` or `sta`, to profile one
//! stage). Events, strides and the per-side parameters are `leg_without_sta` less the stages
//! timed alone (read, preprocess, align, attitude).

mod common;

use ldh_core::align::{align, AlignParams};
use ldh_core::attitude::{estimate, AttitudeParams};
use ldh_core::io::{read_recording_bytes, ReadParams};
use ldh_core::nonlinear::{gait_sta, GaitStaParams};
use ldh_core::pipeline::{Analysis, AnalysisParams};
use ldh_core::preprocess::{preprocess, PreprocessParams};
use ldh_core::Side;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// Nanoseconds the threads of this process (the rayon pool's included) have spent on a CPU,
/// or `None` off Linux.
fn cpu_ns() -> Option<u64> {
    let mut total = 0;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let s = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        total += s.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total)
}

/// Median CPU (or wall) time per call, ms, over `rounds` rounds of `calls` calls.
fn measure(name: &str, only: &str, rounds: usize, calls: usize, mut f: impl FnMut()) {
    if !name.starts_with(only) {
        return;
    }
    for _ in 0..calls.min(3) {
        f();
    }
    let mut per_call: Vec<f64> = (0..rounds)
        .map(|_| {
            let (c0, w0) = (cpu_ns(), Instant::now());
            for _ in 0..calls {
                f();
            }
            let ns = match (c0, cpu_ns()) {
                (Some(a), Some(b)) => (b - a) as f64,
                _ => w0.elapsed().as_nanos() as f64,
            };
            ns / calls as f64 / 1e6
        })
        .collect();
    per_call.sort_by(f64::total_cmp);
    let clock = if cpu_ns().is_some() { "CPU" } else { "wall" };
    println!(
        "{name:28} {:8.3} ms {clock} per call (median of {rounds} × {calls}; min {:.3})",
        per_call[rounds / 2],
        per_call[0]
    );
}

fn main() {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    let args: Vec<usize> = raw.iter().filter_map(|a| a.parse().ok()).collect();
    // the first argument that is not a number (cargo bench passes `--bench`) selects cases
    let only = raw
        .iter()
        .find(|a| a.parse::<usize>().is_err() && !a.starts_with('-'))
        .cloned()
        .unwrap_or_default();
    let rounds = args.first().copied().unwrap_or(9);
    let calls = args.get(1).copied().unwrap_or(20);
    let bytes = common::leg_30s_csv();
    let rp = ReadParams::default().check().unwrap();
    let (rec, _) = read_recording_bytes(&bytes, Path::new("left.csv"), None, &rp).unwrap();
    let pre = preprocess(&rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
    let al = align(&pre, &AlignParams::default().check().unwrap()).unwrap();
    let fusion = AttitudeParams::default().check().unwrap();
    let no_sta = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let with_sta = AnalysisParams::default();
    measure("read_csv", &only, rounds, calls, || {
        black_box(
            read_recording_bytes(black_box(&bytes), Path::new("left.csv"), None, &rp).unwrap(),
        );
    });
    let pp = PreprocessParams::default().check(rec.fs_hz).unwrap();
    measure("preprocess", &only, rounds, calls, || {
        black_box(preprocess(black_box(&rec), &pp).unwrap());
    });
    let ap = AlignParams::default().check().unwrap();
    measure("align", &only, rounds, calls, || {
        black_box(align(black_box(&pre), &ap).unwrap());
    });
    measure("attitude_fusion_rts", &only, rounds, calls, || {
        black_box(estimate(black_box(&al), &fusion).unwrap());
    });
    let forward = AttitudeParams::default().smoother(false).check().unwrap();
    measure("attitude_forward_only", &only, rounds, calls, || {
        black_box(estimate(black_box(&al), &forward).unwrap());
    });
    measure("sta", &only, rounds, calls, || {
        black_box(
            gait_sta(
                black_box(&al.gyro_dps[1]),
                rec.fs_hz,
                1.1,
                &GaitStaParams::default(),
            )
            .unwrap(),
        );
    });
    // Without a sensor height (the leg's length is recomputed at two more heights,
    // `sensor_height_unknown`), and with the leg's own height given.
    for (name, params, height) in [
        ("leg_without_sta", &no_sta, None),
        ("leg_with_sta", &with_sta, None),
        ("leg_with_sta_height_given", &with_sta, Some(0.1)),
    ] {
        let analysis = Analysis::new(params.check().unwrap());
        measure(name, &only, rounds, calls, || {
            let (r, _) =
                read_recording_bytes(black_box(&bytes), Path::new("left.csv"), None, &rp).unwrap();
            black_box(analysis.leg(&r, Side::Left, height).unwrap());
        });
    }
}
