//! Criterion benchmarks of `lyap_r` (Rosenstein) on the x coordinate of the
//! Lorenz system (RK4, dt = 0.01, 1 000-step transient, start (1, 1, 1) —
//! the same series `data-fixtures/scripts/bench_lyapunov_nolds.py` times
//! nolds on). Parameters: lag 10, min_tsep 50, trajectory_len 20, tau 0.01.
//!
//! Run: `cargo bench --bench lyapunov` (numbers in docs/lyapunov.md).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ldh_core::nonlinear::{lyap_r, RosensteinParams, ValidRosensteinParams};

fn lorenz_x(n: usize) -> Vec<f64> {
    let (dt, sigma, rho, beta) = (0.01, 10.0, 28.0, 8.0 / 3.0);
    let f = |s: [f64; 3]| {
        [
            sigma * (s[1] - s[0]),
            s[0] * (rho - s[2]) - s[1],
            s[0] * s[1] - beta * s[2],
        ]
    };
    let add =
        |a: [f64; 3], b: [f64; 3], h: f64| [a[0] + h * b[0], a[1] + h * b[1], a[2] + h * b[2]];
    let mut s = [1.0, 1.0, 1.0];
    let mut out = Vec::with_capacity(n);
    for i in 0..n + 1000 {
        let k1 = f(s);
        let k2 = f(add(s, k1, 0.5 * dt));
        let k3 = f(add(s, k2, 0.5 * dt));
        let k4 = f(add(s, k3, dt));
        for d in 0..3 {
            s[d] += dt / 6.0 * (k1[d] + 2.0 * k2[d] + 2.0 * k3[d] + k4[d]);
        }
        if i >= 1000 {
            out.push(s[0]);
        }
    }
    out
}

fn params(emb_dim: usize) -> ValidRosensteinParams {
    RosensteinParams::default()
        .emb_dim(emb_dim)
        .lag(Some(10))
        .min_tsep(Some(50))
        .trajectory_len(20)
        .tau(0.01)
        .check()
        .expect("valid parameters")
}

fn bench_n10k(c: &mut Criterion) {
    let x = lorenz_x(10_000);
    let mut g = c.benchmark_group("lyap_r_n10000");
    for emb_dim in [5, 10] {
        let p = params(emb_dim);
        g.bench_with_input(BenchmarkId::new("emb_dim", emb_dim), &p, |b, p| {
            b.iter(|| lyap_r(black_box(&x), p).expect("lyap_r"))
        });
    }
    g.finish();
}

fn bench_scaling(c: &mut Criterion) {
    let full = lorenz_x(1_000_000);
    let mut g = c.benchmark_group("lyap_r_scaling_emb5");
    g.sample_size(10);
    for n in [10_000usize, 30_000, 100_000, 300_000, 1_000_000] {
        let x = &full[..n];
        let p = params(5);
        g.bench_with_input(BenchmarkId::from_parameter(n), &p, |b, p| {
            b.iter(|| lyap_r(black_box(x), p).expect("lyap_r"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench_n10k, bench_scaling);
criterion_main!(benches);
