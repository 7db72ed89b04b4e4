#!/usr/bin/env python3
"""`ldh analyze --jobs 2` against `--jobs 1` (issue 17 item 5), whole processes, interleaved.

Simulates a cohort (35 subjects x 30 s, seed 7, unless --cohort is given), then runs
`ldh analyze COHORT --jobs 1` and `--jobs 2` for every binary given, round after round (so load
changes hit every variant alike), and prints the 10th / 25th / 50th percentile of the wall time
(Python `time.perf_counter` around each process) and their ratios. On these 2-vCPU machines a
0.13 s process on both cores is hit by any other activity, which a one-core run absorbs on the
idle core: the lower percentiles show what the program does, the median what the machine did.

    python3 data-fixtures/scripts/bench_jobs.py [--rounds 30] [--cohort DIR] BINARY [BINARY ...]

Results: docs/benchmarks.md "Night main (2026-11-26 00:25)". Needs numpy.
"""
import argparse
import os
import shutil
import subprocess
import tempfile
import time

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binaries", nargs="+", help="ldh binaries to compare")
    ap.add_argument("--rounds", type=int, default=30)
    ap.add_argument("--cohort", help="an existing cohort folder (default: simulate one)")
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="ldh-jobs-")
    try:
        cohort = args.cohort or os.path.join(tmp, "cohort")
        if not args.cohort:
            subprocess.run([args.binaries[0], "simulate", "--out", cohort, "--healthy", "17",
                            "--ldh", "18", "--seconds", "30", "--seed", "7", "-q"], check=True)
        out = os.path.join(tmp, "out")
        env = dict(os.environ, RAYON_NUM_THREADS="1")
        times = {(b, j): [] for b in args.binaries for j in (1, 2)}
        for _ in range(args.rounds):
            for b in args.binaries:
                for j in (1, 2):
                    shutil.rmtree(out, ignore_errors=True)
                    t = time.perf_counter()
                    subprocess.run([b, "analyze", cohort, "--out", out, "-q", "--jobs", str(j)],
                                   check=True, env=env)
                    times[(b, j)].append(time.perf_counter() - t)
        q = [10, 25, 50]
        print("| binary | --jobs 1 p10 / p25 / median (s) | --jobs 2 | ratio p10 / p25 / median |")
        print("|---|---|---|---|")
        for b in args.binaries:
            one, two = np.percentile(times[(b, 1)], q), np.percentile(times[(b, 2)], q)
            fmt = lambda v, f: " / ".join(f.format(x) for x in v)
            print(f"| {b} | {fmt(one, '{:.4f}')} | {fmt(two, '{:.4f}')} | "
                  f"{fmt(one / two, '{:.2f}')} |")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
