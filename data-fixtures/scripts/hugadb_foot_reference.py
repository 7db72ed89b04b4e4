#!/usr/bin/env python3
"""Toe off on real gait against a second sensor: HuGaDB's foot IMUs (issue 20; docs/accuracy.md
"Toe off against the feet of HuGaDB"), and, on its last line, the heel strike against the
foot's contact landmarks ("Heel strike at the impact"). Report only: nothing in ldh is fitted
to it.

HuGaDB (Chereshnev & Kertész-Farkas 2018) has an IMU on each foot as well as on each shin. ldh
reads only the shins; the feet give an independent look at when the foot leaves the ground:

  push-off peak   the largest toes-down rotation rate of the foot between 35 % of the stride and
                  5 % before the next heel strike (parabolic interpolation): the foot rolls over
                  the toes fastest just before it leaves the ground
  zero crossing   the first time after that peak that the foot's sagittal rate crosses zero
                  (linear interpolation): the foot stops plantar-flexing, already in the air.
                  This is gaitmap's `RamppEventDetection` terminal contact (Rampp et al., IEEE
                  TBME 2015;62(4):1089-1097): "the ankle changes from plantar flexion to dorsal
                  extension"

so the true toe off lies between the two (about 50 ms apart at these speeds). The foot's
sagittal axis is the first principal axis of its gyroscope (the sensor sits tilted on the
instep), signed to correlate positively with the shin's sagittal rate, whose mid-swing peak is
positive.

For every valid stride of `ldh analyze` on the five files whose shin gyroscopes are sound
(PROVENANCE.md; the left foot of 11_03 has the x10 gyroscope fault and is left out) it prints,
per file and per leg: ldh's toe off against both foot landmarks, the share of strides whose toe
off lies between them, and the stance ratio with each (ldh's heel strikes). With the runs
`--sa` (`salarian`, offsets 0) and `--zc` (`gyro-zero-crossing`, offsets 0) it also scores the
shank landmarks t_s (Aminian 2002, Salarian 2004), t_p (the pitch peak) and the bracket fraction
t_s + 0.43 (t_p - t_s) of docs/accuracy.md against the push-off peak.

Usage (from the repository root, after `cargo build --release -p ldh-cli`; numpy and pandas):

    python3 data-fixtures/scripts/hugadb_foot_reference.py [--hugadb ../shared/realdata/hugadb]
        [--ldh target/release/ldh] [--work DIR]

It writes the manifest of docs/input.md (with `sensor_height_m` 0.22) into --work and runs
`ldh analyze` three times there (default, `salarian` and `gyro-zero-crossing` with offsets 0).
Tested with numpy 2.4.6, pandas 3.1.1.
"""
import argparse
import collections
import csv
import os
import subprocess
import tempfile

import numpy as np
import pandas as pd

FS_HZ = 58.8  # HuGaDB's nominal rate (PROVENANCE.md); ldh's hugadb maps use the same
FILES = {
    "01_00": "HuGaDB_v1_walking_01_00.txt",
    "06_00": "HuGaDB_v1_walking_06_00.txt",
    "08_02": "HuGaDB_v1_walking_08_02-Test.txt",
    "10_00": "HuGaDB_v1_walking_10_00-Test.txt",
    "11_03": "HuGaDB_v1_walking_11_03-Test.txt",
}
FAULTY_FEET = {("11_03", "left")}  # gyroscope x10 and clipping (27.7 % of the samples on y)
PARAMS = {
    "default": "",
    "sa": '[events]\ndetector = "salarian"\nhs_offset_stride = 0.0\nto_offset_stride = 0.0\n',
    "zc": '[events]\ndetector = "gyro-zero-crossing"\nhs_offset_stride = 0.0\n'
          'to_offset_stride = 0.0\n',
}
FRACTION = 0.43  # the bracket fraction of docs/accuracy.md (median k on family A seed 100)


def run_ldh(ldh, hugadb, work):
    man = os.path.join(work, "manifest.csv")
    with open(man, "w") as f:
        f.write("subject_id,group,affected_side,left,right,left_format,right_format,"
                "sensor_height_m\n")
        for sid, name in FILES.items():
            p = os.path.join(os.path.abspath(hugadb), name)
            f.write(f"{sid},healthy,none,{p},{p},hugadb-left-shank,hugadb-right-shank,0.22\n")
    outs = {}
    for name, text in PARAMS.items():
        pf = os.path.join(work, f"{name}.toml")
        with open(pf, "w") as f:
            f.write(text)
        out = os.path.join(work, f"out_{name}")
        subprocess.run([ldh, "analyze", man, "--out", out, "-q", "--params", pf], check=True)
        outs[name] = out
    return outs


def sagittal(g):
    """Projection on the first principal axis of a 3 x n gyroscope signal."""
    g = g - g.mean(axis=1, keepdims=True)
    _, v = np.linalg.eigh(g @ g.T)
    return v[:, -1] @ g


