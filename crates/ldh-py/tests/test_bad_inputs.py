"""The bad-input corpus (data-fixtures/bad/, see its README.md) through the Python API: every
case gives the outcome its expected.toml documents — the typed exception, or a result with its
warnings — and never a crash. The Rust twin is tests/tests/bad_inputs.rs."""
import gzip
import os
import pathlib
import resource
import shutil
import subprocess
import sys
import warnings

import numpy as np

import pytest

import ldh

try:
    import tomllib
except ImportError:  # Python < 3.11: the corpus' TOML is flat key = literal
    tomllib = None

ROOT = pathlib.Path(__file__).resolve().parents[3]
CORPUS = ROOT / "data-fixtures" / "bad"
EXCEPTIONS = {"data": ldh.LdhDataError, "io": ldh.LdhOSError, "not_found": ldh.LdhFileNotFoundError}


def _load(path):
    text = path.read_text(encoding="utf-8")
    if tomllib is not None:
        return tomllib.loads(text)
    import ast
    out = {}
    for line in text.splitlines():
        if line.strip() and not line.startswith("#"):
            k, v = line.split("=", 1)
            v = v.strip().replace("true", "True").replace("false", "False")
            out[k.strip()] = ast.literal_eval(v)
    return out


CASES = sorted(p.name for p in CORPUS.iterdir() if (p / "expected.toml").is_file())


