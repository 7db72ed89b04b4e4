//! Reading and preprocessing throughput (issue 2): one 35 s, 100 Hz recording of the demo
//! cohort, from CSV bytes in memory (no disk) and preprocessing alone.
//!
//! Run: `cargo bench -p ldh-core --bench preprocess`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use ldh_core::io::{read_recording_bytes, ReadParams};
use ldh_core::preprocess::{preprocess, PreprocessParams};
use std::hint::black_box;
use std::path::Path;

fn bench(c: &mut Criterion) {
    let text = ldh_core::demo::file("H01/left.csv").expect("demo file");
    let rp = ReadParams::default().check().unwrap();
    let (rec, _) =
        read_recording_bytes(text.as_bytes(), Path::new("H01/left.csv"), None, &rp).unwrap();
    let pp = PreprocessParams::default().check(rec.fs_hz).unwrap();

    let mut g = c.benchmark_group("read_csv");
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.bench_function(BenchmarkId::new("bytes", text.len()), |b| {
        b.iter(|| {
            read_recording_bytes(black_box(text.as_bytes()), Path::new("x.csv"), None, &rp).unwrap()
        })
    });
    g.finish();

    let mut g = c.benchmark_group("preprocess");
    g.throughput(Throughput::Elements(rec.len() as u64));
    g.bench_function(BenchmarkId::new("samples", rec.len()), |b| {
        b.iter(|| preprocess(black_box(&rec), &pp).unwrap())
    });
    g.finish();

    let mut g = c.benchmark_group("read_and_preprocess");
    g.throughput(Throughput::Elements(rec.len() as u64));
    g.bench_function(BenchmarkId::new("samples", rec.len()), |b| {
        b.iter(|| {
            let (r, _) =
                read_recording_bytes(black_box(text.as_bytes()), Path::new("x.csv"), None, &rp)
                    .unwrap();
            preprocess(&r, &pp).unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
