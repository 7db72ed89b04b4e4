#!/usr/bin/env python3
"""Generate the golden files for the Rust `nonlinear` (Lyapunov exponent) module.

Every series is generated deterministically here and written *into* the JSON,
so the Rust tests never regenerate anything. Reference values come from
nolds 0.6.2 with explicit parameters and ``fit="poly"`` (no RANSAC, no
randomness).

Setup (nolds 0.6.3 fails to import on Python 3.11; 0.6.2 needs pkg_resources):

    pip install "nolds==0.6.2" "setuptools<81" numpy scipy scikit-learn

Run from the repository root:

    python3 data-fixtures/scripts/gen_lyapunov_golden.py

Output: data-fixtures/golden/lyapunov/{lorenz,logistic,noise,gait}.json
"""
import json
import os
import platform
import sys
import warnings

import numpy as np
import nolds

OUT_DIR = os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "golden", "lyapunov"
)


def lorenz_x(n, dt=0.01, transient=1000, sigma=10.0, rho=28.0, beta=8.0 / 3.0):
    """x coordinate of the Lorenz system, classic RK4, start (1, 1, 1)."""

    def f(s):
        x, y, z = s
        return np.array([sigma * (y - x), x * (rho - z) - y, x * y - beta * z])

    s = np.array([1.0, 1.0, 1.0])
    out = np.empty(n)
    for i in range(transient + n):
        k1 = f(s)
        k2 = f(s + 0.5 * dt * k1)
        k3 = f(s + 0.5 * dt * k2)
        k4 = f(s + dt * k3)
        s = s + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        if i >= transient:
            out[i - transient] = s[0]
    return out


def logistic(n, r=4.0, x0=0.1, transient=100):
    x = x0
    out = np.empty(n)
    for i in range(transient + n):
        x = r * x * (1.0 - x)
        if i >= transient:
            out[i - transient] = x
    return out


def white_noise(n, seed=20261121):
    return np.random.default_rng(seed).standard_normal(n)


def gait_like(n, fs=100.0, seed=7):
    """Sagittal angular-velocity-like signal: 1 Hz stride fundamental plus two
    harmonics, stride-to-stride period jitter (2 %) and additive noise."""
    rng = np.random.default_rng(seed)
    out = np.empty(n)
    phase = 0.0
    period = 1.0
    for i in range(n):
        out[i] = (
            2.0 * np.sin(2 * np.pi * phase)
            + 0.8 * np.sin(4 * np.pi * phase + 0.5)
            + 0.3 * np.sin(6 * np.pi * phase + 1.1)
        )
        phase += 1.0 / (fs * period)
        if phase >= 1.0:
            phase -= 1.0
            period = 1.0 + 0.02 * rng.standard_normal()
    return out + 0.05 * rng.standard_normal(n)


