#!/usr/bin/env python3
"""End to end: the plain Python pipeline with a nolds Lyapunov exponent against `ldh analyze`
(issue 17), whole processes, one thread each, same simulated cohort, same session.

The Python side is the numpy/scipy port of bench_pipeline_python.py (pandas read, scipy filter,
the EKF bank as a per-filter Python loop with the RTS smoother, events, strides, parameters) plus,
with STA, `nolds.lyap_r(omega, emb_dim=5, fit="poly")` on each leg's sagittal angular velocity
(nolds 0.6.2; its other parameters at their defaults). It runs as a child process
(`--peer`), imports included, with OMP/OPENBLAS/MKL limited to one thread. The ldh side is
`ldh analyze COHORT --jobs 1` (and `--no-sta`), start-up and fsynced outputs included.

For each of --repeats rounds (at least 3; interleaved, so load changes hit every variant alike)
it times:
Python with and without nolds, `ldh analyze --jobs 1` with and without STA, and `--jobs 2`
with STA; it prints the medians of the wall time and of the CPU time (user + sys of the child,
from wait4: robust on a loaded machine), the ratios, and ldh's `--timings` table of the last
run. With --scaling it also times `ldh analyze --jobs 1` on one subject whose legs last 1 min,
30 min and 2 h, and on 120 subjects of 1 min (as many samples as the 2 h subject, so start-up
is spread alike), and prints the time per sample (reported, not asserted).

Run from the repository root after `cargo build --release -p ldh-cli`, with numpy, scipy,
pandas, "nolds==0.6.2" and "setuptools<81" installed (e.g. target/bench-venv, see bench_all.sh):

    target/bench-venv/bin/python data-fixtures/scripts/bench_end_to_end.py \\
        [--subjects 35] [--seconds 30] [--repeats 5] [--ldh-runs 3] [--scaling] [--ldh PATH]

Results and the session they were measured in: docs/benchmarks.md.
"""
import argparse
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ONE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
              "RAYON_NUM_THREADS": "1"}


def peer(data, sta):
    """The Python pipeline over a cohort (run in a child process: imports are timed too)."""
    sys.path.insert(0, HERE)
    import bench_pipeline_python as bp  # noqa: E402 (numpy, scipy, pandas)
    if sta:
        import warnings
        warnings.filterwarnings("ignore")
        import nolds
    n = 0
    for sid, legs, h in bp.find_recordings(data):
        per = {}
        for side, path in legs:
            fs, acc, gyro, sat = bp.read_recording(path)
            acc_p, gyro_p, acc_norm = bp.preprocess(fs, acc, gyro, sat)
            acc_f, gyro_f = bp.align(fs, acc_p, gyro_p, acc_norm)
            att = bp.attitude(fs, acc_f, gyro_f)
            hs, to, t_med = bp.detect_events(gyro_f[:, 1], fs)
            st = bp.strides(side, fs, acc_f, gyro_f, att, hs, to, t_med, h)
            if sta:
                nolds.lyap_r(gyro_f[:, 1], emb_dim=5, fit="poly")
            per[side] = (st, hs)
            n += 1
        for side, (st, _) in per.items():
            other = per.get("right" if side == "left" else "left")
            bp.side_parameters(st, other[1] if other else None)
    print(n)


def timed(cmd, env=None, out_dir=None, stderr=False):
    """Wall and CPU (user + sys) seconds of a child process, and its stdout (or stderr).
    `out_dir` is removed first (ldh refuses nothing, but a fresh folder is the same work every
    round)."""
    if out_dir:
        shutil.rmtree(out_dir, ignore_errors=True)
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL if stderr else subprocess.PIPE,
                         stderr=subprocess.PIPE if stderr else subprocess.DEVNULL, env=env)
    out = (p.stderr if stderr else p.stdout).read()
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    if status != 0:
        sys.exit(f"{' '.join(cmd)} failed ({status})")
    return wall, ru.ru_utime + ru.ru_stime, out.decode()


