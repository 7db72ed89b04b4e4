//! The neighbour search (k-d tree == brute force, ties) and numpy's summation order.

use crate::nonlinear::neighbours::{
    cheb_brute, chebyshev_neighbourhoods, nearest_outside_window, nn_brute,
};
use proptest::prelude::*;

/// Random points, optionally quantised to one decimal so that exact ties occur.
fn points_strategy() -> impl Strategy<Value = (Vec<f64>, usize, usize)> {
    (1usize..=12, 2usize..160, any::<bool>(), any::<u64>()).prop_flat_map(
        |(dim, n, quantise, _)| {
            let max_tsep = (n - 2) / 2;
            (
                proptest::collection::vec(-5.0f64..5.0, n * dim).prop_map(move |v| {
                    if quantise {
                        v.into_iter().map(|x| (x * 2.0).round() / 2.0).collect()
                    } else {
                        v
                    }
                }),
                Just(dim),
                0usize..=max_tsep,
            )
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn euclidean_theiler_nn_equals_brute_force((pts, dim, w) in points_strategy()) {
        let fast = nearest_outside_window(&pts, dim, w, None);
        let slow = nn_brute(&pts, dim, w);
        prop_assert_eq!(fast, slow);
    }

    #[test]
    fn chebyshev_neighbourhoods_equal_brute_force(
        (pts, dim, w) in points_strategy(),
        min_nb in 1usize..12,
    ) {
        let fast = chebyshev_neighbourhoods(&pts, dim, w, min_nb);
        let slow = cheb_brute(&pts, dim, w, min_nb);
        prop_assert_eq!(fast, slow);
    }
}

#[test]
fn neighbour_ties_take_the_lowest_index() {
    // 1-D points 0, 1, 0, 1, 0, 1 ...: every point has many neighbours at
    // distance 0; np.argmin picks the lowest index outside the window.
    let pts: Vec<f64> = (0..40).map(|i| (i % 2) as f64).collect();
    let nb = nearest_outside_window(&pts, 1, 3, None);
    for (i, &j) in nb.iter().enumerate() {
        let expect = (0..40usize)
            .find(|&j| j.abs_diff(i) > 3 && j % 2 == i % 2)
            .unwrap();
        assert_eq!(j, expect, "row {i}");
    }
}

#[test]
fn numpy_summation_order() {
    use crate::nonlinear::neighbours::np_sum;
    // below 8 elements: left to right
    assert_eq!(np_sum(&[1e16, 1.0, -1e16]), 0.0);
    // 8..=128: eight interleaved accumulators -> 1.0 survives here
    let mut v = vec![0.0; 9];
    v[0] = 1e16;
    v[1] = -1e16;
    v[8] = 1.0;
    assert_eq!(np_sum(&v), 1.0);
    let big: Vec<f64> = (0..1000).map(|i| i as f64).collect();
    assert_eq!(np_sum(&big), 499_500.0);
}

/// Row-wise numpy sums equal `np_sum` of each lane bit for bit, across the plain loop (< 8
/// rows), the eight accumulators (≤ 128) and the recursive split, from any start row.
#[test]
fn row_sums_equal_numpy_sums_of_each_lane() {
    use crate::nonlinear::neighbours::{np_sum, np_sum_rows};
    let lanes = 5;
    // values of very different magnitudes, so that any change of order changes the bits
    let rows: Vec<Vec<f64>> = (0..3000)
        .map(|i| {
            (0..lanes)
                .map(|k| ((i * 7 + k * 13) as f64 * 0.37).sin() * 10f64.powi((i % 7) as i32 * 3))
                .collect()
        })
        .collect();
    for (start, n) in [
        (0, 0),
        (3, 1),
        (0, 7),
        (5, 8),
        (0, 9),
        (2, 128),
        (0, 129),
        (11, 2898),
    ] {
        let mut out = vec![f64::NAN; lanes];
        np_sum_rows(start, n, &|i| &rows[i][..], &mut out);
        for (k, &o) in out.iter().enumerate() {
            let lane: Vec<f64> = (start..start + n).map(|i| rows[i][k]).collect();
            assert_eq!(
                o.to_bits(),
                np_sum(&lane).to_bits(),
                "start {start}, n {n}, lane {k}"
            );
        }
    }
}

/// A noisy two-harmonic loop (a trajectory, like gait: the rows' neighbours are shifted copies
/// of each other), quantised when asked so that exact ties occur.
fn trajectory(n: usize, seed: u64, quantise: bool) -> Vec<f64> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let t = i as f64 / 37.0;
            let tau = std::f64::consts::TAU;
            let v = (tau * t).sin() + 0.4 * (2.0 * tau * t + 0.3).cos() + 0.05 * rng.gen::<f64>();
            if quantise {
                (v * 16.0).round() / 16.0
            } else {
                v
            }
        })
        .collect()
}

