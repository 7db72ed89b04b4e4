#!/usr/bin/env python3
"""Per-recording analysis from Python: the ldh wheel vs the same steps in numpy/scipy.

Both read each recording of the demo cohort from its CSV and run preprocessing, alignment, the
attitude filter bank, events, strides and per-side parameters (no Lyapunov exponent). The
numpy/scipy version is the port in bench_pipeline_python.py (both of its filter-bank idioms);
ldh is called through its Python API (`ldh.read_recording` + `ldh.analyze_recording`).
Medians of the per-recording time over all recordings and repeats, in one process.

Needs the wheel installed (`pip install ./crates/ldh-py`). Run from the repository root:
    python3 data-fixtures/scripts/bench_python_api.py [--repeats 5]
"""
import argparse
import os
import platform
import statistics
import sys
import tempfile
import time

import numpy as np
import scipy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_pipeline_python as port  # noqa: E402

import ldh  # noqa: E402


def ldh_leg(path, side, h):
    rec, _ = ldh.read_recording(path)
    out = ldh.analyze_recording(
        [rec["acc_x_g"], rec["acc_y_g"], rec["acc_z_g"]],
        [rec["gyro_x_dps"], rec["gyro_y_dps"], rec["gyro_z_dps"]],
        rec["fs_hz"], side=side, sensor_height_m=h, compute_sta=False,
    )
    return out["parameters"]


def timed(fn, legs, repeats):
    per = []
    for _ in range(repeats):
        for sid, side, path, h in legs:
            t = time.perf_counter()
            fn(path, side, h)
            per.append(time.perf_counter() - t)
    return statistics.median(per), per


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    a = ap.parse_args()
    data = tempfile.mkdtemp(prefix="ldh-api-bench-")
    ldh.write_demo(data)
    legs = [(sid, side, path, h) for sid, ls, h in port.find_recordings(data) for side, path in ls]
    # Same answer first: mean stride time and stride length per recording.
    for sid, side, path, h in legs[:2]:
        p = ldh_leg(path, side, h)
        st, _ = port.analyze_leg(path, side, h)
        ref = port.side_parameters(st)
        print(f"{sid}/{side}: stride time {p['stride_time_s']:.4f} vs {ref['stride_time_s']:.4f} s, "
              f"stride length {p['stride_length_m']:.4f} vs {ref['stride_length_m']:.4f} m")
    t_ldh, _ = timed(ldh_leg, legs, a.repeats)
    t_loop, _ = timed(lambda p, s, h: port.analyze_leg(p, s, h, "loop"), legs, a.repeats)
    t_bank, _ = timed(lambda p, s, h: port.analyze_leg(p, s, h, "bank"), legs, a.repeats)
    print(f"\n| per recording, median of {a.repeats} x {len(legs)} | time | ldh is faster by |")
    print("|---|---:|---:|")
    print(f"| numpy/scipy, EKF bank as a per-filter loop | {t_loop * 1e3:.1f} ms | {t_loop / t_ldh:.0f}x |")
    print(f"| numpy/scipy, EKF bank stacked | {t_bank * 1e3:.1f} ms | {t_bank / t_ldh:.0f}x |")
    print(f"| ldh from Python (read_recording + analyze_recording) | {t_ldh * 1e3:.2f} ms | |")
    print(f"\npython {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
          f"ldh {ldh.__version__}; load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
