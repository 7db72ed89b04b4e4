#!/usr/bin/env python3
"""Fit the toe-off landmark model of `EventDetector::GyroLandmarks` (crates/ldh-core/src/events.rs,
`TO_LANDMARK_COEFFS`) on family A and score candidate models on a check cohort and, for the
record only, on family B (issue 20 item 4; docs/accuracy.md "Slow walkers in family A").

    TO = t_p + a·T + b·(t_m − t_p) + c·(t_p − t_s)          (M0, the shipped model)

t_s: the largest late-stance peak of the sagittal angular velocity, t_p: its zero crossing
after it (the pitch peak), t_m: mid-swing, T: the leg's median stride time. The landmarks are
recovered from three `ldh analyze` runs with offsets zeroed: `gyro-zero-crossing` gives t_p,
`salarian` gives t_s, and `gyro-landmarks` with a = 0 gives t_p + b(t_m − t_p) + c(t_p − t_s),
from which t_m follows with the shipped b, c.

Cohorts (made here with the ldh binary, in --work):
  tuning  family A seed 100, 10 healthy + 10 LDH + 10 slow LDH, 25 s  (fit)
  check   family A seed 200, the same groups, 30 s                     (model selection)
  report  family B seed 2026, 15 + 15, default length                  (never used to choose)

Requires numpy. Usage: python3 data-fixtures/scripts/fit_toe_off.py --ldh target/release/ldh
[--work /tmp/fit-to]. Prints, per model, its coefficients and TO MAE / p95 / bias (ms) per
cohort, with family A split into healthy + LDH (HL) and slow (S) subjects.
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np

B_SHIPPED, C_SHIPPED = 0.56902, -0.60292
SHIPPED = [-0.10139, B_SHIPPED, C_SHIPPED]
PARAMS = {
    "zc": '[events]\ndetector = "gyro-zero-crossing"\nhs_offset_stride = 0.0\nto_offset_stride = 0.0\n',
    "sa": '[events]\ndetector = "salarian"\nhs_offset_stride = 0.0\nto_offset_stride = 0.0\n',
    "g0": '[events]\ndetector = "gyro-landmarks"\nto_offset_stride = 0.0\n',
}
MODELS = {
    "M0 a·T (shipped form)": lambda r: [r["T"], r["tm"] - r["tp"], r["tp"] - r["ts"]],
    "M1 constant a": lambda r: [1.0, r["tm"] - r["tp"], r["tp"] - r["ts"]],
    "M2 constant + a·T": lambda r: [1.0, r["T"], r["tm"] - r["tp"], r["tp"] - r["ts"]],
    "M3 constant + (t_s − t_p)": lambda r: [1.0, r["ts"] - r["tp"]],
}


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def make(ldh, work):
    cohorts = {
        "tuning A s100": ["--healthy", "10", "--ldh", "10", "--slow-ldh", "10", "--seed", "100"],
        "check A s200": ["--healthy", "10", "--ldh", "10", "--slow-ldh", "10", "--seconds", "30",
                         "--seed", "200"],
        "report B s2026": ["--family", "b", "--healthy", "15", "--ldh", "15", "--seed", "2026"],
    }
    for name, text in PARAMS.items():
        with open(os.path.join(work, f"p_{name}.toml"), "w") as f:
            f.write(text)
    out = {}
    for name, args in cohorts.items():
        root = os.path.join(work, name.replace(" ", "_"))
        if not os.path.exists(os.path.join(root, "manifest.csv")):
            run([ldh, "simulate", "--out", root, "-q"] + args)
        for p in PARAMS:
            o = f"{root}_{p}"
            if not os.path.exists(os.path.join(o, "events.csv")):
                run([ldh, "analyze", root, "--out", o, "-q", "--params",
                     os.path.join(work, f"p_{p}.toml")])
        out[name] = root
    return out


def events(folder):
    ev = {}
    with open(os.path.join(folder, "events.csv")) as f:
        for r in csv.DictReader(f):
            ev.setdefault((r["subject_id"], r["side"], r["event"]), []).append(float(r["time_s"]))
    return ev


def near(times, t, tol=0.25):
    if not times:
        return None
    d = min(times, key=lambda x: abs(x - t))
    return d if abs(d - t) < tol else None


def rows(root):
    zc, sa, g0 = (events(f"{root}_{p}") for p in ("zc", "sa", "g0"))
    out = []
    for sid in sorted(os.listdir(root)):
        path = os.path.join(root, sid, "truth.json")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            truth = json.load(f)
        for side in ("left", "right"):
            hs = sorted(g0.get((sid, side, "HS"), []))
            iv = sorted(b - a for a, b in zip(hs, hs[1:]) if b - a <= 2.5)
            if not iv:
                continue
            T = iv[len(iv) // 2]
            for st in truth[side]["strides"]:
                if st["turning"] or st["bout_edge"]:
                    continue
                to = st["to_time_s"]
                k = (sid, side, "TO")
                tp, ts, t0 = near(zc.get(k), to), near(sa.get(k), to), near(g0.get(k), to)
                if None in (tp, ts, t0):
                    continue
                tm = tp + (t0 - tp - C_SHIPPED * (tp - ts)) / B_SHIPPED
                out.append(dict(to=to, tp=tp, ts=ts, tm=tm, T=T, sid=sid, side=side,
                                hs=st["hs_time_s"], nhs=st["next_hs_time_s"]))
    return out


def summary(e):
    a = np.abs(e)
    return f"{a.mean():5.1f} / {np.percentile(a, 95):5.1f} / {e.mean():+5.1f}"


def score(coef, f, rs):
    return np.array([r["tp"] + np.dot(coef, f(r)) - r["to"] for r in rs]) * 1e3


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ldh", default="target/release/ldh")
    ap.add_argument("--work", default="/tmp/ldh-fit-toe-off")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    cohorts = {k: rows(v) for k, v in make(os.path.abspath(a.ldh), a.work).items()}
    train = cohorts["tuning A s100"]
    print(f"tuning strides {len(train)}, median stride times "
          f"{min(r['T'] for r in train):.2f}-{max(r['T'] for r in train):.2f} s")
    print("TO error, ms: MAE / p95 / bias")
    fits = [("shipped " + str(SHIPPED), SHIPPED, MODELS["M0 a·T (shipped form)"])]
    for name, f in MODELS.items():
        X = np.array([f(r) for r in train])
        y = np.array([r["to"] - r["tp"] for r in train])
        fits.append((name, np.linalg.lstsq(X, y, rcond=None)[0], f))
    for name, coef, f in fits:
        print(f"{name}: coefficients {np.round(coef, 5).tolist()}")
        for cname, rs in cohorts.items():
            line = f"  {cname:15s} all {summary(score(coef, f, rs))}"
            slow = [r for r in rs if r["sid"].startswith("S")]
            if slow:
                hl = [r for r in rs if not r["sid"].startswith("S")]
                line += f" | HL {summary(score(coef, f, hl))} | S {summary(score(coef, f, slow))}"
            print(line)


if __name__ == "__main__":
    main()
