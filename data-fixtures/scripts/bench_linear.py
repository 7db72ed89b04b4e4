#!/usr/bin/env python3
"""Issue 19: doubling the rows of a recording doubles the time (within 20 %).

Usage: python3 data-fixtures/scripts/bench_linear.py path/to/ldh [--repeats 3] [--tmp DIR]

Makes recordings of N and 2N rows in a temporary folder (never committed; deleted at the end) by
tiling `data-fixtures/bad/baseline_ok` (a simulated walk at 100 Hz, standing at both ends) with
continuous time, and times, median of `--repeats`:

- reading: `ldh inspect FILE` (stream, parse, time base, checks, outlier search) at 1 M / 2 M and
  5 M / 10 M rows (limits raised: `--max-file-size-mb 2000 --max-samples 20000000`);
- the whole analysis: `ldh analyze PAIR --jobs 1` of a pair whose legs have 1 M / 2 M rows
  (within the default `max_samples`, 2 500 000; about 150 bytes a sample).

Wall time and CPU time (user + system of the child, from `os.wait4`) and the child's peak RSS.
Prints a Markdown table; the ratio column is time(2N) / time(N): 2.0 is linear.
"""
import argparse
import os
import pathlib
import shutil
import statistics
import subprocess
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
BASE = HERE.parent / "bad" / "baseline_ok"


def write_tiled(src: pathlib.Path, out: pathlib.Path, rows: int) -> None:
    lines = src.read_text().splitlines()
    header, rests = lines[0], [l.split(",", 1)[1] for l in lines[1:]]
    n = len(rests)
    with open(out, "w") as f:
        f.write(header + "\n")
        chunk = []
        for i in range(rows):
            chunk.append(f"{i // 100}.{i % 100:02d},{rests[i % n]}\n")
            if len(chunk) == 100_000:
                f.write("".join(chunk))
                chunk = []
        f.write("".join(chunk))


def run(cmd):
    """(wall s, CPU s, peak RSS MB) of one run of `cmd`, which must succeed."""
    t = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t
    err = p.stderr.read().decode()
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"{cmd}: exit {status}: {err}")
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss * 1024 / 1e6


def median_of(cmd, repeats):
    runs = [run(cmd) for _ in range(repeats)]
    return (statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs),
            max(r[2] for r in runs))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("ldh")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--tmp", default=None)
    a = ap.parse_args()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="ldh-linear-", dir=a.tmp))
    raised = ["--max-file-size-mb", "2000", "--max-samples", "20000000"]
    rows_out = []
    try:
        for n in (1_000_000, 5_000_000):
            res = []
            for rows in (n, 2 * n):
                f = tmp / f"r{rows}.csv"
                write_tiled(BASE / "left.csv", f, rows)
                res.append((rows, median_of([a.ldh, "inspect", str(f), *raised], a.repeats)))
                f.unlink()
            rows_out.append(("read (`ldh inspect`)", res))
        res = []
        for rows in (1_000_000, 2_000_000):
            subj = tmp / f"S{rows}"
            subj.mkdir()
            for side in ("left.csv", "right.csv"):
                write_tiled(BASE / side, subj / side, rows)
            out = tmp / f"out{rows}"
            cmd = [a.ldh, "analyze", str(subj), "--out", str(out), "--jobs", "1", "-q"]
            res.append((rows, median_of(cmd, a.repeats)))
            shutil.rmtree(subj)
        rows_out.append(("`ldh analyze --jobs 1` (pair)", res))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("| stage | rows N → 2N | wall s (N, 2N) | wall ratio | CPU s (N, 2N) | CPU ratio | peak RSS MB (2N) |")
    print("|---|---|---|---:|---|---:|---:|")
    for name, ((n1, r1), (n2, r2)) in rows_out:
        print(f"| {name} | {n1:,} → {n2:,} | {r1[0]:.2f}, {r2[0]:.2f} | {r2[0] / r1[0]:.2f} "
              f"| {r1[1]:.2f}, {r2[1]:.2f} | {r2[1] / r1[1]:.2f} | {r2[2]:.0f} |")


if __name__ == "__main__":
    main()
