//! Per-stage and end-to-end timing of the per-recording pipeline (issue 3) on one 35 s, 100 Hz
//! recording of the embedded demo cohort, and (group `leg_30s`, issue 17) on one simulated 30 s
//! leg at 100 Hz as `ldh analyze` reads it from CSV: the attitude, STA over the whole leg and
//! the whole per-leg pipeline.
//!
//! Run: `cargo bench -p ldh-sim --bench pipeline`

mod common;

use common::leg_30s_csv;
use criterion::{criterion_group, criterion_main, Criterion};
use ldh_core::align::{align, AlignParams};
use ldh_core::attitude::{estimate, AttitudeModel, AttitudeParams};
use ldh_core::events::{detect, EventParams};
use ldh_core::gait::{side_parameters, strides, StrideParams};
use ldh_core::io::{read_recording_bytes, ReadParams};
use ldh_core::nonlinear::{gait_sta, GaitStaParams};
use ldh_core::pipeline::{Analysis, AnalysisParams};
use ldh_core::preprocess::{preprocess, PreprocessParams};
use ldh_core::Side;
use std::hint::black_box;
use std::path::Path;

fn bench(c: &mut Criterion) {
    let text = ldh_core::demo::file("L01/left.csv").expect("demo file");
    let rp = ReadParams::default().check().unwrap();
    let (rec, _) =
        read_recording_bytes(text.as_bytes(), Path::new("L01/left.csv"), None, &rp).unwrap();
    let pp = PreprocessParams::default().check(rec.fs_hz).unwrap();
    let pre = preprocess(&rec, &pp).unwrap();
    let ap = AlignParams::default().check().unwrap();
    let al = align(&pre, &ap).unwrap();
    let fusion = AttitudeParams::default().check().unwrap();
    let fusion_fwd = AttitudeParams::default().smoother(false).check().unwrap();
    let acc = AttitudeParams::default()
        .model(AttitudeModel::Acc)
        .check()
        .unwrap();
    let att = estimate(&al, &fusion).unwrap();
    let ep = EventParams::default().check().unwrap();
    let ev = detect(&att.pitch_deg, &al.gyro_dps[1], rec.fs_hz, &ep).unwrap();
    let sp = StrideParams::default().check().unwrap();
    let st = strides(Side::Left, &al, &att, &ev, &sp).unwrap();

    let mut g = c.benchmark_group("stage");
    g.bench_function("read_csv", |b| {
        b.iter(|| {
            read_recording_bytes(black_box(text.as_bytes()), Path::new("x.csv"), None, &rp).unwrap()
        })
    });
    g.bench_function("preprocess", |b| {
        b.iter(|| preprocess(black_box(&rec), &pp).unwrap())
    });
    g.bench_function("align", |b| b.iter(|| align(black_box(&pre), &ap).unwrap()));
    g.bench_function("attitude_fusion_rts", |b| {
        b.iter(|| estimate(black_box(&al), &fusion).unwrap())
    });
    g.bench_function("attitude_fusion_forward", |b| {
        b.iter(|| estimate(black_box(&al), &fusion_fwd).unwrap())
    });
    g.bench_function("attitude_acc", |b| {
        b.iter(|| estimate(black_box(&al), &acc).unwrap())
    });
    g.bench_function("events", |b| {
        b.iter(|| detect(black_box(&att.pitch_deg), &al.gyro_dps[1], rec.fs_hz, &ep).unwrap())
    });
    g.bench_function("strides", |b| {
        b.iter(|| strides(Side::Left, black_box(&al), &att, &ev, &sp).unwrap())
    });
    g.bench_function("parameters", |b| {
        b.iter(|| side_parameters(black_box(&st), None))
    });
    g.bench_function("sta", |b| {
        b.iter(|| {
            gait_sta(
                black_box(&al.gyro_dps[1][600..1800]),
                rec.fs_hz,
                1.1,
                &GaitStaParams::default(),
            )
        })
    });
    // the whole 25 s leg, as `ldh analyze` runs STA on a clean walk (issue 17)
    g.bench_function("sta_whole_leg", |b| {
        b.iter(|| {
            gait_sta(
                black_box(&al.gyro_dps[1]),
                rec.fs_hz,
                1.1,
                &GaitStaParams::default(),
            )
        })
    });
    g.finish();

    let mut g = c.benchmark_group("end_to_end");
    let no_sta = Analysis::new(
        AnalysisParams {
            compute_sta: false,
            ..AnalysisParams::default()
        }
        .check()
        .unwrap(),
    );
    let with_sta = Analysis::new(AnalysisParams::default().check().unwrap());
    g.bench_function("recording_without_sta", |b| {
        b.iter(|| {
            let (r, _) =
                read_recording_bytes(black_box(text.as_bytes()), Path::new("x.csv"), None, &rp)
                    .unwrap();
            no_sta.leg(&r, Side::Left, None).unwrap()
        })
    });
    g.bench_function("recording_with_sta", |b| {
        b.iter(|| {
            let (r, _) =
                read_recording_bytes(black_box(text.as_bytes()), Path::new("x.csv"), None, &rp)
                    .unwrap();
            with_sta.leg(&r, Side::Left, None).unwrap()
        })
    });
    g.finish();
}

/// One simulated healthy subject's left leg, 30 s at 100 Hz, as CSV bytes in the default format.
/// Issue 17's targets: STA ≤ 2 ms per 30 s leg at 100 Hz, the whole per-leg pipeline ≤ 3 ms.
fn bench_leg_30s(c: &mut Criterion) {
    let bytes = leg_30s_csv();
    let rp = ReadParams::default().check().unwrap();
    let (rec, _) = read_recording_bytes(&bytes, Path::new("left.csv"), None, &rp).unwrap();
    let pre = preprocess(&rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
    let al = align(&pre, &AlignParams::default().check().unwrap()).unwrap();
    let fusion = AttitudeParams::default().check().unwrap();
    let mut g = c.benchmark_group("leg_30s");
    g.bench_function("attitude_fusion_rts", |b| {
        b.iter(|| estimate(black_box(&al), &fusion).unwrap())
    });
    g.bench_function("sta", |b| {
        b.iter(|| {
            gait_sta(
                black_box(&al.gyro_dps[1]),
                rec.fs_hz,
                1.1,
                &GaitStaParams::default(),
            )
        })
    });
    let no_sta = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let with_sta = AnalysisParams::default();
    for (name, params) in [("leg_without_sta", &no_sta), ("leg_with_sta", &with_sta)] {
        let analysis = Analysis::new(params.check().unwrap());
        g.bench_function(name, |b| {
            b.iter(|| {
                let (r, _) =
                    read_recording_bytes(black_box(&bytes), Path::new("left.csv"), None, &rp)
                        .unwrap();
                analysis.leg(&r, Side::Left, None).unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench, bench_leg_30s);
criterion_main!(benches);
