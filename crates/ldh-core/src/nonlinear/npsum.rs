//! Sums in numpy's order, so that ldh's sums equal numpy's bit for bit (nolds parity,
//! docs/lyapunov.md): the neighbour searches, the divergence curves and the spectra all add
//! through these. Shared by `neighbours` and `window_tree`, below both.

/// Sum in numpy's order (`pairwise_sum` of `numpy/_core/src/umath/loops_utils.h`):
/// plain loop below 8 elements, eight interleaved accumulators up to 128, and a
/// recursive split above. Used so that sums match numpy bit for bit (hand
/// written: no crate reproduces numpy's summation order).
pub(crate) fn np_sum(a: &[f64]) -> f64 {
    let n = a.len();
    if n < 8 {
        let mut res = 0.0;
        for &v in a {
            res += v;
        }
        res
    } else if n <= 128 {
        let (blocks, rest) = a.split_at(n - n % 8);
        let (first, blocks) = blocks.split_at(8);
        let mut r = [0.0f64; 8];
        r.copy_from_slice(first);
        // eight accumulators, each summing every eighth element in order (vectorised)
        for b in blocks.chunks_exact(8) {
            for (acc, &v) in r.iter_mut().zip(b) {
                *acc += v;
            }
        }
        let mut res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
        for &v in rest {
            res += v;
        }
        res
    } else {
        let mut n2 = n / 2;
        n2 -= n2 % 8;
        np_sum(&a[..n2]) + np_sum(&a[n2..])
    }
}

/// [`np_sum`] of the rows `get(start)`, `get(start + 1)`, …, `get(start + n − 1)` (each of
/// `out.len()` values), lane by lane into `out`: `out[k]` has the bits of `np_sum` over the
/// values `get(i)[k]`, in the same order (every lane goes through the same additions), without
/// gathering a lane's values first. A row is read once for all lanes, so the additions run
/// along contiguous memory (vectorised) instead of one gathered value at a time per lane.
pub(crate) fn np_sum_rows<'a>(
    start: usize,
    n: usize,
    get: &impl Fn(usize) -> &'a [f64],
    out: &mut [f64],
) {
    let t = out.len();
    if n < 8 {
        out.fill(0.0);
        for i in start..start + n {
            for (o, &v) in out.iter_mut().zip(get(i)) {
                *o += v;
            }
        }
    } else if n <= 128 {
        // eight accumulator rows, each summing every eighth row in order
        let mut r = vec![0.0f64; 8 * t];
        for (j, acc) in r.chunks_exact_mut(t).enumerate() {
            acc.copy_from_slice(&get(start + j)[..t]);
        }
        let full = start + n - n % 8;
        let mut i = start + 8;
        while i < full {
            for (j, acc) in r.chunks_exact_mut(t).enumerate() {
                for (a, &v) in acc.iter_mut().zip(get(i + j)) {
                    *a += v;
                }
            }
            i += 8;
        }
        let r: Vec<&[f64]> = r.chunks_exact(t).collect();
        for (k, o) in out.iter_mut().enumerate() {
            *o = ((r[0][k] + r[1][k]) + (r[2][k] + r[3][k]))
                + ((r[4][k] + r[5][k]) + (r[6][k] + r[7][k]));
        }
        for i in full..start + n {
            for (o, &v) in out.iter_mut().zip(get(i)) {
                *o += v;
            }
        }
    } else {
        let mut n2 = n / 2;
        n2 -= n2 % 8;
        let mut right = vec![0.0f64; t];
        np_sum_rows(start, n2, get, out);
        np_sum_rows(start + n2, n - n2, get, &mut right);
        for (o, r) in out.iter_mut().zip(&right) {
            *o += r;
        }
    }
}
