#!/usr/bin/env python3
"""Python peer of ldh's per-recording gait pipeline, timed against ldh in the same session.

What it is: the steps `ldh analyze --no-sta` runs on one shank recording, written the way a
scientist would write them with numpy/scipy (pandas for the CSV), ported from the Rust sources
with the same algorithms and default parameters:

1. read      (crates/ldh-core/src/io/reader.rs)  ldh CSV `time_s,acc_x..gyro_z`, rate fitted from
             the timestamps, clipped-sample flags;
2. preprocess (preprocess.rs) magnitude, 3-SD outliers replaced on the acc channels
             (numpy.interp), scipy.signal.butter(4, 10 Hz, sos) + sosfiltfilt on six channels;
3. align     (align.rs) still windows, gyro bias, gravity axis, principal axis of the walking
             angular velocity (numpy.linalg.eigh), sign from mid-swing, rotation to frame F;
4. attitude  (attitude.rs) bank of EKFs on ZYX Euler angles, gates [2.5, 4, 8, 1e6], Sage-Husa R
             with bounds, R inflation, likelihood weights with floor, RTS smoother;
5. events    (events.rs, gyro-bracket) scipy.signal.find_peaks for mid-swing, zero crossings,
             toe off at 0.38855 of the [t_s, t_p] bracket (ldh's rule for a leg no stiffer than
             its partner; ldh's per-subject placement and its impact heel strike, which on the
             demo's family-A walks moves nothing, are not ported);
6. strides   (gait.rs) stride table with validity rules, stride length by rotation + double
             integration with lever-arm correction, per-side means (no STA/Lyapunov).

The Kalman filter bank and the RTS recursion are per-sample Python loops over small numpy arrays
(that recursion is the cost a Python user pays); everything that is naturally vectorised in numpy
(filtering, alignment, rotations, integration, RTS gains) is vectorised. The EKF bank is timed in
two styles that give identical results (to ~1e-14): `attitude()`, one filter at a time as a
scientist usually writes it, and `attitude_bank()`, the four filters stepped together as stacked
arrays (the faster numpy idiom; its ratio is the conservative one).

It then
* checks its results against `ldh analyze DIR --no-sta` (per-recording mean stride time, stance
  ratio, stride length, stride counts; per-stride HS, TO and stride length) and prints the
  differences;
* times the Python pipeline in both EKF styles (median of --repeats passes over all recordings,
  time.perf_counter, divided by the number of recordings) and `ldh analyze DIR --no-sta
  --jobs 1|2` (median of --repeats runs of the whole process: start-up, reading and writing the
  outputs included, nothing subtracted, divided by the number of recordings), interleaved;
* prints a Markdown table and the python/numpy/scipy versions.

Run from the repository root (needs target/release/ldh: `cargo build --release -p ldh-cli`):

    python3 data-fixtures/scripts/bench_pipeline_python.py [--data DIR] [--repeats 7] [--ldh PATH]

Without --data the demo cohort is written to a temporary folder with `ldh demo --out DIR`.
Deterministic: no random numbers; the only variation between runs is the timings.
"""
import argparse
import csv
import glob
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import pandas as pd
import scipy
from scipy.signal import butter, find_peaks, sosfiltfilt

G = 9.80665  # recording.rs STANDARD_GRAVITY_MPS2
TAU = 2.0 * math.pi

# ---------------------------------------------------------------- defaults (Rust Default impls)
PRE = dict(cutoff_hz=10.0, filter_order=4, outlier_sd=3.0)
ALIGN = dict(still_gyro_dps=15.0, still_acc_sd_g=0.02, still_window_s=0.5, min_still_s=1.0,
             walking_gyro_dps=50.0)
ATT = dict(gates_sigma=[2.5, 4.0, 8.0, 1e6], gyro_noise_dps=2.0, acc_tilt_noise_deg=3.0,
           acc_tilt_noise_bounds_deg=(3.0, 30.0), dynamic_scale_g=0.02, rotation_scale_dps=100.0,
           reacquire_s=0.5, forgetting=0.995, min_weight=1e-3)
EV = dict(min_midswing_dps=100.0, min_stride_s=0.7, max_stride_s=2.5,
          hs_offset=0.0160, to_bracket_k0=0.38855)
STRIDE = dict(min_stride_s=0.7, max_stride_s=2.5, turn_deg=20.0, sensor_height_m=0.10)


def rround(x):
    """Rust f64::round (half away from zero) for scalars."""
    return math.floor(x + 0.5) if x >= 0 else -math.floor(-x + 0.5)


# ------------------------------------------------------------------------------------ 1. read
def detect_clipping(ch, floor):
    """reader.rs detect_clipping without a declared range: flat runs (>= 3 equal samples) at the
    channel's extreme, when that extreme is at least `floor`."""
    n = len(ch)
    flags = np.zeros(n, dtype=bool)
    for ext in (ch.max(), ch.min()):
        if abs(ext) < floor:
            continue
        near = np.abs(ch - ext) <= 1e-3 * abs(ext)
        i = 0
        for i0 in np.flatnonzero(near):
            if i0 < i:
                continue
            j = i0
            while j + 1 < n and ch[j + 1] == ch[i0]:
                j += 1
            if j + 1 - i0 >= 3:
                flags[i0:j + 1] = True
            i = j + 1
    return flags


