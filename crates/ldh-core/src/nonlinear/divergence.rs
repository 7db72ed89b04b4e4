//! The mean logarithmic divergence of Rosenstein, Collins & De Luca (1993), Physica D
//! 65:117–134, step 3 of [`super::lyap_r`]: `div[k]` = the mean over the rows `i` of
//! `ln ‖X(i + k) − X(nb[i] + k)‖`, pairs at distance 0 left out, summed in numpy's order over
//! `i` as `nolds.lyap_r` 0.6.2 does (`np.mean` of the finite logs of each step).
//!
//! Most of the cost is the distance and the logarithm of each pair. On a continuous trajectory
//! the neighbours of nearby rows are shifted copies of each other (`nb[i + t] = nb[i] + t`), and
//! then pair (i + t, k) is pair (i, k + t): every pair (a, a − o) of one offset `o = i − nb[i]`
//! is one point of a run of consecutive `a`. [`divergence`] computes each distinct pair once
//! (the runs of each offset, merged) and reads the steps from there; on a 30 s gait leg that is
//! 60 000 logarithms instead of the 162 000 pairs (81 000 with the reuse between adjacent rows
//! alone, the method before). The values and the order in which they are summed are those of
//! the direct computation, bit for bit (tested against it below).

use rayon::prelude::*;

use super::neighbours::{dispatch_dim, np_euclidean, np_sq_sum, np_sum, np_sum_rows};

/// Rows at or above which the streaming computation (parallel over rows) is used.
const PAR_ROWS: usize = 1 << 14;

/// Most distinct pairs held at once by [`divergence`] (32 MB); more use the streaming
/// computation, whose memory is three rows of logs.
const MAX_PAIRS: usize = 1 << 22;

/// `ln ‖row(a) − row(b)‖` in numpy's summation order, −∞ for a pair at distance 0 (left out).
#[inline(always)]
fn log_dist(orbit: &[f64], dim: usize, a: usize, b: usize) -> f64 {
    let d = np_euclidean(
        &orbit[a * dim..(a + 1) * dim],
        &orbit[b * dim..(b + 1) * dim],
    );
    // ln d is finite for every d > 0; −∞ marks a pair left out
    if d == 0.0 {
        f64::NEG_INFINITY
    } else {
        d.ln()
    }
}

/// The mean log divergence `div[k]`, `k = 0..trajectory_len`, of the row pairs
/// (i + k, nb[i] + k) of a row-major `m × dim` orbit (−∞ at a step where every pair is at
/// distance 0). Callers guarantee `nb.len() + trajectory_len − 1 ≤ m` and `nb[i] < nb.len()`.
pub(crate) fn divergence(
    orbit: &[f64],
    dim: usize,
    nb: &[usize],
    trajectory_len: usize,
) -> Vec<f64> {
    if nb.len() < PAR_ROWS {
        if let Some(div) = divergence_by_offset(orbit, dim, nb, trajectory_len) {
            return div;
        }
    }
    divergence_streaming(orbit, dim, nb, trajectory_len)
}

/// Mean of the finite logs of one step, in numpy's order.
fn step_mean(vals: &[f64]) -> f64 {
    if vals.is_empty() {
        f64::NEG_INFINITY
    } else {
        np_sum(vals) / vals.len() as f64
    }
}

/// Each distinct pair once: the runs of consecutive `a` of each offset, merged; `None` when
/// they hold more than [`MAX_PAIRS`] pairs.
fn divergence_by_offset(
    orbit: &[f64],
    dim: usize,
    nb: &[usize],
    trajectory_len: usize,
) -> Option<Vec<f64>> {
    let ntraj = nb.len();
    // runs (first a, end a, first b): the pairs (a, first b + (a − first a))
    let mut runs: Vec<(usize, usize, usize)> = Vec::new();
    // open run of each offset i − nb[i] (shifted by ntraj to index from 0)
    let mut open = vec![u32::MAX; 2 * ntraj];
    let mut row_run = Vec::with_capacity(ntraj);
    for (i, &j) in nb.iter().enumerate() {
        let key = i + ntraj - j;
        let r = open[key] as usize;
        // rows come in increasing order, so a run that reaches row i is the offset's last one
        if r < runs.len() && runs[r].1 >= i {
            runs[r].1 = i + trajectory_len;
        } else {
            open[key] = runs.len() as u32;
            runs.push((i, i + trajectory_len, j));
        }
        row_run.push(open[key] as usize);
    }
    let total: usize = runs.iter().map(|r| r.1 - r.0).sum();
    if total > MAX_PAIRS || runs.len() > u32::MAX as usize {
        return None;
    }
    // logs of every run, one after the other; `start[r]` = where run r begins
    let mut logs = Vec::with_capacity(total);
    let mut start = Vec::with_capacity(runs.len());
    dispatch_dim!(dim, run_logs, orbit, &runs, &mut logs, &mut start).unwrap_or_else(|| {
        for &(a0, a1, b0) in &runs {
            start.push(logs.len());
            logs.extend((a0..a1).map(|a| log_dist(orbit, dim, a, b0 + (a - a0))));
        }
    });
    // no pair at distance 0 (the rule on real signals): nothing to leave out
    let all_finite = !logs.contains(&f64::NEG_INFINITY);
    // row i's pair at step k is logs[at[i] + k]
    let at: Vec<usize> = row_run
        .iter()
        .enumerate()
        .map(|(i, &r)| start[r] + (i - runs[r].0))
        .collect();
    if all_finite {
        // summed where they lie, in the same order: row i's logs of all steps are
        // logs[at[i]..][..trajectory_len], added to the step sums together
        let mut sums = vec![0.0; trajectory_len];
        np_sum_rows(0, ntraj, &|i| &logs[at[i]..][..trajectory_len], &mut sums);
        return Some(sums.iter().map(|s| s / ntraj as f64).collect());
    }
    let mut vals = Vec::new();
    let div = (0..trajectory_len)
        .map(|k| {
            vals.clear();
            vals.extend(
                at.iter()
                    .map(|&p| logs[p + k])
                    .filter(|v| *v != f64::NEG_INFINITY),
            );
            step_mean(&vals)
        })
        .collect();
    Some(div)
}

