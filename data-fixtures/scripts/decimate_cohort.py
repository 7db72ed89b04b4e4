#!/usr/bin/env python3
"""Decimate a simulated cohort (`ldh simulate` output) by an integer factor, as a device would.

Usage: decimate_cohort.py SRC DST K [point]

Each subject's left.csv / right.csv (the default `ldh` format: time_s, acc_x..z in g,
gyro_x..z in deg/s) is reduced to every K-th sample. By default each output sample is the mean
of the K input samples centred on it (a boxcar anti-aliasing filter, what an averaging or
oversampling device delivers); with `point`, the K-th sample itself (point sampling, what
`ldh simulate --rate-hz` writes at a low rate). truth.json keeps its events and strides (times
in s) and gets every K-th sample of its per-sample angle traces and the new rate, so `ldh
evaluate --truth DST` scores it. Used for docs/accuracy.md "Sampling rate" (simulate at
1000 Hz, decimate by 20 to 50 Hz). Needs numpy (tested with numpy 2.4.6).
"""
import json
import os
import shutil
import sys

import numpy as np

HEADER = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n"


def decimate(a, k, point):
    """Rows of `a` (time first) at every k-th sample: the sample itself or a centred mean."""
    out = []
    for j in range(len(a) // k):
        lo, hi = max(0, j * k - k // 2), min(len(a), j * k + k // 2)
        row = a[j * k, 1:] if point else a[lo:hi, 1:].mean(axis=0)
        out.append([a[j * k, 0], *row])
    return np.array(out)


def main():
    src, dst, k = sys.argv[1], sys.argv[2], int(sys.argv[3])
    point = len(sys.argv) > 4 and sys.argv[4] == "point"
    os.makedirs(dst, exist_ok=True)
    shutil.copy(os.path.join(src, "manifest.csv"), dst)
    for s in sorted(os.listdir(src)):
        d = os.path.join(src, s)
        if not os.path.isfile(os.path.join(d, "truth.json")):
            continue
        os.makedirs(os.path.join(dst, s), exist_ok=True)
        for side in ("left", "right"):
            a = np.loadtxt(os.path.join(d, side + ".csv"), delimiter=",", skiprows=1)
            with open(os.path.join(dst, s, side + ".csv"), "w") as f:
                f.write(HEADER)
                for r in decimate(a, k, point):
                    f.write("%.4f,%.5f,%.5f,%.5f,%.3f,%.3f,%.3f\n" % tuple(r))
        t = json.load(open(os.path.join(d, "truth.json")))
        t["fs_hz"] = t["fs_hz"] / k
        for side in ("left", "right"):
            for key in ("pitch_deg", "roll_deg", "yaw_deg"):
                t[side][key] = t[side][key][::k]
        json.dump(t, open(os.path.join(dst, s, "truth.json"), "w"))


if __name__ == "__main__":
    main()