def read_recording(path):
    df = pd.read_csv(path, comment="#", skipinitialspace=True)
    df.columns = [c.strip().lower() for c in df.columns]
    t = df["time_s"].to_numpy(float)
    raw = df[["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"]].to_numpy(float)
    # Rate: integer sample index per row (intervals in median periods), LS fit of t on index.
    dts = np.diff(t)
    median_dt = np.sort(dts)[len(dts) // 2]
    steps = np.maximum(np.floor(dts / median_dt + 0.5), 1.0)
    index = np.concatenate([[0.0], np.cumsum(steps)])
    km, tm = index.mean(), t.mean()
    fs = np.sum((index - km) ** 2) / np.sum((index - km) * (t - tm))
    jitter = np.max(np.abs(t - (t[0] + index / fs)))
    uniform = int(index[-1]) + 1 == len(t) and jitter <= 0.1 / fs
    if not uniform:
        n_out = int(math.floor((t[-1] - t[0]) * fs + 1e-9)) + 1
        grid = t[0] + np.arange(n_out) / fs
        raw = np.column_stack([np.interp(grid, t, raw[:, k]) for k in range(6)])
    sat = np.zeros(len(raw), dtype=bool)
    for k in range(6):
        sat |= detect_clipping(raw[:, k], 1.5 if k < 3 else 200.0)
    return fs, raw[:, :3].copy(), raw[:, 3:].copy(), sat


# ------------------------------------------------------------------------------ 2. preprocess
def interpolate_over(v, bad_mask):
    if not bad_mask.any() or bad_mask.all():
        return v
    good = ~bad_mask
    idx = np.arange(len(v))
    out = v.copy()
    out[bad_mask] = np.interp(idx[bad_mask], idx[good], v[good])
    return out


def preprocess(fs, acc, gyro, sat):
    norm = np.sqrt(np.sum(acc ** 2, axis=1))
    m, sd = norm.mean(), norm.std()
    bad = (np.abs(norm - m) > PRE["outlier_sd"] * sd) | sat
    acc = np.column_stack([interpolate_over(acc[:, k], bad) for k in range(3)])
    gyro = np.column_stack([interpolate_over(gyro[:, k], sat) for k in range(3)])
    sos = butter(PRE["filter_order"], PRE["cutoff_hz"], output="sos", fs=fs)
    acc_f = sosfiltfilt(sos, acc, axis=0)
    gyro_f = sosfiltfilt(sos, gyro, axis=0)
    return acc_f, gyro_f, np.sqrt(np.sum(acc_f ** 2, axis=1))


# ------------------------------------------------------------------------------- 3. alignment
def runs(mask):
    d = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)))