def write_two_hour(src, out):
    """baseline_ok repeated back to back with continuous time until 7200 s are covered."""
    for side in ("left.csv", "right.csv"):
        lines = (src / side).read_text().splitlines()
        header, rows = lines[0], [l.split(",", 1) for l in lines[1:]]
        times = [float(t) for t, _ in rows]
        span = times[-1] - times[0] + (times[1] - times[0])
        tiles = int(-(-7200 // span))
        with open(out / side, "w", newline="\n") as fh:
            fh.write(header + "\n")
            for k in range(tiles):
                off = k * span
                fh.write("".join(f"{t + off:.2f},{rest}\n" for t, (_, rest) in zip(times, rows)))


def generate(kind, d):
    """Make a generated case's input in d; returns a skip reason or None."""
    if kind == "missing":
        pass
    elif kind == "zero_byte":
        (d / "data.csv").write_bytes(b"")
    elif kind == "directory":
        (d / "data.csv").mkdir()
    elif kind == "unreadable":
        f = d / "data.csv"
        shutil.copy(CORPUS / "single_spike" / "data.csv", f)
        f.chmod(0)
        try:
            f.read_bytes()
            return "running as root (or without file permissions): chmod 000 does not stop reading"
        except PermissionError:
            pass
    elif kind == "symlink_loop":
        os.symlink(d / "loop.csv", d / "data.csv")
        os.symlink(d / "data.csv", d / "loop.csv")
    elif kind == "two_hour":
        write_two_hour(CORPUS / "baseline_ok", d)
    elif kind == "nul_late":
        # 2500 rows (~90 kB) with a NUL byte in acc_y on line 2001, past the first 64 KiB.
        rows = [f"{i // 100}.{i % 100:02d},1.000,{'0.0' + chr(0) + '10' if i == 1999 else '0.010'},0.020,0.5,0.6,0.7"
                for i in range(2500)]
        (d / "data.csv").write_text("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n" + "\n".join(rows) + "\n")
    elif kind == "legs_of_two_people":
        # The demo is stored compressed (data-fixtures/cohort/*/*.csv.gz): two people's legs.
        for src, name in (("H01/left.csv.gz", "h01_left.csv"), ("L01/right.csv.gz", "l01_right.csv")):
            with gzip.open(CORPUS.parent / "cohort" / src, "rt", encoding="utf-8") as fh:
                (d / name).write_text(fh.read(), encoding="utf-8")
        (d / "manifest.csv").write_text(
            "subject_id,group,affected_side,left,right\nS1,healthy,none,h01_left.csv,l01_right.csv\n")
    else:
        raise AssertionError(f"unknown generator {kind}")
    return None


def test_the_corpus_is_complete():
    assert len(CASES) >= 60
    readme = (CORPUS / "README.md").read_text(encoding="utf-8")
    for name in CASES:
        assert f"`{name}`" in readme, name


# Runs a `python` case's code and prints how it ended, for run_python_case.
_RUNNER = """
import os, sys, traceback
code = sys.stdin.read()
try:
    exec(compile(code, "case", "exec"), {"__name__": "__main__"})
except BaseException as e:
    print("RAISED", type(e).__name__, flush=True)
    print(str(e)[:100000], flush=True)
    sys.exit(3)
print("SUCCEEDED", flush=True)
"""

ONE_GB_KIB = 1_000_000_000 // 1024


def _shell(lines, case, tmp):
    for line in lines:
        line = line.replace("{case}", str(case)).replace("{tmp}", str(tmp))
        subprocess.run(["bash", "-euo", "pipefail", "-c", line], cwd=tmp, check=True)


def run_python_case(name, exp, tmp_path):
    """A `command = "python"` case: its code in a subprocess (a time limit, peak RSS <= 1 GB),
    the exception it must raise (by class name) and the fragments of its message."""
    case = (CORPUS / name).resolve()
    _shell(exp.get("setup", []), case, tmp_path)
    env = dict(os.environ, LDH_CASE=str(case))
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    p = subprocess.run([sys.executable, "-c", _RUNNER], input=exp["code"], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=exp.get("timeout_s", 120))
    rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    # ru_maxrss of children is the largest of any child so far: a rise means this one set it.
    assert rss <= ONE_GB_KIB or rss == before, f"peak RSS {rss} KiB > 1 GB"
    out = p.stdout
    assert "Traceback" not in p.stderr or "RAISED" in out, p.stderr
    if "raises" in exp:
        assert out.startswith("RAISED "), f"expected {exp['raises']}, got: {out}{p.stderr}"
        got = out.split()[1]
        assert got == exp["raises"], f"raised {got}, expected {exp['raises']}: {out}"
        assert issubclass(getattr(ldh, got), ldh.LdhError), got
    else:
        assert "SUCCEEDED" in out, f"{out}{p.stderr}"
    for m in exp.get("contains", []):
        assert m in out, (m, out)


@pytest.mark.parametrize("name", CASES)
def test_bad_input(name, tmp_path):
    exp = _load(CORPUS / name / "expected.toml")
    if exp["command"] == "cli":
        pytest.skip("a sequence of ldh runs: tests/tests/bad_inputs.rs runs it")
    if exp["command"] == "python":
        run_python_case(name, exp, tmp_path)
        return
    if exp.get("generated"):
        d = tmp_path / name
        d.mkdir()
        reason = generate(exp["generate"], d)
        if reason:
            pytest.skip(reason)
    else:
        d = CORPUS / name
    files = [d / f for f in exp["files"]]
    outcome = exp["outcome"]
    if exp["command"] == "inspect":
        (path,) = files
        if outcome == "error":
            cls = EXCEPTIONS[exp["kind"]]
            with pytest.raises(cls) as e:
                ldh.read_recording(path)
            assert isinstance(e.value, ldh.LdhError)
            for m in exp.get("message_contains", []):
                assert m in str(e.value), (m, str(e.value))
            return
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            rec, report = ldh.read_recording(path)
        issued = [str(w.message) for w in caught if issubclass(w.category, ldh.LdhWarning)]
        assert len(issued) == len(report["warnings"])
        if outcome == "ok":
            assert report["warnings"] == []
        else:
            assert report["warnings"], "expected warnings"
        joined = " | ".join(report["warnings"])
        for m in exp.get("warnings_contain", []):
            assert m in joined, (m, joined)
        notes = " | ".join(report["notes"])
        for m in exp.get("notes_contain", []):
            assert m in notes, (m, notes)
        assert len(rec["time_s"]) == report["samples"]
        return
    # analyze
    compute_sta = False if "--no-sta" in exp.get("args", []) else None
    res = ldh.analyze([str(f) for f in files], compute_sta=compute_sta)
    r = res["recordings"]
    idx = [i for i, s in enumerate(r["side"]) if not exp.get("side") or s == exp["side"]]
    assert idx
    if outcome == "error":
        errors = " | ".join(r["error"][i] for i in idx if r["status"][i] == "error")
        assert errors, "expected a failed recording"
        for m in exp.get("message_contains", []):
            assert m in errors, (m, errors)
        return
    for i in idx:
        # analysed: "ok", or "no_valid_strides" exactly when no stride passed the checks
        want = "no_valid_strides" if r["strides_valid"][i] == 0 else "ok"
        assert r["status"][i] == want, (r["status"][i], r["error"][i])
        # Structured warnings (docs/quality.md): a list of {code, severity, message, affects};
        # notes never make a case "not ok".
        ws = r["warnings"][i]
        serious = [w for w in ws if w["severity"] != "note"]
        flat = " | ".join(f'{w["code"]} [{w["severity"]}]: {w["message"]}' for w in ws)
        if outcome == "ok":
            assert serious == [], serious
        else:
            assert serious, f"expected a warning, got {flat}"
        for m in exp.get("warnings_contain", []) + exp.get("codes", []):
            assert m in flat, (m, flat)
        for c in exp.get("codes_absent", []):
            assert all(w["code"] != c for w in ws), (c, flat)
        for c in exp.get("withheld", []):
            assert np.isnan(r[c][i]) and r["withheld"][i][c], (c, r["withheld"][i])
        for c in exp.get("measured", []):
            assert np.isfinite(r[c][i]), c
        if "min_valid_strides" in exp:
            assert r["strides_valid"][i] >= exp["min_valid_strides"]
        if "fs_hz" in exp:
            assert abs(r["fs_hz"][i] - exp["fs_hz"]) < 1e-6
