#!/usr/bin/env python3
"""Regenerate the bad-input corpus in this folder (data-fixtures/bad/).

Usage: python3 data-fixtures/bad/make_corpus.py [path/to/ldh]

The signal cases start from `ldh simulate` recordings (one healthy subject, no turn, seed 3),
rewritten with fewer decimals to keep the corpus small, and are then edited the way real exports
go wrong. Plain Python, no third-party packages. Each case folder gets its input file(s); the
expected outcome (`expected.toml`) is written by hand and is not touched here. Cases marked
`generated = true` in their expected.toml (0-byte file, directory, unreadable file, symlink loop,
missing file, 2-hour recording) have no committed input: the tests create them at runtime.
"""
import math
import os
import pathlib
import random
import shutil
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
HEADER = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z"
LDH = sys.argv[1] if len(sys.argv) > 1 else os.environ.get("LDH", "ldh")


def simulate(rate_hz=100, seconds=14, seed=3):
    """Rows [(t, ax, ay, az, gx, gy, gz)] of both legs from `ldh simulate`."""
    with tempfile.TemporaryDirectory() as d:
        subprocess.run(
            [LDH, "simulate", "--out", d, "--healthy", "1", "--ldh", "0", "--seconds", str(seconds),
             "--seed", str(seed), "--rate-hz", str(rate_hz), "--no-turn", "--jobs", "1"],
            check=True, capture_output=True)
        legs = []
        for side in ("left", "right"):
            lines = (pathlib.Path(d) / "H01" / f"{side}.csv").read_text().splitlines()
            assert lines[0] == HEADER, lines[0]
            legs.append([tuple(float(v) for v in l.split(",")) for l in lines[1:]])
        return legs


def fmt_row(r, tdec=2):
    t, ax, ay, az, gx, gy, gz = r
    return f"{t:.{tdec}f},{ax:.3f},{ay:.3f},{az:.3f},{gx:.1f},{gy:.1f},{gz:.1f}"


def text(rows, header=HEADER, tdec=2):
    return header + "\n" + "".join(fmt_row(r, tdec) + "\n" for r in rows)


def cut(rows, t_end):
    return [r for r in rows if r[0] <= t_end + 1e-9]


def window(rows, t0, t1):
    """The rows from t0 to t1 s (timestamps kept: the file starts at t0)."""
    return [r for r in rows if t0 - 1e-9 <= r[0] <= t1 + 1e-9]


def case(name, **files):
    d = HERE / name
    d.mkdir(exist_ok=True)
    for fname, content in files.items():
        fname = fname.replace("_csv", ".csv")
        p = d / fname
        if isinstance(content, bytes):
            p.write_bytes(content)
        else:
            p.write_text(content, newline="\n")


def interp(rows, times):
    """Linear interpolation of all channels of `rows` at `times`."""
    out, j = [], 0
    for t in times:
        while j + 2 < len(rows) and rows[j + 1][0] < t:
            j += 1
        a, b = rows[j], rows[j + 1]
        w = min(max((t - a[0]) / (b[0] - a[0]), 0.0), 1.0)
        out.append((t,) + tuple(a[k] + w * (b[k] - a[k]) for k in range(1, 7)))
    return out