def align(fs, acc, gyro, acc_norm):
    p = ALIGN
    n = len(acc_norm)
    w = min(max(int(rround(p["still_window_s"] * fs)), 3), max(n, 3))
    mask = np.zeros(n, dtype=bool)
    gn = np.sqrt(np.sum(gyro ** 2, axis=1))
    i = 0
    while i + w <= n:
        win = acc_norm[i:i + w]
        m = win.mean()
        if win.std() < p["still_acc_sd_g"] and gn[i:i + w].max() < p["still_gyro_dps"] \
                and 0.7 <= m < 1.3:
            mask[i:i + w] = True
        i += w // 2
    min_len = int(p["min_still_s"] * fs)
    long = [(a, b) for a, b in runs(mask) if b - a >= min_len]
    if long:
        sel = np.concatenate([np.arange(a, b) for a, b in long])
        gravity, bias = acc[sel].mean(axis=0), gyro[sel].mean(axis=0)
    else:
        gravity, bias = acc.mean(axis=0), np.zeros(3)
    if np.linalg.norm(gravity) < 0.3:
        raise ValueError("no gravity direction")
    e3 = gravity / np.linalg.norm(gravity)
    wc = gyro - bias
    walking = wc[np.sqrt(np.sum(wc ** 2, axis=1)) > p["walking_gyro_dps"]]
    if len(walking) < max(int(fs), 10):
        raise ValueError("no walking found")
    evals, evecs = np.linalg.eigh(walking.T @ walking)
    axis = evecs[:, np.argmax(evals)]
    e2 = axis - e3 * (axis @ e3)
    if np.linalg.norm(e2) < 0.3:
        raise ValueError("rotation axis along the shank")
    e2 /= np.linalg.norm(e2)
    proj = np.sort(wc @ e2)
    k = max(n // 100, 1)
    if proj[-k:].mean() > -proj[:k].mean():
        e2 = -e2
    e1 = np.cross(e2, e3)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(e3, e1)
    r = np.vstack([e1, e2, e3])
    return acc @ r.T, wc @ r.T


# -------------------------------------------------------------------------------- 4. attitude
def wrap(a):
    return a - TAU * math.floor((a + math.pi) / TAU)


def acc_tilt(f):
    return math.atan2(f[1], f[2]), math.atan2(-f[0], math.sqrt(f[1] * f[1] + f[2] * f[2]))


def euler_rates(x, w):
    sp, cp = math.sin(x[0]), math.cos(x[0])
    st, ct = math.sin(x[1]), math.cos(x[1])
    if abs(ct) < 1e-6:
        ct = math.copysign(1e-6, ct)
    tt = st / ct
    a = sp * w[1] + cp * w[2]
    b = cp * w[1] - sp * w[2]
    rates = np.array([w[0] + a * tt, b, a / ct])
    jac = np.array([[b * tt, a / (ct * ct), 0.0],
                    [-a, 0.0, 0.0],
                    [b / ct, a * st / (ct * ct), 0.0]])
    return rates, jac


def weighted(xs, w):
    """Weighted mean of states (m, 3), angles as wrapped offsets from the first."""
    d = xs - xs[0]
    d = d - TAU * np.floor((d + math.pi) / TAU)
    out = xs[0] + w @ d
    out[2] = wrap(out[2])
    return out


def attitude(fs, acc, gyro):
    p = ATT
    n = len(acc)
    dt = 1.0 / fs
    w_rad = np.radians(gyro)
    w_mid = np.empty_like(w_rad)
    w_mid[0] = w_rad[0]
    w_mid[1:] = 0.5 * (w_rad[:-1] + w_rad[1:])
    norm = np.sqrt(np.sum(acc ** 2, axis=1))
    dyn_dev = np.abs(norm - 1.0)
    infl = 1.0 + (dyn_dev / p["dynamic_scale_g"]) ** 2 \
        + (np.sqrt(np.sum(gyro ** 2, axis=1)) / p["rotation_scale_dps"]) ** 2
    z_all = np.column_stack([np.arctan2(acc[:, 1], acc[:, 2]),
                             np.arctan2(-acc[:, 0], np.hypot(acc[:, 1], acc[:, 2]))])
    q = np.eye(3) * (math.radians(p["gyro_noise_dps"]) * dt) ** 2
    r0 = math.radians(p["acc_tilt_noise_deg"]) ** 2
    rlo = math.radians(p["acc_tilt_noise_bounds_deg"][0]) ** 2
    rhi = math.radians(p["acc_tilt_noise_bounds_deg"][1]) ** 2
    b = p["forgetting"]
    quiet = dyn_dev < 2.0 * p["dynamic_scale_g"]
    reacq = p["reacquire_s"]
    phi0, th0 = acc_tilt(acc[0])
    gates = p["gates_sigma"]
    m = len(gates)
    eye3, eye2 = np.eye(3), np.eye(2)
    # Per-filter state, kept for the smoother.
    X = [np.array([phi0, th0, 0.0]) for _ in range(m)]
    P = [np.diag([r0, r0, 1e-6]) for _ in range(m)]
    R = [np.eye(2) * r0 for _ in range(m)]
    gate2 = [g * g for g in gates]
    logw = np.zeros(m)
    rejected = [0] * m
    xs_pred = np.empty((m, n, 3))
    ps_pred = np.empty((m, n, 3, 3))
    xs = np.empty((m, n, 3))
    ps = np.empty((m, n, 3, 3))
    fjs = np.empty((m, n, 3, 3))
    weights_t = np.empty((n, m))
    bpow = 1.0
    log_tau2 = math.log(TAU ** 2)
    for k in range(n):
        z = z_all[k]
        bpow *= b
        d_k = (1.0 - b) / (1.0 - bpow)
        for j in range(m):
            x, pm = X[j], P[j]
            # Predict (EKF on the Euler-rate kinematics, mid-point angular velocity).
            if k == 0:
                xp, pp, fj = x, pm, eye3
            else:
                rates, jac = euler_rates(x, w_mid[k])
                fj = eye3 + jac * dt
                xp = x + rates * dt
                xp[2] = wrap(xp[2])
                pp = fj @ pm @ fj.T + q
            # Update with the accelerometer tilt, gated.
            nu = z - xp[:2]
            nu[0] = wrap(nu[0])
            nu[1] = wrap(nu[1])
            hph = pp[:2, :2]
            rk = R[j] * infl[k]
            s = hph + rk
            det = np.linalg.det(s)
            s_inv = np.linalg.inv(s) if det != 0.0 else eye2 / r0
            d2 = nu @ s_inv @ nu
            logw[j] += -0.5 * d2 - 0.5 * (math.log(max(det, 1e-300)) + log_tau2)
            if d2 <= gate2[j] or rejected[j] * dt >= reacq:
                rejected[j] = 0
                kg = pp[:, :2] @ s_inv
                ikh = eye3.copy()
                ikh[:, :2] -= kg
                xu = xp + kg @ nu
                pu = ikh @ pp @ ikh.T + kg @ rk @ kg.T
                if quiet[k]:  # Sage-Husa adaptation of R from quasi-static innovations
                    for i in range(2):
                        est = nu[i] * nu[i] - hph[i, i]
                        R[j][i, i] = min(max((1.0 - d_k) * R[j][i, i] + d_k * est, rlo), rhi)
            else:
                rejected[j] += 1
                xu, pu = xp.copy(), pp
            xu[2] = wrap(xu[2])
            X[j], P[j] = xu, pu
            xs_pred[j, k], ps_pred[j, k] = xp, pp
            xs[j, k], ps[j, k], fjs[j, k] = xu, pu, fj
        # Likelihood weights with a floor (eq. 15).
        w = np.exp(logw - logw.max())
        w /= w.sum()
        w = np.maximum(w, p["min_weight"])
        w /= w.sum()
        logw = np.log(w)
        weights_t[k] = w
    # RTS smoother per filter: gains vectorised, the backward recursion per sample.
    smoothed = xs.copy()
    for j in range(m):
        gains = ps[j, :-1] @ np.transpose(fjs[j, 1:], (0, 2, 1)) @ np.linalg.inv(ps_pred[j, 1:])
        sj, xf, xpr = smoothed[j], xs[j], xs_pred[j]
        for k in range(n - 2, -1, -1):
            diff = sj[k + 1] - xpr[k + 1]
            diff[2] = wrap(diff[2])
            sj[k] = xf[k] + gains[k] @ diff
    fused = np.array([weighted(smoothed[:, k], weights_t[k]) for k in range(n)])
    return np.degrees(fused)  # (n, 3): roll, pitch, yaw in deg


def wrap_v(a):
    return a - TAU * np.floor((a + math.pi) / TAU)


def attitude_bank(fs, acc, gyro):
    """The same filter bank with the per-sample recursion kept but the four filters stepped
    together as stacked (m, 3) / (m, 3, 3) arrays (2x2 inverse written out): the faster numpy
    idiom, for a conservative comparison. Same arithmetic as attitude()."""
    p = ATT
    n = len(acc)
    dt = 1.0 / fs
    w_rad = np.radians(gyro)
    w_mid = np.empty_like(w_rad)
    w_mid[0] = w_rad[0]
    w_mid[1:] = 0.5 * (w_rad[:-1] + w_rad[1:])
    norm = np.sqrt(np.sum(acc ** 2, axis=1))
    dyn_dev = np.abs(norm - 1.0)
    infl = 1.0 + (dyn_dev / p["dynamic_scale_g"]) ** 2 \
        + (np.sqrt(np.sum(gyro ** 2, axis=1)) / p["rotation_scale_dps"]) ** 2
    z_all = np.column_stack([np.arctan2(acc[:, 1], acc[:, 2]),
                             np.arctan2(-acc[:, 0], np.hypot(acc[:, 1], acc[:, 2]))])
    q = np.eye(3) * (math.radians(p["gyro_noise_dps"]) * dt) ** 2
    r0 = math.radians(p["acc_tilt_noise_deg"]) ** 2
    rlo = math.radians(p["acc_tilt_noise_bounds_deg"][0]) ** 2
    rhi = math.radians(p["acc_tilt_noise_bounds_deg"][1]) ** 2
    b = p["forgetting"]
    quiet = dyn_dev < 2.0 * p["dynamic_scale_g"]
    gate2 = np.array(p["gates_sigma"]) ** 2
    m = len(gate2)
    phi0, th0 = acc_tilt(acc[0])
    X = np.tile([phi0, th0, 0.0], (m, 1))
    P = np.tile(np.diag([r0, r0, 1e-6]), (m, 1, 1))
    Rd = np.full((m, 2), r0)
    logw = np.zeros(m)
    rejected = np.zeros(m)
    eye3 = np.eye(3)
    xs_pred = np.empty((n, m, 3))
    ps_pred = np.empty((n, m, 3, 3))
    xs = np.empty((n, m, 3))
    ps = np.empty((n, m, 3, 3))
    fjs = np.empty((n, m, 3, 3))
    weights_t = np.empty((n, m))
    log_tau2 = math.log(TAU ** 2)
    reacq_n = p["reacquire_s"]
    bpow = 1.0
    for k in range(n):
        bpow *= b
        d_k = (1.0 - b) / (1.0 - bpow)
        if k == 0:
            Xp, Pp, F = X, P, np.broadcast_to(eye3, (m, 3, 3))
        else:
            w = w_mid[k]
            sp, cp = np.sin(X[:, 0]), np.cos(X[:, 0])
            st, ct = np.sin(X[:, 1]), np.cos(X[:, 1])
            ct = np.where(np.abs(ct) < 1e-6, np.copysign(1e-6, ct), ct)
            tt = st / ct
            a = sp * w[1] + cp * w[2]
            bb = cp * w[1] - sp * w[2]
            F = np.zeros((m, 3, 3))
            F[:, 0, 0] = 1.0 + bb * tt * dt
            F[:, 0, 1] = a / (ct * ct) * dt
            F[:, 1, 0] = -a * dt
            F[:, 1, 1] = 1.0
            F[:, 2, 0] = bb / ct * dt
            F[:, 2, 1] = a * st / (ct * ct) * dt
            F[:, 2, 2] = 1.0
            Xp = X + np.column_stack([w[0] + a * tt, bb, a / ct]) * dt
            Xp[:, 2] = wrap_v(Xp[:, 2])
            Pp = F @ P @ F.transpose(0, 2, 1) + q
        nu = wrap_v(z_all[k] - Xp[:, :2])
        hph = Pp[:, :2, :2]
        rk = Rd * infl[k]
        s00, s01, s10, s11 = hph[:, 0, 0] + rk[:, 0], hph[:, 0, 1], hph[:, 1, 0], hph[:, 1, 1] + rk[:, 1]
        det = s00 * s11 - s01 * s10
        s_inv = np.stack([np.stack([s11, -s01], -1), np.stack([-s10, s00], -1)], 1) / det[:, None, None]
        d2 = np.einsum("mi,mij,mj->m", nu, s_inv, nu)
        logw += -0.5 * d2 - 0.5 * (np.log(np.maximum(det, 1e-300)) + log_tau2)
        accept = (d2 <= gate2) | (rejected * dt >= reacq_n)
        kg = Pp[:, :, :2] @ s_inv
        ikh = np.broadcast_to(eye3, (m, 3, 3)).copy()
        ikh[:, :, :2] -= kg
        Xu = Xp + np.einsum("mij,mj->mi", kg, nu)
        Pu = ikh @ Pp @ ikh.transpose(0, 2, 1) + (kg * rk[:, None, :]) @ kg.transpose(0, 2, 1)
        if quiet[k]:
            est = nu ** 2 - np.stack([hph[:, 0, 0], hph[:, 1, 1]], -1)
            new = np.clip((1.0 - d_k) * Rd + d_k * est, rlo, rhi)
            Rd = np.where(accept[:, None], new, Rd)
        rejected = np.where(accept, 0.0, rejected + 1.0)
        X = np.where(accept[:, None], Xu, Xp)
        X[:, 2] = wrap_v(X[:, 2])
        P = np.where(accept[:, None, None], Pu, Pp)
        xs_pred[k], ps_pred[k], xs[k], ps[k], fjs[k] = Xp, Pp, X, P, F
        wk = np.exp(logw - logw.max())
        wk /= wk.sum()
        wk = np.maximum(wk, p["min_weight"])
        wk /= wk.sum()
        logw = np.log(wk)
        weights_t[k] = wk
    gains = ps[:-1] @ fjs[1:].transpose(0, 1, 3, 2) @ np.linalg.inv(ps_pred[1:])
    sm = xs.copy()
    for k in range(n - 2, -1, -1):
        diff = sm[k + 1] - xs_pred[k + 1]
        diff[:, 2] = wrap_v(diff[:, 2])
        sm[k] = xs[k] + np.einsum("mij,mj->mi", gains[k], diff)
    d = wrap_v(sm - sm[:, :1])
    fused = sm[:, 0] + np.einsum("nm,nmi->ni", weights_t, d)
    fused[:, 2] = wrap_v(fused[:, 2])
    return np.degrees(fused)


# ---------------------------------------------------------------------------------- 5. events
def parabolic(y, i):
    if i == 0 or i + 1 >= len(y):
        return float(i)
    a, b_, c = y[i - 1], y[i], y[i + 1]
    den = a - 2.0 * b_ + c
    if abs(den) < 1e-12:
        return float(i)
    return i + min(max(0.5 * (a - c) / den, -0.5), 0.5)


def detect_events(om, fs):
    p = EV
    n = len(om)
    neg = -om
    min_dist = max(int(p["min_stride_s"] * 0.8 * fs), 1)
    mid, _ = find_peaks(neg, height=p["min_midswing_dps"], prominence=p["min_midswing_dps"],
                        distance=min_dist)
    if len(mid) < 2:
        return [], [], 1.1
    iv = np.sort(np.diff(mid) / fs)
    iv = iv[iv <= p["max_stride_s"]]
    t_med = iv[len(iv) // 2] if len(iv) else 1.1
    half = int(0.5 * t_med * fs)
    up = (om[:-1] < 0.0) & (om[1:] >= 0.0)      # ω_s crosses zero upwards between i and i+1
    down = (om[:-1] >= 0.0) & (om[1:] < 0.0)    # ... downwards
    lmax = np.zeros(n, dtype=bool)              # late-stance local maxima
    lmax[1:-1] = (om[1:-1] >= om[2:]) & (om[1:-1] > om[:-2])
    k0 = p["to_bracket_k0"]
    hs, to = [], []
    for mi in mid:
        end = min(mi + half, n - 1)
        c = np.flatnonzero(up[mi:end])
        if len(c):
            i = mi + c[0]
            hs.append((i + (-om[i]) / (om[i + 1] - om[i])) / fs + p["hs_offset"] * t_med)
        start = max(mi - half, 1)
        c = np.flatnonzero(down[start:mi])
        if len(c):
            zc = start + c[-1]
            c2 = np.flatnonzero(lmax[start:zc + 1])
            if len(c2):
                late = start + c2[-1]
                tp = (zc + om[zc] / (om[zc] - om[zc + 1])) / fs
                ts = parabolic(om, late) / fs
                # ldh's gyro-bracket; ldh then moves the stiffer leg's toe offs later with the
                # other leg's landmark geometry (a median per leg, not mirrored here).
                to.append(ts + k0 * (tp - ts))
    return hs, to, t_med


# --------------------------------------------------------------------------------- 6. strides
def rotations(att_deg):
    """world <- F rotation matrices of ZYX angles, (n, 3, 3)."""
    phi, th, psi = np.radians(att_deg).T
    sf, cf, st, ct, sp, cp = np.sin(phi), np.cos(phi), np.sin(th), np.cos(th), np.sin(psi), np.cos(psi)
    return np.stack([
        np.stack([cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf], axis=-1),
        np.stack([sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf], axis=-1),
        np.stack([-st, ct * sf, ct * cf], axis=-1)], axis=1)


def strides(side, fs, acc, gyro, att_deg, hs, to, t_med, h):
    p = STRIDE
    n = len(att_deg)
    dt = 1.0 / fs
    roll, pitch, yaw = att_deg[:, 0], att_deg[:, 1], att_deg[:, 2]

    def idx(t):
        return min(int(max(rround(t * fs), 0)), n - 1)

    hs = sorted(hs)
    to = np.asarray(to)
    w_norm = np.sqrt(np.sum(gyro ** 2, axis=1))
    # World-frame acceleration without gravity and the lever arm, for every sample.
    rot = rotations(att_deg)
    acc_w = np.einsum("nij,nj->ni", rot, acc) * G
    acc_w[:, 2] -= G
    r_w = rot[:, :, 2] * h
    v_lever = np.cross(np.einsum("nij,nj->ni", rot, np.radians(gyro)), r_w)

    def zv_after(t):
        c = to[(to > t) & (to - t < 0.75 * p["max_stride_s"])]
        end = c[0] if len(c) else t + 0.6 * max(t_med, 0.5)
        a, b = idx(t), idx(end)
        if b <= a + 2:
            return None
        return a + int(np.argmin(w_norm[a:b]))

    def stride_length(z0, z1):
        m = z1 - z0
        a = acc_w[z0:z1 + 1]
        v = np.empty((m + 1, 3))
        v[0] = v_lever[z0]
        v[1:] = v_lever[z0] + np.cumsum(0.5 * dt * (a[:-1] + a[1:]), axis=0)
        v -= np.outer(np.arange(m + 1) / m, v[m] - v_lever[z1])
        d = np.sum(0.5 * dt * (v[:-1] + v[1:]), axis=0)
        ankle = d[:2] - (r_w[z1, :2] - r_w[z0, :2])
        return math.hypot(ankle[0], ankle[1])

    out = []
    for k in range(len(hs) - 1):
        h0, h1 = hs[k], hs[k + 1]
        st = h1 - h0
        reasons = []
        if st < p["min_stride_s"] or st > p["max_stride_s"]:
            reasons.append("stride time")
        tos = to[(to > h0) & (to < h1)]
        if len(tos) == 0:
            reasons.append("no toe off")
            t_off = float("nan")
        else:
            if len(tos) > 1:
                reasons.append("toe offs")
            t_off = tos[0]
        a, b = idx(h0), idx(h1)
        seg = pitch[a:min(max(b, a + 1), n)]
        if math.isfinite(t_off):
            i0 = idx(t_off)
            r = roll[i0:min(max(b, i0 + 1), n)] * (-1.0 if side == "left" else 1.0)
            bdk = r.max() - r.min()
        else:
            bdk = float("nan")
        dpsi = (yaw[min(b, n - 1)] - yaw[a] + 180.0) % 360.0 - 180.0
        turning = abs(dpsi) > p["turn_deg"]
        if turning:
            reasons.append("turning")
        z0, z1 = zv_after(h0), zv_after(h1)
        length = stride_length(z0, z1) if z0 is not None and z1 is not None and z1 > z0 + 1 \
            else float("nan")
        if not math.isfinite(length):
            reasons.append("stride length not integrable")
        out.append(dict(hs=h0, to=t_off, st=st, stance=(t_off - h0) / st, length=length,
                        speed=length / st, wqk=seg.max(), pbi=-seg.min(), bdk=bdk,
                        turning=turning, reasons=reasons))
    # Bouts, split at pauses and turns; first and last stride of each bout flagged.
    bout, prev_break = 0, True
    for s in out:
        if s["st"] > p["max_stride_s"] or s["turning"]:
            if not prev_break:
                bout += 1
            s["bout"], prev_break = None, True
            continue
        s["bout"], prev_break = bout, False
    for i, s in enumerate(out):
        if s["bout"] is None:
            continue
        first = i == 0 or out[i - 1]["bout"] != s["bout"]
        last = i + 1 == len(out) or out[i + 1]["bout"] != s["bout"]
        if first or last:
            s["reasons"].append("bout edge")
    for s in out:
        s["valid"] = not s["reasons"]
    return out


def side_parameters(st, other_hs=None):
    valid = [s for s in st if s["valid"]]

    def col(key):
        v = np.array([s[key] for s in valid], dtype=float)
        return v[np.isfinite(v)]

    def mean(v):
        return float(v.mean()) if len(v) else float("nan")

    def cv(v):
        return float(v.std(ddof=1) / v.mean()) if len(v) >= 2 else float("nan")

    t, sl = col("st"), col("length")
    mean_st = mean(t)
    stt = []
    if other_hs is not None:
        other = np.asarray(other_hs)
        for s in valid:
            c = other[(other < s["hs"]) & (s["hs"] - other < 0.75 * mean_st)]
            if len(c):
                stt.append(s["hs"] - c[-1])
    return dict(strides_total=len(st), strides_valid=len(valid), stride_time_s=mean_st,
                step_time_s=mean(np.array(stt)), stance_ratio=mean(col("stance")),
                stride_length_m=mean(sl), speed_mps=mean(col("speed")),
                stride_length_cv=cv(sl), stride_time_cv=cv(t), wqk_deg=mean(col("wqk")),
                pbi_deg=mean(col("pbi")), bdk_deg=mean(col("bdk")))


# ------------------------------------------------------------------------------ the pipeline
def analyze_leg(path, side, sensor_height_m, ekf="loop"):
    fs, acc, gyro, sat = read_recording(path)
    acc_p, gyro_p, acc_norm = preprocess(fs, acc, gyro, sat)
    acc_f, gyro_f = align(fs, acc_p, gyro_p, acc_norm)
    att = (attitude if ekf == "loop" else attitude_bank)(fs, acc_f, gyro_f)
    hs, to, t_med = detect_events(gyro_f[:, 1], fs)
    st = strides(side, fs, acc_f, gyro_f, att, hs, to, t_med, sensor_height_m)
    return st, hs


def find_recordings(data):
    heights = {}
    man = os.path.join(data, "manifest.csv")
    if os.path.isfile(man):  # ldh uses the manifest's sensor heights when there is one
        with open(man, newline="") as f:
            for row in csv.DictReader(f):
                hv = (row.get("sensor_height_m") or "").strip()
                if hv:
                    heights[row["subject_id"].strip()] = float(hv)
    subjects = []
    for d in sorted(glob.glob(os.path.join(data, "*", ""))):
        sid = os.path.basename(os.path.normpath(d))
        legs = [(s, os.path.join(d, s + ".csv")) for s in ("left", "right")
                if os.path.isfile(os.path.join(d, s + ".csv"))]
        if legs:
            subjects.append((sid, legs, heights.get(sid, STRIDE["sensor_height_m"])))
    return subjects


def analyze_all(subjects, ekf="loop"):
    """Per-side parameters and stride tables of every recording, keyed by (subject, side)."""
    results, tables = {}, {}
    for sid, legs, h in subjects:
        per = {side: analyze_leg(path, side, h, ekf) for side, path in legs}
        for side, (st, _) in per.items():
            other = per.get("right" if side == "left" else "left")
            results[(sid, side)] = side_parameters(st, other[1] if other else None)
            tables[(sid, side)] = st
    return results, tables


# ------------------------------------------------------------------------------------- ldh
def run_ldh(ldh, data, out, jobs=None):
    cmd = [ldh, "analyze", data, "--out", out, "--no-sta"]
    if jobs:
        cmd += ["--jobs", str(jobs)]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def read_ldh(out):
    """ldh's per-recording parameters (recordings.csv) and stride tables (strides.csv)."""
    res, tables = {}, {}
    with open(os.path.join(out, "recordings.csv"), newline="") as f:
        for row in csv.DictReader(f):
            if row["status"] != "ok":
                continue
            res[(row["subject_id"], row["side"])] = {
                k: float(row[k]) for k in ("stride_time_s", "stance_ratio", "stride_length_m",
                                           "strides_total", "strides_valid", "step_time_s")}
    with open(os.path.join(out, "strides.csv"), newline="") as f:
        for row in csv.DictReader(f):
            tables.setdefault((row["subject_id"], row["side"]), []).append(row)
    return res, tables


def fnum(x):
    return float(x) if x not in ("", None) else float("nan")


def agreement(py, py_tables, rs, rs_tables):
    """Print per-recording differences Python - ldh; return the largest |relative difference| in
    %, per parameter, and the largest per-stride differences."""
    print("| recording | strides (valid) py / ldh | stride time s py / ldh (Δ%) "
          "| stance ratio py / ldh (Δ%) | stride length m py / ldh (Δ%) "
          "| max per-stride |Δ| HS ms, TO ms, SL mm |")
    print("|---|---|---|---|---|---|")
    worst = {"stride_time_s": 0.0, "stance_ratio": 0.0, "stride_length_m": 0.0,
             "hs_ms": 0.0, "to_ms": 0.0, "sl_mm": 0.0, "valid_flags_differ": 0}
    for key in sorted(py):
        a, b = py[key], rs.get(key)
        if b is None:
            print(f"| {key[0]}/{key[1]} | ldh has no result | | | | |")
            continue
        cells = []
        for k in ("stride_time_s", "stance_ratio", "stride_length_m"):
            d = 100.0 * (a[k] - b[k]) / b[k]
            worst[k] = max(worst[k], abs(d))
            cells.append(f"{a[k]:.4f} / {b[k]:.4f} ({d:+.3f})")
        ps, ls = py_tables[key], rs_tables.get(key, [])
        dh = dt = dl = 0.0
        for x, y in zip(ps, ls):
            dh = max(dh, abs(x["hs"] - fnum(y["hs_time_s"])) * 1e3)
            if math.isfinite(x["to"]):
                dt = max(dt, abs(x["to"] - fnum(y["to_time_s"])) * 1e3)
            if math.isfinite(x["length"]):
                dl = max(dl, abs(x["length"] - fnum(y["stride_length_m"])) * 1e3)
            worst["valid_flags_differ"] += int(x["valid"] != (y["valid"] == "true"))
        worst["hs_ms"], worst["to_ms"], worst["sl_mm"] = (max(worst["hs_ms"], dh),
                                                          max(worst["to_ms"], dt),
                                                          max(worst["sl_mm"], dl))
        print(f"| {key[0]}/{key[1]} | {a['strides_total']} ({a['strides_valid']}) / "
              f"{int(b['strides_total'])} ({int(b['strides_valid'])}) | " + " | ".join(cells)
              + f" | {dh:.2f}, {dt:.2f}, {dl:.2f} |")
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", help="cohort folder with */left.csv, */right.csv (default: ldh demo)")
    ap.add_argument("--ldh", default=None, help="ldh binary (default: target/release/ldh)")
    ap.add_argument("--repeats", type=int, default=7, help="timing repeats (>= 5)")
    args = ap.parse_args()
    repeats = max(args.repeats, 5)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ldh = args.ldh or os.path.join(root, "target", "release", "ldh")
    if not os.access(ldh, os.X_OK):
        sys.exit(f"{ldh} not found: run `cargo build --release -p ldh-cli` first")
    tmp = tempfile.mkdtemp(prefix="ldh-pypeer-")
    try:
        data = args.data
        if data is None:
            data = os.path.join(tmp, "demo")
            subprocess.run([ldh, "demo", "--out", data], check=True, stdout=subprocess.DEVNULL)
        subjects = find_recordings(data)
        n_rec = sum(len(legs) for _, legs, _ in subjects)
        if n_rec == 0:
            sys.exit(f"no */left.csv or */right.csv in {data}")
        out = os.path.join(tmp, "ldh-out")

        # ---- agreement check (the two EKF variants must agree with each other too)
        py, py_tables = analyze_all(subjects, "loop")
        pyb, _ = analyze_all(subjects, "bank")
        bank_diff = max(abs(py[k][c] - pyb[k][c]) for k in py
                        for c in ("stride_time_s", "stance_ratio", "stride_length_m"))
        run_ldh(ldh, data, out)
        rs, rs_tables = read_ldh(out)
        print(f"## Agreement with ldh ({n_rec} recordings from {data})\n")
        print("Python − ldh; ldh writes 4 decimals, so Δ below ~0.01 % is its rounding.\n")
        worst = agreement(py, py_tables, rs, rs_tables)
        print("\nlargest |Δ|: stride time {stride_time_s:.3f} %, stance ratio {stance_ratio:.3f} %, "
              "stride length {stride_length_m:.3f} %; per stride HS {hs_ms:.2f} ms, TO {to_ms:.2f} ms, "
              "stride length {sl_mm:.2f} mm; strides whose validity differs: {valid_flags_differ}"
              .format(**worst))
        print(f"EKF per-filter loop vs stacked bank: largest difference of the means {bank_diff:.1e}")

        # ---- timing, interleaved so that load changes hit every variant alike
        t_loop, t_bank, t_j1, t_j2 = [], [], [], []
        for _ in range(repeats):
            for ekf, acc in (("loop", t_loop), ("bank", t_bank)):
                t0 = time.perf_counter()
                analyze_all(subjects, ekf)
                acc.append((time.perf_counter() - t0) / n_rec)
            t_j1.append(run_ldh(ldh, data, out, jobs=1) / n_rec)
            t_j2.append(run_ldh(ldh, data, out, jobs=2) / n_rec)
        ml, mb, m1, m2 = (statistics.median(v) for v in (t_loop, t_bank, t_j1, t_j2))
        print(f"\n## Time per recording (median of {repeats} repeats over {n_rec} recordings)\n")
        bl, bb, b1, b2 = (min(v) for v in (t_loop, t_bank, t_j1, t_j2))
        print("| pipeline | median per recording | ÷ ldh --jobs 1 | ÷ ldh --jobs 2 "
              "| best run (ratios of best runs) |")
        print("|---|---:|---:|---:|---:|")
        print(f"| Python numpy/scipy, EKF bank as a per-filter loop | {ml * 1e3:.1f} ms "
              f"| {ml / m1:.0f}× | {ml / m2:.0f}× | {bl * 1e3:.1f} ms ({bl / b1:.0f}×, {bl / b2:.0f}×) |")
        print(f"| Python numpy/scipy, EKF bank stacked (faster idiom) | {mb * 1e3:.1f} ms "
              f"| {mb / m1:.0f}× | {mb / m2:.0f}× | {bb * 1e3:.1f} ms ({bb / b1:.0f}×, {bb / b2:.0f}×) |")
        print(f"| ldh analyze --no-sta --jobs 1 (whole process) | {m1 * 1e3:.2f} ms | 1× | "
              f"| {b1 * 1e3:.2f} ms |")
        print(f"| ldh analyze --no-sta --jobs 2 (whole process) | {m2 * 1e3:.2f} ms | | 1× "
              f"| {b2 * 1e3:.2f} ms |")

        def fmt(v, d):
            return ", ".join(f"{t * 1e3:.{d}f}" for t in v)
        print(f"\nruns, ms per recording: Python loop {fmt(t_loop, 1)}; Python stacked "
              f"{fmt(t_bank, 1)}; ldh --jobs 1 {fmt(t_j1, 2)}; ldh --jobs 2 {fmt(t_j2, 2)}")
        print(f"\npython {platform.python_version()}, numpy {np.__version__}, "
              f"scipy {scipy.__version__}, pandas {pd.__version__}; {platform.machine()}, "
              f"{os.cpu_count()} CPUs; load average {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