/// The delay embedding of `x` in `d` dimensions, first `rows` rows, row-major.
fn embed_rows(x: &[f64], lag: usize, d: usize, rows: usize) -> Vec<f64> {
    (0..rows)
        .flat_map(|i| (0..d).map(move |c| x[i + c * lag]))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// One tree over `k` delay coordinates answers every query over its first `d ≤ k`
    /// coordinates and first `limit` rows as the brute-force scan does (windows, ties, the
    /// rows past the series' end NaN, arbitrary hints, the answers of a wider search taken where
    /// admitted), as false nearest neighbours and Rosenstein's method use it.
    #[test]
    fn delay_index_prefix_queries_equal_brute_force(
        n in 150usize..700,
        seed in any::<u64>(),
        quantise in any::<bool>(),
        lag in 1usize..12,
        k in 1usize..=7,
        d_off in 0usize..7,
        w_frac in 0.0f64..0.3,
        cut in 0usize..40,
        hint_seed in any::<u64>(),
    ) {
        let d = 1 + d_off % k;
        let x = trajectory(n, seed, quantise);
        // as false nearest neighbours: rows with a coordinate d·lag further on
        let rows = n - d * lag;
        let limit = rows.saturating_sub(cut).max(2);
        let w = ((limit as f64 * w_frac) as usize).min((limit - 2) / 2);
        let order = crate::nonlinear::neighbours::total_order(&x);
        let index = crate::nonlinear::neighbours::delay_index(&x, lag, k, rows, &order).unwrap();
        let hint: Vec<usize> = (0..limit)
            .map(|i| (i as u64 ^ hint_seed).wrapping_mul(2654435761) as usize % (2 * n))
            .collect();
        let fast = index.nearest_all(d, w, limit, Some(&hint), None);
        let slow = nn_brute(&embed_rows(&x, lag, d, limit), d, w);
        prop_assert_eq!(&fast, &slow);
        // with the answers of a wider search (a narrower window, all rows) taken where admitted
        let known = index.nearest_all(d, w / 3, rows, None, None);
        let reused = index.nearest_all(d, w, limit, Some(&hint), Some(&known));
        prop_assert_eq!(reused, slow);
    }
}

/// One dimension with only the row itself excluded (false nearest neighbours' first step) is
/// a sorted walk: equal to the brute-force scan, ties to the lowest index included.
#[test]
fn sorted_one_dimensional_search_equals_brute_force() {
    for (seed, quantise) in [(1, false), (2, true), (3, true)] {
        let x = trajectory(1_500, seed, quantise);
        assert_eq!(
            nearest_outside_window(&x, 1, 0, None),
            nn_brute(&x, 1, 0),
            "seed {seed}"
        );
    }
    let steps: Vec<f64> = (0..300).map(|i| (i / 7) as f64).collect();
    assert_eq!(
        nearest_outside_window(&steps, 1, 0, None),
        nn_brute(&steps, 1, 0)
    );
}

/// Above the size searched on the calling thread the rows are searched in parallel chunks
/// (each chunk's first row unseeded): the same answers as a brute-force scan, checked on
/// every 97th row of a 20 000-row orbit, whatever the number of threads.
#[test]
fn parallel_chunks_equal_brute_force() {
    let x = trajectory(20_100, 9, true);
    let pts = embed_rows(&x, 9, 3, 20_000);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| nearest_outside_window(&pts, 3, 40, None))
    };
    let (one, three) = (run(1), run(3));
    assert_eq!(one, three);
    for i in (0..20_000).step_by(97) {
        let q = &pts[i * 3..i * 3 + 3];
        let want = (0..20_000)
            .filter(|j: &usize| j.abs_diff(i) > 40)
            .map(|j| {
                (
                    crate::nonlinear::neighbours::np_euclidean(q, &pts[j * 3..j * 3 + 3]),
                    j,
                )
            })
            .fold(
                (f64::INFINITY, usize::MAX),
                |b, c| if c.0 < b.0 { c } else { b },
            );
        assert_eq!(one[i], want.1, "row {i}");
    }
}