def sensor(d, s, kind):
    """3 x n array of sensor `s` (RF, RS, LF, LS) in deg/s or g; both column spellings."""
    scale = 16.4 if kind == "gyro" else 16384.0
    cols = []
    for ax in "xyz":
        for name in (f"{s}_{kind}_{ax}", f"{kind}_{s.lower()}_{ax}"):
            if name in d:
                cols.append(d[name].to_numpy(float) / scale)
                break
    return np.array(cols)


def parabolic(x, i):
    if 0 < i < len(x) - 1:
        a, b, c = x[i - 1], x[i], x[i + 1]
        den = a - 2 * b + c
        if den != 0:
            return i + 0.5 * (a - c) / den
    return float(i)


def foot_landmarks(gf, hs, nhs):
    """(push-off peak, zero crossing) in s within the stride [hs, nhs), or None."""
    t = nhs - hs
    a, b = int(np.ceil((hs + 0.35 * t) * FS_HZ)), int((nhs - 0.05 * t) * FS_HZ)
    if b >= len(gf) - 1 or b <= a:
        return None
    ip = a + int(np.argmin(gf[a:b]))
    j = ip
    while j < b and gf[j + 1] < 0:
        j += 1
    if j >= b:
        return None
    return parabolic(gf, ip) / FS_HZ, (j + gf[j] / (gf[j] - gf[j + 1])) / FS_HZ


def strides(out):
    by = collections.defaultdict(list)
    with open(os.path.join(out, "strides.csv")) as f:
        for r in csv.DictReader(f):
            if r["model"] == "fusion" and r["valid"] == "true" and r["to_time_s"]:
                by[(r["subject_id"], r["side"])].append(
                    tuple(float(r[c]) for c in ("hs_time_s", "to_time_s", "next_hs_time_s")))
    return by


def to_events(out):
    ev = collections.defaultdict(list)
    with open(os.path.join(out, "events.csv")) as f:
        for r in csv.DictReader(f):
            if r["event"] == "TO":
                ev[(r["subject_id"], r["side"])].append(float(r["time_s"]))
    return {k: np.array(sorted(v)) for k, v in ev.items()}


def q(v, fmt="{:6.1f}"):
    v = np.asarray(v)
    return (fmt.format(np.median(v)) + " [" + fmt.format(np.percentile(v, 10)) + ", "
            + fmt.format(np.percentile(v, 90)) + "]")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hugadb", default="../shared/realdata/hugadb")
    ap.add_argument("--ldh", default="target/release/ldh")
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="ldh-foot-")
    os.makedirs(work, exist_ok=True)
    outs = run_ldh(args.ldh, args.hugadb, work)
    st = strides(outs["default"])
    sa, zc = to_events(outs["sa"]), to_events(outs["zc"])
    rows = []  # (file, side, T, to, peak, zero, t_s, t_p)
    for sid, name in FILES.items():
        d = pd.read_csv(os.path.join(args.hugadb, name), sep="\t", comment="#")
        for side, s in (("right", "R"), ("left", "L")):
            if (sid, side) in FAULTY_FEET:
                continue
            gs = sagittal(sensor(d, s + "S", "gyro"))
            if np.percentile(gs, 99.5) < -np.percentile(gs, 0.5):
                gs = -gs  # the shin's mid-swing peak positive
            gf = sagittal(sensor(d, s + "F", "gyro"))
            if np.corrcoef(gs, gf)[0, 1] < 0:
                gf = -gf
            for hs, to, nhs in st[(sid, side)]:
                lm = foot_landmarks(gf, hs, nhs)
                if lm is None:
                    continue
                ts = tp = np.nan
                e_sa, e_zc = sa.get((sid, side)), zc.get((sid, side))
                if e_sa is not None and e_zc is not None:
                    a, b = e_sa[np.argmin(np.abs(e_sa - to))], e_zc[np.argmin(np.abs(e_zc - to))]
                    if abs(a - to) < 0.25 and abs(b - to) < 0.25 and a < b:
                        ts, tp = a, b
                rows.append((sid, side, nhs - hs, to, lm[0], lm[1], ts, tp, hs))
    print(f"work folder: {work}\n")
    print("| file | leg | strides | stride (s) | ldh TO − foot push-off peak (ms) | ldh TO − foot "
          "zero crossing (ms) | TO between the two | stance: push-off peak / zero crossing "
          "/ ldh |")
    print("|---|---|---:|---:|---|---|---:|---|")
    for sid in FILES:
        for side in ("left", "right"):
            r = [x for x in rows if x[0] == sid and x[1] == side]
            if not r:
                continue
            r = np.array([x[2:] for x in r], dtype=float)
            T, to, pk, zr, hs = r[:, 0], r[:, 1], r[:, 2], r[:, 3], r[:, 6]
            inside = np.mean((pk <= to) & (to <= zr))
            sp, sz, sl = (np.median((x - hs) / T) for x in (pk, zr, to))
            print(f"| {sid} | {side} | {len(r)} | {np.median(T):.2f} | {q(1000 * (to - pk))} | "
                  f"{q(1000 * (to - zr))} | {100 * inside:.0f} % | {sp:.3f} / {sz:.3f} / "
                  f"{sl:.3f} |")
    r = np.array([x[2:] for x in rows], dtype=float)
    T, to, pk, zr, ts, tp = r[:, 0], r[:, 1], r[:, 2], r[:, 3], r[:, 4], r[:, 5]
    print(f"| all | | {len(r)} | | {q(1000 * (to - pk))} | {q(1000 * (to - zr))} | "
          f"{100 * np.mean((pk <= to) & (to <= zr)):.0f} % | |")
    ok = np.isfinite(ts) & np.isfinite(tp)
    print(f"\nShank landmarks against the foot's push-off peak ({ok.sum()} strides), "
          "ms, median [p10, p90]:\n")
    print("| toe-off rule | − push-off peak (ms) | − zero crossing (ms) | between the two |")
    print("|---|---|---|---:|")
    for name, t in (("ldh default detector", to[ok]), ("t_s (Aminian 2002, Salarian 2004)", ts[ok]),
                    ("t_p (pitch peak)", tp[ok]),
                    (f"fraction t_s + {FRACTION}·(t_p − t_s)", ts[ok] + FRACTION * (tp[ok] - ts[ok]))):
        inside = np.mean((pk[ok] <= t) & (t <= zr[ok]))
        print(f"| {name} | {q(1000 * (t - pk[ok]))} | {q(1000 * (t - zr[ok]))} | "
              f"{100 * inside:.0f} % |")
    k_pk = (pk[ok] - ts[ok]) / (tp[ok] - ts[ok])
    k_zr = (zr[ok] - ts[ok]) / (tp[ok] - ts[ok])
    print(f"\nthe foot landmarks as fractions k of the shank bracket [t_s, t_p]: push-off peak "
          f"{q(k_pk, '{:.2f}')}, zero crossing {q(k_zr, '{:.2f}')}")
    heel_strikes(args.hugadb, st)