def main():
    left, right = simulate()
    # Kept small (the corpus is in git): the single-file signal cases are the first 5.5 s
    # (3 s standing, 2.5 s walking); every pair is 2-10 s (1 s standing, then ~7 strides:
    # the shortest window in which baseline_ok keeps its 3 valid strides per leg). Cases that
    # leave a leg unchanged name baseline_ok's file in their expected.toml instead of a copy.
    l10 = cut(left, 5.5)
    lp, rp = window(left, 2.0, 10.0), window(right, 2.0, 10.0)
    tiny = l10[:12]

    # --- malformed text: refused with file, line and column ----------------------------------
    rows = [fmt_row(r) for r in tiny]
    bad = rows.copy(); bad[3] = ",".join(bad[3].split(",")[:4])
    case("truncated_row", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    case("truncated_last_line", data_csv=HEADER + "\n" + "\n".join(rows[:-1]) + "\n" + rows[-1][:17])
    bad = rows.copy(); bad[5] = bad[5] + ",0.5"
    case("too_many_fields", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    bad = rows.copy(); f = bad[6].split(","); f[5] = "n/a"; bad[6] = ",".join(f)
    case("text_in_number", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    bad = rows.copy(); f = bad[2].split(","); f[2] = ""; bad[2] = ",".join(f)
    case("empty_cell", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    case("decimal_comma_semicolon",
         data_csv=HEADER.replace(",", ";") + "\n" + "".join(r.replace(",", ";").replace(".", ",") + "\n" for r in rows))
    case("decimal_comma_comma_delimiter",
         data_csv=HEADER + "\n" + "".join(r.replace(".", ",") + "\n" for r in rows))
    bad = rows.copy(); f = bad[4].split(","); f[4] = "NaN"; bad[4] = ",".join(f)
    case("nan_value", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    bad = rows.copy(); f = bad[7].split(","); f[1] = "-inf"; bad[7] = ",".join(f)
    case("inf_value", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    bad = rows.copy(); f = bad[6].split(","); f[0] = bad[5].split(",")[0]; bad[6] = ",".join(f)
    case("duplicate_timestamps", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    bad = rows.copy(); bad[6], bad[7] = bad[7], bad[6]
    case("backwards_timestamps", data_csv=HEADER + "\n" + "\n".join(bad) + "\n")
    case("header_only", data_csv=HEADER + "\n")
    case("no_header", data_csv="\n".join(rows) + "\n")
    case("unknown_vendor_header",
         data_csv="Time,AccX,AccY,AccZ,GyrX,GyrY,GyrZ\n" + "\n".join(rows) + "\n")
    case("binary_file", data_csv=bytes([0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A]) + bytes(range(256)))
    case("utf16_file", data_csv=(HEADER + "\n" + "\n".join(rows) + "\n").encode("utf-16"))
    case("trailing_text_line", data_csv=HEADER + "\n" + "\n".join(rows) + "\nEND OF RECORDING\n")
    # Milliseconds written into the seconds column: 0, 10, 20 ... "s" is 0.1 Hz.
    case("time_in_ms_declared_s",
         data_csv=HEADER + "\n" + "".join(fmt_row((r[0] * 1000,) + r[1:], 0) + "\n" for r in tiny))

    # --- too short, no signal, wrong units ---------------------------------------------------
    case("one_second", data_csv=text(cut(l10, 1.0)))
    case("all_zero", data_csv=text([(i / 100, 0, 0, 0, 0, 0, 0) for i in range(421)]))
    case("all_constant", data_csv=text([(i / 100, 1.0, 0, 0, 0, 0, 0) for i in range(421)]))
    case("constant_gyro", data_csv=text([r[:4] + (0.0, 0.0, 0.0) for r in l10]))
    case("constant_acc_channel", data_csv=text([r[:3] + (0.0,) + r[4:] for r in l10]))
    # The logger repeats the last sample while the sensor is disconnected, then data jump back.
    frozen = [r if not (3.0 <= r[0] < 4.5) else (r[0],) + l10[300][1:] for r in l10]
    case("disconnected_frozen", data_csv=text(frozen))
    # Zeros until the sensor connects, then the signal jumps in.
    case("disconnected_zeros_then_jump",
         data_csv=text([r if r[0] >= 1.5 else (r[0], 0, 0, 0, 0, 0, 0) for r in l10]))
    # rad/s written where deg/s is declared (4 decimals, so the signal survives the rounding).
    case("gyro_rad_declared_deg", data_csv=HEADER + "\n" + "".join(
        f"{r[0]:.2f},{r[1]:.3f},{r[2]:.3f},{r[3]:.3f},"
        + ",".join(f"{math.radians(v):.4f}" for v in r[4:]) + "\n" for r in l10))
    case("acc_mps2_declared_g", data_csv=text([(r[0],) + tuple(v * 9.80665 for v in r[1:4]) + r[4:] for r in l10]))

    # --- timing: gaps and jitter --------------------------------------------------------------
    case("gap_split", data_csv=text([r for r in cut(left, 6.5) if not (4.5 < r[0] < 5.0)]))
    rnd = random.Random(7)
    jit = [(r[0] + rnd.uniform(-0.003, 0.003),) + r[1:] for r in l10]
    case("jitter_resampled", data_csv=text(jit, tdec=4))
    spike = list(l10); spike[450] = (spike[450][0], 40.0) + spike[450][2:]
    case("single_spike", data_csv=text(spike))
    case("clipped_gyro", data_csv=text([r[:4] + tuple(max(-250.0, min(250.0, v)) for v in r[4:]) for r in l10]))

    # --- pairs: analysed with `ldh analyze` -----------------------------------------------------
    case("baseline_ok", left_csv=text(lp), right_csv=text(rp))
    rnd = random.Random(11)
    stand = lambda: [(i / 100, 1.0 + rnd.gauss(0, 0.004), rnd.gauss(0, 0.004), rnd.gauss(0, 0.004),
                      rnd.gauss(0, 0.3), rnd.gauss(0, 0.3), rnd.gauss(0, 0.3)) for i in range(421)]
    case("standing_only", left_csv=text(stand()), right_csv=text(stand()))
    # Running: the walk played 1.6 times faster (cadence ×1.6, angular velocity ×1.6, the
    # dynamic acceleration ×1.6²), resampled back to 100 Hz.
    def run(rows):
        k = 1.6
        g = [sum(r[i] for r in rows[:100]) / 100 for i in range(1, 4)]
        fast = [((r[0] - rows[0][0]) / k,) + tuple(g[i] + (r[1 + i] - g[i]) * k * k for i in range(3))
                + tuple(v * k for v in r[4:]) for r in rows]
        n = int(fast[-1][0] * 100)
        return interp(fast, [i / 100 for i in range(n + 1)])
    case("walk_played_fast", left_csv=text(run(lp)), right_csv=text(run(rp)))
    # Left device upside down: rotated 180° about its z axis (x and y change sign).
    flip = lambda r: (r[0], -r[1], -r[2], r[3], -r[4], -r[5], r[6])
    # The other leg of these is baseline_ok's (named in expected.toml, not copied).
    case("upside_down", left_csv=text([flip(r) for r in lp]))
    # baseline_ok's legs swapped, through a manifest (which states the sides; no copies).
    case("left_right_swapped", manifest_csv="subject_id,group,affected_side,left,right\n"
         "S1,healthy,none,../baseline_ok/right.csv,../baseline_ok/left.csv\n")
    # A leg from another subject: the demo cohort's H01 left and L01 right (no copies).
    case("leg_from_another_subject", manifest_csv="subject_id,group,affected_side,left,right\n"
         "S1,healthy,none,../../cohort/H01/left.csv,../../cohort/L01/right.csv\n")
    case("different_lengths", right_csv=text(cut(rp, 7.0)))
    case("different_clocks", right_csv=text([(r[0] + 3600.0,) + r[1:] for r in rp]))
    case("clock_drift", right_csv=text([(r[0] * 1.02,) + r[1:] for r in rp], tdec=4))
    l50, r50 = simulate(rate_hz=50)
    l200, r200 = simulate(rate_hz=200)
    # mixed_rates_100_50: baseline_ok's left leg and rate_50hz's right leg (no copies).
    case("rate_50hz", left_csv=text(window(l50, 2.0, 10.0)), right_csv=text(window(r50, 2.0, 10.0)))
    case("rate_200hz", left_csv=text(window(l200, 2.0, 10.0), tdec=3),
         right_csv=text(window(r200, 2.0, 10.0), tdec=3))
    case("missing_right_file", left_csv=text(lp))


if __name__ == "__main__":
    main()