def run_r(data, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        le, (ks, div, poly) = nolds.lyap_r(data, fit="poly", debug_data=True, **kw)
    return {
        "params": kw,
        "lyap": float(le),
        "ks": [int(k) for k in ks],
        "div_traj": [float(v) for v in div],
        "poly": [float(p) for p in poly],
    }


def run_e(data, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        le = nolds.lyap_e(data, **kw)
    return {"params": kw, "lyap": [float(v) for v in le]}


def versions():
    return {
        "python": platform.python_version(),
        "numpy": np.__version__,
        "nolds": getattr(nolds, "__version__", None) or _dist_version("nolds"),
    }


def _dist_version(name):
    from importlib.metadata import version

    return version(name)


def main():
    os.makedirs(OUT_DIR, exist_ok=True)
    series = {
        "lorenz": (lorenz_x(2000), "Lorenz x, sigma=10 rho=28 beta=8/3, RK4 dt=0.01, 1000-step transient, start (1,1,1)"),
        "logistic": (logistic(1500), "logistic map r=4, x0=0.1, 100-iteration transient"),
        "noise": (white_noise(1500), "standard normal, numpy default_rng(20261121)"),
        "gait": (gait_like(2000), "100 Hz, 1 Hz fundamental + 2 harmonics, 2 % period jitter, noise sd 0.05, default_rng(7)"),
    }
    r_sets = {
        "lorenz": [
            dict(emb_dim=10, lag=1, min_tsep=10, trajectory_len=20),
            dict(emb_dim=5, lag=11, min_tsep=60, trajectory_len=30, tau=0.01),
            dict(emb_dim=3, lag=15, min_tsep=100, trajectory_len=50, tau=0.01, fit_offset=5),
            dict(emb_dim=10, lag=None, min_tsep=None, trajectory_len=20, tau=0.01),
        ],
        "logistic": [
            dict(emb_dim=10, lag=1, min_tsep=5, trajectory_len=10),
            dict(emb_dim=2, lag=1, min_tsep=1, trajectory_len=6),
            dict(emb_dim=4, lag=1, min_tsep=0, trajectory_len=8),
            dict(emb_dim=10, lag=None, min_tsep=None, trajectory_len=10),
        ],
        "noise": [
            dict(emb_dim=10, lag=1, min_tsep=5, trajectory_len=20),
            dict(emb_dim=5, lag=2, min_tsep=10, trajectory_len=15),
            dict(emb_dim=1, lag=1, min_tsep=3, trajectory_len=10),
        ],
        "gait": [
            dict(emb_dim=10, lag=10, min_tsep=100, trajectory_len=50, tau=0.01),
            dict(emb_dim=5, lag=25, min_tsep=100, trajectory_len=50, tau=0.01),
            dict(emb_dim=12, lag=8, min_tsep=120, trajectory_len=40, tau=0.01),
            dict(emb_dim=10, lag=None, min_tsep=None, trajectory_len=20, tau=0.01),
        ],
    }
    e_sets = {
        "lorenz": [
            dict(emb_dim=10, matrix_dim=4),
            dict(emb_dim=7, matrix_dim=3, min_nb=6, min_tsep=5, tau=0.01),
            dict(emb_dim=4, matrix_dim=2, min_nb=10, min_tsep=20),
        ],
        "logistic": [
            dict(emb_dim=10, matrix_dim=4),
            dict(emb_dim=3, matrix_dim=2, min_nb=4, min_tsep=2),
        ],
        "noise": [
            dict(emb_dim=10, matrix_dim=4),
            dict(emb_dim=5, matrix_dim=3, min_nb=8, min_tsep=3),
        ],
        "gait": [
            dict(emb_dim=10, matrix_dim=4, min_tsep=100, tau=0.01),
            dict(emb_dim=13, matrix_dim=5, min_nb=10, min_tsep=50, tau=0.01),
        ],
    }
    ver = versions()
    total = 0
    for name, (data, desc) in series.items():
        doc = {
            "description": desc,
            "generator": "data-fixtures/scripts/gen_lyapunov_golden.py",
            "versions": ver,
            "series": [float(v) for v in data],
            # exact IEEE-754 bits of the same values (serde_json's default
            # float parser is not always correctly rounded)
            "series_bits": ["{:016x}".format(int(b)) for b in np.asarray(data, dtype=np.float64).view(np.uint64)],
            "lyap_r": [run_r(data, **kw) for kw in r_sets[name]],
            "lyap_e": [run_e(data, **kw) for kw in e_sets[name]],
        }
        path = os.path.join(OUT_DIR, name + ".json")
        with open(path, "w") as fh:
            json.dump(doc, fh, separators=(",", ":"))
            fh.write("\n")
        size = os.path.getsize(path)
        total += size
        print("wrote {} ({} bytes)".format(path, size))
    print("total {} bytes; python {} numpy {} nolds {}".format(
        total, ver["python"], ver["numpy"], ver["nolds"]))
    assert total < 1_000_000, "goldens must stay below 1 MB"


if __name__ == "__main__":
    sys.exit(main())
