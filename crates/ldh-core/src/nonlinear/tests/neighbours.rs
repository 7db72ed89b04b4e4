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
        let fast = nearest_outside_window(&pts, dim, w);
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
    let nb = nearest_outside_window(&pts, 1, 3);
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
