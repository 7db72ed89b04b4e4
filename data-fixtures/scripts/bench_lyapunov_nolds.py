#!/usr/bin/env python3
"""Time nolds.lyap_r on the series and parameters of the Rust criterion bench
(crates/ldh-core/benches/lyapunov.rs), for the speed table in docs/lyapunov.md.

Series: x coordinate of the Lorenz system (sigma=10, rho=28, beta=8/3), RK4
with dt=0.01, 1000-step transient, start (1, 1, 1) -- the same arithmetic as
the Rust bench. Parameters: lag=10, min_tsep=50, trajectory_len=20, tau=0.01,
fit="poly", emb_dim 5 and 10.

nolds builds the full n x n distance matrix (n=10000: 800 MB, ~1.6 GB peak).

    pip install "nolds==0.6.2" "setuptools<81" numpy scipy scikit-learn
    python3 data-fixtures/scripts/bench_lyapunov_nolds.py [--sizes 1000,2000,5000,10000] [--repeats 3]
"""
import argparse
import json
import platform
import statistics
import time
import warnings

import numpy as np
import nolds


def lorenz_x(n, dt=0.01, transient=1000, sigma=10.0, rho=28.0, beta=8.0 / 3.0):
    # scalar arithmetic in the same order as the Rust bench
    s = [1.0, 1.0, 1.0]

    def f(s):
        return [sigma * (s[1] - s[0]), s[0] * (rho - s[2]) - s[1], s[0] * s[1] - beta * s[2]]

    def add(a, b, h):
        return [a[0] + h * b[0], a[1] + h * b[1], a[2] + h * b[2]]

    out = []
    for i in range(n + transient):
        k1 = f(s)
        k2 = f(add(s, k1, 0.5 * dt))
        k3 = f(add(s, k2, 0.5 * dt))
        k4 = f(add(s, k3, dt))
        s = [s[d] + dt / 6.0 * (k1[d] + 2.0 * k2[d] + 2.0 * k3[d] + k4[d]) for d in range(3)]
        if i >= transient:
            out.append(s[0])
    return np.array(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1000,2000,5000,10000")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    full = lorenz_x(max(sizes))
    rows = []
    for emb_dim in (5, 10):
        for n in sizes:
            x = full[:n]
            times = []
            le = None
            for _ in range(args.repeats):
                t0 = time.perf_counter()
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    le = nolds.lyap_r(x, emb_dim=emb_dim, lag=10, min_tsep=50,
                                      trajectory_len=20, tau=0.01, fit="poly")
                times.append(time.perf_counter() - t0)
            med = statistics.median(times)
            rows.append({"emb_dim": emb_dim, "n": n, "median_s": med,
                         "times_s": times, "lyap": le})
            print("emb_dim={:2d} n={:6d} median {:9.4f} s  (runs: {})  lyap={!r}".format(
                emb_dim, n, med, ", ".join("{:.4f}".format(t) for t in times), le),
                flush=True)
    print(json.dumps({
        "python": platform.python_version(), "numpy": np.__version__,
        "nolds": "0.6.2", "results": rows}))


if __name__ == "__main__":
    main()
