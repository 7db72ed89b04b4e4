#!/usr/bin/env python3
"""Stride length variability (SV) of `ldh analyze` against a simulated cohort's truth, by what
happened to it: reported, withheld for noise (`sv_noise`) or unchecked (`sv_unchecked`).

For every leg, its reported valid strides are matched to the true strides (heel strike within
0.1 s), and the SV error is the CV of the measured lengths minus the CV of the true lengths of
the same strides, in percentage points. Standard library only.

    ldh simulate --family b --out simB --healthy 15 --ldh 15 --seed 2026
    ldh analyze simB --out outB
    python3 data-fixtures/scripts/sv_against_truth.py simB outB

Results: docs/accuracy.md "Stride length variability against its noise".
"""
import collections
import csv
import json
import statistics as st
import sys


def main(sim, out):
    rows = {(r["subject_id"], r["side"]): r for r in json.load(open(f"{out}/recordings.json"))}
    strides = collections.defaultdict(list)
    for s in csv.DictReader(open(f"{out}/strides.csv")):
        if s["valid"] == "true" and s["stride_length_m"] not in ("", "NaN"):
            strides[(s["subject_id"], s["side"])].append(
                (float(s["hs_time_s"]), float(s["stride_length_m"])))

    def cv(v):
        return st.stdev(v) / st.mean(v)

    errs = collections.defaultdict(list)
    for (sid, side), r in sorted(rows.items()):
        truth = json.load(open(f"{sim}/{sid}/truth.json"))[side]["strides"]
        meas, true = [], []
        for hs, length in strides[(sid, side)]:
            best = min(truth, key=lambda x: abs(x["hs_time_s"] - hs)) if truth else None
            if best and abs(best["hs_time_s"] - hs) < 0.1:
                meas.append(length)
                true.append(best["stride_length_m"])
        if len(meas) < 3:
            continue
        codes = {w["code"] for w in r.get("warnings", [])}
        if r.get("stride_length_cv") is not None:
            kind = "reported"
        elif "sv_noise" in codes:
            kind = "sv_noise"
        elif "sv_unchecked" in codes:
            kind = "sv_unchecked"
        else:
            kind = "withheld otherwise"
        errs[kind].append(100 * (cv(meas) - cv(true)))
    for kind, v in errs.items():
        print(f"{kind}: {len(v)} legs, mean {st.mean(v):+.2f} points, "
              f"more than 1 point off: {sum(abs(x) > 1 for x in v)}, largest {max(v, key=abs):+.2f}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