/// The logs of the `runs` (see [`divergence_by_offset`]) for a fixed dimension `K`, appended to
/// `logs`, and where each run begins.
fn run_logs<const K: usize>(
    orbit: &[f64],
    runs: &[(usize, usize, usize)],
    logs: &mut Vec<f64>,
    start: &mut Vec<usize>,
) {
    let (rows, _) = orbit.as_chunks::<K>();
    for &(a0, a1, b0) in runs {
        start.push(logs.len());
        logs.extend(rows[a0..a1].iter().zip(&rows[b0..]).map(|(a, b)| {
            let d = np_sq_sum(a, b).sqrt();
            if d == 0.0 {
                f64::NEG_INFINITY
            } else {
                d.ln()
            }
        }));
    }
}

/// Step by step with three rows of logs, from the last step to the first: pair (i, k) is taken
/// from pair (i − 1, k + 1) when `nb[i] = nb[i − 1] + 1`, else computed (in parallel over the
/// rows from [`PAR_ROWS`] on).
fn divergence_streaming(
    orbit: &[f64],
    dim: usize,
    nb: &[usize],
    trajectory_len: usize,
) -> Vec<f64> {
    let ntraj = nb.len();
    let shifted: Vec<bool> = (0..ntraj)
        .map(|i| i > 0 && nb[i] == nb[i - 1] + 1)
        .collect();
    let mut cur = vec![0.0; ntraj];
    let mut next = vec![0.0; ntraj];
    let mut vals = Vec::with_capacity(ntraj);
    let mut div = vec![0.0; trajectory_len];
    for k in (0..trajectory_len).rev() {
        let reuse = k + 1 < trajectory_len;
        let fill = |i: usize, v: &mut f64| {
            *v = if reuse && shifted[i] {
                next[i - 1]
            } else {
                log_dist(orbit, dim, i + k, nb[i] + k)
            };
        };
        if ntraj >= PAR_ROWS {
            cur.par_iter_mut().enumerate().for_each(|(i, v)| fill(i, v));
        } else {
            cur.iter_mut().enumerate().for_each(|(i, v)| fill(i, v));
        }
        vals.clear();
        vals.extend(cur.iter().copied().filter(|v| *v != f64::NEG_INFINITY));
        div[k] = step_mean(&vals);
        std::mem::swap(&mut cur, &mut next);
    }
    div
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct computation: every pair measured, summed in numpy's order.
    fn direct(orbit: &[f64], dim: usize, nb: &[usize], t: usize) -> Vec<f64> {
        (0..t)
            .map(|k| {
                let vals: Vec<f64> = (0..nb.len())
                    .map(|i| log_dist(orbit, dim, i + k, nb[i] + k))
                    .filter(|v| *v != f64::NEG_INFINITY)
                    .collect();
                step_mean(&vals)
            })
            .collect()
    }

    /// Both computations equal the direct one bit for bit, on neighbours with long shifted runs
    /// (as on gait), random neighbours, repeated offsets, and pairs at distance 0.
    #[test]
    fn divergence_equals_the_direct_computation() {
        let (m, dim, t) = (400usize, 3usize, 25usize);
        let ntraj = m + 1 - t;
        // quantised, with a flat stretch: distance-0 pairs and −∞ steps occur; and smooth,
        // with no pair at distance 0
        let flat: Vec<f64> = (0..m * dim)
            .map(|v| {
                let s = ((v as f64) * 0.37).sin();
                if (600..700).contains(&v) {
                    0.25
                } else {
                    (s * 8.0).round() / 8.0
                }
            })
            .collect();
        let smooth: Vec<f64> = (0..m * dim)
            .map(|v| ((v as f64) * 0.37).sin() + 1e-3 * v as f64)
            .collect();
        let mut state = 12345u64;
        let mut rnd = |n: usize| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize % n
        };
        let mut shifted_runs = vec![0usize; ntraj];
        for i in 0..ntraj {
            shifted_runs[i] = if i % 37 == 0 {
                rnd(ntraj)
            } else {
                (shifted_runs[i - 1] + 1) % ntraj
            };
        }
        let random: Vec<usize> = (0..ntraj).map(|_| rnd(ntraj)).collect();
        let same_offset: Vec<usize> = (0..ntraj).map(|i| (i + 150) % ntraj).collect();
        let alternating: Vec<usize> = (0..ntraj).map(|i| (i / 3 * 3 + 200) % ntraj).collect();
        for (orbit, nb) in [&flat, &smooth]
            .into_iter()
            .flat_map(|o| [&shifted_runs, &random, &same_offset, &alternating].map(|nb| (o, nb)))
        {
            let want = direct(orbit, dim, nb, t);
            let by_offset = divergence_by_offset(orbit, dim, nb, t).unwrap();
            let streaming = divergence_streaming(orbit, dim, nb, t);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&by_offset), bits(&want));
            assert_eq!(bits(&streaming), bits(&want));
            assert_eq!(bits(&divergence(orbit, dim, nb, t)), bits(&want));
        }
    }
}