def foot_contact(gf, an, hs, t):
    """Around ldh's heel strike `hs` (stride `t` s): the foot's reversal from toes-up to
    toes-down rotation (the last upward-to-downward zero crossing before its toes-down peak;
    linear), that peak (parabolic), and the largest |a| of the foot within 80 ms before and
    50 ms after the peak (a stand-in for gaitmap's Rampp initial contact, which reads the
    antero-posterior axis: HuGaDB's foot axes are not documented). Times in s, or None."""
    a, b = int((hs - 0.15 * t) * FS_HZ), int((hs + 0.15 * t) * FS_HZ)
    if a < 1 or b >= len(gf) - 1:
        return None
    im = a + int(np.argmin(gf[a:b]))
    j = im
    while j > a and gf[j - 1] < 0:
        j -= 1
    if gf[j - 1] <= 0:
        return None
    zc = (j - 1 + gf[j - 1] / (gf[j - 1] - gf[j])) / FS_HZ
    lo, hi = max(0, im - int(0.08 * FS_HZ)), min(len(an), im + int(0.05 * FS_HZ) + 1)
    return zc, parabolic(gf, im) / FS_HZ, (lo + int(np.argmax(an[lo:hi]))) / FS_HZ


def heel_strikes(hugadb, st):
    """ldh's heel strikes against the foot's contact landmarks (docs/accuracy.md "Heel strike at
    the impact")."""
    rows = []
    for sid, name in FILES.items():
        d = pd.read_csv(os.path.join(hugadb, name), sep="\t", comment="#")
        for side, s in (("right", "R"), ("left", "L")):
            if (sid, side) in FAULTY_FEET:
                continue
            gs = sagittal(sensor(d, s + "S", "gyro"))
            if np.percentile(gs, 99.5) < -np.percentile(gs, 0.5):
                gs = -gs
            gf = sagittal(sensor(d, s + "F", "gyro"))
            if np.corrcoef(gs, gf)[0, 1] < 0:
                gf = -gf
            an = np.linalg.norm(sensor(d, s + "F", "acc"), axis=0)
            for hs, _, nhs in st[(sid, side)]:
                c = foot_contact(gf, an, hs, nhs - hs)
                if c is not None:
                    rows.append([hs - x for x in c])
    r = 1000 * np.array(rows)
    print(f"\nldh's heel strike against the foot ({len(r)} strides), ms, median [p10, p90]: "
          f"after the foot's toes-up → toes-down reversal {q(r[:, 0])}; after its toes-down peak "
          f"{q(r[:, 1])}; after the foot's largest |a| near that peak (Rampp-like) {q(r[:, 2])}")


if __name__ == "__main__":
    main()
