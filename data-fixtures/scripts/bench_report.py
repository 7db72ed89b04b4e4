#!/usr/bin/env python3
"""Time report generation against the analysis it reports on (issue 8's bar: building the
reports of 100 subjects takes less time than analysing them).

Simulates N subjects (half healthy, half LDH, 30 s each), then per repeat times, in one session:
  analyze         ldh analyze C --out A            (tables only)
  analyze+report  ldh analyze C --out B --report   (tables, traces, HTML reports)
  report          ldh report B                     (HTML from the tables and traces only)
and prints medians and the ratio report / analyze.

    cargo build --release -p ldh-cli
    python3 data-fixtures/scripts/bench_report.py --subjects 100 --repeats 5
"""
import argparse, shutil, statistics, subprocess, tempfile, time, os

ap = argparse.ArgumentParser()
ap.add_argument("--ldh", default="target/release/ldh")
ap.add_argument("--subjects", type=int, default=100)
ap.add_argument("--repeats", type=int, default=5)
ap.add_argument("--jobs", type=int, default=2)
a = ap.parse_args()

tmp = tempfile.mkdtemp(prefix="ldh-bench-report-")
c = os.path.join(tmp, "cohort")
h = a.subjects // 2
subprocess.run([a.ldh, "simulate", "--out", c, "--healthy", str(h), "--ldh", str(a.subjects - h),
                "--seconds", "30", "--seed", "8"], check=True, capture_output=True)

def run(args):
    t = time.perf_counter()
    r = subprocess.run([a.ldh] + args + ["--jobs", str(a.jobs)], capture_output=True, text=True)
    dt = time.perf_counter() - t
    if r.returncode != 0:
        raise SystemExit(r.stderr)
    return dt

times = {"analyze": [], "analyze+report": [], "report": []}
for i in range(a.repeats):
    A, B = os.path.join(tmp, f"A{i}"), os.path.join(tmp, f"B{i}")
    times["analyze"].append(run(["analyze", c, "--out", A]))
    times["analyze+report"].append(run(["analyze", c, "--out", B, "--report"]))
    times["report"].append(run(["report", B]))
med = {k: statistics.median(v) for k, v in times.items()}
size = sum(os.path.getsize(os.path.join(dp, f)) for dp, _, fs in os.walk(os.path.join(tmp, "B0", "reports")) for f in fs)
print(f"{a.subjects} subjects x 30 s, --jobs {a.jobs}, {a.repeats} repeats (median s):")
for k, v in med.items():
    print(f"  {k:15s} {v:7.3f}   (all: {', '.join(f'{x:.3f}' for x in times[k])})")
print(f"  report / analyze                  = {med['report'] / med['analyze']:.2f}")
print(f"  (analyze+report - analyze) / analyze = {(med['analyze+report'] - med['analyze']) / med['analyze']:.2f}")
print(f"  reports on disk: {size / 1e6:.1f} MB ({size / a.subjects / 1e3:.0f} kB per subject)")
shutil.rmtree(tmp)
