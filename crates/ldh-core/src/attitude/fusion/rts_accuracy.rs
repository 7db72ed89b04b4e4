//! How close the smoother's RTS correction C (x̂ₛ − x̂ₚ), C = P Fᵀ P_pred⁻¹, is to exact
//! arithmetic on real recordings (HuGaDB, when present): the shipped Cholesky solve
//! ([`rts_step`]) and the explicit LU inverse it replaced, against a reference that solves
//! P_pred y = x̂ₛ − x̂ₚ by iterative refinement with the residual accumulated in double-double
//! (fma two-product, two-sum) — the f64-rounded solution of the stored P_pred whenever P_pred
//! is not numerically singular. The test also holds that the legs where it is singular (the
//! smoothed angles then depend on rounding) are exactly the legs whose gyroscope the quality
//! checks reject, so no reported angle comes from an undetermined smoother.

use super::bank::Bank;
use super::products::lu_inverse;
use super::rts::{rts_step, times_ft_dense};
use super::{predict, weighted, wrap, Model, SinCos, M5, V5};
use crate::align::{align, AlignParams};
use crate::attitude::AttitudeParams;
use crate::io::{read_recording, FormatSpec, ReadParams};
use crate::preprocess::{preprocess, PreprocessParams};

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// b − A y, each row summed in double-double.
fn residual(a: &M5, y: &V5, b: &V5) -> V5 {
    let mut r = V5::zeros();
    for i in 0..5 {
        let (mut hi, mut lo) = (b[i], 0.0);
        for j in 0..5 {
            let p = -a[(i, j)] * y[j];
            let pe = (-a[(i, j)]).mul_add(y[j], -p);
            let (s, e) = two_sum(hi, p);
            hi = s;
            lo += e + pe;
        }
        r[i] = hi + lo;
    }
    r
}

fn reference_solve(a: &M5, inv: &M5, b: &V5) -> V5 {
    let mut y = inv * b;
    for _ in 0..4 {
        let r = residual(a, &y, b);
        y += inv * r;
    }
    y
}

#[derive(Clone, Copy)]
enum Method {
    /// The explicit inverse and gain (shipped until 2026-11-25).
    Inverse,
    /// The shipped step ([`rts_step`]: Cholesky solve).
    Shipped,
    /// The solve refined in double-double.
    Reference,
}

struct Step {
    x: V5,
    sc: SinCos,
    p: M5,
}

/// The smoothed angles (deg, [roll, pitch, yaw] per sample) with one method, and the worst
/// 1-norm condition number seen.
fn smooth_with(
    m: &Model,
    steps: &[Vec<Step>],
    ws: &[Vec<f64>],
    method: Method,
) -> (Vec<[f64; 3]>, f64) {
    let n = steps.len();
    let mut next: Vec<V5> = steps[n - 1].iter().map(|s| s.x).collect();
    let mut out = vec![[0.0; 3]; n];
    let mut worst_cond: f64 = 0.0;
    let set = |out: &mut Vec<[f64; 3]>, k: usize, x: &V5| {
        out[k] = [x[0].to_degrees(), x[1].to_degrees(), x[2].to_degrees()];
    };
    set(
        &mut out,
        n - 1,
        &weighted(next.len(), |i| next[i], &ws[n - 1]),
    );
    for k in (0..n - 1).rev() {
        let wm = m.w_mid(k + 1);
        for (xs, f) in next.iter_mut().zip(&steps[k]) {
            let (xp, pp, fj) = predict(&f.x, &f.sc, &f.p, &wm, m.dt, &m.q);
            let Some(inv) = lu_inverse(&pp) else {
                *xs = f.x;
                continue;
            };
            let cond = pp.abs().column_sum().max() * inv.abs().column_sum().max();
            worst_cond = worst_cond.max(cond);
            let mut diff = *xs - xp;
            diff[2] = wrap(diff[2]);
            *xs = match method {
                Method::Inverse => f.x + (times_ft_dense(&f.p, &fj) * inv) * diff,
                Method::Shipped => rts_step(&f.x, &f.sc, &f.p, xs, &wm, m),
                Method::Reference => f.x + f.p * fj.tr_mul(&reference_solve(&pp, &inv, &diff)),
            };
        }
        set(&mut out, k, &weighted(next.len(), |i| next[i], &ws[k]));
    }
    (out, worst_cond)
}

fn worst(a: &[[f64; 3]], b: &[[f64; 3]]) -> [f64; 3] {
    let mut w = [0.0f64; 3];
    for (x, y) in a.iter().zip(b) {
        for c in 0..3 {
            let mut d = (x[c] - y[c]).abs();
            if c == 2 {
                d = d.min(360.0 - d);
            }
            w[c] = w[c].max(d);
        }
    }
    w
}

/// Condition number (1-norm) of P_pred above which the smoothed angles are not determined
/// beyond rounding; HuGaDB's legs are either below 5e5 or above 4e15.
const SINGULAR_COND: f64 = 1e12;

#[test]
fn the_smoother_is_exact_on_every_hugadb_leg_whose_gyroscope_is_accepted() {
    let Some(dir) = crate::pipeline::quality::tests::hugadb::hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    let rp = ReadParams::default().check().unwrap();
    let p = AttitudeParams::default();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "txt"))
        .collect();
    files.sort();
    let mut legs = 0;
    for path in files {
        for side in ["left", "right"] {
            legs += 1;
            let spec = FormatSpec::builtin(&format!("hugadb-{side}-shank")).unwrap();
            let rec = read_recording(&path, Some(&spec), &rp).unwrap().0;
            let pre =
                preprocess(&rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
            let al = align(&pre, &AlignParams::default().check().unwrap()).unwrap();
            let m = Model::new(&al, &p);
            let mut bank = Bank::new(&m);
            let n = al.acc_g[0].len();
            let mut steps = Vec::with_capacity(n);
            let mut ws = Vec::with_capacity(n);
            for k in 0..n {
                bank.step(&m, k);
                steps.push(
                    (0..bank.len())
                        .map(|i| {
                            let (x, sc, p) = bank.filter(i);
                            Step { x, sc, p }
                        })
                        .collect::<Vec<_>>(),
                );
                ws.push(bank.weights.clone());
            }
            let (r, cond) = smooth_with(&m, &steps, &ws, Method::Reference);
            let (i, _) = smooth_with(&m, &steps, &ws, Method::Inverse);
            let (c, _) = smooth_with(&m, &steps, &ws, Method::Shipped);
            let (ei, ec) = (worst(&i, &r), worst(&c, &r));
            let name = path.file_name().unwrap().to_string_lossy().to_string();
            println!(
                "{name:36} {side:5} cond {cond:9.2e}  |inverse − ref| roll/pitch/yaw {:.1e} {:.1e} {:.1e} deg  |shipped − ref| {:.1e} {:.1e} {:.1e} deg",
                ei[0], ei[1], ei[2], ec[0], ec[1], ec[2]
            );
            let gyro_fault = crate::pipeline::quality::sensor_checks(&rec).gyro_fault;
            assert_eq!(
                gyro_fault,
                cond > SINGULAR_COND,
                "{name} {side}: condition {cond:e}, gyroscope rejected: {gyro_fault}"
            );
            if !gyro_fault {
                assert!(
                    ec.iter().chain(&ei).all(|e| *e < 1e-8),
                    "{name} {side}: {ec:?} {ei:?}"
                );
            }
        }
    }
    assert!(legs >= 10, "{legs} HuGaDB legs");
}