def med(v):
    return statistics.median(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--peer", help=argparse.SUPPRESS)
    ap.add_argument("--sta", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--ldh", default=None, help="ldh binary (default: target/release/ldh)")
    ap.add_argument("--subjects", type=int, default=35, help="simulated subjects (>= 30)")
    ap.add_argument("--seconds", type=float, default=30.0, help="recording length, s")
    ap.add_argument("--seed", type=int, default=17)
    ap.add_argument("--repeats", type=int, default=5, help="timing rounds (>= 3)")
    ap.add_argument("--scaling", action="store_true", help="also 1 min / 30 min / 2 h legs")
    ap.add_argument("--ldh-runs", type=int, default=3,
                    help="runs of each ldh variant per round (a run takes ~0.2-0.3 s, so one "
                         "noisy run moves a median of 5; the Python side runs once per round)")
    args = ap.parse_args()
    if args.peer:
        peer(args.peer, args.sta)
        return
    repeats = max(args.repeats, 3)
    root = os.path.dirname(os.path.dirname(HERE))
    ldh = args.ldh or os.path.join(root, "target", "release", "ldh")
    if not os.access(ldh, os.X_OK):
        sys.exit(f"{ldh} not found: run `cargo build --release -p ldh-cli` first")
    env = dict(os.environ, **ONE_THREAD)
    tmp = tempfile.mkdtemp(prefix="ldh-e2e-")
    try:
        data, out = os.path.join(tmp, "cohort"), os.path.join(tmp, "out")
        healthy = args.subjects // 2
        subprocess.run([ldh, "simulate", "--out", data, "--healthy", str(healthy), "--ldh",
                        str(args.subjects - healthy), "--seconds", str(args.seconds), "--seed",
                        str(args.seed)], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        py = [sys.executable, os.path.abspath(__file__), "--peer", data]
        lh = [ldh, "analyze", data, "--out", out, "-q"]
        variants = {
            "py_sta": py + ["--sta"],
            "py": py,
            "ldh_sta": lh + ["--jobs", "1"],
            "ldh": lh + ["--jobs", "1", "--no-sta"],
            "ldh_sta_j2": lh + ["--jobs", "2"],
        }
        wall = {k: [] for k in variants}
        cpu = {k: [] for k in variants}
        n_rec = None
        for _ in range(repeats):
            for k, cmd in variants.items():
                for _ in range(max(args.ldh_runs, 1) if k.startswith("ldh") else 1):
                    w, c, o = timed(cmd, None if k == "ldh_sta_j2" else env,
                                    out if k.startswith("ldh") else None)
                    wall[k].append(w)
                    cpu[k].append(c)
                    if k == "py":
                        n_rec = int(o.strip())
        _, _, table = timed(lh + ["--jobs", "1", "--timings"], env, out, stderr=True)
        mw = {k: med(v) for k, v in wall.items()}
        mc = {k: med(v) for k, v in cpu.items()}
        print(f"## {args.subjects} simulated subjects × 2 legs ({n_rec} recordings), "
              f"{args.seconds:g} s at 100 Hz, one thread each, median of {repeats} rounds "
              f"(ldh: {max(args.ldh_runs, 1)} runs of each variant per round)\n")
        print("| | wall s | per leg ms | CPU s | ratio (wall) | ratio (CPU) |")
        print("|---|---:|---:|---:|---:|---:|")
        rows = [("Python: pandas, scipy, Kalman loop, nolds `lyap_r(emb_dim=5)`", "py_sta", "ldh_sta"),
                ("Python without nolds", "py", "ldh"),
                ("`ldh analyze --jobs 1`", "ldh_sta", None),
                ("`ldh analyze --jobs 1 --no-sta`", "ldh", None),
                ("`ldh analyze --jobs 2`", "ldh_sta_j2", None)]
        for label, k, vs in rows:
            rw = f"**{mw[k] / mw[vs]:.0f}×**" if vs else ""
            rc = f"{mc[k] / mc[vs]:.0f}×" if vs else ""
            print(f"| {label} | {mw[k]:.3f} | {1e3 * mw[k] / n_rec:.2f} | {mc[k]:.3f} | {rw} | {rc} |")
        print(f"\nwith STA: Python ÷ ldh = {mw['py_sta'] / mw['ldh_sta']:.1f}× wall, "
              f"{mc['py_sta'] / mc['ldh_sta']:.1f}× CPU; without: {mw['py'] / mw['ldh']:.1f}× wall, "
              f"{mc['py'] / mc['ldh']:.1f}× CPU")
        print(f"--jobs 2 ÷ --jobs 1 (wall, with STA): {mw['ldh_sta'] / mw['ldh_sta_j2']:.2f}×")

        def fmt(v):
            return ", ".join(f"{t:.3f}" for t in v)
        for k in variants:
            print(f"runs {k}: wall {fmt(wall[k])}; CPU {fmt(cpu[k])}")
        print(f"\n`ldh analyze --jobs 1 --timings`:\n\n```\n{table}```")
        if args.scaling:
            scaling(ldh, tmp, env)
        print(f"\npython {platform.python_version()}; {platform.machine()}, {os.cpu_count()} CPUs; "
              f"load average {', '.join(f'{x:.2f}' for x in os.getloadavg())}; "
              f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def scaling(ldh, tmp, env):
    """`ldh analyze --jobs 1` on one subject (2 legs) of 1 min, 30 min and 2 h."""
    print("\n## Time per sample against recording length (`ldh analyze --jobs 1`, one subject)\n")
    print("| per leg | samples per leg | wall s (median of 3) | CPU s | CPU ns per sample |")
    print("|---|---:|---:|---:|---:|")
    # The last row times the same total of samples as the 2 h subject in 1 min legs: the
    # process start-up and the first touch of memory and code, paid once per run, are then
    # spread over as many samples as in the 2 h run, so the rows compare the cost per sample
    # of short and long legs rather than start-up against work.
    for secs, label, subjects in ((60, "1 min", 1), (1800, "30 min", 1), (7200, "2 h", 1),
                                  (60, "1 min × 120 subjects", 120)):
        d = os.path.join(tmp, f"len{secs}x{subjects}")
        subprocess.run([ldh, "simulate", "--out", d, "--healthy", str(subjects), "--ldh", "0",
                        "--seconds", str(secs), "--seed", "5"], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        lo = os.path.join(tmp, "lo")
        runs = [timed([ldh, "analyze", d, "--out", lo, "--jobs", "1", "-q"], env, lo)
                for _ in range(3)]
        w, c = med([r[0] for r in runs]), med([r[1] for r in runs])
        n = secs * 100 + 1
        print(f"| {label} | {n} | {w:.3f} | {c:.3f} | {1e9 * c / (2 * subjects * n):.0f} |")
        shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    main()
