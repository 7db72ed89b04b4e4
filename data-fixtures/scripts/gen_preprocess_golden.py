#!/usr/bin/env python3
"""Golden values for ldh's preprocessing (paper §3.1), computed with numpy and scipy.

Run from the repository root:  python3 data-fixtures/scripts/gen_preprocess_golden.py
Writes data-fixtures/golden/preprocess/{input.csv,expected.json}. Deterministic.

Steps reproduced (see crates/ldh-core/src/preprocess/):
  1. magnitude of the acceleration (eq. 1);
  2. outliers: |norm - mean| > 3 * std (numpy std, ddof=0); those samples are replaced by
     numpy.interp over the remaining samples, on all six channels ("filtered", the paper read
     literally) and on the three acceleration channels only ("filtered_acc_outliers_only", ldh's
     default);
  3. scipy.signal.butter(4, 10, output="sos", fs=fs) and scipy.signal.sosfiltfilt on each channel.
Plus bare sosfiltfilt cases (orders 2, 4, 6; several cut-offs) on white noise.
"""
import json
import platform
from pathlib import Path

import numpy as np
import scipy
from scipy import signal

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "data-fixtures" / "golden" / "preprocess"
SRC = ROOT / "data-fixtures" / "cohort" / "L02" / "right.csv"
N = 800  # 8 s at 100 Hz keeps the files small


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    raw = np.genfromtxt(SRC, delimiter=",", names=True)[:N]
    cols = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"]
    data = np.vstack([raw[c] for c in cols]).astype(float)
    t = raw["time_s"].astype(float)
    # Inject artefacts that the 3-SD rule must catch: a two-sample knock and a single spike.
    data[1, 300] += 4.0
    data[1, 301] += 3.5
    data[0, 611] -= 3.0
    data[5, 300] += 500.0
    lines = ["time_s," + ",".join(cols)]
    for i in range(N):
        lines.append(f"{t[i]:.4f}," + ",".join(f"{data[k, i]:.6f}" for k in range(6)))
    (OUT / "input.csv").write_text("\n".join(lines) + "\n")
    # Re-read exactly what the Rust reader will see (6 decimals).
    rd = np.genfromtxt(OUT / "input.csv", delimiter=",", names=True)
    x = np.vstack([rd[c] for c in cols]).astype(float)
    tt = rd["time_s"].astype(float)
    fs = 1.0 / np.polyfit(np.arange(len(tt)), tt, 1)[0]

    norm = np.sqrt(x[0] ** 2 + x[1] ** 2 + x[2] ** 2)
    mean, sd = norm.mean(), norm.std()
    bad = np.flatnonzero(np.abs(norm - mean) > 3.0 * sd)
    good = np.setdiff1d(np.arange(N), bad)
    y = np.array([np.interp(np.arange(N), good, ch[good]) for ch in x])
    sos = signal.butter(4, 10.0, output="sos", fs=fs)
    filt = np.array([signal.sosfiltfilt(sos, ch) for ch in y])
    y_acc = np.vstack([y[:3], x[3:]])
    filt_acc = np.array([signal.sosfiltfilt(sos, ch) for ch in y_acc])

    rng = np.random.default_rng(20261121)
    noise = rng.standard_normal(300)
    cases = []
    for order, cutoff, rate in [(2, 5.0, 100.0), (4, 10.0, 100.0), (6, 20.0, 200.0), (4, 3.0, 50.0)]:
        s = signal.butter(order, cutoff, output="sos", fs=rate)
        cases.append({"order": order, "cutoff_hz": cutoff, "fs_hz": rate,
                      "sos": s.tolist(), "y": signal.sosfiltfilt(s, noise).tolist()})

    expected = {
        "versions": {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__},
        "source": str(SRC.relative_to(ROOT)),
        "fs_hz": fs,
        "norm_mean_g": mean,
        "norm_sd_g": sd,
        "outliers": bad.tolist(),
        "sos": sos.tolist(),
        "filtered": {c: filt[k].tolist() for k, c in enumerate(cols)},
        "filtered_acc_outliers_only": {c: filt_acc[k].tolist() for k, c in enumerate(cols)},
        "filtered_norm_g": np.sqrt(filt[0] ** 2 + filt[1] ** 2 + filt[2] ** 2).tolist(),
        "noise": noise.tolist(),
        "sosfiltfilt_cases": cases,
    }
    (OUT / "expected.json").write_text(json.dumps(expected))
    print(f"outliers {bad.tolist()}, fs {fs}, wrote {OUT}")


if __name__ == "__main__":
    main()
